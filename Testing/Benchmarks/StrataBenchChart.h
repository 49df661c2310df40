// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The benchmarks' report chart: a vtkChartXY in a 1000 x 650 white view with a title, axes (log
// when asked) and a legend, one table per series, written to PNG. Shared by BenchVolume,
// BenchHybrid and BenchPaging so that their plots look alike.
#ifndef StrataBenchChart_h
#define StrataBenchChart_h

#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <string>
#include <utility>
#include <vector>

class vtkChartXY;
class vtkContextView;
class vtkGenericRenderWindowInteractor;
class vtkPlot;
class vtkTable;

namespace strata_bench
{
class Chart
{
public:
  /// `legendRight`: the legend in the top right corner, else the top left.
  Chart(const std::string& title,
    int titleFontSize,
    const std::string& xTitle,
    bool xLog,
    const std::string& yTitle,
    bool yLog,
    bool legendRight);
  ~Chart();
  /// One series (vtkChart::LINE or POINTS) of (x, y) points in `rgb`; its plot for styling, or
  /// null when there are no points.
  vtkPlot* Add(int kind,
    const std::string& label,
    const std::vector<std::pair<double, double>>& points,
    const unsigned char rgb[3]);
  vtkChartXY* GetChart();
  /// Renders the view and writes it to `png`.
  void Write(const std::string& png);

private:
  vtkNew<vtkContextView> View;
  // An interactor that never talks to a display: the view's own (X) one would, on first render.
  vtkNew<vtkGenericRenderWindowInteractor> Interactor;
  vtkNew<vtkChartXY> XY;
  std::vector<vtkSmartPointer<vtkTable>> Tables; ///< kept alive until rendered
};
}

#endif

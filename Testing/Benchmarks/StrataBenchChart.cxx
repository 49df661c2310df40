// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataBenchChart.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkGenericRenderWindowInteractor.h"
#include "vtkPNGWriter.h"
#include "vtkPlot.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

namespace strata_bench
{
Chart::Chart(const std::string& title,
  int titleFontSize,
  const std::string& xTitle,
  bool xLog,
  const std::string& yTitle,
  bool yLog,
  bool legendRight)
{
  this->View->SetInteractor(this->Interactor);
  this->View->GetRenderWindow()->SetSize(1000, 650);
  this->View->GetRenderWindow()->SetMultiSamples(0);
  this->View->GetRenderer()->SetBackground(1, 1, 1);
  this->View->GetScene()->AddItem(this->XY);
  this->XY->SetTitle(title);
  this->XY->GetTitleProperties()->SetFontSize(titleFontSize);
  this->XY->SetShowLegend(true);
  this->XY->GetLegend()->SetHorizontalAlignment(
    legendRight ? vtkChartLegend::RIGHT : vtkChartLegend::LEFT);
  this->XY->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  this->XY->GetAxis(vtkAxis::BOTTOM)->SetTitle(xTitle);
  this->XY->GetAxis(vtkAxis::BOTTOM)->SetLogScale(xLog);
  this->XY->GetAxis(vtkAxis::LEFT)->SetTitle(yTitle);
  this->XY->GetAxis(vtkAxis::LEFT)->SetLogScale(yLog);
}

Chart::~Chart() = default;

vtkPlot* Chart::Add(int kind,
  const std::string& label,
  const std::vector<std::pair<double, double>>& points,
  const unsigned char rgb[3])
{
  if (points.empty())
    return nullptr;
  vtkNew<vtkDoubleArray> x, y;
  x->SetName(("x " + label).c_str());
  y->SetName(label.c_str());
  for (const auto& p : points)
  {
    x->InsertNextValue(p.first);
    y->InsertNextValue(p.second);
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(x);
  table->AddColumn(y);
  this->Tables.push_back(table);
  vtkPlot* plot = this->XY->AddPlot(kind);
  plot->SetInputData(table, 0, 1);
  plot->SetColor(rgb[0], rgb[1], rgb[2], 255);
  plot->SetLabel(label);
  return plot;
}

vtkChartXY* Chart::GetChart()
{
  return this->XY;
}

void Chart::Write(const std::string& png)
{
  this->View->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(this->View->GetRenderWindow());
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(png.c_str());
  writer->Write();
}
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The main demo: renders (1) three crossing synthetic horizons with holes and a well path as a
// VTK tube, and (2) the four Reek horizons (Irap binary grids on a rotated UTM-scale grid), and
// writes one PNG per scene. Usage: StrataDemo <output-dir> <data-dir>...; the first data dir
// that holds horizons/reek_01_topreek_rota.gri is used. Prints each image's path, last.
#include "StrataHeightFieldScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricSpline.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkTubeFilter.h"
#include "vtkWindowToImageFilter.h"

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
std::string Save(vtkRenderWindow* win, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}
}

int main(int argc, char* argv[])
{
  const std::string out = argc > 1 ? argv[1] : ".";
  std::vector<std::string> written;

  // --- Scene 1: synthetic stack + well.
  {
    auto horizons = strata_test::MakeDemoHorizons(321, 241, 600000.0, 6700000.0, 6.25, 0.0);
    vtkNew<vtkStackedHeightFieldMapper> mapper;
    for (auto& h : horizons)
    {
      mapper->AddInputDataObject(h);
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetSpecular(0.25);
    actor->GetProperty()->SetSpecularPower(30);
    actor->SetScale(1, 1, 1.5);

    // A deviated well through all three horizons.
    vtkNew<vtkPoints> pts;
    pts->InsertNextPoint(600600, 6700500, 150);
    pts->InsertNextPoint(600700, 6700650, -250);
    pts->InsertNextPoint(600950, 6700800, -600);
    pts->InsertNextPoint(601300, 6700900, -1000);
    vtkNew<vtkParametricSpline> spline;
    spline->SetPoints(pts);
    vtkNew<vtkParametricFunctionSource> path;
    path->SetParametricFunction(spline);
    path->SetUResolution(200);
    vtkNew<vtkTubeFilter> tube;
    tube->SetInputConnection(path->GetOutputPort());
    tube->SetRadius(14);
    tube->SetNumberOfSides(24);
    vtkNew<vtkPolyDataMapper> wellMapper;
    wellMapper->SetInputConnection(tube->GetOutputPort());
    vtkNew<vtkActor> well;
    well->SetMapper(wellMapper);
    well->GetProperty()->SetColor(0.95, 0.95, 0.9);
    well->SetScale(1, 1, 1.5);

    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0.08, 0.09, 0.12);
    ren->SetBackground2(0.3, 0.33, 0.4);
    ren->GradientBackgroundOn();
    win->AddRenderer(ren);
    ren->AddActor(actor);
    ren->AddActor(well);
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetFocalPoint(601000, 6700750, -650);
    cam->SetPosition(599300, 6698600, 900);
    cam->SetViewUp(0, 0, 1);
    ren->ResetCameraClippingRange();
    win->Render();
    written.push_back(Save(win, out + "/strata-horizons-synthetic.png"));
  }

  // --- Scene 2: the four Reek horizons.
  std::string reekDir;
  for (int a = 2; a < argc && reekDir.empty(); ++a)
  {
    std::ifstream probe(std::string(argv[a]) + "/horizons/reek_01_topreek_rota.gri");
    if (probe)
    {
      reekDir = std::string(argv[a]) + "/horizons/";
    }
  }
  if (reekDir.empty())
  {
    std::cerr << "Reek horizons not found in the data directories given; skipping that image.\n";
  }
  else
  {
    const char* names[4] = { "reek_01_topreek_rota.gri", "reek_02_midreek_rota.gri",
      "reek_03_lowreek_rota.gri", "reek_04_basereek_rota.gri" };
    vtkNew<vtkStackedHeightFieldMapper> mapper;
    std::vector<vtkSmartPointer<vtkIrapBinaryGridReader>> readers;
    for (const char* name : names)
    {
      auto reader = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
      reader->SetFileName((reekDir + name).c_str());
      mapper->AddInputConnection(reader->GetOutputPort());
      readers.push_back(reader);
    }
    mapper->SetHeightScale(-1.0); // depths grow downwards
    mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetScale(1, 1, 8); // 8x vertical exaggeration: the reservoir is thin
    actor->GetProperty()->SetSpecular(0.2);
    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0.08, 0.09, 0.12);
    win->AddRenderer(ren);
    ren->AddActor(actor);
    double b[6];
    actor->GetBounds(b);
    vtkCamera* cam = ren->GetActiveCamera();
    const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    cam->SetFocalPoint(c);
    cam->SetPosition(c[0] - 0.9 * (b[1] - b[0]), c[1] - 1.1 * (b[3] - b[2]), c[2] + 0.8 * (b[1] - b[0]));
    cam->SetViewUp(0, 0, 1);
    ren->ResetCamera();
    cam->Zoom(1.3);
    ren->ResetCameraClippingRange();
    win->Render();
    written.push_back(Save(win, out + "/strata-horizons-reek.png"));
  }
  for (const auto& path : written)
  {
    std::cout << path << "\n";
  }
  return written.empty() ? 1 : 0;
}

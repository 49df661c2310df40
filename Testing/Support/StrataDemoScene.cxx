// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataDemoScene.h"
#include "StrataHeightFieldScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricSpline.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkTubeFilter.h"

namespace strata_test
{
DemoScene AddDemoScene(vtkRenderer* ren)
{
  DemoScene s;
  s.Horizons = MakeDemoHorizons(321, 241, 600000.0, 6700000.0, 6.25, 0.0);
  s.Mapper = vtkSmartPointer<vtkStackedHeightFieldMapper>::New();
  for (auto& h : s.Horizons)
  {
    s.Mapper->AddInputDataObject(h);
  }
  s.Stack = vtkSmartPointer<vtkActor>::New();
  s.Stack->SetMapper(s.Mapper);
  s.Stack->GetProperty()->SetSpecular(0.25);
  s.Stack->GetProperty()->SetSpecularPower(30);
  s.Stack->SetScale(1, 1, 1.5);

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
  s.Well = vtkSmartPointer<vtkActor>::New();
  s.Well->SetMapper(wellMapper);
  s.Well->GetProperty()->SetColor(0.95, 0.95, 0.9);
  s.Well->SetScale(1, 1, 1.5);

  // The target: centred on the top horizon's mean depth (300 m) so that the horizon cuts it.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(601200, 6700450, -300 * 1.5);
  sphere->SetRadius(150);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  s.Target = vtkSmartPointer<vtkActor>::New();
  s.Target->SetMapper(sphereMapper);
  s.Target->GetProperty()->SetColor(0.95, 0.75, 0.2);

  ren->SetBackground(0.08, 0.09, 0.12);
  ren->SetBackground2(0.3, 0.33, 0.4);
  ren->GradientBackgroundOn();
  ren->AddActor(s.Stack);
  ren->AddActor(s.Well);
  ren->AddActor(s.Target);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(601000, 6700750, -650);
  cam->SetPosition(599300, 6698600, 900);
  cam->SetViewUp(0, 0, 1);
  ren->ResetCameraClippingRange();
  return s;
}

void FrameReekScene(vtkRenderer* ren, vtkActor* actor, double zoom)
{
  double b[6];
  actor->GetBounds(b);
  vtkCamera* cam = ren->GetActiveCamera();
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  cam->SetFocalPoint(c);
  cam->SetPosition(
    c[0] - 0.9 * (b[1] - b[0]), c[1] - 1.1 * (b[3] - b[2]), c[2] + 0.8 * (b[1] - b[0]));
  cam->SetViewUp(0, 0, 1);
  ren->ResetCamera();
  cam->Zoom(zoom);
  ren->ResetCameraClippingRange();
}
}

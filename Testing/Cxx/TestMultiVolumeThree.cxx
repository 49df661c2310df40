// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Three" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestMultiVolumeThree(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Three volumes of different resolution, orientation and scalar type (float, unsigned
  // 16-bit, signed 16-bit: the integer ones hold the blob values rounded, which the
  // reference reads as well), all overlapping in the middle.
  auto cast = [](vtkImageData* image, int type)
  {
    vtkNew<vtkImageCast> c;
    c->SetInputData(image);
    c->SetOutputScalarType(type);
    c->Update();
    auto out = vtkSmartPointer<vtkImageData>::New();
    out->ShallowCopy(c->GetOutput());
    return out;
  };
  VolumeScene s(paths.Output);
  s.Add(Blob(36, 36, 30, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t1;
  t1->Translate(20, 14, 6);
  t1->RotateWXYZ(40, 1, 1, 0);
  s.Add(cast(Blob(20, 22, 18, 1.5, 1.4, 1.3, 0, 0, 0, 2), VTK_UNSIGNED_SHORT),
    MakeVolumeProperty(1),
    t1);
  vtkNew<vtkTransform> t2;
  t2->Translate(8, 24, -4);
  t2->RotateZ(-25);
  s.Add(cast(Blob(30, 14, 24, 1.2, 2.0, 1.1, 0, 0, 0, 3), VTK_SHORT), MakeVolumeProperty(2), t2);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 22, 22, 12 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("Three"), "Three", 0.4, 2, 3000);
  std::cout << "Three: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  return CaseResult(ok, output);
}

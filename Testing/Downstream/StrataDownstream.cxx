// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The downstream consumer: one flat horizon of 100 x 50 points (spacing 1) seen straight down
// through a parallel camera. Its image covers a rectangle whose area in pixels is known exactly,
// so the test can tell a working install (library, headers, autoinit, EGL window, shaders) from
// one that links but draws nothing. Prints one line and exits non-zero on failure.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdio>
#include <cstring>

int main()
{
  const int nx = 100, ny = 50, size = 128;
  vtkNew<vtkImageData> horizon;
  horizon->SetDimensions(nx, ny, 1);
  vtkNew<vtkFloatArray> depth;
  depth->SetNumberOfValues(nx * ny);
  for (int i = 0; i < nx * ny; ++i)
  {
    depth->SetValue(i, -10.0f);
  }
  horizon->GetPointData()->SetScalars(depth);

  vtkNew<vtkStackedHeightFieldMapper> mapper;
  mapper->AddInputDataObject(horizon);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  ren->SetBackground(0, 0, 0);
  vtkNew<vtkRenderWindow> win;
  win->SetSize(size, size);
  win->AddRenderer(ren);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->ParallelProjectionOn();
  cam->SetParallelScale(50.0); // half the window height in world units
  cam->SetFocalPoint(49.5, 24.5, -10.0);
  cam->SetPosition(49.5, 24.5, 100.0);
  cam->SetViewUp(0, 1, 0);
  ren->ResetCameraClippingRange();
  win->Render();

  vtkNew<vtkUnsignedCharArray> rgb;
  win->GetPixelData(0, 0, size - 1, size - 1, 0, rgb);
  long covered = 0;
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    covered += (rgb->GetValue(3 * i) + rgb->GetValue(3 * i + 1) + rgb->GetValue(3 * i + 2)) > 0;
  }
  // The rectangle is 99 x 49 world units at size / 100 pixels per unit; pixels are counted by
  // centre, so the count can differ from the area by at most one row and one column.
  const double ppu = size / 100.0;
  const double expected = (99 * ppu) * (49 * ppu);
  const double slack = 99 * ppu + 49 * ppu + 1;
  const bool ok = std::abs(covered - expected) <= slack;
  std::printf("downstream: window %s, covered %ld px, expected %.1f +- %.1f: %s\n",
    win->GetClassName(),
    covered,
    expected,
    slack,
    ok ? "ok" : "FAILED");
  return ok && std::strcmp(win->GetClassName(), "vtkStrataEGLRenderWindow") == 0 ? 0 : 1;
}

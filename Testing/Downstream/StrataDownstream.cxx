// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The downstream consumer: one flat horizon of 100 x 50 points (spacing 1) seen straight down
// through a parallel camera. Its image covers a rectangle whose area in pixels is known exactly,
// so the test can tell a working install (library, headers, autoinit, EGL window, shaders) from
// one that links but draws nothing. Given a page pool (what the installed strata-convert made of
// the 554 x 451 Reek horizon), it also reads the pool back at full resolution with
// vtkPagePoolReader and prints its dimensions. Prints one line per check and exits non-zero on
// failure.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace
{
/// Reads the tile pool at `path` whole; true when it is the 554 x 451 x 1 Reek grid.
bool ReadPool(const char* path)
{
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path);
  reader->Update();
  int dims[3] = { 0, 0, 0 };
  reader->GetOutput()->GetDimensions(dims);
  const bool ok = reader->GetIsTilePool() && dims[0] == 554 && dims[1] == 451 && dims[2] == 1 &&
                  reader->GetOutput()->GetPointData()->GetScalars() != nullptr;
  std::printf("downstream: pool from the installed strata-convert: %d x %d x %d points, %lld "
              "pages read: %s\n",
    dims[0],
    dims[1],
    dims[2],
    static_cast<long long>(reader->GetNumberOfPagesRead()),
    ok ? "ok" : "FAILED");
  return ok;
}
}

int main(int argc, char* argv[])
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
  const bool poolOk = argc < 2 || ReadPool(argv[1]);
  return ok && poolOk && std::strcmp(win->GetClassName(), "vtkStrataEGLRenderWindow") == 0 ? 0 : 1;
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Plain vtkRenderWindow::New() must give Strata's EGL window (no X server here), render a lit
// sphere correctly, survive a resize, read back depth, and print nothing at all on the way:
// in particular not VTK's "GLEW could not be initialized". With --provoke-gl-error (the
// ctest TestGLDebugOutput) it makes one GL error on purpose: the suite's GL debug output must
// print it as "Strata GL debug:" (the line that fails every other test) and count it.
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStrataEGLRenderWindow.h"

#include "vtk_glew.h"

#include <cmath>
#include <cstring>
#include <iostream>

namespace
{
/// One GL error on purpose (a texture name never generated, GL_INVALID_OPERATION in a core
/// profile), seen by the window's GL debug output: prints the count and the captured message.
int ProvokeGLError(vtkRenderWindow* win, strata_test::CapturingOutputWindow* capture)
{
  auto* egl = vtkStrataEGLRenderWindow::SafeDownCast(win);
  win->SetSize(32, 32);
  win->Render();
  if (!egl->GetGLDebugOutput())
  {
    std::cout << "GLDebugOutput is off: run with STRATA_GL_DEBUG=1\n";
    return EXIT_FAILURE;
  }
  win->MakeCurrent();
  glBindTexture(GL_TEXTURE_2D, 0x7fffff);
  glBindTexture(GL_TEXTURE_2D, 0);
  const bool captured = capture->Errors == 1 && capture->Messages.size() == 1 &&
                        capture->Messages[0].find("GL debug output") != std::string::npos;
  std::cout << "GLDebugOutput: " << egl->GetNumberOfGLDebugErrors() << " error counted, "
            << (captured ? "raised" : "not raised") << " through vtkErrorMacro" << std::endl;
  return egl->GetNumberOfGLDebugErrors() == 1 && captured ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

int TestEGLRenderWindow(int argc, char* argv[])
{
  auto* capture = strata_test::CapturingOutputWindow::Install();

  vtkSmartPointer<vtkRenderWindow> win = vtkSmartPointer<vtkRenderWindow>::New();
  auto* egl = vtkStrataEGLRenderWindow::SafeDownCast(win);
  if (!egl)
  {
    std::cerr << "vtkRenderWindow::New() returned " << win->GetClassName()
              << ", not vtkStrataEGLRenderWindow\n";
    return EXIT_FAILURE;
  }
  if (argc > 1 && std::strcmp(argv[1], "--provoke-gl-error") == 0)
  {
    return ProvokeGLError(win, capture);
  }
  win->SetSize(128, 96);
  win->SetMultiSamples(0);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.0, 0.0, 0.0);
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 0.5, 0.0);
  ren->AddActor(actor);
  ren->ResetCamera();
  win->Render();

  std::cout << "platform " << egl->GetPlatformName() << ", renderer " << egl->GetRendererName()
            << "\n";
  int failures = 0;
  auto check = [&](bool ok, const std::string& what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };

  // The sphere fills the middle of the view and leaves the corners black; its lit centre is
  // orange (red > green > blue), as VTK's headlight on (1, 0.5, 0) gives.
  auto rgb = strata_test::ReadRGB(win);
  const int w = 128, h = 96;
  const unsigned char* c = &rgb[3 * ((h / 2) * w + w / 2)];
  check(c[0] > 200 && c[1] > 80 && c[1] < 160 && c[2] < 20, "centre pixel is lit orange");
  const unsigned char* corner = &rgb[0];
  check(corner[0] == 0 && corner[1] == 0 && corner[2] == 0, "corner pixel is background");
  long lit = 0;
  for (size_t i = 0; i < rgb.size() / 3; ++i)
  {
    lit += rgb[3 * i] > 0 ? 1 : 0;
  }
  // ResetCamera puts the camera at d = r_box / sin(15 deg) from the centre, r_box = sqrt(3)/2
  // for the unit sphere's bounding box; the sphere (radius 0.5) then subtends asin(0.5 / d) and
  // projects to a disc of radius (h/2) tan(asin(0.5/d)) / tan(15 deg) pixels. The 48-segment
  // tessellation is inscribed, so the lit area is slightly less: allow 4 %.
  const double pi = std::acos(-1.0);
  const double d = (std::sqrt(3.0) / 2.0) / std::sin(15.0 * pi / 180.0);
  const double rpx = (h / 2.0) * std::tan(std::asin(0.5 / d)) / std::tan(15.0 * pi / 180.0);
  const double expected = pi * rpx * rpx;
  std::cout << "lit pixels " << lit << ", analytic disc " << expected << "\n";
  check(std::abs(lit - expected) < 0.04 * expected, "sphere covers the analytic disc area");

  // Depth: the sphere's front is nearer than the far plane; background depth is 1.
  auto depth = strata_test::ReadDepth(win);
  check(depth[(h / 2) * w + w / 2] < 0.999f, "centre depth in front of far plane");
  check(depth[0] == 1.0f, "background depth is 1");

  // Resizing recreates the pbuffer; the image follows the new size.
  win->SetSize(64, 64);
  win->Render();
  auto small = strata_test::ReadRGB(win);
  check(small.size() == 64 * 64 * 3, "resized read-back");
  check(small[3 * (32 * 64 + 32)] > 200, "resized render lit centre");

  check(capture->Errors == 0 && capture->Warnings == 0 && capture->Messages.empty(),
    "nothing printed through VTK's output window");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

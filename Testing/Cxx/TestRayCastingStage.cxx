// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The compute stage (strata::ComputeStage) and the choice of stage: the rewrite of a fragment
// source and what it refuses, the screen rectangles, both mappers' images in both stages
// (within the portability policy for two programs computing the same value), and Auto, which
// must pick what its probe measured faster, report the probe's ratio and probe a device once.
// Every other ray-caster image test runs in both stages too (Testing/Cxx/CMakeLists.txt).
#include "StrataComputeStage.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;
using Stage = strata::ComputeStage;

// Two renderings of the same scene: the largest channel difference and the pixels beyond the
// policy's two-program bound, which must be at most its edge fraction.
template<typename T>
void CheckSame(const std::vector<T>& a,
  const std::vector<T>& b,
  int channels,
  double scale,
  const std::string& what)
{
  Check(a.size() == b.size() && !a.empty(), what + ": both images read back");
  if (a.size() != b.size() || a.empty())
    return;
  double worst = 0.0;
  long beyond = 0, differing = 0;
  const long pixels = static_cast<long>(a.size() / channels);
  for (long p = 0; p < pixels; ++p)
  {
    double d = 0.0;
    for (int c = 0; c < channels; ++c)
      d = std::max(d, std::abs(double(a[p * channels + c]) - double(b[p * channels + c])) * scale);
    worst = std::max(worst, d);
    differing += d > 0.0 ? 1 : 0;
    beyond += d > ImagePolicy::TwoProgramsMax ? 1 : 0;
  }
  const long allowed = static_cast<long>(ImagePolicy::EdgePixelFraction * pixels);
  std::cout << what << ": fragment vs compute, " << differing << " of " << pixels
            << " pixels differ, max " << worst << " of 255, " << beyond << " beyond 1 (at most "
            << allowed << ")\n";
  Check(beyond <= allowed, what + ": compute within the two-program policy of fragment");
}

long Covered(const std::vector<unsigned char>& rgb, const std::vector<unsigned char>& background)
{
  long n = 0;
  for (size_t p = 0; p + 2 < rgb.size(); p += 3)
    n += (rgb[p] != background[p] || rgb[p + 1] != background[p + 1] ||
           rgb[p + 2] != background[p + 2])
           ? 1
           : 0;
  return n;
}

void Rewrite()
{
  const std::string body = "//VTK::System::Dec\n//VTK::Output::Dec\nuniform float u;\n"
                           "void main()\n{\n  if (gl_FragCoord.x < u)\n  {\n    discard;\n  }\n"
                           "  gl_FragData[0] = vec4(u);\n  gl_FragDepth = gl_DepthRange.near;\n}\n";
  std::string error;
  Stage::Outputs blended;
  blended.Blending = Stage::Blend::FrontToBack;
  const std::string cs = Stage::FromFragment(body, blended, error);
  Check(error.empty() && !cs.empty(), "a fragment source becomes a compute source: " + error);
  Check(cs.find("#version 430 core") == 0, "it declares GLSL 4.30 first");
  Check(cs.find("layout(local_size_x = 8, local_size_y = 8) in;") != std::string::npos,
    "it declares 8 x 8 work groups");
  Check(cs.find("gl_Frag") == std::string::npos && cs.find("gl_DepthRange") == std::string::npos,
    "no fragment built-in is left");
  Check(cs.find("void strataFragmentMain()") != std::string::npos &&
          cs.find("strataDiscarded = true;\n    return;") != std::string::npos,
    "main is a function, discard a return");
  Check(cs.find("strataFragData[0] * (1.0 - dst.a) + dst") != std::string::npos,
    "front-to-back outputs blend as (1 - destination alpha, 1)");
  Check(cs.find("image2D uStrataDepth") == std::string::npos, "a blended program stages no depth");
  Stage::Outputs staged;
  staged.Staged = true;
  staged.Count = 2;
  const std::string st = Stage::FromFragment(body, staged, error);
  Check(st.find("image2D uStrataDepth") != std::string::npos &&
          st.find("image2D uStrataOutput1") != std::string::npos &&
          st.find("imageLoad") == std::string::npos,
    "a staged program stores two colours and its depth, loading nothing");
  const std::pair<std::string, std::string> refused[] = {
    { "//VTK::System::Dec\n//VTK::Output::Dec\nvoid f()\n{\n  discard;\n}\nvoid main()\n{\n}\n",
      "discard outside main" },
    { "//VTK::System::Dec\n//VTK::Output::Dec\nin vec3 p;\nvoid main()\n{\n}\n", "an input" },
    { "//VTK::System::Dec\n//VTK::Output::Dec\nvoid main()\n{\n  float x = dFdx(1.0);\n}\n",
      "a derivative" },
    { "//VTK::Output::Dec\nvoid main()\n{\n}\n", "no system tag" },
  };
  for (const auto& r : refused)
  {
    error.clear();
    const std::string none = Stage::FromFragment(r.first, blended, error);
    Check(none.empty() && !error.empty(), "refused, " + r.second + ": " + error);
  }
}

void ScreenRects()
{
  vtkNew<vtkMatrix4x4> identity;
  const int size[2] = { 100, 80 };
  const double square[6] = { -0.5, -0.5, 0.0, 0.5, 0.5, 0.0 };
  int rect[4];
  Check(Stage::ScreenRect(identity, square, 2, size, 0.0, rect) && rect[0] == 24 && rect[1] == 19 &&
          rect[2] == 52 && rect[3] == 42,
    "NDC [-0.5, 0.5]^2 in 100 x 80 is pixels [24, 76) x [19, 61) with a pixel's margin");
  Check(Stage::ScreenRect(identity, square, 2, size, 2.0, rect) && rect[0] == 22 && rect[2] == 56,
    "two pixels of dilation widen it by two on each side");
  const double outside[6] = { 2.0, 2.0, 0.0, 3.0, 3.0, 0.0 };
  Check(!Stage::ScreenRect(identity, outside, 2, size, 0.0, rect), "off screen: empty");
  vtkNew<vtkMatrix4x4> perspective; // w = -z: the eye looks down -z
  perspective->SetElement(3, 2, -1.0);
  perspective->SetElement(3, 3, 0.0);
  const double behind[6] = { -1.0, -1.0, -2.0, 1.0, 1.0, 3.0 };
  Check(Stage::ScreenRect(perspective, behind, 2, size, 0.0, rect) && rect[0] == 0 &&
          rect[1] == 0 && rect[2] == 100 && rect[3] == 80,
    "a point behind the eye: the whole viewport");
}

void VolumeStages(const TestPaths& paths)
{
  struct Case
  {
    const char* Name;
    int Rays;
    bool BackToFront;
    int Mode;
  };
  const Case cases[] = {
    { "two volumes, front to back", 1, false, vtkVolumeMapper::COMPOSITE_BLEND },
    { "two volumes, back to front, 2 rays", 2, true, vtkVolumeMapper::COMPOSITE_BLEND },
    { "two volumes, maximum intensity", 1, false, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
  };
  for (const Case& c : cases)
  {
    VolumeScene s(paths.Output);
    AddTwoVolumes(s);
    s.Mapper->SetRaysPerPixel(c.Rays);
    s.Mapper->SetBlendMode(c.Mode);
    if (c.BackToFront)
      s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
    std::vector<unsigned char> images[2];
    const vtkMultiVolumeRayCastMapper::Stages stages[2] = {
      vtkMultiVolumeRayCastMapper::Stages::Fragment, vtkMultiVolumeRayCastMapper::Stages::Compute
    };
    for (int k = 0; k < 2; ++k)
    {
      s.Mapper->SetStage(stages[k]);
      s.Win->Render();
      images[k] = ReadRGB(s.Win);
      Check(s.Mapper->GetStageInUse() == stages[k],
        std::string(c.Name) + ": the frame ran in " +
          Stage::StageName(static_cast<int>(stages[k])));
    }
    const long covered = Covered(images[1],
      std::vector<unsigned char>(images[1].size(), images[1].empty() ? 0 : images[1][0]));
    Check(covered > 1000,
      std::string(c.Name) + ": the compute image shows the volumes (" + std::to_string(covered) +
        " pixels off the corner's colour)");
    CheckSame(images[0], images[1], 3, 1.0, c.Name);
  }
}

void HeightFieldStages(const TestPaths&)
{
  const auto horizons = MakeDemoHorizons();
  struct Case
  {
    const char* Name;
    vtkStackedHeightFieldMapper::OutputModes Output;
    double Opacity; // of horizon 1
  };
  const Case cases[] = {
    { "horizons, shaded", vtkStackedHeightFieldMapper::OutputModes::Shaded, 1.0 },
    { "horizons, ids", vtkStackedHeightFieldMapper::OutputModes::HorizonId, 1.0 },
  };
  for (const Case& c : cases)
  {
    vtkSmartPointer<vtkRenderWindow> win;
    vtkSmartPointer<vtkRenderer> ren;
    MakeWindow(win, ren);
    vtkNew<vtkStackedHeightFieldMapper> mapper;
    for (const auto& h : horizons)
      mapper->AddInputData(h);
    mapper->SetOutputMode(c.Output);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    ren->AddActor(actor);
    ren->ResetCamera();
    ren->GetActiveCamera()->Elevation(35.0);
    ren->GetActiveCamera()->Azimuth(20.0);
    ren->ResetCameraClippingRange();
    std::vector<unsigned char> rgb[2];
    std::vector<float> depth[2];
    const vtkStackedHeightFieldMapper::Stages stages[2] = {
      vtkStackedHeightFieldMapper::Stages::Fragment, vtkStackedHeightFieldMapper::Stages::Compute
    };
    for (int k = 0; k < 2; ++k)
    {
      mapper->SetStage(stages[k]);
      win->Render();
      rgb[k] = ReadRGB(win);
      depth[k] = ReadDepth(win);
      Check(mapper->GetStageInUse() == stages[k],
        std::string(c.Name) + ": the frame ran in " +
          Stage::StageName(static_cast<int>(stages[k])));
    }
    long hit = 0;
    for (float z : depth[1])
      hit += z < 1.0f ? 1 : 0;
    Check(hit > 5000,
      std::string(c.Name) + ": the compute stage hit " + std::to_string(hit) + " pixels of " +
        std::to_string(depth[1].size()));
    CheckSame(rgb[0], rgb[1], 3, 1.0, std::string(c.Name) + ", colour");
    // Depth in 1/255 of 1e-4 of the depth range: a bound far below any visible error.
    CheckSame(depth[0], depth[1], 1, 255.0 / 1e-4 / 255.0, std::string(c.Name) + ", depth (1e-4)");
  }
}

void Auto(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  AddTwoVolumes(s);
  s.Mapper->SetStageToAuto();
  s.Win->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(s.Win);
  gl->MakeCurrent();
  const Stage::ProbeResult probe = Stage::Probe(gl);
  std::cout << "Auto's probe on " << probe.Renderer << ": fragment " << probe.FragmentMs
            << " ms, compute " << probe.ComputeMs << " ms, ratio " << probe.Ratio() << "; chose "
            << s.Mapper->GetStageInUseAsString() << "\n";
  Check(probe.Measured && probe.FragmentMs > 0.0 && probe.ComputeMs > 0.0,
    "the probe measured both stages");
  const auto expected = probe.ComputeMs < probe.FragmentMs
                          ? vtkMultiVolumeRayCastMapper::Stages::Compute
                          : vtkMultiVolumeRayCastMapper::Stages::Fragment;
  Check(s.Mapper->GetStageInUse() == expected, "Auto picked the stage its probe measured faster");
  Check(std::abs(s.Mapper->GetStageProbeRatio() - probe.Ratio()) < 1e-12,
    "the mapper reports the probe's ratio");

  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren);
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  for (const auto& h : MakeDemoHorizons())
    mapper->AddInputData(h);
  mapper->SetStageToAuto();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  win->Render();
  Check(static_cast<int>(mapper->GetStageInUse()) == static_cast<int>(expected),
    "the height-field mapper's Auto agrees on the same device");
  Check(Stage::GetNumberOfProbes() == 1,
    "one probe per renderer string in the process (" + std::to_string(Stage::GetNumberOfProbes()) +
      ")");
}
}

int TestRayCastingStage(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<SubTest> parts;
  parts.push_back({ "rewrite", [] { Rewrite(); } });
  parts.push_back({ "screen rectangles", [] { ScreenRects(); } });
  parts.push_back({ "volumes in both stages", [&paths] { VolumeStages(paths); } });
  parts.push_back({ "horizons in both stages", [&paths] { HeightFieldStages(paths); } });
  parts.push_back({ "auto", [&paths] { Auto(paths); } });
  parts.push_back({ "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } });
  return RunSubTests(parts, Failures);
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Level-of-detail feedback of the paged multi-volume ray caster: an opaque volume in front of
// a second one that it hides completely. With feedback the rays stop in the front volume's
// first layer of bricks, so the hidden volume keeps its root alone and the front volume's
// interior stays coarse, while the screen-space cut refines both everywhere; both images equal
// the in-core rendering with every brick. Seen from the other side (the hidden volume now in
// front, semi-transparent) the feedback refines it. Also: the CPU and OpenCL reductions drive
// the same cut, every feedback scale hides the same volume, and LevelOfDetailThreshold makes the
// rays ask for a coarser level.
//
// Bounds (StrataImagePolicy.h): a paged image against the in-core one is rule 2, paged vs in
// core (with feedback another program; with or without, bricks from pages in other atlas slots
// than the in-core upload's): 1 of 255, ImagePolicy::TwoProgramsMax. The CPU and the OpenCL
// reduction only choose the cut; the drawing program is the same, and nearest interpolation
// makes the slots' placement exact, so their images are bit-exact (ImagePolicy::SameProgramMax,
// rule 1). Resident bricks are counts: exact.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <numeric>
#include <string>
#include <thread>

using namespace strata_test;

namespace
{
const int Size = 128;
const int Page = 16;
const int Edge = 61; // 4^3 level-0 bricks of stride 15, 73 nodes

std::string Levels(const std::vector<int>& counts)
{
  std::string text;
  for (size_t l = 0; l < counts.size(); ++l)
    text += (l ? "/" : "") + std::to_string(counts[l]);
  return text;
}

int Total(const std::vector<int>& counts)
{
  return std::accumulate(counts.begin(), counts.end(), 0);
}

// Volume 0 (x in [0, 60]) is opaque wherever it has data; volume 1 (x in [80, 140]) is the
// semi-transparent blob. Nearest interpolation, so that bricks in other atlas slots than the
// in-core upload chose give bit-identical samples (see TestMultiVolumePaging).
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkMultiVolume> Multi;
  vtkSmartPointer<vtkVolume> Volumes[2];
  Scene()
  {
    MakeWindow(this->Win, this->Ren, Size, Size);
    auto opaque = MakeVolumeProperty(1);
    vtkPiecewiseFunction* a = opaque->GetScalarOpacity(0);
    a->RemoveAllPoints();
    a->AddPoint(0, 1.0);
    a->AddPoint(100, 1.0);
    auto blob = MakeVolumeProperty(0);
    for (auto* p : { opaque.GetPointer(), blob.GetPointer() })
      p->SetInterpolationTypeToNearest();
    vtkVolumeProperty* properties[2] = { opaque, blob };
    for (int i = 0; i < 2; ++i)
    {
      this->Volumes[i] = vtkSmartPointer<vtkVolume>::New();
      this->Volumes[i]->SetProperty(properties[i]);
      vtkNew<vtkTransform> t;
      t->Translate(80.0 * i, 0, 0);
      this->Volumes[i]->SetUserTransform(t);
      this->Multi->SetVolume(this->Volumes[i], i);
    }
    this->Ren->AddVolume(this->Multi);
  }
  /// From the side of volume 0 (front = true), or from behind volume 1, on the x axis.
  void Camera(bool front)
  {
    vtkCamera* cam = this->Ren->GetActiveCamera();
    cam->SetFocalPoint(70, 30, 30);
    cam->SetPosition(front ? -90 : 230, 30, 30);
    cam->SetViewUp(0, 0, 1);
    cam->SetViewAngle(30);
    this->Ren->ResetCameraClippingRange(0, 140, 0, 60, 0, 60);
  }
  std::vector<unsigned char> Render(vtkMultiVolumeRayCastMapper* mapper)
  {
    this->Multi->SetMapper(mapper);
    this->Win->Render();
    return ReadRGB(this->Win);
  }
  /// Renders until the paged mapper has converged (at most 400 frames); the frame count or -1.
  int Converge(vtkMultiVolumeRayCastMapper* mapper, std::vector<unsigned char>& image)
  {
    for (int f = 1; f <= 400; ++f)
    {
      image = this->Render(mapper);
      if (mapper->GetPagingStatistics().Converged)
        return f;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return -1;
  }
};

void Configure(vtkMultiVolumeRayCastMapper* m)
{
  m->SetSampleDistance(0.5);
  m->SetBrickSize(Page);
  m->SetAtlasBudget(64.0); // room for every brick of both volumes
}
}

int TestMultiVolumeFeedback(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { 0.0, 0.0, 0.0 };
  vtkSmartPointer<vtkImageData> images[2] = { MakeBlobVolume(Edge, Edge, Edge, spacing, origin, 5),
    MakeBlobVolume(Edge, Edge, Edge, spacing, origin, 3) };
  std::string pools[2];
  for (int i = 0; i < 2; ++i)
  {
    pools[i] = paths.Output + "/feedback-" + std::to_string(i) + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(images[i]);
    writer->SetFileName(pools[i].c_str());
    writer->SetPageSize(Page);
    Check(writer->Write(), "pool " + std::to_string(i) + " written");
  }
  Scene s;
  vtkNew<vtkMultiVolumeRayCastMapper> incore;
  Configure(incore);
  for (int i = 0; i < 2; ++i)
    incore->SetInputDataObject(i, images[i]);

  // A paged mapper over fresh readers.
  auto makePaged = [&](bool feedback)
  {
    auto m = vtkSmartPointer<vtkMultiVolumeRayCastMapper>::New();
    Configure(m);
    m->SetLevelOfDetailFeedback(feedback);
    for (int i = 0; i < 2; ++i)
    {
      vtkNew<vtkPagePoolReader> reader;
      reader->SetFileName(pools[i].c_str());
      m->SetInputConnection(i, reader->GetOutputPort());
    }
    return m;
  };

  // --- The hidden volume. Without feedback the screen-space cut refines what the frustum
  // holds, hidden or not; with feedback only what the rays reach before they are opaque.
  s.Camera(true);
  std::vector<unsigned char> reference;
  for (int i = 0; i < 3; ++i)
    reference = s.Render(incore);
  const auto incoreHidden = incore->GetResidentBricksPerLevel(1);
  std::vector<int> hidden[2], front[2];
  for (bool feedback : { false, true })
  {
    auto paged = makePaged(feedback);
    std::vector<unsigned char> image;
    const int frames = s.Converge(paged, image);
    const ChannelError e = ImageError(image, reference);
    hidden[feedback] = paged->GetResidentBricksPerLevel(1);
    front[feedback] = paged->GetResidentBricksPerLevel(0);
    const std::string what = feedback ? "feedback" : "screen-space cut";
    std::cout << "Feedback: hidden volume, " << what << ": converged after " << frames
              << " frames; resident bricks per "
              << "level: front volume " << Levels(front[feedback]) << ", hidden volume "
              << Levels(hidden[feedback]) << " (in core " << Levels(incoreHidden)
              << "); max difference to in core " << e.Max << "\n";
    Check(frames > 0 && e.Max <= ImagePolicy::TwoProgramsMax,
      "converged to the in-core image (" + what + ")");
  }
  // The hidden volume: its 58 visible level-0 bricks (6 of 64 are transparent) with the
  // screen-space cut, as in core; its root alone with feedback. The front volume: with
  // feedback its far half of bricks is never reached (rays stop at their first sample, in its
  // near half) and stays at level 1.
  Check(hidden[0] == incoreHidden && hidden[0][0] == 58,
    "screen-space cut: the hidden volume fully refined, as in core");
  Check(Total(hidden[1]) == 1 && hidden[1].back() == 1,
    "feedback: the hidden volume keeps its root alone");
  Check(front[1][0] > 0 && front[1][0] <= 32 && Total(front[1]) < Total(front[0]),
    "feedback: only the near half of the front volume's level-0 bricks is refined");

  // --- CPU and OpenCL reductions give the same lists, hence the same cut and image; and every
  // feedback scale keeps the hidden volume at its root.
  {
    std::vector<unsigned char> cpuImage, clImage;
    auto cpu = makePaged(true);
    cpu->FeedbackOpenCLOff();
    s.Converge(cpu, cpuImage);
    auto cl = makePaged(true);
    s.Converge(cl, clImage);
    std::cout << "Feedback: reduced on the "
              << (cl->GetPagingStatistics().FeedbackOpenCL ? "OpenCL device" : "CPU (no OpenCL)")
              << " and on the CPU: front volume " << Levels(cl->GetResidentBricksPerLevel(0))
              << " and " << Levels(cpu->GetResidentBricksPerLevel(0)) << "\n";
    Check(!cpu->GetPagingStatistics().FeedbackOpenCL, "FeedbackOpenCL off: reduced on the CPU");
    Check(cpu->GetResidentBricksPerLevel(0) == cl->GetResidentBricksPerLevel(0) &&
            cpu->GetResidentBricksPerLevel(1) == cl->GetResidentBricksPerLevel(1) &&
            ImageError(cpuImage, clImage).Max <= ImagePolicy::SameProgramMax,
      "CPU and OpenCL reductions drive the same cut and image");
    for (int scale : { 1, 8 })
    {
      auto m = makePaged(true);
      m->SetFeedbackScale(scale);
      std::vector<unsigned char> image;
      const int frames = s.Converge(m, image);
      std::cout << "Feedback: scale 1/" << scale << ": converged after " << frames
                << " frames; front volume " << Levels(m->GetResidentBricksPerLevel(0))
                << ", hidden volume " << Levels(m->GetResidentBricksPerLevel(1))
                << "; max difference " << ImageError(image, reference).Max << "\n";
      Check(frames > 0 && Total(m->GetResidentBricksPerLevel(1)) == 1 &&
              ImageError(image, reference).Max <= ImagePolicy::TwoProgramsMax,
        "feedback scale 1/" + std::to_string(scale) +
          ": hidden volume at its root, image as in core");
    }
  }

  // --- From the other side the blob is in front (semi-transparent) and the opaque volume
  // behind it: feedback follows the view and refines what is seen now.
  {
    auto paged = makePaged(true);
    std::vector<unsigned char> image;
    s.Converge(paged, image); // from the front first: the blob stays at its root
    s.Camera(false);
    for (int i = 0; i < 3; ++i)
      reference = s.Render(incore);
    const int frames = s.Converge(paged, image);
    const auto blob = paged->GetResidentBricksPerLevel(1);
    std::cout << "Feedback: from the other side: converged after " << frames << " frames; blob "
              << Levels(blob) << ", opaque volume " << Levels(paged->GetResidentBricksPerLevel(0))
              << "; max difference to in core " << ImageError(image, reference).Max << "\n";
    Check(
      frames > 0 && ImageError(image, reference).Max <= ImagePolicy::TwoProgramsMax && blob[0] > 32,
      "seen from the other side the blob is refined and the image equals the in-core one");
  }

  // --- LevelOfDetailThreshold: voxels of the front face cover about 2.4 pixels here (distance 90,
  // 239 pixels per radian); a threshold of 8 pixels asks for level 1 (4.8 pixels), not 0.
  {
    s.Camera(true);
    auto coarse = makePaged(true);
    coarse->SetLevelOfDetailThreshold(8.0);
    std::vector<unsigned char> image;
    const int frames = s.Converge(coarse, image);
    const auto levels = coarse->GetResidentBricksPerLevel(0);
    std::cout << "Feedback: LevelOfDetailThreshold 8 pixels: converged after " << frames
              << " frames; front volume " << Levels(levels) << "\n";
    Check(frames > 0 && levels[0] == 0 && levels[1] > 0,
      "LevelOfDetailThreshold 8: the front volume refined to level 1 only");
  }

  for (const std::string& pool : pools)
    std::remove(pool.c_str());
  Check(output->Errors == 0 && output->Warnings == 0, "no VTK errors or warnings");
  std::cout << (Failures() ? "FAILED" : "passed") << "\n";
  return Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}

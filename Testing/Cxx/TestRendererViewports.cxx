// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What a window does to a renderer between frames, for both ray casters: resized (render,
// resize, render) the image equals a fresh window's at the new size, and back at the first size
// the first image; a renderer off the window's origin (the right half of a window twice as
// wide) draws what a full window of its size draws. Both are the same program rendering the
// same scene, so both comparisons are bit-exact (StrataImagePolicy.h). The multi-volume scene
// has everything that lives in viewport-sized buffers: integration buffers, a MIP volume's
// layer buffers, a translucent plane's peel layers and their progress.
//
// And two mappers' uploads in one frame: a volume whose skip grid is uploaded (empty-space
// skipping) drawn before an 8-bit volume of odd width from a plain texture. The second is
// drawn the same with the first's skipping on or off: two programs, within 1 of 255.
//
// Before the fixes: after a resize the integration buffers kept the deleted textures attached
// (VTK re-attaches a vtkTextureObject only when the object changes), so the volumes vanished
// (0 lit pixels) for good; a renderer at x 0.5-1 drew no volume at all (VTK's scissor on the
// window rectangle clipped the buffers' clears and draws); a raw glPixelStorei left VTK's
// cached unpack alignment wrong and the 8-bit volume came out sheared (13000 pixels off, max
// 247).
#include "StrataHeightFieldCase.h"
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
#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;

/// Pixels with some channel off the background's (the bottom-left corner's) by more than 8.
long Lit(const std::vector<unsigned char>& rgb)
{
  long lit = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
    lit += std::abs(rgb[i] - rgb[0]) > 8 || std::abs(rgb[i + 1] - rgb[1]) > 8 ||
               std::abs(rgb[i + 2] - rgb[2]) > 8
             ? 1
             : 0;
  return lit;
}

/// Columns [x0, x0 + width) of an RGB image `fullWidth` wide.
std::vector<unsigned char> Columns(const std::vector<unsigned char>& rgb,
  int fullWidth,
  int x0,
  int width)
{
  std::vector<unsigned char> out;
  const int height = static_cast<int>(rgb.size() / (3 * fullWidth));
  for (int y = 0; y < height; ++y)
    out.insert(out.end(),
      rgb.begin() + 3 * (y * fullWidth + x0),
      rgb.begin() + 3 * (y * fullWidth + x0 + width));
  return out;
}

/// A scene in a window of its own (owned by the caller of `build`).
struct Scene
{
  vtkRenderWindow* Window;
  vtkRenderer* Renderer;
};

/// Render, resize to 96 x 112, render, back to the first size, render: against a fresh scene at
/// 96 x 112 and the first image; then the renderer on the right half of a window twice as wide.
void CheckViewports(const std::string& name,
  const std::function<Scene()>& build,
  int width,
  int height)
{
  Scene scene = build();
  vtkRenderWindow* win = scene.Window;
  win->SetSize(width, height);
  win->Render();
  const auto first = ReadRGB(win);
  win->SetSize(96, 112);
  win->Render();
  const auto resized = ReadRGB(win);
  win->SetSize(width, height);
  win->Render();
  const auto back = ReadRGB(win);

  Scene fresh = build();
  fresh.Window->SetSize(96, 112);
  fresh.Window->Render();
  const auto freshImage = ReadRGB(fresh.Window);
  const double toFresh = ImageError(resized, freshImage).Max;
  const double toFirst = ImageError(back, first).Max;
  std::cout << name << ": " << Lit(first) << " lit pixels at " << width << " x " << height << ", "
            << Lit(resized) << " resized to 96 x 112 (a fresh window " << Lit(freshImage)
            << "); max difference to the fresh window " << toFresh << ", back to the first size "
            << toFirst << "\n";
  Check(Lit(first) > 1000, name + ": the scene covers the view");
  Check(toFresh <= ImagePolicy::SameProgramMax,
    name + ": resized, the image is a fresh window's at the new size");
  Check(toFirst <= ImagePolicy::SameProgramMax, name + ": resized back, the first image again");

  // The renderer on the right half of a window twice as wide (nothing on the left).
  scene.Renderer->SetViewport(0.5, 0.0, 1.0, 1.0);
  win->SetSize(2 * width, height);
  win->Render();
  const auto right = Columns(ReadRGB(win), 2 * width, width, width);
  const double offOrigin = ImageError(right, first).Max;
  std::cout << name << ": renderer at x 0.5-1 of a " << 2 * width << " x " << height
            << " window: " << Lit(right) << " lit pixels, max difference to the full window "
            << offOrigin << "\n";
  Check(offOrigin <= ImagePolicy::SameProgramMax,
    name + ": a renderer off the window's origin draws what a full window draws");
}

/// Two overlapping volumes, the first drawn as MIP (layer buffers), and a translucent plane
/// crossing them (peel layers and progress).
struct VolumesScene
{
  std::unique_ptr<VolumeScene> S;
  vtkNew<vtkPlaneSource> Plane;
  vtkNew<vtkPolyDataMapper> PlaneMapper;
  vtkNew<vtkActor> PlaneActor;
  explicit VolumesScene(const std::string& output)
    : S(new VolumeScene(output))
  {
    AddTwoVolumes(*this->S);
    this->S->Mapper->SetInputBlendMode(0, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
    this->Plane->SetOrigin(-5, 18, -5);
    this->Plane->SetPoint1(60, 18, -5);
    this->Plane->SetPoint2(-5, 18, 40);
    this->PlaneMapper->SetInputConnection(this->Plane->GetOutputPort());
    this->PlaneActor->SetMapper(this->PlaneMapper);
    this->PlaneActor->GetProperty()->SetColor(1.0, 0.2, 0.1);
    this->PlaneActor->GetProperty()->SetOpacity(0.4);
    this->S->Mapper->AddTranslucentActor(this->PlaneActor);
  }
};

/// An 8-bit volume of odd width: stripes along x, which a sheared upload tilts.
vtkSmartPointer<vtkImageData> Stripes(int n, double ox)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetOrigin(ox, 0, 0);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* v = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        *v++ = static_cast<unsigned char>(
          k > 3 && k < n - 4 ? std::lround(255.0 * (0.5 + 0.5 * std::sin(0.7 * i))) : 0);
  return image;
}

vtkSmartPointer<vtkVolume> StripesVolume(vtkImageData* image, bool skipping, bool atlas)
{
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputDataObject(0, image);
  mapper->SetSampleDistance(0.5);
  mapper->SetEmptySpaceSkipping(skipping);
  mapper->SetUseBrickAtlas(atlas);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.2, 0.4, 0.9);
  color->AddRGBPoint(255, 1.0, 0.8, 0.3);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(255, 0.5);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  return volume;
}

/// The 8-bit volume beside a float one whose skip grid is uploaded first (`skipping`).
std::vector<unsigned char> RenderUploads(bool skipping)
{
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, 150, 150);
  auto first = Stripes(32, -40);
  auto second = Stripes(45, 0);
  auto a = StripesVolume(first, skipping, false);
  auto b = StripesVolume(second, false, false);
  ren->AddVolume(a);
  ren->AddVolume(b);
  ren->GetActiveCamera()->SetPosition(5, 22, 250);
  ren->GetActiveCamera()->SetFocalPoint(5, 22, 22);
  ren->ResetCameraClippingRange();
  win->Render();
  return ReadRGB(win);
}
}

int TestRendererViewports(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<std::unique_ptr<VolumesScene>> volumeScenes;
  std::vector<std::unique_ptr<HeightFieldScene>> horizonScenes;
  const auto volumes = [&]()
  {
    volumeScenes.emplace_back(new VolumesScene(paths.Output));
    VolumeScene* s = volumeScenes.back()->S.get();
    return Scene{ s->Win, s->Ren };
  };
  const auto horizons = [&]()
  {
    horizonScenes.emplace_back(new HeightFieldScene(paths.Output, MakeDemoHorizons()));
    HeightFieldScene* s = horizonScenes.back().get();
    const double pos[3] = { 1000, -900, 1300 }, foc[3] = { 1000, 750, 0 }, up[3] = { 0, 0, 1 };
    s->Camera(pos, foc, up);
    return Scene{ s->Win, s->Ren };
  };
  const int code = RunSubTests(
    {
      { "Volumes",
        [&]()
        {
          CheckViewports("Volumes", volumes, MultiVolumeCaseSize, MultiVolumeCaseSize);
          volumeScenes.clear();
        } },
      { "Horizons",
        [&]()
        {
          CheckViewports("Horizons", horizons, 160, 128);
          horizonScenes.clear();
        } },
      { "Uploads",
        [&]()
        {
          const auto plain = RenderUploads(false);
          const auto skipped = RenderUploads(true);
          const ChannelError e = ImageError(skipped, plain);
          std::cout << "Uploads: " << Lit(plain) << " lit pixels; with the other volume's skip "
                    << "grid uploaded first max difference " << e.Max << ", "
                    << PixelsOff(skipped, plain, 2) << " pixels off by more than 2\n";
          Check(Lit(plain) > 2000, "Uploads: both volumes are drawn");
          Check(e.Max <= ImagePolicy::TwoProgramsMax,
            "Uploads: another mapper's upload leaves the 8-bit volume's unchanged");
        } },
    },
    Failures);
  CheckNoVtkMessages(output);
  return code == EXIT_SUCCESS && Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

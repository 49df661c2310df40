// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What the cases of the multi-volume ray caster (Testing/Cxx/TestMultiVolume<Case>.cxx) share:
// a scene of volumes in one vtkMultiVolume and its camera, the analytic blob volumes, and the
// comparison of each rendering, pixel by pixel, with the double-precision reference integrator
// (StrataVolumeScenes).
//
// Bounds, in 8-bit units over all pixels: RMS <= 0.4 and max <= 2. Writing 8 bits alone costs up
// to 0.5 (RMS 0.29); the GPU samples every 1/4 voxel at segment midpoints along one lattice
// (second order: measured well under 0.3 of a step here) and filters in float. A half-voxel
// shift of the texture coordinates gives RMS 2.7-4.6, a colour 3 % off gives RMS 0.62-0.74:
// both fail.
#ifndef StrataMultiVolumeCase_h
#define StrataMultiVolumeCase_h

#include "StrataVolumeScenes.h" // For VolumeComparison

#include "StrataMultiVolumeReferenceIntegrator.h" // For Surface
#include "vtkActor.h"                             // For vtkActor
#include "vtkMultiVolume.h"                       // For vtkNew<vtkMultiVolume>
#include "vtkMultiVolumeRayCastMapper.h"          // For vtkNew<vtkMultiVolumeRayCastMapper>
#include "vtkNew.h"
#include "vtkPagePoolReader.h" // For WritePagedTwin's reader
#include "vtkPlaneSource.h"    // For vtkPlaneSource
#include "vtkPolyDataMapper.h" // For vtkPolyDataMapper
#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkGPUVolumeRayCastMapper;
class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkTransform;
class vtkVolume;
class vtkVolumeProperty;

namespace strata_test
{
class CapturingOutputWindow;

/// The cases' window: MultiVolumeCaseSize x MultiVolumeCaseSize pixels.
constexpr int MultiVolumeCaseSize = 128;

/// Volumes on the ports of one vtkMultiVolumeRayCastMapper (sample distance 1/4 voxel) in a
/// MultiVolumeCaseSize^2 window; its comparisons write their images to `ImageDirectory`.
struct VolumeScene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkMultiVolumeRayCastMapper> Mapper;
  vtkNew<vtkMultiVolume> Multi;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  std::vector<vtkSmartPointer<vtkVolume>> Volumes;
  std::string ImageDirectory;
  explicit VolumeScene(const std::string& imageDirectory);
  /// Adds an input on the next port, with a member volume carrying `property` and `transform`.
  vtkVolume* Add(vtkImageData* image,
    vtkVolumeProperty* property,
    vtkTransform* transform = nullptr);
  /// Single-volume use: an ordinary vtkVolume with this mapper.
  void UseSingleVolume();
  void UseMultiVolume();
  /// Looks from the direction of `pos` - `focal` at the centre of the volumes' world bounds, from
  /// where their bounding sphere just fills the view (computed here: vtkMultiVolume's bounds need
  /// a rendered vtkGPUVolumeRayCastMapper).
  void Camera(const double pos[3], const double focal[3]);
  /// The rendering against the reference (step 1/16 of the sample distance).
  VolumeComparison Compare(const std::string& name, int raysPerPixel = 1);
};

/**
 * A paged twin of an in-core volume: `image` written as a page pool of `pageSize` pages at
 * `path` (a failed check when it cannot be) and a reader of it, to connect to the mapper.
 */
vtkSmartPointer<vtkPagePoolReader> WritePagedTwin(vtkImageData* image,
  const std::string& path,
  int pageSize);
/// Renders `s` until its mapper's cut has settled, waiting for the pages between frames, at most
/// `maxFrames` times: the frames rendered, or -1 when it never settled.
int RenderUntilConverged(VolumeScene& s, int maxFrames = 200);

/// MakeBlobVolume with spacing (s0, s1, s2) and origin (o0, o1, o2).
vtkSmartPointer<vtkImageData> Blob(int nx,
  int ny,
  int nz,
  double s0,
  double s1,
  double s2,
  double o0,
  double o1,
  double o2,
  int seed);

/// The scene of TestMultiVolumeTwo and TestMultiVolumeUTM into `s`: two overlapping volumes of
/// different resolution and spacing, the second turned 30 degrees about z, shifted by (ox, oy),
/// and the camera on them.
void AddTwoVolumes(VolumeScene& s, double ox = 0.0, double oy = 0.0);

/// AddTwoVolumes against the reference; prints its fragment count under `tag`; images go to
/// `imageDirectory`.
VolumeComparison RenderTwoVolumes(double ox,
  double oy,
  const std::string& tag,
  const std::string& imageDirectory);

/// The scene's single volume `image` with `property` drawn by VTK's own
/// vtkGPUVolumeRayCastMapper (sample distance 0.25, `blendMode`, then `configure` when given,
/// e.g. cropping) under the scene's camera, in a window of the cases' size over mid grey: its
/// RGB.
std::vector<unsigned char> RenderWithVtkGPUMapper(VolumeScene& s,
  vtkImageData* image,
  vtkVolumeProperty* property,
  int blendMode,
  const std::function<void(vtkGPUVolumeRayCastMapper*)>& configure = nullptr);

/// `ours` against VTK's rendering `theirs`: prints RMS, max and the pixels off by more than 2,
/// asserts RMS <= 0.6 and max <= 6 and that ours draws something (over 2000 pixels not
/// background), and writes <directory>/<name>-strata.png and -vtk.png.
void CheckAgainstVtkGPUMapper(const std::vector<unsigned char>& ours,
  const std::vector<unsigned char>& theirs,
  const std::string& name,
  const std::string& directory);

/// A plane actor of constant colour (ambient light alone) and opacity 0.4 for
/// vtkMultiVolumeRayCastMapper::AddTranslucentActor, and the reference's surface of it.
struct TranslucentPlane
{
  vtkNew<vtkPlaneSource> Source;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  strata::MultiVolumeReferenceIntegrator::Surface Surface;
  TranslucentPlane(const double o[3], const double p1[3], const double p2[3], const double rgb[3]);
};

/// `s`'s volumes into the reference `ref` (step 1/16 of the sample distance); with `volumes`
/// false every one fully transparent (for the surfaces alone).
void AddSceneVolumes(VolumeScene& s,
  strata::MultiVolumeReferenceIntegrator& ref,
  bool volumes = true);

/**
 * The reference of `s`'s volumes with `surfaces` (with `volumes` false: every volume fully
 * transparent), stopped at `stop` (window depths) when given; the mean of the mapper's sub-pixel
 * rays. `edges`: pixels whose sub-pixel rays differ (a surface's edge).
 */
std::vector<double> ReferenceWithSurfaces(VolumeScene& s,
  const std::vector<strata::MultiVolumeReferenceIntegrator::Surface>& surfaces,
  bool volumes,
  const double* stop,
  std::vector<bool>* edges = nullptr);

/// A case's exit code: failure when `ok` is false or VTK printed errors or warnings (said so).
int CaseResult(bool ok, const CapturingOutputWindow* output);
}

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Volume scenes and the GPU-versus-reference comparison shared by the multi-volume tests and the
// volume benchmark: analytic volumes, VTK transfer functions, and their exact counterparts for
// strata::MultiVolumeReferenceIntegrator (the same tables the mapper samples).
#ifndef StrataVolumeScenes_h
#define StrataVolumeScenes_h

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkImageData;
class vtkMatrix4x4;
class vtkMultiVolumeRayCastMapper;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkStackedHeightFieldMapper;
class vtkVolume;
class vtkVolumeProperty;

namespace strata_test
{
/// A volume of nx x ny x nz float points: a sum of Gaussian blobs and a gentle ramp, values in
/// about [0, 100], deterministic in `seed`.
vtkSmartPointer<vtkImageData> MakeBlobVolume(int nx,
  int ny,
  int nz,
  const double spacing[3],
  const double origin[3],
  int seed);

/// A property with a colour ramp (hue by `variant`) and a piecewise-linear opacity, linear
/// interpolation, opacity per unit distance `unitDistance`.
vtkSmartPointer<vtkVolumeProperty> MakeVolumeProperty(int variant, double unitDistance = 1.0);

/// `image`'s scalars as `vtkType` (VTK_UNSIGNED_CHAR, ...), value = round(scale v + offset),
/// which must stay inside the type's range (a failed check otherwise).
vtkSmartPointer<vtkImageData> CopyAsType(vtkImageData* image,
  int vtkType,
  double scale,
  double offset);
/// Moves the nodes of `property`'s colour and scalar opacity functions (component 0) by the
/// same map, x -> scale x + offset: CopyAsType's data then renders as the original does.
void MapTransferFunctions(vtkVolumeProperty* property, double scale, double offset);

/// Points for vtkHybridVolumeMapper: `n` points on the line y = z = 5 from x = 2 in steps of
/// `step`, "Value" 90 and "Error" 40 each, and the field "PointSpacing" (0.25, 0.25, 0.25).
vtkSmartPointer<vtkPolyData> MakeHybridPointLine(int n, double step);

/// The reference's description of a mapper input: geometry, model matrix of `member`, scalars as
/// float, and the transfer function tabulated exactly as vtkMultiVolumeRayCastMapper does; with
/// `mapper` and `port`, the blend mode and cropping it draws that input with (its isovalues from
/// the member's property, the mapper's AverageIPScalarRange).
strata::MultiVolumeReferenceIntegrator::Volume ToReferenceVolume(vtkImageData* image,
  vtkVolume* member,
  vtkMultiVolumeRayCastMapper* mapper = nullptr,
  int port = 0);

struct VolumeComparison
{
  double Rms = 0.0;               ///< over all pixels and RGB channels, in 8-bit units
  double Max = 0.0;               ///< largest channel difference, in 8-bit units
  long Covered = 0;               ///< pixels where the reference's opacity is above 1 / 255
  std::vector<unsigned char> Gpu; ///< RGB, bottom row first
  std::vector<double> Reference;  ///< premultiplied RGBA
};

/// The active camera's clip -> world matrix for `ren` (what the reference's rays go through).
vtkSmartPointer<vtkMatrix4x4> ClipToWorld(vtkRenderer* ren);
/// `clipToWorld` shifted to sub-pixel ray `ray` of `rays` (the mapper's GetRayOffset) in a
/// viewport of `width` x `height` pixels.
vtkSmartPointer<vtkMatrix4x4> SubPixelClipToWorld(vtkMatrix4x4* clipToWorld,
  int ray,
  int rays,
  int width,
  int height);

/// The reference's premultiplied RGBA composited over `background` (RGB bytes, same pixel
/// layout), in 8-bit units (not rounded).
std::vector<double> CompositeOver(const std::vector<double>& rgba,
  const std::vector<unsigned char>& background);

/// Premultiplied RGBA `front` composited over `back` (same layout): F + (1 - F.a) B.
std::vector<double> Over(const std::vector<double>& front, const std::vector<double>& back);

/// Writes a comparison's two images, <directory>/<name>-gpu.png (RGB bytes) and -ref.png
/// (`expected` in 8-bit units, rounded).
void WriteComparisonImages(const std::string& directory,
  const std::string& name,
  const std::vector<unsigned char>& gpu,
  const std::vector<double>& expected,
  int width,
  int height);

/// RMS over all channels and largest channel difference, in 8-bit units, of `image` (RGB bytes)
/// from `expected` (same layout, 8-bit units).
struct ChannelError
{
  double Rms = 0.0;
  double Max = 0.0;
};
ChannelError ImageError(const std::vector<unsigned char>& image,
  const std::vector<double>& expected);
/// Two 8-bit images against each other.
ChannelError ImageError(const std::vector<unsigned char>& image,
  const std::vector<unsigned char>& expected);
/// RGB pixels of two 8-bit images with some channel off by more than `threshold`.
long PixelsOff(const std::vector<unsigned char>& image,
  const std::vector<unsigned char>& expected,
  int threshold);

/// Renders `win` over mid grey and compares its RGB with the reference composite of the
/// given inputs and their vtkVolumes, at the reference's step fraction `stepFraction`; with
/// several rays per pixel the reference averages the same sub-pixel rays as the mapper; with
/// `mapper`, input i of the list is the mapper's port i and takes its blend mode. Writes
/// both images as <imageDirectory>/<name>-gpu.png and -ref.png.
VolumeComparison CompareVolumesWithReference(vtkRenderWindow* win,
  vtkRenderer* ren,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  const std::string& name,
  const std::string& imageDirectory,
  double stepFraction = 1.0 / 16.0,
  int raysPerPixel = 1,
  vtkMultiVolumeRayCastMapper* mapper = nullptr);

/// The demo's multi-volume scene: the Bucky ball (real CT-like density, 32^3 uint8 read from
/// `dataDir`/volumes/bucky.raw), an analytic 48 x 40 x 36 volume turned 25 degrees about (1, 1, 0)
/// that overlaps it, and a coarse analytic 20^3 volume turned 60 degrees about z that overlaps the
/// second, all in one vtkMultiVolume with vtkMultiVolumeRayCastMapper. Returns the multi-volume
/// (nullptr if the Bucky ball cannot be read); `inputs` gets (image, member) pairs for the
/// reference.
vtkSmartPointer<vtkVolume> AddVolumeDemoScene(vtkRenderer* ren,
  const std::string& dataDir,
  std::vector<std::pair<vtkSmartPointer<vtkImageData>, vtkSmartPointer<vtkVolume>>>& inputs);

/// The translucent horizons of `mapper` (opacity below 1; read after a render) as the reference's
/// surface crossings, in world coordinates: every crossing of horizon k
/// (strata::HeightFieldReferenceCaster::CastAll) in `colors`[k] (unlit) times its opacity. The
/// stack is read at each call: keep the mapper unchanged while the reference integrates.
strata::MultiVolumeReferenceIntegrator::CrossingFunction HorizonCrossings(
  vtkStackedHeightFieldMapper* mapper,
  const std::vector<std::array<double, 3>>& colors);

/// Prints the comparison and asserts rms <= rmsBound, max <= maxBound, covered >= minCovered.
bool CheckVolumeComparison(const VolumeComparison& c,
  const std::string& name,
  double rmsBound,
  double maxBound,
  long minCovered);
}

#endif

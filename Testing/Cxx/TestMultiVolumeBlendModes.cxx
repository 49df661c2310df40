// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Blend modes per volume (vtkMultiVolumeRayCastMapper::SetInputBlendMode): every mode on one
// volume and modes mixed where volumes overlap, in core and paged, each compared pixel by pixel
// with the double-precision reference integrator taught the same modes; the generated sources
// carry only the modes used; one volume per mode against vtkGPUVolumeRayCastMapper.
//
// Bounds against the reference, in 8-bit units (StrataMultiVolumeCase.h has those of the
// composite cases, RMS 0.4 / max 2, from 8-bit rounding and the 1/4-voxel lattice):
// - MIP, MinIP: the GPU's extreme is the best of the lattice's midpoints, the reference's that
//   of midpoints 16 times denser; its colour follows the extreme's scalar, whose error is about
//   s'' h^2 / 8 (0.01 of a range of 100 here). Where the extreme sits on a plateau's edge
//   (a ray grazing a blob) a pixel may pick a scalar a little apart. Measured RMS 0.29 / 0.41,
//   max 1.2 / 1.7: RMS 0.5, max 4.
// - Average, additive: opaque grey; the midpoint rule over the ray, the GPU's lattice steps cut
//   at the fragment faces against the reference's. Measured RMS 0.18 / 0.15, max 0.5: the same
//   RMS 0.5 / max 4.
// - Isosurface: a crossing is found between the lattice's step ends and composited before
//   that step's medium (the reference: exactly where it lies), and a ray that meets a contour
//   tangentially may see it in one and not the other: measured RMS 0.15, max 11.2 (a few edge
//   pixels); RMS 0.6, max 16.
// - Mixed, overlapping: a layer lands before the step holding its depth, the reference at the
//   depth itself: a step's medium (opacity <= 0.3 per unit, 1/4 voxel: under 8 %, far less on
//   these blobs) may swap sides with it. Measured RMS 0.16-0.23, max 0.9-1.24 over the six mixed
//   renderings: RMS 0.4, max 3. Putting a layer at its fragment's entry instead of its depth
//   measured max 5.8 here: it fails.
// A wrong reduction (max for min, the average without its normalisation, layers at the wrong
// side of the composite medium) costs tens of units RMS: every one fails.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using namespace strata_test;

struct ModeCase
{
  int Mode;
  const char* Name;
  double Rms;
  double Max;
  long Covered; ///< pixels the reference must cover (opacity above 1/255)
};

const ModeCase Modes[] = {
  { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "Maximum", 0.5, 4, 5000 },
  { vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, "Minimum", 0.5, 4, 5000 },
  { vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "Average", 0.5, 4, 10000 },
  { vtkVolumeMapper::ADDITIVE_BLEND, "Additive", 0.5, 4, 10000 },
  { vtkVolumeMapper::ISOSURFACE_BLEND, "IsoSurface", 0.6, 16, 2500 },
};

/// The transfer functions of MakeVolumeProperty with two contours (where their opacity is 0.09
/// and 0.18) for the isosurface mode; for MinIP (`low`) an opacity that shows the low scalars
/// (0.3 up to 15, none from 25 on), so that the minimum along a ray is visible.
vtkSmartPointer<vtkVolumeProperty> Property(int variant, bool low = false)
{
  auto p = MakeVolumeProperty(variant);
  p->GetIsoSurfaceValues()->SetValue(0, 50.0);
  p->GetIsoSurfaceValues()->SetValue(1, 70.0);
  if (low)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0, 0.3);
    opacity->AddPoint(15, 0.3);
    opacity->AddPoint(25, 0.0);
    opacity->AddPoint(100, 0.0);
    p->SetScalarOpacity(opacity);
  }
  return p;
}

bool Compare(VolumeScene& s, const std::string& name, double rms, double max, long covered)
{
  return CheckVolumeComparison(s.Compare(name), name, rms, max, covered);
}

// One volume through an ordinary vtkVolume, the mode as the mapper's own BlendMode.
void SingleVolume(const TestPaths& paths, const ModeCase& m)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1),
    Property(0, m.Mode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND));
  s.UseSingleVolume();
  s.Mapper->SetBlendMode(m.Mode);
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  Check(Compare(s, std::string("BlendSingle") + m.Name, m.Rms, m.Max, m.Covered),
    std::string(m.Name) + " on one volume matches the reference");
}

// Two overlapping volumes (RenderTwoVolumes' scene) in a vtkMultiVolume: port 0 composite, port 1
// of `mode1`; and with port 0 of `mode0`.
void Overlapping(const TestPaths& paths, int mode0, int mode1, const std::string& name)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1), Property(0));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2),
    Property(1, mode1 == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND),
    t);
  s.UseMultiVolume();
  s.Mapper->SetInputBlendMode(0, mode0);
  s.Mapper->SetInputBlendMode(1, mode1);
  Check(s.Mapper->GetEffectiveBlendMode(0) ==
          (mode0 < 0 ? int(vtkVolumeMapper::COMPOSITE_BLEND) : mode0),
    "port 0 without a mode of its own takes the mapper's");
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
  Check(Compare(s, name, 0.4, 3, 3000), name + " matches the reference");
  if (mode1 == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND)
  {
    // Back to front inserts the layers from behind: the same image.
    s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
    Check(Compare(s, name + "BackToFront", 0.4, 3, 3000),
      name + " back to front matches the reference");
    // Pre-integrated media around the layer (the layer's volume still post-classified).
    s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::FrontToBack);
    s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PreIntegrated);
    Check(Compare(s, name + "PreIntegrated", 0.4, 3, 3000),
      name + " pre-integrated matches the reference");
    // Two rays per pixel: a layer buffer per ray; the reference averages the same two rays.
    s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PostClassification);
    s.Mapper->SetRaysPerPixel(2);
    Check(CheckVolumeComparison(s.Compare(name + "TwoRays", 2), name + "TwoRays", 0.4, 3, 3000),
      name + " with two rays per pixel matches the reference");
  }
}

// Only what the scene uses: a composite scene has no reduction or contour code; a MIP volume's
// reduction pass keeps the maximum (and no minimum, no average), and the integration reads it as
// a layer without sampling it.
void ShaderSource(const TestPaths& paths)
{
  auto has = [](const std::string& src, const char* what)
  { return src.find(what) != std::string::npos; };
  VolumeScene s(paths.Output);
  s.Add(Blob(24, 20, 20, 1.0, 1.0, 1.0, 0, 0, 0, 1), Property(0));
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 50 }, foc[3] = { 12, 10, 10 };
  s.Camera(pos, foc);
  s.Win->Render();
  const std::string composite = s.Mapper->GetShaderSource(1);
  Check(!composite.empty(), "a composite source was generated");
  Check(!has(composite, "gLayerT") && !has(composite, "strataIso") && !has(composite, "gState") &&
          s.Mapper->GetReductionShaderSource(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND).empty(),
    "a composite scene has no layer, contour or reduction code");
  s.Mapper->SetBlendMode(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
  s.Win->Render();
  const std::string mip =
    s.Mapper->GetReductionShaderSource(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
  const std::string layer = s.Mapper->GetShaderSource(1);
  Check(has(mip, "s > state.x") && !has(mip, "s < state.x") && !has(mip, "state.y += len"),
    "the MIP reduction keeps the maximum and nothing else");
  Check(!has(mip, "strataSegment") && !has(mip, "uTerminationOpacity"),
    "the reduction has no composite segment and no early termination");
  Check(
    has(layer, "strataLayer0") && !has(layer, "strataScalarAt0") && !has(layer, "strataSegment"),
    "the integration reads the MIP volume as a layer without sampling it");
  s.Mapper->SetBlendMode(vtkVolumeMapper::ISOSURFACE_BLEND);
  s.Win->Render();
  const std::string iso = s.Mapper->GetShaderSource(1);
  Check(has(iso, "strataIso0") && !has(iso, "strataSegment(") && !has(iso, "gLayerT"),
    "an isosurface volume has contour code and no medium or layer");
}

// One volume per mode against VTK's own vtkGPUVolumeRayCastMapper, same property, same sample
// distance. VTK normalises scalars over the data's range and corrects opacities to the sample
// distance (not for MIP and MinIP): here the functions span exactly the data's range and the unit
// distance is the sample distance, so both describe the same image. VTK samples from each ray's
// entry, Strata on one lattice along the ray, and their tables differ in size. Measured: RMS
// 0.10 / 0.27 / 0.08 / 0.30 / 0 and max 1 / 4 / 1 / 2 / 0 (MIP, MinIP, average, additive,
// isosurface: unshaded contours are flat colours and both find the same crossings here); bounds
// RMS 0.6 / max 6. Their MinIP and ours differ most where the minimum sits on the box's faces.
void AgainstVtk(const TestPaths& paths, const ModeCase& m)
{
  VolumeScene s(paths.Output);
  auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  double range[2];
  image->GetScalarRange(range);
  auto prop = Property(0, m.Mode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND);
  prop->SetScalarOpacityUnitDistance(0.25);
  // Both functions over exactly the data's range (the nodes kept, the ends moved).
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkPiecewiseFunction* old = prop->GetScalarOpacity();
  for (int i = 0; i < old->GetSize(); ++i)
  {
    double node[4];
    old->GetNodeValue(i, node);
    opacity->AddPoint(std::min(std::max(node[0], range[0]), range[1]), node[1]);
  }
  opacity->AddPoint(range[0], old->GetValue(range[0]));
  opacity->AddPoint(range[1], old->GetValue(range[1]));
  prop->SetScalarOpacity(opacity);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(range[0], 0.1, 0.2, 1.0);
  color->AddRGBPoint(range[1], 1.0, 0.3, 0.1);
  prop->SetColor(color);
  s.Add(image, prop);
  s.UseSingleVolume();
  s.Mapper->SetBlendMode(m.Mode);
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  s.Ren->SetBackground(128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0);
  s.Win->Render();
  const auto ours = ReadRGB(s.Win);

  const auto theirs = RenderWithVtkGPUMapper(s, image, prop, m.Mode);
  CheckAgainstVtkGPUMapper(ours, theirs, std::string("BlendVtk") + m.Name, paths.Output);
}

/// Writes `image` to a page pool of 8^3 pages.
bool WritePool(vtkImageData* image, const std::string& pool)
{
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(8);
  return writer->Write() != 0;
}

// Paged through the brick atlas with per-brick emptiness and skipping: after convergence each
// reduction matches the reference of the full data. The opacity function is zero below 20 (MinIP:
// above 25), and the blobs' floor lies below it, so many bricks and cells are empty for composite
// blending: MIP (MinIP) may leave out only those transparent down to (up to) the table's end,
// additive those transparent, average and isosurface none (a stand-in next to data would make
// false contours; isosurface skip cells are those without a visible isovalue in their range).
void Paged(const TestPaths& paths, const ModeCase& m)
{
  VolumeScene s(paths.Output);
  auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  s.Add(image, Property(0, m.Mode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND));
  const std::string pool = paths.Output + "/blend-" + m.Name + ".spp";
  Check(WritePool(image, pool), "the pool is written");
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(pool.c_str());
  s.Mapper->SetInputConnection(0, reader->GetOutputPort());
  s.UseSingleVolume();
  s.Mapper->SetBlendMode(m.Mode);
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  bool converged = false;
  for (int f = 0; f < 60 && !converged; ++f)
  {
    s.Win->Render();
    s.Mapper->WaitForPages(5.0);
    converged = s.Mapper->GetPagingStatistics().Converged;
  }
  Check(converged, std::string(m.Name) + " paged converges");
  std::cout << "BlendPaged" << m.Name << ": " << s.Mapper->GetNumberOfResidentBricks()
            << " resident bricks\n";
  Check(Compare(s, std::string("BlendPaged") + m.Name, m.Rms, m.Max, m.Covered),
    std::string(m.Name) + " paged matches the reference");
}
}

int TestMultiVolumeBlendModes(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<SubTest> parts;
  for (const ModeCase& m : Modes)
    parts.push_back({ std::string("single ") + m.Name, [&paths, m] { SingleVolume(paths, m); } });
  parts.push_back(
    { "composite and MIP overlapping", [&paths] {
       Overlapping(paths, -1, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "BlendCompositeMaximum");
     } });
  parts.push_back({ "composite and isosurface overlapping",
    [&paths]
    {
      Overlapping(paths,
        vtkVolumeMapper::COMPOSITE_BLEND,
        vtkVolumeMapper::ISOSURFACE_BLEND,
        "BlendCompositeIso");
    } });
  parts.push_back({ "average and MinIP overlapping",
    [&paths]
    {
      Overlapping(paths,
        vtkVolumeMapper::AVERAGE_INTENSITY_BLEND,
        vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
        "BlendAverageMinimum");
    } });
  parts.push_back({ "shader source", [&paths] { ShaderSource(paths); } });
  for (const ModeCase& m : Modes)
    parts.push_back({ std::string("paged ") + m.Name, [&paths, m] { Paged(paths, m); } });
  for (const ModeCase& m : Modes)
    parts.push_back(
      { std::string("against VTK ") + m.Name, [&paths, m] { AgainstVtk(paths, m); } });
  parts.push_back({ "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } });
  return RunSubTests(parts, Failures);
}

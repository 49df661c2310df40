// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Components as vtkVolumeProperty defines them (IndependentComponents on: each component its own
// functions and weight; off: two components colour + opacity, four RGBA) on in-core volumes of
// vtkMultiVolumeRayCastMapper: each mode on one volume against the double-precision reference
// taught the same model and against vtkGPUVolumeRayCastMapper, each overlapping a one-component
// volume against the reference; the sources carry component code only where a scene has
// components; paged and atlas-sharing limits give errors.
//
// Bounds, in 8-bit units:
// - Against the reference: those of StrataMultiVolumeCase.h (RMS 0.4 / max 2, from 8-bit
//   rounding and the 1/4-voxel lattice) hold for the components too: each component is
//   interpolated alone and classified as one-component volumes are, and the independent rule is
//   a smooth function of the components' extinctions. Measured RMS 0.27 / 0.24 / 0.23, max
//   1.20 / 1.21 / 1.21 alone (2 independent, colour + opacity, RGBA; 4 independent weighted 1,
//   0.7, 0.5, 0: RMS 0.27, max 1.24), RMS 0.23 / 0.22 / 0.20, max 1.24 / 1.24 / 1.23
//   overlapping.
// - A wrong rule fails by far: the independent components mixed as two media (extinctions added,
//   the physically obvious rule, not VTK's), the two dependent components swapped, the RGBA
//   colour read as BGR: measured RMS 17.6 / 27.0 / 17.6 against the bound 0.4 (asserted
//   above 1.6, 4 times the bound).
// - Against vtkGPUVolumeRayCastMapper (one volume, functions over exactly each component's data
//   range, unit distance 1 at sample distance 1/4 in both): VTK applies the independent rule
//   per sample to step opacities (ours is its short-step limit: they differ by O(step) where
//   components overlap), samples from each ray's entry instead of one lattice, and tabulates
//   differently: bounds as TestMultiVolumeBlendModes' against VTK (RMS 0.6 / max 6). Measured
//   RMS 0.24 / 0.15 / 0.15 / 0.12, max 2 / 1 / 2 / 1 (independent, colour + opacity, RGBA as
//   unsigned char and as float); 4 independent components RMS 0.50, max 3 (where more of them
//   overlap, VTK's per-step rule departs further from its short-step limit). VTK 9.1 reads RGBA
//   colour as its texture holds it (8 and 16 bits normalised, float as is), and its opacity table
//   over the fourth component's range at that value: here each component spans [0, 255] (unsigned
//   char) or [0, 1] (float), where that is the fourth component's own value, as Strata reads it.
//
// Paged: a set of component pools (one brick pool per component, strata::PagePoolFormat), each
// component a volume of one scalar in the atlas; in core beside a paged volume, the same from a
// brick tree per component. Bounds: the reference's; paged against the in-core image (plain
// texture, float channels) within 1 of 255: two programs (the atlas and a lookup per component
// against a plain texture), ImagePolicy::TwoProgramsMax (StrataImagePolicy.h rule 2). A port
// switched back to one in-core component draws with the program of a mapper of its own: the same
// program, bit-exact (ImagePolicy::SameProgramMax, rule 1).
#include "StrataErrorCounter.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;
using Ref = strata::MultiVolumeReferenceIntegrator;

enum class Mode
{
  Independent,
  ColorOpacity,
  RGBA,        ///< unsigned char
  RGBAFloat,   ///< float in [0, 1]
  Independent4 ///< four independent components, the last of weight 0
};

const char* Name(Mode m)
{
  const char* names[] = { "Independent", "ColorOpacity", "RGBA", "RGBAFloat", "Independent4" };
  return names[static_cast<int>(m)];
}

int Count(Mode m)
{
  return m == Mode::RGBA || m == Mode::RGBAFloat || m == Mode::Independent4 ? 4 : 2;
}

/// A 40 x 36 x 32 volume (Blob's geometry) whose component c is the blob volume of seed c + 1;
/// RGBA each component over 0 to 255 as unsigned char, or over 0 to 1 as float (`floats`).
vtkSmartPointer<vtkImageData> ComponentVolume(int components, bool floats = false)
{
  auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  vtkSmartPointer<vtkDataArray> values;
  if (components == 4 && !floats)
    values = vtkSmartPointer<vtkUnsignedCharArray>::New();
  else
    values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName("components");
  values->SetNumberOfComponents(components);
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  for (int c = 0; c < components; ++c)
  {
    auto blob = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, c + 1);
    vtkDataArray* s = blob->GetPointData()->GetScalars();
    double r[2];
    s->GetRange(r);
    for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
      values->SetComponent(i,
        c,
        components != 4 ? s->GetComponent(i, 0)
                        : std::round((s->GetComponent(i, 0) - r[0]) * 255.0 / (r[1] - r[0])) /
                            (floats ? 255.0 : 1.0));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// Colour ramp `variant` and MakeVolumeProperty's opacity shape over [lo, hi].
void SetFunctions(vtkVolumeProperty* p, int index, const double range[2], int variant)
{
  const double palette[3][2][3] = { { { 0.1, 0.2, 1.0 }, { 1.0, 0.3, 0.1 } },
    { { 0.1, 0.8, 0.2 }, { 1.0, 1.0, 0.3 } },
    { { 0.6, 0.1, 0.8 }, { 0.2, 0.9, 1.0 } } };
  const auto& pal = palette[variant % 3];
  const double lo = range[0], d = range[1] - range[0];
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(lo, pal[0][0], pal[0][1], pal[0][2]);
  color->AddRGBPoint(lo + d, pal[1][0], pal[1][1], pal[1][2]);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(lo, 0.0);
  opacity->AddPoint(lo + 0.2 * d, 0.0);
  opacity->AddPoint(lo + 0.4 * d, 0.05);
  opacity->AddPoint(lo + d, 0.3);
  p->SetColor(index, color);
  p->SetScalarOpacity(index, opacity);
}

/// The property of `mode` for `image`: functions over exactly each component's data range (so
/// that VTK, which normalises over the data's range, reads the same), unit distance 1 each.
vtkSmartPointer<vtkVolumeProperty> ComponentProperty(Mode mode, vtkImageData* image)
{
  auto p = vtkSmartPointer<vtkVolumeProperty>::New();
  p->SetInterpolationTypeToLinear();
  vtkDataArray* s = image->GetPointData()->GetScalars();
  double r0[2], r1[2], r3[2];
  s->GetRange(r0, 0);
  s->GetRange(r1, 1);
  if (mode == Mode::Independent || mode == Mode::Independent4)
  {
    p->IndependentComponentsOn();
    const double weights[4] = { 1.0, 0.7, 0.5, 0.0 };
    for (int c = 0; c < Count(mode); ++c)
    {
      double r[2];
      s->GetRange(r, c);
      SetFunctions(p, c, r, c);
      p->SetComponentWeight(c, weights[c]);
    }
    return p;
  }
  p->IndependentComponentsOff();
  if (mode == Mode::ColorOpacity)
  {
    // Colour over component 0's range, opacity over component 1's (one function each).
    SetFunctions(p, 0, r0, 0);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(r1[0], 0.0);
    opacity->AddPoint(r1[0] + 0.2 * (r1[1] - r1[0]), 0.0);
    opacity->AddPoint(r1[0] + 0.4 * (r1[1] - r1[0]), 0.05);
    opacity->AddPoint(r1[1], 0.3);
    p->SetScalarOpacity(opacity);
  }
  else
  {
    s->GetRange(r3, 3);
    SetFunctions(p, 0, r3, 2);
  }
  // VTK 9.1 corrects dependent components' opacity by the unit distance of the last component.
  for (int c = 0; c < 4; ++c)
    p->SetScalarOpacityUnitDistance(c, 1.0);
  return p;
}

const double Pos[3] = { -40, -60, 70 }, Focal[3] = { 20, 20, 14 };

/// The reference of `volumes` through `ren`'s camera over mid grey, in 8-bit units.
std::vector<double> ReferenceImage(vtkRenderer* ren, std::vector<Ref::Volume> volumes)
{
  Ref ref;
  for (auto& v : volumes)
    Check(
      ref.AddVolume(std::move(v)) >= 0, "the reference takes the volume: " + ref.GetLastError());
  std::vector<double> rgba;
  const int w = MultiVolumeCaseSize;
  ref.IntegrateImage(ClipToWorld(ren)->GetData(), w, w, rgba);
  return CompositeOver(rgba, std::vector<unsigned char>(3 * size_t(w) * w, 128));
}

/// The reference's description of a component volume with the wrong rule of `mode`.
std::vector<Ref::Volume> WrongRule(Mode mode, vtkImageData* image, vtkVolume* member)
{
  Ref::Volume v = ToReferenceVolume(image, member);
  if (mode == Mode::Independent || mode == Mode::Independent4)
  {
    // One medium per component sharing the box: extinctions added.
    const int nc = v.NumberOfComponents;
    std::vector<Ref::Volume> media(nc, v);
    for (int c = 0; c < nc; ++c)
    {
      Ref::Volume& m = media[c];
      m.NumberOfComponents = 1;
      m.ComponentMode = Ref::Components::One;
      m.ComponentClassifications.clear();
      m.FloatScalars.clear();
      for (size_t i = c; i < v.FloatScalars.size(); i += nc)
        m.FloatScalars.push_back(v.FloatScalars[i]);
      if (c > 0)
        m.Classification = v.ComponentClassifications[c - 1];
    }
    return media;
  }
  if (mode == Mode::ColorOpacity)
  {
    for (size_t i = 0; i + 1 < v.FloatScalars.size(); i += 2)
      std::swap(v.FloatScalars[i], v.FloatScalars[i + 1]);
    return { v };
  }
  for (size_t i = 0; i + 3 < v.FloatScalars.size(); i += 4) // BGR
    std::swap(v.FloatScalars[i], v.FloatScalars[i + 2]);
  return { v };
}

// One volume of `mode` against the reference; the wrong rule against the same rendering.
void Single(const TestPaths& paths, Mode mode)
{
  VolumeScene s(paths.Output);
  auto image = ComponentVolume(Count(mode), mode == Mode::RGBAFloat);
  s.Add(image, ComponentProperty(mode, image));
  s.UseSingleVolume();
  s.Camera(Pos, Focal);
  const std::string name = std::string("Components") + Name(mode);
  const VolumeComparison c = s.Compare(name);
  Check(CheckVolumeComparison(c, name, 0.4, 2, 2500), name + " matches the reference");
  const ChannelError wrong =
    ImageError(c.Gpu, ReferenceImage(s.Ren, WrongRule(mode, image, s.Volumes[0])));
  std::cout << name << " against the wrong rule: RMS " << wrong.Rms << ", max " << wrong.Max
            << "\n";
  Check(wrong.Rms > 1.6, name + ": the wrong rule differs by more than 4 times the RMS bound");
}

// A volume of `mode` and a one-component volume (turned 30 degrees, coarser) overlapping in a
// vtkMultiVolume, and the camera on both.
void AddOverlappingScene(VolumeScene& s, Mode mode)
{
  auto image = ComponentVolume(Count(mode), mode == Mode::RGBAFloat);
  s.Add(image, ComponentProperty(mode, image));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(2), t);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
}

// Overlapping a one-component volume in a vtkMultiVolume.
void Overlapping(const TestPaths& paths, Mode mode)
{
  VolumeScene s(paths.Output);
  AddOverlappingScene(s, mode);
  const std::string name = std::string("ComponentsOverlap") + Name(mode);
  Check(CheckVolumeComparison(s.Compare(name), name, 0.4, 2, 2500),
    name + " overlapping a one-component volume matches the reference");
}

// One volume of `mode` against vtkGPUVolumeRayCastMapper, same property and sample distance.
void AgainstVtk(const TestPaths& paths, Mode mode)
{
  VolumeScene s(paths.Output);
  auto image = ComponentVolume(Count(mode), mode == Mode::RGBAFloat);
  auto prop = ComponentProperty(mode, image);
  s.Add(image, prop);
  s.UseSingleVolume();
  s.Camera(Pos, Focal);
  s.Ren->SetBackground(128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0);
  s.Win->Render();
  const auto ours = ReadRGB(s.Win);

  const auto theirs = RenderWithVtkGPUMapper(s, image, prop, vtkVolumeMapper::COMPOSITE_BLEND);
  CheckAgainstVtkGPUMapper(ours, theirs, std::string("ComponentsVtk") + Name(mode), paths.Output);
}

// Only what the scene uses: one-component volumes have no component code; each mode its own.
void ShaderSource(const TestPaths& paths)
{
  auto has = [](const std::string& src, const char* what)
  { return src.find(what) != std::string::npos; };
  {
    VolumeScene s(paths.Output);
    s.Add(Blob(24, 20, 20, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
    s.UseSingleVolume();
    s.Camera(Pos, Focal);
    s.Win->Render();
    const std::string one = s.Mapper->GetShaderSource(1);
    Check(!one.empty() && !has(one, "strataComponents") && !has(one, "strataMedium") &&
            !has(one, "uWeights") && !has(one, "uColorScale"),
      "a scene of one-component volumes has no component code");
  }
  const char* marks[] = { "uTransfer0_1", "strataComponents0(p).xy", "uColorScale0" };
  for (Mode mode : { Mode::Independent, Mode::ColorOpacity, Mode::RGBA })
  {
    VolumeScene s(paths.Output);
    auto image = ComponentVolume(Count(mode), mode == Mode::RGBAFloat);
    s.Add(image, ComponentProperty(mode, image));
    s.UseSingleVolume();
    s.Camera(Pos, Focal);
    s.Win->Render();
    const std::string src = s.Mapper->GetShaderSource(1);
    const int m = static_cast<int>(mode);
    bool others = false;
    for (int k = 0; k < 3; ++k)
      others = others || (k != m && has(src, marks[k]));
    // Dependent components are skipped by the opacity's component, independent ones not.
    Check(has(src, "strataMedium0") && has(src, marks[m]) && !others &&
            !has(src, "strataScalarAt0") &&
            has(src, "strataEmptyUntil") == (mode != Mode::Independent),
      std::string(Name(mode)) + ": the source reads the components through their own rule, no "
                                "atlas, skipping for dependent components only");
  }
}

// What is not drawn says so: 3 dependent components and more than 4 are not defined.
void Undefined(const TestPaths& paths)
{
  for (int components : { 3, 5 })
  {
    VolumeScene s(paths.Output);
    auto image = ComponentVolume(components);
    auto prop = MakeVolumeProperty(0);
    prop->IndependentComponentsOff();
    s.Add(image, prop);
    s.UseSingleVolume();
    s.Camera(Pos, Focal);
    vtkNew<ErrorCounter> errors;
    errors->Watch(s.Mapper);
    s.Win->Render();
    std::cout << components << " dependent components: \"" << errors->First << "\"\n";
    Check(errors->Errors > 0 && errors->First.find("component") != std::string::npos,
      std::to_string(components) + " dependent components give a VTK error naming them");
  }
}

// Paged from a set of component pools of 8^3 pages (strata::PagePoolFormat, Components), converged:
// each component a volume of one scalar in the atlas, read by its own lookup. Against the
// in-core image (plain texture of a float channel per component) and the reference.
void Paged(const TestPaths& paths, Mode mode)
{
  VolumeScene s(paths.Output);
  auto image = ComponentVolume(Count(mode), mode == Mode::RGBAFloat);
  s.Add(image, ComponentProperty(mode, image));
  s.UseSingleVolume();
  s.Camera(Pos, Focal);
  s.Win->Render();
  const auto inCore = ReadRGB(s.Win);
  const std::string name = std::string("ComponentsPaged") + Name(mode);
  auto reader = WritePagedTwin(image, paths.Output + "/" + name + ".spp", 8);
  s.Mapper->SetInputConnection(0, reader->GetOutputPort());
  const int frames = RenderUntilConverged(s, 100);
  const ChannelError toInCore = ImageError(ReadRGB(s.Win), inCore);
  std::cout << name << ": converged after " << frames << " frames, "
            << s.Mapper->GetNumberOfResidentBricks() << " bricks resident; against in core RMS "
            << toInCore.Rms << ", max " << toInCore.Max << "\n";
  Check(frames > 0, name + " converges");
  Check(
    toInCore.Max <= ImagePolicy::TwoProgramsMax, name + " is the in-core image within 1 of 255");
  Check(
    CheckVolumeComparison(s.Compare(name), name, 0.4, 2, 2500), name + " matches the reference");
  const std::string src = s.Mapper->GetShaderSource(1);
  const int count = Count(mode);
  // Independent4's component 3 weighs 0 (ComponentProperty): no lookup, no table.
  const int read = mode == Mode::Independent4 ? 3 : count;
  bool lookups = src.find("strataScalarAt0(") != std::string::npos;
  for (int c = 1; c < 4; ++c)
    lookups = lookups &&
              (src.find("strataScalarAt0c" + std::to_string(c)) != std::string::npos) == (c < read);
  Check(
    lookups && (src.find("uTransfer0_3") != std::string::npos) == (read == 4 && mode != Mode::RGBA),
    name + ": the source has one atlas lookup per component of weight > 0 (" +
      std::to_string(read) + ")");
  if (mode != Mode::Independent4)
    return;
  // Component 3 weighs 0 (ComponentProperty): it shows nothing, so none of its bricks is paged.
  const int without = s.Mapper->GetNumberOfResidentBricks();
  s.Volumes[0]->GetProperty()->SetComponentWeight(3, 0.3);
  RenderUntilConverged(s, 100);
  const int with = s.Mapper->GetNumberOfResidentBricks();
  std::cout << name << ": " << without << " bricks resident with component 3 of weight 0, " << with
            << " with weight 0.3\n";
  Check(with > without, name + ": a component of weight 0 pages no brick");
}

// Components paged, overlapping an in-core volume of one component; and components in core
// beside a paged volume (the atlas then holds the in-core components too, a tree each).
void PagedOverlapping(const TestPaths& paths, Mode mode, bool pageComponents)
{
  VolumeScene s(paths.Output);
  AddOverlappingScene(s, mode);
  const std::string name =
    std::string(pageComponents ? "ComponentsPagedOverlap" : "ComponentsBesidePaged") + Name(mode);
  const int port = pageComponents ? 0 : 1;
  auto reader = WritePagedTwin(s.Images[port], paths.Output + "/" + name + ".spp", 8);
  s.Mapper->SetInputConnection(port, reader->GetOutputPort());
  const int frames = RenderUntilConverged(s, 100);
  std::cout << name << ": converged after " << frames << " frames\n";
  Check(frames > 0, name + " converges");
  Check(CheckVolumeComparison(s.Compare(name), name, 0.4, 2, 2500),
    name +
      (pageComponents ? ": paged components overlapping an in-core volume"
                      : ": in-core components beside a paged volume") +
      " match the reference");
}

// One port paged from a set of four components, then from a set of two (ParaView shows one
// data set after another on a view's one mapper): the second set's image is its in-core one.
void PagedAfterPaged(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  auto rgba = ComponentVolume(Count(Mode::RGBA));
  auto two = ComponentVolume(Count(Mode::ColorOpacity));
  s.Add(two, ComponentProperty(Mode::ColorOpacity, two));
  s.UseSingleVolume();
  s.Camera(Pos, Focal);
  s.Win->Render();
  const auto inCore = ReadRGB(s.Win);
  auto first = WritePagedTwin(rgba, paths.Output + "/ComponentsPagedFirst.spp", 8);
  auto second = WritePagedTwin(two, paths.Output + "/ComponentsPagedSecond.spp", 8);
  s.Volumes[0]->SetProperty(ComponentProperty(Mode::RGBA, rgba));
  s.Mapper->SetInputConnection(0, first->GetOutputPort());
  Check(RenderUntilConverged(s, 100) > 0, "the four components converge");
  s.Volumes[0]->SetProperty(ComponentProperty(Mode::ColorOpacity, two));
  s.Mapper->SetInputConnection(0, second->GetOutputPort());
  const int frames = RenderUntilConverged(s, 100);
  const ChannelError e = ImageError(ReadRGB(s.Win), inCore);
  std::cout << "ComponentsPagedAfterPaged: converged after " << frames << " frames; against in "
            << "core RMS " << e.Rms << ", max " << e.Max << "\n";
  Check(frames > 0 && e.Max <= ImagePolicy::TwoProgramsMax,
    "a port paged from four components, then from two: the in-core image within 1 of 255");
}

// One port from components to one (ParaView's Strata Volume does so when the colour map's vector
// mode turns to magnitude): in core from two components, and paged from four component pools;
// each the one-component image of a mapper of its own.
void OneAfterComponents(const TestPaths& paths, bool paged)
{
  auto one = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  VolumeScene fresh(paths.Output);
  fresh.Add(one, MakeVolumeProperty(0));
  fresh.UseSingleVolume();
  fresh.Camera(Pos, Focal);
  fresh.Win->Render();
  const auto expected = ReadRGB(fresh.Win);

  VolumeScene s(paths.Output);
  const Mode mode = paged ? Mode::RGBA : Mode::Independent;
  auto before = ComponentVolume(Count(mode));
  s.Add(before, ComponentProperty(mode, before));
  s.UseSingleVolume();
  s.Camera(Pos, Focal);
  vtkNew<vtkTrivialProducer> producer; // one output port, as in ParaView
  producer->SetOutput(before);
  vtkSmartPointer<vtkAlgorithm> pool;
  if (paged)
    pool = WritePagedTwin(before, paths.Output + "/ComponentsThenOne.spp", 8);
  s.Mapper->SetInputConnection(0, paged ? pool->GetOutputPort() : producer->GetOutputPort());
  if (paged)
    Check(RenderUntilConverged(s, 100) > 0, "the paged components converge");
  else
    s.Win->Render();
  producer->SetOutput(one);
  s.Mapper->SetInputConnection(0, producer->GetOutputPort());
  s.Volumes[0]->SetProperty(MakeVolumeProperty(0));
  s.Win->Render();
  const ChannelError e = ImageError(ReadRGB(s.Win), expected);
  const std::string name = paged ? "ComponentsPagedThenOne" : "ComponentsThenOne";
  std::cout << name << ": against a mapper of its own RMS " << e.Rms << ", max " << e.Max << "\n";
  // The same program as the fresh mapper's (one in-core component, the same settings): exact.
  Check(e.Max <= ImagePolicy::SameProgramMax, name + ": the one-component image");
}

// The reference's own model: a second component of weight 0 leaves the first; two equal
// dependent components are the one-component volume (the same scalars in every component, so
// that the pieces are cut at the same kinks).
void ReferenceModel()
{
  auto one = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  vtkNew<vtkVolume> member;
  member->SetProperty(MakeVolumeProperty(0));
  const Ref::Volume single = ToReferenceVolume(one, member);
  Ref::Volume independent = single;
  independent.NumberOfComponents = 2;
  independent.ComponentMode = Ref::Components::Independent;
  independent.ComponentClassifications = { single.Classification };
  independent.ComponentWeights[1] = 0.0;
  independent.FloatScalars.clear();
  for (float v : single.FloatScalars)
    independent.FloatScalars.insert(independent.FloatScalars.end(), { v, v });
  Ref::Volume dependent = independent;
  dependent.ComponentMode = Ref::Components::ColorOpacity;
  dependent.ComponentClassifications.clear();
  const double o[3] = { -10, 15, 14 }, d[3] = { 1, 0.05, 0.02 };
  Ref a, b, c;
  a.AddVolume(single);
  Check(b.AddVolume(independent) >= 0 && c.AddVolume(dependent) >= 0,
    "the reference takes both component volumes: " + b.GetLastError() + c.GetLastError());
  const auto ra = a.IntegrateRay(o, d, 0, 60), rb = b.IntegrateRay(o, d, 0, 60),
             rc = c.IntegrateRay(o, d, 0, 60);
  double db = 0, dc = 0;
  for (int k = 0; k < 4; ++k)
  {
    db = std::max(db, std::abs(ra[k] - rb[k]));
    dc = std::max(dc, std::abs(ra[k] - rc[k]));
  }
  std::cout << "reference: alpha " << ra[3] << "; weight-0 component off by " << db
            << ", equal dependent components by " << dc << "\n";
  Check(ra[3] > 0.1 && db < 1e-12 && dc < 1e-12,
    "the reference's component rules reduce to one component (1e-12)");
}
}

int TestMultiVolumeComponents(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<SubTest> parts;
  parts.push_back({ "reference model", [] { ReferenceModel(); } });
  for (Mode m :
    { Mode::Independent, Mode::ColorOpacity, Mode::RGBA, Mode::RGBAFloat, Mode::Independent4 })
  {
    parts.push_back({ std::string("single ") + Name(m), [&paths, m] { Single(paths, m); } });
    parts.push_back(
      { std::string("against VTK ") + Name(m), [&paths, m] { AgainstVtk(paths, m); } });
    if (m != Mode::RGBAFloat && m != Mode::Independent4)
      parts.push_back(
        { std::string("overlapping ") + Name(m), [&paths, m] { Overlapping(paths, m); } });
  }
  parts.push_back({ "paged after paged", [&paths] { PagedAfterPaged(paths); } });
  parts.push_back({ "one component after two", [&paths] { OneAfterComponents(paths, false); } });
  parts.push_back(
    { "one component after paged four", [&paths] { OneAfterComponents(paths, true); } });
  parts.push_back({ "shader source", [&paths] { ShaderSource(paths); } });
  parts.push_back({ "undefined components", [&paths] { Undefined(paths); } });
  for (Mode m : { Mode::Independent, Mode::ColorOpacity, Mode::RGBA, Mode::Independent4 })
    parts.push_back({ std::string("paged ") + Name(m), [&paths, m] { Paged(paths, m); } });
  for (Mode m : { Mode::Independent, Mode::ColorOpacity, Mode::RGBA })
  {
    parts.push_back({ std::string("paged overlapping ") + Name(m),
      [&paths, m] { PagedOverlapping(paths, m, true); } });
    parts.push_back({ std::string("in core beside paged ") + Name(m),
      [&paths, m] { PagedOverlapping(paths, m, false); } });
  }
  parts.push_back({ "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } });
  return RunSubTests(parts, Failures);
}

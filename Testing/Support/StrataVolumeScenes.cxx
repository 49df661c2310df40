// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeScenes.h"
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"

#include "StrataHeightFieldReferenceCaster.h"
#include "StrataHeightFieldStack.h"
#include "StrataMultiVolumeInput.h"
#include "StrataTransferFunctionTable.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>

namespace strata_test
{
vtkSmartPointer<vtkImageData> MakeBlobVolume(int nx,
  int ny,
  int nz,
  const double spacing[3],
  const double origin[3],
  int seed)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  vtkNew<vtkFloatArray> a;
  a->SetName("density");
  a->SetNumberOfValues(image->GetNumberOfPoints());
  // Three blobs at seed-dependent places inside the unit box of the volume.
  double centre[3][3], width[3];
  for (int b = 0; b < 3; ++b)
  {
    for (int c = 0; c < 3; ++c)
      centre[b][c] = 0.25 + 0.5 * std::fmod(0.37 * (seed + 1) * (b + 1) + 0.23 * c * (b + 2), 1.0);
    width[b] = 0.22 + 0.06 * b;
  }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const double u[3] = { nx > 1 ? double(i) / (nx - 1) : 0.5,
          ny > 1 ? double(j) / (ny - 1) : 0.5,
          nz > 1 ? double(k) / (nz - 1) : 0.5 };
        double v = 10.0 * u[0];
        for (int b = 0; b < 3; ++b)
        {
          double r2 = 0;
          for (int c = 0; c < 3; ++c)
            r2 += (u[c] - centre[b][c]) * (u[c] - centre[b][c]);
          v += (90.0 - 20 * b) * std::exp(-r2 / (width[b] * width[b]));
        }
        a->SetValue((vtkIdType(k) * ny + j) * nx + i, static_cast<float>(v));
      }
  image->GetPointData()->SetScalars(a);
  return image;
}

vtkSmartPointer<vtkVolumeProperty> MakeVolumeProperty(int variant, double unitDistance)
{
  auto p = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkColorTransferFunction> ctf;
  const double palette[3][2][3] = { { { 0.1, 0.2, 1.0 }, { 1.0, 0.3, 0.1 } },
    { { 0.1, 0.8, 0.2 }, { 1.0, 1.0, 0.3 } },
    { { 0.6, 0.1, 0.8 }, { 0.2, 0.9, 1.0 } } };
  const auto& pal = palette[variant % 3];
  ctf->AddRGBPoint(0, pal[0][0], pal[0][1], pal[0][2]);
  ctf->AddRGBPoint(100, pal[1][0], pal[1][1], pal[1][2]);
  vtkNew<vtkPiecewiseFunction> pwf;
  pwf->AddPoint(0, 0.0);
  pwf->AddPoint(20, 0.0);
  pwf->AddPoint(40, 0.05);
  pwf->AddPoint(100, 0.3);
  p->SetColor(ctf);
  p->SetScalarOpacity(pwf);
  p->SetScalarOpacityUnitDistance(unitDistance);
  p->SetInterpolationTypeToLinear();
  return p;
}

vtkSmartPointer<vtkImageData> CopyAsType(vtkImageData* image,
  int vtkType,
  double scale,
  double offset)
{
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->CopyStructure(image);
  out->AllocateScalars(vtkType, 1);
  vtkDataArray* from = image->GetPointData()->GetScalars();
  vtkDataArray* to = out->GetPointData()->GetScalars();
  bool inRange = true;
  for (vtkIdType i = 0; i < from->GetNumberOfTuples(); ++i)
  {
    const double v = std::floor(scale * from->GetTuple1(i) + offset + 0.5);
    inRange = inRange && v >= to->GetDataTypeMin() && v <= to->GetDataTypeMax();
    to->SetTuple1(i, v);
  }
  Check(inRange, "CopyAsType: the values stay inside the type's range");
  return out;
}

void MapTransferFunctions(vtkVolumeProperty* property, double scale, double offset)
{
  // All nodes read first, then set again: moving them one by one would reorder them.
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
  std::vector<std::array<double, 6>> colors(color->GetSize());
  for (size_t i = 0; i < colors.size(); ++i)
    color->GetNodeValue(static_cast<int>(i), colors[i].data());
  color->RemoveAllPoints();
  for (const auto& n : colors)
    color->AddRGBPoint(scale * n[0] + offset, n[1], n[2], n[3], n[4], n[5]);
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  std::vector<std::array<double, 4>> opacities(opacity->GetSize());
  for (size_t i = 0; i < opacities.size(); ++i)
    opacity->GetNodeValue(static_cast<int>(i), opacities[i].data());
  opacity->RemoveAllPoints();
  for (const auto& n : opacities)
    opacity->AddPoint(scale * n[0] + offset, n[1], n[2], n[3]);
}

vtkSmartPointer<vtkPolyData> MakeHybridPointLine(int n, double step)
{
  auto points = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> p;
  vtkNew<vtkFloatArray> value, error, spacing;
  value->SetName("Value");
  error->SetName("Error");
  spacing->SetName("PointSpacing");
  for (int i = 0; i < n; ++i)
  {
    p->InsertNextPoint(2.0 + step * i, 5.0, 5.0);
    value->InsertNextValue(90.0f);
    error->InsertNextValue(40.0f);
  }
  for (int c = 0; c < 3; ++c)
  {
    spacing->InsertNextValue(0.25f);
  }
  points->SetPoints(p);
  points->GetPointData()->AddArray(value);
  points->GetPointData()->AddArray(error);
  points->GetFieldData()->AddArray(spacing);
  return points;
}

namespace
{
// Component c's functions exactly as the mapper tabulates them.
strata::MultiVolumeReferenceIntegrator::TransferFunction ReferenceFunction(vtkVolumeProperty* p,
  int c)
{
  strata::MultiVolumeReferenceIntegrator::TransferFunction tf;
  double range[2];
  std::vector<float> rgb, alpha;
  strata::TransferFunctionTable::Tabulate(
    p, strata::TransferFunctionTable::TableSize, range, rgb, alpha, c);
  tf.Range[0] = range[0];
  tf.Range[1] = range[1];
  tf.Opacity.assign(alpha.begin(), alpha.end());
  tf.Color.assign(rgb.begin(), rgb.end());
  tf.UnitDistance = p->GetScalarOpacityUnitDistance(c);
  return tf;
}

// The components of `v` (scalars already copied, interleaved) under `p`, as the mapper reads
// them: independent functions and weights, or RGBA colour ranges by the data type.
void ReferenceComponents(strata::MultiVolumeReferenceIntegrator::Volume& v,
  vtkVolumeProperty* p,
  vtkDataArray* scalars)
{
  using Components = strata::MultiVolumeReferenceIntegrator::Components;
  const int nc = v.NumberOfComponents;
  if (nc == 1)
    return;
  if (p->GetIndependentComponents())
  {
    v.ComponentMode = Components::Independent;
    for (int c = 0; c < nc; ++c)
    {
      v.ComponentWeights[c] = p->GetComponentWeight(c);
      if (c > 0)
        v.ComponentClassifications.push_back(ReferenceFunction(p, c));
    }
    return;
  }
  v.ComponentMode = nc == 2 ? Components::ColorOpacity : Components::RGBA;
  for (int c = 0; nc == 4 && c < 3; ++c)
    strata::MultiVolumeInput::GetColorRange(scalars, c, v.ColorRange[c]);
}
}

strata::MultiVolumeReferenceIntegrator::Volume ToReferenceVolume(vtkImageData* image,
  vtkVolume* member,
  vtkMultiVolumeRayCastMapper* mapper,
  int port)
{
  strata::MultiVolumeReferenceIntegrator::Volume v;
  image->GetDimensions(v.Dimensions);
  image->GetOrigin(v.Origin);
  image->GetSpacing(v.Spacing);
  std::copy(image->GetDirectionMatrix()->GetData(),
    image->GetDirectionMatrix()->GetData() + 9,
    v.Direction);
  member->ComputeMatrix();
  std::copy(member->GetMatrix()->GetData(), member->GetMatrix()->GetData() + 16, v.ModelMatrix);
  vtkDataArray* s = image->GetPointData()->GetScalars();
  const int nc = s->GetNumberOfComponents();
  v.NumberOfComponents = nc;
  v.FloatScalars.resize(s->GetNumberOfTuples() * nc);
  for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
    for (int c = 0; c < nc; ++c)
      v.FloatScalars[i * nc + c] = static_cast<float>(s->GetComponent(i, c));
  vtkVolumeProperty* p = member->GetProperty();
  ReferenceComponents(v, p, s);
  v.Sampling = p->GetInterpolationType() == VTK_NEAREST_INTERPOLATION
                 ? strata::MultiVolumeReferenceIntegrator::Interpolation::Nearest
                 : strata::MultiVolumeReferenceIntegrator::Interpolation::Linear;
  // Exactly the mapper's table.
  double range[2];
  std::vector<float> rgb, alpha;
  strata::TransferFunctionTable::Tabulate(
    p, strata::TransferFunctionTable::TableSize, range, rgb, alpha);
  v.Classification.Range[0] = range[0];
  v.Classification.Range[1] = range[1];
  v.Classification.Opacity.assign(alpha.begin(), alpha.end());
  v.Classification.Color.assign(rgb.begin(), rgb.end());
  v.Classification.UnitDistance = p->GetScalarOpacityUnitDistance(0);
  std::vector<float> gradient;
  if (strata::TransferFunctionTable::TabulateGradientOpacity(
        p, 256, v.Classification.GradientRange, gradient))
    v.Classification.GradientOpacity.assign(gradient.begin(), gradient.end());
  if (mapper)
  {
    v.BlendMode = static_cast<strata::MultiVolumeReferenceIntegrator::Blend>(
      mapper->GetEffectiveBlendMode(port));
    vtkContourValues* iso = p->GetIsoSurfaceValues();
    for (int i = 0; iso && i < iso->GetNumberOfContours(); ++i)
      v.IsoValues.push_back(iso->GetValue(i));
    mapper->GetAverageIPScalarRange(v.AverageRange);
    double planes[6];
    v.Cropping = mapper->GetEffectiveCropping(port, planes, v.CropFlags);
    for (int k = 0; k < 6; ++k) // data coordinates to index coordinates
      v.CropPlanes[k] = (planes[k] - v.Origin[k / 2]) / v.Spacing[k / 2];
  }
  return v;
}

VolumeComparison CompareVolumesWithReference(vtkRenderWindow* win,
  vtkRenderer* ren,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  const std::string& name,
  const std::string& imageDirectory,
  double stepFraction,
  int raysPerPixel,
  vtkMultiVolumeRayCastMapper* mapper)
{
  // Over mid grey, so that opacity errors show as well as colour errors.
  VolumeComparison r;
  const double background = 128.0 / 255.0; // exact in 8 bits: CompositeOver gets 128
  double oldBackground[3];
  ren->GetBackground(oldBackground);
  ren->SetBackground(background, background, background);
  win->Render();
  r.Gpu = ReadRGB(win);
  const int w = win->GetSize()[0], h = win->GetSize()[1];
  strata::MultiVolumeReferenceIntegrator ref;
  ref.SetStepFraction(stepFraction);
  for (size_t i = 0; i < volumes.size(); ++i)
  {
    const auto& v = volumes[i];
    if (ref.AddVolume(ToReferenceVolume(v.first, v.second, mapper, static_cast<int>(i))) < 0)
    {
      std::cerr << name << ": reference rejected a volume: " << ref.GetLastError() << "\n";
    }
  }
  auto clipToWorld = ClipToWorld(ren);
  r.Reference.assign(4 * size_t(w) * h, 0.0);
  for (int ray = 0; ray < raysPerPixel; ++ray)
  {
    std::vector<double> one;
    ref.IntegrateImage(
      SubPixelClipToWorld(clipToWorld, ray, raysPerPixel, w, h)->GetData(), w, h, one);
    for (size_t i = 0; i < one.size(); ++i)
      r.Reference[i] += one[i] / raysPerPixel;
  }
  const std::vector<unsigned char> grey(3 * size_t(w) * h, 128);
  const std::vector<double> expected = CompositeOver(r.Reference, grey);
  for (int i = 0; i < w * h; ++i)
    r.Covered += r.Reference[4 * i + 3] > 1.0 / 255.0;
  const ChannelError e = ImageError(r.Gpu, expected);
  r.Rms = e.Rms;
  r.Max = e.Max;
  ren->SetBackground(oldBackground);
  WriteComparisonImages(imageDirectory, name, r.Gpu, expected, w, h);
  return r;
}

std::vector<double> Over(const std::vector<double>& front, const std::vector<double>& back)
{
  std::vector<double> out = front;
  for (size_t i = 0; i + 3 < out.size(); i += 4)
    for (int c = 0; c < 4; ++c)
      out[i + c] += (1.0 - front[i + 3]) * back[i + c];
  return out;
}

void WriteComparisonImages(const std::string& directory,
  const std::string& name,
  const std::vector<unsigned char>& gpu,
  const std::vector<double>& expected,
  int width,
  int height)
{
  std::vector<unsigned char> refImage(expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
    refImage[i] = static_cast<unsigned char>(std::lround(expected[i]));
  WritePNG(directory + "/" + name + "-gpu.png", gpu, width, height);
  WritePNG(directory + "/" + name + "-ref.png", refImage, width, height);
}

vtkSmartPointer<vtkMatrix4x4> SubPixelClipToWorld(vtkMatrix4x4* clipToWorld,
  int ray,
  int rays,
  int width,
  int height)
{
  double offset[2];
  vtkMultiVolumeRayCastMapper::GetRayOffset(ray, rays, offset);
  vtkNew<vtkMatrix4x4> shift;
  shift->SetElement(0, 3, 2.0 * offset[0] / width);
  shift->SetElement(1, 3, 2.0 * offset[1] / height);
  auto shifted = vtkSmartPointer<vtkMatrix4x4>::New();
  vtkMatrix4x4::Multiply4x4(clipToWorld, shift, shifted);
  return shifted;
}

vtkSmartPointer<vtkMatrix4x4> ClipToWorld(vtkRenderer* ren)
{
  vtkNew<vtkMatrix4x4> worldToClip;
  worldToClip->DeepCopy(ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1, 1));
  auto clipToWorld = vtkSmartPointer<vtkMatrix4x4>::New();
  vtkMatrix4x4::Invert(worldToClip, clipToWorld);
  return clipToWorld;
}

std::vector<double> CompositeOver(const std::vector<double>& rgba,
  const std::vector<unsigned char>& background)
{
  std::vector<double> out(background.size());
  for (size_t i = 0; i < out.size() / 3; ++i)
    for (int c = 0; c < 3; ++c)
      out[3 * i + c] =
        255.0 *
        std::min(1.0, rgba[4 * i + c] + (1.0 - rgba[4 * i + 3]) * background[3 * i + c] / 255.0);
  return out;
}

ChannelError ImageError(const std::vector<unsigned char>& image,
  const std::vector<double>& expected)
{
  ChannelError e;
  double se = 0.0;
  for (size_t i = 0; i < image.size(); ++i)
  {
    const double d = double(image[i]) - expected[i];
    se += d * d;
    e.Max = std::max(e.Max, std::abs(d));
  }
  e.Rms = image.empty() ? 0.0 : std::sqrt(se / image.size());
  return e;
}

ChannelError ImageError(const std::vector<unsigned char>& image,
  const std::vector<unsigned char>& expected)
{
  return ImageError(image, std::vector<double>(expected.begin(), expected.end()));
}

long PixelsOff(const std::vector<unsigned char>& image,
  const std::vector<unsigned char>& expected,
  int threshold)
{
  long n = 0;
  for (size_t p = 0; p + 2 < image.size() && p + 2 < expected.size(); p += 3)
  {
    int m = 0;
    for (int c = 0; c < 3; ++c)
      m = std::max(m, std::abs(int(image[p + c]) - int(expected[p + c])));
    n += m > threshold ? 1 : 0;
  }
  return n;
}

vtkSmartPointer<vtkVolume> AddVolumeDemoScene(vtkRenderer* ren,
  const std::string& dataDir,
  std::vector<std::pair<vtkSmartPointer<vtkImageData>, vtkSmartPointer<vtkVolume>>>& inputs)
{
  const std::string path = dataDir + "/volumes/bucky.raw";
  if (!std::ifstream(path))
  {
    std::cerr << "Cannot read " << path << "\n";
    return nullptr;
  }
  vtkNew<vtkImageReader2> reader;
  reader->SetFileName(path.c_str());
  reader->SetFileDimensionality(3);
  reader->SetDataScalarTypeToUnsignedChar();
  reader->SetDataExtent(0, 31, 0, 31, 0, 31);
  reader->SetDataByteOrderToLittleEndian();
  reader->Update();
  auto bucky = vtkSmartPointer<vtkImageData>::New();
  bucky->ShallowCopy(reader->GetOutput());

  auto mapper = vtkSmartPointer<vtkMultiVolumeRayCastMapper>::New();
  mapper->SetSampleDistance(0.25);
  auto multi = vtkSmartPointer<vtkMultiVolume>::New();
  multi->SetMapper(mapper);
  auto add = [&](vtkImageData* image, vtkVolumeProperty* property, vtkTransform* transform)
  {
    const int port = static_cast<int>(inputs.size());
    mapper->SetInputDataObject(port, image);
    auto v = vtkSmartPointer<vtkVolume>::New();
    v->SetProperty(property);
    if (transform)
    {
      v->SetUserTransform(transform);
    }
    multi->SetVolume(v, port);
    inputs.emplace_back(image, v);
  };

  // Bucky ball: density 0-255; the carbon shells opaque-ish, the empty inside clear.
  auto buckyProperty = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->AddRGBPoint(0, 0.9, 0.9, 0.95);
  ctf->AddRGBPoint(60, 0.95, 0.85, 0.5);
  ctf->AddRGBPoint(255, 1.0, 0.5, 0.2);
  vtkNew<vtkPiecewiseFunction> pwf;
  pwf->AddPoint(0, 0.0);
  pwf->AddPoint(25, 0.0);
  pwf->AddPoint(80, 0.25);
  pwf->AddPoint(255, 0.6);
  buckyProperty->SetColor(ctf);
  buckyProperty->SetScalarOpacity(pwf);
  buckyProperty->SetInterpolationTypeToLinear();
  add(bucky, buckyProperty, nullptr);

  const double s1[3] = { 0.9, 0.9, 0.9 }, o1[3] = { 0, 0, 0 };
  vtkNew<vtkTransform> t1;
  t1->Translate(14, -6, 2);
  t1->RotateWXYZ(25, 1, 1, 0);
  // Its faint outskirts (values 20-35) would veil the Bucky ball: transparent here.
  auto blobProperty = MakeVolumeProperty(0, 2.0);
  vtkPiecewiseFunction* blobOpacity = blobProperty->GetScalarOpacity(0);
  blobOpacity->RemoveAllPoints();
  blobOpacity->AddPoint(0, 0.0);
  blobOpacity->AddPoint(35, 0.0);
  blobOpacity->AddPoint(60, 0.08);
  blobOpacity->AddPoint(100, 0.3);
  add(MakeBlobVolume(48, 40, 36, s1, o1, 3), blobProperty, t1);

  const double s2[3] = { 1.8, 1.8, 1.8 }, o2[3] = { 0, 0, 0 };
  vtkNew<vtkTransform> t2;
  t2->Translate(40, 18, -8);
  t2->RotateZ(60);
  add(MakeBlobVolume(20, 20, 20, s2, o2, 5), MakeVolumeProperty(1, 2.0), t2);

  ren->AddVolume(multi);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(30, 14, 14);
  cam->SetPosition(-25, -75, 70);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(30);
  ren->ResetCameraClippingRange(-40, 100, -60, 80, -40, 80);
  return multi;
}

bool CheckVolumeComparison(const VolumeComparison& c,
  const std::string& name,
  double rmsBound,
  double maxBound,
  long minCovered)
{
  std::cout << name << ": covered " << c.Covered << " px, RMS error " << c.Rms << " (bound "
            << rmsBound << "), max error " << c.Max << " (bound " << maxBound << ") of 255\n";
  bool ok = true;
  if (c.Covered < minCovered)
  {
    std::cerr << name << ": FAILED: only " << c.Covered
              << " covered pixels, expected >= " << minCovered << "\n";
    ok = false;
  }
  if (c.Rms > rmsBound)
  {
    std::cerr << name << ": FAILED: RMS error above its bound\n";
    ok = false;
  }
  if (c.Max > maxBound)
  {
    std::cerr << name << ": FAILED: max error above its bound\n";
    ok = false;
  }
  return ok;
}

strata::MultiVolumeReferenceIntegrator::CrossingFunction HorizonCrossings(
  vtkStackedHeightFieldMapper* mapper,
  const std::vector<std::array<double, 3>>& colors)
{
  using Ref = strata::MultiVolumeReferenceIntegrator;
  const strata::HeightFieldStack* stack = mapper->GetStack();
  double gridToWorld[16];
  mapper->GetGridToWorld(gridToWorld);
  vtkNew<vtkMatrix4x4> worldToGrid;
  worldToGrid->DeepCopy(gridToWorld);
  worldToGrid->Invert();
  const std::vector<double> m(worldToGrid->GetData(), worldToGrid->GetData() + 16);
  // Premultiplied colour of each translucent horizon (opacity 0 for an opaque one: skipped).
  std::vector<std::array<double, 4>> premultiplied(stack ? stack->GetNumberOfLayers() : 0);
  for (size_t k = 0; k < premultiplied.size(); ++k)
  {
    const double a = mapper->GetHorizonOpacity(static_cast<int>(k));
    const std::array<double, 3> rgb = k < colors.size() ? colors[k] : std::array<double, 3>{};
    premultiplied[k] = a < 1.0 ? std::array<double, 4>{ a * rgb[0], a * rgb[1], a * rgb[2], a }
                               : std::array<double, 4>{};
  }
  return
    [stack, m, premultiplied](
      const double o[3], const double d[3], double t0, double t1, std::vector<Ref::Crossing>& out)
  {
    if (!stack)
      return;
    // World to grid is affine: the ray keeps its parameter.
    double og[3], dg[3];
    for (int r = 0; r < 3; ++r)
    {
      og[r] = m[4 * r + 3];
      dg[r] = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        og[r] += m[4 * r + c] * o[c];
        dg[r] += m[4 * r + c] * d[c];
      }
    }
    for (const auto& hit : strata::HeightFieldReferenceCaster(*stack).CastAll(og, dg, t0, t1))
    {
      const std::array<double, 4>& c = premultiplied[hit.Layer];
      if (c[3] <= 0.0)
        continue; // opaque: the scene's depth stops the ray there
      Ref::Crossing crossing;
      crossing.T = hit.T;
      std::copy(c.begin(), c.end(), crossing.Color);
      out.push_back(crossing);
    }
  };
}
}

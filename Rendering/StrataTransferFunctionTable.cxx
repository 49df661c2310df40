// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataTransferFunctionTable.h"

#include "vtkColorTransferFunction.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

namespace strata
{

TransferFunctionTable::TransferFunctionTable() = default;
TransferFunctionTable::~TransferFunctionTable() = default;

vtkTextureObject* TransferFunctionTable::GetTexture() const
{
  return this->Texture;
}

vtkMTimeType TransferFunctionTable::GetMTime(vtkVolumeProperty* property, int component)
{
  const int c = component;
  const bool rgb = property->GetColorChannels(c) == 3;
  const vtkMTimeType color = rgb ? property->GetRGBTransferFunction(c)->GetMTime()
                                 : property->GetGrayTransferFunction(c)->GetMTime();
  return std::max({ property->GetMTime(), property->GetScalarOpacity(c)->GetMTime(), color });
}

bool TransferFunctionTable::TabulateGradientOpacity(vtkVolumeProperty* property,
  int size,
  double range[2],
  std::vector<float>& opacity)
{
  if (!property->HasGradientOpacity(0) || property->GetDisableGradientOpacity(0))
    return false;
  vtkPiecewiseFunction* go = property->GetStoredGradientOpacity(0);
  go->GetRange(range);
  if (!(range[1] > range[0]))
    range[1] = range[0] + 1.0;
  opacity.resize(size);
  go->GetTable(range[0], range[1], size, opacity.data());
  return true;
}

void TransferFunctionTable::Tabulate(vtkVolumeProperty* property,
  int size,
  double range[2],
  std::vector<float>& rgb,
  std::vector<float>& opacity,
  int component)
{
  // Only the getter of the colour kind in use: VTK's getters create (and switch to) a default.
  const int c = component;
  const bool useRgb = property->GetColorChannels(c) == 3;
  vtkColorTransferFunction* color = useRgb ? property->GetRGBTransferFunction(c) : nullptr;
  vtkPiecewiseFunction* gray = useRgb ? nullptr : property->GetGrayTransferFunction(c);
  vtkPiecewiseFunction* alpha = property->GetScalarOpacity(c);
  alpha->GetRange(range);
  double cr[2];
  if (useRgb)
    color->GetRange(cr);
  else
    gray->GetRange(cr);
  range[0] = std::min(range[0], cr[0]);
  range[1] = std::max(range[1], cr[1]);
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  rgb.resize(3 * size_t(size));
  opacity.resize(size);
  if (useRgb)
  {
    color->GetTable(range[0], range[1], size, rgb.data());
  }
  else
  {
    std::vector<float> g(size);
    gray->GetTable(range[0], range[1], size, g.data());
    for (int i = 0; i < size; ++i)
      rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = g[i];
  }
  alpha->GetTable(range[0], range[1], size, opacity.data());
}

void TransferFunctionTable::TabulateExtinction(vtkVolumeProperty* property,
  int size,
  double range[2],
  std::vector<float>& rgbTau,
  std::vector<float>& opacity,
  int component)
{
  std::vector<float> rgb;
  Tabulate(property, size, range, rgb, opacity, component);
  const double unit = GetUnitDistance(property, component);
  rgbTau.resize(4 * size_t(size));
  for (int i = 0; i < size; ++i)
  {
    const double a = std::min(std::max(double(opacity[i]), 0.0), 1.0 - 1e-6);
    for (int c = 0; c < 3; ++c)
      rgbTau[4 * i + c] = rgb[3 * i + c];
    rgbTau[4 * i + 3] = static_cast<float>(-std::log(1.0 - a) / unit);
  }
}

bool TransferFunctionTable::Update(vtkOpenGLRenderWindow* renWin,
  vtkVolumeProperty* property,
  int component)
{
  const vtkMTimeType time = GetMTime(property, component);
  if (this->Texture && this->Property == property && this->Component == component &&
      this->Time >= time)
  {
    return false;
  }
  TabulateExtinction(
    property, TableSize, this->ScalarRange, this->RGBTau, this->Opacity, component);
  if (!this->Texture)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
  }
  this->Texture->SetContext(renWin);
  this->Texture->ReleaseGraphicsResources(renWin);
  this->Texture->SetContext(renWin);
  this->Texture->Create2DFromRaw(TableSize, 1, 4, VTK_FLOAT, this->RGBTau.data());
  this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
  this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
  this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
  this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
  // Entry i sits at scalar r0 + i (r1 - r0) / (N - 1), its texel centre at (i + 0.5) / N.
  const double* r = this->ScalarRange;
  this->TableRange[0] = r[0];
  this->TableRange[1] = (TableSize - 1.0) / (TableSize * (r[1] - r[0]));
  this->TableRange[2] = 0.5 / TableSize;
  this->Property = property;
  this->Component = component;
  this->Time = time;
  ++this->BuildCount;
  return true;
}

void TransferFunctionTable::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Texture)
  {
    this->Texture->ReleaseGraphicsResources(window);
  }
  this->Texture = nullptr;
  this->Property = nullptr;
  this->Time = 0;
}

double TransferFunctionTable::GetUnitDistance(vtkVolumeProperty* property, int component)
{
  return std::max(property->GetScalarOpacityUnitDistance(component), 1e-30);
}
}

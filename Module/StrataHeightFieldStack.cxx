// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldStack.h"

#include <cmath>
#include <limits>
#include <type_traits>

namespace strata
{

HeightFieldStack::~HeightFieldStack() = default;

bool HeightFieldStack::Initialize(int nx, int ny)
{
  this->Layers.clear();
  this->ErrorMessage.clear();
  // 2^31 points per layer is far beyond any one horizon and keeps every index in 64-bit range
  // arithmetic honest; a GPU texture could not hold it either.
  if (nx < 1 || ny < 1 || static_cast<double>(nx) * ny > 2147483647.0)
  {
    this->ErrorMessage = "height-field grid of " + std::to_string(nx) + " x " + std::to_string(ny) +
                         " points is empty or too large";
    this->NX = this->NY = this->InputNX = this->InputNY = 0;
    return false;
  }
  this->InputNX = nx;
  this->InputNY = ny;
  this->NX = nx == 1 ? 2 : nx;
  this->NY = ny == 1 ? 2 : ny;
  this->IndexOffset[0] = nx == 1 ? -0.5 : 0.0;
  this->IndexOffset[1] = ny == 1 ? -0.5 : 0.0;
  return true;
}

template<typename T>
bool HeightFieldStack::AddLayerT(const T* values, bool useNull, double nullValue, bool mayBorrow)
{
  if (this->NX == 0 || !values)
  {
    this->ErrorMessage = "AddLayer before Initialize, or no values";
    return false;
  }
  const bool expanded = this->NX != this->InputNX || this->NY != this->InputNY;
  const size_t n = static_cast<size_t>(this->InputNX) * this->InputNY;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto isHole = [&](double v)
  { return std::isnan(v) || std::abs(v) >= 1e30 || (useNull && v == nullValue); };

  Layer layer;
  layer.Min = std::numeric_limits<double>::infinity();
  layer.Max = -std::numeric_limits<double>::infinity();
  bool needsChange = false;
  for (size_t i = 0; i < n; ++i)
  {
    const double v = static_cast<double>(values[i]);
    if (isHole(v))
    {
      ++layer.Holes;
      // NaN stays as it is; anything else marked as a hole must be rewritten.
      needsChange = needsChange || !std::isnan(v);
    }
    else
    {
      layer.Min = std::min(layer.Min, static_cast<double>(static_cast<float>(v)));
      layer.Max = std::max(layer.Max, static_cast<double>(static_cast<float>(v)));
    }
  }
  if (layer.Holes == n)
  {
    layer.Min = 0.0;
    layer.Max = -1.0;
  }

  if (mayBorrow && !needsChange && !expanded)
  {
    layer.Values = reinterpret_cast<const float*>(values);
  }
  else
  {
    const size_t m = static_cast<size_t>(this->NX) * this->NY;
    layer.Owned.reset(new float[m]);
    float* out = layer.Owned.get();
    for (int j = 0; j < this->NY; ++j)
    {
      const int sj = this->InputNY == 1 ? 0 : j;
      for (int i = 0; i < this->NX; ++i)
      {
        const int si = this->InputNX == 1 ? 0 : i;
        const double v = static_cast<double>(values[static_cast<size_t>(sj) * this->InputNX + si]);
        out[static_cast<size_t>(j) * this->NX + i] = isHole(v) ? nan : static_cast<float>(v);
      }
    }
    layer.Values = out;
  }
  this->Layers.push_back(std::move(layer));
  return true;
}

bool HeightFieldStack::AddLayer(const float* values, bool useNull, double nullValue)
{
  return this->AddLayerT(values, useNull, nullValue, true);
}

bool HeightFieldStack::AddLayer(const double* values, bool useNull, double nullValue)
{
  return this->AddLayerT(values, useNull, nullValue, false);
}

bool HeightFieldStack::HasHoles() const
{
  for (const auto& layer : this->Layers)
  {
    if (layer.Holes > 0)
    {
      return true;
    }
  }
  return false;
}

bool HeightFieldStack::Interpolate(int k, double x, double y, double& value) const
{
  x = std::min(std::max(x, 0.0), static_cast<double>(this->NX - 1));
  y = std::min(std::max(y, 0.0), static_cast<double>(this->NY - 1));
  const int i = std::min(static_cast<int>(x), this->NX - 2);
  const int j = std::min(static_cast<int>(y), this->NY - 2);
  const double u = x - i, v = y - j;
  const double weights[4] = { (1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v };
  const float corners[4] = { this->GetHeight(k, i, j),
    this->GetHeight(k, i + 1, j),
    this->GetHeight(k, i, j + 1),
    this->GetHeight(k, i + 1, j + 1) };
  double sum = 0.0, weight = 0.0;
  for (int c = 0; c < 4; ++c)
  {
    if (!std::isnan(corners[c]))
    {
      sum += weights[c] * corners[c];
      weight += weights[c];
    }
  }
  // A point exactly on a hole corner has weight 0 from the valid ones: take their mean then.
  if (weight <= 0.0)
  {
    int valid = 0;
    for (int c = 0; c < 4; ++c)
    {
      if (!std::isnan(corners[c]))
      {
        sum += corners[c];
        ++valid;
      }
    }
    if (valid == 0)
      return false;
    value = sum / valid;
    return true;
  }
  value = sum / weight;
  return true;
}

void HeightFieldStack::GetZRange(double range[2]) const
{
  range[0] = std::numeric_limits<double>::infinity();
  range[1] = -std::numeric_limits<double>::infinity();
  for (const auto& layer : this->Layers)
  {
    if (layer.Min <= layer.Max)
    {
      range[0] = std::min(range[0], layer.Min);
      range[1] = std::max(range[1], layer.Max);
    }
  }
  if (range[0] > range[1])
  {
    range[0] = 0.0;
    range[1] = -1.0;
  }
}
}

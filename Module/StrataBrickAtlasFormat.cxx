// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataBrickAtlasFormat.h"

#include "vtkType.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace strata
{

namespace
{
using ScalarType = BrickAtlasFormat::ScalarType;

// The offset an integer volume's values get in an atlas of `atlas` (int16 in uint16).
double StoredOffset(ScalarType atlas, ScalarType volume)
{
  return atlas == ScalarType::UInt16 && volume == ScalarType::Int16 ? 32768.0 : 0.0;
}

// The factor they get (8-bit in uint16: 257, 255 to 65535; exact in float).
double StoredScale(ScalarType atlas, ScalarType volume)
{
  return atlas == ScalarType::UInt16 && volume == ScalarType::UInt8 ? 257.0 : 1.0;
}

template<typename T>
void EncodeAs(const float* values, size_t n, double scale, double offset, T* out)
{
  const float lo = 0.0f, hi = static_cast<float>(std::numeric_limits<T>::max());
  const float s = static_cast<float>(scale);
  const float o = static_cast<float>(offset);
  for (size_t i = 0; i < n; ++i)
  {
    const float v = values[i] * s + o;
    // NaN (which integer data never has) stores as 0.
    out[i] = static_cast<T>(v >= lo ? std::floor(std::min(v, hi) + 0.5f) : 0.0f);
  }
}
}

ScalarType BrickAtlasFormat::Choose(const std::vector<ScalarType>& types, Storage storage)
{
  if (storage == Storage::Float32 || types.empty())
    return ScalarType::Float32;
  ScalarType widest = ScalarType::UInt8;
  for (ScalarType t : types)
  {
    if (t == ScalarType::Float32)
      return ScalarType::Float32;
    if (t != ScalarType::UInt8 || storage == Storage::Normalized16)
      widest = ScalarType::UInt16;
  }
  return widest;
}

ScalarType BrickAtlasFormat::FromVTKType(int vtkType)
{
  switch (vtkType)
  {
    case VTK_UNSIGNED_CHAR:
      return ScalarType::UInt8;
    case VTK_SIGNED_CHAR:
    case VTK_SHORT:
      return ScalarType::Int16;
    case VTK_UNSIGNED_SHORT:
      return ScalarType::UInt16;
    default:
      return ScalarType::Float32;
  }
}

void BrickAtlasFormat::GetDecode(ScalarType atlas, ScalarType volume, double& scale, double& offset)
{
  switch (atlas)
  {
    case ScalarType::UInt8:
      scale = 255.0;
      break;
    case ScalarType::UInt16:
    case ScalarType::Int16:
      scale = 65535.0;
      break;
    default:
      scale = 1.0;
  }
  scale /= StoredScale(atlas, volume);
  offset = -StoredOffset(atlas, volume);
}

void BrickAtlasFormat::Encode(const float* values,
  size_t n,
  ScalarType atlas,
  ScalarType volume,
  void* out)
{
  switch (atlas)
  {
    case ScalarType::UInt8:
      EncodeAs(values, n, 1.0, 0.0, static_cast<uint8_t*>(out));
      return;
    case ScalarType::UInt16:
    case ScalarType::Int16:
      EncodeAs(values,
        n,
        StoredScale(ScalarType::UInt16, volume),
        StoredOffset(ScalarType::UInt16, volume),
        static_cast<uint16_t*>(out));
      return;
    case ScalarType::Float32:
      std::memcpy(out, values, n * sizeof(float));
      return;
  }
}

const char* BrickAtlasFormat::GetName(ScalarType type)
{
  switch (type)
  {
    case ScalarType::UInt8:
      return "uint8";
    case ScalarType::UInt16:
      return "uint16";
    case ScalarType::Int16:
      return "int16";
    default:
      return "float32";
  }
}
}

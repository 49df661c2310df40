// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Writes the seeds of the formats only Strata writes, with Strata's own writers, into
// <corpus>/page_pool/ and <corpus>/hybrid_volume/ (the other seeds come from make-seeds.py):
//   strata-fuzz-seeds Testing/Fuzz/corpus
// Each is a few KB: 8-value pages, a few levels, one page compressed, holes in a tile pool.
#include "StrataHybridVolumeFile.h"
#include "StrataPagePoolWriter.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <sys/stat.h>

namespace
{
using Kind = strata::PagePoolWriter::Kind;
using ScalarType = strata::PagePoolWriter::ScalarType;

/// A pool of `dims` (x fastest) of a smooth pattern in `type`; NaN holes in float tiles.
bool WritePool(const std::string& path,
  Kind kind,
  ScalarType type,
  const int dims[3],
  bool zstd,
  int components = 1)
{
  strata::PagePoolWriter writer;
  writer.SetFileName(path);
  writer.SetComponent(0, components, 0x5eedu); // a set's component 0: a version 2 header
  writer.SetKind(kind);
  writer.SetScalarType(type);
  writer.SetDimensions(dims[0], dims[1], dims[2]);
  writer.SetPageSize(8);
  writer.SetCompression(zstd);
  writer.SetSpacing(2, 3, 4);
  writer.SetOrigin(-1, 5, 10);
  const bool tiles = kind == Kind::TilePool;
  if (type == ScalarType::Float32)
  {
    writer.SetNoDataValue(-999.0);
  }
  writer.SetSource(
    [=](int first, int count, void* buffer)
    {
      // Slabs along z for bricks; along y for tiles, each row holding every layer of its nodes.
      const int nx = dims[0];
      const int rest = tiles ? dims[2] : dims[1];
      for (int s = 0; s < count; ++s)
      {
        for (int b = 0; b < rest; ++b)
        {
          for (int x = 0; x < nx; ++x)
          {
            const size_t n = tiles ? (static_cast<size_t>(b) * count + s) * nx + x
                                   : (static_cast<size_t>(s) * rest + b) * nx + x;
            const double v = 40.0 + 30.0 * std::sin(0.7 * x + 0.3 * b + 0.5 * (first + s));
            switch (type)
            {
              case ScalarType::UInt8:
                static_cast<unsigned char*>(buffer)[n] = static_cast<unsigned char>(v);
                break;
              case ScalarType::UInt16:
                static_cast<unsigned short*>(buffer)[n] = static_cast<unsigned short>(v * 100);
                break;
              case ScalarType::Int16:
                static_cast<short*>(buffer)[n] = static_cast<short>(v * 100 - 4000);
                break;
              case ScalarType::Float32:
                static_cast<float*>(buffer)[n] =
                  (x + b) % 5 == 0 ? std::nanf("") : (x == 3 ? -999.0f : static_cast<float>(v));
                break;
            }
          }
        }
      }
      return true;
    });
  if (!writer.Write())
  {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), writer.GetErrorMessage().c_str());
    return false;
  }
  return true;
}

bool WriteHybrid(const std::string& path, int points)
{
  strata::HybridVolumeFile file;
  const int dims[3] = { 9, 7, 5 };
  for (int a = 0; a < 3; ++a)
  {
    file.Dimensions[a] = dims[a];
    file.Factor[a] = 2;
    file.LowDimensions[a] = strata::HybridVolumeFile::GetLowResolutionDimension(dims[a], 2);
    file.ErrorGridStep[a] = 2;
  }
  file.LowResolution.resize(
    static_cast<size_t>(file.LowDimensions[0]) * file.LowDimensions[1] * file.LowDimensions[2]);
  for (size_t i = 0; i < file.LowResolution.size(); ++i)
  {
    file.LowResolution[i] = static_cast<float>(i % 11) * 0.25f;
  }
  for (int p = 0; p < points; ++p)
  {
    strata::HybridVolumeFile::Point point;
    point.Position[0] = static_cast<uint16_t>(p % dims[0]);
    point.Position[1] = static_cast<uint16_t>(p % dims[1]);
    point.Position[2] = static_cast<uint16_t>(p % dims[2]);
    point.Normal = strata::HybridVolumeFile::EncodeNormal(0.3, -0.4, 0.8);
    point.Value = 1.5f * p;
    point.Error = 0.1f * p;
    file.Points.push_back(point);
  }
  file.Threshold = 0.05;
  file.PointBudget = static_cast<uint64_t>(points);
  if (!file.Write(path))
  {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), file.GetErrorMessage().c_str());
    return false;
  }
  return true;
}
}

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: strata-fuzz-seeds <corpus folder>\n");
    return 2;
  }
  const std::string root = argv[1];
  const std::string pools = root + "/page_pool/";
  const std::string hybrids = root + "/hybrid_volume/";
  mkdir(pools.c_str(), 0755);
  mkdir(hybrids.c_str(), 0755);
  const int brick[3] = { 10, 9, 7 };
  const int flat[3] = { 12, 1, 1 };
  const int tile[3] = { 11, 9, 2 };
  const int tile1[3] = { 6, 5, 1 };
  bool ok = WritePool(pools + "bricks_uint8.spp", Kind::BrickPool, ScalarType::UInt8, brick, false);
  ok &= WritePool(pools + "bricks_int16_zstd.spp", Kind::BrickPool, ScalarType::Int16, brick, true);
  ok &=
    WritePool(pools + "bricks_uint16_row.spp", Kind::BrickPool, ScalarType::UInt16, flat, false);
  ok &=
    WritePool(pools + "tiles_float_holes.spp", Kind::TilePool, ScalarType::Float32, tile, false);
  ok &= WritePool(pools + "tiles_float_zstd.spp", Kind::TilePool, ScalarType::Float32, tile1, true);
  ok &= WritePool(
    pools + "bricks_uint8_component0of2.spp", Kind::BrickPool, ScalarType::UInt8, brick, false, 2);
  ok &= WriteHybrid(hybrids + "points5.shv", 5);
  ok &= WriteHybrid(hybrids + "no_points.shv", 0);
  return ok ? 0 : 1;
}

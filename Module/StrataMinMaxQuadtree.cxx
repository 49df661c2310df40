// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMinMaxQuadtree.h"

#include "StrataHeightFieldStack.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata
{

namespace
{
constexpr float Inf = std::numeric_limits<float>::infinity();
}

std::array<int, 2> MinMaxQuadtree::GetLeafCount(int nx, int ny, int tileSize)
{
  const int T = std::max(1, tileSize);
  // Tiles cover cells: nx-1 of them in x.
  return { std::max(1, (nx - 1 + T - 1) / T), std::max(1, (ny - 1 + T - 1) / T) };
}

void MinMaxQuadtree::BuildLevels(int nx, int ny, int tileSize)
{
  this->TileSize = std::max(1, tileSize);
  this->LevelDims.clear();
  this->LevelOffsets.clear();
  this->Nodes.clear();
  this->Intervals.clear();
  this->LayerLists.clear();
  auto leaves = GetLeafCount(nx, ny, this->TileSize);
  int tx = leaves[0];
  int ty = leaves[1];
  for (;;)
  {
    this->LevelOffsets.push_back(static_cast<int>(
      this->LevelDims.empty()
        ? 0
        : this->LevelOffsets.back() + this->LevelDims.back()[0] * this->LevelDims.back()[1]));
    this->LevelDims.push_back({ tx, ty });
    if (tx == 1 && ty == 1)
    {
      break;
    }
    tx = (tx + 1) / 2;
    ty = (ty + 1) / 2;
  }
  this->Nodes.resize(this->LevelOffsets.back() + 1);
}

void MinMaxQuadtree::Build(const strata::HeightFieldStack& stack, int tileSize)
{
  const int nx = stack.GetNX();
  const int ny = stack.GetNY();
  const int layers = stack.GetNumberOfLayers();
  this->BuildLevels(nx, ny, tileSize);
  const int T = this->TileSize;
  const size_t total = this->Nodes.size();

  // Per node and layer ranges; layer-major within a node.
  std::vector<float> lmin(total * layers, Inf);
  std::vector<float> lmax(total * layers, -Inf);

  // Leaves: one pass over each layer, point (i, j) feeding every tile whose closed footprint
  // holds it (a point on a tile boundary belongs to up to four tiles).
  const int ltx = this->LevelDims[0][0];
  const int lty = this->LevelDims[0][1];
  for (int k = 0; k < layers; ++k)
  {
    const float* h = stack.GetLayer(k);
    for (int j = 0; j < ny; ++j)
    {
      // Tiles b with b T <= j <= (b + 1) T.
      const int b0 = j == 0 ? 0 : (j - 1) / T;
      const int b1 = std::min(j / T, lty - 1);
      const float* row = h + static_cast<size_t>(j) * nx;
      for (int i = 0; i < nx; ++i)
      {
        const float v = row[i];
        if (std::isnan(v))
        {
          continue;
        }
        const int a0 = i == 0 ? 0 : (i - 1) / T;
        const int a1 = std::min(i / T, ltx - 1);
        for (int b = b0; b <= b1; ++b)
        {
          for (int a = a0; a <= a1; ++a)
          {
            const size_t idx = static_cast<size_t>(b * ltx + a) * layers + k;
            lmin[idx] = std::min(lmin[idx], v);
            lmax[idx] = std::max(lmax[idx], v);
          }
        }
      }
    }
  }
  this->BuildUpperLevels(layers, lmin, lmax);
}

void MinMaxQuadtree::BuildFromLeafRanges(int nx,
  int ny,
  int layers,
  int tileSize,
  const std::vector<float>& leafMin,
  const std::vector<float>& leafMax)
{
  this->BuildLevels(nx, ny, tileSize);
  const size_t total = this->Nodes.size();
  const size_t leafValues =
    static_cast<size_t>(this->LevelDims[0][0]) * this->LevelDims[0][1] * layers;
  std::vector<float> lmin(total * layers, Inf);
  std::vector<float> lmax(total * layers, -Inf);
  const size_t given = std::min({ leafValues, leafMin.size(), leafMax.size() });
  std::copy_n(leafMin.begin(), given, lmin.begin());
  std::copy_n(leafMax.begin(), given, lmax.begin());
  this->BuildUpperLevels(layers, lmin, lmax);
}

void MinMaxQuadtree::BuildUpperLevels(int layers,
  std::vector<float>& lmin,
  std::vector<float>& lmax)
{
  const int levels = static_cast<int>(this->LevelDims.size());
  const int total = static_cast<int>(this->Nodes.size());
  // Coarser levels: union of the children.
  for (int l = 1; l < levels; ++l)
  {
    const int cx = this->LevelDims[l - 1][0];
    const int cy = this->LevelDims[l - 1][1];
    for (int b = 0; b < this->LevelDims[l][1]; ++b)
    {
      for (int a = 0; a < this->LevelDims[l][0]; ++a)
      {
        const size_t parent =
          static_cast<size_t>(this->LevelOffsets[l] + b * this->LevelDims[l][0] + a);
        for (int cb = 2 * b; cb < std::min(2 * b + 2, cy); ++cb)
        {
          for (int ca = 2 * a; ca < std::min(2 * a + 2, cx); ++ca)
          {
            const size_t child = static_cast<size_t>(this->LevelOffsets[l - 1] + cb * cx + ca);
            for (int k = 0; k < layers; ++k)
            {
              lmin[parent * layers + k] =
                std::min(lmin[parent * layers + k], lmin[child * layers + k]);
              lmax[parent * layers + k] =
                std::max(lmax[parent * layers + k], lmax[child * layers + k]);
            }
          }
        }
      }
    }
  }
  std::vector<float> nodeMin(layers), nodeMax(layers);
  for (int n = 0; n < total; ++n)
  {
    std::copy_n(lmin.begin() + static_cast<size_t>(n) * layers, layers, nodeMin.begin());
    std::copy_n(lmax.begin() + static_cast<size_t>(n) * layers, layers, nodeMax.begin());
    this->BuildIntervals(nodeMin, nodeMax, layers, this->Nodes[n]);
  }
}

void MinMaxQuadtree::BuildIntervals(const std::vector<float>& layerMin,
  const std::vector<float>& layerMax,
  int layers,
  Node& node)
{
  node.Min = Inf;
  node.Max = -Inf;
  node.IntervalOffset = static_cast<int>(this->Intervals.size());
  node.IntervalCount = 0;
  std::vector<float> ends;
  for (int k = 0; k < layers; ++k)
  {
    if (layerMin[k] <= layerMax[k])
    {
      ends.push_back(layerMin[k]);
      ends.push_back(layerMax[k]);
      node.Min = std::min(node.Min, layerMin[k]);
      node.Max = std::max(node.Max, layerMax[k]);
    }
  }
  if (ends.empty())
  {
    return;
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());

  // Elementary pieces in increasing z: at each end point e_i a point piece [e_i, e_i] for the
  // layers flat at e_i (min == max; no span holds them), then the span [e_i, e_i+1] for the
  // layers whose range covers it. Pieces with no layers are dropped (empty space), adjacent
  // ones with the same layers merged: fewer, longer searches.
  std::vector<int> layersHere;
  auto emit = [&](float lo, float hi)
  {
    if (layersHere.empty())
    {
      return;
    }
    if (node.IntervalCount > 0)
    {
      Interval& last = this->Intervals.back();
      if (last.ZMax == lo && last.LayerCount == static_cast<int>(layersHere.size()) &&
          std::equal(
            layersHere.begin(), layersHere.end(), this->LayerLists.begin() + last.LayerOffset))
      {
        last.ZMax = hi;
        return;
      }
    }
    Interval interval;
    interval.ZMin = lo;
    interval.ZMax = hi;
    interval.LayerOffset = static_cast<int>(this->LayerLists.size());
    interval.LayerCount = static_cast<int>(layersHere.size());
    this->LayerLists.insert(this->LayerLists.end(), layersHere.begin(), layersHere.end());
    this->Intervals.push_back(interval);
    ++node.IntervalCount;
  };
  for (size_t e = 0; e < ends.size(); ++e)
  {
    layersHere.clear();
    for (int k = 0; k < layers; ++k)
    {
      if (layerMin[k] == ends[e] && layerMax[k] == ends[e])
      {
        layersHere.push_back(k);
      }
    }
    emit(ends[e], ends[e]);
    if (e + 1 == ends.size())
    {
      break;
    }
    layersHere.clear();
    for (int k = 0; k < layers; ++k)
    {
      if (layerMin[k] <= ends[e] && layerMax[k] >= ends[e + 1])
      {
        layersHere.push_back(k);
      }
    }
    emit(ends[e], ends[e + 1]);
  }
}

size_t MinMaxQuadtree::GetMemorySize() const
{
  return this->Nodes.size() * 16 + this->Intervals.size() * 16 + this->LayerLists.size() * 4;
}
}

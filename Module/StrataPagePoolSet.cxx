// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPagePoolSet.h"

#include "StrataPagePoolFile.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkType.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace
{
using Format = strata::PagePoolFormat;

int ToVTKType(Format::ScalarType type)
{
  switch (type)
  {
    case Format::ScalarType::UInt8:
      return VTK_UNSIGNED_CHAR;
    case Format::ScalarType::UInt16:
      return VTK_UNSIGNED_SHORT;
    case Format::ScalarType::Int16:
      return VTK_SHORT;
    case Format::ScalarType::Float32:
      return VTK_FLOAT;
  }
  return VTK_VOID;
}

/// First page whose points include level index p (pages share their last point with the next
/// page's first, so p = i S belongs to page i - 1 as well; the lower one is taken).
int PageOf(int p, int stride, int pages)
{
  const int i = p <= 0 ? 0 : (p - 1) / stride;
  return std::min(i, pages - 1);
}

/// Where a page lands in the output: the output `extent` (level indices), component `c` of
/// `nc`, values of `valueSize` bytes; tile pages are x, y, layer (`layer` >= 0), brick pages
/// x, y, z.
struct Destination
{
  const int* Extent;
  int Layer;
  int Component;
  int Components;
  int ValueSize;
  unsigned char* Values;
};

/// The part of page `at` (page indices; B values a side) inside the output.
void CopyPage(const unsigned char* page, const int at[3], int B, const Destination& to)
{
  const bool tiles = to.Layer >= 0;
  const int S = B - 1;
  const int* extent = to.Extent;
  const int base[3] = { at[0] * S, at[1] * S, tiles ? 0 : at[2] * S };
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    const int pageHi = a < (tiles ? 2 : 3) ? base[a] + B - 1 : 0;
    lo[a] = std::max(extent[2 * a], base[a]);
    hi[a] = std::min(extent[2 * a + 1], pageHi);
  }
  const vtkIdType ox = extent[1] - extent[0] + 1;
  const vtkIdType oy = extent[3] - extent[2] + 1;
  const int n = hi[0] - lo[0] + 1;
  const int nc = to.Components, size = to.ValueSize;
  for (int z = lo[2]; z <= hi[2]; ++z)
  {
    for (int y = lo[1]; y <= hi[1]; ++y)
    {
      const size_t pz = tiles ? static_cast<size_t>(to.Layer) : size_t(z - base[2]);
      const size_t src = ((pz * B + size_t(y - base[1])) * B + size_t(lo[0] - base[0]));
      const vtkIdType out =
        ((vtkIdType(z - extent[4]) * oy + (y - extent[2])) * ox + (lo[0] - extent[0]));
      if (nc == 1)
      {
        std::memcpy(to.Values + out * size, page + src * size, size_t(n) * size);
        continue;
      }
      for (int i = 0; i < n; ++i)
        std::memcpy(
          to.Values + ((out + i) * nc + to.Component) * size, page + (src + i) * size, size);
    }
  }
}
}

namespace strata
{
//------------------------------------------------------------------------------
bool PagePoolSet::Open(const std::string& name, std::string& error)
{
  this->Files.clear();
  std::shared_ptr<strata::PagePoolFile> first = strata::PagePoolFile::OpenShared(name, error);
  if (!first)
    return false;
  const Format::Header& h = first->GetHeader();
  if (h.Component != 0)
  {
    error = "the file is component " + std::to_string(h.Component) + " of a set of " +
            std::to_string(h.Components) + ": open its component 0 (the name without \".c" +
            std::to_string(h.Component) + "\")";
    return false;
  }
  std::vector<std::shared_ptr<strata::PagePoolFile>> files{ first };
  for (int c = 1; c < h.Components; ++c)
  {
    files.push_back(strata::PagePoolFile::OpenSharedComponent(*first, c, error));
    if (!files.back())
      return false;
  }
  this->Files = std::move(files);
  return true;
}

//------------------------------------------------------------------------------
bool PagePoolSet::IsTilePool() const
{
  return this->IsOpen() && this->GetFile().GetKind() == Format::Kind::TilePool;
}

//------------------------------------------------------------------------------
int PagePoolSet::GetVTKScalarType() const
{
  return this->IsOpen() ? ToVTKType(this->GetFile().GetScalarType()) : VTK_VOID;
}

//------------------------------------------------------------------------------
bool PagePoolSet::LevelExtent(int level,
  const int updateExtent[6],
  int extent[6],
  double spacing[3]) const
{
  const strata::PagePoolFile& file = this->GetFile();
  const Format::Header& h = file.GetHeader();
  const Format::Level& lv = file.GetLevel(level);
  const int axes = this->IsTilePool() ? 2 : 3;
  for (int a = 0; a < 3; ++a)
  {
    const int n0 = a < axes ? h.Dimensions[a] : 1;
    const int nl = a < axes ? lv.Dimensions[a] : 1;
    const int lo = std::max(updateExtent[2 * a], 0);
    const int hi = std::min(updateExtent[2 * a + 1], n0 - 1);
    if (lo > hi)
      return false;
    spacing[a] = h.Spacing[a];
    extent[2 * a] = extent[2 * a + 1] = 0;
    if (nl > 1)
    {
      const double ratio = static_cast<double>(n0 - 1) / (nl - 1);
      spacing[a] = h.Spacing[a] * ratio;
      // The 1e-9 guards floor/ceil of exact quotients against rounding.
      extent[2 * a] = std::max(0, static_cast<int>(std::floor(lo / ratio + 1e-9)));
      extent[2 * a + 1] = std::min(nl - 1, static_cast<int>(std::ceil(hi / ratio - 1e-9)));
    }
  }
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> PagePoolSet::ReadImage(int level,
  const int updateExtent[6],
  Read& read,
  std::string& error) const
{
  read.PagesRead = 0;
  int extent[6];
  double spacing[3];
  if (!this->LevelExtent(level, updateExtent, extent, spacing))
    return vtkSmartPointer<vtkImageData>::New(); // an empty request: an empty image, no error
  return this->ReadLevelImage(level, extent, read, error);
}

//------------------------------------------------------------------------------
void PagePoolSet::GetLevelGeometry(int level, int extent[6], double spacing[3]) const
{
  const Format::Header& h = this->GetFile().GetHeader();
  const int whole[6] = {
    0, h.Dimensions[0] - 1, 0, h.Dimensions[1] - 1, 0, this->IsTilePool() ? 0 : h.Dimensions[2] - 1
  };
  this->LevelExtent(level, whole, extent, spacing);
}

//------------------------------------------------------------------------------
void PagePoolSet::LevelToFinest(int level, const int extent[6], int finest[6]) const
{
  const Format::Header& h = this->GetFile().GetHeader();
  const Format::Level& lv = this->GetFile().GetLevel(level);
  const int axes = this->IsTilePool() ? 2 : 3;
  for (int a = 0; a < 3; ++a)
  {
    const int n0 = a < axes ? h.Dimensions[a] : 1;
    const int nl = a < axes ? lv.Dimensions[a] : 1;
    const double ratio = nl > 1 ? static_cast<double>(n0 - 1) / (nl - 1) : 1.0;
    // The 1e-9 guards floor/ceil of exact products against rounding.
    finest[2 * a] = std::max(0, static_cast<int>(std::floor(extent[2 * a] * ratio + 1e-9)));
    finest[2 * a + 1] =
      std::min(n0 - 1, static_cast<int>(std::ceil(extent[2 * a + 1] * ratio - 1e-9)));
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> PagePoolSet::ReadLevelImage(int level,
  const int levelExtent[6],
  Read& read,
  std::string& error) const
{
  read.PagesRead = 0;
  const Format::Header& h = this->GetFile().GetHeader();
  const int layers = this->IsTilePool() ? h.Dimensions[2] : 1;
  if (this->IsTilePool() && (read.Layer < 0 || read.Layer >= layers))
  {
    error = "layer " + std::to_string(read.Layer) + " out of range [0, " +
            std::to_string(layers - 1) + "]";
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  int whole[6], extent[6];
  double spacing[3];
  this->GetLevelGeometry(level, whole, spacing);
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = std::max(levelExtent[2 * a], whole[2 * a]);
    extent[2 * a + 1] = std::min(levelExtent[2 * a + 1], whole[2 * a + 1]);
    if (extent[2 * a] > extent[2 * a + 1])
      return image; // an empty request: an empty image, and no error
  }
  const int nc = this->GetNumberOfComponents();
  double megabytes = double(nc) * Format::GetScalarSize(h.Type) / 1048576.0;
  for (int a = 0; a < 3; ++a)
    megabytes *= extent[2 * a + 1] - extent[2 * a] + 1;
  if (read.MemoryLimitMB > 0.0 && megabytes > read.MemoryLimitMB)
  {
    std::ostringstream msg;
    msg << "level " << level << ", extent " << extent[0] << " " << extent[1] << " " << extent[2]
        << " " << extent[3] << " " << extent[4] << " " << extent[5] << ", needs " << megabytes
        << " MB of " << Format::GetScalarTypeName(h.Type) << " values, more than the "
        << read.LimitName << " of " << read.MemoryLimitMB << " MB" << read.LimitAdvice;
    error = msg.str();
    return nullptr;
  }
  image->SetExtent(extent);
  image->SetSpacing(spacing);
  image->SetOrigin(h.Origin);
  image->SetDirectionMatrix(h.Direction);
  image->AllocateScalars(this->GetVTKScalarType(), nc);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = "cannot allocate " + std::to_string(megabytes) + " MB for the image";
    return nullptr;
  }
  scalars->SetName(read.ArrayName.c_str());
  if (!this->ReadPages(level, extent, read, scalars->GetVoidPointer(0), error))
    return nullptr;
  return image;
}

//------------------------------------------------------------------------------
bool PagePoolSet::ReadPages(int level,
  const int extent[6],
  Read& read,
  void* dst,
  std::string& error) const
{
  const strata::PagePoolFile& file = this->GetFile();
  const Format::Level& lv = file.GetLevel(level);
  const int axes = this->IsTilePool() ? 2 : 3;
  const int B = file.GetPageSize();
  int p0[3] = { 0, 0, 0 }, p1[3] = { 0, 0, 0 };
  for (int a = 0; a < axes; ++a)
  {
    p0[a] = PageOf(extent[2 * a], B - 1, lv.Pages[a]);
    p1[a] = PageOf(extent[2 * a + 1], B - 1, lv.Pages[a]);
  }
  const int nc = this->GetNumberOfComponents();
  const double total = double(p1[0] - p0[0] + 1) * (p1[1] - p0[1] + 1) * (p1[2] - p0[2] + 1) * nc;
  Destination to{ extent,
    this->IsTilePool() ? read.Layer : -1,
    0,
    nc,
    Format::GetScalarSize(file.GetScalarType()),
    static_cast<unsigned char*>(dst) };
  std::vector<unsigned char> page(file.GetPageBytes());
  if (read.Progress)
    read.Progress(0.0);
  for (int pk = p0[2]; pk <= p1[2]; ++pk)
    for (int pj = p0[1]; pj <= p1[1]; ++pj)
      for (int pi = p0[0]; pi <= p1[0]; ++pi)
      {
        const uint64_t index =
          uint64_t(pi) + uint64_t(lv.Pages[0]) * (uint64_t(pj) + uint64_t(lv.Pages[1]) * pk);
        for (to.Component = 0; to.Component < nc; ++to.Component)
        {
          if (!this->Files[to.Component]->ReadPageNative(level, index, page.data(), &error))
            return false;
          ++read.PagesRead;
          const int at[3] = { pi, pj, pk };
          CopyPage(page.data(), at, B, to);
          if (read.Progress)
            read.Progress(read.PagesRead / total);
        }
      }
  return true;
}
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkImageToPagePoolWriter and vtkPagePoolReader round trips:
// - a generated 70 x 50 x 41 uint16 volume (page size 16, so 4 levels and pages that do not
//   divide the dimensions), a generated 2-D float grid with NaN holes, Testing/Data's bucky.raw
//   (32^3 uint8, through vtkImageReader2, which streams) and the Reek .gri horizon (through
//   vtkIrapBinaryGridReader): full-resolution reads must equal the input bit for bit, geometry
//   included;
// - a sub-extent read must read exactly the pages overlapping it and give the input's values;
// - a coarse read (UPDATE_RESOLUTION 0.5 and 0) must give level 1 (n/2 + 1 points per axis) and
//   the coarsest level, with the same physical bounds as the full image;
// - the writer's progress events are non-decreasing and end at 1;
// - errors: a missing file, a corrupt page and an unwritable output are reported (counted by an
//   observer) and leave an empty output / no file.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "StrataPagePoolFile.h"
#include "StrataPagePoolSet.h"
#include "StrataPagedPools.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPagePoolProtocol.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedShortArray.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

void RecordProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData));
}

/// Converts `image` (or the output of `producer`) and checks progress and success.
bool Convert(vtkAlgorithm* producer, vtkImageData* image, const std::string& path, int pageSize)
{
  vtkNew<vtkImageToPagePoolWriter> writer;
  if (producer)
  {
    writer->SetInputConnection(producer->GetOutputPort());
  }
  else
  {
    writer->SetInputData(image);
  }
  writer->SetFileName(path.c_str());
  writer->SetPageSize(pageSize);
  writer->SetCompression(true);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(RecordProgress);
  cb->SetClientData(&progress);
  writer->AddObserver(vtkCommand::ProgressEvent, cb);
  const bool ok = writer->Write();
  Check(ok, "conversion to " + path + " succeeds");
  bool monotonic = true;
  for (size_t i = 1; i < progress.size(); ++i)
  {
    monotonic = monotonic && progress[i] >= progress[i - 1];
  }
  Check(progress.size() > 2 && monotonic && progress.back() == 1.0,
    "progress of " + path + " is non-decreasing and ends at 1");
  return ok;
}

/// Bit-exact equality of the scalars of `a` over the extent of `b` (b within a), and of the
/// geometry when `geometry`.
bool SameValues(vtkImageData* full, vtkImageData* part, bool geometry)
{
  vtkDataArray* fa = full->GetPointData()->GetScalars();
  vtkDataArray* pa = part->GetPointData()->GetScalars();
  if (!fa || !pa || fa->GetDataType() != pa->GetDataType() ||
      fa->GetNumberOfComponents() != pa->GetNumberOfComponents())
  {
    std::cerr << "  scalars missing or of different types or components\n";
    return false;
  }
  if (geometry)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (full->GetSpacing()[a] != part->GetSpacing()[a] ||
          std::fabs(full->GetOrigin()[a] - part->GetOrigin()[a]) > 1e-9)
      {
        std::cerr << "  geometry differs on axis " << a << "\n";
        return false;
      }
    }
    for (int i = 0; i < 9; ++i)
    {
      if (full->GetDirectionMatrix()->GetData()[i] != part->GetDirectionMatrix()->GetData()[i])
      {
        std::cerr << "  direction differs\n";
        return false;
      }
    }
  }
  const int size = fa->GetDataTypeSize() * fa->GetNumberOfComponents(); // a tuple
  int e[6];
  part->GetExtent(e);
  for (int k = e[4]; k <= e[5]; ++k)
    for (int j = e[2]; j <= e[3]; ++j)
      for (int i = e[0]; i <= e[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        const vtkIdType fi = full->ComputePointId(ijk);
        const vtkIdType pi = part->ComputePointId(ijk);
        if (std::memcmp(static_cast<char*>(fa->GetVoidPointer(0)) + fi * size,
              static_cast<char*>(pa->GetVoidPointer(0)) + pi * size,
              size) != 0)
        {
          std::cerr << "  value differs at (" << i << ", " << j << ", " << k << ")\n";
          return false;
        }
      }
  return true;
}

vtkSmartPointer<vtkImageData> Read(const std::string& path,
  const int* extent = nullptr,
  double resolution = -1,
  vtkPagePoolReader* keep = nullptr)
{
  vtkNew<vtkPagePoolReader> local;
  vtkPagePoolReader* reader = keep ? keep : local.Get();
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  if (resolution >= 0)
  {
    reader->GetOutputInformation(0)->Set(vtkPagePoolReader::UPDATE_RESOLUTION(), resolution);
  }
  else
  {
    reader->GetOutputInformation(0)->Remove(vtkPagePoolReader::UPDATE_RESOLUTION());
  }
  if (extent)
  {
    reader->UpdateExtent(extent);
  }
  else
  {
    reader->Update();
  }
  vtkNew<vtkImageData> copy;
  copy->DeepCopy(reader->GetOutput());
  return copy.Get();
}

int PageOf(int p, int stride, int pages)
{
  return std::min(p <= 0 ? 0 : (p - 1) / stride, pages - 1);
}

void RoundTrip(const std::string& what, vtkImageData* input, const std::string& path)
{
  vtkSmartPointer<vtkImageData> back = Read(path);
  int a[6], b[6];
  input->GetExtent(a);
  back->GetExtent(b);
  Check(std::equal(a, a + 6, b), what + ": extent preserved");
  Check(SameValues(input, back, true), what + ": full-resolution read is bit-exact");
}
}

namespace
{
void VolumeRoundTrip(vtkImageData* vol, const std::string& volPath)
{
  Convert(nullptr, vol, volPath, 16);
  RoundTrip("uint16 volume", vol, volPath);
}

void SubExtent(vtkImageData* vol, const std::string& volPath)
{
  // Sub-extent: only the overlapping pages.
  vtkNew<vtkPagePoolReader> reader;
  const int sub[6] = { 10, 33, 5, 12, 30, 40 };
  vtkSmartPointer<vtkImageData> part = Read(volPath, sub, 1.0, reader);
  int e[6];
  part->GetExtent(e);
  Check(std::equal(sub, sub + 6, e), "sub-extent read has the requested extent");
  Check(SameValues(vol, part, false), "sub-extent values are bit-exact");
  // Level 0 of 70 x 50 x 41 with B = 16 (stride 15): 5 x 4 x 3 pages.
  long expected = 1;
  const int pages[3] = { 5, 4, 3 };
  for (int a = 0; a < 3; ++a)
  {
    expected *= PageOf(sub[2 * a + 1], 15, pages[a]) - PageOf(sub[2 * a], 15, pages[a]) + 1;
  }
  std::cout << "sub-extent read " << reader->GetNumberOfPagesRead() << " pages (expected "
            << expected << " of 60 at level 0)\n";
  Check(reader->GetNumberOfPagesRead() == expected && expected < 60,
    "sub-extent reads only the overlapping pages");
}

void CoarseReads(vtkImageData* vol, const std::string& volPath)
{
  // Coarse reads: same physical region.
  for (double r : { 0.5, 0.0 })
  {
    vtkNew<vtkPagePoolReader> reader;
    vtkSmartPointer<vtkImageData> coarse = Read(volPath, nullptr, r, reader);
    int dims[3];
    coarse->GetDimensions(dims);
    double fb[6], cb[6];
    vol->GetBounds(fb);
    coarse->GetBounds(cb);
    bool sameBounds = true;
    for (int i = 0; i < 6; ++i)
    {
      sameBounds = sameBounds && std::fabs(fb[i] - cb[i]) < 1e-9;
    }
    std::cout << "resolution " << r << ": level " << reader->GetLevelRead() << ", " << dims[0]
              << " x " << dims[1] << " x " << dims[2] << ", spacing " << coarse->GetSpacing()[0]
              << " " << coarse->GetSpacing()[1] << " " << coarse->GetSpacing()[2] << ", "
              << reader->GetNumberOfPagesRead() << " pages\n";
    if (r == 0.5)
    {
      Check(reader->GetLevelRead() == 1 && dims[0] == 36 && dims[1] == 26 && dims[2] == 21,
        "resolution 0.5 reads level 1 (n/2 + 1 points)");
      Check(coarse->GetSpacing()[0] == 0.5 * 69 / 35, "level-1 spacing covers the same span");
    }
    else
    {
      Check(reader->GetLevelRead() == reader->GetNumberOfLevels() - 1 &&
              reader->GetNumberOfPagesRead() == 1,
        "resolution 0 reads the single root page");
    }
    Check(sameBounds, "coarse read covers the same physical bounds");
    // The pool travels with the data through copies (what ParaView hands a representation).
    vtkNew<vtkImageData> copy;
    copy->ShallowCopy(coarse);
    const vtkPagePoolProtocol::Identity pool = vtkPagePoolProtocol::GetIdentity(copy);
    Check(pool.FileName == volPath && pool.Layer == 0,
      "a shallow copy of the output names its pool (field data)");
    Check(vtkPagePoolProtocol::IsPagePool(reader->GetOutputInformation(0)),
      "the reader marks its output a page pool (PAGE_POOL)");
  }
  Check(!vtkPagePoolProtocol::GetIdentity(vol).IsValid() &&
          !vtkPagePoolProtocol::GetIdentity(nullptr).IsValid(),
    "an image not read from a pool names none");
}

/// The reader declares the level Resolution selects (whole extent, spacing), outputs exactly
/// that, and reads a sub-extent given in that level's indices: what ParaView's filters see.
void DeclaredLevel(const std::string& volPath)
{
  for (double r : { 0.5, 0.0 })
  {
    vtkNew<vtkPagePoolReader> reader;
    reader->SetFileName(volPath.c_str());
    reader->SetResolution(r);
    reader->UpdateInformation();
    vtkInformation* info = reader->GetOutputInformation(0);
    int whole[6];
    double spacing[3];
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    info->Get(vtkDataObject::SPACING(), spacing);
    reader->Update();
    vtkNew<vtkImageData> level;
    level->DeepCopy(reader->GetOutput());
    int e[6];
    level->GetExtent(e);
    std::cout << "resolution " << r << " declares " << whole[1] << " x " << whole[3] << " x "
              << whole[5] << " spacing " << spacing[0] << ", outputs " << e[1] << " x " << e[3]
              << " x " << e[5] << " spacing " << level->GetSpacing()[0] << "\n";
    bool same = true;
    for (int i = 0; i < 6; ++i)
    {
      same = same && whole[i] == e[i];
    }
    for (int a = 0; a < 3; ++a)
    {
      same = same && spacing[a] == level->GetSpacing()[a];
    }
    Check(same, "the declared whole extent and spacing are the output's");
    Check(r != 0.5 || (whole[1] == 35 && whole[3] == 25 && whole[5] == 20),
      "resolution 0.5 declares level 1 (n/2 + 1 points)");
    Check(r != 0.0 || reader->GetLevelRead() == reader->GetNumberOfLevels() - 1,
      "resolution 0 declares and reads the coarsest level");
    // A sub-extent in the declared level's indices: those points, those values.
    int sub[6] = { whole[1] / 4, whole[1] / 2, 1, whole[3] - 1, whole[5] / 3, whole[5] };
    reader->UpdateExtent(sub);
    vtkImageData* part = reader->GetOutput();
    part->GetExtent(e);
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      inside = inside && e[2 * a] <= sub[2 * a] && e[2 * a + 1] >= sub[2 * a + 1] &&
               e[2 * a] >= whole[2 * a] && e[2 * a + 1] <= whole[2 * a + 1];
    }
    Check(inside && SameValues(level, part, true),
      "a sub-extent in level indices reads that level's points");
  }
}

void FloatGrid(const std::string& out)
{
  // ---- Generated 2-D float grid with NaN holes -> tile pool. ----
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(61, 45, 1);
  grid->SetSpacing(25, 12.5, 1);
  grid->SetOrigin(456000, 6780000, 0);
  grid->AllocateScalars(VTK_FLOAT, 1);
  auto* p = static_cast<float*>(grid->GetScalarPointer());
  for (int j = 0; j < 45; ++j)
    for (int i = 0; i < 61; ++i)
    {
      const bool hole = (i - 30) * (i - 30) + (j - 20) * (j - 20) < 49 || (i + j) % 17 == 0;
      p[j * 61 + i] =
        hole ? std::numeric_limits<float>::quiet_NaN() : 1500.0f + 3.7f * std::sin(0.1f * i) * j;
    }
  const std::string path = out + "/grid.spp";
  Convert(nullptr, grid, path, 8);
  RoundTrip("float grid with holes", grid, path);
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  Check(reader->GetIsTilePool() && reader->GetNumberOfLayers() == 1, "2-D input gives a tile pool");
}

void Bucky(const std::string& out, const strata_test::TestPaths& paths)
{
  // ---- bucky.raw (32^3 uint8) through a streaming vtkImageReader2. ----
  const std::string raw = paths.Data + "/volumes/bucky.raw";
  vtkNew<vtkImageReader2> rr;
  rr->SetFileName(raw.c_str());
  rr->SetFileDimensionality(3);
  rr->SetDataExtent(0, 31, 0, 31, 0, 31);
  rr->SetDataScalarTypeToUnsignedChar();
  const std::string path = out + "/bucky.spp";
  Convert(rr, nullptr, path, 8);
  rr->UpdateWholeExtent();
  RoundTrip("bucky.raw", rr->GetOutput(), path);
}

void Reek(const std::string& out, const strata_test::TestPaths& paths)
{
  // ---- Reek horizon (rotated Irap grid) -> tile pool. ----
  vtkNew<vtkIrapBinaryGridReader> gr;
  gr->SetFileName((paths.Data + "/horizons/reek_01_topreek_rota.gri").c_str());
  const std::string path = out + "/reek.spp";
  Convert(gr, nullptr, path, 32);
  gr->Update();
  RoundTrip("reek_01_topreek_rota.gri", gr->GetOutput(), path);
}

// A set of component pools (strata::PagePoolFormat, Components): written from a streaming reader of
// a raw 4-component file (one pass per component), read back whole and in part bit-exact; a
// missing, foreign or wrongly named component is an error, never a volume of fewer components.
void Components(const std::string& out)
{
  const int dims[3] = { 40, 30, 21 };
  const vtkIdType n = vtkIdType(dims[0]) * dims[1] * dims[2];
  vtkNew<vtkImageData> vol;
  vol->SetDimensions(dims);
  vol->SetSpacing(0.5, 1.0, 2.0);
  vol->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  auto* v = static_cast<unsigned char*>(vol->GetScalarPointer());
  for (vtkIdType i = 0; i < 4 * n; ++i)
    v[i] = static_cast<unsigned char>((i * 2654435761u) >> 24);
  const std::string raw = out + "/rgba.raw";
  {
    std::ofstream f(raw, std::ios::binary);
    f.write(reinterpret_cast<const char*>(v), 4 * n);
  }
  vtkNew<vtkImageReader2> rr;
  rr->SetFileName(raw.c_str());
  rr->SetDataScalarTypeToUnsignedChar();
  rr->SetNumberOfScalarComponents(4);
  rr->FileLowerLeftOn();
  rr->SetFileDimensionality(3);
  rr->SetDataExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1);
  rr->SetDataSpacing(0.5, 1.0, 2.0);
  const std::string path = out + "/rgba.spp";
  Convert(rr, nullptr, path, 16);
  std::vector<strata::PagePoolFormat::Header> headers;
  for (int c = 0; c < 4; ++c)
  {
    strata::PagePoolFile f;
    const std::string name = strata::PagePoolFormat::GetComponentFileName(path, c);
    Check(f.Open(name) && f.GetHeader().Version == 2 && f.GetHeader().Components == 4 &&
            f.GetHeader().Component == c,
      "component " + std::to_string(c) + ": " + name + ", version 2, component " +
        std::to_string(c) + " of 4");
    headers.push_back(f.GetHeader());
  }
  Check(headers[3].ComponentsTag == headers[0].ComponentsTag, "one tag for the set");
  vtkNew<vtkPagePoolReader> reader;
  vtkSmartPointer<vtkImageData> back = Read(path, nullptr, -1, reader);
  vtkDataArray* scalars = back->GetPointData()->GetScalars();
  Check(scalars && scalars->GetNumberOfComponents() == 4, "read back with 4 components");
  Check(SameValues(vol, back, true), "4 components: full-resolution read is bit-exact");
  strata::PagePoolFile first;
  first.Open(path);
  Check(
    reader->GetNumberOfPagesRead() ==
      4 * int(first.GetLevel(0).Pages[0] * first.GetLevel(0).Pages[1] * first.GetLevel(0).Pages[2]),
    "each level-0 page read once per component (" + std::to_string(reader->GetNumberOfPagesRead()) +
      ")");
  const int sub[6] = { 3, 20, 16, 29, 0, 7 };
  Check(SameValues(vol, Read(path, sub), false), "4 components: a sub-extent is bit-exact");

  // Two components from data in memory.
  vtkNew<vtkImageData> two;
  two->SetDimensions(17, 9, 12);
  two->AllocateScalars(VTK_FLOAT, 2);
  auto* t = static_cast<float*>(two->GetScalarPointer());
  for (vtkIdType i = 0; i < 2 * 17 * 9 * 12; ++i)
    t[i] = std::sin(0.37f * i) * (i % 2 ? 100.f : 1.f);
  Convert(nullptr, two, out + "/two.spp", 8);
  RoundTrip("2 float components", two, out + "/two.spp");

  vtkNew<ErrorCounter> errors;
  auto readError = [&](const std::string& name, const std::string& what)
  {
    vtkNew<vtkPagePoolReader> r;
    errors->Reset();
    errors->Watch(r);
    r->SetFileName(name.c_str());
    r->Update();
    std::cout << what << ": \"" << errors->First << "\"\n";
    Check(errors->Errors > 0 && r->GetOutput()->GetNumberOfPoints() == 0,
      what + ": error and empty output");
    return errors->First;
  };
  const std::string c1 = strata::PagePoolFormat::GetComponentFileName(path, 1);
  Check(readError(c1, "component 1 opened").find("open its component 0") != std::string::npos,
    "naming component 1 says to open component 0");
  // A component of another write of the same structure.
  const std::string other = out + "/rgba-other.spp";
  Convert(rr, nullptr, other, 16);
  const std::string c2 = strata::PagePoolFormat::GetComponentFileName(path, 2);
  vtksys::SystemTools::CopyAFile(strata::PagePoolFormat::GetComponentFileName(other, 2), c2);
  Check(readError(path, "a foreign component").find("its tag") != std::string::npos,
    "a component of another write is refused");
  vtksys::SystemTools::RemoveFile(c2);
  Check(readError(path, "a missing component").find(".c2.spp") != std::string::npos,
    "a missing component is named");

  // Component 0 is written last; when it fails, the components written before are removed.
  const std::string blocked = out + "/blocked.spp";
  vtksys::SystemTools::MakeDirectory(blocked); // no file can take its name
  vtkNew<vtkImageToPagePoolWriter> writer;
  vtkNew<ErrorCounter> werrors;
  writer->AddObserver(vtkCommand::ErrorEvent, werrors);
  writer->SetInputData(vol);
  writer->SetPageSize(16);
  writer->SetFileName(blocked.c_str());
  const bool wrote = writer->Write();
  bool left = false;
  for (int c = 1; c < 4; ++c)
    left = left || vtksys::SystemTools::FileExists(
                     strata::PagePoolFormat::GetComponentFileName(blocked, c));
  std::cout << "component 0 unwritable: \"" << werrors->First << "\"\n";
  Check(!wrote && werrors->Errors > 0 && !left,
    "a set whose component 0 cannot be written: an error, and no component left behind");
}

void Errors(const std::string& out, vtkImageData* vol, const std::string& volPath)
{
  // ---- Errors. ----
  vtkNew<vtkPagePoolReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName((out + "/does-not-exist.spp").c_str());
  reader->Update();
  Check(errors->Errors > 0 && reader->GetOutput()->GetNumberOfPoints() == 0,
    "missing file: error and empty output");
  Check(!vtkPagePoolReader::CanReadFile((out + "/does-not-exist.spp").c_str()) &&
          vtkPagePoolReader::CanReadFile(volPath.c_str()),
    "CanReadFile");

  // Corrupt the first page of a copy: full reads fail, reads not touching it succeed.
  const std::string bad = out + "/corrupt.spp";
  vtksys::SystemTools::CopyAFile(volPath, bad);
  uint64_t offset = 0;
  {
    strata::PagePoolFile f;
    Check(f.Open(bad), "copy opens");
    offset = f.GetPageEntry(0).Offset;
  }
  {
    std::fstream f(bad, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(offset + 5));
    char c = 0x5a;
    f.write(&c, 1);
  }
  errors->Reset();
  reader->SetFileName(bad.c_str());
  reader->GetOutputInformation(0)->Remove(vtkPagePoolReader::UPDATE_RESOLUTION());
  reader->UpdateInformation();
  reader->UpdateWholeExtent();
  std::cout << "corrupt page: \"" << errors->First << "\"\n";
  Check(errors->Errors > 0 && reader->GetOutput()->GetNumberOfPoints() == 0,
    "corrupt page: error and empty output");
  errors->Reset();
  const int far[6] = { 50, 69, 40, 49, 30, 40 };
  vtkNew<vtkPagePoolReader> fresh;
  errors->Watch(fresh);
  fresh->SetFileName(bad.c_str());
  fresh->UpdateExtent(far);
  std::cout << "far read: " << errors->Errors << " errors (\"" << errors->First << "\"), "
            << fresh->GetOutput()->GetNumberOfPoints() << " points\n";
  Check(errors->Errors == 0 && fresh->GetOutput()->GetNumberOfPoints() > 0,
    "a read away from the corrupt page succeeds");

  // Unwritable output: error, no file.
  vtkNew<vtkImageToPagePoolWriter> writer;
  vtkNew<ErrorCounter> werrors;
  writer->AddObserver(vtkCommand::ErrorEvent, werrors);
  writer->SetInputData(vol);
  const std::string nowhere = out + "/no-such-dir/volume.spp";
  writer->SetFileName(nowhere.c_str());
  Check(!writer->Write() && werrors->Errors > 0 && !vtksys::SystemTools::FileExists(nowhere),
    "unwritable output: error, no file");
  std::cout << "unwritable: \"" << werrors->First << "\"\n";

  // Failing upstream: a raw reader on a missing file.
  vtkNew<vtkImageReader2> rr;
  vtkNew<ErrorCounter> rerrors;
  rerrors->Watch(rr);
  rr->SetFileName((out + "/missing.raw").c_str());
  rr->SetDataExtent(0, 9, 0, 9, 0, 9);
  writer->SetInputConnection(rr->GetOutputPort());
  const std::string target = out + "/from-missing.spp";
  vtksys::SystemTools::RemoveFile(target); // a stale one from an earlier run
  writer->SetFileName(target.c_str());
  werrors->Reset();
  const bool wrote = writer->Write();
  std::cout << "failing upstream: wrote " << wrote << ", " << werrors->Errors
            << " writer errors (\"" << werrors->First << "\"), " << rerrors->Errors
            << " reader errors\n";
  Check(!wrote && werrors->Errors > 0 && !vtksys::SystemTools::FileExists(target),
    "failing upstream: error, no file");
}

}

/// A pool is opened once per process (strata::PagePoolFile::OpenShared): a reader's information
/// and data passes, a second reader, the pagers' pools and the picker's set share one open
/// file; a file replaced on disk is opened afresh, and the last holder's release closes it.
void OpenedOnce(vtkImageData* vol, const std::string& out)
{
  const std::string path = out + "/shared.spp";
  Convert(nullptr, vol, path, 16);
  const long long before = strata::PagePoolFile::GetNumberOfOpens();
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetResolution(0.0);
  reader->Update();
  vtkNew<vtkPagePoolReader> second;
  second->SetFileName(path.c_str());
  second->Update();
  strata::PagedPools pools;
  std::string error;
  std::shared_ptr<strata::PagePoolFile> paged = pools.OpenPool(0, path, error);
  strata::PagePoolSet set;
  Check(paged && set.Open(path, error) && &set.GetFile() == paged.get(),
    "the pager and a picker's set get the reader's file");
  const long long opens = strata::PagePoolFile::GetNumberOfOpens() - before;
  std::cout << "opened once: " << opens << " open(s) for two readers, a pager and a set\n";
  Check(opens == 1, "two readers, a pager and a set open the pool once");
  // Replaced on disk (a new file under the name): the next opener gets the new file.
  const std::string next = out + "/shared-next.spp";
  Convert(nullptr, vol, next, 16);
  Check(std::rename(next.c_str(), path.c_str()) == 0, "the pool replaced on disk");
  std::shared_ptr<strata::PagePoolFile> fresh = strata::PagePoolFile::OpenShared(path, error);
  Check(fresh && fresh != paged && strata::PagePoolFile::GetNumberOfOpens() - before == 2,
    "a pool replaced on disk is opened afresh, not served from the old descriptor");
}

int TestPagePoolReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string out = paths.Output + "/TestPagePoolReader";
  vtksys::SystemTools::MakeDirectory(out);

  // ---- Generated uint16 volume. ----
  vtkNew<vtkImageData> vol;
  vol->SetDimensions(70, 50, 41);
  vol->SetSpacing(0.5, 0.75, 2.0);
  vol->SetOrigin(10, -20, 300);
  vol->AllocateScalars(VTK_UNSIGNED_SHORT, 1);
  {
    auto* p = static_cast<unsigned short*>(vol->GetScalarPointer());
    for (vtkIdType n = 0; n < 70 * 50 * 41; ++n)
    {
      p[n] = static_cast<unsigned short>((n * 2654435761u) >> 16);
    }
  }
  const std::string volPath = out + "/volume.spp";
  return strata_test::RunSubTests(
    {
      { "VolumeRoundTrip", [&] { VolumeRoundTrip(vol, volPath); } },
      { "SubExtent", [&] { SubExtent(vol, volPath); } },
      { "CoarseReads", [&] { CoarseReads(vol, volPath); } },
      { "DeclaredLevel", [&] { DeclaredLevel(volPath); } },
      { "FloatGrid", [&] { FloatGrid(out); } },
      { "Bucky", [&] { Bucky(out, paths); } },
      { "Reek", [&] { Reek(out, paths); } },
      { "Components", [&] { Components(out); } },
      { "Errors", [&] { Errors(out, vol, volPath); } },
      { "OpenedOnce", [&] { OpenedOnce(vol, out); } },
    },
    strata_test::Failures);
}

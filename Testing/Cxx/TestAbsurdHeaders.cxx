// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Issue 14: absurd headers in every file format IO/ reads (dimensions whose product overflows,
// or that need far more memory than the file could fill) are errors that name the header
// field, raised before anything is allocated for the data: each case must report an error
// (through VTK's error mechanism, counted by an observer), leave the output without points, and
// grow the process's peak RSS by less than 64 MB (every case here claims gigabytes to
// exabytes). The files are a few hundred bytes, written here:
// - Irap binary .gri: nx = ny = 2^31 - 1 (product 2^62); 40000 x 50000 (2 x 10^9 nodes, 8 GB)
//   in a file of 4 values;
// - .npy: shape (2^40, 2^40), whose product wraps to 0 in 64 bits; (60000, 60000) float64;
// - whitespace columns: inline numbers 0, 1 and 2^31 (a grid of 2^31 + 1 x 1 nodes);
// - SEG-Y: 32000 samples per trace in the binary header of a file of 20 short traces;
// - MetaImage (vtkStreamingMetaImageReader): DimSize 2^31 - 1 three times (its byte count
//   overflows 64 bits), and DimSize 100000^3 over a raw file of 64 bytes;
// - hybrid .shv: a 160-byte file announcing 65536^3 low-resolution values (1 PB), and one
//   announcing 2^60 points;
// - page pool (vtkPagePoolReader): a valid 64^3 float pool read whole with a MemoryLimit of
//   0.5 MB: the 1 MB output it would need is refused, naming the limit and the level;
//   a coarser level that fits is read; the pool's header re-encoded (valid checksum) with
//   2^21 x 64 x 64 and with 2^20 x 2^20 x 2^20 voxels.
#include "StrataErrorCounter.h"
#include "StrataSegyTestFile.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "StrataPagePoolFormat.h"
#include "vtkAlgorithm.h"
#include "vtkFloatArray.h"
#include "vtkHorizonColumnReader.h"
#include "vtkHybridVolumeReader.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkNew.h"
#include "vtkNumpyGridReader.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkSegyVolumeReader.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingMetaImageReader.h"

#include <vtksys/SystemTools.hxx>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// Updates `reader` (its file already set); checks error, message field, no points, no growth.
void CheckRejected(vtkAlgorithm* reader, const std::string& what, const std::string& field)
{
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  const double before = strata_test::PeakRssMB();
  reader->Update();
  const double grown = strata_test::PeakRssMB() - before;
  vtkImageData* out = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  std::cout << what << ": " << errors->Errors << " error(s), peak RSS +" << grown
            << " MB: " << errors->First << "\n";
  Check(errors->Errors > 0, what + ": an error is reported");
  Check(
    errors->First.find(field) != std::string::npos, what + ": the message names \"" + field + "\"");
  Check(!out || out->GetNumberOfPoints() == 0, what + ": no points");
  Check(grown < 64.0, what + ": nothing allocated for the data (peak RSS + < 64 MB)");
}

//------------------------------------------------------------------------------
void PutBE32(std::string& s, uint32_t v)
{
  for (int b = 3; b >= 0; --b)
  {
    s += static_cast<char>((v >> (8 * b)) & 0xFF);
  }
}

void PutBEFloat(std::string& s, float f)
{
  uint32_t v;
  std::memcpy(&v, &f, 4);
  PutBE32(s, v);
}

/// An Irap binary header (three framed records) and `values` floats in one record.
std::string IrapBinary(int32_t nx, int32_t ny, int values)
{
  std::string s;
  PutBE32(s, 32);
  PutBE32(s, static_cast<uint32_t>(-996));
  PutBE32(s, static_cast<uint32_t>(ny));
  for (float f : { 0.0f, 100.0f, 0.0f, 100.0f, 25.0f, 25.0f })
  {
    PutBEFloat(s, f);
  }
  PutBE32(s, 32);
  PutBE32(s, 16);
  PutBE32(s, static_cast<uint32_t>(nx));
  for (float f : { 0.0f, 0.0f, 0.0f })
  {
    PutBEFloat(s, f);
  }
  PutBE32(s, 16);
  PutBE32(s, 28);
  for (int k = 0; k < 7; ++k)
  {
    PutBE32(s, 0);
  }
  PutBE32(s, 28);
  PutBE32(s, static_cast<uint32_t>(4 * values));
  for (int k = 0; k < values; ++k)
  {
    PutBEFloat(s, 1.0f);
  }
  PutBE32(s, static_cast<uint32_t>(4 * values));
  return s;
}

void IrapBinaryHeaders(const std::string& dir)
{
  Spit(dir + "/overflow.gri", IrapBinary(2147483647, 2147483647, 4));
  vtkNew<vtkIrapBinaryGridReader> a;
  a->SetFileName((dir + "/overflow.gri").c_str());
  CheckRejected(a, "Irap binary nx = ny = 2^31 - 1", "nx = 2147483647");
  Spit(dir + "/big.gri", IrapBinary(40000, 50000, 4));
  vtkNew<vtkIrapBinaryGridReader> b;
  b->SetFileName((dir + "/big.gri").c_str());
  CheckRejected(b, "Irap binary 40000 x 50000 in 4 values", "40000 x 50000");
}

//------------------------------------------------------------------------------
/// A .npy v1.0 header for `shape` of `descr` and `values` bytes of data.
std::string Npy(const std::string& descr, const std::string& shape, size_t dataBytes)
{
  std::string header =
    "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0)
  {
    header += ' ';
  }
  header += '\n';
  std::string s = "\x93NUMPY";
  s += '\x01';
  s += '\x00';
  s += static_cast<char>(header.size() & 0xFF);
  s += static_cast<char>(header.size() >> 8);
  return s + header + std::string(dataBytes, '\0');
}

void NumpyHeaders(const std::string& dir)
{
  Spit(dir + "/wrap.npy", Npy("<f4", "(1099511627776, 1099511627776)", 64));
  vtkNew<vtkNumpyGridReader> a;
  a->SetFileName((dir + "/wrap.npy").c_str());
  CheckRejected(a, ".npy shape (2^40, 2^40)", "shape");
  Spit(dir + "/big.npy", Npy("<f8", "(60000, 60000)", 64));
  vtkNew<vtkNumpyGridReader> b;
  b->SetFileName((dir + "/big.npy").c_str());
  CheckRejected(b, ".npy (60000, 60000) float64 in 64 bytes", "60000");
}

//------------------------------------------------------------------------------
void ColumnHeaders(const std::string& dir)
{
  Spit(dir + "/far.txt", "0 0 1.5\n1 0 2.5\n2147483648 0 3.5\n");
  vtkNew<vtkHorizonColumnReader> a;
  a->SetFileName((dir + "/far.txt").c_str());
  CheckRejected(a, "columns with inlines 0, 1 and 2^31", "2147483649 x 1");
}

//------------------------------------------------------------------------------
void SegyHeaders(const std::string& dir)
{
  strata_test::SegyTestFile segy;
  segy.Format = 5;
  std::string bytes = segy.Bytes();
  // Binary header bytes 3221-3222: samples per trace (signed 16 bits in segyio).
  strata_test::PutBigEndian(bytes, 3220, 32000, 2);
  Spit(dir + "/samples.sgy", bytes);
  vtkNew<vtkSegyVolumeReader> a;
  a->SetFileName((dir + "/samples.sgy").c_str());
  CheckRejected(a, "SEG-Y 32000 samples per trace in 20 short traces", "32000 samples");
}

//------------------------------------------------------------------------------
void MetaImageHeaders(const std::string& dir)
{
  Spit(dir + "/raw.raw", std::string(64, '\0'));
  Spit(dir + "/overflow.mhd",
    "ObjectType = Image\nNDims = 3\nDimSize = 2147483647 2147483647 2147483647\n"
    "ElementType = MET_FLOAT\nElementDataFile = raw.raw\n");
  vtkNew<vtkStreamingMetaImageReader> a;
  a->SetFileName((dir + "/overflow.mhd").c_str());
  CheckRejected(a, "MetaImage DimSize (2^31 - 1)^3", "DimSize");
  Spit(dir + "/big.mhd",
    "ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 100000\n"
    "ElementType = MET_UCHAR\nElementDataFile = raw.raw\n");
  vtkNew<vtkStreamingMetaImageReader> b;
  b->SetFileName((dir + "/big.mhd").c_str());
  CheckRejected(b, "MetaImage DimSize 100000^3 over 64 bytes", "1000000000000000 bytes");
}

//------------------------------------------------------------------------------
template<typename T>
void PutLE(std::string& s, size_t offset, T v)
{
  std::memcpy(&s[offset], &v, sizeof(T)); // the format is little-endian, as this machine
}

/// A version-1 hybrid header (strata::HybridVolumeFile's layout) for an n^3 volume at factor f
/// announcing `points` points, followed by `lowValues` floats.
std::string Hybrid(int n, int f, int low, uint64_t points, size_t lowValues)
{
  std::string s(160 + 4 * lowValues, '\0');
  std::memcpy(&s[0], "STRHYVOL", 8);
  PutLE<uint32_t>(s, 8, 1);
  PutLE<uint32_t>(s, 12, 160);
  for (int a = 0; a < 3; ++a)
  {
    PutLE<int32_t>(s, 16 + 4 * a, n);
    PutLE<int32_t>(s, 28 + 4 * a, f);
    PutLE<int32_t>(s, 40 + 4 * a, low);
    PutLE<int32_t>(s, 52 + 4 * a, 1);
    PutLE<double>(s, 64 + 8 * a, 1.0);
  }
  PutLE<uint32_t>(s, 116, 16);
  PutLE<uint64_t>(s, 144, points);
  return s;
}

void HybridHeaders(const std::string& dir)
{
  // 65536^3 at factor 1: 2^48 low-resolution floats (1 PB) announced by a 160-byte file.
  Spit(dir + "/huge.shv", Hybrid(65536, 1, 65536, 0, 0));
  vtkNew<vtkHybridVolumeReader> a;
  a->SetFileName((dir + "/huge.shv").c_str());
  CheckRejected(a,
    "hybrid 65536^3 low-resolution values in 160 bytes",
    "281474976710656 low-resolution values");
  // 16^3 at factor 2 (9^3 low values, present) with 2^60 points.
  Spit(dir + "/points.shv", Hybrid(16, 2, 9, uint64_t(1) << 60, 729));
  vtkNew<vtkHybridVolumeReader> b;
  b->SetFileName((dir + "/points.shv").c_str());
  CheckRejected(b, "hybrid with 2^60 points", "1152921504606846976 points");
}

//------------------------------------------------------------------------------
void PagePoolLimit(const std::string& dir)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(64, 64, 64);
  image->AllocateScalars(VTK_FLOAT, 1);
  auto* v = static_cast<float*>(image->GetScalarPointer());
  for (vtkIdType n = 0; n < 64 * 64 * 64; ++n)
  {
    v[n] = static_cast<float>(n % 1000);
  }
  const std::string pool = dir + "/limit.spp";
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(16);
  Check(writer->Write(), "the 64^3 pool is written");
  vtkNew<vtkPagePoolReader> whole;
  whole->SetFileName(pool.c_str());
  whole->SetMemoryLimit(0.5);
  CheckRejected(
    whole, "page pool level 0 (1 MB of output) under a 0.5 MB MemoryLimit", "MemoryLimit");
  vtkNew<vtkPagePoolReader> coarse;
  coarse->SetFileName(pool.c_str());
  coarse->SetMemoryLimit(0.5);
  coarse->SetResolution(0.25);
  vtkNew<ErrorCounter> errors;
  errors->Watch(coarse);
  coarse->Update();
  int dims[3];
  coarse->GetOutput()->GetDimensions(dims);
  std::cout << "page pool at resolution 0.25 under 0.5 MB: " << dims[0] << " x " << dims[1] << " x "
            << dims[2] << ", " << errors->Errors << " error(s)\n";
  Check(
    errors->Errors == 0 && dims[0] > 0 && dims[0] < 64, "a coarser level within the limit is read");

  // The same pool's header re-encoded (valid checksum) with absurd dimensions: 2^21 along x
  // (beyond the format's 2^20), and 2^20 on every axis (2^60 voxels: more than 2^31 pages of
  // 16^3).
  std::ifstream in(pool, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  using Format = strata::PagePoolFormat;
  Format::Header h;
  Format::DecodeHeader(reinterpret_cast<const unsigned char*>(bytes.data()), h);
  const int absurd[2][3] = { { 1 << 21, 64, 64 }, { 1 << 20, 1 << 20, 1 << 20 } };
  const char* field[2] = { "dimension 0 is 2097152", "more than 2^31 pages" };
  for (int c = 0; c < 2; ++c)
  {
    Format::Header bad = h;
    std::copy(absurd[c], absurd[c] + 3, bad.Dimensions);
    std::string copy = bytes;
    Format::EncodeHeader(bad, reinterpret_cast<unsigned char*>(&copy[0]));
    const std::string path = dir + "/absurd" + std::to_string(c) + ".spp";
    Spit(path, copy);
    vtkNew<vtkPagePoolReader> reader;
    reader->SetFileName(path.c_str());
    CheckRejected(reader,
      c ? "page pool header 2^20 x 2^20 x 2^20" : "page pool header 2^21 x 64 x 64",
      field[c]);
  }
}
}

int TestAbsurdHeaders(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dir = paths.Output + "/TestAbsurdHeaders";
  vtksys::SystemTools::MakeDirectory(dir);
  return strata_test::RunSubTests(
    {
      { "IrapBinary", [&] { IrapBinaryHeaders(dir); } },
      { "Numpy", [&] { NumpyHeaders(dir); } },
      { "Columns", [&] { ColumnHeaders(dir); } },
      { "Segy", [&] { SegyHeaders(dir); } },
      { "MetaImage", [&] { MetaImageHeaders(dir); } },
      { "Hybrid", [&] { HybridHeaders(dir); } },
      { "PagePool", [&] { PagePoolLimit(dir); } },
    },
    strata_test::Failures);
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkIrapBinaryGridReader against values obtained independently of it:
// - the four Reek horizons (Testing/Data/horizons/reek_0*.gri, equinor/xtgeo-testdata, LGPL-3),
//   checked against literal numbers determined once with `od -t x1` and python3's struct module
//   (see the comments at each number), and against this test's own minimal record walker, which
//   reads the whole file into memory and decodes it without sharing any code with the reader;
// - a synthetic grid written here with odd record lengths, holes of every kind and a rotation;
// - bad input: a missing file, a truncated copy, a garbage file, mismatched markers, absurd
//   dimensions. Each must raise an error (caught by an observer, so nothing prints) and leave the
//   output with no points.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>
#include <cstdint>
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

bool Near(double a, double b, double tol)
{
  return std::fabs(a - b) <= tol;
}

/// Bit-exact equality for floats, NaN equal to NaN.
bool Same(double a, double b)
{
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

// ---- The test's own Irap decoding: whole file in memory, no code shared with the reader. ----
uint32_t Word(const std::vector<unsigned char>& b, size_t at)
{
  return (uint32_t(b[at]) << 24) | (uint32_t(b[at + 1]) << 16) | (uint32_t(b[at + 2]) << 8) |
         uint32_t(b[at + 3]);
}
int32_t Int(const std::vector<unsigned char>& b, size_t at)
{
  return static_cast<int32_t>(Word(b, at));
}
float Float(const std::vector<unsigned char>& b, size_t at)
{
  const uint32_t u = Word(b, at);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

struct Grid
{
  int NX = 0, NY = 0;
  double XMin = 0, XMax = 0, YMin = 0, YMax = 0, XInc = 0, YInc = 0, Rot = 0, XOri = 0, YOri = 0;
  std::vector<float> Values; // raw file values, x fastest
};

std::vector<unsigned char> Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool DecodeIrap(const std::vector<unsigned char>& b, Grid& g)
{
  std::vector<size_t> start; // payload offsets
  std::vector<size_t> length;
  size_t at = 0;
  while (at + 8 <= b.size())
  {
    const size_t n = static_cast<size_t>(Int(b, at));
    if (at + 8 + n > b.size() || Int(b, at + 4 + n) != static_cast<int32_t>(n))
    {
      return false;
    }
    start.push_back(at + 4);
    length.push_back(n);
    at += 8 + n;
  }
  if (start.size() < 4 || Int(b, start[0]) != -996)
  {
    return false;
  }
  g.NY = Int(b, start[0] + 4);
  g.XMin = Float(b, start[0] + 8);
  g.XMax = Float(b, start[0] + 12);
  g.YMin = Float(b, start[0] + 16);
  g.YMax = Float(b, start[0] + 20);
  g.XInc = Float(b, start[0] + 24);
  g.YInc = Float(b, start[0] + 28);
  g.NX = Int(b, start[1]);
  g.Rot = Float(b, start[1] + 4);
  g.XOri = Float(b, start[1] + 8);
  g.YOri = Float(b, start[1] + 12);
  for (size_t r = 3; r < start.size(); ++r)
  {
    for (size_t k = 0; k < length[r]; k += 4)
    {
      g.Values.push_back(Float(b, start[r] + k));
    }
  }
  return static_cast<long long>(g.Values.size()) == static_cast<long long>(g.NX) * g.NY;
}

// ---- Writing synthetic files ----
void PutWord(std::vector<unsigned char>& b, uint32_t u)
{
  b.push_back(static_cast<unsigned char>(u >> 24));
  b.push_back(static_cast<unsigned char>(u >> 16));
  b.push_back(static_cast<unsigned char>(u >> 8));
  b.push_back(static_cast<unsigned char>(u));
}
void PutInt(std::vector<unsigned char>& b, int32_t v)
{
  PutWord(b, static_cast<uint32_t>(v));
}
void PutFloat(std::vector<unsigned char>& b, float f)
{
  uint32_t u;
  std::memcpy(&u, &f, 4);
  PutWord(b, u);
}

/// A Fortran record: marker, payload, marker.
void PutRecord(std::vector<unsigned char>& b, const std::vector<unsigned char>& payload)
{
  PutInt(b, static_cast<int32_t>(payload.size()));
  b.insert(b.end(), payload.begin(), payload.end());
  PutInt(b, static_cast<int32_t>(payload.size()));
}

std::vector<unsigned char>
IrapHeaderBytes(int nx, int ny, float xori, float yori, float xinc, float yinc, float rotation)
{
  std::vector<unsigned char> b, r1, r2, r3;
  PutInt(r1, -996);
  PutInt(r1, ny);
  for (float f : { xori, xori + (nx - 1) * xinc, yori, yori + (ny - 1) * yinc, xinc, yinc })
  {
    PutFloat(r1, f);
  }
  PutInt(r2, nx);
  PutFloat(r2, rotation);
  PutFloat(r2, xori);
  PutFloat(r2, yori);
  for (int k = 0; k < 7; ++k)
  {
    PutInt(r3, 0);
  }
  PutRecord(b, r1);
  PutRecord(b, r2);
  PutRecord(b, r3);
  return b;
}

void Spit(const std::string& path, const std::vector<unsigned char>& b)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

float ValueAt(vtkImageData* image, int i, int j)
{
  int ijk[3] = { i, j, 0 };
  const vtkIdType id = image->ComputePointId(ijk);
  return static_cast<float>(image->GetPointData()->GetScalars()->GetComponent(id, 0));
}

/// Expects an error and an empty output from reading `path`.
void CheckBadInput(const std::string& path, const std::string& what)
{
  vtkNew<vtkIrapBinaryGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  Check(errors->Errors > 0, what + ": an error is reported");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0, what + ": output has no points");
  std::cout << what << ": " << errors->Errors << " error(s): " << errors->First << "\n";
}

// Literal values of the Reek files, per file. Determined once with
//   python3 -c "import struct; ..." (walking the records) and checked against
//   od -A d -t x1 -j OFFSET -N 4 FILE, with OFFSET = 100 + j*2224 + 4 + i*4 (three header records
//   of 32+8, 16+8 and 28+8 bytes, then one record of 554 floats = 2216+8 bytes per row j).
struct ReekExpectation
{
  const char* File;
  double At277_225; // bytes 44 ce 8c 93 in reek_01 at offset 501612
  double At402_2;   // first defined node in file order (index 1510)
  double At100_300;
  double Min;
  double Max;
};
const ReekExpectation Reek[4] = {
  { "reek_01_topreek_rota.gri",
    1652.3929443359375,
    1909.22509765625,
    1723.978759765625,
    1547.1962890625,
    1933.3653564453125 },
  { "reek_02_midreek_rota.gri",
    1673.0201416015625,
    1930.156494140625,
    1745.8697509765625,
    1568.9903564453125,
    1953.7034912109375 },
  { "reek_03_lowreek_rota.gri",
    1687.65234375,
    1945.1339111328125,
    1761.7611083984375,
    1584.72900390625,
    1968.082275390625 },
  { "reek_04_basereek_rota.gri",
    1695.5601806640625,
    1953.9912109375,
    1770.6744384765625,
    1593.5062255859375,
    1976.0126953125 },
};
}

namespace
{
/// One Reek horizon against its expectation: geometry, values, holes, and every value against
/// the test's own decoding of the file.
void CheckReekHorizon(const ReekExpectation& e, const std::string& dataDir)
{
  const std::string path = dataDir + e.File;
  const std::string tag = std::string(e.File) + ": ";
  Check(vtkIrapBinaryGridReader::CanReadFile(path.c_str()), tag + "CanReadFile");
  vtkNew<vtkIrapBinaryGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  // Header literals: od -A d -t x1 -N 100 shows 00 00 00 20 | ff ff fc 1c (-996) 00 00 01 c3
  // (ny 451) 48 e4 f3 e4 ... and record 2 = 00 00 02 2a (nx 554) 43 0c 00 01 (140.0000153)
  // 48 e4 f3 e4 (468895.125) 4a b5 0e b3 (5932889.5); python3 struct.unpack('>f', ...) gives
  // the decimal values below. All four files share the grid.
  Check(reader->GetNX() == 554 && reader->GetNY() == 451, tag + "nx, ny = 554, 451");
  Check(
    reader->GetXOrigin() == 468895.125 && reader->GetYOrigin() == 5932889.5, tag + "xori, yori");
  Check(reader->GetXMin() == 468895.125 && reader->GetXMax() == 479955.125, tag + "xmin, xmax");
  Check(reader->GetYMin() == 5932889.5 && reader->GetYMax() == 5941889.5, tag + "ymin, ymax");
  Check(reader->GetXInc() == 20.0 && reader->GetYInc() == 20.0, tag + "xinc, yinc");
  Check(reader->GetRotation() == 140.00001525878906, tag + "rotation");
  reader->Update();
  Check(errors->Errors == 0 && errors->Warnings == 0, tag + "no errors or warnings");

  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(dims[0] == 554 && dims[1] == 451 && dims[2] == 1, tag + "dimensions 554 x 451 x 1");
  double* origin = image->GetOrigin();
  double* spacing = image->GetSpacing();
  Check(origin[0] == 468895.125 && origin[1] == 5932889.5 && origin[2] == 0.0, tag + "origin");
  Check(spacing[0] == 20.0 && spacing[1] == 20.0 && spacing[2] == 1.0, tag + "spacing");
  // Direction matrix: a rotation by 140.00001525878906 degrees counterclockwise about z.
  const double a = vtkMath::RadiansFromDegrees(140.00001525878906);
  const double expected[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
  vtkMatrix3x3* d = image->GetDirectionMatrix();
  bool directionOk = true;
  for (int k = 0; k < 9; ++k)
  {
    directionOk = directionOk && Near(d->GetData()[k], expected[k], 1e-12);
  }
  Check(directionOk, tag + "direction matrix = rotation by 140 degrees");
  // Node (1, 0) is one xinc from the origin along the rotated x axis; (0, 1) one yinc along y.
  double p[3];
  image->TransformIndexToPhysicalPoint(1, 0, 0, p);
  Check(Near(p[0], 468895.125 + 20 * std::cos(a), 1e-6) &&
          Near(p[1], 5932889.5 + 20 * std::sin(a), 1e-6),
    tag + "node (1, 0) in world coordinates");
  image->TransformIndexToPhysicalPoint(0, 1, 0, p);
  Check(Near(p[0], 468895.125 - 20 * std::sin(a), 1e-6) &&
          Near(p[1], 5932889.5 + 20 * std::cos(a), 1e-6),
    tag + "node (0, 1) in world coordinates");

  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  Check(scalars && vtkFloatArray::SafeDownCast(scalars) &&
          std::string(scalars->GetName() ? scalars->GetName() : "") == "depth",
    tag + "a float array named depth");
  if (!scalars || scalars->GetNumberOfTuples() != 554 * 451)
  {
    Check(false, tag + "554 * 451 values");
    return;
  }
  Check(std::isnan(ValueAt(image, 0, 0)), tag + "(0, 0) is a hole (1e30 in the file)");
  Check(std::isnan(ValueAt(image, 553, 450)), tag + "(553, 450) is a hole");
  Check(ValueAt(image, 277, 225) == static_cast<float>(e.At277_225), tag + "value at (277, 225)");
  Check(ValueAt(image, 402, 2) == static_cast<float>(e.At402_2), tag + "value at (402, 2)");
  Check(ValueAt(image, 100, 300) == static_cast<float>(e.At100_300), tag + "value at (100, 300)");
  // 71003 nodes >= 1e30 in every file (python3: sum(abs(v) >= 1e30 for v in values)).
  Check(reader->GetNumberOfNoDataValues() == 71003, tag + "71003 no-data nodes");
  double lo = std::numeric_limits<double>::max();
  double hi = -lo;
  vtkIdType nans = 0;
  for (vtkIdType k = 0; k < scalars->GetNumberOfTuples(); ++k)
  {
    const double v = scalars->GetComponent(k, 0);
    if (std::isnan(v))
    {
      ++nans;
      continue;
    }
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  Check(nans == 71003, tag + "71003 NaNs in the array");
  Check(lo == e.Min && hi == e.Max, tag + "value range");

  // Every value against the test's own decoding.
  Grid g;
  if (!DecodeIrap(Slurp(path), g))
  {
    Check(false, tag + "the test's own decoder reads the file");
    return;
  }
  Check(g.NX == reader->GetNX() && g.NY == reader->GetNY() && g.Rot == reader->GetRotation() &&
          g.XOri == reader->GetXOrigin() && g.YOri == reader->GetYOrigin() &&
          g.XInc == reader->GetXInc() && g.YInc == reader->GetYInc() &&
          g.XMin == reader->GetXMin() && g.XMax == reader->GetXMax() &&
          g.YMin == reader->GetYMin() && g.YMax == reader->GetYMax(),
    tag + "header equals the test's own decoding");
  vtkIdType mismatches = 0;
  for (size_t k = 0; k < g.Values.size(); ++k)
  {
    const float raw = g.Values[k];
    const double want = std::fabs(raw) >= 1e30f ? std::nan("") : raw;
    mismatches += Same(scalars->GetComponent(static_cast<vtkIdType>(k), 0), want) ? 0 : 1;
  }
  Check(mismatches == 0, tag + "all values equal the test's own decoding");
}

void ReekHorizons(const std::string& dataDir)
{
  // ---- The four Reek horizons ----
  for (const ReekExpectation& e : Reek)
  {
    CheckReekHorizon(e, dataDir);
  }
}

void SyntheticGrid(const std::string& outDir)
{
  // ---- A synthetic grid: odd record lengths, every kind of hole, 30 degrees rotation ----
  const int nx = 5;
  const int ny = 3;
  std::vector<float> values(nx * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      values[i + j * nx] = 1000.0f + 10.0f * j + i;
    }
  }
  values[1] = 1e30f;      // RMS/xtgeo hole
  values[7] = -3e31f;     // any magnitude >= 1e30
  values[8] = 9999900.0f; // Irap's nominal hole
  values[12] = -999.25f;  // a NullValue set on the reader
  std::vector<unsigned char> b = IrapHeaderBytes(nx, ny, 100.0f, 200.0f, 12.5f, 25.0f, 30.0f);
  // Records of 4, 0, 7 and 4 values: nothing aligns with rows.
  size_t at = 0;
  for (size_t count : { 4, 0, 7, 4 })
  {
    std::vector<unsigned char> payload;
    for (size_t k = 0; k < count; ++k)
    {
      PutFloat(payload, values[at + k]);
    }
    PutRecord(b, payload);
    at += count;
  }
  const std::string path = outDir + "TestIrapBinaryGridReader_synthetic.gri";
  Spit(path, b);

  vtkNew<vtkIrapBinaryGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetNullValue(-999.25);
  reader->SetArrayName("twt");
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(errors->Errors == 0, "synthetic: no errors");
  Check(dims[0] == nx && dims[1] == ny && dims[2] == 1, "synthetic: dimensions 5 x 3 x 1");
  Check(reader->GetRotation() == 30.0 && reader->GetXInc() == 12.5 && reader->GetYInc() == 25.0,
    "synthetic: header");
  Check(reader->GetNumberOfNoDataValues() == 4, "synthetic: 4 holes");
  vtkDataArray* s = image->GetPointData()->GetScalars();
  Check(s && std::string(s->GetName()) == "twt", "synthetic: array name twt");
  bool ok = s != nullptr;
  for (int k = 0; ok && k < nx * ny; ++k)
  {
    const bool hole = k == 1 || k == 7 || k == 8 || k == 12;
    ok = hole ? std::isnan(s->GetComponent(k, 0)) : s->GetComponent(k, 0) == values[k];
  }
  Check(ok, "synthetic: every value in place, x fastest");
  double p[3];
  image->TransformIndexToPhysicalPoint(4, 2, 0, p);
  const double a = vtkMath::RadiansFromDegrees(30.0);
  Check(Near(p[0], 100 + 4 * 12.5 * std::cos(a) - 2 * 25 * std::sin(a), 1e-9) &&
          Near(p[1], 200 + 4 * 12.5 * std::sin(a) + 2 * 25 * std::cos(a), 1e-9),
    "synthetic: node (4, 2) in world coordinates");

  // Without NullValue, -999.25 is a value.
  reader->SetNullValue(std::nan(""));
  reader->Update();
  Check(reader->GetNumberOfNoDataValues() == 3 &&
          reader->GetOutput()->GetPointData()->GetScalars()->GetComponent(12, 0) == -999.25,
    "synthetic: NullValue NaN means none");

  // The same reader, now on a broken file, must end up empty.
  std::vector<unsigned char> broken = b;
  broken[broken.size() - 1] ^= 0x04; // last trailing marker 16 -> 20
  const std::string brokenPath = outDir + "TestIrapBinaryGridReader_badmarker.gri";
  Spit(brokenPath, broken);
  reader->SetFileName(brokenPath.c_str());
  errors->Reset();
  reader->Update();
  Check(errors->Errors > 0, "mismatched trailing marker: error reported");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0,
    "mismatched trailing marker: previous output cleared");
  std::cout << "mismatched marker: " << errors->First << "\n";

  // A failure in the information pass (truncated header), then a good file again: the reader
  // recovers.
  std::vector<unsigned char> stub(b.begin(), b.begin() + 60);
  Spit(outDir + "TestIrapBinaryGridReader_stub.gri", stub);
  reader->SetFileName((outDir + "TestIrapBinaryGridReader_stub.gri").c_str());
  errors->Reset();
  reader->Update();
  Check(errors->Errors > 0 && reader->GetOutput()->GetNumberOfPoints() == 0 && reader->GetNX() == 0,
    "truncated header after a good read: error, empty output, header reset");
  reader->SetFileName(path.c_str());
  errors->Reset();
  reader->Update();
  Check(errors->Errors == 0 && reader->GetOutput()->GetNumberOfPoints() == nx * ny,
    "a good file after a bad one reads again");

  // A record that claims more values than the grid has left.
  std::vector<unsigned char> tooLong = IrapHeaderBytes(2, 2, 0, 0, 1, 1, 0);
  std::vector<unsigned char> five;
  for (int k = 0; k < 5; ++k)
  {
    PutFloat(five, 1.0f);
  }
  PutRecord(tooLong, five);
  Spit(outDir + "TestIrapBinaryGridReader_toolong.gri", tooLong);
  CheckBadInput(outDir + "TestIrapBinaryGridReader_toolong.gri", "record longer than the grid");
}

void BadInput(const std::string& dataDir, const std::string& outDir)
{
  // ---- Bad input ----
  CheckBadInput(outDir + "TestIrapBinaryGridReader_does_not_exist.gri", "missing file");
  {
    std::vector<unsigned char> reek = Slurp(dataDir + Reek[0].File);
    reek.resize(500000);
    Spit(outDir + "TestIrapBinaryGridReader_truncated.gri", reek);
    CheckBadInput(outDir + "TestIrapBinaryGridReader_truncated.gri", "truncated copy");
    reek.resize(60); // inside the header
    Spit(outDir + "TestIrapBinaryGridReader_truncated_header.gri", reek);
    CheckBadInput(outDir + "TestIrapBinaryGridReader_truncated_header.gri", "truncated header");
  }
  {
    std::string garbage = "This is not an Irap grid, just some text that happens to be here.\n";
    for (int k = 0; k < 6; ++k)
    {
      garbage += garbage;
    }
    Spit(outDir + "TestIrapBinaryGridReader_garbage.gri",
      std::vector<unsigned char>(garbage.begin(), garbage.end()));
    CheckBadInput(outDir + "TestIrapBinaryGridReader_garbage.gri", "garbage file");
    Check(!vtkIrapBinaryGridReader::CanReadFile(
            (outDir + "TestIrapBinaryGridReader_garbage.gri").c_str()),
      "CanReadFile rejects garbage");
  }
  {
    // Absurd dimensions: 100000 x 100000 nodes (> 2^31), and a negative nx.
    std::vector<unsigned char> b = IrapHeaderBytes(100000, 100000, 0, 0, 1, 1, 0);
    Spit(outDir + "TestIrapBinaryGridReader_huge.gri", b);
    CheckBadInput(outDir + "TestIrapBinaryGridReader_huge.gri", "nx * ny > 2^31");
    b = IrapHeaderBytes(-5, 3, 0, 0, 1, 1, 0);
    Spit(outDir + "TestIrapBinaryGridReader_negative.gri", b);
    CheckBadInput(outDir + "TestIrapBinaryGridReader_negative.gri", "negative nx");
    // A wrong magic number in an otherwise fine header.
    b = IrapHeaderBytes(2, 2, 0, 0, 1, 1, 0);
    b[7] = 0x1d; // -996 -> -995
    Spit(outDir + "TestIrapBinaryGridReader_magic.gri", b);
    CheckBadInput(outDir + "TestIrapBinaryGridReader_magic.gri", "wrong -996 id");
  }
}

void PrintSelf()
{
  vtkNew<vtkIrapBinaryGridReader> printed;
  printed->Print(std::cout);
}

}

int TestIrapBinaryGridReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dataDir = paths.Data + "/horizons/";
  const std::string outDir = paths.Output + "/";
  strata_test::RunSubTests(
    {
      { "ReekHorizons", [&] { ReekHorizons(dataDir); } },
      { "SyntheticGrid", [&] { SyntheticGrid(outDir); } },
      { "BadInput", [&] { BadInput(dataDir, outDir); } },
      { "PrintSelf", PrintSelf },
    },
    strata_test::Failures);

  if (strata_test::Failures())
  {
    std::cerr << strata_test::Failures() << " check(s) failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}

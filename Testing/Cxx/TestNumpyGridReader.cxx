// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkNumpyGridReader against values obtained independently of it:
// - Testing/Data/horizons/penobscot_seabed_crop.npy (rows 0-63, columns 64-111 of the Penobscot
//   seabed horizon, SEG tutorials 2016, Apache-2.0 / CC BY-SA): literal header fields and values
//   determined once with python3's struct module and checked with `od -A d -t f8 -j OFFSET -N 8`
//   (OFFSET = 128 + 8 * (row * 48 + col), the header being 128 bytes);
// - the full 601 x 481 file from the shared data (--shared-data) when present (skipped otherwise);
// - synthetic files written here: every supported dtype in both byte orders, C and Fortran order,
//   format versions 1.0, 2.0 and 3.0, 1-D and (rows, cols, 1) shapes, the axis-swap flag;
// - bad input: missing, truncated, garbage, bad magic, unsupported version, dtype and shape,
//   malformed header, absurd dimensions. Each must raise an error (caught by an observer) and
//   leave the output with no points.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkNumpyGridReader.h"
#include "vtkPointData.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

double ValueAt(vtkImageData* image, int i, int j)
{
  int ijk[3] = { i, j, 0 };
  return image->GetPointData()->GetScalars()->GetComponent(image->ComputePointId(ijk), 0);
}

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// A .npy file as numpy writes it: magic, version, little-endian header length, the dict padded
/// with spaces and a newline to a multiple of 64 bytes, then the data.
std::string Npy(int major, const std::string& dict, const std::string& data)
{
  const size_t preamble = major == 1 ? 10 : 12;
  std::string header = dict;
  while ((preamble + header.size() + 1) % 64 != 0)
  {
    header += ' ';
  }
  header += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(major);
  out += '\0';
  const uint32_t n = static_cast<uint32_t>(header.size());
  out += static_cast<char>(n & 0xff);
  out += static_cast<char>((n >> 8) & 0xff);
  if (major != 1)
  {
    out += static_cast<char>((n >> 16) & 0xff);
    out += static_cast<char>((n >> 24) & 0xff);
  }
  return out + header + data;
}

/// One element of dtype `descr` holding `v`, bytes in the descr's order.
std::string Encode(double v, const std::string& descr)
{
  const char kind = descr[1];
  const int size = std::stoi(descr.substr(2));
  unsigned char b[8] = { 0 };
  auto put = [&](const void* src) { std::memcpy(b, src, static_cast<size_t>(size)); };
  if (kind == 'f' && size == 4)
  {
    const float f = static_cast<float>(v);
    put(&f);
  }
  else if (kind == 'f')
  {
    put(&v);
  }
  else if (kind == 'i')
  {
    const int64_t i = static_cast<int64_t>(v);
    const int8_t i1 = static_cast<int8_t>(i);
    const int16_t i2 = static_cast<int16_t>(i);
    const int32_t i4 = static_cast<int32_t>(i);
    put(size == 1   ? static_cast<const void*>(&i1)
        : size == 2 ? static_cast<const void*>(&i2)
        : size == 4 ? static_cast<const void*>(&i4)
                    : &i);
  }
  else
  {
    const uint64_t u = static_cast<uint64_t>(v);
    const uint8_t u1 = static_cast<uint8_t>(u);
    const uint16_t u2 = static_cast<uint16_t>(u);
    const uint32_t u4 = static_cast<uint32_t>(u);
    put(size == 1   ? static_cast<const void*>(&u1)
        : size == 2 ? static_cast<const void*>(&u2)
        : size == 4 ? static_cast<const void*>(&u4)
                    : &u);
  }
  // The test machine is little-endian (x86-64, aarch64); '>' files get reversed bytes.
  const uint16_t probe = 1;
  const bool hostLittle = *reinterpret_cast<const unsigned char*>(&probe) == 1;
  const bool wantLittle = descr[0] != '>';
  if (size > 1 && hostLittle != wantLittle)
  {
    std::reverse(b, b + size);
  }
  return std::string(reinterpret_cast<const char*>(b), static_cast<size_t>(size));
}

// The logical test array: 3 rows x 4 columns, arr[r][c] = 10 r + c + 1, with a NaN at [1][2]
// (float dtypes) and the null marker 99 at [2][3].
const int Rows = 3;
const int Cols = 4;
double Logical(int r, int c, bool isFloat)
{
  if (r == 1 && c == 2 && isFloat)
  {
    return std::nan("");
  }
  if (r == 2 && c == 3)
  {
    return 99.0;
  }
  return 10.0 * r + c + 1;
}

std::string Data(const std::string& descr, bool fortran)
{
  const bool isFloat = descr[1] == 'f';
  std::string out;
  if (fortran)
  {
    for (int c = 0; c < Cols; ++c)
    {
      for (int r = 0; r < Rows; ++r)
      {
        out += Encode(Logical(r, c, isFloat), descr);
      }
    }
  }
  else
  {
    for (int r = 0; r < Rows; ++r)
    {
      for (int c = 0; c < Cols; ++c)
      {
        out += Encode(Logical(r, c, isFloat), descr);
      }
    }
  }
  return out;
}

std::string Dict(const std::string& descr, bool fortran, const std::string& shape)
{
  return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
         ", 'shape': " + shape + ", }";
}

/// Expects an error and an empty output from reading `path`.
void CheckBadInput(const std::string& path, const std::string& what)
{
  vtkNew<vtkNumpyGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  Check(errors->Errors > 0, what + ": an error is reported");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0, what + ": output has no points");
  std::cout << what << ": " << errors->Errors << " error(s): " << errors->First << "\n";
}
}

namespace
{
void PenobscotCrop(const std::string& dataDir)
{
  // ---- The Penobscot crop ----
  const std::string path = dataDir + "penobscot_seabed_crop.npy";
  Check(vtkNumpyGridReader::CanReadFile(path.c_str()), "crop: CanReadFile");
  vtkNew<vtkNumpyGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  // Header (od -c): \x93 N U M P Y 001 \0, length 'v' \0 = 118, then
  // {'descr': '<f8', 'fortran_order': False, 'shape': (64, 48), }
  Check(reader->GetMajorVersion() == 1 && reader->GetMinorVersion() == 0, "crop: version 1.0");
  Check(std::string(reader->GetDescr()) == "<f8", "crop: descr <f8");
  Check(!reader->GetFortranOrder(), "crop: C order");
  Check(reader->GetNumberOfAxes() == 2 && reader->GetShape(0) == 64 && reader->GetShape(1) == 48,
    "crop: shape (64, 48)");
  Check(reader->GetNX() == 64 && reader->GetNY() == 48, "crop: rows along x");
  Check(reader->GetOutputDataType() == VTK_DOUBLE, "crop: float64 stays double");
  reader->Update();
  Check(errors->Errors == 0 && errors->Warnings == 0, "crop: no errors");
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(dims[0] == 64 && dims[1] == 48 && dims[2] == 1, "crop: dimensions 64 x 48 x 1");
  vtkDataArray* s = image->GetPointData()->GetScalars();
  Check(s && vtkDoubleArray::SafeDownCast(s) && std::string(s->GetName()) == "depth",
    "crop: vtkDoubleArray named depth");
  if (s)
  {
    // arr[r][c] at image index (r, c); literals from python3 struct.unpack('<d'), od -t f8.
    Check(std::isnan(ValueAt(image, 0, 0)), "crop: [0][0] is NaN");
    Check(std::isnan(ValueAt(image, 0, 47)), "crop: [0][47] is NaN");
    Check(std::isnan(ValueAt(image, 10, 40)), "crop: [10][40] is NaN");
    Check(ValueAt(image, 3, 3) == 38.9822497975, "crop: [3][3] = 38.9822497975 (byte 1304)");
    Check(ValueAt(image, 32, 24) == 42.278662325, "crop: [32][24] = 42.278662325 (byte 12608)");
    Check(ValueAt(image, 63, 47) == 42.4587428575, "crop: [63][47] = 42.4587428575 (byte 24696)");
    Check(ValueAt(image, 63, 0) == 43.400004505, "crop: [63][0] = 43.400004505");
    Check(ValueAt(image, 20, 5) == 41.2899516525, "crop: [20][5] = 41.2899516525");
  }
  // python3: sum(math.isnan(v) for v in values) over the crop = 973.
  Check(reader->GetNumberOfNoDataValues() == 973, "crop: 973 NaNs");
  double* o = image->GetOrigin();
  double* sp = image->GetSpacing();
  Check(o[0] == 0 && o[1] == 0 && sp[0] == 1 && sp[1] == 1 && sp[2] == 1,
    "crop: default origin 0, spacing 1");
  vtkMatrix3x3* d = image->GetDirectionMatrix();
  Check(d->IsIdentity(), "crop: default direction is the identity");

  // Geometry on the reader.
  reader->SetOrigin(1000.0, 1064.0);
  reader->SetSpacing(12.5, 25.0);
  reader->SetRotation(30.0);
  reader->Update();
  image = reader->GetOutput();
  o = image->GetOrigin();
  sp = image->GetSpacing();
  Check(o[0] == 1000.0 && o[1] == 1064.0 && sp[0] == 12.5 && sp[1] == 25.0,
    "crop: origin and spacing set on the reader");
  d = image->GetDirectionMatrix();
  const double a = vtkMath::RadiansFromDegrees(30.0);
  Check(std::fabs(d->GetElement(0, 0) - std::cos(a)) < 1e-15 &&
          std::fabs(d->GetElement(0, 1) + std::sin(a)) < 1e-15 &&
          std::fabs(d->GetElement(1, 0) - std::sin(a)) < 1e-15 &&
          std::fabs(d->GetElement(1, 1) - std::cos(a)) < 1e-15 && d->GetElement(2, 2) == 1.0,
    "crop: direction = rotation by 30 degrees");

  // Swapped axes: arr[j][i] at (i, j), 48 x 64.
  reader->SwapAxesOn();
  reader->Update();
  image = reader->GetOutput();
  image->GetDimensions(dims);
  Check(dims[0] == 48 && dims[1] == 64, "crop swapped: dimensions 48 x 64");
  Check(ValueAt(image, 47, 63) == 42.4587428575 && ValueAt(image, 24, 32) == 42.278662325 &&
          ValueAt(image, 0, 63) == 43.400004505,
    "crop swapped: arr[j][i] at (i, j)");
  Check(reader->GetNumberOfNoDataValues() == 973, "crop swapped: 973 NaNs");
}

void PenobscotFull(const strata_test::TestPaths& paths)
{
  // ---- The full Penobscot horizon, when the shared data is there ----
  const std::string shared = paths.SharedData;
  const std::string full = shared + "/horizons/penobscot_seabed.npy";
  if (shared.empty() || !vtksys::SystemTools::FileExists(full, true))
  {
    std::cout << "Skipping the full penobscot_seabed.npy: the shared data (--shared-data) has no "
                 "horizons/penobscot_seabed.npy\n";
  }
  else
  {
    vtkNew<vtkNumpyGridReader> reader;
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->SetFileName(full.c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    int dims[3];
    image->GetDimensions(dims);
    Check(errors->Errors == 0, "penobscot: no errors");
    // Header: {'descr': '<f8', 'fortran_order': False, 'shape': (601, 481), } (od -c).
    Check(dims[0] == 601 && dims[1] == 481 && dims[2] == 1, "penobscot: 601 x 481 x 1");
    // python3 over the 289081 values: 39509 NaN, arr[300][240] = 62.8493949775, etc.
    Check(reader->GetNumberOfNoDataValues() == 39509, "penobscot: 39509 NaNs");
    if (image->GetNumberOfPoints() == 601 * 481)
    {
      Check(ValueAt(image, 300, 240) == 62.8493949775, "penobscot: [300][240]");
      Check(ValueAt(image, 100, 200) == 54.2962066825, "penobscot: [100][200]");
      Check(ValueAt(image, 500, 50) == 54.4285736975, "penobscot: [500][50]");
      Check(ValueAt(image, 3, 67) == 38.9822497975, "penobscot: [3][67] (first value, index 1510)");
      Check(std::isnan(ValueAt(image, 600, 480)), "penobscot: [600][480] is NaN");
    }
  }
}

void SyntheticFiles(const std::string& outDir)
{
  // ---- Synthetic files: dtypes, byte orders, memory orders, versions ----
  struct Case
  {
    const char* Descr;
    bool Fortran;
    int Major;
  };
  const Case cases[] = {
    { "<f8", false, 1 },
    { ">f4", true, 1 },
    { ">f8", false, 2 },
    { "<f4", true, 3 },
    { ">f8", true, 1 },
    { "<i2", false, 1 },
    { ">i2", true, 2 },
    { "<i4", true, 1 },
    { ">i4", false, 3 },
    { "<i8", false, 1 },
    { "|i1", true, 1 },
    { "|u1", false, 1 },
    { "<u2", false, 1 },
    { ">u2", true, 1 },
    { "<u4", false, 2 },
    { ">u8", true, 1 },
  };
  for (const Case& c : cases)
  {
    const std::string descr = c.Descr;
    const std::string tag =
      descr + (c.Fortran ? " Fortran" : " C") + " v" + std::to_string(c.Major) + ".0: ";
    const std::string path = outDir + "TestNumpyGridReader_synthetic.npy";
    Spit(path, Npy(c.Major, Dict(descr, c.Fortran, "(3, 4)"), Data(descr, c.Fortran)));
    vtkNew<vtkNumpyGridReader> reader;
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->SetFileName(path.c_str());
    reader->SetNullValue(99.0);
    for (bool swap : { false, true })
    {
      reader->SetSwapAxes(swap);
      reader->Update();
      const std::string t = tag + (swap ? "swapped: " : "");
      Check(errors->Errors == 0, t + "no errors");
      Check(reader->GetMajorVersion() == c.Major && reader->GetFortranOrder() == c.Fortran &&
              std::string(reader->GetDescr()) == descr,
        t + "header");
      vtkImageData* image = reader->GetOutput();
      int dims[3];
      image->GetDimensions(dims);
      Check(dims[0] == (swap ? Cols : Rows) && dims[1] == (swap ? Rows : Cols), t + "dimensions");
      vtkDataArray* s = image->GetPointData()->GetScalars();
      const bool isDouble = descr == "<f8" || descr == ">f8";
      Check(s && s->GetDataType() == (isDouble ? VTK_DOUBLE : VTK_FLOAT), t + "array type");
      const bool isFloat = descr[1] == 'f';
      Check(reader->GetNumberOfNoDataValues() == (isFloat ? 2 : 1), t + "no-data count");
      bool ok = s && image->GetNumberOfPoints() == Rows * Cols;
      for (int r = 0; ok && r < Rows; ++r)
      {
        for (int col = 0; ok && col < Cols; ++col)
        {
          const double want = Logical(r, col, isFloat);
          const double got = swap ? ValueAt(image, col, r) : ValueAt(image, r, col);
          ok = (want == 99.0 || std::isnan(want)) ? std::isnan(got) : got == want;
        }
      }
      Check(ok, t + "every value at arr[i][j] -> (i, j) (arr[j][i] when swapped)");
    }
  }
}

void OneDimensional(const std::string& outDir)
{
  // 1-D and (rows, cols, 1).
  std::string data;
  for (int k = 0; k < 5; ++k)
  {
    data += Encode(k * 1.5, "<f4");
  }
  const std::string path = outDir + "TestNumpyGridReader_1d.npy";
  Spit(path, Npy(1, Dict("<f4", false, "(5,)"), data));
  vtkNew<vtkNumpyGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  int dims[3];
  reader->GetOutput()->GetDimensions(dims);
  Check(
    dims[0] == 5 && dims[1] == 1 && ValueAt(reader->GetOutput(), 4, 0) == 6.0, "1-D (5,): 5 x 1");
  reader->SwapAxesOn();
  reader->Update();
  reader->GetOutput()->GetDimensions(dims);
  Check(dims[0] == 1 && dims[1] == 5 && ValueAt(reader->GetOutput(), 0, 3) == 4.5,
    "1-D swapped: 1 x 5");

  const std::string path3 = outDir + "TestNumpyGridReader_3d.npy";
  Spit(path3, Npy(1, Dict("<f8", false, "(3, 4, 1)"), Data("<f8", false)));
  vtkNew<vtkNumpyGridReader> reader3;
  reader3->SetFileName(path3.c_str());
  reader3->Update();
  reader3->GetOutput()->GetDimensions(dims);
  Check(dims[0] == 3 && dims[1] == 4 && ValueAt(reader3->GetOutput(), 2, 1) == 22.0 &&
          ValueAt(reader3->GetOutput(), 0, 3) == 4.0,
    "(3, 4, 1): 3 x 4");
}

void BadInput(const std::string& dataDir, const std::string& outDir)
{
  // ---- Bad input ----
  CheckBadInput(outDir + "TestNumpyGridReader_does_not_exist.npy", "missing file");
  {
    std::string crop = Slurp(dataDir + "penobscot_seabed_crop.npy");
    Spit(outDir + "TestNumpyGridReader_truncated.npy", crop.substr(0, 1000));
    CheckBadInput(outDir + "TestNumpyGridReader_truncated.npy", "truncated copy");
    Spit(outDir + "TestNumpyGridReader_truncated_header.npy", crop.substr(0, 50));
    CheckBadInput(outDir + "TestNumpyGridReader_truncated_header.npy", "truncated header");
  }
  {
    std::string garbage;
    for (int k = 0; k < 2000; ++k)
    {
      garbage += static_cast<char>((k * 7919) % 251);
    }
    Spit(outDir + "TestNumpyGridReader_garbage.npy", garbage);
    CheckBadInput(outDir + "TestNumpyGridReader_garbage.npy", "garbage file");
    Check(!vtkNumpyGridReader::CanReadFile((outDir + "TestNumpyGridReader_garbage.npy").c_str()),
      "CanReadFile rejects garbage");
  }
  const std::string data = Data("<f4", false);
  const struct
  {
    std::string Name;
    std::string Bytes;
  } bad[] = {
    { "version 4.0",
      [&]
      {
        std::string b = Npy(1, Dict("<f4", false, "(3, 4)"), data);
        b[6] = 4;
        return b;
      }() },
    { "complex dtype", Npy(1, Dict("<c8", false, "(3, 4)"), data + data) },
    { "structured dtype",
      Npy(1, "{'descr': [('a', '<f4')], 'fortran_order': False, 'shape': (3, 4), }", data) },
    { "3-D shape", Npy(1, Dict("<f4", false, "(3, 2, 2)"), data) },
    { "empty shape", Npy(1, Dict("<f4", false, "()"), data) },
    { "zero rows", Npy(1, Dict("<f4", false, "(0, 4)"), data) },
    { "nx * ny > 2^31", Npy(1, Dict("<f4", false, "(100000, 100000)"), data) },
    { "fortran_order neither True nor False",
      Npy(1, "{'descr': '<f4', 'fortran_order': Maybe, 'shape': (3, 4), }", data) },
    { "unterminated dict",
      Npy(1, "{'descr': '<f4', 'fortran_order': False, 'shape': (3, 4", data) },
    { "no colon after a key",
      Npy(1, "{'descr' '<f4', 'fortran_order': False, 'shape': (3, 4), }", data) },
    { "missing shape", Npy(1, "{'descr': '<f4', 'fortran_order': False, }", data) },
    { "header longer than the file",
      [&]
      {
        std::string b = Npy(1, Dict("<f4", false, "(3, 4)"), data);
        b[9] = '\x7f';
        return b;
      }() },
  };
  for (const auto& b : bad)
  {
    const std::string path = outDir + "TestNumpyGridReader_bad.npy";
    Spit(path, b.Bytes);
    CheckBadInput(path, b.Name);
  }
}

void PrintSelf()
{
  vtkNew<vtkNumpyGridReader> printed;
  printed->Print(std::cout);
}

}

int TestNumpyGridReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dataDir = paths.Data + "/horizons/";
  const std::string outDir = paths.Output + "/";
  strata_test::RunSubTests(
    {
      { "PenobscotCrop", [&] { PenobscotCrop(dataDir); } },
      { "PenobscotFull", [&] { PenobscotFull(paths); } },
      { "SyntheticFiles", [&] { SyntheticFiles(outDir); } },
      { "OneDimensional", [&] { OneDimensional(outDir); } },
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

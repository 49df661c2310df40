// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkSegyVolumeReader:
// - Testing/Data/seismic/f3.sgy (real, int16, inline-sorted): dimensions 18 x 75 x 23
//   (crossline, sample, inline), geometry, and every sample equal to the value parsed from the
//   file's bytes by the test itself (big-endian int16 at the positions the standard gives);
//   a sub-extent reads only the traces of its inlines;
// - files written by the test (StrataSegyTestFile.h, no segyio): traces shuffled, one missing
//   (NaN), line numbers at bytes 17 and 234 (a rev 1 field, and a position segyio knows no
//   field at), in formats 1 (IBM float), 2, 3, 5 (IEEE float) and 8, read back exactly; the
//   default byte positions on a rev 1 layout;
// - errors, each reported and leaving an empty output: truncated file, headers only, a trace
//   longer than the others, format codes 4 and 7 (and SampleFormat overriding a wrong code),
//   byte positions out of range, wrong byte positions (duplicate positions), a missing file, a
//   file changed between the information and the data pass.
#include "StrataErrorCounter.h"
#include "StrataSegyTestFile.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSegyVolumeReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;
using strata_test::SegyTestFile;

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

int32_t BigEndian(const std::string& bytes, size_t offset, int size)
{
  uint32_t v = 0;
  for (int b = 0; b < size; ++b)
  {
    v = (v << 8) | static_cast<unsigned char>(bytes[offset + b]);
  }
  return size == 2 ? static_cast<int16_t>(v) : static_cast<int32_t>(v);
}

float ValueAt(vtkImageData* image, int x, int y, int z)
{
  return static_cast<float>(image->GetScalarComponentAsDouble(x, y, z, 0));
}

bool Empty(vtkImageData* image)
{
  return image->GetNumberOfPoints() == 0;
}

/// Reads `path` with `reader`, expecting an error whose message contains `expect`.
void Rejects(vtkSegyVolumeReader* reader,
  const std::string& path,
  const std::string& expect,
  const std::string& what)
{
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Modified(); // the same name may hold new bytes
  reader->Update();
  std::cout << "  " << what << ": " << errors->First << "\n";
  Check(errors->Errors > 0 && Empty(reader->GetOutput()) &&
          errors->First.find(expect) != std::string::npos,
    what + ": reported (\"" + expect + "\"), empty output");
  reader->RemoveAllObservers();
  reader->GetExecutive()->RemoveAllObservers();
}

/// Checks the reader's output against the generated file, every sample, NaN where missing.
bool SameAsGenerated(vtkImageData* image, const SegyTestFile& file)
{
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] != file.Crosslines || dims[1] != file.Samples || dims[2] != file.Inlines)
  {
    std::cerr << "  dimensions " << dims[0] << " x " << dims[1] << " x " << dims[2] << "\n";
    return false;
  }
  for (int i = 0; i < file.Inlines; ++i)
  {
    for (int x = 0; x < file.Crosslines; ++x)
    {
      const bool missing =
        std::find(file.Missing.begin(), file.Missing.end(), std::make_pair(i, x)) !=
        file.Missing.end();
      for (int s = 0; s < file.Samples; ++s)
      {
        const float v = ValueAt(image, x, s, i);
        const float expected = static_cast<float>(SegyTestFile::Value(file.Format, i, x, s));
        if (missing ? !std::isnan(v) : v != expected)
        {
          std::cerr << "  inline index " << i << ", crossline index " << x << ", sample " << s
                    << ": " << v << ", expected " << (missing ? NAN : expected) << "\n";
          return false;
        }
      }
    }
  }
  return true;
}
}

namespace
{
void F3(const strata_test::TestPaths& paths)
{
  std::cout << "f3.sgy\n";
  const std::string path = paths.Data + "/seismic/f3.sgy";
  const std::string bytes = Slurp(path);
  vtkNew<vtkSegyVolumeReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetPlacement(vtkSegyVolumeReader::Placements::LineNumbers);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  const double* origin = image->GetOrigin();
  std::cout << "  " << dims[0] << " x " << dims[1] << " x " << dims[2] << ", spacing " << spacing[0]
            << " " << spacing[1] << " " << spacing[2] << ", origin " << origin[0] << " "
            << origin[1] << " " << origin[2] << ", " << reader->GetNumberOfTraces()
            << " traces, format " << reader->GetFormatCode() << "\n";
  Check(errors->Errors == 0 && errors->Warnings == 0, "f3: no errors or warnings");
  Check(
    dims[0] == 18 && dims[1] == 75 && dims[2] == 23, "f3: 18 crosslines x 75 samples x 23 inlines");
  Check(reader->GetNumberOfTraces() == 414 && reader->GetNumberOfMissingTraces() == 0 &&
          reader->GetFormatCode() == 3,
    "f3: 414 traces, none missing, format 3 (int16)");
  // Inlines 111-133 and crosslines 875-892 step 1, 4 ms, delay recording time 4 ms.
  Check(spacing[0] == 1 && spacing[1] == 4 && spacing[2] == 1 && origin[0] == 111 &&
          origin[1] == 875 && origin[2] == 4,
    "f3: spacing (1, 4 ms, 1), origin (inline 111, crossline 875, 4 ms)");
  const double expectedDirection[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
  Check(
    std::equal(expectedDirection, expectedDirection + 9, image->GetDirectionMatrix()->GetData()) &&
      image->GetDirectionMatrix()->Determinant() == 1.0,
    "f3: index (crossline, sample, inline) -> world (inline, crossline, time), a rotation");
  Check(std::string(image->GetPointData()->GetScalars()->GetName()) == "amplitude" &&
          image->GetPointData()->GetScalars()->GetDataType() == VTK_FLOAT,
    "f3: float array \"amplitude\"");

  // The reference, from the bytes: trace t at 3600 + t (240 + 150); inline and crossline as
  // big-endian int32 at 189 and 193; samples big-endian int16.
  long mismatches = 0;
  long nonZero = 0;
  for (int t = 0; t < 414; ++t)
  {
    const size_t header = 3600 + static_cast<size_t>(t) * 390;
    const int il = BigEndian(bytes, header + 188, 4);
    const int xl = BigEndian(bytes, header + 192, 4);
    for (int s = 0; s < 75; ++s)
    {
      const int v = BigEndian(bytes, header + 240 + 2 * s, 2);
      nonZero += v != 0;
      mismatches += ValueAt(image, xl - 875, s, il - 111) != static_cast<float>(v);
    }
  }
  std::cout << "  " << nonZero << " non-zero samples, " << mismatches << " mismatches\n";
  Check(mismatches == 0 && nonZero > 10000, "f3: every sample equals the file's int16");
  std::cout << "  inline 120, crossline 880, samples 30-32: " << ValueAt(image, 5, 30, 9) << " "
            << ValueAt(image, 5, 31, 9) << " " << ValueAt(image, 5, 32, 9) << "\n";

  // A sub-extent: inlines 5-7 (116-118), crosslines 2-9, samples 10-40.
  vtkNew<vtkSegyVolumeReader> sub;
  sub->SetFileName(path.c_str());
  sub->SetPlacement(vtkSegyVolumeReader::Placements::LineNumbers);
  sub->UpdateInformation();
  const int extent[6] = { 2, 9, 10, 40, 5, 7 };
  sub->UpdateExtent(extent);
  int e[6];
  sub->GetOutput()->GetExtent(e);
  bool same = std::equal(extent, extent + 6, e);
  for (int k = 5; k <= 7 && same; ++k)
    for (int j = 10; j <= 40; ++j)
      for (int i = 2; i <= 9; ++i)
        same = same && ValueAt(sub->GetOutput(), i, j, k) == ValueAt(image, i, j, k);
  std::cout << "  sub-extent read " << sub->GetNumberOfTracesRead() << " traces\n";
  Check(same && sub->GetNumberOfTracesRead() == 3 * 8,
    "f3: a sub-extent has its values and reads only its 24 traces");
}

/// f3.sgy placed by its CDP coordinates (bytes 181, 185, scalar -10 at 71: 0.1 m).
void F3World(const strata_test::TestPaths& paths)
{
  std::cout << "f3.sgy in world coordinates\n";
  const std::string path = paths.Data + "/seismic/f3.sgy";
  const std::string bytes = Slurp(path);
  vtkNew<vtkSegyVolumeReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  const double* spacing = image->GetSpacing();
  std::cout.precision(12);
  std::cout << "  spacing " << spacing[0] << " " << spacing[1] << " " << spacing[2] << ", rotation "
            << reader->GetGridRotation() << ", residual " << reader->GetFitResidual() << " m\n";
  Check(errors->Errors == 0 && errors->Warnings == 0 && reader->GetGeoreferenced(),
    "f3: placed by its coordinates by default, no errors or warnings");
  // Each trace's own coordinates (the file's bytes) against the place the reader gives its
  // grid position: within the fit residual the reader reports, which is below the 0.1 m the
  // coordinates are rounded to, times a few.
  double worst = 0.0;
  for (int t = 0; t < 414; ++t)
  {
    const size_t header = 3600 + static_cast<size_t>(t) * 390;
    const int il = BigEndian(bytes, header + 188, 4);
    const int xl = BigEndian(bytes, header + 192, 4);
    const double x = BigEndian(bytes, header + 180, 4) / 10.0;
    const double y = BigEndian(bytes, header + 184, 4) / 10.0;
    double p[3];
    image->TransformIndexToPhysicalPoint(xl - 875, 0, il - 111, p);
    worst = std::max(worst, std::hypot(p[0] - x, p[1] - y));
  }
  std::cout << "  largest trace-to-grid distance " << worst << " m\n";
  Check(std::abs(worst - reader->GetFitResidual()) < 1e-6 && worst < 0.2,
    "f3: every trace within the reported residual (< 0.2 m) of its grid position");
  Check(spacing[1] == 4.0 && image->GetOrigin()[2] == -4.0 &&
          image->GetDirectionMatrix()->GetElement(2, 1) == -1.0,
    "f3: samples go down, 4 ms apart, from z = -4 (the 4 ms delay)");
}

/// Bounds of the fit's errors from the coordinates' rounding (each component off by at most
/// r = 0.5 / |scalar|): a least-squares estimate is a fixed linear combination of the
/// coordinates, so its error is at most r sqrt(2) times the sum of its weights' magnitudes.
/// Corner: the hat-matrix row, 1/n + d_c' S^-1 d_t; per-bin vectors: the rows of S^-1 D'.
struct RoundingBounds
{
  double Corner = 0.0, Inline = 0.0, Crossline = 0.0;

  explicit RoundingBounds(const SegyTestFile& file)
  {
    std::vector<std::pair<double, double>> d;
    for (const auto& t : file.Order())
      d.emplace_back(t.first, t.second);
    const double n = static_cast<double>(d.size());
    double mi = 0, mj = 0;
    for (const auto& t : d)
    {
      mi += t.first / n;
      mj += t.second / n;
    }
    double sii = 0, sjj = 0, sij = 0;
    for (auto& t : d)
    {
      t.first -= mi;
      t.second -= mj;
      sii += t.first * t.first;
      sjj += t.second * t.second;
      sij += t.first * t.second;
    }
    const double det = sii * sjj - sij * sij;
    const double r = 0.5 / std::abs(file.CoordinateScalar) * std::sqrt(2.0);
    for (const auto& t : d)
    {
      this->Inline += r * std::abs(sjj * t.first - sij * t.second) / det;
      this->Crossline += r * std::abs(sii * t.second - sij * t.first) / det;
    }
    for (int i : { 0, file.Inlines - 1 })
    {
      for (int x : { 0, file.Crosslines - 1 })
      {
        const double ci = i - mi, cx = x - mj;
        double sum = 0.0;
        for (const auto& t : d)
        {
          sum += std::abs(
            1.0 / n +
            (ci * (sjj * t.first - sij * t.second) + cx * (sii * t.second - sij * t.first)) / det);
        }
        this->Corner = std::max(this->Corner, r * sum);
      }
    }
  }
};

/// The generated survey's checks: geometry, corner traces, samples.
void CheckPlacement(vtkSegyVolumeReader* reader,
  const SegyTestFile& file,
  double scale,
  const std::string& name)
{
  vtkImageData* image = reader->GetOutput();
  const double* spacing = image->GetSpacing();
  std::cout << "  " << name << ": spacing " << spacing[0] << " " << spacing[1] << " " << spacing[2]
            << ", rotation " << reader->GetGridRotation() << ", residual "
            << reader->GetFitResidual() << "\n";
  Check(reader->GetGeoreferenced() && SameAsGenerated(image, file),
    name + ": georeferenced, every sample in its place");
  const RoundingBounds bounds(file);
  double worst = 0.0, worstZ = 0.0;
  for (int i : { 0, file.Inlines - 1 })
  {
    for (int x : { 0, file.Crosslines - 1 })
    {
      double expected[2];
      file.MapPosition(i, x, expected);
      double p[3], q[4];
      const int s = file.Samples - 1;
      image->TransformIndexToPhysicalPoint(x, s, i, p);
      const double index[4] = { double(x), double(s), double(i), 1.0 };
      reader->GetGridToWorld()->MultiplyPoint(index, q);
      const double z = scale * (file.DelayMilliseconds + s * file.IntervalMicroseconds / 1000.0);
      worst = std::max({ worst,
        std::hypot(p[0] - expected[0], p[1] - expected[1]),
        std::hypot(q[0] - expected[0], q[1] - expected[1]) });
      worstZ = std::max({ worstZ, std::abs(p[2] - z), std::abs(q[2] - z) });
    }
  }
  std::cout << "  " << name << ": corners off by " << worst << " m (bound " << bounds.Corner << ", "
            << worst / file.OriginY << " relative), z by " << worstZ << "\n";
  Check(worst <= bounds.Corner && worst / file.OriginY < 1e-6 && worstZ < 1e-9,
    name + ": the four corner traces at their map positions and depths");
  double rotation = file.RotationDegrees;
  while (rotation > 180.0)
    rotation -= 360.0;
  const double det = image->GetDirectionMatrix()->Determinant();
  const double angleBound = bounds.Crossline / file.CrosslineBin * 180.0 / 3.14159265358979;
  std::cout << "  " << name << ": bounds " << bounds.Crossline << " m, " << bounds.Inline << " m, "
            << angleBound << " degrees\n";
  Check(std::abs(reader->GetGridRotation() - rotation) <= angleBound &&
          std::abs(spacing[0] - file.CrosslineBin) <= bounds.Crossline &&
          std::abs(spacing[2] - file.InlineBin) <= bounds.Inline &&
          spacing[1] == std::abs(scale) * file.IntervalMicroseconds / 1000.0 &&
          std::abs(std::abs(det) - 1.0) < 1e-4 && (det > 0) == (file.Mirrored == (scale > 0)),
    name + ": rotation, bin sizes, sample spacing and handedness");
  auto* field = image->GetFieldData()->GetArray("GridToWorld");
  bool same = field && field->GetNumberOfComponents() == 16 && field->GetNumberOfTuples() == 1;
  for (int e = 0; same && e < 16; ++e)
  {
    same = field->GetComponent(0, e) == reader->GetGridToWorld()->GetData()[e];
  }
  Check(same, name + ": field data GridToWorld equals GetGridToWorld()");
}

void World(const std::string& out)
{
  std::cout << "generated surveys in rotated UTM coordinates\n";
  {
    // 456000 E, 6780000 N, 30 degrees, 12.5 m crossline and 25 m inline bins, scalar -100,
    // shuffled, one trace missing.
    SegyTestFile file;
    file.Format = 5;
    file.Georeferenced = true;
    file.Seed = 11;
    file.Missing = { { 1, 3 } };
    const std::string path = out + "/utm.sgy";
    Spit(path, file.Bytes());
    vtkNew<vtkSegyVolumeReader> reader;
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->SetFileName(path.c_str());
    reader->Update();
    std::cout << "  warning: " << errors->First << "\n";
    Check(errors->Errors == 0 && errors->Warnings == 1 &&
            errors->First.find("1 of the 20 grid positions have no trace") != std::string::npos,
      "utm: the missing trace is a warning");
    CheckPlacement(reader, file, -1.0, "utm");
    reader->SetVerticalScale(-10.0);
    reader->Update();
    CheckPlacement(reader, file, -10.0, "utm, VerticalScale -10");
  }
  {
    // Mirrored (inlines clockwise from crosslines), 127 degrees, source X/Y, scalar -10, a
    // second grid step.
    SegyTestFile file;
    file.Format = 3;
    file.Georeferenced = true;
    file.Mirrored = true;
    file.RotationDegrees = 127.0;
    file.InlineBin = 30.0;
    file.CrosslineBin = 20.0;
    file.CoordinateScalar = -10;
    file.XByte = 73;
    file.YByte = 77;
    file.CrosslineStep = 3;
    const std::string path = out + "/mirrored.sgy";
    Spit(path, file.Bytes());
    vtkNew<vtkSegyVolumeReader> reader;
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->SetFileName(path.c_str());
    reader->SetXByte(73);
    reader->SetYByte(77);
    reader->Update();
    Check(errors->Errors == 0 && errors->Warnings == 0, "mirrored: no errors or warnings");
    CheckPlacement(reader, file, -1.0, "mirrored");
  }
}

void WorldErrors(const std::string& out)
{
  std::cout << "world placement errors\n";
  SegyTestFile file;
  file.Georeferenced = true;
  const std::string bad = out + "/bad-world.sgy";
  vtkNew<vtkSegyVolumeReader> reader;

  SegyTestFile off = file;
  off.OffLattice = { 2, 1 };
  Spit(bad, off.Bytes());
  Rejects(reader, bad, "not on a regular grid", "a trace a bin off its place");
  reader->SetMaximumFitResidual(2.0);
  reader->SetFileName(bad.c_str());
  reader->Update();
  // The moved trace keeps (1 - leverage) of its 12.5 m: leverage 1/20 + 0.5^2/25 + 1^2/40 =
  // 0.085 at inline index 2, crossline index 1 of the 4 x 5 grid; +-0.01 for the cm rounding.
  std::cout << "  residual " << reader->GetFitResidual() << " m\n";
  Check(reader->GetGeoreferenced() && std::abs(reader->GetFitResidual() - 12.5 * 0.915) < 0.01,
    "a looser MaximumFitResidual accepts it, with the residual reported (11.44 m)");
  reader->SetMaximumFitResidual(0.25);

  Spit(bad, file.Bytes());
  reader->SetYByte(201); // zeros: X alone changes, along both axes
  Rejects(reader, bad, "nearly along one line", "Y read from an empty field");
  reader->SetYByte(181);
  Rejects(reader, bad, "XByte and YByte are both 181", "X byte = Y byte");
  reader->SetYByte(185);
  reader->SetXByte(238);
  Rejects(reader, bad, "outside [1, 237]", "X byte 238");
  reader->SetXByte(181);
  reader->SetVerticalScale(0.0);
  Rejects(reader, bad, "VerticalScale is 0", "VerticalScale 0");
  reader->SetVerticalScale(-1.0);

  // No coordinates: Automatic places by line numbers, World refuses.
  SegyTestFile plain;
  Spit(bad, plain.Bytes());
  {
    vtkNew<vtkSegyVolumeReader> automatic;
    vtkNew<ErrorCounter> errors;
    errors->Watch(automatic);
    automatic->SetFileName(bad.c_str());
    automatic->Update();
    Check(errors->Errors == 0 && errors->Warnings == 0 && !automatic->GetGeoreferenced() &&
            automatic->GetOutput()->GetOrigin()[0] == 10 &&
            SameAsGenerated(automatic->GetOutput(), plain),
      "no coordinates: Automatic places by line numbers, silently");
  }
  reader->SetPlacement(vtkSegyVolumeReader::Placements::World);
  Rejects(reader, bad, "every trace has X = Y = 0", "no coordinates, World");

  SegyTestFile geographic = file;
  geographic.CoordinateUnits = 2;
  Spit(bad, geographic.Bytes());
  Rejects(reader, bad, "geographic", "seconds of arc, World");
  reader->SetPlacement(vtkSegyVolumeReader::Placements::Automatic);
  {
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->Modified();
    reader->Update();
    Check(errors->Errors == 0 && errors->Warnings == 1 && !reader->GetGeoreferenced() &&
            errors->First.find("geographic") != std::string::npos,
      "seconds of arc, Automatic: a warning, placed by line numbers");
    reader->RemoveAllObservers();
    reader->GetExecutive()->RemoveAllObservers();
  }

  SegyTestFile line = file;
  line.Inlines = 1;
  Spit(bad, line.Bytes());
  reader->SetPlacement(vtkSegyVolumeReader::Placements::World);
  Rejects(reader, bad, "single inline or crossline", "one inline, World");
  reader->SetPlacement(vtkSegyVolumeReader::Placements::Automatic);
  {
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->Modified();
    reader->Update();
    Check(errors->Errors == 0 && errors->Warnings == 1 && !reader->GetGeoreferenced() &&
            errors->First.find("single inline") != std::string::npos &&
            SameAsGenerated(reader->GetOutput(), line),
      "one inline (a 2-D line), Automatic: a warning, placed by line numbers");
    reader->RemoveAllObservers();
    reader->GetExecutive()->RemoveAllObservers();
  }

  SegyTestFile delayed = file;
  delayed.DelayTrace = 6;
  Spit(bad, delayed.Bytes());
  Rejects(reader, bad, "start at different times", "a trace of another delay");
}

void GeneratedFiles(const std::string& out)
{
  std::cout << "generated files: shuffled, one trace missing, custom byte positions\n";
  for (int format : { 1, 2, 3, 5, 8 })
  {
    SegyTestFile file;
    file.Format = format;
    file.InlineByte = 17;     // energy source point number, a 4-byte rev 1 field
    file.CrosslineByte = 234; // inside the unassigned bytes: read as 4 bytes big-endian
    file.Missing = { { 2, 2 } };
    file.Seed = 7;
    const std::string path = out + "/shuffled-" + std::to_string(format) + ".sgy";
    Spit(path, file.Bytes());
    vtkNew<vtkSegyVolumeReader> reader;
    vtkNew<ErrorCounter> errors;
    errors->Watch(reader);
    reader->SetFileName(path.c_str());
    reader->SetInlineByte(17);
    reader->SetCrosslineByte(234);
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    const double* spacing = image->GetSpacing();
    const double* origin = image->GetOrigin();
    const std::string name = "format " + std::to_string(format);
    Check(errors->Errors == 0 && SameAsGenerated(image, file),
      name + ": every sample in its (inline, crossline) place, NaN where the trace is missing");
    Check(reader->GetNumberOfTraces() == 19 && reader->GetNumberOfMissingTraces() == 1 &&
            reader->GetFirstInline() == 10 && reader->GetInlineStep() == 2 &&
            reader->GetFirstCrossline() == 100 && reader->GetCrosslineStep() == 1,
      name + ": 19 traces, 1 missing, inlines 10 + 2k, crosslines 100 + k");
    Check(spacing[0] == 1 && spacing[1] == 2 && spacing[2] == 2 && origin[0] == 10 &&
            origin[1] == 100 && origin[2] == 100,
      name + ": spacing (1, 2 ms, 2), origin (10, 100, 100 ms)");
  }
  {
    // The same grid at rev 1's positions, read with the defaults; the shuffled file read with
    // the defaults finds zeros there: every trace at (0, 0).
    SegyTestFile file;
    file.Seed = 3;
    const std::string path = out + "/rev1.sgy";
    Spit(path, file.Bytes());
    vtkNew<vtkSegyVolumeReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    Check(SameAsGenerated(reader->GetOutput(), file), "default byte positions 189 and 193");
    vtkNew<vtkSegyVolumeReader> wrong;
    Rejects(
      wrong, out + "/shuffled-1.sgy", "are both at inline 0, crossline 0", "wrong byte positions");
  }
}

void Errors(const std::string& out)
{
  std::cout << "errors\n";
  SegyTestFile file;
  const std::string good = file.Bytes();
  const std::string bad = out + "/bad.sgy";
  vtkNew<vtkSegyVolumeReader> reader;

  Spit(bad, good.substr(0, good.size() - 7));
  Rejects(reader, bad, "not a whole, non-zero number of traces", "truncated file");
  Spit(bad, good.substr(0, 3600));
  Rejects(reader, bad, "not a whole, non-zero number of traces", "headers only");
  Spit(bad, good.substr(0, 3000));
  Rejects(reader, bad, "fewer than the 3600", "shorter than its headers");
  SegyTestFile longer = file;
  longer.LongTrace = 5;
  Spit(bad, longer.Bytes());
  Rejects(reader, bad, "not a whole, non-zero number of traces", "a trace 2 samples longer");
  for (int code : { 4, 7 })
  {
    SegyTestFile other = file;
    other.Format = 5;
    std::string bytes = other.Bytes();
    strata_test::PutBigEndian(bytes, 3224, static_cast<uint32_t>(code), 2);
    Spit(bad, bytes);
    Rejects(reader,
      bad,
      "sample format code " + std::to_string(code) + " is not supported",
      "format code " + std::to_string(code));
    if (code == 4)
    {
      vtkNew<vtkSegyVolumeReader> fixed;
      fixed->SetFileName(bad.c_str());
      fixed->SetSampleFormat(5);
      fixed->Update();
      Check(SameAsGenerated(fixed->GetOutput(), other), "SampleFormat 5 overrides code 4");
    }
  }
  Spit(bad, good);
  reader->SetInlineByte(0);
  Rejects(reader, bad, "outside [1, 237]", "inline byte 0");
  reader->SetInlineByte(238);
  Rejects(reader, bad, "outside [1, 237]", "inline byte 238");
  reader->SetInlineByte(193);
  Rejects(reader, bad, "both 193", "inline byte = crossline byte");
  reader->SetInlineByte(189);
  Rejects(reader, out + "/missing.sgy", "cannot open it", "missing file");

  // Recovers on a good file.
  reader->SetFileName(bad.c_str());
  reader->Modified();
  reader->Update();
  Check(SameAsGenerated(reader->GetOutput(), file), "the reader recovers on a good file");

  // A file replaced between the information pass and the data pass is not read with the
  // stale trace index.
  vtkNew<vtkSegyVolumeReader> stale;
  vtkNew<ErrorCounter> errors;
  errors->Watch(stale);
  stale->SetFileName(bad.c_str());
  stale->UpdateInformation();
  SegyTestFile smaller = file;
  smaller.Inlines = 2;
  Spit(bad, smaller.Bytes());
  stale->Update();
  Check(errors->Errors > 0 && Empty(stale->GetOutput()) &&
          errors->First.find("changed after its headers were read") != std::string::npos,
    "a file replaced after the information pass is refused");
  std::cout << "  file replaced: " << errors->First << "\n";
}

}

int TestSegyVolumeReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string out = paths.Output + "/TestSegyVolumeReader";
  vtksys::SystemTools::MakeDirectory(out);
  return strata_test::RunSubTests(
    {
      { "F3", [&] { F3(paths); } },
      { "F3World", [&] { F3World(paths); } },
      { "GeneratedFiles", [&] { GeneratedFiles(out); } },
      { "World", [&] { World(out); } },
      { "WorldErrors", [&] { WorldErrors(out); } },
      { "Errors", [&] { Errors(out); } },
    },
    strata_test::Failures);
}

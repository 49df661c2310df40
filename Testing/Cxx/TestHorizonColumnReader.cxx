// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkHorizonColumnReader against values obtained independently of it:
// - Testing/Data/horizons/top_heimdal_subset.txt (Top Heimdal, Glitne field, aadm/
//   geophysical_notes, CC BY-NC 4.0): literal grid facts determined once with python3 (distinct
//   inlines 1300..1500 step 4 and crosslines 1500..2000 step 2, 12801 = 51 x 251 lines, no
//   holes), and every value against this test's own parse of the file with iostreams;
// - synthetic files written here: x y z points on grids rotated by 30 and 140 degrees, with a
//   missing node and scrambled line order (the expected grid is the one they were generated
//   from), inline/crossline columns with a header, comments, blank lines, CRLF, a missing node,
//   a null value and a duplicate;
// - whitespace matrices (issue 14, defect 1): 40 x 300 written as numpy.savetxt does (fmt
//   "%.18e" and "%d", one "nan") read in Auto mode as the matrix, every value compared with the
//   function that generated it; a 6 x 5 matrix in Matrix mode placed by Origin, spacings and
//   Rotation (node (5, 4) against its position computed here), the same file in Auto mode an
//   error, a ragged matrix and one with a word errors;
// - matrices of heights with a DEM export's '#' header (issue 27): an outside consumer's 327
//   values per row x 468 rows with "Dimensions", "x_extent", "y_extent" and "nodata" used to come
//   out as a 468 x 327 grid, transposed without a word. Written here in that shape, and as 7 x 5
//   with "key = value" lines (too narrow for Auto to call it a matrix without its header): the
//   grid must be (values per row) x (rows), the first row at y = ymax, node (i, j) the value in
//   column i of row ny - 1 - j, placed by the extents (node bounds), nodata a hole; Dimensions
//   that disagree with the data (the transposed pair among them) and half the extents are errors
//   that leave no grid behind;
// - bad input: a missing file, a truncated copy, a garbage file, an empty file, points off any
//   regular grid, non-integer indices in InlineCrossline mode. Each must raise an error (caught
//   by an observer) and leave the output with no points.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkHorizonColumnReader.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

bool Near(double a, double b, double tol)
{
  return std::fabs(a - b) <= tol;
}

double ValueAt(vtkImageData* image, int i, int j)
{
  int ijk[3] = { i, j, 0 };
  return image->GetPointData()->GetScalars()->GetComponent(image->ComputePointId(ijk), 0);
}

void Spit(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool DirectionIs(vtkImageData* image, double degrees, double tol)
{
  const double a = vtkMath::RadiansFromDegrees(degrees);
  const double want[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
  const double* d = image->GetDirectionMatrix()->GetData();
  for (int k = 0; k < 9; ++k)
  {
    if (!Near(d[k], want[k], tol))
    {
      return false;
    }
  }
  return true;
}

/// Expects an error and an empty output from reading `path`.
void CheckBadInput(const std::string& path,
  const std::string& what,
  vtkHorizonColumnReader::ColumnMode mode = vtkHorizonColumnReader::ColumnMode::Auto)
{
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetMode(mode);
  reader->Update();
  Check(errors->Errors > 0, what + ": an error is reported");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0, what + ": output has no points");
  std::cout << what << ": " << errors->Errors << " error(s): " << errors->First << "\n";
}

/// Writes the nodes of a rotated nx x ny grid as "x y z" lines in a scrambled order, leaving out
/// `missing` (an index i + j * nx, or -1). z = 1500 + 3 i + 0.5 j.
std::string RotatedGridText(int nx,
  int ny,
  double ox,
  double oy,
  double du,
  double dv,
  double degrees,
  int missing,
  const char* format,
  const char* header)
{
  const double a = vtkMath::RadiansFromDegrees(degrees);
  const int n = nx * ny;
  std::string text = header;
  char line[128];
  for (int k = 0; k < n; ++k)
  {
    const int id = (k * 17) % n; // 17 is prime to the sizes used: a permutation
    if (id == missing)
    {
      continue;
    }
    const int i = id % nx;
    const int j = id / nx;
    const double x = ox + std::cos(a) * i * du - std::sin(a) * j * dv;
    const double y = oy + std::sin(a) * i * du + std::cos(a) * j * dv;
    std::snprintf(line, sizeof(line), format, x, y, 1500.0 + 3.0 * i + 0.5 * j);
    text += line;
  }
  return text;
}

/// Every "x y z" line of `text` must land on a node of `image` (within `tol` index units) that
/// holds its z.
bool EveryPointOnItsNode(vtkImageData* image, const std::string& text, double tol)
{
  std::istringstream in(text);
  std::string line;
  int dims[3];
  image->GetDimensions(dims);
  int lines = 0;
  while (std::getline(in, line))
  {
    for (char& c : line)
    {
      c = c == ',' ? ' ' : c;
    }
    std::istringstream fields(line);
    double p[3] = { 0, 0, 0 };
    double z = 0;
    if (!(fields >> p[0] >> p[1] >> z))
    {
      continue; // the header
    }
    double ijk[3];
    image->TransformPhysicalPointToContinuousIndex(p, ijk);
    const int i = static_cast<int>(std::lround(ijk[0]));
    const int j = static_cast<int>(std::lround(ijk[1]));
    if (!Near(ijk[0], i, tol) || !Near(ijk[1], j, tol) || i < 0 || j < 0 || i >= dims[0] ||
        j >= dims[1] || ValueAt(image, i, j) != static_cast<float>(z))
    {
      std::cerr << "point " << p[0] << " " << p[1] << " -> index " << ijk[0] << " " << ijk[1]
                << "\n";
      return false;
    }
    ++lines;
  }
  return lines > 0;
}
}

namespace
{
using Mode = vtkHorizonColumnReader::ColumnMode;

void TopHeimdal(const std::string& dataDir)
{
  // ---- Top Heimdal: inline crossline twt ----
  const std::string path = dataDir + "top_heimdal_subset.txt";
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  Check(errors->Errors == 0 && errors->Warnings == 0, "heimdal: no errors or warnings");
  Check(reader->GetDetectedMode() == Mode::InlineCrossline, "heimdal: detected inline/crossline");
  Check(!reader->GetHasHeaderLine(), "heimdal: no header line");
  Check(reader->GetNumberOfRecords() == 12801, "heimdal: 12801 lines (wc -l)");
  Check(reader->GetFirstInline() == 1300 && reader->GetInlineStep() == 4,
    "heimdal: inlines from 1300 step 4");
  Check(reader->GetFirstCrossline() == 1500 && reader->GetCrosslineStep() == 2,
    "heimdal: crosslines from 1500 step 2");
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(dims[0] == 51 && dims[1] == 251 && dims[2] == 1, "heimdal: 51 x 251 x 1");
  Check(reader->GetNumberOfNoDataValues() == 0, "heimdal: no holes (51 * 251 = 12801 lines)");
  double* o = image->GetOrigin();
  double* s = image->GetSpacing();
  Check(o[0] == 1300 && o[1] == 1500 && s[0] == 4 && s[1] == 2 && s[2] == 1,
    "heimdal: index coordinates (origin 1300, 1500; spacing 4, 2)");
  Check(image->GetDirectionMatrix()->IsIdentity(), "heimdal: no rotation");
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  Check(
    scalars && vtkFloatArray::SafeDownCast(scalars) && std::string(scalars->GetName()) == "depth",
    "heimdal: float array named depth");
  if (scalars && dims[0] == 51 && dims[1] == 251)
  {
    // Literals from the text (grep): first line, last line, and three in between.
    Check(ValueAt(image, 0, 0) == 2084.9f, "heimdal: 1300 1500 2084.9");
    Check(ValueAt(image, 50, 250) == 2127.1f, "heimdal: 1500 2000 2127.1");
    Check(ValueAt(image, 25, 125) == 2058.7f, "heimdal: 1400 1750 2058.7");
    Check(ValueAt(image, 10, 50) == 2101.7f, "heimdal: 1340 1600 2101.7");
    Check(ValueAt(image, 40, 201) == 2094.7f, "heimdal: 1460 1902 2094.7");

    // Every line against the test's own parse.
    std::ifstream in(path);
    double il = 0, xl = 0, z = 0;
    int lines = 0;
    int wrong = 0;
    while (in >> il >> xl >> z)
    {
      const int i = static_cast<int>((il - 1300) / 4);
      const int j = static_cast<int>((xl - 1500) / 2);
      wrong += ValueAt(image, i, j) == static_cast<float>(z) ? 0 : 1;
      ++lines;
    }
    Check(lines == 12801 && wrong == 0, "heimdal: every line at its node");
  }

  // World placement instead of index numbers.
  reader->IndexCoordinatesOff();
  reader->SetOrigin(5000.0, 6000.0);
  reader->SetInlineSpacing(12.5);
  reader->SetCrosslineSpacing(25.0);
  reader->SetRotation(30.0);
  reader->Update();
  image = reader->GetOutput();
  o = image->GetOrigin();
  s = image->GetSpacing();
  Check(o[0] == 5000 && o[1] == 6000 && s[0] == 4 * 12.5 && s[1] == 2 * 25.0,
    "heimdal: world origin, spacing = step x bin size");
  Check(DirectionIs(image, 30.0, 1e-15), "heimdal: rotation 30 degrees");
  Check(ValueAt(image, 25, 125) == 2058.7f, "heimdal: values unchanged by the geometry");
}

void InlineCrossline(const std::string& outDir)
{
  // ---- Inline/crossline with header, comments, blank lines, CRLF, a hole, a null value ----
  const std::string text = "# Horizon export for the test\r\n"
                           "\r\n"
                           "inline xline twt\r\n"
                           "100 7 1000.5\r\n"
                           "100 10 1001.5\r\n"
                           "  # a comment in between\r\n"
                           "100 13 1002.5\r\n"
                           "102 7 1010.5\r\n"
                           "102 13 -999.25\r\n"
                           "104\t7\t1020.5\r\n"
                           "104,10,1021.5\r\n"
                           "104 13 1022.5 extra columns ignored\r\n";
  const std::string path = outDir + "TestHorizonColumnReader_indices.txt";
  Spit(path, text);
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetNullValue(-999.25);
  reader->SetArrayName("twt");
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(errors->Errors == 0 && errors->Warnings == 0, "indices: no errors");
  Check(reader->GetHasHeaderLine() && reader->GetDetectedMode() == Mode::InlineCrossline,
    "indices: header line, inline/crossline");
  Check(reader->GetNumberOfRecords() == 8, "indices: 8 data lines");
  Check(dims[0] == 3 && dims[1] == 3, "indices: 3 x 3 (inlines 100..104 step 2, xl 7..13 step 3)");
  Check(reader->GetInlineStep() == 2 && reader->GetCrosslineStep() == 3, "indices: steps 2, 3");
  Check(reader->GetNumberOfNoDataValues() == 2, "indices: missing 102/10 and null 102/13");
  if (image->GetNumberOfPoints() == 9)
  {
    Check(std::isnan(ValueAt(image, 1, 1)) && std::isnan(ValueAt(image, 1, 2)),
      "indices: holes are NaN");
    Check(ValueAt(image, 0, 0) == 1000.5 && ValueAt(image, 0, 2) == 1002.5 &&
            ValueAt(image, 1, 0) == 1010.5 && ValueAt(image, 2, 1) == 1021.5 &&
            ValueAt(image, 2, 2) == 1022.5,
      "indices: values");
    Check(
      std::string(image->GetPointData()->GetScalars()->GetName()) == "twt", "indices: array name");
  }
  reader->IndexCoordinatesOff();
  reader->SetRotation(90.0);
  reader->Update();
  Check(reader->GetOutput()->GetDirectionMatrix()->GetElement(0, 1) == -1.0 &&
          reader->GetOutput()->GetDirectionMatrix()->GetElement(1, 0) == 1.0,
    "indices: a 90 degree rotation is exact");

  // A duplicate node: warned about, the last line wins.
  Spit(path, text + "104 13 2000.0\n");
  reader->Modified();
  reader->Update();
  Check(errors->Warnings == 1 && reader->GetNumberOfDuplicates() == 1,
    "duplicate: one warning, counted");
  Check(ValueAt(reader->GetOutput(), 2, 2) == 2000.0, "duplicate: the last line wins");
}

void RotatedXYZ(const std::string& outDir)
{
  // ---- x y z on a grid rotated by 30 degrees, anisotropic spacing, one node missing ----
  const int nx = 7, ny = 5;
  const double ox = 456789.0, oy = 6543210.0, du = 25.0, dv = 12.5;
  const std::string text =
    RotatedGridText(nx, ny, ox, oy, du, dv, 30.0, 3 + 2 * nx, "%.3f,%.3f,%.2f\n", "x,y,z\n");
  const std::string path = outDir + "TestHorizonColumnReader_xyz30.txt";
  Spit(path, text);
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(errors->Errors == 0, "xyz 30: no errors");
  Check(reader->GetDetectedMode() == Mode::XYZ && reader->GetHasHeaderLine(), "xyz 30: XYZ");
  Check(dims[0] == nx && dims[1] == ny && dims[2] == 1, "xyz 30: 7 x 5 x 1");
  // Coordinates are printed with 3 decimals (error <= 0.0005 each), so the fit recovers the
  // generating grid to a few 1e-4.
  double* o = image->GetOrigin();
  double* s = image->GetSpacing();
  Check(Near(o[0], ox, 2e-3) && Near(o[1], oy, 2e-3), "xyz 30: origin");
  Check(Near(s[0], du, 1e-3) && Near(s[1], dv, 1e-3) && s[2] == 1.0, "xyz 30: spacing 25, 12.5");
  Check(Near(reader->GetGridRotation(), 30.0, 1e-3), "xyz 30: rotation 30 degrees");
  Check(DirectionIs(image, 30.0, 1e-5), "xyz 30: direction matrix");
  Check(reader->GetMaxDeviation() < 1e-3, "xyz 30: points within 1e-3 of their nodes");
  Check(reader->GetNumberOfNoDataValues() == 1, "xyz 30: one missing node");
  if (image->GetNumberOfPoints() == nx * ny)
  {
    Check(std::isnan(ValueAt(image, 3, 2)), "xyz 30: the missing node (3, 2) is NaN");
    Check(ValueAt(image, 6, 4) == static_cast<float>(1500.0 + 18 + 2), "xyz 30: node (6, 4)");
    Check(EveryPointOnItsNode(image, text, 1e-4), "xyz 30: every line at its node");
  }
}

void ReekRotationXYZ(const std::string& outDir)
{
  // ---- x y z on the Reek rotation (140 degrees), whitespace, no header ----
  const std::string text =
    RotatedGridText(6, 4, 468895.125, 5932889.5, 20.0, 20.0, 140.0, -1, "%.2f %.2f %.2f\n", "");
  const std::string path = outDir + "TestHorizonColumnReader_xyz140.txt";
  Spit(path, text);
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Check(errors->Errors == 0, "xyz 140: no errors");
  // The same lattice, labelled with the axis nearest world x: 140 - 180 = -40 degrees, which
  // turns the grid half around and keeps it 6 x 4.
  Check(dims[0] == 6 && dims[1] == 4, "xyz 140: 6 x 4");
  Check(Near(reader->GetGridRotation(), -40.0, 1e-3), "xyz 140: rotation -40 degrees");
  double* s = image->GetSpacing();
  Check(Near(s[0], 20.0, 1e-3) && Near(s[1], 20.0, 1e-3), "xyz 140: spacing 20");
  Check(reader->GetNumberOfNoDataValues() == 0, "xyz 140: no holes");
  Check(EveryPointOnItsNode(image, text, 1e-3), "xyz 140: every line at its node");
}

void BadInput(const std::string& dataDir, const std::string& outDir)
{
  // ---- Bad input ----
  CheckBadInput(outDir + "TestHorizonColumnReader_does_not_exist.txt", "missing file");
  {
    // Cut inside the crossline field of line 101: "      1300        17" has two numbers.
    const std::string heimdal = Slurp(dataDir + "top_heimdal_subset.txt");
    size_t at = 0;
    for (int line = 0; line < 100; ++line)
    {
      at = heimdal.find('\n', at) + 1;
    }
    Spit(outDir + "TestHorizonColumnReader_truncated.txt", heimdal.substr(0, at + 20));
    CheckBadInput(outDir + "TestHorizonColumnReader_truncated.txt", "truncated copy");
  }
  {
    std::string garbage;
    for (int k = 0; k < 3000; ++k)
    {
      garbage += static_cast<char>((k * 7919) % 251);
    }
    Spit(outDir + "TestHorizonColumnReader_garbage.txt", garbage);
    CheckBadInput(outDir + "TestHorizonColumnReader_garbage.txt", "garbage file");
  }
  Spit(outDir + "TestHorizonColumnReader_empty.txt", "");
  CheckBadInput(outDir + "TestHorizonColumnReader_empty.txt", "empty file");
  Spit(outDir + "TestHorizonColumnReader_header_only.txt", "# nothing\nx y z\n\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_header_only.txt", "header only");
  {
    // Points jittered by up to 30% of a cell: no regular grid within the 5% tolerance.
    std::string text;
    char line[128];
    for (int j = 0; j < 6; ++j)
    {
      for (int i = 0; i < 6; ++i)
      {
        const double jx = ((i * 7 + j * 13) % 11 - 5) * 0.06;
        const double jy = ((i * 5 + j * 3) % 7 - 3) * 0.1;
        std::snprintf(line, sizeof(line), "%.3f %.3f 1.0\n", 10.0 * (i + jx), 10.0 * (j + jy));
        text += line;
      }
    }
    Spit(outDir + "TestHorizonColumnReader_jitter.txt", text);
    CheckBadInput(outDir + "TestHorizonColumnReader_jitter.txt", "points off a regular grid");
  }
  Spit(outDir + "TestHorizonColumnReader_fractional.txt", "1.5 2 3\n2.5 2 3\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_fractional.txt",
    "non-integer indices in InlineCrossline mode",
    Mode::InlineCrossline);
  Spit(outDir + "TestHorizonColumnReader_sparse.txt", "1 1 3\n2 1 3\n2000000000 1 3\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_sparse.txt", "absurd index range");
  Spit(outDir + "TestHorizonColumnReader_float_range.txt", "1 1 3\n2 1 1e300\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_float_range.txt", "z beyond float's range");
  Spit(outDir + "TestHorizonColumnReader_same.txt", "5.5 6.5 1\n5.5 6.5 2\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_same.txt", "all points at one position");
}

/// z of the whitespace-matrix tests at row i, column j. Real: smooth and non-integer
/// everywhere, so no two nodes are equal; integer: what savetxt(fmt="%d") writes of integer
/// depths, whose first two values look like inline and crossline numbers.
double MatrixZ(int i, int j, bool integer)
{
  return integer ? 2000.0 + 3.0 * i + j : 2000.0 + 25.0 * std::sin(i / 7.0) + 0.3 * j + 0.001;
}

/// A 2-D array as numpy.savetxt writes it (delimiter " ", header "# ..."; fmt "%.18e", its
/// default, or "%d"): one line per row i, `cols` values per line; (holeI, holeJ) is "nan".
std::string SavetxtMatrix(int rows, int cols, bool integer, int holeI, int holeJ)
{
  std::string text = "# depth grid, rows = inlines, written by numpy.savetxt\n";
  char value[64];
  for (int i = 0; i < rows; ++i)
  {
    for (int j = 0; j < cols; ++j)
    {
      if (i == holeI && j == holeJ)
      {
        std::snprintf(value, sizeof(value), "%s", "nan");
      }
      else if (integer)
      {
        std::snprintf(value, sizeof(value), "%d", static_cast<int>(MatrixZ(i, j, true)));
      }
      else
      {
        std::snprintf(value, sizeof(value), "%.18e", MatrixZ(i, j, false));
      }
      text += (j ? " " : "") + std::string(value);
    }
    text += "\n";
  }
  return text;
}

/// Issue 14, defect 1: a numpy.savetxt matrix (40 rows of 300 values) used to become a small
/// wrong grid (integer values: the first two of each row taken as inline and crossline, 40 x 40
/// nodes for 40 "records") or an error about x y points (real values). It must be read as the
/// 40 x 300 matrix it is, every value in place, the one "nan" a hole, without error or warning.
void SavetxtMatrixAuto(const std::string& outDir, bool integer)
{
  const int rows = 40;
  const int cols = 300;
  const std::string tag = std::string("savetxt matrix (fmt ") + (integer ? "%d" : "%.18e") + ")";
  const std::string path =
    outDir + "TestHorizonColumnReader_savetxt" + (integer ? "_int" : "") + ".txt";
  Spit(path, SavetxtMatrix(rows, cols, integer, 5, 7));
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3] = { 0, 0, 0 };
  image->GetDimensions(dims);
  std::cout << tag << " " << rows << " x " << cols << ": " << errors->Errors << " error(s), "
            << errors->Warnings << " warning(s) " << errors->First << "; grid " << dims[0] << " x "
            << dims[1] << ", " << reader->GetNumberOfNoDataValues() << " no-data node(s)\n";
  Check(errors->Errors == 0 && errors->Warnings == 0, tag + ": no error, no warning");
  Check(dims[0] == rows && dims[1] == cols && dims[2] == 1,
    tag + ": the grid is rows x columns (40 x 300)");
  if (dims[0] != rows || dims[1] != cols)
  {
    return;
  }
  int wrong = 0;
  for (int i = 0; i < rows; ++i)
  {
    for (int j = 0; j < cols; ++j)
    {
      const double v = ValueAt(image, i, j);
      const bool hole = i == 5 && j == 7;
      wrong += (hole ? std::isnan(v) : v == static_cast<float>(MatrixZ(i, j, integer))) ? 0 : 1;
    }
  }
  std::cout << tag << ": " << wrong << " of " << rows * cols << " values wrong\n";
  Check(wrong == 0, tag + ": every value at (row, column), the nan a hole");
  Check(reader->GetNumberOfNoDataValues() == 1, tag + ": one no-data node");
}

/// Mode Matrix on a small matrix (too narrow for Auto to call it one) placed by Origin,
/// spacings and Rotation, with a NullValue hole; the same file in Auto mode is an error (read
/// as columns it would be a 6 x 6 grid of six nodes), and so is a ragged matrix in Matrix mode.
void MatrixMode(const std::string& outDir)
{
  const std::string path = outDir + "TestHorizonColumnReader_small_matrix.txt";
  std::string text = "# 6 x 5\n";
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 5; ++j)
    {
      text += std::to_string(i == 2 && j == 3 ? -999 : 100 + 10 * i + j) + (j < 4 ? " " : "\n");
    }
  }
  Spit(path, text);
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetModeToMatrix();
  reader->IndexCoordinatesOff();
  reader->SetOrigin(1000.0, 2000.0);
  reader->SetInlineSpacing(25.0);
  reader->SetCrosslineSpacing(12.5);
  reader->SetRotation(30.0);
  reader->SetNullValue(-999.0);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3] = { 0, 0, 0 };
  image->GetDimensions(dims);
  double p[3] = { 0, 0, 0 };
  const int ijk[3] = { 5, 4, 0 };
  image->TransformIndexToPhysicalPoint(ijk, p);
  // Node (5, 4): origin + 5 x 25 along 30 degrees + 4 x 12.5 along 120 degrees.
  const double a = vtkMath::RadiansFromDegrees(30.0);
  const double ex = 1000.0 + 125.0 * std::cos(a) - 50.0 * std::sin(a);
  const double ey = 2000.0 + 125.0 * std::sin(a) + 50.0 * std::cos(a);
  std::cout << "Matrix mode 6 x 5: grid " << dims[0] << " x " << dims[1] << ", node (5, 4) at "
            << p[0] << " " << p[1] << " (expected " << ex << " " << ey << "), value "
            << ValueAt(image, 5, 4) << ", " << reader->GetNumberOfNoDataValues() << " hole(s)\n";
  Check(errors->Errors == 0 && errors->Warnings == 0, "Matrix mode: no error, no warning");
  Check(dims[0] == 6 && dims[1] == 5, "Matrix mode: 6 lines x 5 values = 6 x 5 nodes");
  Check(reader->GetDetectedMode() == Mode::Matrix, "Matrix mode: detected mode Matrix");
  Check(dims[0] == 6 && ValueAt(image, 5, 4) == 154.0 && ValueAt(image, 1, 0) == 110.0 &&
          std::isnan(ValueAt(image, 2, 3)),
    "Matrix mode: (5, 4) = 154, (1, 0) = 110, (2, 3) a NullValue hole");
  Check(reader->GetNumberOfNoDataValues() == 1, "Matrix mode: one hole");
  Check(Near(p[0], ex, 1e-9) && Near(p[1], ey, 1e-9) && DirectionIs(image, 30.0, 1e-12),
    "Matrix mode: placed by Origin, InlineSpacing, CrosslineSpacing and Rotation");

  CheckBadInput(path, "6 x 5 matrix in Auto mode (as columns: 6 nodes of 36)");
  Spit(outDir + "TestHorizonColumnReader_ragged.txt", "1 2 3 4\n5 6 7 8\n9 10 11\n");
  CheckBadInput(outDir + "TestHorizonColumnReader_ragged.txt", "ragged matrix", Mode::Matrix);
  Spit(outDir + "TestHorizonColumnReader_text_matrix.txt", "1 2 3 4\n5 6 x 8\n");
  CheckBadInput(
    outDir + "TestHorizonColumnReader_text_matrix.txt", "matrix with a word", Mode::Matrix);
}

/// z of the DEM-export matrices at file row r (0 = the first line, the top), column c: quarter
/// units, exact in float, different at every node, not integer-valued.
double DemZ(int r, int c)
{
  return 1000.25 + 0.5 * c + 400.0 * r;
}

/// Node (c, r) of the DEM-export matrices that holds the header's no-data value.
bool DemHole(int r, int c)
{
  return (3 * r + 5 * c) % 17 == 7; // not (0, 0): the top-left value is checked alone
}

/// A matrix of heights as a DEM export writes it: a '#' header (`header`), then `rows` lines of
/// `cols` values each, the first line the top row (y = ymax), -9999 for no data.
std::string DemMatrix(int cols, int rows, const std::string& header)
{
  std::string text = header;
  char value[64];
  for (int r = 0; r < rows; ++r)
  {
    for (int c = 0; c < cols; ++c)
    {
      std::snprintf(value, sizeof(value), "%.2f", DemHole(r, c) ? -9999.0 : DemZ(r, c));
      text += (c ? " " : "") + std::string(value);
    }
    text += "\n";
  }
  return text;
}

/// Reads a DEM-export matrix of `cols` values per row and `rows` rows in Auto mode and checks
/// the grid against the file: dimensions, every node, holes, placement by the extents.
void CheckDemMatrix(const std::string& path,
  const std::string& tag,
  int cols,
  int rows,
  const double xExtent[2],
  const double yExtent[2])
{
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3] = { 0, 0, 0 };
  image->GetDimensions(dims);
  const double* o = image->GetOrigin();
  const double* s = image->GetSpacing();
  std::cout << tag << ": " << errors->Errors << " error(s), " << errors->Warnings << " warning(s) "
            << errors->First << "; grid " << dims[0] << " x " << dims[1] << " x " << dims[2]
            << ", origin " << o[0] << " " << o[1] << ", spacing " << s[0] << " " << s[1] << ", "
            << reader->GetNumberOfNoDataValues() << " hole(s)\n";
  Check(errors->Errors == 0 && errors->Warnings == 0, tag + ": no error, no warning");
  Check(reader->GetDetectedMode() == Mode::Matrix, tag + ": read as a matrix");
  Check(dims[0] == cols && dims[1] == rows && dims[2] == 1,
    tag + ": (values per row) x (rows) x 1 = " + std::to_string(cols) + " x " +
      std::to_string(rows) + " x 1");
  Check(reader->GetNX() == cols && reader->GetNY() == rows, tag + ": GetNX/GetNY agree");
  // The extents are the bounds of the nodes: the first value of a row at xmin, the last at xmax.
  const double dx = (xExtent[1] - xExtent[0]) / (cols - 1);
  const double dy = (yExtent[1] - yExtent[0]) / (rows - 1);
  Check(o[0] == xExtent[0] && o[1] == yExtent[0] && Near(s[0], dx, 1e-9 * dx) &&
          Near(s[1], dy, 1e-9 * dy) && s[2] == 1.0,
    tag + ": origin (xmin, ymin), spacing from the extents");
  Check(image->GetDirectionMatrix()->IsIdentity(), tag + ": no rotation");
  if (dims[0] != cols || dims[1] != rows)
  {
    return;
  }
  // The top-left value of the file (row 0, column 0) is node (0, ny - 1), at (xmin, ymax).
  double p[3] = { 0, 0, 0 };
  const int topLeft[3] = { 0, rows - 1, 0 };
  image->TransformIndexToPhysicalPoint(topLeft, p);
  Check(ValueAt(image, 0, rows - 1) == static_cast<float>(DemZ(0, 0)) &&
          Near(p[0], xExtent[0], 1e-6) && Near(p[1], yExtent[1], 1e-6),
    tag + ": the first value of the file is node (0, ny - 1), at (xmin, ymax)");
  int wrong = 0;
  int holes = 0;
  for (int j = 0; j < rows; ++j)
  {
    for (int i = 0; i < cols; ++i)
    {
      const int r = rows - 1 - j;
      const double v = ValueAt(image, i, j);
      const bool hole = DemHole(r, i);
      holes += hole ? 1 : 0;
      wrong += (hole ? std::isnan(v) : v == static_cast<float>(DemZ(r, i))) ? 0 : 1;
    }
  }
  std::cout << tag << ": " << wrong << " of " << cols * rows << " values wrong\n";
  Check(wrong == 0, tag + ": node (i, j) holds column i of row ny - 1 - j, nodata a hole (NaN)");
  Check(reader->GetNumberOfNoDataValues() == holes,
    tag + ": " + std::to_string(holes) + " no-data nodes");
}

/// Issue 27: the outside consumer's file, 327 values per row x 468 rows under a DEM export's
/// header ("key: value"), read in Auto mode.
void DemMatrixHeader(const std::string& outDir)
{
  const int cols = 327;
  const int rows = 468;
  const double xExtent[2] = { 500000.0, 500000.0 + 326 * 12.5 };
  const double yExtent[2] = { 6700000.0, 6700000.0 + 467 * 25.0 };
  char header[512];
  std::snprintf(header,
    sizeof(header),
    "# Heights exported from the DEM\n# Dimensions: %d %d\n# x_extent: %.2f %.2f\n"
    "# y_extent: %.2f %.2f\n# nodata: -9999\n",
    cols,
    rows,
    xExtent[0],
    xExtent[1],
    yExtent[0],
    yExtent[1]);
  const std::string path = outDir + "TestHorizonColumnReader_dem_327x468.txt";
  Spit(path, DemMatrix(cols, rows, header));
  CheckDemMatrix(path, "DEM matrix 327 x 468", cols, rows, xExtent, yExtent);
}

/// The same rules on 7 values per row x 5 rows, "key = value" lines: too narrow for Auto to take
/// for a matrix on its shape, its header says it is one.
void DemMatrixSmall(const std::string& outDir)
{
  const double xExtent[2] = { -30.0, 30.0 };
  const double yExtent[2] = { 100.0, 120.0 };
  const std::string path = outDir + "TestHorizonColumnReader_dem_7x5.txt";
  Spit(path,
    DemMatrix(
      7, 5, "# DIMENSIONS = 7 5\n# x_extent = -30 30\n# y_extent = 100 120\n# NODATA = -9999\n"));
  CheckDemMatrix(path, "DEM matrix 7 x 5", 7, 5, xExtent, yExtent);
}

/// Expects an error, no points and no grid (NX, NY zero) from a DEM-export matrix whose header
/// does not describe its data.
void CheckBadDemMatrix(const std::string& path, const std::string& what)
{
  CheckBadInput(path, what);
  vtkNew<vtkHorizonColumnReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  Check(errors->Errors > 0 && reader->GetNX() == 0 && reader->GetNY() == 0 &&
          reader->GetNumberOfRecords() == 0,
    what + ": nothing half-read (NX, NY, records zero after the information pass)");
}

/// Headers that disagree with their data: errors, nothing half-written.
void DemMatrixMismatch(const std::string& outDir)
{
  const std::string extents = "# x_extent: 0 60\n# y_extent: 0 40\n";
  const std::string transposed = outDir + "TestHorizonColumnReader_dem_transposed.txt";
  Spit(transposed, DemMatrix(327, 468, "# Dimensions: 468 327\n" + extents));
  CheckBadDemMatrix(transposed, "Dimensions 468 327 over 327 values per row x 468 rows");
  const std::string rows = outDir + "TestHorizonColumnReader_dem_rows.txt";
  Spit(rows, DemMatrix(7, 5, "# Dimensions: 7 6\n" + extents));
  CheckBadDemMatrix(rows, "Dimensions 7 6 over 7 x 5");
  const std::string half = outDir + "TestHorizonColumnReader_dem_half.txt";
  Spit(half, DemMatrix(7, 5, "# Dimensions: 7 5\n# x_extent: 0 60\n"));
  CheckBadDemMatrix(half, "x_extent without y_extent");
  const std::string bad = outDir + "TestHorizonColumnReader_dem_bad_key.txt";
  Spit(bad, DemMatrix(7, 5, "# Dimensions: 7\n" + extents));
  CheckBadDemMatrix(bad, "Dimensions with one number");
}

void PrintSelf()
{
  vtkNew<vtkHorizonColumnReader> printed;
  printed->Print(std::cout);
}

}

int TestHorizonColumnReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dataDir = paths.Data + "/horizons/";
  const std::string outDir = paths.Output + "/";
  strata_test::RunSubTests(
    {
      { "TopHeimdal", [&] { TopHeimdal(dataDir); } },
      { "InlineCrossline", [&] { InlineCrossline(outDir); } },
      { "RotatedXYZ", [&] { RotatedXYZ(outDir); } },
      { "ReekRotationXYZ", [&] { ReekRotationXYZ(outDir); } },
      { "BadInput", [&] { BadInput(dataDir, outDir); } },
      { "SavetxtMatrixAuto", [&] { SavetxtMatrixAuto(outDir, false); } },
      { "SavetxtMatrixAutoInteger", [&] { SavetxtMatrixAuto(outDir, true); } },
      { "MatrixMode", [&] { MatrixMode(outDir); } },
      { "DemMatrixHeader", [&] { DemMatrixHeader(outDir); } },
      { "DemMatrixSmall", [&] { DemMatrixSmall(outDir); } },
      { "DemMatrixMismatch", [&] { DemMatrixMismatch(outDir); } },
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

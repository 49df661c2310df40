// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkAsciiGridReader on files written here, one per format, from an analytic horizon
// z(x, y) = 1800 + 40 sin(x / 900) + 25 cos(y / 700) + 0.01 x evaluated at each node's world
// position, which this test computes itself from the geometry it writes (origin, spacing,
// rotation, corner or centre). Each value is printed with 6 decimals, so the expected value of a
// node is the float nearest to that printed number. Checked for each format: the detected
// format, every header field, the output geometry (the world positions of the four corner nodes
// against this test's own), every node's value, and the number of holes against the count of
// no-data values written:
// - Irap classic ASCII, 37 x 23, rotated 30 degrees, UTM-sized origin, 9999900 holes;
// - ZMAP+, 31 columns x 19 rows, comments, column-major from the top, null -99999; and one
//   whose values fill their 10-character fields and touch;
// - ESRI ASCII with xllcorner and cellsize (nodes at cell centres) and with xllcenter, dx, dy;
// - a numpy.savetxt matrix, both axis conventions, placed by Origin, Spacing and Rotation;
// - a matrix under a DEM export's header (Dimensions, x_extent, y_extent, nodata): a raster,
//   rows from the top, placed by the header (issue 27).
// Absurd and malformed headers (issue 14): dimensions that overflow, exceed 2^31 nodes, or need
// far more values than the file holds are errors naming the header field, raised before the
// values are allocated (peak RSS grows by less than 64 MB, where 2 x 10^9 float nodes would take
// 8 GB); truncated data, extra values, unknown ESRI keys, a broken ZMAP+ header, binary garbage,
// an empty and a missing file, a value beyond float's range, and "inline crossline z" columns in
// Auto mode (not taken for a 3-column matrix) are errors with an empty output. A byte order mark
// before an ESRI header is skipped.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkAsciiGridReader.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;
using Format = vtkAsciiGridReader::GridFormat;

double Horizon(double x, double y)
{
  return 1800.0 + 40.0 * std::sin(x / 900.0) + 25.0 * std::cos(y / 700.0) + 0.01 * x;
}

/// Holes of the test grids: about one node in eleven.
bool IsHole(int i, int j)
{
  return (i * 7 + j * 3) % 11 == 0;
}

/// A grid as this test lays it out: node (i, j) at origin + rotation (i dx, j dy).
struct Layout
{
  int NX, NY;
  double X0, Y0, DX, DY, Degrees;

  void World(int i, int j, double& x, double& y) const
  {
    const double a = vtkMath::RadiansFromDegrees(this->Degrees);
    x = this->X0 + std::cos(a) * i * this->DX - std::sin(a) * j * this->DY;
    y = this->Y0 + std::sin(a) * i * this->DX + std::cos(a) * j * this->DY;
  }

  /// The value written for node (i, j), as printed ("%.6f"), or `null` at a hole.
  std::string Text(int i, int j, const char* null) const
  {
    if (IsHole(i, j))
    {
      return null;
    }
    double x, y;
    this->World(i, j, x, y);
    char s[64];
    std::snprintf(s, sizeof(s), "%.6f", Horizon(x, y));
    return s;
  }

  int Holes() const
  {
    int n = 0;
    for (int j = 0; j < this->NY; ++j)
    {
      for (int i = 0; i < this->NX; ++i)
      {
        n += IsHole(i, j) ? 1 : 0;
      }
    }
    return n;
  }
};

void Spit(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

bool Near(double a, double b, double tol)
{
  return std::fabs(a - b) <= tol;
}

/// Reads `path`, checks the output against `layout` (geometry of the corner nodes, every value,
/// holes) and returns the reader for the format-specific header checks.
vtkSmartPointer<vtkAsciiGridReader> ReadAndCompare(const std::string& path,
  const Layout& layout,
  Format expected,
  const std::string& tag,
  void (*setup)(vtkAsciiGridReader*) = nullptr)
{
  auto reader = vtkSmartPointer<vtkAsciiGridReader>::New();
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  if (setup)
  {
    setup(reader);
  }
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3] = { 0, 0, 0 };
  image->GetDimensions(dims);
  Check(errors->Errors == 0 && errors->Warnings == 0, tag + ": no error, no warning");
  Check(reader->GetDetectedFormat() == expected, tag + ": format detected");
  Check(dims[0] == layout.NX && dims[1] == layout.NY && dims[2] == 1,
    tag + ": " + std::to_string(layout.NX) + " x " + std::to_string(layout.NY) + " x 1 nodes");
  if (dims[0] != layout.NX || dims[1] != layout.NY)
  {
    std::cout << tag << ": " << errors->First << "\n";
    return reader;
  }
  double worstPosition = 0.0;
  for (int corner = 0; corner < 4; ++corner)
  {
    const int ijk[3] = { corner % 2 ? layout.NX - 1 : 0, corner / 2 ? layout.NY - 1 : 0, 0 };
    double p[3], x, y;
    image->TransformIndexToPhysicalPoint(ijk, p);
    layout.World(ijk[0], ijk[1], x, y);
    worstPosition = std::max(worstPosition, std::hypot(p[0] - x, p[1] - y));
  }
  vtkDataArray* values = image->GetPointData()->GetScalars();
  int wrong = 0;
  for (int j = 0; j < layout.NY; ++j)
  {
    for (int i = 0; i < layout.NX; ++i)
    {
      const double v = values->GetComponent(i + j * layout.NX, 0);
      const float want =
        IsHole(i, j) ? std::nanf("")
                     : static_cast<float>(std::strtod(layout.Text(i, j, "").c_str(), nullptr));
      wrong += (IsHole(i, j) ? std::isnan(v) : v == want) ? 0 : 1;
    }
  }
  std::cout << tag << ": " << dims[0] << " x " << dims[1] << ", corner nodes off by at most "
            << worstPosition << ", " << wrong << " of " << layout.NX * layout.NY
            << " values wrong, " << reader->GetNumberOfNoDataValues() << " holes (written "
            << layout.Holes() << ")\n";
  // Positions: the reader's double origin plus index times spacing, rotated, against this
  // test's own evaluation of the same sum; a few ulps of 7e6.
  Check(worstPosition < 1e-6, tag + ": corner nodes where the header puts them");
  Check(wrong == 0, tag + ": every node's value, holes NaN");
  Check(reader->GetNumberOfNoDataValues() == layout.Holes(), tag + ": hole count");
  Check(std::string(values->GetName()) == "depth", tag + ": array \"depth\"");
  return reader;
}

//------------------------------------------------------------------------------
void IrapClassic(const std::string& dir)
{
  const Layout g{ 37, 23, 456000.5, 6780000.25, 25.0, 12.5, 30.0 };
  char line[256];
  std::string text;
  std::snprintf(line, sizeof(line), "-996 %d %f %f\n", g.NY, g.DX, g.DY);
  text += line;
  std::snprintf(line,
    sizeof(line),
    "%f %f %f %f\n",
    g.X0,
    g.X0 + (g.NX - 1) * g.DX,
    g.Y0,
    g.Y0 + (g.NY - 1) * g.DY);
  text += line;
  std::snprintf(
    line, sizeof(line), "%d %f %f %f\n0  0  0  0  0  0  0\n", g.NX, g.Degrees, g.X0, g.Y0);
  text += line;
  int k = 0;
  for (int j = 0; j < g.NY; ++j)
  {
    for (int i = 0; i < g.NX; ++i, ++k)
    {
      text += g.Text(i, j, "9999900.000000") + (k % 6 == 5 ? "\n" : " ");
    }
  }
  const std::string path = dir + "/irap_classic.fgr";
  Spit(path, text + "\n");
  const std::string tag = "Irap classic";
  Check(vtkAsciiGridReader::DetectFormat(path.c_str()) == Format::IrapClassic &&
          vtkAsciiGridReader::CanReadFile(path.c_str()),
    tag + ": DetectFormat and CanReadFile");
  auto r = ReadAndCompare(path, g, Format::IrapClassic, tag);
  Check(r->GetNX() == 37 && r->GetNY() == 23 && r->GetGridOrigin()[0] == 456000.5 &&
          r->GetGridOrigin()[1] == 6780000.25 && r->GetGridSpacing()[0] == 25.0 &&
          r->GetGridSpacing()[1] == 12.5 && r->GetGridRotation() == 30.0,
    tag + ": nx, ny, xori, yori, xinc, yinc, rotation");
  const double* b = r->GetHeaderBounds();
  Check(b[0] == 456000.5 && b[1] == 456900.5 && b[2] == 6780000.25 && b[3] == 6780275.25,
    tag + ": xmin xmax ymin ymax as written");
  Check(r->GetFileNullValue() == 9999900.0, tag + ": no-data value 9999900");
}

//------------------------------------------------------------------------------
void Zmap(const std::string& dir)
{
  const Layout g{ 31, 19, 1000.0, 2000.0, 50.0, 40.0, 0.0 };
  std::string text = "! ZMAP+ grid written by TestAsciiGridReader\n!\n"
                     "@testgrid HEADER, GRID, 5\n"
                     "     15, -99999.0000000,  , 7, 1\n";
  char line[256];
  std::snprintf(line,
    sizeof(line),
    "%d, %d, %f, %f, %f, %f\n",
    g.NY,
    g.NX,
    g.X0,
    g.X0 + (g.NX - 1) * g.DX,
    g.Y0,
    g.Y0 + (g.NY - 1) * g.DY);
  text += line;
  text += "0.0, 0.0, 0.0\n@\n";
  // Column-major, each column from the top (max Y) down; 5 nodes per line, width 15.
  int k = 0;
  for (int i = 0; i < g.NX; ++i)
  {
    for (int j = g.NY - 1; j >= 0; --j, ++k)
    {
      char field[32];
      std::snprintf(field, sizeof(field), "%15s", g.Text(i, j, "-99999.0000000").c_str());
      text += field;
      text += k % 5 == 4 ? "\n" : "";
    }
  }
  const std::string path = dir + "/grid.zmap";
  Spit(path, text + "\n");
  const std::string tag = "ZMAP+";
  auto r = ReadAndCompare(path, g, Format::Zmap, tag);
  Check(r->GetNX() == 31 && r->GetNY() == 19 && r->GetGridOrigin()[0] == 1000.0 &&
          r->GetGridOrigin()[1] == 2000.0 && r->GetGridSpacing()[0] == 50.0 &&
          r->GetGridSpacing()[1] == 40.0 && r->GetGridRotation() == 0.0,
    tag + ": columns, rows, origin (min X, min Y), spacing (max - min) / (n - 1), no rotation");
  const double* b = r->GetHeaderBounds();
  Check(b[0] == 1000.0 && b[1] == 2500.0 && b[2] == 2000.0 && b[3] == 2720.0,
    tag + ": min X, max X, min Y, max Y");
  Check(r->GetFileNullValue() == -99999.0 && r->GetNodesPerLine() == 5 &&
          std::string(r->GetGridName()) == "testgrid HEADER",
    tag + ": null value -99999, 5 nodes per line, name \"testgrid HEADER\"");
}

/// ZMAP+ values that fill their field width touch ("-1234.5678-1234.5678"): read by the width.
void ZmapFixedWidth(const std::string& dir)
{
  // 3 columns x 4 rows, width 10, 3 nodes per line; node (i, j) = -1000 - 100 i - 10 j - 0.5678,
  // node (1, 2) the null value.
  std::string text = "@fixed HEADER, GRID, 3\n10, -99999.000, , 4, 1\n4, 3, 0, 20, 0, 30\n"
                     "0.0, 0.0, 0.0\n@\n";
  int k = 0;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 3; j >= 0; --j, ++k)
    {
      char field[16];
      std::snprintf(field, sizeof(field), "%10.4f", -1000.0 - 100 * i - 10 * j - 0.5678);
      text += i == 1 && j == 2 ? "-99999.000" : field;
      text += k % 3 == 2 ? "\n" : "";
    }
  }
  const std::string path = dir + "/fixed.zmap";
  Spit(path, text + "\n");
  vtkNew<vtkAsciiGridReader> r;
  vtkNew<ErrorCounter> errors;
  errors->Watch(r);
  r->SetFileName(path.c_str());
  r->Update();
  vtkDataArray* v = r->GetOutput()->GetPointData()->GetScalars();
  int wrong = v ? 0 : 12;
  for (int j = 0; v && j < 4; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      const float want = static_cast<float>(-1000.0 - 100 * i - 10 * j - 0.5678);
      const double got = v->GetComponent(i + 3 * j, 0);
      wrong += (i == 1 && j == 2) ? (std::isnan(got) ? 0 : 1) : (got == want ? 0 : 1);
    }
  }
  std::cout << "ZMAP+ fixed width (touching values): " << r->GetNX() << " x " << r->GetNY() << ", "
            << wrong << " of 12 values wrong, " << r->GetNumberOfNoDataValues() << " hole(s), "
            << errors->Errors << " error(s) " << errors->First << "\n";
  Check(errors->Errors == 0 && wrong == 0 && r->GetNumberOfNoDataValues() == 1,
    "ZMAP+ with touching fields: read by the field width, every value, one hole");
}

//------------------------------------------------------------------------------
void EsriAscii(const std::string& dir)
{
  for (const bool corner : { true, false })
  {
    // Corner: 29 x 17 cells of 30 m from (300000, 5000000); nodes at the centres. Centre: the
    // first centre given, cells of 20 x 10.
    const Layout g = corner ? Layout{ 29, 17, 300015.0, 5000015.0, 30.0, 30.0, 0.0 }
                            : Layout{ 23, 13, 512345.5, 4100000.0, 20.0, 10.0, 0.0 };
    char line[512];
    std::snprintf(line,
      sizeof(line),
      corner ? "ncols        %d\nnrows        %d\nxllcorner    300000\nyllcorner    5000000\n"
               "cellsize     30\nNODATA_value -9999\n"
             : "NCOLS %d\nNROWS %d\nXLLCENTER 512345.5\nYLLCENTER 4100000\nDX 20\nDY 10\n"
               "NODATA_VALUE -9999\n",
      g.NX,
      g.NY);
    std::string text = line;
    for (int j = g.NY - 1; j >= 0; --j) // rows from the top
    {
      for (int i = 0; i < g.NX; ++i)
      {
        text += (i ? " " : "") + g.Text(i, j, "-9999");
      }
      text += "\n";
    }
    const std::string path = dir + (corner ? "/corner.asc" : "/centre.asc");
    Spit(path, (corner ? "" : "\xEF\xBB\xBF") + text); // the centre file with a UTF-8 BOM
    const std::string tag =
      corner ? "ESRI ASCII (xllcorner, cellsize)" : "ESRI ASCII (xllcenter, dx dy)";
    auto r = ReadAndCompare(path, g, Format::EsriAscii, tag);
    Check(r->GetNX() == g.NX && r->GetNY() == g.NY && r->GetGridOrigin()[0] == g.X0 &&
            r->GetGridOrigin()[1] == g.Y0 && r->GetGridSpacing()[0] == g.DX &&
            r->GetGridSpacing()[1] == g.DY && r->GetCellCorner() == corner &&
            r->GetFileNullValue() == -9999.0,
      tag + ": ncols, nrows, first cell centre, cell size, corner flag, NODATA_value");
    const double* b = r->GetHeaderBounds();
    Check(b[0] == g.X0 && b[1] == g.X0 + (g.NX - 1) * g.DX && b[2] == g.Y0 &&
            b[3] == g.Y0 + (g.NY - 1) * g.DY,
      tag + ": bounds of the cell centres");
  }
}

//------------------------------------------------------------------------------
void Matrix(const std::string& dir)
{
  // 13 lines of 11 values; as a matrix the file has no geometry: Origin, Spacing, Rotation.
  for (const bool swap : { false, true })
  {
    const Layout g = swap ? Layout{ 11, 13, 500.0, 700.0, 2.0, 3.0, -20.0 }
                          : Layout{ 13, 11, 500.0, 700.0, 2.0, 3.0, -20.0 };
    std::string text = "# 13 x 11 matrix, numpy.savetxt(fmt=\"%.6f\")\n";
    for (int line = 0; line < 13; ++line)
    {
      for (int value = 0; value < 11; ++value)
      {
        // Without SwapAxes line r is i = r; with it line r is j = r.
        text +=
          (value ? " " : "") + (swap ? g.Text(value, line, "nan") : g.Text(line, value, "nan"));
      }
      text += "\n";
    }
    const std::string path = dir + (swap ? "/matrix_swapped.txt" : "/matrix.txt");
    Spit(path, text);
    const std::string tag = swap ? "matrix (SwapAxes)" : "matrix";
    auto setup = swap ? +[](vtkAsciiGridReader* r)
    {
      r->SetOrigin(500.0, 700.0);
      r->SetSpacing(2.0, 3.0);
      r->SetRotation(-20.0);
      r->SwapAxesOn();
    }
                      : +[](vtkAsciiGridReader* r)
    {
      r->SetOrigin(500.0, 700.0);
      r->SetSpacing(2.0, 3.0);
      r->SetRotation(-20.0);
    };
    auto r = ReadAndCompare(path, g, Format::Matrix, tag, setup);
    Check(std::isnan(r->GetFileNullValue()) && !vtkAsciiGridReader::CanReadFile(path.c_str()),
      tag + ": no file null value; CanReadFile leaves matrices to an explicit choice");
  }
}

/// Format detection looks at the first 64 KiB: rows of 6000 values in "%.18e" (150 KB a line)
/// must still be detected as a matrix, with the line cut mid-number inside that window.
void LongRows(const std::string& dir)
{
  std::string text;
  char value[64];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 6000; ++j)
    {
      std::snprintf(value, sizeof(value), "%.18e", 1000.0 + i + j / 8.0);
      text += (j ? " " : "") + std::string(value);
    }
    text += "\n";
  }
  const std::string path = dir + "/long_rows.txt";
  Spit(path, text);
  vtkNew<vtkAsciiGridReader> r;
  vtkNew<ErrorCounter> errors;
  errors->Watch(r);
  r->SetFileName(path.c_str());
  r->Update();
  vtkDataArray* v = r->GetOutput()->GetPointData()->GetScalars();
  std::cout << "rows of 6000 values: detected "
            << static_cast<int>(vtkAsciiGridReader::DetectFormat(path.c_str())) << ", grid "
            << r->GetNX() << " x " << r->GetNY() << ", " << errors->Errors << " error(s)\n";
  Check(errors->Errors == 0 && r->GetDetectedFormat() == Format::Matrix && r->GetNX() == 3 &&
          r->GetNY() == 6000 && v &&
          v->GetComponent(2 + 3 * 5999, 0) == static_cast<float>(1002.0 + 5999 / 8.0),
    "rows of 6000 values (150 KB lines): a 3 x 6000 matrix, node (2, 5999) = 1751.875");
}

//------------------------------------------------------------------------------
/// `text` as `name` must give an error whose message contains `field`, and no points.
void CheckBad(const std::string& dir,
  const std::string& name,
  const std::string& text,
  const std::string& field,
  Format format = Format::Auto)
{
  const std::string path = dir + "/" + name;
  if (!text.empty() || name != "missing.asc")
  {
    Spit(path, text);
  }
  vtkNew<vtkAsciiGridReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetFormat(format);
  const double before = strata_test::PeakRssMB();
  reader->Update();
  const double grown = strata_test::PeakRssMB() - before;
  std::cout << name << ": " << errors->Errors << " error(s), peak RSS +" << grown
            << " MB: " << errors->First << "\n";
  Check(errors->Errors > 0 && errors->First.find(field) != std::string::npos,
    name + ": an error naming \"" + field + "\"");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0, name + ": no points");
  Check(grown < 64.0, name + ": nothing allocated for the values (peak RSS + < 64 MB)");
}

/// Issue 27: a matrix of heights under a DEM export's header is a raster, read by the same rule
/// as vtkHorizonColumnReader's: 7 values per line x 5 lines is 7 x 5 nodes, the first line the
/// top row, placed by the extents (node bounds) whatever Origin, Spacing, Rotation and SwapAxes
/// say, nodata a hole; taken for a matrix in Auto mode although its lines are narrow. Dimensions
/// the other way round are an error.
void MatrixRasterHeader(const std::string& dir)
{
  const Layout g{ 7, 5, -30.0, 100.0, 10.0, 5.0, 0.0 };
  std::string text = "# Heights\n# Dimensions: 7 5\n# x_extent: -30 30\n# y_extent = 100 120\n"
                     "# NODATA_value: -9999\n";
  for (int line = 0; line < g.NY; ++line)
  {
    for (int i = 0; i < g.NX; ++i)
    {
      text += (i ? " " : "") + g.Text(i, g.NY - 1 - line, "-9999");
    }
    text += "\n";
  }
  const std::string path = dir + "/matrix_raster.txt";
  Spit(path, text);
  auto setup = +[](vtkAsciiGridReader* r)
  {
    r->SetOrigin(500.0, 700.0);
    r->SetSpacing(2.0, 3.0);
    r->SetRotation(-20.0);
    r->SwapAxesOn();
  };
  auto r = ReadAndCompare(path, g, Format::Matrix, "matrix with a raster header", setup);
  const double* b = r->GetHeaderBounds();
  Check(r->GetFileNullValue() == -9999.0 && b[0] == -30.0 && b[1] == 30.0 && b[2] == 100.0 &&
          b[3] == 120.0 && r->GetGridRotation() == 0.0,
    "matrix with a raster header: nodata and extents from the header, no rotation");
  std::string transposed = text;
  transposed.replace(transposed.find("7 5"), 3, "5 7");
  CheckBad(dir, "matrix_raster_transposed.txt", transposed, "Dimensions 5 7");
}

void AbsurdHeaders(const std::string& dir)
{
  const std::string irapTail = "0 0 0 0 0 0 0\n1 2 3 4\n";
  CheckBad(dir,
    "irap_nx_overflow.fgr",
    "-996 10 25 25\n0 1 0 1\n3000000000 0 0 0\n" + irapTail,
    "nx = 3000000000");
  CheckBad(dir,
    "irap_terabytes.fgr",
    "-996 1000000 25 25\n0 1 0 1\n1000000 0 0 0\n" + irapTail,
    "nx x ny = 1000000 x 1000000");
  CheckBad(dir, "irap_negative.fgr", "-996 -4 25 25\n0 1 0 1\n10 0 0 0\n" + irapTail, "ny = -4");
  CheckBad(dir, "irap_xinc.fgr", "-996 2 0 25\n0 1 0 1\n2 0 0 0\n" + irapTail, "xinc = 0");
  // 2 x 10^9 nodes (8 GB of floats) is below 2^31, but the file holds a few bytes of values.
  CheckBad(dir,
    "esri_bigger_than_file.asc",
    "ncols 50000\nnrows 40000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
    "ncols x nrows = 50000 x 40000");
  CheckBad(dir,
    "zmap_overflow.zmap",
    "@g HEADER, GRID, 5\n15, 1e30, , 7, 1\n99999999999, 5, 0, 1, 0, 1\n0.0, 0.0, 0.0\n@\n1 2\n",
    "rows = 99999999999");
  CheckBad(dir,
    "zmap_product.zmap",
    "@g HEADER, GRID, 5\n15, 1e30, , 7, 1\n2000000, 2000000, 0, 1, 0, 1\n0.0, 0.0, 0.0\n@\n1\n",
    "columns x rows = 2000000 x 2000000");
}

void BadInput(const std::string& dir)
{
  CheckBad(dir, "missing.asc", "", "does not exist");
  CheckBad(dir, "empty.asc", "", "not a text grid");
  std::string garbage;
  for (int k = 0; k < 3000; ++k)
  {
    garbage += static_cast<char>((k * 7919) % 251);
  }
  CheckBad(dir, "garbage.asc", garbage, "NUL bytes");
  CheckBad(dir,
    "esri_truncated.asc",
    "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1.5 2.5 3.5\n4.5 5.5\n",
    "ends after 5 of the 6 values");
  CheckBad(dir,
    "esri_extra.asc",
    "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n7\n",
    "more values than the 6");
  CheckBad(dir,
    "esri_key.asc",
    "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2 3\n4 5 6\n",
    "unknown ESRI ASCII grid header key \"celsize\"");
  CheckBad(dir,
    "esri_no_cellsize.asc",
    "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3\n4 5 6\n",
    "needs ncols, nrows");
  CheckBad(dir,
    "zmap_no_grid.zmap",
    "@g HEADER, POINT, 5\n15, 1e30, , 7, 1\n2, 2, 0, 1, 0, 1\n0.0, 0.0, 0.0\n@\n1 2 3 4\n",
    "expected the ZMAP+ header");
  CheckBad(dir,
    "zmap_no_end.zmap",
    "@g HEADER, GRID, 5\n15, 1e30, , 7, 1\n2, 2, 0, 1, 0, 1\n0.0, 0.0, 0.0\n1 2 3 4\n",
    "expected the '@' that ends");
  CheckBad(dir,
    "zmap_word.zmap",
    "@g HEADER, GRID, 5\n15, 1e30, , 7, 1\n2, 2, 0, 1, 0, 1\n0.0, 0.0, 0.0\n@\n1 2 x 4\n",
    "value 3 is \"x\"");
  CheckBad(dir,
    "irap_truncated.fgr",
    "-996 2 25 25\n0 1 0 1\n2 0 0 0\n0 0 0 0 0 0 0\n1.5 2.5 3.5\n",
    "ends after 3 of the 4 values");
  CheckBad(dir, "irap_header_cut.fgr", "-996 2 25 25\n0 1 0 1\n2 0\n", "before xori");
  CheckBad(dir, "not_irap.fgr", "-995 2 25 25\n", "not an Irap classic grid", Format::IrapClassic);
  CheckBad(dir,
    "esri_float_range.asc",
    "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1.5 1e300 3.5\n",
    "1 value(s) beyond the range of float");
  CheckBad(dir,
    "columns.txt",
    "1300 1500 2.5\n1300 1502 2.75\n1304 1500 3.0\n",
    "every line holds 3 numbers");
}

void PrintSelf()
{
  vtkNew<vtkAsciiGridReader> printed;
  printed->Print(std::cout);
}
}

int TestAsciiGridReader(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dir = paths.Output + "/TestAsciiGridReader";
  vtksys::SystemTools::MakeDirectory(dir);
  return strata_test::RunSubTests(
    {
      { "IrapClassic", [&] { IrapClassic(dir); } },
      { "Zmap", [&] { Zmap(dir); } },
      { "ZmapFixedWidth", [&] { ZmapFixedWidth(dir); } },
      { "EsriAscii", [&] { EsriAscii(dir); } },
      { "Matrix", [&] { Matrix(dir); } },
      { "MatrixRasterHeader", [&] { MatrixRasterHeader(dir); } },
      { "LongRows", [&] { LongRows(dir); } },
      { "AbsurdHeaders", [&] { AbsurdHeaders(dir); } },
      { "BadInput", [&] { BadInput(dir); } },
      { "PrintSelf", PrintSelf },
    },
    strata_test::Failures);
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHorizonColumnReader.h"
#include "vtkStrataAsciiGridParser.h"
#include "vtkStrataGridReaderUtilities.h"

#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkHorizonColumnReader);

namespace
{
using strata_io::ClearOutput;
using strata_io::SetGridGeometry;
using strata_io::SetGridInformation;
using ColumnMode = vtkHorizonColumnReader::ColumnMode;

// Same bound as the other horizon readers: 2^31 nodes or more is not a horizon.
constexpr long long MaxNodes = 2147483647LL;
// A grid may have holes, but one with far more nodes than data lines means the columns were
// misread (world coordinates taken as indices, or one stray point far away). Up to this many
// nodes are always accepted...
constexpr long long DenseFloor = 1LL << 24;
// ...and beyond it at most this many nodes per data line.
constexpr long long SparseFactor = 64;
// Index columns must be integers that a double holds exactly.
constexpr double MaxIndexMagnitude = 9007199254740992.0; // 2^53

struct Record
{
  double A; // inline or x
  double B; // crossline or y
  double Z;
  long long Line; // 1-based line number, for messages
};

const char* ModeName(ColumnMode mode)
{
  switch (mode)
  {
    case ColumnMode::InlineCrossline:
      return "InlineCrossline";
    case ColumnMode::XYZ:
      return "XYZ";
    case ColumnMode::Matrix:
      return "Matrix";
    default:
      return "Auto";
  }
}

bool IsSeparator(char c)
{
  return c == ',' || c == ';' || std::isspace(static_cast<unsigned char>(c));
}

/// A whole token as a number, locale-independent ("1.5", "-2e3", "nan"; a leading '+' too).
bool ParseNumber(const char* begin, const char* end, double& value)
{
  if (begin < end && *begin == '+')
  {
    ++begin;
  }
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && begin < end;
}

/// Splits a line at runs of separators.
void Tokenize(const std::string& line, std::vector<std::pair<size_t, size_t>>& tokens)
{
  tokens.clear();
  size_t k = 0;
  const size_t n = line.size();
  while (k < n)
  {
    while (k < n && IsSeparator(line[k]))
    {
      ++k;
    }
    const size_t start = k;
    while (k < n && !IsSeparator(line[k]))
    {
      ++k;
    }
    if (k > start)
    {
      tokens.emplace_back(start, k);
    }
  }
}

std::string Lower(std::string s)
{
  s.erase(
    std::remove_if(s.begin(), s.end(), [](char c) { return c == '"' || c == '\''; }), s.end());
  std::transform(s.begin(),
    s.end(),
    s.begin(),
    [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  return s;
}

/// The mode that header names announce, or Auto when they say nothing clear.
ColumnMode ModeFromHeader(const std::vector<std::string>& names)
{
  if (names.size() < 2)
  {
    return ColumnMode::Auto;
  }
  const std::string a = Lower(names[0]);
  const std::string b = Lower(names[1]);
  auto in = [](const std::string& s, std::initializer_list<const char*> list)
  { return std::any_of(list.begin(), list.end(), [&](const char* w) { return s == w; }); };
  if (in(a, { "inline", "iline", "il", "in-line", "inl", "line" }) &&
      in(b, { "crossline", "xline", "xl", "cross-line", "crl", "trace", "cdp" }))
  {
    return ColumnMode::InlineCrossline;
  }
  if (in(a, { "x", "easting", "east", "utmx", "utm_x", "x_utm", "cdp_x" }) &&
      in(b, { "y", "northing", "north", "utmy", "utm_y", "y_utm", "cdp_y" }))
  {
    return ColumnMode::XYZ;
  }
  return ColumnMode::Auto;
}

bool IsIndexValue(double v)
{
  return std::isfinite(v) && std::floor(v) == v && std::fabs(v) < MaxIndexMagnitude;
}

/// Checks nx * ny against the absolute and the sparseness bounds.
bool CheckGridSize(long long nx, long long ny, size_t records, std::string& error)
{
  std::ostringstream msg;
  if (nx <= 0 || ny <= 0 || nx > MaxNodes || ny > MaxNodes || nx > MaxNodes / ny)
  {
    msg << "absurd grid dimensions " << nx << " x " << ny << " (need 0 < nx * ny < 2^31)";
    error = msg.str();
    return false;
  }
  const long long limit = std::max(DenseFloor, SparseFactor * static_cast<long long>(records));
  if (nx * ny > limit)
  {
    msg << "the columns span a grid of " << nx << " x " << ny << " nodes for only " << records
        << " data lines: the first two columns are probably not what the mode assumes";
    error = msg.str();
    return false;
  }
  return true;
}

/// Distinct values of an index column, their smallest value, gcd step and count.
bool IndexAxis(const std::vector<Record>& records,
  bool first,
  long long& start,
  long long& step,
  long long& count)
{
  std::vector<long long> values;
  values.reserve(records.size());
  for (const Record& r : records)
  {
    values.push_back(static_cast<long long>(first ? r.A : r.B));
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  start = values.front();
  step = 0;
  for (size_t k = 1; k < values.size(); ++k)
  {
    step = std::gcd(step, values[k] - values[k - 1]);
  }
  if (step == 0)
  {
    step = 1;
    count = 1;
    return true;
  }
  count = (values.back() - values.front()) / step + 1;
  return true;
}

/// Groups coordinates along one grid axis into rows and numbers the rows on the lattice.
/// `coordinate` are the points' projections on the axis; `gap` separates rows (half the smallest
/// point distance: points of one row differ by at most twice the tolerance, far less). Returns
/// per-point row index, spacing (0 when there is only one row) and the number of lattice rows.
bool AxisRows(const std::vector<double>& coordinate,
  double gap,
  std::vector<long long>& row,
  double& spacing,
  long long& count)
{
  const size_t n = coordinate.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(
    order.begin(), order.end(), [&](size_t a, size_t b) { return coordinate[a] < coordinate[b]; });

  std::vector<double> centre;
  std::vector<size_t> cluster(n);
  double sum = 0.0;
  size_t members = 0;
  for (size_t k = 0; k < n; ++k)
  {
    const size_t p = order[k];
    if (k > 0 && coordinate[p] - coordinate[order[k - 1]] > gap)
    {
      centre.push_back(sum / members);
      sum = 0.0;
      members = 0;
    }
    cluster[p] = centre.size();
    sum += coordinate[p];
    ++members;
  }
  centre.push_back(sum / members);

  std::vector<long long> lattice(centre.size(), 0);
  spacing = 0.0;
  count = 1;
  if (centre.size() > 1)
  {
    // The smallest gap is one lattice step (or a multiple, when no two neighbouring rows are
    // present, which still describes the data). Every gap is rounded to a multiple of it on its
    // own, so an error in the smallest gap does not accumulate across the grid; the spacing is
    // then the total span over the total number of steps.
    double smallest = std::numeric_limits<double>::max();
    for (size_t k = 1; k < centre.size(); ++k)
    {
      smallest = std::min(smallest, centre[k] - centre[k - 1]);
    }
    long long steps = 0;
    for (size_t k = 1; k < centre.size(); ++k)
    {
      const double m = std::round((centre[k] - centre[k - 1]) / smallest);
      if (!(m >= 1.0) || m > static_cast<double>(MaxNodes))
      {
        return false;
      }
      steps += static_cast<long long>(m);
      if (steps > MaxNodes)
      {
        return false;
      }
      lattice[k] = steps;
    }
    spacing = (centre.back() - centre.front()) / steps;
    count = steps + 1;
  }
  row.resize(n);
  for (size_t p = 0; p < n; ++p)
  {
    row[p] = lattice[cluster[p]];
  }
  return true;
}

/// The regular grid that x y points lie on.
struct Lattice
{
  double Origin[2] = { 0.0, 0.0 };
  double Spacing[2] = { 1.0, 1.0 };
  double Angle = 0.0; // degrees
  long long NX = 1;
  long long NY = 1;
  std::vector<long long> I, J;
  double MaxDeviation = 0.0;
};

/// Finds the lattice of the x y points of `records`; see the class documentation for the method.
bool FitLattice(const std::vector<Record>& records,
  double tolerance,
  Lattice& lattice,
  std::string& error)
{
  const size_t n = records.size();
  // Coordinates relative to the first point: UTM-scale values lose digits in the products below.
  const double x0 = records[0].A;
  const double y0 = records[0].B;
  std::vector<double> px(n), py(n);
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    px[k] = records[k].A - x0;
    py[k] = records[k].B - y0;
    if (!std::isfinite(px[k]) || !std::isfinite(py[k]))
    {
      error = "line " + std::to_string(records[k].Line) + ": x or y is not a finite number";
      return false;
    }
    xmin = std::min(xmin, px[k]);
    xmax = std::max(xmax, px[k]);
    ymin = std::min(ymin, py[k]);
    ymax = std::max(ymax, py[k]);
  }
  lattice = Lattice();
  if (n == 1)
  {
    lattice.Origin[0] = x0;
    lattice.Origin[1] = y0;
    lattice.I.assign(1, 0);
    lattice.J.assign(1, 0);
    return true;
  }
  const double w = xmax - xmin;
  const double h = ymax - ymin;
  if (!std::isfinite(w) || !std::isfinite(h))
  {
    error = "x y coordinates span more than a double can hold";
    return false;
  }
  if (w == 0.0 && h == 0.0)
  {
    error = "all " + std::to_string(n) + " points are at the same x y position";
    return false;
  }

  // Nearest-neighbour vectors through a bucket grid. A neighbour found within one cell size is
  // the true nearest one, since anything closer lies in the 3 x 3 cells around the point. The
  // first cell size holds a few points per cell on a full grid; it doubles until some point finds
  // its neighbour (sparse or strongly anisotropic data).
  double cell = 1.5 * std::max(std::sqrt(w * h / static_cast<double>(n)),
                        std::max(w, h) / static_cast<double>(n));
  std::vector<std::array<double, 2>> neighbourVectors;
  double nearest = std::numeric_limits<double>::max();
  for (int attempt = 0; attempt < 64 && neighbourVectors.empty(); ++attempt, cell *= 2.0)
  {
    const long long cellsY = static_cast<long long>(h / cell) + 1;
    std::vector<std::pair<long long, size_t>> keyed(n);
    auto cellOf = [&](size_t k, long long& cx, long long& cy)
    {
      cx = static_cast<long long>((px[k] - xmin) / cell);
      cy = static_cast<long long>((py[k] - ymin) / cell);
    };
    for (size_t k = 0; k < n; ++k)
    {
      long long cx, cy;
      cellOf(k, cx, cy);
      keyed[k] = { cx * cellsY + cy, k };
    }
    std::sort(keyed.begin(), keyed.end());
    for (size_t k = 0; k < n; ++k)
    {
      long long cx, cy;
      cellOf(k, cx, cy);
      double best = std::numeric_limits<double>::max();
      double bx = 0.0, by = 0.0;
      for (long long ix = cx - 1; ix <= cx + 1; ++ix)
      {
        for (long long iy = cy - 1; iy <= cy + 1; ++iy)
        {
          if (ix < 0 || iy < 0 || iy >= cellsY)
          {
            continue;
          }
          const long long key = ix * cellsY + iy;
          auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, size_t(0)));
          for (; it != keyed.end() && it->first == key; ++it)
          {
            const double dx = px[it->second] - px[k];
            const double dy = py[it->second] - py[k];
            const double d = std::sqrt(dx * dx + dy * dy);
            if (d > 0.0 && d < best) // a duplicate (d = 0) is not a neighbour
            {
              best = d;
              bx = dx;
              by = dy;
            }
          }
        }
      }
      if (best <= cell)
      {
        neighbourVectors.push_back({ bx, by });
        nearest = std::min(nearest, best);
      }
    }
  }
  if (neighbourVectors.empty())
  {
    error = "cannot find neighbouring points";
    return false;
  }

  // Grid orientation from the short neighbour vectors (at most 1.2 x the smallest distance:
  // shorter than any diagonal, so every one of them is along a grid axis). Quadrupling their
  // angles maps all four axis directions onto one, so their mean gives the orientation modulo
  // 90 degrees, and averaging over many vectors cancels the rounding of printed coordinates.
  double sc = 0.0;
  double ss = 0.0;
  size_t used = 0;
  for (const auto& v : neighbourVectors)
  {
    if (std::hypot(v[0], v[1]) <= 1.2 * nearest)
    {
      const double phi = std::atan2(v[1], v[0]);
      sc += std::cos(4.0 * phi);
      ss += std::sin(4.0 * phi);
      ++used;
    }
  }
  if (std::hypot(sc, ss) < 0.5 * used)
  {
    error = "the x y points are not on a regular grid: neighbouring points do not line up along "
            "two perpendicular directions";
    return false;
  }
  double angle = std::atan2(ss, sc) / 4.0; // in (-45, 45] degrees
  double c = std::cos(angle);
  double s = std::sin(angle);

  // Rows along each axis, on the lattice.
  std::vector<double> along(n), across(n);
  for (size_t k = 0; k < n; ++k)
  {
    along[k] = c * px[k] + s * py[k];
    across[k] = -s * px[k] + c * py[k];
  }
  double du = 0.0;
  double dv = 0.0;
  long long nx = 1;
  long long ny = 1;
  if (!AxisRows(along, 0.5 * nearest, lattice.I, du, nx) ||
      !AxisRows(across, 0.5 * nearest, lattice.J, dv, ny))
  {
    error =
      "the x y points are not on a regular grid: the rows along an axis are not evenly spaced";
    return false;
  }
  if (!CheckGridSize(nx, ny, n, error))
  {
    return false;
  }

  // Least-squares fit of p = o + i U + j V, then the nearest rotation with U and V perpendicular.
  double mi = 0.0, mj = 0.0, mx = 0.0, my = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    mi += lattice.I[k];
    mj += lattice.J[k];
    mx += px[k];
    my += py[k];
  }
  mi /= n;
  mj /= n;
  mx /= n;
  my /= n;
  double sii = 0.0, sjj = 0.0, sij = 0.0, six = 0.0, siy = 0.0, sjx = 0.0, sjy = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    const double di = lattice.I[k] - mi;
    const double dj = lattice.J[k] - mj;
    const double dx = px[k] - mx;
    const double dy = py[k] - my;
    sii += di * di;
    sjj += dj * dj;
    sij += di * dj;
    six += di * dx;
    siy += di * dy;
    sjx += dj * dx;
    sjy += dj * dy;
  }
  double U[2] = { du * c, du * s };
  double V[2] = { -dv * s, dv * c };
  const double det = sii * sjj - sij * sij;
  if (nx > 1 && ny > 1 && det > 0.0)
  {
    U[0] = (sjj * six - sij * sjx) / det;
    U[1] = (sjj * siy - sij * sjy) / det;
    V[0] = (sii * sjx - sij * six) / det;
    V[1] = (sii * sjy - sij * siy) / det;
  }
  else if (nx > 1 && sii > 0.0)
  {
    U[0] = six / sii;
    U[1] = siy / sii;
  }
  else if (ny > 1 && sjj > 0.0)
  {
    V[0] = sjx / sjj;
    V[1] = sjy / sjj;
  }
  du = nx > 1 ? std::hypot(U[0], U[1]) : 0.0;
  dv = ny > 1 ? std::hypot(V[0], V[1]) : 0.0;
  if (nx > 1 && ny > 1)
  {
    // Mean of U's direction and V's direction turned back by 90 degrees.
    angle = std::atan2(U[1] / du - V[0] / dv, U[0] / du + V[1] / dv);
  }
  else if (nx > 1)
  {
    angle = std::atan2(U[1], U[0]);
  }
  else
  {
    angle = std::atan2(-V[0], V[1]);
  }
  // A single row or column says nothing about the spacing across it: use the other one.
  if (du == 0.0)
  {
    du = dv;
  }
  if (dv == 0.0)
  {
    dv = du;
  }
  if (!(du > 0.0) || !(dv > 0.0))
  {
    error = "cannot determine the grid spacing";
    return false;
  }
  c = std::cos(angle);
  s = std::sin(angle);
  double ox = mx - (c * mi * du - s * mj * dv);
  double oy = my - (s * mi * du + c * mj * dv);

  // Every point must sit on its node.
  const double limit = tolerance * std::min(du, dv);
  size_t worst = 0;
  double worstDeviation = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    const double ex = ox + c * lattice.I[k] * du - s * lattice.J[k] * dv - px[k];
    const double ey = oy + s * lattice.I[k] * du + c * lattice.J[k] * dv - py[k];
    const double e = std::hypot(ex, ey);
    if (e > worstDeviation)
    {
      worstDeviation = e;
      worst = k;
    }
  }
  if (worstDeviation > limit)
  {
    std::ostringstream msg;
    msg << "the x y points are not on a regular grid: the point on line " << records[worst].Line
        << " lies " << worstDeviation << " from its node of the best-fitting grid (spacing " << du
        << " x " << dv << ", rotation " << vtkMath::DegreesFromRadians(angle)
        << " degrees), more than Tolerance " << tolerance << " x " << std::min(du, dv);
    error = msg.str();
    return false;
  }

  lattice.Origin[0] = ox + x0;
  lattice.Origin[1] = oy + y0;
  lattice.Spacing[0] = du;
  lattice.Spacing[1] = dv;
  lattice.Angle = vtkMath::DegreesFromRadians(angle);
  lattice.NX = nx;
  lattice.NY = ny;
  lattice.MaxDeviation = worstDeviation;
  return true;
}
}

//------------------------------------------------------------------------------
class vtkHorizonColumnReader::vtkInternals
{
public:
  /// The grid built by the last successful RequestInformation, handed to the output (and
  /// released) by the following RequestData.
  vtkSmartPointer<vtkFloatArray> Grid;
};

//------------------------------------------------------------------------------
vtkHorizonColumnReader::vtkHorizonColumnReader()
  : NullValue(std::numeric_limits<double>::quiet_NaN())
  , Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("depth");
}

//------------------------------------------------------------------------------
vtkHorizonColumnReader::~vtkHorizonColumnReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkHorizonColumnReader::ResetResults()
{
  this->DetectedMode = ColumnMode::Auto;
  this->HasHeaderLine = false;
  this->NumberOfRecords = 0;
  this->NumberOfDuplicates = 0;
  this->NX = 0;
  this->NY = 0;
  this->FirstInline = 0;
  this->InlineStep = 0;
  this->FirstCrossline = 0;
  this->CrosslineStep = 0;
  this->GridOrigin[0] = this->GridOrigin[1] = 0.0;
  this->GridSpacing[0] = this->GridSpacing[1] = 0.0;
  this->GridRotation = 0.0;
  this->MaxDeviation = 0.0;
  this->NumberOfNoDataValues = 0;
  this->Internals->Grid = nullptr;
}

//------------------------------------------------------------------------------
bool vtkHorizonColumnReader::ReadGrid(std::string& error)
{
  this->ResetResults();
  if (!this->FileName || !*this->FileName)
  {
    error = "no file name set";
    return false;
  }
  if (!vtksys::SystemTools::FileExists(this->FileName, /*isFile=*/true))
  {
    error = "file does not exist or is not a regular file";
    return false;
  }
  if (this->Mode == ColumnMode::Matrix)
  {
    return this->ReadMatrixGrid(error);
  }
  vtksys::ifstream in(this->FileName, std::ios::in | std::ios::binary);
  if (!in)
  {
    error = "cannot open file";
    return false;
  }
  in.seekg(0, std::ios::end);
  const double fileSize = std::max(1.0, static_cast<double>(in.tellg()));
  in.seekg(0, std::ios::beg);

  // Parsing takes the first 80% of the progress range, building the grid the rest.
  std::vector<Record> records;
  std::vector<std::string> header;
  std::string line;
  std::vector<std::pair<size_t, size_t>> tokens;
  long long lineNumber = 0;
  bool sawContent = false;
  // A '#' header that states a raster's Dimensions or extents (a DEM export) makes a matrix.
  bool matrixHeader = false;
  // Values per data line, smallest and largest: a matrix has many, the same on every line.
  size_t fewestValues = std::numeric_limits<size_t>::max();
  size_t mostValues = 0;
  this->UpdateProgress(0.0);
  try
  {
    while (std::getline(in, line))
    {
      ++lineNumber;
      if (!line.empty() && line.back() == '\r')
      {
        line.pop_back();
      }
      size_t first = 0;
      while (first < line.size() && std::isspace(static_cast<unsigned char>(line[first])))
      {
        ++first;
      }
      if (first == line.size() || line[first] == '#')
      {
        matrixHeader = matrixHeader || (!sawContent && strata_io::IsMatrixGeometryLine(line));
        continue;
      }
      if (matrixHeader && this->Mode == ColumnMode::Auto)
      {
        in.close();
        return this->ReadMatrixGrid(error);
      }
      Tokenize(line, tokens);
      double v[3];
      bool numeric = tokens.size() >= 3;
      for (int c = 0; numeric && c < 3; ++c)
      {
        numeric = ParseNumber(line.data() + tokens[c].first, line.data() + tokens[c].second, v[c]);
      }
      if (!numeric)
      {
        if (!sawContent)
        {
          // One header line is allowed, before any data.
          for (const auto& t : tokens)
          {
            header.push_back(line.substr(t.first, t.second - t.first));
          }
          this->HasHeaderLine = true;
          sawContent = true;
          continue;
        }
        // Quote the line for the message, binary bytes and all made printable.
        std::string shown = line.substr(0, 80);
        std::replace_if(
          shown.begin(),
          shown.end(),
          [](char c) { return !std::isprint(static_cast<unsigned char>(c)); },
          '?');
        std::ostringstream msg;
        msg << "line " << lineNumber << ": expected at least three numbers, found \"" << shown
            << (line.size() > 80 ? "..." : "") << "\"";
        error = msg.str();
        return false;
      }
      sawContent = true;
      records.push_back({ v[0], v[1], v[2], lineNumber });
      fewestValues = std::min(fewestValues, tokens.size());
      mostValues = std::max(mostValues, tokens.size());
      if ((records.size() & 0x3fff) == 0)
      {
        this->UpdateProgress(0.8 * static_cast<double>(in.tellg()) / fileSize);
      }
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory while reading the columns";
    return false;
  }
  if (in.bad())
  {
    error = "read error";
    return false;
  }
  if (records.empty())
  {
    error = "no data lines (need lines of at least three numbers)";
    return false;
  }
  this->NumberOfRecords = static_cast<vtkIdType>(records.size());

  // Which mode. Every line as long as the others and longer than any columns file's: a matrix.
  const bool sameLength = fewestValues == mostValues && mostValues > 3;
  if (this->Mode == ColumnMode::Auto && sameLength && !this->HasHeaderLine &&
      mostValues > static_cast<size_t>(MatrixMinimumColumns))
  {
    in.close();
    return this->ReadMatrixGrid(error);
  }
  ColumnMode mode = this->Mode;
  if (mode == ColumnMode::Auto)
  {
    mode = ModeFromHeader(header);
  }
  const bool integerColumns = std::all_of(records.begin(),
    records.end(),
    [](const Record& r) { return IsIndexValue(r.A) && IsIndexValue(r.B); });
  if (mode == ColumnMode::Auto)
  {
    mode = integerColumns ? ColumnMode::InlineCrossline : ColumnMode::XYZ;
  }
  if (mode == ColumnMode::InlineCrossline && !integerColumns)
  {
    const auto bad = std::find_if(records.begin(),
      records.end(),
      [](const Record& r) { return !(IsIndexValue(r.A) && IsIndexValue(r.B)); });
    error = "line " + std::to_string(bad->Line) +
            ": inline and crossline must be integers (use the XYZ mode for world coordinates)";
    return false;
  }

  // Grid geometry and the node of every record.
  std::vector<long long> nodeI, nodeJ;
  long long nx = 1;
  long long ny = 1;
  if (mode == ColumnMode::InlineCrossline)
  {
    long long il0 = 0, ilStep = 1, xl0 = 0, xlStep = 1;
    IndexAxis(records, true, il0, ilStep, nx);
    IndexAxis(records, false, xl0, xlStep, ny);
    if (!CheckGridSize(nx, ny, records.size(), error))
    {
      return false;
    }
    nodeI.resize(records.size());
    nodeJ.resize(records.size());
    for (size_t k = 0; k < records.size(); ++k)
    {
      nodeI[k] = (static_cast<long long>(records[k].A) - il0) / ilStep;
      nodeJ[k] = (static_cast<long long>(records[k].B) - xl0) / xlStep;
    }
    this->FirstInline = il0;
    this->InlineStep = ilStep;
    this->FirstCrossline = xl0;
    this->CrosslineStep = xlStep;
    if (this->IndexCoordinates)
    {
      this->GridOrigin[0] = static_cast<double>(il0);
      this->GridOrigin[1] = static_cast<double>(xl0);
      this->GridSpacing[0] = static_cast<double>(ilStep);
      this->GridSpacing[1] = static_cast<double>(xlStep);
      this->GridRotation = 0.0;
    }
    else
    {
      if (!(this->InlineSpacing > 0.0) || !(this->CrosslineSpacing > 0.0) ||
          !std::isfinite(this->InlineSpacing) || !std::isfinite(this->CrosslineSpacing))
      {
        error = "InlineSpacing and CrosslineSpacing must be positive";
        return false;
      }
      this->GridOrigin[0] = this->Origin[0];
      this->GridOrigin[1] = this->Origin[1];
      this->GridSpacing[0] = ilStep * this->InlineSpacing;
      this->GridSpacing[1] = xlStep * this->CrosslineSpacing;
      this->GridRotation = this->Rotation;
    }
  }
  else
  {
    Lattice lattice;
    try
    {
      if (!FitLattice(records, this->Tolerance, lattice, error))
      {
        return false;
      }
    }
    catch (const std::bad_alloc&)
    {
      error = "out of memory while fitting the grid";
      return false;
    }
    nx = lattice.NX;
    ny = lattice.NY;
    nodeI.swap(lattice.I);
    nodeJ.swap(lattice.J);
    this->GridOrigin[0] = lattice.Origin[0];
    this->GridOrigin[1] = lattice.Origin[1];
    this->GridSpacing[0] = lattice.Spacing[0];
    this->GridSpacing[1] = lattice.Spacing[1];
    this->GridRotation = lattice.Angle;
    this->MaxDeviation = lattice.MaxDeviation;
  }
  this->UpdateProgress(0.85);

  // Fill the grid; nodes that no line sets stay NaN.
  const vtkIdType total = static_cast<vtkIdType>(nx * ny);
  vtkSmartPointer<vtkFloatArray> grid = vtkSmartPointer<vtkFloatArray>::New();
  grid->SetName(this->ArrayName);
  grid->SetNumberOfTuples(total);
  if (grid->GetNumberOfTuples() != total)
  {
    error = "cannot allocate the grid values";
    return false;
  }
  float* values = grid->GetPointer(0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::fill(values, values + total, nan);
  std::vector<bool> set;
  try
  {
    set.assign(static_cast<size_t>(total), false);
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory for the grid";
    return false;
  }
  const bool hasNull = !std::isnan(this->NullValue);
  vtkIdType duplicates = 0;
  for (size_t k = 0; k < records.size(); ++k)
  {
    const vtkIdType id = static_cast<vtkIdType>(nodeI[k] + nodeJ[k] * nx);
    if (set[id])
    {
      ++duplicates;
    }
    set[id] = true;
    const double z = records[k].Z;
    const bool hole = !std::isfinite(z) || (hasNull && z == this->NullValue);
    if (!hole && std::fabs(z) > std::numeric_limits<float>::max())
    {
      // Stored as float it would be infinity: a misread, not a depth.
      std::ostringstream msg;
      msg << "line " << records[k].Line << ": z = " << z
          << " is beyond the range of float (3.4e38) and not the NullValue";
      error = msg.str();
      return false;
    }
    values[id] = hole ? nan : static_cast<float>(z);
  }
  vtkIdType noData = 0;
  for (vtkIdType id = 0; id < total; ++id)
  {
    noData += std::isnan(values[id]) ? 1 : 0;
  }

  // A small matrix read as columns puts its few rows on nodes already set, or on a grid that is
  // mostly holes (one row per node of a rows x rows grid): in Auto mode, an error that says so.
  if (this->Mode == ColumnMode::Auto && sameLength && (duplicates > 0 || 2 * noData > total))
  {
    std::ostringstream msg;
    msg << "every data line holds " << mostValues << " values, and read as " << ModeName(mode)
        << " columns " << duplicates << " of them fall on a grid node already set and " << noData
        << " of the " << total << " nodes stay holes: this looks like a whitespace "
        << "matrix (one grid row per line), not columns; set Mode to Matrix to read it as one, "
        << "or to " << ModeName(mode) << " to read it as columns";
    error = msg.str();
    return false;
  }

  this->DetectedMode = mode;
  this->NX = static_cast<int>(nx);
  this->NY = static_cast<int>(ny);
  this->NumberOfDuplicates = duplicates;
  this->NumberOfNoDataValues = noData;
  this->Internals->Grid = grid;
  if (duplicates > 0)
  {
    vtkWarningMacro(<< this->FileName << ": " << duplicates
                    << " data lines fall on a grid node already set; the last one was kept.");
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkHorizonColumnReader::ReadMatrixGrid(std::string& error)
{
  this->ResetResults();
  strata_io::AsciiGridOptions options;
  options.NullValue = this->NullValue;
  strata_io::AsciiGrid matrix;
  if (!strata_io::ReadAsciiGrid(
        this->FileName, strata_io::AsciiGridFormat::Matrix, options, matrix, error))
  {
    error = "reading it as a whitespace matrix: " + error;
    return false;
  }
  if (matrix.HasGeometry)
  {
    // The file states its geometry, as the text grid formats do: it wins over the settings.
    std::copy(matrix.Origin, matrix.Origin + 2, this->GridOrigin);
    std::copy(matrix.Spacing, matrix.Spacing + 2, this->GridSpacing);
    this->GridRotation = 0.0;
  }
  else if (this->IndexCoordinates)
  {
    this->GridOrigin[0] = this->GridOrigin[1] = 0.0;
    this->GridSpacing[0] = this->GridSpacing[1] = 1.0;
    this->GridRotation = 0.0;
  }
  else
  {
    if (!(this->InlineSpacing > 0.0) || !(this->CrosslineSpacing > 0.0) ||
        !std::isfinite(this->InlineSpacing) || !std::isfinite(this->CrosslineSpacing))
    {
      error = "InlineSpacing and CrosslineSpacing must be positive";
      return false;
    }
    this->GridOrigin[0] = this->Origin[0];
    this->GridOrigin[1] = this->Origin[1];
    this->GridSpacing[0] = this->InlineSpacing;
    this->GridSpacing[1] = this->CrosslineSpacing;
    this->GridRotation = this->Rotation;
  }
  vtkSmartPointer<vtkFloatArray> grid = vtkSmartPointer<vtkFloatArray>::New();
  grid->SetName(this->ArrayName);
  const vtkIdType total = static_cast<vtkIdType>(matrix.Values.size());
  grid->SetNumberOfTuples(total);
  if (grid->GetNumberOfTuples() != total)
  {
    error = "cannot allocate the grid values";
    return false;
  }
  std::copy(matrix.Values.begin(), matrix.Values.end(), grid->GetPointer(0));
  this->DetectedMode = ColumnMode::Matrix;
  this->NumberOfRecords = matrix.NumberOfLines;
  this->NX = matrix.NX;
  this->NY = matrix.NY;
  this->NumberOfNoDataValues = static_cast<vtkIdType>(matrix.NumberOfNoDataValues);
  this->Internals->Grid = grid;
  return true;
}

//------------------------------------------------------------------------------
int vtkHorizonColumnReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  std::string error;
  if (!this->ReadGrid(error))
  {
    this->ResetResults();
    ClearOutput(outInfo);
    vtkErrorMacro("Cannot read horizon columns \"" << (this->FileName ? this->FileName : "")
                                                   << "\": " << error);
    return 0;
  }
  const double origin[2] = { this->GridOrigin[0], this->GridOrigin[1] };
  const double spacing[2] = { this->GridSpacing[0], this->GridSpacing[1] };
  SetGridInformation(outInfo, this->NX, this->NY, origin, spacing, this->GridRotation, VTK_FLOAT);
  return 1;
}

//------------------------------------------------------------------------------
int vtkHorizonColumnReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!output)
  {
    vtkErrorMacro("No vtkImageData output to fill.");
    return 0;
  }
  output->Initialize();

  // The grid was built in RequestInformation; a second RequestData without a new information
  // pass (another update extent, say) builds it again rather than keeping a copy around.
  if (!this->Internals->Grid)
  {
    const int nx = this->NX;
    const int ny = this->NY;
    std::string error;
    if (!this->ReadGrid(error) || this->NX != nx || this->NY != ny)
    {
      if (error.empty())
      {
        error = "the grid dimensions changed since the information pass";
      }
      this->ResetResults();
      ClearOutput(outInfo);
      vtkErrorMacro("Cannot read horizon columns \"" << (this->FileName ? this->FileName : "")
                                                     << "\": " << error);
      return 0;
    }
  }

  const double gridOrigin[2] = { this->GridOrigin[0], this->GridOrigin[1] };
  const double gridSpacing[2] = { this->GridSpacing[0], this->GridSpacing[1] };
  SetGridGeometry(output, this->NX, this->NY, gridOrigin, gridSpacing, this->GridRotation);
  output->GetPointData()->SetScalars(this->Internals->Grid);
  this->Internals->Grid = nullptr;
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkHorizonColumnReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "Mode: " << ModeName(this->Mode) << "\n";
  os << indent << "IndexCoordinates: " << (this->IndexCoordinates ? "On" : "Off") << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << "\n";
  os << indent << "InlineSpacing: " << this->InlineSpacing << "\n";
  os << indent << "CrosslineSpacing: " << this->CrosslineSpacing << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "DetectedMode: " << ModeName(this->DetectedMode) << "\n";
  os << indent << "HasHeaderLine: " << (this->HasHeaderLine ? "yes" : "no") << "\n";
  os << indent << "NumberOfRecords: " << this->NumberOfRecords << "\n";
  os << indent << "NumberOfDuplicates: " << this->NumberOfDuplicates << "\n";
  os << indent << "NX: " << this->NX << "\n";
  os << indent << "NY: " << this->NY << "\n";
  os << indent << "FirstInline: " << this->FirstInline << "\n";
  os << indent << "InlineStep: " << this->InlineStep << "\n";
  os << indent << "FirstCrossline: " << this->FirstCrossline << "\n";
  os << indent << "CrosslineStep: " << this->CrosslineStep << "\n";
  os << indent << "GridOrigin: " << this->GridOrigin[0] << " " << this->GridOrigin[1] << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing[0] << " " << this->GridSpacing[1] << "\n";
  os << indent << "GridRotation: " << this->GridRotation << "\n";
  os << indent << "MaxDeviation: " << this->MaxDeviation << "\n";
  os << indent << "NumberOfNoDataValues: " << this->NumberOfNoDataValues << "\n";
  os << indent << "GridPending: " << (this->Internals->Grid ? "yes" : "no") << "\n";
}

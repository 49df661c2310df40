// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHorizonColumnReader.h"
#include "StrataAsciiGridParser.h"

#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"

#include <vtksys/FStream.hxx>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkHorizonColumnReader);

namespace
{
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

/// The x y of the records relative to the first one (UTM-scale values lose digits in the
/// products of the fit), and their bounding box, which holds the first point (0, 0).
struct PointSet
{
  double X0 = 0.0;
  double Y0 = 0.0;
  std::vector<double> X, Y;
  double XMin = 0.0, XMax = 0.0, YMin = 0.0, YMax = 0.0;

  size_t Size() const { return this->X.size(); }
};

bool RelativePoints(const std::vector<Record>& records, PointSet& points, std::string& error)
{
  const size_t n = records.size();
  points.X0 = records[0].A;
  points.Y0 = records[0].B;
  points.X.resize(n);
  points.Y.resize(n);
  for (size_t k = 0; k < n; ++k)
  {
    const double x = records[k].A - points.X0;
    const double y = records[k].B - points.Y0;
    if (!std::isfinite(x) || !std::isfinite(y))
    {
      error = "line " + std::to_string(records[k].Line) + ": x or y is not a finite number";
      return false;
    }
    points.X[k] = x;
    points.Y[k] = y;
    points.XMin = std::min(points.XMin, x);
    points.XMax = std::max(points.XMax, x);
    points.YMin = std::min(points.YMin, y);
    points.YMax = std::max(points.YMax, y);
  }
  return true;
}

/// The points sorted into square buckets of side `Cell`, keyed by column * Rows + row.
struct Buckets
{
  double Cell = 0.0;
  long long Rows = 0;
  std::vector<std::pair<long long, size_t>> Keyed; // (key, point), sorted

  void Of(const PointSet& p, size_t k, long long& cx, long long& cy) const
  {
    cx = static_cast<long long>((p.X[k] - p.XMin) / this->Cell);
    cy = static_cast<long long>((p.Y[k] - p.YMin) / this->Cell);
  }

  void Fill(const PointSet& p, double cell)
  {
    this->Cell = cell;
    this->Rows = static_cast<long long>((p.YMax - p.YMin) / cell) + 1;
    this->Keyed.resize(p.Size());
    for (size_t k = 0; k < p.Size(); ++k)
    {
      long long cx, cy;
      this->Of(p, k, cx, cy);
      this->Keyed[k] = { cx * this->Rows + cy, k };
    }
    std::sort(this->Keyed.begin(), this->Keyed.end());
  }
};

/// The vector from point k to its nearest neighbour in the 3 x 3 buckets around it, and its
/// length; false when there is none within one bucket size (then a nearer one may lie beyond).
bool NearestInBuckets(const PointSet& p,
  const Buckets& buckets,
  size_t k,
  std::array<double, 2>& vector,
  double& distance)
{
  long long cx, cy;
  buckets.Of(p, k, cx, cy);
  distance = std::numeric_limits<double>::max();
  for (long long ix = cx - 1; ix <= cx + 1; ++ix)
  {
    for (long long iy = cy - 1; iy <= cy + 1; ++iy)
    {
      if (ix < 0 || iy < 0 || iy >= buckets.Rows)
      {
        continue;
      }
      const long long key = ix * buckets.Rows + iy;
      auto it = std::lower_bound(
        buckets.Keyed.begin(), buckets.Keyed.end(), std::make_pair(key, size_t(0)));
      for (; it != buckets.Keyed.end() && it->first == key; ++it)
      {
        const double dx = p.X[it->second] - p.X[k];
        const double dy = p.Y[it->second] - p.Y[k];
        const double d = std::sqrt(dx * dx + dy * dy);
        if (d > 0.0 && d < distance) // a duplicate (d = 0) is not a neighbour
        {
          distance = d;
          vector = { dx, dy };
        }
      }
    }
  }
  return distance <= buckets.Cell;
}

/// Nearest-neighbour vectors through a bucket grid. A neighbour found within one cell size is
/// the true nearest one, since anything closer lies in the 3 x 3 cells around the point. The
/// first cell size holds a few points per cell on a full grid; it doubles until some point finds
/// its neighbour (sparse or strongly anisotropic data). `nearest`: the shortest of them.
void NeighbourVectors(const PointSet& p,
  std::vector<std::array<double, 2>>& vectors,
  double& nearest)
{
  const double w = p.XMax - p.XMin;
  const double h = p.YMax - p.YMin;
  const double n = static_cast<double>(p.Size());
  double cell = 1.5 * std::max(std::sqrt(w * h / n), std::max(w, h) / n);
  vectors.clear();
  nearest = std::numeric_limits<double>::max();
  Buckets buckets;
  for (int attempt = 0; attempt < 64 && vectors.empty(); ++attempt, cell *= 2.0)
  {
    buckets.Fill(p, cell);
    for (size_t k = 0; k < p.Size(); ++k)
    {
      std::array<double, 2> v = { 0.0, 0.0 };
      double d = 0.0;
      if (NearestInBuckets(p, buckets, k, v, d))
      {
        vectors.push_back(v);
        nearest = std::min(nearest, d);
      }
    }
  }
}

/// Grid orientation from the short neighbour vectors (at most 1.2 x the smallest distance:
/// shorter than any diagonal, so every one of them is along a grid axis). Quadrupling their
/// angles maps all four axis directions onto one, so their mean gives the orientation modulo
/// 90 degrees, and averaging over many vectors cancels the rounding of printed coordinates.
/// `angle` in radians, in (-45, 45] degrees.
bool GridOrientation(const std::vector<std::array<double, 2>>& vectors,
  double nearest,
  double& angle,
  std::string& error)
{
  double sc = 0.0;
  double ss = 0.0;
  size_t used = 0;
  for (const auto& v : vectors)
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
  angle = std::atan2(ss, sc) / 4.0;
  return true;
}

/// Numbers the points' rows along the axes at `angle` (radians) into lattice.I and lattice.J
/// (AxisRows), with the spacings of the rows along each axis.
bool LatticeRows(const PointSet& p,
  double angle,
  double nearest,
  Lattice& lattice,
  double& du,
  double& dv,
  std::string& error)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const size_t n = p.Size();
  std::vector<double> along(n), across(n);
  for (size_t k = 0; k < n; ++k)
  {
    along[k] = c * p.X[k] + s * p.Y[k];
    across[k] = -s * p.X[k] + c * p.Y[k];
  }
  if (!AxisRows(along, 0.5 * nearest, lattice.I, du, lattice.NX) ||
      !AxisRows(across, 0.5 * nearest, lattice.J, dv, lattice.NY))
  {
    error =
      "the x y points are not on a regular grid: the rows along an axis are not evenly spaced";
    return false;
  }
  return CheckGridSize(lattice.NX, lattice.NY, n, error);
}

/// Means and centred second moments of node indices (i, j) and positions (x, y), for the
/// least-squares fit of p = o + i U + j V.
struct Moments
{
  double MI = 0.0, MJ = 0.0, MX = 0.0, MY = 0.0;
  double SII = 0.0, SJJ = 0.0, SIJ = 0.0, SIX = 0.0, SIY = 0.0, SJX = 0.0, SJY = 0.0;

  Moments(const PointSet& p, const Lattice& lattice)
  {
    const size_t n = p.Size();
    for (size_t k = 0; k < n; ++k)
    {
      this->MI += lattice.I[k];
      this->MJ += lattice.J[k];
      this->MX += p.X[k];
      this->MY += p.Y[k];
    }
    this->MI /= n;
    this->MJ /= n;
    this->MX /= n;
    this->MY /= n;
    for (size_t k = 0; k < n; ++k)
    {
      const double di = lattice.I[k] - this->MI;
      const double dj = lattice.J[k] - this->MJ;
      const double dx = p.X[k] - this->MX;
      const double dy = p.Y[k] - this->MY;
      this->SII += di * di;
      this->SJJ += dj * dj;
      this->SIJ += di * dj;
      this->SIX += di * dx;
      this->SIY += di * dy;
      this->SJX += dj * dx;
      this->SJY += dj * dy;
    }
  }
};

/// The least-squares axis vectors U and V (world step per i and per j) from the moments; an
/// axis the fit cannot determine (a single row or column) keeps its start value.
void FitAxisVectors(const Moments& m, long long nx, long long ny, double U[2], double V[2])
{
  const double det = m.SII * m.SJJ - m.SIJ * m.SIJ;
  if (nx > 1 && ny > 1 && det > 0.0)
  {
    U[0] = (m.SJJ * m.SIX - m.SIJ * m.SJX) / det;
    U[1] = (m.SJJ * m.SIY - m.SIJ * m.SJY) / det;
    V[0] = (m.SII * m.SJX - m.SIJ * m.SIX) / det;
    V[1] = (m.SII * m.SJY - m.SIJ * m.SIY) / det;
  }
  else if (nx > 1 && m.SII > 0.0)
  {
    U[0] = m.SIX / m.SII;
    U[1] = m.SIY / m.SII;
  }
  else if (ny > 1 && m.SJJ > 0.0)
  {
    V[0] = m.SJX / m.SJJ;
    V[1] = m.SJY / m.SJJ;
  }
}

/// The nearest rotation with perpendicular axes to the fitted U and V: `angle` (radians) and the
/// spacings du, dv (a single row or column takes the other axis's spacing).
bool PerpendicularAxes(const double U[2],
  const double V[2],
  long long nx,
  long long ny,
  double& angle,
  double& du,
  double& dv,
  std::string& error)
{
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
  return true;
}

/// The largest distance of a point from its node of the grid with origin (ox, oy) (relative to
/// the first point), axes at `angle` and spacings du, dv; `worst` is that point.
double WorstDeviation(const PointSet& p,
  const Lattice& lattice,
  double ox,
  double oy,
  double angle,
  double du,
  double dv,
  size_t& worst)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  worst = 0;
  double worstDeviation = 0.0;
  for (size_t k = 0; k < p.Size(); ++k)
  {
    const double ex = ox + c * lattice.I[k] * du - s * lattice.J[k] * dv - p.X[k];
    const double ey = oy + s * lattice.I[k] * du + c * lattice.J[k] * dv - p.Y[k];
    const double e = std::hypot(ex, ey);
    if (e > worstDeviation)
    {
      worstDeviation = e;
      worst = k;
    }
  }
  return worstDeviation;
}

/// Fits origin, rotation and spacings of `lattice` (its I, J, NX, NY numbered from the rows
/// along the axes at `angle` with spacings du, dv) to all points by least squares, and checks
/// that every point sits on its node within `tolerance` x the smaller spacing.
bool FitLatticeGeometry(const PointSet& p,
  const std::vector<Record>& records,
  double tolerance,
  double angle,
  double du,
  double dv,
  Lattice& lattice,
  std::string& error)
{
  const Moments m(p, lattice);
  double U[2] = { du * std::cos(angle), du * std::sin(angle) };
  double V[2] = { -dv * std::sin(angle), dv * std::cos(angle) };
  FitAxisVectors(m, lattice.NX, lattice.NY, U, V);
  if (!PerpendicularAxes(U, V, lattice.NX, lattice.NY, angle, du, dv, error))
  {
    return false;
  }
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double ox = m.MX - (c * m.MI * du - s * m.MJ * dv);
  const double oy = m.MY - (s * m.MI * du + c * m.MJ * dv);

  // Every point must sit on its node.
  size_t worst = 0;
  const double deviation = WorstDeviation(p, lattice, ox, oy, angle, du, dv, worst);
  if (deviation > tolerance * std::min(du, dv))
  {
    std::ostringstream msg;
    msg << "the x y points are not on a regular grid: the point on line " << records[worst].Line
        << " lies " << deviation << " from its node of the best-fitting grid (spacing " << du
        << " x " << dv << ", rotation " << vtkMath::DegreesFromRadians(angle)
        << " degrees), more than Tolerance " << tolerance << " x " << std::min(du, dv);
    error = msg.str();
    return false;
  }
  lattice.Origin[0] = ox + p.X0;
  lattice.Origin[1] = oy + p.Y0;
  lattice.Spacing[0] = du;
  lattice.Spacing[1] = dv;
  lattice.Angle = vtkMath::DegreesFromRadians(angle);
  lattice.MaxDeviation = deviation;
  return true;
}

/// Finds the lattice of the x y points of `records`; see the class documentation for the method.
bool FitLattice(const std::vector<Record>& records,
  double tolerance,
  Lattice& lattice,
  std::string& error)
{
  PointSet points;
  if (!RelativePoints(records, points, error))
  {
    return false;
  }
  lattice = Lattice();
  const size_t n = records.size();
  if (n == 1)
  {
    lattice.Origin[0] = points.X0;
    lattice.Origin[1] = points.Y0;
    lattice.I.assign(1, 0);
    lattice.J.assign(1, 0);
    return true;
  }
  const double w = points.XMax - points.XMin;
  const double h = points.YMax - points.YMin;
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
  std::vector<std::array<double, 2>> neighbours;
  double nearest = 0.0;
  NeighbourVectors(points, neighbours, nearest);
  if (neighbours.empty())
  {
    error = "cannot find neighbouring points";
    return false;
  }
  double angle = 0.0;
  double du = 0.0;
  double dv = 0.0;
  return GridOrientation(neighbours, nearest, angle, error) &&
         LatticeRows(points, angle, nearest, lattice, du, dv, error) &&
         FitLatticeGeometry(points, records, tolerance, angle, du, dv, lattice, error);
}

/// A data line quoted for a message: at most 80 characters, binary bytes made printable.
std::string ShownLine(const std::string& line)
{
  std::string shown = line.substr(0, 80);
  std::replace_if(
    shown.begin(),
    shown.end(),
    [](char c) { return !std::isprint(static_cast<unsigned char>(c)); },
    '?');
  return "\"" + shown + (line.size() > 80 ? "...\"" : "\"");
}

/// A columns file as read: its data lines, its header line and what tells a matrix apart.
struct ColumnFile
{
  std::vector<Record> Records;
  std::vector<std::string> Header; // the names of the header line, if any
  bool HasHeaderLine = false;
  // A '#' header that states a raster's Dimensions or extents (a DEM export) came before the
  // data: in Auto mode the file is a matrix, and reading stops at its first data line.
  bool RasterHeader = false;
  // Values per data line, smallest and largest: a matrix has many, the same on every line.
  size_t FewestValues = std::numeric_limits<size_t>::max();
  size_t MostValues = 0;

  bool SameLength() const { return this->FewestValues == this->MostValues && this->MostValues > 3; }
};

/// Takes one line of a columns file (without its end of line) into `file`: skips blank and '#'
/// lines, keeps one header line before any data, parses a data line. False with a message on a
/// line that is none of these.
bool TakeColumnLine(const std::string& line,
  long long lineNumber,
  std::vector<std::pair<size_t, size_t>>& tokens,
  ColumnFile& file,
  std::string& error)
{
  const bool sawContent = file.HasHeaderLine || !file.Records.empty();
  size_t first = 0;
  while (first < line.size() && std::isspace(static_cast<unsigned char>(line[first])))
  {
    ++first;
  }
  if (first == line.size() || line[first] == '#')
  {
    file.RasterHeader = file.RasterHeader || (!sawContent && strata_io::IsMatrixGeometryLine(line));
    return true;
  }
  Tokenize(line, tokens);
  double v[3];
  bool numeric = tokens.size() >= 3;
  for (int c = 0; numeric && c < 3; ++c)
  {
    numeric = ParseNumber(line.data() + tokens[c].first, line.data() + tokens[c].second, v[c]);
  }
  if (numeric)
  {
    file.Records.push_back({ v[0], v[1], v[2], lineNumber });
    file.FewestValues = std::min(file.FewestValues, tokens.size());
    file.MostValues = std::max(file.MostValues, tokens.size());
    return true;
  }
  if (!sawContent)
  {
    // One header line is allowed, before any data.
    for (const auto& t : tokens)
    {
      file.Header.push_back(line.substr(t.first, t.second - t.first));
    }
    file.HasHeaderLine = true;
    return true;
  }
  error = "line " + std::to_string(lineNumber) + ": expected at least three numbers, found " +
          ShownLine(line);
  return false;
}

/// Reads the lines of `path` into `file`, reporting progress (fraction of the bytes) now and
/// then; with `stopAtRasterHeader`, stops at the first data line after a raster header.
bool ReadColumnFile(const char* path,
  bool stopAtRasterHeader,
  const std::function<void(double)>& progress,
  ColumnFile& file,
  std::string& error)
{
  vtksys::ifstream in(path, std::ios::in | std::ios::binary);
  if (!in)
  {
    error = "cannot open file";
    return false;
  }
  in.seekg(0, std::ios::end);
  const double fileSize = std::max(1.0, static_cast<double>(in.tellg()));
  in.seekg(0, std::ios::beg);
  std::string line;
  std::vector<std::pair<size_t, size_t>> tokens;
  long long lineNumber = 0;
  try
  {
    while (std::getline(in, line))
    {
      ++lineNumber;
      if (!line.empty() && line.back() == '\r')
      {
        line.pop_back();
      }
      const size_t records = file.Records.size();
      if (!TakeColumnLine(line, lineNumber, tokens, file, error))
      {
        return false;
      }
      if (stopAtRasterHeader && file.RasterHeader && (file.HasHeaderLine || !file.Records.empty()))
      {
        return true;
      }
      if (file.Records.size() > records && (file.Records.size() & 0x3fff) == 0)
      {
        progress(static_cast<double>(in.tellg()) / fileSize);
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
  if (file.Records.empty())
  {
    error = "no data lines (need lines of at least three numbers)";
    return false;
  }
  return true;
}

/// The mode the columns are read in: the requested one, else the header's, else integer first
/// two columns mean InlineCrossline, anything else XYZ. False when InlineCrossline meets
/// non-integer indices.
bool ChooseColumnMode(ColumnMode requested,
  const ColumnFile& file,
  ColumnMode& mode,
  std::string& error)
{
  mode = requested == ColumnMode::Auto ? ModeFromHeader(file.Header) : requested;
  const auto isIndex = [](const Record& r) { return IsIndexValue(r.A) && IsIndexValue(r.B); };
  const auto bad = std::find_if_not(file.Records.begin(), file.Records.end(), isIndex);
  if (mode == ColumnMode::Auto)
  {
    mode = bad == file.Records.end() ? ColumnMode::InlineCrossline : ColumnMode::XYZ;
  }
  if (mode == ColumnMode::InlineCrossline && bad != file.Records.end())
  {
    error = "line " + std::to_string(bad->Line) +
            ": inline and crossline must be integers (use the XYZ mode for world coordinates)";
    return false;
  }
  return true;
}

/// Where a grid lies and which node each record sets.
struct Placement
{
  long long NX = 1;
  long long NY = 1;
  std::vector<long long> I, J;
  double Origin[2] = { 0.0, 0.0 };
  double Spacing[2] = { 1.0, 1.0 };
  double Rotation = 0.0; // degrees
  long long FirstInline = 0, InlineStep = 0, FirstCrossline = 0, CrosslineStep = 0;
  double MaxDeviation = 0.0;
};

/// What places a grid of index numbers (InlineCrossline, Matrix) in the world.
struct IndexSettings
{
  bool IndexCoordinates = true;
  double Origin[2] = { 0.0, 0.0 };
  double InlineSpacing = 1.0;
  double CrosslineSpacing = 1.0;
  double Rotation = 0.0;
};

/// Places a grid whose node (i, j) is inline first + i * step, crossline first + j * step: at
/// its index numbers, or by the settings (spacing = step x bin size).
bool PlaceIndexGrid(const IndexSettings& settings, Placement& placement, std::string& error)
{
  Placement& p = placement;
  if (settings.IndexCoordinates)
  {
    p.Origin[0] = static_cast<double>(p.FirstInline);
    p.Origin[1] = static_cast<double>(p.FirstCrossline);
    p.Spacing[0] = static_cast<double>(p.InlineStep);
    p.Spacing[1] = static_cast<double>(p.CrosslineStep);
    p.Rotation = 0.0;
    return true;
  }
  if (!(settings.InlineSpacing > 0.0) || !(settings.CrosslineSpacing > 0.0) ||
      !std::isfinite(settings.InlineSpacing) || !std::isfinite(settings.CrosslineSpacing))
  {
    error = "InlineSpacing and CrosslineSpacing must be positive";
    return false;
  }
  p.Origin[0] = settings.Origin[0];
  p.Origin[1] = settings.Origin[1];
  p.Spacing[0] = p.InlineStep * settings.InlineSpacing;
  p.Spacing[1] = p.CrosslineStep * settings.CrosslineSpacing;
  p.Rotation = settings.Rotation;
  return true;
}

/// InlineCrossline mode: the grid spanned by the index columns, and each record's node.
bool PlaceByIndices(const std::vector<Record>& records,
  const IndexSettings& settings,
  Placement& p,
  std::string& error)
{
  IndexAxis(records, true, p.FirstInline, p.InlineStep, p.NX);
  IndexAxis(records, false, p.FirstCrossline, p.CrosslineStep, p.NY);
  if (!CheckGridSize(p.NX, p.NY, records.size(), error))
  {
    return false;
  }
  p.I.resize(records.size());
  p.J.resize(records.size());
  for (size_t k = 0; k < records.size(); ++k)
  {
    p.I[k] = (static_cast<long long>(records[k].A) - p.FirstInline) / p.InlineStep;
    p.J[k] = (static_cast<long long>(records[k].B) - p.FirstCrossline) / p.CrosslineStep;
  }
  return PlaceIndexGrid(settings, p, error);
}

/// XYZ mode: the lattice of the x y points (FitLattice), and each record's node.
bool PlaceByLattice(const std::vector<Record>& records,
  double tolerance,
  Placement& p,
  std::string& error)
{
  Lattice lattice;
  try
  {
    if (!FitLattice(records, tolerance, lattice, error))
    {
      return false;
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory while fitting the grid";
    return false;
  }
  p.NX = lattice.NX;
  p.NY = lattice.NY;
  p.I.swap(lattice.I);
  p.J.swap(lattice.J);
  std::copy(lattice.Origin, lattice.Origin + 2, p.Origin);
  std::copy(lattice.Spacing, lattice.Spacing + 2, p.Spacing);
  p.Rotation = lattice.Angle;
  p.MaxDeviation = lattice.MaxDeviation;
  return true;
}

/// The grid of the records: nodes that no line sets stay NaN, and so do NaN, infinite and
/// `nullValue` z (a NaN `nullValue`: none); the last line on a node wins. A finite z beyond
/// float's range is an error.
struct FilledGrid
{
  vtkSmartPointer<vtkFloatArray> Values;
  vtkIdType Duplicates = 0;
  vtkIdType NoData = 0;
};

bool FillGrid(const std::vector<Record>& records,
  const Placement& p,
  double nullValue,
  FilledGrid& grid,
  std::string& error)
{
  const vtkIdType total = static_cast<vtkIdType>(p.NX * p.NY);
  grid.Values = vtkSmartPointer<vtkFloatArray>::New();
  grid.Values->SetNumberOfTuples(total);
  if (grid.Values->GetNumberOfTuples() != total)
  {
    error = "cannot allocate the grid values";
    return false;
  }
  float* values = grid.Values->GetPointer(0);
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
  const bool hasNull = !std::isnan(nullValue);
  for (size_t k = 0; k < records.size(); ++k)
  {
    const vtkIdType id = static_cast<vtkIdType>(p.I[k] + p.J[k] * p.NX);
    grid.Duplicates += set[id] ? 1 : 0;
    set[id] = true;
    const double z = records[k].Z;
    const bool hole = !std::isfinite(z) || (hasNull && z == nullValue);
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
  grid.NoData = static_cast<vtkIdType>(
    std::count_if(values, values + total, [](float v) { return std::isnan(v); }));
  return true;
}

/// A small matrix read as columns puts its few rows on nodes already set, or on a grid that is
/// mostly holes (one row per node of a rows x rows grid): in Auto mode, an error that says so.
bool LooksLikeMatrix(const ColumnFile& file, const FilledGrid& grid, const Placement& p)
{
  return file.SameLength() && (grid.Duplicates > 0 || 2 * grid.NoData > p.NX * p.NY);
}

std::string MatrixReadAsColumnsMessage(const ColumnFile& file,
  const FilledGrid& grid,
  const Placement& p,
  ColumnMode mode)
{
  std::ostringstream msg;
  msg << "every data line holds " << file.MostValues << " values, and read as " << ModeName(mode)
      << " columns " << grid.Duplicates << " of them fall on a grid node already set and "
      << grid.NoData << " of the " << p.NX * p.NY << " nodes stay holes: this looks like a "
      << "whitespace matrix (one grid row per line), not columns; set Mode to Matrix to read it "
      << "as one, or to " << ModeName(mode) << " to read it as columns";
  return msg.str();
}

/// The settings that place a grid of index numbers.
IndexSettings IndexSettingsOf(vtkHorizonColumnReader* reader)
{
  IndexSettings settings;
  settings.IndexCoordinates = reader->GetIndexCoordinates();
  reader->GetOrigin(settings.Origin);
  settings.InlineSpacing = reader->GetInlineSpacing();
  settings.CrosslineSpacing = reader->GetCrosslineSpacing();
  settings.Rotation = reader->GetRotation();
  return settings;
}
}

//------------------------------------------------------------------------------
vtkHorizonColumnReader::vtkHorizonColumnReader() = default;

//------------------------------------------------------------------------------
vtkHorizonColumnReader::~vtkHorizonColumnReader() = default;

//------------------------------------------------------------------------------
void vtkHorizonColumnReader::ResetResults()
{
  this->Superclass::ResetResults();
  this->DetectedMode = ColumnMode::Auto;
  this->HasHeaderLine = false;
  this->NumberOfRecords = 0;
  this->NumberOfDuplicates = 0;
  this->FirstInline = 0;
  this->InlineStep = 0;
  this->FirstCrossline = 0;
  this->CrosslineStep = 0;
  this->MaxDeviation = 0.0;
}

//------------------------------------------------------------------------------
bool vtkHorizonColumnReader::ReadGridInformation(std::string& error)
{
  this->ResetResults();
  if (this->Mode == ColumnMode::Matrix)
  {
    return this->ReadMatrixGrid(error);
  }
  // Parsing takes the first 80% of the progress range, building the grid the rest.
  const bool autoMode = this->Mode == ColumnMode::Auto;
  ColumnFile file;
  this->UpdateProgress(0.0);
  if (!ReadColumnFile(
        this->FileName,
        autoMode,
        [this](double fraction) { this->UpdateProgress(0.8 * fraction); },
        file,
        error))
  {
    return false;
  }
  // A raster header, or every line as long as the others and longer than any columns file's: a
  // matrix.
  if (autoMode &&
      (file.RasterHeader || (file.SameLength() && !file.HasHeaderLine &&
                              file.MostValues > static_cast<size_t>(MatrixMinimumColumns))))
  {
    return this->ReadMatrixGrid(error);
  }
  ColumnMode mode = ColumnMode::Auto;
  Placement placement;
  if (!ChooseColumnMode(this->Mode, file, mode, error) ||
      !(mode == ColumnMode::InlineCrossline
          ? PlaceByIndices(file.Records, IndexSettingsOf(this), placement, error)
          : PlaceByLattice(file.Records, this->Tolerance, placement, error)))
  {
    return false;
  }
  this->UpdateProgress(0.85);
  FilledGrid grid;
  if (!FillGrid(file.Records, placement, this->NullValue, grid, error))
  {
    return false;
  }
  if (autoMode && LooksLikeMatrix(file, grid, placement))
  {
    error = MatrixReadAsColumnsMessage(file, grid, placement, mode);
    return false;
  }

  this->DetectedMode = mode;
  this->HasHeaderLine = file.HasHeaderLine;
  this->NumberOfRecords = static_cast<vtkIdType>(file.Records.size());
  this->NumberOfDuplicates = grid.Duplicates;
  this->NumberOfNoDataValues = grid.NoData;
  this->NX = static_cast<int>(placement.NX);
  this->NY = static_cast<int>(placement.NY);
  this->FirstInline = placement.FirstInline;
  this->InlineStep = placement.InlineStep;
  this->FirstCrossline = placement.FirstCrossline;
  this->CrosslineStep = placement.CrosslineStep;
  std::copy(placement.Origin, placement.Origin + 2, this->GridOrigin);
  std::copy(placement.Spacing, placement.Spacing + 2, this->GridSpacing);
  this->GridRotation = placement.Rotation;
  this->MaxDeviation = placement.MaxDeviation;
  this->SetPendingValues(grid.Values);
  if (grid.Duplicates > 0)
  {
    vtkWarningMacro(<< this->FileName << ": " << grid.Duplicates
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
  // The file's extents place it when it gives them; else its index numbers, as a grid of
  // inlines and crosslines numbered from 0 in steps of 1.
  Placement placement;
  placement.InlineStep = placement.CrosslineStep = 1;
  if (matrix.HasGeometry)
  {
    std::copy(matrix.Origin, matrix.Origin + 2, placement.Origin);
    std::copy(matrix.Spacing, matrix.Spacing + 2, placement.Spacing);
  }
  else if (!PlaceIndexGrid(IndexSettingsOf(this), placement, error))
  {
    return false;
  }
  std::copy(placement.Origin, placement.Origin + 2, this->GridOrigin);
  std::copy(placement.Spacing, placement.Spacing + 2, this->GridSpacing);
  this->GridRotation = placement.Rotation;
  vtkSmartPointer<vtkDataArray> grid =
    NewValues(VTK_FLOAT, static_cast<vtkIdType>(matrix.Values.size()), error);
  if (!grid)
  {
    return false;
  }
  std::copy(matrix.Values.begin(),
    matrix.Values.end(),
    static_cast<vtkFloatArray*>(grid.GetPointer())->GetPointer(0));
  this->DetectedMode = ColumnMode::Matrix;
  this->NumberOfRecords = matrix.NumberOfLines;
  this->NX = matrix.NX;
  this->NY = matrix.NY;
  this->NumberOfNoDataValues = static_cast<vtkIdType>(matrix.NumberOfNoDataValues);
  this->SetPendingValues(grid);
  return true;
}

//------------------------------------------------------------------------------
void vtkHorizonColumnReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
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
  os << indent << "FirstInline: " << this->FirstInline << "\n";
  os << indent << "InlineStep: " << this->InlineStep << "\n";
  os << indent << "FirstCrossline: " << this->FirstCrossline << "\n";
  os << indent << "CrosslineStep: " << this->CrosslineStep << "\n";
  os << indent << "MaxDeviation: " << this->MaxDeviation << "\n";
}

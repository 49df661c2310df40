// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataAsciiGridParser.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <string_view>

namespace strata_io
{
namespace
{
// Same bound as the other horizon readers: 2^31 nodes or more is not a horizon.
constexpr double MaxNodes = 2147483647.0;
// Every value in a text grid takes at least one character and one separator.
constexpr double MinBytesPerValue = 2.0;
// Irap's nominal undefined value; like the binary reader, magnitudes from 1e30 are holes too.
constexpr double IrapUndefined = 9999900.0;
constexpr double IrapHuge = 1e30;

/// The text of the file, walked line by line.
class Text
{
public:
  explicit Text(std::string data)
    : Data(std::move(data))
  {
  }

  /// The next line (without its end of line and '\r'); false at the end.
  bool NextLine(std::string_view& line)
  {
    if (this->Position >= this->Data.size())
    {
      return false;
    }
    const size_t end = this->Data.find('\n', this->Position);
    const size_t stop = end == std::string::npos ? this->Data.size() : end;
    line = std::string_view(this->Data).substr(this->Position, stop - this->Position);
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    this->Position = end == std::string::npos ? this->Data.size() : end + 1;
    ++this->Line;
    return true;
  }

  long long LineNumber() const { return this->Line; }
  const char* End() const { return this->Data.data() + this->Data.size(); }
  double BytesLeft() const { return static_cast<double>(this->Data.size() - this->Position); }

private:
  std::string Data;
  size_t Position = 0;
  long long Line = 0;
};

bool IsSeparator(char c)
{
  return c == ',' || c == ';' || std::isspace(static_cast<unsigned char>(c));
}

bool IsBlank(std::string_view line)
{
  return std::all_of(
    line.begin(), line.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

std::string_view Trim(std::string_view s)
{
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
  {
    s.remove_prefix(1);
  }
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
  {
    s.remove_suffix(1);
  }
  return s;
}

/// Splits at runs of whitespace, commas and semicolons.
void Tokenize(std::string_view line, std::vector<std::string_view>& tokens)
{
  tokens.clear();
  size_t k = 0;
  while (k < line.size())
  {
    while (k < line.size() && IsSeparator(line[k]))
    {
      ++k;
    }
    const size_t start = k;
    while (k < line.size() && !IsSeparator(line[k]))
    {
      ++k;
    }
    if (k > start)
    {
      tokens.push_back(line.substr(start, k - start));
    }
  }
}

/// Splits at commas only, keeping empty fields (ZMAP+ header lines).
std::vector<std::string_view> CommaFields(std::string_view line)
{
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true)
  {
    const size_t comma = line.find(',', start);
    fields.push_back(
      Trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos)
    {
      return fields;
    }
    start = comma + 1;
  }
}

/// A whole token as a number, locale-independent ("1.5", "-2e3", "nan", "+4").
bool ParseNumber(std::string_view token, double& value)
{
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin < end && *begin == '+')
  {
    ++begin;
  }
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && begin < end;
}

std::string Lower(std::string_view s)
{
  std::string out(s);
  std::transform(out.begin(),
    out.end(),
    out.begin(),
    [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  return out;
}

/// The token quoted for a message, non-printable bytes made '?', at most 40 characters.
std::string Shown(std::string_view token)
{
  std::string s(token.substr(0, 40));
  std::replace_if(
    s.begin(), s.end(), [](char c) { return !std::isprint(static_cast<unsigned char>(c)); }, '?');
  return "\"" + s + (token.size() > 40 ? "...\"" : "\"");
}

std::string AtLine(long long line)
{
  return "line " + std::to_string(line) + ": ";
}

/// Reads the whole file; false with a message when it cannot.
bool Slurp(const std::string& path, std::string& data, std::string& error)
{
  if (path.empty())
  {
    error = "no file name set";
    return false;
  }
  if (!vtksys::SystemTools::FileExists(path, /*isFile=*/true))
  {
    error = "file does not exist or is not a regular file";
    return false;
  }
  vtksys::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
  if (!in)
  {
    error = "cannot open file";
    return false;
  }
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0)
  {
    error = "cannot tell the size of the file";
    return false;
  }
  try
  {
    data.resize(static_cast<size_t>(size));
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory for the file's " + std::to_string(size) + " bytes";
    return false;
  }
  if (size > 0 && !in.read(&data[0], size))
  {
    error = "read error";
    return false;
  }
  return true;
}

/// Sets up grid.Values for nx x ny nodes, all NaN.
bool AllocateValues(AsciiGrid& grid, std::string& error)
{
  try
  {
    grid.Values.assign(static_cast<size_t>(grid.NX) * static_cast<size_t>(grid.NY),
      std::numeric_limits<float>::quiet_NaN());
  }
  catch (const std::bad_alloc&)
  {
    error =
      "out of memory for " + std::to_string(grid.NX) + " x " + std::to_string(grid.NY) + " values";
    return false;
  }
  return true;
}

/// Stores a value read from the file at node `id`: a hole when NaN, infinite or one of the
/// no-data values, else the value as float.
class ValueSink
{
public:
  ValueSink(AsciiGrid& grid, const AsciiGridOptions& options, bool irapHoles)
    : Grid(grid)
    , Extra(options.NullValue)
    , IrapHoles(irapHoles)
  {
  }

  void Set(size_t id, double v)
  {
    bool hole = !std::isfinite(v) || (!std::isnan(this->Extra) && v == this->Extra);
    if (this->IrapHoles)
    {
      hole = hole || v == IrapUndefined || std::fabs(v) >= IrapHuge;
    }
    else if (!std::isnan(this->Grid.FileNullValue))
    {
      // Written with the header's number of decimals the null value may come back rounded.
      const double null = this->Grid.FileNullValue;
      hole = hole || std::fabs(v - null) <= 1e-9 * std::max(1.0, std::fabs(null));
    }
    // A value no float holds (|v| > 3.4e38, not a no-data value) would become infinity: counted,
    // and the read fails with it.
    if (!hole && std::fabs(v) > std::numeric_limits<float>::max())
    {
      if (this->Grid.OutOfRangeValues++ == 0)
      {
        this->Grid.FirstOutOfRange = v;
      }
      hole = true;
    }
    this->Grid.Values[id] = hole ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(v);
    this->Grid.NumberOfNoDataValues += hole ? 1 : 0;
  }

private:
  AsciiGrid& Grid;
  double Extra;
  bool IrapHoles;
};

/// Reads header numbers one after the other, across lines, skipping blank lines.
class NumberStream
{
public:
  explicit NumberStream(Text& text)
    : Source(text)
  {
  }

  /// The next number; false with a message (naming `field`) at the end or on a non-number.
  bool Next(const char* field, double& value, std::string& error)
  {
    while (this->Index >= this->Tokens.size())
    {
      std::string_view line;
      if (!this->Source.NextLine(line))
      {
        error = std::string("the file ends before ") + field;
        return false;
      }
      this->Split(line);
      this->Index = 0;
    }
    const std::string_view token = this->Tokens[this->Index++];
    if (!ParseNumber(token, value))
    {
      error = AtLine(this->Source.LineNumber()) + field + " is " + Shown(token) + ", not a number";
      return false;
    }
    return true;
  }

  /// ZMAP+: the header's field width. A line holding something that is not a number with
  /// separators (writers let wide values touch: "-1234.5678-1234.5678") is cut into fields
  /// of this width instead. 0: never.
  int FieldWidth = 0;

  /// Tokens of the current line not consumed yet.
  size_t Pending() const { return this->Tokens.size() - this->Index; }

  /// Reads `count` values into the sink (node of value k: node(k)); false on a non-number, too
  /// few values, or more values than `count`. `done` values were read before (for messages).
  template<typename Node>
  bool Values(size_t count, ValueSink& sink, Node node, std::string& error, size_t done = 0)
  {
    for (size_t k = 0; k < count; ++k)
    {
      while (this->Index >= this->Tokens.size())
      {
        std::string_view line;
        if (!this->Source.NextLine(line))
        {
          error = "the file ends after " + std::to_string(done + k) + " of the " +
                  std::to_string(done + count) + " values the header announces";
          return false;
        }
        this->Split(line);
        this->Index = 0;
      }
      const std::string_view token = this->Tokens[this->Index++];
      double v = 0.0;
      if (!ParseNumber(token, v))
      {
        error = AtLine(this->Source.LineNumber()) + "value " + std::to_string(done + k + 1) +
                " is " + Shown(token) + ", not a number";
        return false;
      }
      sink.Set(node(k), v);
    }
    return this->NothingAfter(done + count, error);
  }

  /// False (with a message) when anything but blanks follows the values.
  bool NothingAfter(size_t count, std::string& error)
  {
    std::string_view line;
    while (this->Index >= this->Tokens.size() && this->Source.NextLine(line))
    {
      this->Split(line);
      this->Index = 0;
    }
    if (this->Index < this->Tokens.size())
    {
      error = AtLine(this->Source.LineNumber()) + "more values than the " + std::to_string(count) +
              " the header announces (" + Shown(this->Tokens[this->Index]) +
              "): the header does not describe this data";
      return false;
    }
    return true;
  }

  Text& Source;

private:
  void Split(std::string_view line)
  {
    Tokenize(line, this->Tokens);
    double v = 0.0;
    auto numbers = [&](const std::vector<std::string_view>& tokens)
    {
      return std::all_of(
        tokens.begin(), tokens.end(), [&](std::string_view t) { return ParseNumber(t, v); });
    };
    if (this->FieldWidth <= 0 || numbers(this->Tokens))
    {
      return;
    }
    // Fields of the width, used only when they all are numbers: otherwise the whitespace tokens
    // stay, so that the error quotes the offending one.
    std::vector<std::string_view> fields;
    const size_t w = static_cast<size_t>(this->FieldWidth);
    for (size_t at = 0; at < line.size(); at += w)
    {
      const std::string_view field = Trim(line.substr(at, w));
      if (!field.empty())
      {
        fields.push_back(field);
      }
    }
    if (numbers(fields))
    {
      this->Tokens.swap(fields);
    }
  }

  std::vector<std::string_view> Tokens;
  size_t Index = 0;
};

bool PositiveFinite(const char* field, double v, std::string& error)
{
  if (!(v > 0.0) || !std::isfinite(v))
  {
    std::ostringstream msg;
    msg << field << " = " << v << ": must be a positive number";
    error = msg.str();
    return false;
  }
  return true;
}

bool Finite(const char* field, double v, std::string& error)
{
  if (!std::isfinite(v))
  {
    error = std::string(field) + " is not a finite number";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool ReadIrapClassic(Text& text,
  const AsciiGridOptions& options,
  AsciiGrid& grid,
  std::string& error)
{
  NumberStream numbers(text);
  double magic = 0, ny = 0, xinc = 0, yinc = 0, xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  double nx = 0, rot = 0, xori = 0, yori = 0;
  if (!numbers.Next("the -996 that starts an Irap classic grid", magic, error))
  {
    return false;
  }
  if (magic != -996.0)
  {
    std::ostringstream msg;
    msg << "not an Irap classic grid: the first value is " << magic << ", not -996";
    error = msg.str();
    return false;
  }
  if (!numbers.Next("ny", ny, error) || !numbers.Next("xinc", xinc, error) ||
      !numbers.Next("yinc", yinc, error) || !numbers.Next("xmin", xmin, error) ||
      !numbers.Next("xmax", xmax, error) || !numbers.Next("ymin", ymin, error) ||
      !numbers.Next("ymax", ymax, error) || !numbers.Next("nx", nx, error) ||
      !numbers.Next("rotation", rot, error) || !numbers.Next("xori", xori, error) ||
      !numbers.Next("yori", yori, error))
  {
    return false;
  }
  for (int k = 0; k < 7; ++k)
  {
    double zero = 0.0;
    if (!numbers.Next("the seven integers of the fourth header line", zero, error))
    {
      return false;
    }
  }
  if (!CheckAsciiGridDimensions(
        "nx", nx, "ny", ny, text.BytesLeft() / MinBytesPerValue + numbers.Pending(), error) ||
      !PositiveFinite("xinc", xinc, error) || !PositiveFinite("yinc", yinc, error) ||
      !Finite("rotation", rot, error) || !Finite("xori", xori, error) ||
      !Finite("yori", yori, error))
  {
    return false;
  }
  grid.NX = static_cast<int>(nx);
  grid.NY = static_cast<int>(ny);
  grid.Origin[0] = xori;
  grid.Origin[1] = yori;
  grid.Spacing[0] = xinc;
  grid.Spacing[1] = yinc;
  grid.Rotation = rot;
  grid.Bounds[0] = xmin;
  grid.Bounds[1] = xmax;
  grid.Bounds[2] = ymin;
  grid.Bounds[3] = ymax;
  grid.FileNullValue = IrapUndefined;
  if (!AllocateValues(grid, error))
  {
    return false;
  }
  // Values x fastest, rows from ymin up: file order is node order.
  ValueSink sink(grid, options, /*irapHoles=*/true);
  return numbers.Values(
    grid.Values.size(), sink, [](size_t k) { return k; }, error);
}

//------------------------------------------------------------------------------
/// The next ZMAP+ header line: not blank, not a '!' comment.
bool ZmapHeaderLine(Text& text, const char* what, std::string_view& line, std::string& error)
{
  while (text.NextLine(line))
  {
    const std::string_view t = Trim(line);
    if (!t.empty() && t.front() != '!')
    {
      line = t;
      return true;
    }
  }
  error = std::string("the file ends before the ZMAP+ header's ") + what;
  return false;
}

bool ZmapNumber(std::string_view field,
  const char* name,
  long long line,
  double& v,
  std::string& error)
{
  if (!ParseNumber(field, v))
  {
    error = AtLine(line) + name + " is " + Shown(field) + ", not a number";
    return false;
  }
  return true;
}

/// The '@' line, the format line (field width, null value, [null text], decimals, start column)
/// and the dimensions line; leaves `text` after the closing '@'.
bool ReadZmapHeader(Text& text, AsciiGrid& grid, double& rows, double& cols, std::string& error)
{
  std::string_view line;
  if (!ZmapHeaderLine(text, "'@' line", line, error))
  {
    return false;
  }
  std::vector<std::string_view> f = CommaFields(line.substr(1));
  if (line.front() != '@' || f.size() < 3 || Lower(f[1]) != "grid")
  {
    error = AtLine(text.LineNumber()) +
            "expected the ZMAP+ header \"@<name> HEADER, GRID, <nodes per line>\", found " +
            Shown(line);
    return false;
  }
  grid.Name = std::string(f[0]);
  double perLine = 0.0;
  if (!ZmapNumber(f[2], "nodes per line", text.LineNumber(), perLine, error))
  {
    return false;
  }
  if (!(perLine >= 1.0 && perLine <= 1e6) || perLine != std::floor(perLine))
  {
    error = AtLine(text.LineNumber()) + "nodes per line = " + std::string(f[2]) +
            ": must be a positive integer";
    return false;
  }
  grid.NodesPerLine = static_cast<int>(perLine);

  if (!ZmapHeaderLine(text, "format line", line, error))
  {
    return false;
  }
  f = CommaFields(line);
  if (f.size() != 4 && f.size() != 5)
  {
    error = AtLine(text.LineNumber()) +
            "expected \"field width, null value, [null text,] decimals, start column\", found " +
            Shown(line);
    return false;
  }
  // Five fields: the null value is the second, or the third (as text) when the second is empty.
  const std::string_view null = (f.size() == 5 && f[1].empty()) ? f[2] : f[1];
  double width = 0.0, nullValue = 0.0;
  if (!ZmapNumber(f[0], "field width", text.LineNumber(), width, error) ||
      !ZmapNumber(null, "null value", text.LineNumber(), nullValue, error))
  {
    return false;
  }
  grid.FileNullValue = nullValue;
  grid.FieldWidth =
    (width >= 1.0 && width <= 1000.0 && width == std::floor(width)) ? static_cast<int>(width) : 0;

  if (!ZmapHeaderLine(text, "dimensions line", line, error))
  {
    return false;
  }
  std::vector<std::string_view> tokens;
  Tokenize(line, tokens);
  double d[6];
  const char* names[6] = { "rows", "columns", "min X", "max X", "min Y", "max Y" };
  if (tokens.size() != 6)
  {
    error = AtLine(text.LineNumber()) +
            "expected \"rows, columns, min X, max X, min Y, max Y\", found " + Shown(line);
    return false;
  }
  for (int k = 0; k < 6; ++k)
  {
    if (!ZmapNumber(tokens[k], names[k], text.LineNumber(), d[k], error) ||
        !Finite(names[k], d[k], error))
    {
      return false;
    }
  }
  rows = d[0];
  cols = d[1];
  std::copy(d + 2, d + 6, grid.Bounds);

  if (!ZmapHeaderLine(text, "transformation line (0.0, 0.0, 0.0)", line, error))
  {
    return false;
  }
  Tokenize(line, tokens);
  if (tokens.size() != 3)
  {
    error = AtLine(text.LineNumber()) + "expected the line \"0.0, 0.0, 0.0\", found " + Shown(line);
    return false;
  }
  if (!ZmapHeaderLine(text, "closing '@'", line, error))
  {
    return false;
  }
  if (line != "@")
  {
    error = AtLine(text.LineNumber()) + "expected the '@' that ends the ZMAP+ header, found " +
            Shown(line);
    return false;
  }
  return true;
}

bool ReadZmap(Text& text, const AsciiGridOptions& options, AsciiGrid& grid, std::string& error)
{
  double rows = 0.0, cols = 0.0;
  if (!ReadZmapHeader(text, grid, rows, cols, error) ||
      !CheckAsciiGridDimensions(
        "columns", cols, "rows", rows, text.BytesLeft() / MinBytesPerValue, error))
  {
    return false;
  }
  grid.NX = static_cast<int>(cols);
  grid.NY = static_cast<int>(rows);
  const double* b = grid.Bounds;
  if ((grid.NX > 1 && !(b[1] > b[0])) || (grid.NY > 1 && !(b[3] > b[2])))
  {
    error = "max X must exceed min X and max Y min Y (the bounds of the nodes)";
    return false;
  }
  grid.Origin[0] = b[0];
  grid.Origin[1] = b[2];
  grid.Spacing[0] = grid.NX > 1 ? (b[1] - b[0]) / (grid.NX - 1) : 1.0;
  grid.Spacing[1] = grid.NY > 1 ? (b[3] - b[2]) / (grid.NY - 1) : 1.0;
  if (!AllocateValues(grid, error))
  {
    return false;
  }
  // Column-major, each column from the top (max Y) down.
  const size_t nx = static_cast<size_t>(grid.NX);
  const size_t ny = static_cast<size_t>(grid.NY);
  ValueSink sink(grid, options, /*irapHoles=*/false);
  NumberStream numbers(text);
  numbers.FieldWidth = grid.FieldWidth;
  return numbers.Values(
    nx * ny, sink, [&](size_t k) { return k / ny + (ny - 1 - k % ny) * nx; }, error);
}

//------------------------------------------------------------------------------
bool ReadEsri(Text& text, const AsciiGridOptions& options, AsciiGrid& grid, std::string& error)
{
  // Header: "key value" lines in any order, until the first line that starts with a number.
  double ncols = -1, nrows = -1, x = 0, y = 0, cellsize = -1, dx = -1, dy = -1;
  bool hasX = false, hasY = false, xCorner = false, yCorner = false;
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::string_view firstValues;
  long long firstValuesLine = 0;
  while (text.NextLine(line))
  {
    Tokenize(line, tokens);
    if (tokens.empty())
    {
      continue;
    }
    double v = 0.0;
    if (ParseNumber(tokens[0], v))
    {
      firstValues = line;
      firstValuesLine = text.LineNumber();
      break;
    }
    const std::string key = Lower(tokens[0]);
    if (tokens.size() != 2 || !ParseNumber(tokens[1], v))
    {
      error = AtLine(text.LineNumber()) + "expected \"" + key + " <number>\", found " + Shown(line);
      return false;
    }
    if (key == "ncols")
      ncols = v;
    else if (key == "nrows")
      nrows = v;
    else if (key == "xllcorner" || key == "xllcenter")
    {
      x = v;
      hasX = true;
      xCorner = key == "xllcorner";
    }
    else if (key == "yllcorner" || key == "yllcenter")
    {
      y = v;
      hasY = true;
      yCorner = key == "yllcorner";
    }
    else if (key == "cellsize")
      cellsize = v;
    else if (key == "dx")
      dx = v;
    else if (key == "dy")
      dy = v;
    else if (key == "nodata_value")
      grid.FileNullValue = v;
    else
    {
      error = AtLine(text.LineNumber()) + "unknown ESRI ASCII grid header key " + Shown(tokens[0]);
      return false;
    }
  }
  if (ncols < 0 || nrows < 0 || !hasX || !hasY || (cellsize < 0 && (dx < 0 || dy < 0)))
  {
    error = "the ESRI ASCII grid header needs ncols, nrows, xllcorner or xllcenter, yllcorner or "
            "yllcenter, and cellsize (or dx and dy)";
    return false;
  }
  if (xCorner != yCorner)
  {
    error = "the ESRI ASCII grid header mixes a corner and a centre (xll... and yll...)";
    return false;
  }
  if (cellsize >= 0)
  {
    dx = dy = cellsize;
  }
  const double maxValues = (text.BytesLeft() + firstValues.size() + 1) / MinBytesPerValue;
  if (!CheckAsciiGridDimensions("ncols", ncols, "nrows", nrows, maxValues, error) ||
      !PositiveFinite(cellsize >= 0 ? "cellsize" : "dx", dx, error) ||
      !PositiveFinite(cellsize >= 0 ? "cellsize" : "dy", dy, error) ||
      !Finite(xCorner ? "xllcorner" : "xllcenter", x, error) ||
      !Finite(yCorner ? "yllcorner" : "yllcenter", y, error))
  {
    return false;
  }
  grid.NX = static_cast<int>(ncols);
  grid.NY = static_cast<int>(nrows);
  grid.CellCorner = xCorner;
  // Values are cells; their centres are the nodes.
  grid.Origin[0] = xCorner ? x + 0.5 * dx : x;
  grid.Origin[1] = yCorner ? y + 0.5 * dy : y;
  grid.Spacing[0] = dx;
  grid.Spacing[1] = dy;
  grid.Bounds[0] = grid.Origin[0];
  grid.Bounds[1] = grid.Origin[0] + (grid.NX - 1) * dx;
  grid.Bounds[2] = grid.Origin[1];
  grid.Bounds[3] = grid.Origin[1] + (grid.NY - 1) * dy;
  if (firstValues.empty())
  {
    error = "the ESRI ASCII grid has a header but no values";
    return false;
  }
  if (!AllocateValues(grid, error))
  {
    return false;
  }
  // Rows from the top (max y) down, x fastest. The first value line was already taken from the
  // text: read its values here, then the rest through the stream.
  const size_t nx = static_cast<size_t>(grid.NX);
  const size_t ny = static_cast<size_t>(grid.NY);
  const size_t total = nx * ny;
  auto node = [&](size_t k) { return k % nx + (ny - 1 - k / nx) * nx; };
  ValueSink sink(grid, options, /*irapHoles=*/false);
  Tokenize(firstValues, tokens);
  size_t k = 0;
  for (; k < tokens.size(); ++k)
  {
    double v = 0.0;
    if (k >= total)
    {
      error = AtLine(firstValuesLine) +
              "more values than the ncols x nrows = " + std::to_string(total) +
              " the header announces";
      return false;
    }
    if (!ParseNumber(tokens[k], v))
    {
      error = AtLine(firstValuesLine) + "value " + std::to_string(k + 1) + " is " +
              Shown(tokens[k]) + ", not a number";
      return false;
    }
    sink.Set(node(k), v);
  }
  const size_t done = k;
  NumberStream numbers(text);
  return numbers.Values(
    total - done, sink, [&](size_t m) { return node(m + done); }, error, done);
}

//------------------------------------------------------------------------------
/// What the '#' lines above a matrix may say of it, as DEM exports write them:
/// "# Dimensions: 327 468" (values per row, rows), "# x_extent = 0 3260" (first and last node),
/// "# y_extent: ...", "# nodata: -9999".
struct MatrixHeader
{
  double Dimensions[2] = { 0.0, 0.0 };
  double XExtent[2] = { 0.0, 0.0 };
  double YExtent[2] = { 0.0, 0.0 };
  double NoData = std::numeric_limits<double>::quiet_NaN();
  bool HasDimensions = false;
  bool HasXExtent = false;
  bool HasYExtent = false;
  long long DimensionsLine = 0;

  /// The header describes a raster: lines are rows of x from the top.
  bool Raster() const { return this->HasDimensions || this->HasXExtent || this->HasYExtent; }
};

enum class MatrixKey
{
  None,
  Dimensions,
  XExtent,
  YExtent,
  NoData
};

/// The key of a comment line "# key: values" or "# key = values" (any case, '_' and blanks in
/// the key ignored) and the text after the separator; None for any other line.
MatrixKey MatrixHeaderKey(std::string_view line, std::string_view& values)
{
  std::string_view t = Trim(line);
  if (t.empty() || t.front() != '#')
  {
    return MatrixKey::None;
  }
  t.remove_prefix(std::min(t.find_first_not_of('#'), t.size()));
  const size_t separator = t.find_first_of(":=");
  if (separator == std::string_view::npos)
  {
    return MatrixKey::None;
  }
  std::string key;
  for (char c : t.substr(0, separator))
  {
    if (c != '_' && !std::isspace(static_cast<unsigned char>(c)))
    {
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  values = t.substr(separator + 1);
  if (key == "dimensions")
    return MatrixKey::Dimensions;
  if (key == "xextent")
    return MatrixKey::XExtent;
  if (key == "yextent")
    return MatrixKey::YExtent;
  if (key == "nodata" || key == "nodatavalue")
    return MatrixKey::NoData;
  return MatrixKey::None;
}

/// Reads `count` numbers after a header key into `out`; false with a message otherwise.
bool MatrixHeaderNumbers(std::string_view values,
  const char* key,
  size_t count,
  long long line,
  double* out,
  std::string& error)
{
  std::vector<std::string_view> tokens;
  Tokenize(values, tokens);
  bool ok = tokens.size() == count;
  for (size_t k = 0; ok && k < count; ++k)
  {
    ok = ParseNumber(tokens[k], out[k]) && std::isfinite(out[k]);
  }
  if (!ok)
  {
    error = AtLine(line) + key + " needs " + (count == 1 ? "one number" : "two numbers") +
            ", found " + Shown(values);
  }
  return ok;
}

/// Takes a comment line into `header` when it is one of the matrix header's keys; false (with a
/// message) when it is one but its values are not what the key needs.
bool ReadMatrixHeaderLine(std::string_view line,
  long long lineNumber,
  MatrixHeader& header,
  std::string& error)
{
  std::string_view values;
  switch (MatrixHeaderKey(line, values))
  {
    case MatrixKey::Dimensions:
      header.HasDimensions = true;
      header.DimensionsLine = lineNumber;
      return MatrixHeaderNumbers(
        values, "Dimensions (values per row, rows)", 2, lineNumber, header.Dimensions, error);
    case MatrixKey::XExtent:
      header.HasXExtent = true;
      return MatrixHeaderNumbers(
        values, "x_extent (xmin xmax)", 2, lineNumber, header.XExtent, error);
    case MatrixKey::YExtent:
      header.HasYExtent = true;
      return MatrixHeaderNumbers(
        values, "y_extent (ymin ymax)", 2, lineNumber, header.YExtent, error);
    case MatrixKey::NoData:
      return MatrixHeaderNumbers(values, "nodata", 1, lineNumber, &header.NoData, error);
    default:
      return true;
  }
}

/// The rows of numbers of a matrix as they come (the file bounds them), and the header of '#'
/// lines before the first row.
struct MatrixRows
{
  MatrixHeader Header;
  std::vector<double> Values;
  size_t Columns = 0;
  size_t Rows = 0;
};

bool ReadMatrixRows(Text& text, MatrixRows& matrix, std::string& error)
{
  std::vector<std::string_view> tokens;
  std::string_view line;
  long long firstLine = 0;
  while (text.NextLine(line))
  {
    const std::string_view t = Trim(line);
    if (t.empty() || t.front() == '#')
    {
      if (matrix.Rows == 0 && !ReadMatrixHeaderLine(t, text.LineNumber(), matrix.Header, error))
      {
        return false;
      }
      continue;
    }
    Tokenize(t, tokens);
    if (matrix.Rows == 0)
    {
      matrix.Columns = tokens.size();
      firstLine = text.LineNumber();
    }
    else if (tokens.size() != matrix.Columns)
    {
      error = AtLine(text.LineNumber()) + "a row of " + std::to_string(tokens.size()) +
              " values, but line " + std::to_string(firstLine) + " has " +
              std::to_string(matrix.Columns) +
              ": the rows of a matrix must all have the same length";
      return false;
    }
    for (size_t c = 0; c < tokens.size(); ++c)
    {
      double v = 0.0;
      if (!ParseNumber(tokens[c], v))
      {
        error = AtLine(text.LineNumber()) + "value " + std::to_string(c + 1) + " is " +
                Shown(tokens[c]) + ", not a number";
        return false;
      }
      matrix.Values.push_back(v);
    }
    ++matrix.Rows;
  }
  if (matrix.Rows == 0)
  {
    error = "no rows of numbers";
    return false;
  }
  return true;
}

/// A raster matrix's header against its data: Dimensions equal to (values per row, rows), both
/// extents or neither, each increasing along an axis of more than one node.
bool CheckMatrixHeader(const MatrixRows& matrix, std::string& error)
{
  const MatrixHeader& h = matrix.Header;
  const double columns = static_cast<double>(matrix.Columns);
  const double rows = static_cast<double>(matrix.Rows);
  std::ostringstream msg;
  if (h.HasDimensions && (h.Dimensions[0] != columns || h.Dimensions[1] != rows))
  {
    msg << AtLine(h.DimensionsLine) << "the header's Dimensions " << h.Dimensions[0] << " "
        << h.Dimensions[1] << " (values per row, rows) do not match the data: " << columns
        << " values per row, " << rows << " rows";
    if (h.Dimensions[0] == rows && h.Dimensions[1] == columns)
    {
      msg << " (they are its rows and values per row, the other way round)";
    }
    msg << ": the header does not describe this data";
    error = msg.str();
    return false;
  }
  if (h.HasXExtent != h.HasYExtent)
  {
    error = std::string("the header gives ") +
            (h.HasXExtent ? "x_extent but no y_extent" : "y_extent but no x_extent") +
            ": a matrix is placed by both or by neither";
    return false;
  }
  if ((h.HasXExtent && columns > 1 && !(h.XExtent[1] > h.XExtent[0])) ||
      (h.HasYExtent && rows > 1 && !(h.YExtent[1] > h.YExtent[0])))
  {
    msg << "x_extent " << h.XExtent[0] << " " << h.XExtent[1] << ", y_extent " << h.YExtent[0]
        << " " << h.YExtent[1] << ": each must go from the smaller value to the larger";
    error = msg.str();
    return false;
  }
  return true;
}

/// A raster matrix's geometry: node bounds from the extents (or zeros), spacing over the nodes.
void PlaceRasterMatrix(const MatrixHeader& h, AsciiGrid& grid)
{
  grid.RowsFromTop = true;
  grid.HasGeometry = h.HasXExtent && h.HasYExtent;
  if (!grid.HasGeometry)
  {
    return;
  }
  const double* extent[2] = { h.XExtent, h.YExtent };
  const int count[2] = { grid.NX, grid.NY };
  for (int a = 0; a < 2; ++a)
  {
    grid.Origin[a] = extent[a][0];
    grid.Spacing[a] = count[a] > 1 ? (extent[a][1] - extent[a][0]) / (count[a] - 1) : 1.0;
    grid.Bounds[2 * a] = extent[a][0];
    grid.Bounds[2 * a + 1] = extent[a][1];
  }
}

bool ReadMatrix(Text& text, const AsciiGridOptions& options, AsciiGrid& grid, std::string& error)
{
  MatrixRows matrix;
  try
  {
    if (!ReadMatrixRows(text, matrix, error))
    {
      return false;
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "out of memory while reading the matrix";
    return false;
  }
  const bool raster = matrix.Header.Raster();
  if (raster && !CheckMatrixHeader(matrix, error))
  {
    return false;
  }
  // A raster's lines are rows of x (as are a matrix's with SwapAxes); otherwise line r is the
  // column i = r, numpy's first axis being x as vtkNumpyGridReader has it.
  const bool linesAreRows = raster || options.SwapAxes;
  const size_t rows = matrix.Rows;
  const size_t columns = matrix.Columns;
  const double nx = static_cast<double>(linesAreRows ? columns : rows);
  const double ny = static_cast<double>(linesAreRows ? rows : columns);
  if (!CheckAsciiGridDimensions(linesAreRows ? "values per row" : "rows",
        nx,
        linesAreRows ? "rows" : "values per row",
        ny,
        MaxNodes,
        error))
  {
    return false;
  }
  grid.NX = static_cast<int>(nx);
  grid.NY = static_cast<int>(ny);
  grid.NumberOfLines = static_cast<int>(rows);
  grid.FileNullValue = matrix.Header.NoData;
  if (raster)
  {
    PlaceRasterMatrix(matrix.Header, grid);
  }
  if (!AllocateValues(grid, error))
  {
    return false;
  }
  // Row r, column c is node (r, c); node (c, r) with SwapAxes; node (c, ny - 1 - r) in a raster,
  // whose first line is the top row.
  ValueSink sink(grid, options, /*irapHoles=*/false);
  for (size_t r = 0; r < rows; ++r)
  {
    const size_t row = raster ? rows - 1 - r : r;
    for (size_t c = 0; c < columns; ++c)
    {
      const size_t id = linesAreRows ? c + row * columns : r + c * rows;
      sink.Set(id, matrix.Values[r * columns + c]);
    }
  }
  return true;
}
}

//------------------------------------------------------------------------------
bool IsMatrixGeometryLine(std::string_view line)
{
  std::string_view values;
  const MatrixKey key = MatrixHeaderKey(line, values);
  return key == MatrixKey::Dimensions || key == MatrixKey::XExtent || key == MatrixKey::YExtent;
}

//------------------------------------------------------------------------------
const char* AsciiGridFormatName(AsciiGridFormat format)
{
  switch (format)
  {
    case AsciiGridFormat::IrapClassic:
      return "IrapClassic";
    case AsciiGridFormat::Zmap:
      return "Zmap";
    case AsciiGridFormat::EsriAscii:
      return "EsriAscii";
    case AsciiGridFormat::Matrix:
      return "Matrix";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
bool CheckAsciiGridDimensions(const char* nxField,
  double nx,
  const char* nyField,
  double ny,
  double maxValues,
  std::string& error)
{
  std::ostringstream msg;
  msg.precision(17);
  for (const auto& f : { std::make_pair(nxField, nx), std::make_pair(nyField, ny) })
  {
    if (!(f.second >= 1.0) || f.second > MaxNodes || f.second != std::floor(f.second))
    {
      msg << f.first << " = " << f.second << ": must be an integer in [1, 2^31)";
      error = msg.str();
      return false;
    }
  }
  // Both below 2^31: the product is exact in a double up to 2^62.
  if (nx * ny > MaxNodes)
  {
    msg << nxField << " x " << nyField << " = " << nx << " x " << ny << " = " << nx * ny
        << " nodes (" << nx * ny * 4.0 / (1 << 30) << " GiB of float32): more than a horizon "
        << "grid can have (2^31 - 1 nodes)";
    error = msg.str();
    return false;
  }
  if (nx * ny > maxValues)
  {
    msg << nxField << " x " << nyField << " = " << nx << " x " << ny << " = " << nx * ny
        << " values, but the rest of the file can hold at most " << std::floor(maxValues)
        << ": the header does not describe this file";
    error = msg.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
AsciiGridFormat DetectAsciiGridFormat(const std::string& path)
{
  vtksys::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
  if (!in)
  {
    return AsciiGridFormat::Unknown;
  }
  // The first 64 KiB decide: a binary file need not hold a line break soon.
  std::string head(1 << 16, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  const bool full = in.gcount() == static_cast<std::streamsize>(head.size());
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.compare(0, 3, "\xEF\xBB\xBF") == 0)
  {
    head.erase(0, 3); // a UTF-8 byte order mark
  }
  Text text(std::move(head));
  std::string_view line;
  while (text.NextLine(line))
  {
    if (IsBlank(line))
    {
      continue;
    }
    const std::string_view t = Trim(line);
    if (t.front() == '!' || t.front() == '@')
    {
      return AsciiGridFormat::Zmap;
    }
    if (t.front() == '#')
    {
      return AsciiGridFormat::Matrix;
    }
    std::vector<std::string_view> tokens;
    Tokenize(t, tokens);
    if (tokens.empty())
    {
      return AsciiGridFormat::Unknown; // separators only (",", ";"): no format starts so
    }
    if (full && line.data() + line.size() == text.End() && tokens.size() > 1)
    {
      tokens.pop_back(); // a line longer than the head: its last token may be cut
    }
    const std::string key = Lower(tokens[0]);
    for (const char* k : { "ncols",
           "nrows",
           "xllcorner",
           "xllcenter",
           "yllcorner",
           "yllcenter",
           "cellsize",
           "nodata_value",
           "dx",
           "dy" })
    {
      if (key == k)
      {
        return AsciiGridFormat::EsriAscii;
      }
    }
    double v = 0.0;
    if (!std::all_of(
          tokens.begin(), tokens.end(), [&](std::string_view s) { return ParseNumber(s, v); }))
    {
      return AsciiGridFormat::Unknown;
    }
    ParseNumber(tokens[0], v);
    return (v == -996.0 && tokens.size() == 4) ? AsciiGridFormat::IrapClassic
                                               : AsciiGridFormat::Matrix;
  }
  return AsciiGridFormat::Unknown;
}

//------------------------------------------------------------------------------
bool ReadAsciiGrid(const std::string& path,
  AsciiGridFormat format,
  const AsciiGridOptions& options,
  AsciiGrid& grid,
  std::string& error)
{
  grid = AsciiGrid();
  std::string data;
  if (!Slurp(path, data, error))
  {
    return false;
  }
  if (data.compare(0, 3, "\xEF\xBB\xBF") == 0)
  {
    data.erase(0, 3); // a UTF-8 byte order mark
  }
  if (data.find('\0') != std::string::npos)
  {
    error = "the file holds NUL bytes: not a text grid";
    return false;
  }
  if (format == AsciiGridFormat::Unknown)
  {
    format = DetectAsciiGridFormat(path);
    if (format == AsciiGridFormat::Unknown)
    {
      error = "not a text grid: the first line is none of Irap classic (-996 ny xinc yinc), "
              "ZMAP+ ('!' or '@'), ESRI ASCII (ncols ...) or a row of numbers";
      return false;
    }
  }
  grid.Format = format;
  Text text(std::move(data));
  bool ok = false;
  switch (format)
  {
    case AsciiGridFormat::IrapClassic:
      ok = ReadIrapClassic(text, options, grid, error);
      break;
    case AsciiGridFormat::Zmap:
      ok = ReadZmap(text, options, grid, error);
      break;
    case AsciiGridFormat::EsriAscii:
      ok = ReadEsri(text, options, grid, error);
      break;
    default:
      ok = ReadMatrix(text, options, grid, error);
      break;
  }
  if (ok && grid.OutOfRangeValues > 0)
  {
    std::ostringstream msg;
    msg << grid.OutOfRangeValues << " value(s) beyond the range of float (3.4e38), the first "
        << grid.FirstOutOfRange << ", and not the no-data value";
    error = msg.str();
    ok = false;
  }
  if (!ok)
  {
    grid.Values.clear();
    grid.Values.shrink_to_fit();
  }
  return ok;
}
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Private parser (not installed) of the text grid formats that vtkAsciiGridReader reads and
// that vtkHorizonColumnReader hands a whitespace matrix to: Irap classic ASCII, ZMAP+, ESRI
// ASCII grids and the plain matrix of numpy.savetxt (or of a DEM export, whose '#' header
// gives Dimensions, extents and nodata). One parser, so that both readers agree on every value,
// hole and error.
#ifndef StrataAsciiGridParser_h
#define StrataAsciiGridParser_h

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace strata_io
{
/// The text grid formats; Unknown when detection finds none of them.
enum class AsciiGridFormat : int
{
  Unknown = 0,
  IrapClassic = 1,
  Zmap = 2,
  EsriAscii = 3,
  Matrix = 4
};

const char* AsciiGridFormatName(AsciiGridFormat format);

/// What the caller sets rather than the file.
struct AsciiGridOptions
{
  /// An extra no-data value (NaN: none); NaN in the file is always a hole.
  double NullValue = std::numeric_limits<double>::quiet_NaN();
  /// Matrix: lines are rows along j (the y axis) instead of i; see vtkAsciiGridReader.
  bool SwapAxes = false;
};

/// A grid as read: node (i, j) is Values[i + j * NX], holes NaN.
struct AsciiGrid
{
  AsciiGridFormat Format = AsciiGridFormat::Unknown;
  int NX = 0;
  int NY = 0;
  double Origin[2] = { 0.0, 0.0 };  ///< world x, y of node (0, 0); zero for a matrix
  double Spacing[2] = { 1.0, 1.0 }; ///< node spacing along i and j; one for a matrix
  double Rotation = 0.0;            ///< degrees counterclockwise from world x (Irap only)
  /// Irap: the header's xmin xmax ymin ymax; ZMAP+: its node bounds; ESRI: the node bounds
  /// derived from its corner or centre; a matrix: zero.
  double Bounds[4] = { 0.0, 0.0, 0.0, 0.0 };
  /// The file's own no-data value (Irap: 9999900, ZMAP+ and ESRI: the header's), NaN if none.
  double FileNullValue = std::numeric_limits<double>::quiet_NaN();
  bool CellCorner = false; ///< ESRI: the header gave xllcorner/yllcorner (not ...center)
  /// Matrix: its '#' header gave Dimensions or extents (a DEM export's raster): each line is a
  /// row of x, the first line the top one (y = ymax), as in ESRI ASCII grids.
  bool RowsFromTop = false;
  /// Matrix: its header's x_extent and y_extent placed it (Origin, Spacing and Bounds are theirs).
  bool HasGeometry = false;
  int NumberOfLines = 0; ///< Matrix: the number of rows of numbers in the file
  int NodesPerLine = 0;  ///< ZMAP+: the header's nodes per line
  int FieldWidth = 0;    ///< ZMAP+: the header's field width (0 if not a usable integer)
  std::string Name;      ///< ZMAP+: the grid name of the '@' line
  long long NumberOfNoDataValues = 0;
  long long OutOfRangeValues = 0; ///< values beyond float's range: a failed read
  double FirstOutOfRange = 0.0;
  std::vector<float> Values;
};

/// True when `line` is a matrix header line that states the grid's geometry, a '#' comment
/// "Dimensions", "x_extent" or "y_extent" followed by ':' or '=' (as DEM exports write them;
/// keys in any case, '_' optional): it makes a file of rows of numbers a raster (see
/// vtkHorizonColumnReader).
bool IsMatrixGeometryLine(std::string_view line);

/// Which format `path` is in, from its first non-blank line: '!' or '@' is ZMAP+, an ESRI key
/// (ncols, nrows, ...) ESRI, a line of four numbers starting with -996 Irap classic, '#' or other
/// numbers a matrix. Unknown when the file cannot be read or is none of these.
AsciiGridFormat DetectAsciiGridFormat(const std::string& path);

/// Reads `path` as `format` (Unknown: detected). False with a message naming the line or the
/// header field on any malformed, truncated or absurd input; nothing is allocated for the values
/// before the header's dimensions have been checked against the size of the file.
bool ReadAsciiGrid(const std::string& path,
  AsciiGridFormat format,
  const AsciiGridOptions& options,
  AsciiGrid& grid,
  std::string& error);

/// Checks nx x ny nodes before anything is allocated: both positive, the product below 2^31 and
/// at most `maxValues` (what the remaining text can hold). The message names the fields.
bool CheckAsciiGridDimensions(const char* nxField,
  double nx,
  const char* nyField,
  double ny,
  double maxValues,
  std::string& error);
}

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkAsciiGridReader
 * @brief   Reads a horizon from a text grid (Irap classic, ZMAP+, ESRI ASCII, matrix).
 *
 * Besides Irap binary, NumPy arrays and columns, horizons are exchanged as text grids that
 * state their own geometry. This reader takes the four common ones, detected from the first
 * line (Format Auto, the default) or named:
 *
 * - IrapClassic: the ASCII twin of Irap binary (vtkIrapBinaryGridReader). Header
 *   "-996 ny xinc yinc / xmin xmax ymin ymax / nx rotation xori yori / 0 0 0 0 0 0 0", then
 *   nx * ny values, x fastest. Origin (xori, yori), spacing (xinc, yinc), rotation in degrees
 *   counterclockwise; 9999900 (and magnitudes from 1e30) are holes, as in the binary reader.
 * - Zmap: ZMAP+ grids. '!' comment lines, then the header between '@' lines:
 *   "@name HEADER, GRID, nodes per line", "field width, null value, [null text,] decimals,
 *   start column", "rows, columns, min X, max X, min Y, max Y", "0.0, 0.0, 0.0", "@". The
 *   values are column-major, each column from the top (max Y) down. Nodes span min..max X and
 *   Y, so the spacing is (max - min) / (count - 1); no rotation; the null value is a hole.
 * - EsriAscii: ESRI ASCII grids (.asc): "ncols", "nrows", "xllcorner" or "xllcenter",
 *   "yllcorner" or "yllcenter", "cellsize" (or "dx" and "dy"), optional "NODATA_value", then the
 *   rows from the top down. Each value is a cell, and the output's nodes are the cell centres:
 *   a corner header puts node (0, 0) half a cell inside it. NODATA_value is a hole.
 * - Matrix: a whitespace matrix, one grid row per line, as numpy.savetxt writes a 2-D array
 *   ('#' comment lines; commas or semicolons may separate too). Auto detects one only when its
 *   lines hold more than MatrixMinimumColumns (8) values, as vtkHorizonColumnReader does: fewer
 *   are more likely columns, and an error says so. Line r, value c is node (r, c):
 *   the first numpy axis is x, as vtkNumpyGridReader and vtkHorizonColumnReader's Matrix mode
 *   have it; SwapAxes makes line r the row j = r. The file has no geometry: Origin, Spacing and
 *   Rotation place it. A matrix of heights under a DEM export's header is a raster instead,
 *   read by the rule of vtkHorizonColumnReader's Matrix mode: '#' lines "Dimensions: nx ny",
 *   "x_extent: xmin xmax", "y_extent: ymin ymax" (node bounds), "nodata: v" (':' or '='), lines
 *   rows of x from the top (y = ymax) down, placed by the extents when it gives them; SwapAxes
 *   does not apply, and Auto takes it for a matrix however narrow.
 *
 * In every format NaN and NullValue (when set) are holes too; holes are NaN in the output, as
 * in the other horizon readers (vtkHorizonGridReader: FileName, ArrayName, NullValue, the
 * dimensions, geometry and number of holes). The output is an nx x ny x 1 vtkImageData with one
 * float point-data array (ArrayName, "depth" by default) and the rotation as its direction
 * matrix.
 *
 * The file is read in RequestInformation and the grid handed over in RequestData. Errors
 * (missing, truncated or malformed file, a header whose dimensions overflow, need more nodes
 * than a horizon can have (2^31) or more values than the file can hold, checked before
 * anything is allocated) are reported with vtkErrorMacro naming the line or header field, and
 * leave the output empty.
 *
 * @sa vtkHorizonGridReader vtkIrapBinaryGridReader vtkNumpyGridReader vtkHorizonColumnReader
 */
#ifndef vtkAsciiGridReader_h
#define vtkAsciiGridReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkHorizonGridReader.h"

#include <string> // For std::string

class STRATAIO_EXPORT vtkAsciiGridReader : public vtkHorizonGridReader
{
public:
  static vtkAsciiGridReader* New();
  vtkTypeMacro(vtkAsciiGridReader, vtkHorizonGridReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Auto takes rows of numbers for a matrix only when they hold more values than this.
  static constexpr int MatrixMinimumColumns = 8;

  /// The text grid formats.
  enum class GridFormat : int
  {
    Auto = 0,
    IrapClassic = 1,
    Zmap = 2,
    EsriAscii = 3,
    Matrix = 4
  };

  ///@{
  /**
   * The format of the file. Default: Auto (detected from the first non-blank line).
   */
  vtkSetEnumMacro(Format, GridFormat);
  vtkGetEnumMacro(Format, GridFormat);
  void SetFormatToAuto() { this->SetFormat(GridFormat::Auto); }
  void SetFormatToIrapClassic() { this->SetFormat(GridFormat::IrapClassic); }
  void SetFormatToZmap() { this->SetFormat(GridFormat::Zmap); }
  void SetFormatToEsriAscii() { this->SetFormat(GridFormat::EsriAscii); }
  void SetFormatToMatrix() { this->SetFormat(GridFormat::Matrix); }
  ///@}

  ///@{
  /**
   * Matrix only: line r of the file is the row j = r (an image stored as (y, x)) instead of
   * the column i = r. A raster header (Dimensions, extents) decides instead. Default: false.
   */
  vtkSetMacro(SwapAxes, bool);
  vtkGetMacro(SwapAxes, bool);
  vtkBooleanMacro(SwapAxes, bool);
  ///@}

  ///@{
  /**
   * Matrix only (the other formats, and a matrix whose header gives x_extent and y_extent,
   * state their geometry): world x, y of node (0, 0), node spacing and rotation (degrees
   * counterclockwise from x). Defaults: (0, 0), (1, 1), 0.
   */
  vtkSetVector2Macro(Origin, double);
  vtkGetVector2Macro(Origin, double);
  vtkSetVector2Macro(Spacing, double);
  vtkGetVector2Macro(Spacing, double);
  vtkSetMacro(Rotation, double);
  vtkGetMacro(Rotation, double);
  ///@}

  /**
   * The format of `fileName` judged from its first non-blank line (Auto when it is none of
   * them or cannot be read).
   */
  static GridFormat DetectFormat(const char* fileName);

  /// True when DetectFormat finds a format other than Matrix (a matrix is any rows of numbers).
  static bool CanReadFile(const char* fileName);

  ///@{
  /**
   * What the last UpdateInformation() read (zeros, Auto, NaN, empty before or after a failure;
   * the dimensions, the output geometry and the number of holes are vtkHorizonGridReader's):
   * the format, the header's bounds (Irap: xmin xmax ymin ymax as written; ZMAP+: min/max X and
   * Y; ESRI: the first and last cell centres; a matrix: its header's extents, or zeros), the
   * file's own no-data value (Irap: 9999900; a matrix: its header's nodata, or NaN), whether an
   * ESRI header gave the lower-left corner (true) or centre, a ZMAP+ grid's name and nodes per
   * line, and the number of holes in the grid.
   */
  vtkGetEnumMacro(DetectedFormat, GridFormat);
  vtkGetVector4Macro(HeaderBounds, double);
  vtkGetMacro(FileNullValue, double);
  vtkGetMacro(CellCorner, bool);
  vtkGetMacro(NodesPerLine, int);
  const char* GetGridName() const { return this->GridName.c_str(); }
  ///@}

protected:
  vtkAsciiGridReader();
  ~vtkAsciiGridReader() override;

  const char* GetGridDescription() override { return "text grid"; }
  /// Reads the whole file (its values become the pending values).
  bool ReadGridInformation(std::string& error) override;
  void ResetResults() override;

  GridFormat Format = GridFormat::Auto;
  bool SwapAxes = false;
  double Origin[2] = { 0.0, 0.0 };
  double Spacing[2] = { 1.0, 1.0 };
  double Rotation = 0.0;

  GridFormat DetectedFormat = GridFormat::Auto;
  double HeaderBounds[4] = { 0.0, 0.0, 0.0, 0.0 };
  double FileNullValue;
  bool CellCorner = false;
  int NodesPerLine = 0;
  std::string GridName;

private:
  vtkAsciiGridReader(const vtkAsciiGridReader&) = delete;
  void operator=(const vtkAsciiGridReader&) = delete;
};

#endif

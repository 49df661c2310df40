// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHorizonColumnReader
 * @brief   Reads a horizon from ASCII columns (inline crossline z, or x y z) into a regular grid.
 *
 * Interpretation packages export horizons as plain text with one node per line, either by
 * seismic index ("inline crossline z") or by world position ("x y z"). Both describe a regular
 * grid with holes, but neither states the grid: this reader recovers it, so the horizon becomes
 * a vtkImageData of nx x ny x 1 points like the Irap and NumPy readers produce, with missing
 * nodes as NaN.
 *
 * Text: columns separated by whitespace, commas or semicolons; blank lines and lines starting
 * with '#' are skipped; the first remaining line may be a non-numeric header ("x y z",
 * "inline,xline,twt"); columns after the third are ignored. A NaN or infinite z, or z equal to
 * NullValue, is a hole (as in vtkAsciiGridReader); a finite z beyond float's range is an error.
 *
 * Mode:
 * - InlineCrossline: the first two columns are integer inline and crossline numbers. The grid
 *   spans the distinct values of each, with a step equal to the greatest common divisor of their
 *   differences (inlines 1300, 1304, ... give step 4). Index (i, j) is inline
 *   first + i * step, crossline first + j * step: the inline axis is x. With IndexCoordinates on
 *   (default) the image is placed at the index numbers themselves (origin = first inline and
 *   crossline, spacing = the steps), so it lines up with a seismic volume addressed the same way;
 *   with it off, Origin is the world position of the first node, InlineSpacing and
 *   CrosslineSpacing the world distance between consecutive inline and crossline NUMBERS (the bin
 *   size, so nodes are step * spacing apart), and Rotation the counterclockwise angle of the
 *   inline axis from world x in degrees.
 * - XYZ: the first two columns are world x and y of nodes of a regular, possibly rotated grid.
 *   The reader finds the grid axes from nearest-neighbour vectors, the spacing along each axis
 *   from the gaps between the point rows, and then fits origin, rotation and spacings to all
 *   points by least squares. It is an error if some point lies farther than
 *   Tolerance * (smaller spacing) from its node. The lattice does not say which of its axes is
 *   "x": the reader picks the axis within 45 degrees of world x, so the recovered rotation is in
 *   (-45, 45] degrees and axes are right-handed.
 * - Matrix: not columns but a whitespace matrix of heights, one grid row per line, as
 *   numpy.savetxt writes a 2-D array ('#' comment lines, every row the same number of values;
 *   see vtkAsciiGridReader, which reads it the same way). Line r, value c is node (r, c): the
 *   lines are inlines (the image x axis), as vtkNumpyGridReader has the first numpy axis, so a
 *   savetxt and an np.save of one array give the same grid. Placed like InlineCrossline: at the
 *   index numbers (origin 0, spacing 1) with IndexCoordinates on, by Origin, InlineSpacing,
 *   CrosslineSpacing and Rotation with it off. NaN and NullValue are holes.
 * - Matrix with a raster header: a matrix of heights as DEM exports write it, under '#' lines
 *   "Dimensions: nx ny", "x_extent: xmin xmax", "y_extent: ymin ymax", "nodata: v" (':' or
 *   '=', keys in any case, '_' optional; other '#' lines are comments). Its lines are rows of
 *   x, as in ESRI ASCII grids: nx values per line, ny lines, the first line the top row
 *   (y = ymax), so node (i, j) is value i of line ny - 1 - j. Dimensions must be (values per
 *   line, lines); the extents are the bounds of the nodes (the first and last value of a line
 *   at xmin and xmax), and when given (both, or neither) they place the grid (origin (xmin,
 *   ymin), spacing (xmax - xmin) / (nx - 1) and (ymax - ymin) / (ny - 1), no rotation) whatever
 *   IndexCoordinates says; without them it is placed as a plain matrix. nodata is a hole. Any
 *   of Dimensions or an extent makes the file a raster, also for Auto mode however narrow its
 *   lines; a header that disagrees with the data is an error.
 * - Auto (default): every data line holding the same number of values, more than
 *   MatrixMinimumColumns (8), and no header line, mean Matrix: no columns file has that many
 *   columns on every line. Otherwise a header line whose first two names say so ("inline xline
 *   ...", "x y ...", "easting northing ...") decides; otherwise integer-valued first two columns
 *   mean InlineCrossline, anything else XYZ. (Integer world coordinates need an explicit mode or
 *   a header.) A file of 4 to 8 values on every line that the column modes read with data lines
 *   falling on nodes already set, or into a grid more than half holes, is an error: it is
 *   probably a small matrix, to be read with Mode Matrix (or as columns with an explicit mode).
 *
 * The output is one float point-data array (ArrayName, "depth" by default); the grid rotation is
 * the image's direction matrix. NullValue, a z that means "no data" (e.g. -999.25), and the
 * results common to the horizon readers (dimensions, geometry given to the output, number of
 * NaN nodes: missing nodes plus NaN or NullValue z) are vtkHorizonGridReader's. The file is parsed
 * in RequestInformation (the dimensions depend on all of it) and the grid handed over in
 * RequestData. Errors (missing file, no data, malformed lines, absurd dimensions, points off a
 * regular grid) are reported with vtkErrorMacro and leave the output empty.
 *
 * @sa vtkHorizonGridReader vtkIrapBinaryGridReader vtkNumpyGridReader vtkAsciiGridReader
 */
#ifndef vtkHorizonColumnReader_h
#define vtkHorizonColumnReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkHorizonGridReader.h"

#include <string> // For std::string

class STRATAIO_EXPORT vtkHorizonColumnReader : public vtkHorizonGridReader
{
public:
  static vtkHorizonColumnReader* New();
  vtkTypeMacro(vtkHorizonColumnReader, vtkHorizonGridReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// What the first two columns hold.
  enum class ColumnMode : int
  {
    Auto = 0,
    InlineCrossline = 1,
    XYZ = 2,
    Matrix = 3
  };

  /// Auto mode takes a file whose every line holds more values than this for a matrix.
  static constexpr int MatrixMinimumColumns = 8;

  ///@{
  /**
   * What the first two columns are. Default: Auto.
   */
  vtkSetEnumMacro(Mode, ColumnMode);
  vtkGetEnumMacro(Mode, ColumnMode);
  void SetModeToAuto() { this->SetMode(ColumnMode::Auto); }
  void SetModeToInlineCrossline() { this->SetMode(ColumnMode::InlineCrossline); }
  void SetModeToXYZ() { this->SetMode(ColumnMode::XYZ); }
  void SetModeToMatrix() { this->SetMode(ColumnMode::Matrix); }
  ///@}

  ///@{
  /**
   * InlineCrossline mode: place the grid at its index numbers (true) or by Origin,
   * InlineSpacing, CrosslineSpacing and Rotation (false). Default: true.
   */
  vtkSetMacro(IndexCoordinates, bool);
  vtkGetMacro(IndexCoordinates, bool);
  vtkBooleanMacro(IndexCoordinates, bool);
  ///@}

  ///@{
  /**
   * InlineCrossline mode with IndexCoordinates off: world position of the first node (smallest
   * inline and crossline). Default: (0, 0).
   */
  vtkSetVector2Macro(Origin, double);
  vtkGetVector2Macro(Origin, double);
  ///@}

  ///@{
  /**
   * InlineCrossline mode with IndexCoordinates off: world distance between consecutive inline
   * (crossline) numbers. Default: 1.
   */
  vtkSetMacro(InlineSpacing, double);
  vtkGetMacro(InlineSpacing, double);
  vtkSetMacro(CrosslineSpacing, double);
  vtkGetMacro(CrosslineSpacing, double);
  ///@}

  ///@{
  /**
   * InlineCrossline mode with IndexCoordinates off: counterclockwise angle of the inline axis
   * from world x, degrees. Default: 0.
   */
  vtkSetMacro(Rotation, double);
  vtkGetMacro(Rotation, double);
  ///@}

  ///@{
  /**
   * XYZ mode: how far a point may lie from its grid node, as a fraction of the smaller grid
   * spacing. Default 0.05: coordinates printed with a few decimals, or stored as float32 at UTM
   * scale (about 0.5 m steps at northings of 6e6), stay well inside it, while points that are not
   * on a lattice are typically off by a quarter of a cell or more. Clamped to [0, 0.25] so that
   * rows stay separable.
   */
  vtkSetClampMacro(Tolerance, double, 0.0, 0.25);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * What the last UpdateInformation() found: the mode used (never Auto after a successful read),
   * whether there was a header line, the number of data lines, the number of data lines that
   * hit a node already set (the last one wins; zero for a matrix); the grid dimensions are
   * vtkHorizonGridReader's GetNX() and GetNY(). A matrix's records are its lines of numbers.
   */
  vtkGetEnumMacro(DetectedMode, ColumnMode);
  vtkGetMacro(HasHeaderLine, bool);
  vtkGetMacro(NumberOfRecords, vtkIdType);
  vtkGetMacro(NumberOfDuplicates, vtkIdType);
  ///@}

  ///@{
  /**
   * InlineCrossline mode: the smallest inline (crossline) number and the step between grid
   * inlines (crosslines). Zero in XYZ mode.
   */
  vtkGetMacro(FirstInline, vtkIdType);
  vtkGetMacro(InlineStep, vtkIdType);
  vtkGetMacro(FirstCrossline, vtkIdType);
  vtkGetMacro(CrosslineStep, vtkIdType);
  ///@}

  /**
   * XYZ mode: the largest distance of a point from its fitted node (world units). Zero in
   * InlineCrossline mode.
   */
  vtkGetMacro(MaxDeviation, double);

protected:
  vtkHorizonColumnReader();
  ~vtkHorizonColumnReader() override;

  const char* GetGridDescription() override { return "horizon columns"; }
  /// Parses the file and builds the grid (the pending values).
  bool ReadGridInformation(std::string& error) override;
  void ResetResults() override;

  ColumnMode Mode = ColumnMode::Auto;
  bool IndexCoordinates = true;
  double Origin[2] = { 0.0, 0.0 };
  double InlineSpacing = 1.0;
  double CrosslineSpacing = 1.0;
  double Rotation = 0.0;
  double Tolerance = 0.05;

  ColumnMode DetectedMode = ColumnMode::Auto;
  bool HasHeaderLine = false;
  vtkIdType NumberOfRecords = 0;
  vtkIdType NumberOfDuplicates = 0;
  vtkIdType FirstInline = 0;
  vtkIdType InlineStep = 0;
  vtkIdType FirstCrossline = 0;
  vtkIdType CrosslineStep = 0;
  double MaxDeviation = 0.0;

private:
  vtkHorizonColumnReader(const vtkHorizonColumnReader&) = delete;
  void operator=(const vtkHorizonColumnReader&) = delete;

  /// ReadGridInformation for a whitespace matrix (Matrix mode, or Auto mode's finding).
  bool ReadMatrixGrid(std::string& error);
};

#endif

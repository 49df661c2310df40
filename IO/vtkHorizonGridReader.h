// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHorizonGridReader
 * @brief   Abstract superclass of the readers of a 2-D horizon grid into a height-field image.
 *
 * Irap binary grids, NumPy arrays, text grids and columns differ in how they are parsed, not in
 * what they give: an nx x ny x 1 vtkImageData whose lateral origin, spacing and rotation (the
 * direction matrix, a rotation about z) place the grid, with one point-data array of heights
 * (ArrayName, "depth" by default) in which holes are NaN, whatever the file's no-data
 * convention (NullValue adds one of the caller's). This class is that common part, so that the
 * readers agree on it: the settings, the results every reader reports (dimensions, geometry,
 * number of holes), the two pipeline passes and what a failure leaves behind.
 *
 * A subclass implements two steps (template method):
 * - ReadGridInformation(), in RequestInformation: reads what the pipeline information needs
 *   (the header; a text file whole, since its dimensions depend on all of it) and sets NX, NY,
 *   GridOrigin, GridSpacing and GridRotation. A reader that read the values too hands them to
 *   SetPendingValues(), and RequestData takes them without reading the file again.
 * - ReadGridValues(), in RequestData when nothing is pending: reads the values (NaN at holes)
 *   and sets NumberOfNoDataValues. The default serves the readers that read everything in
 *   ReadGridInformation: it reads the file again and checks that the dimensions did not change.
 *
 * Errors in either pass (no file name, a missing file, anything the subclass finds) are reported
 * with vtkErrorMacro as "Cannot read <GetGridDescription()> "<file>": <reason>" and leave the
 * output empty; a failed information pass also clears every result (ResetResults()).
 *
 * @sa vtkIrapBinaryGridReader vtkNumpyGridReader vtkAsciiGridReader vtkHorizonColumnReader
 */
#ifndef vtkHorizonGridReader_h
#define vtkHorizonGridReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string> // For std::string

class vtkDataArray;

class STRATAIO_EXPORT vtkHorizonGridReader : public vtkImageAlgorithm
{
public:
  vtkAbstractTypeMacro(vtkHorizonGridReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read. Default: none.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /**
   * Name of the output point-data array. Default: "depth".
   */
  vtkSetStringMacro(ArrayName);
  vtkGetStringMacro(ArrayName);
  ///@}

  ///@{
  /**
   * An extra no-data value of the file (e.g. -999.25), turned into NaN like the format's own.
   * Default: NaN, meaning none (NaN in a file is always a hole).
   */
  vtkSetMacro(NullValue, double);
  vtkGetMacro(NullValue, double);
  ///@}

  ///@{
  /**
   * What the last information pass (UpdateInformation()) found, zeros before it and after a
   * failure: the grid dimensions, the world x, y of node (0, 0), the node spacing along the
   * image axes and the rotation (degrees counterclockwise from world x) that the output has.
   */
  int GetNX() const { return this->NX; }
  int GetNY() const { return this->NY; }
  vtkGetVector2Macro(GridOrigin, double);
  vtkGetVector2Macro(GridSpacing, double);
  vtkGetMacro(GridRotation, double);
  ///@}

  /**
   * Number of grid nodes that are NaN in the output (holes of any kind, NaN in the file
   * included): after Update(), and for the readers that read the whole file in the information
   * pass (text grids, columns) already after UpdateInformation().
   */
  vtkGetMacro(NumberOfNoDataValues, vtkIdType);

protected:
  vtkHorizonGridReader();
  ~vtkHorizonGridReader() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// What the error messages call the file, e.g. "Irap binary grid".
  virtual const char* GetGridDescription() = 0;

  /**
   * Reads what the information pass reports and sets NX, NY, GridOrigin, GridSpacing and
   * GridRotation (and the subclass's own results); FileName names an existing regular file.
   * False with the reason on failure.
   */
  virtual bool ReadGridInformation(std::string& error) = 0;

  /**
   * Reads the values of the grid reported by the last information pass (NaN at holes), sets
   * NumberOfNoDataValues and, if the file says so, refreshes the geometry. nullptr with the
   * reason on failure. The default reads the file again with ReadGridInformation(), for the
   * readers that hand over their values there, and fails if the dimensions changed.
   */
  virtual vtkSmartPointer<vtkDataArray> ReadGridValues(std::string& error);

  /// The VTK type of the values array (reported to the pipeline). Default: VTK_FLOAT.
  virtual int GetValuesType() { return VTK_FLOAT; }

  /// Clears every result (and the pending values); overrides clear theirs and call this.
  virtual void ResetResults();

  /// Values read in the information pass, for the next RequestData (which then releases them).
  void SetPendingValues(vtkDataArray* values);

  /// False with the reason when FileName is unset or names no regular file.
  bool CheckFileName(std::string& error) const;

  /**
   * A new array of `count` values of VTK type `type` (VTK_FLOAT or VTK_DOUBLE); nullptr with a
   * message when it cannot be allocated.
   */
  static vtkSmartPointer<vtkDataArray> NewValues(int type, vtkIdType count, std::string& error);

  char* FileName = nullptr;
  char* ArrayName = nullptr;
  double NullValue;

  int NX = 0;
  int NY = 0;
  double GridOrigin[2] = { 0.0, 0.0 };
  double GridSpacing[2] = { 0.0, 0.0 };
  double GridRotation = 0.0;
  vtkIdType NumberOfNoDataValues = 0;

private:
  vtkHorizonGridReader(const vtkHorizonGridReader&) = delete;
  void operator=(const vtkHorizonGridReader&) = delete;

  void ReportError(const std::string& error);

  vtkSmartPointer<vtkDataArray> PendingValues;
};

#endif

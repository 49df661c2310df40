// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkNumpyGridReader
 * @brief   Reads a 2-D NumPy array (.npy) as a horizon grid in vtkImageData.
 *
 * Interpreted horizons are often passed around as `np.save`d arrays indexed by
 * (inline, crossline): that is how the SEG tutorials ship the Penobscot horizons, for example.
 * The file holds only the values, so the grid geometry (Origin, Spacing, Rotation) is set on
 * the reader; the defaults place node (i, j) at (i, j, 0).
 *
 * Supported: format versions 1.0, 2.0 and 3.0; 'descr' of float32/float64, int8/16/32/64 and
 * uint8/16/32/64 in either byte order ('<', '>', '|', '='); 'fortran_order' True or False;
 * 'shape' (n,), (rows, cols) or (rows, cols, 1). Structured, complex, object and string dtypes
 * are rejected.
 *
 * Axis convention: the array shape is (rows, cols), and the FIRST numpy axis (rows) is the image
 * x axis (i, the inline axis), the second (cols) the y axis (j, the crossline axis). So an array
 * of shape (601, 481) becomes an image of 601 x 481 x 1 points and arr[i, j] is the value at
 * image index (i, j). This matches the (inline, crossline) indexing of seismic horizon arrays;
 * SwapAxes turns it around for arrays stored as (y, x) images, where arr[j, i] is at (i, j).
 * A 1-D array of n values is n x 1 (1 x n with SwapAxes).
 *
 * Output: one point-data array named ArrayName ("depth" by default), vtkDoubleArray for float64
 * files and vtkFloatArray for every other dtype (horizon values need no more than float32;
 * float64 is kept so a file round-trips exactly). NaN in the file and NullValue (when set)
 * are holes and come out as NaN (NullValue, e.g. -999.25 or, for integer arrays, -32768, is
 * compared after conversion to the output type). The grid rotation about z (degrees,
 * counterclockwise from +x) is the image's direction matrix.
 *
 * Header getters are valid after UpdateInformation(), GetNumberOfNoDataValues() after Update().
 * Errors (missing or truncated file, bad magic, unsupported dtype or version, malformed header,
 * absurd shapes) are reported with vtkErrorMacro and leave the output empty.
 *
 * @sa vtkHorizonGridReader vtkIrapBinaryGridReader vtkHorizonColumnReader
 */
#ifndef vtkNumpyGridReader_h
#define vtkNumpyGridReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkHorizonGridReader.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class STRATAIO_EXPORT vtkNumpyGridReader : public vtkHorizonGridReader
{
public:
  static vtkNumpyGridReader* New();
  vtkTypeMacro(vtkNumpyGridReader, vtkHorizonGridReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * World position of node (0, 0). Default: (0, 0).
   */
  vtkSetVector2Macro(Origin, double);
  vtkGetVector2Macro(Origin, double);
  ///@}

  ///@{
  /**
   * Node spacing along the image x and y axes. Default: (1, 1).
   */
  vtkSetVector2Macro(Spacing, double);
  vtkGetVector2Macro(Spacing, double);
  ///@}

  ///@{
  /**
   * Grid rotation about z, degrees counterclockwise from the world x axis (the Irap convention).
   * Default: 0.
   */
  vtkSetMacro(Rotation, double);
  vtkGetMacro(Rotation, double);
  ///@}

  ///@{
  /**
   * False (default): numpy axis 0 (rows) is the image x axis, arr[i, j] at index (i, j).
   * True: numpy axis 1 (columns) is x, arr[j, i] at index (i, j).
   */
  vtkSetMacro(SwapAxes, bool);
  vtkGetMacro(SwapAxes, bool);
  vtkBooleanMacro(SwapAxes, bool);
  ///@}

  /**
   * True when the file starts with the .npy magic string.
   */
  static bool CanReadFile(const char* fileName);

  ///@{
  /**
   * The header as read by the last UpdateInformation(): format version, the 'descr' string
   * (e.g. "<f8"), 'fortran_order', the shape (number of axes and their lengths; 0 for an axis
   * the file does not have); the resulting image dimensions are vtkHorizonGridReader's GetNX()
   * and GetNY(). Empty/zero before a successful read.
   */
  int GetMajorVersion() const;
  int GetMinorVersion() const;
  const char* GetDescr() const;
  bool GetFortranOrder() const;
  int GetNumberOfAxes() const;
  vtkIdType GetShape(int axis) const;
  ///@}

  /**
   * The VTK type of the output array (VTK_DOUBLE for float64 files, VTK_FLOAT otherwise), or 0
   * before a successful UpdateInformation().
   */
  int GetOutputDataType() const;

protected:
  vtkNumpyGridReader();
  ~vtkNumpyGridReader() override;

  const char* GetGridDescription() override { return "NumPy grid"; }
  /// Reads the header.
  bool ReadGridInformation(std::string& error) override;
  /// Reads the header again (the file may have changed) and the values, chunk by chunk.
  vtkSmartPointer<vtkDataArray> ReadGridValues(std::string& error) override;
  int GetValuesType() override { return this->GetOutputDataType(); }
  void ResetResults() override;

  double Origin[2] = { 0.0, 0.0 };
  double Spacing[2] = { 1.0, 1.0 };
  double Rotation = 0.0;
  bool SwapAxes = false;

private:
  vtkNumpyGridReader(const vtkNumpyGridReader&) = delete;
  void operator=(const vtkNumpyGridReader&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

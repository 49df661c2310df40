// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkIrapBinaryGridReader
 * @brief   Reads an Irap/RMS binary surface grid (.gri) as a rotated vtkImageData.
 *
 * Irap binary is the grid format that Roxar RMS, xtgeo and most reservoir-modelling tools
 * exchange horizons in, so a horizon stack usually arrives as a set of .gri files on one shared
 * (and often rotated) grid. The file is a sequence of big-endian Fortran records, each framed by a
 * 4-byte length marker before and after its payload:
 *
 * - record 1 (32 bytes): int -996, int ny, float xmin, xmax, ymin, ymax, xinc, yinc
 * - record 2 (16 bytes): int nx, float rotation (degrees, counterclockwise from +x), xori, yori
 * - record 3 (28 bytes): seven int zeros
 * - then nx * ny float values, x fastest, spread over records of any length.
 *
 * The reader follows the markers rather than assuming a record length (writers differ: RMS,
 * xtgeo and older Irap tools all chunk differently) and rejects a file whose leading and trailing
 * markers disagree, since that is the one check that tells a corrupt or non-Irap file from a
 * valid one.
 *
 * The output is a vtkImageData of nx x ny x 1 points: image index (i, j) is Irap column i
 * (along the grid's x axis) and row j (along its y axis), the origin is (xori, yori, 0), the
 * spacing (xinc, yinc, 1), and the rotation is the image's direction matrix, a rotation about z by
 * the stored angle, so that world positions come out exactly where RMS puts them. The values
 * become one float point-data array (named by ArrayName, "depth" by default). Holes become NaN:
 * values of magnitude >= 1e30 (what RMS and xtgeo write), the format's nominal undefined value
 * 9999900.0 (always holes), and NullValue (e.g. -999.25) when it is set. FileName, ArrayName,
 * NullValue and the results every horizon reader reports are vtkHorizonGridReader's.
 *
 * The header getters are valid after UpdateInformation(); GetNumberOfNoDataValues() after
 * Update(). Errors (missing or truncated file, mismatched markers, a wrong magic number, absurd
 * dimensions) are reported with vtkErrorMacro and leave the output empty.
 *
 * @sa vtkHorizonGridReader vtkNumpyGridReader vtkHorizonColumnReader
 * vtkImageData::SetDirectionMatrix
 */
#ifndef vtkIrapBinaryGridReader_h
#define vtkIrapBinaryGridReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkHorizonGridReader.h"

#include <string> // For std::string

class STRATAIO_EXPORT vtkIrapBinaryGridReader : public vtkHorizonGridReader
{
public:
  static vtkIrapBinaryGridReader* New();
  vtkTypeMacro(vtkIrapBinaryGridReader, vtkHorizonGridReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * True when the file starts like an Irap binary grid: a 32-byte first record holding -996.
   * Cheap; reads 12 bytes.
   */
  static bool CanReadFile(const char* fileName);

  ///@{
  /**
   * The header as read by the last UpdateInformation() (zeros before, or after a failed read).
   * GetNX()/GetNY() (vtkHorizonGridReader) are the numbers of columns and rows; XOrigin/YOrigin are
   * record 2's xori/yori, the world position of node (0, 0); XMin..YMax are record 1's (unrotated)
   * bounds, kept for reference; Rotation is in degrees, counterclockwise from the x axis.
   */
  vtkGetMacro(XMin, double);
  vtkGetMacro(XMax, double);
  vtkGetMacro(YMin, double);
  vtkGetMacro(YMax, double);
  vtkGetMacro(XInc, double);
  vtkGetMacro(YInc, double);
  vtkGetMacro(XOrigin, double);
  vtkGetMacro(YOrigin, double);
  vtkGetMacro(Rotation, double);
  ///@}

protected:
  vtkIrapBinaryGridReader();
  ~vtkIrapBinaryGridReader() override;

  const char* GetGridDescription() override { return "Irap binary grid"; }
  /// Reads the three header records.
  bool ReadGridInformation(std::string& error) override;
  /// Reads the header again (the file may have changed) and the value records after it.
  vtkSmartPointer<vtkDataArray> ReadGridValues(std::string& error) override;
  void ResetResults() override;

  double XMin = 0.0;
  double XMax = 0.0;
  double YMin = 0.0;
  double YMax = 0.0;
  double XInc = 0.0;
  double YInc = 0.0;
  double XOrigin = 0.0;
  double YOrigin = 0.0;
  double Rotation = 0.0;

private:
  vtkIrapBinaryGridReader(const vtkIrapBinaryGridReader&) = delete;
  void operator=(const vtkIrapBinaryGridReader&) = delete;
};

#endif

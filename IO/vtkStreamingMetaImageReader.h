// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStreamingMetaImageReader
 * @brief   Reads a MetaImage (.mhd/.mha) volume slab by slab, as a sub-extent request asks.
 *
 * VTK 9.1's vtkMetaImageReader cannot serve a sub-extent: it allocates the requested extent and
 * then reads the whole image into it, overrunning the buffer, so a slab-by-slab converter
 * (vtkImageToPagePoolWriter) crashes on it. This reader parses the MetaImage header itself and
 * reads, for the update extent only, each of its rows from the raw data (one seek and one read
 * a row): memory is the requested slab, whatever the size of the volume.
 *
 * Header keys used: NDims (2 or 3), DimSize, ElementType (MET_UCHAR, MET_CHAR, MET_USHORT,
 * MET_SHORT, MET_UINT, MET_INT, MET_FLOAT, MET_DOUBLE), ElementNumberOfChannels,
 * ElementSpacing (or ElementSize), Offset (or Position, Origin), BinaryDataByteOrderMSB (or
 * ElementByteOrderMSB), CompressedData, HeaderSize (-1: the data end the file) and
 * ElementDataFile, the last key (LOCAL: the data follow the header in the same file, as in
 * .mha; otherwise a file name relative to the header's folder). As in vtkMetaImageReader, the
 * output array is "MetaImage" and a TransformMatrix is not applied.
 *
 * Data that cannot be entered mid-way, compressed (CompressedData = True) or spread over a list
 * or pattern of files, are refused with an error: read those whole with vtkMetaImageReader
 * (IsStreamable() tells the two cases apart without an error). Other errors (missing header or
 * data file, unknown or missing keys, a data file shorter than the header says, a failed read)
 * are reported with vtkErrorMacro too and leave an empty output.
 *
 * @sa vtkMetaImageReader vtkImageToPagePoolWriter
 */
#ifndef vtkStreamingMetaImageReader_h
#define vtkStreamingMetaImageReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <memory> // For std::unique_ptr

class STRATAIO_EXPORT vtkStreamingMetaImageReader : public vtkImageAlgorithm
{
public:
  static vtkStreamingMetaImageReader* New();
  vtkTypeMacro(vtkStreamingMetaImageReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The header file (.mhd, or .mha with the data inside). Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  /// True when `fileName` is a MetaImage header whose data this reader can read slab by slab
  /// (uncompressed, in one file); false for any other file, without reporting an error.
  static bool IsStreamable(const char* fileName);

protected:
  vtkStreamingMetaImageReader();
  ~vtkStreamingMetaImageReader() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;

private:
  vtkStreamingMetaImageReader(const vtkStreamingMetaImageReader&) = delete;
  void operator=(const vtkStreamingMetaImageReader&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

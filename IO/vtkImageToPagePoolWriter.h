// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkImageToPagePoolWriter
 * @brief   Converts the vtkImageData of a pipeline into a Strata page pool, slab by slab.
 *
 * The VTK face of strata::PagePoolWriter. A 3-D input (more than one point along z) becomes a brick
 * pool, a 2-D input (one point along z) a tile pool with one layer. The input is never updated
 * as a whole: Write() asks the upstream pipeline for one slab of z slices (rows for tile pools)
 * at a time, as many as strata::PagePoolWriter's memory limit allows per call, so a streaming
 * reader upstream (vtkImageReader2, vtkXMLImageDataReader, vtkPagePoolReader) never holds the whole
 * data set either. Memory is therefore the writer's bounded buffers plus one slab of the input.
 *
 * Scalars: the input's active point scalars (else its first point-data array). A 3-D input of
 * 2 to 4 components (RGBA colour, independent channels) becomes a set of brick pools, one per
 * component (strata::PagePoolFormat, Components): component 0 in FileName, component c in
 * strata::PagePoolFormat::GetComponentFileName(FileName, c), each written as a pass over the input;
 * components beyond 4 (and of a 2-D input, beyond 1) are dropped with a warning.
 * uint8, uint16, int16 and float are stored as they are; every other type is converted to
 * float (with the usual loss beyond 24 bits of mantissa). The geometry (spacing, origin,
 * direction) comes from the input's pipeline information.
 *
 * Write() returns true on success. Errors (no input, no scalars, an upstream failure, a file
 * that cannot be written) are reported with vtkErrorMacro, and nothing is left under FileName
 * (nor the component files of a set that failed):
 * strata::PagePoolWriter writes to a temporary file renamed only when complete. Progress events
 * report the fraction of pages written, non-decreasing, ending at 1 on success.
 *
 * Update() does nothing; call Write().
 *
 * @sa strata::PagePoolWriter vtkPagePoolReader strata::PagePoolFormat
 */
#ifndef vtkImageToPagePoolWriter_h
#define vtkImageToPagePoolWriter_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class STRATAIO_EXPORT vtkImageToPagePoolWriter : public vtkImageAlgorithm
{
public:
  static vtkImageToPagePoolWriter* New();
  vtkTypeMacro(vtkImageToPagePoolWriter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Output page pool file. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// Page size B (values per axis), in [8, 512]. Default 32.
  vtkSetMacro(PageSize, int);
  vtkGetMacro(PageSize, int);
  ///@}

  ///@{
  /// Per-page zstd compression. Default off.
  vtkSetMacro(Compression, bool);
  vtkGetMacro(Compression, bool);
  vtkBooleanMacro(Compression, bool);
  ///@}

  ///@{
  /// Memory the page writer's buffers may use, in MB. Default 512.
  vtkSetMacro(MemoryLimit, double);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /// Converts. Returns true on success.
  bool Write();

  ///@{
  /// What the last successful Write() produced: pages and bytes (over a set's files), and the
  /// number of slab requests made to the upstream pipeline.
  vtkGetMacro(NumberOfPages, vtkIdType);
  vtkGetMacro(FileSize, vtkTypeInt64);
  vtkGetMacro(NumberOfSlabRequests, vtkIdType);
  ///@}

protected:
  vtkImageToPagePoolWriter();
  ~vtkImageToPagePoolWriter() override;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;
  int PageSize = 32;
  bool Compression = false;
  double MemoryLimit = 512.0;
  vtkIdType NumberOfPages = 0;
  vtkTypeInt64 FileSize = 0;
  vtkIdType NumberOfSlabRequests = 0;

private:
  vtkImageToPagePoolWriter(const vtkImageToPagePoolWriter&) = delete;
  void operator=(const vtkImageToPagePoolWriter&) = delete;
};

#endif

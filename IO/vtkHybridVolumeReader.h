// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHybridVolumeReader
 * @brief   Reads a hybrid point/volume file (.shv) into the outputs vtkHybridVolumeFilter
 *          produces.
 *
 * The file holds only the low-resolution volume and the points, a small fraction of the
 * original volume, so RequestInformation reads and validates it as a whole
 * (strata::HybridVolumeFile::Read: sizes, fields, checksum) and reports output 0's whole extent,
 * spacing and origin; RequestData hands what was read to the outputs (reading again if the
 * pipeline asks for data without new information). A missing, truncated or corrupt file is
 * reported with vtkErrorMacro, saying what is wrong, and leaves both outputs empty.
 *
 * @sa vtkHybridVolumeFilter strata::HybridVolumeFile vtkHybridVolumeAlgorithm
 */
#ifndef vtkHybridVolumeReader_h
#define vtkHybridVolumeReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkHybridVolumeAlgorithm.h"

#include <memory> // For std::unique_ptr

namespace strata
{
class HybridVolumeFile;
}

class STRATAIO_EXPORT vtkHybridVolumeReader : public vtkHybridVolumeAlgorithm
{
public:
  static vtkHybridVolumeReader* New();
  vtkTypeMacro(vtkHybridVolumeReader, vtkHybridVolumeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The hybrid volume file to read. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

protected:
  vtkHybridVolumeReader();
  ~vtkHybridVolumeReader() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;

private:
  vtkHybridVolumeReader(const vtkHybridVolumeReader&) = delete;
  void operator=(const vtkHybridVolumeReader&) = delete;

  /// Reads FileName into File; false (with the error reported) on failure.
  bool ReadFile();

  /// What RequestInformation read, until RequestData hands it to the outputs.
  std::unique_ptr<strata::HybridVolumeFile> File;
};

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataHybridVolumeSource
 * @brief   A hybrid volume file (.shv) as one data set: a multiblock of the low-resolution volume
 *          (block 0, "Volume") and its points (block 1, "Points").
 *
 * vtkHybridVolumeReader gives the two parts on two output ports; ParaView shows one data set per
 * representation, so the plugin's reader is this source, and the Strata Hybrid representation
 * draws both blocks with vtkHybridVolumeMapper.
 */
#ifndef vtkStrataHybridVolumeSource_h
#define vtkStrataHybridVolumeSource_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkMultiBlockDataSetAlgorithm.h"
#include "vtkNew.h" // For vtkNew

class vtkHybridVolumeReader;

class STRATAPARAVIEW_EXPORT vtkStrataHybridVolumeSource : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkStrataHybridVolumeSource* New();
  vtkTypeMacro(vtkStrataHybridVolumeSource, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .shv file (see vtkHybridVolumeReader).
  void SetFileName(const char* name);
  const char* GetFileName();
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkStrataHybridVolumeSource();
  ~vtkStrataHybridVolumeSource() override;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkStrataHybridVolumeSource(const vtkStrataHybridVolumeSource&) = delete;
  void operator=(const vtkStrataHybridVolumeSource&) = delete;

  vtkNew<vtkHybridVolumeReader> Reader;
};

#endif

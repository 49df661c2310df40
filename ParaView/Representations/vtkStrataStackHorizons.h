// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataStackHorizons
 * @brief   Groups horizon grids into one stack (a multiblock, one block per horizon, in input
 *          order, shallow copies).
 *
 * The "Stack Horizons" filter of Strata's ParaView plugin: select several horizons (Irap .gri,
 * .npy, columns, tile pools) and apply it, and the stack is one data set that the Strata
 * Horizons representation ray casts in one pass (vtkStackedHeightFieldMapper). The horizons
 * must share one lateral grid; the representation reports the ones that do not. Inputs that come
 * from page pools are asked for their coarsest level only (vtkPagePoolReader::UPDATE_RESOLUTION
 * 0), so stacking pooled horizons reads one page each: the representation's mapper pages the
 * rest from the pools, named in each block's field data.
 */
#ifndef vtkStrataStackHorizons_h
#define vtkStrataStackHorizons_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkMultiBlockDataSetAlgorithm.h"

class STRATAPARAVIEW_EXPORT vtkStrataStackHorizons : public vtkMultiBlockDataSetAlgorithm
{
public:
  static vtkStrataStackHorizons* New();
  vtkTypeMacro(vtkStrataStackHorizons, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkStrataStackHorizons() = default;
  ~vtkStrataStackHorizons() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkStrataStackHorizons(const vtkStrataStackHorizons&) = delete;
  void operator=(const vtkStrataStackHorizons&) = delete;
};

#endif

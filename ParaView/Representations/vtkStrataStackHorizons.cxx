// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataStackHorizons.h"

#include "vtkAlgorithm.h"
#include "vtkCompositeDataSet.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStrataParaViewUtilities.h"

#include <string>

vtkStandardNewMacro(vtkStrataStackHorizons);

//------------------------------------------------------------------------------
void vtkStrataStackHorizons::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Horizons: " << this->GetNumberOfInputConnections(0) << "\n";
}

//------------------------------------------------------------------------------
int vtkStrataStackHorizons::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataStackHorizons::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Pools give their coarsest level (one page); every other reader ignores the key.
  vtkStrataParaViewUtilities::RequestCoarsestLevels(inputVector[0]);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataStackHorizons::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  const int n = inputVector[0]->GetNumberOfInformationObjects();
  output->SetNumberOfBlocks(n);
  for (int i = 0; i < n; ++i)
  {
    vtkImageData* input = vtkImageData::GetData(inputVector[0], i);
    if (!input)
    {
      vtkErrorMacro("Input " << i << " of the stack is not an image.");
      return 0;
    }
    vtkNew<vtkImageData> horizon;
    horizon->ShallowCopy(input);
    output->SetBlock(i, horizon);
    output->GetMetaData(i)->Set(
      vtkCompositeDataSet::NAME(), ("Horizon " + std::to_string(i)).c_str());
  }
  return 1;
}

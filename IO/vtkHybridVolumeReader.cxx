// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHybridVolumeReader.h"

#include "StrataHybridVolumeFile.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkStandardNewMacro(vtkHybridVolumeReader);

//------------------------------------------------------------------------------
vtkHybridVolumeReader::vtkHybridVolumeReader() = default;

//------------------------------------------------------------------------------
vtkHybridVolumeReader::~vtkHybridVolumeReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
void vtkHybridVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

//------------------------------------------------------------------------------
bool vtkHybridVolumeReader::ReadFile()
{
  this->File.reset(new strata::HybridVolumeFile);
  if (!this->FileName || !*this->FileName)
  {
    this->File.reset();
    vtkErrorMacro("Cannot read a hybrid volume: no file name set");
    return false;
  }
  if (!this->File->Read(this->FileName))
  {
    // The file's message starts with the path.
    vtkErrorMacro("Cannot read hybrid volume " << this->File->GetErrorMessage());
    this->File.reset();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  if (!this->ReadFile())
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outputVector->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    ClearOutputs(outputVector);
    return 0;
  }
  const strata::HybridVolumeFile& f = *this->File;
  SetLowResolutionInformation(
    outputVector->GetInformationObject(0), f.Dimensions, f.Factor, f.Spacing, f.Origin);
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  ClearOutputs(outputVector);
  if (!this->File && !this->ReadFile())
  {
    return 0;
  }
  this->UpdateProgress(0.5);
  FillOutputs(
    *this->File, vtkImageData::GetData(outputVector, 0), vtkPolyData::GetData(outputVector, 1));
  // The outputs hold the data now; a later execution without new information reads again.
  this->File.reset();
  this->UpdateProgress(1.0);
  return 1;
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHorizonGridReader.h"
#include "StrataGridReaderUtilities.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"

#include <vtksys/SystemTools.hxx>

#include <limits>

//------------------------------------------------------------------------------
vtkHorizonGridReader::vtkHorizonGridReader()
  : NullValue(std::numeric_limits<double>::quiet_NaN())
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("depth");
}

//------------------------------------------------------------------------------
vtkHorizonGridReader::~vtkHorizonGridReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkHorizonGridReader::ResetResults()
{
  this->NX = 0;
  this->NY = 0;
  this->GridOrigin[0] = this->GridOrigin[1] = 0.0;
  this->GridSpacing[0] = this->GridSpacing[1] = 0.0;
  this->GridRotation = 0.0;
  this->NumberOfNoDataValues = 0;
  this->PendingValues = nullptr;
}

//------------------------------------------------------------------------------
void vtkHorizonGridReader::SetPendingValues(vtkDataArray* values)
{
  this->PendingValues = values;
}

//------------------------------------------------------------------------------
bool vtkHorizonGridReader::CheckFileName(std::string& error) const
{
  if (!this->FileName || !*this->FileName)
  {
    error = "no file name set";
    return false;
  }
  if (!vtksys::SystemTools::FileExists(this->FileName, /*isFile=*/true))
  {
    error = "file does not exist or is not a regular file";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> vtkHorizonGridReader::NewValues(int type,
  vtkIdType count,
  std::string& error)
{
  vtkSmartPointer<vtkDataArray> values;
  if (type == VTK_DOUBLE)
  {
    values = vtkSmartPointer<vtkDoubleArray>::New();
  }
  else
  {
    values = vtkSmartPointer<vtkFloatArray>::New();
  }
  values->SetNumberOfTuples(count);
  if (values->GetNumberOfTuples() != count)
  {
    error = "cannot allocate the grid values";
    return nullptr;
  }
  return values;
}

//------------------------------------------------------------------------------
void vtkHorizonGridReader::ReportError(const std::string& error)
{
  vtkErrorMacro("Cannot read " << this->GetGridDescription() << " \""
                               << (this->FileName ? this->FileName : "") << "\": " << error);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> vtkHorizonGridReader::ReadGridValues(std::string& error)
{
  // A second RequestData without a new information pass (another update extent, say) reads the
  // file again rather than keeping a copy of the grid around.
  const int nx = this->NX;
  const int ny = this->NY;
  if (!this->CheckFileName(error) || !this->ReadGridInformation(error) || this->NX != nx ||
      this->NY != ny || !this->PendingValues)
  {
    if (error.empty())
    {
      error = "the grid dimensions changed since the information pass";
    }
    this->ResetResults();
    return nullptr;
  }
  vtkSmartPointer<vtkDataArray> values = this->PendingValues;
  this->PendingValues = nullptr;
  return values;
}

//------------------------------------------------------------------------------
int vtkHorizonGridReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  this->ResetResults();
  std::string error;
  if (!this->CheckFileName(error) || !this->ReadGridInformation(error))
  {
    this->ResetResults();
    strata_io::ClearOutput(outInfo);
    this->ReportError(error);
    return 0;
  }
  strata_io::SetGridInformation(outInfo,
    this->NX,
    this->NY,
    this->GridOrigin,
    this->GridSpacing,
    this->GridRotation,
    this->GetValuesType());
  return 1;
}

//------------------------------------------------------------------------------
int vtkHorizonGridReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!output)
  {
    vtkErrorMacro("No vtkImageData output to fill.");
    return 0;
  }
  output->Initialize();
  std::string error;
  vtkSmartPointer<vtkDataArray> values = this->PendingValues;
  this->PendingValues = nullptr;
  if (!values)
  {
    values = this->ReadGridValues(error);
  }
  if (!values)
  {
    strata_io::ClearOutput(outInfo);
    this->ReportError(error);
    return 0;
  }
  values->SetName(this->ArrayName);
  strata_io::SetGridGeometry(
    output, this->NX, this->NY, this->GridOrigin, this->GridSpacing, this->GridRotation);
  output->GetPointData()->SetScalars(values);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkHorizonGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "NX: " << this->NX << "\n";
  os << indent << "NY: " << this->NY << "\n";
  os << indent << "GridOrigin: " << this->GridOrigin[0] << " " << this->GridOrigin[1] << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing[0] << " " << this->GridSpacing[1] << "\n";
  os << indent << "GridRotation: " << this->GridRotation << "\n";
  os << indent << "NumberOfNoDataValues: " << this->NumberOfNoDataValues << "\n";
  os << indent << "PendingValues: " << (this->PendingValues ? "yes" : "no") << "\n";
}

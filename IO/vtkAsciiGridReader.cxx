// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkAsciiGridReader.h"
#include "vtkStrataAsciiGridParser.h"
#include "vtkStrataGridReaderUtilities.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkAsciiGridReader);

namespace
{
using GridFormat = vtkAsciiGridReader::GridFormat;
using strata_io::AsciiGridFormat;

// The enums share their numbers, Auto being the parser's Unknown.
GridFormat FromParser(AsciiGridFormat f)
{
  return static_cast<GridFormat>(static_cast<int>(f));
}

AsciiGridFormat ToParser(GridFormat f)
{
  return static_cast<AsciiGridFormat>(static_cast<int>(f));
}

const char* FormatName(GridFormat f)
{
  return f == GridFormat::Auto ? "Auto" : strata_io::AsciiGridFormatName(ToParser(f));
}
}

//------------------------------------------------------------------------------
class vtkAsciiGridReader::vtkInternals
{
public:
  /// The grid read by the last successful RequestInformation, handed to the output (and
  /// released) by the following RequestData.
  vtkSmartPointer<vtkFloatArray> Grid;
};

//------------------------------------------------------------------------------
vtkAsciiGridReader::vtkAsciiGridReader()
  : NullValue(std::numeric_limits<double>::quiet_NaN())
  , FileNullValue(std::numeric_limits<double>::quiet_NaN())
  , Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("depth");
}

//------------------------------------------------------------------------------
vtkAsciiGridReader::~vtkAsciiGridReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

//------------------------------------------------------------------------------
vtkAsciiGridReader::GridFormat vtkAsciiGridReader::DetectFormat(const char* fileName)
{
  return fileName ? FromParser(strata_io::DetectAsciiGridFormat(fileName)) : GridFormat::Auto;
}

//------------------------------------------------------------------------------
bool vtkAsciiGridReader::CanReadFile(const char* fileName)
{
  const GridFormat f = DetectFormat(fileName);
  return f != GridFormat::Auto && f != GridFormat::Matrix;
}

//------------------------------------------------------------------------------
void vtkAsciiGridReader::ResetResults()
{
  this->DetectedFormat = GridFormat::Auto;
  this->NX = this->NY = 0;
  this->GridOrigin[0] = this->GridOrigin[1] = 0.0;
  this->GridSpacing[0] = this->GridSpacing[1] = 0.0;
  this->GridRotation = 0.0;
  std::fill(this->HeaderBounds, this->HeaderBounds + 4, 0.0);
  this->FileNullValue = std::numeric_limits<double>::quiet_NaN();
  this->CellCorner = false;
  this->NodesPerLine = 0;
  this->GridName.clear();
  this->NumberOfNoDataValues = 0;
  this->Internals->Grid = nullptr;
}

//------------------------------------------------------------------------------
bool vtkAsciiGridReader::ReadGrid(std::string& error)
{
  this->ResetResults();
  if (!this->FileName || !*this->FileName)
  {
    error = "no file name set";
    return false;
  }
  strata_io::AsciiGridOptions options;
  options.NullValue = this->NullValue;
  options.SwapAxes = this->SwapAxes;
  strata_io::AsciiGrid grid;
  this->UpdateProgress(0.0);
  if (!strata_io::ReadAsciiGrid(this->FileName, ToParser(this->Format), options, grid, error))
  {
    return false;
  }
  const bool matrix = grid.Format == AsciiGridFormat::Matrix;
  // Lines of a few numbers are far more often columns (inline crossline z, x y z) than a
  // matrix: Auto mode does not guess, as vtkHorizonColumnReader's Auto mode does not either,
  // unless a raster header (Dimensions, extents) says what they are.
  const int valuesPerLine = (this->SwapAxes || grid.RowsFromTop) ? grid.NX : grid.NY;
  if (matrix && this->Format == GridFormat::Auto && !grid.RowsFromTop &&
      valuesPerLine <= MatrixMinimumColumns)
  {
    error = "every line holds " + std::to_string(valuesPerLine) +
            " numbers: columns (read them with vtkHorizonColumnReader) or a narrow matrix (set "
            "Format to Matrix); Auto takes only lines of more than " +
            std::to_string(MatrixMinimumColumns) + " numbers for a matrix";
    return false;
  }
  // A matrix is placed by Origin, Spacing and Rotation unless its header gives its extents.
  const bool placedBySettings = matrix && !grid.HasGeometry;
  if (placedBySettings && (!(this->Spacing[0] > 0.0) || !(this->Spacing[1] > 0.0) ||
                            !std::isfinite(this->Spacing[0]) || !std::isfinite(this->Spacing[1])))
  {
    error = "Spacing must be positive";
    return false;
  }
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(this->ArrayName);
  const vtkIdType total = static_cast<vtkIdType>(grid.Values.size());
  array->SetNumberOfTuples(total);
  if (array->GetNumberOfTuples() != total)
  {
    error = "cannot allocate the grid values";
    return false;
  }
  std::copy(grid.Values.begin(), grid.Values.end(), array->GetPointer(0));

  this->DetectedFormat = FromParser(grid.Format);
  this->NX = grid.NX;
  this->NY = grid.NY;
  for (int k = 0; k < 2; ++k)
  {
    this->GridOrigin[k] = placedBySettings ? this->Origin[k] : grid.Origin[k];
    this->GridSpacing[k] = placedBySettings ? this->Spacing[k] : grid.Spacing[k];
  }
  this->GridRotation = placedBySettings ? this->Rotation : grid.Rotation;
  std::copy(grid.Bounds, grid.Bounds + 4, this->HeaderBounds);
  this->FileNullValue = grid.FileNullValue;
  this->CellCorner = grid.CellCorner;
  this->NodesPerLine = grid.NodesPerLine;
  this->GridName = grid.Name;
  this->NumberOfNoDataValues = static_cast<vtkIdType>(grid.NumberOfNoDataValues);
  this->Internals->Grid = array;
  return true;
}

//------------------------------------------------------------------------------
int vtkAsciiGridReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  std::string error;
  if (!this->ReadGrid(error))
  {
    this->ResetResults();
    strata_io::ClearOutput(outInfo);
    vtkErrorMacro(
      "Cannot read text grid \"" << (this->FileName ? this->FileName : "") << "\": " << error);
    return 0;
  }
  strata_io::SetGridInformation(outInfo,
    this->NX,
    this->NY,
    this->GridOrigin,
    this->GridSpacing,
    this->GridRotation,
    VTK_FLOAT);
  return 1;
}

//------------------------------------------------------------------------------
int vtkAsciiGridReader::RequestData(vtkInformation*,
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
  // A second RequestData without a new information pass reads the file again rather than
  // keeping a copy of the grid around.
  if (!this->Internals->Grid)
  {
    const int nx = this->NX;
    const int ny = this->NY;
    std::string error;
    if (!this->ReadGrid(error) || this->NX != nx || this->NY != ny)
    {
      if (error.empty())
      {
        error = "the grid dimensions changed since the information pass";
      }
      this->ResetResults();
      strata_io::ClearOutput(outInfo);
      vtkErrorMacro(
        "Cannot read text grid \"" << (this->FileName ? this->FileName : "") << "\": " << error);
      return 0;
    }
  }
  strata_io::SetGridGeometry(
    output, this->NX, this->NY, this->GridOrigin, this->GridSpacing, this->GridRotation);
  output->GetPointData()->SetScalars(this->Internals->Grid);
  this->Internals->Grid = nullptr;
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkAsciiGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "Format: " << FormatName(this->Format) << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "SwapAxes: " << (this->SwapAxes ? "On" : "Off") << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "DetectedFormat: " << FormatName(this->DetectedFormat) << "\n";
  os << indent << "NX: " << this->NX << "\n";
  os << indent << "NY: " << this->NY << "\n";
  os << indent << "GridOrigin: " << this->GridOrigin[0] << " " << this->GridOrigin[1] << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing[0] << " " << this->GridSpacing[1] << "\n";
  os << indent << "GridRotation: " << this->GridRotation << "\n";
  os << indent << "HeaderBounds: " << this->HeaderBounds[0] << " " << this->HeaderBounds[1] << " "
     << this->HeaderBounds[2] << " " << this->HeaderBounds[3] << "\n";
  os << indent << "FileNullValue: " << this->FileNullValue << "\n";
  os << indent << "CellCorner: " << (this->CellCorner ? "yes" : "no") << "\n";
  os << indent << "NodesPerLine: " << this->NodesPerLine << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "NumberOfNoDataValues: " << this->NumberOfNoDataValues << "\n";
  os << indent << "GridPending: " << (this->Internals->Grid ? "yes" : "no") << "\n";
}

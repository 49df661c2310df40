// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkAsciiGridReader.h"
#include "StrataAsciiGridParser.h"

#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
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
vtkAsciiGridReader::vtkAsciiGridReader()
  : FileNullValue(std::numeric_limits<double>::quiet_NaN())
{
}

//------------------------------------------------------------------------------
vtkAsciiGridReader::~vtkAsciiGridReader() = default;

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
  this->Superclass::ResetResults();
  this->DetectedFormat = GridFormat::Auto;
  std::fill(this->HeaderBounds, this->HeaderBounds + 4, 0.0);
  this->FileNullValue = std::numeric_limits<double>::quiet_NaN();
  this->CellCorner = false;
  this->NodesPerLine = 0;
  this->GridName.clear();
}

//------------------------------------------------------------------------------
bool vtkAsciiGridReader::ReadGridInformation(std::string& error)
{
  this->ResetResults();
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
  vtkSmartPointer<vtkDataArray> array =
    NewValues(VTK_FLOAT, static_cast<vtkIdType>(grid.Values.size()), error);
  if (!array)
  {
    return false;
  }
  std::copy(grid.Values.begin(),
    grid.Values.end(),
    static_cast<vtkFloatArray*>(array.GetPointer())->GetPointer(0));

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
  this->SetPendingValues(array);
  return true;
}

//------------------------------------------------------------------------------
void vtkAsciiGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Format: " << FormatName(this->Format) << "\n";
  os << indent << "SwapAxes: " << (this->SwapAxes ? "On" : "Off") << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "DetectedFormat: " << FormatName(this->DetectedFormat) << "\n";
  os << indent << "HeaderBounds: " << this->HeaderBounds[0] << " " << this->HeaderBounds[1] << " "
     << this->HeaderBounds[2] << " " << this->HeaderBounds[3] << "\n";
  os << indent << "FileNullValue: " << this->FileNullValue << "\n";
  os << indent << "CellCorner: " << (this->CellCorner ? "yes" : "no") << "\n";
  os << indent << "NodesPerLine: " << this->NodesPerLine << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHorizonVolumeSampler
 * @brief   Samples a volume along a horizon: the volume's value at every grid point of the
 *          horizon, as a new point array of the horizon (an amplitude map), in core or paged.
 *
 * What an interpreter calls extracting an attribute along a horizon. Input 0 is a horizon as
 * vtkStackedHeightFieldMapper takes it (an nx x ny x 1 vtkImageData whose point value, times
 * HeightScale along the image's third axis, places each point; origin, spacing and direction
 * honoured; NaN, |v| >= 1e30 and NullValue when UseNullValue are no data). Input 1 is a volume
 * in the same world coordinates: a vtkImageData in core, or the output of a vtkPagePoolReader,
 * whose pool is then read at full resolution block by block of BlockSize x BlockSize horizon
 * points, each block reading only the pages under its points (a horizon across a survey of
 * many GB reads a slab of it, never the whole). The output is the horizon with one more point
 * array, OutputArrayName (float), trilinear (or nearest-point) in the volume's voxels, NaN
 * where the horizon has no data or leaves the volume; the mapper colours the horizon with it
 * (vtkStackedHeightFieldMapper::SetHorizonColorArray), bilinear between the grid points.
 *
 * Progress events per block; AbortExecute stops between blocks (no output then).
 *
 * @code
 * vtkNew<vtkHorizonVolumeSampler> drape;
 * drape->SetInputConnection(horizonReader->GetOutputPort());
 * drape->SetVolumeConnection(poolReader->GetOutputPort());
 * drape->SetHeightScale(-1.0); // as the mapper's
 * mapper->AddInputConnection(drape->GetOutputPort());
 * mapper->SetHorizonColorArray(0, "amplitude");
 * @endcode
 *
 * @sa vtkStackedHeightFieldMapper vtkPagePoolReader
 */
#ifndef vtkHorizonVolumeSampler_h
#define vtkHorizonVolumeSampler_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkDataArray;
class vtkImageData;

#include <string> // For std::string

class STRATAIO_EXPORT vtkHorizonVolumeSampler : public vtkImageAlgorithm
{
public:
  static vtkHorizonVolumeSampler* New();
  vtkTypeMacro(vtkHorizonVolumeSampler, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The volume to sample (input port 1).
  void SetVolumeConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// Factor from the horizon's value to its third axis, as the mapper's. Default 1.
  vtkSetMacro(HeightScale, double);
  vtkGetMacro(HeightScale, double);
  ///@}

  ///@{
  /// The horizon's height array; empty (default) is its active point scalars.
  vtkSetStdStringFromCharMacro(HeightArrayName);
  vtkGetCharFromStdStringMacro(HeightArrayName);
  ///@}

  ///@{
  /// A height value meaning no data, when UseNullValue (default off, value 0).
  vtkSetMacro(NullValue, double);
  vtkGetMacro(NullValue, double);
  vtkSetMacro(UseNullValue, bool);
  vtkGetMacro(UseNullValue, bool);
  ///@}

  ///@{
  /// The volume's array; empty (default) is its active point scalars (component 0).
  vtkSetStdStringFromCharMacro(VolumeArrayName);
  vtkGetCharFromStdStringMacro(VolumeArrayName);
  ///@}

  ///@{
  /// Name of the output array. Default "amplitude".
  vtkSetStdStringFromCharMacro(OutputArrayName);
  vtkGetCharFromStdStringMacro(OutputArrayName);
  ///@}

  ///@{
  /// Nearest-point instead of trilinear sampling. Default off.
  vtkSetMacro(NearestNeighbor, bool);
  vtkGetMacro(NearestNeighbor, bool);
  vtkBooleanMacro(NearestNeighbor, bool);
  ///@}

  ///@{
  /// Horizon points per side of one block read from a paged volume. Default 128.
  vtkSetClampMacro(BlockSize, int, 2, 65536);
  vtkGetMacro(BlockSize, int);
  ///@}

  ///@{
  /// What the last update did: points sampled inside the volume, points of no data (holes or
  /// outside), and, paged, pages read from the pool (0 in core).
  vtkGetMacro(NumberOfSampledPoints, vtkIdType);
  vtkGetMacro(NumberOfEmptyPoints, vtkIdType);
  vtkGetMacro(NumberOfPagesRead, vtkIdType);
  ///@}

protected:
  vtkHorizonVolumeSampler();
  ~vtkHorizonVolumeSampler() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double HeightScale = 1.0;
  std::string HeightArrayName;
  double NullValue = 0.0;
  bool UseNullValue = false;
  std::string VolumeArrayName;
  std::string OutputArrayName = "amplitude";
  bool NearestNeighbor = false;
  int BlockSize = 128;
  vtkIdType NumberOfSampledPoints = 0;
  vtkIdType NumberOfEmptyPoints = 0;
  vtkIdType NumberOfPagesRead = 0;

private:
  vtkHorizonVolumeSampler(const vtkHorizonVolumeSampler&) = delete;
  void operator=(const vtkHorizonVolumeSampler&) = delete;
};

#endif

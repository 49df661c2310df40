// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHybridVolumeAlgorithm
 * @brief   Superclass of the algorithms that produce a hybrid point/volume representation:
 *          the low-resolution volume on output 0, the points on output 1.
 *
 * vtkHybridVolumeFilter (which builds the representation) and vtkHybridVolumeReader (which
 * loads it) must give identical outputs for the same strata::HybridVolumeFile, so the outputs are
 * defined once, here:
 * - Output 0, vtkImageData: the low-resolution volume, float point scalars "LowResolution",
 *   extent [0, LowDimensions - 1], origin = the file's Origin (the original volume's first
 *   point), spacing = Factor * Spacing, identity direction (the file stores none).
 * - Output 1, vtkPolyData: one point per hybrid point at its world position
 *   Origin + index * Spacing (double coordinates: UTM-sized coordinates lose metres in float),
 *   one vertex cell per point (what vtkPolyDataMapper draws; vtkPointGaussianMapper ignores
 *   cells), point data "Value" (float, active scalars), "Error" (float, original minus
 *   reconstruction), "Normals" (float x 3, decoded, active normals) and "NormalCode" (uint16,
 *   the stored octahedral code, for renderers that decode on the GPU); field data
 *   "PointSpacing" (3 doubles: ErrorGridStep * Spacing, the cell a point stands for). Points keep
 * the file's order (original linear index, x fastest).
 *
 * Subclasses implement RequestData (and RequestInformation / RequestUpdateExtent as needed)
 * and call FillOutputs and SetLowResolutionInformation.
 *
 * @sa vtkHybridVolumeFilter vtkHybridVolumeReader strata::HybridVolumeFile
 */
#ifndef vtkHybridVolumeAlgorithm_h
#define vtkHybridVolumeAlgorithm_h

#include "StrataIOModule.h" // For export macro
#include "vtkAlgorithm.h"

namespace strata
{
class HybridVolumeFile;
}
class vtkImageData;
class vtkPolyData;

class STRATAIO_EXPORT vtkHybridVolumeAlgorithm : public vtkAlgorithm
{
public:
  vtkTypeMacro(vtkHybridVolumeAlgorithm, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Dispatches the pipeline requests to RequestInformation, RequestUpdateExtent, RequestData.
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// Output 0: the low-resolution volume.
  vtkImageData* GetLowResolutionOutput();
  /// Output 1: the points.
  vtkPolyData* GetPointsOutput();

#ifndef __VTK_WRAP__
  /// Fills both outputs from `file` as the class documentation describes.
  static void FillOutputs(const strata::HybridVolumeFile& file,
    vtkImageData* lowResolution,
    vtkPolyData* points);
#endif

  /**
   * Reports output 0's whole extent, spacing, origin, identity direction and float scalars in
   * `outInfo`, for an original volume of `dimensions` points with `spacing` and `origin`
   * (its first point) reduced by `factor`.
   */
  static void SetLowResolutionInformation(vtkInformation* outInfo,
    const int dimensions[3],
    const int factor[3],
    const double spacing[3],
    const double origin[3]);

protected:
  vtkHybridVolumeAlgorithm();
  ~vtkHybridVolumeAlgorithm() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;

  virtual int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);
  virtual int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);
  virtual int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) = 0;

  /// Empties both outputs (after a failure).
  static void ClearOutputs(vtkInformationVector* outputVector);

private:
  vtkHybridVolumeAlgorithm(const vtkHybridVolumeAlgorithm&) = delete;
  void operator=(const vtkHybridVolumeAlgorithm&) = delete;
};

#endif

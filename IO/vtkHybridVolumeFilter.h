// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHybridVolumeFilter
 * @brief   Builds the hybrid point/volume representation of a vtkImageData in a pipeline.
 *
 * The VTK face of strata::HybridVolumeBuilder (Wilson, Ma and McCormick, "A hybrid point and
 * volume rendering"): input 0 is a vtkImageData whose point scalars (the input array to
 * process, by default the active scalars; any type, component 0) are down-sampled; output 0
 * is the low-resolution volume and output 1 the points where it errs, as
 * vtkHybridVolumeAlgorithm describes. The outputs equal the builder's result exactly: the
 * filter only feeds the builder's slab source from the input array and converts the result.
 *
 * Memory. The builder's own working memory is bounded by MemoryLimit, but this filter asks
 * its input for the whole extent, so the original volume is in memory as a whole; memory
 * stays bounded only when the input itself is streamed outside the pipeline, by driving
 * strata::HybridVolumeBuilder from a slab source directly (ConfigureBuilder gives it this filter's
 * settings; strata-hybrid does so for raw files).
 *
 * Geometry. The origin of both outputs is the world position of the input's first point (the
 * input origin when its extent starts at 0). The input's direction matrix is ignored (with a
 * warning when it is not the identity): the file format stores none, and the filter must
 * give what vtkHybridVolumeReader gives back.
 *
 * When FileName is set the representation is also written there (strata::HybridVolumeFile::Write:
 * a temporary file renamed when complete). Errors (no scalars, bad settings, an unwritable
 * file) are reported with vtkErrorMacro and leave both outputs empty. Progress events follow
 * the builder (pass 1 the first half), non-decreasing, ending at 1. AbortExecute stops the
 * build at the next slab.
 *
 * @sa strata::HybridVolumeBuilder vtkHybridVolumeReader vtkHybridVolumeAlgorithm
 */
#ifndef vtkHybridVolumeFilter_h
#define vtkHybridVolumeFilter_h

#include "StrataHybridVolumeFile.h" // For FilterType
#include "StrataIOModule.h"         // For export macro
#include "vtkHybridVolumeAlgorithm.h"

namespace strata
{
class HybridVolumeBuilder;
}
class vtkPiecewiseFunction;

class STRATAIO_EXPORT vtkHybridVolumeFilter : public vtkHybridVolumeAlgorithm
{
public:
  using FilterType = strata::HybridVolumeFile::FilterType;

  static vtkHybridVolumeFilter* New();
  vtkTypeMacro(vtkHybridVolumeFilter, vtkHybridVolumeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sets a vtkImageData as input 0 (for a pipeline connection use SetInputConnection).
  void SetInputData(vtkDataObject* input) { this->SetInputDataObject(0, input); }

  ///@{
  /// Down-sampling factor per axis: 1, 2, 4 or 8. Default 2, 2, 2.
  vtkSetVector3Macro(Factor, int);
  vtkGetVector3Macro(Factor, int);
  ///@}

  ///@{
  /// Down-sampling filter; see strata::HybridVolumeBuilder. Default Cubic.
  void SetFilter(FilterType filter);
  FilterType GetFilter() const { return this->Filter; }
  void SetFilterToBox() { this->SetFilter(FilterType::Box); }
  void SetFilterToLinear() { this->SetFilter(FilterType::Linear); }
  void SetFilterToCubic() { this->SetFilter(FilterType::Cubic); }
  void SetFilterToOptimized() { this->SetFilter(FilterType::Optimized); }
  const char* GetFilterAsString() const { return GetFilterName(this->Filter); }
  ///@}
  /// "box", "linear", "cubic" or "optimized" (the names strata-hybrid accepts).
  static const char* GetFilterName(FilterType filter);

  ///@{
  /// Largest over-estimation of the Optimized filter, >= 0. Default 0.
  vtkSetMacro(OverestimationBound, double);
  vtkGetMacro(OverestimationBound, double);
  ///@}

  ///@{
  /// Error grid step per axis in original points, >= 1. Default 1, 1, 1.
  vtkSetVector3Macro(ErrorGridStep, int);
  vtkGetVector3Macro(ErrorGridStep, int);
  ///@}

  ///@{
  /// Points need |error| > Threshold (>= 0), or, with an opacity function, missing opacity
  /// above it. Default 0.
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);

  /**
   * Optional: the opacity function the data will be seen with. Points are then ranked by the
   * opacity the low-resolution volume misses, max(0, f(original) - f(reconstruction)), instead
   * of |error| (see strata::HybridVolumeBuilder::SetImportance); Threshold is in opacity units.
   */
  void SetOpacityFunction(vtkPiecewiseFunction* opacity);
  vtkGetObjectMacro(OpacityFunction, vtkPiecewiseFunction);

  /// Includes the opacity function's modification time.
  vtkMTimeType GetMTime() override;
  ///@}

  ///@{
  /// At most this many points, the largest errors; 0 means no budget. Default 0.
  vtkSetClampMacro(PointBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(PointBudget, vtkIdType);
  ///@}

  ///@{
  /// Working memory of the builder for original slices, in MB. Default 256.
  vtkSetMacro(MemoryLimit, double);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /// When set, the representation is also written to this file. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

#ifndef __VTK_WRAP__
  /// Gives `builder` this filter's settings (all but the input and the progress callback).
  void ConfigureBuilder(strata::HybridVolumeBuilder& builder) const;
#endif

protected:
  vtkHybridVolumeFilter();
  ~vtkHybridVolumeFilter() override;

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

  int Factor[3] = { 2, 2, 2 };
  FilterType Filter = FilterType::Cubic;
  double OverestimationBound = 0.0;
  int ErrorGridStep[3] = { 1, 1, 1 };
  double Threshold = 0.0;
  vtkPiecewiseFunction* OpacityFunction = nullptr;
  vtkIdType PointBudget = 0;
  double MemoryLimit = 256.0;
  char* FileName = nullptr;

private:
  vtkHybridVolumeFilter(const vtkHybridVolumeFilter&) = delete;
  void operator=(const vtkHybridVolumeFilter&) = delete;
};

#endif

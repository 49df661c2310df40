// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkSubsurfacePicker
 * @brief   Picks horizons and volumes of Strata's mappers from a pixel: the world position,
 *          the horizon hit (id, value) and the volume values along the ray to an opacity
 *          threshold, in core or paged.
 *
 * A vtkPicker: Pick(x, y, 0, renderer) casts the pixel's ray from the near to the far clipping
 * plane through every pickable prop, and GetPickPosition(), GetProp3D(), GetMapper() and
 * GetPickedPositions() answer as VTK's pickers do, for the nearest of
 * - a horizon of a vtkStackedHeightFieldMapper (vtkActor): the exact first hit of the ray with
 *   the stack's bilinear patches in double precision (strata::HeightFieldReferenceCaster, the
 *   surfaces the GPU draws: the mapper's HeightScale, HeightArrayName and null value, the
 *   actor's transform); GetHorizonId() is the input index, GetHorizonValue() the horizon's
 *   value there (a depth or a time);
 * - the volumes of a vtkMultiVolumeRayCastMapper (vtkVolume or vtkMultiVolume): the point where
 *   the ray's accumulated opacity reaches OpacityThreshold, composited as the mapper does
 *   (extinctions of overlapping volumes add; tau = -ln(1 - opacity) / unit distance from the
 *   mapper's own transfer function tables, trilinear or nearest as the property says, samples
 *   every StepFraction of the smallest voxel at segment midpoints, the crossing solved inside
 *   its step). The samples up to there (or to the horizon hit, which stops the rays as in the
 *   renderer, or to the far end) are GetRayPoints() (world), GetRayValues() (one component
 *   per volume input, NaN outside it) and GetRayOpacity() (accumulated after each sample).
 *
 * A vtkMultiVolume is cast along the whole ray after vtkPicker's own pass (whose bounding-box
 * test sees only the mapper's first input), its members placed by their own transforms; its
 * pick events fire before that.
 *
 * Paged inputs (vtkPagePoolReader outputs, which hold only their coarsest level) are read at
 * full resolution from their pools, only the pages under the ray: the pick is the one of the
 * in-core data, whatever is resident on the GPU.
 *
 * @sa vtkPicker strata::HeightFieldReferenceCaster strata::MultiVolumeReferenceIntegrator
 */
#ifndef vtkSubsurfacePicker_h
#define vtkSubsurfacePicker_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkDoubleArray.h"        // For vtkNew<vtkDoubleArray>
#include "vtkNew.h"                // For vtkNew
#include "vtkPicker.h"
#include "vtkPoints.h" // For vtkNew<vtkPoints>

#include <vector> // For std::vector

class STRATARENDERING_EXPORT vtkSubsurfacePicker : public vtkPicker
{
public:
  static vtkSubsurfacePicker* New();
  vtkTypeMacro(vtkSubsurfacePicker, vtkPicker);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Accumulated opacity at which a ray through volumes is picked. Default 0.5.
  vtkSetClampMacro(OpacityThreshold, double, 1e-6, 1.0);
  vtkGetMacro(OpacityThreshold, double);
  ///@}

  ///@{
  /// Step along the ray through volumes, as a fraction of the smallest voxel edge. Default 1/4
  /// (the mapper's sample distance).
  vtkSetClampMacro(StepFraction, double, 1e-3, 1.0);
  vtkGetMacro(StepFraction, double);
  ///@}

  ///@{
  /// The last pick's horizon hit: input index (-1: none), its value there, world position, and
  /// the parametric position along the pick ray (near plane 0, far plane 1).
  vtkGetMacro(HorizonId, int);
  vtkGetMacro(HorizonValue, double);
  vtkGetVector3Macro(HorizonPosition, double);
  vtkGetMacro(HorizonT, double);
  ///@}

  ///@{
  /// The last pick's volume hit: whether the accumulated opacity reached OpacityThreshold,
  /// where (world), and the parametric position along the pick ray.
  vtkGetMacro(VolumeHit, bool);
  vtkGetVector3Macro(VolumePosition, double);
  vtkGetMacro(VolumeT, double);
  ///@}

  ///@{
  /// The samples along the ray through the volumes (see the class comment).
  vtkPoints* GetRayPoints() { return this->RayPoints; }
  vtkDoubleArray* GetRayValues() { return this->RayValues; }
  vtkDoubleArray* GetRayOpacity() { return this->RayOpacity; }
  ///@}

protected:
  vtkSubsurfacePicker();
  ~vtkSubsurfacePicker() override;

  void Initialize() override;
  int Pick3DInternal(vtkRenderer* ren, double p1World[4], double p2World[4]) override;
  double IntersectWithLine(const double p1[3],
    const double p2[3],
    double tol,
    vtkAssemblyPath* path,
    vtkProp3D* prop,
    vtkAbstractMapper3D* mapper) override;

  double OpacityThreshold = 0.5;
  double StepFraction = 0.25;
  int HorizonId = -1;
  double HorizonValue = 0.0;
  double HorizonPosition[3] = { 0, 0, 0 };
  double HorizonT = VTK_DOUBLE_MAX;
  bool VolumeHit = false;
  double VolumePosition[3] = { 0, 0, 0 };
  double VolumeT = VTK_DOUBLE_MAX;
  vtkNew<vtkPoints> RayPoints;
  vtkNew<vtkDoubleArray> RayValues;
  vtkNew<vtkDoubleArray> RayOpacity;

private:
  vtkSubsurfacePicker(const vtkSubsurfacePicker&) = delete;
  void operator=(const vtkSubsurfacePicker&) = delete;

  class vtkInternals;
  double PickHorizons(const double p1[3],
    const double p2[3],
    vtkAssemblyPath* path,
    vtkProp3D* prop,
    vtkAbstractMapper3D* mapper);
  double PickVolumes(const double p1[3],
    const double p2[3],
    vtkAssemblyPath* path,
    vtkProp3D* prop,
    vtkAbstractMapper3D* mapper);
  /// Parametric positions of the ray samples (to cut them at a nearer horizon).
  std::vector<double> RayT;
};

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkHybridVolumeMapper
 * @brief   Draws a hybrid point + volume representation: a low-resolution volume plus points
 *          where it is wrong, in one composite.
 *
 * Wilson, Ma and McCormick's hybrid rendering, on today's pipeline. Input 0 is the
 * low-resolution vtkImageData, input 1 the points (vtkHybridVolumeFilter or
 * vtkHybridVolumeReader outputs: point data "Value" and "Error", optionally "Normals", field
 * data "PointSpacing", the world size of the error-grid cell a point stands for). The volume is
 * ray cast by an internal vtkMultiVolumeRayCastMapper (bricks, skipping, pre-integration and
 * all), in NumberOfSlabs depth slabs perpendicular to the view direction, back to front; after
 * each slab the points inside it are drawn, sorted back to front, blended over it. Where the
 * paper interleaved point slices with volume slices, depth slabs of the ray-cast volume are the
 * equivalent here: one slab is the cheapest and coarsest ordering, more slabs order points and
 * volume more finely and cost one more ray-casting pass each (the ray's sample lattice is
 * shared, so slabs add no sampling error).
 *
 * A point's colour and opacity come from the transfer function of its original value, as the
 * correction over the low-resolution value it replaces (see vtkHybridPointsVS.glsl). Points are
 * screen-aligned squares or Gaussian splats (PointShape), footprints rounded up to whole pixels
 * with opacity reduced by the area ratio. Only what is used is compiled: no kernel code for
 * squares, no normals unless the volume property asks for shading. With no points the result is
 * exactly the low-resolution volume's rendering.
 *
 * Out of core: input 0 may be a vtkPagePoolReader of a brick pool of the low-resolution volume;
 * the internal mapper then pages it (see vtkMultiVolumeRayCastMapper's PageCacheBudget and
 * level-of-detail feedback, set on GetVolumeMapper()). One frame keeps one cut for all its slabs
 * (the first slab chooses it, the others hold it), and the feedback of every slab ranks the
 * bricks for the next frame.
 */
#ifndef vtkHybridVolumeMapper_h
#define vtkHybridVolumeMapper_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkImageData;
class vtkMultiVolumeRayCastMapper;
class vtkPolyData;

class STRATARENDERING_EXPORT vtkHybridVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkHybridVolumeMapper* New();
  vtkTypeMacro(vtkHybridVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum class PointShapes
  {
    Squares,
    GaussianSplats
  };

  ///@{
  /// Squares (default) or Gaussian splats.
  void SetPointShape(PointShapes shape);
  PointShapes GetPointShape() const { return this->PointShape; }
  ///@}

  ///@{
  /// Depth slabs the volume is cut into for ordering the points against it (1 to 256, default 8).
  vtkSetClampMacro(NumberOfSlabs, int, 1, 256);
  vtkGetMacro(NumberOfSlabs, int);
  ///@}

  ///@{
  /**
   * World size of the cell a point stands for. 0 (default): the points input's field data
   * "PointSpacing" (3 values; their geometric mean is used).
   */
  vtkSetClampMacro(PointSpacing, double, 0.0, 1.0e300);
  vtkGetMacro(PointSpacing, double);
  ///@}

  /// The points input (port 1).
  void SetPointsInputData(vtkPolyData* points);
  void SetPointsInputConnection(vtkAlgorithmOutput* output);

  ///@{
  /**
   * Draw only what lies in the world box `bounds` (xmin, xmax, ymin, ymax, zmin, zmax), for
   * sort-last parallel rendering as vtkMultiVolumeRayCastMapper::SetRegion describes: the volume
   * is clipped to the box by its ray caster (bricks outside it never paged), and only the points
   * whose centres lie in it (min <= x < max per axis) are drawn, so that the boxes of a partition
   * together draw every point once. A point's footprint is drawn whole by the box of its centre, at
   * its depth: next to a face that the view sees obliquely, it is blended over the other box's
   * volume where that lies in front of the point within its footprint.
   */
  void SetRegion(const double bounds[6]);
  void RemoveRegion();
  /// False when no region is set.
  bool GetRegion(double bounds[6]) const;
  ///@}

  /// The ray caster of the low-resolution volume, for its settings (sample distance, ...).
  vtkMultiVolumeRayCastMapper* GetVolumeMapper();

  /// Points sent to be drawn in the last frame (those adding no opacity are culled on the GPU).
  vtkIdType GetNumberOfPointsDrawn() const;

  /// The generated point shaders of the last frame, for tests.
  std::string GetPointVertexShaderSource() const;
  std::string GetPointFragmentShaderSource() const;

  ///@{
  /**
   * Point shader sources built and programs compiled since the mapper was made (its volume
   * mapper counts its own): a frame that draws what the last one drew adds nothing.
   */
  int GetNumberOfShaderSourcesBuilt() const;
  int GetNumberOfShaderCompilations() const;
  ///@}

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  /// Asks a page-pool reader on input 0 for its coarsest level (the volume mapper pages it).
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkHybridVolumeMapper();
  ~vtkHybridVolumeMapper() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  PointShapes PointShape = PointShapes::Squares;
  int NumberOfSlabs = 8;
  double PointSpacing = 0.0;

private:
  vtkHybridVolumeMapper(const vtkHybridVolumeMapper&) = delete;
  /// Updates both inputs (a pool's reader at its coarsest level) and hands input 0 to the
  /// volume mapper; the low-resolution image, null (an error given) without one.
  vtkImageData* UpdateInputs(vtkPolyData*& points);
  /// The world size of the cell a point stands for; 0 (an error given) when unknown.
  double GetCellSize(vtkPolyData* points);
  void operator=(const vtkHybridVolumeMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkPagePoolReader
 * @brief   Reads a Strata page pool (brick or tile pool) as vtkImageData, page by page.
 *
 * The VTK face of the out-of-core format (strata::PagePoolFormat): RequestInformation opens the
 * file (header and page table only) and reports the whole extent, spacing, origin, direction and
 * scalar type of the level Resolution selects (level 0 by default), and CAN_PRODUCE_SUB_EXTENT;
 * RequestData reads only the pages that overlap the requested update extent (in that level's
 * indices), so a downstream filter gets a correct, possibly coarse, image whose extent and
 * spacing are the ones declared, without the data set ever being read as a whole (an outline
 * or a surface of a coarse level is the box of the data, not of level 0). One class serves both
 * kinds:
 * - BrickPool (nx, ny, nz): an nx x ny x nz image.
 * - TilePool (nx, ny, L): an nx x ny x 1 image of the layer selected by Layer.
 *
 * Resolution. VTK 9.1 has no UPDATE_RESOLUTION key (it was dropped in VTK 7), so the core
 * defines one, vtkPagePoolProtocol::UPDATE_RESOLUTION() (also UPDATE_RESOLUTION() here), which a
 * downstream filter sets on its input information in RequestUpdateExtent (it is copied
 * upstream through intermediate filters like UPDATE_EXTENT) or a caller sets on the reader's
 * output information; without it the Resolution member is used. A consumer that asks for
 * another level than Resolution's (the Strata mappers ask for the coarsest: they page the rest)
 * gets that level's image of the requested region, with that level's extent and spacing: only
 * consumers that page the pool themselves should ask. A resolution r in (0, 1]
 * selects level l = floor(log2(1 / r)) clamped to the pool's levels: 1 is level 0 (full
 * resolution), 0.5 level 1, 0.25 level 2, and r <= 0 the coarsest level.
 *
 * Geometry of a coarse level: strata::PagePoolSet (the output keeps the origin and the
 * direction, its spacing grows so that the coarse image covers exactly the full one's region;
 * an update extent in the declared level's indices maps to the smallest extent of the level
 * asked for that covers the same region).
 *
 * Pools and their consumers (vtkPagePoolProtocol). RequestInformation marks the output
 * information PAGE_POOL, so that a mapper paging the pool itself asks for the coarsest level
 * only; RequestData writes the pool's identity (file, layer, step, series) on the output's
 * field data. The files are opened once per process (strata::PagePoolFile::OpenShared): the reader
 * holds the pools it names open, and the mappers paging them share its descriptors.
 *
 * Time series. A series is one pool per time step, given with AddTimeStep(file, time) in
 * increasing time (FileName is then ignored): RequestInformation checks that every step's
 * pool opens and has the kind, dimensions, page size, levels and scalar type of the first
 * (else an error naming the step and what differs, and no output), and reports the times as
 * TIME_STEPS and TIME_RANGE. A request's UPDATE_TIME_STEP t selects the step at or below t,
 * as VTK's readers do: the last step whose time is <= t, the first step for t before it,
 * the last for t after it; without UPDATE_TIME_STEP, the first step. The output's
 * DATA_TIME_STEP is that step's time, and its identity names that step's pool, its index and
 * every step's pool in time order, so that a mapper paging the pool pages the step shown and
 * can prefetch the next one. Steps share one geometry: the first step's
 * spacing, origin and direction.
 *
 * Components. A set of brick pools, one per component (strata::PagePoolFormat, Components), is one
 * image of 2 to 4 components: FileName names component 0 and the reader opens and checks the
 * others (each must belong to the same write and have the same structure; a missing or foreign
 * one is an error, never a volume of fewer components); every page is read once per component.
 * Naming a file of component c > 0 is an error that names component 0's file.
 *
 * Pages read are counted (GetNumberOfPagesRead, reset at every RequestData) so tests and
 * benchmarks can verify that a sub-extent reads only what it needs. Errors (missing file,
 * corrupt header, table or page) are reported with vtkErrorMacro and leave the output empty.
 * Progress events are fired per page.
 *
 * @sa strata::PagePoolFile strata::PagePoolFormat vtkImageToPagePoolWriter
 */
#ifndef vtkPagePoolReader_h
#define vtkPagePoolReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include "vtkSmartPointer.h" // For LastOutput

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkImageData;
class vtkInformationDoubleKey;
class vtkInformationVector;

class STRATAIO_EXPORT vtkPagePoolReader : public vtkImageAlgorithm
{
public:
  static vtkPagePoolReader* New();
  vtkTypeMacro(vtkPagePoolReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The page pool file (.spp) to read. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// Layer of a tile pool to output, in [0, layers - 1]. Ignored for brick pools. Default 0.
  vtkSetMacro(Layer, int);
  vtkGetMacro(Layer, int);
  ///@}

  ///@{
  /// The level declared (whole extent, spacing) and read when the request carries no
  /// UPDATE_RESOLUTION; see the class documentation for the mapping to levels. Default 1 (full
  /// resolution).
  vtkSetClampMacro(Resolution, double, 0.0, 1.0);
  vtkGetMacro(Resolution, double);
  ///@}

  ///@{
  /// The most memory, in MB, that one output may take: a request whose level and extent need
  /// more (a whole terabyte pool at full resolution, say) is an error naming this limit and the
  /// level, raised before anything is allocated; ask for a lower Resolution or a smaller update
  /// extent instead. 0 (the default) means the machine's physical memory.
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /// Name of the output point-data array. Default: "values".
  vtkSetStringMacro(ArrayName);
  vtkGetStringMacro(ArrayName);
  ///@}

  ///@{
  /**
   * A time series: step `fileName` at time `time` (times strictly increasing; see the class
   * documentation). With any step, FileName is ignored. Default: no steps.
   */
  void AddTimeStep(const char* fileName, double time);
  void RemoveAllTimeSteps();
  int GetNumberOfTimeSteps() const { return static_cast<int>(this->StepFiles.size()); }
  const char* GetTimeStepFileName(int step) const;
  double GetTimeStepValue(int step) const;
  ///@}
  /// The step that time `t` selects among increasing `times` (the last at or below t).
  static int ChooseTimeStep(const double* times, int count, double t);
  /// The step the last RequestData read (-1 before, 0 without a series).
  vtkGetMacro(TimeStepRead, int);

  /**
   * The resolution a consumer asks for: vtkPagePoolProtocol::UPDATE_RESOLUTION (the same key,
   * here for wrapped languages, where the core is not wrapped). The pipeline protocol (the
   * PAGE_POOL mark this reader sets in RequestInformation, the pool's identity it writes on
   * its output's field data) is vtkPagePoolProtocol's.
   */
  static vtkInformationDoubleKey* UPDATE_RESOLUTION();

  /// True when the file starts with a valid page pool header (magic, version, checksum).
  static bool CanReadFile(const char* fileName);

  ///@{
  /// What the last RequestInformation found (0 before, or after a failure): number of levels,
  /// layers of a tile pool (1 for bricks), whether it is a tile pool.
  vtkGetMacro(NumberOfLevels, int);
  vtkGetMacro(NumberOfLayers, int);
  vtkGetMacro(IsTilePool, bool);
  ///@}

  ///@{
  /// Pages read by the last RequestData, and the level it read.
  vtkGetMacro(NumberOfPagesRead, vtkIdType);
  vtkGetMacro(LevelRead, int);
  ///@}

protected:
  /// The pool's identity (vtkPagePoolProtocol) and the step's time on `output`.
  void MarkPool(vtkImageData* output, const std::string& name);
  /// The request `outInfo` makes of pool `name` as a string (to answer a repeat from
  /// LastOutput), and the level it reads.
  std::string DescribeRequest(vtkInformation* outInfo, const std::string& name, int& level) const;
  /// MemoryLimit, or the physical memory when it is 0 (0 if unknown).
  double GetMemoryLimitMB() const;
  /// The pool that `outInfo`'s request reads (the series' step of its time), the step's
  /// index in `step`; the request's pool keys set on `outInfo`.
  std::string SelectPool(vtkInformation* outInfo, int& step);
  /// A series' steps checked against the first (see the class documentation); false, with
  /// `error` set, when one cannot be opened or differs.
  bool CheckSeries(std::string& error) const;

  vtkPagePoolReader();
  ~vtkPagePoolReader() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;
  char* ArrayName = nullptr;
  int Layer = 0;
  double Resolution = 1.0;
  double MemoryLimit = 0.0;
  int NumberOfLevels = 0;
  int NumberOfLayers = 0;
  bool IsTilePool = false;
  vtkIdType NumberOfPagesRead = 0;
  int LevelRead = -1;
  int TimeStepRead = -1;
  std::vector<std::string> StepFiles;
  std::vector<double> StepTimes;
  // The last output and the request it answered: the executive asks again for every update of
  // a level other than the declared one (its extent is never "inside" the request), and
  // the answer must not cost I/O again, nor fail if the file changed on disk since.
  vtkSmartPointer<vtkImageData> LastOutput;
  std::string LastRequest;
  vtkMTimeType LastTime = 0;

private:
  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;

  vtkPagePoolReader(const vtkPagePoolReader&) = delete;
  void operator=(const vtkPagePoolReader&) = delete;
};

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkPagePoolProtocol
 * @brief   How a page pool and its consumers talk through a VTK pipeline: the pool's identity
 *          on the data, the pool-source mark and the resolution request on the information.
 *
 * A consumer that pages a pool itself (the Strata mappers, the picker, the horizon sampler)
 * must not have the pipeline read the pool as a whole, and must know which pool a data set
 * shows. Three things travel, each one way only:
 * - PAGE_POOL(), set by a pool's source (vtkPagePoolReader, or ParaView's producer of a
 *   representation's copy) on its output information in RequestInformation: "the data of this
 *   connection is a page pool's coarse view". It is not copied downstream, so a filter between
 *   the source and a consumer ends the paging: the consumer then renders the filter's output,
 *   as it must (a filter's output is not the pool).
 * - UPDATE_RESOLUTION(), set by a consumer on its input information: the resolution in [0, 1]
 *   to read (VTK 9.1 has no such key; this one travels upstream with the update extent).
 *   RequestCoarsestLevel asks for 0, the coarsest level, on a connection marked PAGE_POOL.
 * - The pool's identity (SetIdentity, GetIdentity): file name, tile layer, time step and the
 *   series' files, as one-value field-data arrays of the data object. It is the only transport
 *   of the identity: shallow copies and ParaView's delivery keep field data where pipeline
 *   information is lost.
 *
 * GetInputPool combines them: the identity of the data on a connection marked PAGE_POOL, or
 * an invalid identity when either is missing.
 *
 * @sa strata::PagePoolFile strata::PagePoolFormat
 */
#ifndef vtkPagePoolProtocol_h
#define vtkPagePoolProtocol_h

#include "StrataCoreModule.h" // For export macro
#include "vtkObject.h"

#include <string> // For std::string
#include <vector> // For std::vector

class vtkDataObject;
class vtkInformation;
class vtkInformationDoubleKey;
class vtkInformationIntegerKey;
class vtkInformationVector;

class STRATACORE_EXPORT vtkPagePoolProtocol : public vtkObject
{
public:
  static vtkPagePoolProtocol* New();
  vtkTypeMacro(vtkPagePoolProtocol, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Which pool a data set shows.
  struct Identity
  {
    std::string FileName;            ///< the pool (component 0 of a set of components)
    int Layer = 0;                   ///< the tile pool's layer shown (0 for bricks)
    int TimeStep = 0;                ///< the step of Series shown (0 without a series)
    std::vector<std::string> Series; ///< every step's pool in time order (empty without)
    bool IsValid() const { return !this->FileName.empty(); }
    bool operator==(const Identity& other) const
    {
      return this->FileName == other.FileName && this->Layer == other.Layer &&
             this->TimeStep == other.TimeStep && this->Series == other.Series;
    }
    bool operator!=(const Identity& other) const { return !(*this == other); }
  };

  /// "This connection's data is a page pool's coarse view": on a pool source's output
  /// information (1), never copied downstream.
  static vtkInformationIntegerKey* PAGE_POOL();
  /// The resolution in [0, 1] a consumer asks of a pool (1 the finest, 0 the coarsest level).
  static vtkInformationDoubleKey* UPDATE_RESOLUTION();

  ///@{
  /// The identity as field data of `data` (replacing any); an invalid identity removes it.
  static void SetIdentity(vtkDataObject* data, const Identity& identity);
  static Identity GetIdentity(vtkDataObject* data);
  ///@}

  /// The identity of `data` when `inputInfo` (its connection) is marked PAGE_POOL; else invalid.
  static Identity GetInputPool(vtkInformation* inputInfo, vtkDataObject* data);
  /// Whether `info` (a connection) is marked PAGE_POOL.
  static bool IsPagePool(vtkInformation* info);

  /**
   * For a consumer that pages from the pool itself: if `inputInfo` is marked PAGE_POOL, asks
   * for the coarsest level and returns true. Call it before updating the input and in the
   * consumer's REQUEST_UPDATE_EXTENT, so that no update (a render, GetBounds) reads the pool.
   */
  static bool RequestCoarsestLevel(vtkInformation* inputInfo);
  /// RequestCoarsestLevel on every input of the first `ports` ports when `request` is a
  /// REQUEST_UPDATE_EXTENT pass; a consumer's ProcessRequest calls it after its superclass's.
  static void RequestCoarsestLevels(vtkInformation* request,
    vtkInformationVector** inputVector,
    int ports);

  /**
   * The level resolution `r` selects in a pool of `levels` levels: l = floor(log2(1 / r))
   * clamped to the levels, so 1 is level 0, 0.5 level 1, and r <= 0 the coarsest level.
   */
  static int ResolutionToLevel(double r, int levels);

  ///@{
  /// Names of the field-data arrays that carry the identity.
  static const char* const FileNameArray;
  static const char* const LayerArray;
  static const char* const SeriesArray;
  static const char* const TimeStepArray;
  ///@}

protected:
  vtkPagePoolProtocol() = default;
  ~vtkPagePoolProtocol() override = default;

private:
  vtkPagePoolProtocol(const vtkPagePoolProtocol&) = delete;
  void operator=(const vtkPagePoolProtocol&) = delete;
};

#endif

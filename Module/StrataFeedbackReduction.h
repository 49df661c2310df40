// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::FeedbackReduction
 * @brief   Reduces a level-of-detail feedback buffer to a sorted list of (page, coverage).
 *
 * The feedback of Hollemeersch et al. as used by the stacked height-field ray caster (Lux and
 * Froehlich, section 3.2): while ray casting, the shader writes the id of each page it needed
 * into a feedback buffer a fraction of the viewport in size (image load/store, so no extra
 * pass and no MRT of viewport size). The buffer is then reduced to a compact list of the
 * distinct pages and the number of texels that asked for each; that list, orders of
 * magnitude smaller than the buffer, drives the cut update (coverage is the priority) and the
 * page loads. The reduction is done by an OpenCL kernel (any OpenCL 1.2 device; PoCL on the
 * CPU where there is no GPU) or by plain C++; both give the same list for any input, which
 * is what lets the renderer pick either and the tests compare them.
 *
 * Feedback buffer: W x H x L texels of uint32 page ids, L layers (a ray that needs pages of
 * several data sets writes one per layer), 0 = no page. Texel order does not matter, so the
 * input is just a pointer and a count. Coverage counts texels: a shader that writes a page at
 * most once per pixel makes it a pixel count.
 *
 * Page id packing (32 bits, id 0 is never a page):
 * | bits  | 31..26           | 25..21   | 20..0                         |
 * |-------|------------------|----------|-------------------------------|
 * | field | data set + 1     | level    | page index within the level   |
 * | range | 0..62 (6 bits)   | 0..31    | 0..2^21-1 (2,097,152 pages)   |
 * The data set is stored plus one so that every valid id is non-zero. Level and page index
 * are those of the data set's hierarchy (level 0 the finest, index x fastest, as in
 * strata::VolumeBrickTree); 2^21 pages is a 128^3 grid of bricks or a 1448^2 grid of tiles per
 * level. Sorting by id thus groups by data set, then level, then page.
 *
 * Output: entries sorted by page id, each id once, coverage > 0. Ancestors are NOT added by
 * the reduction: the parent of a page depends on the data set's tree (quadtree or octree,
 * level sizes), which the buffer does not know. PropagateToAncestors() does it for a caller
 * that supplies the parent function, so the cut can keep coarser levels resident.
 *
 * The OpenCL context, queue, program and buffers are created on first use and reused; buffers
 * only grow. When there is no platform or device, or the program fails to build,
 * ReduceOpenCL() returns false and GetOpenCLMessage() says why; Reduce() then uses the CPU.
 *
 * @sa strata::BrickAtlasAllocator strata::VolumeCut
 */
#ifndef StrataFeedbackReduction_h
#define StrataFeedbackReduction_h

#include "StrataCoreModule.h" // For export macro

#include <cstddef>    // For size_t
#include <cstdint>    // For uint32_t
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace strata
{
class STRATACORE_EXPORT FeedbackReduction
{
public:
  struct Entry
  {
    uint32_t Page = 0;     ///< packed page id, never 0
    uint32_t Coverage = 0; ///< texels that asked for the page
    bool operator==(const Entry& o) const
    {
      return this->Page == o.Page && this->Coverage == o.Coverage;
    }
    bool operator!=(const Entry& o) const { return !(*this == o); }
  };

  ///@{
  /// Page id field widths and limits (see the class documentation).
  static constexpr uint32_t NoPage = 0;
  static constexpr int DataSetBits = 6;
  static constexpr int LevelBits = 5;
  static constexpr int PageBits = 21;
  static constexpr int MaxDataSets = (1 << DataSetBits) - 1; ///< 63: data sets 0..62
  static constexpr int MaxLevels = 1 << LevelBits;           ///< 32: levels 0..31
  static constexpr uint32_t MaxPagesPerLevel = 1u << PageBits;
  ///@}

  ///@{
  /// Packs (data set, level, page index); NoPage (0) when a field is out of range.
  static uint32_t PackPage(int dataSet, int level, uint32_t pageIndex);
  static int GetDataSet(uint32_t id) { return static_cast<int>(id >> (LevelBits + PageBits)) - 1; }
  static int GetLevel(uint32_t id)
  {
    return static_cast<int>((id >> PageBits) & ((1u << LevelBits) - 1));
  }
  static uint32_t GetPageIndex(uint32_t id) { return id & (MaxPagesPerLevel - 1); }
  ///@}

  /**
   * GLSL of `uint strataPackPage(uint dataSet, uint level, uint pageIndex)`, the same packing
   * for the ray casters that write the buffer (no range check: the shader writes valid ids).
   */
  static std::string GetGLSLPackFunction();

  FeedbackReduction();
  ~FeedbackReduction();
  FeedbackReduction(const FeedbackReduction&) = delete;
  FeedbackReduction& operator=(const FeedbackReduction&) = delete;

  /**
   * Plain C++: run-length pre-count (feedback is spatially coherent, so neighbouring texels
   * mostly repeat an id) into an open-addressing hash table, then the distinct ids are sorted.
   * Fails only for count >= 2^30 (32-bit coverage and kernel indices) or a null buffer.
   */
  bool ReduceCPU(const uint32_t* ids, size_t count, std::vector<Entry>& list);

  /**
   * OpenCL: per-work-group histograms in local memory (hash with bounded probing), flushed
   * with atomic adds into a global hash table twice the buffer size (so it never fills), then
   * a compaction kernel; only the compact list is read back and sorted on the host. Returns
   * false (list emptied, GetOpenCLMessage() says why) when OpenCL is unavailable or fails.
   */
  bool ReduceOpenCL(const uint32_t* ids, size_t count, std::vector<Entry>& list);

  /// ReduceOpenCL() when UseOpenCL is on and it succeeds, else ReduceCPU().
  bool Reduce(const uint32_t* ids, size_t count, std::vector<Entry>& list);

  ///@{
  /// Whether Reduce() tries OpenCL first. Default true.
  void SetUseOpenCL(bool use) { this->UseOpenCL = use; }
  bool GetUseOpenCL() const { return this->UseOpenCL; }
  ///@}

  /// Sets OpenCL up on the first call (first platform with a device, GPU preferred).
  bool IsOpenCLAvailable();
  /// Why OpenCL is unavailable or the last OpenCL call failed; empty when all went well.
  const std::string& GetOpenCLMessage() const;
  /// "platform / device" once set up; empty otherwise.
  const std::string& GetOpenCLDeviceName() const;

  ///@{
  /**
   * Wall time in seconds of the last call of each (upload, kernels, read-back and sort for
   * OpenCL; one-time set-up excluded and reported by GetOpenCLSetupSeconds()). -1 before any.
   */
  double GetLastCPUSeconds() const { return this->LastCPUSeconds; }
  double GetLastOpenCLSeconds() const { return this->LastOpenCLSeconds; }
  double GetOpenCLSetupSeconds() const { return this->OpenCLSetupSeconds; }
  ///@}

  /**
   * Adds each page's coverage to all its ancestors, given `parent(id)` (the packed id of the
   * parent, NoPage at the root); the result stays sorted and unique. Coverage then says how
   * many texels a node's subtree was asked for, the priority of keeping it resident.
   * Coverage saturates at UINT32_MAX.
   */
  static void PropagateToAncestors(std::vector<Entry>& list,
    const std::function<uint32_t(uint32_t)>& parent);

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  bool UseOpenCL = true;
  double LastCPUSeconds = -1;
  double LastOpenCLSeconds = -1;
  double OpenCLSetupSeconds = -1;
};
}

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::BrickAtlasAllocator
 * @brief   Slot bookkeeping of one brick atlas 3-D texture shared by all volumes.
 *
 * The atlas of Lux and Froehlich (multi-volume multi-resolution ray casting, sections 3.2-3.3):
 * one pre-allocated 3-D texture of SX x SY x SZ slots, each holding one brick of B^3 voxels
 * of any volume and level. All slots are the same size, so there is no fragmentation, and
 * one budget serves every volume. The atlas is the first-level cache: bricks that left the
 * cut keep their slot until it is needed (LRU), so a cut that comes back costs no upload.
 *
 * Slots are keyed by (volume, level, brick index within the level). A frame counter gives
 * the pinning rule: a brick requested during the current frame is pinned, never evicted
 * before the next BeginFrame(), because the frame's index tables point at it. Pinned slots
 * are always the most recently used, so the LRU end of the list is the eviction candidate
 * and pinning costs nothing extra. Only bookkeeping: the GPU side owns the texture and
 * uploads what Request() reports as a miss.
 *
 * Slot s lies at (s % SX, (s / SX) % SY, s / (SX SY)); its first texel is that times B.
 *
 * @sa strata::VolumeBrickTree strata::VolumeCut
 */
#ifndef StrataBrickAtlasAllocator_h
#define StrataBrickAtlasAllocator_h

#include "StrataCoreModule.h" // For export macro

#include <array>         // For std::array
#include <cstddef>       // For size_t
#include <cstdint>       // For int64_t
#include <unordered_map> // For std::unordered_map
#include <vector>        // For std::vector

namespace strata
{
class STRATACORE_EXPORT BrickAtlasAllocator
{
public:
  struct Key
  {
    int Volume = -1;
    int Level = 0;
    int64_t Brick = 0; ///< brick index within its level (x fastest)
    bool operator==(const Key& o) const
    {
      return this->Volume == o.Volume && this->Level == o.Level && this->Brick == o.Brick;
    }
  };

  struct Result
  {
    int Slot = -1;        ///< -1: every slot is pinned by this frame
    bool Hit = false;     ///< the brick is already there; false: the caller must upload it
    bool Evicted = false; ///< the slot held another brick, EvictedKey, now gone
    Key EvictedKey;
  };

  struct Statistics
  {
    int64_t Hits = 0;
    int64_t Misses = 0;    ///< requests that needed an upload (including failed ones)
    int64_t Evictions = 0; ///< misses that displaced a resident brick
    int64_t Failures = 0;  ///< misses that found no slot (all pinned)
  };

  /**
   * Slots per axis (SX >= SY >= SZ) holding the most bricks of brickSize^3 voxels of
   * bytesPerVoxel bytes within budgetMiB (2^20 bytes), each axis at most
   * maxTextureSize / brickSize slots; among layouts of equal count the most cubic. {0,0,0}
   * when not even one brick fits.
   */
  static std::array<int, 3> ComputeLayout(double budgetMiB,
    int brickSize,
    int bytesPerVoxel,
    int maxTextureSize = 2048);

  ///@{
  /**
   * Empties the atlas and sets its layout. Returns false (and leaves it with no slots) for
   * a layout without slots or a brick size below 2.
   */
  bool Initialize(int slotsX, int slotsY, int slotsZ, int brickSize);
  bool InitializeFromBudget(double budgetMiB,
    int brickSize,
    int bytesPerVoxel,
    int maxTextureSize = 2048);
  ///@}

  int GetBrickSize() const { return this->BrickSize; }
  const std::array<int, 3>& GetSlotLayout() const { return this->Layout; }
  int GetNumberOfSlots() const { return static_cast<int>(this->Slots.size()); }
  /// Texels of the atlas texture per axis: slots times brick size.
  std::array<int, 3> GetTextureSize() const;
  /// Slot coordinates (sx, sy, sz) of slot s; texel origin is these times the brick size.
  std::array<int, 3> GetSlotPosition(int slot) const;

  /// Starts a new frame: bricks requested so far become evictable.
  void BeginFrame();
  int64_t GetFrame() const { return this->Frame; }

  /**
   * Finds or allocates the slot of `key` and pins it for this frame. On a miss the slot is a
   * free one, else the least recently used unpinned one (reported in the result); the caller
   * uploads the brick. Fails (Slot -1) only when every slot is pinned.
   */
  Result Request(const Key& key);
  /// Slot of a resident brick, or -1; changes nothing (no pin, no LRU update, no statistics).
  int Find(const Key& key) const;
  /// Key held by a slot; false for a free slot.
  bool GetSlotKey(int slot, Key& key) const;
  bool IsPinned(int slot) const { return this->Slots[slot].LastUsed == this->Frame; }
  int GetNumberOfUsedSlots() const { return static_cast<int>(this->Map.size()); }
  int GetNumberOfPinnedSlots() const { return this->Pinned; }

  ///@{
  /// Frees slots (a brick that changed, a volume removed); freed slots are reused first.
  void Release(const Key& key);
  void ReleaseVolume(int volume);
  void Clear();
  ///@}

  const Statistics& GetStatistics() const { return this->Stats; }
  void ResetStatistics() { this->Stats = Statistics(); }

private:
  struct KeyHash
  {
    size_t operator()(const Key& k) const;
  };
  struct Slot
  {
    Key Owner;             ///< Owner.Volume < 0: free
    int64_t LastUsed = -1; ///< frame of the last request
    int Prev = -1;         ///< LRU list: towards least recently used
    int Next = -1;         ///< towards most recently used
  };
  void Unlink(int s);
  void PushFront(int s); ///< least recently used end
  void PushBack(int s);  ///< most recently used end
  void Free(int s);

  int BrickSize = 0;
  std::array<int, 3> Layout = { { 0, 0, 0 } };
  std::vector<Slot> Slots;
  int Head = -1; ///< least recently used (free slots first)
  int Tail = -1; ///< most recently used
  std::unordered_map<Key, int, KeyHash> Map;
  int64_t Frame = 0;
  int Pinned = 0;
  Statistics Stats;
};
}

#endif

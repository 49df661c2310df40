// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataBrickAtlasAllocator.h"

#include <algorithm>
#include <cmath>

namespace strata
{

std::array<int, 3> BrickAtlasAllocator::ComputeLayout(double budgetMiB,
  int brickSize,
  int bytesPerVoxel,
  int maxTextureSize)
{
  std::array<int, 3> best = { { 0, 0, 0 } };
  if (brickSize < 2 || bytesPerVoxel < 1 || !(budgetMiB > 0))
  {
    return best;
  }
  const double brickBytes = std::pow(static_cast<double>(brickSize), 3) * bytesPerVoxel;
  const int64_t perAxis = maxTextureSize / brickSize;
  const int64_t wanted = static_cast<int64_t>(std::floor(budgetMiB * 1048576.0 / brickBytes));
  const int64_t slots = std::min(wanted, perAxis * perAxis * perAxis);
  if (slots < 1)
  {
    return best;
  }
  // Exhaustive over two axes, the third the most that fits: at most (2048 / B)^2 steps, and
  // it finds the exact best count where a prime count would defeat factoring by hand.
  int64_t bestCount = 0, bestMax = 0, bestMin = 0;
  const int64_t limit = std::min(perAxis, slots);
  for (int64_t x = 1; x <= limit; ++x)
  {
    for (int64_t y = 1; y <= x && x * y <= slots; ++y)
    {
      const int64_t z = std::min(std::min(y, perAxis), slots / (x * y));
      if (z < 1)
      {
        continue;
      }
      const int64_t count = x * y * z;
      // Most slots; then the smallest largest axis; then the largest smallest axis.
      if (count > bestCount ||
          (count == bestCount && (x < bestMax || (x == bestMax && z > bestMin))))
      {
        bestCount = count;
        bestMax = x;
        bestMin = z;
        best = { { static_cast<int>(x), static_cast<int>(y), static_cast<int>(z) } };
      }
    }
  }
  return best;
}

bool BrickAtlasAllocator::Initialize(int slotsX, int slotsY, int slotsZ, int brickSize)
{
  this->Slots.clear();
  this->Map.clear();
  this->Head = this->Tail = -1;
  this->Frame = 0;
  this->Pinned = 0;
  this->Stats = Statistics();
  if (slotsX < 1 || slotsY < 1 || slotsZ < 1 || brickSize < 2)
  {
    this->Layout = { { 0, 0, 0 } };
    this->BrickSize = 0;
    return false;
  }
  this->Layout = { { slotsX, slotsY, slotsZ } };
  this->BrickSize = brickSize;
  this->Slots.resize(static_cast<size_t>(slotsX) * slotsY * slotsZ);
  for (int s = 0; s < this->GetNumberOfSlots(); ++s)
  {
    this->PushBack(s); // slot order: low slots are handed out first
  }
  return true;
}

bool BrickAtlasAllocator::InitializeFromBudget(double budgetMiB,
  int brickSize,
  int bytesPerVoxel,
  int maxTextureSize)
{
  const std::array<int, 3> l = ComputeLayout(budgetMiB, brickSize, bytesPerVoxel, maxTextureSize);
  return this->Initialize(l[0], l[1], l[2], brickSize);
}

std::array<int, 3> BrickAtlasAllocator::GetTextureSize() const
{
  return { { this->Layout[0] * this->BrickSize,
    this->Layout[1] * this->BrickSize,
    this->Layout[2] * this->BrickSize } };
}

std::array<int, 3> BrickAtlasAllocator::GetSlotPosition(int slot) const
{
  return { { slot % this->Layout[0],
    (slot / this->Layout[0]) % this->Layout[1],
    slot / (this->Layout[0] * this->Layout[1]) } };
}

void BrickAtlasAllocator::BeginFrame()
{
  ++this->Frame;
  this->Pinned = 0;
}

BrickAtlasAllocator::Result BrickAtlasAllocator::Request(const Key& key)
{
  Result result;
  auto it = this->Map.find(key);
  if (it != this->Map.end())
  {
    const int s = it->second;
    ++this->Stats.Hits;
    if (this->Slots[s].LastUsed != this->Frame)
    {
      ++this->Pinned;
    }
    this->Slots[s].LastUsed = this->Frame;
    this->Unlink(s);
    this->PushBack(s);
    result.Slot = s;
    result.Hit = true;
    return result;
  }
  ++this->Stats.Misses;
  const int s = this->Head;
  // Requests move slots to the back, so a pinned head means every slot is pinned.
  if (s < 0 || this->Slots[s].LastUsed == this->Frame)
  {
    ++this->Stats.Failures;
    return result;
  }
  Slot& slot = this->Slots[s];
  if (slot.Owner.Volume >= 0)
  {
    ++this->Stats.Evictions;
    result.Evicted = true;
    result.EvictedKey = slot.Owner;
    this->Map.erase(slot.Owner);
  }
  slot.Owner = key;
  slot.LastUsed = this->Frame;
  ++this->Pinned;
  this->Map[key] = s;
  this->Unlink(s);
  this->PushBack(s);
  result.Slot = s;
  return result;
}

int BrickAtlasAllocator::Find(const Key& key) const
{
  auto it = this->Map.find(key);
  return it == this->Map.end() ? -1 : it->second;
}

bool BrickAtlasAllocator::GetSlotKey(int slot, Key& key) const
{
  if (slot < 0 || slot >= this->GetNumberOfSlots() || this->Slots[slot].Owner.Volume < 0)
  {
    return false;
  }
  key = this->Slots[slot].Owner;
  return true;
}

void BrickAtlasAllocator::Release(const Key& key)
{
  auto it = this->Map.find(key);
  if (it != this->Map.end())
  {
    const int s = it->second;
    this->Map.erase(it);
    this->Free(s);
  }
}

void BrickAtlasAllocator::ReleaseVolume(int volume)
{
  for (int s = 0; s < this->GetNumberOfSlots(); ++s)
  {
    if (this->Slots[s].Owner.Volume == volume)
    {
      this->Map.erase(this->Slots[s].Owner);
      this->Free(s);
    }
  }
}

void BrickAtlasAllocator::Clear()
{
  this->Map.clear();
  for (int s = 0; s < this->GetNumberOfSlots(); ++s)
  {
    this->Free(s);
  }
}

void BrickAtlasAllocator::Free(int s)
{
  if (this->Slots[s].LastUsed == this->Frame)
  {
    --this->Pinned;
  }
  this->Slots[s].Owner = Key();
  this->Slots[s].LastUsed = -1;
  this->Unlink(s);
  this->PushFront(s);
}

size_t BrickAtlasAllocator::KeyHash::operator()(const Key& k) const
{
  // Volume and level in the top bits, the brick below: unique for < 2^40 bricks per level.
  const uint64_t v = (static_cast<uint64_t>(static_cast<uint32_t>(k.Volume)) << 46) ^
                     (static_cast<uint64_t>(static_cast<uint32_t>(k.Level)) << 40) ^
                     static_cast<uint64_t>(k.Brick);
  return std::hash<uint64_t>()(v);
}

void BrickAtlasAllocator::Unlink(int s)
{
  Slot& slot = this->Slots[s];
  (slot.Prev >= 0 ? this->Slots[slot.Prev].Next : this->Head) = slot.Next;
  (slot.Next >= 0 ? this->Slots[slot.Next].Prev : this->Tail) = slot.Prev;
  slot.Prev = slot.Next = -1;
}

void BrickAtlasAllocator::PushFront(int s)
{
  this->Slots[s].Prev = -1;
  this->Slots[s].Next = this->Head;
  (this->Head >= 0 ? this->Slots[this->Head].Prev : this->Tail) = s;
  this->Head = s;
}

void BrickAtlasAllocator::PushBack(int s)
{
  this->Slots[s].Next = -1;
  this->Slots[s].Prev = this->Tail;
  (this->Tail >= 0 ? this->Slots[this->Tail].Next : this->Head) = s;
  this->Tail = s;
}
}

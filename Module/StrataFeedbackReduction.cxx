// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataFeedbackReduction.h"

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

namespace strata
{

namespace
{
// The kernels. Both sides hash with the same finaliser (MurmurHash3's fmix32): page ids are
// structured (high bits nearly constant), so a plain mask of the id would cluster badly.
const char* const ReductionKernelSource = R"CLC(
inline uint strata_hash(uint x)
{
  x ^= x >> 16;
  x *= 0x85ebca6bu;
  x ^= x >> 13;
  x *= 0xc2b2ae35u;
  x ^= x >> 16;
  return x;
}

// Open addressing with linear probing; the table has more slots than texels, so an id always
// finds its slot or a free one within `mask + 1` probes.
inline void strata_global_add(__global uint* keys, __global uint* counts, uint mask, uint id,
  uint n)
{
  uint h = strata_hash(id) & mask;
  for (uint p = 0u; p <= mask; ++p)
  {
    const uint k = atomic_cmpxchg(&keys[h], 0u, id);
    if (k == 0u || k == id)
    {
      atomic_add(&counts[h], n);
      return;
    }
    h = (h + 1u) & mask;
  }
}

// One work-group counts `chunk` consecutive texels (coalesced: items stride by the group size)
// into a histogram in local memory, then flushes it, one global atomic per distinct id of the
// chunk instead of one per texel. An id that finds no local slot within a few probes (a chunk
// with more distinct ids than the local table holds) goes straight to the global table.
__kernel void strata_count(__global const uint* ids, uint n, uint chunk,
  __global uint* keys, __global uint* counts, uint mask,
  __local uint* lkeys, __local uint* lcounts, uint lmask)
{
  const uint lid = get_local_id(0);
  const uint lsize = get_local_size(0);
  for (uint i = lid; i <= lmask; i += lsize)
  {
    lkeys[i] = 0u;
    lcounts[i] = 0u;
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  const uint begin = get_group_id(0) * chunk;
  const uint end = min(n, begin + chunk);
  for (uint t = begin + lid; t < end; t += lsize)
  {
    const uint id = ids[t];
    if (id == 0u)
    {
      continue;
    }
    uint h = strata_hash(id) & lmask;
    bool done = false;
    for (uint p = 0u; p < 8u && !done; ++p)
    {
      const uint k = atomic_cmpxchg(&lkeys[h], 0u, id);
      if (k == 0u || k == id)
      {
        atomic_inc(&lcounts[h]);
        done = true;
      }
      h = (h + 1u) & lmask;
    }
    if (!done)
    {
      strata_global_add(keys, counts, mask, id, 1u);
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  for (uint i = lid; i <= lmask; i += lsize)
  {
    const uint id = lkeys[i];
    if (id != 0u)
    {
      strata_global_add(keys, counts, mask, id, lcounts[i]);
    }
  }
}

// Packs the occupied slots into a list; the order is arbitrary (the host sorts it).
__kernel void strata_compact(__global const uint* keys, __global const uint* counts, uint size,
  __global uint* outKeys, __global uint* outCounts, __global uint* outCount)
{
  const uint i = get_global_id(0);
  if (i >= size)
  {
    return;
  }
  const uint id = keys[i];
  if (id != 0u)
  {
    const uint j = atomic_inc(outCount);
    outKeys[j] = id;
    outCounts[j] = counts[i];
  }
}
)CLC";

inline uint32_t Hash(uint32_t x)
{
  x ^= x >> 16;
  x *= 0x85ebca6bu;
  x ^= x >> 13;
  x *= 0xc2b2ae35u;
  x ^= x >> 16;
  return x;
}

size_t NextPowerOfTwo(size_t v)
{
  size_t p = 1;
  while (p < v)
  {
    p <<= 1;
  }
  return p;
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Texels per work-item in one work-group's chunk: enough to amortise the local table's
// clearing and flushing, few enough to keep every compute unit busy at 1/4 of full HD.
constexpr size_t TexelsPerItem = 16;
// Local histogram slots (two uint each); shrunk to the device's local memory if needed.
constexpr size_t LocalEntries = 1024;
// Upper bound on texels: coverage and kernel indices are 32-bit, and the global table
// (a power of two >= 2 n) must stay addressable by a uint.
constexpr size_t MaxTexels = size_t(1) << 30;
}

class FeedbackReduction::vtkInternals
{
public:
  ~vtkInternals() { this->ReleaseOpenCL(); }

  // CPU: open-addressing table, reused between calls.
  struct Slot
  {
    uint32_t Key;
    uint32_t Count;
  };
  std::vector<Slot> Table;
  size_t LastDistinct = 0;

  // OpenCL
  bool Tried = false;
  bool Ready = false;
  std::string Message;
  std::string DeviceName;
  cl_context Context = nullptr;
  cl_device_id Device = nullptr;
  cl_command_queue Queue = nullptr;
  cl_program Program = nullptr;
  cl_kernel Count = nullptr;
  cl_kernel Compact = nullptr;
  size_t GroupSize = 1;
  size_t LocalSlots = LocalEntries;
  cl_mem Ids = nullptr;
  size_t IdsCapacity = 0;
  cl_mem Keys = nullptr;
  cl_mem Counts = nullptr;
  size_t TableCapacity = 0;
  size_t CountsCapacity = 0;
  cl_mem OutKeys = nullptr;
  cl_mem OutCounts = nullptr;
  cl_mem OutCount = nullptr;
  size_t OutCapacity = 0;
  size_t OutCountsCapacity = 0;
  std::vector<uint32_t> HostKeys;
  std::vector<uint32_t> HostCounts;

  bool Fail(const char* what, cl_int err)
  {
    std::ostringstream os;
    os << what << " failed (OpenCL error " << err << ")";
    this->Message = os.str();
    return false;
  }

  static void ReleaseMem(cl_mem& m)
  {
    if (m)
    {
      clReleaseMemObject(m);
      m = nullptr;
    }
  }

  void ReleaseOpenCL()
  {
    ReleaseMem(this->Ids);
    ReleaseMem(this->Keys);
    ReleaseMem(this->Counts);
    ReleaseMem(this->OutKeys);
    ReleaseMem(this->OutCounts);
    ReleaseMem(this->OutCount);
    this->IdsCapacity = this->TableCapacity = this->CountsCapacity = 0;
    this->OutCapacity = this->OutCountsCapacity = 0;
    if (this->Count)
    {
      clReleaseKernel(this->Count);
      this->Count = nullptr;
    }
    if (this->Compact)
    {
      clReleaseKernel(this->Compact);
      this->Compact = nullptr;
    }
    if (this->Program)
    {
      clReleaseProgram(this->Program);
      this->Program = nullptr;
    }
    if (this->Queue)
    {
      clReleaseCommandQueue(this->Queue);
      this->Queue = nullptr;
    }
    if (this->Context)
    {
      clReleaseContext(this->Context);
      this->Context = nullptr;
    }
    this->Ready = false;
  }

  static std::string DeviceString(cl_device_id device, cl_device_info what)
  {
    size_t size = 0;
    if (clGetDeviceInfo(device, what, 0, nullptr, &size) != CL_SUCCESS || size == 0)
    {
      return std::string();
    }
    std::string s(size, '\0');
    clGetDeviceInfo(device, what, size, &s[0], nullptr);
    s.resize(std::strlen(s.c_str()));
    return s;
  }

  // The first GPU of any platform, else the first device of any type.
  bool PickDevice(cl_platform_id& platformOut)
  {
    cl_uint numPlatforms = 0;
    cl_int err = clGetPlatformIDs(0, nullptr, &numPlatforms);
    if (err != CL_SUCCESS || numPlatforms == 0)
    {
      std::ostringstream os;
      os << "no OpenCL platform found (clGetPlatformIDs: error " << err << ", " << numPlatforms
         << " platforms); is an ICD such as pocl-opencl-icd installed?";
      this->Message = os.str();
      return false;
    }
    std::vector<cl_platform_id> platforms(numPlatforms);
    clGetPlatformIDs(numPlatforms, platforms.data(), nullptr);
    for (cl_device_type type :
      { cl_device_type(CL_DEVICE_TYPE_GPU), cl_device_type(CL_DEVICE_TYPE_ALL) })
    {
      for (cl_platform_id p : platforms)
      {
        cl_device_id d = nullptr;
        cl_uint n = 0;
        if (clGetDeviceIDs(p, type, 1, &d, &n) == CL_SUCCESS && n > 0)
        {
          platformOut = p;
          this->Device = d;
          return true;
        }
      }
    }
    this->Message = "OpenCL platforms found but none has a device";
    return false;
  }

  bool Setup()
  {
    this->Tried = true;
    cl_platform_id platform = nullptr;
    if (!this->PickDevice(platform))
    {
      return false;
    }
    size_t size = 0;
    std::string platformName;
    if (clGetPlatformInfo(platform, CL_PLATFORM_NAME, 0, nullptr, &size) == CL_SUCCESS && size)
    {
      platformName.assign(size, '\0');
      clGetPlatformInfo(platform, CL_PLATFORM_NAME, size, &platformName[0], nullptr);
      platformName.resize(std::strlen(platformName.c_str()));
    }
    this->DeviceName = platformName + " / " + DeviceString(this->Device, CL_DEVICE_NAME);

    cl_int err = CL_SUCCESS;
    const cl_context_properties props[] = {
      CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(platform), 0
    };
    this->Context = clCreateContext(props, 1, &this->Device, nullptr, nullptr, &err);
    if (err != CL_SUCCESS)
    {
      return this->Fail("clCreateContext", err);
    }
    this->Queue = clCreateCommandQueue(this->Context, this->Device, 0, &err);
    if (err != CL_SUCCESS)
    {
      return this->Fail("clCreateCommandQueue", err);
    }
    const char* src = ReductionKernelSource;
    this->Program = clCreateProgramWithSource(this->Context, 1, &src, nullptr, &err);
    if (err != CL_SUCCESS)
    {
      return this->Fail("clCreateProgramWithSource", err);
    }
    err = clBuildProgram(this->Program, 1, &this->Device, "", nullptr, nullptr);
    if (err != CL_SUCCESS)
    {
      std::string log;
      size_t logSize = 0;
      if (clGetProgramBuildInfo(
            this->Program, this->Device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &logSize) ==
            CL_SUCCESS &&
          logSize)
      {
        log.assign(logSize, '\0');
        clGetProgramBuildInfo(
          this->Program, this->Device, CL_PROGRAM_BUILD_LOG, logSize, &log[0], nullptr);
      }
      this->Fail("clBuildProgram", err);
      this->Message += ": " + log;
      return false;
    }
    this->Count = clCreateKernel(this->Program, "strata_count", &err);
    if (err != CL_SUCCESS)
    {
      return this->Fail("clCreateKernel(strata_count)", err);
    }
    this->Compact = clCreateKernel(this->Program, "strata_compact", &err);
    if (err != CL_SUCCESS)
    {
      return this->Fail("clCreateKernel(strata_compact)", err);
    }

    // Work-group size: 128 where allowed (a multiple of every common SIMD width).
    size_t deviceMax = 1, kernelMax = 1;
    clGetDeviceInfo(
      this->Device, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof(deviceMax), &deviceMax, nullptr);
    clGetKernelWorkGroupInfo(
      this->Count, this->Device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(kernelMax), &kernelMax, nullptr);
    this->GroupSize = std::max<size_t>(1, std::min<size_t>({ 128, deviceMax, kernelMax }));
    size_t compactMax = 1;
    clGetKernelWorkGroupInfo(this->Compact,
      this->Device,
      CL_KERNEL_WORK_GROUP_SIZE,
      sizeof(compactMax),
      &compactMax,
      nullptr);
    this->GroupSize = std::max<size_t>(1, std::min(this->GroupSize, compactMax));

    cl_ulong localMem = 0;
    clGetDeviceInfo(this->Device, CL_DEVICE_LOCAL_MEM_SIZE, sizeof(localMem), &localMem, nullptr);
    this->LocalSlots = LocalEntries;
    while (this->LocalSlots > 64 && this->LocalSlots * 2 * sizeof(cl_uint) > localMem / 2)
    {
      this->LocalSlots /= 2;
    }
    this->Ready = true;
    this->Message.clear();
    return true;
  }

  // Grows `buffer` to hold `needed` uints (never shrinks).
  bool Reserve(cl_mem& buffer, size_t& capacity, size_t needed, cl_mem_flags flags)
  {
    if (buffer && capacity >= needed)
    {
      return true;
    }
    ReleaseMem(buffer);
    capacity = 0;
    cl_int err = CL_SUCCESS;
    buffer = clCreateBuffer(
      this->Context, flags, std::max<size_t>(needed, 1) * sizeof(cl_uint), nullptr, &err);
    if (err != CL_SUCCESS)
    {
      buffer = nullptr;
      return this->Fail("clCreateBuffer", err);
    }
    capacity = needed;
    return true;
  }
};

//------------------------------------------------------------------------------
uint32_t FeedbackReduction::PackPage(int dataSet, int level, uint32_t pageIndex)
{
  if (dataSet < 0 || dataSet >= MaxDataSets || level < 0 || level >= MaxLevels ||
      pageIndex >= MaxPagesPerLevel)
  {
    return NoPage;
  }
  return (static_cast<uint32_t>(dataSet + 1) << (LevelBits + PageBits)) |
         (static_cast<uint32_t>(level) << PageBits) | pageIndex;
}

//------------------------------------------------------------------------------
std::string FeedbackReduction::GetGLSLPackFunction()
{
  std::ostringstream os;
  os << "// Strata page id: (data set + 1) << " << (LevelBits + PageBits) << " | level << "
     << PageBits << " | page index; 0 = no page.\n"
     << "uint strataPackPage(uint dataSet, uint level, uint pageIndex)\n"
     << "{\n"
     << "  return ((dataSet + 1u) << " << (LevelBits + PageBits) << "u) | (level << " << PageBits
     << "u) | pageIndex;\n"
     << "}\n";
  return os.str();
}

//------------------------------------------------------------------------------
FeedbackReduction::FeedbackReduction()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
FeedbackReduction::~FeedbackReduction() = default;

//------------------------------------------------------------------------------
bool FeedbackReduction::ReduceCPU(const uint32_t* ids, size_t count, std::vector<Entry>& list)
{
  const auto start = std::chrono::steady_clock::now();
  list.clear();
  if (count >= MaxTexels || (count > 0 && !ids))
  {
    this->LastCPUSeconds = Seconds(start);
    return false;
  }
  auto& in = *this->Internals;
  // Sized from the last frame's distinct count (frames are coherent), grown at half load.
  size_t capacity = NextPowerOfTwo(std::max<size_t>(1024, 2 * in.LastDistinct));
  in.Table.assign(capacity, vtkInternals::Slot{ 0, 0 });
  size_t mask = capacity - 1;
  size_t distinct = 0;

  auto insert = [&](uint32_t id, uint32_t n)
  {
    size_t h = Hash(id) & mask;
    while (in.Table[h].Key != 0 && in.Table[h].Key != id)
    {
      h = (h + 1) & mask;
    }
    if (in.Table[h].Key == 0)
    {
      in.Table[h].Key = id;
      ++distinct;
    }
    in.Table[h].Count += n;
  };
  auto grow = [&]()
  {
    std::vector<vtkInternals::Slot> old;
    old.swap(in.Table);
    capacity *= 2;
    mask = capacity - 1;
    in.Table.assign(capacity, vtkInternals::Slot{ 0, 0 });
    distinct = 0;
    for (const auto& s : old)
    {
      if (s.Key)
      {
        insert(s.Key, s.Count);
      }
    }
  };

  size_t i = 0;
  while (i < count)
  {
    const uint32_t id = ids[i];
    size_t j = i + 1;
    while (j < count && ids[j] == id)
    {
      ++j;
    }
    if (id != NoPage)
    {
      insert(id, static_cast<uint32_t>(j - i));
      if (2 * distinct > capacity)
      {
        grow();
      }
    }
    i = j;
  }

  list.reserve(distinct);
  for (const auto& s : in.Table)
  {
    if (s.Key)
    {
      list.push_back(Entry{ s.Key, s.Count });
    }
  }
  std::sort(
    list.begin(), list.end(), [](const Entry& a, const Entry& b) { return a.Page < b.Page; });
  in.LastDistinct = distinct;
  this->LastCPUSeconds = Seconds(start);
  return true;
}

//------------------------------------------------------------------------------
bool FeedbackReduction::IsOpenCLAvailable()
{
  auto& in = *this->Internals;
  if (!in.Tried)
  {
    const auto start = std::chrono::steady_clock::now();
    if (!in.Setup())
    {
      in.ReleaseOpenCL();
    }
    this->OpenCLSetupSeconds = Seconds(start);
  }
  return in.Ready;
}

//------------------------------------------------------------------------------
const std::string& FeedbackReduction::GetOpenCLMessage() const
{
  return this->Internals->Message;
}

//------------------------------------------------------------------------------
const std::string& FeedbackReduction::GetOpenCLDeviceName() const
{
  return this->Internals->DeviceName;
}

//------------------------------------------------------------------------------
bool FeedbackReduction::ReduceOpenCL(const uint32_t* ids, size_t count, std::vector<Entry>& list)
{
  list.clear();
  if (!this->IsOpenCLAvailable())
  {
    return false;
  }
  const auto start = std::chrono::steady_clock::now();
  auto& in = *this->Internals;
  in.Message.clear();
  auto done = [&](bool ok)
  {
    if (!ok)
    {
      clFinish(in.Queue);
      list.clear();
    }
    this->LastOpenCLSeconds = Seconds(start);
    return ok;
  };
  if (count >= MaxTexels || (count > 0 && !ids))
  {
    in.Message = "feedback buffer too large or null";
    return done(false);
  }
  if (count == 0)
  {
    return done(true);
  }

  const size_t tableSize = NextPowerOfTwo(std::max<size_t>(1024, 2 * count));
  if (!in.Reserve(in.Ids, in.IdsCapacity, count, CL_MEM_READ_ONLY) ||
      !in.Reserve(in.Keys, in.TableCapacity, tableSize, CL_MEM_READ_WRITE))
  {
    return done(false);
  }
  if (!in.Reserve(in.Counts, in.CountsCapacity, tableSize, CL_MEM_READ_WRITE) ||
      !in.Reserve(in.OutKeys, in.OutCapacity, count, CL_MEM_WRITE_ONLY) ||
      !in.Reserve(in.OutCounts, in.OutCountsCapacity, count, CL_MEM_WRITE_ONLY))
  {
    return done(false);
  }
  cl_int err = CL_SUCCESS;
  if (!in.OutCount)
  {
    in.OutCount = clCreateBuffer(in.Context, CL_MEM_READ_WRITE, sizeof(cl_uint), nullptr, &err);
    if (err != CL_SUCCESS)
    {
      in.OutCount = nullptr;
      in.Fail("clCreateBuffer", err);
      return done(false);
    }
  }

  const cl_uint zero = 0;
  err = clEnqueueWriteBuffer(
    in.Queue, in.Ids, CL_TRUE, 0, count * sizeof(cl_uint), ids, 0, nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    in.Fail("clEnqueueWriteBuffer", err);
    return done(false);
  }
  err = clEnqueueFillBuffer(
    in.Queue, in.Keys, &zero, sizeof(zero), 0, tableSize * sizeof(cl_uint), 0, nullptr, nullptr);
  err |= clEnqueueFillBuffer(
    in.Queue, in.Counts, &zero, sizeof(zero), 0, tableSize * sizeof(cl_uint), 0, nullptr, nullptr);
  err |= clEnqueueFillBuffer(
    in.Queue, in.OutCount, &zero, sizeof(zero), 0, sizeof(cl_uint), 0, nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    in.Fail("clEnqueueFillBuffer", err);
    return done(false);
  }

  const size_t group = in.GroupSize;
  const size_t chunk = group * TexelsPerItem;
  const size_t groups = (count + chunk - 1) / chunk;
  const cl_uint n = static_cast<cl_uint>(count);
  const cl_uint chunkArg = static_cast<cl_uint>(chunk);
  const cl_uint mask = static_cast<cl_uint>(tableSize - 1);
  const cl_uint lmask = static_cast<cl_uint>(in.LocalSlots - 1);
  err = clSetKernelArg(in.Count, 0, sizeof(cl_mem), &in.Ids);
  err |= clSetKernelArg(in.Count, 1, sizeof(cl_uint), &n);
  err |= clSetKernelArg(in.Count, 2, sizeof(cl_uint), &chunkArg);
  err |= clSetKernelArg(in.Count, 3, sizeof(cl_mem), &in.Keys);
  err |= clSetKernelArg(in.Count, 4, sizeof(cl_mem), &in.Counts);
  err |= clSetKernelArg(in.Count, 5, sizeof(cl_uint), &mask);
  err |= clSetKernelArg(in.Count, 6, in.LocalSlots * sizeof(cl_uint), nullptr);
  err |= clSetKernelArg(in.Count, 7, in.LocalSlots * sizeof(cl_uint), nullptr);
  err |= clSetKernelArg(in.Count, 8, sizeof(cl_uint), &lmask);
  if (err != CL_SUCCESS)
  {
    in.Fail("clSetKernelArg(strata_count)", err);
    return done(false);
  }
  size_t global = groups * group;
  err =
    clEnqueueNDRangeKernel(in.Queue, in.Count, 1, nullptr, &global, &group, 0, nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    in.Fail("clEnqueueNDRangeKernel(strata_count)", err);
    return done(false);
  }

  const cl_uint size = static_cast<cl_uint>(tableSize);
  err = clSetKernelArg(in.Compact, 0, sizeof(cl_mem), &in.Keys);
  err |= clSetKernelArg(in.Compact, 1, sizeof(cl_mem), &in.Counts);
  err |= clSetKernelArg(in.Compact, 2, sizeof(cl_uint), &size);
  err |= clSetKernelArg(in.Compact, 3, sizeof(cl_mem), &in.OutKeys);
  err |= clSetKernelArg(in.Compact, 4, sizeof(cl_mem), &in.OutCounts);
  err |= clSetKernelArg(in.Compact, 5, sizeof(cl_mem), &in.OutCount);
  if (err != CL_SUCCESS)
  {
    in.Fail("clSetKernelArg(strata_compact)", err);
    return done(false);
  }
  global = (tableSize + group - 1) / group * group;
  err =
    clEnqueueNDRangeKernel(in.Queue, in.Compact, 1, nullptr, &global, &group, 0, nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    in.Fail("clEnqueueNDRangeKernel(strata_compact)", err);
    return done(false);
  }

  cl_uint distinct = 0;
  err = clEnqueueReadBuffer(
    in.Queue, in.OutCount, CL_TRUE, 0, sizeof(cl_uint), &distinct, 0, nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    in.Fail("clEnqueueReadBuffer", err);
    return done(false);
  }
  if (distinct > count)
  {
    in.Message = "reduction kernel returned more pages than texels";
    return done(false);
  }
  if (distinct > 0)
  {
    in.HostKeys.resize(distinct);
    in.HostCounts.resize(distinct);
    err = clEnqueueReadBuffer(in.Queue,
      in.OutKeys,
      CL_FALSE,
      0,
      distinct * sizeof(cl_uint),
      in.HostKeys.data(),
      0,
      nullptr,
      nullptr);
    err |= clEnqueueReadBuffer(in.Queue,
      in.OutCounts,
      CL_TRUE,
      0,
      distinct * sizeof(cl_uint),
      in.HostCounts.data(),
      0,
      nullptr,
      nullptr);
    if (err != CL_SUCCESS)
    {
      in.Fail("clEnqueueReadBuffer", err);
      return done(false);
    }
  }
  list.resize(distinct);
  for (cl_uint i = 0; i < distinct; ++i)
  {
    list[i] = Entry{ in.HostKeys[i], in.HostCounts[i] };
  }
  std::sort(
    list.begin(), list.end(), [](const Entry& a, const Entry& b) { return a.Page < b.Page; });
  return done(true);
}

//------------------------------------------------------------------------------
bool FeedbackReduction::Reduce(const uint32_t* ids, size_t count, std::vector<Entry>& list)
{
  if (this->UseOpenCL && this->ReduceOpenCL(ids, count, list))
  {
    return true;
  }
  return this->ReduceCPU(ids, count, list);
}

//------------------------------------------------------------------------------
void FeedbackReduction::PropagateToAncestors(std::vector<Entry>& list,
  const std::function<uint32_t(uint32_t)>& parent)
{
  std::map<uint32_t, uint64_t> sums;
  for (const Entry& e : list)
  {
    sums[e.Page] += e.Coverage;
    // A page is at most MaxLevels - 1 levels below its root; the bound also stops a parent
    // function that cycles.
    uint32_t p = parent ? parent(e.Page) : NoPage;
    for (int depth = 0; p != NoPage && depth < MaxLevels; ++depth)
    {
      sums[p] += e.Coverage;
      p = parent(p);
    }
  }
  list.clear();
  list.reserve(sums.size());
  const uint64_t maxCoverage = std::numeric_limits<uint32_t>::max();
  for (const auto& s : sums)
  {
    list.push_back(Entry{ s.first, static_cast<uint32_t>(std::min(s.second, maxCoverage)) });
  }
}
}

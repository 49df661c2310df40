// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkSegyVolumeReader.h"
#include "vtkStrataGridReaderUtilities.h"

#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <segyio/segy.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSegyVolumeReader);

namespace
{
using strata_io::ClearOutput;

/// Per axis, the page pool format's limit; more lines than this means misread headers.
constexpr int64_t MaxLines = int64_t(1) << 20;
/// A survey outline fills well over 1/16 of its inline/crossline bounding box; wrong byte
/// positions (a coordinate read as a line number) give grids millions of times sparser.
constexpr int64_t MaxPositionsPerTrace = 16;

struct SegyCloser
{
  void operator()(segy_file* f) const { segy_close(f); }
};
using SegyFile = std::unique_ptr<segy_file, SegyCloser>;

bool SupportedFormat(int format)
{
  return format == SEGY_IBM_FLOAT_4_BYTE || format == SEGY_SIGNED_INTEGER_4_BYTE ||
         format == SEGY_SIGNED_SHORT_2_BYTE || format == SEGY_IEEE_FLOAT_4_BYTE ||
         format == SEGY_SIGNED_CHAR_1_BYTE;
}

/// The integer at 1-based `byte` of a trace header: with the field's own width where SEG-Y
/// rev 1 defines a field there (segyio's table), else 4 bytes big-endian.
int32_t HeaderInt(const char* header, int byte)
{
  int32_t v = 0;
  if (segy_get_field(header, byte, &v) == SEGY_OK)
  {
    return v;
  }
  const auto* b = reinterpret_cast<const unsigned char*>(header) + byte - 1;
  return static_cast<int32_t>(
    (uint32_t(b[0]) << 24) | (uint32_t(b[1]) << 16) | (uint32_t(b[2]) << 8) | uint32_t(b[3]));
}

/// Size and modification time: what says the file is still the one that was scanned.
std::string FileState(const std::string& path, long long* size = nullptr)
{
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
  {
    return std::string();
  }
  if (size)
  {
    *size = static_cast<long long>(st.st_size);
  }
  std::ostringstream s;
  s << st.st_size << ':' << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec;
  return s.str();
}

/// What a scan depends on: the file, its state (FileState) and the reader's settings.
std::string ScanKey(const std::string& path,
  int inlineByte,
  int crosslineByte,
  int format,
  const std::string& state)
{
  std::ostringstream key;
  key << path << '\n' << inlineByte << ' ' << crosslineByte << ' ' << format << '\n' << state;
  return key.str();
}

/// The grid of a set of line numbers: first, step (gcd of the differences) and count.
struct LineAxis
{
  int First = 0;
  int Step = 1;
  int64_t Count = 0;

  explicit LineAxis(std::vector<int32_t> numbers)
  {
    std::sort(numbers.begin(), numbers.end());
    numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
    int64_t step = 0;
    for (size_t i = 1; i < numbers.size(); ++i)
    {
      step = std::gcd(step, int64_t(numbers[i]) - numbers[i - 1]);
    }
    this->First = numbers.front();
    this->Step = step > 0 && step <= INT_MAX ? static_cast<int>(step) : 1;
    this->Count = (int64_t(numbers.back()) - numbers.front()) / this->Step + 1;
  }

  int64_t IndexOf(int32_t number) const { return (int64_t(number) - this->First) / this->Step; }
};

/// Converts `n` samples segyio has made native (segy_to_native) to float, `stride` apart.
void ToFloat(int format, const unsigned char* in, int n, float* out, vtkIdType stride)
{
  for (int s = 0; s < n; ++s, out += stride)
  {
    switch (format)
    {
      case SEGY_IBM_FLOAT_4_BYTE:
      case SEGY_IEEE_FLOAT_4_BYTE:
        std::memcpy(out, in + 4 * s, 4);
        break;
      case SEGY_SIGNED_INTEGER_4_BYTE:
      {
        int32_t v;
        std::memcpy(&v, in + 4 * s, 4);
        *out = static_cast<float>(v);
        break;
      }
      case SEGY_SIGNED_SHORT_2_BYTE:
      {
        int16_t v;
        std::memcpy(&v, in + 2 * s, 2);
        *out = static_cast<float>(v);
        break;
      }
      default: // SEGY_SIGNED_CHAR_1_BYTE
        *out = static_cast<float>(static_cast<int8_t>(in[s]));
        break;
    }
  }
}
}

/// The header scan: file layout, the (inline, crossline) -> trace index and the geometry.
class vtkSegyVolumeReader::vtkInternals
{
public:
  /// File state and settings the scan belongs to (empty: no valid scan).
  std::string Key;
  std::string State;
  int Format = 0;
  int Samples = 0;
  long Trace0 = 0;
  int TraceBytes = 0;
  vtkIdType Traces = 0;
  int Crosslines = 0;
  int Inlines = 0;
  /// Trace number at inline index * Crosslines + crossline index; -1 where none.
  std::vector<int32_t> Index;
  int FirstInline = 0, InlineStep = 1, FirstCrossline = 0, CrosslineStep = 1;
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  /// Index (x, y, z) = (crossline, sample, inline) -> world (inline, crossline, time).
  static constexpr double Direction[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
  std::string Warning;

  std::string Scan(const std::string& path, int inlineByte, int crosslineByte, int format);
  void SetGeometry(vtkImageData* image) const
  {
    image->SetSpacing(this->Spacing);
    image->SetOrigin(this->Origin);
    image->SetDirectionMatrix(Direction);
  }
};

//------------------------------------------------------------------------------
std::string vtkSegyVolumeReader::vtkInternals::Scan(const std::string& path,
  int inlineByte,
  int crosslineByte,
  int formatOverride)
{
  this->Key.clear();
  this->Index.clear();
  this->Warning.clear();
  for (int byte : { inlineByte, crosslineByte })
  {
    if (byte < 1 || byte > SEGY_TRACE_HEADER_SIZE - 3)
    {
      return "trace-header byte position " + std::to_string(byte) + " is outside [1, 237]";
    }
  }
  if (inlineByte == crosslineByte)
  {
    return "InlineByte and CrosslineByte are both " + std::to_string(inlineByte);
  }
  long long size = 0;
  this->State = FileState(path, &size);
  SegyFile fp(this->State.empty() ? nullptr : segy_open(path.c_str(), "rb"));
  if (!fp)
  {
    return std::string("cannot open it: ") + std::strerror(errno);
  }
  constexpr long long headers = SEGY_TEXT_HEADER_SIZE + SEGY_BINARY_HEADER_SIZE;
  std::vector<char> bin(static_cast<size_t>(segy_binheader_size()));
  if (size < headers || segy_binheader(fp.get(), bin.data()) != SEGY_OK)
  {
    return "the file has " + std::to_string(size) + " bytes, fewer than the " +
           std::to_string(headers) + " of its textual and binary headers";
  }
  this->Format = formatOverride ? formatOverride : segy_format(bin.data());
  if (!SupportedFormat(this->Format))
  {
    return "sample format code " + std::to_string(this->Format) +
           " is not supported (1 IBM float, 2 int32, 3 int16, 5 IEEE float, 8 int8; SampleFormat "
           "overrides a wrong code)";
  }
  this->Trace0 = segy_trace0(bin.data());
  if (this->Trace0 < headers)
  {
    return "a variable number of extended textual headers is not supported";
  }
  std::vector<char> header(SEGY_TRACE_HEADER_SIZE);
  this->Samples = segy_samples(bin.data());
  if (this->Samples <= 0 && size >= this->Trace0 + SEGY_TRACE_HEADER_SIZE &&
      segy_traceheader(fp.get(), 0, header.data(), this->Trace0, 0) == SEGY_OK)
  {
    // Some writers leave the binary header's count at 0: the first trace says it too.
    this->Samples = HeaderInt(header.data(), SEGY_TR_SAMPLE_COUNT);
  }
  if (this->Samples <= 0)
  {
    return "neither the binary header nor the first trace header gives a sample count";
  }
  segy_set_format(fp.get(), this->Format);
  this->TraceBytes = segy_trsize(this->Format, this->Samples);
  const long long stride = SEGY_TRACE_HEADER_SIZE + static_cast<long long>(this->TraceBytes);
  const long long body = size - this->Trace0;
  if (body <= 0 || body % stride != 0)
  {
    std::ostringstream msg;
    msg << "its " << std::max(body, 0LL) << " bytes after the headers are not a whole, non-zero "
        << "number of traces of " << stride << " bytes (240-byte header + " << this->Samples
        << " samples of format " << this->Format << "): truncated, or traces of other lengths";
    return msg.str();
  }
  if (body / stride > INT_MAX)
  {
    return "more than 2^31 - 1 traces";
  }
  this->Traces = static_cast<vtkIdType>(body / stride);

  // One pass over the trace headers for the line numbers. Their sample counts are not checked:
  // writers leave them stale (f3.sgy says 462 in every trace of 75 samples), and segyio too
  // trusts the binary header; traces of other lengths show in the file size above.
  std::vector<int32_t> inlines(this->Traces), crosslines(this->Traces);
  double delay = 0.0;
  for (int t = 0; t < this->Traces; ++t)
  {
    if (segy_traceheader(fp.get(), t, header.data(), this->Trace0, this->TraceBytes) != SEGY_OK)
    {
      return "cannot read the header of trace " + std::to_string(t);
    }
    inlines[t] = HeaderInt(header.data(), inlineByte);
    crosslines[t] = HeaderInt(header.data(), crosslineByte);
    if (t == 0)
    {
      delay = HeaderInt(header.data(), SEGY_TR_DELAY_REC_TIME);
    }
  }

  const LineAxis il(inlines);
  const LineAxis xl(crosslines);
  if (il.Count > MaxLines || xl.Count > MaxLines ||
      il.Count * xl.Count > MaxPositionsPerTrace * this->Traces)
  {
    std::ostringstream msg;
    msg << "inline numbers " << il.First << " + " << il.Step << " k (" << il.Count
        << " lines) and crossline numbers " << xl.First << " + " << xl.Step << " k (" << xl.Count
        << " lines) make a grid far too large for " << this->Traces << " traces: are InlineByte ("
        << inlineByte << ") and CrosslineByte (" << crosslineByte << ") right?";
    return msg.str();
  }
  this->Inlines = static_cast<int>(il.Count);
  this->Crosslines = static_cast<int>(xl.Count);
  this->Index.assign(static_cast<size_t>(il.Count * xl.Count), -1);
  for (int t = 0; t < this->Traces; ++t)
  {
    int32_t& slot = this->Index[il.IndexOf(inlines[t]) * xl.Count + xl.IndexOf(crosslines[t])];
    if (slot >= 0)
    {
      std::ostringstream msg;
      msg << "traces " << slot << " and " << t << " are both at inline " << inlines[t]
          << ", crossline " << crosslines[t] << " (pre-stack gathers are not supported; are "
          << "InlineByte (" << inlineByte << ") and CrosslineByte (" << crosslineByte
          << ") right?)";
      this->Index.clear();
      return msg.str();
    }
    slot = t;
  }

  float dt = 0.0f;
  if (segy_sample_interval(fp.get(), 0.0f, &dt) != SEGY_OK || !(dt > 0.0f))
  {
    this->Warning = "no sample interval in the binary or first trace header; 1 ms assumed";
    dt = 1000.0f;
  }
  this->FirstInline = il.First;
  this->InlineStep = il.Step;
  this->FirstCrossline = xl.First;
  this->CrosslineStep = xl.Step;
  this->Spacing[0] = xl.Step;
  this->Spacing[1] = dt / 1000.0;
  this->Spacing[2] = il.Step;
  this->Origin[0] = il.First;
  this->Origin[1] = xl.First;
  this->Origin[2] = delay;
  this->Key = ScanKey(path, inlineByte, crosslineByte, formatOverride, this->State);
  return std::string();
}

//------------------------------------------------------------------------------
vtkSegyVolumeReader::vtkSegyVolumeReader()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("amplitude");
}

//------------------------------------------------------------------------------
vtkSegyVolumeReader::~vtkSegyVolumeReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkSegyVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "InlineByte: " << this->InlineByte << "\n";
  os << indent << "CrosslineByte: " << this->CrosslineByte << "\n";
  os << indent << "SampleFormat: " << this->SampleFormat << "\n";
  os << indent << "NumberOfTraces: " << this->NumberOfTraces << "\n";
  os << indent << "NumberOfMissingTraces: " << this->NumberOfMissingTraces << "\n";
  os << indent << "FormatCode: " << this->FormatCode << "\n";
  os << indent << "FirstInline: " << this->FirstInline << "\n";
  os << indent << "InlineStep: " << this->InlineStep << "\n";
  os << indent << "FirstCrossline: " << this->FirstCrossline << "\n";
  os << indent << "CrosslineStep: " << this->CrosslineStep << "\n";
  os << indent << "NumberOfTracesRead: " << this->NumberOfTracesRead << "\n";
}

//------------------------------------------------------------------------------
int vtkSegyVolumeReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  this->NumberOfTraces = 0;
  this->NumberOfMissingTraces = 0;
  this->FormatCode = 0;
  this->FirstInline = this->InlineStep = this->FirstCrossline = this->CrosslineStep = 0;
  const std::string name = this->FileName ? this->FileName : "";
  vtkInternals& in = *this->Internals;
  // Scanning every trace header is the expensive part: done again only for another file, other
  // settings, or a file that changed.
  if (in.Key.empty() ||
      in.Key !=
        ScanKey(name, this->InlineByte, this->CrosslineByte, this->SampleFormat, FileState(name)))
  {
    const std::string error =
      name.empty() ? std::string("no file name set")
                   : in.Scan(name, this->InlineByte, this->CrosslineByte, this->SampleFormat);
    if (!error.empty())
    {
      in.Key.clear();
      ClearOutput(outInfo);
      vtkErrorMacro("Cannot read SEG-Y file \"" << name << "\": " << error);
      return 0;
    }
    if (!in.Warning.empty())
    {
      vtkWarningMacro("SEG-Y file \"" << name << "\": " << in.Warning);
    }
  }
  this->NumberOfTraces = in.Traces;
  this->NumberOfMissingTraces = static_cast<vtkIdType>(in.Index.size()) - in.Traces;
  this->FormatCode = in.Format;
  this->FirstInline = in.FirstInline;
  this->InlineStep = in.InlineStep;
  this->FirstCrossline = in.FirstCrossline;
  this->CrosslineStep = in.CrosslineStep;

  const int extent[6] = { 0, in.Crosslines - 1, 0, in.Samples - 1, 0, in.Inlines - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), in.Spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), in.Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), vtkInternals::Direction, 9);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSegyVolumeReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  this->NumberOfTracesRead = 0;
  if (!output)
  {
    vtkErrorMacro("No vtkImageData output to fill.");
    return 0;
  }
  output->Initialize();
  const std::string name = this->FileName ? this->FileName : "";
  auto fail = [&](const std::string& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot read SEG-Y file \"" << name << "\": " << error);
    return 0;
  };
  const vtkInternals& in = *this->Internals;
  if (in.Key.empty())
  {
    return fail("its headers could not be read");
  }
  // The index describes the file as scanned; a file replaced since then is not read with it.
  if (FileState(name) != in.State)
  {
    return fail("the file changed after its headers were read; update the information again");
  }

  const int whole[6] = { 0, in.Crosslines - 1, 0, in.Samples - 1, 0, in.Inlines - 1 };
  int extent[6];
  std::copy(whole, whole + 6, extent);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  }
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = std::max(extent[2 * a], whole[2 * a]);
    extent[2 * a + 1] = std::min(extent[2 * a + 1], whole[2 * a + 1]);
    if (extent[2 * a] > extent[2 * a + 1])
    {
      return 1; // an empty request: an empty output, and no error
    }
  }

  SegyFile fp(segy_open(name.c_str(), "rb"));
  if (!fp)
  {
    return fail(std::string("cannot open it: ") + std::strerror(errno));
  }
  segy_set_format(fp.get(), in.Format);

  output->SetExtent(extent);
  in.SetGeometry(output);
  output->AllocateScalars(VTK_FLOAT, 1);
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  scalars->SetName(this->ArrayName);
  float* values = static_cast<float*>(scalars->GetVoidPointer(0));
  const vtkIdType nx = extent[1] - extent[0] + 1;
  const vtkIdType ny = extent[3] - extent[2] + 1;
  const int first = extent[2];
  const int count = extent[3] - extent[2] + 1;
  std::vector<unsigned char> raw(static_cast<size_t>(in.TraceBytes));
  const float nan = std::numeric_limits<float>::quiet_NaN();

  this->UpdateProgress(0.0);
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int i = extent[0]; i <= extent[1]; ++i)
    {
      // The trace is the column (i, *, k): consecutive samples are nx values apart.
      float* column = values + (vtkIdType(k - extent[4]) * ny) * nx + (i - extent[0]);
      const int32_t trace = in.Index[static_cast<size_t>(k) * in.Crosslines + i];
      if (trace < 0)
      {
        for (int s = 0; s < count; ++s)
        {
          column[s * nx] = nan;
        }
        continue;
      }
      if (segy_readsubtr(fp.get(),
            trace,
            first,
            first + count,
            1,
            raw.data(),
            nullptr,
            in.Trace0,
            in.TraceBytes) != SEGY_OK ||
          segy_to_native(in.Format, count, raw.data()) != SEGY_OK)
      {
        return fail("cannot read trace " + std::to_string(trace));
      }
      ToFloat(in.Format, raw.data(), count, column, nx);
      ++this->NumberOfTracesRead;
    }
    this->UpdateProgress(static_cast<double>(k - extent[4] + 1) / (extent[5] - extent[4] + 1));
  }
  return 1;
}

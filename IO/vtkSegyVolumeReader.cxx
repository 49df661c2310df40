// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkSegyVolumeReader.h"
#include "StrataGridReaderUtilities.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
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

/// The reader's settings a scan depends on.
struct ScanSettings
{
  int InlineByte = 189;
  int CrosslineByte = 193;
  int Format = 0;
  int XByte = 181;
  int YByte = 185;
  int ScalarByte = 71;
  int Placement = 0; ///< vtkSegyVolumeReader::Placements
  double VerticalScale = -1.0;
  double MaximumFitResidual = 0.25;

  /// What a scan depends on: the file, its state (FileState) and these settings.
  std::string Key(const std::string& path, const std::string& state) const
  {
    std::ostringstream key;
    key.precision(17);
    key << path << '\n'
        << this->InlineByte << ' ' << this->CrosslineByte << ' ' << this->Format << ' '
        << this->XByte << ' ' << this->YByte << ' ' << this->ScalarByte << ' ' << this->Placement
        << ' ' << this->VerticalScale << ' ' << this->MaximumFitResidual << '\n'
        << state;
    return key.str();
  }
};

/// Map coordinates of a trace header: the integers at `xByte` and `yByte` times the coordinate
/// scalar at `scalarByte` (SEG-Y rev 1: negative divides by its magnitude, 0 means 1).
void TraceCoordinates(const char* header, const ScanSettings& s, double xy[2])
{
  const int32_t scalar = HeaderInt(header, s.ScalarByte);
  const double factor = scalar > 0 ? double(scalar) : scalar < 0 ? 1.0 / -double(scalar) : 1.0;
  xy[0] = HeaderInt(header, s.XByte) * factor;
  xy[1] = HeaderInt(header, s.YByte) * factor;
}

/// The least-squares affine map from (inline index, crossline index) to map (x, y) over the
/// traces: p = Origin + i * Inline + j * Crossline, and the largest residual. Centred sums keep
/// UTM-sized coordinates exact to well below a millimetre in double.
struct LatticeFit
{
  double Origin[2] = { 0, 0 };
  double Inline[2] = { 0, 0 };
  double Crossline[2] = { 0, 0 };
  double MaxResidual = 0.0;
  vtkIdType WorstTrace = -1;

  /// False when the traces do not span both axes (one line, or one trace). i(t) and j(t) are
  /// trace t's grid indices (computed, not stored: a survey has millions of traces).
  template<typename I, typename J>
  bool Fit(size_t n, I i, J j, const std::vector<double>& xy)
  {
    double mi = 0, mj = 0, mp[2] = { 0, 0 };
    for (size_t t = 0; t < n; ++t)
    {
      mi += i(t) / n;
      mj += j(t) / n;
      mp[0] += xy[2 * t] / n;
      mp[1] += xy[2 * t + 1] / n;
    }
    double sii = 0, sjj = 0, sij = 0, sip[2] = { 0, 0 }, sjp[2] = { 0, 0 };
    for (size_t t = 0; t < n; ++t)
    {
      const double di = i(t) - mi, dj = j(t) - mj;
      sii += di * di;
      sjj += dj * dj;
      sij += di * dj;
      for (int c = 0; c < 2; ++c)
      {
        sip[c] += di * (xy[2 * t + c] - mp[c]);
        sjp[c] += dj * (xy[2 * t + c] - mp[c]);
      }
    }
    const double det = sii * sjj - sij * sij;
    // Integer indices: det is an integer, 0 exactly when all traces lie on one line of the grid.
    if (!(det > 0.5))
    {
      return false;
    }
    for (int c = 0; c < 2; ++c)
    {
      this->Inline[c] = (sjj * sip[c] - sij * sjp[c]) / det;
      this->Crossline[c] = (sii * sjp[c] - sij * sip[c]) / det;
      this->Origin[c] = mp[c] - this->Inline[c] * mi - this->Crossline[c] * mj;
    }
    for (size_t t = 0; t < n; ++t)
    {
      const double dx =
        this->Origin[0] + this->Inline[0] * i(t) + this->Crossline[0] * j(t) - xy[2 * t];
      const double dy =
        this->Origin[1] + this->Inline[1] * i(t) + this->Crossline[1] * j(t) - xy[2 * t + 1];
      const double r = std::hypot(dx, dy);
      if (r > this->MaxResidual)
      {
        this->MaxResidual = r;
        this->WorstTrace = static_cast<vtkIdType>(t);
      }
    }
    return true;
  }
};

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
  /// Row-major; LineNumbers: index (x, y, z) = (crossline, sample, inline) -> world (inline,
  /// crossline, time).
  double Direction[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
  bool Georeferenced = false;
  double FitResidual = 0.0;
  double GridRotation = 0.0;
  std::string Warning;
  vtkNew<vtkMatrix4x4> GridToWorld;

  std::string Scan(const std::string& path, const ScanSettings& settings);
  void SetGeometry(vtkImageData* image) const
  {
    image->SetSpacing(this->Spacing);
    image->SetOrigin(this->Origin);
    image->SetDirectionMatrix(this->Direction);
    vtkNew<vtkDoubleArray> matrix;
    matrix->SetName("GridToWorld");
    matrix->SetNumberOfComponents(16);
    matrix->InsertNextTuple(this->GridToWorld->GetData());
    image->GetFieldData()->AddArray(matrix);
  }

private:
  /// Per trace, from the header pass: line numbers, map coordinates and the coordinate unit.
  struct TraceHeaders
  {
    std::vector<int32_t> Inlines, Crosslines;
    std::vector<double> XY;
    int CoordinateUnits = 0;
    bool AnyCoordinate = false;
  };
  std::string ReadTraceHeaders(segy_file* fp, const ScanSettings& s, TraceHeaders& h);
  std::string BuildIndex(const TraceHeaders& h, const ScanSettings& s);
  std::string Place(const TraceHeaders& h, const ScanSettings& s, double dt);
  void PlaceByLineNumbers(double dt);
  void UpdateGridToWorld();

  double Delay = 0.0;
};

//------------------------------------------------------------------------------
std::string vtkSegyVolumeReader::vtkInternals::Scan(const std::string& path,
  const ScanSettings& settings)
{
  const int inlineByte = settings.InlineByte;
  const int crosslineByte = settings.CrosslineByte;
  const int formatOverride = settings.Format;
  this->Key.clear();
  this->Index.clear();
  this->Warning.clear();
  for (int byte :
    { inlineByte, crosslineByte, settings.XByte, settings.YByte, settings.ScalarByte })
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
  if (settings.XByte == settings.YByte)
  {
    return "XByte and YByte are both " + std::to_string(settings.XByte);
  }
  if (!(settings.VerticalScale != 0.0) || !std::isfinite(settings.VerticalScale))
  {
    return "VerticalScale is " + std::to_string(settings.VerticalScale) +
           "; it must be finite and not 0";
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

  TraceHeaders h;
  std::string error = this->ReadTraceHeaders(fp.get(), settings, h);
  if (error.empty())
  {
    error = this->BuildIndex(h, settings);
  }
  if (!error.empty())
  {
    this->Index.clear();
    return error;
  }
  float dt = 0.0f;
  if (segy_sample_interval(fp.get(), 0.0f, &dt) != SEGY_OK || !(dt > 0.0f))
  {
    this->Warning = "no sample interval in the binary or first trace header; 1 ms assumed";
    dt = 1000.0f;
  }
  error = this->Place(h, settings, dt / 1000.0);
  if (!error.empty())
  {
    this->Index.clear();
    return error;
  }
  const vtkIdType missing = static_cast<vtkIdType>(this->Index.size()) - this->Traces;
  if (missing > 0)
  {
    std::ostringstream msg;
    msg << (this->Warning.empty() ? "" : "; ") << missing << " of the " << this->Index.size()
        << " grid positions have no trace; they read as NaN";
    this->Warning += msg.str();
  }
  this->Key = settings.Key(path, this->State);
  return std::string();
}

//------------------------------------------------------------------------------
// One pass over the trace headers. Their sample counts are not checked: writers leave them
// stale (f3.sgy says 462 in every trace of 75 samples), and segyio too trusts the binary header;
// traces of other lengths show in the file size.
std::string vtkSegyVolumeReader::vtkInternals::ReadTraceHeaders(segy_file* fp,
  const ScanSettings& s,
  TraceHeaders& h)
{
  std::vector<char> header(SEGY_TRACE_HEADER_SIZE);
  h.Inlines.resize(this->Traces);
  h.Crosslines.resize(this->Traces);
  h.XY.resize(2 * static_cast<size_t>(this->Traces));
  for (int t = 0; t < this->Traces; ++t)
  {
    if (segy_traceheader(fp, t, header.data(), this->Trace0, this->TraceBytes) != SEGY_OK)
    {
      return "cannot read the header of trace " + std::to_string(t);
    }
    h.Inlines[t] = HeaderInt(header.data(), s.InlineByte);
    h.Crosslines[t] = HeaderInt(header.data(), s.CrosslineByte);
    TraceCoordinates(header.data(), s, &h.XY[2 * static_cast<size_t>(t)]);
    h.AnyCoordinate = h.AnyCoordinate || h.XY[2 * t] != 0.0 || h.XY[2 * t + 1] != 0.0;
    const double delay = HeaderInt(header.data(), SEGY_TR_DELAY_REC_TIME);
    if (t == 0)
    {
      this->Delay = delay;
      h.CoordinateUnits = HeaderInt(header.data(), SEGY_TR_COORD_UNITS);
    }
    else if (delay != this->Delay)
    {
      std::ostringstream msg;
      msg << "trace " << t << " starts at " << delay << " ms (delay recording time, bytes "
          << "109-110) and trace 0 at " << this->Delay << " ms: traces that start at different "
          << "times are not supported";
      return msg.str();
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
// The grid of the line numbers and the (inline, crossline) -> trace index.
std::string vtkSegyVolumeReader::vtkInternals::BuildIndex(const TraceHeaders& h,
  const ScanSettings& s)
{
  const LineAxis il(h.Inlines);
  const LineAxis xl(h.Crosslines);
  if (il.Count > MaxLines || xl.Count > MaxLines ||
      il.Count * xl.Count > MaxPositionsPerTrace * this->Traces)
  {
    std::ostringstream msg;
    msg << "inline numbers " << il.First << " + " << il.Step << " k (" << il.Count
        << " lines) and crossline numbers " << xl.First << " + " << xl.Step << " k (" << xl.Count
        << " lines) make a grid far too large for " << this->Traces << " traces: are InlineByte ("
        << s.InlineByte << ") and CrosslineByte (" << s.CrosslineByte << ") right?";
    return msg.str();
  }
  this->Inlines = static_cast<int>(il.Count);
  this->Crosslines = static_cast<int>(xl.Count);
  this->Index.assign(static_cast<size_t>(il.Count * xl.Count), -1);
  for (int t = 0; t < this->Traces; ++t)
  {
    int32_t& slot = this->Index[il.IndexOf(h.Inlines[t]) * xl.Count + xl.IndexOf(h.Crosslines[t])];
    if (slot >= 0)
    {
      std::ostringstream msg;
      msg << "traces " << slot << " and " << t << " are both at inline " << h.Inlines[t]
          << ", crossline " << h.Crosslines[t] << " (pre-stack gathers are not supported; are "
          << "InlineByte (" << s.InlineByte << ") and CrosslineByte (" << s.CrosslineByte
          << ") right?)";
      return msg.str();
    }
    slot = t;
  }
  this->FirstInline = il.First;
  this->InlineStep = il.Step;
  this->FirstCrossline = xl.First;
  this->CrosslineStep = xl.Step;
  return std::string();
}

//------------------------------------------------------------------------------
void vtkSegyVolumeReader::vtkInternals::PlaceByLineNumbers(double dt)
{
  this->Georeferenced = false;
  this->FitResidual = 0.0;
  this->GridRotation = 0.0;
  const double direction[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
  std::copy(direction, direction + 9, this->Direction);
  this->Spacing[0] = this->CrosslineStep;
  this->Spacing[1] = dt;
  this->Spacing[2] = this->InlineStep;
  this->Origin[0] = this->FirstInline;
  this->Origin[1] = this->FirstCrossline;
  this->Origin[2] = this->Delay;
  this->UpdateGridToWorld();
}

//------------------------------------------------------------------------------
// World placement: the affine lattice fitted to the trace coordinates (LatticeFit), checked.
std::string vtkSegyVolumeReader::vtkInternals::Place(const TraceHeaders& h,
  const ScanSettings& s,
  double dt)
{
  const auto placement = static_cast<vtkSegyVolumeReader::Placements>(s.Placement);
  const bool forced = placement == vtkSegyVolumeReader::Placements::World;
  if (placement == vtkSegyVolumeReader::Placements::LineNumbers || (!forced && !h.AnyCoordinate))
  {
    this->PlaceByLineNumbers(dt);
    return std::string();
  }
  std::ostringstream where;
  where << " (XByte " << s.XByte << ", YByte " << s.YByte << ", CoordinateScalarByte "
        << s.ScalarByte << ")";
  if (!h.AnyCoordinate)
  {
    return "World placement: every trace has X = Y = 0" + where.str() +
           "; the file carries no coordinates there";
  }
  if (h.CoordinateUnits >= 2 && h.CoordinateUnits <= 4)
  {
    const std::string msg = "the trace coordinates are geographic (coordinate units " +
                            std::to_string(h.CoordinateUnits) + " at byte 89), not map " +
                            "coordinates";
    if (forced)
    {
      return "World placement: " + msg;
    }
    this->Warning = msg + "; placed by line numbers";
    this->PlaceByLineNumbers(dt);
    return std::string();
  }
  auto i = [&](size_t t)
  { return static_cast<double>((int64_t(h.Inlines[t]) - this->FirstInline) / this->InlineStep); };
  auto j = [&](size_t t)
  {
    return static_cast<double>(
      (int64_t(h.Crosslines[t]) - this->FirstCrossline) / this->CrosslineStep);
  };
  LatticeFit fit;
  if (!fit.Fit(static_cast<size_t>(this->Traces), i, j, h.XY))
  {
    const std::string msg = "the traces lie on a single inline or crossline, so the other axis "
                            "cannot be placed";
    if (forced)
    {
      return "World placement: " + msg + " (use LineNumbers placement)";
    }
    this->Warning = msg + "; placed by line numbers";
    this->PlaceByLineNumbers(dt);
    return std::string();
  }
  const double il = std::hypot(fit.Inline[0], fit.Inline[1]);
  const double xl = std::hypot(fit.Crossline[0], fit.Crossline[1]);
  const double cross = fit.Crossline[0] * fit.Inline[1] - fit.Crossline[1] * fit.Inline[0];
  // |sin| of the angle between the axes: bins squashed below 1/10 of a square are misread
  // headers (a coordinate that does not change along one axis).
  const double sine = il > 0 && xl > 0 ? std::abs(cross) / (il * xl) : 0.0;
  if (!(sine > 0.1))
  {
    std::ostringstream msg;
    msg << "World placement: the coordinates" << where.str() << " move " << il << " per inline and "
        << xl << " per crossline, nearly along one line: are the "
        << "coordinate byte positions right?";
    return msg.str();
  }
  const double bin = std::min(il, xl);
  if (fit.MaxResidual > s.MaximumFitResidual * bin)
  {
    const vtkIdType t = fit.WorstTrace;
    std::ostringstream msg;
    msg.precision(12);
    msg << "World placement: trace " << t << " (inline " << h.Inlines[t] << ", crossline "
        << h.Crosslines[t] << ") at (" << h.XY[2 * t] << ", " << h.XY[2 * t + 1] << ") is "
        << fit.MaxResidual << " from its place on the lattice fitted to all traces, more than "
        << s.MaximumFitResidual << " bins of " << bin << where.str()
        << ": the traces are not on a regular grid";
    return msg.str();
  }
  if (sine < 1.0 - 1.5e-4) // about 1 degree from a right angle
  {
    std::ostringstream msg;
    msg << (this->Warning.empty() ? "" : "; ") << "the bins are not rectangular (their sides are "
        << std::asin(std::min(sine, 1.0)) * 180.0 / vtkMath::Pi()
        << " degrees apart); placed as fitted, sheared";
    this->Warning += msg.str();
  }
  const double down = s.VerticalScale < 0 ? -1.0 : 1.0;
  const double direction[9] = { fit.Crossline[0] / xl,
    0,
    fit.Inline[0] / il, //
    fit.Crossline[1] / xl,
    0,
    fit.Inline[1] / il, //
    0,
    down,
    0 };
  std::copy(direction, direction + 9, this->Direction);
  this->Spacing[0] = xl;
  this->Spacing[1] = std::abs(s.VerticalScale) * dt;
  this->Spacing[2] = il;
  this->Origin[0] = fit.Origin[0];
  this->Origin[1] = fit.Origin[1];
  this->Origin[2] = s.VerticalScale * this->Delay;
  this->Georeferenced = true;
  this->FitResidual = fit.MaxResidual;
  this->GridRotation = std::atan2(fit.Crossline[1], fit.Crossline[0]) * 180.0 / vtkMath::Pi();
  this->UpdateGridToWorld();
  return std::string();
}

//------------------------------------------------------------------------------
void vtkSegyVolumeReader::vtkInternals::UpdateGridToWorld()
{
  this->GridToWorld->Identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->GridToWorld->SetElement(r, c, this->Direction[3 * r + c] * this->Spacing[c]);
    }
    this->GridToWorld->SetElement(r, 3, this->Origin[r]);
  }
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
  os << indent << "XByte: " << this->XByte << "\n";
  os << indent << "YByte: " << this->YByte << "\n";
  os << indent << "CoordinateScalarByte: " << this->CoordinateScalarByte << "\n";
  os << indent << "Placement: " << static_cast<int>(this->Placement) << "\n";
  os << indent << "VerticalScale: " << this->VerticalScale << "\n";
  os << indent << "MaximumFitResidual: " << this->MaximumFitResidual << "\n";
  os << indent << "Georeferenced: " << this->Georeferenced << "\n";
  os << indent << "FitResidual: " << this->FitResidual << "\n";
  os << indent << "GridRotation: " << this->GridRotation << "\n";
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
void vtkSegyVolumeReader::SetPlacement(Placements placement)
{
  if (this->Placement != placement)
  {
    this->Placement = placement;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkMatrix4x4* vtkSegyVolumeReader::GetGridToWorld()
{
  return this->Internals->GridToWorld;
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
  this->Georeferenced = false;
  this->FitResidual = this->GridRotation = 0.0;
  const std::string name = this->FileName ? this->FileName : "";
  vtkInternals& in = *this->Internals;
  ScanSettings settings;
  settings.InlineByte = this->InlineByte;
  settings.CrosslineByte = this->CrosslineByte;
  settings.Format = this->SampleFormat;
  settings.XByte = this->XByte;
  settings.YByte = this->YByte;
  settings.ScalarByte = this->CoordinateScalarByte;
  settings.Placement = static_cast<int>(this->Placement);
  settings.VerticalScale = this->VerticalScale;
  settings.MaximumFitResidual = this->MaximumFitResidual;
  // Scanning every trace header is the expensive part: done again only for another file, other
  // settings, or a file that changed.
  if (in.Key.empty() || in.Key != settings.Key(name, FileState(name)))
  {
    const std::string error =
      name.empty() ? std::string("no file name set") : in.Scan(name, settings);
    if (!error.empty())
    {
      in.Key.clear();
      in.GridToWorld->Identity();
      ClearOutput(outInfo);
      vtkErrorMacro("Cannot read SEG-Y file \"" << name << "\": " << error);
      return 0;
    }
    if (!in.Warning.empty())
    {
      vtkWarningMacro("SEG-Y file \"" << name << "\": " << in.Warning);
    }
  }
  this->Georeferenced = in.Georeferenced;
  this->FitResidual = in.FitResidual;
  this->GridRotation = in.GridRotation;
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
  outInfo->Set(vtkDataObject::DIRECTION(), in.Direction, 9);
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

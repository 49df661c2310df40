// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Small post-stack SEG-Y files written byte by byte for the tests (no segyio, so the reader is
// checked against an independent encoder): 3200-byte textual header, 400-byte binary header,
// traces with their line numbers at chosen byte positions, in shuffled order, with holes, in
// the sample formats vtkSegyVolumeReader reads. Header-only; shared by TestSegyVolumeReader and
// TestConverters.
#ifndef StrataSegyTestFile_h
#define StrataSegyTestFile_h

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace strata_test
{
/// Writes `bytes` big-endian bytes of `v` at 0-based `offset`.
inline void PutBigEndian(std::string& out, size_t offset, uint32_t v, int bytes)
{
  for (int b = 0; b < bytes; ++b)
  {
    out[offset + b] = static_cast<char>((v >> (8 * (bytes - 1 - b))) & 0xFF);
  }
}

/// IBM System/360 single precision of `v`: sign, 7-bit excess-64 exponent of 16, 24-bit
/// fraction in [1/16, 1). Exact for the values the tests write (few significant bits).
inline uint32_t ToIbmFloat(double v)
{
  if (v == 0.0)
  {
    return 0;
  }
  const uint32_t sign = v < 0 ? 0x80000000u : 0u;
  double a = std::fabs(v);
  int e = 0;
  while (a >= 1.0)
  {
    a /= 16.0;
    ++e;
  }
  while (a < 1.0 / 16.0)
  {
    a *= 16.0;
    --e;
  }
  return sign | (static_cast<uint32_t>(e + 64) << 24) | static_cast<uint32_t>(a * 16777216.0);
}

/// A regular inline/crossline grid of traces, some missing, in any order, as a SEG-Y file.
struct SegyTestFile
{
  int Format = 1; ///< 1 IBM, 2 int32, 3 int16, 5 IEEE, 8 int8 (other codes: header only)
  int InlineByte = 189;
  int CrosslineByte = 193;
  int FirstInline = 10, InlineStep = 2, Inlines = 4;
  int FirstCrossline = 100, CrosslineStep = 1, Crosslines = 5;
  int Samples = 6;
  int IntervalMicroseconds = 2000;
  int DelayMilliseconds = 100;
  std::vector<std::pair<int, int>> Missing; ///< (inline index, crossline index) left out
  unsigned Seed = 0;                        ///< 0: inline-sorted order, else a shuffle
  int LongTrace = -1;  ///< position in the file of a trace given 2 extra samples (-1: none)
  int DelayTrace = -1; ///< position in the file of a trace given another delay (-1: none)

  /// Map coordinates (written when Georeferenced): grid index (0, 0) at (OriginX, OriginY);
  /// crossline index x moves CrosslineBin along the azimuth RotationDegrees (counterclockwise
  /// from +x), inline index i moves InlineBin 90 degrees counterclockwise from there, or
  /// clockwise when Mirrored. Written as integers at XByte and YByte with CoordinateScalar at
  /// byte ScalarByte (negative: the integers are the coordinates times its magnitude).
  bool Georeferenced = false;
  double OriginX = 456000.0, OriginY = 6780000.0, RotationDegrees = 30.0;
  double InlineBin = 25.0, CrosslineBin = 12.5;
  bool Mirrored = false;
  int CoordinateScalar = -100;
  int XByte = 181, YByte = 185, ScalarByte = 71;
  int CoordinateUnits = 1;
  std::pair<int, int> OffLattice{ -1, -1 }; ///< a trace written one crossline bin off its place

  /// The exact map position of grid index (i, x).
  void MapPosition(double i, double x, double p[2]) const
  {
    const double a = this->RotationDegrees * 3.14159265358979323846 / 180.0;
    const double ux[2] = { std::cos(a), std::sin(a) };
    const double side = this->Mirrored ? -1.0 : 1.0;
    const double ui[2] = { -side * ux[1], side * ux[0] };
    for (int c = 0; c < 2; ++c)
    {
      p[c] = (c ? this->OriginY : this->OriginX) + i * this->InlineBin * ui[c] +
             x * this->CrosslineBin * ux[c];
    }
  }

  /// Writes the coordinates of grid index (i, x) into trace header `t`.
  void PutCoordinates(std::string& t, int i, int x) const
  {
    double p[2];
    this->MapPosition(i, x + (std::make_pair(i, x) == this->OffLattice ? 1.0 : 0.0), p);
    const double factor = this->CoordinateScalar < 0   ? -double(this->CoordinateScalar)
                          : this->CoordinateScalar > 0 ? 1.0 / this->CoordinateScalar
                                                       : 1.0;
    PutBigEndian(t, this->ScalarByte - 1, static_cast<uint32_t>(this->CoordinateScalar), 2);
    PutBigEndian(t, 88, static_cast<uint32_t>(this->CoordinateUnits), 2);
    for (int c = 0; c < 2; ++c)
    {
      const auto v = static_cast<int32_t>(std::llround(p[c] * factor));
      PutBigEndian(t, (c ? this->YByte : this->XByte) - 1, static_cast<uint32_t>(v), 4);
    }
  }

  /// The value of sample s of the trace at grid indices (i, x): exactly representable in
  /// `format`, of both signs, distinct per trace, in range for int8 on grids up to 4 x 5 x 6.
  static double Value(int format, int i, int x, int s)
  {
    const int g = (i - 2) * 24 + (x - 2) * 5 - s;
    switch (format)
    {
      case 8:
        return g;
      case 3:
        return g * 301;
      case 2:
        return g * 100003.0;
      default:
        return g * 1.5 + 0.25 * (s % 4);
    }
  }

  static int SampleBytes(int format) { return format == 3 ? 2 : format == 8 ? 1 : 4; }

  /// (inline index, crossline index) of each trace, in file order.
  std::vector<std::pair<int, int>> Order() const
  {
    std::vector<std::pair<int, int>> order;
    for (int i = 0; i < this->Inlines; ++i)
    {
      for (int x = 0; x < this->Crosslines; ++x)
      {
        if (std::find(this->Missing.begin(), this->Missing.end(), std::make_pair(i, x)) ==
            this->Missing.end())
        {
          order.emplace_back(i, x);
        }
      }
    }
    if (this->Seed)
    {
      std::shuffle(order.begin(), order.end(), std::mt19937(this->Seed));
    }
    return order;
  }

  std::string Bytes() const
  {
    std::string out(3600, ' ');
    const std::string text = "C 1 STRATA TEST FILE, WRITTEN BY THE TESTS";
    out.replace(0, text.size(), text);
    std::fill(out.begin() + 3200, out.end(), '\0');
    PutBigEndian(out, 3216, static_cast<uint32_t>(this->IntervalMicroseconds), 2);
    PutBigEndian(out, 3220, static_cast<uint32_t>(this->Samples), 2);
    PutBigEndian(out, 3224, static_cast<uint32_t>(this->Format), 2);
    const int size = SampleBytes(this->Format);
    int position = 0;
    for (const auto& trace : this->Order())
    {
      const int here = position++;
      const int samples = this->Samples + (here == this->LongTrace ? 2 : 0);
      std::string t(240 + static_cast<size_t>(samples) * size, '\0');
      PutBigEndian(t,
        108,
        static_cast<uint32_t>(this->DelayMilliseconds + (here == this->DelayTrace ? 4 : 0)),
        2);
      PutBigEndian(t, 114, static_cast<uint32_t>(this->Samples), 2);
      PutBigEndian(t, 116, static_cast<uint32_t>(this->IntervalMicroseconds), 2);
      PutBigEndian(t,
        this->InlineByte - 1,
        static_cast<uint32_t>(this->FirstInline + trace.first * this->InlineStep),
        4);
      PutBigEndian(t,
        this->CrosslineByte - 1,
        static_cast<uint32_t>(this->FirstCrossline + trace.second * this->CrosslineStep),
        4);
      if (this->Georeferenced)
      {
        this->PutCoordinates(t, trace.first, trace.second);
      }
      for (int s = 0; s < samples; ++s)
      {
        const double v = Value(this->Format, trace.first, trace.second, s);
        uint32_t bits = 0;
        if (this->Format == 1)
        {
          bits = ToIbmFloat(v);
        }
        else if (this->Format == 5)
        {
          const float f = static_cast<float>(v);
          std::memcpy(&bits, &f, 4);
        }
        else
        {
          bits = static_cast<uint32_t>(static_cast<int32_t>(v));
        }
        PutBigEndian(t, 240 + static_cast<size_t>(s) * size, bits, size);
      }
      out += t;
    }
    return out;
  }
};
}

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkSyntheticSurveyWriter.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <unistd.h> // For getpid (the temporary's name)

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkSyntheticSurveyWriter);

namespace
{
constexpr double Pi = 3.14159265358979323846;

void PutBigEndian(std::string& out, size_t offset, uint32_t v, int bytes)
{
  for (int b = 0; b < bytes; ++b)
  {
    out[offset + b] = static_cast<char>((v >> (8 * (bytes - 1 - b))) & 0xFF);
  }
}

/// One horizon as the traces sample it: map -> continuous grid index, and the values.
struct Horizon
{
  int Nx = 0, Ny = 0;
  double Origin[2] = { 0, 0 };
  double ToIndex[4] = { 1, 0, 0, 1 }; ///< inverse of the 2x2 of direction x spacing
  vtkDataArray* Values = nullptr;

  /// The horizon's value at map (x, y), bilinear; NaN at a hole or off the grid.
  double At(double x, double y) const
  {
    const double dx = x - this->Origin[0], dy = y - this->Origin[1];
    const double fi = this->ToIndex[0] * dx + this->ToIndex[1] * dy;
    const double fj = this->ToIndex[2] * dx + this->ToIndex[3] * dy;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // A position on the last line (within rounding) still belongs to the grid.
    constexpr double slack = 1e-9;
    if (!(fi >= -slack && fj >= -slack && fi <= this->Nx - 1 + slack && fj <= this->Ny - 1 + slack))
    {
      return nan;
    }
    const int i =
      std::min(std::max(static_cast<int>(std::floor(fi)), 0), std::max(this->Nx - 2, 0));
    const int j =
      std::min(std::max(static_cast<int>(std::floor(fj)), 0), std::max(this->Ny - 2, 0));
    const double u = this->Nx > 1 ? fi - i : 0.0, v = this->Ny > 1 ? fj - j : 0.0;
    double sum = 0.0;
    for (int c = 0; c < 4; ++c)
    {
      const int ci = std::min(i + (c & 1), this->Nx - 1), cj = std::min(j + (c >> 1), this->Ny - 1);
      const double w = ((c & 1) ? u : 1.0 - u) * ((c >> 1) ? v : 1.0 - v);
      const double h = this->Values->GetComponent(static_cast<vtkIdType>(cj) * this->Nx + ci, 0);
      if (w == 0.0)
      {
        continue;
      }
      if (!std::isfinite(h) || std::abs(h) >= 1e30)
      {
        return nan;
      }
      sum += w * h;
    }
    return sum;
  }
};

/// The horizons on `self`'s port 0, as the traces sample them; an error message or empty.
std::string CollectHorizons(vtkAlgorithm* self, std::vector<Horizon>& horizons)
{
  const int n = self->GetNumberOfInputConnections(0);
  horizons.assign(n, Horizon());
  for (int h = 0; h < n; ++h)
  {
    self->GetInputAlgorithm(0, h)->Update();
    auto* image = vtkImageData::SafeDownCast(self->GetInputDataObject(0, h));
    vtkDataArray* values = image ? image->GetPointData()->GetScalars() : nullptr;
    if (image && !values && image->GetPointData()->GetNumberOfArrays() > 0)
    {
      values = image->GetPointData()->GetArray(0);
    }
    int dims[3] = { 0, 0, 0 };
    if (image)
    {
      image->GetDimensions(dims);
    }
    if (!values || dims[2] != 1 || dims[0] < 1 || dims[1] < 1)
    {
      return "horizon " + std::to_string(h) +
             " is not a vtkImageData of nx x ny x 1 points with scalars";
    }
    Horizon& g = horizons[h];
    g.Nx = dims[0];
    g.Ny = dims[1];
    g.Values = values;
    g.Origin[0] = image->GetOrigin()[0];
    g.Origin[1] = image->GetOrigin()[1];
    const double* d = image->GetDirectionMatrix()->GetData();
    const double* s = image->GetSpacing();
    const double m[4] = { d[0] * s[0], d[1] * s[1], d[3] * s[0], d[4] * s[1] };
    const double det = m[0] * m[3] - m[1] * m[2];
    if (!(std::abs(det) > 0.0))
    {
      return "horizon " + std::to_string(h) + " has a degenerate lateral grid";
    }
    const double inverse[4] = { m[3] / det, -m[1] / det, -m[2] / det, m[0] / det };
    std::copy(inverse, inverse + 4, g.ToIndex);
  }
  return std::string();
}

/// A uniform double in (0, 1) from mt19937_64's exactly specified output.
double Uniform(std::mt19937_64& g)
{
  return (static_cast<double>(g() >> 11) + 0.5) / 9007199254740992.0;
}
}

//------------------------------------------------------------------------------
vtkSyntheticSurveyWriter::vtkSyntheticSurveyWriter()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(0);
}

//------------------------------------------------------------------------------
vtkSyntheticSurveyWriter::~vtkSyntheticSurveyWriter()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
int vtkSyntheticSurveyWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSyntheticSurveyWriter::FillOutputPortInformation(int, vtkInformation*)
{
  return 1;
}

//------------------------------------------------------------------------------
void vtkSyntheticSurveyWriter::SetSamples(int count, double interval, int start)
{
  if (this->Samples != count || this->SampleInterval != interval || this->StartTime != start)
  {
    this->Samples = count;
    this->SampleInterval = interval;
    this->StartTime = start;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSyntheticSurveyWriter::SetImpedance(int layer, double impedance)
{
  if (layer < 0 || layer > 1 << 16)
  {
    vtkErrorMacro("Layer " << layer << " is outside [0, 65536].");
    return;
  }
  while (static_cast<int>(this->Impedances.size()) <= layer)
  {
    this->Impedances.push_back(4e6 + 1e6 * static_cast<double>(this->Impedances.size()));
  }
  this->Impedances[layer] = impedance;
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkSyntheticSurveyWriter::GetImpedance(int layer) const
{
  if (layer >= 0 && layer < static_cast<int>(this->Impedances.size()))
  {
    return this->Impedances[layer];
  }
  return 4e6 + 1e6 * layer;
}

//------------------------------------------------------------------------------
void vtkSyntheticSurveyWriter::MapPosition(double i, double x, double p[2]) const
{
  const double a = this->Rotation * Pi / 180.0;
  const double ux[2] = { std::cos(a), std::sin(a) };
  const double ui[2] = { -ux[1], ux[0] };
  for (int c = 0; c < 2; ++c)
  {
    p[c] = this->Origin[c] + i * this->Bins[0] * ui[c] + x * this->Bins[1] * ux[c];
  }
}

//------------------------------------------------------------------------------
double vtkSyntheticSurveyWriter::Ricker(double t) const
{
  const double a = Pi * this->PeakFrequency * t / 1000.0;
  return (1.0 - 2.0 * a * a) * std::exp(-a * a);
}

//------------------------------------------------------------------------------
double vtkSyntheticSurveyWriter::CoordinateFactor() const
{
  return this->CoordinateScalar < 0   ? -double(this->CoordinateScalar)
         : this->CoordinateScalar > 0 ? 1.0 / this->CoordinateScalar
                                      : 1.0;
}

//------------------------------------------------------------------------------
std::string vtkSyntheticSurveyWriter::CheckSettings(int n) const
{
  for (int k = 0; k <= n; ++k)
  {
    if (!(this->GetImpedance(k) > 0.0) || !std::isfinite(this->GetImpedance(k)))
    {
      return "the impedance of layer " + std::to_string(k) + " is not positive";
    }
  }
  if (static_cast<int>(this->Impedances.size()) > n + 1)
  {
    return std::to_string(this->Impedances.size()) + " impedances set for " + std::to_string(n) +
           " horizons (" + std::to_string(n + 1) + " layers)";
  }
  const double micro = this->SampleInterval * 1000.0;
  if (!(micro >= 1.0 && micro <= 65535.0 && micro == std::round(micro)))
  {
    return "sample interval " + std::to_string(this->SampleInterval) +
           " ms is not a whole number of microseconds in [1, 65535]";
  }
  if (this->Samples < 1 || this->Samples > 65535 || this->StartTime < 0 || this->StartTime > 32767)
  {
    return "samples (" + std::to_string(this->Samples) + ") outside [1, 65535] or start time (" +
           std::to_string(this->StartTime) + " ms) outside [0, 32767]";
  }
  if (this->Lines[0] < 1 || this->Lines[1] < 1 ||
      int64_t(this->Lines[0]) * this->Lines[1] > (int64_t(1) << 31) - 1 || !(this->Bins[0] > 0.0) ||
      !(this->Bins[1] > 0.0))
  {
    return "the survey needs at least one inline and crossline and positive bins";
  }
  const double factor = this->CoordinateFactor();
  for (int corner = 0; corner < 4; ++corner)
  {
    double p[2];
    this->MapPosition(
      (corner & 1) * (this->Lines[0] - 1.0), (corner >> 1) * (this->Lines[1] - 1.0), p);
    if (!(std::abs(p[0] * factor) < 2147483647.0 && std::abs(p[1] * factor) < 2147483647.0))
    {
      return "the survey's coordinates do not fit 32-bit integers at coordinate scalar " +
             std::to_string(this->CoordinateScalar);
    }
  }

  return std::string();
}

//------------------------------------------------------------------------------
bool vtkSyntheticSurveyWriter::Write()
{
  const std::string name = this->FileName ? this->FileName : "";
  auto fail = [&](const std::string& error)
  {
    vtkErrorMacro("Cannot write synthetic survey \"" << name << "\": " << error);
    return false;
  };
  if (name.empty())
  {
    return fail("no file name set");
  }
  const int n = this->GetNumberOfInputConnections(0);
  if (n == 0)
  {
    return fail("no horizons (inputs on port 0)");
  }
  std::vector<Horizon> horizons;
  std::string error = CollectHorizons(this, horizons);
  if (error.empty())
  {
    error = this->CheckSettings(n);
  }
  if (!error.empty())
  {
    return fail(error);
  }
  const double factor = this->CoordinateFactor();
  const double micro = this->SampleInterval * 1000.0;
  std::ostringstream tmpName;
  tmpName << name << ".tmp-" << ::getpid();
  const std::string tmp = tmpName.str();
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out)
  {
    return fail("cannot create " + tmp + ": " + std::strerror(errno));
  }
  std::string head(3600, ' ');
  const std::string text = "C 1 SYNTHETIC SURVEY WRITTEN BY STRATA (vtkSyntheticSurveyWriter)";
  head.replace(0, text.size(), text);
  std::fill(head.begin() + 3200, head.end(), '\0');
  PutBigEndian(head, 3216, static_cast<uint32_t>(micro), 2);
  PutBigEndian(head, 3220, static_cast<uint32_t>(this->Samples), 2);
  PutBigEndian(head, 3224, 5, 2);      // IEEE float
  PutBigEndian(head, 3254, 1, 2);      // metres
  PutBigEndian(head, 3500, 0x0100, 2); // revision 1
  PutBigEndian(head, 3502, 1, 2);      // fixed-length traces
  out.write(head.data(), head.size());

  std::string trace(240 + 4 * static_cast<size_t>(this->Samples), '\0');
  std::vector<std::pair<double, int>> crossings;
  this->UpdateProgress(0.0);
  for (int i = 0; i < this->Lines[0] && out; ++i)
  {
    for (int x = 0; x < this->Lines[1]; ++x)
    {
      std::fill(trace.begin(), trace.end(), '\0');
      const uint32_t sequence = static_cast<uint32_t>(i * this->Lines[1] + x + 1);
      double p[2];
      this->MapPosition(i, x, p);
      PutBigEndian(trace, 0, sequence, 4);
      PutBigEndian(trace, 4, sequence, 4);
      for (int byte : { 8, 188 })
        PutBigEndian(trace, byte, static_cast<uint32_t>(this->FirstInline + i), 4);
      for (int byte : { 20, 192 })
        PutBigEndian(trace, byte, static_cast<uint32_t>(this->FirstCrossline + x), 4);
      PutBigEndian(trace, 70, static_cast<uint32_t>(this->CoordinateScalar), 2);
      for (int byte : { 72, 180 })
      {
        PutBigEndian(
          trace, byte, static_cast<uint32_t>(static_cast<int32_t>(std::llround(p[0] * factor))), 4);
        PutBigEndian(trace,
          byte + 4,
          static_cast<uint32_t>(static_cast<int32_t>(std::llround(p[1] * factor))),
          4);
      }
      PutBigEndian(trace, 88, 1, 2); // length units
      PutBigEndian(trace, 108, static_cast<uint32_t>(this->StartTime), 2);
      PutBigEndian(trace, 114, static_cast<uint32_t>(this->Samples), 2);
      PutBigEndian(trace, 116, static_cast<uint32_t>(micro), 2);

      crossings.clear();
      for (int h = 0; h < n; ++h)
      {
        const double t = horizons[h].At(p[0], p[1]);
        if (!std::isnan(t))
          crossings.emplace_back(t, h);
      }
      std::stable_sort(crossings.begin(),
        crossings.end(),
        [](const std::pair<double, int>& a, const std::pair<double, int>& b)
        { return a.first < b.first; });
      std::vector<std::pair<double, double>> spikes; // (time, reflection coefficient)
      double above = this->GetImpedance(0);
      for (const auto& c : crossings)
      {
        const double below = this->GetImpedance(c.second + 1);
        spikes.emplace_back(c.first, (below - above) / (below + above));
        above = below;
      }
      std::seed_seq seeds{ this->Seed, static_cast<unsigned>(i), static_cast<unsigned>(x) };
      std::mt19937_64 noise(seeds);
      for (int s = 0; s < this->Samples; ++s)
      {
        const double t = this->StartTime + s * this->SampleInterval;
        double a = 0.0;
        for (const auto& spike : spikes)
          a += spike.second * this->Ricker(t - spike.first);
        if (this->NoiseLevel > 0.0)
        {
          // Box-Muller: portable where std::normal_distribution is not.
          const double u1 = Uniform(noise), u2 = Uniform(noise);
          a += this->NoiseLevel * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * Pi * u2);
        }
        const float f = static_cast<float>(a);
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        PutBigEndian(trace, 240 + 4 * static_cast<size_t>(s), bits, 4);
      }
      out.write(trace.data(), trace.size());
    }
    this->UpdateProgress(static_cast<double>(i + 1) / this->Lines[0]);
  }
  out.close();
  if (!out)
  {
    std::remove(tmp.c_str());
    return fail("writing " + tmp + " failed: " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), name.c_str()) != 0)
  {
    const std::string error = std::strerror(errno);
    std::remove(tmp.c_str());
    return fail("cannot rename " + tmp + " to it: " + error);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkSyntheticSurveyWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "Lines: " << this->Lines[0] << " " << this->Lines[1] << "\n";
  os << indent << "Bins: " << this->Bins[0] << " " << this->Bins[1] << "\n";
  os << indent << "FirstInline: " << this->FirstInline << "\n";
  os << indent << "FirstCrossline: " << this->FirstCrossline << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "SampleInterval: " << this->SampleInterval << "\n";
  os << indent << "StartTime: " << this->StartTime << "\n";
  os << indent << "Impedances:";
  for (double z : this->Impedances)
    os << " " << z;
  os << "\n";
  os << indent << "PeakFrequency: " << this->PeakFrequency << "\n";
  os << indent << "NoiseLevel: " << this->NoiseLevel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "CoordinateScalar: " << this->CoordinateScalar << "\n";
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPreIntegrationTable.h"

#include <algorithm>
#include <cmath>

namespace strata
{

namespace
{
constexpr double MaxOpacity = 1.0 - 1e-6; // see OpacityToExtinction()
constexpr double MaxTau = 1e30;           // keeps T, K and d tau finite in float
constexpr double MaxColorValue = 1e6;
constexpr double MaxStep = 1e30; // d tau <= 1e60: no inf * 0 in the quadrature
// Light from behind an optical depth of 40 is exp(-40) = 4e-18 of its colour: below double
// rounding of results <= 1, so integration stops there.
constexpr double CutoffDepth = 40.0;
// Largest optical depth of a quadrature sub-piece of width h. There |D'| <= 0.5 / h and
// |D''| <= 0.5 / h^2, so h^8 |d^8/du^8 exp(-D)| <= 23 (Hermite expansion) and 4-point
// Gauss-Legendre gets the mean opacity within 23 * 5.6e-10 = 1.3e-8.
constexpr double MaxSubDepth = 0.5;
// 4-point Gauss-Legendre on [0, 1].
constexpr double GLX[4] = { 0.0694318442029737,
  0.3300094782075719,
  0.6699905217924281,
  0.9305681557970263 };
constexpr double GLW[4] = { 0.1739274225687269,
  0.3260725774312731,
  0.3260725774312731,
  0.1739274225687269 };

double Sanitize(double v, double maxValue)
{
  return v > 0.0 ? std::min(v, maxValue) : 0.0; // NaN -> 0
}

/**
 * Adds the emission of one piece on which tau and colour are linear, from (t0, c0) at its front
 * to (t1, c1) at its back; len turns tau into optical depth (d times the piece's share of w).
 * depth: optical depth from the segment's front to the piece's front, advanced past the piece.
 * With A(u) = 1 - exp(-D(u)) the opacity from the piece's front, integration by parts gives
 * int c dA = c0 mean(A) + c1 (A(1) - mean(A)) for linear c: no cancellation, never negative.
 */
void AddPiece(double t0,
  double t1,
  const double* c0,
  const double* c1,
  double len,
  double& depth,
  double* rgb)
{
  const double front = depth;
  const double pieceDepth = 0.5 * (t0 + t1) * len;
  depth = front + pieceDepth;
  if (!(pieceDepth > 0.0) || front > CutoffDepth)
  {
    return;
  }
  const int n = static_cast<int>(std::min(std::ceil(std::max(t0, t1) * len / MaxSubDepth), 1e6));
  const bool flat = c0[0] == c1[0] && c0[1] == c1[1] && c0[2] == c1[2];
  const double rate0 = t0 * len;
  const double slope = (t1 - t0) * len;
  double d = front;
  for (int k = 0; k < n && d <= CutoffDepth; ++k)
  {
    const double x0 = static_cast<double>(k) / n;
    const double x1 = k + 1 == n ? 1.0 : static_cast<double>(k + 1) / n;
    const double h = x1 - x0;
    const double rate = rate0 + slope * x0; // D(u) = rate u + slope u^2 / 2 on [0, h]
    const double subDepth = h * (rate + 0.5 * slope * h);
    const double aEnd = -std::expm1(-subDepth);
    const double tr = std::exp(-d);
    if (flat)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] += tr * c0[c] * aEnd;
      }
    }
    else
    {
      double aMean = 0.0;
      for (int q = 0; q < 4; ++q)
      {
        const double u = GLX[q] * h;
        aMean -= GLW[q] * std::expm1(-u * (rate + 0.5 * slope * u));
      }
      for (int c = 0; c < 3; ++c)
      {
        const double ca = c0[c] + (c1[c] - c0[c]) * x0;
        const double cb = c0[c] + (c1[c] - c0[c]) * x1;
        rgb[c] += tr * (ca * aMean + cb * std::max(aEnd - aMean, 0.0));
      }
    }
    d += subDepth;
  }
}

std::uint64_t Fnv1a(std::uint64_t hash, const void* data, size_t bytes)
{
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i)
  {
    hash = (hash ^ p[i]) * 1099511628211ull;
  }
  return hash;
}
}

struct PreIntegrationTable::Piece
{
  double Length; // share of its table cell
  double Tau0, Tau1;
  double C0[3], C1[3];
};

PreIntegrationTable::PreIntegrationTable()
{
  const double rgb[6] = { 1, 1, 1, 1, 1, 1 };
  const double tau[2] = { 0, 0 };
  this->SetTransferFunction(0.0, 1.0, 2, rgb, tau);
}

double PreIntegrationTable::OpacityToExtinction(double alpha, double unitDistance)
{
  const double a = std::min(Sanitize(alpha, 1.0), MaxOpacity);
  return unitDistance > 0.0 ? -std::log1p(-a) / unitDistance : 0.0;
}

bool PreIntegrationTable::SetTransferFunction(double scalarMin,
  double scalarMax,
  int n,
  const double* rgb,
  const double* tau)
{
  if (n < 1 || !rgb || !tau || !std::isfinite(scalarMin) || !std::isfinite(scalarMax) ||
      !(scalarMin < scalarMax) || !std::isfinite(scalarMax - scalarMin))
  {
    return false;
  }
  const int entries = std::max(n, 2); // a constant TF is two equal entries
  std::vector<double> newRgb(3 * entries);
  std::vector<double> newTau(entries);
  for (int j = 0; j < entries; ++j)
  {
    const int src = std::min(j, n - 1);
    for (int c = 0; c < 3; ++c)
    {
      newRgb[3 * j + c] = Sanitize(rgb[3 * src + c], MaxColorValue);
    }
    newTau[j] = Sanitize(tau[src], MaxTau);
  }
  if (scalarMin == this->ScalarMin && scalarMax == this->ScalarMax && newRgb == this->Rgb &&
      newTau == this->Tau)
  {
    return true;
  }
  this->ScalarMin = scalarMin;
  this->ScalarMax = scalarMax;
  this->Rgb = std::move(newRgb);
  this->Tau = std::move(newTau);
  this->MaxColor = *std::max_element(this->Rgb.begin(), this->Rgb.end());
  this->FullTableValid = false;
  this->IntegralTableValid = false;
  return true;
}

void PreIntegrationTable::SetTableSize(int m)
{
  m = std::min(std::max(m, 2), 4096);
  if (m != this->TableSize)
  {
    this->TableSize = m;
    this->FullTableValid = false;
    this->IntegralTableValid = false;
  }
}

void PreIntegrationTable::SetStepLength(double d)
{
  d = std::min(d, MaxStep);
  if (d >= 0.0 && d != this->StepLength)
  {
    this->StepLength = d;
    this->FullTableValid = false;
  }
}

std::uint64_t PreIntegrationTable::GetHash() const
{
  std::uint64_t h = 14695981039346656037ull;
  h = Fnv1a(h, &this->ScalarMin, sizeof(double));
  h = Fnv1a(h, &this->ScalarMax, sizeof(double));
  h = Fnv1a(h, this->Rgb.data(), this->Rgb.size() * sizeof(double));
  h = Fnv1a(h, this->Tau.data(), this->Tau.size() * sizeof(double));
  h = Fnv1a(h, &this->TableSize, sizeof(int));
  return Fnv1a(h, &this->StepLength, sizeof(double));
}

double PreIntegrationTable::Normalize(double s) const
{
  const double x = (s - this->ScalarMin) / (this->ScalarMax - this->ScalarMin);
  return x > 0.0 ? std::min(x, 1.0) : 0.0; // NaN -> 0
}

float PreIntegrationTable::NormalizeF(float s) const
{
  // The shader's uniforms: float minimum and float inverse range.
  const float x = (s - static_cast<float>(this->ScalarMin)) *
                  static_cast<float>(1.0 / (this->ScalarMax - this->ScalarMin));
  return x > 0.0f ? std::min(x, 1.0f) : 0.0f;
}

void PreIntegrationTable::EvaluateTF(double x, double rgb[3], double& tau) const
{
  const int n = this->GetNumberOfEntries();
  const double p = x * (n - 1);
  const int j = std::min(static_cast<int>(p), n - 2);
  const double f = p - j;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = this->Rgb[3 * j + c] + f * (this->Rgb[3 * j + 3 + c] - this->Rgb[3 * j + c]);
  }
  tau = this->Tau[j] + f * (this->Tau[j + 1] - this->Tau[j]);
}

std::vector<float> PreIntegrationTable::GetTransferFunctionTable() const
{
  const int n = this->GetNumberOfEntries();
  std::vector<float> table(4 * static_cast<size_t>(n));
  for (int j = 0; j < n; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      table[4 * j + c] = static_cast<float>(this->Rgb[3 * j + c]);
    }
    table[4 * j + 3] = static_cast<float>(this->Tau[j]);
  }
  return table;
}

std::array<double, 4> PreIntegrationTable::Classify(double s, double d) const
{
  double rgb[3];
  double tau;
  this->EvaluateTF(this->Normalize(s), rgb, tau);
  const double alpha = d > 0.0 ? -std::expm1(-d * tau) : 0.0;
  return { rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha };
}

std::array<double, 4> PreIntegrationTable::Integrate(double sf, double sb, double d) const
{
  const double xf = this->Normalize(sf);
  const double xb = this->Normalize(sb);
  if (xf == xb || !(d > 0.0))
  {
    return this->Classify(sf, d);
  }
  d = std::min(d, MaxStep);
  const int n = this->GetNumberOfEntries();
  const double a = xf * (n - 1); // TF index coordinates
  const double b = xb * (n - 1);
  double rgb[3] = { 0, 0, 0 };
  double depth = 0.0;
  double c0[3];
  double t0;
  this->EvaluateTF(xf, c0, t0);
  double w0 = 0.0;
  // Pieces end at the TF entries strictly between a and b, in ray order; the only division by
  // b - a places them, so a tiny b - a cannot blow up.
  const int step = b > a ? 1 : -1;
  int j = b > a ? static_cast<int>(std::floor(a)) + 1 : static_cast<int>(std::ceil(a)) - 1;
  for (; (b > a ? j < b : j > b) && depth <= CutoffDepth; j += step)
  {
    const double w = std::min(std::max((j - a) / (b - a), w0), 1.0);
    AddPiece(t0, this->Tau[j], c0, &this->Rgb[3 * j], d * (w - w0), depth, rgb);
    std::copy_n(&this->Rgb[3 * j], 3, c0);
    t0 = this->Tau[j];
    w0 = w;
  }
  if (depth <= CutoffDepth)
  {
    double c1[3];
    double t1;
    this->EvaluateTF(xb, c1, t1);
    AddPiece(t0, t1, c0, c1, d * (1.0 - w0), depth, rgb);
  }
  const double alpha = -std::expm1(-depth);
  return { rgb[0], rgb[1], rgb[2], alpha };
}

std::vector<PreIntegrationTable::Piece> PreIntegrationTable::BuildPieces(
  std::vector<int>& cellStart) const
{
  // Cell m = [x_m, x_{m+1}] of the table, cut at the TF entries inside it.
  const long long m1 = this->TableSize - 1;
  const long long n1 = this->GetNumberOfEntries() - 1;
  std::vector<Piece> pieces;
  pieces.reserve(static_cast<size_t>(m1 + n1));
  cellStart.assign(static_cast<size_t>(m1 + 1), 0);
  for (long long m = 0; m < m1; ++m)
  {
    cellStart[m] = static_cast<int>(pieces.size());
    Piece p;
    this->EvaluateTF(static_cast<double>(m) / static_cast<double>(m1), p.C0, p.Tau0);
    double f0 = 0.0;
    // Entry j lies strictly inside the cell iff m n1 < j m1 < (m + 1) n1 (exact integers).
    for (long long j = m * n1 / m1 + 1; j * m1 < (m + 1) * n1; ++j)
    {
      const double f = static_cast<double>(j * m1 - m * n1) / static_cast<double>(n1);
      p.Length = f - f0;
      p.Tau1 = this->Tau[j];
      std::copy_n(&this->Rgb[3 * j], 3, p.C1);
      pieces.push_back(p);
      p.Tau0 = p.Tau1;
      std::copy_n(p.C1, 3, p.C0);
      f0 = f;
    }
    p.Length = 1.0 - f0;
    this->EvaluateTF(static_cast<double>(m + 1) / static_cast<double>(m1), p.C1, p.Tau1);
    pieces.push_back(p);
  }
  cellStart[m1] = static_cast<int>(pieces.size());
  return pieces;
}

bool PreIntegrationTable::UpdateFullTable()
{
  if (this->FullTableValid)
  {
    return false;
  }
  const int m = this->TableSize;
  const int cells = m - 1;
  const double d = this->StepLength;
  std::vector<int> cellStart;
  const std::vector<Piece> pieces = this->BuildPieces(cellStart);
  std::vector<double> cellTau(cells, 0.0); // int tau over the cell / cell width
  for (int c = 0; c < cells; ++c)
  {
    for (int p = cellStart[c]; p < cellStart[c + 1]; ++p)
    {
      cellTau[c] += pieces[p].Length * 0.5 * (pieces[p].Tau0 + pieces[p].Tau1);
    }
  }

  this->FullTable.assign(4 * static_cast<size_t>(m) * m, 0.0f);
  auto store = [&](int iF, int iB, const double* rgb, double alpha)
  {
    float* e = &this->FullTable[4 * (static_cast<size_t>(iB) * m + iF)];
    for (int c = 0; c < 3; ++c)
    {
      e[c] = static_cast<float>(std::max(rgb[c], 0.0));
    }
    e[3] = static_cast<float>(alpha);
  };
  for (int i = 0; i < m; ++i) // the s_b -> s_f limit: post-classification
  {
    double rgb[3];
    double tau;
    this->EvaluateTF(static_cast<double>(i) / cells, rgb, tau);
    const double alpha = -std::expm1(-d * tau);
    for (double& c : rgb)
    {
      c *= alpha;
    }
    store(i, i, rgb, alpha);
  }

  // A segment from x_i to x_{i+delta} crosses delta cells with the same kappa = d / delta per
  // cell width. g(c): cell c's own emission with its own absorption, from its entry side;
  // S(i): everything from sample i to the end of the range in ray order, composited. A segment is
  // then S(i) minus what lies behind it, attenuated by the segment: O(M (M + N)) instead of the
  // O(M^2 (M + N)) of integrating every pair. S <= max colour, so the difference loses
  // nothing significant.
  std::vector<double> gF(3 * cells), gB(3 * cells), t(cells);
  std::vector<double> sF(3 * static_cast<size_t>(m)), sB(3 * static_cast<size_t>(m));
  std::vector<double> window(cells, 0.0); // sum of cellTau over the delta cells from i
  for (int delta = 1; delta < m; ++delta)
  {
    const double kappa = d / delta;
    for (int c = 0; c < cells; ++c)
    {
      t[c] = std::exp(-kappa * cellTau[c]);
      double depth = 0.0;
      double* f = &gF[3 * c];
      f[0] = f[1] = f[2] = 0.0;
      for (int p = cellStart[c]; p < cellStart[c + 1]; ++p)
      {
        const Piece& q = pieces[p];
        AddPiece(q.Tau0, q.Tau1, q.C0, q.C1, kappa * q.Length, depth, f);
      }
      depth = 0.0;
      double* b = &gB[3 * c];
      b[0] = b[1] = b[2] = 0.0;
      for (int p = cellStart[c + 1] - 1; p >= cellStart[c]; --p)
      {
        const Piece& q = pieces[p];
        AddPiece(q.Tau1, q.Tau0, q.C1, q.C0, kappa * q.Length, depth, b);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      sF[3 * cells + k] = 0.0;
      sB[k] = 0.0;
    }
    for (int i = cells - 1; i >= 0; --i)
    {
      for (int k = 0; k < 3; ++k)
      {
        sF[3 * i + k] = gF[3 * i + k] + t[i] * sF[3 * (i + 1) + k];
      }
    }
    for (int j = 1; j < m; ++j)
    {
      for (int k = 0; k < 3; ++k)
      {
        sB[3 * j + k] = gB[3 * (j - 1) + k] + t[j - 1] * sB[3 * (j - 1) + k];
      }
    }
    for (int i = 0; i + delta < m; ++i)
    {
      // Sums of non-negative terms, not prefix differences: exact to rounding however large
      // tau is elsewhere in the range.
      window[i] += cellTau[i + delta - 1];
      const double depth = kappa * window[i];
      const double tr = std::exp(-depth);
      const double alpha = -std::expm1(-depth);
      const int j = i + delta;
      double rgb[3];
      for (int k = 0; k < 3; ++k)
      {
        rgb[k] = sF[3 * i + k] - tr * sF[3 * j + k];
      }
      store(i, j, rgb, alpha);
      for (int k = 0; k < 3; ++k)
      {
        rgb[k] = sB[3 * j + k] - tr * sB[3 * i + k];
      }
      store(j, i, rgb, alpha);
    }
  }
  this->FullTableValid = true;
  ++this->FullBuildCount;
  return true;
}

bool PreIntegrationTable::UpdateIntegralTable()
{
  if (this->IntegralTableValid)
  {
    return false;
  }
  const int m = this->TableSize;
  std::vector<int> cellStart;
  const std::vector<Piece> pieces = this->BuildPieces(cellStart);
  this->IntegralTable.assign(4 * static_cast<size_t>(m), 0.0f);
  double sum[4] = { 0, 0, 0, 0 }; // K_r, K_g, K_b, T
  for (int c = 0; c + 1 < m; ++c)
  {
    for (int p = cellStart[c]; p < cellStart[c + 1]; ++p)
    {
      // Exact integrals of linear tau and of the product of two linear functions.
      const Piece& q = pieces[p];
      const double len = q.Length / (m - 1);
      for (int k = 0; k < 3; ++k)
      {
        sum[k] +=
          len *
          (2.0 * q.C0[k] * q.Tau0 + q.C0[k] * q.Tau1 + q.C1[k] * q.Tau0 + 2.0 * q.C1[k] * q.Tau1) /
          6.0;
      }
      sum[3] += len * 0.5 * (q.Tau0 + q.Tau1);
    }
    for (int k = 0; k < 4; ++k)
    {
      this->IntegralTable[4 * (c + 1) + k] = static_cast<float>(sum[k]);
    }
  }
  this->IntegralTableValid = true;
  ++this->IntegralBuildCount;
  return true;
}

std::array<float, 4> PreIntegrationTable::LookupFullTable(float sf, float sb) const
{
  std::array<float, 4> r = { 0, 0, 0, 0 };
  const int m = this->TableSize;
  if (this->FullTable.size() != 4 * static_cast<size_t>(m) * m)
  {
    return r;
  }
  const float pf = this->NormalizeF(sf) * static_cast<float>(m - 1);
  const float pb = this->NormalizeF(sb) * static_cast<float>(m - 1);
  const int i = std::min(static_cast<int>(pf), m - 2);
  const int j = std::min(static_cast<int>(pb), m - 2);
  const float fx = pf - static_cast<float>(i);
  const float fy = pb - static_cast<float>(j);
  const float* t00 = &this->FullTable[4 * (static_cast<size_t>(j) * m + i)];
  const float* t10 = t00 + 4;
  const float* t01 = t00 + 4 * static_cast<size_t>(m);
  const float* t11 = t01 + 4;
  for (int k = 0; k < 4; ++k)
  {
    // GLSL mix(a, b, t) = a (1 - t) + b t
    const float lo = t00[k] * (1.0f - fx) + t10[k] * fx;
    const float hi = t01[k] * (1.0f - fx) + t11[k] * fx;
    r[k] = lo * (1.0f - fy) + hi * fy;
  }
  return r;
}

std::array<float, 4> PreIntegrationTable::LookupTwoIntegral(float sf, float sb, float d) const
{
  std::array<float, 4> r = { 0, 0, 0, 0 };
  const int m = this->TableSize;
  if (this->IntegralTable.size() != 4 * static_cast<size_t>(m))
  {
    return r;
  }
  d = d > 0.0f ? d : 0.0f;
  const float h = 1.0f / static_cast<float>(m - 1);
  const float xf = this->NormalizeF(sf);
  const float xb = this->NormalizeF(sb);
  const float w = std::max(std::abs(xb - xf), h);
  const float lo = std::min(std::max(0.5f * (xf + xb) - 0.5f * w, 0.0f), 1.0f - w);
  const float hi = std::min(lo + w, 1.0f);
  auto fetch = [&](float x, float* v)
  {
    const float p = x * static_cast<float>(m - 1);
    const int i = std::min(static_cast<int>(p), m - 2);
    const float f = p - static_cast<float>(i);
    const float* a = &this->IntegralTable[4 * static_cast<size_t>(i)];
    for (int k = 0; k < 4; ++k)
    {
      v[k] = a[k] * (1.0f - f) + a[k + 4] * f;
    }
  };
  float vLo[4], vHi[4];
  fetch(lo, vLo);
  fetch(hi, vHi);
  const float width = hi - lo; // >= h up to rounding, never 0
  const float tau = std::max((vHi[3] - vLo[3]) / width, 0.0f);
  const float x = d * tau;
  float alpha, dFactor; // dFactor = d (1 - exp(-X)) / X
  if (x < 0.01f)
  {
    const float f = 1.0f - x * (0.5f - x / 6.0f);
    alpha = x * f;
    dFactor = d * f;
  }
  else
  {
    alpha = 1.0f - std::exp(-x);
    dFactor = alpha / tau;
  }
  const float kMax = static_cast<float>(this->MaxColor) * tau;
  for (int k = 0; k < 3; ++k)
  {
    const float kMean = std::min(std::max((vHi[k] - vLo[k]) / width, 0.0f), kMax);
    r[k] = kMean * dFactor;
  }
  r[3] = alpha;
  return r;
}
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMultiVolumeReferenceIntegrator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <thread>

namespace strata
{

namespace
{
// Table opacities are clamped here so that tau stays finite (the class comment's convention).
constexpr double MaxOpacity = 1.0 - 1e-6;

// c0 + c1 u + c2 u^2 + c3 u^3: a scalar along a ray inside one trilinear cell.
using Poly = std::array<double, 4>;

double Horner(const Poly& p, double u)
{
  return ((p[3] * u + p[2]) * u + p[1]) * u + p[0];
}

// p + (q - p) * (y0 + ey u), truncated to degree 3 (never needed beyond).
Poly LerpPoly(const Poly& p, const Poly& q, double y0, double ey)
{
  Poly r;
  for (int k = 0; k < 4; ++k)
  {
    r[k] = p[k] + (q[k] - p[k]) * y0 + (k > 0 ? (q[k - 1] - p[k - 1]) * ey : 0.0);
  }
  return r;
}

// Roots of a u^2 + b u + c in (lo, hi), in the numerically stable form.
int QuadraticRoots(double a, double b, double c, double lo, double hi, double roots[2])
{
  int n = 0;
  auto keep = [&](double r)
  {
    if (r > lo && r < hi)
    {
      roots[n++] = r;
    }
  };
  if (a == 0.0)
  {
    if (b != 0.0)
    {
      keep(-c / b);
    }
    return n;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0)
  {
    return 0;
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (q != 0.0)
  {
    keep(q / a);
    keep(c / q);
  }
  else
  {
    keep(0.0); // b == 0 and disc == 0: double root at 0
  }
  if (n == 2 && roots[0] > roots[1])
  {
    std::swap(roots[0], roots[1]);
  }
  return n;
}

// Appends every u in (0, len) where the cubic p crosses the value v (sign changes only: a
// tangency leaves the classification on one side of its kink, so it stays smooth).
// Monotone intervals between critical points, then bisection to full precision.
void AppendCrossings(const Poly& p, double v, double len, std::vector<double>& out)
{
  double knots[4];
  int nk = 0;
  knots[nk++] = 0.0;
  double cps[2];
  const int ncp = QuadraticRoots(3.0 * p[3], 2.0 * p[2], p[1], 0.0, len, cps);
  for (int k = 0; k < ncp; ++k)
  {
    knots[nk++] = cps[k];
  }
  knots[nk++] = len;
  for (int k = 0; k + 1 < nk; ++k)
  {
    double lo = knots[k], hi = knots[k + 1];
    double flo = Horner(p, lo) - v;
    const double fhi = Horner(p, hi) - v;
    if (k > 0 && flo == 0.0)
    {
      out.push_back(lo); // an inflection exactly on the node value
      continue;
    }
    if (!(flo * fhi < 0.0))
    {
      continue;
    }
    for (int it = 0; it < 200; ++it)
    {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi)
      {
        break;
      }
      const double fm = Horner(p, mid) - v;
      if (fm == 0.0)
      {
        lo = hi = mid;
        break;
      }
      if ((fm < 0.0) == (flo < 0.0))
      {
        lo = mid;
        flo = fm;
      }
      else
      {
        hi = mid;
      }
    }
    out.push_back(0.5 * (lo + hi));
  }
}

// exp(-x) and 1 - exp(-x) for x >= 0, both to a few ulp: the series below 0.1 (the first term
// left out is < 3e-16 of the sum), 1 - exp(-x) above (relative error < 1.2e-15; 6e-16 measured
// against long double expm1 over [1e-12, 50]). glibc's expm1 costs about three exps, and this
// runs once per step.
void Attenuation(double x, double& transmitted, double& absorbed)
{
  transmitted = std::exp(-x);
  if (x < 0.1)
  {
    // x (1 - x/2 (1 - x/3 (... (1 - x/9)))), with reciprocals (no division chain)
    static constexpr double inv[10] = {
      0.0, 1.0, 1.0 / 2, 1.0 / 3, 1.0 / 4, 1.0 / 5, 1.0 / 6, 1.0 / 7, 1.0 / 8, 1.0 / 9
    };
    double sum = 1.0;
    for (int k = 9; k >= 2; --k)
    {
      sum = 1.0 - x * inv[k] * sum;
    }
    absorbed = x * sum;
  }
  else
  {
    absorbed = 1.0 - transmitted;
  }
}

bool Invert3x3(const double m[9], double inv[9])
{
  const double c00 = m[4] * m[8] - m[5] * m[7];
  const double c01 = m[5] * m[6] - m[3] * m[8];
  const double c02 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
  {
    return false;
  }
  const double r = 1.0 / det;
  inv[0] = c00 * r;
  inv[1] = (m[2] * m[7] - m[1] * m[8]) * r;
  inv[2] = (m[1] * m[5] - m[2] * m[4]) * r;
  inv[3] = c01 * r;
  inv[4] = (m[0] * m[8] - m[2] * m[6]) * r;
  inv[5] = (m[2] * m[3] - m[0] * m[5]) * r;
  inv[6] = c02 * r;
  inv[7] = (m[1] * m[6] - m[0] * m[7]) * r;
  inv[8] = (m[0] * m[4] - m[1] * m[3]) * r;
  for (int k = 0; k < 9; ++k)
  {
    if (!std::isfinite(inv[k]))
    {
      return false;
    }
  }
  return true;
}

void MulVec3(const double m[9], const double v[3], double out[3])
{
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m[3 * r] * v[0] + m[3 * r + 1] * v[1] + m[3 * r + 2] * v[2];
  }
}
}

class MultiVolumeReferenceIntegrator::vtkInternals
{
public:
  struct Table;
  struct Vol;
  bool SetGeometry(const Volume& in, Vol& v, const char*& error);
  static void BuildTable(const TransferFunction& tf, Table& t);
  void SetDerivativeBounds(Vol& v);
  // A tabulated transfer function and the bounds its pieces put on tau and emission.
  struct Table
  {
    double SMin = 0.0;
    double Scale = 0.0; ///< (N - 1) / (smax - smin)
    int N = 1;
    double UnitDistance = 1.0;
    std::vector<double> Alpha; ///< clamped to MaxOpacity
    std::vector<double> Color; ///< 3 N
    std::vector<double> Kinks; ///< node scalars where a slope changes, increasing
    // Bounds over s: tau, |dtau/ds|, |d2tau/ds2| and the same for c tau (largest channel).
    double Tau[3] = { 0.0, 0.0, 0.0 };
    double Emission[3] = { 0.0, 0.0, 0.0 };
    double ColorMax = 0.0;
    std::vector<double> Gradient; ///< gradient opacity entries, empty for none
    double GradientMin = 0.0, GradientScale = 0.0;

    /// The gradient opacity at magnitude g (piecewise linear, clamped).
    double GradientOpacity(double g) const
    {
      const int n = static_cast<int>(this->Gradient.size());
      if (n < 2)
        return n == 1 ? this->Gradient[0] : 1.0;
      const double x =
        std::min(std::max((g - this->GradientMin) * this->GradientScale, 0.0), n - 1.0);
      const int j = std::min(static_cast<int>(x), n - 2);
      return this->Gradient[j] + (x - j) * (this->Gradient[j + 1] - this->Gradient[j]);
    }

    void Classify(double s, double& tau, double rgb[3]) const
    {
      tau = -std::log1p(-this->Lookup(s, rgb)) / this->UnitDistance;
    }

    /// The (clamped) table opacity and colour at s.
    double Lookup(double s, double rgb[3]) const
    {
      int j = 0;
      double f = 0.0;
      if (this->N > 1)
      {
        const double x = (s - this->SMin) * this->Scale;
        if (x >= this->N - 1)
        {
          j = this->N - 2;
          f = 1.0;
        }
        else if (x > 0.0) // NaN and below the range: first entry
        {
          j = std::min(static_cast<int>(x), this->N - 2);
          f = x - j;
        }
      }
      const double* a = &this->Alpha[j];
      const double* c = &this->Color[3 * j];
      double alpha = a[0];
      if (this->N > 1)
      {
        alpha += f * (a[1] - a[0]);
        for (int k = 0; k < 3; ++k)
        {
          rgb[k] = c[k] + f * (c[k + 3] - c[k]);
        }
      }
      else
      {
        std::copy(c, c + 3, rgb);
      }
      return alpha;
    }

    /// s over the table's range, (s - smin) / (smax - smin).
    double Normalized(double s) const
    {
      return this->N > 1 ? (s - this->SMin) * this->Scale / (this->N - 1) : 0.0;
    }
  };

  struct Vol
  {
    int Dims[3] = { 1, 1, 1 };
    bool Linear = true;
    std::vector<double> D;
    std::vector<float> F;
    double A[9];    ///< index -> local world, A = M3 Direction diag(spacing)
    double Ainv[9]; ///< local world -> index
    double B[3];    ///< local world position of index (0, 0, 0)
    double Lo[3], Hi[3];
    Table Tf;
    // World-unit bounds along any ray: tau, tau', tau'', E, E', E''.
    double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
    Blend Mode = Blend::Composite;
    std::vector<double> Iso;
    double AverageRange[2] = { -1.0e300, 1.0e300 };
    bool Cropping = false;
    double CropPlanes[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
    int CropFlags = 0;
    Components Comp = Components::One;
    int NC = 1;               ///< components per point
    std::vector<Table> Extra; ///< Independent: the tables of components 1, 2, ...
    double Weights[4] = { 1.0, 1.0, 1.0, 1.0 };
    double ColorLo[3] = { 0.0, 0.0, 0.0 }, ColorScale[3] = { 1.0, 1.0, 1.0 }; ///< RGBA

    /// The table whose kinks component c's scalar crosses (null: its use has none).
    const Table* KinkTable(int c) const
    {
      switch (this->Comp)
      {
        case Components::Independent:
          return c == 0 ? &this->Tf : &this->Extra[c - 1];
        case Components::RGBA:
          return c == 3 ? &this->Tf : nullptr;
        default: // one scalar; colour and opacity both read Tf
          return &this->Tf;
      }
    }

    /// Extinction and colour of the medium at the components' values s (the class comment).
    void Classify(const double s[4], double& tau, double rgb[3]) const
    {
      switch (this->Comp)
      {
        case Components::One:
          this->Tf.Classify(s[0], tau, rgb);
          return;
        case Components::ColorOpacity:
        case Components::RGBA:
        {
          double unused[3];
          const int opacity = this->Comp == Components::RGBA ? 3 : 1;
          tau = -std::log1p(-this->Tf.Lookup(s[opacity], unused)) / this->Tf.UnitDistance;
          if (this->Comp == Components::ColorOpacity)
            this->Tf.Lookup(s[0], rgb);
          for (int k = 0; this->Comp == Components::RGBA && k < 3; ++k)
            rgb[k] = std::min(std::max((s[k] - this->ColorLo[k]) * this->ColorScale[k], 0.0), 1.0);
          return;
        }
        case Components::Independent:
          break;
      }
      // sigma = sum_(w > 0) tau_i^2 / sum w_i tau_i, emission sum w_i c_i tau_i.
      double weighted = 0.0, squares = 0.0, e[3] = { 0.0, 0.0, 0.0 };
      for (int i = 0; i < this->NC; ++i)
      {
        double t, c[3];
        (i == 0 ? this->Tf : this->Extra[i - 1]).Classify(s[i], t, c);
        const double w = this->Weights[i];
        weighted += w * t;
        squares += w > 0.0 ? t * t : 0.0;
        for (int ch = 0; ch < 3; ++ch)
          e[ch] += w * c[ch] * t;
      }
      tau = weighted > 0.0 ? squares / weighted : 0.0;
      for (int ch = 0; ch < 3; ++ch)
        rgb[ch] = tau > 0.0 ? e[ch] / tau : 0.0;
    }

    /// Whether cropping shows the index point x.
    bool Shown(const double x[3]) const
    {
      if (!this->Cropping)
        return true;
      int region = 0;
      const int weight[3] = { 1, 3, 9 };
      for (int k = 0; k < 3; ++k)
        region += weight[k] * ((x[k] >= this->CropPlanes[2 * k] ? 1 : 0) +
                                (x[k] >= this->CropPlanes[2 * k + 1] ? 1 : 0));
      return ((this->CropFlags >> region) & 1) != 0;
    }

    bool Reduces() const
    {
      return this->Mode != Blend::Composite && this->Mode != Blend::IsoSurface;
    }

    /// Component c at index position x (trilinear or nearest, clamped at the borders).
    double Sample(const double x[3], int c = 0) const
    {
      int i0[3], i1[3];
      double f[3];
      for (int k = 0; k < 3; ++k)
      {
        const int n = this->Dims[k];
        const double xc = std::min(std::max(x[k], 0.0), n - 1.0);
        if (!this->Linear)
        {
          i0[k] = i1[k] = std::min(static_cast<int>(std::floor(xc + 0.5)), n - 1);
          f[k] = 0.0;
          continue;
        }
        i0[k] = std::min(static_cast<int>(std::floor(xc)), std::max(n - 2, 0));
        i1[k] = std::min(i0[k] + 1, n - 1);
        f[k] = xc - i0[k];
      }
      double v = 0.0;
      for (int m = 0; m < 8; ++m)
      {
        double w = 1.0;
        for (int k = 0; k < 3; ++k)
          w *= (m >> k) & 1 ? f[k] : 1.0 - f[k];
        if (w != 0.0)
          v += w * this->Value(
                     (m & 1) ? i1[0] : i0[0], (m & 2) ? i1[1] : i0[1], (m & 4) ? i1[2] : i0[2], c);
      }
      return v;
    }

    double Value(int i, int j, int k, int c = 0) const
    {
      const size_t idx =
        (static_cast<size_t>(i) +
          this->Dims[0] * (static_cast<size_t>(j) + this->Dims[1] * static_cast<size_t>(k))) *
          this->NC +
        c;
      return this->F.empty() ? this->D[idx] : static_cast<double>(this->F[idx]);
    }
  };

  // A volume the current ray crosses.
  struct Active
  {
    const Vol* V;
    double Te, Tx;
    double P0[3], DI[3]; ///< index position at t = 0 and per unit t
    double Chord;        ///< longest chord of one cell along the ray, in t
  };
  // A volume covering the current piece, with its scalars (per component) along the piece.
  struct Cover
  {
    const Vol* V;
    const Active* A;
    Poly S[4];
    double SLo[4], SHi[4]; ///< range of the cell's corners
  };
  // Something composited at one place along the ray: a reduced volume's layer, a surface.
  struct Layer
  {
    double T;
    double C[4]; ///< premultiplied
    bool operator<(const Layer& o) const { return this->T < o.T; }
  };
  struct Workspace
  {
    std::vector<Layer> Layers;
    std::vector<Layer> Surfaces;
    std::vector<Active> Act;
    std::vector<double> Breaks;
    std::vector<double> Sub;
    std::vector<Cover> Cov;
  };

  std::vector<Vol> Volumes;
  std::vector<Surface> Surfaces; ///< world coordinates
  std::vector<CrossingFunction> CrossingFunctions;
  double LocalOrigin[3] = { 0.0, 0.0, 0.0 };
  double SmallestVoxel = 0.0;
  double StepFraction = 1.0 / 16.0;
  double TerminationTransmittance = 1e-14;
  int NumberOfThreads = 0;
  std::string LastError;

  double StepLength() const { return this->StepFraction * this->SmallestVoxel; }

  std::array<double, 4> Integrate(const double o[3],
    const double d[3],
    double t0,
    double t1,
    Workspace& ws) const;
  void BuildCover(const Active& a, double ta, double tm, Cover& c) const;
  Layer Reduce(const Active& a, double dn) const;
  void ClipSurfaces(const double o[3],
    const double d[3],
    double t0,
    double t1,
    Workspace& ws) const;
  void Clip(const double o[3], const double d[3], double t0, double t1, double dn, Workspace& ws)
    const;
  void AppendSurfaces(const Cover& c, double len, Workspace& ws) const;
  void AppendKinks(const Cover& c, int comp, double len, Workspace& ws) const;
  double GradientTau(const Cover& c, double t, double s, double rgb[3]) const;
};

// Extinction of a gradient-opacity volume at ray parameter t (scalar s there): alpha scaled by
// the function of |grad s|, central differences of the interpolant one voxel apart, to world by
// the transpose of the world -> index matrix.
double MultiVolumeReferenceIntegrator::vtkInternals::GradientTau(const Cover& c,
  double t,
  double s,
  double rgb[3]) const
{
  const Vol& v = *c.V;
  const double x[3] = {
    c.A->P0[0] + c.A->DI[0] * t, c.A->P0[1] + c.A->DI[1] * t, c.A->P0[2] + c.A->DI[2] * t
  };
  double gi[3];
  for (int k = 0; k < 3; ++k)
  {
    double xp[3] = { x[0], x[1], x[2] }, xm[3] = { x[0], x[1], x[2] };
    xp[k] += 1.0;
    xm[k] -= 1.0;
    gi[k] = 0.5 * (v.Sample(xp) - v.Sample(xm));
  }
  double g2 = 0.0;
  for (int j = 0; j < 3; ++j)
  {
    const double gw = v.Ainv[j] * gi[0] + v.Ainv[3 + j] * gi[1] + v.Ainv[6 + j] * gi[2];
    g2 += gw * gw;
  }
  const double alpha =
    v.Tf.Lookup(s, rgb) * std::min(std::max(v.Tf.GradientOpacity(std::sqrt(g2)), 0.0), 1.0);
  return -std::log1p(-std::min(alpha, MaxOpacity)) / v.Tf.UnitDistance;
}

// A Maximum, Minimum, Average or Additive volume alone over its chord [Te, Tx]: midpoint
// samples at most one step apart (see the class comment).
MultiVolumeReferenceIntegrator::vtkInternals::Layer
MultiVolumeReferenceIntegrator::vtkInternals::Reduce(const Active& a, double dn) const
{
  const Vol& v = *a.V;
  const double hT = this->StepLength() / dn;
  const int steps = std::max(1, static_cast<int>(std::ceil((a.Tx - a.Te) / hT)));
  const double dt = (a.Tx - a.Te) / steps;
  double best = 0.0, bestT = a.Te, sum = 0.0, length = 0.0;
  bool found = false;
  for (int k = 0; k < steps; ++k)
  {
    const double t = a.Te + (k + 0.5) * dt;
    const double x[3] = { a.P0[0] + a.DI[0] * t, a.P0[1] + a.DI[1] * t, a.P0[2] + a.DI[2] * t };
    if (!v.Shown(x))
      continue;
    const double s = v.Sample(x);
    if (!found || (v.Mode == Blend::Maximum ? s > best : s < best))
    {
      best = s;
      bestT = t;
      found = true;
    }
    if (v.Mode == Blend::Average && !(s >= v.AverageRange[0] && s <= v.AverageRange[1]))
      continue;
    double rgb[3];
    sum += v.Tf.Lookup(s, rgb) * v.Tf.Normalized(s) * dt * dn;
    length += dt * dn;
  }
  Layer layer{ a.Te, { 0.0, 0.0, 0.0, 0.0 } };
  if ((v.Mode == Blend::Maximum || v.Mode == Blend::Minimum) && found)
  {
    double rgb[3];
    const double alpha = v.Tf.Lookup(best, rgb);
    layer = { bestT, { rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha } };
  }
  else if (v.Mode == Blend::Additive || (v.Mode == Blend::Average && length > 0.0))
  {
    const double g = std::min(
      std::max(v.Mode == Blend::Additive ? sum / v.Tf.UnitDistance : sum / length, 0.0), 1.0);
    layer.C[0] = layer.C[1] = layer.C[2] = g;
    layer.C[3] = 1.0;
  }
  return layer;
}

// The surfaces of an IsoSurface volume's contours in one piece (u in (0, len)), at u.
void MultiVolumeReferenceIntegrator::vtkInternals::AppendSurfaces(const Cover& c,
  double len,
  Workspace& ws) const
{
  std::vector<double> roots;
  for (double value : c.V->Iso)
  {
    if (!(c.SHi[0] > c.SLo[0]) || value <= c.SLo[0] || value >= c.SHi[0])
      continue;
    roots.clear();
    AppendCrossings(c.S[0], value, len, roots);
    double rgb[3];
    const double alpha = c.V->Tf.Lookup(value, rgb);
    for (double u : roots)
      ws.Surfaces.push_back({ u, { rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha } });
  }
}

// Where component comp's (trilinear) scalar crosses a kink of the function it goes through.
void MultiVolumeReferenceIntegrator::vtkInternals::AppendKinks(const Cover& c,
  int comp,
  double len,
  Workspace& ws) const
{
  const Table* table = c.V->KinkTable(comp);
  if (!table || !(c.SHi[comp] > c.SLo[comp]))
    return;
  const std::vector<double>& kinks = table->Kinks;
  for (auto it = std::upper_bound(kinks.begin(), kinks.end(), c.SLo[comp]);
       it != kinks.end() && *it < c.SHi[comp];
       ++it)
    AppendCrossings(c.S[comp], *it, len, ws.Sub);
}

void MultiVolumeReferenceIntegrator::vtkInternals::BuildCover(const Active& a,
  double ta,
  double tm,
  Cover& c) const
{
  const Vol& v = *a.V;
  c.V = &v;
  c.A = &a;
  int i0[3], i1[3];
  double x0[3], ex[3];
  for (int k = 0; k < 3; ++k)
  {
    const int n = v.Dims[k];
    const double pm = a.P0[k] + a.DI[k] * tm;
    if (n == 1)
    {
      i0[k] = i1[k] = 0;
      x0[k] = ex[k] = 0.0;
    }
    else if (v.Linear)
    {
      i0[k] = std::min(std::max(static_cast<int>(std::floor(pm)), 0), n - 2);
      i1[k] = i0[k] + 1;
      x0[k] = a.P0[k] + a.DI[k] * ta - i0[k];
      ex[k] = a.DI[k];
    }
    else
    {
      i0[k] = i1[k] = std::min(std::max(static_cast<int>(std::floor(pm + 0.5)), 0), n - 1);
      x0[k] = ex[k] = 0.0;
    }
  }
  for (int comp = 0; comp < v.NC; ++comp)
  {
    if (!v.Linear)
    {
      const double s = v.Value(i0[0], i0[1], i0[2], comp);
      c.S[comp] = { s, 0.0, 0.0, 0.0 };
      c.SLo[comp] = c.SHi[comp] = s;
      continue;
    }
    double corner[8];
    for (int m = 0; m < 8; ++m)
    {
      corner[m] =
        v.Value((m & 1) ? i1[0] : i0[0], (m & 2) ? i1[1] : i0[1], (m & 4) ? i1[2] : i0[2], comp);
    }
    c.SLo[comp] = *std::min_element(corner, corner + 8);
    c.SHi[comp] = *std::max_element(corner, corner + 8);
    // Trilinear along the ray: lerp in x (degree 1), then y (2), then z (3).
    Poly px[4];
    for (int m = 0; m < 4; ++m)
    {
      const double a0 = corner[2 * m], a1 = corner[2 * m + 1];
      px[m] = { a0 + (a1 - a0) * x0[0], (a1 - a0) * ex[0], 0.0, 0.0 };
    }
    const Poly py0 = LerpPoly(px[0], px[1], x0[1], ex[1]);
    const Poly py1 = LerpPoly(px[2], px[3], x0[1], ex[1]);
    c.S[comp] = LerpPoly(py0, py1, x0[2], ex[2]);
  }
}

// Every box the ray crosses in [t0, t1], clipped exactly in the volume's index space: the
// active volumes with their box faces and cell planes as breaks, and the reduced volumes' layers.
void MultiVolumeReferenceIntegrator::vtkInternals::Clip(const double o[3],
  const double d[3],
  double t0,
  double t1,
  double dn,
  Workspace& ws) const
{
  ws.Act.clear();
  ws.Breaks.clear();
  ws.Layers.clear();
  for (const Vol& v : this->Volumes)
  {
    Active a;
    a.V = &v;
    double rel[3] = { o[0] - v.B[0], o[1] - v.B[1], o[2] - v.B[2] };
    MulVec3(v.Ainv, rel, a.P0);
    MulVec3(v.Ainv, d, a.DI);
    a.Te = t0;
    a.Tx = t1;
    a.Chord = std::numeric_limits<double>::infinity();
    bool hit = true;
    for (int k = 0; k < 3 && hit; ++k)
    {
      if (a.DI[k] == 0.0)
      {
        hit = a.P0[k] >= v.Lo[k] && a.P0[k] <= v.Hi[k];
        continue;
      }
      double ta = (v.Lo[k] - a.P0[k]) / a.DI[k];
      double tb = (v.Hi[k] - a.P0[k]) / a.DI[k];
      if (ta > tb)
      {
        std::swap(ta, tb);
      }
      a.Te = std::max(a.Te, ta);
      a.Tx = std::min(a.Tx, tb);
      a.Chord = std::min(a.Chord, 1.0 / std::abs(a.DI[k]));
    }
    if (!hit || !(a.Te < a.Tx))
    {
      continue;
    }
    for (int k = 0; v.Cropping && k < 6; ++k)
    {
      const int axis = k / 2;
      const double t = a.DI[axis] != 0.0 ? (v.CropPlanes[k] - a.P0[axis]) / a.DI[axis] : a.Te;
      if (t > a.Te && t < a.Tx)
        ws.Breaks.push_back(t);
    }
    if (v.Reduces())
    {
      ws.Layers.push_back(this->Reduce(a, dn));
      ws.Breaks.push_back(ws.Layers.back().T);
      continue;
    }
    ws.Act.push_back(a);
    ws.Breaks.push_back(a.Te);
    ws.Breaks.push_back(a.Tx);
    // Cell planes strictly inside the chord: integers (trilinear) or half-integers (nearest).
    const double offset = v.Linear ? 0.0 : 0.5;
    for (int k = 0; k < 3; ++k)
    {
      const int n = v.Dims[k];
      if (n == 1 || a.DI[k] == 0.0)
      {
        continue;
      }
      const double pa = a.P0[k] + a.DI[k] * a.Te;
      const double pb = a.P0[k] + a.DI[k] * a.Tx;
      const double lo = std::min(pa, pb) - offset, hi = std::max(pa, pb) - offset;
      const int qMin = v.Linear ? 1 : 0;
      const int qFirst = std::max(qMin, static_cast<int>(std::floor(lo)) + 1);
      const int qLast = std::min(n - 2, static_cast<int>(std::ceil(hi)) - 1);
      for (int q = qFirst; q <= qLast; ++q)
      {
        const double t = (q + offset - a.P0[k]) / a.DI[k];
        if (t > a.Te && t < a.Tx)
        {
          ws.Breaks.push_back(t);
        }
      }
    }
  }
  this->ClipSurfaces(o, d, t0, t1, ws);
  std::sort(ws.Breaks.begin(), ws.Breaks.end());
}

// Every translucent surface the ray crosses in [t0, t1) becomes a layer at its crossing, and the
// ray is cut there (Cramer's rule on corner + u e1 + v e2 = o + t d, local frame).
void MultiVolumeReferenceIntegrator::vtkInternals::ClipSurfaces(const double o[3],
  const double d[3],
  double t0,
  double t1,
  Workspace& ws) const
{
  auto cross = [](const double a[3], const double b[3], double c[3])
  {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto dot = [](const double a[3], const double b[3])
  { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  for (const Surface& s : this->Surfaces)
  {
    const double q[3] = { o[0] - (s.Corner[0] - this->LocalOrigin[0]),
      o[1] - (s.Corner[1] - this->LocalOrigin[1]),
      o[2] - (s.Corner[2] - this->LocalOrigin[2]) };
    double p[3], r[3];
    cross(d, s.Edge2, p);
    const double det = dot(s.Edge1, p);
    if (det == 0.0)
      continue; // the ray lies in the surface's plane
    const double u = dot(q, p) / det;
    cross(q, s.Edge1, r);
    const double v = dot(d, r) / det;
    const double t = dot(s.Edge2, r) / det;
    if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0 || !(t >= t0 && t < t1))
      continue;
    ws.Layers.push_back(Layer{ t, { s.Color[0], s.Color[1], s.Color[2], s.Color[3] } });
    ws.Breaks.push_back(t);
  }
  if (this->CrossingFunctions.empty())
    return;
  const double world[3] = {
    o[0] + this->LocalOrigin[0], o[1] + this->LocalOrigin[1], o[2] + this->LocalOrigin[2]
  };
  std::vector<Crossing> crossings;
  for (const CrossingFunction& f : this->CrossingFunctions)
  {
    crossings.clear();
    f(world, d, t0, t1, crossings);
    for (const Crossing& c : crossings)
    {
      if (!(c.T >= t0 && c.T < t1))
        continue;
      ws.Layers.push_back(Layer{ c.T, { c.Color[0], c.Color[1], c.Color[2], c.Color[3] } });
      ws.Breaks.push_back(c.T);
    }
  }
}

std::array<double, 4> MultiVolumeReferenceIntegrator::vtkInternals::Integrate(const double o[3],
  const double d[3],
  double t0,
  double t1,
  Workspace& ws) const
{
  std::array<double, 4> out = { 0.0, 0.0, 0.0, 0.0 };
  const double dn = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(dn > 0.0) || !(t1 > t0) || this->Volumes.empty())
  {
    return out;
  }
  const double hT = this->StepLength() / dn;

  this->Clip(o, d, t0, t1, dn, ws);
  std::stable_sort(ws.Layers.begin(), ws.Layers.end()); // equal depths in the order given

  double T = 1.0;
  double C[3] = { 0.0, 0.0, 0.0 };
  auto over = [&](const Layer& layer)
  {
    for (int ch = 0; ch < 3; ++ch)
      C[ch] += T * layer.C[ch];
    T *= 1.0 - layer.C[3];
  };
  size_t nextLayer = 0;
  for (size_t b = 0; b + 1 < ws.Breaks.size(); ++b)
  {
    const double ta = ws.Breaks[b], tb = ws.Breaks[b + 1];
    for (; nextLayer < ws.Layers.size() && ws.Layers[nextLayer].T <= ta; ++nextLayer)
      over(ws.Layers[nextLayer]);
    if (!(tb > ta))
    {
      continue;
    }
    const double tm = 0.5 * (ta + tb);
    ws.Cov.clear();
    double chord = std::numeric_limits<double>::infinity();
    for (const Active& a : ws.Act)
    {
      const double x[3] = {
        a.P0[0] + a.DI[0] * tm, a.P0[1] + a.DI[1] * tm, a.P0[2] + a.DI[2] * tm
      };
      if (a.Te < tm && tm < a.Tx && a.V->Shown(x))
      {
        Cover c;
        this->BuildCover(a, ta, tm, c);
        ws.Cov.push_back(c);
        chord = std::min(chord, a.Chord);
      }
    }
    if (ws.Cov.empty())
    {
      continue; // a gap between volumes
    }
    // Fixed per direction and coverage (continuity); the 1e-12 keeps ratios that are exactly
    // integers (axis-aligned rays) from rounding up to one step more.
    const double ratio = chord / hT * (1.0 - 1e-12);
    const int steps = std::max(1, static_cast<int>(std::min(std::ceil(ratio), 1e9)));
    const double len = tb - ta;

    // Split at the transfer-function kinks each trilinear scalar crosses and at the surfaces.
    ws.Sub.clear();
    ws.Sub.push_back(0.0);
    ws.Surfaces.clear();
    for (const Cover& c : ws.Cov)
    {
      if (c.V->Mode == Blend::IsoSurface)
      {
        this->AppendSurfaces(c, len, ws);
      }
      else
      {
        for (int comp = 0; comp < c.V->NC; ++comp)
          this->AppendKinks(c, comp, len, ws);
      }
    }
    for (const Layer& surface : ws.Surfaces)
      ws.Sub.push_back(surface.T);
    std::sort(ws.Surfaces.begin(), ws.Surfaces.end());
    size_t nextSurface = 0;
    ws.Sub.push_back(len);
    if (ws.Sub.size() > 2)
    {
      std::sort(ws.Sub.begin(), ws.Sub.end());
    }

    for (size_t s = 0; s + 1 < ws.Sub.size(); ++s)
    {
      const double ua = ws.Sub[s], ub = ws.Sub[s + 1];
      for (; nextSurface < ws.Surfaces.size() && ws.Surfaces[nextSurface].T <= ua; ++nextSurface)
        over(ws.Surfaces[nextSurface]);
      if (!(ub > ua))
      {
        continue;
      }
      const double du = (ub - ua) / steps;
      const double dl = du * dn; // world length of a step
      for (int k = 0; k < steps; ++k)
      {
        const double um = ua + (k + 0.5) * du;
        double sigma = 0.0;
        double e[3] = { 0.0, 0.0, 0.0 };
        for (const Cover& c : ws.Cov)
        {
          if (c.V->Mode == Blend::IsoSurface)
            continue;
          double tau, rgb[3], s[4];
          for (int comp = 0; comp < c.V->NC; ++comp)
            s[comp] = Horner(c.S[comp], um);
          if (c.V->Tf.Gradient.empty())
            c.V->Classify(s, tau, rgb);
          else
            tau = this->GradientTau(c, ta + um, s[0], rgb);
          sigma += tau;
          for (int ch = 0; ch < 3; ++ch)
          {
            e[ch] += rgb[ch] * tau;
          }
        }
        if (!(sigma > 0.0))
        {
          continue;
        }
        double transmitted, absorbed;
        Attenuation(sigma * dl, transmitted, absorbed);
        const double w = T * absorbed / sigma;
        for (int ch = 0; ch < 3; ++ch)
        {
          C[ch] += w * e[ch];
        }
        T *= transmitted;
        if (T < this->TerminationTransmittance)
        {
          return { C[0], C[1], C[2], 1.0 - T };
        }
      }
    }
    for (; nextSurface < ws.Surfaces.size(); ++nextSurface)
      over(ws.Surfaces[nextSurface]);
  }
  for (; nextLayer < ws.Layers.size(); ++nextLayer)
    over(ws.Layers[nextLayer]);
  return { C[0], C[1], C[2], 1.0 - T };
}

MultiVolumeReferenceIntegrator::MultiVolumeReferenceIntegrator()
  : Internals(new vtkInternals)
{
}

MultiVolumeReferenceIntegrator::~MultiVolumeReferenceIntegrator() = default;

// Geometry: index -> world is M3 Direction diag(spacing) idx + M3 Origin + m_t, kept as
// A idx + B relative to the scene's local origin (set by the first volume: an integer point
// near its centre, so that UTM-scale coordinates lose nothing). False with `error` set when
// the matrix is singular or not finite.
bool MultiVolumeReferenceIntegrator::vtkInternals::SetGeometry(const Volume& in,
  Vol& v,
  const char*& error)
{
  vtkInternals& self = *this;
  const double* m = in.ModelMatrix;
  for (int k = 0; k < 3; ++k)
    v.Dims[k] = in.Dimensions[k];
  double ds[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      ds[3 * r + c] = in.Direction[3 * r + c] * in.Spacing[c];
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      v.A[3 * r + c] = m[4 * r] * ds[c] + m[4 * r + 1] * ds[3 + c] + m[4 * r + 2] * ds[6 + c];
    }
  }
  if (!Invert3x3(v.A, v.Ainv))
  {
    error = "direction or model matrix is singular";
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    v.Lo[k] = v.Dims[k] == 1 ? -0.5 : 0.0;
    v.Hi[k] = v.Dims[k] == 1 ? 0.5 : v.Dims[k] - 1.0;
  }
  double mo[3];
  for (int r = 0; r < 3; ++r)
  {
    mo[r] = m[4 * r] * in.Origin[0] + m[4 * r + 1] * in.Origin[1] + m[4 * r + 2] * in.Origin[2];
  }
  if (self.Volumes.empty())
  {
    double centre[3], p[3];
    for (int k = 0; k < 3; ++k)
    {
      centre[k] = 0.5 * (v.Lo[k] + v.Hi[k]);
    }
    MulVec3(v.A, centre, p);
    for (int r = 0; r < 3; ++r)
    {
      self.LocalOrigin[r] = std::round(mo[r] + m[4 * r + 3] + p[r]);
    }
  }
  // Large terms first cancel exactly against the (integer) local origin.
  for (int r = 0; r < 3; ++r)
  {
    v.B[r] = mo[r] + (m[4 * r + 3] - self.LocalOrigin[r]);
  }
  for (int r = 0; r < 3; ++r)
  {
    if (!std::isfinite(v.B[r]))
    {
      error = "origin or model matrix is not finite";
      return false;
    }
  }

  return true;
}

// The classification table as the integrator reads it: clamped opacities, colours, the
// kinks of the piecewise-linear functions (integrated across exactly) and the bounds of
// extinction and emission and their derivatives per scalar that the error control uses.
void MultiVolumeReferenceIntegrator::vtkInternals::BuildTable(const TransferFunction& tf, Table& t)
{
  const int n = static_cast<int>(tf.Opacity.size());
  t.N = n;
  t.SMin = tf.Range[0];
  t.Scale = n > 1 ? (n - 1) / (tf.Range[1] - tf.Range[0]) : 0.0;
  t.UnitDistance = tf.UnitDistance;
  t.Alpha.resize(n);
  t.Color.resize(3 * static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
  {
    const double a = tf.Opacity[k];
    t.Alpha[k] = std::isfinite(a) ? std::min(std::max(a, 0.0), MaxOpacity) : 0.0;
    for (int ch = 0; ch < 3; ++ch)
    {
      t.Color[3 * k + ch] = tf.Color.empty() ? 1.0 : tf.Color[3 * k + ch];
    }
  }
  auto slopeDiffers = [&](int k)
  {
    // Slopes left and right of node k (zero outside the table): alpha, then colours.
    for (int q = 0; q < 4; ++q)
    {
      auto val = [&](int idx) { return q == 0 ? t.Alpha[idx] : t.Color[3 * idx + q - 1]; };
      const double left = k > 0 ? val(k) - val(k - 1) : 0.0;
      const double right = k < n - 1 ? val(k + 1) - val(k) : 0.0;
      // Float rounding of the table (about 6e-8 per value) makes every entry look like a kink;
      // a slope change below 1e-6 per entry is rounding, and integrating across one costs less
      // than the step error.
      if (std::abs(left - right) > 1e-6)
      {
        return true;
      }
    }
    return false;
  };
  for (int k = 0; n > 1 && k < n; ++k)
  {
    if (slopeDiffers(k))
    {
      t.Kinks.push_back(tf.Range[0] + k * (tf.Range[1] - tf.Range[0]) / (n - 1));
    }
  }
  for (int k = 0; k < n; ++k)
  {
    const double tau = -std::log1p(-t.Alpha[k]) / t.UnitDistance;
    double cmax = 0.0;
    for (int ch = 0; ch < 3; ++ch)
    {
      cmax = std::max(cmax, std::abs(t.Color[3 * k + ch]));
    }
    t.Tau[0] = std::max(t.Tau[0], tau);
    t.ColorMax = std::max(t.ColorMax, cmax);
    t.Emission[0] = std::max(t.Emission[0], cmax * tau);
  }
  for (int k = 0; k + 1 < n; ++k)
  {
    // On a piece alpha = a0 + as s, so tau' = as / (u (1 - alpha)), tau'' = as^2 / (u (1-alpha)^2)
    // (largest where alpha is), and (c tau)' = c' tau + c tau', (c tau)'' = 2 c' tau' + c tau''.
    const double amax = std::max(t.Alpha[k], t.Alpha[k + 1]);
    const double as = std::abs(t.Alpha[k + 1] - t.Alpha[k]) * t.Scale;
    const double u = t.UnitDistance;
    const double tau = -std::log1p(-amax) / u;
    const double tau1 = as / (u * (1.0 - amax));
    const double tau2 = as * as / (u * (1.0 - amax) * (1.0 - amax));
    double cs = 0.0, cmax = 0.0;
    for (int ch = 0; ch < 3; ++ch)
    {
      cs = std::max(cs, std::abs(t.Color[3 * (k + 1) + ch] - t.Color[3 * k + ch]) * t.Scale);
      cmax = std::max({ cmax, std::abs(t.Color[3 * k + ch]), std::abs(t.Color[3 * k + 3 + ch]) });
    }
    t.Tau[1] = std::max(t.Tau[1], tau1);
    t.Tau[2] = std::max(t.Tau[2], tau2);
    t.Emission[1] = std::max(t.Emission[1], cs * tau + cmax * tau1);
    t.Emission[2] = std::max(t.Emission[2], 2.0 * cs * tau1 + cmax * tau2);
  }
}

// Bounds of s' and s'' along a world-unit ray: per-axis edge differences bound the index
// gradient, face twists bound the (zero-diagonal) index Hessian, |A^-1|_F converts; then the
// bounds of extinction and emission and of their first two derivatives along a ray.
void MultiVolumeReferenceIntegrator::vtkInternals::SetDerivativeBounds(Vol& v)
{
  const Table& t = v.Tf;
  double s1 = 0.0, s2 = 0.0;
  if (v.Linear)
  {
    double g[3] = { 0.0, 0.0, 0.0 }, tw[3] = { 0.0, 0.0, 0.0 }; // twists: xy, xz, yz
    const int nx = v.Dims[0], ny = v.Dims[1], nz = v.Dims[2];
    for (int k = 0; k < nz; ++k)
    {
      for (int j = 0; j < ny; ++j)
      {
        for (int i = 0; i < nx; ++i)
        {
          const double s = v.Value(i, j, k);
          const double sx = i + 1 < nx ? v.Value(i + 1, j, k) : s;
          const double sy = j + 1 < ny ? v.Value(i, j + 1, k) : s;
          const double sz = k + 1 < nz ? v.Value(i, j, k + 1) : s;
          g[0] = std::max(g[0], std::abs(sx - s));
          g[1] = std::max(g[1], std::abs(sy - s));
          g[2] = std::max(g[2], std::abs(sz - s));
          if (i + 1 < nx && j + 1 < ny)
          {
            tw[0] = std::max(tw[0], std::abs(s - sx - sy + v.Value(i + 1, j + 1, k)));
          }
          if (i + 1 < nx && k + 1 < nz)
          {
            tw[1] = std::max(tw[1], std::abs(s - sx - sz + v.Value(i + 1, j, k + 1)));
          }
          if (j + 1 < ny && k + 1 < nz)
          {
            tw[2] = std::max(tw[2], std::abs(s - sy - sz + v.Value(i, j + 1, k + 1)));
          }
        }
      }
    }
    double gInv = 0.0;
    for (int k = 0; k < 9; ++k)
    {
      gInv += v.Ainv[k] * v.Ainv[k];
    }
    gInv = std::sqrt(gInv);
    s1 = gInv * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    s2 = gInv * gInv * std::sqrt(2.0 * (tw[0] * tw[0] + tw[1] * tw[1] + tw[2] * tw[2]));
  }
  v.Bounds[0] = t.Tau[0];
  v.Bounds[1] = t.Tau[1] * s1;
  v.Bounds[2] = t.Tau[2] * s1 * s1 + t.Tau[1] * s2;
  v.Bounds[3] = t.Emission[0];
  v.Bounds[4] = t.Emission[1] * s1;
  v.Bounds[5] = t.Emission[2] * s1 * s1 + t.Emission[1] * s2;
}

int MultiVolumeReferenceIntegrator::AddVolume(Volume in)
{
  vtkInternals& self = *this->Internals;
  const char* error = Validate(in);
  vtkInternals::Vol v;
  if (error || !self.SetGeometry(in, v, error))
  {
    self.LastError = error;
    return -1;
  }
  vtkInternals::BuildTable(in.Classification, v.Tf);
  v.Tf.Gradient = in.Classification.GradientOpacity;
  const double* gr = in.Classification.GradientRange;
  v.Tf.GradientMin = gr[0];
  v.Tf.GradientScale =
    v.Tf.Gradient.size() > 1 && gr[1] > gr[0] ? (v.Tf.Gradient.size() - 1) / (gr[1] - gr[0]) : 0.0;
  v.Linear = in.Sampling == Interpolation::Linear;
  v.Comp = in.ComponentMode;
  v.NC = in.NumberOfComponents;
  for (const TransferFunction& tf : in.ComponentClassifications)
  {
    v.Extra.emplace_back();
    vtkInternals::BuildTable(tf, v.Extra.back());
  }
  std::copy(in.ComponentWeights, in.ComponentWeights + 4, v.Weights);
  for (int k = 0; k < 3; ++k)
  {
    v.ColorLo[k] = in.ColorRange[k][0];
    v.ColorScale[k] = 1.0 / (in.ColorRange[k][1] - in.ColorRange[k][0]);
  }
  v.Mode = in.BlendMode;
  v.Cropping = in.Cropping;
  std::copy(in.CropPlanes, in.CropPlanes + 6, v.CropPlanes);
  v.CropFlags = in.CropFlags;
  v.Iso = in.IsoValues;
  std::copy(in.AverageRange, in.AverageRange + 2, v.AverageRange);
  if (in.Scalars.empty())
  {
    v.F = std::move(in.FloatScalars);
  }
  else
  {
    v.D = std::move(in.Scalars);
  }

  self.SetDerivativeBounds(v);
  for (int c = 0; c < 3; ++c)
  {
    const double edge =
      std::sqrt(v.A[c] * v.A[c] + v.A[3 + c] * v.A[3 + c] + v.A[6 + c] * v.A[6 + c]);
    self.SmallestVoxel = self.Volumes.empty() && c == 0 ? edge : std::min(self.SmallestVoxel, edge);
  }
  self.Volumes.push_back(std::move(v));
  self.LastError.clear();
  return static_cast<int>(self.Volumes.size()) - 1;
}

void MultiVolumeReferenceIntegrator::AddSurface(const Surface& surface)
{
  this->Internals->Surfaces.push_back(surface);
}

void MultiVolumeReferenceIntegrator::AddSurfaceCrossings(CrossingFunction crossings)
{
  if (crossings)
    this->Internals->CrossingFunctions.push_back(std::move(crossings));
}

void MultiVolumeReferenceIntegrator::RemoveAllSurfaces()
{
  this->Internals->Surfaces.clear();
  this->Internals->CrossingFunctions.clear();
}

void MultiVolumeReferenceIntegrator::RemoveAllVolumes()
{
  this->Internals->Volumes.clear();
  this->Internals->SmallestVoxel = 0.0;
  std::fill(this->Internals->LocalOrigin, this->Internals->LocalOrigin + 3, 0.0);
}

int MultiVolumeReferenceIntegrator::GetNumberOfVolumes() const
{
  return static_cast<int>(this->Internals->Volumes.size());
}

const std::string& MultiVolumeReferenceIntegrator::GetLastError() const
{
  return this->Internals->LastError;
}

void MultiVolumeReferenceIntegrator::SetStepFraction(double fraction)
{
  if (fraction > 0.0 && std::isfinite(fraction))
  {
    this->Internals->StepFraction = fraction;
  }
}

double MultiVolumeReferenceIntegrator::GetStepFraction() const
{
  return this->Internals->StepFraction;
}

double MultiVolumeReferenceIntegrator::GetStepLength() const
{
  return this->Internals->StepLength();
}

double MultiVolumeReferenceIntegrator::GetSmallestVoxelSize() const
{
  return this->Internals->SmallestVoxel;
}

void MultiVolumeReferenceIntegrator::SetTerminationTransmittance(double transmittance)
{
  this->Internals->TerminationTransmittance = std::max(transmittance, 0.0);
}

double MultiVolumeReferenceIntegrator::GetTerminationTransmittance() const
{
  return this->Internals->TerminationTransmittance;
}

void MultiVolumeReferenceIntegrator::SetNumberOfThreads(int threads)
{
  this->Internals->NumberOfThreads = std::max(threads, 0);
}

int MultiVolumeReferenceIntegrator::GetNumberOfThreads() const
{
  return this->Internals->NumberOfThreads;
}

void MultiVolumeReferenceIntegrator::GetLocalOrigin(double origin[3]) const
{
  std::copy(this->Internals->LocalOrigin, this->Internals->LocalOrigin + 3, origin);
}

std::array<double, 4> MultiVolumeReferenceIntegrator::IntegrateRay(const double origin[3],
  const double direction[3],
  double t0,
  double t1) const
{
  const double* l = this->Internals->LocalOrigin;
  const double o[3] = { origin[0] - l[0], origin[1] - l[1], origin[2] - l[2] };
  vtkInternals::Workspace ws;
  return this->Internals->Integrate(o, direction, t0, t1, ws);
}

void MultiVolumeReferenceIntegrator::IntegrateImage(const double clipToWorld[16],
  int width,
  int height,
  std::vector<double>& rgba,
  const double* start,
  const double* stop,
  DepthKind kind) const
{
  rgba.assign(4 * static_cast<size_t>(std::max(width, 0)) * std::max(height, 0), 0.0);
  if (width <= 0 || height <= 0)
  {
    return;
  }
  // clip -> local = translate(-origin) * clip -> world; fma keeps the cancellation exact.
  double m[16];
  const double* l = this->Internals->LocalOrigin;
  for (int c = 0; c < 4; ++c)
  {
    for (int r = 0; r < 3; ++r)
    {
      m[4 * r + c] = std::fma(-l[r], clipToWorld[12 + c], clipToWorld[4 * r + c]);
    }
    m[12 + c] = clipToWorld[12 + c];
  }
  auto transform = [&m](double x, double y, double z, double out[3])
  {
    const double w = m[12] * x + m[13] * y + m[14] * z + m[15];
    for (int r = 0; r < 3; ++r)
    {
      out[r] = (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]) / w;
    }
  };
  auto work = [&](int rowBegin, int rowStep)
  {
    vtkInternals::Workspace ws;
    for (int py = rowBegin; py < height; py += rowStep)
    {
      for (int px = 0; px < width; ++px)
      {
        const double nx = (px + 0.5) / width * 2.0 - 1.0;
        const double ny = (py + 0.5) / height * 2.0 - 1.0;
        double nearP[3], farP[3], dir[3];
        transform(nx, ny, -1.0, nearP);
        transform(nx, ny, 1.0, farP);
        for (int a = 0; a < 3; ++a)
        {
          dir[a] = farP[a] - nearP[a];
        }
        const double dd = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        const size_t idx = static_cast<size_t>(py) * width + px;
        auto toT = [&](double value)
        {
          if (kind == DepthKind::WorldDistance)
          {
            return value / std::sqrt(dd);
          }
          double p[3];
          transform(nx, ny, 2.0 * value - 1.0, p);
          return ((p[0] - nearP[0]) * dir[0] + (p[1] - nearP[1]) * dir[1] +
                   (p[2] - nearP[2]) * dir[2]) /
                 dd;
        };
        const double t0 = start ? std::max(0.0, toT(start[idx])) : 0.0;
        const double t1 = stop ? std::min(1.0, toT(stop[idx])) : 1.0;
        const std::array<double, 4> c = this->Internals->Integrate(nearP, dir, t0, t1, ws);
        std::copy(c.begin(), c.end(), rgba.begin() + 4 * idx);
      }
    }
  };
  int threads = this->Internals->NumberOfThreads;
  if (threads <= 0)
  {
    threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  threads = std::min(threads, height);
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k)
  {
    pool.emplace_back(work, k, threads);
  }
  work(0, threads);
  for (auto& th : pool)
  {
    th.join();
  }
}

MultiVolumeReferenceIntegrator::ErrorBound MultiVolumeReferenceIntegrator::GetErrorBound(
  double length) const
{
  ErrorBound bound;
  double b[6] = { 0, 0, 0, 0, 0, 0 };
  double cmax = 0.0;
  for (const vtkInternals::Vol& v : this->Internals->Volumes)
  {
    for (int k = 0; k < 6; ++k)
    {
      b[k] += v.Bounds[k];
    }
    cmax = std::max(cmax, v.Tf.ColorMax);
  }
  const double h = this->GetStepLength();
  const double scale = std::max(length, 0.0) * h * h;
  bound.Alpha = scale * b[2] / 24.0;
  bound.Color = scale * (cmax * b[2] / 24.0 + b[5] / 24.0 + (b[3] * b[1] + b[4] * b[0]) / 12.0);
  return bound;
}
}

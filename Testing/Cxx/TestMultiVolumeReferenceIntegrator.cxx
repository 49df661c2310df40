// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The multi-volume reference integrator against closed forms and against itself:
// (a) constant boxes, axis-aligned and rotated (direction and model matrix), exact chords;
// (b) a linear scalar ramp under linear transfer functions, closed forms derived below;
// (c) coincident, nested and face-sharing volumes (physical mixing, no double counting);
// (d) a 90-degree direction matrix equals the permuted data; (e) translation to UTM
// coordinates; (f) a one-voxel-thin volume; (g) convergence when halving the step;
// (h) per-pixel start and stop depths. Every checked number is printed with its bound.
#include "StrataSubTests.h"

#include "StrataMultiVolumeReferenceIntegrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace
{
using Integrator = strata::MultiVolumeReferenceIntegrator;
using Volume = strata::MultiVolumeReferenceIntegrator::Volume;
using TransferFunction = strata::MultiVolumeReferenceIntegrator::TransferFunction;
using RGBA = std::array<double, 4>;

int Failures = 0;

// Prints one checked quantity and whether it is within its bound.
void Check(const char* what, double value, double bound)
{
  const bool ok = std::abs(value) <= bound;
  std::printf("%-58s %12.4e <= %10.3e  %s\n", what, value, bound, ok ? "ok" : "FAILED");
  if (!ok)
  {
    ++Failures;
  }
}

double MaxDiff(const RGBA& a, const RGBA& b)
{
  double m = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    m = std::max(m, std::abs(a[k] - b[k]));
  }
  return m;
}

double MaxDiff(const std::vector<double>& a, const std::vector<double>& b)
{
  double m = 0.0;
  for (size_t k = 0; k < a.size(); ++k)
  {
    m = std::max(m, std::abs(a[k] - b[k]));
  }
  return m;
}

double MaxAlpha(const std::vector<double>& img)
{
  double m = 0.0;
  for (size_t k = 3; k < img.size(); k += 4)
  {
    m = std::max(m, img[k]);
  }
  return m;
}

// Row-major 3x3 rotation about a (normalised here) axis.
std::array<double, 9> Rotation(double ax, double ay, double az, double angle)
{
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n;
  ay /= n;
  az /= n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  return { t * ax * ax + c,
    t * ax * ay - s * az,
    t * ax * az + s * ay,
    t * ax * ay + s * az,
    t * ay * ay + c,
    t * ay * az - s * ax,
    t * ax * az - s * ay,
    t * ay * az + s * ax,
    t * az * az + c };
}

void SetModel(Volume& v, const std::array<double, 9>& r, double tx, double ty, double tz)
{
  const double m[16] = {
    r[0], r[1], r[2], tx, r[3], r[4], r[5], ty, r[6], r[7], r[8], tz, 0, 0, 0, 1
  };
  std::copy(m, m + 16, v.ModelMatrix);
}

// World position of index point p: M (O + D diag(s) p).
void IndexToWorld(const Volume& v, const double p[3], double w[3])
{
  double q[3];
  for (int r = 0; r < 3; ++r)
  {
    q[r] = v.Origin[r];
    for (int c = 0; c < 3; ++c)
    {
      q[r] += v.Direction[3 * r + c] * v.Spacing[c] * p[c];
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    const double* m = v.ModelMatrix + 4 * r;
    w[r] = m[0] * q[0] + m[1] * q[1] + m[2] * q[2] + m[3];
  }
}

TransferFunction ConstantTF(double alpha, double r, double g, double b, double unit)
{
  TransferFunction tf;
  tf.Opacity = { alpha };
  tf.Color = { r, g, b };
  tf.UnitDistance = unit;
  return tf;
}

double Tau(double alpha, double unit)
{
  return -std::log(1.0 - alpha) / unit;
}

// A five-node transfer function with slope changes at every node.
TransferFunction RichTF(double unit)
{
  TransferFunction tf;
  tf.Range[0] = 0.0;
  tf.Range[1] = 1.0;
  tf.Opacity = { 0.0, 0.15, 0.45, 0.25, 0.05 };
  tf.Color = { 0.1, 0.2, 0.9, 0.2, 0.8, 0.6, 0.9, 0.9, 0.1, 1.0, 0.3, 0.1, 0.6, 0.1, 0.4 };
  tf.UnitDistance = unit;
  return tf;
}

Volume MakeVolume(int nx,
  int ny,
  int nz,
  double sx,
  double sy,
  double sz,
  double ox,
  double oy,
  double oz,
  double (*f)(int, int, int))
{
  Volume v;
  const int dims[3] = { nx, ny, nz };
  const double sp[3] = { sx, sy, sz }, org[3] = { ox, oy, oz };
  std::copy(dims, dims + 3, v.Dimensions);
  std::copy(sp, sp + 3, v.Spacing);
  std::copy(org, org + 3, v.Origin);
  v.Scalars.resize(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        v.Scalars[(static_cast<size_t>(k) * ny + j) * nx + i] = f(i, j, k);
      }
    }
  }
  return v;
}

double Smooth(int i, int j, int k)
{
  return 0.5 + 0.3 * std::sin(0.55 * i + 0.3 * j) * std::cos(0.45 * k + 0.2 * i) +
         0.15 * std::sin(0.7 * j - 0.25 * k);
}

// ---- 4x4 row-major matrices (column vectors) -------------------------------------------------
using Mat4 = std::array<double, 16>;

Mat4 Mul(const Mat4& a, const Mat4& b)
{
  Mat4 r{};
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      for (int k = 0; k < 4; ++k)
      {
        r[4 * i + j] += a[4 * i + k] * b[4 * k + j];
      }
    }
  }
  return r;
}

Mat4 Inverse(Mat4 a)
{
  Mat4 inv = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  for (int c = 0; c < 4; ++c)
  {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
    {
      if (std::abs(a[4 * r + c]) > std::abs(a[4 * p + c]))
      {
        p = r;
      }
    }
    for (int k = 0; k < 4; ++k)
    {
      std::swap(a[4 * c + k], a[4 * p + k]);
      std::swap(inv[4 * c + k], inv[4 * p + k]);
    }
    const double d = a[4 * c + c];
    for (int k = 0; k < 4; ++k)
    {
      a[4 * c + k] /= d;
      inv[4 * c + k] /= d;
    }
    for (int r = 0; r < 4; ++r)
    {
      if (r != c)
      {
        const double f = a[4 * r + c];
        for (int k = 0; k < 4; ++k)
        {
          a[4 * r + k] -= f * a[4 * c + k];
          inv[4 * r + k] -= f * inv[4 * c + k];
        }
      }
    }
  }
  return inv;
}

// World -> eye of a camera at eye looking at centre.
Mat4 View(const double eye[3], const double centre[3], const double up[3])
{
  double f[3] = { centre[0] - eye[0], centre[1] - eye[1], centre[2] - eye[2] };
  const double fn = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (double& x : f)
  {
    x /= fn;
  }
  double s[3] = {
    f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]
  };
  const double sn = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (double& x : s)
  {
    x /= sn;
  }
  const double u[3] = {
    s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]
  };
  return { s[0],
    s[1],
    s[2],
    -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
    u[0],
    u[1],
    u[2],
    -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
    -f[0],
    -f[1],
    -f[2],
    f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2],
    0,
    0,
    0,
    1 };
}

// World -> clip of an OpenGL perspective camera.
Mat4 WorldToClip(const double eye[3],
  const double centre[3],
  const double up[3],
  double fovyDeg,
  double nearZ,
  double farZ)
{
  const double t = 1.0 / std::tan(0.5 * fovyDeg * 3.14159265358979323846 / 180.0);
  const Mat4 proj = { t,
    0,
    0,
    0,
    0,
    t,
    0,
    0,
    0,
    0,
    (farZ + nearZ) / (nearZ - farZ),
    2.0 * farZ * nearZ / (nearZ - farZ),
    0,
    0,
    -1,
    0 };
  return Mul(proj, View(eye, centre, up));
}

// World -> clip of an OpenGL orthographic camera showing [-half, half]^2.
Mat4 WorldToClipOrtho(const double eye[3],
  const double centre[3],
  const double up[3],
  double half,
  double nearZ,
  double farZ)
{
  const Mat4 proj = { 1.0 / half,
    0,
    0,
    0,
    0,
    1.0 / half,
    0,
    0,
    0,
    0,
    -2.0 / (farZ - nearZ),
    -(farZ + nearZ) / (farZ - nearZ),
    0,
    0,
    0,
    1 };
  return Mul(proj, View(eye, centre, up));
}

void Transform(const Mat4& m, double x, double y, double z, double out[3])
{
  const double w = m[12] * x + m[13] * y + m[14] * z + m[15];
  for (int r = 0; r < 3; ++r)
  {
    out[r] = (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]) / w;
  }
}

// ---- independent closed form for scenes of constant, rigidly placed boxes ----------------------
struct Box
{
  double Centre[3];
  double Axes[9]; ///< rows: the box's unit axes in world
  double Half[3];
  double Sigma;
  double Color[3];
};

// The box of a constant volume under rigid direction and model matrices.
Box BoxOf(const Volume& v, double sigma, const double color[3])
{
  Box b;
  double c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = v.Dimensions[a] == 1 ? 0.0 : 0.5 * (v.Dimensions[a] - 1);
    b.Half[a] = v.Dimensions[a] == 1 ? 0.5 * v.Spacing[a] : c[a] * v.Spacing[a];
  }
  IndexToWorld(v, c, b.Centre);
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      const double* m = v.ModelMatrix + 4 * r;
      b.Axes[3 * a + r] =
        m[0] * v.Direction[a] + m[1] * v.Direction[3 + a] + m[2] * v.Direction[6 + a];
    }
  }
  b.Sigma = sigma;
  std::copy(color, color + 3, b.Color);
  return b;
}

// Segments between all box entries and exits; each is a homogeneous medium.
RGBA ExactBoxes(const std::vector<Box>& boxes,
  const double o[3],
  const double d[3],
  double t0,
  double t1)
{
  std::vector<double> ev = { t0, t1 };
  std::vector<std::array<double, 2>> span;
  for (const Box& b : boxes)
  {
    double te = t0, tx = t1;
    for (int a = 0; a < 3; ++a)
    {
      const double* ax = b.Axes + 3 * a;
      const double p =
        ax[0] * (o[0] - b.Centre[0]) + ax[1] * (o[1] - b.Centre[1]) + ax[2] * (o[2] - b.Centre[2]);
      const double q = ax[0] * d[0] + ax[1] * d[1] + ax[2] * d[2];
      if (q == 0.0)
      {
        if (std::abs(p) > b.Half[a])
        {
          tx = -1e300;
        }
        continue;
      }
      double ta = (-b.Half[a] - p) / q, tb = (b.Half[a] - p) / q;
      if (ta > tb)
      {
        std::swap(ta, tb);
      }
      te = std::max(te, ta);
      tx = std::min(tx, tb);
    }
    span.push_back({ te, tx });
    if (te < tx)
    {
      ev.push_back(te);
      ev.push_back(tx);
    }
  }
  std::sort(ev.begin(), ev.end());
  const double dn = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double T = 1.0;
  RGBA out = { 0, 0, 0, 0 };
  for (size_t k = 0; k + 1 < ev.size(); ++k)
  {
    const double a = ev[k], b = ev[k + 1], m = 0.5 * (a + b);
    if (!(b > a) || a < t0 || b > t1)
    {
      continue;
    }
    double sigma = 0.0, e[3] = { 0, 0, 0 };
    for (size_t i = 0; i < boxes.size(); ++i)
    {
      if (span[i][0] < m && m < span[i][1])
      {
        sigma += boxes[i].Sigma;
        for (int c = 0; c < 3; ++c)
        {
          e[c] += boxes[i].Sigma * boxes[i].Color[c];
        }
      }
    }
    if (sigma > 0.0)
    {
      const double absorbed = -std::expm1(-sigma * (b - a) * dn);
      for (int c = 0; c < 3; ++c)
      {
        out[c] += T * absorbed * e[c] / sigma;
      }
      T *= 1.0 - absorbed;
    }
  }
  out[3] = 1.0 - T;
  return out;
}

// Closed-form image of constant boxes, same pixel convention as IntegrateImage.
std::vector<double> ExactImage(const std::vector<Box>& boxes, const Mat4& clipToWorld, int w, int h)
{
  std::vector<double> img(4 * static_cast<size_t>(w) * h);
  for (int py = 0; py < h; ++py)
  {
    for (int px = 0; px < w; ++px)
    {
      const double nx = (px + 0.5) / w * 2.0 - 1.0, ny = (py + 0.5) / h * 2.0 - 1.0;
      double a[3], b[3], d[3];
      Transform(clipToWorld, nx, ny, -1.0, a);
      Transform(clipToWorld, nx, ny, 1.0, b);
      for (int k = 0; k < 3; ++k)
      {
        d[k] = b[k] - a[k];
      }
      const RGBA c = ExactBoxes(boxes, a, d, 0.0, 1.0);
      std::copy(c.begin(), c.end(), img.begin() + 4 * (static_cast<size_t>(py) * w + px));
    }
  }
  return img;
}

Mat4 Camera(const double eye[3], const double centre[3])
{
  const double up[3] = { 0.0, 0.0, 1.0 };
  return Inverse(WorldToClip(eye, centre, up, 40.0, 2.0, 80.0));
}

int Add(Integrator& integ, const Volume& v)
{
  const int id = integ.AddVolume(v);
  if (id < 0)
  {
    std::printf("AddVolume failed: %s\n", integ.GetLastError().c_str());
    ++Failures;
  }
  return id;
}

// The two-volume scene of (e) and (g): a rotated trilinear volume and a rotated nearest one
// overlapping it, both with a five-node transfer function, optionally translated.
void AddOverlapScene(Integrator& integ, double tx, double ty, double tz)
{
  Volume a = MakeVolume(14, 12, 9, 1.0, 1.25, 0.75, -7.0, -6.0, -3.0, Smooth);
  a.Classification = RichTF(2.0);
  SetModel(a, Rotation(0.3, -0.2, 1.0, 0.6), 0.5 + tx, -0.25 + ty, 0.125 + tz);
  Add(integ, a);
  Volume b = MakeVolume(9,
    11,
    7,
    0.8,
    0.7,
    0.9,
    0.0 + tx,
    -1.5 + ty,
    -2.0 + tz,
    [](int i, int j, int k) { return 0.3 + 0.05 * i - 0.02 * j + 0.04 * k; });
  const std::array<double, 9> r = Rotation(1.0, 1.0, 0.2, -0.5);
  std::copy(r.begin(), r.end(), b.Direction);
  b.Sampling = Integrator::Interpolation::Nearest;
  b.Classification = RichTF(1.5);
  Add(integ, b);
}
}

namespace
{
void ConstantBoxes(double exactTol)
{
  // (a) Constant boxes. Constant classification is integrated exactly (exact exponentials of a
  // homogeneous medium), so only rounding separates it from alpha = 1 - exp(-tau L), C = c alpha.
  std::printf("(a) constant boxes\n");
  Volume v = MakeVolume(11, 9, 7, 0.5, 1.0, 1.5, 1.0, 2.0, 3.0, [](int, int, int) { return 0.3; });
  v.Classification.Range[0] = 0.0;
  v.Classification.Range[1] = 1.0;
  v.Classification.Opacity = { 0.1, 0.5 };
  v.Classification.Color = { 1.0, 0.2, 0.1, 0.2, 0.6, 1.0 };
  v.Classification.UnitDistance = 2.0;
  // At s = 0.3: alpha = 0.22 per 2 units, c = (0.76, 0.32, 0.37).
  const double tau = Tau(0.22, 2.0);
  const double c[3] = { 0.76, 0.32, 0.37 };
  auto expected = [&](double len)
  {
    const double a = 1.0 - std::exp(-tau * len);
    return RGBA{ c[0] * a, c[1] * a, c[2] * a, a };
  };
  {
    Integrator integ;
    Add(integ, v);
    // Box x in [1, 6]: a ray along x from x = -2 (non-unit direction) has chord 5.
    const double o[3] = { -2.0, 5.3, 7.1 }, d[3] = { 2.0, 0.0, 0.0 };
    const RGBA got = integ.IntegrateRay(o, d, 0.0, 10.0);
    std::printf("    axis-aligned: alpha %.15f expected %.15f\n", got[3], expected(5.0)[3]);
    Check("(a) axis-aligned ray, |RGBA - closed form|", MaxDiff(got, expected(5.0)), exactTol);
  }
  // Rotated: a ray from index point pa (face i = 0) to pb (face i = 10); the chord is the world
  // distance between them (rigid transforms).
  const double pa[3] = { 0.0, 3.2, 2.5 }, pb[3] = { 10.0, 5.1, 4.4 };
  auto rotatedCase = [&](const Volume& rv, const char* what)
  {
    Integrator integ;
    Add(integ, rv);
    double wa[3], wb[3], d[3], o[3];
    IndexToWorld(rv, pa, wa);
    IndexToWorld(rv, pb, wb);
    for (int k = 0; k < 3; ++k)
    {
      d[k] = wb[k] - wa[k];
      o[k] = wa[k] - 0.3 * d[k];
    }
    const double chord = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const RGBA got = integ.IntegrateRay(o, d, 0.0, 2.0); // inside for t in [0.3, 1.3]
    std::printf("    chord %.12f: alpha %.15f expected %.15f\n", chord, got[3], expected(chord)[3]);
    Check(what, MaxDiff(got, expected(chord)), exactTol);
  };
  Volume rd = v;
  const std::array<double, 9> r = Rotation(1.0, 2.0, 3.0, 0.7);
  std::copy(r.begin(), r.end(), rd.Direction);
  rotatedCase(rd, "(a) rotated by direction matrix, |RGBA - closed form|");
  Volume rm = v;
  SetModel(rm, Rotation(-1.0, 0.5, 2.0, 1.1), 10.0, -4.0, 7.0);
  rotatedCase(rm, "(a) rotated by model matrix, |RGBA - closed form|");
}

void LinearRamp()
{
  // (b) Linear ramp s = x / 8 on x in [0, 8] (33 points, spacing 1/4: trilinear is exact for
  // linear data), ray along x, unit distance 1, alpha(s) = a + b s, c(s) = c0 + (c1 - c0) s.
  // With w(x) = 1 - a - b x / 8 and beta = b / 8, tau = -ln w and the optical depth is
  //   Lambda(x) = int_0^x -ln w = (F(w(x)) - F(w(0))) / beta,  F(w) = w ln w - w,
  // so A = 1 - exp(-Lambda(8)). Integrating C = int c tau e^-Lambda by parts
  // (d e^-Lambda = -tau e^-Lambda dx):
  //   C = c(0) - c(8) e^-Lambda(8) + c' int_0^8 e^-Lambda(x) dx,   c' = (c1 - c0) / 8,
  // the last integral of a smooth function by 8-point Gauss-Legendre on 64 panels (~1e-16).
  // (b1) constant colour: C = c A. (b2) constant alpha (tau constant):
  //   C = c0 (1 - e^-tau X) + c' ((1 - e^-tau X) / tau - X e^-tau X),  X = 8.
  // The integrator's error must stay below its stated leading-order bound GetErrorBound(8)
  // (where that is 0, the quantity is integrated exactly: 1e-13 is left for rounding).
  std::printf("(b) linear ramp, linear transfer functions\n");
  const double X = 8.0;
  Volume v =
    MakeVolume(33, 5, 5, 0.25, 0.25, 0.25, 0.0, 0.0, 0.0, [](int i, int, int) { return i / 32.0; });
  const double o[3] = { -1.0, 0.55, 0.6 }, d[3] = { 1.0, 0.0, 0.0 };
  struct Case
  {
    const char* Name;
    double A0, A1;
    double C0[3], C1[3];
  };
  const Case cases[3] = {
    { "(b1) linear alpha, constant colour", 0.05, 0.6, { 0.9, 0.5, 0.2 }, { 0.9, 0.5, 0.2 } },
    { "(b2) constant alpha, linear colour", 0.3, 0.3, { 0.0, 0.2, 1.0 }, { 1.0, 0.8, 0.0 } },
    { "(b3) linear alpha, linear colour", 0.05, 0.6, { 0.0, 0.2, 1.0 }, { 1.0, 0.8, 0.0 } },
  };
  for (const Case& cs : cases)
  {
    Volume cv = v;
    cv.Classification.Opacity = { cs.A0, cs.A1 };
    cv.Classification.Color = { cs.C0[0], cs.C0[1], cs.C0[2], cs.C1[0], cs.C1[1], cs.C1[2] };
    const double a = cs.A0, b = cs.A1 - cs.A0, beta = b / 8.0;
    auto lambda = [&](double x)
    {
      if (b == 0.0)
      {
        return -std::log(1.0 - a) * x;
      }
      auto F = [](double w) { return w * std::log(w) - w; };
      return (F(1.0 - a - beta * x) - F(1.0 - a)) / beta;
    };
    // int_0^X exp(-Lambda): composite 8-point Gauss-Legendre.
    static const double gx[4] = {
      0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363
    };
    static const double gw[4] = {
      0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763
    };
    double integralT = 0.0;
    const int panels = 64;
    for (int p = 0; p < panels; ++p)
    {
      const double lo = X * p / panels, half = 0.5 * X / panels, mid = lo + half;
      for (int q = 0; q < 4; ++q)
      {
        integralT +=
          half * gw[q] *
          (std::exp(-lambda(mid - half * gx[q])) + std::exp(-lambda(mid + half * gx[q])));
      }
    }
    const double TX = std::exp(-lambda(X));
    RGBA exact;
    exact[3] = 1.0 - TX;
    for (int ch = 0; ch < 3; ++ch)
    {
      const double cp = (cs.C1[ch] - cs.C0[ch]) / X;
      exact[ch] = cs.C0[ch] - cs.C1[ch] * TX + cp * integralT;
      if (b == 0.0) // (b2): the fully closed form, as a cross-check of the quadrature
      {
        const double tau = -std::log(1.0 - a);
        const double closed = cs.C0[ch] * (1.0 - TX) + cp * ((1.0 - TX) / tau - X * TX);
        if (std::abs(closed - exact[ch]) > 1e-14)
        {
          std::printf("    closed form and quadrature disagree: %g\n", closed - exact[ch]);
          ++Failures;
        }
        exact[ch] = closed;
      }
    }
    Integrator integ;
    integ.SetStepFraction(1.0 / 16.0);
    Add(integ, cv);
    const RGBA got = integ.IntegrateRay(o, d, 0.0, 10.0);
    const Integrator::ErrorBound bound = integ.GetErrorBound(X);
    integ.SetStepFraction(1.0 / 32.0);
    const RGBA fine = integ.IntegrateRay(o, d, 0.0, 10.0);
    const double errA = std::abs(got[3] - exact[3]);
    double errC = 0.0, errFine = MaxDiff(fine, exact);
    for (int ch = 0; ch < 3; ++ch)
    {
      errC = std::max(errC, std::abs(got[ch] - exact[ch]));
    }
    std::printf("    %s: A %.12f (exact %.12f), h = 1/64: err A %.3e C %.3e, "
                "h = 1/128: err %.3e (ratio %.2f)\n",
      cs.Name,
      got[3],
      exact[3],
      errA,
      errC,
      errFine,
      MaxDiff(got, exact) / errFine);
    char label[128];
    std::snprintf(label, sizeof(label), "%s, alpha error", cs.Name);
    Check(label, errA, std::max(bound.Alpha, 1e-13));
    std::snprintf(label, sizeof(label), "%s, colour error", cs.Name);
    Check(label, errC, std::max(bound.Color, 1e-13));
  }
}

void Mixing(int W, int H, const Mat4& cam, double exactTol)
{
  // (c) Mixing.
  std::printf("(c) coincident, nested and face-sharing volumes\n");
  // Two identical coincident volumes are one medium with twice the extinction: the same
  // transfer function at half the unit distance (tau = -ln(1 - alpha) / u exactly doubles).
  Volume v = MakeVolume(12, 10, 8, 1.0, 1.25, 0.75, -6.0, -5.0, -3.0, Smooth);
  SetModel(v, Rotation(0.2, 0.4, 1.0, 0.35), 0.25, 0.5, -0.5);
  v.Classification = RichTF(2.0);
  Integrator two, one;
  Add(two, v);
  Add(two, v);
  Volume dbl = v;
  dbl.Classification.UnitDistance = 1.0;
  Add(one, dbl);
  std::vector<double> imgTwo, imgOne;
  two.IntegrateImage(cam.data(), W, H, imgTwo);
  one.IntegrateImage(cam.data(), W, H, imgOne);
  const Integrator::ErrorBound eb = one.GetErrorBound(40.0);
  std::printf("    max alpha %.4f, step error bound (40 units) %.3e\n", MaxAlpha(imgOne), eb.Color);
  Check(
    "(c) two coincident = one with doubled tau, max |dRGBA|", MaxDiff(imgTwo, imgOne), exactTol);

  // Nested: a rotated, finer, nearest-sampled constant volume inside a constant box.
  Volume outer =
    MakeVolume(9, 9, 9, 1.0, 1.0, 1.0, -4.0, -4.0, -4.0, [](int, int, int) { return 0.0; });
  outer.Classification = ConstantTF(0.12, 0.9, 0.3, 0.1, 1.0);
  Volume inner =
    MakeVolume(5, 7, 4, 0.5, 0.5, 0.5, -0.5, -1.0, -0.75, [](int, int, int) { return 0.0; });
  const std::array<double, 9> r = Rotation(1.0, -1.0, 0.5, 0.8);
  std::copy(r.begin(), r.end(), inner.Direction);
  inner.Sampling = Integrator::Interpolation::Nearest;
  inner.Classification = ConstantTF(0.5, 0.1, 0.4, 1.0, 0.5);
  Integrator nested;
  Add(nested, outer);
  Add(nested, inner);
  const double cOuter[3] = { 0.9, 0.3, 0.1 }, cInner[3] = { 0.1, 0.4, 1.0 };
  const std::vector<Box> boxes = { BoxOf(outer, Tau(0.12, 1.0), cOuter),
    BoxOf(inner, Tau(0.5, 0.5), cInner) };
  std::vector<double> img;
  nested.IntegrateImage(cam.data(), W, H, img);
  const std::vector<double> ref = ExactImage(boxes, cam, W, H);
  std::printf("    nested: max alpha %.4f\n", MaxAlpha(img));
  Check("(c) nested volumes vs closed form, max |dRGBA|", MaxDiff(img, ref), exactTol);

  // Shared face z = 4: A (trilinear) below, B (nearest, other x-y resolution) above.
  Volume lower =
    MakeVolume(5, 5, 5, 1.0, 1.0, 1.0, -2.0, -2.0, 0.0, [](int, int, int) { return 0.0; });
  lower.Classification = ConstantTF(0.2, 1.0, 0.5, 0.0, 1.0);
  Volume upper =
    MakeVolume(9, 9, 5, 0.5, 0.5, 1.0, -2.0, -2.0, 4.0, [](int, int, int) { return 0.0; });
  upper.Sampling = Integrator::Interpolation::Nearest;
  upper.Classification = ConstantTF(0.35, 0.0, 0.5, 1.0, 1.0);
  Integrator shared;
  Add(shared, lower);
  Add(shared, upper);
  const double tA = Tau(0.2, 1.0), tB = Tau(0.35, 1.0);
  const double o[3] = { 0.3, -0.7, -1.0 }, dz[3] = { 0.0, 0.0, 1.0 };
  const RGBA got = shared.IntegrateRay(o, dz, 0.0, 10.0);
  const double TA = std::exp(-4.0 * tA), TB = std::exp(-4.0 * tB);
  const RGBA expect = { 1.0 * (1.0 - TA) + TA * 0.0 * (1.0 - TB),
    0.5 * (1.0 - TA) + TA * 0.5 * (1.0 - TB),
    0.0 * (1.0 - TA) + TA * 1.0 * (1.0 - TB),
    1.0 - TA * TB };
  std::printf("    shared face: alpha %.15f, 1 - T_A T_B = %.15f\n", got[3], expect[3]);
  Check("(c) shared face, ray along the normal vs T_A T_B, max |dRGBA|",
    MaxDiff(got, expect),
    exactTol);
  const double cl[3] = { 1.0, 0.5, 0.0 }, cu[3] = { 0.0, 0.5, 1.0 };
  const std::vector<Box> faceBoxes = { BoxOf(lower, tA, cl), BoxOf(upper, tB, cu) };
  shared.IntegrateImage(cam.data(), W, H, img);
  Check("(c) shared face, image vs closed form, max |dRGBA|",
    MaxDiff(img, ExactImage(faceBoxes, cam, W, H)),
    exactTol);
}

void RotationByDirectionMatrix(int W, int H, double exactTol)
{
  // (d) A 90-degree rotation about z in the direction matrix equals the permuted data:
  // V1 point (i, j, k) lies at O1 + (-j sy, i sx, k sz), which is V2's point (ny-1-j, i, k)
  // with V2 spacing (sy, sx, sz) and origin O1 - ((ny - 1) sy, 0, 0).
  std::printf("(d) rotation by direction matrix vs permuted data\n");
  for (int nearest = 0; nearest < 2; ++nearest)
  {
    const int nx = 10, ny = 7, nz = 6;
    const double sx = 1.0, sy = 0.8, sz = 1.2;
    Volume v1 = MakeVolume(nx, ny, nz, sx, sy, sz, 2.0, 1.0, -3.0, Smooth);
    const double rz[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
    std::copy(rz, rz + 9, v1.Direction);
    Volume v2 = MakeVolume(ny,
      nx,
      nz,
      sy,
      sx,
      sz,
      2.0 - (ny - 1) * sy,
      1.0,
      -3.0,
      [](int i2, int j2, int k) { return Smooth(j2, 7 - 1 - i2, k); });
    for (Volume* v : { &v1, &v2 })
    {
      v->Classification = RichTF(1.0);
      v->Sampling =
        nearest ? Integrator::Interpolation::Nearest : Integrator::Interpolation::Linear;
    }
    Integrator i1, i2;
    Add(i1, v1);
    Add(i2, v2);
    std::vector<double> img1, img2;
    const double eyeD[3] = { 12.0, 18.0, 10.0 }, centreD[3] = { -1.0, 4.5, 0.0 };
    const Mat4 camD = Camera(eyeD, centreD);
    i1.IntegrateImage(camD.data(), W, H, img1);
    i2.IntegrateImage(camD.data(), W, H, img2);
    std::printf("    %s: max alpha %.4f\n", nearest ? "nearest" : "trilinear", MaxAlpha(img1));
    Check(nearest ? "(d) rotated vs permuted (nearest), max |dRGBA|"
                  : "(d) rotated vs permuted (trilinear), max |dRGBA|",
      MaxDiff(img1, img2),
      exactTol);
  }
}

void TranslationToUTM(int W,
  int H,
  const double eye[3],
  const double centre[3],
  const Mat4& cam,
  double exactTol,
  std::vector<double>& base)
{
  // (e) Translation to UTM coordinates: the scene (model-matrix translation for one volume,
  // origin for the other) and the camera moved by (600000, 6700000, 0). The translated
  // clip->world matrix is itself rounded at UTM scale (ulp(6.7e6)/2 = 4.7e-10 in its translation
  // column, divided by w ~ 1 / eye distance for perspective): that moves the rays by
  // ~1e-10 x 30 = 3e-9 world units, which the integrator cannot undo. So the exact check runs
  // the local scene through the local equivalent of the UTM matrix (T^-1 times it, one rounding
  // at local scale, via fma); the raw comparison is printed against the bound its rounding allows.
  std::printf("(e) translation invariance at UTM coordinates\n");
  const double tr[3] = { 600000.0, 6700000.0, 0.0 };
  Integrator local, utm;
  AddOverlapScene(local, 0.0, 0.0, 0.0);
  AddOverlapScene(utm, tr[0], tr[1], tr[2]);
  double lo[3];
  utm.GetLocalOrigin(lo);
  std::printf("    UTM local origin (%.1f, %.1f, %.1f)\n", lo[0], lo[1], lo[2]);
  const Mat4 shift = { 1, 0, 0, tr[0], 0, 1, 0, tr[1], 0, 0, 1, tr[2], 0, 0, 0, 1 };
  auto untranslate = [&](const Mat4& m)
  {
    Mat4 back = m;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        const double p = tr[r] * m[12 + c];
        const double e = std::fma(tr[r], m[12 + c], -p); // tr * m = p + e exactly
        back[4 * r + c] = (m[4 * r + c] - p) - e;
      }
    }
    return back;
  };
  const double up[3] = { 0.0, 0.0, 1.0 };
  const Mat4 ortho = Inverse(WorldToClipOrtho(eye, centre, up, 12.0, 2.0, 80.0));
  for (int o = 0; o < 2; ++o)
  {
    const Mat4& camLocal = o ? ortho : cam;
    const Mat4 camUTM = Mul(shift, camLocal);
    std::vector<double> imgLocal, imgUTM, imgSame;
    local.IntegrateImage(camLocal.data(), W, H, imgLocal);
    utm.IntegrateImage(camUTM.data(), W, H, imgUTM);
    local.IntegrateImage(untranslate(camUTM).data(), W, H, imgSame);
    if (!o)
    {
      base = imgLocal;
    }
    std::printf("    %s: max alpha %.4f\n", o ? "orthographic" : "perspective", MaxAlpha(imgLocal));
    Check(o ? "(e) orthographic, same camera translated, max |dRGBA|"
            : "(e) perspective, same camera translated, max |dRGBA|",
      MaxDiff(imgUTM, imgSame),
      exactTol);
    Check(o ? "(e) orthographic, T * camera rounded at UTM, max |dRGBA|"
            : "(e) perspective, T * camera rounded at UTM, max |dRGBA|",
      MaxDiff(imgUTM, imgLocal),
      1e-8);
  }
}

void ThinVolume(double exactTol)
{
  // (f) One-voxel-thin volume (nz = 1, sz = 1/4): one spacing thick, values constant across.
  std::printf("(f) one-voxel-thin volume\n");
  for (int nearest = 0; nearest < 2; ++nearest)
  {
    Volume v = MakeVolume(
      6, 6, 1, 1.0, 1.0, 0.25, 0.0, 0.0, 5.0, [](int i, int j, int) { return 0.1 * i + 0.05 * j; });
    v.Classification.Opacity = { 0.2, 0.8 };
    v.Classification.Color = { 0.2, 0.4, 0.6, 1.0, 0.8, 0.0 };
    v.Sampling = nearest ? Integrator::Interpolation::Nearest : Integrator::Interpolation::Linear;
    Integrator integ;
    Add(integ, v);
    // Trilinear at (2.5, 1.5): s = 0.325 (linear data); nearest at (2.4, 1.3): s(2, 1) = 0.25.
    const double s = nearest ? 0.25 : 0.325;
    const double o[3] = { nearest ? 2.4 : 2.5, nearest ? 1.3 : 1.5, 3.0 }, d[3] = { 0, 0, 1 };
    const double alpha = 0.2 + 0.6 * s, tau = Tau(alpha, 1.0);
    const double a = 1.0 - std::exp(-tau * 0.25);
    const RGBA expect = { (0.2 + 0.8 * s) * a, (0.4 + 0.4 * s) * a, 0.6 * (1.0 - s) * a, a };
    const RGBA got = integ.IntegrateRay(o, d, 0.0, 4.0);
    std::printf("    %s: alpha %.15f, 1 - exp(-tau sz) = %.15f\n",
      nearest ? "nearest" : "trilinear",
      got[3],
      a);
    Check(nearest ? "(f) thin volume along z (nearest), max |dRGBA|"
                  : "(f) thin volume along z (trilinear), max |dRGBA|",
      MaxDiff(got, expect),
      exactTol);
  }
}

void Convergence(int W, int H, const Mat4& cam, const std::vector<double>& base)
{
  // (g) Convergence on the overlap scene: halving h changes the image by at most
  // B(h) + B(h/2) = 1.25 B(h) (B: the stated leading-order bound, for the longest possible
  // covered length, the sum of the box diagonals); second order shows as a ratio near 4.
  std::printf("(g) convergence when halving the step\n");
  Integrator integ;
  AddOverlapScene(integ, 0.0, 0.0, 0.0);
  const double diagonals = std::sqrt(13.0 * 13.0 + 13.75 * 13.75 + 6.0 * 6.0) +
                           std::sqrt(6.4 * 6.4 + 7.0 * 7.0 + 5.4 * 5.4);
  std::vector<double> coarse, mid, fine;
  integ.SetStepFraction(1.0 / 8.0);
  integ.IntegrateImage(cam.data(), W, H, coarse);
  const Integrator::ErrorBound b8 = integ.GetErrorBound(diagonals);
  integ.SetStepFraction(1.0 / 16.0);
  integ.IntegrateImage(cam.data(), W, H, mid);
  const Integrator::ErrorBound b16 = integ.GetErrorBound(diagonals);
  integ.SetStepFraction(1.0 / 32.0);
  integ.IntegrateImage(cam.data(), W, H, fine);
  const double d1 = MaxDiff(coarse, mid), d2 = MaxDiff(mid, fine);
  std::printf("    max |I(1/8) - I(1/16)| = %.3e, max |I(1/16) - I(1/32)| = %.3e, ratio %.2f\n",
    d1,
    d2,
    d1 / d2);
  std::printf("    stated bounds B(1/8): alpha %.3e colour %.3e; B(1/16): alpha %.3e colour %.3e\n",
    b8.Alpha,
    b8.Color,
    b16.Alpha,
    b16.Color);
  Check("(g) |I(1/8) - I(1/16)| vs 1.25 B(1/8)", d1, 1.25 * std::max(b8.Alpha, b8.Color));
  Check("(g) |I(1/16) - I(1/32)| vs 1.25 B(1/16)", d2, 1.25 * std::max(b16.Alpha, b16.Color));
  Check("(g) second order: |ratio - 4|", d1 / d2 - 4.0, 1.0);
  Check("(g) explicit 1/16 equals the default step ((e)), max |dRGBA|", MaxDiff(mid, base), 0.0);
}

void StartAndStop(const Mat4& cam)
{
  // (h) Per-pixel start and stop, as window depths (projected by the test's own world->clip)
  // and as world distances, against single rays over the same t range. Depth -> t through the
  // projection costs ~1e-16 / (1 - depth) relative in t, far below the bound.
  std::printf("(h) per-pixel start and stop\n");
  Integrator integ;
  AddOverlapScene(integ, 0.0, 0.0, 0.0);
  const int w = 12, h = 12;
  const Mat4 worldToClip = Inverse(cam);
  std::vector<double> startDepth(w * h), stopDepth(w * h), startDist(w * h), stopDist(w * h);
  std::vector<RGBA> both(w * h), startOnly(w * h), stopOnly(w * h);
  for (int py = 0; py < h; ++py)
  {
    for (int px = 0; px < w; ++px)
    {
      const int idx = py * w + px;
      const double nx = (px + 0.5) / w * 2.0 - 1.0, ny = (py + 0.5) / h * 2.0 - 1.0;
      double a[3], b[3], d[3];
      Transform(cam, nx, ny, -1.0, a);
      Transform(cam, nx, ny, 1.0, b);
      for (int k = 0; k < 3; ++k)
      {
        d[k] = b[k] - a[k];
      }
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double t0 = 0.25 + 0.002 * px, t1 = 0.4 + 0.003 * py;
      auto depthAt = [&](double t)
      {
        double q[3];
        Transform(worldToClip, a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2], q);
        return 0.5 * (q[2] + 1.0);
      };
      startDepth[idx] = depthAt(t0);
      stopDepth[idx] = depthAt(t1);
      startDist[idx] = t0 * len;
      stopDist[idx] = t1 * len;
      both[idx] = integ.IntegrateRay(a, d, t0, t1);
      startOnly[idx] = integ.IntegrateRay(a, d, t0, 1.0);
      stopOnly[idx] = integ.IntegrateRay(a, d, 0.0, t1);
    }
  }
  auto compare = [&](const std::vector<double>& img, const std::vector<RGBA>& ref)
  {
    double m = 0.0;
    for (int idx = 0; idx < w * h; ++idx)
    {
      for (int k = 0; k < 4; ++k)
      {
        m = std::max(m, std::abs(img[4 * idx + k] - ref[idx][k]));
      }
    }
    return m;
  };
  using DK = Integrator::DepthKind;
  std::vector<double> img;
  integ.IntegrateImage(cam.data(), w, h, img, nullptr, stopDepth.data(), DK::WindowDepth);
  Check("(h) stop as window depth vs IntegrateRay, max |dRGBA|", compare(img, stopOnly), 1e-9);
  double maxA = MaxAlpha(img);
  integ.IntegrateImage(cam.data(), w, h, img, startDepth.data(), stopDepth.data());
  Check("(h) start and stop as window depths, max |dRGBA|", compare(img, both), 1e-9);
  integ.IntegrateImage(cam.data(), w, h, img, startDist.data(), nullptr, DK::WorldDistance);
  Check("(h) start as world distance vs IntegrateRay, max |dRGBA|", compare(img, startOnly), 1e-9);
  maxA = std::max(maxA, MaxAlpha(img));
  integ.IntegrateImage(cam.data(), w, h, img, startDist.data(), stopDist.data(), DK::WorldDistance);
  Check("(h) start and stop as world distances, max |dRGBA|", compare(img, both), 1e-9);
  std::printf("    max alpha of the clipped rays %.4f\n", maxA);
}

// (i) Blend modes on the ramp s = x / 10 over x in [0, 10] (11 points, spacing 1), opacity
// 0.2 + 0.3 s per unit, colour (s, 0, 1 - s), one ray along x: closed forms. Reductions take
// midpoint samples h = 1/16 apart, so the extreme's scalar is off by at most the ramp's slope
// times h / 2 (0.0031): tolerance 0.1 h on RGBA. Averages of a quadratic by the midpoint rule:
// off by h^2 / 12 times its curvature, under 1e-4. Contours of a ramp are found exactly.
void BlendModes()
{
  std::printf("(i) blend modes\n");
  using B = Integrator::Blend;
  Volume ramp =
    MakeVolume(11, 3, 3, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, [](int i, int, int) { return 0.1 * i; });
  ramp.Classification.Opacity = { 0.2, 0.5 };
  ramp.Classification.Color = { 0.0, 0.0, 1.0, 1.0, 0.0, 0.0 };
  auto layer = [](double s) { // colour and opacity of scalar s, premultiplied
    const double a = 0.2 + 0.3 * s;
    return RGBA{ s * a, 0.0, (1.0 - s) * a, a };
  };
  auto over = [](const RGBA& front, const RGBA& back)
  {
    RGBA r;
    for (int k = 0; k < 4; ++k)
      r[k] = front[k] + (1.0 - front[3]) * back[k];
    return r;
  };
  const double h = 1.0 / 16.0;
  const double o[3] = { -2.0, 1.0, 1.0 }, d[3] = { 1.0, 0.0, 0.0 };
  const double ob[3] = { 12.0, 1.0, 1.0 }, db[3] = { -1.0, 0.0, 0.0 };
  auto ray = [&](const std::vector<Volume>& volumes, bool backwards)
  {
    Integrator integ;
    for (const Volume& v : volumes)
      Add(integ, v);
    return integ.IntegrateRay(backwards ? ob : o, backwards ? db : d, 0.0, 14.0);
  };
  Volume v = ramp;
  v.BlendMode = B::Maximum;
  Check("(i) maximum: the colour of s = 1", MaxDiff(ray({ v }, false), layer(1.0)), 0.1 * h);
  v.BlendMode = B::Minimum;
  Check("(i) minimum: the colour of s = 0", MaxDiff(ray({ v }, false), layer(0.0)), 0.1 * h);
  // mean of alpha(s) s = 0.2 s + 0.3 s^2 over s in [0, 1]: 0.2; over [0.5, 1]: 0.325.
  v.BlendMode = B::Average;
  Check("(i) average: grey 0.2", MaxDiff(ray({ v }, false), RGBA{ 0.2, 0.2, 0.2, 1.0 }), 1e-4);
  v.AverageRange[0] = 0.5;
  Check("(i) average over [0.5, 1]: grey 0.325",
    MaxDiff(ray({ v }, false), RGBA{ 0.325, 0.325, 0.325, 1.0 }),
    1e-4);
  // the integral over the 10 units, 2, per unit distance 20: 0.1.
  v = ramp;
  v.BlendMode = B::Additive;
  v.Classification.UnitDistance = 20.0;
  Check("(i) additive: grey 0.1", MaxDiff(ray({ v }, false), RGBA{ 0.1, 0.1, 0.1, 1.0 }), 1e-4);
  v.Classification.UnitDistance = 1.0;
  Check("(i) additive clamped to 1", MaxDiff(ray({ v }, false), RGBA{ 1.0, 1.0, 1.0, 1.0 }), 1e-12);
  // Contours at s = 0.3 and 0.7 (x = 3 and 7): two surfaces, nearest first either way.
  v = ramp;
  v.BlendMode = B::IsoSurface;
  v.IsoValues = { 0.7, 0.3 };
  Check("(i) isosurfaces along +x", MaxDiff(ray({ v }, false), over(layer(0.3), layer(0.7))), 1e-9);
  Check("(i) isosurfaces along -x", MaxDiff(ray({ v }, true), over(layer(0.7), layer(0.3))), 1e-9);
  // Among a composite medium: a constant box over x in [4, 6] (tau 0.5, grey 0.5) lies between
  // the contours, and in front of the maximum's layer (at x = 10) along +x, behind it along -x.
  Volume box = MakeVolume(3, 3, 3, 1.0, 1.0, 1.0, 4.0, 0.0, 0.0, [](int, int, int) { return 0.0; });
  box.Classification = ConstantTF(1.0 - std::exp(-0.5), 0.5, 0.5, 0.5, 1.0);
  const double a = 1.0 - std::exp(-1.0); // 2 units at tau 0.5
  const RGBA medium = { 0.5 * a, 0.5 * a, 0.5 * a, a };
  Check("(i) contours around a composite medium",
    MaxDiff(ray({ v, box }, false), over(layer(0.3), over(medium, layer(0.7)))),
    1e-9);
  v = ramp;
  v.BlendMode = B::Maximum;
  Check("(i) maximum's layer behind the medium along +x",
    MaxDiff(ray({ v, box }, false), over(medium, layer(1.0))),
    0.1 * h);
  Check("(i) maximum's layer in front of the medium along -x",
    MaxDiff(ray({ v, box }, true), over(layer(1.0), medium)),
    0.1 * h);
}
}

namespace
{
// Translucent surfaces: layers at their exact crossing, in ray order with the media.
void Surfaces(double exactTol)
{
  std::printf("(j) translucent surfaces\n");
  auto over = [](const RGBA& front, const RGBA& back)
  {
    RGBA r;
    for (int k = 0; k < 4; ++k)
      r[k] = front[k] + (1.0 - front[3]) * back[k];
    return r;
  };
  // A constant box over x in [0, 10] (tau 0.5, grey 0.5), a ray along +x from x = -2.
  Volume box =
    MakeVolume(11, 3, 3, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, [](int, int, int) { return 0.0; });
  box.Classification = ConstantTF(1.0 - std::exp(-0.5), 0.5, 0.5, 0.5, 1.0);
  auto medium = [](double length)
  {
    const double a = 1.0 - std::exp(-0.5 * length);
    return RGBA{ 0.5 * a, 0.5 * a, 0.5 * a, a };
  };
  // Surfaces x = c, spanning y, z in [-5, 5]: colour 0.4 (0.3, 0.1, 0.2) premultiplied.
  auto plane = [](double x)
  {
    Integrator::Surface s;
    const double corner[3] = { x, -5.0, -5.0 }, e1[3] = { 0.0, 10.0, 0.0 },
                 e2[3] = { 0.0, 0.0, 10.0 };
    std::copy(corner, corner + 3, s.Corner);
    std::copy(e1, e1 + 3, s.Edge1);
    std::copy(e2, e2 + 3, s.Edge2);
    const double c[4] = { 0.12, 0.04, 0.08, 0.4 };
    std::copy(c, c + 4, s.Color);
    return s;
  };
  const RGBA layer = { 0.12, 0.04, 0.08, 0.4 };
  const double o[3] = { -2.0, 1.0, 1.0 }, d[3] = { 1.0, 0.0, 0.0 };
  auto ray = [&](const std::vector<double>& xs, double t1)
  {
    Integrator integ;
    Add(integ, box);
    for (double x : xs)
      integ.AddSurface(plane(x));
    return integ.IntegrateRay(o, d, 0.0, t1);
  };
  Check("(j) surface inside the medium at x = 3",
    MaxDiff(ray({ 3.0 }, 14.0), over(medium(3.0), over(layer, medium(7.0)))),
    exactTol);
  Check("(j) two surfaces, given far first, nearest composited first",
    MaxDiff(ray({ 8.0, 3.0 }, 14.0),
      over(medium(3.0), over(layer, over(medium(5.0), over(layer, medium(2.0)))))),
    exactTol);
  Check("(j) surfaces in front of and behind the medium",
    MaxDiff(ray({ -1.0, 11.0 }, 14.0), over(layer, over(medium(10.0), layer))),
    exactTol);
  Check("(j) a surface beyond the stop is not reached",
    MaxDiff(ray({ 3.0, 8.0 }, 7.0), over(medium(3.0), over(layer, medium(2.0)))),
    exactTol);
  Integrator integ;
  Add(integ, box);
  integ.AddSurface(plane(3.0));
  const double away[3] = { -2.0, 7.0, 1.0 }; // y = 7: misses the surface (|y| <= 5) and the box
  Check("(j) a ray beside the surface meets nothing",
    MaxDiff(integ.IntegrateRay(away, d, 0.0, 14.0), RGBA{ 0.0, 0.0, 0.0, 0.0 }),
    0.0);
}
}

int TestMultiVolumeReferenceIntegrator(int, char*[])
{
  const auto startTime = std::chrono::steady_clock::now();
  const double exactTol = 1e-9; // closed forms of piecewise-constant media: rounding only

  // Camera for the images: perspective, oblique, 48 x 48.
  const int W = 48, H = 48;
  const double eye[3] = { 17.0, -21.0, 13.0 }, centre[3] = { 0.5, 0.25, 0.0 };
  const Mat4 cam = Camera(eye, centre);
  std::vector<double> base; // (e)'s image, the default step's, which (g) compares with
  strata_test::RunSubTests(
    {
      { "ConstantBoxes", [&] { ConstantBoxes(exactTol); } },
      { "LinearRamp", [&] { LinearRamp(); } },
      { "Mixing", [&] { Mixing(W, H, cam, exactTol); } },
      { "RotationByDirectionMatrix", [&] { RotationByDirectionMatrix(W, H, exactTol); } },
      { "TranslationToUTM", [&] { TranslationToUTM(W, H, eye, centre, cam, exactTol, base); } },
      { "ThinVolume", [&] { ThinVolume(exactTol); } },
      { "Convergence", [&] { Convergence(W, H, cam, base); } },
      { "StartAndStop", [&] { StartAndStop(cam); } },
      { "BlendModes", [&] { BlendModes(); } },
      { "Surfaces", [&] { Surfaces(exactTol); } },
    },
    [] { return Failures; });

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
  std::printf("%d failure(s), %.2f s\n", Failures, seconds);
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

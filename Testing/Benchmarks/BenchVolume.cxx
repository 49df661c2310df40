// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Benchmark of the multi-volume ray caster (vtkMultiVolumeRayCastMapper): its accuracy and cost
// against the double-precision reference integrator over its settings, and its frame time
// against VTK's vtkGPUVolumeRayCastMapper on one volume, on a sparse volume and on VTK's own
// multi-volume path (vtkMultiVolume), plus the BSP rebuild time. scripts/bench volume runs the
// sub-modes, one process each (one per mapper where peak memory is measured), and collects
// bench-results/volume.csv. Usage:
//   BenchVolume header                      -> the CSV header line
//   BenchVolume accuracy <data>             -> the settings grid at 256 x 256, each image
//                                              against the reference
//   BenchVolume blend <data>                -> every blend mode at two sample distances, each
//                                              against the reference of that mode
//   BenchVolume frame <single|sparse> <data> [<method>=<MB>,...] [--viewport <w>x<h>]
//                                           -> strata, strata-no-atlas (each in the fragment
//                                              and the compute stage, -compute) and VTK at 512 x
//                                              512 (or the viewport), timed interleaved: wall, GPU
//                                              (GL_TIME_ELAPSED) and render-thread CPU ms per
//                                              frame and the stage; peak RSS from `memory`
//   BenchVolume memory <single|sparse> <data> <strata[-no-atlas][-compute]|vtk>
//                                           -> "<method>=<peak RSS MB>", one mapper alone
//   BenchVolume storage <data>              -> the lean atlas: the data as uint8, uint16, int16
//                                              and float32 under one atlas budget
//   BenchVolume components <data>           -> two independent components and RGBA, in core
//                                              and paged from component pools
//   BenchVolume layers                      -> TranslucentLayers 1 .. 7 with six translucent
//                                              planes through two volumes, against the reference
//   BenchVolume multi <2-4>                 -> Strata (both stages) and VTK's vtkMultiVolume, 96^3
//   volumes BenchVolume bsp <volumes> [ring|grid]   -> ms per strata::VolumeBSPTree::Build
//   BenchVolume converge <data> [1/h 1/h']  -> reference at step 1/16 against 1/32 of a voxel
//   BenchVolume report <csv> <png>          -> summary tables and the RMS-vs-time plot
// Each prints CSV rows on stdout and progress on stderr. Data: bucky, tooth, engine, bonsai,
// read from <shared>/volumes with `--shared-data <shared>` (default ../shared/data; bucky and
// tooth first from <data>/volumes with `-D <data>`, StrataTestPaths.h); a missing file gives a row
// with a note, never a failure.
// sample_distance is in world units; every volume here has unit spacing, so it is in voxels.
// Frame times are the median of several renders after warm-up, each ended by
// WaitForCompletion. STRATA_BENCH_FRAMES overrides the number of timed frames;
// STRATA_BENCH_IMAGES names a directory to write each measured image (and its reference) to.
// Checks of the reference itself: STRATA_BENCH_CONVERGE=1 makes `multi` also compare its
// reference with one at half the step; STRATA_BENCH_UNSNAPPED=1 makes `converge` also compare
// with the integrator fed ToReferenceVolume's float tables as they are (see SnapRuns).
#include "BenchVolumeReport.h"
#include "StrataBenchChart.h"
#include "StrataFrameTimer.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataRealVolumes.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "StrataVolumeBSPTree.h"
#include "vtkAxis.h"
#include "vtkCamera.h"
#include "vtkChartXY.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNrrdReader.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlotPoints.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h> // For getpid

using strata_test::PeakRssMB;

namespace
{
using Clock = std::chrono::steady_clock;
using Classifications = vtkMultiVolumeRayCastMapper::Classifications;
using CompositeOrders = vtkMultiVolumeRayCastMapper::CompositeOrders;
const double NaN = std::numeric_limits<double>::quiet_NaN();
// CompareVolumesWithReference's background: mid grey, exact in 8 bits, so that opacity errors
// show as well as colour errors.
const double Grey = 128.0 / 255.0;
// The reference integrator's step, as a fraction of a voxel: converged, see Accuracy().
const double ReferenceStep = 1.0 / 16.0;

const char* const Header = "case,method,ms_per_frame,rms_error,classification,order,rays,coherence,"
                           "sample_distance,volumes,rms_error_same_rays,width,height,fragments,"
                           "peak_rss_mb,blend_mode,note,gpu_ms,cpu_ms,stage";

/// The viewport of the frame and memory cases (--viewport <width>x<height>; 512 x 512 unless
/// given): a data-center GPU's view is 1920 x 1080.
int Viewport[2] = { 512, 512 };

/// One CSV row; NaN or negative fields are written empty.
struct Row
{
  std::string Case, Method;
  double Ms = NaN, Rms = NaN;
  std::string Classification, Order;
  int Rays = -1, Coherence = -1;
  double SampleDistance = NaN;
  int Volumes = -1;
  double RmsSameRays = NaN;
  int Width = -1, Height = -1, Fragments = -1;
  double PeakRss = NaN;
  std::string BlendMode; ///< empty: composite (every row but the blend-mode grid's)
  std::string Note;
  double GpuMs = NaN, CpuMs = NaN; ///< per frame: GL_TIME_ELAPSED, the render thread's CPU
  std::string Stage; ///< fragment or compute (Strata's), vtk (VTK's mapper); empty: untimed

  std::string Csv() const
  {
    std::ostringstream s;
    auto num = [&](double v, int digits)
    {
      if (!std::isnan(v))
      {
        char b[32];
        std::snprintf(b, sizeof(b), "%.*f", digits, v);
        s << b;
      }
      s << ',';
    };
    auto integer = [&](int v)
    {
      if (v >= 0)
        s << v;
      s << ',';
    };
    s << this->Case << ',' << this->Method << ',';
    num(this->Ms, this->Ms < 1.0 ? 4 : this->Ms < 10.0 ? 3 : 1);
    num(this->Rms, 3);
    s << this->Classification << ',' << this->Order << ',';
    integer(this->Rays);
    s << (this->Coherence < 0 ? "" : this->Coherence ? "on" : "off") << ',';
    num(this->SampleDistance, 3);
    integer(this->Volumes);
    num(this->RmsSameRays, 3);
    integer(this->Width);
    integer(this->Height);
    integer(this->Fragments);
    num(this->PeakRss, 0);
    s << this->BlendMode << ',';
    std::string note = this->Note;
    std::replace(note.begin(), note.end(), ',', ';'); // one field, unquoted
    s << note << ',';
    num(this->GpuMs, 3);
    num(this->CpuMs, 3);
    s << this->Stage;
    return s.str();
  }
};

void Emit(const Row& row)
{
  std::cout << row.Csv() << std::endl;
}

/// A case whose data is missing: said on stderr and as a row with the reason.
int Skipped(const std::string& name, const std::string& why)
{
  std::cerr << name << ": skipped: " << why << "\n";
  Row row;
  row.Case = name;
  row.Method = "strata";
  row.Note = "skipped: " + why;
  Emit(row);
  return 0;
}

/// The 1-minute load average: this machine's 2 cores are shared, and the timings show it.
std::string LoadNote()
{
  std::ifstream in("/proc/loadavg");
  std::string load;
  in >> load;
  return load.empty() ? std::string() : "; load average " + load;
}

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

int TimedFrames(int fallback)
{
  const char* n = std::getenv("STRATA_BENCH_FRAMES");
  return n && std::atoi(n) > 0 ? std::atoi(n) : fallback;
}

// --- Data sets ------------------------------------------------------------------------------

/// Fraction of points whose opacity under `p` is not zero.
double VisibleFraction(vtkImageData* image, vtkVolumeProperty* p)
{
  vtkDataArray* s = image->GetPointData()->GetScalars();
  vtkPiecewiseFunction* pwf = p->GetScalarOpacity(0);
  long visible = 0;
  for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
    visible += pwf->GetValue(s->GetComponent(i, 0)) > 0.0;
  return double(visible) / std::max<vtkIdType>(1, s->GetNumberOfTuples());
}

// --- Scenes ---------------------------------------------------------------------------------

/// Renders until uploads, shader compiles and the brick cut of `strata` (which may refine over
/// several frames) are done: at least `minimum` frames, then until the resident bricks stop
/// changing (at most 10). Returns the number of frames rendered.
int WarmUp(vtkRenderWindow* win, vtkMultiVolumeRayCastMapper* strata, int minimum)
{
  int frames = 0, bricks = -1;
  do
  {
    bricks = strata ? strata->GetNumberOfResidentBricks() : 0;
    win->Render();
    win->WaitForCompletion();
    ++frames;
  } while (
    frames < minimum || (strata && strata->GetNumberOfResidentBricks() != bricks && frames < 10));
  return frames;
}

double Median(std::vector<double> v)
{
  if (v.empty())
    return NaN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Median of `frames` timed renders (after warm-up), each ended by WaitForCompletion.
double MedianMs(vtkRenderWindow* win, int frames)
{
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i)
  {
    const auto t0 = Clock::now();
    win->Render();
    win->WaitForCompletion();
    ms.push_back(1000.0 * Seconds(t0));
  }
  return Median(ms);
}

// --- Reference --------------------------------------------------------------------------------

/// The reference image as CompareVolumesWithReference forms it, before rounding to 8 bits:
/// RGB in 8-bit units, the reference's premultiplied colour over the grey background.
struct Reference
{
  std::vector<double> Rgb;
  int Width = 0, Height = 0;
  long Covered = 0;
  double Seconds = 0.0;
};

/**
 * Makes every straight run of a table an exact arithmetic progression. The integrator splits
 * rays wherever a table's slope changes, comparing slopes exactly; the mapper's 1024-entry float
 * table (which ToReferenceVolume copies) has rounding noise in every slope, so every entry counts
 * as a kink: a cell whose 8-bit scalars span 100 units is cut into ~400 pieces, each root-found
 * and given the full number of steps. Here runs are grown greedily while the straight line from a
 * run's first entry to its last stays within 1e-6 of the channel's largest value of every entry
 * between (float noise is 6e-8 of it, so runs span whole linear pieces of the transfer
 * function); each run becomes a + k d with a and d multiples of 2^-40, so that all its values
 * and differences are exact and its slopes bit-identical. The table then differs from the
 * mapper's by at most 1e-6 of its largest value, far below an 8-bit step (4e-3), and the
 * integrator splits only at the transfer function's real nodes: the bucky reference at 256 x 256
 * and step 1/16 takes 1.0 s instead of 50 s, and the two differ by RMS 0.0005 (max 0.006) of an
 * 8-bit step.
 */
void SnapRuns(std::vector<double>& table, size_t stride, size_t offset)
{
  const size_t n = table.size() / stride;
  if (n < 2)
    return;
  std::vector<double> original(n);
  for (size_t k = 0; k < n; ++k)
    original[k] = table[k * stride + offset];
  auto grid = [](double x) { return std::ldexp(std::round(std::ldexp(x, 40)), -40); };
  double largest = 0.0;
  for (double v : original)
    largest = std::max(largest, std::abs(v));
  const double tolerance = 1e-6 * largest;
  std::vector<double> snapped(n);
  snapped[0] = grid(original[0]);
  size_t start = 0;
  while (start + 1 < n)
  {
    // The longest run [start, end] whose line through snapped[start] and original[end] stays
    // within the tolerance of every entry in between.
    const double a = snapped[start];
    size_t end = start + 1;
    double d = grid(original[end] - a);
    for (size_t e = end + 1; e < n; ++e)
    {
      const double de = grid((original[e] - a) / double(e - start));
      bool straight = true;
      for (size_t m = start + 1; m <= e && straight; ++m)
        straight = std::abs(a + double(m - start) * de - original[m]) <= tolerance;
      if (!straight)
        break;
      end = e;
      d = de;
    }
    for (size_t m = start + 1; m <= end; ++m)
      snapped[m] = a + double(m - start) * d;
    start = end;
  }
  for (size_t k = 0; k < n; ++k)
    table[k * stride + offset] = snapped[k];
}

/// ToReferenceVolume with its tables' runs made exact (SnapRuns).
strata::MultiVolumeReferenceIntegrator::Volume ReferenceVolume(vtkImageData* image,
  vtkVolume* member,
  vtkMultiVolumeRayCastMapper* mapper = nullptr)
{
  auto v = strata_test::ToReferenceVolume(image, member, mapper, 0);
  SnapRuns(v.Classification.Opacity, 1, 0);
  for (size_t c = 0; c < 3 && !v.Classification.Color.empty(); ++c)
    SnapRuns(v.Classification.Color, 3, c);
  return v;
}

/// The reference with one ray per pixel through the pixel centre moved by `offset` pixels.
Reference ComputeReference(vtkRenderer* ren,
  int width,
  int height,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  double stepFraction,
  bool snap = true,
  const double offset[2] = nullptr,
  vtkMultiVolumeRayCastMapper* blendOf = nullptr)
{
  const auto t0 = Clock::now();
  strata::MultiVolumeReferenceIntegrator integrator;
  integrator.SetStepFraction(stepFraction);
  for (const auto& v : volumes)
  {
    if (integrator.AddVolume(snap ? ReferenceVolume(v.first, v.second, blendOf)
                                  : strata_test::ToReferenceVolume(v.first, v.second)) < 0)
    {
      std::cerr << "reference rejected a volume: " << integrator.GetLastError() << "\n";
    }
  }
  vtkNew<vtkMatrix4x4> worldToClip, clipToWorld;
  worldToClip->DeepCopy(
    ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(double(width) / height, -1, 1));
  if (offset)
  {
    // Shift the image by -offset (a pixel is 2 / size in NDC), so that the integrator's ray
    // through a pixel centre goes through centre + offset of the unshifted image.
    vtkNew<vtkMatrix4x4> shift, shifted;
    shift->SetElement(0, 3, -2.0 * offset[0] / width);
    shift->SetElement(1, 3, -2.0 * offset[1] / height);
    vtkMatrix4x4::Multiply4x4(shift, worldToClip, shifted);
    worldToClip->DeepCopy(shifted);
  }
  vtkMatrix4x4::Invert(worldToClip, clipToWorld);
  std::vector<double> rgba;
  integrator.IntegrateImage(clipToWorld->GetData(), width, height, rgba);
  Reference r;
  r.Width = width;
  r.Height = height;
  r.Rgb.resize(3 * size_t(width) * height);
  for (int i = 0; i < width * height; ++i)
  {
    r.Covered += rgba[4 * i + 3] > 1.0 / 255.0;
    for (int c = 0; c < 3; ++c)
      r.Rgb[3 * i + c] = 255.0 * std::min(1.0, rgba[4 * i + c] + (1.0 - rgba[4 * i + 3]) * Grey);
  }
  r.Seconds = Seconds(t0);
  return r;
}

/**
 * The converged value of what the mapper computes with `rays` rays per pixel: the mean of the
 * references through its rays' sub-pixel positions (vtkMultiVolumeRayCastMapper::GetRayOffset).
 * Against this, only the integration error of the rays is left; against the pixel-centre
 * reference, also the difference between the rays' mean and the centre (anti-aliasing blur, and
 * any shift of the pattern's centroid). References of offsets already computed are reused.
 */
Reference SameRaysReference(vtkRenderer* ren,
  int width,
  int height,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  int rays,
  std::map<std::pair<double, double>, Reference>& byOffset)
{
  Reference mean;
  for (int r = 0; r < rays; ++r)
  {
    double offset[2];
    vtkMultiVolumeRayCastMapper::GetRayOffset(r, rays, offset);
    const auto key = std::make_pair(offset[0], offset[1]);
    if (!byOffset.count(key))
      byOffset[key] = ComputeReference(ren, width, height, volumes, ReferenceStep, true, offset);
    const Reference& one = byOffset[key];
    if (r == 0)
    {
      mean = one;
      mean.Seconds = 0.0;
    }
    else
      for (size_t i = 0; i < mean.Rgb.size(); ++i)
        mean.Rgb[i] += one.Rgb[i];
    mean.Seconds += one.Seconds;
  }
  for (double& v : mean.Rgb)
    v /= rays;
  return mean;
}

/// RMS over all pixels and channels, in 8-bit units, as CompareVolumesWithReference.
double Rms(const std::vector<unsigned char>& gpu, const Reference& ref, double* maxError = nullptr)
{
  double se = 0.0, mx = 0.0;
  for (size_t i = 0; i < ref.Rgb.size(); ++i)
  {
    const double d = double(gpu[i]) - ref.Rgb[i];
    se += d * d;
    mx = std::max(mx, std::abs(d));
  }
  if (maxError)
    *maxError = mx;
  return std::sqrt(se / std::max<size_t>(1, ref.Rgb.size()));
}

/// RMS and largest difference of two references, in 8-bit units.
double Difference(const Reference& a, const Reference& b, double* maxError)
{
  double se = 0.0, mx = 0.0;
  for (size_t i = 0; i < a.Rgb.size(); ++i)
  {
    const double d = a.Rgb[i] - b.Rgb[i];
    se += d * d;
    mx = std::max(mx, std::abs(d));
  }
  *maxError = mx;
  return std::sqrt(se / std::max<size_t>(1, a.Rgb.size()));
}

void MaybeWriteImages(const std::string& name,
  const std::vector<unsigned char>& gpu,
  const Reference* ref,
  int width,
  int height)
{
  const char* dir = std::getenv("STRATA_BENCH_IMAGES");
  if (!dir || !*dir)
    return;
  strata_test::WritePNG(std::string(dir) + "/" + name + ".png", gpu, width, height);
  if (ref)
  {
    std::vector<unsigned char> r(ref->Rgb.size());
    for (size_t i = 0; i < r.size(); ++i)
      r[i] = static_cast<unsigned char>(std::lround(ref->Rgb[i]));
    strata_test::WritePNG(std::string(dir) + "/" + name + "-ref.png", r, width, height);
  }
}

const char* ClassificationName(Classifications c)
{
  return c == Classifications::PostClassification ? "post"
         : c == Classifications::PreIntegrated    ? "pre"
                                                  : "pre-approx";
}

// --- Sub-modes --------------------------------------------------------------------------------

/// The settings grid on one data set at 256 x 256, each image against one reference.
///
/// The reference is converged: the integrator's step is 1/16 of a voxel (shorter where it cuts
/// rays at cell planes and transfer-function nodes), its error second order in the step.
/// `BenchVolume converge <data> 16 32` measured step 1/16 against 1/32 at these cameras: RMS
/// 0.0004 / 0.0003 / 0.0004 and largest difference 0.004 / 0.008 / 0.010 of an 8-bit step for
/// bucky / tooth / engine, below the 0.05 of a step asked for and far below the 0.29 that 8-bit
/// rounding of the GPU image alone contributes.
int Accuracy(const std::string& data, const strata_test::TestPaths& paths)
{
  const int size = 256;
  const std::string name = "accuracy-" + data;
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
  {
    return Skipped(name, why);
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, size, size);
  ren->SetBackground(Grey, Grey, Grey);
  auto property = strata_test::MakeRealVolumeProperty(data);
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  ren->AddVolume(volume);
  const std::vector<std::pair<vtkImageData*, vtkVolume*>> list = { { image, volume } };
  double dir[3], up[3];
  strata_test::RealVolumeView(data, dir, up);
  strata_test::FrameVolumes(ren, list, dir, up, 0.75);

  std::cerr << name << ": reference at step 1/16 voxel, " << size << " x " << size << " ... ";
  const Reference ref = ComputeReference(ren, size, size, list, ReferenceStep);
  std::cerr << ref.Seconds << " s, " << ref.Covered << " covered pixels\n";
  std::map<std::pair<double, double>, Reference> byOffset;
  std::map<int, Reference> sameRays;
  for (int rays : { 1, 2, 5 })
  {
    sameRays[rays] = SameRaysReference(ren, size, size, list, rays, byOffset);
    std::cerr << name << ": reference of the " << rays
              << " rays' positions: " << sameRays[rays].Seconds << " s\n";
  }

  const Classifications classifications[] = { Classifications::PostClassification,
    Classifications::PreIntegrated,
    Classifications::PreIntegratedApproximate };
  const CompositeOrders orders[] = { CompositeOrders::FrontToBack, CompositeOrders::BackToFront };
  // Coherence only matters with several rays: one ray alone, then each count with it off and on.
  const std::pair<int, bool> rays[] = {
    { 1, false }, { 2, false }, { 2, true }, { 5, false }, { 5, true }
  };
  const double distances[] = { 1.0, 0.5 };
  const int frames = TimedFrames(3);
  const int total = 3 * 2 * 5 * 2;
  int done = 0;
  const auto t0 = Clock::now();
  for (double d : distances)
    for (Classifications c : classifications)
      for (CompositeOrders o : orders)
        for (const auto& r : rays)
        {
          mapper->SetSampleDistance(d);
          mapper->SetClassification(c);
          mapper->SetCompositeOrder(o);
          mapper->SetRaysPerPixel(r.first);
          mapper->SetRayCoherence(r.second);
          Row row;
          row.Case = name;
          row.Method = "strata";
          WarmUp(win, mapper, 1);
          row.Ms = MedianMs(win, frames);
          // The last timed frame is still in the window: read it rather than render again.
          const auto gpu = strata_test::ReadRGB(win);
          row.Rms = Rms(gpu, ref);
          row.RmsSameRays = Rms(gpu, sameRays[r.first]);
          row.Classification = ClassificationName(c);
          row.Order = o == CompositeOrders::FrontToBack ? "front-to-back" : "back-to-front";
          row.Rays = r.first;
          row.Coherence = r.second;
          row.SampleDistance = d;
          row.Volumes = 1;
          row.Width = row.Height = size;
          row.Fragments = mapper->GetNumberOfFragments();
          Emit(row);
          ++done;
          std::cerr << "  [" << done << "/" << total << "] " << row.Classification << " "
                    << row.Order << " rays " << r.first << (r.second ? " coherent" : "") << " d "
                    << d << ": " << row.Ms << " ms, RMS " << row.Rms << " (same rays "
                    << row.RmsSameRays << ") (" << Seconds(t0) << " s)\n";
          MaybeWriteImages(name + "-" + row.Classification + "-" + row.Order + "-r" +
                             std::to_string(r.first) + (r.second ? "c" : "") + "-d" +
                             std::to_string(d),
            gpu,
            &ref,
            size,
            size);
        }
  return 0;
}

/// A method named "...-compute" ray casts in the compute stage, the others in the fragment stage.
void SetStage(vtkMultiVolumeRayCastMapper* mapper, const std::string& method)
{
  const std::string suffix = "-compute";
  const bool compute = method.size() > suffix.size() &&
                       method.compare(method.size() - suffix.size(), suffix.size(), suffix) == 0;
  mapper->SetStage(compute ? vtkMultiVolumeRayCastMapper::Stages::Compute
                           : vtkMultiVolumeRayCastMapper::Stages::Fragment);
}

/// The stage the mapper's last frame ran in: "fragment" or "compute".
std::string StageOf(vtkMultiVolumeRayCastMapper* mapper)
{
  return mapper->GetStageInUse() == vtkMultiVolumeRayCastMapper::Stages::Compute ? "compute"
                                                                                 : "fragment";
}

/// One way of rendering a scene, in its own window, and its frame times.
struct Contender
{
  std::string Method;
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkSmartPointer<vtkProp> Prop;
  vtkMultiVolumeRayCastMapper* Strata = nullptr; ///< when the mapper is Strata's
  int WarmupFrames = 0;
  std::vector<double> Ms;
  std::vector<strata_bench::FrameTime> Times; ///< the same frames: wall, GPU, CPU
};

void WarmUp(Contender& c)
{
  c.WarmupFrames = WarmUp(c.Win, c.Strata, 2);
}

/**
 * A row of the one-volume scenes at 512 x 512 (post-classified, sample distance 0.5): case,
 * method and, from the contender when it ran, its median frame time and Strata's settings.
 */
Row SingleVolumeRow(const std::string& name, const std::string& method, const Contender* c)
{
  Row row;
  row.Case = name;
  row.Method = method;
  row.Classification = "post";
  row.SampleDistance = 0.5;
  row.Volumes = 1;
  row.Width = Viewport[0];
  row.Height = Viewport[1];
  if (c)
  {
    row.Ms = Median(c->Ms);
    const strata_bench::FrameTime t = strata_bench::FrameTimer::Median(c->Times);
    row.GpuMs = t.GpuMs >= 0.0 ? t.GpuMs : NaN;
    row.CpuMs = t.CpuMs;
    row.Stage = c->Strata ? StageOf(c->Strata) : "vtk";
  }
  if (c && c->Strata)
  {
    row.Order = "front-to-back";
    row.Rays = 1;
    row.Coherence = 0;
    row.Fragments = c->Strata->GetNumberOfFragments();
  }
  return row;
}

/**
 * Times the contenders' frames interleaved: round after round, one frame of each, the order
 * rotating. This machine's two cores are shared, and a neighbour's burst of work then slows all
 * contenders alike instead of whichever happened to be measured at the time.
 */
void TimeInterleaved(std::vector<Contender>& contenders, int frames)
{
  for (auto& c : contenders)
    WarmUp(c);
  const size_t n = contenders.size();
  for (int round = 0; round < frames; ++round)
    for (size_t k = 0; k < n; ++k)
    {
      Contender& c = contenders[(k + round) % n];
      c.Times.push_back(strata_bench::FrameTimer::Time(c.Win));
      c.Ms.push_back(c.Times.back().WallMs);
    }
}

/// The single-volume scene of `data` at 512 x 512 with one mapper: strata, strata-no-atlas
/// (UseBrickAtlas off: one plain texture, no skipping of transparent bricks) or vtk.
Contender MakeSingle(const std::string& method,
  const std::string& data,
  vtkImageData* image,
  vtkVolumeProperty* p)
{
  Contender c;
  c.Method = method == "vtk" ? "vtkGPUVolumeRayCastMapper" : method;
  strata_test::MakeWindow(c.Win, c.Ren, Viewport[0], Viewport[1]);
  c.Ren->SetBackground(Grey, Grey, Grey);
  vtkSmartPointer<vtkGPUVolumeRayCastMapper> mapper;
  if (method == "vtk")
    mapper = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
  else
  {
    c.Strata = vtkMultiVolumeRayCastMapper::New();
    mapper.TakeReference(c.Strata);
    c.Strata->SetUseBrickAtlas(method.find("no-atlas") == std::string::npos);
    SetStage(c.Strata, method);
  }
  mapper->SetInputData(image);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetSampleDistance(0.5);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(p);
  c.Ren->AddVolume(volume);
  c.Prop = volume;
  double dir[3], up[3];
  strata_test::RealVolumeView(data, dir, up);
  strata_test::FrameVolumes(c.Ren, { { image, volume } }, dir, up, 0.7);
  return c;
}

const char* const SingleMethods[] = { "strata",
  "strata-compute",
  "strata-no-atlas",
  "strata-no-atlas-compute",
  "vtk" };
constexpr size_t NumberOfSingleMethods = sizeof(SingleMethods) / sizeof(SingleMethods[0]);

/// Peak RSS of one mapper alone on the single-volume scene, one process per mapper: prints
/// "<method>=<MB>" for `frame` to put in its rows.
int Memory(const std::string& kind,
  const std::string& data,
  const std::string& method,
  const strata_test::TestPaths& paths)
{
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
  {
    std::cerr << kind << "-" << data << ": skipped: " << why << "\n";
    return 0;
  }
  auto property = strata_test::MakeRealVolumeProperty(data);
  Contender c = MakeSingle(method, data, image, property);
  WarmUp(c);
  std::printf("%s=%.0f\n", method.c_str(), PeakRssMB());
  return 0;
}

/**
 * One volume at 512 x 512 (or --viewport), sample distance 0.5 voxel, the three mappers in one
 * process and
 * timed interleaved (TimeInterleaved). `memory` lists "<method>=<MB>" from `memory` runs, for
 * the peak_rss_mb column.
 */
int FrameCase(const std::string& kind,
  const std::string& data,
  const std::string& memory,
  const strata_test::TestPaths& paths)
{
  // A viewport other than 512 x 512 is its own case, so the report's tables keep both apart.
  const bool other = Viewport[0] != 512 || Viewport[1] != 512;
  const std::string name =
    kind + "-" + data +
    (other ? "@" + std::to_string(Viewport[0]) + "x" + std::to_string(Viewport[1]) : "");
  std::map<std::string, std::string> rss;
  std::stringstream list(memory);
  std::string item;
  while (std::getline(list, item, ','))
    if (item.find('=') != std::string::npos)
      rss[item.substr(0, item.find('='))] = item.substr(item.find('=') + 1);
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  std::vector<Contender> contenders;
  auto property = strata_test::MakeRealVolumeProperty(data);
  if (image)
    for (const char* m : SingleMethods)
      contenders.push_back(MakeSingle(m, data, image, property));
  else
    std::cerr << name << ": skipped: " << why << "\n";
  TimeInterleaved(contenders, TimedFrames(7));
  const std::string load = LoadNote();
  for (size_t k = 0; k < NumberOfSingleMethods; ++k)
  {
    Row row = SingleVolumeRow(name,
      SingleMethods[k] == std::string("vtk") ? "vtkGPUVolumeRayCastMapper" : SingleMethods[k],
      image ? &contenders[k] : nullptr);
    if (!image)
    {
      row.Note = "skipped: " + why;
      Emit(row);
      continue;
    }
    Contender& c = contenders[k];
    if (rss.count(SingleMethods[k]) && !rss[SingleMethods[k]].empty())
      row.PeakRss = std::atof(rss[SingleMethods[k]].c_str());
    std::ostringstream note;
    note.precision(3);
    note << 100.0 * VisibleFraction(image, property) << "% of voxels visible";
    if (c.Strata && c.Strata->GetUseBrickAtlas())
      note << "; " << c.Strata->GetNumberOfResidentBricks() << " bricks resident of "
           << c.Strata->GetNumberOfAtlasSlots() << " atlas slots";
    note << "; " << c.WarmupFrames << " warm-up frames; timed interleaved with the others";
    if (k > 0)
    {
      // The same picture: RMS difference from Strata's image (8-bit units).
      const auto mine = strata_test::ReadRGB(c.Win),
                 theirs = strata_test::ReadRGB(contenders[0].Win);
      double se = 0.0;
      for (size_t i = 0; i < mine.size(); ++i)
        se += (double(mine[i]) - theirs[i]) * (double(mine[i]) - theirs[i]);
      note << "; image differs from strata's by RMS "
           << std::sqrt(se / std::max<size_t>(1, mine.size()));
    }
    note << load;
    row.Note = note.str();
    Emit(row);
    MaybeWriteImages(name + "-" + SingleMethods[k],
      strata_test::ReadRGB(c.Win),
      nullptr,
      Viewport[0],
      Viewport[1]);
    std::cerr << name << " " << row.Method << ": " << row.Ms << " ms\n";
  }
  return 0;
}

/**
 * The lean atlas: the 8-bit `data` set stored as uint8 (R8; and in R16, the default storage), as
 * uint16 (v 257, R16), as int16
 * (v 257 - 32768, R16) and as float32 (R32F), its transfer functions mapped alike, under one
 * atlas budget of `floatBricks` float bricks; 512 x 512, timed interleaved. Each row: bytes per
 * brick, slots and resident bricks, and the RMS (8-bit) against the float32 rendering with room
 * for every brick (how far the budget forces coarser levels), in the note.
 */
int Storage(const std::string& data, const strata_test::TestPaths& paths, int floatBricks = 40)
{
  const std::string name = "storage-" + data;
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
    return Skipped(name, why);
  using Storages = vtkMultiVolumeRayCastMapper::ScalarStorages;
  struct Kind
  {
    const char* Name;
    int VTKType;
    double Scale, Offset;
    Storages Storage;
  };
  const Kind kinds[] = { { "uint8", VTK_UNSIGNED_CHAR, 1.0, 0.0, Storages::Native },
    { "uint8-r16", VTK_UNSIGNED_CHAR, 1.0, 0.0, Storages::Normalized16 },
    { "uint16", VTK_UNSIGNED_SHORT, 257.0, 0.0, Storages::Native },
    { "int16", VTK_SHORT, 257.0, -32768.0, Storages::Native },
    { "float32", VTK_FLOAT, 1.0, 0.0, Storages::Native } };
  std::vector<vtkSmartPointer<vtkImageData>> images;
  std::vector<vtkSmartPointer<vtkVolumeProperty>> properties;
  std::vector<Contender> contenders;
  const int B = 32;
  const double budget = floatBricks * std::pow(double(B), 3) * 4.0 / (1024.0 * 1024.0);
  for (const Kind& k : kinds)
  {
    images.push_back(strata_test::CopyAsType(image, k.VTKType, k.Scale, k.Offset));
    properties.push_back(strata_test::MakeRealVolumeProperty(data));
    strata_test::MapTransferFunctions(properties.back(), k.Scale, k.Offset);
    contenders.push_back(MakeSingle("strata", data, images.back(), properties.back()));
    contenders.back().Strata->SetBrickSize(B);
    contenders.back().Strata->SetAtlasBudget(budget);
    contenders.back().Strata->SetScalarStorage(k.Storage);
  }
  // The reference image: float32 with room for every brick.
  Contender full = MakeSingle("strata", data, images.back(), properties.back());
  full.Strata->SetBrickSize(B);
  WarmUp(full);
  const auto fullImage = strata_test::ReadRGB(full.Win);
  TimeInterleaved(contenders, TimedFrames(7));
  const std::string load = LoadNote();
  for (size_t k = 0; k < contenders.size(); ++k)
  {
    Contender& c = contenders[k];
    Row row = SingleVolumeRow(name, std::string("strata-") + kinds[k].Name, &c);
    std::ostringstream note;
    note.precision(4);
    note << "atlas " << c.Strata->GetAtlasScalarTypeName() << "; "
         << c.Strata->GetAtlasBytesPerBrick() << " bytes per brick; budget " << budget
         << " MiB holds " << c.Strata->GetNumberOfAtlasSlots() << " slots; "
         << c.Strata->GetNumberOfResidentBricks()
         << " bricks resident (every brick: " << full.Strata->GetNumberOfResidentBricks()
         << "); RMS to the float32 image with room "
         << "for every brick "
         << strata_test::ImageError(strata_test::ReadRGB(c.Win), fullImage).Rms
         << "; timed interleaved with the other types" << load;
    row.Note = note.str();
    Emit(row);
    std::cerr << name << " " << row.Method << ": " << row.Ms << " ms, "
              << c.Strata->GetNumberOfAtlasSlots() << " slots\n";
  }
  return 0;
}

/**
 * What components cost, in core and paged: `data` as two independent components (the data, and
 * the data moved 6 voxels along x through its own functions, weight 0.5), as RGBA (colours
 * from the data, opacity the data), and the RGBA data as four independent components through
 * the data's functions, all of weight 1 and with only the fourth of weight 1 (ParaView's
 * component mode: the others neither paged nor read), each drawn in core (one texture of a float
 * channel per component) and paged from a set of component pools of 32^3 pages (a volume of one
 * scalar per component in the atlas, its own index fetch each), converged before timing; 512 x 512,
 * timed interleaved. Each paged row's note: its RMS (8-bit) against the in-core image, resident
 * bricks and the pools' MB.
 */
int ComponentsCost(const std::string& data, const strata_test::TestPaths& paths)
{
  const std::string name = "components-" + data;
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
    return Skipped(name, why);
  vtkDataArray* s = image->GetPointData()->GetScalars();
  int dims[3];
  image->GetDimensions(dims);
  double range[2];
  s->GetRange(range);
  auto make = [&](int components, bool rgba)
  {
    auto out = vtkSmartPointer<vtkImageData>::New();
    out->CopyStructure(image);
    vtkSmartPointer<vtkDataArray> values;
    values.TakeReference(s->NewInstance());
    values->SetNumberOfComponents(components);
    values->SetNumberOfTuples(s->GetNumberOfTuples());
    const double scale = 255.0 / std::max(range[1] - range[0], 1e-30);
    for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
    {
      const double v = s->GetComponent(i, 0);
      const vtkIdType x = i % dims[0];
      const double moved = s->GetComponent(i - x + std::max<vtkIdType>(x - 6, 0), 0);
      if (!rgba)
      {
        values->SetComponent(i, 0, v);
        values->SetComponent(i, 1, moved);
        continue;
      }
      const double g = (v - range[0]) * scale;
      values->SetComponent(i, 0, range[0] + (255.0 - g) / scale);
      values->SetComponent(i, 1, range[0] + (0.5 * g + 64.0) / scale);
      values->SetComponent(i, 2, range[0] + g / scale);
      values->SetComponent(i, 3, v);
    }
    out->GetPointData()->SetScalars(values);
    return out;
  };
  struct Mode
  {
    const char* Name;
    vtkSmartPointer<vtkImageData> Image;
    vtkSmartPointer<vtkVolumeProperty> Property;
  };
  auto rgba = make(4, true);
  std::vector<Mode> modes = { { "independent2", make(2, false), nullptr },
    { "rgba", rgba, nullptr },
    { "independent4", rgba, nullptr },
    { "independent4-one", rgba, nullptr } };
  for (Mode& m : modes)
  {
    const std::string mode = m.Name;
    m.Property = strata_test::MakeRealVolumeProperty(data);
    if (mode == "rgba")
    {
      m.Property->IndependentComponentsOff();
      continue;
    }
    const int count = mode == "independent2" ? 2 : 4;
    for (int c = 1; c < count; ++c)
    {
      m.Property->SetColor(c, m.Property->GetRGBTransferFunction(0));
      m.Property->SetScalarOpacity(c, m.Property->GetScalarOpacity(0));
    }
    // independent4-one: ParaView's component mode (component 3, the data, alone; the others
    // weigh 0, so they are neither paged nor read).
    for (int c = 0; c < count; ++c)
      m.Property->SetComponentWeight(c,
        mode == "independent2" ? (c ? 0.5 : 1.0) : (mode == "independent4" || c == 3 ? 1.0 : 0.0));
  }
  const std::string dir = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/strata-bench-" +
                          std::to_string(static_cast<long>(getpid()));
  vtksys::SystemTools::MakeDirectory(dir);
  std::vector<Contender> contenders;
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  std::vector<double> poolMB;
  for (Mode& m : modes)
  {
    contenders.push_back(MakeSingle("strata", data, m.Image, m.Property));
    contenders.back().Method = std::string("strata-") + m.Name + "-in-core";
    const std::string pool = dir + "/" + m.Name + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(m.Image);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(32);
    if (!writer->Write())
      return Skipped(name, "the component pools could not be written to " + dir);
    poolMB.push_back(writer->GetFileSize() / (1024.0 * 1024.0));
    readers.push_back(vtkSmartPointer<vtkPagePoolReader>::New());
    readers.back()->SetFileName(pool.c_str());
    contenders.push_back(MakeSingle("strata", data, m.Image, m.Property));
    contenders.back().Method = std::string("strata-") + m.Name + "-paged";
    contenders.back().Strata->SetInputConnection(readers.back()->GetOutputPort());
    int frames = 0;
    for (; frames < 300; ++frames)
    {
      contenders.back().Win->Render();
      if (contenders.back().Strata->GetPagingStatistics().Converged)
        break;
      contenders.back().Strata->WaitForPages(30.0);
    }
    std::cerr << name << " " << m.Name << " paged: converged after " << frames << " frames\n";
  }
  TimeInterleaved(contenders, TimedFrames(7));
  const std::string load = LoadNote();
  for (size_t k = 0; k < contenders.size(); ++k)
  {
    Contender& c = contenders[k];
    Row row = SingleVolumeRow(name, c.Method, &c);
    std::ostringstream note;
    note.precision(4);
    if (k % 2 == 1)
      note << "paged, RMS to the in-core image "
           << strata_test::ImageError(
                strata_test::ReadRGB(c.Win), strata_test::ReadRGB(contenders[k - 1].Win))
                .Rms
           << "; " << c.Strata->GetNumberOfResidentBricks() << " bricks resident; pools "
           << poolMB[k / 2] << " MB; ";
    else
      note << "in core (a float channel per component); ";
    note << "timed interleaved with the others" << load;
    row.Note = note.str();
    Emit(row);
    std::cerr << name << " " << row.Method << ": " << row.Ms << " ms\n";
  }
  contenders.clear();
  readers.clear();
  vtksys::SystemTools::RemoveADirectory(dir);
  return 0;
}

/**
 * The translucent-layers knob: TestMultiVolumeTranslucentGeometry's two volumes crossed by six
 * parallel planes of opacity 0.4 (AddTranslucentActor), TranslucentLayers = 1 .. 7, each image
 * against the reference that composites every plane at its exact depth; 128 x 128 (the cases'
 * size). Fewer layers than planes drop the farthest ones at each pixel.
 */
int Layers()
{
  using strata_test::TranslucentPlane;
  strata_test::VolumeScene s("");
  strata_test::AddTwoVolumes(s);
  s.Ren->SetBackground(Grey, Grey, Grey);
  s.Multi->VisibilityOff();
  s.Win->Render();
  const auto sceneRgb = strata_test::ReadRGB(s.Win);
  const auto depth = strata_test::ReadDepth(s.Win);
  s.Multi->VisibilityOn();
  const double colours[3][3] = { { 1.0, 0.2, 0.1 }, { 0.1, 0.3, 1.0 }, { 0.9, 0.9, 0.2 } };
  std::vector<std::unique_ptr<TranslucentPlane>> planes;
  std::vector<strata::MultiVolumeReferenceIntegrator::Surface> surfaces;
  for (int k = 0; k < 6; ++k)
  {
    const double y = 2.0 + 6.0 * k;
    // Wider than the view: no plane edge on screen (a rasterised edge is off by a pixel).
    const double o[3] = { -60, y, -60 }, a[3] = { 120, y + 9, -60 }, b[3] = { -60, y, 100 };
    planes.push_back(std::make_unique<TranslucentPlane>(o, a, b, colours[k % 3]));
    s.Mapper->AddTranslucentActor(planes.back()->Actor);
    surfaces.push_back(planes.back()->Surface);
  }
  const std::vector<double> stop(depth.begin(), depth.end());
  const auto expected = strata_test::CompositeOver(
    strata_test::ReferenceWithSurfaces(s, surfaces, true, stop.data()), sceneRgb);
  const int size = strata_test::MultiVolumeCaseSize;
  for (int layers = 1; layers <= 7; ++layers)
  {
    s.Mapper->SetTranslucentLayers(layers);
    WarmUp(s.Win, s.Mapper, 2);
    Row row;
    row.Case = "layers-blob";
    row.Method = "strata-layers-" + std::to_string(layers);
    row.Ms = MedianMs(s.Win, TimedFrames(5));
    const strata_test::ChannelError e =
      strata_test::ImageError(strata_test::ReadRGB(s.Win), expected);
    row.Rms = e.Rms;
    row.Classification = "post";
    row.Order = "front-to-back";
    row.Rays = 1;
    row.Coherence = 0;
    row.SampleDistance = s.Mapper->GetSampleDistance();
    row.Volumes = 2;
    row.Width = row.Height = size;
    row.Fragments = s.Mapper->GetNumberOfFragments();
    std::ostringstream note;
    note << layers << " translucent layers for 6 overlapping planes of opacity 0.4; max error "
         << e.Max << " of 255" << LoadNote();
    row.Note = note.str();
    Emit(row);
    std::cerr << "layers " << layers << ": " << row.Ms << " ms, RMS " << e.Rms << ", max " << e.Max
              << "\n";
  }
  return 0;
}

/// n overlapping 96^3 analytic volumes, each turned differently, at 384 x 384: Strata and VTK's
/// own multi-volume path, each timed and compared with the reference (which mixes the media
/// physically where they overlap; VTK composites the volumes' samples one after the other).
int Multi(int n)
{
  const int size = 384, dim = 96;
  const double distance = 1.0;
  const std::string name = "multi" + std::to_string(n) + "-blob";

  std::vector<vtkSmartPointer<vtkImageData>> images;
  std::vector<vtkSmartPointer<vtkVolumeProperty>> properties;
  std::vector<vtkSmartPointer<vtkTransform>> transforms;
  // Centres on a small circle (each box overlapping the others by more than half), axes
  // turned about different directions.
  const double axes[4][3] = { { 0, 0, 1 }, { 1, 1, 0 }, { 1, 0, 1 }, { 0, 1, 1 } };
  const double angles[4] = { 0, 30, -25, 45 };
  for (int i = 0; i < n; ++i)
  {
    const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
    images.push_back(strata_test::MakeBlobVolume(dim, dim, dim, spacing, origin, 11 + i));
    // Opacity per 3 voxels: each volume semi-transparent, so the overlaps show.
    properties.push_back(strata_test::MakeVolumeProperty(i, 3.0));
    auto t = vtkSmartPointer<vtkTransform>::New();
    const double a = 2.0 * std::acos(-1.0) * i / n;
    t->Translate(16 * std::cos(a), 16 * std::sin(a), 8.0 * (i % 2));
    t->Translate(0.5 * (dim - 1), 0.5 * (dim - 1), 0.5 * (dim - 1));
    t->RotateWXYZ(angles[i], axes[i][0], axes[i][1], axes[i][2]);
    t->Translate(-0.5 * (dim - 1), -0.5 * (dim - 1), -0.5 * (dim - 1));
    transforms.push_back(t);
  }
  auto build = [&](vtkGPUVolumeRayCastMapper* mapper,
                 vtkMultiVolume* multi,
                 std::vector<vtkSmartPointer<vtkVolume>>& members)
  {
    mapper->AutoAdjustSampleDistancesOff();
    mapper->SetSampleDistance(distance);
    multi->SetMapper(mapper);
    for (int i = 0; i < n; ++i)
    {
      mapper->SetInputDataObject(i, images[i]);
      auto v = vtkSmartPointer<vtkVolume>::New();
      v->SetProperty(properties[i]);
      v->SetUserTransform(transforms[i]);
      multi->SetVolume(v, i);
      members.push_back(v);
    }
  };
  // Each in its own window, the same camera: close, as the blobs fill the middle of their boxes
  // and the boxes' corners are empty.
  // Strata in both stages and VTK's mapper.
  std::vector<Contender> contenders(3);
  std::vector<std::vector<vtkSmartPointer<vtkVolume>>> members(3);
  const double dir[3] = { -0.5, -1.0, 0.6 }, up[3] = { 0, 0, 1 };
  std::vector<std::pair<vtkImageData*, vtkVolume*>> list;
  for (int k = 0; k < 3; ++k)
  {
    Contender& c = contenders[k];
    vtkSmartPointer<vtkGPUVolumeRayCastMapper> mapper;
    if (k < 2)
    {
      c.Method = k == 0 ? "strata" : "strata-compute";
      c.Strata = vtkMultiVolumeRayCastMapper::New();
      mapper.TakeReference(c.Strata);
      SetStage(c.Strata, c.Method);
    }
    else
    {
      c.Method = "vtkGPUVolumeRayCastMapper";
      mapper = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
    }
    auto multi = vtkSmartPointer<vtkMultiVolume>::New();
    build(mapper, multi, members[k]);
    strata_test::MakeWindow(c.Win, c.Ren, size, size);
    c.Ren->SetBackground(Grey, Grey, Grey);
    c.Ren->AddVolume(multi);
    c.Prop = multi;
    list.clear();
    for (int i = 0; i < n; ++i)
      list.emplace_back(images[i], members[k][i]);
    strata_test::FrameVolumes(c.Ren, list, dir, up, 0.5);
  }
  vtkRenderer* ren = contenders[0].Ren;
  std::cerr << name << ": reference at step 1/16 voxel, " << size << " x " << size << " ... ";
  const Reference ref = ComputeReference(ren, size, size, list, ReferenceStep);
  std::cerr << ref.Seconds << " s, " << ref.Covered << " covered pixels\n";
  if (std::getenv("STRATA_BENCH_CONVERGE"))
  {
    // The same check as `converge` for this scene, step 1/16 against 1/32: measured RMS 3e-6,
    // max 3e-5 (2 volumes) and RMS 5e-6, max 6e-5 (4 volumes) of an 8-bit step.
    const Reference fine = ComputeReference(ren, size, size, list, ReferenceStep / 2.0);
    double mx = 0.0;
    const double rms = Difference(ref, fine, &mx);
    std::cerr << name << ": reference at 1/16 vs 1/32: RMS " << rms << ", max " << mx << "\n";
  }

  TimeInterleaved(contenders, TimedFrames(7));
  const std::string load = LoadNote();
  for (Contender& c : contenders)
  {
    const bool strata = c.Strata != nullptr;
    Row row;
    row.Case = name;
    row.Method = c.Method;
    row.Ms = Median(c.Ms);
    const strata_bench::FrameTime t = strata_bench::FrameTimer::Median(c.Times);
    row.GpuMs = t.GpuMs >= 0.0 ? t.GpuMs : NaN;
    row.CpuMs = t.CpuMs;
    row.Stage = strata ? StageOf(c.Strata) : "vtk";
    const auto gpu = strata_test::ReadRGB(c.Win);
    double mx = 0.0;
    row.Rms = Rms(gpu, ref, &mx);
    row.Classification = "post";
    if (strata)
    {
      row.Order = "front-to-back";
      row.Rays = 1;
      row.Coherence = 0;
      row.Fragments = c.Strata->GetNumberOfFragments();
    }
    row.SampleDistance = distance;
    row.Volumes = n;
    row.Width = row.Height = size;
    std::ostringstream note;
    note.precision(3);
    note << "max error " << mx << "; timed interleaved with the others" << load;
    row.Note = note.str();
    Emit(row);
    MaybeWriteImages(name + "-" + (strata ? c.Method : "vtk"), gpu, &ref, size, size);
    std::cerr << name << " " << row.Method << ": " << row.Ms << " ms, RMS " << row.Rms << "\n";
  }
  return 0;
}

/// Rebuild time of the BSP tree for n overlapping 96^3 boxes, each turned differently.
int Bsp(int n, const std::string& layout)
{
  std::vector<strata::VolumeBSPTree::Box> boxes;
  for (int i = 0; i < n; ++i)
  {
    vtkNew<vtkTransform> t;
    if (layout == "grid")
    {
      // Tiles of a survey: a square grid at a pitch of 3/4 of a box, so that each overlaps its
      // neighbours by a quarter, each turned by up to 12 degrees about its own axes.
      const int side = static_cast<int>(std::ceil(std::sqrt(double(n))));
      t->Translate(72.0 * (i % side), 72.0 * (i / side), 4.0 * (i % 3));
      t->RotateWXYZ(5.0 + 7.0 * ((i * 5) % 3), std::sin(1.3 * i), std::cos(0.7 * i), 1.0);
    }
    else
    {
      // Centres on a ring (radius 40 for 3, growing with n), rotations by 17 to 200 degrees
      // about varied axes: each box overlaps its neighbours and some those across the ring.
      const double a = 2.0 * std::acos(-1.0) * i / n, r = 40.0 * std::sqrt(n / 3.0);
      t->Translate(r * std::cos(a), r * std::sin(a), 10.0 * ((i % 3) - 1));
      t->RotateWXYZ(17.0 + 23.0 * i, std::sin(1.3 * i), std::cos(0.7 * i), 0.5 + 0.1 * i);
    }
    t->Scale(96, 96, 96);
    t->Translate(-0.5, -0.5, -0.5);
    strata::VolumeBSPTree::Box box;
    std::copy(t->GetMatrix()->GetData(), t->GetMatrix()->GetData() + 16, box.Matrix.begin());
    box.VolumeId = i;
    boxes.push_back(box);
  }
  strata::VolumeBSPTree tree;
  tree.SetBoxes(boxes);
  tree.Build(); // warm-up
  int builds = 0;
  const auto t0 = Clock::now();
  while (builds < 100 || Seconds(t0) < 1.0)
  {
    tree.Build();
    ++builds;
  }
  Row row;
  row.Case = "bsp" + std::to_string(n) + (layout == "grid" ? "-grid" : "");
  row.Method = "strata";
  row.Ms = 1000.0 * Seconds(t0) / builds;
  row.Volumes = n;
  row.Fragments = tree.GetNumberOfFragments();
  std::ostringstream note;
  note << "ms per strata::VolumeBSPTree::Build over " << builds << " builds; " << layout
       << " of 96^3 boxes; depth " << tree.GetDepth() << "; max overlap "
       << tree.GetMaximumOverlap();
  row.Note = note.str();
  Emit(row);
  std::cerr << row.Case << ": " << row.Ms << " ms per build, " << row.Fragments << " fragments\n";
  return 0;
}

/// The blend-mode knob on one data set at 256 x 256: every mode of vtkVolumeMapper::BlendModes
/// (contours at 40 % and 70 % of the transfer functions' range) at two sample distances, each
/// image against the reference of that mode.
int Blend(const std::string& data, const strata_test::TestPaths& paths)
{
  const int size = 256;
  const std::string name = "blend-" + data;
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
  {
    return Skipped(name, why);
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, size, size);
  ren->SetBackground(Grey, Grey, Grey);
  auto property = strata_test::MakeRealVolumeProperty(data);
  double range[2];
  property->GetScalarOpacity()->GetRange(range);
  property->GetIsoSurfaceValues()->SetValue(0, range[0] + 0.4 * (range[1] - range[0]));
  property->GetIsoSurfaceValues()->SetValue(1, range[0] + 0.7 * (range[1] - range[0]));
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  ren->AddVolume(volume);
  const std::vector<std::pair<vtkImageData*, vtkVolume*>> list = { { image, volume } };
  double dir[3], up[3];
  strata_test::RealVolumeView(data, dir, up);
  strata_test::FrameVolumes(ren, list, dir, up, 0.75);
  const std::pair<int, const char*> modes[] = { { vtkVolumeMapper::COMPOSITE_BLEND, "composite" },
    { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "maximum" },
    { vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, "minimum" },
    { vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "average" },
    { vtkVolumeMapper::ADDITIVE_BLEND, "additive" },
    { vtkVolumeMapper::ISOSURFACE_BLEND, "isosurface" } };
  const int frames = TimedFrames(3);
  const auto t0 = Clock::now();
  for (const auto& m : modes)
  {
    mapper->SetBlendMode(m.first);
    const Reference ref =
      ComputeReference(ren, size, size, list, ReferenceStep, true, nullptr, mapper);
    for (double d : { 1.0, 0.5 })
    {
      mapper->SetSampleDistance(d);
      Row row;
      row.Case = name;
      row.Method = "strata";
      WarmUp(win, mapper, 1);
      row.Ms = MedianMs(win, frames);
      const auto gpu = strata_test::ReadRGB(win);
      double maxError = 0.0;
      row.Rms = Rms(gpu, ref, &maxError);
      row.Classification = "post";
      row.Order = "front-to-back";
      row.Rays = 1;
      row.SampleDistance = d;
      row.Volumes = 1;
      row.Width = row.Height = size;
      row.Fragments = mapper->GetNumberOfFragments();
      row.BlendMode = m.second;
      row.Note = "max error " + std::to_string(maxError) + LoadNote();
      Emit(row);
      std::cerr << "  " << m.second << " d " << d << ": " << row.Ms << " ms, RMS " << row.Rms
                << ", max " << maxError << " (reference " << ref.Seconds << " s; " << Seconds(t0)
                << " s)\n";
      MaybeWriteImages(name + "-" + m.second + "-d" + std::to_string(d), gpu, &ref, size, size);
    }
  }
  return 0;
}

/// Reference convergence: step 1/`coarse` against 1/`fine` of a voxel at the accuracy
/// benchmark's camera.
int Converge(const std::string& data,
  double coarse,
  double fine,
  const strata_test::TestPaths& paths)
{
  const int size = 256;
  std::string why;
  auto image = strata_test::LoadRealVolume(data, paths, why);
  if (!image)
  {
    std::cerr << data << ": " << why << "\n";
    return 1;
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, size, size);
  auto property = strata_test::MakeRealVolumeProperty(data);
  vtkNew<vtkVolume> volume;
  volume->SetProperty(property);
  const std::vector<std::pair<vtkImageData*, vtkVolume*>> list = { { image, volume } };
  double dir[3], up[3];
  strata_test::RealVolumeView(data, dir, up);
  strata_test::FrameVolumes(ren, list, dir, up, 0.75);
  const Reference a = ComputeReference(ren, size, size, list, 1.0 / coarse);
  const Reference b = ComputeReference(ren, size, size, list, 1.0 / fine);
  double mx;
  double rms = Difference(a, b, &mx);
  std::printf("%s: step 1/%g (%.1f s) vs 1/%g (%.1f s): RMS %.6f, max %.6f of 255, %ld covered\n",
    data.c_str(),
    coarse,
    a.Seconds,
    fine,
    b.Seconds,
    rms,
    mx,
    a.Covered);
  if (std::getenv("STRATA_BENCH_UNSNAPPED"))
  {
    // The same at the coarse step with ToReferenceVolume's tables as they are (slow).
    const Reference c = ComputeReference(ren, size, size, list, 1.0 / coarse, false);
    rms = Difference(a, c, &mx);
    std::printf(
      "%s: exact runs vs float table at step 1/%g (%.1f s vs %.1f s): RMS %.6f, max %.6f\n",
      data.c_str(),
      coarse,
      a.Seconds,
      c.Seconds,
      rms,
      mx);
  }
  return 0;
}

}

int main(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::TakeFromArguments(argc, argv);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "header")
  {
    std::cout << Header << "\n";
    return 0;
  }
  if (mode == "accuracy" && argc > 2)
    return Accuracy(argv[2], paths);
  if (mode == "blend" && argc > 2)
    return Blend(argv[2], paths);
  for (int i = 2; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--viewport")
    {
      if (std::sscanf(argv[i + 1], "%dx%d", &Viewport[0], &Viewport[1]) != 2 || Viewport[0] < 1 ||
          Viewport[1] < 1)
      {
        std::cerr << "BenchVolume: --viewport takes <width>x<height>, not " << argv[i + 1] << "\n";
        return 2;
      }
      for (int j = i; j + 2 < argc; ++j)
        argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  if (mode == "frame" && argc > 3)
    return FrameCase(argv[2], argv[3], argc > 4 ? argv[4] : "", paths);
  if (mode == "memory" && argc > 4)
    return Memory(argv[2], argv[3], argv[4], paths);
  if (mode == "layers")
    return Layers();
  if (mode == "storage" && argc > 2)
    return Storage(argv[2], paths);
  if (mode == "components" && argc > 2)
    return ComponentsCost(argv[2], paths);
  if (mode == "multi" && argc > 2)
    return Multi(std::max(2, std::min(4, std::atoi(argv[2]))));
  if (mode == "bsp" && argc > 2)
    return Bsp(std::max(1, std::atoi(argv[2])), argc > 3 ? argv[3] : "ring");
  if (mode == "converge" && argc > 2)
    return Converge(
      argv[2], argc > 3 ? std::atof(argv[3]) : 16.0, argc > 4 ? std::atof(argv[4]) : 32.0, paths);
  if (mode == "report" && argc > 3)
    return Report(argv[2], argv[3]);
  std::cerr
    << "usage: BenchVolume header | accuracy <data> | blend <data> | frame <single|sparse> <data> "
       "[<method>=<MB>,...] | memory <single|sparse> <data> <strata|strata-no-atlas|vtk> | "
       "storage <data> | components <data> | layers | multi <2-4> | bsp <n> [ring|grid] | converge "
       "<data> [1/h 1/h'] | report <csv> <png>\n";
  return 2;
}

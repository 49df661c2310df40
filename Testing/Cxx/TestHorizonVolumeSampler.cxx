// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkHorizonVolumeSampler: a volume's value along a horizon, in core and paged, at UTM
// coordinates with the volume and the horizon rotated differently. The volume holds a linear
// function of world position, which trilinear interpolation reproduces exactly: the sampled
// values must equal the function at each horizon point up to float storage; points outside
// the volume and holes of the horizon must be NaN, counted exactly; the paged path must give
// the in-core values while reading only the pages under the horizon (which crosses a corner
// of the volume).
#include "StrataErrorCounter.h"
#include "StrataTestPaths.h"

#include "vtkCallbackCommand.h"
#include "vtkFloatArray.h"
#include "vtkHorizonVolumeSampler.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
bool ok = true;

void Check(bool condition, const std::string& what)
{
  std::cout << (condition ? "ok: " : "FAILED: ") << what << "\n";
  ok = ok && condition;
}

const double X0 = 600000.0, Y0 = 6700000.0;
const int VX = 129, VY = 97, VZ = 81;
// The function the volume holds, of world position.
double F(double x, double y, double z)
{
  return 0.01 * (x - X0) + 0.02 * (y - Y0) - 0.05 * z + 3.0;
}

void Rotation(double degrees, double d[9])
{
  const double a = degrees * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  const double r[9] = { c, -s, 0, s, c, 0, 0, 0, 1 };
  std::copy_n(r, 9, d);
}

void World(vtkImageData* image, double i, double j, double k, double w[3])
{
  const double* o = image->GetOrigin();
  const double* s = image->GetSpacing();
  const double* d = image->GetDirectionMatrix()->GetData();
  const double idx[3] = { i * s[0], j * s[1], k * s[2] };
  for (int r = 0; r < 3; ++r)
    w[r] = o[r] + d[3 * r] * idx[0] + d[3 * r + 1] * idx[1] + d[3 * r + 2] * idx[2];
}

void RecordProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData));
}
}

int TestHorizonVolumeSampler(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const float nan = std::numeric_limits<float>::quiet_NaN();

  // The volume: 129 x 97 x 81 points of 12.5 x 12.5 x 4 m from (X0, Y0, -1000), rotated 20 deg.
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(VX, VY, VZ);
  volume->SetOrigin(X0, Y0, -1000.0);
  volume->SetSpacing(12.5, 12.5, 4.0);
  double d[9];
  Rotation(20.0, d);
  volume->SetDirectionMatrix(d);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("amplitude");
  scalars->SetNumberOfTuples(VX * VY * VZ);
  for (int k = 0; k < VZ; ++k)
    for (int j = 0; j < VY; ++j)
      for (int i = 0; i < VX; ++i)
      {
        double w[3];
        World(volume, i, j, k, w);
        scalars->SetValue((k * VY + j) * VX + i, static_cast<float>(F(w[0], w[1], w[2])));
      }
  volume->GetPointData()->SetScalars(scalars);

  // The horizon: 90 x 70 points of 10 m, rotated 35 deg, depths 860-980 m (HeightScale -1),
  // partly outside the volume laterally, with a disc of no data.
  const int nx = 90, ny = 70;
  vtkNew<vtkImageData> horizon;
  horizon->SetDimensions(nx, ny, 1);
  horizon->SetOrigin(X0 + 150.0, Y0 - 100.0, 0.0);
  horizon->SetSpacing(10.0, 10.0, 1.0);
  Rotation(35.0, d);
  horizon->SetDirectionMatrix(d);
  vtkNew<vtkFloatArray> depth;
  depth->SetName("depth");
  depth->SetNumberOfTuples(nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const bool hole = (i - 30) * (i - 30) + (j - 35) * (j - 35) < 64;
      depth->SetValue(
        j * nx + i, hole ? nan : static_cast<float>(920.0 + 60.0 * std::sin(0.07 * i + 0.05 * j)));
    }
  horizon->GetPointData()->SetScalars(depth);

  // The expectation: F at each horizon point inside the volume, NaN elsewhere.
  vtkNew<vtkMatrix3x3> volumeRotation;
  volumeRotation->DeepCopy(volume->GetDirectionMatrix());
  volumeRotation->Invert();
  std::vector<double> expected(nx * ny, std::nan(""));
  long inside = 0, holes = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const double h = depth->GetValue(j * nx + i);
      if (std::isnan(h))
      {
        ++holes;
        continue;
      }
      double w[3];
      World(horizon, i, j, -h, w); // HeightScale -1 on the third axis
      const double rel[3] = { w[0] - X0, w[1] - Y0, w[2] + 1000.0 };
      double local[3];
      volumeRotation->MultiplyPoint(rel, local);
      const double idx[3] = { local[0] / 12.5, local[1] / 12.5, local[2] / 4.0 };
      const double eps = 1e-9;
      if (idx[0] >= -eps && idx[0] <= VX - 1 + eps && idx[1] >= -eps && idx[1] <= VY - 1 + eps &&
          idx[2] >= -eps && idx[2] <= VZ - 1 + eps)
      {
        expected[j * nx + i] = F(w[0], w[1], w[2]);
        ++inside;
      }
    }
  std::cout << "horizon points: " << inside << " inside the volume, " << holes << " holes, "
            << nx * ny - inside - holes << " outside\n";
  Check(inside > 2000 && nx * ny - inside - holes > 500, "the horizon is partly inside the volume");

  auto compare = [&](vtkHorizonVolumeSampler* sampler, const std::string& name)
  {
    auto* out =
      vtkFloatArray::SafeDownCast(sampler->GetOutput()->GetPointData()->GetArray("amplitude"));
    Check(out && out->GetNumberOfTuples() == nx * ny, name + ": one amplitude per horizon point");
    if (!out)
      return std::vector<float>();
    double maxError = 0.0;
    long nanWhereExpected = 0;
    for (int p = 0; p < nx * ny; ++p)
    {
      const double v = out->GetValue(p);
      if (std::isnan(expected[p]))
        nanWhereExpected += std::isnan(v) ? 1 : 0;
      else
        maxError = std::max(maxError, std::isnan(v) ? 1e30 : std::abs(v - expected[p]));
    }
    std::cout << name << ": max |sample - F| " << maxError << ", sampled "
              << sampler->GetNumberOfSampledPoints() << ", empty "
              << sampler->GetNumberOfEmptyPoints() << ", pages read "
              << sampler->GetNumberOfPagesRead() << "\n";
    // Float storage of values up to ~60 (6e-8 relative, 4e-6) and float output.
    Check(maxError < 2e-5, name + ": trilinear samples equal the linear function (bound 2e-5)");
    Check(nanWhereExpected == nx * ny - inside && sampler->GetNumberOfSampledPoints() == inside &&
            sampler->GetNumberOfEmptyPoints() == nx * ny - inside,
      name + ": exactly the points outside the volume and the holes are NaN");
    return std::vector<float>(out->GetPointer(0), out->GetPointer(0) + nx * ny);
  };

  // In core.
  vtkNew<vtkHorizonVolumeSampler> sampler;
  sampler->SetInputData(0, horizon);
  sampler->SetInputData(1, volume);
  sampler->SetHeightScale(-1.0);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(RecordProgress);
  cb->SetClientData(&progress);
  sampler->AddObserver(vtkCommand::ProgressEvent, cb);
  sampler->SetBlockSize(32);
  sampler->Update();
  const std::vector<float> inCore = compare(sampler, "in core");
  Check(!progress.empty() && progress.back() == 1.0, "progress is reported up to 1");
  Check(sampler->GetOutput()->GetPointData()->GetArray("depth") != nullptr,
    "the output keeps the horizon's own arrays");

  // Nearest point: the value of the nearest voxel, which differs from the trilinear one.
  sampler->NearestNeighborOn();
  sampler->Update();
  auto* nearest =
    vtkFloatArray::SafeDownCast(sampler->GetOutput()->GetPointData()->GetArray("amplitude"));
  double nearestDiff = 0.0;
  for (int p = 0; p < nx * ny; ++p)
    if (!std::isnan(expected[p]))
      nearestDiff = std::max(nearestDiff, std::abs(nearest->GetValue(p) - double(inCore[p])));
  // Half a voxel along each axis of a gradient 0.01, 0.02, 0.05 per m: at most 0.29.
  std::cout << "nearest vs trilinear: max difference " << nearestDiff << "\n";
  Check(nearestDiff > 0.02 && nearestDiff <= 0.29,
    "nearest-point sampling differs within half a voxel");
  sampler->NearestNeighborOff();

  // Paged: the same volume as a brick pool of 16^3 pages, read block by block.
  const std::string pool = paths.Output + "/TestHorizonVolumeSampler.spp";
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(16);
  Check(writer->Write(), "the volume is written as a page pool");
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(pool.c_str());
  vtkNew<vtkHorizonVolumeSampler> paged;
  paged->SetInputData(0, horizon);
  paged->SetVolumeConnection(reader->GetOutputPort());
  paged->SetHeightScale(-1.0);
  paged->SetBlockSize(32);
  paged->Update();
  const std::vector<float> fromPool = compare(paged, "paged");
  auto same = [](const std::vector<float>& a, const std::vector<float>& b)
  {
    bool equal = a.size() == b.size();
    for (size_t p = 0; equal && p < a.size(); ++p)
      equal = (std::isnan(a[p]) && std::isnan(b[p])) || a[p] == b[p];
    return equal;
  };
  Check(same(inCore, fromPool), "paged samples equal the in-core ones exactly");
  Check(reader->GetLevelRead() != 0, "the pipeline's reader stays at a coarse level");
  // Only the pages under the horizon: fewer than the whole volume's at the default block size
  // (one block here); smaller blocks read again the pages their neighbours share.
  vtkNew<vtkPagePoolReader> whole;
  whole->SetFileName(pool.c_str());
  whole->Update();
  const vtkIdType all = whole->GetNumberOfPagesRead();
  const vtkIdType blocks32 = paged->GetNumberOfPagesRead();
  paged->SetBlockSize(128);
  paged->Update();
  std::cout << "pages read: " << paged->GetNumberOfPagesRead() << " in one block, " << blocks32
            << " in blocks of 32, of the volume's " << all << "\n";
  Check(paged->GetNumberOfPagesRead() > 0 && paged->GetNumberOfPagesRead() < all,
    "one block reads only the pages under the horizon");
  Check(
    same(compare(paged, "paged, one block"), fromPool), "block size does not change the samples");

  // Bad input: a 3-D "horizon" is an error, not a misread.
  vtkNew<strata_test::ErrorCounter> errors;
  vtkNew<vtkHorizonVolumeSampler> bad;
  errors->Watch(bad);
  bad->SetInputData(0, volume);
  bad->SetInputData(1, volume);
  bad->Update();
  Check(errors->Errors >= 1, "a 3-D image as the horizon is one clear error: " + errors->First);
  std::remove(pool.c_str());
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

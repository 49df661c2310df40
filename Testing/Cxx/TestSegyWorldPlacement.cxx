// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// A SEG-Y survey in rotated UTM coordinates renders where its trace headers put it: the
// generated file (StrataSegyTestFile: 456000 E, 6780000 N, 12.5 m x 25 m bins, coordinate
// scalar -100), read by vtkSegyVolumeReader with its default (world) placement and drawn by
// vtkMultiVolumeRayCastMapper through the image's own origin, spacing and direction matrix, is
// compared
// - with the double-precision reference integrator (StrataMultiVolumeCase.h's bounds: RMS 0.4,
//   max 2 in 8-bit units), and
// - with the same samples on an axis-aligned image at the origin, placed by a vtkTransform built
//   here from the survey's parameters alone (not from the reader): the two images differ by at
//   most 2 in any channel (the placements agree to the millimetres the coordinates are rounded
//   to; an axis swapped, mirrored or turned the wrong way moves the slab by tens of pixels).
// - and GetGridToWorld() as the vtkVolume's matrix of the samples in index space draws the
//   same picture (within 2).
// Both at 30 degrees (inlines counterclockwise from crosslines) and mirrored at 127 degrees.
#include "StrataMultiVolumeCase.h"
#include "StrataSegyTestFile.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSegyVolumeReader.h"
#include "vtkTransform.h"
#include "vtkVolumeProperty.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using namespace strata_test;

/// The transform that puts an axis-aligned image of the survey's samples (origin 0, spacing
/// (crossline bin, |scale| x interval, inline bin)) where the survey is: from the file's
/// parameters, as a user of a reader without world placement would have to compute it.
vtkSmartPointer<vtkTransform> ExpectedPlacement(const SegyTestFile& file, double scale)
{
  double o[2], x[2], i[2];
  file.MapPosition(0, 0, o);
  file.MapPosition(0, 1, x);
  file.MapPosition(1, 0, i);
  vtkNew<vtkMatrix4x4> m;
  for (int r = 0; r < 2; ++r)
  {
    m->SetElement(r, 0, (x[r] - o[r]) / file.CrosslineBin);
    m->SetElement(r, 1, 0.0);
    m->SetElement(r, 2, (i[r] - o[r]) / file.InlineBin);
    m->SetElement(r, 3, o[r]);
  }
  m->SetElement(2, 0, 0.0);
  m->SetElement(2, 1, scale < 0 ? -1.0 : 1.0);
  m->SetElement(2, 2, 0.0);
  m->SetElement(2, 3, scale * file.DelayMilliseconds);
  auto t = vtkSmartPointer<vtkTransform>::New();
  t->SetMatrix(m);
  return t;
}

bool Placement(const SegyTestFile& file, const std::string& name, const std::string& out)
{
  const double scale = -2.0; // the slab twice as thick as its milliseconds
  const std::string path = out + "/" + name + ".sgy";
  {
    const std::string bytes = file.Bytes();
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
  }
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetVerticalScale(scale);
  reader->Update();
  vtkImageData* world = reader->GetOutput();
  if (!reader->GetGeoreferenced())
  {
    std::cerr << "FAILED: " << name << " not georeferenced\n";
    return false;
  }
  vtkNew<vtkImageData> local;
  local->ShallowCopy(world);
  local->SetOrigin(0, 0, 0);
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  local->SetDirectionMatrix(identity);

  auto property = MakeVolumeProperty(1, 40.0);
  VolumeScene expected(out);
  expected.Add(local, property, ExpectedPlacement(file, scale));
  expected.UseSingleVolume();
  const double pos[3] = { 456000 - 400, 6780000 - 300, 500 }, focal[3] = { 456000, 6780000, 0 };
  expected.Camera(pos, focal);
  VolumeScene placed(out);
  placed.Add(world, property);
  placed.UseSingleVolume();
  placed.Ren->GetActiveCamera()->DeepCopy(expected.Ren->GetActiveCamera());

  const VolumeComparison a = placed.Compare(name + "-reader");
  bool ok = CheckVolumeComparison(a, name + "-reader", 0.4, 2, 2000);
  const VolumeComparison b = expected.Compare(name + "-expected");
  const ChannelError e = ImageError(a.Gpu, b.Gpu);
  const long off = PixelsOff(a.Gpu, b.Gpu, 2);
  std::cout << name << ": reader's placement vs the expected transform: RMS " << e.Rms << ", max "
            << e.Max << ", " << off << " pixels off by more than 2\n";
  if (off > 0)
  {
    std::cerr << "FAILED: " << name << ": the survey is not drawn where its coordinates say\n";
    ok = false;
  }
  // GetGridToWorld as the prop's matrix of an image in index space (unit spacing, zero origin,
  // identity direction): the same picture, for consumers that ignore direction matrices.
  vtkNew<vtkImageData> indexed;
  indexed->ShallowCopy(world);
  indexed->SetOrigin(0, 0, 0);
  indexed->SetSpacing(1, 1, 1);
  indexed->SetDirectionMatrix(identity);
  auto byMatrix = vtkSmartPointer<vtkTransform>::New();
  byMatrix->SetMatrix(reader->GetGridToWorld());
  VolumeScene user(out);
  user.Add(indexed, property, byMatrix);
  user.UseSingleVolume();
  user.Ren->GetActiveCamera()->DeepCopy(expected.Ren->GetActiveCamera());
  const VolumeComparison c = user.Compare(name + "-gridtoworld");
  const long userOff = PixelsOff(c.Gpu, a.Gpu, 2);
  std::cout << name << ": GetGridToWorld as the prop's matrix: " << userOff
            << " pixels off by more than 2\n";
  if (userOff > 0)
  {
    std::cerr << "FAILED: " << name << ": GetGridToWorld does not place the index-space image\n";
    ok = false;
  }
  return ok;
}
}

int TestSegyWorldPlacement(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  const std::string out = paths.Output + "/TestSegyWorldPlacement";
  vtksys::SystemTools::MakeDirectory(out);
  SegyTestFile file;
  file.Format = 5;
  file.Georeferenced = true;
  file.Inlines = 12;
  file.Crosslines = 16;
  file.Samples = 24;
  file.IntervalMicroseconds = 4000;
  bool ok = Placement(file, "rotated", out);
  file.Mirrored = true;
  file.RotationDegrees = 127.0;
  ok = Placement(file, "mirrored", out) && ok;
  return CaseResult(ok, output);
}

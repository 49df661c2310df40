// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataSubsurfaceDemo.h"

#include "vtkActor.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkHorizonVolumeSampler.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyLineSource.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSegyVolumeReader.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkSyntheticSurveyWriter.h"
#include "vtkTubeFilter.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace strata_test
{
namespace
{
const char* const ReekFiles[4] = { "reek_01_topreek_rota.gri",
  "reek_02_midreek_rota.gri",
  "reek_03_lowreek_rota.gri",
  "reek_04_basereek_rota.gri" };
const double Exaggeration = 8.0;

/// Seismic colours: blue troughs, white zero, red peaks, over +-a.
vtkSmartPointer<vtkColorTransferFunction> SeismicColors(double a)
{
  auto ctf = vtkSmartPointer<vtkColorTransferFunction>::New();
  ctf->AddRGBPoint(-a, 0.05, 0.15, 0.75);
  ctf->AddRGBPoint(0.0, 0.95, 0.95, 0.95);
  ctf->AddRGBPoint(a, 0.75, 0.08, 0.05);
  ctf->SetNanColor(0.4, 0.4, 0.4);
  return ctf;
}

/// Only the strong reflections visible: opacity grows with |amplitude| above a third of a.
vtkSmartPointer<vtkVolumeProperty> SeismicProperty(double a, double unitDistance)
{
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetColor(SeismicColors(a));
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(-a, 0.5);
  opacity->AddPoint(-0.5 * a, 0.0);
  opacity->AddPoint(0.5 * a, 0.0);
  opacity->AddPoint(a, 0.5);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(unitDistance);
  property->SetInterpolationTypeToLinear();
  return property;
}

/// A survey over the horizons' grid from `origin` (world x, y), `rotation` degrees more than
/// the grid, bins of `binFactor` grid cells, `lines` (inlines, crosslines), samples of dz m.
bool WriteSurvey(const std::vector<vtkSmartPointer<vtkIrapBinaryGridReader>>& grids,
  const double origin[2],
  double rotation,
  double binFactor,
  const int lines[2],
  int samples,
  double dz,
  const std::string& path)
{
  vtkNew<vtkSyntheticSurveyWriter> survey;
  for (const auto& grid : grids)
    survey->AddInputConnection(grid->GetOutputPort());
  vtkImageData* grid = grids[0]->GetOutput();
  survey->SetOrigin(origin[0], origin[1]);
  survey->SetRotation(rotation);
  survey->SetBins(binFactor * grid->GetSpacing()[1], binFactor * grid->GetSpacing()[0]);
  survey->SetLines(lines[0], lines[1]);
  survey->SetSamples(samples, dz, 1444); // depths in m over the reservoir
  survey->SetPeakFrequency(30.0);        // cycles per km for depths
  survey->SetFileName(path.c_str());
  return survey->Write();
}
}

bool AddSubsurfaceDemo(vtkRenderer* ren,
  const std::string& horizonDir,
  const std::string& work,
  SubsurfaceDemo& scene)
{
  std::vector<vtkSmartPointer<vtkIrapBinaryGridReader>> grids;
  for (const char* name : ReekFiles)
  {
    auto reader = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
    reader->SetFileName((horizonDir + "/" + name).c_str());
    reader->Update();
    if (!reader->GetOutput() || reader->GetOutput()->GetNumberOfPoints() == 0)
    {
      std::cerr << "Cannot read " << horizonDir << "/" << name << "\n";
      return false;
    }
    grids.push_back(reader);
    scene.Sources.push_back(reader);
  }
  vtkImageData* grid = grids[0]->GetOutput();
  int dims[3];
  grid->GetDimensions(dims);
  vtkMatrix3x3* d = grid->GetDirectionMatrix();
  const double rotation =
    vtkMath::DegreesFromRadians(std::atan2(d->GetElement(1, 0), d->GetElement(0, 0)));

  // Survey A: the whole grid on every 8th node, 4 m samples; paged from a pool.
  const std::string segyA = work + "/subsurface-a.sgy", poolA = work + "/subsurface-a.spp";
  const std::string segyB = work + "/subsurface-b.sgy";
  scene.Files = { segyA, poolA, segyB };
  const double originA[2] = { grid->GetOrigin()[0], grid->GetOrigin()[1] };
  const int linesA[2] = { (dims[1] - 1) / 8 + 1, (dims[0] - 1) / 8 + 1 };
  // Survey B: 2x finer bins and 2 m samples over the middle, turned 15 degrees further.
  double quarter[3];
  const double index[3] = {
    0.3 * (dims[0] - 1) * grid->GetSpacing()[0], 0.2 * (dims[1] - 1) * grid->GetSpacing()[1], 0.0
  };
  d->MultiplyPoint(index, quarter);
  const double originB[2] = { originA[0] + quarter[0], originA[1] + quarter[1] };
  const int linesB[2] = { (dims[1] - 1) / 8, (dims[0] - 1) / 8 };
  if (!WriteSurvey(grids, originA, rotation, 8.0, linesA, 160, 4.0, segyA) ||
      !WriteSurvey(grids, originB, rotation + 15.0, 4.0, linesB, 320, 2.0, segyB))
  {
    std::cerr << "Cannot write the synthetic surveys to " << work << "\n";
    return false;
  }
  // A as strata-convert converts it: SEG-Y placed in world coordinates, then a brick pool.
  vtkNew<vtkSegyVolumeReader> seismicA;
  seismicA->SetFileName(segyA.c_str());
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(seismicA->GetOutputPort());
  writer->SetFileName(poolA.c_str());
  writer->SetPageSize(32);
  if (!writer->Write())
    return false;
  auto pooled = vtkSmartPointer<vtkPagePoolReader>::New();
  pooled->SetFileName(poolA.c_str());
  auto seismicB = vtkSmartPointer<vtkSegyVolumeReader>::New();
  seismicB->SetFileName(segyB.c_str());
  seismicB->Update();
  scene.Sources.push_back(pooled);
  scene.Sources.push_back(seismicB);

  // The second horizon draped with A's amplitude, read from the pool.
  scene.Drape = vtkSmartPointer<vtkHorizonVolumeSampler>::New();
  scene.Drape->SetInputConnection(grids[1]->GetOutputPort());
  scene.Drape->SetVolumeConnection(pooled->GetOutputPort());
  scene.Drape->SetHeightScale(-1.0);
  scene.Drape->Update();
  // The volumes' colours over 0.6 of the largest amplitude of survey B (A's is the same model).
  double range[2];
  seismicB->GetOutput()->GetScalarRange(range);
  const double a = 0.6 * std::max(std::abs(range[0]), std::abs(range[1]));
  // The draped amplitude over its own range: how the top reflection's strength varies.
  double drapeRange[2];
  scene.Drape->GetOutput()->GetPointData()->GetArray("amplitude")->GetRange(drapeRange);
  vtkNew<vtkColorTransferFunction> drapeColors;
  drapeColors->AddRGBPoint(drapeRange[0], 0.1, 0.2, 0.7);
  drapeColors->AddRGBPoint(0.5 * (drapeRange[0] + drapeRange[1]), 0.95, 0.95, 0.9);
  drapeColors->AddRGBPoint(drapeRange[1], 0.8, 0.1, 0.05);
  drapeColors->SetNanColor(0.4, 0.4, 0.4);

  scene.HorizonMapper = vtkSmartPointer<vtkStackedHeightFieldMapper>::New();
  scene.HorizonMapper->AddInputConnection(scene.Drape->GetOutputPort());
  scene.HorizonMapper->AddInputConnection(grids[3]->GetOutputPort());
  scene.HorizonMapper->SetHeightScale(-1.0);
  scene.HorizonMapper->SetHorizonColorArray(0, "amplitude");
  scene.HorizonMapper->SetHorizonLookupTable(0, drapeColors);
  double baseRange[2];
  grids[3]->GetOutput()->GetScalarRange(baseRange);
  vtkNew<vtkColorTransferFunction> depth;
  depth->AddRGBPoint(baseRange[0], 0.95, 0.8, 0.35);
  depth->AddRGBPoint(baseRange[1], 0.45, 0.25, 0.1);
  scene.HorizonMapper->SetHorizonLookupTable(1, depth);
  // The top horizon, translucent: composited inside the volumes where their rays cross it.
  scene.HorizonMapper->AddInputConnection(grids[0]->GetOutputPort());
  scene.HorizonMapper->SetHorizonColor(2, 0.3, 0.85, 0.95);
  scene.HorizonMapper->SetHorizonOpacity(2, 0.45);
  scene.Horizons = vtkSmartPointer<vtkActor>::New();
  scene.Horizons->SetMapper(scene.HorizonMapper);
  scene.Horizons->SetScale(1, 1, Exaggeration);
  scene.Horizons->GetProperty()->SetSpecular(0.15);
  ren->AddActor(scene.Horizons);

  // Both surveys in one ray caster; A cropped to the last third of its first axis.
  scene.VolumeMapper = vtkSmartPointer<vtkMultiVolumeRayCastMapper>::New();
  scene.VolumeMapper->SetInputConnection(0, pooled->GetOutputPort());
  scene.VolumeMapper->SetInputConnection(1, seismicB->GetOutputPort());
  // World units: half survey B's exaggerated 2 m sample.
  scene.VolumeMapper->SetSampleDistance(0.5 * 2.0 * Exaggeration);
  scene.VolumeMapper->SetAtlasBudget(32);
  scene.VolumeMapper->SetPagesPerFrame(64);
  scene.VolumeMapper->AddTranslucentActor(scene.Horizons);
  seismicA->Update();
  vtkImageData* full = seismicA->GetOutput();
  double planes[6];
  for (int c = 0; c < 3; ++c)
  {
    const int* e = full->GetExtent();
    planes[2 * c] = full->GetOrigin()[c] + e[2 * c] * full->GetSpacing()[c];
    planes[2 * c + 1] = full->GetOrigin()[c] + e[2 * c + 1] * full->GetSpacing()[c];
  }
  planes[0] = planes[0] + 0.65 * (planes[1] - planes[0]);
  scene.VolumeMapper->SetInputCropping(0, true, planes, 0x2000 /* VTK_CROP_SUBVOLUME */);
  scene.Volumes = vtkSmartPointer<vtkMultiVolume>::New();
  scene.Volumes->SetMapper(scene.VolumeMapper);
  for (int port = 0; port < 2; ++port)
  {
    vtkNew<vtkVolume> v;
    v->SetProperty(SeismicProperty(a, port == 0 ? 64.0 : 32.0));
    v->SetScale(1, 1, Exaggeration);
    scene.Volumes->SetVolume(v, port);
  }
  ren->AddVolume(scene.Volumes);

  // A deviated well from above the grid's middle through the reservoir.
  double b[6];
  grids[3]->GetOutput()->GetBounds(b);
  const double cx = 0.5 * (b[0] + b[1]), cy = 0.5 * (b[2] + b[3]);
  vtkNew<vtkPolyLineSource> path;
  path->SetNumberOfPoints(12);
  for (int i = 0; i < 12; ++i)
  {
    const double t = i / 11.0;
    path->SetPoint(i, cx + 600.0 * t * t, cy - 400.0 * t * t, -(1250.0 + 650.0 * t));
  }
  vtkNew<vtkTubeFilter> tube;
  tube->SetInputConnection(path->GetOutputPort());
  tube->SetRadius(30.0);
  tube->SetNumberOfSides(12);
  vtkNew<vtkPolyDataMapper> wellMapper;
  wellMapper->SetInputConnection(tube->GetOutputPort());
  scene.Well = vtkSmartPointer<vtkActor>::New();
  scene.Well->SetMapper(wellMapper);
  scene.Well->SetScale(1, 1, Exaggeration);
  scene.Well->GetProperty()->SetColor(1.0, 0.85, 0.1);
  ren->AddActor(scene.Well);
  scene.Sources.push_back(tube);
  return true;
}

void RemoveSubsurfaceDemoFiles(const SubsurfaceDemo& scene)
{
  for (const auto& file : scene.Files)
    std::remove(file.c_str());
}
}

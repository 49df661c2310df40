// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The subsurface scene end to end: two horizons of two-way time (ms) on a UTM grid, a synthetic
// survey written from them (vtkSyntheticSurveyWriter: rotated 30 degrees, 12.5 m x 25 m bins,
// 2 ms samples, 30 Hz, no noise), read back with vtkSegyVolumeReader's world placement and drawn
// with vtkMultiVolumeRayCastMapper beside the horizons (vtkStackedHeightFieldMapper, HeightScale
// -1), with no transform anywhere. They line up: on a 20 x 16 grid of pixel centres,
// vtkSubsurfacePicker's first horizon hit and the volume samples along the same ray put the
// reflection's peak (the largest amplitude along the ray within the wavelet's main lobe, +-7 ms)
// within 2 ms of the horizon's depth: the trilinear volume peaks on a sample of its trace
// (half a sample, 1 ms, from the horizon) and between traces the horizon's time changes by
// up to 0.05 ms/m x 25 m = 1.25 ms, half of which the interpolation can add. A horizon
// misplaced by one sample (2 ms) in the survey, or the volume's z axis upwards, fails.
// The picture is written to <Testing/Temporary>/TestSubsurfaceScene.png.
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSegyVolumeReader.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkSubsurfacePicker.h"
#include "vtkSyntheticSurveyWriter.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
constexpr int W = 120, H = 96;
const double Centre[2] = { 456060.0, 6780130.0 };

double HorizonTime(int h, double x, double y)
{
  return (h ? 420.0 : 300.0) + (h ? -0.03 : 0.05) * (x - Centre[0]) +
         (h ? 0.04 : 0.02) * (y - Centre[1]);
}

/// 50 x 50 points at 8 m, axis-aligned, around the survey.
vtkSmartPointer<vtkImageData> MakeTimeHorizon(int h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(50, 50, 1);
  image->SetSpacing(8.0, 8.0, 1.0);
  image->SetOrigin(Centre[0] - 196.0, Centre[1] - 196.0, 0.0);
  vtkNew<vtkFloatArray> t;
  t->SetName("twt");
  t->SetNumberOfTuples(2500);
  for (int j = 0; j < 50; ++j)
    for (int i = 0; i < 50; ++i)
      t->SetValue(j * 50 + i,
        static_cast<float>(
          HorizonTime(h, image->GetOrigin()[0] + 8.0 * i, image->GetOrigin()[1] + 8.0 * j)));
  image->GetPointData()->SetScalars(t);
  return image;
}
}

int TestSubsurfaceScene(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  const std::string out = paths.Output + "/TestSubsurfaceScene";
  vtksys::SystemTools::MakeDirectory(out);
  std::vector<vtkSmartPointer<vtkImageData>> horizons{ MakeTimeHorizon(0), MakeTimeHorizon(1) };

  vtkNew<vtkSyntheticSurveyWriter> survey;
  for (const auto& h : horizons)
    survey->AddInputDataObject(0, h);
  survey->SetOrigin(456000.0, 6780000.0);
  survey->SetRotation(30.0);
  survey->SetLines(10, 12);
  survey->SetBins(25.0, 12.5);
  survey->SetSamples(200, 2.0, 200);
  survey->SetPeakFrequency(30.0);
  survey->SetNoiseLevel(0.0);
  const std::string path = out + "/survey.sgy";
  survey->SetFileName(path.c_str());
  if (!survey->Write())
    return EXIT_FAILURE;
  vtkNew<vtkSegyVolumeReader> seismic;
  seismic->SetFileName(path.c_str());
  seismic->Update();

  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, W, H);
  vtkNew<vtkStackedHeightFieldMapper> horizonMapper;
  for (const auto& h : horizons)
    horizonMapper->AddInputDataObject(0, h);
  horizonMapper->SetHeightScale(-1.0);
  vtkNew<vtkActor> horizonActor;
  horizonActor->SetMapper(horizonMapper);
  ren->AddActor(horizonActor);
  vtkNew<vtkMultiVolumeRayCastMapper> volumeMapper;
  volumeMapper->SetInputConnection(0, seismic->GetOutputPort());
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkColorTransferFunction> colors;
  colors->AddRGBPoint(-0.1, 0.1, 0.2, 1.0);
  colors->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  colors->AddRGBPoint(0.1, 1.0, 0.2, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(-0.1, 0.3);
  opacity->AddPoint(-0.02, 0.0);
  opacity->AddPoint(0.02, 0.0);
  opacity->AddPoint(0.1, 0.3);
  property->SetColor(colors);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(20.0);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkVolume> volume;
  volume->SetMapper(volumeMapper);
  volume->SetProperty(property);
  ren->AddVolume(volume);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetPosition(Centre[0] - 260.0, Centre[1] - 420.0, 150.0);
  camera->SetFocalPoint(Centre[0], Centre[1], -330.0);
  camera->SetViewUp(0, 0, 1);
  ren->ResetCameraClippingRange();
  win->Render();
  WritePNG(out + ".png", ReadRGB(win), W, H);

  vtkNew<vtkSubsurfacePicker> horizonPicker, volumePicker;
  horizonPicker->PickFromListOn();
  horizonPicker->AddPickList(horizonActor);
  volumePicker->PickFromListOn();
  volumePicker->AddPickList(volume);
  volumePicker->SetOpacityThreshold(1.0);
  long checked = 0, off = 0;
  double worst = 0.0;
  for (int j = 2; j < H; j += 6)
  {
    for (int i = 2; i < W; i += 6)
    {
      if (!horizonPicker->Pick(i + 0.5, j + 0.5, 0.0, ren) || horizonPicker->GetHorizonId() != 0)
        continue;
      volumePicker->Pick(i + 0.5, j + 0.5, 0.0, ren);
      const double* h = horizonPicker->GetHorizonPosition();
      vtkPoints* points = volumePicker->GetRayPoints();
      vtkDoubleArray* values = volumePicker->GetRayValues();
      vtkIdType best = -1;
      double bestValue = -1e30, zMin = 0.0, zMax = -1e30;
      for (vtkIdType n = 0; n < points->GetNumberOfPoints(); ++n)
      {
        const double* p = points->GetPoint(n);
        if (std::isnan(values->GetValue(n)))
          continue;
        zMin = std::min(zMin, p[2]);
        zMax = std::max(zMax, p[2]);
        if (std::abs(p[2] - h[2]) <= 7.0 && values->GetValue(n) > bestValue)
        {
          best = n;
          bestValue = values->GetValue(n);
        }
      }
      if (best < 0 || zMin > h[2] - 7.0 || zMax < h[2] + 7.0)
        continue; // the ray leaves the survey within the main lobe: its peak may be outside
      const double d = std::abs(points->GetPoint(best)[2] - h[2]);
      worst = std::max(worst, d);
      ++checked;
      off += d > 2.0;
    }
  }
  std::cout << checked << " pixels where the ray meets horizon 0 inside the survey; the "
            << "reflection's peak within " << worst << " ms of the horizon\n";
  const bool ok = checked >= 10 && off == 0;
  if (!ok)
    std::cerr << "FAILED: the survey's reflections and the horizons line up\n";
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

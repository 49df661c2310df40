// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The scenes of Examples/Python/*.py written in C++, line for line: what a C++ user writes for
// each renderer, and the reference the Python tests compare the scripts' images with.
//
//   StrataExamples <horizons|horizons_numpy|volumes|hybrid|paged_volume|paged_horizons|
//                   subsurface|time_series> <out.png> [--data <folder with horizons/ and volumes/>]
//                   [--work <folder>]
//                  [--camera <view.json>] [--keep-pools]
//
// --work is where the paged scenes write their pools (default: the folder of out.png);
// --keep-pools leaves them there (the volumes scene also writes its shell as shell.vti, the hybrid
// scene its representation as tooth.shv). --camera writes the view (camera, viewport size,
// background, the visible props' bounds) as JSON, so that another front end (the ParaView plugin's
// test) renders the same scene from the same point of view.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkNumpyGridReader.h"
#include "vtkPNGWriter.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSegyVolumeReader.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkSubsurfacePicker.h"
#include "vtkSyntheticSurveyWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace
{
struct Arguments
{
  std::string Output;
  std::string Data;
  std::string Work;
  std::string Camera;
  bool KeepPools = false;
};

const char* const ReekNames[4] = { "reek_01_topreek_rota",
  "reek_02_midreek_rota",
  "reek_03_lowreek_rota",
  "reek_04_basereek_rota" };

void WriteVector(std::ostream& os, const char* name, const double* v, int n, const char* end)
{
  os << "  \"" << name << "\": [";
  for (int i = 0; i < n; ++i)
    os << (i ? ", " : "") << v[i];
  os << "]" << end << "\n";
}

/// The view as JSON (see --camera).
bool WriteCamera(vtkRenderWindow* window, const std::string& path)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  vtkCamera* camera = renderer->GetActiveCamera();
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const double size[2] = { double(window->GetSize()[0]), double(window->GetSize()[1]) };
  const double angle = camera->GetViewAngle();
  std::ofstream os(path);
  os.precision(17);
  os << "{\n";
  WriteVector(os, "size", size, 2, ",");
  WriteVector(os, "background", renderer->GetBackground(), 3, ",");
  WriteVector(os, "position", camera->GetPosition(), 3, ",");
  WriteVector(os, "focal_point", camera->GetFocalPoint(), 3, ",");
  WriteVector(os, "view_up", camera->GetViewUp(), 3, ",");
  WriteVector(os, "view_angle", &angle, 1, ",");
  WriteVector(os, "clipping_range", camera->GetClippingRange(), 2, ",");
  WriteVector(os, "bounds", bounds, 6, "");
  os << "}\n";
  return bool(os);
}

bool Save(vtkRenderWindow* window, const Arguments& args)
{
  if (!args.Camera.empty() && !WriteCamera(window, args.Camera))
  {
    std::cerr << "cannot write " << args.Camera << "\n";
    return false;
  }
  const std::string& path = args.Output;
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  std::cout << path << "\n";
  return writer->GetErrorCode() == 0;
}

/// The examples' view: reset to the scene, tilt, turn, zoom.
void View(vtkRenderer* renderer, double elevation, double azimuth, double zoom)
{
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  camera->Azimuth(azimuth);
  camera->Zoom(zoom);
  renderer->ResetCameraClippingRange();
}

vtkSmartPointer<vtkRenderWindow> Window(vtkRenderer* renderer, int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  return window;
}

vtkSmartPointer<vtkRenderer> Renderer()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0.08, 0.09, 0.12);
  return renderer;
}

/// A property from (value, r, g, b) and (value, opacity) points, linear interpolation.
vtkSmartPointer<vtkVolumeProperty> VolumeProperty(const std::vector<std::array<double, 4>>& colors,
  const std::vector<std::array<double, 2>>& opacities)
{
  vtkNew<vtkColorTransferFunction> color;
  for (const auto& c : colors)
  {
    color->AddRGBPoint(c[0], c[1], c[2], c[3]);
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& o : opacities)
  {
    opacity->AddPoint(o[0], o[1]);
  }
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  return property;
}

vtkSmartPointer<vtkVolumeProperty> ToothProperty()
{
  return VolumeProperty(
    { { 0, 0.5, 0.5, 0.5 }, { 140, 0.8, 0.35, 0.25 }, { 200, 1.0, 0.9, 0.8 }, { 255, 1, 1, 1 } },
    { { 0, 0.0 }, { 110, 0.0 }, { 150, 0.03 }, { 255, 0.5 } });
}

/// The Reek stack's actor and its view, in core or paged (the mapper is given).
int ShowReek(const Arguments& args, vtkStackedHeightFieldMapper* mapper, bool paged)
{
  mapper->SetHeightScale(-1.0); // depths grow downwards
  mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(1, 1, 8); // 8x vertical exaggeration: the reservoir is thin
  actor->GetProperty()->SetSpecular(0.2);
  auto renderer = Renderer();
  renderer->AddActor(actor);
  View(renderer, -60, 30, 1.9);
  auto window = Window(renderer, 320, 240);
  int frames = 0;
  if (paged)
  {
    // What strata.render_until_converged does.
    for (; frames < 500; ++frames)
    {
      window->Render();
      if (mapper->GetPagingStatistics().Converged)
      {
        break;
      }
      mapper->WaitForPages(1.0);
    }
    const auto st = mapper->GetPagingStatistics();
    std::cerr << "settled after " << frames << " frames, " << st.FinestTiles << " level-0 tiles of "
              << st.CutTiles << ", " << st.BytesRead / 1024 << " KiB read\n";
  }
  else
  {
    window->Render();
  }
  return Save(window, args) ? 0 : 1;
}

int Horizons(const Arguments& args)
{
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  for (const char* name : ReekNames)
  {
    vtkNew<vtkIrapBinaryGridReader> reader;
    reader->SetFileName((args.Data + "/horizons/" + name + ".gri").c_str());
    mapper->AddInputConnection(reader->GetOutputPort());
  }
  return ShowReek(args, mapper, false);
}

int PagedHorizons(const Arguments& args)
{
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  for (const char* name : ReekNames)
  {
    vtkNew<vtkIrapBinaryGridReader> grid;
    grid->SetFileName((args.Data + "/horizons/" + name + ".gri").c_str());
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputConnection(grid->GetOutputPort());
    writer->SetFileName((args.Work + "/" + name + ".spp").c_str());
    writer->SetPageSize(65); // tiles of 64 cells, the mapper's TileSize
    if (!writer->Write())
    {
      return 1;
    }
    vtkNew<vtkPagePoolReader> reader;
    reader->SetFileName(writer->GetFileName());
    mapper->AddInputConnection(reader->GetOutputPort());
  }
  mapper->SetPagesPerFrame(16);
  const int result = ShowReek(args, mapper, true);
  for (const char* name : ReekNames)
  {
    if (!args.KeepPools)
      std::remove((args.Work + "/" + name + ".spp").c_str());
  }
  return result;
}

int HorizonsNumpy(const Arguments& args)
{
  // The NumPy array's (inline, crossline) index is the image's (i, j): vtkNumpyGridReader's
  // convention and the example's Fortran-order flattening agree.
  vtkNew<vtkNumpyGridReader> reader;
  reader->SetFileName((args.Data + "/horizons/penobscot_seabed_crop.npy").c_str());
  reader->SetSpacing(25.0, 25.0);
  reader->SetArrayName("twt");
  reader->Update();
  vtkNew<vtkImageData> seabed, below;
  seabed->ShallowCopy(reader->GetOutput());
  below->DeepCopy(reader->GetOutput());
  vtkDataArray* times = below->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < times->GetNumberOfTuples(); ++i)
  {
    times->SetTuple1(i, times->GetTuple1(i) + 40.0);
  }
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  mapper->AddInputData(seabed);
  mapper->AddInputData(below);
  mapper->SetHeightScale(-10.0); // two-way time grows downwards, exaggerated 10x
  mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  auto renderer = Renderer();
  renderer->AddActor(actor);
  View(renderer, -55, 30, 1.1);
  auto window = Window(renderer, 320, 240);
  window->Render();
  return Save(window, args) ? 0 : 1;
}

/// The spherical shell of volumes.py: 255 on the sphere of radius 24 voxels, fading over 21.
vtkSmartPointer<vtkImageData> Shell()
{
  auto shell = vtkSmartPointer<vtkImageData>::New();
  shell->SetDimensions(64, 64, 64);
  shell->SetSpacing(1.5, 1.5, 1.5);
  shell->SetOrigin(20.0, 0.0, 60.0);
  vtkNew<vtkUnsignedCharArray> values;
  values->SetNumberOfValues(64 * 64 * 64);
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
      {
        const double di = i - 31.5, dj = j - 31.5, dk = k - 31.5;
        const double r = std::sqrt(di * di + dj * dj + dk * dk);
        const double v =
          std::floor(std::min(255.0, std::max(0.0, 255.0 - 12.0 * std::abs(r - 24.0))));
        values->SetValue(i + 64 * (j + 64 * k), static_cast<unsigned char>(v));
      }
  shell->GetPointData()->SetScalars(values);
  return shell;
}

int Volumes(const Arguments& args)
{
  vtkNew<vtkNrrdReader> tooth;
  tooth->SetFileName((args.Data + "/volumes/tooth.nrrd").c_str());
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetSampleDistance(0.5);
  mapper->SetInputConnection(0, tooth->GetOutputPort());
  const auto shell = Shell();
  mapper->SetInputDataObject(1, shell);
  if (args.KeepPools)
  {
    // The shell as a file too, for front ends that cannot build it (the plugin's test).
    vtkNew<vtkImageData> copy;
    copy->DeepCopy(shell);
    copy->GetPointData()->GetScalars()->SetName("shell");
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(copy);
    writer->SetFileName((args.Work + "/shell.vti").c_str());
    if (!writer->Write())
      return 1;
  }
  vtkNew<vtkMultiVolume> scene;
  scene->SetMapper(mapper);
  const vtkSmartPointer<vtkVolumeProperty> properties[2] = { ToothProperty(),
    VolumeProperty({ { 0, 0.1, 0.3, 0.9 }, { 255, 0.3, 0.9, 1.0 } },
      { { 0, 0.0 }, { 120, 0.0 }, { 255, 0.08 } }) };
  vtkNew<vtkVolume> members[2];
  for (int port = 0; port < 2; ++port)
  {
    members[port]->SetProperty(properties[port]);
    scene->SetVolume(members[port], port);
  }
  auto renderer = Renderer();
  renderer->AddVolume(scene);
  View(renderer, -80, 35, 1.1);
  auto window = Window(renderer, 240, 240);
  window->Render();
  return Save(window, args) ? 0 : 1;
}

int Hybrid(const Arguments& args)
{
  vtkNew<vtkNrrdReader> tooth;
  tooth->SetFileName((args.Data + "/volumes/tooth.nrrd").c_str());
  vtkNew<vtkHybridVolumeFilter> hybrid;
  hybrid->SetInputConnection(tooth->GetOutputPort());
  hybrid->SetFactor(4, 4, 4);
  hybrid->SetFilterToCubic();
  hybrid->SetThreshold(24.0); // a point wherever the low resolution misses more than 24 of 255
  if (args.KeepPools)
    hybrid->SetFileName((args.Work + "/tooth.shv").c_str()); // the same representation as a file
  vtkNew<vtkHybridVolumeMapper> mapper;
  mapper->SetInputConnection(hybrid->GetOutputPort(0));
  mapper->SetPointsInputConnection(hybrid->GetOutputPort(1));
  mapper->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
  mapper->GetVolumeMapper()->SetSampleDistance(0.5);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(ToothProperty());
  auto renderer = Renderer();
  renderer->AddVolume(volume);
  View(renderer, -80, 35, 1.3);
  auto window = Window(renderer, 240, 240);
  window->Render();
  std::cerr << mapper->GetNumberOfPointsDrawn() << " points drawn\n";
  return Save(window, args) ? 0 : 1;
}

/// Renders until the paged mapper has settled (the loaders waited on between frames); returns
/// the frames it took (500 when it did not settle).
int Settle(vtkRenderWindow* window, vtkMultiVolumeRayCastMapper* mapper)
{
  int frames = 0;
  for (; frames < 500; ++frames)
  {
    window->Render();
    if (mapper->GetPagingStatistics().Converged)
      break;
    mapper->WaitForPages(1.0);
  }
  return frames;
}

int PagedVolume(const Arguments& args)
{
  const std::string pool = args.Work + "/tooth.spp";
  vtkNew<vtkNrrdReader> tooth;
  tooth->SetFileName((args.Data + "/volumes/tooth.nrrd").c_str());
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(tooth->GetOutputPort());
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(32);
  if (!writer->Write())
  {
    return 1;
  }
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(pool.c_str());
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetSampleDistance(0.5);
  mapper->SetAtlasBudget(16);  // MB of bricks on the GPU
  mapper->SetPagesPerFrame(8); // uploads per frame: the cut refines over several frames
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(ToothProperty());
  auto renderer = Renderer();
  renderer->AddVolume(volume);
  View(renderer, -80, 35, 1.3);
  auto window = Window(renderer, 240, 240);
  const int frames = Settle(window, mapper);
  std::cerr << "settled after " << frames << " frames, " << mapper->GetNumberOfResidentBricks()
            << " bricks resident, " << mapper->GetPagingStatistics().BytesRead / 1024
            << " KiB read\n";
  const int result = Save(window, args) ? 0 : 1;
  if (!args.KeepPools)
    std::remove(pool.c_str());
  return result;
}

/// A paged time series (4-D data: a volume that changes from step to step): the tooth CT
/// fading, step k its values scaled by 1 - 0.12 k, written as one pool per step and given to
/// one reader at uneven times (0, 0.5, 2, 3.5). The mapper pages the step its input's
/// UPDATE_TIME_STEP selects (what VTK's and ParaView's animation set) and prefetches the next
/// one. Each step's settled image is written as <out>_<k>.png; <work>/time_series_steps.json
/// lists the steps' pools and times for the ParaView test.
int TimeSeries(const Arguments& args)
{
  const double times[] = { 0.0, 0.5, 2.0, 3.5 };
  vtkNew<vtkNrrdReader> tooth;
  tooth->SetFileName((args.Data + "/volumes/tooth.nrrd").c_str());
  vtkNew<vtkPagePoolReader> reader;
  std::vector<std::string> pools;
  std::ofstream steps(args.Work + "/time_series_steps.json");
  steps << "[\n";
  for (int k = 0; k < 4; ++k)
  {
    vtkNew<vtkImageShiftScale> fade;
    fade->SetInputConnection(tooth->GetOutputPort());
    fade->SetScale(1.0 - 0.12 * k);
    fade->SetOutputScalarTypeToUnsignedChar();
    pools.push_back(args.Work + "/tooth_t" + std::to_string(k) + ".spp");
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputConnection(fade->GetOutputPort());
    writer->SetFileName(pools.back().c_str());
    writer->SetPageSize(32);
    if (!writer->Write())
      return 1;
    reader->AddTimeStep(pools.back().c_str(), times[k]);
    steps << "  {\"file\": \"" << pools.back() << "\", \"time\": " << times[k] << "}"
          << (k < 3 ? ",\n" : "\n");
  }
  steps << "]\n";
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetSampleDistance(0.5);
  mapper->SetAtlasBudget(16);
  mapper->SetPagesPerFrame(8);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(ToothProperty());
  auto renderer = Renderer();
  renderer->AddVolume(volume);
  View(renderer, -80, 35, 1.3);
  auto window = Window(renderer, 240, 240);
  // The time asked for after the first information pass (VTK drops an UPDATE_TIME_STEP set
  // before the reader's output exists).
  reader->UpdateInformation();
  Arguments step = args;
  const std::string base = args.Output.substr(0, args.Output.rfind(".png"));
  int result = steps ? 0 : 1;
  for (int k = 0; k < 4 && result == 0; ++k)
  {
    mapper->GetInputInformation(0, 0)->Set(
      vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), times[k]);
    const int frames = Settle(window, mapper);
    std::cerr << "step " << k << " (time " << times[k] << "): settled after " << frames
              << " frames, " << mapper->GetPagingStatistics().IoWaitFrames
              << " I/O-wait frames in all\n";
    step.Output = base + "_" + std::to_string(k) + ".png";
    step.Camera = k == 0 ? args.Camera : "";
    result = Save(window, step) ? 0 : 1;
  }
  if (!args.KeepPools)
    for (const std::string& pool : pools)
      std::remove(pool.c_str());
  return result;
}

/// The subsurface scene: a synthetic survey written from the Reek horizons on their own grid
/// (every 8th node), read back in world coordinates, drawn over the base horizon with no
/// transform, and one pick at the window's centre.
int Subsurface(const Arguments& args)
{
  vtkNew<vtkSyntheticSurveyWriter> survey;
  std::vector<vtkSmartPointer<vtkIrapBinaryGridReader>> grids;
  for (const char* name : ReekNames)
  {
    auto reader = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
    reader->SetFileName((args.Data + "/horizons/" + name + ".gri").c_str());
    survey->AddInputConnection(reader->GetOutputPort());
    grids.push_back(reader);
  }
  grids[0]->Update();
  vtkImageData* grid = grids[0]->GetOutput();
  int dims[3];
  grid->GetDimensions(dims);
  vtkMatrix3x3* d = grid->GetDirectionMatrix();
  survey->SetOrigin(grid->GetOrigin()[0], grid->GetOrigin()[1]);
  survey->SetRotation(
    vtkMath::DegreesFromRadians(std::atan2(d->GetElement(1, 0), d->GetElement(0, 0))));
  survey->SetBins(8 * grid->GetSpacing()[1], 8 * grid->GetSpacing()[0]);
  survey->SetLines((dims[1] - 1) / 8 + 1, (dims[0] - 1) / 8 + 1);
  survey->SetSamples(160, 4.0, 1444); // depths in m: 4 m samples over the reservoir
  survey->SetPeakFrequency(30.0);     // cycles per km for depths
  const std::string path = args.Work + "/reek-synthetic.sgy";
  survey->SetFileName(path.c_str());
  if (!survey->Write())
    return 1;

  vtkNew<vtkSegyVolumeReader> seismic;
  seismic->SetFileName(path.c_str()); // placed by its trace coordinates, z = -depth
  vtkNew<vtkMultiVolumeRayCastMapper> volumeMapper;
  volumeMapper->SetInputConnection(seismic->GetOutputPort());
  auto property =
    VolumeProperty({ { -0.1, 0.15, 0.3, 1.0 }, { 0, 1, 1, 1 }, { 0.1, 1.0, 0.25, 0.1 } },
      { { -0.1, 0.6 }, { -0.02, 0.0 }, { 0.02, 0.0 }, { 0.1, 0.6 } });
  property->SetScalarOpacityUnitDistance(20.0);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(volumeMapper);
  volume->SetProperty(property);
  volume->SetScale(1, 1, 8);
  vtkNew<vtkStackedHeightFieldMapper> base;
  base->AddInputConnection(grids[3]->GetOutputPort());
  base->SetHeightScale(-1.0); // the same z as the volume
  base->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  vtkNew<vtkActor> actor;
  actor->SetMapper(base);
  actor->SetScale(1, 1, 8);
  auto renderer = Renderer();
  renderer->AddActor(actor);
  renderer->AddVolume(volume);
  View(renderer, -60, 30, 2.0);
  auto window = Window(renderer, 320, 240);
  window->Render();
  vtkNew<vtkSubsurfacePicker> picker;
  if (picker->Pick(160.5, 120.5, 0.0, renderer))
  {
    const double* p = picker->GetPickPosition();
    std::cerr << "pick at the centre: (" << p[0] << ", " << p[1] << ", " << p[2] << "), horizon "
              << picker->GetHorizonId() << ", " << picker->GetRayPoints()->GetNumberOfPoints()
              << " volume samples\n";
  }
  const int result = Save(window, args) ? 0 : 1;
  if (!args.KeepPools)
    std::remove(path.c_str());
  return result;
}
}

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<int(const Arguments&)>> scenes = {
    { "horizons", Horizons },
    { "horizons_numpy", HorizonsNumpy },
    { "volumes", Volumes },
    { "hybrid", Hybrid },
    { "paged_volume", PagedVolume },
    { "paged_horizons", PagedHorizons },
    { "subsurface", Subsurface },
    { "time_series", TimeSeries },
  };
  if (argc < 3 || !scenes.count(argv[1]))
  {
    std::cerr
      << "usage: StrataExamples <horizons|horizons_numpy|volumes|hybrid|paged_volume|"
         "paged_horizons|subsurface|time_series> <out.png> [--data <folder>] [--work <folder>] "
         "[--camera <view.json>] "
         "[--keep-pools]\n";
    return 2;
  }
  Arguments args;
  args.Output = argv[2];
  args.Data = STRATA_EXAMPLES_DATA;
  const size_t slash = args.Output.find_last_of('/');
  args.Work = slash == std::string::npos ? "." : args.Output.substr(0, slash);
  for (int a = 3; a < argc; a += 2)
  {
    const std::string option = argv[a];
    if (option == "--keep-pools")
    {
      args.KeepPools = true;
      --a;
      continue;
    }
    if (a + 1 >= argc)
    {
      std::cerr << option << " needs a value\n";
      return 2;
    }
    if (option == "--data")
      args.Data = argv[a + 1];
    else if (option == "--work")
      args.Work = argv[a + 1];
    else if (option == "--camera")
      args.Camera = argv[a + 1];
    else
    {
      std::cerr << "unknown option " << option << "\n";
      return 2;
    }
  }
  return scenes.at(argv[1])(args);
}

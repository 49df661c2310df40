// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The mappers' shader composers: a frame that draws what the last one drew builds no shader
// source and compiles nothing (programs are kept by their feature key, bound without building
// or hashing a source), a new feature builds exactly the programs it needs, going back to
// features seen before builds nothing, and a release makes the programs be handed to VTK again
// without building their sources again. Counted through each mapper's
// GetNumberOfShaderSourcesBuilt() and GetNumberOfShaderCompilations(), for the height-field
// mapper (solid colours, then a lookup table), the multi-volume mapper (two overlapping
// volumes: two one-volume fragments and one two-volume fragment, then two rays per pixel) and
// the hybrid mapper (squares, then splats).
#include "StrataHeightFieldScenes.h" // For MakeHorizon
#include "StrataTestHelpers.h"
#include "StrataVolumeScenes.h" // For MakeBlobVolume, MakeVolumeProperty

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <string>

using namespace strata_test;

namespace
{
/// Sources built and compilations of a mapper so far.
struct Counts
{
  int Sources = 0;
  int Compilations = 0;
  std::string Text() const
  {
    return std::to_string(this->Sources) + " sources, " + std::to_string(this->Compilations) +
           " compilations";
  }
};

template<typename Mapper>
Counts CountsOf(Mapper* m)
{
  return { m->GetNumberOfShaderSourcesBuilt(), m->GetNumberOfShaderCompilations() };
}

/// Renders and returns what the render added to the counts.
template<typename Mapper>
Counts Render(vtkRenderWindow* win, Mapper* m)
{
  const Counts before = CountsOf(m);
  win->Render();
  const Counts after = CountsOf(m);
  return { after.Sources - before.Sources, after.Compilations - before.Compilations };
}

vtkSmartPointer<vtkImageData> Grid(int n, double height)
{
  std::vector<float> z(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      z[size_t(j) * n + i] = static_cast<float>(height + std::sin(0.3 * i) * std::cos(0.2 * j));
  return MakeHorizon(n, n, 0.0, 0.0, 1.0, 1.0, 0.0, z);
}

vtkSmartPointer<vtkImageData> Blob(int n, double shift)
{
  const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { shift, 0.0, 0.0 };
  return MakeBlobVolume(n, n, n, spacing, origin, 1);
}

/// The common sequence: first frame, an unchanged frame, a moved camera, a new feature, the
/// old feature back, and a frame after the mapper released its resources.
template<typename Mapper>
void Sequence(const std::string& name,
  vtkRenderer* ren,
  vtkRenderWindow* win,
  Mapper* m,
  int firstSources,
  int featureSources,
  const std::function<void(bool)>& feature)
{
  const Counts first = Render(win, m);
  std::cout << name << ": first frame " << first.Text() << "\n";
  Check(first.Sources == firstSources && first.Compilations == firstSources,
    name + ": the first frame builds and compiles " + std::to_string(firstSources));
  const Counts same = Render(win, m);
  Check(same.Sources == 0 && same.Compilations == 0,
    name + ": an unchanged frame builds no source and compiles nothing (" + same.Text() + ")");
  ren->GetActiveCamera()->Azimuth(30.0);
  const Counts moved = Render(win, m);
  Check(moved.Sources == 0 && moved.Compilations == 0,
    name + ": a moved camera builds and compiles nothing (" + moved.Text() + ")");
  feature(true);
  const Counts changed = Render(win, m);
  Check(changed.Sources == featureSources && changed.Compilations == featureSources,
    name + ": a new feature builds and compiles its " + std::to_string(featureSources) + " (" +
      changed.Text() + ")");
  feature(false);
  const Counts back = Render(win, m);
  Check(back.Sources == 0 && back.Compilations == 0,
    name + ": back to the first features builds and compiles nothing (" + back.Text() + ")");
  m->ReleaseGraphicsResources(win);
  const Counts released = Render(win, m);
  Check(released.Sources == 0 && released.Compilations == firstSources,
    name + ": after a release the programs are compiled again from the sources kept (" +
      released.Text() + ")");
}

vtkSmartPointer<vtkRenderWindow> MakeWindow(vtkRenderer* ren)
{
  auto win = vtkSmartPointer<vtkRenderWindow>::New();
  win->SetSize(96, 96);
  win->SetMultiSamples(0);
  win->AddRenderer(ren);
  vtkNew<vtkLight> light;
  ren->AddLight(light);
  return win;
}
}

int TestShaderCache(int, char*[])
{
  {
    vtkNew<vtkRenderer> ren;
    auto win = MakeWindow(ren);
    vtkNew<vtkStackedHeightFieldMapper> mapper;
    mapper->AddInputDataObject(Grid(33, 0.0));
    mapper->AddInputDataObject(Grid(33, 2.0));
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    ren->AddActor(actor);
    ren->ResetCamera();
    Sequence("horizons",
      ren,
      win,
      mapper.Get(),
      1,
      1,
      [&](bool lut)
      {
        mapper->SetColorMode(lut ? vtkStackedHeightFieldMapper::ColorModes::LookupTable
                                 : vtkStackedHeightFieldMapper::ColorModes::Solid);
      });
  }
  {
    vtkNew<vtkRenderer> ren;
    auto win = MakeWindow(ren);
    vtkNew<vtkMultiVolumeRayCastMapper> mapper;
    mapper->SetSampleDistance(0.5);
    vtkNew<vtkMultiVolume> multi;
    multi->SetMapper(mapper);
    for (int port = 0; port < 2; ++port)
    {
      mapper->SetInputDataObject(port, Blob(20, 10.0 * port));
      vtkNew<vtkVolume> member;
      member->SetProperty(MakeVolumeProperty(0));
      multi->SetVolume(member, port);
    }
    ren->AddVolume(multi);
    ren->ResetCamera();
    // Three fragments, of one, one and two volumes: two fragment programs and the composite;
    // two rays per pixel need them again, for two rays.
    Sequence("volumes",
      ren,
      win,
      mapper.Get(),
      3,
      3,
      [&](bool rays) { mapper->SetRaysPerPixel(rays ? 2 : 1); });
    Check(mapper->GetNumberOfFragments() == 3, "volumes: three fragments drawn");
  }
  {
    vtkNew<vtkRenderer> ren;
    auto win = MakeWindow(ren);
    vtkNew<vtkHybridVolumeMapper> mapper;
    mapper->SetInputData(Blob(12, 0.0));
    mapper->SetPointsInputData(MakeHybridPointLine(40, 0.2));
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(MakeVolumeProperty(0));
    ren->AddVolume(volume);
    ren->ResetCamera();
    Sequence("hybrid points",
      ren,
      win,
      mapper.Get(),
      1,
      1,
      [&](bool splats)
      {
        mapper->SetPointShape(splats ? vtkHybridVolumeMapper::PointShapes::GaussianSplats
                                     : vtkHybridVolumeMapper::PointShapes::Squares);
      });
    const Counts inner = CountsOf(mapper->GetVolumeMapper());
    Check(inner.Sources == 2,
      "hybrid: its ray caster built one fragment and one composite source (" + inner.Text() + ")");
  }
  std::cout << "TestShaderCache: " << Failures() << " failure(s)\n";
  return Failures() == 0 ? 0 : 1;
}

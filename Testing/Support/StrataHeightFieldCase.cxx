// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldCase.h"

#include "StrataHeightFieldScenes.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

namespace strata_test
{
HeightFieldScene::HeightFieldScene(const std::string& imageDirectory,
  const std::vector<vtkSmartPointer<vtkImageData>>& images,
  int w,
  int h)
  : Images(images)
  , ImageDirectory(imageDirectory)
{
  MakeWindow(this->Win, this->Ren, w, h);
  for (auto& image : images)
  {
    this->Mapper->AddInputDataObject(image);
  }
  this->Mapper->SetTileSize(16);
  this->Actor->SetMapper(this->Mapper);
  this->Ren->AddActor(this->Actor);
}

void HeightFieldScene::Camera(const double pos[3], const double focal[3], const double up[3])
{
  vtkCamera* c = this->Ren->GetActiveCamera();
  c->SetPosition(pos[0], pos[1], pos[2]);
  c->SetFocalPoint(focal[0], focal[1], focal[2]);
  c->SetViewUp(up[0], up[1], up[2]);
  this->Ren->ResetCameraClippingRange();
}

bool HeightFieldScene::Check(const std::string& name, long minCovered)
{
  return CheckReference(
    CompareWithReference(
      this->Win, this->Ren, this->Actor, this->Mapper, this->Images, name, this->ImageDirectory),
    name,
    minCovered);
}

std::vector<float> Field(int nx, int ny, int seed, double base, double amp)
{
  std::vector<float> h(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      h[static_cast<size_t>(j) * nx + i] =
        static_cast<float>(base + amp * FractalNoise(i * 0.07, j * 0.07, seed, 5));
  return h;
}

void Center(vtkImageData* image, double c[3])
{
  double b[6];
  image->GetBounds(b);
  c[0] = 0.5 * (b[0] + b[1]);
  c[1] = 0.5 * (b[2] + b[3]);
  c[2] = 0.0;
}
}

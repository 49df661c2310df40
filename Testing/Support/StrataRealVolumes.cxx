// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataRealVolumes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace strata_test
{
namespace
{
std::string SharedData(const TestPaths& paths)
{
  return paths.SharedData.empty() ? "../shared/data" : paths.SharedData;
}

bool Readable(const std::string& path)
{
  return static_cast<bool>(std::ifstream(path));
}
}

/// Reads a data set by name; on failure returns nullptr and says why in `why`.
vtkSmartPointer<vtkImageData> LoadRealVolume(const std::string& name,
  const TestPaths& paths,
  std::string& why)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const std::string dir = SharedData(paths) + "/volumes/";
  if (name == "bucky")
  {
    std::string path = paths.Data + "/volumes/bucky.raw";
    if (!Readable(path))
      path = dir + "bucky.raw";
    if (!Readable(path))
    {
      why = "missing " + path;
      return nullptr;
    }
    vtkNew<vtkImageReader2> reader;
    reader->SetFileName(path.c_str());
    reader->SetFileDimensionality(3);
    reader->SetDataScalarTypeToUnsignedChar();
    reader->SetDataExtent(0, 31, 0, 31, 0, 31);
    reader->SetDataByteOrderToLittleEndian();
    reader->Update();
    image->ShallowCopy(reader->GetOutput());
  }
  else if (name == "tooth")
  {
    std::string path = paths.Data + "/volumes/tooth.nrrd";
    if (!Readable(path))
      path = dir + "tooth.nrrd";
    if (!Readable(path))
    {
      why = "missing " + path;
      return nullptr;
    }
    vtkNew<vtkNrrdReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    image->ShallowCopy(reader->GetOutput());
  }
  else if (name == "engine" || name == "bonsai")
  {
    const std::string path = dir + name + ".vti";
    if (!Readable(path))
    {
      why = "missing " + path;
      return nullptr;
    }
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    image->ShallowCopy(reader->GetOutput());
  }
  else
  {
    why = "unknown data set " + name + " (known: bucky tooth engine bonsai)";
    return nullptr;
  }
  if (image->GetNumberOfPoints() < 8 || !image->GetPointData()->GetScalars())
  {
    why = "could not read " + name;
    return nullptr;
  }
  image->SetOrigin(0, 0, 0);
  return image;
}

/// Hand-tuned transfer functions over the full 8-bit range of each data set (so that neither
/// mapper clamps data to the table's ends), opacity per voxel, trilinear interpolation.
vtkSmartPointer<vtkVolumeProperty> MakeRealVolumeProperty(const std::string& name)
{
  auto p = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkColorTransferFunction> ctf;
  vtkNew<vtkPiecewiseFunction> pwf;
  if (name == "bucky")
  {
    // The demo's: carbon shells orange and fairly opaque, the empty inside clear.
    ctf->AddRGBPoint(0, 0.9, 0.9, 0.95);
    ctf->AddRGBPoint(60, 0.95, 0.85, 0.5);
    ctf->AddRGBPoint(255, 1.0, 0.5, 0.2);
    pwf->AddPoint(0, 0.0);
    pwf->AddPoint(25, 0.0);
    pwf->AddPoint(80, 0.25);
    pwf->AddPoint(255, 0.6);
  }
  else if (name == "tooth")
  {
    // Background (72-88) clear, dentin (150-170) a faint red haze, enamel (> 215) white.
    ctf->AddRGBPoint(0, 0.5, 0.5, 0.5);
    ctf->AddRGBPoint(140, 0.8, 0.35, 0.25);
    ctf->AddRGBPoint(180, 0.95, 0.7, 0.5);
    ctf->AddRGBPoint(230, 1.0, 1.0, 0.95);
    ctf->AddRGBPoint(255, 1.0, 1.0, 1.0);
    pwf->AddPoint(0, 0.0);
    pwf->AddPoint(110, 0.0);
    pwf->AddPoint(150, 0.02);
    pwf->AddPoint(185, 0.04);
    pwf->AddPoint(215, 0.15);
    pwf->AddPoint(235, 0.5);
    pwf->AddPoint(255, 0.6);
  }
  else if (name == "engine")
  {
    // Air (< 60) clear, the block (120-160) a thin blue-grey shell, dense parts (> 190) orange.
    ctf->AddRGBPoint(0, 0.0, 0.0, 0.0);
    ctf->AddRGBPoint(90, 0.3, 0.4, 0.9);
    ctf->AddRGBPoint(150, 0.8, 0.8, 0.9);
    ctf->AddRGBPoint(200, 1.0, 0.6, 0.2);
    ctf->AddRGBPoint(255, 1.0, 0.95, 0.6);
    pwf->AddPoint(0, 0.0);
    pwf->AddPoint(70, 0.0);
    pwf->AddPoint(130, 0.015);
    pwf->AddPoint(170, 0.03);
    pwf->AddPoint(200, 0.3);
    pwf->AddPoint(255, 0.8);
  }
  else
  {
    // bonsai: the tree only (leaves 48-60 green, branches to 110 brown); air, the noise below
    // 48, soil and pot (> 118) clear, so most of the volume is empty under the transfer function.
    ctf->AddRGBPoint(0, 0.2, 0.7, 0.2);
    ctf->AddRGBPoint(50, 0.2, 0.7, 0.2);
    ctf->AddRGBPoint(100, 0.55, 0.35, 0.15);
    ctf->AddRGBPoint(255, 0.55, 0.35, 0.15);
    pwf->AddPoint(0, 0.0);
    pwf->AddPoint(48, 0.0);
    pwf->AddPoint(60, 0.08);
    pwf->AddPoint(100, 0.3);
    pwf->AddPoint(118, 0.0);
    pwf->AddPoint(255, 0.0);
  }
  p->SetColor(ctf);
  p->SetScalarOpacity(pwf);
  p->SetScalarOpacityUnitDistance(1.0);
  p->SetInterpolationTypeToLinear();
  return p;
}

/// Camera from direction `dir` at the centre of the world bounds of the (image, volume) pairs,
/// at `distanceFactor` times the distance from which their bounding sphere just fills the view
/// (below 1: closer, the sphere's rim outside the view).
void FrameVolumes(vtkRenderer* ren,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  const double dir[3],
  const double up[3],
  double distanceFactor)
{
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (const auto& v : volumes)
  {
    double b[6];
    v.first->GetBounds(b);
    v.second->ComputeMatrix();
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[4] = {
        b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1
      };
      double w[4];
      v.second->GetMatrix()->MultiplyPoint(p, w);
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], w[c]);
        hi[c] = std::max(hi[c], w[c]);
      }
    }
  }
  double centre[3], radius = 0.0, len = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    centre[c] = 0.5 * (lo[c] + hi[c]);
    radius += 0.25 * (hi[c] - lo[c]) * (hi[c] - lo[c]);
    len += dir[c] * dir[c];
  }
  radius = std::sqrt(radius);
  len = std::sqrt(len);
  const double distance = distanceFactor * radius / std::sin(15.0 * std::acos(-1.0) / 180.0);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(centre);
  cam->SetPosition(centre[0] + distance * dir[0] / len,
    centre[1] + distance * dir[1] / len,
    centre[2] + distance * dir[2] / len);
  cam->SetViewUp(up[0], up[1], up[2]);
  cam->SetViewAngle(30);
  ren->ResetCameraClippingRange(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
}

/// Each data set's view: direction from the focal point towards the eye, and up.
void RealVolumeView(const std::string& name, double dir[3], double up[3])
{
  const double d[3] = { -0.6, -1.0, 0.7 }, z[3] = { 0, 0, 1 };
  const double e[3] = { 1.0, -0.8, 0.4 };                     // the tooth from its side
  const double b[3] = { 0.9, 0.35, 0.6 }, y[3] = { 0, 1, 0 }; // the bonsai grows along +y
  const double* s = name == "tooth" ? e : name == "bonsai" ? b : d;
  const double* u = name == "bonsai" ? y : z;
  std::copy(s, s + 3, dir);
  std::copy(u, u + 3, up);
}

}

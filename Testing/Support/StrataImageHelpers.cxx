// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataImageHelpers.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"

#include <algorithm>
#include <cmath>

namespace strata_test
{
std::vector<unsigned char> ReadRGB(vtkRenderWindow* win)
{
  const int* size = win->GetSize();
  std::vector<unsigned char> rgb(size_t(size[0]) * size[1] * 3);
  unsigned char* data = win->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, 0);
  std::copy(data, data + rgb.size(), rgb.begin());
  delete[] data;
  return rgb;
}

std::vector<float> RenderRGBA(vtkRenderWindow* win)
{
  win->Render();
  const int* size = win->GetSize();
  vtkNew<vtkFloatArray> pixels;
  win->GetRGBAPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  const float* data = pixels->GetPointer(0);
  return std::vector<float>(data, data + size_t(size[0]) * size[1] * 4);
}

OverDifference CompareOver(const std::vector<float>& front,
  const std::vector<float>& back,
  const std::vector<float>& whole)
{
  OverDifference d;
  for (size_t p = 0; p < whole.size(); p += 4)
  {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const double over = front[p + c] + (1.0 - front[p + 3]) * back[p + c];
      worst = std::max(worst, 255.0 * std::abs(over - whole[p + c]));
    }
    d.Max = std::max(d.Max, worst);
    d.Off += worst > 1.01 ? 1 : 0;
  }
  return d;
}

std::vector<float> ReadDepth(vtkRenderWindow* win)
{
  const int* size = win->GetSize();
  std::vector<float> depth(size_t(size[0]) * size[1]);
  win->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, depth.data());
  return depth;
}

std::vector<int> DecodeIds(const std::vector<unsigned char>& rgb)
{
  std::vector<int> ids(rgb.size() / 3);
  for (size_t i = 0; i < ids.size(); ++i)
  {
    const int v = rgb[3 * i] | (rgb[3 * i + 1] << 8) | (rgb[3 * i + 2] << 16);
    ids[i] = v - 1;
  }
  return ids;
}

IdComparison CompareIds(const std::vector<int>& test,
  const std::vector<int>& reference,
  int width,
  int height)
{
  IdComparison c;
  std::vector<char> bad(size_t(width) * height, 0);
  for (size_t i = 0; i < bad.size(); ++i)
  {
    if (test[i] >= 0 || reference[i] >= 0)
    {
      ++c.Covered;
      if (test[i] != reference[i])
      {
        ++c.Mismatched;
        bad[i] = 1;
      }
    }
  }
  for (int y = 0; y + 1 < height && !c.WideRegion; ++y)
  {
    for (int x = 0; x + 1 < width; ++x)
    {
      const size_t i = size_t(y) * width + x;
      if (bad[i] && bad[i + 1] && bad[i + width] && bad[i + width + 1])
      {
        c.WideRegion = true;
        c.WideX = x;
        c.WideY = y;
        break;
      }
    }
  }
  return c;
}

void WritePNG(const std::string& path, const std::vector<unsigned char>& rgb, int width, int height)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* ptr = static_cast<unsigned char*>(image->GetScalarPointer());
  std::copy(rgb.begin(), rgb.end(), ptr);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

void WriteIdPNG(const std::string& path, const std::vector<int>& ids, int width, int height)
{
  static const unsigned char palette[8][3] = { { 230, 60, 50 },
    { 60, 180, 75 },
    { 0, 130, 200 },
    { 245, 130, 48 },
    { 145, 30, 180 },
    { 70, 240, 240 },
    { 240, 50, 230 },
    { 210, 245, 60 } };
  std::vector<unsigned char> rgb(ids.size() * 3, 0);
  for (size_t i = 0; i < ids.size(); ++i)
  {
    if (ids[i] >= 0)
    {
      for (int k = 0; k < 3; ++k)
      {
        rgb[3 * i + k] = palette[ids[i] % 8][k];
      }
    }
  }
  WritePNG(path, rgb, width, height);
}
}

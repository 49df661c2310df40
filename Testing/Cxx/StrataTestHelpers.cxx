// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataTestHelpers.h"

#include "vtkAlgorithm.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPNGWriter.h"
#include "vtkPagePoolFile.h"
#include "vtkRenderWindow.h"
#include "vtkUnsignedCharArray.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>

namespace strata_test
{
vtkStandardNewMacro(CapturingOutputWindow);

void CapturingOutputWindow::DisplayText(const char* text)
{
  this->Messages.emplace_back(text ? text : "");
  std::cerr << "[captured] " << (text ? text : "") << "\n";
}
void CapturingOutputWindow::DisplayErrorText(const char* text)
{
  ++this->Errors;
  this->DisplayText(text);
}
void CapturingOutputWindow::DisplayWarningText(const char* text)
{
  ++this->Warnings;
  this->DisplayText(text);
}
void CapturingOutputWindow::DisplayGenericWarningText(const char* text)
{
  ++this->Warnings;
  this->DisplayText(text);
}
void CapturingOutputWindow::DisplayDebugText(const char* text)
{
  this->DisplayText(text);
}
CapturingOutputWindow* CapturingOutputWindow::Install()
{
  CapturingOutputWindow* w = CapturingOutputWindow::New();
  vtkOutputWindow::SetInstance(w);
  w->Delete(); // vtkOutputWindow keeps a reference
  return w;
}

std::vector<unsigned char> ReadRGB(vtkRenderWindow* win)
{
  const int* size = win->GetSize();
  std::vector<unsigned char> rgb(size_t(size[0]) * size[1] * 3);
  unsigned char* data = win->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, 0);
  std::copy(data, data + rgb.size(), rgb.begin());
  delete[] data;
  return rgb;
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

void ErrorCounter::Execute(vtkObject*, unsigned long event, void* data)
{
  (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
  // Keep the first message (the algorithm's own; the executive's "returned failure" follows it),
  // without VTK's "ERROR: In file, line" prefix line.
  if (this->First.empty() && data)
  {
    this->First = static_cast<const char*>(data);
    const size_t body = this->First.find("): ");
    this->First = body == std::string::npos ? this->First : this->First.substr(body + 3);
    this->First = this->First.substr(0, this->First.find_last_not_of("\n") + 1);
  }
}

void ErrorCounter::Watch(vtkAlgorithm* algorithm)
{
  for (vtkObject* o :
    { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
  {
    o->AddObserver(vtkCommand::ErrorEvent, this);
    o->AddObserver(vtkCommand::WarningEvent, this);
  }
}

void ErrorCounter::Reset()
{
  this->Errors = this->Warnings = 0;
  this->First.clear();
}

namespace
{
int FailureCount = 0;
}

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++FailureCount;
  }
}

int Failures()
{
  return FailureCount;
}

std::string OutputDirectory()
{
  const char* d = std::getenv("STRATA_TEST_OUTPUT");
  return d && *d ? d : ".";
}
std::string TestDataDirectory()
{
  const char* d = std::getenv("STRATA_TEST_DATA");
  return d && *d ? d : "Testing/Data";
}
std::string SharedDataDirectory()
{
  const char* d = std::getenv("STRATA_SHARED_DATA");
  return d && *d ? d : "";
}
}

namespace strata_test
{
bool CopyFile(const std::string& from, const std::string& to, double fraction)
{
  std::ifstream in(from, std::ios::binary);
  if (!in)
    return false;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t count =
    fraction >= 1.0 ? bytes.size() : static_cast<size_t>(bytes.size() * std::max(0.0, fraction));
  std::ofstream out(to, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(count));
  return static_cast<bool>(out);
}

bool CorruptPage(const std::string& pool, uint64_t page, int offset)
{
  vtkPagePoolFile file;
  if (!file.Open(pool) || page >= file.GetNumberOfPages())
    return false;
  const auto position = static_cast<std::streamoff>(file.GetPageEntry(page).Offset + offset);
  file.Close();
  std::fstream f(pool, std::ios::binary | std::ios::in | std::ios::out);
  char c = 0;
  f.seekg(position);
  f.read(&c, 1);
  c = static_cast<char>(c ^ 0x5A);
  f.seekp(position);
  f.write(&c, 1);
  return static_cast<bool>(f);
}

double PeakRssMB()
{
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // kilobytes on Linux
}

bool FileExists(const std::string& path)
{
  return static_cast<bool>(std::ifstream(path));
}

double Percentile(std::vector<double> values, double q)
{
  if (values.empty())
    return 0.0;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<size_t>(q * (values.size() - 1) + 0.5))];
}
}

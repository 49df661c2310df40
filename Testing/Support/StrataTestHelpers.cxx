// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataTestHelpers.h"

#include "StrataPagePoolFile.h"
#include "vtkObjectFactory.h"

#include <sys/resource.h>

#include <algorithm>
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

void CheckNoVtkMessages(const CapturingOutputWindow* output)
{
  Check(output->Errors == 0 && output->Warnings == 0,
    "VTK printed " + std::to_string(output->Errors) + " errors and " +
      std::to_string(output->Warnings) + " warnings");
}

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
  strata::PagePoolFile file;
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

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// strata-convert: converts a volume or a horizon grid into a Strata page pool (.spp), streaming
// the input slab by slab with bounded memory (vtkImageToPagePoolWriter).
//   volumes -> brick pool: .vti, .mhd/.mha, .nrrd/.nhdr, raw (--raw ...)
//   grids   -> tile pool:  .npy, .gri, and any 2-D input (one point along z)
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkAlgorithm.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMetaImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkNumpyGridReader.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
void Usage(std::ostream& os)
{
  os << "usage: strata-convert <input> <output.spp> [--page-size B] [--compress]\n"
        "         [--memory-limit MB]\n"
        "         [--raw DIMX DIMY DIMZ uint8|uint16|int16|float [--spacing sx sy sz]\n"
        "          [--little|--big] [--header-size BYTES]]\n"
        "inputs: .vti, .mhd/.mha, .nrrd/.nhdr, raw (with --raw) -> brick pool;\n"
        "        .npy, .gri (and any input one point thick along z) -> tile pool\n";
}

struct Progress
{
  int Last = -1;
  static void Callback(vtkObject* caller, unsigned long, void* clientData, void* callData)
  {
    (void)caller;
    auto* self = static_cast<Progress*>(clientData);
    const double f = *static_cast<double*>(callData);
    const int percent = static_cast<int>(f * 100.0 + 1e-9);
    if (percent == self->Last)
    {
      return;
    }
    self->Last = percent;
    constexpr int width = 40;
    const int filled = std::min(width, percent * width / 100);
    std::string bar(filled, '#');
    bar.append(width - filled, '.');
    std::fprintf(stderr, "\r[%s] %3d%%", bar.c_str(), percent);
    std::fflush(stderr);
  }
};

/// Forwards VTK's error messages to stderr without the object/file prefix clutter.
class PlainOutputWindow : public vtkOutputWindow
{
public:
  static PlainOutputWindow* New();
  vtkTypeMacro(PlainOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { std::cerr << "\n" << text; }
};
vtkStandardNewMacro(PlainOutputWindow);

bool ParseInt(const char* s, int& v)
{
  char* end = nullptr;
  const long x = std::strtol(s, &end, 10);
  if (!end || *end || x < -2147483647L || x > 2147483647L)
  {
    return false;
  }
  v = static_cast<int>(x);
  return true;
}

bool ParseDouble(const char* s, double& v)
{
  char* end = nullptr;
  v = std::strtod(s, &end);
  return end && !*end;
}

int Die(const std::string& message)
{
  std::cerr << "strata-convert: " << message << "\n";
  return 1;
}
}

int main(int argc, char* argv[])
{
  std::string input, output;
  int pageSize = 32;
  bool compress = false;
  double memoryMB = 512;
  bool raw = false;
  int rawDims[3] = { 0, 0, 0 };
  std::string rawType;
  double spacing[3] = { 1, 1, 1 };
  bool bigEndian = false;
  int headerSize = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto need = [&](int n) { return i + n < argc; };
    if (a == "-h" || a == "--help")
    {
      Usage(std::cout);
      return 0;
    }
    else if (a == "--page-size" && need(1))
    {
      if (!ParseInt(argv[++i], pageSize))
        return Die("--page-size needs an integer");
    }
    else if (a == "--compress")
    {
      compress = true;
    }
    else if (a == "--memory-limit" && need(1))
    {
      if (!ParseDouble(argv[++i], memoryMB) || !(memoryMB > 0))
        return Die("--memory-limit needs a positive number of MB");
    }
    else if (a == "--raw" && need(4))
    {
      raw = true;
      for (int d = 0; d < 3; ++d)
      {
        if (!ParseInt(argv[++i], rawDims[d]) || rawDims[d] <= 0)
          return Die("--raw needs three positive dimensions");
      }
      rawType = argv[++i];
    }
    else if (a == "--spacing" && need(3))
    {
      for (int d = 0; d < 3; ++d)
      {
        if (!ParseDouble(argv[++i], spacing[d]) || !(spacing[d] > 0))
          return Die("--spacing needs three positive numbers");
      }
    }
    else if (a == "--little")
    {
      bigEndian = false;
    }
    else if (a == "--big")
    {
      bigEndian = true;
    }
    else if (a == "--header-size" && need(1))
    {
      if (!ParseInt(argv[++i], headerSize) || headerSize < 0)
        return Die("--header-size needs a non-negative integer");
    }
    else if (!a.empty() && a[0] == '-')
    {
      Usage(std::cerr);
      return Die("unknown or incomplete option " + a);
    }
    else if (input.empty())
    {
      input = a;
    }
    else if (output.empty())
    {
      output = a;
    }
    else
    {
      Usage(std::cerr);
      return Die("too many arguments");
    }
  }
  if (input.empty() || output.empty())
  {
    Usage(std::cerr);
    return 1;
  }
  if (!vtksys::SystemTools::FileExists(input, true))
  {
    return Die("input \"" + input + "\" does not exist or is not a file");
  }
  vtkOutputWindow::SetInstance(vtkSmartPointer<PlainOutputWindow>::New());

  const std::string ext = vtksys::SystemTools::LowerCase(
    vtksys::SystemTools::GetFilenameLastExtension(input));
  vtkSmartPointer<vtkAlgorithm> reader;
  if (raw)
  {
    auto r = vtkSmartPointer<vtkImageReader2>::New();
    r->SetFileName(input.c_str());
    r->SetFileDimensionality(3);
    r->SetDataExtent(0, rawDims[0] - 1, 0, rawDims[1] - 1, 0, rawDims[2] - 1);
    r->SetDataSpacing(spacing);
    r->SetHeaderSize(static_cast<unsigned long>(headerSize));
    if (rawType == "uint8")
      r->SetDataScalarTypeToUnsignedChar();
    else if (rawType == "uint16")
      r->SetDataScalarTypeToUnsignedShort();
    else if (rawType == "int16")
      r->SetDataScalarTypeToShort();
    else if (rawType == "float")
      r->SetDataScalarTypeToFloat();
    else
      return Die("unknown raw type \"" + rawType + "\" (uint8, uint16, int16 or float)");
    if (bigEndian)
      r->SetDataByteOrderToBigEndian();
    else
      r->SetDataByteOrderToLittleEndian();
    // Check the size before the pipeline reads past the end of a too-short file.
    const unsigned long long size = vtksys::SystemTools::FileLength(input);
    const int bytes = rawType == "uint8" ? 1 : rawType == "float" ? 4 : 2;
    const unsigned long long need = static_cast<unsigned long long>(headerSize) +
      static_cast<unsigned long long>(rawDims[0]) * rawDims[1] * rawDims[2] * bytes;
    if (size < need)
    {
      return Die("raw file \"" + input + "\" has " + std::to_string(size) + " bytes, " +
        std::to_string(need) + " needed");
    }
    reader = r;
  }
  else if (ext == ".vti")
  {
    auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".mhd" || ext == ".mha")
  {
    auto r = vtkSmartPointer<vtkMetaImageReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".nrrd" || ext == ".nhdr")
  {
    auto r = vtkSmartPointer<vtkNrrdReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".npy")
  {
    auto r = vtkSmartPointer<vtkNumpyGridReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".gri")
  {
    auto r = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else
  {
    Usage(std::cerr);
    return Die("cannot tell the format of \"" + input + "\" (use --raw for raw files)");
  }

  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(output.c_str());
  writer->SetPageSize(pageSize);
  writer->SetCompression(compress);
  writer->SetMemoryLimit(memoryMB);
  Progress progress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetCallback(&Progress::Callback);
  onProgress->SetClientData(&progress);
  writer->AddObserver(vtkCommand::ProgressEvent, onProgress);

  const auto start = std::chrono::steady_clock::now();
  const bool ok = writer->Write();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress.Last >= 0)
  {
    std::fprintf(stderr, "\n");
  }
  if (!ok)
  {
    return Die("conversion of \"" + input + "\" failed; no output written");
  }
  std::printf("%s: %lld bytes, %lld pages (%s), %.2f s\n", output.c_str(),
    static_cast<long long>(writer->GetFileSize()), static_cast<long long>(writer->GetNumberOfPages()),
    compress ? "zstd" : "raw", seconds);
  return 0;
}

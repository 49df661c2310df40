// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// strata-hybrid: builds the hybrid point/volume representation of a volume (a low-resolution
// volume plus points where it errs; strata::HybridVolumeBuilder) and writes it as a .shv file.
//   raw (--raw ...):           streamed from the file slab by slab, memory bounded by
//                              --memory-limit plus one slice;
//   .vti, .mhd/.mha, .nrrd:    read whole through its VTK reader, then vtkHybridVolumeFilter.
#include "StrataCommandLine.h"
#include "StrataHybridVolumeBuilder.h"
#include "StrataHybridVolumeFile.h"
#include "vtkByteSwap.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <vtksys/FStream.hxx>

#include <chrono>
#include <cstdint>
#include <vector>

namespace
{
using strata_cli::ParseDouble;
using strata_cli::ParseInt;

void Usage(std::ostream& os)
{
  os << "usage: strata-hybrid <input> <output.shv> [--factor F]\n"
        "         [--filter box|linear|cubic|optimized] [--bound B] [--threshold T]\n"
        "         [--budget N] [--error-grid S] [--memory-limit MB]\n"
        "         "
     << strata_cli::RawVolumeOptions::Usage
     << "\n"
        "inputs: .vti, .mhd/.mha, .nrrd/.nhdr (read whole), raw with --raw (streamed)\n"
        "defaults: factor 2, cubic, bound 0, threshold 0, no budget, error grid 1, 256 MB\n";
}

int Die(const std::string& message)
{
  std::cerr << "strata-hybrid: " << message << "\n";
  return 1;
}

/// Reads `n` raw samples of type T in file byte order and converts them to float.
template<typename T>
bool ReadSlice(std::istream& file, size_t n, bool bigEndian, float* out)
{
  std::vector<T> values(n);
  if (!file.read(reinterpret_cast<char*>(values.data()), n * sizeof(T)))
  {
    return false;
  }
  if (bigEndian)
  {
    vtkByteSwap::SwapBERange(values.data(), n);
  }
  else
  {
    vtkByteSwap::SwapLERange(values.data(), n);
  }
  std::copy(values.begin(), values.end(), out);
  return true;
}

/// z slices of a raw volume, read one at a time straight from the file (the builder asks for
/// each slice once per pass and holds no more than its memory limit).
struct RawVolume
{
  explicit RawVolume(const strata_cli::RawVolumeOptions& options)
    : Options(options)
    , SliceValues(static_cast<size_t>(options.Dimensions[0]) * options.Dimensions[1])
  {
  }

  bool Read(int first, int count, float* out)
  {
    const strata_cli::RawVolumeOptions& o = this->Options;
    const unsigned long long sliceBytes = this->SliceValues * o.GetTypeSize();
    for (int z = first; z < first + count; ++z)
    {
      float* dst = out + this->SliceValues * (z - first);
      this->File.seekg(static_cast<std::streamoff>(o.HeaderSize + sliceBytes * z));
      const bool ok =
        o.Type == "uint8"    ? ReadSlice<uint8_t>(this->File, this->SliceValues, o.BigEndian, dst)
        : o.Type == "uint16" ? ReadSlice<uint16_t>(this->File, this->SliceValues, o.BigEndian, dst)
        : o.Type == "int16"  ? ReadSlice<int16_t>(this->File, this->SliceValues, o.BigEndian, dst)
                             : ReadSlice<float>(this->File, this->SliceValues, o.BigEndian, dst);
      if (!ok)
      {
        return false;
      }
    }
    return true;
  }

  const strata_cli::RawVolumeOptions& Options;
  const size_t SliceValues;
  vtksys::ifstream File;
};

void CountError(vtkObject*, unsigned long, void* clientData, void*)
{
  ++*static_cast<int*>(clientData);
}
}

int main(int argc, char* argv[])
{
  std::string input, output;
  vtkNew<vtkHybridVolumeFilter> filter;
  strata_cli::RawVolumeOptions raw;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto need = [&](int n) { return i + n < argc; };
    int n = 0;
    double x = 0;
    std::string error;
    if (a == "-h" || a == "--help")
    {
      Usage(std::cout);
      return 0;
    }
    else if (raw.Parse(argc, argv, i, error))
    {
      if (!error.empty())
        return Die(error);
    }
    else if (a == "--factor" && need(1))
    {
      if (!ParseInt(argv[++i], n))
        return Die("--factor needs an integer (1, 2, 4 or 8)");
      filter->SetFactor(n, n, n);
    }
    else if (a == "--filter" && need(1))
    {
      const std::string name = argv[++i];
      bool known = false;
      for (auto f : { vtkHybridVolumeFilter::FilterType::Box,
             vtkHybridVolumeFilter::FilterType::Linear,
             vtkHybridVolumeFilter::FilterType::Cubic,
             vtkHybridVolumeFilter::FilterType::Optimized })
      {
        if (name == vtkHybridVolumeFilter::GetFilterName(f))
        {
          filter->SetFilter(f);
          known = true;
        }
      }
      if (!known)
        return Die("--filter needs box, linear, cubic or optimized");
    }
    else if (a == "--bound" && need(1))
    {
      if (!ParseDouble(argv[++i], x) || !(x >= 0))
        return Die("--bound needs a number >= 0");
      filter->SetOverestimationBound(x);
    }
    else if (a == "--threshold" && need(1))
    {
      if (!ParseDouble(argv[++i], x) || !(x >= 0))
        return Die("--threshold needs a number >= 0");
      filter->SetThreshold(x);
    }
    else if (a == "--budget" && need(1))
    {
      long long budget = 0;
      if (!strata_cli::ParseInt64(argv[++i], budget) || budget < 0)
        return Die("--budget needs a non-negative integer");
      filter->SetPointBudget(static_cast<vtkIdType>(budget));
    }
    else if (a == "--error-grid" && need(1))
    {
      if (!ParseInt(argv[++i], n) || n < 1)
        return Die("--error-grid needs a positive integer");
      filter->SetErrorGridStep(n, n, n);
    }
    else if (a == "--memory-limit" && need(1))
    {
      if (!ParseDouble(argv[++i], x) || !(x > 0))
        return Die("--memory-limit needs a positive number of MB");
      filter->SetMemoryLimit(x);
    }
    else if (!strata_cli::TakePositional(a, input, output, error))
    {
      Usage(std::cerr);
      return Die(error);
    }
  }
  bool usage = false;
  const std::string pathError = strata_cli::CheckPaths(input, output, usage);
  if (usage)
    Usage(std::cerr);
  if (!pathError.empty())
    return Die(pathError);
  strata_cli::PlainOutputWindow::Install();
  strata_cli::ProgressBar bar;
  const auto start = std::chrono::steady_clock::now();
  long long points = 0;
  int lowDims[3] = { 0, 0, 0 };

  if (raw.Enabled)
  {
    const std::string sizeError = raw.CheckFileSize(input);
    if (!sizeError.empty())
    {
      return Die(sizeError);
    }
    RawVolume volume(raw);
    volume.File.open(input.c_str(), std::ios::in | std::ios::binary);
    if (!volume.File)
    {
      return Die("cannot open \"" + input + "\"");
    }
    strata::HybridVolumeBuilder builder;
    filter->ConfigureBuilder(builder);
    const double origin[3] = { 0, 0, 0 };
    builder.SetInput(raw.Dimensions,
      raw.Spacing,
      origin,
      [&volume](int first, int count, float* out) { return volume.Read(first, count, out); });
    builder.SetProgressCallback([&bar](double fraction) { bar.Show(fraction); });
    strata::HybridVolumeFile file;
    const bool built = builder.Build(file);
    bar.Finish();
    if (!built)
    {
      return Die(builder.GetErrorMessage());
    }
    if (!file.Write(output))
    {
      return Die(file.GetErrorMessage());
    }
    points = static_cast<long long>(file.Points.size());
    std::copy(file.LowDimensions, file.LowDimensions + 3, lowDims);
  }
  else
  {
    vtkSmartPointer<vtkAlgorithm> reader = strata_cli::NewVolumeReader(input);
    if (!reader)
    {
      Usage(std::cerr);
      return Die("cannot tell the format of \"" + input + "\" (use --raw for raw files)");
    }
    if (auto* vti = vtkXMLImageDataReader::SafeDownCast(reader))
    {
      const std::string pieceError = strata_cli::CheckImagePieces(vti);
      if (!pieceError.empty())
        return Die("\"" + input + "\": " + pieceError + "; no output written");
    }
    // Some VTK readers report a bad file with an error and still succeed, with garbage data.
    int errors = 0;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetCallback(CountError);
    onError->SetClientData(&errors);
    reader->AddObserver(vtkCommand::ErrorEvent, onError);
    filter->AddObserver(vtkCommand::ErrorEvent, onError);
    vtkNew<vtkCallbackCommand> onProgress;
    onProgress->SetCallback(&strata_cli::ProgressBar::Callback);
    onProgress->SetClientData(&bar);
    filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
    filter->SetInputConnection(reader->GetOutputPort());
    filter->SetFileName(output.c_str());
    const bool updated = filter->Update(0, nullptr) != 0;
    bar.Finish();
    if (!updated || errors > 0)
    {
      if (updated)
      {
        // Built from what a failing reader left: not a file to keep.
        std::remove(output.c_str());
      }
      return Die("conversion of \"" + input + "\" failed");
    }
    points = static_cast<long long>(filter->GetPointsOutput()->GetNumberOfPoints());
    filter->GetLowResolutionOutput()->GetDimensions(lowDims);
  }

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int* f = filter->GetFactor();
  std::printf("%s: %lld points, %lld bytes, low resolution %dx%dx%d (factor %d,%d,%d, %s), "
              "%.2f s\n",
    output.c_str(),
    points,
    static_cast<long long>(vtksys::SystemTools::FileLength(output)),
    lowDims[0],
    lowDims[1],
    lowDims[2],
    f[0],
    f[1],
    f[2],
    filter->GetFilterAsString(),
    seconds);
  return 0;
}

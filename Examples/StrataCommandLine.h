// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What Strata's command-line tools share (header-only, one translation unit per tool): argument
// parsing (numbers, positional arguments, the raw-volume options), VTK messages on stderr
// without VTK's prefix lines, a progress bar fed by VTK progress events or a plain fraction,
// and the volume readers chosen by file extension.
#ifndef StrataCommandLine_h
#define StrataCommandLine_h

#include "vtkAlgorithm.h"
#include "vtkMetaImageReader.h"
#include "vtkNrrdReader.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace strata_cli
{
/// Whole-string integer in [-2^31 + 1, 2^31 - 1].
inline bool ParseInt(const char* s, int& v)
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

/// Whole-string 64-bit integer.
inline bool ParseInt64(const char* s, long long& v)
{
  char* end = nullptr;
  v = std::strtoll(s, &end, 10);
  return end && end != s && !*end;
}

/// Whole-string floating-point number.
inline bool ParseDouble(const char* s, double& v)
{
  char* end = nullptr;
  v = std::strtod(s, &end);
  return end && end != s && !*end;
}

/// Takes a positional argument into `input`, then `output`; false with `error` for an
/// unrecognised option or a third positional argument.
inline bool TakePositional(const std::string& a,
  std::string& input,
  std::string& output,
  std::string& error)
{
  if (!a.empty() && a[0] == '-')
  {
    error = "unknown or incomplete option " + a;
    return false;
  }
  std::string& slot = input.empty() ? input : output;
  if (!slot.empty())
  {
    error = "too many arguments";
    return false;
  }
  slot = a;
  return true;
}

/// After the arguments: both paths given and the input a file. Empty when so, else what is
/// wrong ("" with `usage` true when a path is missing, so the caller prints its usage).
inline std::string CheckPaths(const std::string& input, const std::string& output, bool& usage)
{
  usage = input.empty() || output.empty();
  if (usage)
    return "an input and an output are needed";
  if (!vtksys::SystemTools::FileExists(input, true))
    return "input \"" + input + "\" does not exist or is not a file";
  return std::string();
}

/// The raw-volume options: --raw DIMX DIMY DIMZ uint8|uint16|int16|float, --spacing sx sy sz,
/// --little | --big, --header-size BYTES.
struct RawVolumeOptions
{
  bool Enabled = false;
  int Dimensions[3] = { 0, 0, 0 };
  std::string Type;
  double Spacing[3] = { 1, 1, 1 };
  bool BigEndian = false;
  int HeaderSize = 0;

  static constexpr const char* Usage = "[--raw DIMX DIMY DIMZ uint8|uint16|int16|float "
                                       "[--spacing sx sy sz]\n"
                                       "          [--little|--big] [--header-size BYTES]]";

  /// Bytes of a sample of Type, 0 for an unknown type.
  int GetTypeSize() const
  {
    const std::string& t = this->Type;
    return t == "uint8" ? 1 : (t == "uint16" || t == "int16") ? 2 : t == "float" ? 4 : 0;
  }

  /// Header plus samples: the least size of the file.
  unsigned long long GetRequiredBytes() const
  {
    return static_cast<unsigned long long>(this->HeaderSize) +
           static_cast<unsigned long long>(this->Dimensions[0]) * this->Dimensions[1] *
             this->Dimensions[2] * this->GetTypeSize();
  }

  /// Empty when the file at `path` holds the whole volume, else what is wrong (checked before
  /// reading, so a short file cannot be read past its end).
  std::string CheckFileSize(const std::string& path) const
  {
    const unsigned long long size = vtksys::SystemTools::FileLength(path);
    if (size < this->GetRequiredBytes())
    {
      return "raw file \"" + path + "\" has " + std::to_string(size) + " bytes, " +
             std::to_string(this->GetRequiredBytes()) + " needed";
    }
    return std::string();
  }

  /// Consumes argv[i] and its values (advancing i) when it is one of these options with all its
  /// values; `error` says when a value is bad. False when argv[i] is none of them.
  bool Parse(int argc, char* argv[], int& i, std::string& error)
  {
    const std::string a = argv[i];
    auto has = [&](int n) { return i + n < argc; };
    if (a == "--raw" && has(4))
    {
      this->Enabled = true;
      for (int d = 0; d < 3; ++d)
      {
        if (!ParseInt(argv[++i], this->Dimensions[d]) || this->Dimensions[d] <= 0)
          error = "--raw needs three positive dimensions";
      }
      this->Type = argv[++i];
      if (error.empty() && !this->GetTypeSize())
        error = "unknown raw type \"" + this->Type + "\" (uint8, uint16, int16 or float)";
    }
    else if (a == "--spacing" && has(3))
    {
      for (int d = 0; d < 3; ++d)
      {
        if (!ParseDouble(argv[++i], this->Spacing[d]) || !(this->Spacing[d] > 0))
          error = "--spacing needs three positive numbers";
      }
    }
    else if (a == "--little" || a == "--big")
    {
      this->BigEndian = a == "--big";
    }
    else if (a == "--header-size" && has(1))
    {
      if (!ParseInt(argv[++i], this->HeaderSize) || this->HeaderSize < 0)
        error = "--header-size needs a non-negative integer";
    }
    else
    {
      return false;
    }
    return true;
  }
};

/// Forwards VTK's messages to stderr without the object/file prefix clutter.
class PlainOutputWindow : public vtkOutputWindow
{
public:
  static PlainOutputWindow* New() { VTK_STANDARD_NEW_BODY(PlainOutputWindow); }
  vtkTypeMacro(PlainOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { std::cerr << "\n" << text; }

  /// Makes it VTK's output window.
  static void Install() { vtkOutputWindow::SetInstance(vtkSmartPointer<PlainOutputWindow>::New()); }
};

/// A 40-character progress bar on stderr, redrawn only when the percentage changes.
class ProgressBar
{
public:
  void Show(double fraction)
  {
    const int percent = static_cast<int>(fraction * 100.0 + 1e-9);
    if (percent == this->Last)
    {
      return;
    }
    this->Last = percent;
    constexpr int width = 40;
    const int filled = std::min(width, std::max(0, percent * width / 100));
    std::string bar(filled, '#');
    bar.append(width - filled, '.');
    std::fprintf(stderr, "\r[%s] %3d%%", bar.c_str(), percent);
    std::fflush(stderr);
  }

  /// Ends the bar's line, if one was drawn.
  void Finish()
  {
    if (this->Last >= 0)
    {
      std::fprintf(stderr, "\n");
    }
  }

  /// A vtkCallbackCommand callback for ProgressEvent; clientData is the ProgressBar.
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    static_cast<ProgressBar*>(clientData)->Show(*static_cast<double*>(callData));
  }

private:
  int Last = -1;
};

/// A reader for a .vti, .mhd/.mha or .nrrd/.nhdr volume, chosen by extension; null otherwise.
inline vtkSmartPointer<vtkAlgorithm> NewVolumeReader(const std::string& path)
{
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  if (ext == ".vti")
  {
    auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == ".mhd" || ext == ".mha")
  {
    auto r = vtkSmartPointer<vtkMetaImageReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == ".nrrd" || ext == ".nhdr")
  {
    auto r = vtkSmartPointer<vtkNrrdReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  return nullptr;
}
}

#endif

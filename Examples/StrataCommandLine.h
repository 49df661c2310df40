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
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

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

/// Where the pieces of an image leave points of `whole` uncovered: "" when their union covers
/// it, else the first uncovered box as "x0 x1 y0 y1 z0 z1". The boundaries of the pieces cut
/// each axis into intervals; every box of intervals lies inside a piece or outside all of them,
/// so testing one corner of each box decides its points.
inline std::string UncoveredExtent(const int whole[6],
  const std::vector<std::array<int, 6>>& pieces)
{
  std::vector<int> cuts[3];
  for (int a = 0; a < 3; ++a)
  {
    const int lo = whole[2 * a];
    const int end = whole[2 * a + 1] + 1;
    cuts[a] = { lo, end };
    for (const auto& p : pieces)
    {
      for (const int c : { p[2 * a], p[2 * a + 1] + 1 })
      {
        if (c > lo && c < end)
        {
          cuts[a].push_back(c);
        }
      }
    }
    std::sort(cuts[a].begin(), cuts[a].end());
    cuts[a].erase(std::unique(cuts[a].begin(), cuts[a].end()), cuts[a].end());
  }
  for (size_t k = 0; k + 1 < cuts[2].size(); ++k)
  {
    for (size_t j = 0; j + 1 < cuts[1].size(); ++j)
    {
      for (size_t i = 0; i + 1 < cuts[0].size(); ++i)
      {
        const int corner[3] = { cuts[0][i], cuts[1][j], cuts[2][k] };
        const bool inside = std::any_of(pieces.begin(),
          pieces.end(),
          [&](const auto& p)
          {
            return p[0] <= corner[0] && corner[0] <= p[1] && p[2] <= corner[1] &&
                   corner[1] <= p[3] && p[4] <= corner[2] && corner[2] <= p[5];
          });
        if (!inside)
        {
          std::ostringstream box;
          box << cuts[0][i] << " " << cuts[0][i + 1] - 1 << " " << cuts[1][j] << " "
              << cuts[1][j + 1] - 1 << " " << cuts[2][k] << " " << cuts[2][k + 1] - 1;
          return box.str();
        }
      }
    }
  }
  return std::string();
}

/// For a .vti reader: "" when its pieces cover its WholeExtent, else why not. VTK's reader
/// fills points outside every piece with zeros and says nothing, so a converter must refuse.
inline std::string CheckImagePieces(vtkXMLImageDataReader* reader)
{
  reader->UpdateInformation();
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* image = root ? root->FindNestedElementWithName("ImageData") : nullptr;
  int whole[6];
  if (!image || image->GetVectorAttribute("WholeExtent", 6, whole) != 6)
  {
    return "cannot read the ImageData element's WholeExtent";
  }
  std::vector<std::array<int, 6>> pieces;
  for (int n = 0; n < image->GetNumberOfNestedElements(); ++n)
  {
    vtkXMLDataElement* piece = image->GetNestedElement(n);
    std::array<int, 6> e;
    if (std::strcmp(piece->GetName(), "Piece") == 0)
    {
      if (piece->GetVectorAttribute("Extent", 6, e.data()) != 6)
      {
        return "a Piece without an Extent";
      }
      pieces.push_back(e);
    }
  }
  const std::string uncovered = UncoveredExtent(whole, pieces);
  if (uncovered.empty())
  {
    return uncovered;
  }
  std::ostringstream msg;
  msg << "its WholeExtent " << whole[0] << " " << whole[1] << " " << whole[2] << " " << whole[3]
      << " " << whole[4] << " " << whole[5] << " is larger than the union of its " << pieces.size()
      << " piece(s): the points of extent " << uncovered
      << " are in none of them (VTK's reader would make them zeros)";
  return msg.str();
}

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

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// strata-convert: converts a volume or a horizon grid into a Strata page pool (.spp), streaming
// the input slab by slab with bounded memory (vtkImageToPagePoolWriter).
//   volumes -> brick pool: .vti, .mhd/.mha (compressed ones read whole), .nrrd/.nhdr,
//                          raw (--raw ...), SEG-Y (.sgy/.segy, read inline by inline)
//   grids   -> tile pool:  .npy, .gri (Irap binary), text grids told by their content (Irap
//                          classic ASCII, ZMAP+, ESRI ASCII .asc), columns or a whitespace
//                          matrix (.txt, .dat, .xyz, .csv), and any 2-D input (one point along z)
// The pool is written to <output>.tmp-<pid> and renamed when complete; temporaries that killed
// runs left beside the output are removed first.
#include "StrataCommandLine.h"
#include "StrataPagePoolFile.h"
#include "vtkAsciiGridReader.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkHorizonColumnReader.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkNew.h"
#include "vtkNumpyGridReader.h"
#include "vtkSegyVolumeReader.h"
#include "vtkStreamingMetaImageReader.h"

#include <vtksys/Directory.hxx>

#include <cerrno>
#include <chrono>
#include <signal.h> // For kill (is a temporary's writer alive?)

namespace
{
using strata_cli::ParseDouble;
using strata_cli::ParseInt;

void Usage(std::ostream& os)
{
  os << "usage: strata-convert <input> <output.spp> [--page-size B] [--compress]\n"
        "         [--memory-limit MB]\n"
        "         "
     << strata_cli::RawVolumeOptions::Usage
     << "\n"
        "         [--inline-byte N] [--crossline-byte N] [--segy-format CODE]\n"
        "         [--x-byte N] [--y-byte N] [--scalar-byte N]\n"
        "         [--placement auto|world|lines] [--vertical-scale S]\n"
        "         [--grid-format irap-ascii|zmap|esri|matrix|columns]\n"
        "inputs: .vti, .mhd/.mha, .nrrd/.nhdr, raw (with --raw), .sgy/.segy -> brick pool;\n"
        "        .npy, .gri, Irap classic ASCII, ZMAP+, ESRI ASCII (.asc), columns or a\n"
        "        whitespace matrix (.txt, .dat, .xyz, .csv), and any input one point thick\n"
        "        along z -> tile pool; a volume of 2-4 components (RGBA, independent\n"
        "        channels) -> a brick pool per component (output.spp, output.c1.spp, ...)\n"
        "SEG-Y: inline and crossline numbers at trace-header bytes 189 and 193 unless given;\n"
        "       --segy-format overrides the binary header's sample format (1, 2, 3, 5, 8);\n"
        "       placed by the trace coordinates (CDP X/Y at 181/185, scalar at 71 unless\n"
        "       given) when they are there, z = vertical scale (default -1) x time or depth;\n"
        "       --placement lines: world = (inline, crossline, time) as before\n"
        "text grids: told by their content unless --grid-format names one (a matrix of 8\n"
        "       values a line or fewer needs --grid-format matrix)\n";
}

int Die(const std::string& message)
{
  std::cerr << "strata-convert: " << message << "\n";
  return 1;
}

/// Removes <output>.tmp-<pid> files whose process is gone: what a conversion killed before its
/// rename left behind (strata::PagePoolWriter names its temporary so). A live pid's file is left.
void RemoveStaleTemporaries(const std::string& output)
{
  const std::string dir = vtksys::SystemTools::GetFilenamePath(output);
  const std::string prefix = vtksys::SystemTools::GetFilenameName(output) + ".tmp-";
  vtksys::Directory listing;
  if (!listing.Load(dir.empty() ? "." : dir))
  {
    return;
  }
  for (unsigned long f = 0; f < listing.GetNumberOfFiles(); ++f)
  {
    const std::string name = listing.GetFile(f);
    long long pid = 0;
    if (name.compare(0, prefix.size(), prefix) != 0 ||
        !strata_cli::ParseInt64(name.c_str() + prefix.size(), pid) || pid <= 0 ||
        pid > 2147483647LL)
    {
      continue;
    }
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
    {
      const std::string path = dir.empty() ? name : dir + "/" + name;
      if (std::remove(path.c_str()) == 0)
      {
        std::cerr << "strata-convert: removed \"" << path << "\", left by a killed conversion\n";
      }
    }
  }
}

/// The raw volume of the --raw options, streamed by vtkImageReader2.
vtkSmartPointer<vtkAlgorithm> NewRawReader(const std::string& path,
  const strata_cli::RawVolumeOptions& raw)
{
  auto r = vtkSmartPointer<vtkImageReader2>::New();
  r->SetFileName(path.c_str());
  r->SetFileDimensionality(3);
  r->SetDataExtent(0, raw.Dimensions[0] - 1, 0, raw.Dimensions[1] - 1, 0, raw.Dimensions[2] - 1);
  r->SetDataSpacing(raw.Spacing[0], raw.Spacing[1], raw.Spacing[2]);
  r->SetHeaderSize(static_cast<unsigned long>(raw.HeaderSize));
  if (raw.Type == "uint8")
    r->SetDataScalarTypeToUnsignedChar();
  else if (raw.Type == "uint16")
    r->SetDataScalarTypeToUnsignedShort();
  else if (raw.Type == "int16")
    r->SetDataScalarTypeToShort();
  else
    r->SetDataScalarTypeToFloat();
  if (raw.BigEndian)
    r->SetDataByteOrderToBigEndian();
  else
    r->SetDataByteOrderToLittleEndian();
  return r;
}

/// The text grid reader that --grid-format names; null for an unknown name.
vtkSmartPointer<vtkAlgorithm> NewTextGridReader(const std::string& input, const std::string& format)
{
  if (format == "columns")
  {
    auto r = vtkSmartPointer<vtkHorizonColumnReader>::New();
    r->SetFileName(input.c_str());
    return r;
  }
  using Format = vtkAsciiGridReader::GridFormat;
  const std::pair<const char*, Format> names[] = { { "irap-ascii", Format::IrapClassic },
    { "zmap", Format::Zmap },
    { "esri", Format::EsriAscii },
    { "matrix", Format::Matrix } };
  for (const auto& n : names)
  {
    if (format == n.first)
    {
      auto r = vtkSmartPointer<vtkAsciiGridReader>::New();
      r->SetFileName(input.c_str());
      r->SetFormat(n.second);
      return r;
    }
  }
  return nullptr;
}

/// A volume reader by extension, else a text grid reader by content (Irap classic, ZMAP+, ESRI
/// ASCII), else the column reader for text extensions (it reads a whitespace matrix too).
vtkSmartPointer<vtkAlgorithm> NewGridOrVolumeReader(const std::string& input,
  const std::string& ext)
{
  if (vtkSmartPointer<vtkAlgorithm> volume = strata_cli::NewVolumeReader(input))
  {
    return volume;
  }
  if (vtkAsciiGridReader::CanReadFile(input.c_str()))
  {
    auto r = vtkSmartPointer<vtkAsciiGridReader>::New();
    r->SetFileName(input.c_str());
    return r;
  }
  if (ext == ".txt" || ext == ".dat" || ext == ".xyz" || ext == ".csv")
  {
    auto r = vtkSmartPointer<vtkHorizonColumnReader>::New();
    r->SetFileName(input.c_str());
    return r;
  }
  return nullptr;
}
}

int main(int argc, char* argv[])
{
  std::string input, output;
  int pageSize = 32;
  bool compress = false;
  double memoryMB = 512;
  strata_cli::RawVolumeOptions raw;
  int inlineByte = 189;
  int crosslineByte = 193;
  int segyFormat = 0;
  int xByte = 181, yByte = 185, scalarByte = 71;
  auto placement = vtkSegyVolumeReader::Placements::Automatic;
  double verticalScale = -1.0;
  std::string gridFormat;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto need = [&](int n) { return i + n < argc; };
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
    else if ((a == "--inline-byte" || a == "--crossline-byte" || a == "--x-byte" ||
               a == "--y-byte" || a == "--scalar-byte") &&
             need(1))
    {
      int& byte = a == "--inline-byte"      ? inlineByte
                  : a == "--crossline-byte" ? crosslineByte
                  : a == "--x-byte"         ? xByte
                  : a == "--y-byte"         ? yByte
                                            : scalarByte;
      if (!ParseInt(argv[++i], byte) || byte < 1 || byte > 237)
        return Die(a + " needs a trace-header byte position in [1, 237]");
    }
    else if (a == "--grid-format" && need(1))
    {
      gridFormat = argv[++i];
      if (!NewTextGridReader("", gridFormat))
        return Die("--grid-format needs irap-ascii, zmap, esri, matrix or columns");
    }
    else if (a == "--placement" && need(1))
    {
      const std::string p = argv[++i];
      if (p != "auto" && p != "world" && p != "lines")
        return Die("--placement needs auto, world or lines");
      placement = p == "world"   ? vtkSegyVolumeReader::Placements::World
                  : p == "lines" ? vtkSegyVolumeReader::Placements::LineNumbers
                                 : vtkSegyVolumeReader::Placements::Automatic;
    }
    else if (a == "--vertical-scale" && need(1))
    {
      if (!ParseDouble(argv[++i], verticalScale) || verticalScale == 0.0)
        return Die("--vertical-scale needs a number other than 0");
    }
    else if (a == "--segy-format" && need(1))
    {
      if (!ParseInt(argv[++i], segyFormat) || segyFormat < 1)
        return Die("--segy-format needs a format code (1, 2, 3, 5 or 8)");
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

  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(input));
  vtkSmartPointer<vtkAlgorithm> reader;
  if (raw.Enabled)
  {
    // Checked before the pipeline reads past the end of a too-short file.
    const std::string sizeError = raw.CheckFileSize(input);
    if (!sizeError.empty())
      return Die(sizeError);
    reader = NewRawReader(input, raw);
  }
  else if (!gridFormat.empty())
  {
    reader = NewTextGridReader(input, gridFormat);
  }
  else if (ext == ".sgy" || ext == ".segy")
  {
    auto r = vtkSmartPointer<vtkSegyVolumeReader>::New();
    r->SetFileName(input.c_str());
    r->SetInlineByte(inlineByte);
    r->SetCrosslineByte(crosslineByte);
    r->SetSampleFormat(segyFormat);
    r->SetXByte(xByte);
    r->SetYByte(yByte);
    r->SetCoordinateScalarByte(scalarByte);
    r->SetPlacement(placement);
    r->SetVerticalScale(verticalScale);
    reader = r;
  }
  else if ((ext == ".mhd" || ext == ".mha") &&
           vtkStreamingMetaImageReader::IsStreamable(input.c_str()))
  {
    auto r = vtkSmartPointer<vtkStreamingMetaImageReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".npy")
  {
    auto r = vtkSmartPointer<vtkNumpyGridReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else if (ext == ".gri" && !vtkAsciiGridReader::CanReadFile(input.c_str()))
  {
    auto r = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
    r->SetFileName(input.c_str());
    reader = r;
  }
  else
  {
    reader = NewGridOrVolumeReader(input, ext);
  }
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

  RemoveStaleTemporaries(output);
  vtkNew<vtkImageToPagePoolWriter> writer;
  if (reader->IsA("vtkMetaImageReader"))
  {
    // Compressed or multi-file MetaImage data: VTK's reader cannot read a sub-extent (it would
    // overrun a slab's buffer), so the volume is read whole.
    std::cerr << "strata-convert: compressed or multi-file MetaImage data, read whole\n";
    reader->Update();
    writer->SetInputData(reader->GetOutputDataObject(0));
  }
  else
  {
    writer->SetInputConnection(reader->GetOutputPort());
  }
  writer->SetFileName(output.c_str());
  writer->SetPageSize(pageSize);
  writer->SetCompression(compress);
  writer->SetMemoryLimit(memoryMB);
  strata_cli::ProgressBar bar;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetCallback(&strata_cli::ProgressBar::Callback);
  onProgress->SetClientData(&bar);
  writer->AddObserver(vtkCommand::ProgressEvent, onProgress);

  const auto start = std::chrono::steady_clock::now();
  const bool ok = writer->Write();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bar.Finish();
  if (!ok)
  {
    return Die("conversion of \"" + input + "\" failed; no output written");
  }
  if (auto* segy = vtkSegyVolumeReader::SafeDownCast(reader))
  {
    if (segy->GetGeoreferenced())
    {
      const double* s = segy->GetOutputInformation(0)->Get(vtkDataObject::SPACING());
      std::printf("SEG-Y placed by its trace coordinates: crosslines at %.6g degrees, bins %.6g "
                  "x %.6g, largest trace residual %.3g\n",
        segy->GetGridRotation(),
        s[0],
        s[2],
        segy->GetFitResidual());
    }
    else
    {
      std::printf("SEG-Y placed by its line numbers (world = inline, crossline, time)\n");
    }
  }
  std::printf("%s: %lld bytes, %lld pages (%s), %.2f s\n",
    output.c_str(),
    static_cast<long long>(writer->GetFileSize()),
    static_cast<long long>(writer->GetNumberOfPages()),
    compress ? "zstd" : "raw",
    seconds);
  // A volume of several components is a set of pools, one per component.
  strata::PagePoolFile written;
  const int components = written.Open(output) ? written.GetHeader().Components : 1;
  for (int c = 1; c < components; ++c)
    std::printf("  component %d of %d: %s\n",
      c,
      components,
      strata::PagePoolFormat::GetComponentFileName(output, c).c_str());
  return 0;
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// strata-synth: writes a synthetic post-stack SEG-Y survey from a horizon stack
// (vtkSyntheticSurveyWriter): reflections at the horizons, a Ricker wavelet, seeded noise, trace
// coordinates in the horizons' map projection. Without --origin/--rotation/--bins/--lines the
// survey is the first horizon's grid (every --step-th node); without --samples/--start the time
// range covers every horizon with 100 ms to spare. strata-convert pages the result.
#include "StrataCommandLine.h"
#include "vtkAsciiGridReader.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkHorizonColumnReader.h"
#include "vtkImageData.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkNumpyGridReader.h"
#include "vtkPointData.h"
#include "vtkSyntheticSurveyWriter.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace
{
using strata_cli::ParseDouble;
using strata_cli::ParseInt;

void Usage(std::ostream& os)
{
  os << "usage: strata-synth <horizon>... -o <output.sgy>\n"
        "         [--origin X Y] [--rotation DEG] [--bins INLINE XLINE] [--lines NIL NXL]\n"
        "         [--step N] [--samples N] [--interval MS] [--start MS]\n"
        "         [--frequency HZ] [--noise STD] [--seed N] [--impedances Z0,Z1,...]\n"
        "horizons (top to bottom): .gri (Irap binary), .npy, Irap classic ASCII, ZMAP+, ESRI\n"
        "        ASCII, columns; values are two-way times in ms (or depths), growing downwards\n"
        "survey: the first horizon's grid, every --step-th node (default 1), unless --origin,\n"
        "        --rotation (azimuth of the crosslines, degrees counterclockwise from east),\n"
        "        --bins and --lines give it; samples every --interval ms (default 4) covering\n"
        "        the horizons with 100 ms to spare unless --samples/--start give them\n"
        "wavelet: Ricker of peak --frequency (default 25 Hz); --noise: standard deviation in\n"
        "        reflection coefficient units (default 0.002); layer impedances default\n"
        "        4e6 + 1e6 k\n";
}

int Die(const std::string& message)
{
  std::cerr << "strata-synth: " << message << "\n";
  return 1;
}

vtkSmartPointer<vtkAlgorithm> NewHorizonReader(const std::string& path)
{
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  if (ext == ".npy")
  {
    auto r = vtkSmartPointer<vtkNumpyGridReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (vtkAsciiGridReader::CanReadFile(path.c_str()))
  {
    auto r = vtkSmartPointer<vtkAsciiGridReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == ".gri")
  {
    auto r = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  auto r = vtkSmartPointer<vtkHorizonColumnReader>::New();
  r->SetFileName(path.c_str());
  return r;
}

struct Options
{
  std::vector<std::string> Horizons;
  std::string Output;
  bool Geometry = false; ///< any of --origin, --rotation, --bins, --lines
  double Origin[2] = { 0, 0 };
  double Rotation = 0.0;
  double Bins[2] = { 25.0, 25.0 };
  int Lines[2] = { 0, 0 };
  int Step = 1;
  int Samples = 0;
  double Interval = 4.0;
  int Start = -1;
  double Frequency = 25.0;
  double Noise = 0.002;
  int Seed = 1;
  std::vector<double> Impedances;

  /// Parses argv; an error message, or empty.
  std::string Parse(int argc, char* argv[]);
};

std::string Options::Parse(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto need = [&](int n) { return i + n < argc; };
    auto twoDoubles = [&](double v[2])
    { return need(2) && ParseDouble(argv[++i], v[0]) && ParseDouble(argv[++i], v[1]); };
    if (a == "-o" && need(1))
      this->Output = argv[++i];
    else if (a == "--origin")
    {
      if (!twoDoubles(this->Origin))
        return "--origin needs two numbers";
      this->Geometry = true;
    }
    else if (a == "--rotation")
    {
      if (!need(1) || !ParseDouble(argv[++i], this->Rotation))
        return "--rotation needs degrees";
      this->Geometry = true;
    }
    else if (a == "--bins")
    {
      if (!twoDoubles(this->Bins) || !(this->Bins[0] > 0) || !(this->Bins[1] > 0))
        return "--bins needs two positive sizes";
      this->Geometry = true;
    }
    else if (a == "--lines")
    {
      if (!need(2) || !ParseInt(argv[++i], this->Lines[0]) ||
          !ParseInt(argv[++i], this->Lines[1]) || this->Lines[0] < 1 || this->Lines[1] < 1)
        return "--lines needs two positive counts";
      this->Geometry = true;
    }
    else if (a == "--step")
    {
      if (!need(1) || !ParseInt(argv[++i], this->Step) || this->Step < 1)
        return "--step needs a positive integer";
    }
    else if (a == "--samples")
    {
      if (!need(1) || !ParseInt(argv[++i], this->Samples) || this->Samples < 1)
        return "--samples needs a positive integer";
    }
    else if (a == "--interval")
    {
      if (!need(1) || !ParseDouble(argv[++i], this->Interval) || !(this->Interval > 0))
        return "--interval needs a positive number of ms";
    }
    else if (a == "--start")
    {
      if (!need(1) || !ParseInt(argv[++i], this->Start) || this->Start < 0)
        return "--start needs a whole number of ms >= 0";
    }
    else if (a == "--frequency")
    {
      if (!need(1) || !ParseDouble(argv[++i], this->Frequency) || !(this->Frequency > 0))
        return "--frequency needs a positive number of Hz";
    }
    else if (a == "--noise")
    {
      if (!need(1) || !ParseDouble(argv[++i], this->Noise) || !(this->Noise >= 0))
        return "--noise needs a number >= 0";
    }
    else if (a == "--seed")
    {
      if (!need(1) || !ParseInt(argv[++i], this->Seed) || this->Seed < 0)
        return "--seed needs an integer >= 0";
    }
    else if (a == "--impedances" && need(1))
    {
      std::stringstream list(argv[++i]);
      std::string item;
      double z = 0;
      while (std::getline(list, item, ','))
      {
        if (!ParseDouble(item.c_str(), z) || !(z > 0))
          return "--impedances needs positive numbers separated by commas";
        this->Impedances.push_back(z);
      }
    }
    else if (!a.empty() && a[0] == '-')
      return "unknown option " + a;
    else
      this->Horizons.push_back(a);
  }
  if (this->Horizons.empty() || this->Output.empty())
    return "needs at least one horizon and -o <output.sgy>";
  return std::string();
}

/// The survey of the first horizon's grid, every `step`-th node: origin, rotation, bins, lines.
std::string GeometryFromHorizon(vtkImageData* h, Options& o)
{
  const double* d = h->GetDirectionMatrix()->GetData();
  if (d[0] * d[4] - d[1] * d[3] < 0)
    return "the first horizon's grid is mirrored; give --origin, --rotation, --bins, --lines";
  int dims[3];
  h->GetDimensions(dims);
  o.Origin[0] = h->GetOrigin()[0];
  o.Origin[1] = h->GetOrigin()[1];
  o.Rotation = std::atan2(d[3], d[0]) * 180.0 / 3.14159265358979323846;
  o.Bins[0] = h->GetSpacing()[1] * o.Step;
  o.Bins[1] = h->GetSpacing()[0] * o.Step;
  o.Lines[0] = (dims[1] - 1) / o.Step + 1;
  o.Lines[1] = (dims[0] - 1) / o.Step + 1;
  return std::string();
}
}

int main(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help")
    {
      Usage(std::cout);
      return 0;
    }
  }
  const std::string error = o.Parse(argc, argv);
  if (!error.empty())
  {
    Usage(std::cerr);
    return Die(error);
  }
  strata_cli::PlainOutputWindow::Install();
  vtkNew<vtkSyntheticSurveyWriter> writer;
  double lo = 1e300, hi = -1e300;
  for (size_t h = 0; h < o.Horizons.size(); ++h)
  {
    vtkSmartPointer<vtkAlgorithm> reader = NewHorizonReader(o.Horizons[h]);
    reader->Update();
    auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    vtkDataArray* values = image ? image->GetPointData()->GetScalars() : nullptr;
    if (!values)
      return Die("cannot read the horizon \"" + o.Horizons[h] + "\"; nothing written");
    for (vtkIdType n = 0; n < values->GetNumberOfTuples(); ++n)
    {
      const double v = values->GetComponent(n, 0);
      if (std::isfinite(v) && std::abs(v) < 1e30)
      {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    if (h == 0 && !o.Geometry)
    {
      const std::string geometryError = GeometryFromHorizon(image, o);
      if (!geometryError.empty())
        return Die(geometryError);
    }
    writer->AddInputConnection(0, reader->GetOutputPort());
  }
  if (!(lo <= hi))
    return Die("the horizons hold no values");
  if (o.Start < 0)
    o.Start = static_cast<int>(std::max(0.0, std::floor((lo - 100.0) / o.Interval) * o.Interval));
  if (o.Samples == 0)
    o.Samples = static_cast<int>(std::ceil((hi + 100.0 - o.Start) / o.Interval)) + 1;
  writer->SetOrigin(o.Origin);
  writer->SetRotation(o.Rotation);
  writer->SetBins(o.Bins);
  writer->SetLines(o.Lines);
  writer->SetSamples(o.Samples, o.Interval, o.Start);
  writer->SetPeakFrequency(o.Frequency);
  writer->SetNoiseLevel(o.Noise);
  writer->SetSeed(static_cast<unsigned>(o.Seed));
  for (size_t k = 0; k < o.Impedances.size(); ++k)
    writer->SetImpedance(static_cast<int>(k), o.Impedances[k]);
  writer->SetFileName(o.Output.c_str());
  strata_cli::ProgressBar bar;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetCallback(&strata_cli::ProgressBar::Callback);
  onProgress->SetClientData(&bar);
  writer->AddObserver(vtkCommand::ProgressEvent, onProgress);
  const bool ok = writer->Write();
  bar.Finish();
  if (!ok)
    return Die("no survey written");
  std::printf("%s: %d inlines x %d crosslines x %d samples (%g ms from %d ms), origin %.2f %.2f, "
              "rotation %g degrees, bins %g x %g\n",
    o.Output.c_str(),
    o.Lines[0],
    o.Lines[1],
    o.Samples,
    o.Interval,
    o.Start,
    o.Origin[0],
    o.Origin[1],
    o.Rotation,
    o.Bins[0],
    o.Bins[1]);
  return 0;
}

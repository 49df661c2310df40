// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkHybridVolumeFilter, vtkHybridVolumeReader and strata-hybrid on a generated 33 x 20 x 17
// uint16 volume (dimensions not divisible by the factor, a planted spike, non-unit spacing and
// a non-zero origin):
// - the filter's outputs equal strata::HybridVolumeBuilder's result exactly (low-resolution values,
//   geometry, point count, world positions, values, errors, normals), also for an extent that
//   does not start at 0 and for a two-component float input (its first component);
// - progress events are non-decreasing and end at 1;
// - the file written through FileName reads back bit-exact through vtkHybridVolumeReader,
//   whose information pass reports output 0's extent, spacing and origin;
// - a constant volume gives no points;
// - errors (bad factor, unwritable file, missing, truncated and corrupt files) are reported
//   (counted by an observer) and leave empty outputs;
// - strata-hybrid on a raw file (streamed) and on a .vti file exits 0 and writes the same
//   representation.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "StrataHybridVolumeBuilder.h"
#include "StrataHybridVolumeFile.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeReader.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedShortArray.h"
#include "vtkXMLImageDataWriter.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

constexpr int Dims[3] = { 33, 20, 17 };
constexpr double Spacing[3] = { 0.5, 1.0, 2.0 };
constexpr double Origin[3] = { 100.0, -20.0, 5.0 };

/// Smooth field plus a spike at (11, 7, 5), as uint16.
std::vector<uint16_t> MakeValues()
{
  std::vector<uint16_t> v;
  for (int z = 0; z < Dims[2]; ++z)
    for (int y = 0; y < Dims[1]; ++y)
      for (int x = 0; x < Dims[0]; ++x)
      {
        v.push_back(
          static_cast<uint16_t>(1000 + 300 * std::sin(0.4 * x) * std::cos(0.3 * y) + 20 * z));
      }
  v[(static_cast<size_t>(5) * Dims[1] + 7) * Dims[0] + 11] = 60000;
  return v;
}

vtkSmartPointer<vtkImageData> MakeImage(const std::vector<uint16_t>& values)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Dims[0], Dims[1], Dims[2]);
  image->SetSpacing(Spacing[0], Spacing[1], Spacing[2]);
  image->SetOrigin(Origin[0], Origin[1], Origin[2]);
  image->AllocateScalars(VTK_UNSIGNED_SHORT, 1);
  auto* p = static_cast<uint16_t*>(image->GetScalarPointer());
  std::copy(values.begin(), values.end(), p);
  return image;
}

/// The settings every run here uses; the 0.02 MB limit holds 7 of the 2640-byte slices.
void Configure(vtkHybridVolumeFilter* filter)
{
  filter->SetFactor(2, 2, 2);
  filter->SetFilterToCubic();
  filter->SetThreshold(20.0);
  filter->SetMemoryLimit(0.02);
}

void RecordProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData));
}

bool SameBytes(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetDataType() != b->GetDataType() ||
      a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
      a->GetNumberOfTuples() != b->GetNumberOfTuples())
  {
    return false;
  }
  const size_t bytes = static_cast<size_t>(a->GetNumberOfValues()) * a->GetDataTypeSize();
  return bytes == 0 || std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0), bytes) == 0;
}

/// Bit-exact equality of two algorithms' outputs: geometry, every array, the vertex cells.
bool SameOutputs(vtkHybridVolumeAlgorithm* a, vtkHybridVolumeAlgorithm* b)
{
  vtkImageData* la = a->GetLowResolutionOutput();
  vtkImageData* lb = b->GetLowResolutionOutput();
  bool same = SameBytes(la->GetPointData()->GetScalars(), lb->GetPointData()->GetScalars());
  for (int i = 0; i < 3; ++i)
  {
    same = same && la->GetDimensions()[i] == lb->GetDimensions()[i] &&
           la->GetSpacing()[i] == lb->GetSpacing()[i] && la->GetOrigin()[i] == lb->GetOrigin()[i];
  }
  vtkPolyData* pa = a->GetPointsOutput();
  vtkPolyData* pb = b->GetPointsOutput();
  same = same && pa->GetNumberOfPoints() == pb->GetNumberOfPoints() &&
         pa->GetNumberOfVerts() == pb->GetNumberOfVerts();
  if (same && pa->GetNumberOfPoints() > 0)
  {
    same = SameBytes(pa->GetPoints()->GetData(), pb->GetPoints()->GetData());
  }
  for (const char* name : { "Value", "Error", "Normals", "NormalCode" })
  {
    same =
      same && SameBytes(pa->GetPointData()->GetArray(name), pb->GetPointData()->GetArray(name));
  }
  return same;
}

/// Both outputs empty (after a failure).
bool Empty(vtkHybridVolumeAlgorithm* algorithm)
{
  return algorithm->GetLowResolutionOutput()->GetNumberOfPoints() == 0 &&
         algorithm->GetPointsOutput()->GetNumberOfPoints() == 0;
}

/// The filter's outputs against the builder's result, value by value.
bool MatchesBuilder(vtkHybridVolumeFilter* filter, const strata::HybridVolumeFile& ref)
{
  vtkImageData* low = filter->GetLowResolutionOutput();
  vtkDataArray* lowValues = low->GetPointData()->GetScalars();
  bool same = lowValues && lowValues->GetDataType() == VTK_FLOAT &&
              std::string(lowValues->GetName()) == "LowResolution" &&
              lowValues->GetNumberOfTuples() == static_cast<vtkIdType>(ref.LowResolution.size()) &&
              std::memcmp(lowValues->GetVoidPointer(0),
                ref.LowResolution.data(),
                ref.LowResolution.size() * sizeof(float)) == 0;
  for (int a = 0; a < 3; ++a)
  {
    same = same && low->GetDimensions()[a] == ref.LowDimensions[a] &&
           low->GetSpacing()[a] == ref.Factor[a] * Spacing[a] && low->GetOrigin()[a] == Origin[a];
  }
  vtkPolyData* points = filter->GetPointsOutput();
  const vtkIdType n = points->GetNumberOfPoints();
  same = same && n == static_cast<vtkIdType>(ref.Points.size()) &&
         points->GetNumberOfVerts() == n && points->GetPoints()->GetDataType() == VTK_DOUBLE;
  vtkPointData* pd = points->GetPointData();
  auto* value = vtkFloatArray::SafeDownCast(pd->GetArray("Value"));
  auto* error = vtkFloatArray::SafeDownCast(pd->GetArray("Error"));
  auto* normals = vtkFloatArray::SafeDownCast(pd->GetNormals());
  auto* codes = vtkUnsignedShortArray::SafeDownCast(pd->GetArray("NormalCode"));
  same = same && value && error && normals && codes && pd->GetScalars() == value;
  for (vtkIdType i = 0; same && i < n; ++i)
  {
    const strata::HybridVolumeFile::Point& p = ref.Points[static_cast<size_t>(i)];
    double x[3], normal[3];
    points->GetPoint(i, x);
    strata::HybridVolumeFile::DecodeNormal(p.Normal, normal);
    for (int a = 0; a < 3; ++a)
    {
      same = same && x[a] == Origin[a] + p.Position[a] * Spacing[a] &&
             normals->GetComponent(i, a) == static_cast<float>(normal[a]);
    }
    same = same && value->GetValue(i) == p.Value && error->GetValue(i) == p.Error &&
           codes->GetValue(i) == p.Normal;
  }
  return same;
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary).write(bytes.data(), bytes.size());
}

/// strata-hybrid: $STRATA_HYBRID_TOOL, else beside this test's executable (both go to the
/// build tree's bin folder); empty when not built.
std::string FindTool()
{
  const char* env = std::getenv("STRATA_HYBRID_TOOL");
  std::string tool =
    env ? env
        : vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::GetRealPath("/proc/self/exe")) +
            "/strata-hybrid";
  return vtksys::SystemTools::FileExists(tool, true) ? tool : std::string();
}

int Run(const std::string& command)
{
  std::cout << "  $ " << command << std::endl;
  return std::system(command.c_str());
}

bool SameFile(const strata::HybridVolumeFile& a, const strata::HybridVolumeFile& b)
{
  return a.LowResolution == b.LowResolution && a.Points.size() == b.Points.size() &&
         std::memcmp(a.Points.data(),
           b.Points.data(),
           a.Points.size() * sizeof(strata::HybridVolumeFile::Point)) == 0;
}
}

namespace
{
/// What the parts share: the input, the builder's reference, the filter (which writes Shv) with
/// its error counter and progress, and a reader with its error counter.
struct FilterFixture
{
  std::string Dir;
  std::vector<uint16_t> Values;
  vtkSmartPointer<vtkImageData> Image;
  strata::HybridVolumeFile Ref;
  std::string Shv;
  vtkNew<vtkHybridVolumeFilter> Filter;
  vtkNew<ErrorCounter> FilterErrors;
  std::vector<double> Progress;
  vtkNew<vtkCallbackCommand> OnProgress;
  vtkNew<vtkHybridVolumeReader> Reader;
  vtkNew<ErrorCounter> ReaderErrors;
};

/// The reference: the builder fed from the same values.
void BuilderReference(FilterFixture& fx)
{
  const std::vector<uint16_t>& values = fx.Values;
  strata::HybridVolumeFile& ref = fx.Ref;
  // The reference: the builder fed from the same values.
  {
    vtkNew<vtkHybridVolumeFilter> settings;
    Configure(settings);
    strata::HybridVolumeBuilder builder;
    settings->ConfigureBuilder(builder);
    const std::vector<float> floats(values.begin(), values.end());
    builder.SetInput(Dims,
      Spacing,
      Origin,
      [&](int first, int count, float* out)
      {
        const size_t slice = static_cast<size_t>(Dims[0]) * Dims[1];
        std::copy(floats.begin() + first * slice, floats.begin() + (first + count) * slice, out);
        return true;
      });
    Check(builder.Build(ref) && !ref.Points.empty(), "the builder's reference has points");
  }
}

void FilterAgainstBuilder(FilterFixture& fx)
{
  const std::string& dir = fx.Dir;
  vtkImageData* image = fx.Image;
  strata::HybridVolumeFile& ref = fx.Ref;
  vtkHybridVolumeFilter* filter = fx.Filter;
  ErrorCounter* filterErrors = fx.FilterErrors;
  std::vector<double>& progress = fx.Progress;
  vtkCallbackCommand* onProgress = fx.OnProgress;
  std::cout << "Filter against the builder (" << ref.Points.size() << " points, low resolution "
            << ref.LowDimensions[0] << "x" << ref.LowDimensions[1] << "x" << ref.LowDimensions[2]
            << ")\n";
  fx.Shv = dir + "/TestHybridVolumeFilter.shv";
  const std::string& shv = fx.Shv;
  filterErrors->Watch(filter);
  onProgress->SetCallback(RecordProgress);
  onProgress->SetClientData(&progress);
  filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
  filter->SetInputData(image);
  Configure(filter);
  filter->SetFileName(shv.c_str());
  filter->Update();
  Check(filterErrors->Errors == 0 && filterErrors->Warnings == 0,
    "filter runs without errors or warnings: " + filterErrors->First);
  Check(MatchesBuilder(filter, ref), "filter outputs equal the builder's result exactly");
  Check(ref.LowDimensions[0] == 17 && ref.LowDimensions[1] == 11 && ref.LowDimensions[2] == 9,
    "low-resolution dimensions 17x11x9 for 33x20x17, factor 2");
  bool spike = false;
  for (const auto& p : ref.Points)
  {
    spike = spike || (p.Position[0] == 11 && p.Position[1] == 7 && p.Position[2] == 5);
  }
  Check(spike, "the spike at (11, 7, 5) is a point");
  bool monotonic = progress.size() > 2;
  for (size_t i = 1; i < progress.size(); ++i)
  {
    monotonic = monotonic && progress[i] >= progress[i - 1];
  }
  Check(monotonic && !progress.empty() && progress.back() == 1.0,
    "progress: " + std::to_string(progress.size()) + " events, non-decreasing, ending at 1");
}

void ExtentAndComponents(FilterFixture& fx)
{
  const std::vector<uint16_t>& values = fx.Values;
  vtkImageData* image = fx.Image;
  vtkHybridVolumeFilter* filter = fx.Filter;
  std::cout << "Extent not starting at 0, and a two-component float input\n";
  {
    // Same world positions: origin - start * spacing.
    vtkNew<vtkImageData> shifted;
    shifted->ShallowCopy(image);
    shifted->SetExtent(4, 4 + Dims[0] - 1, -3, -3 + Dims[1] - 1, 2, 2 + Dims[2] - 1);
    shifted->SetOrigin(
      Origin[0] - 4 * Spacing[0], Origin[1] + 3 * Spacing[1], Origin[2] - 2 * Spacing[2]);
    vtkNew<vtkHybridVolumeFilter> other;
    Configure(other);
    other->SetInputData(shifted);
    other->Update();
    Check(SameOutputs(filter, other), "extent (4, -3, 2): the same outputs");

    vtkNew<vtkImageData> pairs;
    pairs->CopyStructure(image);
    vtkNew<vtkFloatArray> two;
    two->SetName("pairs");
    two->SetNumberOfComponents(2);
    two->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    for (vtkIdType i = 0; i < two->GetNumberOfTuples(); ++i)
    {
      two->SetTypedComponent(i, 0, values[static_cast<size_t>(i)]);
      two->SetTypedComponent(i, 1, -7.0f * i);
    }
    pairs->GetPointData()->SetScalars(two);
    vtkNew<vtkHybridVolumeFilter> first;
    vtkNew<ErrorCounter> warnings;
    warnings->Watch(first);
    Configure(first);
    first->SetInputData(pairs);
    first->Update();
    Check(SameOutputs(filter, first) && warnings->Warnings == 1 && warnings->Errors == 0,
      "two components: the first one's outputs, one warning: " + warnings->First);
  }
}

void Reader(FilterFixture& fx)
{
  const std::string& shv = fx.Shv;
  vtkHybridVolumeFilter* filter = fx.Filter;
  vtkHybridVolumeReader* reader = fx.Reader;
  ErrorCounter* readerErrors = fx.ReaderErrors;
  std::cout << "Reader: information, then a bit-exact round trip\n";
  readerErrors->Watch(reader);
  reader->SetFileName(shv.c_str());
  reader->UpdateInformation();
  {
    vtkInformation* info = reader->GetOutputInformation(0);
    int whole[6] = { 0, -1, 0, -1, 0, -1 };
    double spacing[3] = { 0, 0, 0 }, origin[3] = { 0, 0, 0 };
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    info->Get(vtkDataObject::SPACING(), spacing);
    info->Get(vtkDataObject::ORIGIN(), origin);
    Check(whole[1] == 16 && whole[3] == 10 && whole[5] == 8 && spacing[0] == 1.0 &&
            spacing[1] == 2.0 && spacing[2] == 4.0 && origin[0] == 100.0 && origin[1] == -20.0 &&
            origin[2] == 5.0,
      "information: extent [0,16]x[0,10]x[0,8], spacing 1 2 4, origin 100 -20 5");
  }
  reader->Update();
  Check(readerErrors->Errors == 0 && SameOutputs(filter, reader),
    "read back bit-exact: " + std::to_string(reader->GetPointsOutput()->GetNumberOfPoints()) +
      " points");
  // A second execution without new information reads the file again.
  reader->GetLowResolutionOutput()->ReleaseData();
  reader->GetPointsOutput()->ReleaseData();
  reader->Update();
  Check(readerErrors->Errors == 0 && SameOutputs(filter, reader), "re-execution reads again");
}

void ConstantVolume(FilterFixture& fx)
{
  const std::vector<uint16_t>& values = fx.Values;
  std::cout << "Constant volume: no points\n";
  {
    vtkNew<vtkImageData> constant;
    constant->SetDimensions(10, 9, 7);
    constant->AllocateScalars(VTK_FLOAT, 1);
    constant->GetPointData()->GetScalars()->Fill(42.0);
    vtkNew<vtkHybridVolumeFilter> c;
    Configure(c);
    c->SetThreshold(0.0);
    c->SetFilterToOptimized();
    c->SetInputData(constant);
    c->Update();
    vtkDataArray* low = c->GetLowResolutionOutput()->GetPointData()->GetScalars();
    Check(c->GetPointsOutput()->GetNumberOfPoints() == 0 &&
            c->GetPointsOutput()->GetNumberOfVerts() == 0 && low &&
            low->GetNumberOfTuples() == 6 * 5 * 4 && low->GetRange()[0] == 42.0 &&
            low->GetRange()[1] == 42.0,
      "10x9x7 constant 42: 0 points, 6x5x4 low-resolution values of 42");
  }
}

void Errors(FilterFixture& fx)
{
  const std::string& dir = fx.Dir;
  strata::HybridVolumeFile& ref = fx.Ref;
  const std::string& shv = fx.Shv;
  vtkHybridVolumeFilter* filter = fx.Filter;
  ErrorCounter* filterErrors = fx.FilterErrors;
  vtkHybridVolumeReader* reader = fx.Reader;
  ErrorCounter* readerErrors = fx.ReaderErrors;
  std::cout << "Errors leave empty outputs\n";
  {
    filterErrors->Reset();
    filter->SetFactor(3, 3, 3);
    filter->Update();
    Check(filterErrors->Errors > 0 && Empty(filter), "factor 3: " + filterErrors->First);
    filterErrors->Reset();
    filter->SetFactor(2, 2, 2);
    filter->SetFileName((dir + "/no-such-folder/out.shv").c_str());
    filter->Update();
    Check(filterErrors->Errors > 0 && Empty(filter), "unwritable file: " + filterErrors->First);
    filterErrors->Reset();
    filter->SetFileName(nullptr);
    filter->Update();
    Check(filterErrors->Errors == 0 && MatchesBuilder(filter, ref), "the filter recovers");

    const std::string bytes = Slurp(shv);
    const std::string bad = dir + "/TestHybridVolumeFilter-bad.shv";
    auto rejects = [&](const std::string& path, const std::string& what)
    {
      vtkNew<vtkHybridVolumeReader> r;
      vtkNew<ErrorCounter> errors;
      errors->Watch(r);
      r->SetFileName(path.c_str());
      r->Update();
      Check(errors->Errors > 0 && Empty(r), what + ": " + errors->First);
      std::cout << "  " << what << ": " << errors->First << "\n";
    };
    Spit(bad, bytes.substr(0, bytes.size() - 5));
    rejects(bad, "truncated file");
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x04;
    Spit(bad, flipped);
    rejects(bad, "corrupt byte");
    rejects(dir + "/TestHybridVolumeFilter-missing.shv", "missing file");

    // A reader that failed recovers once the file is good again.
    readerErrors->Reset();
    reader->SetFileName(bad.c_str());
    reader->Update();
    const bool failed = readerErrors->Errors > 0 && Empty(reader);
    reader->SetFileName(shv.c_str());
    reader->Update();
    Check(failed && SameOutputs(filter, reader), "a reader recovers after a bad file");
    std::remove(bad.c_str());
  }
}

void StrataHybridTool(FilterFixture& fx)
{
  const std::string& dir = fx.Dir;
  const std::vector<uint16_t>& values = fx.Values;
  vtkImageData* image = fx.Image;
  strata::HybridVolumeFile& ref = fx.Ref;
  vtkHybridVolumeFilter* filter = fx.Filter;
  vtkHybridVolumeReader* reader = fx.Reader;
  std::cout << "strata-hybrid\n";
  const std::string tool = FindTool();
  if (tool.empty())
  {
    std::cout << "  skipped: strata-hybrid not built (STRATA_BUILD_EXAMPLES off)\n";
  }
  else
  {
    // Raw, little-endian uint16, streamed by the tool.
    const std::string raw = dir + "/TestHybridVolumeFilter.raw";
    std::string bytes;
    for (uint16_t v : values)
    {
      bytes.push_back(static_cast<char>(v & 0xFF));
      bytes.push_back(static_cast<char>(v >> 8));
    }
    Spit(raw, bytes);
    const std::string fromRaw = dir + "/TestHybridVolumeFilter-raw.shv";
    const std::string options = " --factor 2 --filter cubic --threshold 20 --memory-limit 0.02";
    const int rc = Run("\"" + tool + "\" \"" + raw + "\" \"" + fromRaw +
                       "\" --raw 33 20 17 uint16 --spacing 0.5 1 2 --little" + options);
    strata::HybridVolumeFile back;
    const bool read = back.Read(fromRaw);
    Check(rc == 0 && read && SameFile(back, ref) && back.Origin[0] == 0.0,
      "raw input: exit 0, the builder's low-resolution volume and points, origin 0");

    // .vti, read whole, through the filter: the origin comes from the file.
    const std::string vti = dir + "/TestHybridVolumeFilter.vti";
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(vti.c_str());
    writer->Write();
    const std::string fromVti = dir + "/TestHybridVolumeFilter-vti.shv";
    const int rcVti = Run("\"" + tool + "\" \"" + vti + "\" \"" + fromVti + "\"" + options);
    reader->SetFileName(fromVti.c_str());
    reader->Update();
    Check(rcVti == 0 && SameOutputs(filter, reader), ".vti input: exit 0, the filter's outputs");

    const int rcShort =
      Run("\"" + tool + "\" \"" + raw + "\" \"" + fromRaw + "\" --raw 33 20 18 uint16");
    Check(rcShort != 0, "a raw file shorter than its dimensions: non-zero exit");
    for (const std::string& path : { raw, fromRaw, vti, fromVti })
    {
      std::remove(path.c_str());
    }
  }
}

}

int TestHybridVolumeFilter(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  FilterFixture fx;
  fx.Dir = paths.Output;
  fx.Values = MakeValues();
  fx.Image = MakeImage(fx.Values);
  strata_test::RunSubTests(
    {
      { "BuilderReference", [&] { BuilderReference(fx); } },
      { "FilterAgainstBuilder", [&] { FilterAgainstBuilder(fx); } },
      { "ExtentAndComponents", [&] { ExtentAndComponents(fx); } },
      { "Reader", [&] { Reader(fx); } },
      { "ConstantVolume", [&] { ConstantVolume(fx); } },
      { "Errors", [&] { Errors(fx); } },
      { "StrataHybridTool", [&] { StrataHybridTool(fx); } },
    },
    strata_test::Failures);
  std::remove(fx.Shv.c_str());

  const int failures = strata_test::Failures();
  std::cout << (failures ? "FAILED: " + std::to_string(failures) + " checks\n" : "all passed\n");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}

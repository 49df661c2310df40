// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The converters to page pools (vtkImageToPagePoolWriter behind each reader, and strata-convert)
// on every input kind, each pool read back at its finest level with vtkPagePoolReader and
// compared value by value with the source, bit for bit (the source value stored in the pool's
// type: float for double, int32 and SEG-Y inputs; NaN stays NaN):
// - raw float 128^3 (8 MB) through vtkImageReader2 with a 2 MB memory limit: converted in slabs
//   no larger than the limit;
// - .vti (float with NaN); .mhd and .mha (int16) through vtkStreamingMetaImageReader, in slabs,
//   and a compressed .mhd (which only VTK's reader reads, whole); Testing/Data's tooth.nrrd;
// - SEG-Y: Testing/Data's f3.sgy with a memory limit of a few inlines (the reader is asked for a
//   few inlines at a time and reads only their traces), a generated shuffled IEEE file 4.9 times
//   the memory limit, and a generated file with shuffled traces, one missing, IBM floats and
//   line numbers at bytes 17 and 234;
// - the real horizons of Testing/Data/horizons: Reek .gri, Penobscot .npy (float64), Top Heimdal
//   columns, as tile pools (and the whole Penobscot horizon of ../shared/data when present);
// - strata-convert on the SEG-Y files (default and custom byte positions) and on the raw and
//   compressed .mhd gives the same pools;
// - the text grids (Irap classic ASCII, ZMAP+, ESRI ASCII, a whitespace matrix), 12 x 9 with a
//   hole each, through the writer and through strata-convert (format told by content); a
//   4 x 5 matrix refused as columns and converted with --grid-format matrix;
// - strata-convert on a .vti whose WholeExtent is larger than its pieces fails with a message,
//   leaving no output (issue 14, defect 2), and so does strata-hybrid; one of two pieces that
//   cover it converts;
// - strata-convert killed with SIGKILL while writing a 256^3 float volume leaves no file under
//   the output name (its temporary <output>.tmp-<pid> is left), and the next conversion to that
//   name removes the stale temporary and succeeds.
#include "StrataErrorCounter.h"
#include "StrataSegyTestFile.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "StrataPagePoolFile.h"
#include "StrataPagePoolFormat.h"
#include "vtkAsciiGridReader.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkHorizonColumnReader.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMatrix3x3.h"
#include "vtkMetaImageReader.h"
#include "vtkMetaImageWriter.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkNumpyGridReader.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkSegyVolumeReader.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingMetaImageReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <vtksys/Directory.hxx>
#include <vtksys/SystemTools.hxx>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;
using strata_test::SegyTestFile;

/// What the upstream reader was asked for during a conversion: requests and their largest size.
struct SlabLog
{
  int Requests = 0;
  unsigned long LargestKiB = 0;
  vtkIdType LargestTraces = 0; ///< SEG-Y traces read by one request

  static void OnEnd(vtkObject* caller, unsigned long, void* clientData, void*)
  {
    auto* self = static_cast<SlabLog*>(clientData);
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    ++self->Requests;
    vtkDataObject* data = algorithm->GetOutputDataObject(0);
    self->LargestKiB = std::max(self->LargestKiB, data->GetActualMemorySize());
    if (auto* segy = vtkSegyVolumeReader::SafeDownCast(caller))
    {
      self->LargestTraces = std::max(self->LargestTraces, segy->GetNumberOfTracesRead());
    }
  }
};

/// Converts the output of `producer` to a page pool at `path`; logs the upstream requests.
bool Convert(vtkAlgorithm* producer,
  const std::string& path,
  int pageSize,
  double memoryMB,
  SlabLog* log = nullptr)
{
  vtkNew<vtkCallbackCommand> onEnd;
  onEnd->SetCallback(SlabLog::OnEnd);
  onEnd->SetClientData(log);
  const unsigned long tag = log ? producer->AddObserver(vtkCommand::EndEvent, onEnd) : 0;
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(producer->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetPageSize(pageSize);
  writer->SetMemoryLimit(memoryMB);
  writer->SetCompression(true);
  const bool ok = writer->Write();
  if (log)
  {
    producer->RemoveObserver(tag);
  }
  return ok;
}

/// Level 0 of the pool at `path`, read whole.
vtkSmartPointer<vtkImageData> ReadPool(const std::string& path)
{
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

template<typename T>
bool IsNaN(T v)
{
  return v != v;
}

/// Whether pool[n] is source value n stored as T, bit for bit (NaN as any NaN).
template<typename T>
vtkIdType FirstDifference(vtkDataArray* source, const T* pool, vtkIdType n)
{
  for (vtkIdType i = 0; i < n; ++i)
  {
    const T expected = static_cast<T>(source->GetComponent(i, 0));
    if (std::memcmp(&expected, pool + i, sizeof(T)) != 0 && !(IsNaN(expected) && IsNaN(pool[i])))
    {
      return i;
    }
  }
  return -1;
}

/// The pool holds the source: same dimensions, geometry and every value (see above).
bool SameAsSource(vtkImageData* source, vtkImageData* pool)
{
  int sd[3], pd[3];
  source->GetDimensions(sd);
  pool->GetDimensions(pd);
  if (!std::equal(sd, sd + 3, pd))
  {
    std::cerr << "  dimensions " << pd[0] << " x " << pd[1] << " x " << pd[2] << ", source "
              << sd[0] << " x " << sd[1] << " x " << sd[2] << "\n";
    return false;
  }
  double sourceFirst[3], poolFirst[3];
  source->TransformIndexToPhysicalPoint(
    source->GetExtent()[0], source->GetExtent()[2], source->GetExtent()[4], sourceFirst);
  pool->TransformIndexToPhysicalPoint(0, 0, 0, poolFirst);
  for (int a = 0; a < 3; ++a)
  {
    if (source->GetSpacing()[a] != pool->GetSpacing()[a] ||
        std::fabs(sourceFirst[a] - poolFirst[a]) > 1e-9 * (1 + std::fabs(sourceFirst[a])))
    {
      std::cerr << "  geometry differs on axis " << a << "\n";
      return false;
    }
  }
  if (!std::equal(source->GetDirectionMatrix()->GetData(),
        source->GetDirectionMatrix()->GetData() + 9,
        pool->GetDirectionMatrix()->GetData()))
  {
    std::cerr << "  direction differs\n";
    return false;
  }
  vtkDataArray* s = source->GetPointData()->GetScalars();
  vtkDataArray* p = pool->GetPointData()->GetScalars();
  const vtkIdType n = source->GetNumberOfPoints();
  vtkIdType bad = -1;
  switch (p->GetDataType())
  {
    vtkTemplateMacro(bad = FirstDifference(s, static_cast<const VTK_TT*>(p->GetVoidPointer(0)), n));
  }
  if (bad >= 0)
  {
    std::cerr << "  value " << bad << " differs: " << p->GetComponent(bad, 0) << ", source "
              << s->GetComponent(bad, 0) << "\n";
  }
  return bad < 0;
}

/// Converts `reader`'s output and checks the pool against the reader's whole output.
void RoundTrip(vtkAlgorithm* reader,
  const std::string& path,
  const std::string& what,
  int pageSize = 16,
  double memoryMB = 64,
  SlabLog* log = nullptr)
{
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  const bool converted = Convert(reader, path, pageSize, memoryMB, log);
  vtkSmartPointer<vtkImageData> pool = ReadPool(path);
  reader->UpdateWholeExtent(); // the writer left a slab's update extent behind
  vtkImageData* source = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  Check(converted && errors->Errors == 0 && source && source->GetNumberOfPoints() > 0 &&
          SameAsSource(source, pool),
    what + ": the pool's finest level is the source, bit for bit");
}

void Spit(const std::string& path, const void* data, size_t size)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc)
    .write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

/// Starts `args` (args[0] is the program) with stdout sent to /dev/null and stderr to
/// `errorLog` (/dev/null by default).
pid_t Spawn(const std::vector<std::string>& args, const std::string& errorLog = "/dev/null")
{
  std::vector<char*> argv;
  for (const std::string& a : args)
  {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(
    &actions, 2, errorLog.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0)
  {
    pid = -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

/// Runs `args` to the end; its exit code, -1 if it could not run or did not exit.
int Run(const std::vector<std::string>& args, const std::string& errorLog = "/dev/null")
{
  const pid_t pid = Spawn(args, errorLog);
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
  {
    return -1;
  }
  return WEXITSTATUS(status);
}

/// strata-convert: $STRATA_CONVERT_TOOL, else beside this test's executable (both go to the
/// build tree's bin folder); empty when not built.
std::string FindConverter()
{
  const char* env = std::getenv("STRATA_CONVERT_TOOL");
  const std::string tool =
    env ? env
        : vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::GetRealPath("/proc/self/exe")) +
            "/strata-convert";
  return vtksys::SystemTools::FileExists(tool, true) ? tool : std::string();
}

/// Deterministic noise in [0, 1): the volumes need no structure, only distinct values.
float Noise(uint64_t n)
{
  return static_cast<float>(((n + 1) * 0x9E3779B97F4A7C15ull) >> 40) / 16777216.0f;
}

/// Fills image (dims, one component of `type`) with values from `value(n)`.
template<typename F>
vtkSmartPointer<vtkImageData> MakeImage(int nx, int ny, int nz, int type, F value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(0.5, 1.25, 2);
  image->SetOrigin(-3, 7, 100);
  image->AllocateScalars(type, 1);
  vtkDataArray* a = image->GetPointData()->GetScalars();
  for (vtkIdType n = 0; n < image->GetNumberOfPoints(); ++n)
  {
    a->SetComponent(n, 0, value(n));
  }
  return image;
}

void KilledConversion(const std::string& tool, const std::string& dataDir, const std::string& dir)
{
  // 256^3 float: about a second of work with zstd, plenty of time to be killed in.
  const int n = 256;
  std::vector<float> values(static_cast<size_t>(n) * n * n);
  for (size_t i = 0; i < values.size(); ++i)
  {
    values[i] = Noise(i) * 1000.0f;
  }
  const std::string raw = dir + "/killed-input.raw";
  Spit(raw, values.data(), values.size() * sizeof(float));
  values = std::vector<float>();
  const std::string output = dir + "/killed.spp";
  std::remove(output.c_str());
  const std::string size = std::to_string(n);
  const pid_t pid = Spawn({ tool,
    raw,
    output,
    "--raw",
    size,
    size,
    size,
    "float",
    "--compress",
    "--memory-limit",
    "16" });
  const std::string temp = output + ".tmp-" + std::to_string(static_cast<long>(pid));
  // Killed once the temporary holds some pages: it is writing, and far from done.
  bool writing = false;
  const auto start = std::chrono::steady_clock::now();
  while (pid > 0 && !writing && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
  {
    struct stat st;
    writing = ::stat(temp.c_str(), &st) == 0 && st.st_size > 0;
    if (!writing)
    {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  if (pid > 0)
  {
    ::kill(pid, SIGKILL);
  }
  int status = 0;
  const bool killed = pid > 0 && waitpid(pid, &status, 0) == pid && WIFSIGNALED(status) &&
                      WTERMSIG(status) == SIGKILL;
  const bool leftover = vtksys::SystemTools::FileExists(temp, true);
  std::cout << "  killed pid " << pid << " while writing: " << (killed ? "yes" : "no")
            << "; temporary " << temp << (leftover ? " left" : " gone") << "\n";
  Check(writing && killed, "strata-convert was killed with SIGKILL while writing its temporary");
  Check(!vtksys::SystemTools::FileExists(output), "a killed conversion leaves no output file");

  // The next conversion to the same name removes the dead process's temporary.
  const std::string bucky = dataDir + "/volumes/bucky.raw";
  const int rc = Run({ tool, bucky, output, "--raw", "32", "32", "32", "uint8" });
  strata::PagePoolFile pool;
  Check(rc == 0 && pool.Open(output) && !vtksys::SystemTools::FileExists(temp),
    "the next conversion succeeds and removes the stale temporary");
  std::remove(raw.c_str());
  std::remove(output.c_str());
  std::remove(temp.c_str());
}
}

namespace
{
void RawFloat(const std::string& dir)
{
  std::cout << "raw float 128^3 (8 MB), memory limit 2 MB\n";
  const int n = 128;
  vtkSmartPointer<vtkImageData> image =
    MakeImage(n, n, n, VTK_FLOAT, [](vtkIdType i) { return Noise(i) * 2 - 1; });
  const std::string raw = dir + "/volume.raw";
  Spit(raw, image->GetScalarPointer(), sizeof(float) * n * n * n);
  vtkNew<vtkImageReader2> reader;
  reader->SetFileName(raw.c_str());
  reader->SetFileDimensionality(3);
  reader->SetDataExtent(0, n - 1, 0, n - 1, 0, n - 1);
  reader->SetDataScalarTypeToFloat();
  reader->SetDataByteOrderToLittleEndian();
  reader->SetDataSpacing(image->GetSpacing());
  reader->SetDataOrigin(image->GetOrigin());
  SlabLog log;
  const double limitMB = 2.0;
  RoundTrip(reader, dir + "/raw.spp", "raw", 16, limitMB, &log);
  std::cout << "  " << log.Requests << " upstream requests, largest " << log.LargestKiB
            << " KiB; volume " << n * n * n * 4 / 1024 << " KiB\n";
  Check(log.Requests > 4 && log.LargestKiB * 1024.0 < limitMB * 1048576.0 / 4,
    "raw: a volume 4 times the memory limit converts in slabs well within it");
  std::remove(raw.c_str());
}

void VolumeFormats(const std::string& dir, const std::string& data)
{
  std::cout << ".vti float with NaN, .mhd int16, tooth.nrrd uint8\n";
  {
    vtkSmartPointer<vtkImageData> image = MakeImage(40,
      33,
      27,
      VTK_FLOAT,
      [](vtkIdType i) { return i % 97 == 0 ? std::nan("") : Noise(i) * 500 - 250; });
    const std::string vti = dir + "/volume.vti";
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(vti.c_str());
    writer->Write();
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(vti.c_str());
    RoundTrip(reader, dir + "/vti.spp", ".vti");
    Check(SameAsSource(image, ReadPool(dir + "/vti.spp")), ".vti: the pool is the generated image");
  }
  for (const char* name : { "volume.mhd", "volume.mha" })
  {
    // int16 through vtkMetaImageWriter (a .mhd with a .raw beside it, or one .mha), read slab
    // by slab by vtkStreamingMetaImageReader.
    vtkSmartPointer<vtkImageData> image = MakeImage(
      37, 41, 23, VTK_SHORT, [](vtkIdType i) { return std::floor(Noise(i) * 65535) - 32768; });
    const std::string path = dir + "/" + name;
    vtkNew<vtkMetaImageWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(path.c_str());
    writer->SetCompression(false);
    writer->Write();
    vtkNew<vtkStreamingMetaImageReader> reader;
    reader->SetFileName(path.c_str());
    SlabLog log;
    const std::string pool = path + ".spp";
    RoundTrip(reader, pool, name, 16, 0.11, &log);
    std::cout << "  " << name << ": " << log.Requests << " upstream requests, largest "
              << log.LargestKiB << " KiB\n";
    Check(SameAsSource(image, ReadPool(pool)) && log.Requests > 2,
      std::string(name) + ": the pool is the generated image, read in slabs");
    if (std::string(name) == "volume.mhd")
    {
      // Compressed: refused by the streaming reader, read whole by VTK's.
      writer->SetFileName((dir + "/compressed.mhd").c_str());
      writer->SetCompression(true);
      writer->Write();
      Check(vtkStreamingMetaImageReader::IsStreamable(path.c_str()) &&
              !vtkStreamingMetaImageReader::IsStreamable((dir + "/compressed.mhd").c_str()),
        "compressed MetaImage data are not streamable, raw ones are");
      vtkNew<vtkMetaImageReader> whole;
      whole->SetFileName((dir + "/compressed.mhd").c_str());
      whole->Update();
      Check(SameAsSource(whole->GetOutput(), ReadPool(pool)), "compressed .mhd: the same values");
    }
  }
  {
    vtkNew<vtkNrrdReader> reader;
    reader->SetFileName((data + "/volumes/tooth.nrrd").c_str());
    RoundTrip(reader, dir + "/tooth.spp", "tooth.nrrd");
  }
}

void Segy(const std::string& dir, const std::string& data)
{
  std::cout << "SEG-Y\n";
  const std::string f3 = data + "/seismic/f3.sgy";
  {
    // 18 x 75 x 23 float; with page size 8 the writer's own buffers take 0.098 MB and an
    // inline 0.005 MB, so 0.12 MB leaves room for 4 inlines per request.
    vtkNew<vtkSegyVolumeReader> reader;
    reader->SetFileName(f3.c_str());
    SlabLog log;
    RoundTrip(reader, dir + "/f3.spp", "f3.sgy", 8, 0.12, &log);
    std::cout << "  " << log.Requests << " upstream requests, at most " << log.LargestTraces
              << " of 414 traces each\n";
    Check(log.Requests > 3 && log.LargestTraces < 414 && log.LargestTraces % 18 == 0,
      "f3.sgy: converted a few whole inlines at a time");
  }
  {
    // A larger shuffled IEEE SEG-Y, 48 crosslines x 250 samples x 160 inlines (7.3 MiB of
    // float), through a 1.5 MiB limit (page size 8: the writer's own buffers take 1.1 MiB).
    SegyTestFile large;
    large.Format = 5;
    large.Inlines = 160;
    large.Crosslines = 48;
    large.Samples = 250;
    large.Seed = 5;
    const std::string path = dir + "/large.sgy";
    const std::string bytes = large.Bytes();
    Spit(path, bytes.data(), bytes.size());
    vtkNew<vtkSegyVolumeReader> reader;
    reader->SetFileName(path.c_str());
    SlabLog log;
    const double limitMB = 1.5;
    RoundTrip(reader, dir + "/large.spp", "large shuffled SEG-Y", 8, limitMB, &log);
    std::cout << "  " << log.Requests << " upstream requests, at most " << log.LargestTraces
              << " of " << 160 * 48 << " traces and " << log.LargestKiB << " KiB each\n";
    Check(log.Requests > 4 && log.LargestTraces % 48 == 0 &&
            log.LargestKiB * 1024.0 < limitMB * 1048576.0 / 2,
      "large SEG-Y: 4.9 times the memory limit, converted whole inlines at a time within it");
    std::remove(path.c_str());
  }
  SegyTestFile shuffled;
  shuffled.InlineByte = 17;
  shuffled.CrosslineByte = 234;
  shuffled.Missing = { { 1, 3 } };
  shuffled.Seed = 11;
  const std::string shuffledPath = dir + "/shuffled.sgy";
  {
    const std::string bytes = shuffled.Bytes();
    Spit(shuffledPath, bytes.data(), bytes.size());
    vtkNew<vtkSegyVolumeReader> reader;
    reader->SetFileName(shuffledPath.c_str());
    reader->SetInlineByte(17);
    reader->SetCrosslineByte(234);
    RoundTrip(reader, dir + "/shuffled.spp", "shuffled IBM SEG-Y", 8);
    vtkSmartPointer<vtkImageData> pool = ReadPool(dir + "/shuffled.spp");
    bool placed = true;
    for (int i = 0; i < shuffled.Inlines; ++i)
      for (int x = 0; x < shuffled.Crosslines; ++x)
        for (int s = 0; s < shuffled.Samples; ++s)
        {
          const float v = pool->GetScalarComponentAsFloat(x, s, i, 0);
          placed =
            placed && (i == 1 && x == 3 ? std::isnan(v)
                                        : v == static_cast<float>(SegyTestFile::Value(1, i, x, s)));
        }
    Check(placed, "shuffled IBM SEG-Y: every trace in its place in the pool, NaN where missing");
  }
}

void Horizons(const strata_test::TestPaths& paths, const std::string& dir, const std::string& data)
{
  std::cout << "horizons\n";
  {
    vtkNew<vtkIrapBinaryGridReader> reader;
    reader->SetFileName((data + "/horizons/reek_01_topreek_rota.gri").c_str());
    RoundTrip(reader, dir + "/reek.spp", "reek_01_topreek_rota.gri", 32);
  }
  {
    vtkNew<vtkNumpyGridReader> reader;
    reader->SetFileName((data + "/horizons/penobscot_seabed_crop.npy").c_str());
    RoundTrip(reader, dir + "/penobscot.spp", "penobscot_seabed_crop.npy", 16);
  }
  const std::string shared = paths.SharedData + "/horizons/penobscot_seabed.npy";
  if (!paths.SharedData.empty() && vtksys::SystemTools::FileExists(shared, true))
  {
    // The whole Penobscot horizon (601 x 481, 2.3 MB) where ../shared/data is at hand.
    vtkNew<vtkNumpyGridReader> reader;
    reader->SetFileName(shared.c_str());
    RoundTrip(reader, dir + "/penobscot-full.spp", "penobscot_seabed.npy (shared data)", 32, 4);
  }
  {
    vtkNew<vtkHorizonColumnReader> reader;
    reader->SetFileName((data + "/horizons/top_heimdal_subset.txt").c_str());
    RoundTrip(reader, dir + "/heimdal.spp", "top_heimdal_subset.txt", 16);
  }
}

/// Issue 14, defect 2: a .vti whose WholeExtent is larger than the union of its pieces used to
/// convert (exit 0, no message) into a pool whose uncovered part is zeros. strata-convert must
/// fail with a message naming the WholeExtent and leave no file under the output name (nor a
/// temporary). A .vti of two pieces that do cover it (the positive control) converts to the
/// same values.
void UncoveredVti(const std::string& tool, const std::string& dir)
{
  vtkSmartPointer<vtkImageData> image =
    MakeImage(24, 20, 16, VTK_FLOAT, [](vtkIdType i) { return Noise(i) * 100 - 50; });
  const std::string covered = dir + "/two-pieces.vti";
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(covered.c_str());
  writer->SetNumberOfPieces(2);
  writer->Write();
  const std::string coveredPool = dir + "/two-pieces.spp";
  Check(Run({ tool, covered, coveredPool, "--page-size", "8" }) == 0 &&
          SameAsSource(image, ReadPool(coveredPool)),
    "strata-convert, .vti of two pieces covering its WholeExtent: the generated image");

  // The same file claiming 32 slices instead of 16: slices 16..31 are in no piece.
  std::ifstream in(covered, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string whole = "WholeExtent=\"0 23 0 19 0 15\"";
  const size_t at = text.find(whole);
  Check(at != std::string::npos, "the written .vti states WholeExtent=\"0 23 0 19 0 15\"");
  if (at == std::string::npos)
  {
    return;
  }
  text.replace(at, whole.size(), "WholeExtent=\"0 23 0 19 0 31\"");
  const std::string uncovered = dir + "/uncovered.vti";
  Spit(uncovered, text.data(), text.size());
  const std::string pool = dir + "/uncovered.spp";
  const std::string log = dir + "/uncovered.log";
  std::remove(pool.c_str());
  const int rc = Run({ tool, uncovered, pool, "--page-size", "8" }, log);
  std::ifstream logIn(log);
  const std::string message(
    (std::istreambuf_iterator<char>(logIn)), std::istreambuf_iterator<char>());
  bool temporaryLeft = false;
  vtksys::Directory listing;
  listing.Load(dir);
  for (unsigned long f = 0; f < listing.GetNumberOfFiles(); ++f)
  {
    temporaryLeft |= std::string(listing.GetFile(f)).rfind("uncovered.spp.tmp-", 0) == 0;
  }
  std::cout << "  uncovered .vti: exit " << rc << ", output "
            << (vtksys::SystemTools::FileExists(pool) ? "written" : "absent")
            << ", message: " << message;
  Check(rc != 0, "strata-convert, .vti with uncovered WholeExtent: nonzero exit");
  Check(message.find("WholeExtent") != std::string::npos &&
          message.find("0 23 0 19 16 31") != std::string::npos,
    "strata-convert, uncovered .vti: the message names the WholeExtent and the uncovered part");
  Check(!vtksys::SystemTools::FileExists(pool) && !temporaryLeft,
    "strata-convert, uncovered .vti: no output file and no temporary left");
  // strata-hybrid reads a .vti whole through the same reader: the same refusal.
  const std::string hybrid = vtksys::SystemTools::GetFilenamePath(tool) + "/strata-hybrid";
  if (vtksys::SystemTools::FileExists(hybrid, true))
  {
    const std::string shv = dir + "/uncovered.shv";
    const std::string hybridLog = dir + "/uncovered-hybrid.log";
    std::remove(shv.c_str());
    const int hybridRc = Run({ hybrid, uncovered, shv }, hybridLog);
    std::ifstream hybridIn(hybridLog);
    const std::string hybridMessage(
      (std::istreambuf_iterator<char>(hybridIn)), std::istreambuf_iterator<char>());
    std::cout << "  uncovered .vti, strata-hybrid: exit " << hybridRc
              << ", message: " << hybridMessage;
    Check(hybridRc != 0 && hybridMessage.find("0 23 0 19 16 31") != std::string::npos &&
            !vtksys::SystemTools::FileExists(shv),
      "strata-hybrid, uncovered .vti: nonzero exit, the uncovered extent named, no output");
  }
}

/// The text grids of issue 14 (written here, small): each read by its reader and converted both
/// by vtkImageToPagePoolWriter and by strata-convert, which must tell the format from the
/// content (or, for the matrix, from the .txt extension) and give the same pool.
void TextGrids(const std::string& tool, const std::string& dir)
{
  std::cout << "text grids: Irap classic, ZMAP+, ESRI ASCII, whitespace matrix\n";
  auto z = [](int i, int j)
  { return std::to_string(1500 + 7 * i - 3 * j) + "." + std::to_string(i % 10); };
  std::string irap =
    "-996 9 12.5 25.0\n100.0 237.5 200.0 400.0\n12 15.0 100.0 200.0\n0 0 0 0 0 0 0\n";
  std::string zmap =
    "! test\n@g HEADER, GRID, 4\n15, -99999.0, , 3, 1\n9, 12, 0.0, 110.0, 0.0, 80.0\n"
    "0.0, 0.0, 0.0\n@\n";
  std::string esri =
    "ncols 12\nnrows 9\nxllcorner 1000\nyllcorner 2000\ncellsize 5\nNODATA_value -9999\n";
  std::string matrix = "# 12 rows of 9\n";
  for (int j = 0; j < 9; ++j)
  {
    for (int i = 0; i < 12; ++i)
    {
      irap += (i == 3 && j == 4 ? std::string("9999900.0") : z(i, j)) + (i % 6 == 5 ? "\n" : " ");
      esri += (i == 5 && j == 2 ? std::string("-9999") : z(i, 8 - j)) + (i == 11 ? "\n" : " ");
    }
  }
  for (int i = 0; i < 12; ++i)
  {
    for (int j = 8; j >= 0; --j)
    {
      zmap += (i == 2 && j == 2 ? std::string("-99999.0") : z(i, j)) + (j % 4 == 0 ? "\n" : " ");
    }
    for (int j = 0; j < 9; ++j)
    {
      matrix += (i == 7 && j == 1 ? std::string("nan") : z(i, j)) + (j == 8 ? "\n" : " ");
    }
  }
  const std::pair<const char*, const std::string*> files[] = {
    { "irap.fgr", &irap }, { "grid.zmap", &zmap }, { "grid.asc", &esri }, { "matrix.txt", &matrix }
  };
  for (const auto& f : files)
  {
    const std::string path = dir + "/" + f.first;
    Spit(path, f.second->data(), f.second->size());
    vtkSmartPointer<vtkAlgorithm> reader;
    if (std::string(f.first) == "matrix.txt")
    {
      auto r = vtkSmartPointer<vtkHorizonColumnReader>::New();
      r->SetFileName(path.c_str());
      reader = r;
    }
    else
    {
      auto r = vtkSmartPointer<vtkAsciiGridReader>::New();
      r->SetFileName(path.c_str());
      reader = r;
    }
    RoundTrip(reader, path + ".spp", f.first, 8);
    vtkImageData* source = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    int dims[3] = { 0, 0, 0 };
    source->GetDimensions(dims);
    vtkDataArray* values = source->GetPointData()->GetScalars();
    int holes = 0;
    for (vtkIdType n = 0; values && n < values->GetNumberOfTuples(); ++n)
    {
      holes += std::isnan(values->GetComponent(n, 0)) ? 1 : 0;
    }
    const int rc = tool.empty() ? -1 : Run({ tool, path, path + "-tool.spp", "--page-size", "8" });
    std::cout << "  " << f.first << ": " << dims[0] << " x " << dims[1] << ", " << holes
              << " hole(s), strata-convert exit " << rc << "\n";
    Check(dims[0] == 12 && dims[1] == 9 && dims[2] == 1 && holes == 1,
      std::string(f.first) + ": 12 x 9 nodes, one hole");
    if (tool.empty())
    {
      continue;
    }
    const std::string pool = path + "-tool.spp";
    Check(rc == 0 && SameAsSource(source, ReadPool(pool)),
      std::string("strata-convert ") + f.first + ": the same pool as the reader's");
  }
  if (tool.empty())
  {
    return;
  }
  // A matrix too narrow for Auto (5 values a line): refused as columns, read with
  // --grid-format matrix (line r = node row i, as vtkAsciiGridReader's Matrix format).
  const std::string narrow = dir + "/narrow.txt";
  const std::string text = "# 4 x 5\n1 2 3 4 5\n6 7 8 9 10\n11 12 13 14 15\n16 17 18 19 nan\n";
  Spit(narrow, text.data(), text.size());
  const int refused = Run({ tool, narrow, narrow + ".spp", "--page-size", "8" });
  const int forced =
    Run({ tool, narrow, narrow + "-matrix.spp", "--page-size", "8", "--grid-format", "matrix" });
  vtkSmartPointer<vtkImageData> pool = ReadPool(narrow + "-matrix.spp");
  int dims[3] = { 0, 0, 0 };
  pool->GetDimensions(dims);
  vtkDataArray* v = pool->GetPointData()->GetScalars();
  std::cout << "  narrow.txt: exit " << refused << " without --grid-format, " << forced
            << " with --grid-format matrix: " << dims[0] << " x " << dims[1] << "\n";
  Check(refused != 0 && !vtksys::SystemTools::FileExists(narrow + ".spp"),
    "strata-convert, a 4 x 5 matrix as columns: refused, nothing written");
  Check(forced == 0 && dims[0] == 4 && dims[1] == 5 && v && v->GetComponent(1, 0) == 6.0 &&
          v->GetComponent(4, 0) == 2.0 && std::isnan(v->GetComponent(19, 0)),
    "strata-convert --grid-format matrix: 4 x 5, node (1, 0) = 6, (0, 1) = 2, (3, 4) a hole");
}

void StrataConvert(const strata_test::TestPaths& paths, const std::string& dir)
{
  const std::string f3 = paths.Data + "/seismic/f3.sgy";
  const std::string shuffledPath = dir + "/shuffled.sgy"; // Segy's
  std::cout << "strata-convert\n";
  const std::string tool = FindConverter();
  if (tool.empty())
  {
    std::cout << "  skipped: strata-convert not built (STRATA_BUILD_EXAMPLES off)\n";
  }
  else
  {
    const std::string fromTool = dir + "/f3-tool.spp";
    Check(Run({ tool, f3, fromTool, "--page-size", "8" }) == 0 &&
            SameAsSource(ReadPool(dir + "/f3.spp"), ReadPool(fromTool)),
      "strata-convert f3.sgy: the same pool as the writer's");
    const std::string shuffledTool = dir + "/shuffled-tool.spp";
    Check(Run({ tool,
            shuffledPath,
            shuffledTool,
            "--page-size",
            "8",
            "--inline-byte",
            "17",
            "--crossline-byte",
            "234" }) == 0 &&
            SameAsSource(ReadPool(dir + "/shuffled.spp"), ReadPool(shuffledTool)),
      "strata-convert --inline-byte 17 --crossline-byte 234: the same pool as the writer's");
    Check(Run({ tool, shuffledPath, shuffledTool + "-wrong" }) != 0 &&
            !vtksys::SystemTools::FileExists(shuffledTool + "-wrong"),
      "strata-convert with the wrong byte positions fails and writes nothing");
    for (const char* name : { "volume.mhd", "compressed.mhd" })
    {
      const std::string pool = dir + "/" + name + "-tool.spp";
      Check(Run({ tool, dir + "/" + name, pool, "--page-size", "16" }) == 0 &&
              SameAsSource(ReadPool(dir + "/volume.mhd.spp"), ReadPool(pool)),
        std::string("strata-convert ") + name + ": the same pool as the writer's");
    }
    KilledConversion(tool, paths.Data, dir);
    UncoveredVti(tool, dir);
  }
}

/// strata-convert on a .vti of two float components: a set of two pools, read back as one image
/// of two components, bit-exact.
void ComponentsVti(const std::string& tool, const std::string& dir)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(21, 18, 13);
  image->AllocateScalars(VTK_FLOAT, 2);
  auto* v = static_cast<float*>(image->GetScalarPointer());
  for (vtkIdType i = 0; i < 2 * image->GetNumberOfPoints(); ++i)
    v[i] = static_cast<float>(Noise(i) * (i % 2 ? 1000.0 : 1.0));
  const std::string vti = dir + "/two-components.vti";
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(vti.c_str());
  writer->Write();
  const std::string pool = dir + "/two-components.spp";
  const int rc = Run({ tool, vti, pool, "--page-size", "8" });
  vtkSmartPointer<vtkImageData> back = ReadPool(pool);
  vtkDataArray* scalars = back ? back->GetPointData()->GetScalars() : nullptr;
  bool same = scalars && scalars->GetNumberOfComponents() == 2 &&
              scalars->GetNumberOfTuples() == image->GetNumberOfPoints();
  for (vtkIdType i = 0; same && i < image->GetNumberOfPoints(); ++i)
    same = scalars->GetComponent(i, 0) == v[2 * i] && scalars->GetComponent(i, 1) == v[2 * i + 1];
  std::cout << "  two-component .vti: exit " << rc << ", component 1 in "
            << strata::PagePoolFormat::GetComponentFileName(pool, 1) << "\n";
  Check(rc == 0 &&
          vtksys::SystemTools::FileExists(strata::PagePoolFormat::GetComponentFileName(pool, 1)),
    "strata-convert, .vti of two components: a pool per component");
  Check(same, "strata-convert, .vti of two components: read back bit-exact, both components");
}

}

int TestConverters(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dir = paths.Output + "/TestConverters";
  vtksys::SystemTools::MakeDirectory(dir);
  const std::string data = paths.Data;
  return strata_test::RunSubTests(
    {
      { "RawFloat", [&] { RawFloat(dir); } },
      { "VolumeFormats", [&] { VolumeFormats(dir, data); } },
      { "Segy", [&] { Segy(dir, data); } },
      { "Horizons", [&] { Horizons(paths, dir, data); } },
      { "StrataConvert", [&] { StrataConvert(paths, dir); } },
      { "TextGrids", [&] { TextGrids(FindConverter(), dir); } },
      { "ComponentsVti", [&] { ComponentsVti(FindConverter(), dir); } },
    },
    strata_test::Failures);
}

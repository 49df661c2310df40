// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataFuzz.h"

#include "vtkObject.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <cstdio>
#include <cstdlib>
#include <sys/stat.h>
#include <unistd.h>

namespace strata_fuzz
{
namespace
{
/// An output window that drops everything.
class vtkSilentOutputWindow : public vtkOutputWindow
{
public:
  static vtkSilentOutputWindow* New();
  vtkTypeMacro(vtkSilentOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}

protected:
  vtkSilentOutputWindow() = default;
  ~vtkSilentOutputWindow() override = default;
};
vtkStandardNewMacro(vtkSilentOutputWindow);

std::string InputFolder()
{
  struct stat s;
  const char* base = (stat("/dev/shm", &s) == 0 && S_ISDIR(s.st_mode)) ? "/dev/shm" : nullptr;
  if (!base)
  {
    base = std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp";
  }
  return std::string(base) + "/strata-fuzz-" + std::to_string(getpid());
}
}

void SilenceVTK()
{
  static bool done = false;
  if (done)
  {
    return;
  }
  done = true;
  if (std::getenv("STRATA_FUZZ_VERBOSE"))
  {
    return; // to see why an input is refused
  }
  vtkObject::GlobalWarningDisplayOff();
  vtkSilentOutputWindow* window = vtkSilentOutputWindow::New();
  vtkOutputWindow::SetInstance(window);
  window->Delete();
}

std::string WriteInput(const uint8_t* data, size_t size, const std::string& extension)
{
  // One folder and one file per process, removed at exit (a crash leaves them, in memory).
  static std::string folder;
  static std::string path;
  if (path.empty())
  {
    folder = InputFolder();
    path = folder + "/input" + extension;
    mkdir(folder.c_str(), 0700);
    std::atexit(
      []()
      {
        unlink(path.c_str());
        rmdir(folder.c_str());
      });
  }
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f)
  {
    std::perror(path.c_str());
    std::abort();
  }
  if (size > 0 && std::fwrite(data, 1, size, f) != size)
  {
    std::perror(path.c_str());
    std::abort();
  }
  std::fclose(f);
  return path;
}
}

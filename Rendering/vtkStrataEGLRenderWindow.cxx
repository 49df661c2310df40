// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataEGLRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

vtkStandardNewMacro(vtkStrataEGLRenderWindow);

namespace
{
// All windows of a process share one EGLDisplay: eglTerminate would destroy every context on
// it, so the display is initialised once and terminated never (the driver frees it at exit).
struct SharedDisplay
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  std::string Platform;
  bool Tried = false;
};

SharedDisplay& GetSharedDisplay()
{
  static SharedDisplay display;
  return display;
}

template<typename T>
T LoadProc(const char* name)
{
  return reinterpret_cast<T>(eglGetProcAddress(name));
}

bool HasExtension(const char* list, const char* name)
{
  if (!list)
  {
    return false;
  }
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
  {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
    {
      return true;
    }
  }
  return false;
}

bool TryInitialize(EGLDisplay display)
{
  EGLint major = 0, minor = 0;
  return display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) == EGL_TRUE;
}

// A hardware EGL device if there is one (Mesa also lists a software device: skip it).
EGLDisplay OpenDeviceDisplay(const char* clientExtensions)
{
  if (!HasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
      !HasExtension(clientExtensions, "EGL_EXT_device_base"))
  {
    return EGL_NO_DISPLAY;
  }
  auto queryDevices = LoadProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto queryDeviceString = LoadProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  auto getPlatformDisplay = LoadProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!queryDevices || !getPlatformDisplay)
  {
    return EGL_NO_DISPLAY;
  }
  EGLint count = 0;
  if (!queryDevices(0, nullptr, &count) || count <= 0)
  {
    return EGL_NO_DISPLAY;
  }
  std::vector<EGLDeviceEXT> devices(count);
  queryDevices(count, devices.data(), &count);
  const char* forced = std::getenv("STRATA_EGL_DEVICE");
  for (EGLint i = 0; i < count; ++i)
  {
    if (forced && std::atoi(forced) != i)
    {
      continue;
    }
    const char* ext = queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
    if (!forced && HasExtension(ext, "EGL_MESA_device_software"))
    {
      continue;
    }
    EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (TryInitialize(display))
    {
      return display;
    }
  }
  return EGL_NO_DISPLAY;
}

EGLDisplay OpenSurfacelessDisplay(const char* clientExtensions)
{
  if (!HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
  {
    return EGL_NO_DISPLAY;
  }
  auto getPlatformDisplay = LoadProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  EGLDisplay display =
    getPlatformDisplay
      ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
      : EGL_NO_DISPLAY;
  return TryInitialize(display) ? display : EGL_NO_DISPLAY;
}

SharedDisplay& OpenDisplay()
{
  SharedDisplay& shared = GetSharedDisplay();
  if (shared.Tried)
  {
    return shared;
  }
  shared.Tried = true;
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const char* forced = std::getenv("STRATA_EGL_PLATFORM");
  const std::string want = forced ? forced : "";
  if (want.empty() || want == "device")
  {
    shared.Display = OpenDeviceDisplay(clientExtensions);
    shared.Platform = "device";
  }
  if (shared.Display == EGL_NO_DISPLAY && (want.empty() || want == "surfaceless"))
  {
    shared.Display = OpenSurfacelessDisplay(clientExtensions);
    shared.Platform = "surfaceless";
  }
  if (shared.Display == EGL_NO_DISPLAY && (want.empty() || want == "default"))
  {
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    shared.Display = TryInitialize(display) ? display : EGL_NO_DISPLAY;
    shared.Platform = "default";
  }
  if (shared.Display == EGL_NO_DISPLAY)
  {
    shared.Platform.clear();
  }
  return shared;
}

/// Where a window's debug messages go: the window (for vtkErrorMacro) and the count.
struct DebugSink
{
  vtkStrataEGLRenderWindow* Window = nullptr;
  int Errors = 0;
};

const char* DebugTypeName(GLenum type)
{
  return type == GL_DEBUG_TYPE_ERROR ? "error" : "undefined behaviour";
}

// KHR_debug's callback: errors and undefined behaviour count, the rest is chatter (NVIDIA's
// buffer placement notes, performance hints).
void GLAPIENTRY ReportGLDebugMessage(GLenum,
  GLenum type,
  GLuint id,
  GLenum,
  GLsizei,
  const GLchar* message,
  const void* user)
{
  if (type != GL_DEBUG_TYPE_ERROR && type != GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR)
  {
    return;
  }
  auto* sink = static_cast<DebugSink*>(const_cast<void*>(user));
  ++sink->Errors;
  std::cerr << "Strata GL debug: " << DebugTypeName(type) << " 0x" << std::hex << id << std::dec
            << ": " << message << std::endl;
  vtkErrorWithObjectMacro(
    sink->Window, "GL debug output: " << DebugTypeName(type) << ": " << message);
}
}

class vtkStrataEGLRenderWindow::vtkInternals
{
public:
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLConfig Config = nullptr;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE;
  int SurfaceSize[2] = { 0, 0 };
  std::string Platform;
  bool Failed = false;
  /// What was current at each PushContext: display, draw and read surfaces, context.
  struct Current
  {
    EGLDisplay Display;
    EGLSurface Draw, Read;
    EGLContext Context;
  };
  std::vector<Current> Pushed;
  DebugSink Debug;
};

vtkStrataEGLRenderWindow::vtkStrataEGLRenderWindow()
  : Internals(new vtkInternals)
{
  // Offscreen by nature: nothing is ever shown, and VTK should not try to.
  this->SetOffScreenRendering(1);
  this->ShowWindow = false;
  this->SetReadyForRendering(true);
  this->Size[0] = 300;
  this->Size[1] = 300;
  const char* debug = std::getenv("STRATA_GL_DEBUG");
  this->GLDebugOutput = debug && std::strcmp(debug, "1") == 0;
}

vtkStrataEGLRenderWindow::~vtkStrataEGLRenderWindow()
{
  this->Finalize();
}

bool vtkStrataEGLRenderWindow::ShouldOverrideRenderWindow()
{
  const char* offscreen = std::getenv("STRATA_OFFSCREEN");
  if (offscreen && *offscreen)
  {
    return std::strcmp(offscreen, "0") != 0;
  }
  const char* display = std::getenv("DISPLAY");
  return !display || !*display;
}

bool vtkStrataEGLRenderWindow::CreateContext()
{
  vtkInternals& in = *this->Internals;
  if (in.Context != EGL_NO_CONTEXT)
  {
    return true;
  }
  if (in.Failed)
  {
    return false;
  }
  SharedDisplay& shared = OpenDisplay();
  if (shared.Display == EGL_NO_DISPLAY)
  {
    in.Failed = true;
    vtkErrorMacro("No EGL display: neither an EGL device nor Mesa's surfaceless platform is "
                  "available (install libegl-mesa0 for software rendering).");
    return false;
  }
  in.Display = shared.Display;
  in.Platform = shared.Platform;

  const EGLint configAttribs[] = { EGL_SURFACE_TYPE,
    EGL_PBUFFER_BIT,
    EGL_RED_SIZE,
    8,
    EGL_GREEN_SIZE,
    8,
    EGL_BLUE_SIZE,
    8,
    EGL_ALPHA_SIZE,
    8,
    EGL_DEPTH_SIZE,
    24,
    EGL_STENCIL_SIZE,
    8,
    EGL_RENDERABLE_TYPE,
    EGL_OPENGL_BIT,
    EGL_NONE };
  EGLint numConfigs = 0;
  if (!eglChooseConfig(in.Display, configAttribs, &in.Config, 1, &numConfigs) || numConfigs < 1)
  {
    in.Failed = true;
    vtkErrorMacro("No EGL config with an RGBA8 pbuffer and a 24-bit depth buffer.");
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    in.Failed = true;
    vtkErrorMacro("EGL cannot bind the desktop OpenGL API.");
    return false;
  }
  // The newest core profile the driver gives: Strata's shaders need 3.3, later features 4.3+.
  const int versions[][2] = { { 4, 6 }, { 4, 5 }, { 4, 3 }, { 4, 1 }, { 3, 3 }, { 3, 2 } };
  for (const auto& v : versions)
  {
    const EGLint contextAttribs[] = { EGL_CONTEXT_MAJOR_VERSION,
      v[0],
      EGL_CONTEXT_MINOR_VERSION,
      v[1],
      EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
      EGL_CONTEXT_OPENGL_DEBUG,
      this->GLDebugOutput ? EGL_TRUE : EGL_FALSE,
      EGL_NONE };
    in.Context = eglCreateContext(in.Display, in.Config, EGL_NO_CONTEXT, contextAttribs);
    if (in.Context != EGL_NO_CONTEXT)
    {
      break;
    }
  }
  if (in.Context == EGL_NO_CONTEXT)
  {
    in.Failed = true;
    vtkErrorMacro("eglCreateContext failed for every OpenGL core profile from 4.6 to 3.2.");
    return false;
  }
  return this->ResizeSurface(this->Size[0], this->Size[1]);
}

bool vtkStrataEGLRenderWindow::ResizeSurface(int width, int height)
{
  vtkInternals& in = *this->Internals;
  width = width > 0 ? width : 1;
  height = height > 0 ? height : 1;
  if (in.Surface != EGL_NO_SURFACE && in.SurfaceSize[0] == width && in.SurfaceSize[1] == height)
  {
    return true;
  }
  const bool wasCurrent = in.Surface != EGL_NO_SURFACE && eglGetCurrentContext() == in.Context;
  if (in.Surface != EGL_NO_SURFACE)
  {
    if (wasCurrent)
    {
      eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroySurface(in.Display, in.Surface);
    in.Surface = EGL_NO_SURFACE;
  }
  const EGLint surfaceAttribs[] = { EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE };
  in.Surface = eglCreatePbufferSurface(in.Display, in.Config, surfaceAttribs);
  if (in.Surface == EGL_NO_SURFACE)
  {
    vtkErrorMacro("eglCreatePbufferSurface failed for " << width << " x " << height << ".");
    return false;
  }
  in.SurfaceSize[0] = width;
  in.SurfaceSize[1] = height;
  if (wasCurrent)
  {
    eglMakeCurrent(in.Display, in.Surface, in.Surface, in.Context);
  }
  return true;
}

void vtkStrataEGLRenderWindow::Initialize()
{
  if (this->Internals->Context == EGL_NO_CONTEXT)
  {
    if (!this->CreateContext())
    {
      return;
    }
    this->MakeCurrent();
    this->OpenGLInit();
  }
}

void vtkStrataEGLRenderWindow::OpenGLInitContext()
{
  // VTK's own glewInit fails here (GLEW's GLX part looks for an X display) although every core
  // entry point is loaded by then: run it ourselves, accept that error, and tell VTK it is done.
  if (!this->Initialized)
  {
    this->MakeCurrent();
    glewExperimental = GL_TRUE;
    const GLenum result = glewInit();
#ifdef GLEW_ERROR_NO_GLX_DISPLAY
    const bool acceptable = result == GLEW_OK || result == GLEW_ERROR_NO_GLX_DISPLAY;
#else
    const bool acceptable = result == GLEW_OK;
#endif
    if (!acceptable || !glGetString)
    {
      vtkErrorMacro("GLEW could not load OpenGL through EGL: " << glewGetErrorString(result));
      return;
    }
    // glewInit may leave a GL error behind (GL_INVALID_ENUM on core profiles): clear it.
    while (glGetError() != GL_NO_ERROR)
    {
    }
    this->GlewInitValid = true;
    this->Initialized = true;
    if (this->GLDebugOutput)
    {
      this->EnableGLDebugOutput();
    }
  }
  this->Superclass::OpenGLInitContext();
}

void vtkStrataEGLRenderWindow::EnableGLDebugOutput()
{
  if (!GLEW_VERSION_4_3 && !GLEW_KHR_debug)
  {
    vtkWarningMacro("GL debug output asked for, but the context has no KHR_debug.");
    return;
  }
  // Synchronous: the message arrives inside the call that caused it (a stack trace points at
  // it), on the render thread.
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  this->Internals->Debug.Window = this;
  glDebugMessageCallback(ReportGLDebugMessage, &this->Internals->Debug);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

int vtkStrataEGLRenderWindow::GetNumberOfGLDebugErrors() const
{
  return this->Internals->Debug.Errors;
}

void vtkStrataEGLRenderWindow::Finalize()
{
  vtkInternals& in = *this->Internals;
  if (in.Context != EGL_NO_CONTEXT)
  {
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
    eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(in.Display, in.Context);
    in.Context = EGL_NO_CONTEXT;
  }
  if (in.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(in.Display, in.Surface);
    in.Surface = EGL_NO_SURFACE;
  }
  this->Initialized = false;
  this->GlewInitValid = false;
}

void vtkStrataEGLRenderWindow::Render()
{
  this->Initialize();
  if (this->Internals->Context == EGL_NO_CONTEXT)
  {
    return; // the error was reported when the context failed
  }
  this->MakeCurrent();
  this->Superclass::Render();
}

void vtkStrataEGLRenderWindow::Frame()
{
  // The generic window only fires an event here; do what a real window does: finish the frame
  // into the display framebuffer (what ReadPixels and vtkWindowToImageFilter read).
  this->MakeCurrent();
  this->vtkOpenGLRenderWindow::Frame();
}

void vtkStrataEGLRenderWindow::MakeCurrent()
{
  vtkInternals& in = *this->Internals;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() != in.Context)
  {
    if (eglMakeCurrent(in.Display, in.Surface, in.Surface, in.Context) != EGL_TRUE)
    {
      vtkErrorMacro(
        "eglMakeCurrent failed (error 0x" << std::hex << eglGetError() << std::dec << ").");
    }
  }
}

void vtkStrataEGLRenderWindow::PushContext()
{
  this->Internals->Pushed.push_back({ eglGetCurrentDisplay(),
    eglGetCurrentSurface(EGL_DRAW),
    eglGetCurrentSurface(EGL_READ),
    eglGetCurrentContext() });
  this->MakeCurrent();
}

void vtkStrataEGLRenderWindow::PopContext()
{
  vtkInternals& in = *this->Internals;
  if (in.Pushed.empty())
  {
    return;
  }
  const vtkInternals::Current before = in.Pushed.back();
  in.Pushed.pop_back();
  if (before.Context == eglGetCurrentContext())
  {
    return;
  }
  if (before.Context == EGL_NO_CONTEXT)
  {
    eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  else
  {
    eglMakeCurrent(before.Display, before.Draw, before.Read, before.Context);
  }
}

void vtkStrataEGLRenderWindow::ReleaseCurrent()
{
  vtkInternals& in = *this->Internals;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() == in.Context)
  {
    eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

bool vtkStrataEGLRenderWindow::IsCurrent()
{
  return this->Internals->Context != EGL_NO_CONTEXT &&
         eglGetCurrentContext() == this->Internals->Context;
}

int vtkStrataEGLRenderWindow::SupportsOpenGL()
{
  this->Initialize();
  return this->Internals->Context != EGL_NO_CONTEXT ? 1 : 0;
}

vtkTypeBool vtkStrataEGLRenderWindow::IsDirect()
{
  return this->Internals->Context != EGL_NO_CONTEXT ? 1 : 0;
}

#if VTK_VERSION_NUMBER < VTK_VERSION_CHECK(9, 2, 0)
bool vtkStrataEGLRenderWindow::IsDrawable()
{
  return this->Internals->Context != EGL_NO_CONTEXT;
}
#endif

void vtkStrataEGLRenderWindow::SetShowWindow(bool)
{
  // Nothing can be shown: stay offscreen whatever a caller asks.
  this->Superclass::SetShowWindow(false);
}

void vtkStrataEGLRenderWindow::SetSize(int width, int height)
{
  if (this->Size[0] == width && this->Size[1] == height)
  {
    return;
  }
  this->Superclass::SetSize(width, height);
  if (this->Internals->Context != EGL_NO_CONTEXT)
  {
    this->ResizeSurface(width, height);
  }
}

void* vtkStrataEGLRenderWindow::GetGenericContext()
{
  return this->Internals->Context;
}

void* vtkStrataEGLRenderWindow::GetGenericDisplayId()
{
  return this->Internals->Display;
}

std::string vtkStrataEGLRenderWindow::GetPlatformName() const
{
  return this->Internals->Platform;
}

std::string vtkStrataEGLRenderWindow::GetRendererName()
{
  this->Initialize();
  if (this->Internals->Context == EGL_NO_CONTEXT)
  {
    return std::string();
  }
  this->MakeCurrent();
  const GLubyte* renderer = glGetString(GL_RENDERER);
  return renderer ? reinterpret_cast<const char*>(renderer) : "";
}

void vtkStrataEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Platform: " << this->Internals->Platform << "\n";
  os << indent << "GLDebugOutput: " << this->GLDebugOutput
     << " (errors reported: " << this->Internals->Debug.Errors << ")\n";
  os << indent << "HasContext: " << (this->Internals->Context != EGL_NO_CONTEXT) << "\n";
  os << indent << "SurfaceSize: " << this->Internals->SurfaceSize[0] << " x "
     << this->Internals->SurfaceSize[1] << "\n";
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataEGLRenderWindow
 * @brief   Offscreen render window on an EGL context: no X server, GPU or llvmpipe.
 *
 * Debian's VTK 9.1 is built for X only. This window creates its own EGL context (the NVIDIA/
 * AMD EGL device platform when a hardware device is present, Mesa's surfaceless platform
 * otherwise) with a pbuffer surface of the window's size, and lets VTK's generic OpenGL window
 * drive it. VTK's glewInit reports GLEW_ERROR_NO_GLX_DISPLAY there although all core entry
 * points are loaded, so OpenGLInitContext accepts that one error.
 *
 * Strata's object factory makes plain vtkRenderWindow::New() return this window when no
 * DISPLAY is set, or when STRATA_OFFSCREEN=1; STRATA_OFFSCREEN=0 leaves VTK's X window in
 * place. STRATA_EGL_PLATFORM=device|surfaceless|default forces a platform and
 * STRATA_EGL_DEVICE=N a device index.
 *
 * @sa vtkGenericOpenGLRenderWindow
 */
#ifndef vtkStrataEGLRenderWindow_h
#define vtkStrataEGLRenderWindow_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkVersionMacros.h" // For VTK_VERSION_CHECK (VTK 9.1 and ParaView's 9.2)

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class STRATARENDERING_EXPORT vtkStrataEGLRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkStrataEGLRenderWindow* New();
  vtkTypeMacro(vtkStrataEGLRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Initialize() override;
  void Finalize() override;
  void Render() override;
  void Frame() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  ///@{
  /**
   * Makes this window's context current and, on PopContext, gives back whatever was current
   * before (as VTK's X window does): work done in this window's context in the middle of
   * another window's frame (a resource-free callback releasing a mapper's names from here)
   * must not leave the other window's frame drawing into this context.
   */
  void PushContext() override;
  void PopContext() override;
  ///@}
  bool IsCurrent() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;
  void SetSize(int width, int height) override;
  void SetSize(int a[2]) override { this->SetSize(a[0], a[1]); }
  void* GetGenericContext() override;
  void* GetGenericDisplayId() override;
#if VTK_VERSION_NUMBER < VTK_VERSION_CHECK(9, 2, 0)
  bool IsDrawable() override; // (VTK 9.2 dropped it from vtkRenderWindow)
#endif
  void SetShowWindow(bool) override;

  /**
   * Which EGL platform the context runs on: "device" (a hardware EGL device), "surfaceless"
   * (Mesa, llvmpipe without a GPU) or "default"; empty before the first render.
   */
  std::string GetPlatformName() const;

  /**
   * The GL_RENDERER string of the context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
   */
  std::string GetRendererName();

  ///@{
  /**
   * GL debug output (KHR_debug, synchronous, on a debug context): each GL error and each
   * undefined-behaviour report of this window's context is printed to stderr as
   * "Strata GL debug: ..." and raised through vtkErrorMacro; other messages (performance and
   * portability notes, API chatter) are ignored. The context is created with the debug flag, so
   * set this before the first render. Default: on when STRATA_GL_DEBUG=1 (the C++ suite sets
   * it and fails a test on that line), else off.
   */
  vtkSetMacro(GLDebugOutput, bool);
  vtkGetMacro(GLDebugOutput, bool);
  vtkBooleanMacro(GLDebugOutput, bool);
  ///@}

  /// The GL errors and undefined-behaviour reports debug output has delivered so far.
  int GetNumberOfGLDebugErrors() const;

  /**
   * True when this process should use this window for plain vtkRenderWindow::New(): no DISPLAY,
   * or STRATA_OFFSCREEN=1; STRATA_OFFSCREEN=0 says no.
   */
  static bool ShouldOverrideRenderWindow();

protected:
  vtkStrataEGLRenderWindow();
  ~vtkStrataEGLRenderWindow() override;

  void OpenGLInitContext() override;

private:
  vtkStrataEGLRenderWindow(const vtkStrataEGLRenderWindow&) = delete;
  void operator=(const vtkStrataEGLRenderWindow&) = delete;

  bool CreateContext();
  void EnableGLDebugOutput();

  bool GLDebugOutput = false;
  bool ResizeSurface(int width, int height);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

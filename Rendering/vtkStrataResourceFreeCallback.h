// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataResourceFreeCallback
 * @brief   Frees a mapper's GL resources in its window's context, whichever of the two goes
 *          first (VTK's resource-free callback mechanism).
 *
 * A mapper registers one with the window it renders into (RegisterGraphicsResources, each
 * render; a change of window releases from the old one first). When the window releases its
 * resources (Finalize, destruction) it calls Release(), and the mapper's destructor calls it
 * too: Release() makes the window's context current, calls the mapper's
 * ReleaseGraphicsResources(window) and unregisters, so GL names are deleted in the context
 * that made them and never after it is gone.
 *
 * vtkOpenGLRenderWindow keeps these callbacks as vtkGenericOpenGLResourceFreeCallback, whose
 * header neither Debian's libvtk9-dev nor paraview-dev (ParaView 5.11) installs; where it is
 * missing the interface is declared here with the same virtual functions in the same order and the
 * same members, which is all the window relies on (it calls Release() on each registered one).
 */
#ifndef vtkStrataResourceFreeCallback_h
#define vtkStrataResourceFreeCallback_h

#include "vtkOpenGLRenderWindow.h" // For RegisterGraphicsResources, PushContext

#if defined(__has_include) && __has_include("vtkOpenGLResourceFreeCallback.h")
#include "vtkOpenGLResourceFreeCallback.h" // For vtkGenericOpenGLResourceFreeCallback
#else
class vtkGenericOpenGLResourceFreeCallback
{
public:
  vtkGenericOpenGLResourceFreeCallback() = default;
  virtual ~vtkGenericOpenGLResourceFreeCallback() = default;
  virtual void Release() = 0;
  virtual void RegisterGraphicsResources(vtkOpenGLRenderWindow* window) = 0;
  bool IsReleasing() { return this->Releasing; }

protected:
  vtkOpenGLRenderWindow* VTKWindow = nullptr;
  bool Releasing = false;
};
#endif

template<class T>
class vtkStrataResourceFreeCallback : public vtkGenericOpenGLResourceFreeCallback
{
public:
  vtkStrataResourceFreeCallback(T* owner, void (T::*release)(vtkWindow*))
    : Owner(owner)
    , Method(release)
  {
  }
  ~vtkStrataResourceFreeCallback() override = default;

  void RegisterGraphicsResources(vtkOpenGLRenderWindow* window) override
  {
    if (this->VTKWindow == window)
      return;
    this->Release();
    this->VTKWindow = window;
    if (window)
      window->RegisterGraphicsResources(this);
  }

  void Release() override
  {
    if (!this->VTKWindow || this->Releasing)
      return;
    this->Releasing = true;
    vtkOpenGLRenderWindow* window = this->VTKWindow;
    window->PushContext();
    (this->Owner->*this->Method)(window);
    window->UnregisterGraphicsResources(this);
    window->PopContext();
    this->VTKWindow = nullptr;
    this->Releasing = false;
  }

  /// The window the resources live in, null when none are held.
  vtkOpenGLRenderWindow* GetWindow() const { return this->VTKWindow; }

private:
  T* Owner;
  void (T::*Method)(vtkWindow*);
};

#endif

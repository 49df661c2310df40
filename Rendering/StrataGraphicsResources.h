// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::GraphicsResources
 * @brief   Frees a mapper's GL resources in the context that made them, whichever of mapper
 *          and window goes first, through VTK's public API alone.
 *
 * A mapper registers its window every render (Register). Its GL names are then freed in that
 * window's context, made current for the purpose (PushContext), when
 * - the mapper goes: its destructor calls Release();
 * - the mapper moves to another window: Register releases from the old one first;
 * - the window goes first: its DeleteEvent (fired while the window is still whole, before its
 *   destructor runs) releases, so nothing is left to free in a context that is gone. (A window
 *   finalised but kept releases through its renderers' props, VTK's own path.)
 * The window is held by a weak pointer and observed, never owned. (VTK's own mechanism,
 * vtkGenericOpenGLResourceFreeCallback, is declared in a header that neither Debian's VTK nor
 * ParaView installs; this class does not depend on its layout.)
 */
#ifndef StrataGraphicsResources_h
#define StrataGraphicsResources_h

#include "vtkCommand.h"            // For DeleteEvent
#include "vtkOpenGLRenderWindow.h" // For PushContext, PopContext
#include "vtkTextureUnitManager.h" // For the window's texture units
#include "vtkWeakPointer.h"        // For the window

namespace strata
{
template<class T>
class GraphicsResources
{
public:
  GraphicsResources(T* owner, void (T::*release)(vtkWindow*))
    : Owner(owner)
    , Method(release)
  {
  }
  ~GraphicsResources() { this->Forget(); }
  GraphicsResources(const GraphicsResources&) = delete;
  GraphicsResources& operator=(const GraphicsResources&) = delete;

  /**
   * The window the owner renders into now; resources in another one are released first. Also
   * counts the window's texture units again when it counts none: a window whose graphics
   * resources were released keeps its context but has no units until it is initialised again
   * (ParaView's windows after ReleaseGraphicsResources: every unit asked for was -1, and
   * freeing -1 aborts), so before the owner draws.
   */
  void Register(vtkOpenGLRenderWindow* window)
  {
    vtkTextureUnitManager* units = window ? window->GetTextureUnitManager() : nullptr;
    if (units && units->GetNumberOfTextureUnits() == 0)
      units->Initialize();
    if (this->Window.GetPointer() == window)
      return;
    this->Release();
    this->Window = window;
    if (window)
      this->Observer =
        window->AddObserver(vtkCommand::DeleteEvent, this, &GraphicsResources::WindowDeleted);
  }

  /// The owner's ReleaseGraphicsResources(window) in the window's context, then unregistered.
  void Release()
  {
    vtkOpenGLRenderWindow* window = this->Window;
    if (!window || this->Releasing)
      return;
    this->Releasing = true;
    window->PushContext();
    (this->Owner->*this->Method)(window);
    window->PopContext();
    this->Forget();
    this->Releasing = false;
  }

  /// The window the resources live in, null when none are held.
  vtkOpenGLRenderWindow* GetWindow() const { return this->Window; }

private:
  void WindowDeleted(vtkObject*, unsigned long, void*) { this->Release(); }
  void Forget()
  {
    if (this->Window)
      this->Window->RemoveObserver(this->Observer);
    this->Window = nullptr;
    this->Observer = 0;
  }

  T* Owner;
  void (T::*Method)(vtkWindow*);
  vtkWeakPointer<vtkOpenGLRenderWindow> Window;
  unsigned long Observer = 0;
  bool Releasing = false;
};
}

#endif

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Strata's object factory, registered by VTK's autoinit (the module IMPLEMENTS
// VTK::RenderingCore). Written by hand rather than by vtk_object_factory_configure because
// whether the EGL window replaces VTK's X window is decided at run time. A build with
// STRATA_OVERRIDE_RENDER_WINDOW off (the ParaView plugin: ParaView chooses its own windows)
// registers nothing.

#include "StrataRenderingModule.h"
#include "vtkObjectFactory.h"
#include "vtkStrataEGLRenderWindow.h"
#include "vtkVersion.h"

namespace
{
vtkObject* CreateStrataEGLRenderWindow()
{
  return vtkStrataEGLRenderWindow::New();
}

class vtkStrataObjectFactory : public vtkObjectFactory
{
public:
  static vtkStrataObjectFactory* New()
  {
    auto* f = new vtkStrataObjectFactory;
    f->InitializeObjectBase();
    return f;
  }
  vtkTypeMacro(vtkStrataObjectFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override { return "Strata: offscreen EGL render window"; }

protected:
  vtkStrataObjectFactory()
  {
    this->RegisterOverride("vtkRenderWindow",
      "vtkStrataEGLRenderWindow",
      "Offscreen EGL window (no X server)",
      1,
      CreateStrataEGLRenderWindow);
  }
};

unsigned int StrataFactoryCount = 0;
}

STRATARENDERING_EXPORT void StrataRendering_AutoInit_Construct()
{
#if !STRATA_OVERRIDE_RENDER_WINDOW
  // Built into a host that owns its windows (the ParaView plugin): never replace them.
  return;
#endif
  if (++StrataFactoryCount != 1 || !vtkStrataEGLRenderWindow::ShouldOverrideRenderWindow())
  {
    return;
  }
  // Factories answer in registration order; VTK's X window may already be registered (module
  // initialisation order is alphabetical), so switch it off rather than rely on being first.
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow", "vtkXOpenGLRenderWindow");
  vtkStrataObjectFactory* factory = vtkStrataObjectFactory::New();
  vtkObjectFactory::RegisterFactory(factory);
  factory->Delete();
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataClientSide.h"
#include "vtkCallbackCommand.h"
#include "vtkClientServerStream.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkInteractorStyle.h"
#include "vtkNew.h"
#include "vtkPVSession.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyIterator.h"
#include "vtkSMProxyManager.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkWeakPointer.h"

#include <cstring>
#include <vector>

namespace
{
/// A view being refined: the timer its interactor runs for it (0: none pending).
struct Refined
{
  vtkWeakPointer<vtkSMRenderViewProxy> View;
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  int Timer = 0;
};

struct Watch
{
  vtkNew<vtkCallbackCommand> OnSession;  // the active session changed
  vtkNew<vtkCallbackCommand> OnRegister; // a session registered a proxy
  vtkNew<vtkCallbackCommand> OnProperty; // a watched display's property changed
  vtkNew<vtkCallbackCommand> OnRender;   // a watched view rendered
  vtkNew<vtkCallbackCommand> OnTimer;    // an interactor's timer fired
  std::vector<vtkWeakPointer<vtkSMSessionProxyManager>> Sessions;
  std::vector<vtkWeakPointer<vtkRenderWindowInteractor>> Interactors; // observed for timers
  std::vector<Refined> Views;
  unsigned long Renders = 0;
  bool Busy = false; // colouring changes properties of the display being watched
};

Watch* TheWatch = nullptr;

void WatchProxy(vtkSMProxy* proxy, const char* group)
{
  if (!proxy || !group)
    return;
  if (std::strcmp(group, "representations") == 0 &&
      vtkSMPVRepresentationProxy::SafeDownCast(proxy) &&
      proxy->GetProperty("StrataVolumeSampleDistance") && proxy->GetProperty("Representation") &&
      !proxy->HasObserver(vtkCommand::PropertyModifiedEvent, TheWatch->OnProperty))
  {
    proxy->AddObserver(vtkCommand::PropertyModifiedEvent, TheWatch->OnProperty);
    // Registered as a Strata Volume already (a display made with that type).
    vtkStrataClientSide::ColorIfStrataVolume(proxy);
  }
  else if (std::strcmp(group, "views") == 0 && vtkSMRenderViewProxy::SafeDownCast(proxy) &&
           !proxy->HasObserver(vtkCommand::EndEvent, TheWatch->OnRender))
  {
    proxy->AddObserver(vtkCommand::EndEvent, TheWatch->OnRender);
  }
}

void WatchSession(vtkSMSessionProxyManager* pxm)
{
  if (!pxm)
    return;
  for (const auto& known : TheWatch->Sessions)
  {
    if (known == pxm)
      return;
  }
  TheWatch->Sessions.emplace_back(pxm);
  pxm->AddObserver(vtkCommand::RegisterEvent, TheWatch->OnRegister);
  // The views made before the plugin loaded (the GUI's first view).
  vtkNew<vtkSMProxyIterator> views;
  views->SetSessionProxyManager(pxm);
  views->SetModeToOneGroup();
  for (views->Begin("views"); !views->IsAtEnd(); views->Next())
    WatchProxy(views->GetProxy(), "views");
}

void SessionChanged(vtkObject*, unsigned long, void*, void*)
{
  if (vtkSMProxyManager::IsInitialized())
    WatchSession(vtkSMProxyManager::GetProxyManager()->GetActiveSessionProxyManager());
}

void Registered(vtkObject*, unsigned long, void*, void* callData)
{
  const auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(callData);
  if (info && info->Type == vtkSMProxyManager::RegisteredProxyInformation::PROXY)
    WatchProxy(info->Proxy, info->GroupName);
}

void PropertyChanged(vtkObject* caller, unsigned long, void*, void* callData)
{
  const char* name = static_cast<const char*>(callData);
  if (!TheWatch->Busy && name && std::strcmp(name, "Representation") == 0)
    vtkStrataClientSide::ColorIfStrataVolume(vtkSMProxy::SafeDownCast(caller));
}

Refined& EntryOf(vtkSMRenderViewProxy* view)
{
  auto& views = TheWatch->Views;
  for (auto it = views.begin(); it != views.end();)
    it = it->View ? it + 1 : views.erase(it);
  for (auto& entry : views)
  {
    if (entry.View == view)
      return entry;
  }
  views.push_back(Refined{ view, nullptr, 0 });
  return views.back();
}

/// Arms `entry`'s one-shot timer on its view's interactor (none: the view has no event loop).
void Arm(Refined& entry)
{
  vtkRenderWindowInteractor* interactor = entry.View ? entry.View->GetInteractor() : nullptr;
  if (!interactor || entry.Timer != 0)
    return;
  bool observed = false;
  for (const auto& known : TheWatch->Interactors)
    observed = observed || known == interactor;
  if (!observed)
  {
    TheWatch->Interactors.emplace_back(interactor);
    interactor->AddObserver(vtkCommand::TimerEvent, TheWatch->OnTimer);
  }
  entry.Interactor = interactor;
  entry.Timer = interactor->CreateOneShotTimer(vtkStrataClientSide::RefineDelay);
}

void Rendered(vtkObject* caller, unsigned long, void*, void* callData)
{
  auto* view = vtkSMRenderViewProxy::SafeDownCast(caller);
  const bool interactive = callData && *static_cast<int*>(callData) != 0;
  if (!view || interactive || !view->GetInteractor())
    return;
  Refined& entry = EntryOf(view);
  if (entry.Timer == 0 && !vtkStrataClientSide::IsConverged(view))
    Arm(entry);
}

void TimerFired(vtkObject* caller, unsigned long, void*, void* callData)
{
  const int timer = callData ? *static_cast<int*>(callData) : 0;
  for (auto& entry : TheWatch->Views)
  {
    if (entry.Timer == 0 || entry.Timer != timer || entry.Interactor != caller)
      continue;
    entry.Timer = 0;
    auto* style = vtkInteractorStyle::SafeDownCast(entry.Interactor->GetInteractorStyle());
    if (style && style->GetState() != VTKIS_NONE)
    {
      Arm(entry); // the user is interacting: the interaction's renders come first
      return;
    }
    if (entry.View)
    {
      ++TheWatch->Renders;
      entry.View->StillRender(); // (its end arms the next timer while not converged)
    }
    return;
  }
}

/**
 * The representation's PagingConverged as the process that renders it says (the render server's
 * root; in a builtin session this process). Not UpdatePropertyInformation: ParaView pulls the
 * information properties of a proxy that also lives on the client from the client's copy,
 * which in client-server renders nothing.
 */
bool ConvergedWhereRendered(vtkSMProperty* property)
{
  vtkSMProxy* representation = property ? property->GetParent() : nullptr;
  vtkSMSession* session = representation ? representation->GetSession() : nullptr;
  if (!session)
    return true;
  vtkClientServerStream stream;
  stream << vtkClientServerStream::Invoke << VTKOBJECT(representation) << "GetPagingConverged"
         << vtkClientServerStream::End;
  session->ExecuteStream(vtkPVSession::RENDER_SERVER_ROOT, stream, false);
  int converged = 1;
  return !session->GetLastResult(vtkPVSession::RENDER_SERVER_ROOT).GetArgument(0, 0, &converged) ||
         converged != 0;
}

/// Set up when the library loads into a process (the plugin's, client or server).
struct Installer
{
  Installer() { vtkStrataClientSide::Install(); }
};
const Installer InstallOnLoad;
}

//------------------------------------------------------------------------------
bool vtkStrataClientSide::Install()
{
  if (!vtkSMProxyManager::IsInitialized())
    return false;
  if (!TheWatch)
  {
    TheWatch = new Watch; // lives as long as the process: its observers may fire until exit
    TheWatch->OnSession->SetCallback(SessionChanged);
    TheWatch->OnRegister->SetCallback(Registered);
    TheWatch->OnProperty->SetCallback(PropertyChanged);
    TheWatch->OnRender->SetCallback(Rendered);
    TheWatch->OnTimer->SetCallback(TimerFired);
    vtkSMProxyManager::GetProxyManager()->AddObserver(
      vtkSMProxyManager::ActiveSessionChanged, TheWatch->OnSession);
  }
  SessionChanged(nullptr, 0, nullptr, nullptr);
  return true;
}

//------------------------------------------------------------------------------
bool vtkStrataClientSide::ColorIfStrataVolume(vtkSMProxy* representation)
{
  auto* display = vtkSMPVRepresentationProxy::SafeDownCast(representation);
  vtkSMProperty* type = display ? display->GetProperty("Representation") : nullptr;
  const char* now = type ? vtkSMPropertyHelper(type).GetAsString() : nullptr;
  if (!now || std::strcmp(now, "Strata Volume") != 0 || display->GetUsingScalarColoring())
    return false;
  vtkSMSessionProxyManager* pxm = display->GetSessionProxyManager();
  if (pxm && pxm->GetInLoadXMLState())
    return false; // the state says what to colour by
  vtkSMProperty* array = display->GetProperty("ColorArrayName");
  auto* arrays = array ? array->FindDomain<vtkSMArrayListDomain>() : nullptr;
  if (!arrays || arrays->GetNumberOfStrings() == 0)
    return false;
  unsigned int chosen = 0;
  for (unsigned int i = 0; i < arrays->GetNumberOfStrings(); ++i)
  {
    if (arrays->GetFieldAssociation(i) == vtkDataObject::POINT)
    {
      chosen = i;
      break;
    }
  }
  const bool busy = TheWatch && TheWatch->Busy;
  if (TheWatch)
    TheWatch->Busy = true;
  const bool colored =
    display->SetScalarColoring(arrays->GetString(chosen), arrays->GetFieldAssociation(chosen));
  if (colored)
    display->RescaleTransferFunctionToDataRange(true);
  if (TheWatch)
    TheWatch->Busy = busy;
  return colored;
}

//------------------------------------------------------------------------------
bool vtkStrataClientSide::IsConverged(vtkSMViewProxy* view)
{
  vtkSMProperty* shown = view ? view->GetProperty("Representations") : nullptr;
  if (!shown)
    return true;
  vtkSMPropertyHelper representations(shown);
  for (unsigned int i = 0; i < representations.GetNumberOfElements(); ++i)
  {
    vtkSMProxy* display = representations.GetAsProxy(i);
    vtkSMProperty* type = display ? display->GetProperty("Representation") : nullptr;
    vtkSMProperty* visible = display ? display->GetProperty("Visibility") : nullptr;
    if (!type || !visible || vtkSMPropertyHelper(visible).GetAsInt() == 0)
      continue;
    const char* now = vtkSMPropertyHelper(type).GetAsString();
    const char* converged = !now                                     ? nullptr
                            : std::strcmp(now, "Strata Volume") == 0 ? "StrataVolumePagingConverged"
                            : std::strcmp(now, "Strata Horizons") == 0
                              ? "StrataHorizonsPagingConverged"
                              : nullptr;
    if (converged && !ConvergedWhereRendered(display->GetProperty(converged)))
      return false;
  }
  return true;
}

//------------------------------------------------------------------------------
unsigned long vtkStrataClientSide::GetNumberOfRefinementRenders()
{
  return TheWatch ? TheWatch->Renders : 0;
}

// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * What Strata does in a ParaView client (the GUI, pvpython; in builtin and client-server
 * sessions): two behaviours ParaView 5.11 has no hook for, set up once per client process when
 * the plugin's library loads (a static initialiser; a server, where no proxy manager exists,
 * does nothing). Both watch the proxies every session registers (and the views that exist when
 * the plugin loads).
 *
 * - Default colouring. vtkSMPVRepresentationProxy::SetRepresentationType picks a colour array
 *   only for ParaView's own "Volume" and "Slice", so a pool switched to Strata Volume would keep
 *   Coloring at Solid Color: a box with no transfer function. When a display becomes a Strata
 *   Volume (SetRepresentationType, the GUI's combo box, `Representation = ...`) and colours by
 *   nothing, it is coloured as ParaView colours its Volume: by the first point array of the
 *   Coloring list (else the first array), the transfer function rescaled to the data's range;
 *   the Coloring box shows the array. A display that colours by an array, or a state file being
 *   loaded (it says what to colour by), is left alone.
 *
 * - Progressive refinement. The mappers page a pool while frames are drawn: with no render,
 *   nothing refines. After every still render of a render view that has an event loop (the GUI's
 *   views, pvpython's after Interact()), if one of its visible Strata Volume or Strata Horizons
 *   displays reports PagingConverged 0 (asked of the server that renders: in client-server the
 *   round trip of UpdatePropertyInformation), a one-shot timer of the view's interactor
 *   (RefineDelay ms) renders it again, until all have converged. Interaction keeps priority: a
 *   timer that fires while the user drags the camera waits for the next one, and interactive
 *   renders arm nothing (the still render at the end of an interaction does). Scripts without an
 *   event loop (pvbatch, pvpython's Render) loop on PagingConverged themselves.
 */
#ifndef vtkStrataClientSide_h
#define vtkStrataClientSide_h

class vtkSMProxy;
class vtkSMViewProxy;

namespace vtkStrataClientSide
{
/// Starts watching (idempotent); false where the process has no proxy manager (a server).
bool Install();

/// Milliseconds between a render that left pages in flight and the next one.
constexpr unsigned long RefineDelay = 40;

/**
 * Default colouring: colours `representation` by its first point array when it is a Strata
 * Volume that colours by nothing. True when it coloured.
 */
bool ColorIfStrataVolume(vtkSMProxy* representation);

/// Whether every visible Strata Volume and Strata Horizons display of `view` has converged.
bool IsConverged(vtkSMViewProxy* view);

/// Renders done by the refinement timers so far, in all views (for tests and notes).
unsigned long GetNumberOfRefinementRenders();
}

#endif

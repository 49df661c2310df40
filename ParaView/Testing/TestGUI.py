# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""Run by the ParaView GUI (see RunGUI.cmake), as a GUI user's Python shell would.

STRATA_GUI_MODE=load (paraview --script=TestGUI.py --exit): loads the plugin, shows a page
pool with the Strata Volume representation and writes what it found to $STRATA_GUI_RESULT
(the driver asserts it).

STRATA_GUI_MODE=refine or refine-cs (no --exit: the GUI's event loop runs; refine-cs: the GUI
is the client of a pvserver, where the plugin is loaded too): the paged_volume scene of
TestPlugin.py (its pool, view and transfer functions) in the GUI's own view, rendered once by
the script; then nobody touches anything. A timer of the view's interactor watches (never
rendering) until the view has stopped rendering for a second, then takes the view's image and
writes how many renders the view made after the first, how long the refinement took, whether
PagingConverged says so (builtin), and the image's largest difference from the standalone C++
rendering (the converged image); then it leaves the GUI.

STRATA_GUI_MODE=resize (no --exit): the pool as Strata Volume in the GUI's view, the main window
resized three times as a user would (X requests: xwindow.py); after each resize has settled,
the window's pixels (what the X server shows, not a re-render) give the volume's size against
the view's height, which must stay (a Strata Volume once vanished on a resize)."""
import json
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403

lines = []


def load():
    LoadPlugin(os.environ["STRATA_PLUGIN"], remote=False, ns=globals())
    reader = StrataPagePool(FileName=os.environ["STRATA_POOL"])
    display = Show(reader)
    lines.append("representations: " + ", ".join(
        t for t in display.GetProperty("Representation").Available if t.startswith("Strata")))
    display.SetRepresentationType("Strata Volume")
    Render()
    display.UpdatePropertyInformation()
    lines.append("volumes in scene: %d" % display.GetPropertyValue(
        "StrataVolumeNumberOfVolumesInScene"))
    lines.append("paged: %d" % display.GetPropertyValue("StrataVolumePaged"))


def finish():
    with open(os.environ["STRATA_GUI_RESULT"], "w") as f:
        f.write("\n".join(lines) + "\n")


def plugin_scenes():
    """TestPlugin.py (its scenes' views and displays, beside this script) with the plugin's
    proxies loaded into it, as the GUI's Python shell would load them."""
    sys.path.insert(0, os.path.dirname(os.environ["STRATA_GUI_SCRIPT"]))
    import TestPlugin
    LoadPlugin(os.environ["STRATA_PLUGIN"], remote=False, ns=vars(TestPlugin))
    return TestPlugin


def refine():
    TestPlugin = plugin_scenes()
    from strata_png import load_png
    import numpy
    from paraview import servermanager
    remote = servermanager.ActiveConnection.IsRemote()
    if remote:
        LoadPlugin(os.environ["STRATA_PLUGIN"], remote=True, ns=vars(TestPlugin))
    lines.append("session: %s" % ("client-server" if remote else "builtin"))
    work = os.path.dirname(os.environ["STRATA_POOL"])
    with open(os.path.join(work, "paged_volume.json")) as f:
        camera = json.load(f)
    view = GetActiveViewOrCreate("RenderView")
    GetLayout(view).PreviewMode = [int(v) for v in camera["size"]]
    TestPlugin.configure_view(view, camera)
    reader = TestPlugin.StrataPagePool(FileName=os.environ["STRATA_POOL"])
    display = TestPlugin.show_paged_tooth(reader, view)
    # The C++ view's camera, not the one the GUI's first render would reset to.
    import paraview.simple
    paraview.simple._DisableFirstRenderCameraReset()
    TestPlugin.configure_view(view, camera)
    renders = []
    view.SMProxy.AddObserver("EndEvent", lambda *unused: renders.append(time.time()))
    start = time.time()
    Render(view)
    interactor = view.GetInteractor()
    state = {"polls": 0}

    def poll(caller, event):
        # Settled: the view stopped rendering by itself (the plugin renders again only while
        # the render server's PagingConverged says 0), a second after its last render.
        now = time.time()
        settled = len(renders) > 1 and now - renders[-1] > 1.0
        if not settled and now - start < 120.0:
            return
        made = len(renders) - 1
        took = renders[-1] - start
        lines.append("settled without interaction: %d" % settled)
        if not remote:
            # (In a builtin session the information property is this process's, the one that
            # renders; in client-server it is the client's copy.)
            display.UpdatePropertyInformation()
            lines.append("paging converged: %d" % display.GetPropertyValue(
                "StrataVolumePagingConverged"))
        path = os.path.join(work, "gui_refined.png")
        SaveScreenshot(path, view, ImageResolution=[int(v) for v in camera["size"]],
                       TransparentBackground=0)
        image = load_png(path)[1].astype(int)
        reference = load_png(os.path.join(work, "cxx.png"))[1].astype(int)
        worst = int(numpy.abs(image - reference).max()) if image.shape == reference.shape else -1
        lines.append("renders after the first: %d in %.2f s" % (made, took))
        lines.append("against the C++ image: max %d of 255" % worst)
        finish()
        os._exit(0)

    interactor.AddObserver("TimerEvent", poll)
    interactor.CreateRepeatingTimer(250)


def volume_measure(image):
    """Of a capture of the main window (the view's background pure green): the view's height
    (the rows its green spans), and the volume's pixels (the others inside the green's box)
    over that height squared, which a resize leaves as it was (the vertical view angle is
    fixed: the volume's size on screen follows the view's height)."""
    import numpy
    green = (image[:, :, 1] > 200) & (image[:, :, 0] < 60) & (image[:, :, 2] < 60)
    rows = numpy.nonzero(green.any(axis=1))[0]
    columns = numpy.nonzero(green.any(axis=0))[0]
    if len(rows) == 0:
        return 0, 0, 0.0
    box = green[rows[0]:rows[-1] + 1, columns[0]:columns[-1] + 1]
    height = rows[-1] - rows[0] + 1
    volume = int(box.size - numpy.count_nonzero(box))
    return int(height), volume, volume / float(height * height)


def resize():
    """The window resized (as a user drags its corner) between settled renders: the volume
    stays, as large against the view's height as before."""
    TestPlugin = plugin_scenes()
    import xwindow
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 1.0, 0.0]
    reader = TestPlugin.StrataPagePool(FileName=os.environ["STRATA_POOL"])
    TestPlugin.show_paged_tooth(reader, view)
    renders = []
    view.SMProxy.AddObserver("EndEvent", lambda *unused: renders.append(time.time()))
    Render(view)
    display = xwindow.Display()
    window = display.find("ParaView")
    sizes = [None, (900, 600), (1400, 900), (700, 460)]
    state = {"step": 0, "since": time.time(), "ratios": []}

    def poll(caller, event):
        now = time.time()
        quiet = not renders or now - renders[-1] > 1.0
        if now - state["since"] < 2.0 or not quiet:
            if now - state["since"] < 60.0:
                return
        height, volume, ratio = volume_measure(display.capture(window))
        width_height = display.size(window)[:2]
        lines.append("window %d x %d: view %d px high, volume %d px, %.4f of the height squared "
                     "(%d renders so far)" % (width_height[0], width_height[1], height, volume,
                                              ratio, len(renders)))
        state["ratios"].append(ratio)
        state["step"] += 1
        if state["step"] < len(sizes):
            display.resize(window, *sizes[state["step"]])
            state["since"] = time.time()
            return
        first = state["ratios"][0]
        kept = first > 0.02 and all(0.8 * first <= r <= 1.25 * first for r in state["ratios"])
        lines.append("the volume kept its size through the resizes: %d" % kept)
        display.close()
        finish()
        os._exit(0)

    interactor = view.GetInteractor()
    interactor.AddObserver("TimerEvent", poll)
    interactor.CreateRepeatingTimer(250)


def screenshot():
    """Not a test: the README's picture of the GUI ($STRATA_GUI_SCREENSHOT), a paged pool
    switched to Strata Volume (coloured by its scalars by default), once it has settled."""
    TestPlugin = plugin_scenes()
    import xwindow
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    view = GetActiveViewOrCreate("RenderView")
    reader = TestPlugin.StrataPagePool(FileName=os.environ["STRATA_POOL"])
    SetActiveSource(reader)
    display = Show(reader, view)
    display.SetRepresentationType("Strata Volume")
    opacity = GetOpacityTransferFunction(reader.PointData.keys()[0])
    opacity.Points = [v for o in TestPlugin.TOOTH_OPACITIES for v in (o[0], o[1], 0.5, 0.0)]
    view.CameraPosition = [285.1, -282.8, 138.1]
    view.CameraFocalPoint = [51.0, 46.5, 80.0]
    view.CameraViewUp = [0.0, 0.17, 0.98]
    ResetCamera(view)
    Render(view)
    started = time.time()

    def poll(caller, event):
        if time.time() - started < 8.0:
            return
        x = xwindow.Display()
        pixels = x.capture(x.find("ParaView"))
        x.close()
        image = vtkImageData()
        image.SetDimensions(pixels.shape[1], pixels.shape[0], 1)
        image.GetPointData().SetScalars(numpy_to_vtk(pixels[::-1].reshape(-1, 3).copy(), deep=1))
        writer = vtkPNGWriter()
        writer.SetInputData(image)
        writer.SetFileName(os.environ["STRATA_GUI_SCREENSHOT"])
        writer.Write()
        lines.append("screenshot: " + os.environ["STRATA_GUI_SCREENSHOT"])
        finish()
        os._exit(0)

    interactor = view.GetInteractor()
    interactor.AddObserver("TimerEvent", poll)
    interactor.CreateRepeatingTimer(250)


try:
    if os.environ.get("STRATA_GUI_MODE") == "screenshot":
        screenshot()
    elif os.environ.get("STRATA_GUI_MODE") == "resize":
        resize()
    elif os.environ.get("STRATA_GUI_MODE", "load").startswith("refine"):
        refine()
    else:
        load()
        finish()
except Exception as error:  # the GUI swallows exceptions: report them to the driver
    lines.append("error: %s" % error)
    finish()
    if os.environ.get("STRATA_GUI_MODE", "load") != "load":
        os._exit(1)

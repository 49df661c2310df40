# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""pvbatch (or pvpython) test of Strata's ParaView plugin.

    pvbatch TestPlugin.py --plugin Strata.so --scene <paged_volume|paged_horizons|time_series|...>
                          [--work <folder>] [--tolerance <max channel difference>]

paged_volume, paged_horizons, horizons, volumes, hybrid and time_series: the folder holds what `StrataExamples <scene>
<folder>/cxx_<scene>.png --work <folder> --camera <folder>/<scene>.json --keep-pools` wrote: the
standalone C++ rendering, its view and the page pools. The script opens the pools with the
plugin's reader, shows them through Strata's representations from the same view, renders until
the paging has settled, and asserts: the pipeline read only the pools' coarsest level (one page
each), the data are paged by the representation, overlapping volumes share one ray cast, the visible bounds equal the C++ ones, the
render window is ParaView's own, and the image matches the C++ one (max channel difference and
number of differing pixels printed; the maximum asserted).

components: volumes of several components (written here) through Strata Volume and ParaView's
own Volume representation, with Map Scalars and Multi Components Mapping.

proxies: loads the plugin and lists its proxies (sources, filters, representations), asserting
that each is there.
"""
import argparse
import json
import os
import time
import sys

import paraview.simple
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting interface)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from strata_png import load_png  # noqa: E402 (beside this script)
from strata_colors import color_by_depth  # noqa: E402

STRATA_PROXIES = {
    "sources": ["StrataPagePoolReader", "StrataIrapGridReader", "StrataNumpyGridReader",
                "StrataHorizonColumnReader", "StrataAsciiGridReader", "StrataSegyVolumeReader",
                "StrataStreamingMetaImageReader", "StrataHybridVolumeReader"],
    "filters": ["StrataStackHorizons", "StrataHorizonVolumeSampler"],
    "representations": ["StrataVolumeRepresentation", "StrataHorizonsRepresentation",
                        "StrataHybridRepresentation"],
}
REEK = ["reek_01_topreek_rota", "reek_02_midreek_rota", "reek_03_lowreek_rota",
        "reek_04_basereek_rota"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def list_proxies():
    manager = servermanager.ProxyManager().SMProxyManager
    for group, names in STRATA_PROXIES.items():
        for name in names:
            proxy = manager.GetPrototypeProxy(group, name)
            label = proxy.GetXMLLabel() if proxy else None
            check(proxy is not None, "proxy %s/%s (%s) is defined" % (group, name, label))
    # The Python names of the readers and the filter, from their labels.
    for name in ["StrataPagePool", "StrataIrapBinaryGrid", "StrataNumPyHorizon",
                 "StrataHorizonColumns", "StrataTextHorizonGrid", "StrataSEGYVolume",
                 "StrataHybridVolume", "StackHorizons", "SampleVolumeAlongHorizon"]:
        check(name in globals(), "paraview.simple has %s()" % name)


def setup_view(camera):
    view = CreateView("RenderView")
    configure_view(view, camera)
    paraview.simple._DisableFirstRenderCameraReset()
    return view


def configure_view(view, camera):
    """`view` as the standalone scene's: size, background, VTK's default headlight, camera."""
    view.ViewSize = [int(v) for v in camera["size"]]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = camera["background"]
    view.UseFXAA = 0
    view.UseToneMapping = 0
    # The standalone scenes have VTK's default light: one white headlight of intensity 1.
    view.UseLight = 0
    light = AddLight(view=view)
    light.Coords = "Headlight"
    light.Intensity = 1.0
    view.CameraPosition = camera["position"]
    view.CameraFocalPoint = camera["focal_point"]
    view.CameraViewUp = camera["view_up"]
    view.CameraViewAngle = camera["view_angle"][0]
    view.CameraParallelProjection = 0


def render_until_converged(view, display, prefix, frames=500):
    """Renders until the representation's PagingConverged is 1 (the pages arrive on worker
    threads between renders)."""
    for frame in range(1, frames + 1):
        Render(view)
        display.UpdatePropertyInformation()
        if display.GetPropertyValue(prefix + "PagingConverged") == 1:
            return frame
        time.sleep(0.02)
    return frames + 1


def compare(view, camera, work, scene, tolerance):
    # The camera as the C++ view had it (ParaView resets the clipping range on render).
    view.CameraPosition = camera["position"]
    view.CameraFocalPoint = camera["focal_point"]
    view.CameraViewUp = camera["view_up"]
    Render(view)
    active = view.GetActiveCamera()
    print("camera: position %s, view angle %.6g, clipping range %s" % (
        ["%.6g" % v for v in active.GetPosition()], active.GetViewAngle(),
        ["%.6g" % v for v in active.GetClippingRange()]))
    renderer = view.GetRenderer()
    bounds = [0.0] * 6
    renderer.ComputeVisiblePropBounds(bounds)
    expected = camera["bounds"]
    scale = max(abs(b) for b in expected) or 1.0
    error = max(abs(a - b) for a, b in zip(bounds, expected)) / scale
    print("bounds: ParaView %s, C++ %s (relative difference %.2e)" % (
        ["%.6g" % b for b in bounds], ["%.6g" % b for b in expected], error))
    check(error < 1e-9, "the visible bounds equal the standalone scene's")
    window = view.GetRenderWindow()
    check(window.GetClassName() != "vtkStrataEGLRenderWindow",
          "ParaView keeps its own render window (%s)" % window.GetClassName())

    import numpy
    out = os.path.join(work, "pv_%s.png" % scene)
    SaveScreenshot(out, view, ImageResolution=view.ViewSize, TransparentBackground=0)
    dims_pv, pv = load_png(out)
    dims_cxx, cxx = load_png(os.path.join(work, "cxx_%s.png" % scene))
    check(dims_pv == dims_cxx, "image sizes match (%s, %s)" % (dims_pv[:2], dims_cxx[:2]))
    if dims_pv != dims_cxx:
        return
    difference = numpy.abs(pv - cxx)
    background = numpy.round(numpy.array(camera["background"]) * 255).astype(numpy.int32)
    covered = numpy.count_nonzero(numpy.any(numpy.abs(cxx - background) > 2, axis=1))
    print("%s: %s, max channel difference %d of 255, %d of %d pixels differ, %d pixels covered"
          % (scene, out, difference.max(), numpy.count_nonzero(difference.max(axis=1)),
             len(difference), covered))
    check(covered > len(difference) // 10, "the scene covers more than a tenth of the view")
    check(difference.max() <= tolerance,
          "ParaView's image equals the standalone one within %d of 255" % tolerance)


def check_pool_reads(reader, what):
    reader.UpdatePropertyInformation()
    levels = reader.GetPropertyValue("NumberOfLevels")
    level = reader.GetPropertyValue("LevelRead")
    pages = reader.GetPropertyValue("NumberOfPagesRead")
    print("%s: %d levels, the pipeline read level %d, %d page(s)" % (what, levels, level, pages))
    # (0 pages: ParaView's update found the level already read.)
    check(levels > 1 and level == levels - 1 and pages <= 1,
          "%s: ParaView's pipeline read only the coarsest level (one page)" % what)


def show_paged_tooth(reader, view):
    """The paged_volume scene's display (a small atlas, few pages a frame: many frames)."""
    display = show_volume(reader, view, TOOTH_COLORS, TOOTH_OPACITIES)
    display.StrataVolumeSampleDistance = 0.5
    display.StrataVolumeAtlasBudget = 16
    display.StrataVolumePagesPerFrame = 8
    return display


def paged_volume(args, camera):
    reader = StrataPagePool(FileName=os.path.join(args.work, "tooth.spp"))
    view = setup_view(camera)
    display = show_paged_tooth(reader, view)
    check(display.StrataVolumeScalarStorage == "16-bit",
          "the default storage is 16-bit (the tooth in R16, as the C++ mapper's default)")
    frames = render_until_converged(view, display, "StrataVolume")
    print("paged volume settled after %d renders" % frames)
    check(frames <= 500, "the paged volume settles")
    display.UpdatePropertyInformation()
    check(display.GetPropertyValue("StrataVolumePaged") == 1,
          "the volume is paged by the representation")
    check(display.GetPropertyValue("StrataVolumeNumberOfVolumesInScene") == 1,
          "one volume in the view's ray cast")
    check_pool_reads(reader, "tooth.spp")
    compare(view, camera, args.work, "paged_volume", args.tolerance)


def time_series(args, camera):
    """A paged time series (StrataExamples time_series: the tooth fading over four steps at
    uneven times): the reader's TimeStepFiles give ParaView the steps' times, the animation
    plays them, and the representation pages the step the view's time selects. Asserted per
    step: the step shown, its image against the C++ one, and that the step after it in
    playback order was prefetched while it was shown, so that the switch to it waited on the
    disk in no frame (I/O-wait frames stay at their count after the first step)."""
    with open(os.path.join(args.work, "time_series_steps.json")) as f:
        steps = json.load(f)
    times = [s["time"] for s in steps]
    reader = StrataPagePool(TimeStepFiles=[v for s in steps for v in (s["file"], repr(s["time"]))])
    reader.UpdatePipelineInformation()
    check(list(reader.TimestepValues) == times,
          "the reader reports the series' times %s (%s)" % (times, list(reader.TimestepValues)))
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    check(list(GetTimeKeeper().TimestepValues) == times, "the animation has the series' times")
    view = setup_view(camera)
    display = show_volume(reader, view, TOOTH_COLORS, TOOTH_OPACITIES)
    display.StrataVolumeSampleDistance = 0.5
    display.StrataVolumeAtlasBudget = 16
    display.StrataVolumePagesPerFrame = 8
    waits = None
    for k, t in enumerate(times):
        scene.AnimationTime = t
        frames = render_until_converged(view, display, "StrataVolume")
        display.UpdatePropertyInformation()
        shown = display.GetPropertyValue("StrataVolumeTimeStep")
        io_waits = display.GetPropertyValue("StrataVolumeIoWaitFrames")
        print("time %g: step %d shown, settled after %d renders, %d I/O-wait frames in all"
              % (t, shown, frames, io_waits))
        check(frames <= 500 and shown == k, "time %g shows step %d, settled" % (t, k))
        check(display.GetPropertyValue("StrataVolumePaged") == 1, "step %d is paged" % k)
        if waits is not None:
            check(io_waits == waits, "the switch to step %d waited on the disk in no frame "
                  "(%d I/O-wait frames, %d before)" % (k, io_waits, waits))
        waits = io_waits
        compare(view, camera, args.work, "time_series_%d" % k, args.tolerance)
        if k + 1 < len(times):
            # The workers prefetch the next step's pages of every brick held between renders.
            for _ in range(500):
                display.UpdatePropertyInformation()
                resident = display.GetPropertyValue("StrataVolumeNextStepPagesResident")
                wanted = display.GetPropertyValue("StrataVolumeNextStepPagesWanted")
                if wanted > 0 and resident == wanted:
                    break
                time.sleep(0.02)
                Render(view)
            print("step %d: %d of the %d pages held prefetched for step %d"
                  % (k, resident, wanted, k + 1))
            check(wanted > 0 and resident == wanted, "step %d prefetched" % (k + 1))


def show_volume(reader, view, colors, opacities):
    """A Strata Volume of `reader` with its own transfer functions ((value, r, g, b) and
    (value, opacity) points, linear), as the C++ scenes' VolumeProperty builds them."""
    display = Show(reader, view)
    display.SetRepresentationType("Strata Volume")
    array = reader.PointData.keys()[0]
    ColorBy(display, ("POINTS", array))
    lut = GetColorTransferFunction(array)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = [v for c in colors for v in c]
    opacity = GetOpacityTransferFunction(array)
    opacity.Points = [v for o in opacities for v in (o[0], o[1], 0.5, 0.0)]
    display.InterpolationType = "Linear"
    display.ScalarOpacityUnitDistance = 1.0
    return display


TOOTH_COLORS = [(0, 0.5, 0.5, 0.5), (140, 0.8, 0.35, 0.25), (200, 1.0, 0.9, 0.8), (255, 1, 1, 1)]
TOOTH_OPACITIES = [(0, 0.0), (110, 0.0), (150, 0.03), (255, 0.5)]


def compare_in_stages(view, camera, args, scene, displays, prefix):
    """The scene in each ray-casting stage against the same reference: the stage the render
    used is the one asked for; then Auto, which reports its probe of this device."""
    for value, name in ((1, "Fragment"), (2, "Compute")):
        for display in displays:
            setattr(display, prefix + "Stage", name)
        Render(view)
        displays[0].UpdatePropertyInformation()
        used = displays[0].GetPropertyValue(prefix + "StageInUse")
        check(used == value, "%s: rendered in the %s stage (%d)" % (scene, name, used))
        compare(view, camera, args.work, scene, args.tolerance)
    for display in displays:
        setattr(display, prefix + "Stage", "Auto")
    Render(view)
    displays[0].UpdatePropertyInformation()
    ratio = displays[0].GetPropertyValue(prefix + "StageProbeRatio")
    used = displays[0].GetPropertyValue(prefix + "StageInUse")
    print("%s: Auto's probe, compute / fragment %.3f; chose %s" %
          (scene, ratio, {1: "Fragment", 2: "Compute"}.get(used, "?")))
    check(ratio > 0 and used == (2 if ratio < 1 else 1),
          "%s: Auto took the stage its probe measured faster" % scene)


def volumes(args, camera):
    """Two overlapping volumes, each with its own transfer function, in one ray cast: the
    tooth (ParaView's own NRRD reader) and the shell around it (a .vti)."""
    tooth = OpenDataFile(os.path.join(args.data, "volumes", "tooth.nrrd"))
    shell = OpenDataFile(os.path.join(args.work, "shell.vti"))
    view = setup_view(camera)
    first = show_volume(tooth, view, TOOTH_COLORS, TOOTH_OPACITIES)
    first.StrataVolumeSampleDistance = 0.5
    second = show_volume(shell, view, [(0, 0.1, 0.3, 0.9), (255, 0.3, 0.9, 1.0)],
                         [(0, 0.0), (120, 0.0), (255, 0.08)])
    Render(view)
    for display in (first, second):
        display.UpdatePropertyInformation()
        check(display.GetPropertyValue("StrataVolumeNumberOfVolumesInScene") == 2,
              "both volumes in the view's one ray cast")
    compare(view, camera, args.work, "volumes", args.tolerance)
    compare_in_stages(view, camera, args, "volumes", [first, second], "StrataVolume")
    # Hiding one leaves the other alone in the ray cast.
    Hide(shell, view)
    Render(view)
    first.UpdatePropertyInformation()
    check(first.GetPropertyValue("StrataVolumeNumberOfVolumesInScene") == 1,
          "hiding the shell leaves the tooth alone")
    # ParaView's own Transforming properties move a Strata Volume (they once reached only
    # StrataVolumePosition, and display.Position left it where it was).
    before = [0.0] * 6
    view.GetRenderer().ComputeVisiblePropBounds(before)
    first.Position = [40.0, 0.0, 0.0]
    first.Scale = [1.0, 2.0, 1.0]
    Render(view)
    after = [0.0] * 6
    view.GetRenderer().ComputeVisiblePropBounds(after)
    print("tooth bounds %s, moved by Position and Scale: %s" % (before, after))
    check(abs(after[0] - before[0] - 40.0) < 1e-6 and abs(after[1] - before[1] - 40.0) < 1e-6 and
          abs((after[3] - after[2]) - 2.0 * (before[3] - before[2])) < 1e-6,
          "display.Position and display.Scale move and scale the Strata Volume")


def hybrid(args, camera):
    """The tooth's hybrid point + volume representation, read from the .shv the C++ scene wrote.

    Under mpirun (ParaView-hybrid_2ranks) each rank draws its box of the scene (the points whose
    centres lie in it, the volume clipped to it) and IceT blends the two: against the one-process
    C++ image the boxes order points and volume by box as well as by depth slab, up to one slab's
    ordering error apart (TestHybridVolumeMapper's Region: 5.5 of 255), so the bound there is 6
    (measured 4; every rank drawing the whole scene, as before the region, gave 255)."""
    reader = StrataHybridVolume(FileName=os.path.join(args.work, "tooth.shv"))
    view = setup_view(camera)
    display = Show(reader, view)
    display.SetRepresentationType("Strata Hybrid")
    ColorBy(display, ("POINTS", "LowResolution"))
    lut = GetColorTransferFunction("LowResolution")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = [v for c in TOOTH_COLORS for v in c]
    opacity = GetOpacityTransferFunction("LowResolution")
    opacity.Points = [v for o in TOOTH_OPACITIES for v in (o[0], o[1], 0.5, 0.0)]
    display.StrataHybridScalarOpacityFunction = opacity
    display.StrataHybridInterpolationType = "Linear"
    display.StrataHybridScalarOpacityUnitDistance = 1.0
    display.StrataHybridPointShape = "Gaussian splats"
    display.StrataHybridSampleDistance = 0.5
    Render(view)
    display.UpdatePropertyInformation()
    drawn = display.GetPropertyValue("StrataHybridNumberOfPointsDrawn")
    print("hybrid: %d points drawn" % drawn)
    check(drawn > 0, "the hybrid representation draws its points")
    compare(view, camera, args.work, "hybrid", args.tolerance)
    display.StrataHybridStage = "Compute"
    Render(view)
    display.UpdatePropertyInformation()
    check(display.GetPropertyValue("StrataHybridStageInUse") == 2,
          "the hybrid's volume part rendered in the compute stage")
    compare(view, camera, args.work, "hybrid", args.tolerance)


def show_reek(stack, view, paged, value_range=None):
    display = Show(stack, view)
    display.SetRepresentationType("Strata Horizons")
    display.StrataHorizonsHeightScale = -1.0
    color_by_depth(display, stack, value_range)
    display.StrataHorizonsScale = [1, 1, 8]
    display.StrataHorizonsSpecular = 0.2
    if paged:
        display.StrataHorizonsPagesPerFrame = 16
    return display


def horizons(args, camera):
    """The Reek stack in core: four Irap binary grids stacked and ray cast in one pass."""
    readers = [StrataIrapBinaryGrid(FileName=os.path.join(args.data, "horizons", name + ".gri"))
               for name in REEK]
    view = setup_view(camera)
    display = show_reek(StackHorizons(Input=readers), view, False)
    Render(view)
    display.UpdatePropertyInformation()
    check(display.GetPropertyValue("StrataHorizonsNumberOfHorizons") == 4,
          "four horizons in the stack")
    check(display.GetPropertyValue("StrataHorizonsNumberOfPagedHorizons") == 0, "none paged")
    compare(view, camera, args.work, "horizons", args.tolerance)
    compare_in_stages(view, camera, args, "horizons", [display], "StrataHorizons")


def paged_horizons(args, camera):
    readers = [StrataPagePool(FileName=os.path.join(args.work, name + ".spp")) for name in REEK]
    view = setup_view(camera)
    # The colour map over the horizons' full range, the grids' the pools were made from.
    grids = StackHorizons(Input=[StrataIrapBinaryGrid(
        FileName=os.path.join(args.data, "horizons", name + ".gri")) for name in REEK])
    grids.UpdatePipeline()
    full = grids.PointData[grids.PointData.keys()[0]].GetRange()
    display = show_reek(StackHorizons(Input=readers), view, True, full)
    frames = render_until_converged(view, display, "StrataHorizons")
    print("paged horizons settled after %d renders" % frames)
    check(frames <= 500, "the paged stack settles")
    display.UpdatePropertyInformation()
    check(display.GetPropertyValue("StrataHorizonsNumberOfHorizons") == 4,
          "four horizons in the stack")
    check(display.GetPropertyValue("StrataHorizonsNumberOfPagedHorizons") == 4,
          "all four paged by the representation")
    for name, reader in zip(REEK, readers):
        check_pool_reads(reader, name + ".spp")
    compare(view, camera, args.work, "paged_horizons", args.tolerance)


def write_component_images(work):
    """rgba.vti: 40^3 unsigned char RGBA (colour ramps along x, y and z, opacity a ball) and
    two.vti: two float components (a colour scalar, and the ball as opacity)."""
    import numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    from vtkmodules.util.numpy_support import numpy_to_vtk
    n = 40
    z, y, x = numpy.mgrid[0:n, 0:n, 0:n].astype(numpy.float64)
    ball = numpy.clip(1.0 - numpy.sqrt((x - 19.5) ** 2 + (y - 19.5) ** 2 + (z - 19.5) ** 2) / 18.0,
                      0.0, 1.0)
    rgba = numpy.stack([x * 6.5, y * 6.5, 255.0 - z * 6.5, ball * 255.0], axis=-1)
    two = numpy.stack([x * 6.5, ball * 255.0], axis=-1)
    for name, values, kind in (("rgba", rgba, numpy.uint8), ("two", two, numpy.float32)):
        image = vtkImageData()
        image.SetDimensions(n, n, n)
        array = numpy_to_vtk(values.reshape(-1, values.shape[-1]).astype(kind), deep=1)
        array.SetName(name)
        image.GetPointData().SetScalars(array)
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(image)
        writer.SetFileName(os.path.join(work, name + ".vti"))
        writer.Write()


def screenshot(view, path):
    """Saves the view as `path` and returns its RGB pixels (load_png)."""
    SaveScreenshot(path, view, ImageResolution=view.ViewSize, TransparentBackground=0)
    return load_png(path)[1]


def set_component_functions(display, array, map_scalars, multi):
    """The components scene's colour map and opacity (over [0, 255]) on `display`, shared and
    separate (Multi Components Mapping makes ParaView use a separate colour map), and the
    component mapping."""
    ColorBy(display, ("POINTS", array))
    display.MapScalars = map_scalars
    display.MultiComponentsMapping = multi
    display.InterpolationType = "Linear"
    display.ScalarOpacityUnitDistance = 1.0
    for separate in (False, True):
        lut = GetColorTransferFunction(array, display, separate=separate)
        lut.AutomaticRescaleRangeMode = "Never"
        lut.VectorMode = "Component"
        lut.VectorComponent = 0
        lut.RGBPoints = [0.0, 0.1, 0.2, 0.9, 128.0, 0.9, 0.9, 0.3, 255.0, 0.9, 0.1, 0.1]
        opacity = GetOpacityTransferFunction(array, display, separate=separate)
        opacity.Points = [0.0, 0.0, 0.5, 0.0, 255.0, 0.15, 0.5, 0.0]


def set_vector_mode(display, array, mode, component):
    """The colour maps' (shared and separate) vector mode and component."""
    for separate in (False, True):
        lut = GetColorTransferFunction(array, display, separate=separate)
        lut.VectorMode = mode
        lut.VectorComponent = component


def against_volume(args, view, display, name, what):
    """`display` drawn by ParaView's Volume and by Strata Volume: checks they agree (within
    --tolerance of 255, RMS 1) and returns both images."""
    import numpy
    images = {}
    for representation in ("Volume", "Strata Volume"):
        display.SetRepresentationType(representation)
        if representation == "Strata Volume":
            display.StrataVolumeSampleDistance = 0.25
        Render(view)
        images[representation] = screenshot(
            view, os.path.join(args.work, "%s_%s.png" % (name, representation.replace(" ", ""))))
    difference = numpy.abs(images["Volume"] - images["Strata Volume"])
    rms = float(numpy.sqrt(numpy.mean(difference.astype(numpy.float64) ** 2)))
    covered = numpy.count_nonzero(numpy.any(numpy.abs(images["Volume"] - 128) > 2, axis=1))
    print("%s (%s): Strata Volume against ParaView's Volume: RMS %.3f, max %d of 255, %d pixels "
          "covered" % (name, what, rms, difference.max(), covered))
    check(covered > len(difference) // 10, name + ": the volume covers more than a tenth")
    check(difference.max() <= args.tolerance and rms <= 1.0,
          "%s: Strata Volume draws %s as ParaView's Volume does (max %d, RMS 1)"
          % (name, what, args.tolerance))
    return images


def components(args, camera=None):
    """Volumes of several components follow ParaView's Map Scalars and Multi Components
    Mapping (shared with its own Volume representation): off / on, RGBA and colour + opacity
    (VTK's dependent components), drawn as ParaView's Volume draws them; on / off, the
    components independent."""
    import numpy
    write_component_images(args.work)
    view = CreateRenderView()
    view.ViewSize = [160, 160]
    view.OrientationAxesVisibility = 0
    view.Background = [0.5, 0.5, 0.5]
    view.UseColorPaletteForBackground = 0
    view.CameraPosition = [-45.0, -70.0, 80.0]
    view.CameraFocalPoint = [19.5, 19.5, 19.5]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    for name, map_scalars, multi in (("rgba", 0, 0), ("two", 1, 1)):
        reader = OpenDataFile(os.path.join(args.work, name + ".vti"))
        display = Show(reader, view)
        set_component_functions(display, name, map_scalars, multi)
        images = against_volume(args, view, display, name,
                                "MapScalars %d, MultiComponentsMapping %d" % (map_scalars, multi))
        # The property reaches Strata: the components drawn independent are another image.
        display.MapScalars = 1
        display.MultiComponentsMapping = 0
        Render(view)
        independent = screenshot(view, os.path.join(args.work, name + "_independent.png"))
        apart = float(numpy.sqrt(numpy.mean((independent - images["Strata Volume"]) ** 2.0)))
        print("%s drawn as independent components: RMS %.2f from the dependent image" % (name, apart))
        check(apart > 5.0, name + ": Map Scalars and Multi Components Mapping reach Strata Volume")
        display.MapScalars = map_scalars
        display.MultiComponentsMapping = multi
        Hide(reader, view)
        vector_modes(args, view, name)
        if args.convert:
            paged_components(args, view, name, map_scalars, multi, images["Strata Volume"])
    if args.convert:
        paged_magnitude(args, view, "two")


def vector_modes(args, view, name):
    """Independent components, the colour map's vector mode chooses, as for ParaView's Volume:
    one component (the others weigh 0), or the magnitude (of float data only: ParaView's Volume
    takes an integer array's magnitude in the array's own type, 8 bits for rgba). Each on a
    display of its own: ParaView 5.11's Volume crashes when Map Scalars turns on under a
    component other than 0 (in vtkVolumeInputHelper::UpdateOpacityTransferFunction)."""
    modes = [("Component", 1)] + ([("Magnitude", 0)] if name == "two" else [])
    for mode, component in modes:
        reader = OpenDataFile(os.path.join(args.work, name + ".vti"))
        display = Show(reader, view)
        set_component_functions(display, name, 1, 0)
        set_vector_mode(display, name, mode, component)
        against_volume(args, view, display, "%s_%s%d" % (name, mode, component),
                       "independent, %s %d" % (mode, component))
        set_vector_mode(display, name, "Component", 0)
        Hide(reader, view)
        Delete(reader)


def paged_magnitude(args, view, name):
    """A paged volume of several components has no magnitude (its components page from pools
    of their own): Strata Volume draws the chosen component instead (and warns), the image of
    that component mode."""
    import numpy
    reader = StrataPagePool(FileName=os.path.join(args.work, name + ".spp"))
    display = Show(reader, view)
    display.SetRepresentationType("Strata Volume")
    array = reader.PointData.keys()[0]
    set_component_functions(display, array, 1, 0)
    display.StrataVolumeSampleDistance = 0.25
    shown = {}
    for mode in ("Component", "Magnitude"):
        set_vector_mode(display, array, mode, 1)
        frames = render_until_converged(view, display, "StrataVolume")
        shown[mode] = screenshot(view, os.path.join(args.work, "%s_paged_%s.png" % (name, mode)))
        check(frames <= 500, "%s paged, %s: settles" % (name, mode))
    difference = numpy.abs(shown["Magnitude"] - shown["Component"])
    print("%s paged under Magnitude (component 1 drawn instead): max %d of 255 from the "
          "component 1 image" % (name, difference.max()))
    check(difference.max() == 0, name + " paged: Magnitude draws the chosen component")
    set_vector_mode(display, array, "Component", 0)
    Hide(reader, view)
    Delete(reader)


def paged_components(args, view, name, map_scalars, multi, in_core):
    """The same volume converted by strata-convert to a set of component pools and paged by
    Strata Volume: the in-core image once settled."""
    import subprocess
    import numpy
    pool = os.path.join(args.work, name + ".spp")
    subprocess.run([args.convert, os.path.join(args.work, name + ".vti"), pool, "--page-size",
                    "16"], check=True, stdout=subprocess.DEVNULL)
    reader = StrataPagePool(FileName=pool)
    display = Show(reader, view)
    display.SetRepresentationType("Strata Volume")
    set_component_functions(display, reader.PointData.keys()[0], map_scalars, multi)
    display.StrataVolumeSampleDistance = 0.25
    frames = render_until_converged(view, display, "StrataVolume")
    display.UpdatePropertyInformation()
    paged = screenshot(view, os.path.join(args.work, name + "_paged.png"))
    difference = numpy.abs(paged - in_core)
    print("%s paged from %s and its components' pools: settled after %d renders, against in "
          "core max %d of 255" % (name, pool, frames, difference.max()))
    check(display.GetPropertyValue("StrataVolumePaged") == 1 and frames <= 500,
          name + ": the component pools are paged and settle")
    check(difference.max() <= 1, name + ": paged, the in-core image within 1 of 255")
    Hide(reader, view)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--scene", required=True,
                        choices=["paged_volume", "paged_horizons", "horizons", "volumes", "hybrid",
                                 "time_series", "proxies", "components"])
    parser.add_argument("--work", default=".")
    parser.add_argument("--data", default=".", help="Testing/Data (the volumes scene)")
    parser.add_argument("--tolerance", type=int, default=0)
    parser.add_argument("--convert", default="", help="strata-convert (the components scene)")
    args = parser.parse_args()
    LoadPlugin(args.plugin, remote=False, ns=globals())
    print("ParaView %d.%d, plugin %s" % (GetParaViewVersion().major,
                                         GetParaViewVersion().minor, args.plugin))
    if args.scene == "proxies":
        list_proxies()
    elif args.scene == "components":
        components(args)
    else:
        with open(os.path.join(args.work, args.scene + ".json")) as f:
            camera = json.load(f)
        globals()[args.scene](args, camera)
    print("%d failure(s)" % len(failures))
    if failures:
        # (An exception makes pvbatch exit 1; sys.exit in pvbatch crashes ParaView 5.11's
        # finalisation, with or without Strata.)
        raise RuntimeError("%d check(s) failed: %s" % (len(failures), "; ".join(failures)))


if __name__ == "__main__":
    main()

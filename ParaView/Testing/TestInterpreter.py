# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""pvpython test of Strata's plugin as an interpreter uses ParaView: what the GUI and a script
see of a pool and of the Strata representations, apart from the images of the scenes
(TestPlugin.py).

    pvpython TestInterpreter.py --plugin Strata.so --work <folder> --convert <strata-convert>
                                --check <extent|coloring|panels|state|trace>

extent: a pool's reader declares the level it outputs: ParaView's Outline is the data's box,
  its Surface has every face, at Resolution 0 and 0.5.
translucent_horizons: a stack's top horizon at opacity 0.45 inside a Strata Volume of the view,
  against the same scene drawn by the C++ mappers (the strata package in ParaView's Python).
drape: a horizon sampled in a volume (Sample Volume Along Horizon), stacked with another and
  coloured by the sampled array through Coloring, against the C++ classes' image.
horizon_coloring: Strata Horizons coloured by Coloring (one control): one colour per horizon, the
  heights, another point array of the horizons: three different images.
coloring: a pool switched to Strata Volume colours by its scalars (Coloring shows the array,
  the colour map spans its range), as ParaView's Volume does; Strata Volume draws the array
  Coloring names (a point array, another point array, a cell array) and the chosen array as
  ParaView's Volume draws it.
panels: each Strata representation's properties show only under that representation (the
  GUI's visibility decorators), with labels no other visible property has.
state: a state file with a Strata Volume and its settings reloads (after a session reset) to
  the same image.
trace: a Python trace of opening a pool, switching to Strata Volume and editing its
  properties (as the GUI's Apply traces them) records the Strata properties, and the trace
  replayed in a fresh session draws the same image.
"""
import argparse
import os
import subprocess
import sys

import paraview.simple
from paraview import servermanager, smtrace
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting interface)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from strata_png import load_png  # noqa: E402 (beside this script)

failures = []
SIZE = [160, 160]


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def save_vti(image, path):
    """Writes `image` to `path` (.vti) and returns the path."""
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()
    return path


def write_volume(work):
    """arrays.vti: 33 x 25 x 17 points, spacing 0.5 0.75 1, origin (3, -2, 5), three arrays:
    `a` (point scalars, a ramp along x), `b` (point, a ramp along y) and `c` (cell, the ramp
    of `a` at the cell centres). Returns its path."""
    import numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    dims = (33, 25, 17)
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.SetSpacing(0.5, 0.75, 1.0)
    image.SetOrigin(3.0, -2.0, 5.0)
    k, j, i = numpy.mgrid[0:dims[2], 0:dims[1], 0:dims[0]].astype(numpy.float32)
    ramps = {"a": 255.0 * i / (dims[0] - 1), "b": 255.0 * j / (dims[1] - 1)}
    for name, values in ramps.items():
        array = numpy_to_vtk(values.ravel(), deep=1)
        array.SetName(name)
        image.GetPointData().AddArray(array)
    image.GetPointData().SetActiveScalars("a")
    kc, jc, ic = numpy.mgrid[0:dims[2] - 1, 0:dims[1] - 1, 0:dims[0] - 1].astype(numpy.float32)
    cells = numpy_to_vtk((255.0 * (ic + 0.5) / (dims[0] - 1)).ravel(), deep=1)
    cells.SetName("c")
    image.GetCellData().AddArray(cells)
    return save_vti(image, os.path.join(work, "arrays.vti"))


def make_pool(args):
    """The volume's `a` as a page pool of 8-point pages (levels 0-3)."""
    pool = os.path.join(args.work, "arrays.spp")
    subprocess.run([args.convert, write_volume(args.work), pool, "--page-size", "8"], check=True,
                   stdout=subprocess.DEVNULL)
    return pool


def make_view():
    view = CreateView("RenderView")
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.5, 0.5, 0.5]
    view.CameraPosition = [-30.0, -45.0, 50.0]
    view.CameraFocalPoint = [11.0, 7.0, 13.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    paraview.simple._DisableFirstRenderCameraReset()
    return view


def screenshot(view, path):
    SaveScreenshot(path, view, ImageResolution=view.ViewSize, TransparentBackground=0)
    return load_png(path)[1]


def rms(one, two):
    import numpy
    return float(numpy.sqrt(numpy.mean((one.astype(numpy.float64) - two) ** 2)))


def covered(image):
    """Pixels that differ from the grey background."""
    import numpy
    return int(numpy.count_nonzero(numpy.any(numpy.abs(image.astype(int) - 128) > 2, axis=1)))


def extent(args):
    """Outline and Surface of a pool at two resolutions: the data's box, every face."""
    pool = make_pool(args)
    for resolution in (0.0, 0.5):
        reader = StrataPagePool(FileName=pool, Resolution=resolution)
        reader.UpdatePipeline()
        reader.UpdatePropertyInformation()
        info = reader.GetDataInformation()
        bounds = info.GetBounds()
        dims = [info.GetExtent()[2 * a + 1] - info.GetExtent()[2 * a] + 1 for a in range(3)]
        outline = Outline(Input=reader)
        outline.UpdatePipeline()
        box = outline.GetDataInformation().GetBounds()
        surface = ExtractSurface(Input=reader)
        surface.UpdatePipeline()
        faces = surface.GetDataInformation().GetNumberOfCells()
        expected = 2 * ((dims[0] - 1) * (dims[1] - 1) + (dims[0] - 1) * (dims[2] - 1) +
                        (dims[1] - 1) * (dims[2] - 1))
        true_box = [3.0, 19.0, -2.0, 16.0, 5.0, 21.0]
        print("resolution %g: level %d, %d x %d x %d points, bounds %s, outline %s, surface %d "
              "quads (a closed box of them: %d)" % (
                  resolution, reader.GetPropertyValue("LevelRead"), dims[0], dims[1], dims[2],
                  ["%g" % b for b in bounds], ["%g" % b for b in box], faces, expected))
        check(max(abs(x - y) for x, y in zip(box, true_box)) < 1e-6 and
              max(abs(x - y) for x, y in zip(bounds, true_box)) < 1e-6,
              "resolution %g: the Outline is the data's box" % resolution)
        check(faces == expected and faces > 0,
              "resolution %g: the Surface has all six faces" % resolution)
        Delete(surface)
        Delete(outline)
        Delete(reader)


def coloring(args):
    """The default colouring of a pool, and Strata Volume following Coloring."""
    pool = make_pool(args)
    view = make_view()
    reader = StrataPagePool(FileName=pool)
    display = Show(reader, view)
    check(display.ColorArrayName[1] == "", "a pool shows in solid colour before Strata Volume")
    display.SetRepresentationType("Strata Volume")
    array = reader.PointData.keys()[0]
    lut = GetColorTransferFunction(array)
    shown = display.ColorArrayName
    print("switched to Strata Volume: Coloring %s, colour map over [%g, %g]" % (
        list(shown), lut.RGBPoints[0], lut.RGBPoints[-4]))
    check(shown[0] == "POINTS" and shown[1] == array,
          "switched to Strata Volume, a pool colours by its point scalars")
    data_range = reader.PointData[array].GetRange()
    print("the data ParaView holds (the coarsest level) range over [%g, %g]" % data_range)
    check(abs(lut.RGBPoints[0] - data_range[0]) < 1e-3 and
          abs(lut.RGBPoints[-4] - data_range[1]) < 1e-3,
          "the colour map spans the data's range")
    for frame in range(500):
        Render(view)
        display.UpdatePropertyInformation()
        if display.GetPropertyValue("StrataVolumePagingConverged") == 1:
            break
    check(covered(screenshot(view, os.path.join(args.work, "default.png"))) > 1000,
          "the default Strata Volume draws the data")
    Hide(reader, view)
    # A display that colours by nothing on purpose stays so (Solid Color chosen after).
    ColorBy(display, None)
    display.SetRepresentationType("Outline")
    display.SetRepresentationType("Strata Volume")
    check(display.ColorArrayName[1] == array,
          "switched back to Strata Volume, it colours by the scalars again")

    # Coloring chooses the array: point arrays, a cell array, against ParaView's Volume.
    volume = OpenDataFile(os.path.join(args.work, "arrays.vti"))
    display = Show(volume, view)
    display.SetRepresentationType("Strata Volume")
    check(display.ColorArrayName[1] == "a", "an in-core image colours by its active scalars")
    images = {}
    for association, name in (("POINTS", "a"), ("POINTS", "b"), ("CELLS", "c")):
        ColorBy(display, (association, name))
        lut = GetColorTransferFunction(name)
        lut.AutomaticRescaleRangeMode = "Never"
        lut.RGBPoints = [0.0, 0.1, 0.2, 0.9, 128.0, 0.9, 0.9, 0.3, 255.0, 0.9, 0.1, 0.1]
        opacity = GetOpacityTransferFunction(name)
        opacity.Points = [0.0, 0.0, 0.5, 0.0, 255.0, 0.3, 0.5, 0.0]
        display.StrataVolumeSampleDistance = 0.1
        Render(view)
        images[name] = screenshot(view, os.path.join(args.work, "by_%s.png" % name))
    apart = rms(images["a"], images["b"])
    near = rms(images["a"], images["c"])
    print("Coloring a / b: RMS %.2f apart; cell array c (a at the cell centres) / a: RMS %.2f"
          % (apart, near))
    check(apart > 10.0, "Strata Volume draws the point array Coloring names")
    check(near < 8.0 and covered(images["c"]) > 1000,
          "Strata Volume draws a cell array at the cell centres")
    import numpy
    display.SetRepresentationType("Volume")
    for association, name in (("POINTS", "b"), ("CELLS", "c")):
        ColorBy(display, (association, name))
        Render(view)
        theirs = screenshot(view, os.path.join(args.work, "by_%s_volume.png" % name))
        worst = int(numpy.abs(theirs.astype(int) - images[name]).max())
        print("array %s: Strata Volume against ParaView's Volume: RMS %.2f, max %d of 255"
              % (name, rms(theirs, images[name]), worst))
        # (ParaView's Volume draws cells as voxels over the whole box, its outer half cells
        # clamped to the border cells' values; Strata Volume draws the lattice of the cell
        # centres: the border half cells differ.)
        bound = 1.5 if association == "POINTS" else 6.0
        check(rms(theirs, images[name]) < bound,
              "Strata Volume draws %s as ParaView's Volume does (RMS %g)" % (name, bound))


def write_horizons(work):
    """top.vti and base.vti: 40 x 30 grids, `depth` (the active scalars, planes) and
    `thickness` (a bump), as two horizons of a stack."""
    import numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    j, i = numpy.mgrid[0:30, 0:40].astype(numpy.float32)
    paths = []
    for name, depth in (("top", 10.0 + 0.1 * i), ("base", 20.0 + 0.2 * j)):
        image = vtkImageData()
        image.SetDimensions(40, 30, 1)
        for array_name, values in (("depth", depth),
                                   ("thickness", numpy.exp(-((i - 20) ** 2 + (j - 15) ** 2) / 60.0))):
            array = numpy_to_vtk(values.ravel(), deep=1)
            array.SetName(array_name)
            image.GetPointData().AddArray(array)
        image.GetPointData().SetActiveScalars("depth")
        paths.append(save_vti(image, os.path.join(work, name + ".vti")))
    return paths


def horizon_coloring(args):
    """Strata Horizons coloured by ParaView's Coloring, one control: nothing (one colour per
    horizon), the heights, another point array of the horizons."""
    from strata_colors import color_by_depth
    view = make_view()
    view.CameraPosition = [20.0, -45.0, 75.0]
    view.CameraFocalPoint = [20.0, 15.0, 15.0]
    stack = StackHorizons(Input=[XMLImageDataReader(FileName=[p])
                                 for p in write_horizons(args.work)])
    display = Show(stack, view)
    display.SetRepresentationType("Strata Horizons")
    images = {}
    ColorBy(display, None)
    Render(view)
    images["solid"] = screenshot(view, os.path.join(args.work, "horizons_solid.png"))
    color_by_depth(display, stack)
    Render(view)
    images["depth"] = screenshot(view, os.path.join(args.work, "horizons_depth.png"))
    ColorBy(display, ("POINTS", "thickness"))
    GetColorTransferFunction("thickness").ApplyPreset("Cool to Warm", True)
    Render(view)
    images["thickness"] = screenshot(view, os.path.join(args.work, "horizons_thickness.png"))
    for one, two in (("solid", "depth"), ("solid", "thickness"), ("depth", "thickness")):
        apart = rms(images[one], images[two])
        print("horizons coloured by %s / by %s: RMS %.2f apart" % (one, two, apart))
        check(apart > 5.0, "Coloring %s and %s draw different horizons" % (one, two))
    check(min(covered(image) for image in images.values()) > 2000, "the horizons are drawn")
    print("Coloring shows %s" % list(display.ColorArrayName))
    check(display.ColorArrayName[1] == "thickness", "the Coloring box names what is drawn")


def write_blob(work):
    """blob.vti: 40 x 30 x 40 points (spacing 1, origin 0), `density` a smooth ball around the
    write_horizons stack."""
    import numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    k, j, i = numpy.mgrid[0:40, 0:30, 0:40].astype(numpy.float32)
    values = 255.0 * numpy.exp(-((i - 20) ** 2 + (j - 15) ** 2 + (k - 18) ** 2) / 150.0)
    image = vtkImageData()
    image.SetDimensions(40, 30, 40)
    array = numpy_to_vtk(values.ravel(), deep=1)
    array.SetName("density")
    image.GetPointData().SetScalars(array)
    return save_vti(image, os.path.join(work, "blob.vti"))


BLOB_COLORS = [0.0, 0.2, 0.3, 0.8, 255.0, 1.0, 0.6, 0.2]
BLOB_OPACITIES = [0.0, 0.0, 0.5, 0.0, 255.0, 0.35, 0.5, 0.0]
BLOB_CAMERA = {"size": SIZE, "background": [0.5, 0.5, 0.5], "position": [20.0, -70.0, 60.0],
               "focal_point": [20.0, 15.0, 18.0], "view_up": [0.0, 0.0, 1.0],
               "view_angle": [30.0]}


def blob_view():
    """A view of the blob scenes as the standalone scenes' (TestPlugin.configure_view: VTK's
    default headlight, no FXAA), so that the C++ classes' window draws the same."""
    import TestPlugin
    view = CreateView("RenderView")
    TestPlugin.configure_view(view, BLOB_CAMERA)
    paraview.simple._DisableFirstRenderCameraReset()
    return view


def render_reference(renderer):
    """`renderer` in an offscreen VTK window of the views' size and BLOB_CAMERA (no
    multisampling: the translucent surfaces need texture barriers); its RGB pixels, rows bottom
    to top as load_png gives them."""
    from vtkmodules.vtkRenderingCore import vtkRenderWindow, vtkWindowToImageFilter
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
    renderer.SetBackground(*BLOB_CAMERA["background"])
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(*SIZE)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(BLOB_CAMERA["position"])
    camera.SetFocalPoint(BLOB_CAMERA["focal_point"])
    camera.SetViewUp(BLOB_CAMERA["view_up"])
    camera.SetViewAngle(BLOB_CAMERA["view_angle"][0])
    renderer.ResetCameraClippingRange()
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    return vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)


def reference_translucent(blob, horizons, opacity):
    """The scene drawn by Strata's C++ mappers directly (the strata package in ParaView's
    Python), in a VTK window of the view's size: a Strata volume ray cast with the stack given
    to it as a translucent actor (vtkMultiVolumeRayCastMapper::AddTranslucentActor)."""
    import strata
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkRenderer,
                                             vtkVolume, vtkVolumeProperty)
    reader = vtkXMLImageDataReader()
    reader.SetFileName(blob)
    colors, opacities = vtkColorTransferFunction(), vtkPiecewiseFunction()
    for n in range(0, len(BLOB_COLORS), 4):
        colors.AddRGBPoint(*BLOB_COLORS[n:n + 4])
    for n in range(0, len(BLOB_OPACITIES), 4):
        opacities.AddPoint(*BLOB_OPACITIES[n:n + 4])
    prop = vtkVolumeProperty()
    prop.SetColor(colors)
    prop.SetScalarOpacity(opacities)
    prop.SetInterpolationTypeToLinear()
    prop.SetScalarOpacityUnitDistance(1.0)
    volume_mapper = strata.vtkMultiVolumeRayCastMapper()
    volume_mapper.SetInputConnection(reader.GetOutputPort())
    volume_mapper.SetSampleDistance(0.5)
    volume = vtkVolume()
    volume.SetMapper(volume_mapper)
    volume.SetProperty(prop)
    horizon_mapper = strata.vtkStackedHeightFieldMapper()
    for path in horizons:
        grid = vtkXMLImageDataReader()
        grid.SetFileName(path)
        horizon_mapper.AddInputConnection(grid.GetOutputPort())
    horizon_mapper.SetHorizonOpacity(0, opacity)
    actor = vtkActor()
    actor.SetMapper(horizon_mapper)
    volume_mapper.AddTranslucentActor(actor)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.AddVolume(volume)
    return render_reference(renderer)


def translucent_horizons(args):
    """A stack's top horizon at opacity 0.45 inside a Strata Volume of the same view: the image
    of the C++ mappers composing the same scene, and not the opaque one."""
    blob = write_blob(args.work)
    horizons = write_horizons(args.work)
    view = blob_view()
    volume = XMLImageDataReader(FileName=[blob])
    shown = Show(volume, view)
    shown.SetRepresentationType("Strata Volume")
    ColorBy(shown, ("POINTS", "density"))
    lut = GetColorTransferFunction("density")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = BLOB_COLORS
    GetOpacityTransferFunction("density").Points = BLOB_OPACITIES
    shown.InterpolationType = "Linear"
    shown.ScalarOpacityUnitDistance = 1.0
    shown.StrataVolumeSampleDistance = 0.5
    stack = StackHorizons(Input=[XMLImageDataReader(FileName=[p]) for p in horizons])
    display = Show(stack, view)
    display.SetRepresentationType("Strata Horizons")
    ColorBy(display, None)
    import numpy
    images = {}
    for opacity in (1.0, 0.45):
        display.StrataHorizonsHorizonOpacities = [opacity, 1.0]
        Render(view)
        images[opacity] = screenshot(view, os.path.join(args.work, "translucent_%g.png" % opacity))
    reference = reference_translucent(blob, horizons, 0.45)
    worst = int(numpy.abs(images[0.45].astype(int) - reference).max())
    print("top horizon at 0.45 inside the volume: ParaView against the C++ mappers: RMS %.2f, "
          "max %d of 255; against the opaque horizon RMS %.2f" % (
              rms(images[0.45], reference), worst, rms(images[0.45], images[1.0])))
    check(rms(images[0.45], images[1.0]) > 5.0, "the translucent horizon is not the opaque one")
    check(worst <= 2, "ParaView composites the translucent horizon as the C++ mappers do")


DRAPE_COLORS = [0.0, 0.1, 0.1, 0.4, 128.0, 0.9, 0.9, 0.9, 255.0, 0.8, 0.1, 0.1]


def reference_drape(blob, horizons):
    """The drape drawn by Strata's C++ classes directly (strata package): the top horizon
    sampled in the volume (vtkHorizonVolumeSampler), coloured by it through a colour map, the
    base in its palette colour."""
    import strata
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    from vtkmodules.vtkRenderingCore import vtkActor, vtkColorTransferFunction, vtkRenderer
    readers = []
    for path in [blob] + horizons:
        reader = vtkXMLImageDataReader()
        reader.SetFileName(path)
        readers.append(reader)
    drape = strata.vtkHorizonVolumeSampler()
    drape.SetInputConnection(readers[1].GetOutputPort())
    drape.SetVolumeConnection(readers[0].GetOutputPort())
    colors = vtkColorTransferFunction()
    for n in range(0, len(DRAPE_COLORS), 4):
        colors.AddRGBPoint(*DRAPE_COLORS[n:n + 4])
    mapper = strata.vtkStackedHeightFieldMapper()
    mapper.AddInputConnection(drape.GetOutputPort())
    mapper.AddInputConnection(readers[2].GetOutputPort())
    mapper.SetHorizonColorArray(0, "amplitude")
    mapper.SetHorizonLookupTable(0, colors)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    return render_reference(renderer)


def drape(args):
    """A horizon draped with a volume (Sample Volume Along Horizon), coloured by the sampled
    array through Coloring, in a stack with a plain horizon: the C++ classes' image."""
    blob = write_blob(args.work)
    horizons = write_horizons(args.work)
    view = blob_view()
    volume = XMLImageDataReader(FileName=[blob])
    top, base = [XMLImageDataReader(FileName=[p]) for p in horizons]
    draped = SampleVolumeAlongHorizon(Input=top, Volume=volume)
    stack = StackHorizons(Input=[draped, base])
    display = Show(stack, view)
    display.SetRepresentationType("Strata Horizons")
    ColorBy(display, None)
    Render(view)
    solid = screenshot(view, os.path.join(args.work, "drape_solid.png"))
    ColorBy(display, ("POINTS", "amplitude"))
    lut = GetColorTransferFunction("amplitude")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = DRAPE_COLORS
    Render(view)
    image = screenshot(view, os.path.join(args.work, "drape.png"))
    reference = reference_drape(blob, horizons)
    import numpy
    worst = int(numpy.abs(image.astype(int) - reference).max())
    print("top horizon draped with the volume: ParaView against the C++ classes: RMS %.2f, max %d "
          "of 255; against the undraped stack RMS %.2f" % (rms(image, reference), worst,
                                                            rms(image, solid)))
    check(rms(image, solid) > 5.0, "the draped horizon is coloured by the volume")
    check(worst <= 1, "ParaView drapes the horizon as the C++ classes do")


def decorator_value(prop):
    """The representation a property's visibility decorator shows it under (None: always)."""
    hints = prop.GetHints()
    decorator = hints.FindNestedElementByName("PropertyWidgetDecorator") if hints else None
    if decorator is None or decorator.GetAttribute("type") != "GenericDecorator" or \
            decorator.GetAttribute("mode") != "visibility":
        return None
    if decorator.GetAttribute("property") != "Representation":
        return None
    return decorator.GetAttribute("value")


def panels(args):
    """The properties a panel shows per representation type, as the GUI decides."""
    view = make_view()
    image_display = Show(Wavelet(), view)  # UniformGridRepresentation
    polygons_display = Show(Sphere(), view)  # GeometryRepresentation
    for display, types in ((image_display, ["Strata Volume", "Strata Horizons"]),
                           (polygons_display, ["Strata Hybrid", "Strata Horizons"])):
        proxy = display.SMProxy
        iterator = proxy.NewPropertyIterator()
        visible_always = {}
        per_type = {t: {} for t in types}
        strata = 0
        iterator.Begin()
        while not iterator.IsAtEnd():
            name, prop = iterator.GetKey(), iterator.GetProperty()
            iterator.Next()
            if prop.GetInformationOnly() or prop.GetIsInternal() or \
                    prop.GetPanelVisibility() == "never":
                continue
            label = prop.GetXMLLabel() or name
            shown_under = decorator_value(prop)
            if name.startswith("Strata"):
                strata += 1
                owner = "Strata Volume" if name.startswith("StrataVolume") else \
                    "Strata Horizons" if name.startswith("StrataHorizons") else "Strata Hybrid"
                check(shown_under == owner, "%s shows only under %s (decorator: %s)"
                      % (name, owner, shown_under))
            if shown_under is None:
                visible_always[name] = label
            elif shown_under in per_type:
                per_type[shown_under][name] = label
        check(strata > 10, "%s: %d Strata properties in the panel" % (proxy.GetXMLName(), strata))
        for shown_under, own in per_type.items():
            labels = list(visible_always.values()) + list(own.values())
            clashes = sorted({l for l in own.values() if labels.count(l) > 1})
            print("%s as %s: %d properties of its own, %d shown always; labels shown twice: %s"
                  % (proxy.GetXMLName(), shown_under, len(own), len(visible_always), clashes))
            check(len(own) > 3 and not clashes,
                  "%s: each label shows once under %s" % (proxy.GetXMLName(), shown_under))


def strata_scene(args, view, traced=False):
    """The volume coloured by `b` through Strata Volume, its colour map and opacity edited (as
    the GUI's editor traces them when `traced`)."""
    volume = OpenDataFile(os.path.join(args.work, "arrays.vti"))
    display = Show(volume, view)
    display.SetRepresentationType("Strata Volume")
    ColorBy(display, ("POINTS", "b"))
    lut = GetColorTransferFunction("b")
    opacity = GetOpacityTransferFunction("b")
    items = [smtrace._create_trace_item_internal("PropertiesModified", kwargs={"proxy": p})
             for p in (lut, opacity)] if traced else []
    lut.RGBPoints = [0.0, 0.1, 0.2, 0.9, 128.0, 0.9, 0.9, 0.3, 255.0, 0.9, 0.1, 0.1]
    opacity.Points = [0.0, 0.0, 0.5, 0.0, 255.0, 0.3, 0.5, 0.0]
    for item in items:
        item.finalize()
    return display


def state(args):
    """Save a state with a Strata Volume, reset the session, load it: the same image."""
    write_volume(args.work)
    view = make_view()
    display = strata_scene(args, view)
    display.StrataVolumeSampleDistance = 0.2
    display.StrataVolumeRaysPerPixel = 2
    Render(view)
    before = screenshot(view, os.path.join(args.work, "state_before.png"))
    path = os.path.join(args.work, "strata.pvsm")
    SaveState(path)
    with open(path) as f:
        text = f.read()
    check("StrataVolumeSampleDistance" in text and "StrataVolumeRaysPerPixel" in text,
          "the state file holds the Strata properties")
    ResetSession()
    LoadState(path)
    views = GetRenderViews()
    check(len(views) == 1, "the state holds one view")
    view = views[0]
    view.ViewSize = SIZE
    sources = list(GetSources().values())
    check(len(sources) == 1, "the state holds one source")
    display = GetDisplayProperties(sources[0], view)
    print("reloaded: representation %s, coloring %s, sample distance %g, rays per pixel %d" % (
        display.Representation, list(display.ColorArrayName), display.StrataVolumeSampleDistance,
        display.StrataVolumeRaysPerPixel))
    check(display.Representation == "Strata Volume" and display.ColorArrayName[1] == "b" and
          display.StrataVolumeSampleDistance == 0.2 and display.StrataVolumeRaysPerPixel == 2,
          "the reloaded display is the saved one")
    Render(view)
    after = screenshot(view, os.path.join(args.work, "state_after.png"))
    import numpy
    worst = int(numpy.abs(after.astype(int) - before).max())
    print("state reloaded: max %d of 255 from the image before saving, %d pixels covered"
          % (worst, covered(after)))
    check(worst == 0 and covered(after) > 1000, "the reloaded state draws the same image")


def trace(args):
    """Trace as the GUI does (properties traced on Apply), replay in a fresh session."""
    write_volume(args.work)
    view = make_view()
    smtrace.start_trace()
    display = strata_scene(args, view, traced=True)
    # The GUI traces a panel's Apply as PropertiesModified on the display.
    item = smtrace._create_trace_item_internal("PropertiesModified", kwargs={"proxy": display})
    display.StrataVolumeSampleDistance = 0.2
    display.StrataVolumeClassification = "Pre-integrated"
    item.finalize()
    del item
    text = smtrace.stop_trace()
    path = os.path.join(args.work, "trace.py")
    with open(path, "w") as f:
        f.write(text)
    Render(view)
    traced = screenshot(view, os.path.join(args.work, "trace_before.png"))
    recorded = [line.strip() for line in text.splitlines() if "Strata" in line]
    print("trace (%s) records %d Strata lines: %s" % (path, len(recorded), recorded))
    check("SetRepresentationType('Strata Volume')" in text, "the trace records Strata Volume")
    check(any("StrataVolumeSampleDistance = 0.2" in line for line in recorded) and
          any("StrataVolumeClassification = 'Pre-integrated'" in line for line in recorded),
          "the trace records the Strata properties edited")
    ResetSession()
    view = make_view()
    exec(compile(text, path, "exec"), {})
    view = GetActiveView()
    Render(view)
    replayed = screenshot(view, os.path.join(args.work, "trace_after.png"))
    import numpy
    worst = int(numpy.abs(replayed.astype(int) - traced).max())
    print("trace replayed: max %d of 255 from the traced session's image" % worst)
    check(worst <= 1 and covered(replayed) > 1000, "the replayed trace draws the same image")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--work", default=".")
    parser.add_argument("--convert", default="")
    parser.add_argument("--check", required=True,
                        choices=["extent", "coloring", "horizon_coloring",
                                 "translucent_horizons", "drape", "panels", "state", "trace"])
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    globals()[args.check](args)
    print("%d failure(s)" % len(failures))
    if failures:
        raise RuntimeError("%d check(s) failed: %s" % (len(failures), "; ".join(failures)))


main()

"""A paged time series (4-D data): the tooth CT fading over four steps, one brick pool per step
given to one reader at uneven times; the ray caster pages the step its input's time selects and
prefetches the next one while a step is shown. Writes OUT_0.png .. OUT_3.png (one per step).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/time_series.py out.png
"""
import argparse
import pathlib
import shutil
import tempfile

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkImagingCore import vtkImageShiftScale
from vtkmodules.vtkIOImage import vtkNrrdReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="time_series.png")
parser.add_argument("--data", default=str(DATA), help="folder with volumes/tooth.nrrd")
parser.add_argument("--pools", help="the folder to write the step pools in (default: a temporary one)")
args = parser.parse_args()
folder = pathlib.Path(args.pools or tempfile.mkdtemp())
times = [0.0, 0.5, 2.0, 3.5]

# One pool per step: step k is the tooth with its values scaled by 1 - 0.12 k.
tooth = vtkNrrdReader()
tooth.SetFileName(f"{args.data}/volumes/tooth.nrrd")
reader = strata.vtkPagePoolReader()
for k, t in enumerate(times):
    fade = vtkImageShiftScale()
    fade.SetInputConnection(tooth.GetOutputPort())
    fade.SetScale(1.0 - 0.12 * k)
    fade.SetOutputScalarTypeToUnsignedChar()
    pool = str(folder / f"tooth_t{k}.spp")
    writer = strata.vtkImageToPagePoolWriter()
    writer.SetInputConnection(fade.GetOutputPort())
    writer.SetFileName(pool)
    writer.SetPageSize(32)
    if not writer.Write():
        raise SystemExit(f"cannot write {pool}")
    reader.AddTimeStep(pool, t)

mapper = strata.vtkMultiVolumeRayCastMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetSampleDistance(0.5)
mapper.SetAtlasBudget(16)
mapper.SetPagesPerFrame(8)

color = vtkColorTransferFunction()
for value, r, g, b in ((0, 0.5, 0.5, 0.5), (140, 0.8, 0.35, 0.25), (200, 1.0, 0.9, 0.8), (255, 1, 1, 1)):
    color.AddRGBPoint(value, r, g, b)
opacity = vtkPiecewiseFunction()
for value, alpha in ((0, 0.0), (110, 0.0), (150, 0.03), (255, 0.5)):
    opacity.AddPoint(value, alpha)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(prop)

renderer = vtkRenderer()
renderer.SetBackground(0.08, 0.09, 0.12)
renderer.AddVolume(volume)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(-80)
camera.OrthogonalizeViewUp()
camera.Azimuth(35)
camera.Zoom(1.3)
renderer.ResetCameraClippingRange()
window = vtkRenderWindow()
window.SetSize(240, 240)
window.SetMultiSamples(0)
window.AddRenderer(renderer)

# The time is asked for as an animation asks for it: on the mapper's input, after the first
# information pass (VTK drops an UPDATE_TIME_STEP set before the reader's output exists).
reader.UpdateInformation()
base = args.output[:-4] if args.output.endswith(".png") else args.output
for k, t in enumerate(times):
    mapper.GetInputInformation(0, 0).Set(vtkStreamingDemandDrivenPipeline.UPDATE_TIME_STEP(), t)
    frames = strata.render_until_converged(window, mapper)
    statistics = strata.paging_statistics(mapper)
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    png = vtkPNGWriter()
    png.SetInputConnection(grab.GetOutputPort())
    png.SetFileName(f"{base}_{k}.png")
    png.Write()
    print(f"{base}_{k}.png", f"step {k} (time {t}): settled after {frames} frames,",
          f"{statistics['IoWaitFrames']} I/O-wait frames in all")
if not args.pools:
    shutil.rmtree(folder)

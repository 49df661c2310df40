"""Out of core: the tooth CT written to a brick pool, then paged by the ray caster (a RAM cache
and a GPU atlas of bricks) from coarse to fine until the cut settles.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/paged_volume.py out.png
"""
import argparse
import pathlib
import shutil
import tempfile

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkNrrdReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="paged_volume.png")
parser.add_argument("--data", default=str(DATA), help="folder with volumes/tooth.nrrd")
parser.add_argument("--pool", help="the brick pool to write and page (default: a temporary file)")
args = parser.parse_args()
pool = args.pool or str(pathlib.Path(tempfile.mkdtemp()) / "tooth.spp")

# Convert once (strata-convert does the same from the command line); never read whole again.
tooth = vtkNrrdReader()
tooth.SetFileName(f"{args.data}/volumes/tooth.nrrd")
writer = strata.vtkImageToPagePoolWriter()
writer.SetInputConnection(tooth.GetOutputPort())
writer.SetFileName(pool)
writer.SetPageSize(32)
if not writer.Write():
    raise SystemExit(f"cannot write {pool}")

reader = strata.vtkPagePoolReader()
reader.SetFileName(pool)
mapper = strata.vtkMultiVolumeRayCastMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetSampleDistance(0.5)
mapper.SetAtlasBudget(16)  # MB of bricks on the GPU
mapper.SetPagesPerFrame(8)  # uploads per frame: the cut refines over several frames

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
frames = strata.render_until_converged(window, mapper)
statistics = strata.paging_statistics(mapper)

grab = vtkWindowToImageFilter()
grab.SetInput(window)
png = vtkPNGWriter()
png.SetInputConnection(grab.GetOutputPort())
png.SetFileName(args.output)
png.Write()
print(args.output, f"settled after {frames} frames,", mapper.GetNumberOfResidentBricks(),
      f"bricks resident, {statistics['BytesRead'] / 1024:.0f} KiB read")
if not args.pool:
    shutil.rmtree(pathlib.Path(pool).parent)

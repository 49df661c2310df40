"""The subsurface scene: a synthetic SEG-Y survey written from the Reek horizons on their own grid
(every 8th node), read back in world coordinates and drawn over the base horizon with no
transform; then one pick at the window's centre.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/subsurface.py out.png
"""
import argparse
import math
import pathlib
import shutil
import sys
import tempfile

from vtkmodules.vtkCommonCore import vtkMath
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkRenderer,
                                         vtkRenderWindow, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
REEK = ("reek_01_topreek_rota", "reek_02_midreek_rota", "reek_03_lowreek_rota", "reek_04_basereek_rota")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="subsurface.png")
parser.add_argument("--data", default=str(DATA), help="folder with horizons/reek_*.gri")
parser.add_argument("--survey", help="the SEG-Y file to write (default: a temporary file)")
args = parser.parse_args()
work = None if args.survey else tempfile.mkdtemp()
path = args.survey or str(pathlib.Path(work) / "reek-synthetic.sgy")

# The survey: reflections at the four horizons (impedance per layer), a Ricker wavelet, noise.
survey = strata.vtkSyntheticSurveyWriter()
grids = []
for name in REEK:
    reader = strata.vtkIrapBinaryGridReader()
    reader.SetFileName(f"{args.data}/horizons/{name}.gri")
    survey.AddInputConnection(reader.GetOutputPort())
    grids.append(reader)
grids[0].Update()
grid = grids[0].GetOutput()
nx, ny, _ = grid.GetDimensions()
d = grid.GetDirectionMatrix()
survey.SetOrigin(grid.GetOrigin()[0], grid.GetOrigin()[1])
survey.SetRotation(vtkMath.DegreesFromRadians(math.atan2(d.GetElement(1, 0), d.GetElement(0, 0))))
survey.SetBins(8 * grid.GetSpacing()[1], 8 * grid.GetSpacing()[0])
survey.SetLines((ny - 1) // 8 + 1, (nx - 1) // 8 + 1)
survey.SetSamples(160, 4.0, 1444)  # depths in m: 4 m samples over the reservoir
survey.SetPeakFrequency(30.0)  # cycles per km for depths
survey.SetFileName(path)
if not survey.Write():
    sys.exit(f"cannot write {path}")

# Read back: placed by its trace coordinates, z = -depth, as horizons with HeightScale -1.
seismic = strata.vtkSegyVolumeReader()
seismic.SetFileName(path)
volume_mapper = strata.vtkMultiVolumeRayCastMapper()
volume_mapper.SetInputConnection(seismic.GetOutputPort())
color = vtkColorTransferFunction()
for value, r, g, b in ((-0.1, 0.15, 0.3, 1.0), (0, 1, 1, 1), (0.1, 1.0, 0.25, 0.1)):
    color.AddRGBPoint(value, r, g, b)
opacity = vtkPiecewiseFunction()
for value, alpha in ((-0.1, 0.6), (-0.02, 0.0), (0.02, 0.0), (0.1, 0.6)):
    opacity.AddPoint(value, alpha)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
prop.SetScalarOpacityUnitDistance(20.0)
volume = vtkVolume()
volume.SetMapper(volume_mapper)
volume.SetProperty(prop)
volume.SetScale(1, 1, 8)

base = strata.vtkStackedHeightFieldMapper()
base.AddInputConnection(grids[3].GetOutputPort())
base.SetHeightScale(-1.0)  # the same z as the volume
base.SetColorMode(strata.vtkStackedHeightFieldMapper.ColorModes.LookupTable)
actor = vtkActor()
actor.SetMapper(base)
actor.SetScale(1, 1, 8)

renderer = vtkRenderer()
renderer.SetBackground(0.08, 0.09, 0.12)
renderer.AddActor(actor)
renderer.AddVolume(volume)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(-60)
camera.OrthogonalizeViewUp()
camera.Azimuth(30)
camera.Zoom(2.0)
renderer.ResetCameraClippingRange()
window = vtkRenderWindow()
window.SetSize(320, 240)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
window.Render()

picker = strata.vtkSubsurfacePicker()
if picker.Pick(160.5, 120.5, 0.0, renderer):
    x, y, z = picker.GetPickPosition()
    print(f"pick at the centre: ({x:.1f}, {y:.1f}, {z:.1f}), horizon {picker.GetHorizonId()}, "
          f"{picker.GetRayPoints().GetNumberOfPoints()} volume samples", file=sys.stderr)

grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(args.output)
writer.Write()
if work:
    shutil.rmtree(work)
print(args.output)

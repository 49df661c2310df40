"""The four horizons of the Reek reservoir model (Irap binary grids) ray cast in one pass.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/horizons.py out.png
"""
import argparse
import pathlib

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="horizons.png")
parser.add_argument("--data", default=str(DATA), help="folder with horizons/reek_*.gri")
args = parser.parse_args()

mapper = strata.vtkStackedHeightFieldMapper()
for name in ("reek_01_topreek_rota", "reek_02_midreek_rota", "reek_03_lowreek_rota", "reek_04_basereek_rota"):
    reader = strata.vtkIrapBinaryGridReader()
    reader.SetFileName(f"{args.data}/horizons/{name}.gri")
    mapper.AddInputConnection(reader.GetOutputPort())
mapper.SetHeightScale(-1.0)  # depths grow downwards
mapper.SetColorMode(strata.vtkStackedHeightFieldMapper.ColorModes.LookupTable)

actor = vtkActor()
actor.SetMapper(mapper)
actor.SetScale(1, 1, 8)  # 8x vertical exaggeration: the reservoir is thin
actor.GetProperty().SetSpecular(0.2)
renderer = vtkRenderer()
renderer.SetBackground(0.08, 0.09, 0.12)
renderer.AddActor(actor)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(-60)
camera.OrthogonalizeViewUp()
camera.Azimuth(30)
camera.Zoom(1.9)
renderer.ResetCameraClippingRange()
window = vtkRenderWindow()
window.SetSize(320, 240)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
window.Render()

grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(args.output)
writer.Write()
print(args.output)

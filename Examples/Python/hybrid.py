"""Hybrid point + volume rendering: the tooth CT as a 1/4-resolution volume plus the points that
carry what the down-sampling lost (vtkHybridVolumeFilter), drawn together as Gaussian splats.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/hybrid.py out.png
"""
import argparse
import pathlib

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkNrrdReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="hybrid.png")
parser.add_argument("--data", default=str(DATA), help="folder with volumes/tooth.nrrd")
args = parser.parse_args()

tooth = vtkNrrdReader()
tooth.SetFileName(f"{args.data}/volumes/tooth.nrrd")
hybrid = strata.vtkHybridVolumeFilter()
hybrid.SetInputConnection(tooth.GetOutputPort())
hybrid.SetFactor(4, 4, 4)
hybrid.SetFilterToCubic()
hybrid.SetThreshold(24.0)  # a point wherever the low resolution misses more than 24 of 255

mapper = strata.vtkHybridVolumeMapper()
mapper.SetInputConnection(hybrid.GetOutputPort(0))
mapper.SetPointsInputConnection(hybrid.GetOutputPort(1))
mapper.SetPointShape(strata.vtkHybridVolumeMapper.PointShapes.GaussianSplats)
mapper.GetVolumeMapper().SetSampleDistance(0.5)

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
window.Render()

grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(args.output)
writer.Write()
print(args.output, mapper.GetNumberOfPointsDrawn(), "points drawn")

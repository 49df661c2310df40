"""Two overlapping volumes in one ray cast: a CT of a tooth (NRRD) and a spherical shell made
with NumPy, each with its own transfer function and placement, mixed sample by sample.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/volumes.py out.png
"""
import argparse
import pathlib

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkNrrdReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkMultiVolume

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="volumes.png")
parser.add_argument("--data", default=str(DATA), help="folder with volumes/tooth.nrrd")
args = parser.parse_args()


def volume_property(colors, opacities):
    """A property from (value, r, g, b) and (value, opacity) points, linear interpolation."""
    color = vtkColorTransferFunction()
    for value, r, g, b in colors:
        color.AddRGBPoint(value, r, g, b)
    opacity = vtkPiecewiseFunction()
    for value, alpha in opacities:
        opacity.AddPoint(value, alpha)
    prop = vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()
    return prop


# A spherical shell, 64^3 uint8 voxels: 255 on the sphere of radius 24 voxels, fading over 21.
i, j, k = np.meshgrid(np.arange(64.0), np.arange(64.0), np.arange(64.0), indexing="ij")
r = np.sqrt((i - 31.5) ** 2 + (j - 31.5) ** 2 + (k - 31.5) ** 2)
shell_values = np.floor(np.clip(255.0 - 12.0 * np.abs(r - 24.0), 0.0, 255.0)).astype(np.uint8)
shell = vtkImageData()
shell.SetDimensions(64, 64, 64)
shell.SetSpacing(1.5, 1.5, 1.5)
shell.SetOrigin(20.0, 0.0, 60.0)
shell.GetPointData().SetScalars(numpy_support.numpy_to_vtk(shell_values.ravel(order="F"), deep=True))

tooth = vtkNrrdReader()
tooth.SetFileName(f"{args.data}/volumes/tooth.nrrd")

mapper = strata.vtkMultiVolumeRayCastMapper()
mapper.SetSampleDistance(0.5)
mapper.SetInputConnection(0, tooth.GetOutputPort())
mapper.SetInputDataObject(1, shell)
scene = vtkMultiVolume()
scene.SetMapper(mapper)
for port, prop in enumerate((
        volume_property([(0, 0.5, 0.5, 0.5), (140, 0.8, 0.35, 0.25), (200, 1.0, 0.9, 0.8), (255, 1, 1, 1)],
                        [(0, 0.0), (110, 0.0), (150, 0.03), (255, 0.5)]),
        volume_property([(0, 0.1, 0.3, 0.9), (255, 0.3, 0.9, 1.0)],
                        [(0, 0.0), (120, 0.0), (255, 0.08)]))):
    member = vtkVolume()
    member.SetProperty(prop)
    scene.SetVolume(member, port)

renderer = vtkRenderer()
renderer.SetBackground(0.08, 0.09, 0.12)
renderer.AddVolume(scene)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(-80)
camera.OrthogonalizeViewUp()
camera.Azimuth(35)
camera.Zoom(1.1)
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
print(args.output)

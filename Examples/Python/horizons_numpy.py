"""Horizons from NumPy: a 2-D array of two-way times (the Penobscot seabed, NaN where it was not
interpreted) and a second horizon 40 ms below it, as vtkImageData straight into the mapper.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/horizons_numpy.py out.png
"""
import argparse
import pathlib

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="horizons_numpy.png")
parser.add_argument("--data", default=str(DATA), help="folder with horizons/penobscot_seabed_crop.npy")
args = parser.parse_args()


def horizon(times, spacing=25.0):
    """A horizon grid: array index (i, j) = (inline, crossline) -> point (i, j) of the image."""
    image = vtkImageData()
    image.SetDimensions(times.shape[0], times.shape[1], 1)
    image.SetSpacing(spacing, spacing, 1.0)
    # VTK stores x fastest: the first NumPy axis (inline) is x, so flatten in Fortran order.
    scalars = numpy_support.numpy_to_vtk(times.ravel(order="F"), deep=True)
    scalars.SetName("twt")
    image.GetPointData().SetScalars(scalars)
    return image


seabed = np.load(f"{args.data}/horizons/penobscot_seabed_crop.npy")  # float64, NaN = hole
mapper = strata.vtkStackedHeightFieldMapper()
mapper.AddInputData(horizon(seabed))
mapper.AddInputData(horizon(seabed + 40.0))
mapper.SetHeightScale(-10.0)  # two-way time grows downwards, exaggerated 10x
mapper.SetColorMode(strata.vtkStackedHeightFieldMapper.ColorModes.LookupTable)

actor = vtkActor()
actor.SetMapper(mapper)
renderer = vtkRenderer()
renderer.SetBackground(0.08, 0.09, 0.12)
renderer.AddActor(actor)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(-55)
camera.OrthogonalizeViewUp()
camera.Azimuth(30)
camera.Zoom(1.1)
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

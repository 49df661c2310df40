"""Run from an install tree (PYTHONPATH=<prefix>/lib/python3/dist-packages): the package loads
from there, not from the build tree, finds its libraries, and renders a two-horizon stack."""
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter

import strata

prefix = sys.argv[1]
if not strata.__file__.startswith(prefix):
    sys.exit(f"FAIL: strata was imported from {strata.__file__}, not from {prefix}")
with open("/proc/self/maps") as maps:
    libraries = {line.split()[-1] for line in maps if "libStrata" in line}
if not libraries or not all(lib.startswith(prefix) for lib in libraries):
    sys.exit(f"FAIL: Strata's libraries were loaded from {sorted(libraries)}, not from {prefix}")
mapper = strata.vtkStackedHeightFieldMapper()
for height in (0.0, 4.0):
    image = vtkImageData()
    image.SetDimensions(32, 32, 1)
    image.AllocateScalars(10, 1)  # VTK_FLOAT
    image.GetPointData().GetScalars().Fill(height)
    mapper.AddInputData(image)
actor = vtkActor()
actor.SetMapper(mapper)
renderer = vtkRenderer()
renderer.AddActor(actor)
window = vtkRenderWindow()
window.SetSize(64, 64)
window.AddRenderer(renderer)
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.Update()
rgb = grab.GetOutput().GetPointData().GetScalars()
covered = sum(1 for i in range(0, rgb.GetNumberOfTuples()) if any(rgb.GetTuple3(i)))
print(f"installed strata from {strata.__file__}, {len(libraries)} libraries from the prefix: window {window.GetClassName()}, "
      f"{covered} of 4096 pixels covered")
if covered < 1000:
    sys.exit("FAIL: the stack covers too few pixels")
print("installed: ok")

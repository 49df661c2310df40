"""Bad input reaches Python as VTK errors and warnings a script can observe: an ErrorEvent /
WarningEvent observer on the object receives the message (and stops it reaching the output
window), and the executive's failure goes to vtkOutputWindow, here a vtkStringOutputWindow the
test reads. Each case asserts the message says what is wrong.

    TestErrors.py --data Testing/Data --out <scratch folder>
"""
import argparse
import os
import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkIntArray, vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow

import strata

parser = argparse.ArgumentParser()
parser.add_argument("--data", required=True)
parser.add_argument("--out", required=True)
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)

window_log = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window_log)
failures = []


class Messages:
    """Collects the ErrorEvent and WarningEvent messages of one object."""

    def __init__(self, obj):
        self.errors, self.warnings = [], []
        obj.AddObserver("ErrorEvent", self.on_error)
        obj.AddObserver("WarningEvent", self.on_warning)

    @calldata_type(VTK_STRING)
    def on_error(self, caller, event, message):
        self.errors.append(message)

    @calldata_type(VTK_STRING)
    def on_warning(self, caller, event, message):
        self.warnings.append(message)


def check(condition, what, detail=""):
    print(f"{'ok  ' if condition else 'FAIL'} {what}{': ' + detail if detail else ''}")
    if not condition:
        failures.append(what)


def scratch(name, content):
    path = os.path.join(args.out, name)
    with open(path, "wb") as f:
        f.write(content)
    return path


# 1. A truncated Irap binary grid: an error naming the file, an empty output.
with open(os.path.join(args.data, "horizons", "reek_01_topreek_rota.gri"), "rb") as f:
    truncated = scratch("truncated.gri", f.read()[:300])
grid = strata.vtkIrapBinaryGridReader()
grid.SetFileName(truncated)
seen = Messages(grid)
grid.Update()
check(len(seen.errors) >= 1 and "truncated.gri" in seen.errors[0],
      "truncated .gri: an ErrorEvent naming the file", repr(seen.errors[:1]))
check(grid.GetOutput().GetNumberOfPoints() == 0, "truncated .gri: the output is empty")
check("returned failure" in window_log.GetOutput(),
      "truncated .gri: the executive's failure reaches the output window")

# 2. A .npy file with a wrong magic string.
bad_npy = scratch("bad.npy", b"\x93NUMPX\x01\x00" + b"\x00" * 120)
npy = strata.vtkNumpyGridReader()
npy.SetFileName(bad_npy)
seen = Messages(npy)
npy.Update()
check(len(seen.errors) >= 1, "bad .npy magic: an ErrorEvent", repr(seen.errors[:1]))

# 3. A page pool that does not exist.
pool = strata.vtkPagePoolReader()
pool.SetFileName(os.path.join(args.out, "no-such-pool.spp"))
seen = Messages(pool)
pool.Update()
check(len(seen.errors) >= 1 and "no-such-pool.spp" in seen.errors[0],
      "missing pool: an ErrorEvent naming the file", repr(seen.errors[:1]))

# 4. A wrongly shaped cut handed to the volume mapper.
mapper = strata.vtkMultiVolumeRayCastMapper()
seen = Messages(mapper)
one_component = vtkIntArray()
one_component.SetNumberOfComponents(1)
mapper.SetFixedCut(0, one_component)
check(len(seen.errors) == 1 and "two components" in seen.errors[0],
      "SetFixedCut with one component: an ErrorEvent saying two are needed", repr(seen.errors))

# 5. Horizons on two different lateral grids in one stack: an error at render time, no crash.
def flat(nx, ny, height):
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    image.AllocateScalars(10, 1)  # VTK_FLOAT
    image.GetPointData().GetScalars().Fill(height)
    return image


stack = strata.vtkStackedHeightFieldMapper()
stack.AddInputData(flat(16, 16, 0.0))
stack.AddInputData(flat(20, 16, 1.0))
seen = Messages(stack)
actor = vtkActor()
actor.SetMapper(stack)
renderer = vtkRenderer()
renderer.AddActor(actor)
window = vtkRenderWindow()
window.SetSize(64, 64)
window.AddRenderer(renderer)
window.Render()
check(len(seen.errors) >= 1 and "grid" in " ".join(seen.errors),
      "horizons on different grids: an ErrorEvent at render time", repr(seen.errors[:1]))

# 6. A warning: a writer given more components than a set of pools holds (the first 4 written).
doubles = vtkImageData()
doubles.SetDimensions(8, 8, 8)
doubles.AllocateScalars(11, 5)  # VTK_DOUBLE, 5 components: components 0 to 3 are written
writer = strata.vtkImageToPagePoolWriter()
writer.SetInputData(doubles)
writer.SetFileName(os.path.join(args.out, "doubles.spp"))
seen = Messages(writer)
written = writer.Write()
check(written and len(seen.warnings) >= 1, "a five-component input: a WarningEvent",
      repr(seen.warnings[:1]))

if failures:
    sys.exit(f"FAIL: {len(failures)} check(s) failed: {failures}")
print("TestErrors: 0 failures")

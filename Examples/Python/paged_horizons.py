"""Out of core: the four Reek horizons written to tile pools, then paged by the height-field ray
caster (RAM cache, GPU tile atlas, stitched levels) until the cut settles; the settled image is
the in-core one of horizons.py.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/paged_horizons.py out.png
"""
import argparse
import pathlib
import shutil
import tempfile

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter

import strata

DATA = pathlib.Path(__file__).resolve().parents[2] / "Testing" / "Data"
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default="paged_horizons.png")
parser.add_argument("--data", default=str(DATA), help="folder with horizons/reek_*.gri")
parser.add_argument("--pools", help="folder for the tile pools (default: a temporary one)")
args = parser.parse_args()
pools = pathlib.Path(args.pools or tempfile.mkdtemp())

mapper = strata.vtkStackedHeightFieldMapper()
for name in ("reek_01_topreek_rota", "reek_02_midreek_rota", "reek_03_lowreek_rota", "reek_04_basereek_rota"):
    grid = strata.vtkIrapBinaryGridReader()
    grid.SetFileName(f"{args.data}/horizons/{name}.gri")
    writer = strata.vtkImageToPagePoolWriter()
    writer.SetInputConnection(grid.GetOutputPort())
    writer.SetFileName(str(pools / f"{name}.spp"))
    writer.SetPageSize(65)  # tiles of 64 cells, the mapper's TileSize
    if not writer.Write():
        raise SystemExit(f"cannot write {writer.GetFileName()}")
    reader = strata.vtkPagePoolReader()
    reader.SetFileName(writer.GetFileName())
    mapper.AddInputConnection(reader.GetOutputPort())
mapper.SetHeightScale(-1.0)  # depths grow downwards
mapper.SetColorMode(strata.vtkStackedHeightFieldMapper.ColorModes.LookupTable)
mapper.SetPagesPerFrame(16)

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
frames = strata.render_until_converged(window, mapper)
statistics = strata.paging_statistics(mapper)

grab = vtkWindowToImageFilter()
grab.SetInput(window)
png = vtkPNGWriter()
png.SetInputConnection(grab.GetOutputPort())
png.SetFileName(args.output)
png.Write()
print(args.output, f"settled after {frames} frames, {statistics['FinestTiles']} level-0 tiles of",
      f"{statistics['CutTiles']}, {statistics['BytesRead'] / 1024:.0f} KiB read")
if not args.pools:
    shutil.rmtree(pools)

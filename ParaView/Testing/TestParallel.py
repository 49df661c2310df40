# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""Sort-last parallel rendering of a Strata scene in pvbatch over MPI (IceT ordered compositing).

    pvbatch TestParallel.py --plugin Strata.so --work <folder> --make-data
    mpirun -np N pvbatch TestParallel.py --plugin Strata.so --work <folder> --render
    pvbatch TestParallel.py --plugin Strata.so --work <folder> --compare 2 4
    mpirun -np 2 pvserver --server-port=P & pvpython TestParallel.py --plugin Strata.so
        --work <folder> --render --server localhost:P --label _server
    pvbatch TestParallel.py --plugin Strata.so --work <folder> --compare 2 --label _server

The scene: three overlapping volumes of different resolutions and transfer functions, the
largest one paged from a brick pool (strata-convert makes it from paged.vti between --make-data
and --render), and a stack of two opaque horizons crossing all three. With N processes each
rank draws one box of the scene (vtkStrataParaViewUtilities::PartitionBox: the scene is 64 x
48 x 40, so 2 ranks split x at 32 and 4 ranks also split y at 24) and IceT blends the boxes in
order. Two views: "face" looks along -x straight at the face x = 32 between the ranks (every
ray crosses it, and with 4 ranks the face y = 24 is seen edge-on along the middle column), post-
classified; "oblique" sees both faces at an angle, pre-integrated. --render writes
parallel_<N>_<view>.png; --compare asserts that the images of N ranks equal those of 1 rank.
"""
import argparse
import json
import os
import time
import sys

import paraview.simple
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting interface)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from strata_png import load_png  # noqa: E402 (beside this script)
from strata_colors import color_by_depth  # noqa: E402

SIZE = [160, 160]
VIEWS = {
    "face": dict(position=[150.0, 24.0, 20.0], focal_point=[32.0, 24.0, 20.0],
                 view_up=[0.0, 0.0, 1.0], classification=0),
    "oblique": dict(position=[110.0, -70.0, 80.0], focal_point=[32.0, 24.0, 20.0],
                    view_up=[0.0, 0.0, 1.0], classification=1),
}
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def write_image(path, dims, spacing, origin, values):
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    from vtkmodules.util.numpy_support import numpy_to_vtk
    image = vtkImageData()
    image.SetDimensions(dims)
    image.SetSpacing(spacing)
    image.SetOrigin(origin)
    array = numpy_to_vtk(values.ravel(order="F").astype("float32"), deep=1)
    array.SetName("density")
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def make_data(work):
    """Smooth fields in code (no file to ship): blobs and waves, and two horizons."""
    import numpy
    def field(dims, spacing, origin, centres):
        axes = [origin[a] + spacing[a] * numpy.arange(dims[a]) for a in range(3)]
        x, y, z = numpy.meshgrid(*axes, indexing="ij")
        value = 40.0 * (1.0 + numpy.sin(0.9 * x + 0.3 * z) * numpy.cos(0.7 * y + 0.4 * z))
        for (cx, cy, cz, r, a) in centres:
            value += a * numpy.exp(-((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) / (r * r))
        return numpy.clip(value, 0.0, 255.0)
    write_image(os.path.join(work, "paged.vti"), [64, 48, 40], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0],
                field([64, 48, 40], [1, 1, 1], [0, 0, 0],
                      [(20, 20, 20, 9, 170), (45, 30, 22, 7, 150), (32, 24, 8, 6, 120)]))
    write_image(os.path.join(work, "small.vti"), [40, 40, 36], [0.8, 0.8, 0.8], [10.0, 5.0, 5.0],
                field([40, 40, 36], [0.8] * 3, [10, 5, 5], [(26, 20, 18, 8, 200)]))
    write_image(os.path.join(work, "coarse.vti"), [24, 24, 24], [1.25, 1.25, 1.25],
                [28.0, 12.0, 4.0], field([24, 24, 24], [1.25] * 3, [28, 12, 4],
                                         [(40, 26, 16, 7, 210)]))
    # (The reader's first array axis is x: 65 x 49 points over x in [0, 64], y in [0, 48].)
    gx, gy = numpy.meshgrid(numpy.arange(65.0), numpy.arange(49.0), indexing="ij")
    numpy.save(os.path.join(work, "top.npy"),
               (30.0 + 4.0 * numpy.sin(0.15 * gx) + 3.0 * numpy.cos(0.2 * gy)).astype("float32"))
    numpy.save(os.path.join(work, "base.npy"),
               (12.0 + 3.0 * numpy.cos(0.12 * gx + 0.3) + 2.0 * numpy.sin(0.25 * gy)).astype(
                   "float32"))
    print("data written to %s" % work)


def show_volume(source, view, array, colors, opacities):
    display = Show(source, view)
    display.SetRepresentationType("Strata Volume")
    ColorBy(display, ("POINTS", array))
    lut = GetColorTransferFunction(array, display, separate=True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.RGBPoints = [v for c in colors for v in c]
    opacity = GetOpacityTransferFunction(array, display, separate=True)
    opacity.Points = [v for o in opacities for v in (o[0], o[1], 0.5, 0.0)]
    display.UseSeparateColorMap = 1
    display.LookupTable = lut
    display.ScalarOpacityFunction = opacity
    display.InterpolationType = "Linear"
    display.ScalarOpacityUnitDistance = 1.0
    return display


def build_scene(work, view):
    paged = StrataPagePool(FileName=os.path.join(work, "paged.spp"))
    small = XMLImageDataReader(FileName=[os.path.join(work, "small.vti")])
    coarse = XMLImageDataReader(FileName=[os.path.join(work, "coarse.vti")])
    first = show_volume(paged, view, paged.PointData.keys()[0],
                        [(0, 0.2, 0.3, 0.8), (120, 0.9, 0.6, 0.2), (255, 1.0, 1.0, 0.9)],
                        [(0, 0.0), (60, 0.0), (150, 0.12), (255, 0.5)])
    show_volume(small, view, "density", [(0, 0.1, 0.8, 0.3), (255, 0.9, 1.0, 0.4)],
                [(0, 0.0), (90, 0.0), (255, 0.25)])
    show_volume(coarse, view, "density", [(0, 0.8, 0.1, 0.6), (255, 1.0, 0.5, 0.9)],
                [(0, 0.0), (100, 0.0), (255, 0.3)])
    first.StrataVolumeSampleDistance = 1.0
    first.StrataVolumeBrickSize = 16
    first.StrataVolumePagesPerFrame = 256
    first.StrataVolumeAtlasBudget = 64
    horizons = [StrataNumPyHorizon(FileName=os.path.join(work, name + ".npy"))
                for name in ("top", "base")]
    stack = StackHorizons(Input=horizons)
    shown = Show(stack, view)
    shown.SetRepresentationType("Strata Horizons")
    color_by_depth(shown, stack)
    return first


def setup_view():
    view = CreateView("RenderView")
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.UseFXAA = 0
    view.UseToneMapping = 0
    paraview.simple._DisableFirstRenderCameraReset()
    return view


def all_settled(stats, ranks):
    """Whether every rank's cut had settled at the last render (the last line of its
    statistics, written before each render, describes the render before)."""
    for rank in range(ranks):
        with open("%s.%d" % (stats, rank)) as f:
            lines = f.read().split()
        fields = lines[-1].split(",") if lines else []
        if len(fields) < 6 or fields[5] != "1":  # (a line being written reads short)
            return False
    return True


def render(args):
    view = setup_view()
    display = build_scene(args.work, view)
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    # Every rank appends its own figures (MB paged) to stats_<N>.<rank>.
    stats = os.path.join(args.work, "stats_%d%s" % (ranks, args.label))
    for rank in range(ranks):
        if os.path.exists("%s.%d" % (stats, rank)):
            os.remove("%s.%d" % (stats, rank))
    display.StrataVolumeStatisticsFile = stats
    for name, v in VIEWS.items():
        view.CameraPosition = v["position"]
        view.CameraFocalPoint = v["focal_point"]
        view.CameraViewUp = v["view_up"]
        view.CameraViewAngle = 30.0
        display.StrataVolumeClassification = v["classification"]
        # Until every rank's cut has settled (ParaView's PagingConverged is rank 0's alone).
        settled = False
        for frame in range(300):
            Render(view)
            settled = frame > 0 and all_settled(stats, ranks)
            if settled:
                break
            time.sleep(0.02)
        check(settled, "%s: the paged volume settled on every rank (%d ranks, %d renders)"
              % (name, ranks, frame + 1))
        if not args.server:  # (a client's information properties are its own objects')
            display.UpdatePropertyInformation()
            check(display.GetPropertyValue("StrataVolumeNumberOfVolumesInScene") == 3,
                  "%s: three volumes in one ray cast" % name)
        out = os.path.join(args.work, "parallel_%d%s_%s.png" % (ranks, args.label, name))
        SaveScreenshot(out, view, ImageResolution=SIZE, TransparentBackground=0)
        print("%s: %d ranks -> %s" % (name, ranks, out))
    Render(view)  # (the statistics lines describe the render before)


def paged_megabytes(work, ranks, label):
    """Each rank's MB paged from the pool over the whole run (its last statistics line)."""
    paged = []
    for rank in range(ranks):
        with open(os.path.join(work, "stats_%d%s.%d" % (ranks, label, rank))) as f:
            lines = [line.split(",") for line in f.read().split()]
        paged.append(float(lines[-1][2]))
    return paged


def process_boxes(work, ranks, label):
    """Each rank's box at its last render (the last six fields of its statistics)."""
    boxes = []
    for rank in range(ranks):
        with open(os.path.join(work, "stats_%d%s.%d" % (ranks, label, rank))) as f:
            boxes.append([float(v) for v in f.read().split()[-1].split(",")[6:12]])
    return boxes


def check_cut(work, n, label):
    """The ranks' boxes (each rank's own statistics): the cut every rank found alike, a tiling of
    space (each of 29^3 points, off the faces, in exactly one rank's box), with its inner faces
    where the bisection puts them (x = 32, and y = 24 with 4 ranks)."""
    import numpy
    boxes = process_boxes(work, n, label)
    print("%d ranks: boxes %s" % (n, boxes))
    lo = numpy.array([min(b[2 * a] for b in boxes) for a in range(3)])
    hi = numpy.array([max(b[2 * a + 1] for b in boxes) for a in range(3)])
    t = (numpy.arange(29) + 0.5 / numpy.pi) / 29.0
    points = numpy.stack(numpy.meshgrid(*[lo[a] + (hi[a] - lo[a]) * t for a in range(3)],
                                        indexing="ij"), axis=-1).reshape(-1, 3)
    holders = numpy.zeros(len(points), dtype=int)
    for b in boxes:
        holders += numpy.all((points >= b[0::2]) & (points <= b[1::2]), axis=1)
    check(numpy.all(holders == 1), "%d ranks: the boxes tile the scene (%d of %d points in "
          "exactly one)" % (n, int(numpy.count_nonzero(holders == 1)), len(points)))
    inner = sorted({v for b in boxes for a in range(3) for v in b[2 * a:2 * a + 2]
                    if lo[a] < v < hi[a]})
    check(inner == ([32.0] if n == 2 else [24.0, 32.0]), "%d ranks: inner faces at %s"
          % (n, inner))


def compare(args):
    import numpy
    whole = paged_megabytes(args.work, 1, "")[0]
    for n in args.compare:
        paged = paged_megabytes(args.work, n, args.label)
        print("MB paged: 1 rank %.3f; %d ranks %s (largest %.0f%% of 1 rank's)" % (
            whole, n, ["%.3f" % p for p in paged], 100.0 * max(paged) / whole))
        # Each rank pages the bricks its box, grown by a step and a voxel, touches. The pool's
        # 16^3 bricks (stride 15) make 5 x 4 x 3 at level 0, 3 x 2 x 2 at level 1, then 2 and
        # 1: with 2 ranks (x = 32) each gets 3 of the 5 columns along x at level 0 (the one
        # across the face on both sides) and 2 or 3 of 3 at level 1, 47 and 51 of 75 pages
        # (0.63, 0.68); with 4 ranks (also y = 24) 2 or 3 of the 4 along y as well: at most
        # 42 of 75 (0.56). Bounds 0.8 and 0.65 leave room for a brick the transfer function
        # empties (never paged) and fail if a rank paged the whole pool.
        bound = {2: 0.8, 4: 0.65}.get(n, 1.0)
        check(max(paged) <= bound * whole and min(paged) > 0.0,
              "each of %d ranks paged only its share (at most %.2f of 1 rank's MB, none idle)"
              % (n, bound))
        if n > 1:  # (one process draws everything: no box)
            check_cut(args.work, n, args.label)
    for name in VIEWS:
        dims1, one = load_png(os.path.join(args.work, "parallel_1_%s.png" % name))
        covered = numpy.count_nonzero(one.max(axis=1) > 2)
        check(covered > len(one) // 4, "%s: the scene covers %d of %d pixels (more than a "
              "quarter)" % (name, covered, len(one)))
        for n in args.compare:
            dims, many = load_png(os.path.join(args.work, "parallel_%d%s_%s.png"
                                               % (n, args.label, name)))
            check(dims == dims1, "%s: %d-rank image size" % (name, n))
            if dims != dims1:
                continue
            difference = numpy.abs(many - one)
            worst = int(difference.max())
            differing = int(numpy.count_nonzero(difference.max(axis=1) > 1))
            rms = float(numpy.sqrt(numpy.mean(difference.astype("float64") ** 2)))
            print("%s: %d ranks vs 1: max channel difference %d of 255, RMS %.4f, %d pixels "
                  "differ by more than 1" % (name, n, worst, rms, differing))
            # IceT blends 8-bit RGBA: each rank's premultiplied colour and opacity are
            # rounded (0.5 of 255 each) before C = Cf + (1 - Af) Cb, so every blend along a
            # ray adds up to 1.5, and the two images' own rounding 1 more. A ray crosses at
            # most 2 boxes with 2 ranks and 3 of the 2 x 2 boxes of 4 ranks: 2.5 and 4. One
            # more for the step a box face splits in two (one process splits steps at its
            # BSP faces alike): bounds 4 and 5. Measured: 3 and 3-4, RMS 0.26-0.40. Seams show
            # far above: with the faces moved to lattice points (a ray running past the face
            # into a horizon only the next rank draws) the oblique view reached 29.
            boxes = min(n, 3)
            bound = int(numpy.ceil(1.0 + 1.5 * (boxes - 1))) + 1
            check(worst <= bound and rms <= 0.6,
                  "%s: the %d-rank image equals the 1-rank one within %d of 255 (RMS within "
                  "0.6)" % (name, n, bound))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--make-data", action="store_true")
    parser.add_argument("--render", action="store_true")
    parser.add_argument("--compare", type=int, nargs="*")
    parser.add_argument("--server", help="host:port of a pvserver to render on (pvpython)")
    parser.add_argument("--label", default="",
                        help="added to the image names (parallel_<N><label>_<view>.png)")
    args = parser.parse_args()
    if args.server:
        host, port = args.server.rsplit(":", 1)
        Connect(host, int(port))
        LoadPlugin(args.plugin, remote=True, ns=globals())
    LoadPlugin(args.plugin, remote=False, ns=globals())
    if args.make_data:
        make_data(args.work)
    if args.render:
        render(args)
    if args.compare:
        compare(args)
    print("%d failure(s)" % len(failures))
    if failures:
        # (An exception makes pvbatch exit 1; sys.exit in pvbatch crashes ParaView 5.11.)
        raise RuntimeError("%d check(s) failed: %s" % (len(failures), "; ".join(failures)))


main()

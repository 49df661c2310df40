# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""Distributed benchmark (scripts/bench distributed): the nine-volume paged scene of
`scripts/bench paging` (nine 1024^3 uint8 pools in 32^3 bricks, BenchPaging generate) in
pvbatch under mpirun -np N, each rank drawing its box of the scene (sort-last, IceT).

    mpirun -np N pvbatch BenchDistributed.py --plugin Strata.so --data <pools> --csv <file>
        [--cache MB] [--atlas MB] [--pages N] [--split] [--still] [--png <file>]

The same fly-through as BenchPaging flythrough (48 moving frames, then still until every
rank's cut has settled, at most 100 more), 256 x 256, sample distance 2, feedback at 1/4, the same
transfer function. Budgets are per rank: --split divides the given page cache, atlas and pages
per frame by N (the 1-rank memory and I/O rate spread over the ranks), otherwise every rank has
them whole. --still: no
fly-through, the last pose from the first frame until every rank has settled (one view's I/O,
without the refinement and eviction a moving camera adds). Each rank
writes its own figures through the representation's StatisticsFile; rank 0 then appends one
row to --csv: frame ms (rank 0's wall clock around Render, compositing included: median and
p99), the slowest rank's ray cast per frame (its mapper, GPU finished), compositing (frame minus
that), and per rank the peak RSS, its growth over the run and the MB paged.
"""
import argparse
import math
import os
import time

import paraview.simple
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting interface)

EDGE = 1024
SIZE = [256, 256]
COLORS = [(0, 0.1, 0.2, 0.6), (120, 0.3, 0.7, 0.9), (170, 0.95, 0.8, 0.4), (255, 1.0, 0.3, 0.2)]
OPACITIES = [(0, 0.0), (140, 0.0), (170, 0.02), (210, 0.08), (255, 0.3)]


def percentile(values, q):
    ordered = sorted(values)
    if not ordered:
        return float("nan")
    return ordered[min(len(ordered) - 1, int(math.ceil(q * len(ordered))) - 1 if q > 0 else 0)]


def all_settled(stats, ranks):
    """Whether every rank's cut had settled at the render before the last one (its statistics
    line, written before each render): ParaView's own PagingConverged is rank 0's alone."""
    for rank in range(ranks):
        try:
            with open("%s.%d" % (stats, rank)) as f:
                lines = f.read().split()
        except OSError:
            return False
        fields = lines[-1].split(",") if lines else []
        if len(fields) < 6 or fields[5] != "1":  # (a line being written reads short)
            return False
    return True


def pose(view, s):
    # BenchPaging's path: a low pass across the grid, turning, then still at the last pose.
    centre = [1.6 * EDGE, 1.6 * EDGE, 0.5 * EDGE]
    a = -2.2 + 1.6 * s
    r = (3.6 - 1.2 * s) * EDGE
    view.CameraFocalPoint = [centre[0] + 0.4 * EDGE * math.cos(3 * s), centre[1], centre[2]]
    view.CameraPosition = [centre[0] + r * math.cos(a), centre[1] + r * math.sin(a),
                           centre[2] + (1.5 - 0.5 * s) * EDGE]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--data", required=True)
    parser.add_argument("--csv", required=True)
    parser.add_argument("--cache", type=float, default=256.0)
    parser.add_argument("--atlas", type=float, default=128.0)
    parser.add_argument("--pages", type=int, default=64, help="pages per frame (1 rank)")
    parser.add_argument("--split", action="store_true")
    parser.add_argument("--still", action="store_true",
                        help="no fly-through: the last pose from the first frame until settled")
    parser.add_argument("--png")
    args = parser.parse_args()
    LoadPlugin(args.plugin, remote=False, ns=globals())
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    cache = args.cache / ranks if args.split else args.cache
    atlas = args.atlas / ranks if args.split else args.atlas
    # The pages a frame may read and upload: the I/O rate, split like the memory.
    pages = max(1, args.pages // ranks) if args.split else args.pages

    view = CreateView("RenderView")
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.UseFXAA = 0
    view.CameraViewAngle = 35
    view.CameraViewUp = [0, 0, 1]
    paraview.simple._DisableFirstRenderCameraReset()
    stats = args.csv + ".ranks%d%s%s" % (ranks, "-split" if args.split else "",
                                          "-still" if args.still else "")
    for rank in range(ranks):
        if os.path.exists("%s.%d" % (stats, rank)):
            os.remove("%s.%d" % (stats, rank))
    lut = opacity = None
    first = None
    for i in range(9):
        reader = StrataPagePool(FileName=os.path.join(args.data, "paging-volume-%d.spp" % i))
        display = Show(reader, view)
        display.SetRepresentationType("Strata Volume")
        array = reader.PointData.keys()[0]
        ColorBy(display, ("POINTS", array))
        if lut is None:
            lut = GetColorTransferFunction(array)
            lut.AutomaticRescaleRangeMode = "Never"
            lut.ColorSpace = "RGB"
            lut.RGBPoints = [v for c in COLORS for v in c]
            opacity = GetOpacityTransferFunction(array)
            opacity.Points = [v for o in OPACITIES for v in (o[0], o[1], 0.5, 0.0)]
        display.InterpolationType = "Linear"
        display.ScalarOpacityUnitDistance = 1.0
        display.Position = [(i % 3) * 1.1 * EDGE, (i // 3) * 1.1 * EDGE, 0.0]
        if first is None:
            first = display
    first.StrataVolumeSampleDistance = 2.0
    first.StrataVolumeBrickSize = 32
    first.StrataVolumeAtlasBudget = atlas
    first.StrataVolumePageCacheBudget = cache
    first.StrataVolumePagesPerFrame = pages
    first.StrataVolumeLevelOfDetailFeedback = 1
    first.StrataVolumeStatisticsFile = stats

    moving = 1 if args.still else 48
    frame_ms = []
    converged = -1
    for f in range(moving + 100):
        pose(view, 1.0 if args.still else min(1.0, f / float(moving - 1)))
        t0 = time.perf_counter()
        Render(view)
        frame_ms.append(1000.0 * (time.perf_counter() - t0))
        if f >= moving and all_settled(stats, ranks):
            converged = f - moving + 1
            break
        if f % 16 == 0:
            print("frame %d: %.0f ms" % (f, frame_ms[-1]))
    Render(view)  # (each statistics line describes the render before it)
    if args.png:
        SaveScreenshot(args.png, view, ImageResolution=SIZE, TransparentBackground=0)

    per_rank = []
    for rank in range(ranks):
        with open("%s.%d" % (stats, rank)) as f:
            per_rank.append([[float(v) for v in line.split(",")] for line in f.read().split()])
    frames = len(frame_ms)
    # Line k + 1 of a rank describes render k (line 0: before the first render).
    cast = [max(lines[k + 1][1] for lines in per_rank) for k in range(frames)
            if all(len(lines) > k + 1 for lines in per_rank)]
    composite = [frame_ms[k] - cast[k] for k in range(len(cast))]
    rss = [lines[-1][3] for lines in per_rank]
    growth = [lines[-1][3] - lines[0][3] for lines in per_rank]
    paged = [lines[-1][2] for lines in per_rank]
    header = ("ranks,budgets,cache_mb_per_rank,atlas_mb_per_rank,frames,frames_to_converge,"
              "ms_per_frame_median,ms_per_frame_p99,raycast_ms_slowest_rank_median,"
              "compositing_ms_median,peak_rss_mb_per_rank,rss_growth_mb_per_rank,"
              "mb_paged_per_rank,peak_rss_mb_max,rss_growth_mb_max,mb_paged_max,mb_paged_total,"
              "camera,pages_per_frame_per_rank\n")
    camera = "still" if args.still else "flythrough"
    new = not os.path.exists(args.csv)
    with open(args.csv, "a") as out:
        if new:
            out.write(header)
        out.write("%d,%s,%g,%g,%d,%d,%.1f,%.1f,%.1f,%.1f,%s,%s,%s,%.0f,%.0f,%.1f,%.1f,%s,%d\n" % (
            ranks, "split" if args.split else "per-rank", cache, atlas, frames, converged,
            percentile(frame_ms, 0.5), percentile(frame_ms, 0.99), percentile(cast, 0.5),
            percentile(composite, 0.5), ";".join("%.0f" % v for v in rss),
            ";".join("%.0f" % v for v in growth), ";".join("%.1f" % v for v in paged),
            max(rss), max(growth), max(paged), sum(paged), camera, pages))
    print("%d ranks (%s budgets, %s): %d frames, median %.0f ms, compositing %.0f ms, MB paged %s, "
          "peak RSS %s" % (ranks, "split" if args.split else "per-rank", camera, frames,
                           percentile(frame_ms, 0.5), percentile(composite, 0.5),
                           ["%.1f" % v for v in paged], ["%.0f" % v for v in rss]))


main()

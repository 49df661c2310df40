# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""Colours the plugin tests share (imported by TestPlugin.py, TestParallel.py)."""
from paraview.simple import ColorBy, GetColorTransferFunction

# vtkStackedHeightFieldMapper's own depth colour map (the paper's: deep blue through cyan, green
# and yellow to red), evenly spaced over the range.
DEPTH_STOPS = [(0.15, 0.20, 0.75), (0.10, 0.70, 0.90), (0.20, 0.80, 0.30), (0.95, 0.85, 0.20),
               (0.85, 0.20, 0.15)]


def color_by_depth(display, source, value_range=None):
    """Strata Horizons `display` coloured by its heights through ParaView's Coloring, the colour
    map the mapper's own depth map over the heights' range (what the C++ scenes draw with a
    null lookup table): linear in RGB, not discretized. The range is the source's unless given
    (a paged stack's data in ParaView are the coarsest level: the mapper's range is the
    pools' full one)."""
    array = source.PointData.keys()[0]
    ColorBy(display, ("POINTS", array))
    low, high = value_range or source.PointData[array].GetRange()
    lut = GetColorTransferFunction(array, display)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = [v for k, stop in enumerate(DEPTH_STOPS)
                     for v in (low + (high - low) * k / 4.0,) + stop]
    return lut

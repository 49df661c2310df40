"""Strata: ray casting for very large subsurface data, as VTK classes.

Import it beside VTK's own modules::

    from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow
    import strata
    mapper = strata.vtkStackedHeightFieldMapper()

``strata.vtkHorizonColumnReader``, ``strata.vtkIrapBinaryGridReader``, ``strata.vtkAsciiGridReader``
... are the readers, ``strata.vtkStackedHeightFieldMapper``, ``strata.vtkMultiVolumeRayCastMapper``
and ``strata.vtkHybridVolumeMapper`` the renderers. Importing the package also registers Strata's
offscreen EGL render window where there is no X display (or with STRATA_OFFSCREEN=1), as the C++
modules do through VTK's autoinit.
"""

# The VTK modules Strata's classes derive from, loaded first so that their types are known
# (and VTK's OpenGL factory registered before Strata's own window).
import vtkmodules.vtkCommonDataModel as _vtkCommonDataModel  # noqa: F401
import vtkmodules.vtkCommonExecutionModel as _vtkCommonExecutionModel  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2 as _vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolume as _vtkRenderingVolume  # noqa: F401

from .StrataIO import *  # noqa: F401,F403
from .StrataRendering import *  # noqa: F401,F403


def paging_statistics(mapper):
    """What paging did in the mapper's last frame, as a dict of the fields of its
    GetPagingStatistics() struct: {"Converged": 0 or 1, "BytesRead": ..., "PendingPages": ...}."""
    fields = _vtkCommonDataModel.vtkFieldData()
    mapper.GetPagingStatistics(fields)
    values = {}
    for i in range(fields.GetNumberOfArrays()):
        array = fields.GetArray(i)
        value = array.GetValue(0)
        values[array.GetName()] = value if array.IsA("vtkDoubleArray") else int(value)
    return values


def render_until_converged(window, mapper, frames=500, seconds=1.0):
    """Renders until a paged mapper's cut settles (or `frames` frames), waiting up to `seconds`
    for page loads between frames; returns the number of frames rendered before it settled."""
    for frame in range(frames):
        window.Render()
        if paging_statistics(mapper)["Converged"]:
            return frame
        mapper.WaitForPages(seconds)
    return frames

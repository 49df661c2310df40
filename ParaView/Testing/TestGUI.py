# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""Run by the ParaView GUI (paraview --script=TestGUI.py --exit, see RunGUI.cmake): loads the
plugin as a GUI user's Python shell would, shows a page pool with the Strata Volume
representation and writes what it found to $STRATA_GUI_RESULT (the driver asserts it)."""
import os

from paraview.simple import *  # noqa: F401,F403

lines = []
try:
    LoadPlugin(os.environ["STRATA_PLUGIN"], remote=False, ns=globals())
    reader = StrataPagePool(FileName=os.environ["STRATA_POOL"])
    display = Show(reader)
    lines.append("representations: " + ", ".join(
        t for t in display.GetProperty("Representation").Available if t.startswith("Strata")))
    display.SetRepresentationType("Strata Volume")
    Render()
    display.UpdatePropertyInformation()
    lines.append("volumes in scene: %d" % display.GetPropertyValue("StrataVolumeNumberOfVolumesInScene"))
    lines.append("paged: %d" % display.GetPropertyValue("StrataVolumePaged"))
except Exception as error:  # the GUI swallows exceptions: report them to the driver
    lines.append("error: %s" % error)
with open(os.environ["STRATA_GUI_RESULT"], "w") as f:
    f.write("\n".join(lines) + "\n")

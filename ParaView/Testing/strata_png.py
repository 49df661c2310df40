# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""The PNG reader the ParaView tests (TestPlugin.py, TestParallel.py) compare images with."""


def load_png(path):
    """A PNG's dimensions and its RGB pixels as int32, one row a pixel."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    return image.GetDimensions(), values[:, :3].astype("int32")

"""The ray-casting stage from Python: both mappers take Stages.Fragment, Stages.Compute and
Stages.Auto, report the stage each frame used (GetStageInUse, GetStageInUseAsString) and Auto's
probe (GetStageProbeRatio, compute / fragment time of the same kernel on this device); the images
of the two stages are the same scene (max channel difference at most 1 of 255, the portability
policy for two programs computing the same value). Prints what it measured.
"""
import sys

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkRenderWindow,
                                         vtkRenderer, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory overrides)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

import strata

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def grab(window):
    window.Render()
    w2i = vtkWindowToImageFilter()
    w2i.SetInput(window)
    w2i.Update()
    image = w2i.GetOutput()
    return numpy_support.vtk_to_numpy(image.GetPointData().GetScalars()).astype(np.int32)


def image(values, spacing=1.0):
    data = vtkImageData()
    data.SetDimensions(*values.shape)
    data.SetSpacing(spacing, spacing, spacing)
    data.GetPointData().SetScalars(numpy_support.numpy_to_vtk(values.ravel(order="F"), deep=True))
    return data


def window_with(prop):
    renderer = vtkRenderer()
    renderer.SetBackground(0.1, 0.1, 0.15)
    if isinstance(prop, vtkVolume):
        renderer.AddVolume(prop)
    else:
        renderer.AddActor(prop)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Elevation(30)
    renderer.GetActiveCamera().Azimuth(25)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.SetSize(160, 160)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    return window


def both_stages(name, mapper, window, stages):
    images = {}
    for stage in (stages.Fragment, stages.Compute):
        mapper.SetStage(stage)
        images[stage] = grab(window)
        check(mapper.GetStageInUse() == stage,
              f"{name}: the frame ran in the {mapper.GetStageInUseAsString()} stage as asked")
    diff = np.abs(images[stages.Fragment] - images[stages.Compute])
    covered = np.count_nonzero(np.any(images[stages.Compute] != images[stages.Compute][0], axis=1))
    print(f"{name}: fragment vs compute, max difference {diff.max()} of 255, "
          f"{np.count_nonzero(diff.max(axis=1))} pixels differ; {covered} pixels drawn")
    check(diff.max() <= 1 and covered > 2000, f"{name}: the two stages draw the same scene")
    mapper.SetStage(stages.Auto)
    window.Render()
    ratio = mapper.GetStageProbeRatio()
    expected = stages.Compute if 0 < ratio < 1 else stages.Fragment
    print(f"{name}: Auto's probe, compute / fragment {ratio:.3f}: {mapper.GetStageInUseAsString()}")
    check(ratio > 0 and mapper.GetStageInUse() == expected,
          f"{name}: Auto took the stage its probe measured faster")


# A blob volume, 48^3 floats.
i, j, k = np.meshgrid(np.arange(48.0), np.arange(48.0), np.arange(48.0), indexing="ij")
blob = np.exp(-((i - 24) ** 2 + (j - 20) ** 2 + (k - 26) ** 2) / 150.0).astype(np.float32)
volume_mapper = strata.vtkMultiVolumeRayCastMapper()
volume_mapper.SetInputDataObject(0, image(blob))
volume_mapper.SetSampleDistance(0.5)
color = vtkColorTransferFunction()
color.AddRGBPoint(0.0, 0.2, 0.3, 0.9)
color.AddRGBPoint(1.0, 1.0, 0.8, 0.3)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(0.1, 0.0)
opacity.AddPoint(1.0, 0.3)
volume_property = vtkVolumeProperty()
volume_property.SetColor(color)
volume_property.SetScalarOpacity(opacity)
volume_property.SetInterpolationTypeToLinear()
volume = vtkVolume()
volume.SetMapper(volume_mapper)
volume.SetProperty(volume_property)
both_stages("volume", volume_mapper, window_with(volume), strata.vtkMultiVolumeRayCastMapper.Stages)

# Two horizons on a 96 x 80 grid.
x, y = np.meshgrid(np.arange(96.0), np.arange(80.0), indexing="ij")
horizon_mapper = strata.vtkStackedHeightFieldMapper()
for depth in (10.0, 25.0):
    heights = (depth + 6.0 * np.sin(x / 9.0) * np.cos(y / 11.0)).astype(np.float32)
    horizon_mapper.AddInputData(image(heights[:, :, None]))
actor = vtkActor()
actor.SetMapper(horizon_mapper)
both_stages("horizons", horizon_mapper, window_with(actor), strata.vtkStackedHeightFieldMapper.Stages)

if failures:
    sys.exit(f"FAIL: {len(failures)} checks failed")
print("stages: ok")

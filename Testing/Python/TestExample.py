"""Runs one of Examples/Python/*.py and its C++ twin (StrataExamples) and asserts that the two
images are the same scene: equal pixel for pixel (max channel difference 0 of 255 measured on
llvmpipe; the bound is `--max-difference`), and not empty (at least `--min-covered` of the
pixels differ from the background).

    TestExample.py --example NAME --cxx StrataExamples --examples DIR --out DIR [--data DIR]
                   [--steps N] [--python INTERPRETER]

The ParaView tests run it with ParaView's pvpython and the example under pvpython or pvbatch
(`strata` wrapped against ParaView's VTK).
"""
import argparse
import os
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

parser = argparse.ArgumentParser()
parser.add_argument("--example", required=True)
parser.add_argument("--cxx", required=True, help="the StrataExamples executable")
parser.add_argument("--examples", required=True, help="Examples/Python")
parser.add_argument("--out", required=True)
parser.add_argument("--data")
parser.add_argument("--max-difference", type=int, default=0)
parser.add_argument("--min-covered", type=float, default=0.15)
parser.add_argument("--python", default=sys.executable,
                    help="the interpreter of the example (ParaView's pvpython or pvbatch too)")
parser.add_argument("--steps", type=int, default=0,
                    help="a time series: compare OUT_k.png for k < STEPS instead of OUT.png")
args = parser.parse_args()


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    if image.GetNumberOfPoints() == 0:
        sys.exit(f"FAIL: {path} is not a readable PNG")
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(np.int32)
    return pixels.reshape(height, width, -1)[:, :, :3]


def run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    sys.stdout.write(done.stdout)
    sys.stdout.write(done.stderr)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(command)} exited with {done.returncode}")


os.makedirs(args.out, exist_ok=True)
data = ["--data", args.data] if args.data else []
python_png = os.path.join(args.out, f"python-{args.example}.png")
cxx_png = os.path.join(args.out, f"cxx-{args.example}.png")
work = os.path.join(args.out, f"work-{args.example}")
os.makedirs(work, exist_ok=True)
run([args.python, os.path.join(args.examples, f"{args.example}.py"), python_png] + data)
# The C++ twin renders through Strata's EGL window: no X display for it (ParaView's tests run
# under Xvfb).
run([args.cxx, args.example, cxx_png, "--work", work] + data,
    {k: v for k, v in os.environ.items() if k != "DISPLAY"})



def compare(python_png, cxx_png, label):
    python_image, cxx_image = read_png(python_png), read_png(cxx_png)
    if python_image.shape != cxx_image.shape:
        sys.exit(f"FAIL: image sizes differ: Python {python_image.shape}, C++ {cxx_image.shape}")
    difference = np.abs(python_image - cxx_image)
    background = cxx_image[0, 0]
    covered = np.any(cxx_image != background, axis=2).mean()
    print(f"{label}: Python against C++: max channel difference {difference.max()} of 255, "
          f"{int(np.any(difference > 0, axis=2).sum())} of {difference.shape[0] * difference.shape[1]} "
          f"pixels differ; {100 * covered:.1f} % of the pixels covered")
    if covered < args.min_covered:
        sys.exit(f"FAIL: only {100 * covered:.1f} % of the pixels show the scene "
                 f"(at least {100 * args.min_covered:.0f} % expected)")
    if difference.max() > args.max_difference:
        sys.exit(f"FAIL: max channel difference {difference.max()} > {args.max_difference}")


if args.steps:
    # A time series writes one image per step: OUT_0.png, OUT_1.png, ...
    for k in range(args.steps):
        compare(python_png[:-4] + f"_{k}.png", cxx_png[:-4] + f"_{k}.png",
                f"{args.example} step {k}")
else:
    compare(python_png, cxx_png, args.example)
print(f"{args.example}: ok")

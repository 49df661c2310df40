"""Every setting of every wrapped Strata class round-trips through Python: for each SetX with a
GetX (and no argument), a value other than the default is set and read back. Clamped settings
(GetXMinValue/GetXMaxValue) are tried at a value inside the range and at one beyond each end
(which must read back clamped); enums at every one of their values; booleans both ways; vectors
component by component. Prints the count per class and asserts that no setting fails and that
every class has settings that were tried.
"""
import math
import sys

import strata

# Settings that are not plain values (inputs, connections, objects) or that need a file.
SKIP = {"InputConnection", "InputData", "InputDataObject", "InputArrayToProcess", "Input",
        "PointsInputData", "PointsInputConnection", "LookupTable", "ProgressText",
        "AbortExecute", "ReleaseDataFlag", "ProgressObserver", "InformationInput",
        "Executive", "Progress", "DebugOn", "ReferenceCount", "GlobalWarningDisplay",
        "Debug", "ObjectName", "Output"}


def candidates(obj, name, current):
    """Values to try for setting `name` whose current value is `current`."""
    low = getattr(obj, f"Get{name}MinValue", None)
    high = getattr(obj, f"Get{name}MaxValue", None)
    if isinstance(current, bool):
        return [not current, current]
    kind = type(current)
    if kind is not int and isinstance(current, int):  # a wrapped C++ enum: an int subclass
        return [getattr(kind, m) for m in dir(kind) if isinstance(getattr(kind, m), kind)]
    if isinstance(current, (int, float)):
        if low and high:
            lo, hi = low(), high()
            inside = lo + (hi - lo) * 0.25 if isinstance(current, float) else (lo + hi) // 3
            if inside == current:
                inside = lo
            return [inside, (lo - 1, lo), (hi + 1 if hi < 1e300 else hi, hi), current]
        if isinstance(current, float):
            return [0.75 if math.isnan(current) else current * 0.5 + 0.75, current]
        return [current + 3, current]
    if isinstance(current, tuple) and current and all(isinstance(c, (int, float)) for c in current):
        return [tuple(c + (3 if isinstance(c, int) else 0.5) for c in current), current]
    if isinstance(current, str) or current is None:
        return ["strata-test-value"]
    return []


def same(a, b):
    if isinstance(a, float) or isinstance(b, float):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        return math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9)
    if isinstance(a, tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    return a == b


failures, total = [], 0
classes = sorted(n for n in dir(strata) if n.startswith("vtk") and n != "vtkStrataEGLRenderWindow")
for class_name in classes:
    try:
        obj = getattr(strata, class_name)()
    except TypeError:
        print(f"{class_name}: abstract, its settings are tried on its subclasses")
        continue
    tried = 0
    for attr in sorted(dir(obj)):
        if not attr.startswith("Set"):
            continue
        name = attr[3:]
        getter = getattr(obj, f"Get{name}", None)
        if name in SKIP or getter is None or name.endswith("ToDefault"):
            continue
        try:
            current = getter()
        except TypeError:
            continue  # a getter that takes arguments (per port, per horizon)
        values = candidates(obj, name, current)
        for value in values:
            expected = value
            if isinstance(value, tuple) and len(value) == 2 and isinstance(current, (int, float)):
                value, expected = value
            try:
                getattr(obj, attr)(*value) if isinstance(value, tuple) else getattr(obj, attr)(value)
            except TypeError:
                break  # not a plain value setter (objects, arrays)
            except OverflowError:
                continue  # beyond the C++ type (an unclamped int at its limit)
            got = getter()
            tried += 1
            if not same(got, expected):
                failures.append(f"{class_name}.{name}: set {value!r}, got {got!r}, expected {expected!r}")
    total += tried
    print(f"{class_name}: {tried} round trips")
    if tried == 0:
        failures.append(f"{class_name}: no setting tried")

# The paging settings both mappers share: the same names and the same defaults.
volume, horizons = strata.vtkMultiVolumeRayCastMapper(), strata.vtkStackedHeightFieldMapper()
for name in ("PageCacheBudget", "AtlasBudget", "PagesPerFrame", "Prefetch", "LevelOfDetailFeedback",
             "LevelOfDetailThreshold", "FeedbackScale", "FeedbackOpenCL"):
    a, b = getattr(volume, f"Get{name}")(), getattr(horizons, f"Get{name}")()
    if a != b:
        failures.append(f"{name}: {a!r} on the volume mapper, {b!r} on the horizon mapper")
print("shared paging settings: same names and defaults on both mappers" if not failures else "")

print(f"{total} round trips over {len(classes)} classes, {len(failures)} failures")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)

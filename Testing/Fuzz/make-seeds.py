#!/usr/bin/python3
"""Writes the seed inputs of the text and simple binary formats into corpus/<target>/ (the page
pool and hybrid seeds come from strata-fuzz-seeds, which uses Strata's own writers). Small files
on purpose: a few KB each, so the checked-in corpus stays small and each execution fast.
Run from anywhere: /usr/bin/python3 Testing/Fuzz/make-seeds.py"""
import math
import os
import struct

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "Data")


def put(target, name, data):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def record(payload):
    return struct.pack(">i", len(payload)) + payload + struct.pack(">i", len(payload))


def irap(nx, ny, values, rotation=0.0, chunk=None):
    head = record(struct.pack(">ii6f", -996, ny, 100.0, 100.0 + 12.5 * (nx - 1), 200.0,
                              200.0 + 25.0 * (ny - 1), 12.5, 25.0))
    head += record(struct.pack(">i3f", nx, rotation, 100.0, 200.0))
    head += record(struct.pack(">7i", *([0] * 7)))
    chunk = chunk or nx
    body = b""
    for s in range(0, len(values), chunk):
        body += record(struct.pack(">%df" % len(values[s:s + chunk]), *values[s:s + chunk]))
    return head + body


def seeds_irap():
    v = [float(i % 7) * 1.5 for i in range(6 * 4)]
    put("irap_binary", "grid6x4.gri", irap(6, 4, v))
    v[3] = 1e30
    v[5] = 9999900.0
    put("irap_binary", "holes_rotated_odd_records.gri", irap(6, 4, v, 30.0, chunk=5))
    put("irap_binary", "one_node.gri", irap(1, 1, [42.0]))
    # The first 600 bytes of a real grid (RMS' record layout), truncated mid-row.
    with open(os.path.join(DATA, "horizons", "reek_01_topreek_rota.gri"), "rb") as f:
        put("irap_binary", "reek_truncated.gri", f.read(600))


def npy(array, version=(1, 0), fortran=False):
    header = "{'descr': '%s', 'fortran_order': %s, 'shape': %s, }" % (
        array.dtype.str, fortran, str(array.shape))
    size_bytes = 2 if version == (1, 0) else 4
    pre = 8 + size_bytes
    total = pre + len(header) + 1
    pad = (64 - total % 64) % 64
    header = header + " " * pad + "\n"
    out = b"\x93NUMPY" + bytes(version)
    out += struct.pack("<H" if size_bytes == 2 else "<I", len(header)) + header.encode("latin1")
    return out + (array.T.tobytes() if fortran else array.tobytes())


def seeds_npy():
    a = np.arange(12, dtype="<f4").reshape(3, 4)
    a[1, 2] = np.nan
    put("numpy", "f4_3x4.npy", npy(a))
    put("numpy", "f8_fortran.npy", npy(a.astype("<f8"), fortran=True))
    put("numpy", "i2_big_endian_v2.npy", npy(np.nan_to_num(a).astype(">i2"), version=(2, 0)))
    put("numpy", "u1_v3.npy", npy(np.arange(10, dtype="u1").reshape(5, 2), version=(3, 0)))
    put("numpy", "i8_1d.npy", npy(np.arange(5, dtype="<i8")))
    put("numpy", "u4_3d.npy", npy(np.ones((2, 3, 1), dtype="<u4")))
    with open(os.path.join(DATA, "horizons", "penobscot_seabed_crop.npy"), "rb") as f:
        put("numpy", "penobscot_truncated.npy", f.read(1024))


def seeds_columns():
    with open(os.path.join(DATA, "horizons", "top_heimdal_subset.txt")) as f:
        lines = f.readlines()
    put("horizon_columns", "heimdal_rows.txt", "".join(lines[:40] + lines[251:291]))
    put("horizon_columns", "header_commas.txt",
        "inline,xline,twt\n" + "".join("%d,%d,%.1f\n" % (10 + 2 * i, 100 + j, 1000 + i + j)
                                       for i in range(4) for j in range(5) if (i, j) != (1, 1)))
    rows = []
    c, s = math.cos(0.3), math.sin(0.3)
    for i in range(5):
        for j in range(4):
            x, y = 1000 + 25 * i * c - 12.5 * j * s, 5000 + 25 * i * s + 12.5 * j * c
            rows.append("%.3f %.3f %s\n" % (x, y, "NaN" if (i, j) == (2, 2) else "%.2f" % (i * j)))
    put("horizon_columns", "xyz_rotated.txt", "# x y z\n" + "".join(rows))
    put("horizon_columns", "easting_semicolons.txt", "easting;northing;depth;extra\n" +
        "".join("%d.5;%d.25;%d;7\n" % (i * 10, j * 10, i - j) for i in range(3) for j in range(3)))
    put("horizon_columns", "matrix.txt", "# 3 x 5 matrix\n" +
        "".join(" ".join("%.1f" % (r * 5 + k) for k in range(5)) + "\n" for r in range(3)))


def ibm(v):
    if v == 0:
        return 0
    sign = 0x80000000 if v < 0 else 0
    a, e = abs(v), 0
    while a >= 1:
        a, e = a / 16, e + 1
    while a < 1 / 16:
        a, e = a * 16, e - 1
    return sign | ((e + 64) << 24) | int(a * 16777216)


def segy(fmt, inlines, xlines, samples, missing=(), shuffle=False, il_byte=189, xl_byte=193,
         coords=None):
    """coords: (azimuth in degrees, scalar, mirrored, off-lattice (i, x) or None): CDP X/Y at 181
    and 185 of a 12.5 m x 25 m lattice from 456000 E, 6780000 N, with the scalar at 71."""
    text = b"C 1 STRATA FUZZ SEED".ljust(3200, b" ")
    binary = bytearray(400)
    struct.pack_into(">H", binary, 16, 4000)
    struct.pack_into(">H", binary, 20, samples)
    struct.pack_into(">H", binary, 24, fmt)
    size = {3: 2, 8: 1}.get(fmt, 4)
    order = [(i, x) for i in range(inlines) for x in range(xlines) if (i, x) not in missing]
    if shuffle:
        order = order[1::2] + order[0::2]
    out = text + bytes(binary)
    for i, x in order:
        h = bytearray(240)
        struct.pack_into(">H", h, 114, samples)
        struct.pack_into(">H", h, 116, 4000)
        struct.pack_into(">i", h, il_byte - 1, 10 + 2 * i)
        struct.pack_into(">i", h, xl_byte - 1, 100 + x)
        if coords:
            azimuth, scalar, mirrored, off = coords
            a = math.radians(azimuth)
            side = -1 if mirrored else 1
            xb = x + (1 if (i, x) == off else 0)
            px = 456000 + xb * 12.5 * math.cos(a) - i * 25 * side * math.sin(a)
            py = 6780000 + xb * 12.5 * math.sin(a) + i * 25 * side * math.cos(a)
            f = -scalar if scalar < 0 else 1 / scalar
            struct.pack_into(">h", h, 70, scalar)
            struct.pack_into(">ii", h, 180, round(px * f), round(py * f))
        body = b""
        for s in range(samples):
            v = (i - 1) * 12 + (x - 1) * 3 - s
            if fmt == 1:
                body += struct.pack(">I", ibm(v * 1.5))
            elif fmt == 5:
                body += struct.pack(">f", v * 1.5)
            else:
                body += struct.pack(">" + {2: "i", 3: "h", 8: "b"}[fmt], v)
        out += bytes(h) + body
    return out


def seeds_segy():
    put("segy", "ibm_3x2x4.sgy", segy(1, 3, 2, 4))
    put("segy", "ieee_shuffled_hole.sgy", segy(5, 3, 3, 3, missing=((1, 1),), shuffle=True))
    put("segy", "int16_2x2x5.sgy", segy(3, 2, 2, 5))
    put("segy", "int8_bytes9_21.sgy", segy(8, 2, 3, 2, il_byte=9, xl_byte=21))
    put("segy", "int32_one_trace.sgy", segy(2, 1, 1, 6))
    put("segy", "ieee_utm_rotated.sgy", segy(5, 3, 4, 3, coords=(30, -100, False, None)))
    put("segy", "int16_utm_mirrored_offgrid.sgy",
        segy(3, 3, 3, 2, missing=((0, 2),), coords=(127, -10, True, (1, 1))))


def mha(dims, etype, data, extra=""):
    head = "ObjectType = Image\nNDims = %d\nDimSize = %s\n" % (len(dims), " ".join(map(str, dims)))
    head += "ElementSpacing = %s\nOffset = %s\n" % (" ".join(["0.5"] * len(dims)),
                                                   " ".join(["1"] * len(dims)))
    head += extra + "ElementType = %s\nElementDataFile = LOCAL\n" % etype
    return head.encode() + data


def seeds_metaimage():
    put("streaming_metaimage", "uchar_4x3x2.mha",
        mha((4, 3, 2), "MET_UCHAR", bytes(range(24))))
    put("streaming_metaimage", "short_msb_2d.mha",
        mha((3, 2), "MET_SHORT", struct.pack(">6h", *range(-3, 3)),
            "BinaryDataByteOrderMSB = True\n"))
    put("streaming_metaimage", "float_channels.mha",
        mha((2, 2, 2), "MET_FLOAT", struct.pack("<16f", *range(16)),
            "ElementNumberOfChannels = 2\n"))
    put("streaming_metaimage", "double_headersize.mha",
        mha((2, 2, 3), "MET_DOUBLE", b"\0" * 8 + struct.pack("<12d", *range(12)),
            "HeaderSize = 8\n"))
    put("streaming_metaimage", "compressed.mha",
        mha((2, 2, 2), "MET_UINT", b"x\x9c" + b"\0" * 8, "CompressedData = True\n"))
    put("streaming_metaimage", "external.mhd",
        ("NDims = 3\nDimSize = 2 2 2\nElementType = MET_USHORT\nElementDataFile = data.raw\n"))


if __name__ == "__main__":
    seeds_irap()
    seeds_npy()
    seeds_columns()
    seeds_segy()
    seeds_metaimage()

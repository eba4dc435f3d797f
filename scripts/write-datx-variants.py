#!/usr/bin/env python3
"""Writes the Zygo DATX variants of fixtures/surface/datx/ with h5py (an
HDF5 writer independent of tribo's reader), laid out as the real file
fixtures/surface/zygo_test.datx is: Data/Surface/{GUID} with `No Data`,
`Unit` and the X/Y/Z Converter compounds (Category, BaseUnit: vlen
strings; Parameters: a vlen sequence of f64), an Attributes/{GUID} group
with the instrument's attributes, and a MetaData table.

Heights: the value stored at row r, column c is
    v(r, c) = ((7 r + 3 c) % 23 - 11) + 0.25
in the file's height unit (`tests/binary_datx.rs` computes the same
numbers); the pixel size is given per variant. Run from the repository
root:  python3 scripts/write-datx-variants.py
"""

import os

import h5py
import numpy as np

OUT = "fixtures/surface/datx"
GUID = "{00000000-0000-0000-0000-000000000001}"
NO_DATA = np.finfo(np.float64).max
STR = h5py.string_dtype("ascii")
CONVERTER = np.dtype(
    [("Category", STR), ("BaseUnit", STR), ("Parameters", h5py.vlen_dtype(np.float64))]
)
TIMEB = np.dtype([("time", "<i8"), ("millitm", "<u2"), ("timezone", "<i2"), ("dstflag", "<i2")])


def heights(rows, cols):
    r, c = np.mgrid[0:rows, 0:cols]
    return ((7 * r + 3 * c) % 23 - 11) + 0.25


def converter(category, unit, params):
    return np.array([(category, unit, np.array(params, dtype=np.float64))], dtype=CONVERTER)


def surface_attrs(d, unit, dx, dy, z_params, no_data=NO_DATA, fringes=False):
    d.attrs["No Data"] = np.array([no_data])
    d.attrs.create("Unit", np.array([unit], dtype=object), dtype=STR)
    d.attrs["X Converter"] = converter("LateralCat", "Pixels", [0, dx, 0, 0])
    d.attrs["Y Converter"] = converter("LateralCat", "Pixels", [0, dy, 0, 0])
    d.attrs["Z Converter"] = converter("HeightCat", unit, z_params)
    if fringes:
        d.attrs["Wavelength"] = np.array([z_params[1]])
        d.attrs["Interferometric Scale Factor"] = np.array([z_params[2]])
        d.attrs["Obliquity Factor"] = np.array([z_params[3]])


def instrument(f):
    g = f.create_group("Attributes/" + GUID)
    p = "Data Context.Data Attributes."
    for k, v in [
        ("System Type", "NewView 9000"),
        ("System Serial Number", "12345"),
        ("Software Info Name", "Mx"),
        ("Software Info Version", "7.3.0"),
        ("Objective", "50x Mirau"),
    ]:
        g.attrs.create(p + k, np.array([v], dtype=object), dtype=STR)
    g.attrs[p + "Time Stamp"] = np.array([(1_700_000_000, 250, 60, 0)], dtype=TIMEB)
    rows = [("Root", "Measurement", "{M}"), ("{M}", "Surface", GUID)]
    f.create_dataset("MetaData", data=np.array(rows, dtype=object), dtype=STR)


def write(name, z, unit, dx, dy, z_params, libver="earliest", extra=None, **kw):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, name)
    with h5py.File(path, "w", libver=libver, userblock_size=kw.pop("userblock", 0)) as f:
        fringes = kw.pop("fringes", False)
        no_data = kw.pop("no_data", NO_DATA)
        d = f.create_dataset("Data/Surface/" + GUID, data=z, **kw)
        surface_attrs(d, unit, dx, dy, z_params, no_data, fringes)
        instrument(f)
        if extra:
            extra(f)
    print(path, os.path.getsize(path), "bytes")


def intensity(f):
    i = np.arange(12 * 9, dtype=np.uint16).reshape(12, 9) * 10
    f.create_dataset("Data/Intensity/{00000000-0000-0000-0000-000000000002}", data=i)


def main():
    z = heights(12, 9)
    # Chunked (5 × 4: partial chunks at the edges), gzip and shuffle; an
    # intensity image as a second channel.
    write("chunked-gzip-nm.datx", z, "NanoMeters", 2e-6, 2e-6, [0, 1, 0, 0],
          chunks=(5, 4), compression="gzip", shuffle=True, extra=intensity)
    # HDF5 1.10+ latest format: superblock v3, OHDR headers, compact links.
    write("latest-um.datx", z, "MicroMeters", 5e-7, 5e-7, [0, 1, 0, 0], libver="latest")
    # The same, chunked and compressed (fixed-array chunk index).
    write("latest-chunked-um.datx", z, "MicroMeters", 5e-7, 5e-7, [0, 1, 0, 0],
          libver="latest", chunks=(5, 4), compression="gzip")
    # Non-square pixels, row 3 all No Data, and NaN at (5, 2) and (7, 8).
    zz = z.copy()
    zz[3, :] = NO_DATA
    zz[5, 2] = np.nan
    zz[7, 8] = np.nan
    write("nodata-nonsquare-um.datx", zz, "MicroMeters", 1e-6, 3e-6, [0, 1, 0, 0])
    # Fringes of 632.8 nm with scale factor 0.5 and obliquity 1.25, after a
    # 512-byte user block; NaN as the no-data value.
    zf = z.copy()
    zf[0, 0] = np.nan
    write("fringes-userblock.datx", zf, "Fringes", 1e-3, 1e-3, [0, 632.8e-9, 0.5, 1.25],
          userblock=512, fringes=True, no_data=np.nan)
    # No Surface dataset: an HDF5 file that is not a DATX file.
    with h5py.File(os.path.join(OUT, "no-surface.h5"), "w") as f:
        f.create_dataset("Data/Other", data=z)


if __name__ == "__main__":
    main()

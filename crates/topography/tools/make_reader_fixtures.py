#!/usr/bin/env python3
"""Writes the reader fixtures of crates/topography/tests/readers.rs with programs other than
stiction: .npy files with numpy's own np.save, and a Gwyddion Simple Field (.gsf) written here
byte by byte from Gwyddion's documented format
(http://gwyddion.net/documentation/user-guide-en/gsf.html):

  magic line   "Gwyddion Simple Field 1.0\\n"
  text header  "name = value\\n" lines (XRes, YRes mandatory; XReal, YReal in XYUnits; ZUnits)
  NUL padding  one to four NUL bytes, so that the data starts at a multiple of 4
  binary data  XRes * YRes little-endian IEEE float32, row by row from the top, each row left to right

The map is known in closed form, so the test can check every pixel at its place:

  z[iy, ix] = (ix + 100 iy + 0.5) nm     (NX = 5 columns, NY = 3 rows; non-square, so a transposed
                                          read is a different shape and every value is distinct)

with one missing pixel (NaN) at iy = 1, ix = 3 in the .npy files. Pixel size 0.25 um.

Run from the repository root (numpy; the CI only reads the committed files):

  python3 crates/topography/tools/make_reader_fixtures.py
"""

import os
import struct

import numpy as np

NX, NY = 5, 3
PIXEL_M = 0.25e-6
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "fixtures")


def known_map():
    iy, ix = np.mgrid[0:NY, 0:NX]
    return (ix + 100.0 * iy + 0.5) * 1e-9


def main():
    os.makedirs(OUT, exist_ok=True)
    z = known_map()
    with_nan = z.copy()
    with_nan[1, 3] = np.nan
    # np.save writes shape (NY, NX), C order unless the array is Fortran-contiguous.
    np.save(os.path.join(OUT, "known_c_f8.npy"), with_nan.astype("<f8"))
    np.save(os.path.join(OUT, "known_fortran_f8.npy"), np.asfortranarray(with_nan.astype("<f8")))
    np.save(os.path.join(OUT, "known_big_f8.npy"), with_nan.astype(">f8"))
    np.save(os.path.join(OUT, "known_c_f4.npy"), with_nan.astype("<f4"))
    np.save(os.path.join(OUT, "known_big_fortran_f4.npy"), np.asfortranarray(with_nan.astype(">f4")))
    # Gwyddion Simple Field, from the documented layout (no numpy writer involved).
    header = (
        "Gwyddion Simple Field 1.0\n"
        f"XRes = {NX}\n"
        f"YRes = {NY}\n"
        f"XReal = {NX * PIXEL_M!r}\n"
        f"YReal = {NY * PIXEL_M!r}\n"
        "XYUnits = m\n"
        "ZUnits = m\n"
        "Title = known map z = (ix + 100 iy + 0.5) nm\n"
    ).encode("ascii")
    padding = 4 - len(header) % 4  # one to four NUL bytes
    data = b"".join(struct.pack("<f", float(z[iy, ix])) for iy in range(NY) for ix in range(NX))
    with open(os.path.join(OUT, "known.gsf"), "wb") as f:
        f.write(header + b"\0" * padding + data)
    for name in sorted(os.listdir(OUT)):
        print(name, os.path.getsize(os.path.join(OUT, name)))


if __name__ == "__main__":
    main()

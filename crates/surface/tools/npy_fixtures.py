#!/usr/bin/env python3
"""Writes the .npy summit fixtures of crates/surface/tests/npy.rs with NumPy itself, so that the
reader is tested against files it did not write (a bug shared by the reader and the writer cannot
pass). Run from the repository root with NumPy installed:

    python3 crates/surface/tools/npy_fixtures.py

The values (metres) are those the tests expect: row k has x = (k + 1) * 1.5e-6,
y = (k + 1) * 0.5e-6, height = (k - 2) * 1.25e-8, radius = 0.5e-6 + k * 0.1e-6, k = 0..4, over an
apparent area of 20 um x 5 um.
"""
import os

import numpy as np

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data")

k = np.arange(5, dtype=np.float64)
x = (k + 1) * 1.5e-6
y = (k + 1) * 0.5e-6
h = (k - 2) * 1.25e-8
r = 0.5e-6 + k * 0.1e-6
table = np.stack([x, y, h, r], axis=1)  # N x 4


def save(name, arr):
    np.save(os.path.join(OUT, name), arr)


os.makedirs(OUT, exist_ok=True)
save("summits_f8_c.npy", np.ascontiguousarray(table, dtype="<f8"))
save("summits_f8_fortran_big_endian.npy", np.asfortranarray(table.astype(">f8")))
save("summits_f4_big_endian.npy", np.ascontiguousarray(table.astype(">f4")))
rec = np.zeros(5, dtype=[("x", "<f8"), ("y", ">f8"), ("height", "<f8"), ("radius", "<f4")])
rec["x"], rec["y"], rec["height"], rec["radius"] = x, y, h, r
save("summits_structured.npy", rec)
rec3 = np.zeros(5, dtype=[("height_m", "<f8"), ("x_m", "<f8"), ("y_m", "<f8")])
rec3["x_m"], rec3["y_m"], rec3["height_m"] = x, y, h
save("summits_structured_no_radius.npy", rec3)
save("heights_f8.npy", h.astype("<f8"))
save("wrong_int64.npy", np.arange(20, dtype="<i8").reshape(5, 4))
save("wrong_shape_n_by_3.npy", table[:, :3].copy())

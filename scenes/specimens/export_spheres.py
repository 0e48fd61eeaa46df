#!/usr/bin/python3
"""Writes the last frame of a mesocrack output (e.g. of `mesocrack generate`) as a sphere list `id x y z r tag`,
the spheres whose centres lie within 3 r of the lower / upper end face along z tagged 1 / 2 (one layer: the
supports of Šmilauer's uniaxial setup), the others 0.  Usage: export_spheres.py OUT.h5 SPHERES"""
import sys
import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    r = f["/specimen/radius"][:]
    x = f["/frames/x"][-1].reshape(-1, 3)
lo, hi = (x[:, 2] - r).min(), (x[:, 2] + r).max()
tag = np.where(x[:, 2] < lo + 3 * r, 1, np.where(x[:, 2] > hi - 3 * r, 2, 0))
with open(sys.argv[2], "w") as out:
    out.write("# id x y z r tag [m]: scenes/specimens/cpm_1x1x2.toml by `mesocrack generate`, exported by\n"
              "# export_spheres.py; tags 1, 2: centres within 3 r of the lower, upper end face\n")
    for i in range(len(r)):
        out.write("%d %.12e %.12e %.12e %.12e %d\n" % (i, x[i, 0], x[i, 1], x[i, 2], r[i], tag[i]))
print("%d spheres, %d and %d in the end layers" % (len(r), (tag == 1).sum(), (tag == 2).sum()))

#!/usr/bin/python3
"""Compares two folders of PNG pictures (read with VTK's PNG reader): for every picture of the
first, the share of its pixels that differ in the second. Exits 1 if a picture is missing, has
another size, or more than --most (default 0.001) of its pixels differ.
Usage: compare_pictures.py DIR_A DIR_B [--most 0.001]"""
import os
import sys

import numpy as np
import vtk
from vtkmodules.util.numpy_support import vtk_to_numpy


def pixels(path):
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetScalars())


def main():
    a, b = sys.argv[1], sys.argv[2]
    most = float(sys.argv[sys.argv.index("--most") + 1]) if "--most" in sys.argv else 0.001
    names = sorted(f for f in os.listdir(a) if f.endswith(".png"))
    if not names:
        sys.exit(f"{a}: no picture")
    worst = 0.0
    for name in names:
        if not os.path.exists(os.path.join(b, name)):
            sys.exit(f"{name}: missing in {b}")
        (da, pa), (db, pb) = pixels(os.path.join(a, name)), pixels(os.path.join(b, name))
        if da != db:
            sys.exit(f"{name}: {da} pixels against {db}")
        if pa.shape != pb.shape:
            sys.exit(f"{name}: {pa.shape} values against {pb.shape}")
        differ = (pa != pb).reshape(len(pa), -1).any(axis=1)
        share = np.count_nonzero(differ) / len(pa)
        worst = max(worst, share)
        print(f"{name}: {share:.5%} of {len(pa)} pixels differ")
    return 0 if worst <= most else 1


if __name__ == "__main__":
    sys.exit(main())

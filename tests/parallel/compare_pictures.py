#!/usr/bin/python3
"""Compares two folders of PNG pictures (read with VTK's PNG reader): for every picture of the
first, the share of its pixels that differ in the second. Exits 1 if a picture is missing, has
another size, or more than --most (default 0.001) of its pixels differ.
Usage: compare_pictures.py DIR_A DIR_B [--most 0.001]"""
import os
import sys

import vtk


def pixels(path):
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    return image.GetDimensions(), [scalars.GetTuple(k) for k in range(scalars.GetNumberOfTuples())]


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
        share = sum(1 for u, v in zip(pa, pb) if u != v) / len(pa)
        worst = max(worst, share)
        print(f"{name}: {share:.5%} of {len(pa)} pixels differ")
    return 0 if worst <= most else 1


if __name__ == "__main__":
    sys.exit(main())

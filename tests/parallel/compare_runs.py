#!/usr/bin/python3
"""Compares the particles of two runs' outputs (a .vtu or .pvtu each, read with VTK's own
readers), matched by p.particleID: per array, the largest difference relative to that array's
scale (its largest magnitude in the first run), and the totals of mass and lithium (with p.mass
saved). Exits 1 if the particle sets differ, an array differs by more than the tolerance or a
total by more than 1e-12. Usage: compare_runs.py A B [--tolerance 1e-9]"""
import sys

import numpy as np
import vtk
from vtkmodules.util.numpy_support import vtk_to_numpy


def read(path):
    if path.endswith(".pvtu"):
        reader = vtk.vtkXMLPUnstructuredGridReader()
    else:
        reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    out = reader.GetOutput()
    if (
        out is None
        or reader.GetErrorCode() != 0
        or out.GetPointData().GetArray("p.particleID") is None
    ):
        sys.exit(f"{path}: not readable as particle output")
    # As doubles, the integer arrays too: compared like the others.
    arrays = {"p.x": vtk_to_numpy(out.GetPoints().GetData()).astype(float)}
    data = out.GetPointData()
    for k in range(data.GetNumberOfArrays()):
        arrays[data.GetArrayName(k)] = vtk_to_numpy(data.GetArray(k)).astype(float)
    order = np.argsort(arrays["p.particleID"], kind="stable")
    return {name: values[order] for name, values in arrays.items()}


def main():
    args = sys.argv[1:]
    tolerance = 1e-9
    if "--tolerance" in args:
        k = args.index("--tolerance")
        tolerance = float(args[k + 1])
        del args[k : k + 2]
    a, b = read(args[0]), read(args[1])
    if not np.array_equal(a["p.particleID"], b["p.particleID"]):
        print(
            f"particle sets differ: {len(a['p.particleID'])} and {len(b['p.particleID'])} particles"
        )
        return 1
    worst = 0.0
    for name in sorted(a):
        if name not in b:
            print(f"{name}: missing in {args[1]}")
            return 1
        if a[name].shape != b[name].shape:
            print(f"{name}: {a[name].shape} values against {b[name].shape} in {args[1]}")
            return 1
        scale = np.abs(a[name]).max(initial=0.0)
        diff = np.abs(a[name] - b[name]).max(initial=0.0)
        rel = diff / scale if scale > 0 else diff
        worst = max(worst, rel)
        print(f"{name:28s} max |difference| / scale = {rel:.3e}")
    # Totals: mass, and lithium sum m c, to 1e-12 relative.
    totals_ok = True
    if "p.mass" in a:
        for label, weight in (("mass", None), ("lithium", "p.concentration")):
            if weight is not None and weight not in a:
                continue

            def total(run):
                # Added one by one in ID order: the totals are printed to 17 digits.
                return sum((run["p.mass"] * (run[weight] if weight else 1.0)).tolist())

            ta, tb = total(a), total(b)
            rel = abs(ta - tb) / abs(ta) if ta else abs(tb)
            totals_ok = totals_ok and rel <= 1e-12
            print(f"total {label:22s} {ta:.17g} and {tb:.17g}: relative difference {rel:.3e}")
    print(
        f"{len(a['p.particleID'])} particles, largest relative difference {worst:.3e} "
        f"(tolerance {tolerance:g})"
    )
    return 0 if worst <= tolerance and totals_ok else 1


if __name__ == "__main__":
    sys.exit(main())

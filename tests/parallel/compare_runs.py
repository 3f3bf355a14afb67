#!/usr/bin/python3
"""Compares the particles of two runs' outputs (a .vtu or .pvtu each, read with VTK's own
readers), matched by p.particleID: per array, the largest difference relative to that array's
scale (its largest magnitude in the first run), and the totals of mass and lithium (with p.mass
saved). Exits 1 if the particle sets differ, an array differs by more than the tolerance or a
total by more than 1e-12. Usage: compare_runs.py A B [--tolerance 1e-9]"""
import sys

import vtk


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
    n = out.GetNumberOfPoints()
    arrays = {"p.x": [out.GetPoint(i) for i in range(n)]}
    data = out.GetPointData()
    for k in range(data.GetNumberOfArrays()):
        a = data.GetArray(k)
        arrays[data.GetArrayName(k)] = [a.GetTuple(i) for i in range(n)]
    order = sorted(range(n), key=lambda i: arrays["p.particleID"][i][0])
    return {name: [values[i] for i in order] for name, values in arrays.items()}


def main():
    args = sys.argv[1:]
    tolerance = 1e-9
    if "--tolerance" in args:
        k = args.index("--tolerance")
        tolerance = float(args[k + 1])
        del args[k : k + 2]
    a, b = read(args[0]), read(args[1])
    if a["p.particleID"] != b["p.particleID"]:
        print(
            f"particle sets differ: {len(a['p.particleID'])} and {len(b['p.particleID'])} particles"
        )
        return 1
    worst = 0.0
    for name in sorted(a):
        if name not in b:
            print(f"{name}: missing in {args[1]}")
            return 1
        scale = max((abs(v) for t in a[name] for v in t), default=0.0)
        diff = max(
            (abs(u - v) for s, t in zip(a[name], b[name]) for u, v in zip(s, t)), default=0.0
        )
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
                return sum(
                    m[0] * (run[weight][i][0] if weight else 1.0)
                    for i, m in enumerate(run["p.mass"])
                )

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

#!/usr/bin/python3
"""Opens a run's particles.pvd with VTK's own readers, as ParaView does: every time it lists,
each with its points and arrays. --like B: the same times, particle counts and array names (and
components) as the series B. --any: every listed file opens.
Usage: read_series.py SERIES.pvd [--like OTHER.pvd | --any]"""
import os
import sys
import xml.etree.ElementTree as ET

import vtk


def series(path):
    """(time, particle count, {array: components}) per entry of the .pvd, each file opened with
    VTK's generic XML reader (the reader ParaView's .pvd reader hands each file to)."""
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    times = []
    for entry in root.iter("DataSet"):
        t = float(entry.get("timestep"))
        reader = vtk.vtkXMLGenericDataObjectReader()
        reader.SetFileName(os.path.join(folder, entry.get("file")))
        reader.Update()
        data = reader.GetOutput()
        if data is None or reader.GetErrorCode() != 0 or data.GetNumberOfPoints() == 0:
            sys.exit(f"{path}: the output at t = {t} ({entry.get('file')}) does not open")
        arrays = {}
        point_data = data.GetPointData()
        for k in range(point_data.GetNumberOfArrays()):
            a = point_data.GetArray(k)
            if a.GetNumberOfTuples() != data.GetNumberOfPoints():
                sys.exit(
                    f"{path}: t = {t}: {a.GetName()} has {a.GetNumberOfTuples()} values for "
                    f"{data.GetNumberOfPoints()} particles"
                )
            arrays[a.GetName()] = a.GetNumberOfComponents()
        times.append((t, data.GetNumberOfPoints(), arrays))
    return times


def main():
    a = series(sys.argv[1])
    if not a and "--any" not in sys.argv:
        sys.exit(f"{sys.argv[1]}: no time")
    for t, n, arrays in a:
        print(f"t = {t:.6g}: {n} particles, {len(arrays)} arrays")
    if "--like" in sys.argv:
        b = series(sys.argv[sys.argv.index("--like") + 1])
        # Times to round-off: the ranks sum shared nodes in another order, so dt (Eq. 43 from the
        # particle velocities) may differ in its last bits.
        same = len(a) == len(b) and all(
            abs(ta - tb) <= 1e-12 * max(abs(ta), abs(tb)) and (na, xa) == (nb, xb)
            for (ta, na, xa), (tb, nb, xb) in zip(a, b)
        )
        if not same:
            sys.exit("the series differ in times, particle counts or arrays")
        print(f"{len(a)} times, the same particles and arrays as the other series")
    return 0


if __name__ == "__main__":
    sys.exit(main())

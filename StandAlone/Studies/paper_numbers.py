"""Reads a run's particle output (VTK's XML readers, /usr/bin/python3 with python3-vtk9)."""
import os
import xml.etree.ElementTree as ET


def outputs(run_dir):
    """(time, file) of every entry of the run's particles.pvd."""
    pvd = os.path.join(run_dir, "particles.pvd")
    entries = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    return [(float(e.get("timestep")), os.path.join(run_dir, e.get("file"))) for e in entries]


def read_output(run_dir, time, arrays):
    """The arrays (and "time", "points") of the output nearest to `time`, as Python lists."""
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    t, path = min(outputs(run_dir), key=lambda e: abs(e[0] - time))
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    n = grid.GetNumberOfPoints()
    points = grid.GetPoints().GetData()
    data = dict(time=t, points=[points.GetTuple3(i) for i in range(n)])
    for name in arrays:
        a = grid.GetPointData().GetArray(name)
        if a is None:
            raise RuntimeError("%s holds no array %s" % (path, name))
        k = a.GetNumberOfComponents()
        data[name] = [a.GetValue(i) for i in range(n)] if k == 1 else [a.GetTuple(i) for i in range(n)]
    return data

#include "vis/VTKWriters.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "Core/Util/AtomicFile.h"

namespace anode {

namespace {

// Wraps the array's own storage (no copy: output must not double the memory of a large run);
// `a` must outlive the VTK object.
vtkSmartPointer<vtkDataArray> toVTK(const NamedArray& a, size_t tuples) {
  const vtkIdType values = static_cast<vtkIdType>(tuples) * a.components;
  if (a.isInteger()) {
    auto arr = vtkSmartPointer<vtkTypeInt64Array>::New();
    arr->SetName(a.name.c_str());
    arr->SetNumberOfComponents(a.components);
    arr->SetArray(
        const_cast<vtkTypeInt64*>(reinterpret_cast<const vtkTypeInt64*>(a.integer.data())), values,
        1);
    return arr;
  }
  auto arr = vtkSmartPointer<vtkDoubleArray>::New();
  arr->SetName(a.name.c_str());
  arr->SetNumberOfComponents(a.components);
  arr->SetArray(const_cast<double*>(a.real.data()), values, 1);
  return arr;
}

template <class Writer>
void runWriter(Writer* writer, const std::string& path) {
  writeAtomically(path, [&](const std::string& tmp) {
    writer->SetFileName(tmp.c_str());
    writer->SetDataModeToBinary();
    writer->SetCompressorTypeToZLib();
    // Level 1: particle doubles barely compress further at VTK's default 5 (the same 15 MB for
    // three outputs of the 141k-particle case), which takes a third longer.
    writer->SetCompressionLevel(1);
    if (writer->Write() != 1) throw std::runtime_error("VTK could not write " + tmp);
  });
}

}  // namespace

void writeParticlesVTU(const std::string& path, const ParticleData& data) {
  const size_t n = data.count();
  auto coordinates = vtkSmartPointer<vtkDoubleArray>::New();
  coordinates->SetNumberOfComponents(3);
  coordinates->SetArray(const_cast<double*>(data.points.data()), static_cast<vtkIdType>(3 * n), 1);
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coordinates);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(static_cast<vtkIdType>(n), static_cast<vtkIdType>(n));
  for (size_t i = 0; i < n; ++i) {
    const vtkIdType id = static_cast<vtkIdType>(i);
    cells->InsertNextCell(1, &id);
  }
  auto ug = vtkSmartPointer<vtkUnstructuredGrid>::New();
  ug->SetPoints(points);
  ug->SetCells(VTK_VERTEX, cells);
  for (const NamedArray& a : data.arrays) ug->GetPointData()->AddArray(toVTK(a, n));
  auto writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
  writer->SetInputData(ug);
  runWriter(writer.Get(), path);
}

void writeGridVTI(const std::string& path, const GridData& data) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(data.dims[0], data.dims[1], data.dims[2]);
  image->SetOrigin(data.origin[0], data.origin[1], data.origin[2]);
  image->SetSpacing(data.spacing[0], data.spacing[1], data.spacing[2]);
  const size_t nodes = static_cast<size_t>(data.dims[0]) * data.dims[1] * data.dims[2];
  for (const NamedArray& a : data.arrays) image->GetPointData()->AddArray(toVTK(a, nodes));
  auto writer = vtkSmartPointer<vtkXMLImageDataWriter>::New();
  writer->SetInputData(image);
  runWriter(writer.Get(), path);
}

void PVDSeries::write(const std::string& path) const {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  "
       "<Collection>\n";
  s << std::setprecision(17);
  for (const auto& [time, file] : entries_)
    s << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << file
      << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path, s.str());
}

}  // namespace anode

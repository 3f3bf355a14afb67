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
  image->SetExtent(data.first[0], data.first[0] + data.dims[0] - 1, data.first[1],
                   data.first[1] + data.dims[1] - 1, data.first[2],
                   data.first[2] + data.dims[2] - 1);
  image->SetOrigin(data.origin[0], data.origin[1], data.origin[2]);
  image->SetSpacing(data.spacing[0], data.spacing[1], data.spacing[2]);
  const size_t nodes = static_cast<size_t>(data.dims[0]) * data.dims[1] * data.dims[2];
  for (const NamedArray& a : data.arrays) image->GetPointData()->AddArray(toVTK(a, nodes));
  auto writer = vtkSmartPointer<vtkXMLImageDataWriter>::New();
  writer->SetInputData(image);
  runWriter(writer.Get(), path);
}

namespace {

// The <PDataArray> lines of a parallel file for the arrays of one piece.
std::string parallelArrays(const std::vector<NamedArray>& arrays) {
  std::ostringstream s;
  for (const NamedArray& a : arrays)
    s << "      <PDataArray type=\"" << (a.isInteger() ? "Int64" : "Float64") << "\" Name=\""
      << a.name << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
  return s.str();
}

}  // namespace

void writeParticlesPVTU(const std::string& path, const std::vector<std::string>& pieces,
                        const ParticleData& sample) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
    << "  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n"
    << parallelArrays(sample.arrays) << "    </PPointData>\n"
    << "    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" "
       "NumberOfComponents=\"3\"/>\n    </PPoints>\n"
    << "    <PCells>\n      <PDataArray type=\"Int64\" Name=\"connectivity\"/>\n"
    << "      <PDataArray type=\"Int64\" Name=\"offsets\"/>\n"
    << "      <PDataArray type=\"UInt8\" Name=\"types\"/>\n    </PCells>\n";
  for (const std::string& piece : pieces) s << "    <Piece Source=\"" << piece << "\"/>\n";
  s << "  </PUnstructuredGrid>\n</VTKFile>\n";
  writeFileAtomically(path, s.str());
}

void writeGridPVTI(const std::string& path, const std::vector<std::string>& pieces,
                   const std::vector<std::array<int, 6>>& pieceExtents,
                   const std::array<int, 6>& wholeExtent, const GridData& sample) {
  auto extent = [](const std::array<int, 6>& e) {
    std::ostringstream s;
    for (int k = 0; k < 6; ++k) s << (k ? " " : "") << e[k];
    return s.str();
  };
  std::ostringstream s;
  s << std::setprecision(17) << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
    << "  <PImageData WholeExtent=\"" << extent(wholeExtent) << "\" GhostLevel=\"0\" Origin=\""
    << sample.origin[0] << " " << sample.origin[1] << " " << sample.origin[2] << "\" Spacing=\""
    << sample.spacing[0] << " " << sample.spacing[1] << " " << sample.spacing[2] << "\">\n"
    << "    <PPointData>\n"
    << parallelArrays(sample.arrays) << "    </PPointData>\n";
  for (size_t k = 0; k < pieces.size(); ++k)
    s << "    <Piece Extent=\"" << extent(pieceExtents[k]) << "\" Source=\"" << pieces[k]
      << "\"/>\n";
  s << "  </PImageData>\n</VTKFile>\n";
  writeFileAtomically(path, s.str());
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

#include "vis/VTKReaders.h"

#include <tinyxml2.h>
#include <vtkDataArray.h>
#include <vtkDataArraySelection.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>
#include <stdexcept>

namespace anode {

ParticleData readParticlesVTU(const std::string& path, const std::vector<std::string>& arrays) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error("cannot open " + path);
  // A distributed run's output (.pvtu): its pieces one after the other, in the file's order.
  vtkSmartPointer<vtkXMLReader> reader;
  if (std::filesystem::path(path).extension() == ".pvtu")
    reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
  else
    reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkDataArraySelection* selection = reader->GetPointDataArraySelection();
  selection->DisableAllArrays();
  for (const std::string& name : arrays) selection->EnableArray(name.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(reader->GetOutputDataObject(0));
  if (!grid || (!grid->GetPoints() && grid->GetNumberOfPoints() > 0))
    throw std::runtime_error(path + " holds no particles VTK can read");
  if (!grid->GetPoints()) return {};  // a file of no particles (a panel that shows none)

  ParticleData data;
  const vtkIdType n = grid->GetNumberOfPoints();
  data.points.resize(3 * static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) grid->GetPoints()->GetPoint(i, &data.points[3 * i]);
  for (const std::string& name : arrays) {
    vtkDataArray* a = grid->GetPointData()->GetArray(name.c_str());
    if (!a) continue;
    NamedArray out{name, a->GetNumberOfComponents(), {}, {}};
    const size_t values = static_cast<size_t>(n) * out.components;
    if (a->GetDataType() == VTK_DOUBLE || a->GetDataType() == VTK_FLOAT) {
      out.real.resize(values);
      for (size_t k = 0; k < values; ++k)
        out.real[k] = a->GetComponent(k / out.components, k % out.components);
    } else {
      out.integer.resize(values);
      for (size_t k = 0; k < values; ++k)
        out.integer[k] =
            static_cast<int64_t>(a->GetComponent(k / out.components, k % out.components));
    }
    data.arrays.push_back(std::move(out));
  }
  return data;
}

std::vector<std::pair<double, std::string>> readPVD(const std::string& path) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error("cannot read " + path);
  const tinyxml2::XMLElement* collection =
      doc.RootElement() ? doc.RootElement()->FirstChildElement("Collection") : nullptr;
  if (!collection) throw std::runtime_error(path + " is not a .pvd collection");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<std::pair<double, std::string>> entries;
  for (const auto* e = collection->FirstChildElement("DataSet"); e;
       e = e->NextSiblingElement("DataSet")) {
    const char* file = e->Attribute("file");
    if (!file) throw std::runtime_error(path + ": a <DataSet> without file=");
    entries.emplace_back(e->DoubleAttribute("timestep", 0.0), (folder / file).string());
  }
  return entries;
}

}  // namespace anode

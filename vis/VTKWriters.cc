#include "vis/VTKWriters.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "Core/Util/AtomicFile.h"
#include "vis/AppendedData.h"

namespace anode {

namespace {

// The arrays of one file, described in its XML and stored in its appended section.
class ArrayList {
 public:
  void add(const char* type, const std::string& name, int components, const void* data,
           size_t bytes) {
    descriptions_.push_back({type, name, components});
    raw_.push_back({data, bytes});
  }
  void add(const NamedArray& a, size_t tuples) {
    const size_t values = tuples * static_cast<size_t>(a.components);
    if (a.isInteger())
      add("Int64", a.name, a.components, a.integer.data(), values * sizeof(int64_t));
    else
      add("Float64", a.name, a.components, a.real.data(), values * sizeof(double));
  }
  // The <DataArray> lines of arrays [first, last), with their offsets in the appended section
  // written 20 digits wide, so that the head keeps its length when the offsets are filled in.
  std::string xml(size_t first, size_t last, const std::vector<uint64_t>& offsets) const {
    std::ostringstream s;
    for (size_t k = first; k < last; ++k) {
      const Description& d = descriptions_[k];
      s << "        <DataArray type=\"" << d.type << "\" Name=\"" << d.name
        << "\" NumberOfComponents=\"" << d.components << "\" format=\"appended\" offset=\""
        << std::setw(20) << std::setfill('0') << offsets[k] << std::setfill(' ') << "\"/>\n";
    }
    return s.str();
  }
  size_t size() const { return raw_.size(); }
  const std::vector<RawArray>& raw() const { return raw_; }

 private:
  struct Description {
    const char* type;
    std::string name;
    int components;
  };
  std::vector<Description> descriptions_;
  std::vector<RawArray> raw_;
};

// The XML head (`head(offsets)`), then the appended section (zlib blocks, or each array's UInt64
// byte count and its bytes), written atomically; the head is written first with zero offsets and
// again once the arrays are written and their offsets known.
void writeVTKFile(const std::string& path, const ArrayList& arrays, bool compressed,
                  const std::function<std::string(const std::vector<uint64_t>&)>& head) {
  writeAtomically(path, [&](const std::string& tmp) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(tmp.c_str(), "wb"),
                                                        &std::fclose);
    if (!out) throw std::runtime_error("cannot open " + tmp + " for writing");
    const std::string open =
        head(std::vector<uint64_t>(arrays.size(), 0)) + "  <AppendedData encoding=\"raw\">\n   _";
    const std::string close = "\n  </AppendedData>\n</VTKFile>\n";
    bool ok = std::fwrite(open.data(), 1, open.size(), out.get()) == open.size();
    const std::string filled = head(compressed ? writeAppendedData(out.get(), arrays.raw())
                                               : writeUncompressedData(out.get(), arrays.raw()));
    ok = ok && std::fwrite(close.data(), 1, close.size(), out.get()) == close.size();
    ok = ok && std::fseek(out.get(), 0, SEEK_SET) == 0;
    ok = ok && std::fwrite(filled.data(), 1, filled.size(), out.get()) == filled.size();
    ok = std::fclose(out.release()) == 0 && ok;
    if (!ok) throw std::runtime_error("cannot write " + tmp);
  });
}

// The file's first lines: a VTK XML file of `type` with UInt64 headers (and zlib blocks).
std::string fileHeader(const std::string& type, bool compressed = true) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + type +
         "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"" +
         (compressed ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n";
}

}  // namespace

namespace {

// The single-precision copies of one file's arrays (ArrayList keeps pointers: they outlive it).
struct SinglePrecision {
  std::vector<std::vector<float>> reals;
  std::vector<std::vector<int32_t>> integers;

  const std::vector<float>& of(const std::vector<double>& v) {
    for (double x : v)
      if (std::isfinite(x) && std::abs(x) > FLT_MAX)  // below FLT_MIN: subnormal or 0
        throw std::runtime_error("a real number beyond Float32's range: " + std::to_string(x));
    return reals.emplace_back(v.begin(), v.end());
  }
  const std::vector<int32_t>& of(const std::vector<int64_t>& v) {
    for (int64_t x : v)
      if (x < INT32_MIN || x > INT32_MAX)
        throw std::runtime_error("an integer out of Int32's range cannot be written as Int32");
    return integers.emplace_back(v.begin(), v.end());
  }
};

}  // namespace

void writeParticlesVTU(const std::string& path, const ParticleData& data, VTUData form) {
  const size_t n = data.count();
  const bool single = form == VTUData::Picture;
  SinglePrecision copies;
  ArrayList arrays;
  auto addReals = [&](const std::string& name, int components, const std::vector<double>& v) {
    if (single)
      arrays.add("Float32", name, components, copies.of(v).data(), v.size() * sizeof(float));
    else
      arrays.add("Float64", name, components, v.data(), v.size() * sizeof(double));
  };
  auto addIntegers = [&](const std::string& name, int components, const std::vector<int64_t>& v) {
    if (single)
      arrays.add("Int32", name, components, copies.of(v).data(), v.size() * sizeof(int32_t));
    else
      arrays.add("Int64", name, components, v.data(), v.size() * sizeof(int64_t));
  };
  for (const NamedArray& a : data.arrays) {
    if (a.isInteger())
      addIntegers(a.name, a.components, a.integer);
    else
      addReals(a.name, a.components, a.real);
  }
  const size_t pointData = arrays.size();
  addReals("Points", 3, data.points);
  // One vertex cell per particle (VTK_VERTEX = 1).
  std::vector<int64_t> connectivity(n), cellEnds(n);
  for (size_t i = 0; i < n; ++i) {
    connectivity[i] = static_cast<int64_t>(i);
    cellEnds[i] = static_cast<int64_t>(i) + 1;
  }
  const std::vector<uint8_t> types(n, 1);
  addIntegers("connectivity", 1, connectivity);
  addIntegers("offsets", 1, cellEnds);
  arrays.add("UInt8", "types", 1, types.data(), n);
  writeVTKFile(path, arrays, !single, [&](const std::vector<uint64_t>& offsets) {
    std::ostringstream s;
    s << fileHeader("UnstructuredGrid", !single)
      << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n
      << "\">\n      <PointData>\n"
      << arrays.xml(0, pointData, offsets) << "      </PointData>\n      <Points>\n"
      << arrays.xml(pointData, pointData + 1, offsets) << "      </Points>\n      <Cells>\n"
      << arrays.xml(pointData + 1, arrays.size(), offsets)
      << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    return s.str();
  });
}

void writeGridVTI(const std::string& path, const GridData& data) {
  const size_t nodes = static_cast<size_t>(data.dims[0]) * data.dims[1] * data.dims[2];
  ArrayList arrays;
  for (const NamedArray& a : data.arrays) arrays.add(a, nodes);
  std::ostringstream extent;
  for (int d = 0; d < 3; ++d)
    extent << (d ? " " : "") << data.first[d] << " " << data.first[d] + data.dims[d] - 1;
  writeVTKFile(path, arrays, true, [&](const std::vector<uint64_t>& offsets) {
    std::ostringstream s;
    s << std::setprecision(17) << fileHeader("ImageData") << "  <ImageData WholeExtent=\""
      << extent.str() << "\" Origin=\"" << data.origin[0] << " " << data.origin[1] << " "
      << data.origin[2] << "\" Spacing=\"" << data.spacing[0] << " " << data.spacing[1] << " "
      << data.spacing[2] << "\" Direction=\"1 0 0 0 1 0 0 0 1\">\n    <Piece Extent=\""
      << extent.str() << "\">\n      <PointData>\n"
      << arrays.xml(0, arrays.size(), offsets)
      << "      </PointData>\n    </Piece>\n  </ImageData>\n";
    return s.str();
  });
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

size_t PVDSeries::dropMissing(const std::string& directory) {
  const size_t before = entries_.size();
  entries_.erase(
      std::remove_if(entries_.begin(), entries_.end(),
                     [&](const auto& e) {
                       return !std::filesystem::exists(std::filesystem::path(directory) / e.second);
                     }),
      entries_.end());
  return before - entries_.size();
}

}  // namespace anode

// Pins the binary section the VTK writers produce (vis/AppendedData): VTK's compressed block
// layout, every byte of every array recovered, the same bytes for any thread count, and files
// that VTK's own readers open (particles, including a rank's empty piece, and grid nodes).
#include <gtest/gtest.h>
#include <omp.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "vis/AppendedData.h"
#include "vis/VTKWriters.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

// The section's bytes and the arrays' offsets, written after `lead` bytes of something else.
struct Written {
  std::vector<unsigned char> bytes;
  std::vector<uint64_t> offsets;
};
Written writtenBytes(const std::vector<RawArray>& arrays, size_t lead = 7) {
  std::FILE* out = std::tmpfile();
  const std::vector<unsigned char> before(lead, 'x');
  std::fwrite(before.data(), 1, lead, out);
  Written w;
  w.offsets = writeAppendedData(out, arrays);
  const long size = std::ftell(out);
  w.bytes.resize(static_cast<size_t>(size) - lead);
  std::fseek(out, static_cast<long>(lead), SEEK_SET);
  EXPECT_EQ(std::fread(w.bytes.data(), 1, w.bytes.size(), out), w.bytes.size());
  std::fclose(out);
  return w;
}

std::vector<unsigned char> randomBytes(size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<unsigned char> bytes(n);
  for (unsigned char& b : bytes) b = static_cast<unsigned char>(random() % 7);  // compressible
  return bytes;
}

TEST(AppendedData, EveryArrayIsRecoveredFromVTKsBlockLayout) {
  // Also more blocks than one batch of compression (64).
  const size_t block = kAppendedBlockSize;
  const std::vector<size_t> sizes = {0, 1, block, block + 1, 3 * block + 5, 130 * block + 9};
  std::vector<std::vector<unsigned char>> arrays;
  std::vector<RawArray> raw;
  for (size_t k = 0; k < sizes.size(); ++k) arrays.push_back(randomBytes(sizes[k], k));
  for (const auto& a : arrays) raw.push_back({a.data(), a.size()});
  const Written written = writtenBytes(raw);
  const std::vector<unsigned char>& bytes = written.bytes;
  for (size_t k = 0; k < arrays.size(); ++k) {
    SCOPED_TRACE("array of " + std::to_string(sizes[k]) + " bytes");
    const unsigned char* at = bytes.data() + written.offsets[k];
    uint64_t header[3];
    std::memcpy(header, at, sizeof header);
    const uint64_t blocks = header[0];
    EXPECT_EQ(blocks, (sizes[k] + block - 1) / block);
    EXPECT_EQ(header[1], block);
    EXPECT_EQ(header[2], sizes[k] % block) << "size of a partial last block, 0 if none";
    std::vector<uint64_t> compressed(blocks);
    if (blocks > 0) std::memcpy(compressed.data(), at + 24, 8 * blocks);
    const unsigned char* next = at + 24 + 8 * blocks;
    std::vector<unsigned char> recovered;
    for (uint64_t b = 0; b < blocks; ++b) {
      std::vector<unsigned char> out(block);
      uLongf outSize = static_cast<uLongf>(out.size());
      ASSERT_EQ(uncompress(out.data(), &outSize, next, static_cast<uLong>(compressed[b])), Z_OK);
      recovered.insert(recovered.end(), out.begin(), out.begin() + outSize);
      next += compressed[b];
    }
    EXPECT_EQ(recovered, arrays[k]);
    const size_t end = k + 1 < arrays.size() ? written.offsets[k + 1] : bytes.size();
    EXPECT_EQ(static_cast<size_t>(next - bytes.data()), end) << "arrays follow each other";
  }
}

TEST(AppendedData, BytesDoNotDependOnTheThreadCount) {
  const std::vector<unsigned char> a = randomBytes(100 * kAppendedBlockSize + 3, 1);
  const std::vector<unsigned char> b = randomBytes(77, 2);
  const std::vector<RawArray> raw = {{a.data(), a.size()}, {b.data(), b.size()}};
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<unsigned char> one = writtenBytes(raw).bytes;
  omp_set_num_threads(3);
  const std::vector<unsigned char> three = writtenBytes(raw).bytes;
  omp_set_num_threads(threads);
  EXPECT_EQ(one, three);
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("anode_appended_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

ParticleData particles(size_t n) {
  ParticleData d;
  d.arrays.reserve(2);
  NamedArray& stress = d.arrays.emplace_back();
  stress.name = "p.stress";
  stress.components = 9;
  NamedArray& id = d.arrays.emplace_back();
  id.name = "p.particleID";
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) d.points.push_back(0.5 * i + c);
    for (int c = 0; c < 9; ++c) stress.real.push_back(1e-3 * i - c);
    id.integer.push_back(static_cast<int64_t>(1000000 + i));
  }
  return d;
}

TEST(AppendedData, VTKReadsTheParticlesBack) {
  TempDir dir;
  for (size_t n : {size_t(0), size_t(5000)}) {
    SCOPED_TRACE(std::to_string(n) + " particles");
    const ParticleData d = particles(n);
    const std::string path = (dir.path / "p.vtu").string();
    writeParticlesVTU(path, d);
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName(path.c_str());
    reader->Update();
    ASSERT_EQ(reader->GetErrorCode(), 0);
    vtkUnstructuredGrid* ug = reader->GetOutput();
    ASSERT_EQ(ug->GetNumberOfPoints(), static_cast<vtkIdType>(n));
    EXPECT_EQ(ug->GetNumberOfCells(), static_cast<vtkIdType>(n));
    vtkDataArray* stress = ug->GetPointData()->GetArray("p.stress");
    vtkDataArray* id = ug->GetPointData()->GetArray("p.particleID");
    ASSERT_TRUE(stress && id);
    EXPECT_EQ(stress->GetNumberOfComponents(), 9);
    for (size_t i = 0; i < n; ++i) {
      double x[3];
      ug->GetPoint(static_cast<vtkIdType>(i), x);
      EXPECT_EQ(x[2], d.points[3 * i + 2]);
      EXPECT_EQ(stress->GetComponent(static_cast<vtkIdType>(i), 8), d.arrays[0].real[9 * i + 8]);
      EXPECT_EQ(id->GetTuple1(static_cast<vtkIdType>(i)), 1000000.0 + i);
      if (HasFailure()) return;
    }
    if (n > 0) {
      EXPECT_EQ(ug->GetCellType(static_cast<vtkIdType>(n - 1)), 1) << "vertex cells";
    }
  }
}

TEST(AppendedData, VTKReadsTheGridBack) {
  TempDir dir;
  GridData g;
  g.dims[0] = 4;
  g.dims[1] = 3;
  g.dims[2] = 2;
  g.first[0] = 7;
  g.origin[1] = -1.5;
  g.spacing[2] = 0.25;
  NamedArray& mass = g.arrays.emplace_back();
  mass.name = "g.mass";
  for (int i = 0; i < 24; ++i) mass.real.push_back(i * 0.1);
  const std::string path = (dir.path / "g.vti").string();
  writeGridVTI(path, g);
  auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
  reader->SetFileName(path.c_str());
  reader->Update();
  ASSERT_EQ(reader->GetErrorCode(), 0);
  vtkImageData* image = reader->GetOutput();
  int extent[6];
  image->GetExtent(extent);
  EXPECT_EQ(extent[0], 7);
  EXPECT_EQ(extent[1], 10);
  EXPECT_EQ(extent[5], 1);
  EXPECT_EQ(image->GetOrigin()[1], -1.5);
  EXPECT_EQ(image->GetSpacing()[2], 0.25);
  vtkDataArray* m = image->GetPointData()->GetArray("g.mass");
  ASSERT_TRUE(m);
  for (int i = 0; i < 24; ++i) EXPECT_EQ(m->GetTuple1(i), i * 0.1);
}

}  // namespace
}  // namespace anode

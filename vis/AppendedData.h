// The binary section of a VTK XML file: "appended" data, raw (not base64), zlib-compressed in
// VTK's block layout. Every array is cut into blocks of `blockSize` bytes and all blocks of all
// arrays are compressed at once on the run's OpenMP threads (output is no longer one serial zlib
// stream: docs/performance.md, "Output"). The bytes do not depend on the thread count.
#pragma once

#include <cstdint>
#include <cstdio>
#include <vector>

namespace anode {

// An array's bytes as they go into the file (little-endian, as VTK's byte_order says).
struct RawArray {
  const void* data;
  size_t bytes;
};

class AppendedData {
 public:
  static constexpr size_t blockSize = 1 << 15;  // VTK's own writer's block size

  // Compresses every block of `arrays` (the arrays are read only here). Throws
  // std::runtime_error if zlib fails.
  explicit AppendedData(const std::vector<RawArray>& arrays);

  // The offset attribute of array k: where its header starts, counted from the byte after '_'.
  uint64_t offset(size_t k) const { return offsets_[k]; }
  // Writes the section's bytes (each array: UInt64 block count, block size, size of a partial
  // last block or 0, each block's compressed size; then the compressed blocks).
  void write(std::FILE* out) const;
  // Memory held for the compressed blocks, in bytes.
  size_t bytesHeld() const;

 private:
  struct Array {
    size_t bytes;
    size_t firstBlock, blocks;
  };
  std::vector<Array> arrays_;
  std::vector<std::vector<unsigned char>> compressed_;  // every array's blocks, in file order
  std::vector<uint64_t> offsets_;
};

}  // namespace anode

// The binary section of a VTK XML file: "appended" data, raw (not base64), zlib-compressed in
// VTK's block layout. Every array is cut into blocks of `kAppendedBlockSize` bytes; the blocks are
// compressed a batch at a time on the run's OpenMP threads (output is not one serial zlib stream:
// docs/performance.md, "Output") and written as each batch is done, so the memory held is one
// batch, not the file. The bytes do not depend on the thread count.
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

constexpr size_t kAppendedBlockSize = 1 << 15;  // VTK's own writer's block size

// Writes `arrays` at the current position of `out` (which must be seekable: each array's header,
// its block count, block size, size of a partial last block or 0 and each block's compressed
// size, is filled in after its blocks). Returns each array's offset from the section's start,
// the `offset` attribute of its <DataArray>. Throws std::runtime_error if zlib or a write fails.
std::vector<uint64_t> writeAppendedData(std::FILE* out, const std::vector<RawArray>& arrays);
// The same without compression (a file with no compressor attribute): each array its UInt64 byte
// count, then its bytes.
std::vector<uint64_t> writeUncompressedData(std::FILE* out, const std::vector<RawArray>& arrays);

}  // namespace anode

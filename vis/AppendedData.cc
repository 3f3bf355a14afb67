#include "vis/AppendedData.h"

#include <zlib.h>

#include <algorithm>
#include <stdexcept>

namespace anode {

namespace {

// Level 1: particle doubles barely compress further at zlib's default 6, which takes longer.
constexpr int compressionLevel = 1;
// Blocks compressed at once: 2 MiB of input, enough to keep every thread busy.
constexpr size_t batchBlocks = 64;

void check(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(std::string("VTK output: ") + what);
}

// Compresses blocks [first, first + count) of `bytes` bytes at `data` into `out[0..count)`.
void compressBatch(const unsigned char* data, size_t bytes, size_t first, size_t count,
                   std::vector<std::vector<unsigned char>>& out) {
  bool failed = false;
#pragma omp parallel reduction(|| : failed)
  {
    z_stream zs{};
    failed = deflateInit(&zs, compressionLevel) != Z_OK;
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < static_cast<long>(count); ++k) {
      if (failed) continue;
      const size_t begin = (first + k) * kAppendedBlockSize;
      const size_t size = std::min(kAppendedBlockSize, bytes - begin);
      std::vector<unsigned char>& block = out[k];
      block.resize(deflateBound(&zs, size));
      failed = deflateReset(&zs) != Z_OK;
      zs.next_in = const_cast<unsigned char*>(data + begin);
      zs.avail_in = static_cast<uInt>(size);
      zs.next_out = block.data();
      zs.avail_out = static_cast<uInt>(block.size());
      failed = failed || deflate(&zs, Z_FINISH) != Z_STREAM_END;
      block.resize(zs.total_out);
    }
    deflateEnd(&zs);
  }
  check(!failed, "zlib could not compress an array");
}

}  // namespace

std::vector<uint64_t> writeAppendedData(std::FILE* out, const std::vector<RawArray>& arrays) {
  const long start = std::ftell(out);
  check(start >= 0, "the file is not seekable");
  std::vector<uint64_t> offsets;
  std::vector<std::vector<unsigned char>> batch(batchBlocks);
  for (const RawArray& a : arrays) {
    const long headerAt = std::ftell(out);
    offsets.push_back(static_cast<uint64_t>(headerAt - start));
    const size_t blocks = (a.bytes + kAppendedBlockSize - 1) / kAppendedBlockSize;
    std::vector<uint64_t> header = {blocks, kAppendedBlockSize, a.bytes % kAppendedBlockSize};
    header.resize(3 + blocks);
    check(std::fwrite(header.data(), 8, header.size(), out) == header.size(), "write failed");
    const auto* data = static_cast<const unsigned char*>(a.data);
    for (size_t first = 0; first < blocks; first += batchBlocks) {
      const size_t count = std::min(batchBlocks, blocks - first);
      compressBatch(data, a.bytes, first, count, batch);
      for (size_t k = 0; k < count; ++k) {
        header[3 + first + k] = batch[k].size();
        check(std::fwrite(batch[k].data(), 1, batch[k].size(), out) == batch[k].size(),
              "write failed");
      }
    }
    // The compressed sizes, now known, into the array's header.
    const long end = std::ftell(out);
    check(std::fseek(out, headerAt, SEEK_SET) == 0, "seek failed");
    check(std::fwrite(header.data(), 8, header.size(), out) == header.size(), "write failed");
    check(std::fseek(out, end, SEEK_SET) == 0, "seek failed");
  }
  return offsets;
}

std::vector<uint64_t> writeUncompressedData(std::FILE* out, const std::vector<RawArray>& arrays) {
  std::vector<uint64_t> offsets;
  uint64_t at = 0;
  for (const RawArray& a : arrays) {
    offsets.push_back(at);
    const uint64_t bytes = a.bytes;
    check(std::fwrite(&bytes, 8, 1, out) == 1, "write failed");
    check(std::fwrite(a.data, 1, a.bytes, out) == a.bytes, "write failed");
    at += 8 + bytes;
  }
  return offsets;
}

}  // namespace anode

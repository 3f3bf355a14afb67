#include "vis/AppendedData.h"

#include <zlib.h>

#include <stdexcept>

namespace anode {

namespace {

// Level 1: particle doubles barely compress further at zlib's default 6, which takes longer.
constexpr int compressionLevel = 1;

}  // namespace

AppendedData::AppendedData(const std::vector<RawArray>& arrays) {
  struct Block {
    const unsigned char* data;
    size_t bytes;
  };
  std::vector<Block> blocks;
  for (const RawArray& a : arrays) {
    const size_t count = (a.bytes + blockSize - 1) / blockSize;
    arrays_.push_back({a.bytes, blocks.size(), count});
    const auto* bytes = static_cast<const unsigned char*>(a.data);
    for (size_t b = 0; b < count; ++b)
      blocks.push_back({bytes + b * blockSize, std::min(blockSize, a.bytes - b * blockSize)});
  }
  compressed_.resize(blocks.size());
  const long n = static_cast<long>(blocks.size());
  bool failed = false;
#pragma omp parallel reduction(|| : failed)
  {
    z_stream zs{};
    failed = deflateInit(&zs, compressionLevel) != Z_OK;
#pragma omp for schedule(dynamic, 4)
    for (long b = 0; b < n; ++b) {
      if (failed) continue;
      std::vector<unsigned char>& out = compressed_[b];
      out.resize(deflateBound(&zs, blocks[b].bytes));
      failed = deflateReset(&zs) != Z_OK;
      zs.next_in = const_cast<unsigned char*>(blocks[b].data);
      zs.avail_in = static_cast<uInt>(blocks[b].bytes);
      zs.next_out = out.data();
      zs.avail_out = static_cast<uInt>(out.size());
      failed = failed || deflate(&zs, Z_FINISH) != Z_STREAM_END;
      out.resize(zs.total_out);
      out.shrink_to_fit();
    }
    deflateEnd(&zs);
  }
  if (failed) throw std::runtime_error("zlib could not compress the output's arrays");
  uint64_t at = 0;
  for (const Array& a : arrays_) {
    offsets_.push_back(at);
    at += 8 * (3 + a.blocks);
    for (size_t b = 0; b < a.blocks; ++b) at += compressed_[a.firstBlock + b].size();
  }
}

void AppendedData::write(std::FILE* out) const {
  bool ok = true;
  for (const Array& a : arrays_) {
    std::vector<uint64_t> header = {a.blocks, blockSize, a.bytes % blockSize};
    for (size_t b = 0; b < a.blocks; ++b) header.push_back(compressed_[a.firstBlock + b].size());
    ok = ok && std::fwrite(header.data(), 8, header.size(), out) == header.size();
    for (size_t b = 0; b < a.blocks; ++b) {
      const std::vector<unsigned char>& block = compressed_[a.firstBlock + b];
      ok = ok && std::fwrite(block.data(), 1, block.size(), out) == block.size();
    }
  }
  if (!ok) throw std::runtime_error("could not write the output's arrays");
}

size_t AppendedData::bytesHeld() const {
  size_t held = 0;
  for (const std::vector<unsigned char>& block : compressed_) held += block.capacity();
  return held;
}

}  // namespace anode

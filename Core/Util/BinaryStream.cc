#include "Core/Util/BinaryStream.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace anode {

namespace {

constexpr uint64_t kPrime = 1099511628211ull;

}  // namespace

void StreamHash::addWord(uint64_t word) {
  hash_ = (hash_ ^ word) * kPrime;
}

void StreamHash::add(const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (pendingBytes_ > 0) {
    const size_t take = std::min(bytes, sizeof pending_ - pendingBytes_);
    std::memcpy(pending_ + pendingBytes_, p, take);
    pendingBytes_ += take;
    p += take;
    bytes -= take;
    if (pendingBytes_ < sizeof pending_) return;
    uint64_t word;
    std::memcpy(&word, pending_, 8);
    addWord(word);
    pendingBytes_ = 0;
  }
  for (; bytes >= 8; bytes -= 8, p += 8) {
    uint64_t word;
    std::memcpy(&word, p, 8);
    addWord(word);
  }
  std::memcpy(pending_, p, bytes);
  pendingBytes_ = bytes;
}

uint64_t StreamHash::value() const {
  uint64_t h = hash_;
  for (size_t i = 0; i < pendingBytes_; ++i) h = (h ^ pending_[i]) * kPrime;
  return h;
}

HashCheck checkHash(const std::string& path, std::string* error) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    if (error) *error = path + ": cannot open: " + std::strerror(errno);
    return HashCheck::Unreadable;
  }
  std::vector<unsigned char> buffer(1 << 20);
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::rewind(f);
  bool ok = size >= 8;
  StreamHash h;
  for (long left = size - 8; ok && left > 0;) {
    const size_t n =
        std::fread(buffer.data(), 1, std::min<long>(left, static_cast<long>(buffer.size())), f);
    if (n == 0) ok = false;
    h.add(buffer.data(), n);
    left -= static_cast<long>(n);
  }
  uint64_t stored = 0;
  ok = ok && std::fread(&stored, sizeof stored, 1, f) == 1 && stored == h.value();
  const bool readError = std::ferror(f) != 0;
  const int readErrno = errno;
  std::fclose(f);
  if (readError) {
    if (error) *error = path + ": read error: " + std::strerror(readErrno);
    return HashCheck::Unreadable;
  }
  return ok ? HashCheck::Intact : HashCheck::Damaged;
}

BinaryWriter::BinaryWriter(const std::string& path)
    : path_(path), file_(std::fopen(path.c_str(), "wb")) {
  if (!file_) throw std::runtime_error("cannot create " + path);
}

BinaryWriter::~BinaryWriter() {
  if (file_) std::fclose(file_);
}

void BinaryWriter::bytes(const void* data, size_t n) {
  if (n == 0) return;
  hash_.add(data, n);
  if (std::fwrite(data, 1, n, file_) != n) throw std::runtime_error("cannot write " + path_);
}

void BinaryWriter::string(const std::string& s) {
  value<uint64_t>(s.size());
  bytes(s.data(), s.size());
}

uint64_t BinaryWriter::finish() {
  const uint64_t h = hash_.value();
  const bool written = std::fwrite(&h, sizeof h, 1, file_) == 1;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!written || !closed) throw std::runtime_error("cannot write " + path_);
  return h;
}

BinaryReader::BinaryReader(const std::string& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb")) {
  if (!file_) throw std::runtime_error("cannot open " + path);
  if (std::fseek(file_, 0, SEEK_END) != 0) fail("cannot seek");
  const long size = std::ftell(file_);
  if (size < static_cast<long>(sizeof(uint64_t))) fail("too short");
  size_ = static_cast<uint64_t>(size) - sizeof(uint64_t);  // the hash ends the file
  std::rewind(file_);
}

BinaryReader::~BinaryReader() {
  if (file_) std::fclose(file_);
}

void BinaryReader::fail(const std::string& what) const {
  throw std::runtime_error(path_ + ": " + what + " (not a complete restart file)");
}

void BinaryReader::bytes(void* data, size_t n) {
  if (n > remaining()) fail("ends early");
  if (n == 0) return;
  if (std::fread(data, 1, n, file_) != n) fail("read error");
  position_ += n;
  hash_.add(data, n);
}

std::string BinaryReader::string() {
  const uint64_t n = value<uint64_t>();
  if (n > remaining()) fail("a string longer than the file");
  std::string s(n, '\0');
  bytes(s.data(), n);
  return s;
}

uint64_t BinaryReader::finish() {
  if (remaining() != 0) fail("unread bytes before the end");
  uint64_t stored = 0;
  if (std::fread(&stored, sizeof stored, 1, file_) != 1) fail("no hash at the end");
  if (stored != hash_.value()) fail("hash mismatch");
  return stored;
}

}  // namespace anode

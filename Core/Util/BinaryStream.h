// Binary files with an integrity check: the writer hashes everything it writes and ends the file
// with the hash; the reader recomputes it and refuses a file whose bytes or length differ, so a
// truncated or damaged restart file is never read as state.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace anode {

// What is written as its bytes: plain values, and fixed-size Eigen matrices (their storage is a
// plain array, though their copy constructor makes them not trivially copyable).
template <class T>
constexpr bool kStoredAsBytes = std::is_trivially_copyable_v<T> || std::is_standard_layout_v<T>;

// Running 64-bit hash of a byte stream: FNV-1a over its 8-byte words, then over the bytes of a
// last partial word. The value depends on the bytes only, not on how they were split into calls.
class StreamHash {
 public:
  void add(const void* data, size_t bytes);
  uint64_t value() const;

 private:
  void addWord(uint64_t word);
  uint64_t hash_ = 14695981039346656037ull;
  unsigned char pending_[8] = {};
  size_t pendingBytes_ = 0;
};

// Whether the file at `path` ends with the hash of the bytes before it (a complete file):
// Damaged when it is too short or the hash differs, Unreadable when it cannot be opened or read
// (an I/O error, said in `error`, which is no evidence of damage).
enum class HashCheck { Intact, Damaged, Unreadable };
HashCheck checkHash(const std::string& path, std::string* error = nullptr);
inline bool hasIntactHash(const std::string& path) {
  return checkHash(path) == HashCheck::Intact;
}

class BinaryWriter {
 public:
  // Opens `path` for writing; throws std::runtime_error.
  explicit BinaryWriter(const std::string& path);
  ~BinaryWriter();
  BinaryWriter(const BinaryWriter&) = delete;
  BinaryWriter& operator=(const BinaryWriter&) = delete;

  void bytes(const void* data, size_t n);
  template <class T>
  void value(const T& v) {
    static_assert(kStoredAsBytes<T>);
    bytes(&v, sizeof v);
  }
  void string(const std::string& s);
  // Length, then the elements' bytes.
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(kStoredAsBytes<T>);
    value<uint64_t>(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  // Appends the hash and closes the file; returns the hash; throws if any write failed.
  uint64_t finish();

 private:
  std::string path_;
  FILE* file_ = nullptr;
  StreamHash hash_;
};

class BinaryReader {
 public:
  // Opens `path`; throws std::runtime_error.
  explicit BinaryReader(const std::string& path);
  ~BinaryReader();
  BinaryReader(const BinaryReader&) = delete;
  BinaryReader& operator=(const BinaryReader&) = delete;

  // Each read throws std::runtime_error when the file ends early.
  void bytes(void* data, size_t n);
  template <class T>
  T value() {
    static_assert(kStoredAsBytes<T>);
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  std::string string();
  // Reads an array written by BinaryWriter::array; a length beyond what the file holds throws.
  template <class T>
  void array(std::vector<T>& v) {
    static_assert(kStoredAsBytes<T>);
    const uint64_t n = value<uint64_t>();
    if (n > remaining() / sizeof(T)) fail("an array longer than the file");
    v.resize(n);
    bytes(v.data(), n * sizeof(T));
  }
  // Checks the hash at the end against the bytes read, and that nothing follows it.
  uint64_t finish();

 private:
  [[noreturn]] void fail(const std::string& what) const;
  uint64_t remaining() const { return size_ - position_; }

  std::string path_;
  FILE* file_ = nullptr;
  uint64_t size_ = 0, position_ = 0;
  StreamHash hash_;
};

}  // namespace anode

// Loaded with LD_PRELOAD into sus by test_checkpoint_sync: appends one line per fsync, rename
// and removal to the file $ANODE_SYNC_LOG ("fsync PATH", "rename FROM TO", "unlink PATH"), then
// does the call, so a test can check the order in which a checkpoint reaches the disk.
#include <dlfcn.h>
#include <fcntl.h>
#include <limits.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

void logLine(const std::string& line) {
  const char* path = std::getenv("ANODE_SYNC_LOG");
  if (!path) return;
  const int fd = ::open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return;
  const std::string text = line + "\n";
  if (::write(fd, text.data(), text.size()) < 0) {
  }
  ::close(fd);
}

template <class F>
F next(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" {

int fsync(int fd) {
  char link[64], target[PATH_MAX];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, target, sizeof target - 1);
  logLine("fsync " + std::string(target, n > 0 ? static_cast<size_t>(n) : 0));
  return next<int (*)(int)>("fsync")(fd);
}

int rename(const char* from, const char* to) {
  logLine(std::string("rename ") + from + " " + to);
  return next<int (*)(const char*, const char*)>("rename")(from, to);
}

int unlink(const char* path) {
  logLine(std::string("unlink ") + path);
  return next<int (*)(const char*)>("unlink")(path);
}

int remove(const char* path) {
  logLine(std::string("unlink ") + path);
  return next<int (*)(const char*)>("remove")(path);
}

int unlinkat(int dirfd, const char* path, int flags) {
  logLine(std::string("unlink ") + path);
  return next<int (*)(int, const char*, int)>("unlinkat")(dirfd, path, flags);
}
}

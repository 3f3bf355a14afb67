#include "Core/Util/AtomicFile.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace anode {

void syncToDisk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error("cannot open " + path + " to sync it: " + std::strerror(errno));
  const bool synced = ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  if (!synced) throw std::runtime_error("cannot sync " + path + ": " + std::strerror(error));
}

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     Durability durability) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  write(tmp);
  if (durability == Durability::Synced) syncToDisk(tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
  }
  if (durability == Durability::Synced) {
    const std::string::size_type slash = path.find_last_of('/');
    syncToDisk(slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash));
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << content;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + tmp);
  });
}

}  // namespace anode

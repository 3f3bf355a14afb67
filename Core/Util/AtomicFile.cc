#include "Core/Util/AtomicFile.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace anode {

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  write(tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
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

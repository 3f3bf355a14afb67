// Reading a whole file in a test.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace anode::testing {

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace anode::testing

#include "StandAlone/Studies/StudyTools.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace anode {

StudyCommandLine::StudyCommandLine(std::string tool, void (*usage)(FILE*))
    : tool_(std::move(tool)), usage_(usage) {}

void StudyCommandLine::flag(const std::string& name, std::function<void()> set) {
  flags_[name] = std::move(set);
}

void StudyCommandLine::option(const std::string& name, std::function<void(const char*)> set) {
  options_[name] = std::move(set);
}

void StudyCommandLine::positiveNumber(const std::string& name, double& value) {
  option(name, [this, name, &value](const char* text) {
    value = std::atof(text);
    if (!(value > 0)) fail(name + " needs a positive number");
  });
}

void StudyCommandLine::positiveInteger(const std::string& name, int& value) {
  option(name, [this, name, &value](const char* text) {
    value = std::atoi(text);
    if (value < 1) fail(name + " needs a positive integer");
  });
}

std::optional<int> StudyCommandLine::parse(int argc, char** argv) const {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (const auto flag = flags_.find(arg); flag != flags_.end()) {
      flag->second();
    } else if (const auto option = options_.find(arg); option != options_.end() && i + 1 < argc) {
      option->second(argv[++i]);
    } else if (arg == "--help" || arg == "-h") {
      usage_(stdout);
      return 0;
    } else {
      usage_(stderr);
      return 2;
    }
  }
  return std::nullopt;
}

void StudyCommandLine::fail(const std::string& message) const {
  std::fprintf(stderr, "%s: %s\n", tool_.c_str(), message.c_str());
  std::exit(2);
}

std::string convergenceOrder(double coarse, double fine, double ratio) {
  if (!(coarse > 0) || !(fine > 0) || !(ratio > 1)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", std::log(coarse / fine) / std::log(ratio));
  return buf;
}

std::ofstream createOutputFile(const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream out(p);
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

}  // namespace anode

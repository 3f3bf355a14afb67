// What the study tools (vibrating_bar_study, flux_slab_study, diffusion_1d_study,
// swelling_sphere_study) share: their thread count, reading their command line, running a case at
// each resolution, the convergence order between resolutions and the files they write.
#pragma once

#include <omp.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace anode {

// Sets the OpenMP thread count for a scope (n = 0: unchanged).
class ThreadScope {
 public:
  explicit ThreadScope(int n) : saved_(omp_get_max_threads()), set_(n > 0) {
    if (set_) omp_set_num_threads(n);
  }
  ~ThreadScope() {
    if (set_) omp_set_num_threads(saved_);
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
  bool set_;
};

// Reads a study tool's arguments in order: flags, options taking the next argument, --help/-h.
class StudyCommandLine {
 public:
  // `tool` starts the messages; `usage` prints the help to the stream it is given.
  StudyCommandLine(std::string tool, void (*usage)(FILE*));

  void flag(const std::string& name, std::function<void()> set);
  void option(const std::string& name, std::function<void(const char* value)> set);
  // An option whose value must be a number > 0.
  void positiveNumber(const std::string& name, double& value);
  // An option whose value must be an integer >= 1.
  void positiveInteger(const std::string& name, int& value);

  // The exit code if the tool is to stop: 0 after --help (usage on stdout), 2 for an unknown
  // argument or an option without its value (usage on stderr).
  std::optional<int> parse(int argc, char** argv) const;
  // For a bad option value: "<tool>: <message>" on stderr, exit code 2.
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string tool_;
  void (*usage_)(FILE*);
  std::map<std::string, std::function<void()>> flags_;
  std::map<std::string, std::function<void(const char*)>> options_;
};

// Runs `base` at each of `cells` (coarsest first) with the linear, GIMP and CPDI interpolators in
// turn; hands each result to `report` with the one a resolution coarser (null for the coarsest).
template <class Case, class Result, class Report>
void runEachResolution(const Case& base, const std::vector<int>& cells, Result (*run)(const Case&),
                       Report&& report) {
  for (const char* interpolator : {"linear", "gimp", "cpdi"}) {
    Result coarser;
    for (size_t i = 0; i < cells.size(); ++i) {
      Case c = base;
      c.cells = cells[i];
      c.interpolator = interpolator;
      const Result r = run(c);
      report(r, i == 0 ? nullptr : &coarser);
      coarser = r;
    }
  }
}

// log(coarse / fine) / log(ratio) as "%.2f"; empty unless both errors are positive and ratio > 1.
std::string convergenceOrder(double coarse, double fine, double ratio);
// The same for `metric` from the coarser result (none: empty) to `fine`, the ratio of their cells.
template <class Result>
std::string convergenceOrder(const Result* coarser, const Result& fine, double Result::*metric) {
  if (!coarser) return "";
  return convergenceOrder(coarser->*metric, fine.*metric, double(fine.cells) / coarser->cells);
}

// `path` open for writing, its folder created; throws std::runtime_error("cannot write <path>").
std::ofstream createOutputFile(const std::string& path);

}  // namespace anode

#include "tests/fuzz/RunFuzz.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/TestFiles.h"
#include "tests/fuzz/InputMutator.h"

namespace anode::fuzz {

namespace {

// Values setup accepts (or refuses with file:line) for each ImpMPM tag of <MPM>: the runtime
// fuzz is after what the time loop does with them.
const std::vector<std::pair<std::string, std::vector<std::string>>>& implicitValues() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> values = {
      {"dynamic", {"true", "false"}},
      {"convergence_criteria_disp", {"1e-12", "1e-8", "1e-3", "0.5"}},
      {"convergence_criteria_energy", {"1e-12", "1e-8", "1e-3", "0.5"}},
      {"iters_before_timestep_restart", {"1", "2", "4", "100"}},
      {"num_iters_to_decrease_delT", {"1", "2", "12"}},
      {"num_iters_to_increase_delT", {"1", "3", "20"}},
      {"delT_decrease_factor", {"0.01", "0.5", "0.99"}},
      {"delT_increase_factor", {"1", "1.25", "10"}},
      {"solver", {"petsc", "simple"}},
      {"hourglass_stabilization", {"0", "1e-6", "0.1", "1", "100"}},
      {"jacobian_coupling_share", {"0", "1e-4", "0.5", "1"}},
      {"jacobian_reuse", {"true", "false"}},
      {"max_concentration_change", {"1e-6", "0.01", "0.3", "1"}},
      {"error_tolerance", {"0", "1e-6", "1e-3", "0.01", "0.5"}},
      {"concentration_coupling", {"staggered", "trapezoidal"}},
      {"diffusion_integrator", {"euler", "rkl2"}},
      {"subcell_concentration_relaxation", {"true", "false"}},
      {"swelling_strain", {"cell_mean", "particle"}}};
  return values;
}

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool parseNumber(const std::string& s, double* v) {
  const std::string t = trimmed(s);
  if (t.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(t.c_str(), &end);
  return *end == '\0';
}

// A number of the text: [begin, end) holds it.
struct NumberSpan {
  size_t begin, end;
  std::string tag;
};

// The tags that set how many particles, cells or patches there are: sizes are the input fuzz's
// (setup refuses what the memory does not hold), not this one's.
bool setsTheProblemSize(const std::string& tag) {
  return tag == "res" || tag == "resolution" || tag == "patches" || tag == "num_axial" ||
         tag == "num_radial";
}

// Every number that is a leaf element's whole value or one component of its vector "[a, b, c]",
// but for the problem's size.
std::vector<NumberSpan> numbersOf(const std::string& text) {
  std::vector<NumberSpan> spans;
  for (const ElementSpan& e : scanElements(text)) {
    if (!e.leaf || e.selfClosing || e.contentEnd <= e.contentBegin) continue;
    const std::string tag = text.substr(e.nameBegin, e.nameLength);
    if (setsTheProblemSize(tag)) continue;
    const std::string content = text.substr(e.contentBegin, e.contentEnd - e.contentBegin);
    const std::string t = trimmed(content);
    double v = 0;
    if (t.size() > 1 && t.front() == '[' && t.back() == ']') {
      const size_t open = e.contentBegin + content.find('[');
      size_t at = open + 1;
      const size_t close = e.contentBegin + content.rfind(']');
      while (at < close) {
        const size_t comma = std::min(text.find(',', at), close);
        if (parseNumber(text.substr(at, comma - at), &v)) spans.push_back({at, comma, tag});
        at = comma + 1;
      }
    } else if (parseNumber(content, &v)) {
      spans.push_back({e.contentBegin, e.contentEnd, tag});
    }
  }
  return spans;
}

std::string formatted(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace

const char* RunMutator::operatorName(int op) {
  static const char* names[kOperatorCount] = {"scale-up", "scale-down", "negate",
                                              "zero",     "extreme",    "implicit-option"};
  return op >= 0 && op < kOperatorCount ? names[op] : "?";
}

bool RunMutator::changeNumber(int op, std::string& text, std::string* what) {
  // Scaling, negating or zeroing a zero changes nothing: those take the other numbers.
  std::vector<NumberSpan> spans;
  for (const NumberSpan& n : numbersOf(text)) {
    double v = 0;
    parseNumber(text.substr(n.begin, n.end - n.begin), &v);
    if (v != 0 || op == Extreme) spans.push_back(n);
  }
  if (spans.empty()) return false;
  const NumberSpan& n = spans[pick(spans.size())];
  double v = 0;
  parseNumber(text.substr(n.begin, n.end - n.begin), &v);
  double changed = v;
  switch (op) {
    case ScaleUp:
      changed = v * 1e4;
      break;
    case ScaleDown:
      changed = v * 1e-4;
      break;
    case Negate:
      changed = -v;
      break;
    case Zero:
      changed = 0;
      break;
    default: {
      static const double extremes[] = {1e30, -1e30, 1e-30, 1e300};
      changed = extremes[pick(4)];
    }
  }
  const std::string replacement = formatted(changed);
  if (what)
    *what = std::string(operatorName(op)) + ": <" + n.tag + "> " +
            trimmed(text.substr(n.begin, n.end - n.begin)) + " -> " + replacement;
  text.replace(n.begin, n.end - n.begin, replacement);
  return true;
}

bool RunMutator::apply(int op, std::string& text, std::string* what) {
  if (op != ImplicitOption) return changeNumber(op, text, what);
  const auto& [tag, values] = implicitValues()[pick(implicitValues().size())];
  const std::string& value = values[pick(values.size())];
  if (!editTag(text, "MPM", tag, TagEdit::Set, value)) return false;
  if (what) *what = std::string(operatorName(op)) + ": <" + tag + "> " + value;
  return true;
}

std::string RunMutator::mutate(std::string& text, std::vector<int>* operatorsUsed) {
  const size_t count = 1 + pick(3);
  std::string all;
  for (size_t k = 0; k < count; ++k) {
    const int op = static_cast<int>(pick(kOperatorCount));
    std::string what;
    if (!apply(op, text, &what)) continue;
    if (operatorsUsed) operatorsUsed->push_back(op);
    all += (all.empty() ? "" : "; ") + what;
  }
  return all;
}

std::vector<std::string> defaultRunCorpus(const std::string& sourceDir) {
  std::vector<std::string> corpus;
  for (const auto& entry : std::filesystem::directory_iterator(sourceDir + "/inputs/Stability")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("Implicit_", 0) == 0 && entry.path().extension() == ".ups")
      corpus.push_back(entry.path().string());
  }
  std::sort(corpus.begin(), corpus.end());
  return corpus;
}

SusRun runWithTimeLimit(const std::string& program, const std::vector<std::string>& arguments,
                        const std::string& logPath, double stopAfter, double timeLimit) {
  SusRun run;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) return run;
  if (pid == 0) {
    std::FILE* log = std::fopen(logPath.c_str(), "w");
    if (log) {
      dup2(fileno(log), 1);
      dup2(fileno(log), 2);
    }
    std::vector<char*> argv{const_cast<char*>(program.c_str())};
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (!run.askedToStop && elapsed() > stopAfter) {
      run.askedToStop = true;
      kill(pid, SIGUSR1);
    }
    if (elapsed() > timeLimit) {
      run.timedOut = true;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.seconds = elapsed();
  if (WIFEXITED(status)) run.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  return run;
}

namespace {

using testing::readFile;

// "" when the run ended as a case may end, else what went wrong.
std::string problemOf(const SusRun& run, const std::string& log, double timeLimit) {
  if (run.timedOut) return "ran past " + formatted(timeLimit) + " s";
  if (run.signal != 0) return "ended by signal " + std::to_string(run.signal);
  switch (run.exitCode) {
    case 0:
      return "";
    case 4:
      return run.askedToStop ? "" : "exit 4 without a stop request";
    case 2:
      // An input error names the case's file and a line of it.
      if (std::regex_search(log, std::regex(R"(case\.ups:[0-9]+)"))) return "";
      return "exit 2 without file:line";
    case 3:
      if (log.find("sus: simulation stopped:") != std::string::npos) return "";
      return "exit 3 without a diagnostic";
    default:
      return "exit " + std::to_string(run.exitCode);
  }
}

}  // namespace

RunFuzzReport runRunFuzz(const RunFuzzOptions& options) {
  RunFuzzReport report;
  std::vector<std::string> seedTexts;
  for (const std::string& path : options.corpus) seedTexts.push_back(readFile(path));
  std::filesystem::create_directories(options.workDir);
  const std::string casePath = options.workDir + "/case.ups";
  const std::string outDir = options.workDir + "/run";
  const std::string logPath = options.workDir + "/case.log";
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < options.cases && !seedTexts.empty(); ++i) {
    // Each case its own random stream: case I of seed S is always the same input.
    RunMutator mutator(options.seed * 1000003u + static_cast<uint64_t>(i));
    const size_t s = static_cast<size_t>(i) % seedTexts.size();
    std::string text = seedTexts[s];
    std::vector<int> used;
    const std::string mutations = mutator.mutate(text, &used);
    for (int op : used) ++report.perOperator[op];
    std::ofstream(casePath) << text;
    std::filesystem::remove_all(outDir);
    const SusRun run = runWithTimeLimit(options.sus,
                                        {"--one-process", "--threads", "1", "--max-timesteps",
                                         std::to_string(options.steps), "-o", outDir, casePath},
                                        logPath, options.stopAfter, options.caseTimeLimit);
    ++report.tried;
    report.slowestCase = std::max(report.slowestCase, run.seconds);
    const std::string log = readFile(logPath);
    const std::string problem = problemOf(run, log, options.caseTimeLimit);
    if (problem.empty()) {
      long* count[5] = {&report.ran, nullptr, &report.refused, &report.diagnosed, &report.stopped};
      ++*count[run.exitCode];
    } else {
      const std::string kept =
          options.workDir + "/failure" + std::to_string(report.failures.size()) + ".ups";
      std::ofstream(kept) << text;
      std::ofstream(kept + ".txt") << "case " << i << " of seed " << options.seed << "\nseed input "
                                   << options.corpus[s] << "\n"
                                   << mutations << "\n"
                                   << problem << "\n--- sus output ---\n"
                                   << log;
      report.failures.push_back({i, options.corpus[s], mutations, problem});
    }
    if (options.progress)
      std::fprintf(
          stderr, "case %ld: %s in %.1f s (%s; %s)\n", i,
          problem.empty() ? ("exit " + std::to_string(run.exitCode)).c_str() : problem.c_str(),
          run.seconds, std::filesystem::path(options.corpus[s]).filename().c_str(),
          mutations.c_str());
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace anode::fuzz

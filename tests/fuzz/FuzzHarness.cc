#include "tests/fuzz/FuzzHarness.h"

#include <cxxabi.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <thread>
#include <typeinfo>

#include "Core/Util/Errors.h"
#include "Core/Util/MemoryBudget.h"
#include "StandAlone/Driver/Simulation.h"

namespace fs = std::filesystem;

namespace anode::fuzz {

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif

std::string demangle(const char* name) {
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> s(abi::__cxa_demangle(name, nullptr, nullptr, &status),
                                           std::free);
  return status == 0 && s ? s.get() : name;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Caps the address space so an allocation the size checks missed fails (std::bad_alloc, reported
// as a failure) instead of exhausting the machine. Not under AddressSanitizer, whose shadow
// memory needs a huge address space (it reports such allocations itself).
class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(size_t budget) {
    if (kAddressSanitizer || getrlimit(RLIMIT_AS, &saved_) != 0) return;
    long pages = 0, size = sysconf(_SC_PAGE_SIZE);
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
      std::fclose(f);
    }
    // Room for the process as it is, the budget twice over (estimates are lower bounds), and the
    // thread stacks of OpenMP.
    rlimit cap = saved_;
    cap.rlim_cur = static_cast<rlim_t>(pages) * size + 2 * budget + (size_t(2) << 30);
    if (saved_.rlim_max != RLIM_INFINITY) cap.rlim_cur = std::min(cap.rlim_cur, saved_.rlim_max);
    active_ = setrlimit(RLIMIT_AS, &cap) == 0;
  }
  ~AddressSpaceCap() {
    if (active_) setrlimit(RLIMIT_AS, &saved_);
  }

 private:
  rlimit saved_{};
  bool active_ = false;
};

// Aborts the process when one case runs longer than the limit (in-process mode: a hang cannot
// be interrupted), naming the case.
class Watchdog {
 public:
  Watchdog(double limit, std::string casePath) : limit_(limit), casePath_(std::move(casePath)) {
    thread_ = std::thread([this] {
      while (!stop_) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        const double start = start_;
        if (start > 0 && now() - start > limit_) {
          std::fprintf(
              stderr,
              "fuzz: case %ld ran longer than %g s (a hang); its input is %s, its origin %s.txt\n",
              index_.load(), limit_, casePath_.c_str(), casePath_.c_str());
          std::_Exit(4);
        }
      }
    });
  }
  ~Watchdog() {
    stop_ = true;
    thread_.join();
  }
  void begin(long index) {
    index_ = index;
    start_ = now();
  }
  void end() { start_ = 0; }

 private:
  double limit_;
  std::string casePath_;
  std::atomic<bool> stop_{false};
  std::atomic<double> start_{0};
  std::atomic<long> index_{0};
  std::thread thread_;
};

std::string describeSignal(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return sig == SIGALRM
               ? std::string("hang (killed by the case time limit)")
               : "crash: killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  return "child exited with code " + std::to_string(WEXITSTATUS(status));
}

// One case in a child process. Exit codes: 0 accepted, 10 rejected correctly, 11 a failure
// (described on the pipe).
std::string checkSetupInChild(const std::string& text, const std::string& name, double limit,
                              bool* accepted) {
  int fd[2];
  if (pipe(fd) != 0) return "pipe() failed";
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return "fork() failed";
  if (pid == 0) {
    close(fd[0]);
    alarm(static_cast<unsigned>(std::max(1.0, limit)));
    bool ok = false;
    const std::string problem = checkSetup(text, name, &ok);
    if (!problem.empty() && write(fd[1], problem.data(), problem.size()) < 0) _exit(12);
    _exit(!problem.empty() ? 11 : ok ? 0 : 10);
  }
  close(fd[1]);
  std::string message;
  char buffer[4096];
  ssize_t n;
  while ((n = read(fd[0], buffer, sizeof buffer)) > 0)
    message.append(buffer, static_cast<size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) *accepted = true;
  if (WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 10)) return "";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 11) return message;
  return describeSignal(status);
}

}  // namespace

std::vector<std::string> defaultCorpus(const std::string& sourceDir) {
  std::vector<std::string> files;
  const fs::path inputs = fs::path(sourceDir) / "inputs";
  if (fs::exists(inputs))
    for (const auto& e : fs::recursive_directory_iterator(inputs))
      if (e.is_regular_file() && e.path().extension() == ".ups") files.push_back(e.path().string());
  const fs::path minimal = fs::path(sourceDir) / "tests/bad_inputs/valid_minimal.ups";
  if (fs::exists(minimal)) files.push_back(minimal.string());
  const fs::path uintah = fs::path(sourceDir) / "../shared/inputs/uintah";
  if (fs::exists(uintah))
    for (const auto& e : fs::directory_iterator(uintah))
      if (e.is_regular_file() && e.path().extension() == ".ups") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string checkSetup(const std::string& text, const std::string& name, bool* accepted) {
  *accepted = false;
  try {
    RunOptions options;
    options.input = name;
    options.progress = false;
    Simulation simulation(text, name, options);
    *accepted = true;
    return "";
  } catch (const InputError& e) {
    const long lines = 1 + std::count(text.begin(), text.end(), '\n');
    const std::string prefix = name + ":" + std::to_string(e.line()) + ": ";
    const std::string what = e.what();
    if (e.file() != name)
      return "InputError names the file '" + e.file() + "', not '" + name + "': " + what;
    if (e.line() < 1 || e.line() > lines)
      return "InputError names line " + std::to_string(e.line()) + " of a text of " +
             std::to_string(lines) + " lines: " + what;
    if (what.compare(0, prefix.size(), prefix) != 0 || what.size() == prefix.size())
      return "InputError message does not read '" + prefix + "message': " + what;
    return "";
  } catch (const std::bad_alloc&) {
    return "std::bad_alloc: an allocation the input's size checks did not foresee";
  } catch (const std::exception& e) {
    return "exception of type " + demangle(typeid(e).name()) +
           " instead of an InputError: " + e.what();
  } catch (...) {
    return "an exception that is not a std::exception";
  }
}

FuzzCase makeCase(const FuzzOptions& options, const std::vector<std::string>& seedTexts,
                  long index) {
  InputMutator mutator(options.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(index));
  const size_t s = std::uniform_int_distribution<size_t>(0, seedTexts.size() - 1)(mutator.rng());
  FuzzCase c;
  c.seed = options.corpus[s];
  c.text = seedTexts[s];
  c.mutations = mutator.mutate(c.text, &c.operators);
  return c;
}

FuzzReport runFuzz(const FuzzOptions& options) {
  FuzzReport report;
  if (options.corpus.empty()) return report;
  std::vector<std::string> seedTexts;
  for (const std::string& f : options.corpus) seedTexts.push_back(readFile(f));

  const std::string casePath =
      options.casePath.empty()
          ? (fs::temp_directory_path() / ("anode_fuzz_case_" + std::to_string(getpid()) + ".ups"))
                .string()
          : options.casePath;
  // Setup must write nothing: cases run in an empty directory that must stay empty.
  const fs::path work = fs::temp_directory_path() / ("anode_fuzz_work_" + std::to_string(getpid()));
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path home = fs::current_path();
  fs::current_path(work);

  setMemoryBudget(options.memoryBudget);
  AddressSpaceCap cap(options.memoryBudget);
  std::unique_ptr<Watchdog> watchdog;
  if (!options.fork) watchdog = std::make_unique<Watchdog>(options.caseTimeLimit, casePath);

  const double start = now();
  double lastProgress = start;
  for (long i = 0; i < options.cases; ++i) {
    if (options.seconds > 0 && now() - start > options.seconds) break;
    const FuzzCase c = makeCase(options, seedTexts, i);
    const std::string name = "fuzz/" + fs::path(c.seed).filename().string();
    writeFile(casePath, c.text);
    writeFile(casePath + ".txt", "case " + std::to_string(i) + " (seed " +
                                     std::to_string(options.seed) + ") of " + c.seed + ": " +
                                     c.mutations + "\n");
    bool accepted = false;
    std::string problem;
    if (options.fork) {
      problem = checkSetupInChild(c.text, name, options.caseTimeLimit, &accepted);
    } else {
      watchdog->begin(i);
      problem = checkSetup(c.text, name, &accepted);
      watchdog->end();
    }
    if (problem.empty() && !fs::is_empty(work)) {
      problem = "setup wrote into the working directory";
      fs::remove_all(work);
      fs::create_directories(work);
    }
    ++report.tried;
    for (int op : c.operators) ++report.perOperator[op];
    if (!problem.empty()) {
      report.failures.push_back({i, c.seed, c.mutations, problem});
      writeFile(casePath + ".failure" + std::to_string(report.failures.size()) + ".ups", c.text);
    } else if (accepted) {
      ++report.accepted;
    } else {
      ++report.rejected;
    }
    if (options.progress && now() - lastProgress > 10) {
      lastProgress = now();
      std::fprintf(stderr, "fuzz: %ld cases, %ld accepted, %ld rejected, %zu failures, %.0f s\n",
                   report.tried, report.accepted, report.rejected, report.failures.size(),
                   lastProgress - start);
    }
  }
  report.seconds = now() - start;
  watchdog.reset();
  setMemoryBudget(0);
  fs::current_path(home);
  fs::remove_all(work);
  if (report.failures.empty()) {
    fs::remove(casePath);
    fs::remove(casePath + ".txt");
  }
  return report;
}

}  // namespace anode::fuzz

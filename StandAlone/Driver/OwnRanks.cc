#include "StandAlone/Driver/OwnRanks.h"

#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "StandAlone/Driver/Progress.h"

namespace anode {

namespace {

volatile sig_atomic_t mpirunProcess = 0;

// A stop asked of this process, for mpirun to pass on to every rank.
extern "C" void passStopOn(int) {
  if (mpirunProcess > 0) kill(mpirunProcess, SIGUSR1);
}

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGUSR1};

// The first executable `name` in a directory of PATH, or empty.
std::string findOnPath(const char* name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t begin = 0;
  while (begin <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::string dir = end > begin ? dirs.substr(begin, end - begin) : ".";
    const std::string candidate = dir + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    begin = end + 1;
  }
  return {};
}

}  // namespace

int coresOfThisProcess() {
  cpu_set_t set;
  CPU_ZERO(&set);
  return sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
}

bool asksForImplicitPath(const std::string& path) {
  try {
    ProblemSpec spec(path, true);
    const PSNode mpm = spec.root().child("MPM");
    return mpm && mpm.get<std::string>("time_integrator", "explicit") == "implicit";
  } catch (const std::exception&) {
    return false;
  }
}

int runOnOwnRanks(int ranks, const std::string& program, const std::vector<std::string>& arguments,
                  std::string& why) {
  const std::string mpirun = findOnPath("mpirun");
  if (mpirun.empty()) {
    why = "mpirun is not on PATH";
    return -1;
  }
  // -q: no banner of Open MPI's when the ranks end with a code other than 0 (2, 3 or 4 are
  // sus's own); no standard input for the ranks (mpirun would read the terminal from a process
  // group in the background and be stopped).
  std::vector<std::string> words = {mpirun, "-q", "--stdin", "none", "-np", std::to_string(ranks)};
  if (geteuid() == 0) words.push_back("--allow-run-as-root");  // as this process runs
  if (ranks > coresOfThisProcess()) words.push_back("--oversubscribe");
  words.push_back(program);
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  // The stop signals wait while mpirun starts, then reach it through passStopOn.
  sigset_t stops, before;
  sigemptyset(&stops);
  for (int s : kStopSignals) sigaddset(&stops, s);
  sigprocmask(SIG_BLOCK, &stops, &before);
  struct sigaction pass = {};
  pass.sa_handler = passStopOn;
  sigemptyset(&pass.sa_mask);
  pass.sa_flags = SA_RESTART;
  for (int s : kStopSignals) sigaction(s, &pass, nullptr);
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child == 0) {
    setpgid(0, 0);                     // out of the terminal's foreground group
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // mpirun ends the ranks when this process dies
    if (getppid() != parent) _exit(1);
    sigprocmask(SIG_SETMASK, &before, nullptr);
    if (isatty(STDERR_FILENO)) setenv(kProgressOnTerminal, "1", 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (child < 0) {
    why = std::string("fork failed: ") + std::strerror(errno);
    sigprocmask(SIG_SETMASK, &before, nullptr);
    return -1;
  }
  setpgid(child, child);
  mpirunProcess = child;
  sigprocmask(SIG_SETMASK, &before, nullptr);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  mpirunProcess = 0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace anode

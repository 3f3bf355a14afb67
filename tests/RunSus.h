// Runs this build's sus (ANODE_SUS) from a test through the shell, as a user would.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

namespace anode::testing {

struct SusResult {
  int exitCode = -1;   // -1: sus did not start or did not exit normally
  std::string output;  // stdout and stderr together
};

inline std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// sus with `args`, each quoted for the shell.
inline SusResult runSus(const std::vector<std::string>& args) {
  std::string command = shellQuote(ANODE_SUS);
  for (const std::string& a : args) command += " " + shellQuote(a);
  command += " 2>&1";
  SusResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  if (status != -1 && WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  return r;
}

}  // namespace anode::testing

#include "StandAlone/Studies/VerificationRun.h"

#include <stdexcept>

namespace anode {

namespace {

RunOptions withoutProgress() {
  RunOptions options;
  options.progress = false;
  return options;
}

}  // namespace

VerificationRun::VerificationRun(const std::string& problem, const std::string& input,
                                 const std::string& name)
    : start_(std::chrono::steady_clock::now()), sim_(input, name, withoutProgress()) {
  if (sim_.mpm().materials().size() != 1)
    throw std::logic_error(problem + ": expected one material");
}

bool VerificationRun::beforeEndTime() const {
  return sim_.time() < sim_.timeControl().maxTime * (1 - 1e-12);
}

double VerificationRun::wallSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace anode

// One case of a verification problem (VibratingBar.h, FluxSlab.h, DiffusionSlab1D.h) as a run:
// the Simulation built in memory from the case's .ups text, without progress line, holding one
// material, and stepped to its end time.
#pragma once

#include <chrono>
#include <string>

#include "StandAlone/Driver/Simulation.h"

namespace anode {

class VerificationRun {
 public:
  // `name` stands for the input file in messages. Throws what the Simulation throws, and
  // std::logic_error("<problem>: expected one material").
  VerificationRun(const std::string& problem, const std::string& input, const std::string& name);

  Simulation& simulation() { return sim_; }
  ParticleSet& particles() { return sim_.mpm().materials()[0].particles; }
  // Until the last step, which <end_at_max_time_exactly> lands on <maxTime> (up to rounding).
  bool beforeEndTime() const;
  // Since the construction began.
  double wallSeconds() const;

 private:
  std::chrono::steady_clock::time_point start_;
  Simulation sim_;
};

}  // namespace anode

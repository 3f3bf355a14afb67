// The stable time step of the current state before the multiplier (paper Eq. 45): the smallest
// of the mechanical limit (Eq. 43), the diffusion limit (Eq. 44) and the flux limit
// (docs/diffusion.md, "Time step"), each over all ranks, and which of them sets it. An implicit
// run has two: the last dt grown or shrunk by its Newton iterations (ImpMPM's rule), and with
// diffusion the dt whose largest change of c would be <max_concentration_change> and the dt its
// diffusion pass covers in DiffusionPass::kMaxRateEvaluations sub-steps or stages; with
// <error_tolerance>, the dt the error controller gives from the last steps' error estimates
// (before the first estimate: the tolerance times the flux limit, ImplicitStep::stableTimestep).
#pragma once

#include <algorithm>
#include <array>
#include <limits>

namespace anode {

struct StableTimestep {
  enum Limit {
    Mechanics,
    Diffusion,
    Flux,
    Newton,
    ConcentrationChange,
    DiffusionPassCap,
    ErrorEstimate,
    kLimits
  };
  // Each limit's dt; infinity where it does not apply.
  std::array<double, kLimits> bound = unbounded();

  double dt() const { return *std::min_element(bound.begin(), bound.end()); }
  Limit binding() const {
    return static_cast<Limit>(std::min_element(bound.begin(), bound.end()) - bound.begin());
  }
  static const char* name(Limit limit) {
    constexpr const char* names[kLimits] = {"mechanics (Eq. 43)",
                                            "diffusion (Eq. 44)",
                                            "flux restriction",
                                            "Newton iterations",
                                            "concentration change per step",
                                            "sub-steps per diffusion pass",
                                            "error estimate"};
    return names[limit];
  }

 private:
  static std::array<double, kLimits> unbounded() {
    std::array<double, kLimits> all;
    all.fill(std::numeric_limits<double>::infinity());
    return all;
  }
};

}  // namespace anode

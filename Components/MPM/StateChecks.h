// Instability diagnostics run after every step (DESIGN.md §8, docs/stability.md), besides the
// ones the step itself makes (a particle leaving the grid, det F <= 0, a concentration out of
// range): a non-finite position, velocity or stress; J = V rho0 / m outside [kMinJ, kMaxJ]; the
// oscillation of an explicit update beyond its stable time step, in the velocities or the
// concentrations; a kinetic energy that grows geometrically. The velocity and kinetic-energy
// watches serve steps with inertia (explicit, or implicit with <dynamic>true): a quasi-static
// step's velocity is its displacement over dt and turns with the load. Each throws a
// SimulationError naming the particle (ID, material, position), the field and the offending value.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "Components/MPM/MPM.h"
#include "Components/MPM/ParticleSet.h"

namespace anode {

class StateChecks {
 public:
  // J outside [kMinJ, kMaxJ]: a volume no swelling, tension or compression explains (Uintah
  // stops above the same upper bound).
  static constexpr double kMaxJ = 1e5;
  static constexpr double kMinJ = 1e-5;
  // Oscillation: an explicit update beyond its stable time step amplifies its highest mode,
  // which flips sign every step. Watched in the particles' increments per step d_n (velocity,
  // and concentration with diffusion): in a run of steps whose consecutive increments are
  // anti-correlated (mass-weighted correlation below kAlternation), the energy of two
  // consecutive increments, sum m (|d_n|^2 + |d_{n-1}|^2) / 2, must neither grow by
  // kOscillationGrowth over its smallest value in the run, nor by kSustainedGrowth once the run
  // is kSustainedSteps long. Stable runs keep the correlation positive (its lowest value was
  // +0.59 in the 2-D and +0.70 in the 3-D cases of docs/stability.md); a single stable mode of
  // phase theta per step gives cos theta and a pair energy that does not grow.
  static constexpr double kAlternation = -0.5;
  static constexpr double kOscillationGrowth = 100;
  static constexpr int kSustainedSteps = 10;
  static constexpr double kSustainedGrowth = 2;
  // Kinetic-energy blow-up: the energy grew by at least kGrowthPerStep at each of
  // kGrowthSteps consecutive steps (2^20 ~ 1e6 overall). Physical growth from rest follows a
  // power p of time, whose ratio per step (1 + 1/n)^p drops below 2 after about 1.44 p steps.
  static constexpr double kGrowthPerStep = 2;
  static constexpr int kGrowthSteps = 20;
  // Local oscillation: the whole-body watch above sees an instability confined to a few particles
  // only once it dominates the body's increments. Each particle is also watched: its velocity
  // increment reversed the previous one (cosine below kAlternation) and grew by at least
  // kLocalGrowth, kLocalSteps steps in a row (x2.5 in all), and is not round-off: above
  // kLocalFloor times the body's rms speed and large enough to move the particle kLocalMotion
  // of a cell in a step.
  static constexpr int kLocalSteps = 5;
  static constexpr double kLocalGrowth = 1.2;
  static constexpr double kLocalFloor = 1e-3;
  static constexpr double kLocalMotion = 1e-9;

  // Checks the state after a step of length dt; throws SimulationError on the first problem found
  // (in a distributed run on every rank together).
  void afterStep(Collective, const MPM& mpm, double dt);

 private:
  // The oscillation watch of one field (velocity or concentration).
  struct Oscillation {
    double lastEnergy = 0;  // sum m |d_{n-1}|^2 / 2
    int steps = 0;          // consecutive anti-correlated steps
    double smallest = 0;    // the smallest pair energy of those steps
  };
  // Updates `o` with this step's increment energy and correlation; true when it trips.
  static bool oscillates(Oscillation& o, double energy, double product, double* growth,
                         double* correlation);
  void checkOscillation(Collective, const MPM& mpm, double velocityEnergy, double velocityProduct,
                        double concentrationEnergy, double concentrationProduct);
  void checkKineticEnergy(Collective, const MPM& mpm, double energy);
  std::string describeLocalOscillation(const MPMMaterial& mat, size_t m, size_t i) const;
  // Calls f(history, start) on each per-particle history of material m (those of the
  // concentration only with diffusion), where start(j) is the value particle j's begins with.
  template <class F>
  void forEachHistory(size_t m, const ParticleSet& p, F&& f);
  // Carries material m's per-particle history along with the last step's splitting and migration.
  void followReordering(const ParticleReordering& r, size_t m, const ParticleSet& p);

  // Per material: last step's velocities and concentrations, and their increments then; per
  // particle, the steps in a row its velocity increment reversed and grew.
  std::vector<std::vector<Vec3>> velocity_, velocityIncrement_;
  std::vector<std::vector<uint8_t>> localStreak_;
  std::vector<std::vector<double>> concentration_, concentrationIncrement_;
  Oscillation velocityOscillation_, concentrationOscillation_;

  int layoutGeneration_ = 0;  // RankLayout::generation of the histories above
  double lastKineticEnergy_ = 0, lastMass_ = 0;
  int growingSteps_ = 0;
  double energyBeforeGrowth_ = 0;
};

}  // namespace anode

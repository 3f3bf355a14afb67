// Diffusivity laws of <diffusion_model type="..."> (UINTAH_UPS.md §2.11, §4; paper Eqs. 23-24).
// A model maps each particle's normalised concentration (and pressure) to its diffusivity D_p;
// the flux q_p = D_p grad c_p and its divergence (Eqs. 6-7) are computed by the MPM step.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/BinaryStream.h"

namespace anode {

class ScalarDiffusionModel {
 public:
  virtual ~ScalarDiffusionModel() = default;

  // Sets p.diffusivity for the step that starts at time t from the particles' current
  // concentration and stress; returns the largest diffusivity (for Eq. 44).
  virtual double computeDiffusivity(ParticleSet& p, double t) = 0;
  // The uniform dc/dt of constant_rate; 0 for the others.
  virtual double constantRate() const { return 0.0; }
  // The scaled pressure entering D (Eq. 23), for output as Uintah's removed p.pressure_t1.
  virtual double scaledPressure(const Mat3&) const { return 0.0; }
  // k of phi = k tau_h, the stress's part of the chemical potential over RT (ChemicalPotential.h),
  // in 1 / the input's stress unit: 0 for a flux by grad c alone (all but chemical_potential).
  virtual double stressPotentialPerStress() const { return 0.0; }
  // s: the change of phi with the particle's own c (normalised) that a pass takes implicitly, at
  // J = 1: phi(c) = phi_0 - s J (c - c_0) (ChemicalPotential.h); 0 without a stress part.
  virtual double stressPotentialStabilization() const { return 0.0; }
  // False when the model has no flux at all (constant_rate, or a zero diffusivity everywhere).
  virtual bool diffuses() const { return D0 > 0; }
  // What the model carries from step to step besides the particle arrays (empty when it has
  // none): checkpoints save it, a quasi-static step retaken with a smaller dt restores it.
  virtual std::vector<uint64_t> stepState() const { return {}; }
  // Throws std::runtime_error for a state the model cannot take.
  virtual void restoreStepState(const std::vector<uint64_t>&) {}
  void saveState(BinaryWriter& out) const {
    for (uint64_t v : stepState()) out.value(v);
  }
  void loadState(BinaryReader& in) {
    std::vector<uint64_t> state = stepState();
    for (uint64_t& v : state) v = in.value<uint64_t>();
    restoreStepState(state);
  }

  double D0 = 0;                // <diffusivity>
  double maxConcentration = 1;  // <max_concentration>
  double minConcentration = 0;  // <min_concentration>
  std::string type;
};

// A concentration may leave [min, max] by this much (relative to max - min) before the run is
// stopped: round-off of the explicit update, never a clamp.
constexpr double kConcentrationTolerance = 1e-6;

// What the diffusion subcomponent keeps of each <material>.
struct DiffusionMaterial {
  std::unique_ptr<ScalarDiffusionModel> model;  // <diffusion_model>
  // <do_conc_reduction>: its particles count in the concentration <do_auto_cycle_bc> watches.
  bool reducesConcentration = false;
};

// What a diffusivity model reads of its material and run besides its <diffusion_model>.
struct DiffusionModelContext {
  double maxTime = 0;                        // bounds diff_curve
  double swellingCoefficient = 0;            // the material's eta (<volume_expansion_coeff>)
  double bulkModulus = 0, shearModulus = 0;  // the material's K and G (the largest over c)
  bool implicit = false;  // <time_integrator>implicit (chemical_potential needs it)
};

// Factory keyed by type=: jg, constant_rate, non_linear1, cubic, chemical_potential.
std::unique_ptr<ScalarDiffusionModel> createDiffusionModel(const PSNode& node,
                                                           const DiffusionModelContext& context);

// Eq. 23: D0 exp(alpha c) exp(-beta clamp(scale p, floor, p_max)), p = -tr(sigma)/3.
double nonLinear1Diffusivity(double D0, double alpha, double beta, double c, double scaledPressure);
// Eq. 24: D0 (1 - c)^3 + Dmax c^3.
double cubicDiffusivity(double D0, double Dmax, double c);

}  // namespace anode

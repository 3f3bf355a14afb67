#include "Components/MPM/ImplicitOptions.h"

#include <algorithm>
#include <optional>
#include <string>

namespace anode {

namespace {

template <class T>
void readPositive(const PSNode& mpm, const char* tag, T& value) {
  value = mpm.get<T>(tag, value);
  if (!(value > 0)) mpm.requireChild(tag).fail("<" + std::string(tag) + "> must be positive");
}

}  // namespace

ImplicitOptions ImplicitOptions::fromInput(const PSNode& mpm, bool diffusion) {
  ImplicitOptions o;
  o.dynamic = mpm.get<bool>("dynamic", o.dynamic);
  // Quasi-static steps with diffusion are chosen by their error estimate unless the input says
  // otherwise (<error_tolerance>0, or a staggered coupling, which has no estimate).
  const PSNode coupling = mpm.child("concentration_coupling");
  if (diffusion && !o.dynamic && !(coupling && coupling.value<std::string>() == "staggered"))
    o.errorTolerance = kDefaultErrorTolerance;
  readPositive(mpm, "convergence_criteria_disp", o.convergenceDisp);
  readPositive(mpm, "convergence_criteria_energy", o.convergenceEnergy);
  readPositive(mpm, "iters_before_timestep_restart", o.maxIterations);
  readPositive(mpm, "num_iters_to_decrease_delT", o.itersToDecrease);
  o.itersToIncrease = mpm.get<int>("num_iters_to_increase_delT", o.itersToIncrease);
  if (o.itersToIncrease < 0)
    mpm.requireChild("num_iters_to_increase_delT")
        .fail("<num_iters_to_increase_delT> must be >= 0");
  if (o.itersToIncrease >= o.itersToDecrease)
    mpm.requireChild("num_iters_to_increase_delT")
        .fail("<num_iters_to_increase_delT> must be below <num_iters_to_decrease_delT> (" +
              std::to_string(o.itersToDecrease) + ")");
  readPositive(mpm, "delT_decrease_factor", o.decreaseFactor);
  if (!(o.decreaseFactor < 1))
    mpm.requireChild("delT_decrease_factor").fail("<delT_decrease_factor> must be in (0, 1)");
  readPositive(mpm, "delT_increase_factor", o.increaseFactor);
  if (!(o.increaseFactor >= 1))
    mpm.requireChild("delT_increase_factor").fail("<delT_increase_factor> must be >= 1");
  o.hourglassStabilization = mpm.get<double>("hourglass_stabilization", o.hourglassStabilization);
  if (!(o.hourglassStabilization >= 0))
    mpm.requireChild("hourglass_stabilization").fail("<hourglass_stabilization> must be >= 0");
  o.jacobianCouplingShare = mpm.get<double>("jacobian_coupling_share", o.jacobianCouplingShare);
  if (!(o.jacobianCouplingShare >= 0 && o.jacobianCouplingShare <= 1e-3))
    mpm.requireChild("jacobian_coupling_share")
        .fail("<jacobian_coupling_share> must be in [0, 1e-3]");
  o.jacobianReuse = mpm.get<bool>("jacobian_reuse", o.jacobianReuse);
  o.errorTolerance = mpm.get<double>("error_tolerance", o.errorTolerance);
  if (!(o.errorTolerance >= 0 && o.errorTolerance < 1))
    mpm.requireChild("error_tolerance").fail("<error_tolerance> must be in [0, 1)");
  if (o.errorTolerance > 0) {
    if (o.dynamic)
      mpm.requireChild("error_tolerance")
          .unsupported("<error_tolerance> with <dynamic>true (it serves quasi-static steps)");
    o.maxConcentrationChange = 0;
    o.concentrationCoupling = ConcentrationCoupling::Trapezoidal;
    // Newton's criteria that the input leaves out follow the tolerance: the last correction at
    // most a tenth of it against the step's largest, (tol / 10)^2 of |du|^2, and 4x that for the
    // energy as ImpMPM's defaults are; never tighter than those (docs/quasi-static.md, "Steps by
    // error estimate").
    const double disp = (o.errorTolerance / 10) * (o.errorTolerance / 10);
    if (!mpm.child("convergence_criteria_disp"))
      o.convergenceDisp = std::max(o.convergenceDisp, disp);
    if (!mpm.child("convergence_criteria_energy"))
      o.convergenceEnergy = std::max(o.convergenceEnergy, 4 * disp);
    // A Newton held to those criteria needs no exact Jacobian: where the input leaves it out,
    // the Jacobian drops the round-off couplings (docs/quasi-static.md, "Steps by error
    // estimate"); the residual keeps them, so the equilibrium is the same.
    if (!mpm.child("jacobian_coupling_share")) o.jacobianCouplingShare = kErrorControlCouplingShare;
    // The diffusion passes' stages follow the diffusivity, not a fixed share of the explicit
    // limit: where the input leaves the integrator out, RKL2 (docs/quasi-static.md, "Steps by
    // error estimate").
    if (!mpm.child("diffusion_integrator")) {
      o.diffusionIntegrator = DiffusionIntegrator::Rkl2;
      o.rkl2ByDefault = true;
    }
  }
  if (const std::optional<double> change = mpm.find<double>("max_concentration_change")) {
    o.maxConcentrationChange = *change;
    if (!(o.maxConcentrationChange > 0 && o.maxConcentrationChange <= 1))
      mpm.requireChild("max_concentration_change")
          .fail("<max_concentration_change> must be in (0, 1]");
  }
  if (coupling) {
    const std::string name = coupling.value<std::string>();
    if (name == "trapezoidal")
      o.concentrationCoupling = ConcentrationCoupling::Trapezoidal;
    else if (name != "staggered")
      coupling.fail("<concentration_coupling> must be staggered or trapezoidal, found \"" + name +
                    "\"");
    else if (o.errorTolerance > 0)
      coupling.fail(
          "<concentration_coupling>staggered with <error_tolerance>: the error estimate is made "
          "from a trapezoidal step's two diffusion passes");
    if (o.dynamic && o.concentrationCoupling == ConcentrationCoupling::Trapezoidal)
      coupling.unsupported(
          "<concentration_coupling>trapezoidal with <dynamic>true (it serves "
          "quasi-static steps)");
  }
  if (const PSNode integrator = mpm.child("diffusion_integrator")) {
    const std::string name = integrator.value<std::string>();
    if (name == "rkl2")
      o.diffusionIntegrator = DiffusionIntegrator::Rkl2;
    else if (name != "euler")
      integrator.fail("<diffusion_integrator> must be euler or rkl2, found \"" + name + "\"");
  }
  o.subcellConcentrationRelaxation =
      mpm.get<bool>("subcell_concentration_relaxation", o.subcellConcentrationRelaxation);
  if (const PSNode swelling = mpm.child("swelling_strain")) {
    const std::string name = swelling.value<std::string>();
    if (name == "cell_mean")
      o.swellingStrain = SwellingStrain::CellMean;
    else if (name != "particle")
      swelling.fail("<swelling_strain> must be cell_mean or particle, found \"" + name + "\"");
  }
  if (const PSNode solver = mpm.child("solver")) {
    const std::string name = solver.value<std::string>();
    if (name == "simple")
      solver.warn(
          "<solver>simple: the linear systems are solved by PETSc (GMRES, GAMG) all the same");
    else if (name != "petsc")
      solver.fail("<solver> must be petsc or simple, found \"" + name + "\"");
  }
  if (const PSNode mechanics = mpm.child("DoMechanics"))
    if (!mechanics.value<bool>()) mechanics.unsupported("<DoMechanics>false");
  if (const PSNode temperature = mpm.child("temperature_solve"))
    if (temperature.value<bool>()) temperature.unsupported("the implicit heat conduction solve");
  if (const PSNode reset = mpm.child("do_grid_reset"))
    if (!reset.value<bool>()) reset.unsupported("<do_grid_reset>false (a grid that moves)");
  if (const PSNode factor = mpm.child("ForceBC_force_increment_factor"))
    if (factor.value<double>() != 1) factor.unsupported("<ForceBC_force_increment_factor>");
  if (const PSNode faces = mpm.child("boundary_traction_faces"))
    faces.unsupported("<boundary_traction_faces> (the reaction forces on grid faces)");
  mpm.acceptInert("ProjectHeatSource");
  mpm.acceptInert("interpolateParticleTempToGridEveryStep");
  return o;
}

}  // namespace anode

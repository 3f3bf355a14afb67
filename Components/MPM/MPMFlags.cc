#include "Components/MPM/MPMFlags.h"

#include <optional>
#include <string>

namespace anode {

namespace {

// A boolean flag whose `true` asks for a feature this code does not have.
void rejectIfTrue(const PSNode& mpm, const char* tag, const std::string& feature) {
  if (const PSNode n = mpm.child(tag))
    if (n.value<bool>()) n.unsupported("<" + std::string(tag) + ">true: " + feature);
}

void readAMR(const PSNode& root) {
  const PSNode amr = root.child("AMR");
  if (!amr) return;
  if (const PSNode lock = amr.child("useLockStep"))
    if (!lock.value<bool>()) lock.fail("<useLockStep> must be true for amrmpm");
  if (const PSNode regridder = amr.child("Regridder")) {
    if (regridder.get<int>("max_levels", 1) > 1)
      regridder.requireChild("max_levels").unsupported("adaptive refinement with several levels");
    regridder.markSubtreeUsed();
  }
}

// <AMR><MPM><Refinement_Criteria_Thresholds>: the stretch ratio that splits a particle
// (UINTAH_UPS.md §9), read only when <refine_particles> is on.
void readRefinementCriteria(const PSNode& root, MPMFlags& f) {
  const PSNode amr = root.child("AMR");
  const PSNode amrMPM = amr ? amr.child("MPM") : PSNode();
  if (!f.refineParticles) {
    if (amrMPM) amrMPM.markSubtreeUsed();
    return;
  }
  const PSNode criteria = amrMPM ? amrMPM.child("Refinement_Criteria_Thresholds") : PSNode();
  if (!criteria)
    root.child("MPM")
        .requireChild("refine_particles")
        .fail(
            "<refine_particles>true needs <AMR><MPM><Refinement_Criteria_Thresholds> with a "
            "stretchRatio");
  for (const PSNode& v : criteria.children()) {
    if (v.name() != "Variable") v.fail("<Refinement_Criteria_Thresholds> holds <Variable> tags");
    const std::string name = v.requireAttribute("name");
    if (name != "stretchRatio") {
      v.unsupported("refinement criterion \"" + name + "\" (accepted: stretchRatio)");
      continue;
    }
    try {
      f.stretchRatio = parseValue<double>(v.requireAttribute("value"));
    } catch (const std::invalid_argument& e) {
      v.fail(std::string("<Variable value=...>: ") + e.what());
    }
    if (!(f.stretchRatio > 1)) v.fail("the stretchRatio must exceed 1");
    // Without matl= Uintah reads material 0 (and warns).
    const std::optional<std::string> given = v.attribute("matl");
    if (!given) v.warn("<Variable> without matl=: only material 0 splits, as in Uintah");
    const std::string matl = given.value_or("0");
    if (matl == "all") {
      f.refineMaterial = -1;
    } else {
      try {
        f.refineMaterial = parseValue<int>(matl);
      } catch (const std::invalid_argument&) {
        v.fail("matl=\"" + matl + "\" must be \"all\" or a material index");
      }
    }
  }
  if (!(f.stretchRatio > 0))
    criteria.fail("<refine_particles>true needs a stretchRatio <Variable>");
}

}  // namespace

MPMFlags MPMFlags::fromInput(const PSNode& root) {
  const PSNode component = root.requireChild("SimulationComponent");
  const std::string type = component.requireAttribute("type");
  if (type != "amrmpm" && type != "mpm" && type != "impm")
    component.fail("SimulationComponent type=\"" + type +
                   "\" is not supported; accepted: amrmpm, mpm, impm");
  if (type == "amrmpm" && !root.child("AMR"))
    component.fail("type=\"amrmpm\" requires an <AMR> block with <useLockStep>true</useLockStep>");
  readAMR(root);
  root.acceptInert("Meta");

  MPMFlags f;
  const PSNode mpm = root.child("MPM");
  // Uintah reads gravity from <PhysicalConstants>, or without that block from <MPM>, where it
  // requires it; here it defaults to 0 (docs/differences-from-uintah.md).
  if (const PSNode constants = root.child("PhysicalConstants")) {
    f.gravity = constants.require<Vec3>("gravity");
    constants.acceptInert("reference_pressure");
    if (mpm) mpm.acceptInert("gravity");
  } else if (mpm) {
    f.gravity = mpm.get<Vec3>("gravity", Vec3::Zero());
  }
  if (type == "impm" && (!mpm || mpm.get<std::string>("time_integrator", "") != "implicit"))
    component.fail("type=\"impm\" needs <MPM><time_integrator>implicit</time_integrator>");
  if (!mpm) {
    readRefinementCriteria(root, f);  // no <refine_particles>: the thresholds are inert
    return f;
  }

  f.doScalarDiffusion = mpm.get<bool>("do_scalar_diffusion", false);
  const std::string integrator = mpm.get<std::string>("time_integrator", "explicit");
  if (integrator == "implicit") {
    f.implicit = ImplicitOptions::fromInput(mpm, f.doScalarDiffusion);
  } else if (integrator == "explicit") {
    // The explicit step's stress update takes each particle's own dc (ParticleLoops.h).
    if (const PSNode swelling = mpm.child("swelling_strain"))
      if (const std::string name = swelling.value<std::string>(); name != "particle")
        swelling.unsupported("<swelling_strain>" + name +
                             " with <time_integrator>explicit (its stress update takes each "
                             "particle's own dc)");
  } else {
    mpm.requireChild("time_integrator")
        .fail("time_integrator \"" + integrator +
              "\" is not supported; accepted: explicit, implicit");
  }

  const std::string interp = mpm.get<std::string>("interpolator", "linear");
  if (interp == "linear") {
    f.interpolator = InterpolatorKind::Linear;
  } else if (interp == "gimp") {
    f.interpolator = InterpolatorKind::GIMP;
  } else if (interp == "cpdi" || interp == "fast_cpdi") {
    f.interpolator = InterpolatorKind::CPDI;
  } else if (interp == "cpti" || interp == "3rdorderBS" || interp == "4thorderBS") {
    mpm.requireChild("interpolator")
        .fail("interpolator \"" + interp + "\" is not supported; accepted: linear, gimp, cpdi");
  } else {
    mpm.requireChild("interpolator")
        .fail("unknown interpolator \"" + interp + "\"; accepted: linear, gimp, cpdi");
  }
  if (const PSNode lcrit = mpm.child("cpdi_lcrit"))
    if (lcrit.value<double>() < 1e10) lcrit.unsupported("CPDI corner limiting <cpdi_lcrit>");

  f.useLoadCurves = mpm.get<bool>("use_load_curves", false);
  // This code's extension (docs/diffusion.md): how SD-Type Dirichlet conditions reach particles.
  if (const PSNode t = mpm.child("concentration_dirichlet")) {
    const std::string v = t.value<std::string>();
    if (v != "particle" && v != "nodal")
      t.fail("<concentration_dirichlet> must be particle or nodal, found \"" + v + "\"");
    f.particleDirichlet = v == "particle";
  }
  // This code's extensions for studies (docs/differences-from-uintah.md): Uintah's rules for the
  // flux source.
  if (const PSNode t = mpm.child("flux_source_receivers")) {
    const std::string v = t.value<std::string>();
    if (v != "restricted" && v != "weights")
      t.fail("<flux_source_receivers> must be restricted or weights, found \"" + v + "\"");
    f.restrictedFluxReceivers = v == "restricted";
  }
  f.fluxSourceInCStar = mpm.get<bool>("flux_source_in_cstar", true);
  f.refineParticles = mpm.get<bool>("refine_particles", false);
  readRefinementCriteria(root, f);
  rejectIfTrue(mpm, "DoPressureStabilization", "pressure stabilization");
  f.autoCycle = mpm.get<bool>("do_auto_cycle_bc", false);
  f.autoCycleUseMinMax = mpm.get<bool>("auto_cycle_use_minmax", false);
  f.autoCycleMax = mpm.get<double>("auto_cycle_max", 0.9);
  f.autoCycleMin = mpm.get<double>("auto_cycle_min", 0.1);
  if (f.autoCycle && !(f.autoCycleMin < f.autoCycleMax))
    mpm.requireChild("auto_cycle_min").fail("<auto_cycle_min> must be below <auto_cycle_max>");
  rejectIfTrue(mpm, "with_gauss_solver", "the Gauss (electric potential) solver");
  rejectIfTrue(mpm, "artificial_viscosity", "artificial viscosity");
  rejectIfTrue(mpm, "axisymmetric", "axisymmetric MPM");
  rejectIfTrue(mpm, "UseGradientEnhancedVelocityProjection",
               "gradient-enhanced velocity projection");
  mpm.acceptInert("withColor");

  f.minimumSubcyclesForF = mpm.get<int>("minimum_subcycles_for_F", 1);
  if (f.minimumSubcyclesForF < 1)
    mpm.requireChild("minimum_subcycles_for_F")
        .unsupported("matrix-exponential F update (value < 1)");
  f.minimumMassForAcc = mpm.get<double>("minimum_mass_for_acc", 0.0);
  f.minimumParticleMass = mpm.get<double>("minimum_particle_mass", 3e-15);
  f.artificialDampingCoeff = mpm.get<double>("artificial_damping_coeff", 0.0);
  if (f.artificialDampingCoeff < 0)
    mpm.requireChild("artificial_damping_coeff").fail("<artificial_damping_coeff> must be >= 0");
  return f;
}

}  // namespace anode

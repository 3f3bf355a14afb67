#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/ReactiveFlow/ConcentrationBCs.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

// The <scalar_flux> blocks with the checks that do not depend on the materials.
std::vector<ScalarFluxBC> readFluxBCs(const PSNode& root, const MPMFlags& flags,
                                      const PhysicalBCs& physical) {
  if (!physical.node) return {};
  std::vector<ScalarFluxBC> bcs = ScalarFluxBC::fromInput(physical.scalarFlux);
  if (!bcs.empty() && !flags.doScalarDiffusion)
    physical.node.fail("<scalar_flux> needs <MPM><do_scalar_diffusion>true");
  if (flags.autoCycle && bcs.empty())
    root.requireChild("MPM")
        .requireChild("do_auto_cycle_bc")
        .fail("<do_auto_cycle_bc>true needs <scalar_flux> boundary conditions");
  for (const ScalarFluxBC& bc : bcs)
    if (flags.autoCycle && bc.mode == ScalarFluxBC::Mode::Potentiostatic)
      throw InputError(root.file(), bc.line,
                       "<do_auto_cycle_bc>true reverses fluxes, and this <scalar_flux> holds a "
                       "concentration (potentiostatic): not both");
  if (!bcs.empty() && !flags.useLoadCurves)
    physical.node.fail(
        "<scalar_flux> needs <MPM><use_load_curves>true (without it Uintah applies no flux)");
  return bcs;
}

std::vector<PSNode> materialNodes(const PSNode& root) {
  return root.requireChild("MaterialProperties").requireChild("MPM").children("material");
}

// Declares the diffusion arrays on a material's particles and sets the initial state the input
// gives: each <geom_object>'s <concentration> and the model's diffusivity D0.
void setInitialState(const ScalarDiffusionModel& model, const MaterialSeeds& seeds,
                     ParticleSet& p) {
  declareDiffusionArrays(p);
  const DiffusionParticles d(p);
  for (const MaterialSeeds::Object& object : seeds.objects) {
    const double c0 = object.node.require<double>("concentration");
    if (c0 < model.minConcentration || c0 > model.maxConcentration)
      object.node.requireChild("concentration")
          .fail("<concentration> must lie in [min_concentration, max_concentration] = [" +
                std::to_string(model.minConcentration) + ", " +
                std::to_string(model.maxConcentration) + "]");
    std::fill_n(d.concentration.begin() + object.first, object.count, c0);
  }
  std::fill(d.diffusivity.begin(), d.diffusivity.end(), model.D0);
}

}  // namespace

ReactiveFlow::ReactiveFlow(const PSNode& root, const MPMFlags& flags,
                           const std::vector<MPMMaterial>& materials, double maxTime,
                           const PhysicalBCs& physical, const std::vector<BCType>& concentrationBCs)
    : flags_(flags),
      interface_(DiffusionInterface::fromInput(
          root.requireChild("MaterialProperties").requireChild("MPM"), true, materials.size())),
      flux_(readFluxBCs(root, flags, physical)) {
  const std::vector<PSNode> nodes = materialNodes(root);
  for (size_t m = 0; m < materials.size(); ++m) {
    DiffusionMaterial& mat = materials_.emplace_back();
    mat.reducesConcentration = nodes[m].get<bool>("do_conc_reduction", false);
    const ConstitutiveModel& mechanics = *materials[m].model;
    const DiffusionModelContext context{maxTime, mechanics.swellingCoefficient(),
                                        mechanics.bulkModulus(), mechanics.shearModulus(),
                                        flags.implicit.has_value()};
    mat.model = createDiffusionModel(nodes[m].requireChild("diffusion_model"), context);
  }
  for (const BCType& bc : concentrationBCs)
    concentrationBCs_.push_back(ConcentrationBC::fromInput(bc));
}

std::unique_ptr<ReactiveFlow> ReactiveFlow::fromInput(const PSNode& root, const MPMFlags& flags,
                                                      const std::vector<MPMMaterial>& materials,
                                                      double maxTime, const PhysicalBCs& physical,
                                                      const std::vector<BCType>& concentrationBCs) {
  if (flags.doScalarDiffusion)
    return std::unique_ptr<ReactiveFlow>(
        new ReactiveFlow(root, flags, materials, maxTime, physical, concentrationBCs));
  DiffusionInterface::fromInput(root.requireChild("MaterialProperties").requireChild("MPM"), false,
                                0);
  readFluxBCs(root, flags, physical);
  for (const PSNode& material : materialNodes(root)) {
    material.get<bool>("do_conc_reduction", false);
    material.acceptInert("diffusion_model");  // Uintah reads it only with do_scalar_diffusion
    for (const PSNode& object : material.children("geom_object"))
      object.acceptInert("concentration");  // it matters only with diffusion
  }
  if (!concentrationBCs.empty()) ConcentrationBC::rejectWithoutDiffusion(concentrationBCs.front());
  return nullptr;
}

CellBox ReactiveFlow::setupRegion(const CellBox& box, const Grid& whole,
                                  const std::vector<MaterialSeeds>& seeds) const {
  const bool sharesSurfaces =
      std::any_of(flux_.bcs().begin(), flux_.bcs().end(), [](const ScalarFluxBC& bc) {
        return bc.face == ScalarFluxBC::Face::Surface ||
               (bc.face != ScalarFluxBC::Face::Box && !bc.particleFaceArea);
      });
  if (Communicator::size() == 1 || !sharesSurfaces) return box;
  // A sample of a BC's surface goes to the nearest flagged particle within 1.5 particle spacings
  // (FluxSurfaceArea.h): the samples a particle of the box can get lie within 1.5 spacings of
  // it, and the particles they can go to within 3.
  Vec3 spacing = Vec3::Zero();
  for (const MaterialSeeds& s : seeds)
    for (const MaterialSeeds::Object& object : s.objects)
      spacing = spacing.cwiseMax(object.spacing);
  const int reach = static_cast<int>(std::ceil(3 * spacing.norm() / whole.dx.minCoeff())) + 1;
  return {(box.lower.array() - reach).max(0), (box.upper.array() + reach).min(whole.cells.array())};
}

void ReactiveFlow::checkSurfaceBCs(const PSNode& root, const std::vector<MPMMaterial>& materials,
                                   const std::vector<MaterialSeeds>& seeds) const {
  const auto indexOf = [&](const std::string& name) {
    for (size_t m = 0; m < materials.size(); ++m)
      if (materials[m].name == name) return static_cast<long>(m);
    return -1L;
  };
  for (const ScalarFluxBC& bc : flux_.bcs()) {
    if (bc.face != ScalarFluxBC::Face::Surface) continue;
    const auto fail = [&](const std::string& message) {
      throw InputError(root.file(), bc.geomLine, message);
    };
    const long m = indexOf(bc.surfaceMaterial);
    if (m < 0) fail("<surface material=\"" + bc.surfaceMaterial + "\">: no material has that name");
    for (const std::string& name : bc.excluded)
      if (indexOf(name) < 0) fail("<surface exclude=\"" + name + "\">: no material has that name");
    if (seeds[m].smooth)
      fail("<surface> BCs share out the surface of grid-filled bodies; " + bc.surfaceMaterial +
           " is laid out by a <smoothcyl>: give it <geom_object> BCs");
    if (flags_.refineParticles)
      fail(
          "<surface> BCs have no normal to share a split particle's faces by: not with "
          "particle splitting (refine_particles)");
  }
}

void ReactiveFlow::initialize(const PSNode& root, const Grid& grid,
                              std::vector<MPMMaterial>& materials,
                              const std::vector<MaterialSeeds>& seeds, const CellBox& box,
                              const CellBox& region, double initTime) {
  for (size_t m = 0; m < materials.size(); ++m) {
    setInitialState(model(m), seeds[m], materials[m].particles);
    if (model(m).stressPotentialPerStress() > 0)
      materials[m].particles.enable(Physics::StressDrivenDiffusion);
  }
  checkSurfaceBCs(root, materials, seeds);
  inputFile_ = root.file();
  flagged_ = flux_.assignToParticles(materials, materials_, seeds, grid, box, region);
  if (flags_.autoCycle && std::none_of(materials_.begin(), materials_.end(),
                                       [](const auto& mat) { return mat.reducesConcentration; }))
    root.requireChild("MPM")
        .requireChild("do_auto_cycle_bc")
        .fail(
            "<do_auto_cycle_bc>true watches the concentration of the materials with "
            "<do_conc_reduction>true, and none has it (Uintah then never reverses the flux)");
  for (size_t m = 0; m < materials.size(); ++m) {
    // From the input (the flux BCs gave the material their arrays), not from this rank's
    // particles: every rank lays out the same fields, with or without particles of m.
    receivesFlux_.push_back(materials[m].particles.has(Physics::FluxBC));
    cmax_.push_back(model(m).maxConcentration);
    constantRate_.push_back(model(m).constantRate());
  }
  for (size_t m = 0; m < materials.size(); ++m)
    changes_.push_back(concentrationCanChange(m, model(m)));
  computeDiffusivity(materials, initTime);
}

std::vector<std::string> ReactiveFlow::completeSetup(Collective every,
                                                     std::vector<MPMMaterial>& materials,
                                                     double initTime, bool everyMaterial) {
  if (everyMaterial) {
    everyMaterial_ = true;
    for (size_t m = 0; m < fields_.size(); ++m)
      if (!changes_[m]) fields_[m].resize(grid_.numNodes(), receivesFlux_[m]);
  }
  // What the BCs flagged, the areas of their shared surfaces (each rank's part) and each
  // material's mass, over every rank.
  const bool overRanks = Communicator::size() > 1;
  std::vector<double> sums;
  for (const ExternalScalarFlux::Flagged& f : flagged_)
    sums.insert(sums.end(), {static_cast<double>(f.particles), f.area, f.surfaceArea, f.bodyArea});
  for (const MPMMaterial& mat : materials) {
    double mass = 0;
    for (double mp : mat.particles.mass) mass += mp;
    sums.push_back(mass);
  }
  if (overRanks) collective::sum(every, sums.data(), static_cast<int>(sums.size()));
  std::vector<ExternalScalarFlux::Flagged> flagged;
  for (size_t k = 0; k < flagged_.size(); ++k) {
    ExternalScalarFlux::Flagged f = flagged_[k];
    f.particles = static_cast<size_t>(sums[4 * k]);
    f.area = sums[4 * k + 1];
    f.surfaceArea = sums[4 * k + 2];
    f.bodyArea = sums[4 * k + 3];
    if (f.particles > 0) flagged.push_back(f);
  }
  flagged_.clear();
  const double* materialMass = sums.data() + sums.size() - materials.size();
  std::vector<double> capacities(flux_.bcs().size(), 0.0);
  // The same on every rank: errors without a collective, agreed for one message.
  collective::readTogether(every, [&] {
    for (size_t b = 0; b < flux_.bcs().size(); ++b)
      if (std::none_of(flagged.begin(), flagged.end(), [b](const auto& f) { return f.bc == b; }))
        throw InputError(
            inputFile_, flux_.bcs()[b].geomLine,
            "this <scalar_flux> flags no particle: its geometry selects no surface particle of a "
            "material that diffuses (selection rules in docs/diffusion.md), so its flux would go "
            "nowhere");
    for (const ExternalScalarFlux::Flagged& f : flagged) {
      const ScalarFluxBC& bc = flux_.bcs()[f.bc];
      const ScalarDiffusionModel& held = model(f.material);
      if (bc.mode == ScalarFluxBC::Mode::Potentiostatic)
        for (double c : bc.load.loads())
          if (c < held.minConcentration || c > held.maxConcentration)
            throw InputError(inputFile_, bc.line,
                             "this potentiostatic <scalar_flux> holds c = " + std::to_string(c) +
                                 ", outside [min_concentration, max_concentration] of " +
                                 describeMaterial(materials[f.material], f.material));
      capacities[f.bc] += materialMass[f.material] * model(f.material).maxConcentration;
    }
    // A surface reaction's particles need an open-circuit potential: c inside (0, c_max).
    for (size_t m = 0; m < materials.size(); ++m) {
      const ConstDiffusionParticles d(materials[m].particles);
      for (size_t i = 0; i < d.loadCurveID.size(); ++i)
        for (int s = 0; s < 3 && d.loadCurveID[i][s] > 0; ++s) {
          const ScalarFluxBC& bc = flux_.bcs()[d.loadCurveID[i][s] - 1];
          const double c = d.concentration[i] / model(m).maxConcentration;
          if (bc.reaction && !(c > 0 && c < 1))
            throw InputError(
                inputFile_, bc.line,
                "this <scalar_flux>'s <surface_reaction> needs its particles' c inside (0, "
                "max_concentration), where the open-circuit potential U(c) exists; " +
                    describeMaterial(materials[m], m) + " starts at c / c_max = " +
                    std::to_string(c) + " (its <geom_object><concentration>)");
        }
    }
  });
  std::vector<std::string> lines;
  for (const ExternalScalarFlux::Flagged& f : flagged) {
    std::ostringstream s;
    s << "<scalar_flux> " << f.bc + 1 << " (line " << flux_.bcs()[f.bc].line << ") flags "
      << f.particles << " particles of " << describeMaterial(materials[f.material], f.material)
      << ", flux area " << f.area;
    if (flux_.bcs()[f.bc].face == ScalarFluxBC::Face::Surface)
      s << " (the free surface of its body: " << f.bodyArea << " of its pieces' " << f.surfaceArea
        << ")";
    else if (f.surfaceArea > 0)
      s << " (its surface " << f.surfaceArea << ", of which on the body " << f.bodyArea << ")";
    else
      s << " (their particle faces)";
    const ScalarFluxBC& bc = flux_.bcs()[f.bc];
    if (bc.mode == ScalarFluxBC::Mode::Galvanostatic) {
      s << "; galvanostatic: its load is ";
      if (bc.hour > 0)
        s << "a C-rate (1C: " << capacities[f.bc] / bc.hour << " of lithium per time unit)";
      else
        s << "the lithium rate into them in all";
      s << "; the BC's materials hold " << capacities[f.bc]
        << " of lithium (sum m c) at max_concentration";
    } else if (bc.mode == ScalarFluxBC::Mode::Potentiostatic) {
      s << "; potentiostatic: its load is the surface concentration, held through J = k (c_s - "
           "c) with k = "
        << bc.surfaceRate;
    }
    lines.push_back(s.str());
  }
  for (size_t m = 0; m < materials.size(); ++m)
    if (!changes_[m])
      lines.push_back(describeMaterial(materials[m], m) +
                      " takes up no lithium (no diffusivity, flux or concentration condition): its "
                      "concentration stays as given" +
                      (everyMaterial_ ? "; its nodal concentration is computed for the output"
                                      : " and is not computed"));
  for (size_t m = 0; m < materials.size(); ++m)
    if (stressDriven(m)) {
      std::ostringstream s;
      s.precision(4);
      s << describeMaterial(materials[m], m)
        << ": a stress-driven flux (chemical_potential), phi = "
        << model(m).stressPotentialPerStress() << " tau_h";
      const double s0 = model(m).stressPotentialStabilization();
      if (s0 > 0)
        s << ", its local response s = " << s0 << " per unit c taken implicitly in each pass; "
          << "steps keep c's change below " << model(m).maxConcentration / s0 << " (1/s)";
      lines.push_back(s.str());
    }
  flux_.setCapacities(std::move(capacities));
  flux_.computeFluxRates(every, materials, materials_, initTime, overRanks);
  return lines;
}

double ReactiveFlow::stressDrivenConcentrationChange() const {
  // From the models alone: MPM asks at setup, before initialize() knows which materials change.
  double bound = std::numeric_limits<double>::infinity();
  for (size_t m = 0; m < materials_.size(); ++m) {
    const double s = model(m).stressPotentialStabilization();
    if (s > 0) bound = std::min(bound, model(m).maxConcentration / s);
  }
  return bound;
}

std::vector<ConcentrationGridFields>& ReactiveFlow::layOutGrid(const Grid& grid,
                                                               const GhostNodes* ghosts) {
  grid_ = grid;
  ghosts_ = ghosts;
  dirichletMask_ = dirichletNodeMasks(grid, concentrationBCs_, receivesFlux_.size());
  const int nodes = grid.numNodes();
  fields_.assign(receivesFlux_.size(), {});
  for (size_t m = 0; m < fields_.size(); ++m)
    if (computesConcentration(m)) fields_[m].resize(nodes, receivesFlux_[m]);
  return fields_;
}

bool ReactiveFlow::concentrationCanChange(size_t m, const ScalarDiffusionModel& model) const {
  if (model.diffuses() || model.constantRate() != 0 || receivesFlux_[m] || interface_.common)
    return true;
  return std::any_of(
      concentrationBCs_.begin(), concentrationBCs_.end(),
      [m](const ConcentrationBC& b) { return b.face.appliesTo(static_cast<int>(m)); });
}

void ReactiveFlow::computeNodalConcentration(const std::vector<GridFields>& mechanics,
                                             const std::vector<NodeRange>& nodes) {
  for (size_t m = 0; m < mechanics.size(); ++m) {
    if (!computesConcentration(m)) continue;
    ConcentrationGridFields& g = fields_[m];
    const GridFields& f = mechanics[m];
    forEachNode(nodes, [&](long k) {
      const double c = f.mass[k] > 0 ? g.massConcentration[k] / f.mass[k] : 0.0;  // Eq. 5
      g.concentrationNoBC[k] = c;
      g.concentration[k] = c;
    });
    applyConcentrationBCs(grid_, concentrationBCs_, static_cast<int>(m), g.concentration);
  }
  interface_.apply(mechanics, fields_, nodes);
}

void ReactiveFlow::integrateConcentration(const std::vector<GridFields>& mechanics, double dt,
                                          const std::vector<NodeRange>& nodes) {
  // Eq. 18: c* = c + (R/m + G/m) dt, then the SD-Type BCs on c*. Unlike Uintah (UINTAH_UPS.md
  // §6 step 7) the flux source is part of c*, so the next step's gradient sees the lithium that
  // entered (<flux_source_in_cstar>false leaves it out, as Uintah). The nodal rate that drives the
  // particles, (c° - c_noBC)/dt with c° = c + (R/m) dt under the same BCs, leaves the source out:
  // each node hands its G to the particles it reaches in proportion to m S R, R the restriction of
  // Eq. 17 at each particle's own c (R(1 - c) for an outflow), so a full (or emptied) particle
  // receives nothing from its neighbours' sources and the node delivers all of G (G / W, W = sum m
  // S R). <flux_source_receivers>weights drops R from both (W = sum m S): every particle gets S G /
  // m, Uintah's rule.
  for (size_t m = 0; m < fields_.size(); ++m) {
    if (!computesConcentration(m)) continue;
    ConcentrationGridFields& g = fields_[m];
    const std::vector<double>& mass = mechanics[m].mass;
    const double constantRate = constantRate_[m];
    const bool source = receivesFlux_[m];
    std::vector<double>& noSource = source ? g.concentrationNoSource : g.concentrationStar;
    forEachNode(nodes, [&](long k) {
      const double invMass = mass[k] > 0 ? 1.0 / mass[k] : 0.0;
      const double rate = invMass > 0 ? g.diffusionRate[k] * invMass + constantRate : 0.0;
      noSource[k] = g.concentration[k] + rate * dt;
      if (!source) return;
      const double G = g.fluxSource[k];
      g.concentrationStar[k] = noSource[k] + (flags_.fluxSourceInCStar ? G * invMass * dt : 0.0);
      const double receivers = G >= 0 ? g.receiverWeightIn[k] : g.receiverWeightOut[k];
      g.sourcePerWeight[k] = receivers > 0 ? G / receivers : 0.0;
    });
    applyConcentrationBCs(grid_, concentrationBCs_, static_cast<int>(m), g.concentrationStar);
    if (source)
      applyConcentrationBCs(grid_, concentrationBCs_, static_cast<int>(m), g.concentrationNoSource);
    forEachNode(nodes, [&](long k) {
      g.concentrationRate[k] = mass[k] > 0 ? (noSource[k] - g.concentrationNoBC[k]) / dt : 0.0;
    });
  }
}

void ReactiveFlow::updateDiffusionState(Collective every, std::vector<MPMMaterial>& materials,
                                        double t) {
  collective::stopTogether(every, [&] { checkConcentrationRange(materials, t); });
  if (flags_.autoCycle) flux_.updateAutoCycle(every, materials, materials_, flags_);
  computeDiffusivity(materials, t);
  flux_.computeFluxRates(every, materials, materials_, t, true);
}

void ReactiveFlow::computeDiffusivity(std::vector<MPMMaterial>& materials, double t) {
  // A material whose concentration cannot change has D = 0 everywhere: p.diffusivity keeps its
  // initial 0.
  maxDiffusivity_ = 0;
  for (size_t m = 0; m < materials.size(); ++m)
    if (changes_[m])
      maxDiffusivity_ = std::max(
          maxDiffusivity_, materials_[m].model->computeDiffusivity(materials[m].particles, t));
}

void ReactiveFlow::checkConcentrationRange(const std::vector<MPMMaterial>& materials,
                                           double t) const {
  for (size_t m = 0; m < materials.size(); ++m) {
    const std::vector<double>& concentration =
        diffusionParticles(materials[m].particles).concentration;
    const ScalarDiffusionModel& d = model(m);
    const double tol = kConcentrationTolerance * (d.maxConcentration - d.minConcentration);
    for (size_t i = 0; i < concentration.size(); ++i) {
      const double c = concentration[i];
      if (c >= d.minConcentration - tol && c <= d.maxConcentration + tol) continue;
      std::ostringstream s;
      s.precision(10);  // enough digits to show by how much it left the range
      s << describeParticle(materials[m], m, i) << " has concentration " << c << " at t = " << t
        << ", outside [" << d.minConcentration << ", " << d.maxConcentration << "] by more than "
        << tol << " (no clamp is applied)";
      throw SimulationError(s.str());
    }
  }
}

double ReactiveFlow::diffusionTimestep(const Grid& grid) const {
  const double dx = grid.dx.minCoeff();
  return maxDiffusivity_ > 0 ? dx * dx / (2 * maxDiffusivity_)  // Eq. 44
                             : std::numeric_limits<double>::infinity();
}

void ReactiveFlow::summarize(const std::vector<MPMMaterial>& materials, StepSummary& s) const {
  s.diffusion = true;
  for (size_t b = 0; b < flux_.bcs().size(); ++b)
    if (flux_.bcs()[b].reaction)
      s.electrodePotentials.emplace_back(static_cast<int>(b) + 1,
                                         b < flux_.potentials().size()
                                             ? flux_.potentials()[b]
                                             : std::numeric_limits<double>::quiet_NaN());
  // The range is of the materials whose concentration can change (a substrate's fixed c would
  // pin it), of every material when none can; history.csv gives each of them columns of its own
  // when there are two or more.
  const auto changing = std::count(changes_.begin(), changes_.end(), true);
  for (size_t m = 0; m < materials.size(); ++m) {
    const ParticleSet& p = materials[m].particles;
    const std::vector<double>& c = diffusionParticles(p).concentration;
    const bool inRange = changes_[m] || changing == 0;
    StepSummary::MaterialLithium* material = nullptr;
    if (changing > 1 && changes_[m])
      material = &s.perMaterial.emplace_back(
          StepSummary::MaterialLithium{m, 0.0, std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity()});
    for (size_t i = 0; i < p.count(); ++i) {
      s.totalLithium += p.mass[i] * c[i];
      if (!inRange) continue;
      s.chargeableLithium += p.mass[i] * c[i];
      s.lithiumCapacity += p.mass[i] * model(m).maxConcentration;
      s.minConcentration = std::min(s.minConcentration, c[i]);
      s.maxConcentration = std::max(s.maxConcentration, c[i]);
      if (!material) continue;
      material->lithium += p.mass[i] * c[i];
      material->minConcentration = std::min(material->minConcentration, c[i]);
      material->maxConcentration = std::max(material->maxConcentration, c[i]);
    }
  }
}

ReactiveFlow::StepState ReactiveFlow::stepState() const {
  StepState state{flux_, {}, maxDiffusivity_};
  for (const DiffusionMaterial& mat : materials_) state.models.push_back(mat.model->stepState());
  return state;
}

void ReactiveFlow::restoreStepState(const StepState& state) {
  flux_ = state.flux;
  maxDiffusivity_ = state.maxDiffusivity;
  for (size_t m = 0; m < materials_.size(); ++m)
    materials_[m].model->restoreStepState(state.models[m]);
}

void ReactiveFlow::saveState(BinaryWriter& out) const {
  out.value(maxDiffusivity_);
  flux_.saveState(out);
  for (const DiffusionMaterial& mat : materials_) mat.model->saveState(out);
}

void ReactiveFlow::loadState(BinaryReader& in, bool merge) {
  const double maxDiffusivity = in.value<double>();
  maxDiffusivity_ = merge ? std::max(maxDiffusivity_, maxDiffusivity) : maxDiffusivity;
  flux_.loadState(in, merge);
  for (DiffusionMaterial& mat : materials_) mat.model->loadState(in);
}

}  // namespace anode

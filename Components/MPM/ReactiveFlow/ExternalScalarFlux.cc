#include "Components/MPM/ReactiveFlow/ExternalScalarFlux.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "Components/MPM/ReactiveFlow/ChemicalPotential.h"
#include "Components/MPM/ReactiveFlow/FluxRestriction.h"
#include "Components/MPM/ReactiveFlow/FluxSurfaceArea.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

// Shares the parent's flux faces among its 4 children: a face normal to the split goes whole to
// the child nearest it, a face along the split is shared by the 4.
void shareFluxFaces(ParticleSet& p, const std::vector<ScalarFluxBC>& bcs,
                    const SplitParticle& split) {
  const size_t* child = split.child;
  const size_t parent = child[0];
  const DiffusionParticles d(p);
  const Vec3 parentX = p.x[parent] - split.offset[0];
  const Vec3i ids = d.loadCurveID[parent];
  const Vec3 areas = d.area[parent];
  for (int c = 0; c < 4; ++c) {
    d.loadCurveID[child[c]].setZero();
    d.area[child[c]].setZero();
  }
  int slots[4] = {0, 0, 0, 0};
  for (int s = 0; s < 3 && ids[s] > 0; ++s) {
    const ScalarFluxBC& bc = bcs[ids[s] - 1];
    const bool acrossFace = std::abs(split.direction.dot(bc.normalAt(parentX))) > M_SQRT1_2;
    int nearest = 0;
    for (int c = 1; c < 4; ++c)
      if (bc.distanceToFace(p.x[child[c]]) < bc.distanceToFace(p.x[child[nearest]])) nearest = c;
    for (int c = 0; c < 4; ++c) {
      if (acrossFace && c != nearest) continue;
      d.loadCurveID[child[c]][slots[c]] = ids[s];
      d.area[child[c]][slots[c]] = acrossFace ? areas[s] : 0.25 * areas[s];
      ++slots[c];
    }
  }
}

// A_k of Eq. 16 for particle i's slot s: the area it was given, or with <area_update>deformed
// that area carried by its deformation (Nanson).
template <class Particles>
double fluxArea(const ScalarFluxBC& bc, const ParticleSet& p, const Particles& d, long i, int s) {
  return bc.deformedArea ? d.area[i][s] * bc.areaStretch(p.F[i], p.x[i] - p.displacement[i])
                         : d.area[i][s];
}

// A potentiostatic BC's k_eff at a particle of volume V whose face of area A lies
// delta = V / (2 A) from its centre (half its thickness normal to the face): the surface reaction
// k and diffusion D across delta in series, J = (c_s - c_p) / (1/k + delta/D), since c_p is the
// particle's mean, not the surface's concentration.
double surfaceConductance(const ScalarFluxBC& bc, double area, double volume, double D) {
  const double delta = 0.5 * volume / area;
  return bc.surfaceRate * D / (D + bc.surfaceRate * delta);
}

// The note of galvanostatic BC b's current resuming at t (`ends` false), the load charging or
// not, `how` saying at what state, or ending at its cutoff, `how` saying which and why; an
// ended current's note says until when.
std::string currentNote(size_t b, const ScalarFluxBC& bc, double t, bool ends, bool charging,
                        const std::string& how) {
  std::ostringstream s;
  s << "<scalar_flux> " << b + 1 << " (line " << bc.line << ", galvanostatic): its current ";
  if (!ends) {
    s << "resumes at t = " << t << " (" << (charging ? "charging" : "discharging") << ", " << how
      << ")";
    return s.str();
  }
  s << "ends at t = " << t << ": " << how;
  const double next = bc.load.nextTimeAfter(t);
  if (std::isfinite(next))
    s << ", until its load curve's next segment at t = " << next;
  else
    s << ", for the rest of the run";
  return s.str();
}

// A note's `how` for a restriction cutoff (R the flagged surface's mean restriction) and for a
// surface reaction's potential cutoff (phi the electrode's potential).
std::string restrictionState(const ScalarFluxBC& bc, bool ends, bool charging, double R) {
  std::ostringstream s;
  s << "the flagged surface's mean restriction R " << (ends ? "is " : "") << R;
  if (ends)
    s << ", at or below <cutoff> " << bc.cutoff << " (the surface is nearly "
      << (charging ? "full" : "empty") << ")";
  return s.str();
}
std::string potentialState(const ScalarFluxBC& bc, bool ends, bool charging, double phi) {
  std::ostringstream s;
  if (!ends) {
    s << "at the electrode's potential " << phi << " V";
    return s.str();
  }
  s << "the electrode's potential " << phi << " V is at or "
    << (charging ? "below <lower_cutoff_potential> " : "above <upper_cutoff_potential> ")
    << (charging ? bc.reaction->lowerCutoff : bc.reaction->upperCutoff) << " V";
  return s.str();
}

// The open-circuit potential of particle i of a material whose stress part of mu / RT is
// `perStress` k (SurfaceReaction.h): a SimulationError where c / cmax is outside (0, 1), where
// it has none.
double openCircuitOf(const SurfaceReaction& r, size_t b, const ScalarFluxBC& bc,
                     const ParticleSet& p, const ConstDiffusionParticles& d, long i, double cmax,
                     double perStress, double t) {
  const double c = d.concentration[i] / cmax;
  if (!(c > 0 && c < 1)) {
    std::ostringstream s;
    s << "particle " << p.id[i] << " at [" << p.x[i].transpose() << "] has c / c_max = " << c
      << " at t = " << t << ": the surface reaction of <scalar_flux> " << b + 1 << " (line "
      << bc.line << ") has no open-circuit potential outside (0, 1)";
    throw SimulationError(s.str());
  }
  return r.openCircuit(c, stressPotential(perStress, p.stress[i], p.F[i]));
}

}  // namespace

std::vector<ExternalScalarFlux::Flagged> ExternalScalarFlux::assignToParticles(
    std::vector<MPMMaterial>& materials, const std::vector<DiffusionMaterial>& diffusion,
    const std::vector<MaterialSeeds>& seeds, const Grid& grid, const CellBox& counted,
    const CellBox& kept) const {
  // Surface particles get, per BC that flags them, the area of the face that BC names
  // (UINTAH_UPS.md §3.1; unlike Uintah, not the area left by the last BC tested).
  std::vector<Flagged> report;
  const SampleRegion region{&grid, kept, counted};
  for (size_t m = 0; m < materials.size(); ++m) {
    MPMMaterial& mat = materials[m];
    const MaterialSeeds& surface = seeds[m];
    ParticleSet& p = mat.particles;
    if (bcs_.empty() || !diffusion[m].model->diffuses())
      continue;  // a material without diffusivity gets no lithium
    p.enable(Physics::FluxBC);
    const DiffusionParticles d(p);
    // Per BC, how many particles it flags, those that hold it (at most 3 BCs a particle) and
    // the slot it has in each.
    std::vector<size_t> flagged(bcs_.size(), 0);
    std::vector<std::vector<size_t>> holding(bcs_.size());
    std::vector<std::vector<int>> slots(bcs_.size());
    // A shared surface is sampled at a quarter of the body's largest particle spacing.
    Vec3 spacing = Vec3::Zero();
    for (const MaterialSeeds::Object& object : surface.objects)
      spacing = spacing.cwiseMax(object.spacing);
    for (const MaterialSeeds::Object& object : surface.objects)
      for (size_t i = object.first; i < object.first + object.count; ++i) {
        // Smooth pieces are not searched for their surface: every particle is tested by the
        // flux BCs (UINTAH_UPS.md §3.2), with the spacing dx/res.
        if (!object.smooth && !onSurface(*object.piece, p.x[i], object.spacing, grid.ndim()))
          continue;
        int slot = 0;
        for (size_t b = 0; b < bcs_.size(); ++b) {
          const double a = bcs_[b].flaggedArea(p.x[i], object.spacing, object.faceAreaOf(i));
          if (a <= 0) continue;
          if (region.counts(p.x[i])) ++flagged[b];
          if (slot == 3) continue;  // a particle holds at most 3 load curves
          d.loadCurveID[i][slot] = static_cast<int>(b) + 1;
          d.area[i][slot] = a;
          holding[b].push_back(i);
          slots[b].push_back(slot);
          ++slot;
        }
      }
    std::vector<SurfaceShare> bodyShares(bcs_.size());
    for (size_t b = 0; b < bcs_.size(); ++b)
      if (bcs_[b].face == ScalarFluxBC::Face::Surface && bcs_[b].surfaceMaterial == mat.name)
        flagFreeSurface(b, m, materials, seeds, grid, region, flagged[b], holding[b], slots[b],
                        bodyShares[b]);
    // The surfaces are shared out on every rank (each adds the areas of its box's samples),
    // whether or not its particles are flagged.
    for (size_t b = 0; b < bcs_.size(); ++b) {
      Flagged f{b, m, flagged[b]};
      if (bcs_[b].face == ScalarFluxBC::Face::Surface) {
        f.surfaceArea = bodyShares[b].surfaceArea;
        f.bodyArea = bodyShares[b].bodyArea;
      }
      if (bcs_[b].face != ScalarFluxBC::Face::Box && bcs_[b].face != ScalarFluxBC::Face::Surface &&
          !surface.smooth && !bcs_[b].particleFaceArea) {
        // A curved face on a body filled on the grid: its own surface shared out.
        std::vector<GeometryPieceP> body;
        for (const MaterialSeeds::FilledPiece& piece : surface.filledPieces)
          body.push_back(piece.piece);
        const SurfaceShare share =
            shareSurfaceArea(bcs_[b], body, grid, spacing, holding[b], slots[b], p, region);
        f.surfaceArea = share.surfaceArea;
        f.bodyArea = share.bodyArea;
      }
      for (size_t k = 0; k < holding[b].size(); ++k)
        if (region.counts(p.x[holding[b][k]])) f.area += d.area[holding[b][k]][slots[b][k]];
      report.push_back(f);
    }
  }
  return report;
}

std::vector<double> ExternalScalarFlux::fluxes(Collective every,
                                               const std::vector<MPMMaterial>& materials,
                                               const std::vector<DiffusionMaterial>& diffusion,
                                               double t, bool overRanks) {
  const size_t n = bcs_.size();
  std::vector<double> J(n);
  bool galvanostatic = false;
  for (size_t b = 0; b < n; ++b) {
    J[b] = sign_ * bcs_[b].load.at(t);
    galvanostatic = galvanostatic || bcs_[b].mode == ScalarFluxBC::Mode::Galvanostatic;
  }
  if (!galvanostatic) return J;
  endedIn_.resize(n, -1);
  // Per BC: sum m R(c) A / V cmax (the lithium rate per unit J) and sum m A / V cmax (the same
  // unrestricted), in particle order (the same bits run to run).
  std::vector<double> sums(2 * n, 0.0);
  for (size_t m = 0; m < materials.size(); ++m) {
    const ParticleSet& p = materials[m].particles;
    const ConstDiffusionParticles d(p);
    if (d.loadCurveID.empty()) continue;
    const double cmax = diffusion[m].model->maxConcentration;
    for (size_t i = 0; i < p.count(); ++i)
      for (int s = 0; s < 3 && d.loadCurveID[i][s] > 0; ++s) {
        const size_t b = d.loadCurveID[i][s] - 1;
        if (bcs_[b].mode != ScalarFluxBC::Mode::Galvanostatic || bcs_[b].reaction) continue;
        const double area = fluxArea(bcs_[b], p, d, i, s);
        const double unrestricted = p.mass[i] * area / p.volume[i] * cmax;
        sums[b] += unrestricted * fluxRestriction(d.concentration[i] / cmax, J[b] >= 0);
        sums[n + b] += unrestricted;
      }
  }
  if (overRanks) collective::sum(every, sums.data(), static_cast<int>(sums.size()));
  potentials_.resize(n, std::numeric_limits<double>::quiet_NaN());
  for (size_t b = 0; b < n; ++b) {
    const ScalarFluxBC& bc = bcs_[b];
    if (bc.mode != ScalarFluxBC::Mode::Galvanostatic) continue;
    if (bc.reaction) {
      const double lithiumRate = bc.hour > 0 ? J[b] * capacities_[b] / bc.hour : J[b];
      potentials_[b] =
          electrodePotential(every, materials, diffusion, b, lithiumRate, t, overRanks);
      J[b] = 0;  // each particle's flux follows from the potential (computeFluxRates)
      continue;
    }
    // The flagged surface's mean restriction (weighted as the flux shares the rate).
    const double meanRestriction = sums[n + b] > 0 ? sums[b] / sums[n + b] : 0.0;
    // The current resumes once the surface is above the cutoff for the direction it now runs in.
    const double lithiumRate = bc.hour > 0 ? J[b] * capacities_[b] / bc.hour : J[b];
    const bool resumes = mayResume(b, lithiumRate, t) && meanRestriction > bc.cutoff;
    if (resumes) endedIn_[b] = -1;
    const bool ends = endedIn_[b] < 0 && meanRestriction <= bc.cutoff;
    if (ends) endedIn_[b] = segmentOf(b, t);
    if (ends || resumes)
      notes_.push_back(currentNote(b, bc, t, ends, J[b] >= 0,
                                   restrictionState(bc, ends, J[b] >= 0, meanRestriction)));
    J[b] = endedIn_[b] >= 0 ? 0.0 : lithiumRate / sums[b];
  }
  return J;
}

double ExternalScalarFlux::electrodePotential(Collective every,
                                              const std::vector<MPMMaterial>& materials,
                                              const std::vector<DiffusionMaterial>& diffusion,
                                              size_t b, double lithiumRate, double t,
                                              bool overRanks) {
  const ScalarFluxBC& bc = bcs_[b];
  const SurfaceReaction& r = *bc.reaction;
  // The flagged particles' weights m A / V c_max (the lithium rate per unit flux) and their
  // open-circuit potentials, in particle order.
  std::vector<double> weight, openCircuit;
  const auto collect = [&] {
    for (size_t m = 0; m < materials.size(); ++m) {
      const ParticleSet& p = materials[m].particles;
      const ConstDiffusionParticles d(p);
      if (d.loadCurveID.empty()) continue;
      const double cmax = diffusion[m].model->maxConcentration;
      const double perStress = diffusion[m].model->stressPotentialPerStress();
      for (size_t i = 0; i < p.count(); ++i)
        for (int s = 0; s < 3 && d.loadCurveID[i][s] > 0; ++s) {
          if (static_cast<size_t>(d.loadCurveID[i][s] - 1) != b) continue;
          weight.push_back(p.mass[i] * fluxArea(bc, p, d, i, s) / p.volume[i] * cmax);
          openCircuit.push_back(
              openCircuitOf(r, b, bc, p, d, static_cast<long>(i), cmax, perStress, t));
        }
    }
  };
  if (overRanks)
    collective::stopTogether(every, collect);
  else
    collect();
  const auto carries = [&](double rate) {
    return potentialCarrying(every, r, weight, openCircuit, rate, overRanks);
  };
  // The cutoffs: a charge ends where phi falls to the lower, a discharge where it rises to the
  // upper, until a later segment of the load curve in which the current, resumed, keeps phi
  // inside them; it resumes once the load runs the way the segment ends (past a ramp's turn).
  const bool charging = lithiumRate >= 0;
  const auto beyondCutoff = [&](double phi) {
    return charging ? phi <= r.lowerCutoff : phi >= r.upperCutoff;
  };
  if (mayResume(b, lithiumRate, t)) {
    const double phi = carries(lithiumRate);
    if (!beyondCutoff(phi)) {
      endedIn_[b] = -1;
      notes_.push_back(
          currentNote(b, bc, t, false, charging, potentialState(bc, false, charging, phi)));
      return phi;
    }
  }
  if (endedIn_[b] >= 0) return carries(0.0);
  const double phi = carries(lithiumRate);
  if (lithiumRate == 0 || !beyondCutoff(phi)) return phi;
  endedIn_[b] = segmentOf(b, t);
  notes_.push_back(currentNote(b, bc, t, true, charging, potentialState(bc, true, charging, phi)));
  return carries(0.0);
}

long ExternalScalarFlux::segmentOf(size_t b, double t) const {
  return 2 * static_cast<long>(bcs_[b].load.segmentAt(t)) + (sign_ < 0 ? 1 : 0);
}

bool ExternalScalarFlux::mayResume(size_t b, double lithiumRate, double t) const {
  const LoadCurve& load = bcs_[b].load;
  const double next = load.nextTimeAfter(t);
  const double ahead = sign_ * load.at(std::isfinite(next) ? next : t);
  return endedIn_[b] >= 0 && endedIn_[b] != segmentOf(b, t) && lithiumRate != 0 &&
         (lithiumRate > 0) == (ahead > 0);
}

std::vector<std::string> ExternalScalarFlux::takeNotes() {
  std::vector<std::string> notes;
  notes.swap(notes_);
  return notes;
}

void ExternalScalarFlux::flagFreeSurface(size_t b, size_t m, std::vector<MPMMaterial>& materials,
                                         const std::vector<MaterialSeeds>& seeds, const Grid& grid,
                                         const SampleRegion& region, size_t& count,
                                         std::vector<size_t>& holding, std::vector<int>& slots,
                                         SurfaceShare& share) const {
  ParticleSet& p = materials[m].particles;
  const DiffusionParticles d(p);
  // The material's surface particles (as the geometry BCs find them), the largest spacing.
  std::vector<size_t> candidates;
  Vec3 spacing = Vec3::Zero();
  for (const MaterialSeeds::Object& object : seeds[m].objects) {
    spacing = spacing.cwiseMax(object.spacing);
    for (size_t i = object.first; i < object.first + object.count; ++i)
      if (onSurface(*object.piece, p.x[i], object.spacing, grid.ndim())) candidates.push_back(i);
  }
  std::vector<GeometryPieceP> body, excluded;
  for (const MaterialSeeds::FilledPiece& piece : seeds[m].filledPieces) body.push_back(piece.piece);
  for (size_t o = 0; o < materials.size(); ++o)
    if (std::find(bcs_[b].excluded.begin(), bcs_[b].excluded.end(), materials[o].name) !=
        bcs_[b].excluded.end())
      for (const MaterialSeeds::FilledPiece& piece : seeds[o].filledPieces)
        excluded.push_back(piece.piece);
  std::vector<double> area;
  shareBodySurface(body, excluded, grid, spacing, candidates, p, area, share, region);
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (area[k] <= 0) continue;
    const size_t i = candidates[k];
    if (region.counts(p.x[i])) ++count;
    int slot = 0;
    while (slot < 3 && d.loadCurveID[i][slot] > 0) ++slot;
    if (slot == 3) continue;  // a particle holds at most 3 load curves
    d.loadCurveID[i][slot] = static_cast<int>(b) + 1;
    d.area[i][slot] = area[k];
    holding.push_back(i);
    slots.push_back(slot);
  }
}

void ExternalScalarFlux::computeFluxRates(Collective every, std::vector<MPMMaterial>& materials,
                                          const std::vector<DiffusionMaterial>& diffusion, double t,
                                          bool overRanks) {
  maxInflowRate_ = maxOutflowRate_ = 0;
  if (bcs_.empty()) return;
  const std::vector<double> J = fluxes(every, materials, diffusion, t, overRanks);
  for (size_t m = 0; m < materials.size(); ++m) {
    ParticleSet& p = materials[m].particles;
    const DiffusionParticles d(p);
    if (d.loadCurveID.empty()) continue;
    const double cmax = diffusion[m].model->maxConcentration;
    const double perStress = diffusion[m].model->stressPotentialPerStress();
    const long n = static_cast<long>(p.count());
    double inflow = 0, outflow = 0;
#pragma omp parallel for schedule(static) reduction(max : inflow, outflow)
    for (long i = 0; i < n; ++i) {
      const double c = d.concentration[i] / cmax;
      double rate = 0, held = 0, in = 0, out = 0;
      for (int s = 0; s < 3 && d.loadCurveID[i][s] > 0; ++s) {
        const int b = d.loadCurveID[i][s] - 1;
        const double area = fluxArea(bcs_[b], p, d, i, s);
        const bool potentiostatic = bcs_[b].mode == ScalarFluxBC::Mode::Potentiostatic;
        const SurfaceReaction* reaction = bcs_[b].reaction.get();
        // A potentiostatic BC's J = k_eff (c_s - c) / c_max, its load being c_s; a surface
        // reaction's Butler-Volmer flux at the electrode's potential.
        double j = J[b];
        if (potentiostatic)
          j = surfaceConductance(bcs_[b], area, p.volume[i], d.diffusivity[i]) * (J[b] / cmax - c);
        else if (reaction)
          j = reaction->flux(
              potentials_[b],
              reaction->openCircuit(c, stressPotential(perStress, p.stress[i], p.F[i])));
        (potentiostatic || reaction ? held : rate) += j * area;
        (j > 0 ? in : out) += std::abs(j) * area;
      }
      // Eq. 17 restricts inflow as c -> 1; outflow is restricted the same way as c -> 0. A
      // potentiostatic BC's flux needs no restriction: it vanishes at c_s; nor a surface
      // reaction's, whose open-circuit potential diverges at c = 0 and 1.
      d.externalScalarFlux[i] = rate / p.volume[i] * fluxRestriction(c, rate >= 0) * cmax;
      if (held != 0) d.externalScalarFlux[i] += held / p.volume[i] * cmax;
      inflow = std::max(inflow, in / p.volume[i]);
      outflow = std::max(outflow, out / p.volume[i]);
    }
    maxInflowRate_ = std::max(maxInflowRate_, inflow);
    maxOutflowRate_ = std::max(maxOutflowRate_, outflow);
  }
}

double ExternalScalarFlux::stableTimestep(Collective every,
                                          const std::vector<MPMMaterial>& materials,
                                          const std::vector<DiffusionMaterial>& diffusion) const {
  // A particle's source s_p = R(c_p) sum_i S_ip G_i / W_i (docs/diffusion.md step 5), and each
  // G_i / W_i is a weighted mean of unrestricted rates, at most the largest of its sign. The
  // step to the root falls as c nears it, so the fullest particle below the root (for an
  // outflow: the emptiest above e^-4) bounds them all.
  // A potentiostatic BC's particle relaxes to c_s at the rate sum k A / V: a step of at most
  // its inverse takes it at most to c_s (no overshoot, no oscillation).
  // A surface reaction's particle relaxes at sum A / V |dj/dc| (SurfaceReaction::fluxSlope).
  const bool potentiostatic = std::any_of(bcs_.begin(), bcs_.end(), [](const ScalarFluxBC& bc) {
    return bc.mode == ScalarFluxBC::Mode::Potentiostatic || bc.reaction;
  });
  double fullest = 0, emptiest = 1, relaxation = 0;
  for (size_t m = 0; m < materials.size(); ++m) {
    const ParticleSet& p = materials[m].particles;
    const ConstDiffusionParticles d(p);
    if (d.loadCurveID.empty()) continue;
    const double cmax = diffusion[m].model->maxConcentration;
    const double perStress = diffusion[m].model->stressPotentialPerStress();
    const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static) reduction(max                                  \
                                                    : fullest, relaxation) reduction(min \
                                                                                     : emptiest)
    for (long i = 0; i < n; ++i) {
      const double c = d.concentration[i] / cmax;
      if (c < kRestrictionRoot) fullest = std::max(fullest, c);
      if (1 - c < kRestrictionRoot) emptiest = std::min(emptiest, c);
      if (!potentiostatic) continue;
      double k = 0;
      for (int s = 0; s < 3 && d.loadCurveID[i][s] > 0; ++s) {
        const int b = d.loadCurveID[i][s] - 1;
        const ScalarFluxBC& bc = bcs_[b];
        const double area = fluxArea(bc, p, d, i, s);
        if (bc.mode == ScalarFluxBC::Mode::Potentiostatic)
          k += surfaceConductance(bc, area, p.volume[i], d.diffusivity[i]) * area;
        else if (bc.reaction && c > 0 && c < 1)
          k +=
              bc.reaction->fluxSlope(
                  potentials_[b],
                  bc.reaction->openCircuit(c, stressPotential(perStress, p.stress[i], p.F[i])), c) *
              area;
      }
      relaxation = std::max(relaxation, k / p.volume[i]);
    }
  }
  double lows[5] = {-maxInflowRate_, -maxOutflowRate_, -fullest, emptiest, -relaxation};
  collective::minimum(every, lows, 5);
  double dt = std::numeric_limits<double>::infinity();
  if (lows[0] < 0) dt = std::min(dt, fluxStepToRoot(-lows[2]) / -lows[0]);
  if (lows[1] < 0) dt = std::min(dt, fluxStepToRoot(1 - lows[3]) / -lows[1]);
  if (lows[4] < 0) dt = std::min(dt, 1 / -lows[4]);
  return dt;
}

void ExternalScalarFlux::updateAutoCycle(Collective every,
                                         const std::vector<MPMMaterial>& materials,
                                         const std::vector<DiffusionMaterial>& diffusion,
                                         const MPMFlags& flags) {
  // Mean (or min and max) normalised concentration of the materials with <do_conc_reduction>.
  double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  size_t n = 0;
  for (size_t m = 0; m < materials.size(); ++m) {
    if (!diffusion[m].reducesConcentration) continue;
    const double cmax = diffusion[m].model->maxConcentration;
    for (double c : diffusionParticles(materials[m].particles).concentration) {
      sum += c / cmax;
      lo = std::min(lo, c / cmax);
      hi = std::max(hi, c / cmax);
    }
    n += materials[m].particles.count();
  }
  // Over every rank's particles (the identity on one rank).
  const double count = collective::sum(every, static_cast<double>(n));
  if (count == 0) return;
  const double mean = collective::sum(every, sum) / count;
  lo = collective::minimum(every, lo);
  hi = collective::maximum(every, hi);
  if (sign_ > 0 && (flags.autoCycleUseMinMax ? lo : mean) > flags.autoCycleMax) sign_ = -1;
  if (sign_ < 0 && (flags.autoCycleUseMinMax ? hi : mean) < flags.autoCycleMin) sign_ = 1;
}

double ExternalScalarFlux::nextLoadCurveTimeAfter(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const ScalarFluxBC& bc : bcs_) next = std::min(next, bc.load.nextTimeAfter(t));
  return next;
}

void ExternalScalarFlux::shareFacesOnSplit(ParticleSet& p,
                                           const std::vector<SplitParticle>& splits) const {
  if (diffusionParticles(p).loadCurveID.empty()) return;
  for (const SplitParticle& s : splits) shareFluxFaces(p, bcs_, s);
}

void ExternalScalarFlux::saveState(BinaryWriter& out) const {
  out.value(sign_);
  out.value(maxInflowRate_);
  out.value(maxOutflowRate_);
  out.value<uint64_t>(endedIn_.size());
  for (long e : endedIn_) out.value(e);
  out.value<uint64_t>(potentials_.size());
  for (double phi : potentials_) out.value(phi);
}

void ExternalScalarFlux::loadState(BinaryReader& in, bool merge) {
  sign_ = in.value<double>();
  const double inflow = in.value<double>(), outflow = in.value<double>();
  maxInflowRate_ = merge ? std::max(maxInflowRate_, inflow) : inflow;
  maxOutflowRate_ = merge ? std::max(maxOutflowRate_, outflow) : outflow;
  endedIn_.resize(in.value<uint64_t>());
  for (long& e : endedIn_) e = in.value<long>();
  potentials_.resize(in.value<uint64_t>());
  for (double& phi : potentials_) phi = in.value<double>();
}

void markSourceNodes(const ParticleSet& p, const InterpolationWeights& W,
                     std::vector<unsigned char>& reached, const std::vector<NodeRange>& cleared) {
  forEachNodeRange(cleared, [&reached](long begin, long end) {
    std::fill(reached.begin() + begin, reached.begin() + end, 0);
  });
  unsigned char* mark = reached.data();
  const ConstDiffusionParticles d(p);
  const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double rate = d.externalScalarFlux[i];
    if (rate == 0) continue;
    const unsigned char bit = rate > 0 ? 1 : 2;
    for (int e = 0; e < W.count[i]; ++e) {
      unsigned char& node = mark[W.node[W.offset[i] + e]];
      unsigned char seen;
#pragma omp atomic read
      seen = node;
      if (!(seen & bit)) {
#pragma omp atomic update
        node |= bit;
      }
    }
  }
}

}  // namespace anode

#include "Components/MPM/StateChecks.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

double jacobian(const MPMMaterial& mat, size_t i) {
  return mat.particles.volume[i] * mat.density / mat.particles.mass[i];
}

// What is wrong with particle i (one that failed the check in afterStep).
std::string problemOf(const MPMMaterial& mat, size_t i) {
  const ParticleSet& p = mat.particles;
  std::ostringstream s;
  const double J = jacobian(mat, i);
  if (!p.x[i].allFinite()) {
    s << "has a non-finite position p.x = " << formatVector(p.x[i]);
  } else if (!p.velocity[i].allFinite()) {
    s << "has a non-finite velocity p.velocity = " << formatVector(p.velocity[i]);
  } else if (!p.stress[i].allFinite()) {
    s << "has a non-finite stress p.stress = [";
    for (int k = 0; k < 9; ++k) s << (k ? ", " : "") << p.stress[i](k / 3, k % 3);
    s << "]";
  } else if (!(J > 0)) {
    s << "has J = V rho0 / m = " << J << " (inverted, degenerate or not a number)";
  } else if (J < StateChecks::kMinJ) {
    s << "has J = V rho0 / m = " << J << ", below " << StateChecks::kMinJ
      << ": a compression no material sustains (the particle is collapsing)";
  } else {
    s << "has J = V rho0 / m = " << J << ", above " << StateChecks::kMaxJ
      << ": a volume growth no swelling or tension explains";
  }
  return s.str();
}

}  // namespace

template <class F>
void StateChecks::forEachHistory(size_t m, const ParticleSet& p, F&& f) {
  f(velocity_[m], [&](size_t j) { return p.velocity[j]; });
  f(velocityIncrement_[m], [](size_t) { return Vec3::Zero().eval(); });
  f(localStreak_[m], [](size_t) { return uint8_t{0}; });
  const std::vector<double>* concentration = concentrationOf(p);
  if (!concentration || concentration->empty()) return;
  f(concentration_[m], [concentration](size_t j) { return (*concentration)[j]; });
  f(concentrationIncrement_[m], [](size_t) { return 0.0; });
}

bool StateChecks::oscillates(Oscillation& o, double energy, double product, double* growth,
                             double* correlation) {
  const double c =
      o.lastEnergy > 0 && energy > 0 ? product / std::sqrt(energy * o.lastEnergy) : 0.0;
  const double pair = energy + o.lastEnergy;
  o.lastEnergy = energy;
  *correlation = c;
  if (!(c < kAlternation)) {
    o.steps = 0;
    return false;
  }
  o.smallest = o.steps == 0 ? pair : std::min(o.smallest, pair);
  ++o.steps;
  *growth = pair / o.smallest;
  return *growth >= kOscillationGrowth ||
         (o.steps >= kSustainedSteps && *growth >= kSustainedGrowth);
}

void StateChecks::afterStep(Collective every, const MPM& mpm, double dt) {
  const auto& materials = mpm.materials();
  const size_t count = materials.size();
  if (velocity_.size() != count || mpm.layout().generation() != layoutGeneration_) {
    layoutGeneration_ = mpm.layout().generation();
    velocity_.assign(count, {});
    velocityIncrement_.assign(count, {});
    localStreak_.assign(count, {});
    concentration_.assign(count, {});
    concentrationIncrement_.assign(count, {});
  }
  // A quasi-static step's velocity is its displacement over dt, with no inertia behind it: it
  // turns with the load (a charge turning to a discharge reverses it) and is not watched for
  // oscillation or growth; its concentrations are.
  const std::optional<ImplicitOptions>& implicit = mpm.problem().flags.implicit;
  const bool dynamics = !implicit || implicit->dynamic;
  // One pass per material: finite values and J, kinetic energy, the increments of the step.
  double energy = 0, totalMass = 0, velocityEnergy = 0, velocityProduct = 0,
         concentrationEnergy = 0, concentrationProduct = 0;
  bool restart = false;
  // Below this squared increment a particle's oscillation is not reported (round-off).
  const double motion = kLocalMotion * mpm.grid().dx.minCoeff() / dt;
  const double localFloor2 = std::max(
      motion * motion,
      lastMass_ > 0 ? kLocalFloor * kLocalFloor * 2 * lastKineticEnergy_ / lastMass_ : 0.0);
  // A problem one particle shows, reported after the sums over the ranks (which every rank
  // reaches) by every rank together.
  std::string problem;
  for (size_t m = 0; m < count; ++m) {
    const MPMMaterial& mat = materials[m];
    const ParticleSet& p = mat.particles;
    const long n = static_cast<long>(p.count());
    const std::vector<double>* concentration = concentrationOf(p);
    const bool diffusion = concentration && !concentration->empty();
    followReordering(mpm.lastReordering()[m], m, p);
    if (velocity_[m].size() != p.count()) {
      // The first step (or the particles were shared out anew): the oscillation watch starts.
      forEachHistory(m, p, [&](auto& history, auto start) {
        history.resize(p.count());
        for (size_t j = 0; j < p.count(); ++j) history[j] = start(j);
      });
      restart = true;
    }
    Vec3* v = velocity_[m].data();
    Vec3* dv = velocityIncrement_[m].data();
    uint8_t* streak = localStreak_[m].data();
    double* c = diffusion ? concentration_[m].data() : nullptr;
    double* dc = diffusion ? concentrationIncrement_[m].data() : nullptr;
    long firstBad = n, firstLocal = n;
    double kinetic = 0, mass = 0, ve = 0, vp = 0, ce = 0, cp = 0;
#pragma omp parallel for schedule(static) reduction(min : firstBad, firstLocal) \
    reduction(+ : kinetic, mass, ve, vp, ce, cp)
    for (long i = 0; i < n; ++i) {
      const double J = p.volume[i] * mat.density / p.mass[i];
      if (!p.x[i].allFinite() || !p.velocity[i].allFinite() || !p.stress[i].allFinite() ||
          !(J >= kMinJ && J <= kMaxJ))
        firstBad = std::min(firstBad, i);
      const double half = 0.5 * p.mass[i];
      kinetic += half * p.velocity[i].squaredNorm();
      mass += p.mass[i];
      const Vec3 d = p.velocity[i] - v[i];
      const double dd = d.squaredNorm(), pp = dv[i].squaredNorm();
      const bool reversedAndGrew =
          d.dot(dv[i]) < kAlternation * std::sqrt(dd * pp) && dd > kLocalGrowth * kLocalGrowth * pp;
      streak[i] = reversedAndGrew ? static_cast<uint8_t>(std::min(streak[i] + 1, 255)) : 0;
      if (dynamics && streak[i] >= kLocalSteps && dd > localFloor2)
        firstLocal = std::min(firstLocal, i);
      ve += half * dd;
      vp += half * d.dot(dv[i]);
      v[i] = p.velocity[i];
      dv[i] = d;
      if (c) {
        const double e = (*concentration)[i] - c[i];
        ce += half * e * e;
        cp += half * e * dc[i];
        c[i] = (*concentration)[i];
        dc[i] = e;
      }
    }
    if (problem.empty() && firstBad < n)
      problem = describeParticle(mat, m, firstBad) + " " + problemOf(mat, firstBad);
    if (problem.empty() && firstLocal < n && !restart)
      problem = describeLocalOscillation(mat, m, firstLocal);
    energy += kinetic;
    totalMass += mass;
    velocityEnergy += ve, velocityProduct += vp, concentrationEnergy += ce,
        concentrationProduct += cp;
  }
  collective::stopTogether(every, [&] {
    if (!problem.empty()) throw SimulationError(problem);
  });
  double sums[6] = {energy,          totalMass,           velocityEnergy,
                    velocityProduct, concentrationEnergy, concentrationProduct};
  collective::sum(every, sums, 6);
  energy = sums[0], totalMass = sums[1], velocityEnergy = sums[2], velocityProduct = sums[3],
  concentrationEnergy = sums[4], concentrationProduct = sums[5];
  restart = collective::any(every, restart);
  if (restart) {
    velocityOscillation_ = concentrationOscillation_ = Oscillation();
  } else {
    checkOscillation(every, mpm, dynamics ? velocityEnergy : 0.0, velocityProduct,
                     concentrationEnergy, concentrationProduct);
  }
  lastMass_ = totalMass;
  if (dynamics) checkKineticEnergy(every, mpm, energy);
}

void StateChecks::followReordering(const ParticleReordering& r, size_t m, const ParticleSet& p) {
  // A split particle's 3 children continue its history: they have its velocity and
  // concentration, and the 4 share its mass, so the watched sums go on unchanged.
  if (!r.split.empty() && velocity_[m].size() == r.beforeSplitting)
    forEachHistory(m, p, [&](auto& history, auto) {
      for (const SplitParticle& s : r.split)
        for (int c = 0; c < 3; ++c) history.push_back(history[s.child[0]]);
    });
  // Of those that migrated, the ones that stayed keep their history; those that arrived start.
  if (r.migrated && velocity_[m].size() == r.beforeMigration)
    forEachHistory(m, p, [&](auto& history, auto start) {
      for (size_t j = 0; j < r.kept.size(); ++j) history[j] = history[r.kept[j]];
      history.resize(r.kept.size());
      for (size_t j = r.kept.size(); j < p.count(); ++j) history.push_back(start(j));
    });
}

std::string StateChecks::describeLocalOscillation(const MPMMaterial& mat, size_t m,
                                                  size_t i) const {
  const ParticleSet& p = mat.particles;
  std::ostringstream s;
  s << "the velocity of " << describeParticle(mat, m, i)
    << " oscillates with growing amplitude: for " << static_cast<int>(localStreak_[m][i])
    << " steps in a row its increment reversed the previous one and grew by " << kLocalGrowth
    << " or more, to " << formatVector(velocityIncrement_[m][i])
    << " (p.velocity = " << formatVector(p.velocity[i])
    << "): a local instability of the explicit update at this time step (lower "
       "<timestep_multiplier>)";
  return s.str();
}

void StateChecks::checkOscillation(Collective every, const MPM& mpm, double velocityEnergy,
                                   double velocityProduct, double concentrationEnergy,
                                   double concentrationProduct) {
  double growth = 0, correlation = 0;
  const bool velocity =
      oscillates(velocityOscillation_, velocityEnergy, velocityProduct, &growth, &correlation);
  const bool concentration = !velocity && oscillates(concentrationOscillation_, concentrationEnergy,
                                                     concentrationProduct, &growth, &correlation);
  if (!velocity && !concentration) return;

  // The particle whose increment is largest, as the place to look (the rank holding it reports).
  const auto& materials = mpm.materials();
  size_t worstM = 0, worstI = 0;
  double worst = -1;
  for (size_t m = 0; m < materials.size(); ++m) {
    const size_t n = velocity ? velocityIncrement_[m].size() : concentrationIncrement_[m].size();
    for (size_t i = 0; i < n; ++i) {
      const double size = velocity ? velocityIncrement_[m][i].squaredNorm()
                                   : std::abs(concentrationIncrement_[m][i]);
      if (size > worst) worst = size, worstM = m, worstI = i;
    }
  }
  const bool holdsWorst = worst == collective::maximum(every, worst);
  collective::stopTogether(every, [&] {
    if (!holdsWorst) return;
    const ParticleSet& p = materials[worstM].particles;
    const Oscillation& o = velocity ? velocityOscillation_ : concentrationOscillation_;
    std::ostringstream s;
    s << "the particle " << (velocity ? "velocities" : "concentrations")
      << " oscillate with growing amplitude: for " << o.steps
      << " steps each step's increment reversed the previous one "
      << "(mass-weighted correlation " << correlation << ") and their energy grew by a factor of "
      << growth << ": the explicit " << (velocity ? "momentum" : "diffusion")
      << " update is unstable at this time step (lower <timestep_multiplier>); the largest "
         "increment is at "
      << describeParticle(materials[worstM], worstM, worstI);
    if (velocity)
      s << ": p.velocity = " << formatVector(p.velocity[worstI]) << " after a change of "
        << formatVector(velocityIncrement_[worstM][worstI]);
    else
      s << ": p.concentration = " << (*concentrationOf(p))[worstI] << " after a change of "
        << concentrationIncrement_[worstM][worstI];
    throw SimulationError(s.str());
  });
}

void StateChecks::checkKineticEnergy(Collective every, const MPM& mpm, double energy) {
  if (lastKineticEnergy_ > 0 && energy >= kGrowthPerStep * lastKineticEnergy_) {
    if (growingSteps_ == 0) energyBeforeGrowth_ = lastKineticEnergy_;
    ++growingSteps_;
  } else {
    growingSteps_ = 0;
  }
  lastKineticEnergy_ = energy;
  if (growingSteps_ < kGrowthSteps && std::isfinite(energy)) return;

  // The fastest particle, as the place to look (the rank holding it reports).
  const auto& materials = mpm.materials();
  size_t fastM = 0, fastI = 0;
  double fastest = -1;
  for (size_t m = 0; m < materials.size(); ++m)
    for (size_t i = 0; i < materials[m].particles.count(); ++i)
      if (materials[m].particles.velocity[i].squaredNorm() > fastest) {
        fastest = materials[m].particles.velocity[i].squaredNorm();
        fastM = m;
        fastI = i;
      }
  const bool holdsFastest = fastest == collective::maximum(every, fastest);
  collective::stopTogether(every, [&] {
    if (!holdsFastest) return;
    std::ostringstream s;
    if (!std::isfinite(energy)) {
      s << "the kinetic energy overflows (" << energy << ")";
    } else {
      s << "the kinetic energy grew by a factor of at least " << kGrowthPerStep
        << " at each of the last " << growingSteps_ << " steps, from " << energyBeforeGrowth_
        << " to " << energy
        << ": a numerical instability (a time step beyond the stable one: lower "
           "<timestep_multiplier>)";
    }
    s << "; the fastest is " << describeParticle(materials[fastM], fastM, fastI)
      << " with p.velocity = " << formatVector(materials[fastM].particles.velocity[fastI]);
    throw SimulationError(s.str());
  });
}

}  // namespace anode

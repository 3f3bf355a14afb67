#include "Components/MPM/MPM.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "Components/MPM/GridBoundaryConditions.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

void readPhysicalBCs(const PSNode& root) {
  const PSNode physical = root.child("PhysicalBC");
  if (!physical) return;
  const PSNode mpm = physical.child("MPM");
  if (!mpm) return;
  for (const PSNode& bc : mpm.children()) {
    if (bc.name() == "scalar_flux")
      bc.unsupported("<scalar_flux> lithium flux boundary condition");
    else if (bc.name() == "pressure" || bc.name() == "force" || bc.name() == "heat_flux" ||
             bc.name() == "arches_heat_flux")
      bc.unsupported("<" + bc.name() + "> boundary condition");
    else
      bc.fail("unknown physical boundary condition <" + bc.name() + ">");
    bc.markSubtreeUsed();
  }
}

std::string particleLabel(const MPMMaterial& m, size_t matl, size_t i) {
  std::ostringstream s;
  const Vec3& x = m.particles.x[i];
  s << "particle " << m.particles.id[i] << " of material " << matl;
  if (!m.name.empty()) s << " (" << m.name << ")";
  s << " at [" << x.x() << ", " << x.y() << ", " << x.z() << "]";
  return s.str();
}

}  // namespace

void MPM::problemSetup(const PSNode& root) {
  flags_ = MPMFlags::fromInput(root);
  const PSNode gridNode = root.requireChild("Grid");
  grid_ = Grid::fromInput(gridNode);
  if (flags_.interpolator != InterpolatorKind::Linear && (grid_.extra.array() < 1).any())
    gridNode.requireChild("Level")
        .requireChild("Box")
        .fail("interpolator \"" + interpolatorName(flags_.interpolator) +
              "\" reaches beyond the cell: it needs <extraCells>[1,1,1]");

  const PSNode matProps = root.requireChild("MaterialProperties");
  const PSNode mpmMats = matProps.requireChild("MPM");
  GeometryPieceFactory pieces;
  int64_t nextId = 0;
  const auto materialNodes = mpmMats.children("material");
  if (materialNodes.empty()) mpmMats.fail("<MaterialProperties><MPM> needs at least one <material>");
  for (const PSNode& m : materialNodes)
    materials_.push_back(MPMMaterial::fromInput(m, grid_, flags_, pieces, nextId));
  contact_ = Contact::fromInput(mpmMats, static_cast<int>(materials_.size()));
  if (const PSNode iface = mpmMats.child("diffusion_interface")) {
    const std::string type = iface.get<std::string>("type", "null");
    if (type != "null") iface.requireChild("type").unsupported("diffusion_interface type \"" + type + "\"");
    iface.markSubtreeUsed();
  }
  faceBCs_ = readFaceBCs(gridNode, static_cast<int>(materials_.size()));
  readPhysicalBCs(root);

  const int nodes = grid_.numNodes();
  fields_.resize(materials_.size());
  for (auto& f : fields_) f.resize(nodes);
  weights_.resize(materials_.size());
  velocityGradient_.resize(materials_.size());
  newF_.resize(materials_.size());
  for (size_t m = 0; m < materials_.size(); ++m) {
    const size_t n = materials_[m].particles.count();
    weights_[m].resize(n, maxNodesPerParticle(flags_.interpolator));
    velocityGradient_[m].resize(n);
    newF_[m].resize(n);
  }
  threadScatter_.resize(omp_get_max_threads() > 1 ? omp_get_max_threads() : 0);
  for (auto& t : threadScatter_) {
    t.mass.resize(nodes);
    t.velocity.resize(nodes);
    t.internalForce.resize(nodes);
  }
}

size_t MPM::numParticles() const {
  size_t n = 0;
  for (const auto& m : materials_) n += m.particles.count();
  return n;
}

void MPM::timeAdvance(double dt) {
  static const char* names[] = {"computeInterpolationWeights", "interpolateParticlesToGrid",
                                "exchangeMomentum+integrateGrid", "interpolateToParticlesAndUpdate",
                                "computeStressTensor"};
  int t[5];
  for (int i = 0; i < 5; ++i) t[i] = timers_.task(names[i]);
  { ScopedTimer s(timers_, t[0]); computeInterpolationWeights(); }      // step 1
  { ScopedTimer s(timers_, t[1]); interpolateParticlesToGrid(); }       // step 3 and 5 (Eq. 4)
  {
    ScopedTimer s(timers_, t[2]);
    exchangeMomentumInterpolated();                                      // step 4
    integrateGridMomentum(dt);                                           // step 6
    setGridBoundaryConditions(dt);
  }
  { ScopedTimer s(timers_, t[3]); interpolateToParticlesAndUpdate(dt); }  // step 7
  { ScopedTimer s(timers_, t[4]); computeStressTensor(dt); }              // step 8 (Eqs. 26-39)
}

void MPM::computeInterpolationWeights() {
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    InterpolationWeights& W = weights_[m];
    const long n = static_cast<long>(p.count());
    const int stride = W.stride;
    long firstOutside = n;
#pragma omp parallel for schedule(static) reduction(min : firstOutside)
    for (long i = 0; i < n; ++i) {
      const size_t b = static_cast<size_t>(i) * stride;
      int count = 0;
      switch (flags_.interpolator) {
        case InterpolatorKind::Linear:
          count = linearWeights(grid_, p.x[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
        case InterpolatorKind::GIMP:
          count = gimpWeights(grid_, p.x[i], p.size[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
        case InterpolatorKind::CPDI:
          count = cpdiWeights(grid_, p.x[i], p.size[i], p.F[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
      }
      if (count < 0) firstOutside = std::min(firstOutside, i);
      W.count[i] = static_cast<uint8_t>(std::max(count, 0));
    }
    if (firstOutside < n)
      throw SimulationError(particleLabel(materials_[m], m, firstOutside) +
                            " has left the grid (its interpolation support reaches beyond the last node)");
  }
}

namespace {

// Scatters mass, momentum and internal force (Eq. 4; f_int = -sum V sigma grad S) of particles
// [begin, end) into the given nodal arrays.
void scatterToGrid(const ParticleSet& p, const InterpolationWeights& W, long begin, long end,
                   double* mass, Vec3* momentum, Vec3* force) {
  for (long i = begin; i < end; ++i) {
    const double mp = p.mass[i];
    const Vec3 mv = mp * p.velocity[i];
    const Mat3 Vsigma = p.volume[i] * p.stress[i];
    const size_t b = static_cast<size_t>(i) * W.stride;
    for (int e = 0; e < W.count[i]; ++e) {
      const int n = W.node[b + e];
      const double w = W.weight[b + e];
      mass[n] += mp * w;
      momentum[n] += mv * w;
      force[n] -= Vsigma * W.gradient[b + e];
    }
  }
}

}  // namespace

void MPM::interpolateParticlesToGrid() {
  const long nodes = grid_.numNodes();
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    GridFields& g = fields_[m];
    const long n = static_cast<long>(p.count());
    std::fill(g.mass.begin(), g.mass.end(), 0.0);
    std::fill(g.velocity.begin(), g.velocity.end(), Vec3::Zero());
    std::fill(g.internalForce.begin(), g.internalForce.end(), Vec3::Zero());
    if (threadScatter_.empty()) {
      scatterToGrid(p, weights_[m], 0, n, g.mass.data(), g.velocity.data(), g.internalForce.data());
    } else {
      // Each thread scatters a contiguous block of particles into its own buffer; the buffers are
      // summed in thread order, so results do not depend on scheduling.
      const int threads = static_cast<int>(threadScatter_.size());
#pragma omp parallel num_threads(threads)
      {
        const int t = omp_get_thread_num();
        GridFields& s = threadScatter_[t];
        std::fill(s.mass.begin(), s.mass.end(), 0.0);
        std::fill(s.velocity.begin(), s.velocity.end(), Vec3::Zero());
        std::fill(s.internalForce.begin(), s.internalForce.end(), Vec3::Zero());
        const long begin = n * t / threads, end = n * (t + 1) / threads;
        scatterToGrid(p, weights_[m], begin, end, s.mass.data(), s.velocity.data(), s.internalForce.data());
#pragma omp barrier
#pragma omp for schedule(static)
        for (long k = 0; k < nodes; ++k)
          for (int u = 0; u < threads; ++u) {
            g.mass[k] += threadScatter_[u].mass[k];
            g.velocity[k] += threadScatter_[u].velocity[k];
            g.internalForce[k] += threadScatter_[u].internalForce[k];
          }
      }
    }
#pragma omp parallel for schedule(static)
    for (long k = 0; k < nodes; ++k)
      g.velocity[k] = g.mass[k] > 0 ? Vec3(g.velocity[k] / g.mass[k]) : Vec3::Zero();
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.velocity);
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.internalForce);
  }
}

void MPM::exchangeMomentumInterpolated() {
  if (contact_.exchangeInterpolated) contact_.exchange(fields_, &GridFields::velocity);
}

void MPM::integrateGridMomentum(double dt) {
  const long nodes = grid_.numNodes();
  for (GridFields& g : fields_) {
#pragma omp parallel for schedule(static)
    for (long k = 0; k < nodes; ++k) {
      Vec3 a = Vec3::Zero();
      if (g.mass[k] > flags_.minimumMassForAcc && g.mass[k] > 0)
        a = g.internalForce[k] / g.mass[k] + flags_.gravity - flags_.artificialDampingCoeff * g.velocity[k];
      g.velocityStar[k] = g.velocity[k] + a * dt;
    }
  }
}

void MPM::setGridBoundaryConditions(double dt) {
  contact_.exchange(fields_, &GridFields::velocityStar);
  const long nodes = grid_.numNodes();
  for (size_t m = 0; m < fields_.size(); ++m) {
    GridFields& g = fields_[m];
    applyVelocityDirichlet(grid_, faceBCs_, static_cast<int>(m), g.velocityStar);
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.velocityStar);
#pragma omp parallel for schedule(static)
    for (long k = 0; k < nodes; ++k) g.acceleration[k] = (g.velocityStar[k] - g.velocity[k]) / dt;
  }
}

void MPM::interpolateToParticlesAndUpdate(double dt) {
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    ParticleSet& p = mat.particles;
    const InterpolationWeights& W = weights_[m];
    const GridFields& g = fields_[m];
    std::vector<Mat3>& L = velocityGradient_[m];
    std::vector<Mat3>& Fnew = newF_[m];
    const long n = static_cast<long>(p.count());
    const double rho0 = mat.density;
    long firstInverted = n;
#pragma omp parallel for schedule(static) reduction(min : firstInverted)
    for (long i = 0; i < n; ++i) {
      Mat3 gradV = Mat3::Zero();
      Vec3 acc = Vec3::Zero(), vel = Vec3::Zero();
      const size_t b = static_cast<size_t>(i) * W.stride;
      for (int e = 0; e < W.count[i]; ++e) {
        const int k = W.node[b + e];
        const double w = W.weight[b + e];
        gradV += g.velocityStar[k] * W.gradient[b + e].transpose();
        acc += g.acceleration[k] * w;
        vel += g.velocityStar[k] * w;
      }
      // F^{n+1} = (I + L dt/N)^N F^n, subcycled when L dt is large (Uintah's rule).
      const int cycles = std::min(std::max(flags_.minimumSubcyclesForF,
                                           2 * static_cast<int>(gradV.norm() * dt)), 10000);
      const Mat3 increment = Mat3::Identity() + gradV * (dt / cycles);
      Mat3 F = p.F[i];
      for (int c = 0; c < cycles; ++c) F = increment * F;
      const double J = F.determinant();
      if (!(J > 0)) firstInverted = std::min(firstInverted, i);
      L[i] = gradV;
      Fnew[i] = F;
      p.velocity[i] += acc * dt;
      p.x[i] += vel * dt;
      p.displacement[i] += vel * dt;
      p.volume[i] = p.mass[i] / rho0 * J;
    }
    if (firstInverted < n) {
      std::ostringstream s;
      s << particleLabel(mat, m, firstInverted) << " has det F = " << Fnew[firstInverted].determinant()
        << " (inverted or degenerate deformation)";
      throw SimulationError(s.str());
    }
  }
}

void MPM::computeStressTensor(double dt) {
  for (size_t m = 0; m < materials_.size(); ++m)
    materials_[m].model->computeStressTensor(materials_[m].particles, velocityGradient_[m], newF_[m], dt);
}

double MPM::computeStableTimestep() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const double modulus = mat.model->dilatationalModulus();
    const long n = static_cast<long>(p.count());
    double wx = 0, wy = 0, wz = 0;
#pragma omp parallel for schedule(static) reduction(max : wx, wy, wz)
    for (long i = 0; i < n; ++i) {
      const double c = std::sqrt(modulus * p.volume[i] / p.mass[i]);  // Eq. 41 with rho = m/V
      wx = std::max(wx, c + std::abs(p.velocity[i].x()));
      wy = std::max(wy, c + std::abs(p.velocity[i].y()));
      wz = std::max(wz, c + std::abs(p.velocity[i].z()));
    }
    // Eq. 43.
    dt = std::min({dt, grid_.dx.x() / wx, grid_.dx.y() / wy, grid_.dx.z() / wz});
  }
  return dt;
}

void MPM::interpolateToGridForOutput() {
  computeInterpolationWeights();
  interpolateParticlesToGrid();
}

StepSummary MPM::summarize() const {
  StepSummary s;
  s.minJ = std::numeric_limits<double>::infinity();
  s.maxJ = -std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    for (size_t i = 0; i < p.count(); ++i) {
      s.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
      const double J = p.volume[i] * mat.density / p.mass[i];
      s.minJ = std::min(s.minJ, J);
      s.maxJ = std::max(s.maxJ, J);
    }
    s.particles += p.count();
  }
  return s;
}

}  // namespace anode

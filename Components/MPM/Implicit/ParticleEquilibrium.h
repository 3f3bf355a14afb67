// The particles' side of the equilibrium step (DESIGN.md §4b, steps 3 and 5), compiled per
// constitutive model: the stress each particle would reach under trial nodal displacement
// increments u, from its start-of-step state, with its derivative for Newton's Jacobian; and,
// once Newton has converged, the update of the particles with the converged u.
//
// Kinematics relative to the start of the step (weights and gradients of that configuration):
// H = sum_I u_I (x) grad S_I, dF = I + H, F = dF F_n; the model sees the rate of deformation of
// the midpoint rule, L dt = 2 (dF - I)(I + dF)^-1 (second order in the step, where explicit MPM
// takes L dt = H), and the particle's concentration change over the step (dc, from the
// diffusion sub-steps that come first; none without diffusion). The nodal forces need the first
// Piola-Kirchhoff stress relative to the start-of-step configuration, P = J_d sigma dF^-T = sigma
// cof(dF), on the start-of-step volume V_n: f_I = sum_p V_n P grad S_I. Its derivative A = dP/dH (9
// x 9, index 3a + d for component (a, d)) is the model's algorithmic tangent, taken by central
// differences of the model's own update (step kTangentStep in H): any model listed in
// ConcreteModels.h gets it without code of its own.
#pragma once

#include <vector>

#include "Components/MPM/Interpolator.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/StressLanes.h"
#include "Core/Math/Simd.h"

namespace anode {

constexpr double kTangentStep = 1e-6;

template <class S>
Mat3Of<S> cofactorOf(const Mat3Of<S>& m) {
  Mat3Of<S> c;
  c(0, 0) = m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1);
  c(0, 1) = m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2);
  c(0, 2) = m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0);
  c(1, 0) = m(0, 2) * m(2, 1) - m(0, 1) * m(2, 2);
  c(1, 1) = m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0);
  c(1, 2) = m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1);
  c(2, 0) = m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1);
  c(2, 1) = m(0, 2) * m(1, 0) - m(0, 0) * m(1, 2);
  c(2, 2) = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  return c;
}

// H = sum_I u_I (x) grad S_I of particle i, u by node.
inline Mat3 displacementGradient(const InterpolationWeights& W, long i,
                                 const std::vector<Vec3>& u) {
  Mat3 H = Mat3::Zero();
  const size_t b = W.offset[i];
  for (int e = 0; e < W.count[i]; ++e) H += u[W.node[b + e]] * W.gradient[b + e].transpose();
  return H;
}

// One block of Pack::size() particles at its start-of-step state (StressLanes.h) with the
// displacement gradient H of the trial u.
template <class Model>
struct TrialBlock : StressLanes<Model> {
  Mat3Pack H;

  // `concentrationChange`: dc per particle, or null (no swelling in this step).
  TrialBlock(const ParticleSet& p, const typename Model::StateArrays& arrays,
             const InterpolationWeights& W, const std::vector<Vec3>& u,
             const double* concentrationChange, long first) {
    for (int l = 0; l < static_cast<int>(Pack::size()); ++l) {
      const long i = first + l;
      if (i >= static_cast<long>(p.count())) {
        this->setPlaceholder(l);
        setLane(H, l, Mat3::Zero());
        continue;
      }
      this->setParticle(l, p, i, p.F[i], concentrationChange ? concentrationChange[i] : 0.0,
                        arrays);
      setLane(H, l, displacementGradient(W, i, u));
    }
  }

  // sigma of the trial dF = I + h, with the state it leaves in `after`.
  Mat3Pack cauchy(const Model& model, const Mat3Pack& h, double dt,
                  typename Model::template State<Pack>& after) const {
    const Mat3Pack I = Mat3Pack::Identity();
    const Mat3Pack dF = I + h;
    const Mat3Pack sum = I + dF;
    const Mat3Pack inverseSum = cofactorOf(sum).transpose() / sum.determinant();
    const Mat3Pack L = Pack(2.0 / dt) * h * inverseSum;
    after = this->state;
    return model.updateStress(this->stress, Mat3Pack(dF * this->F), L, this->dc, dt, after);
  }
  Mat3Pack piola(const Model& model, const Mat3Pack& h, double dt) const {
    typename Model::template State<Pack> after;
    return cauchy(model, h, dt, after) * cofactorOf(Mat3Pack(Mat3Pack::Identity() + h));
  }
};

// P of every particle of the set and, when A is given, its tangent dP/dH; dc as for TrialBlock.
template <class Model>
void evaluateTrialStress(ParticleSet& p, const InterpolationWeights& W, const Model& model,
                         const std::vector<Vec3>& u, const double* dc, double dt,
                         std::vector<Mat3>& P, std::vector<Mat9>* A) {
  const auto arrays = model.stateArrays(p);
  const long n = static_cast<long>(p.count());
  constexpr int lanes = static_cast<int>(Pack::size());
  P.resize(n);
  if (A) A->resize(n);
#pragma omp parallel for schedule(static)
  for (long block = 0; block < (n + lanes - 1) / lanes; ++block) {
    const TrialBlock<Model> t(p, arrays, W, u, dc, block * lanes);
    const Mat3Pack P0 = t.piola(model, t.H, dt);
    for (int l = 0; l < lanes && block * lanes + l < n; ++l) P[block * lanes + l] = lane(P0, l);
    if (!A) continue;
    for (int k = 0; k < 9; ++k) {
      Mat3Pack plus = t.H, minus = t.H;
      plus(k / 3, k % 3) += Pack(kTangentStep);
      minus(k / 3, k % 3) -= Pack(kTangentStep);
      const Mat3Pack dP =
          (t.piola(model, plus, dt) - t.piola(model, minus, dt)) / Pack(2 * kTangentStep);
      for (int l = 0; l < lanes && block * lanes + l < n; ++l) {
        Mat9& a = (*A)[block * lanes + l];
        for (int r = 0; r < 9; ++r) a(r, 3 * (k / 3) + k % 3) = dP(r / 3, r % 3)[l];
      }
    }
  }
}

// The particles after the step with the converged u (Eq. 8's counterpart): position and
// displacement by sum S u, F, volume, stress and the model's state; the velocity u/dt
// interpolated or, in implicit dynamics (`acceleration`: the nodes' at the step's end), Newmark's
// v += dt/2 (a_p + sum S a') and a_p = sum S a' (Newmark.h). dc as for TrialBlock. Returns the
// first particle whose det F is not positive (n if none).
template <class Model>
long updateParticlesFromDisplacement(ParticleSet& p, const InterpolationWeights& W,
                                     const Model& model, double density, const std::vector<Vec3>& u,
                                     const std::vector<Vec3>* acceleration, const double* dc,
                                     double dt) {
  const auto arrays = model.stateArrays(p);
  const long n = static_cast<long>(p.count());
  constexpr int lanes = static_cast<int>(Pack::size());
  long firstInverted = n;
#pragma omp parallel for schedule(static) reduction(min : firstInverted)
  for (long block = 0; block < (n + lanes - 1) / lanes; ++block) {
    const TrialBlock<Model> t(p, arrays, W, u, dc, block * lanes);
    typename Model::template State<Pack> after;
    const Mat3Pack sigma = t.cauchy(model, t.H, dt, after);
    for (int l = 0; l < lanes; ++l) {
      const long i = block * lanes + l;
      if (i >= n) break;
      Vec3 moved = Vec3::Zero(), accelerated = Vec3::Zero();
      const size_t b = W.offset[i];
      for (int e = 0; e < W.count[i]; ++e) {
        moved += W.weight[b + e] * u[W.node[b + e]];
        if (acceleration) accelerated += W.weight[b + e] * (*acceleration)[W.node[b + e]];
      }
      const Mat3 F = (Mat3::Identity() + lane(t.H, l)) * p.F[i];
      const double J = F.determinant();
      if (!(J > 0)) {
        firstInverted = std::min(firstInverted, i);
        continue;
      }
      moveParticle(p, i, moved, F, J, density);
      if (acceleration) {
        p.velocity[i] += dt / 2 * (p.acceleration[i] + accelerated);
        p.acceleration[i] = accelerated;
      } else {
        p.velocity[i] = moved / dt;
      }
      storeStress<Model>(p, i, arrays, sigma, after, l);
    }
  }
  return firstInverted;
}

}  // namespace anode

// Uintah's rf_elastic_plastic (paper Eqs. 25-39): hypoelastic in the unrotated frame of F = RU,
// the swelling rate eta*dc/dt*I subtracted from the rate of deformation, von Mises yield with
// radial return; without a <flow_model> it is linear elastic (no plasticity state is stored).
// Lithium-dependent laws (ours): with <bulk_modulus_lithiated>, <shear_modulus_lithiated> or the
// flow model's <sigma_Y_lithiated>, K, G and sigma_Y are linear in c / c_max between their values
// at c = 0 and at c = c_max. A step's elastic rates take K and G at the step's mid-point c (c at
// its end less half its change), its return to the yield surface sigma_Y at its end c; the
// hypoelastic rate form has no stored energy then. Rate-dependent flow (ours): with the flow
// model's <reference_strain_rate>, viscoplasticReturn (docs/quasi-static.md, "Lithium-dependent
// laws and rate-dependent flow").
#pragma once

#include <algorithm>
#include <optional>

#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"
#include "Core/Math/PolarDecomposition.h"
#include "Core/Math/Simd.h"

namespace anode {

class RFElasticPlastic : public ConstitutiveModel {
 public:
  // K and G at c = c_max (<bulk_modulus_lithiated>, <shear_modulus_lithiated>).
  struct LithiatedModuli {
    double K, G;
  };
  RFElasticPlastic(double bulk, double shear, std::optional<FlowModel> flow, double expansion = 0,
                   std::optional<LithiatedModuli> lithiated = {})
      : K_(bulk),
        G_(shear),
        K1_(lithiated ? lithiated->K : bulk),
        G1_(lithiated ? lithiated->G : shear),
        eta_(expansion),
        flow_(flow),
        lithiumDependent_(lithiated.has_value() || (flow && flow->lithiumDependent())) {}
  // `diffusion`: whether concentration exists (then volume_expansion_coeff is required).
  static std::unique_ptr<RFElasticPlastic> fromInput(const PSNode& node, bool diffusion);

  // What the stress update carries from step to step, for one particle (S = double) or a pack of
  // them (S = Pack): R of F = RU (the frame of the hypoelastic update), the plastic strain and
  // its rate (0 for an elastic material); and, read only, c / c_max at the step's end (0 unless
  // the laws depend on lithium).
  template <class S>
  struct State {
    Mat3Of<S> rotation;
    S ep, epdot;
    S c;
  };
  // Every per-particle array the model may declare, in its order: R always, the plastic strain
  // and its rate with a <flow_model>.
  template <class F>
  static void eachStateField(F&& f) {
    f(ParticleField<Mat3>{nullptr, Physics::Mechanics, Mat3::Identity(), OnSplit::Copy});
    f(ParticleField<double>{"p.plasticStrain", Physics::Plasticity, 0.0, OnSplit::Copy});
    f(ParticleField<double>{"p.plasticStrainRate", Physics::Plasticity, 0.0, OnSplit::Copy});
  }
  // The arrays of a particle set declared by initializeState, read and written a lane at a time.
  class StateArrays {
   public:
    // `maxConcentration`: with laws that depend on lithium, the c_max that p.concentration is
    // read over; 0 otherwise.
    StateArrays(ParticleSet& p, bool yields, double maxConcentration);
    void load(State<Pack>& s, int l, size_t i) const {
      setLane(s.rotation, l, rotation_[i]);
      s.ep[l] = ep_ ? ep_[i] : 0.0;
      s.epdot[l] = epdot_ ? epdot_[i] : 0.0;
      s.c[l] = concentration_ ? concentration_[i] * perMax_ : 0.0;
    }
    static void loadUnstrained(State<Pack>& s, int l) {
      setLane(s.rotation, l, Mat3::Identity());
      s.ep[l] = s.epdot[l] = s.c[l] = 0;
    }
    void store(const State<Pack>& s, int l, size_t i) const {
      rotation_[i] = lane(s.rotation, l);
      if (ep_) {
        ep_[i] = s.ep[l];
        epdot_[i] = s.epdot[l];
      }
    }

   private:
    Mat3* rotation_;
    double *ep_ = nullptr, *epdot_ = nullptr;
    const double* concentration_ = nullptr;
    double perMax_ = 0;
  };

  void initializeState(ParticleSet& p) const override;
  StateArrays stateArrays(ParticleSet& p) const {
    return {p, flow_.has_value(), lithiumDependent_ ? maxConcentration_ : 0.0};
  }
  bool swells() const override { return eta_ != 0; }
  double swellingCoefficient() const override { return eta_; }
  double bulkModulus() const override { return std::max(K_, K1_); }
  double shearModulus() const override { return std::max(G_, G1_); }
  double bulkModulusAt(double c) const override { return K_ + (K1_ - K_) * c / maxConcentration_; }
  double shearModulusAt(double c) const override { return G_ + (G1_ - G_) * c / maxConcentration_; }
  void setMaxConcentration(double cmax) override { maxConcentration_ = cmax; }
  bool lithiumDependent() const override { return lithiumDependent_; }
  ConcreteModel concrete() const override;
  const std::vector<double>* plasticStrainRate(const ParticleSet& p) const override {
    return flow_ ? &p.modelArray<double>(1) : nullptr;
  }

  // The radial return's multiplier dgamma of s = s_trial (1 - 2 G dgamma / |s_trial|) in the
  // lanes that yield: the root of |s_trial| - sqrt(2/3) sigma_y(ep + sqrt(2/3) dgamma) - 2 G dgamma
  // by Newton's iteration, each lane's stopping where it converges.
  template <class S>
  S rateIndependentReturn(const S& sNorm, const S& G, const S& ep, const S& yieldShift,
                          const decltype(S(0.0) > S(0.0))& yields) const;
  // The rate-dependent return (ours): the multiplier dgamma of s = s_trial (1 - 2 G dgamma /
  // |s_trial|) whose plastic strain increment sqrt(2/3) dgamma over dt is e0 dt (sigma_e /
  // sigma_y - 1)^m, sigma_e = sqrt(3/2) (|s_trial| - 2 G dgamma) and sigma_y at the new plastic
  // strain: the root of g = |s_trial| - 2 G dgamma - sqrt(2/3) sigma_y (1 + (sqrt(2/3) dgamma /
  // (e0 dt))^(1/m)), which falls from g(0) > 0 (the lane yields) to g(|s_trial| / 2G) < 0.
  // Newton's steps within that bracket, halving it where a step would leave it. As e0 dt grows the
  // root tends to the rate-independent one.
  template <class S>
  S viscoplasticReturn(const S& sNorm, const S& G, const S& ep, const S& yieldShift, double dt,
                       const decltype(S(0.0) > S(0.0))& yields) const;

  // Returns the new lab-frame stress; state.rotation is R of the old F on entry and R of Fnew on
  // return; dc is the concentration change of the step. Each lane of a pack gets the bits of the
  // scalar update (Core/Math/Simd.h).
  template <class S>
  Mat3Of<S> updateStress(const Mat3Of<S>& stress, const Mat3Of<S>& Fnew, const Mat3Of<S>& L,
                         const S& dc, double dt, State<S>& state) const;

 private:
  double K_, G_, K1_, G1_, eta_;
  std::optional<FlowModel> flow_;
  bool lithiumDependent_;
  double maxConcentration_ = 1;
};

template <class S>
Mat3Of<S> RFElasticPlastic::updateStress(const Mat3Of<S>& stress, const Mat3Of<S>& Fnew,
                                         const Mat3Of<S>& L, const S& dc, double dt,
                                         State<S>& state) const {
  using M = Mat3Of<S>;
  const M I = M::Identity();
  S& ep = state.ep;
  S& epdot = state.epdot;
  // Unrotate the rate of deformation and the stress with R of the old F (Eqs. 26-29).
  const M Rold = state.rotation;
  const M D = S(0.5) * (L + L.transpose());
  // Elastic-plus-plastic rate: the swelling rate eta dc/dt on each normal component removed
  // (Eqs. 25, 33, 36); c of this step, not the previous one as in Uintah.
  const M Dbar = Rold.transpose() * D * Rold - S(eta_) * dc / S(dt) * I;
  const M sigmaBar = Rold.transpose() * stress * Rold;

  // The moduli at the step's mid-point c, sigma_Y's shift at its end c (lithium-dependent laws).
  S K(K_), G(G_), yieldShift(0.0);
  if (lithiumDependent_) {
    const S middle = state.c - S(0.5 / maxConcentration_) * dc;
    K = S(K_) + S(K1_ - K_) * middle;
    G = S(G_) + S(G1_ - G_) * middle;
    if (flow_) yieldShift = flow_->lithiumShift(state.c);
  }
  // Hypoelastic trial (Eqs. 31, 37-38): deviatoric and volumetric parts separately.
  const S trD = Dbar.trace();
  const M Ddev = Dbar - trD / S(3.0) * I;
  const S mean = sigmaBar.trace() / S(3.0);
  M s = sigmaBar - mean * I + S(2.0 * dt) * G * Ddev;

  if (flow_) {
    // Radial return to the von Mises surface (Eqs. 34-35), in the lanes that yield.
    const S sNorm = frobeniusNorm(s);
    const double sqrt23 = std::sqrt(2.0 / 3.0);
    const auto yields = S(std::sqrt(1.5)) * sNorm > flow_->flowStress(ep) + yieldShift;
    epdot = S(0.0);
    if (anyOf(yields)) {
      const S dgamma = flow_->rateDependent()
                           ? viscoplasticReturn(sNorm, G, ep, yieldShift, dt, yields)
                           : rateIndependentReturn(sNorm, G, ep, yieldShift, yields);
      const S scale = S(1.0) - S(2.0) * G * dgamma / sNorm;
      for (int k = 0; k < 9; ++k) s(k) = select(yields, s(k) * scale, s(k));
      ep = select(yields, ep + S(sqrt23) * dgamma, ep);
      epdot = select(yields, S(sqrt23) * dgamma / S(dt), S(0.0));
    }
  }
  // default_hypo equation of state: p_{n+1} = p_n + K tr(D) dt (Eq. 38, volumetric part).
  const M sigmaBarNew = s + (mean + K * trD * S(dt)) * I;
  // Rotate back with R of the new F (Eq. 39).
  state.rotation = rotationOf(Fnew);
  return state.rotation * sigmaBarNew * state.rotation.transpose();
}

template <class S>
S RFElasticPlastic::rateIndependentReturn(const S& sNorm, const S& G, const S& ep,
                                          const S& yieldShift,
                                          const decltype(S(0.0) > S(0.0))& yields) const {
  const double sqrt23 = std::sqrt(2.0 / 3.0);
  S dgamma(0.0);
  auto iterating = yields;
  for (int iter = 0; iter < 50; ++iter) {
    const S e = ep + S(sqrt23) * dgamma;
    const S g = sNorm - S(sqrt23) * (flow_->flowStress(e) + yieldShift) - S(2.0) * G * dgamma;
    const S dg = S(-2.0 / 3.0) * flow_->hardeningModulus(e) - S(2.0) * G;
    const S step = g / dg;
    dgamma = select(iterating, dgamma - step, dgamma);
    iterating = iterating && !(absOf(step) <= S(1e-15) * sNorm / G);
    if (!anyOf(iterating)) break;
  }
  return maxOf(dgamma, S(0.0));
}

template <class S>
S RFElasticPlastic::viscoplasticReturn(const S& sNorm, const S& G, const S& ep, const S& yieldShift,
                                       double dt, const decltype(S(0.0) > S(0.0))& yields) const {
  const double sqrt23 = std::sqrt(2.0 / 3.0);
  const double perRate = sqrt23 / (flow_->referenceRate * dt), power = 1 / flow_->rateExponent;
  S lo(0.0), hi = sNorm / (S(2.0) * G);
  S dgamma = S(0.5) * hi;
  auto iterating = yields;
  for (int iter = 0; iter < 200; ++iter) {
    const S e = ep + S(sqrt23) * dgamma;
    const S sigmaY = flow_->flowStress(e) + yieldShift;
    const S over = powOf(S(perRate) * dgamma, power);
    const S g = sNorm - S(2.0) * G * dgamma - S(sqrt23) * sigmaY * (S(1.0) + over);
    // The bracket keeps the root: g > 0 below it, g < 0 above.
    lo = select(iterating && g > S(0.0), dgamma, lo);
    hi = select(iterating && !(g > S(0.0)), dgamma, hi);
    const S slope =
        S(-2.0) * G - S(sqrt23) * (S(sqrt23) * flow_->hardeningModulus(e) * (S(1.0) + over) +
                                   sigmaY * S(power) * over / maxOf(dgamma, S(1e-300)));
    S next = dgamma - g / slope;
    next = select(next > lo && next < hi, next, S(0.5) * (lo + hi));
    const S step = absOf(next - dgamma);
    dgamma = select(iterating, next, dgamma);
    iterating = iterating && !(step <= S(1e-15) * sNorm / G);
    if (!anyOf(iterating)) break;
  }
  return dgamma;
}

}  // namespace anode

// Uintah's rf_elastic_plastic (paper Eqs. 25-39): hypoelastic in the unrotated frame of F = RU,
// the swelling rate eta*dc/dt*I subtracted from the rate of deformation, von Mises yield with
// radial return; without a <flow_model> it is linear elastic (no plasticity state is stored).
#pragma once

#include <optional>

#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"
#include "Core/Math/PolarDecomposition.h"
#include "Core/Math/Simd.h"

namespace anode {

class RFElasticPlastic : public ConstitutiveModel {
 public:
  RFElasticPlastic(double bulk, double shear, std::optional<FlowModel> flow, double expansion = 0)
      : K_(bulk), G_(shear), eta_(expansion), flow_(flow) {}
  // `diffusion`: whether concentration exists (then volume_expansion_coeff is required).
  static std::unique_ptr<RFElasticPlastic> fromInput(const PSNode& node, bool diffusion);

  // What the stress update carries from step to step, for one particle (S = double) or a pack of
  // them (S = Pack): R of F = RU (the frame of the hypoelastic update), the plastic strain and
  // its rate (0 for an elastic material).
  template <class S>
  struct State {
    Mat3Of<S> rotation;
    S ep, epdot;
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
    StateArrays(ParticleSet& p, bool yields);
    void load(State<Pack>& s, int l, size_t i) const {
      setLane(s.rotation, l, rotation_[i]);
      s.ep[l] = ep_ ? ep_[i] : 0.0;
      s.epdot[l] = epdot_ ? epdot_[i] : 0.0;
    }
    static void loadUnstrained(State<Pack>& s, int l) {
      setLane(s.rotation, l, Mat3::Identity());
      s.ep[l] = s.epdot[l] = 0;
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
  };

  void initializeState(ParticleSet& p) const override;
  StateArrays stateArrays(ParticleSet& p) const { return {p, flow_.has_value()}; }
  bool swells() const override { return eta_ != 0; }
  double swellingCoefficient() const override { return eta_; }
  double bulkModulus() const override { return K_; }
  double shearModulus() const override { return G_; }
  ConcreteModel concrete() const override;
  const std::vector<double>* plasticStrainRate(const ParticleSet& p) const override {
    return flow_ ? &p.modelArray<double>(1) : nullptr;
  }

  // Returns the new lab-frame stress; state.rotation is R of the old F on entry and R of Fnew on
  // return; dc is the concentration change of the step. Each lane of a pack gets the bits of the
  // scalar update (Core/Math/Simd.h).
  template <class S>
  Mat3Of<S> updateStress(const Mat3Of<S>& stress, const Mat3Of<S>& Fnew, const Mat3Of<S>& L,
                         const S& dc, double dt, State<S>& state) const;

 private:
  double K_, G_, eta_;
  std::optional<FlowModel> flow_;
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

  // Hypoelastic trial (Eqs. 31, 37-38): deviatoric and volumetric parts separately.
  const S trD = Dbar.trace();
  const M Ddev = Dbar - trD / S(3.0) * I;
  const S mean = sigmaBar.trace() / S(3.0);
  M s = sigmaBar - mean * I + S(2.0 * G_ * dt) * Ddev;

  if (flow_) {
    // Radial return to the von Mises surface (Eqs. 34-35), in the lanes that yield; each lane's
    // Newton iteration stops where it converges.
    const S sNorm = frobeniusNorm(s);
    const double sqrt23 = std::sqrt(2.0 / 3.0);
    const auto yields = S(std::sqrt(1.5)) * sNorm > flow_->flowStress(ep);
    epdot = S(0.0);
    if (anyOf(yields)) {
      S dgamma(0.0);
      auto iterating = yields;
      for (int iter = 0; iter < 50; ++iter) {
        const S e = ep + S(sqrt23) * dgamma;
        const S g = sNorm - S(sqrt23) * flow_->flowStress(e) - S(2.0 * G_) * dgamma;
        const S dg = S(-2.0 / 3.0) * flow_->hardeningModulus(e) - S(2.0 * G_);
        const S step = g / dg;
        dgamma = select(iterating, dgamma - step, dgamma);
        iterating = iterating && !(absOf(step) <= S(1e-15) * sNorm / S(G_));
        if (!anyOf(iterating)) break;
      }
      dgamma = maxOf(dgamma, S(0.0));
      const S scale = S(1.0) - S(2.0 * G_) * dgamma / sNorm;
      for (int k = 0; k < 9; ++k) s(k) = select(yields, s(k) * scale, s(k));
      ep = select(yields, ep + S(sqrt23) * dgamma, ep);
      epdot = select(yields, S(sqrt23) * dgamma / S(dt), S(0.0));
    }
  }
  // default_hypo equation of state: p_{n+1} = p_n + K tr(D) dt (Eq. 38, volumetric part).
  const M sigmaBarNew = s + (mean + S(K_) * trD * S(dt)) * I;
  // Rotate back with R of the new F (Eq. 39).
  state.rotation = rotationOf(Fnew);
  return state.rotation * sigmaBarNew * state.rotation.transpose();
}

}  // namespace anode

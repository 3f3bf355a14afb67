// Uintah's comp_neo_hook (UCNH without plasticity or damage): compressible neo-Hookean
// hyperelasticity, sigma = K/2 (J - 1/J) I + G J^(-5/3) dev(F F^T), with this code's swelling:
// F = Fe Fs, Fs = exp(theta) I, theta = eta (c - c0) (the swelling of rf_elastic_plastic, eta dc/dt
// on each normal rate, integrated exactly), and the stress of Fe. Path-independent: the stress
// follows from F and c alone, so free swelling is stress-free to round-off at any stretch and
// closed forms hold at finite strain (docs/verification.md, "Neo-Hookean swelling").
#pragma once

#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Core/Math/Simd.h"

namespace anode {

class CompNeoHookean : public ConstitutiveModel {
 public:
  CompNeoHookean(double bulk, double shear, double expansion = 0)
      : K_(bulk), G_(shear), eta_(expansion) {}
  // `diffusion`: whether concentration exists (then volume_expansion_coeff is required).
  static std::unique_ptr<CompNeoHookean> fromInput(const PSNode& node, bool diffusion);

  // What the stress update carries from step to step: theta, the log of the swelling stretch.
  template <class S>
  struct State {
    S swellingStrain;
  };
  template <class F>
  static void eachStateField(F&& f) {
    f(ParticleField<double>{nullptr, Physics::Mechanics, 0.0, OnSplit::Copy});
  }
  class StateArrays {
   public:
    explicit StateArrays(ParticleSet& p) : theta_(p.modelArray<double>(0).data()) {}
    void load(State<Pack>& s, int l, size_t i) const { s.swellingStrain[l] = theta_[i]; }
    static void loadUnstrained(State<Pack>& s, int l) { s.swellingStrain[l] = 0; }
    void store(const State<Pack>& s, int l, size_t i) const { theta_[i] = s.swellingStrain[l]; }

   private:
    double* theta_;
  };

  void initializeState(ParticleSet& p) const override;
  StateArrays stateArrays(ParticleSet& p) const { return StateArrays(p); }
  bool swells() const override { return eta_ != 0; }
  double swellingCoefficient() const override { return eta_; }
  double bulkModulus() const override { return K_; }
  double shearModulus() const override { return G_; }
  ConcreteModel concrete() const override;

  // The Cauchy stress of Fnew after the concentration change dc (the old stress, L and dt are
  // not needed: the model is hyperelastic).
  template <class S>
  Mat3Of<S> updateStress(const Mat3Of<S>&, const Mat3Of<S>& Fnew, const Mat3Of<S>&, const S& dc,
                         double, State<S>& state) const {
    using M = Mat3Of<S>;
    state.swellingStrain = state.swellingStrain + S(eta_) * dc;
    const M Fe = Fnew * expOf(-state.swellingStrain);
    const S Je = Fe.determinant();
    const M b = Fe * Fe.transpose();
    const M devB = b - b.trace() / S(3.0) * M::Identity();
    return S(0.5 * K_) * (Je - S(1.0) / Je) * M::Identity() + S(G_) * powOf(Je, -5.0 / 3.0) * devB;
  }

 private:
  double K_, G_, eta_;
};

}  // namespace anode

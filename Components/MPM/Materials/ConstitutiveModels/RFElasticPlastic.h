// Uintah's rf_elastic_plastic (paper Eqs. 25-39): hypoelastic in the unrotated frame of F = RU,
// the swelling rate eta*dc/dt*I subtracted from the rate of deformation, von Mises yield with
// radial return; without a <flow_model> it is linear elastic (no plasticity state is stored).
#pragma once

#include <optional>

#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"

namespace anode {

class RFElasticPlastic : public ConstitutiveModel {
 public:
  RFElasticPlastic(double bulk, double shear, std::optional<FlowModel> flow, double expansion = 0)
      : K_(bulk), G_(shear), eta_(expansion), flow_(flow) {}
  // `diffusion`: whether concentration exists (then volume_expansion_coeff is required).
  static std::unique_ptr<RFElasticPlastic> fromInput(const PSNode& node, bool diffusion);

  void initializeState(ParticleSet& p) const override;
  bool swells() const override { return eta_ != 0; }
  double swellingCoefficient() const override { return eta_; }
  double dilatationalModulus() const override { return K_ + 4.0 * G_ / 3.0; }
  bool canYield() const override { return flow_.has_value(); }
  ConcreteConstitutiveModel concrete() const override { return this; }

  // One particle: returns the new lab-frame stress; `rotation` is R of the old F on entry and R
  // of Fnew on return; ep/epdot are the plastic strain and its rate (untouched for an elastic
  // material); dc is the concentration change of the step.
  Mat3 updateStress(const Mat3& stress, Mat3& rotation, const Mat3& Fnew, const Mat3& L, double dc,
                    double dt, double& ep, double& epdot) const;

 private:
  double K_, G_, eta_;
  std::optional<FlowModel> flow_;
};

}  // namespace anode

// Uintah's rf_elastic_plastic, mechanical part (paper Eqs. 26-31, 34-39): hypoelastic in the
// unrotated frame of F = RU, von Mises yield with radial return; without a <flow_model> it is
// linear elastic (no plasticity state is stored).
#pragma once

#include <optional>

#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"

namespace anode {

class RFElasticPlastic : public ConstitutiveModel {
 public:
  RFElasticPlastic(double bulk, double shear, std::optional<FlowModel> flow)
      : K_(bulk), G_(shear), flow_(flow) {}
  static std::unique_ptr<RFElasticPlastic> fromInput(const PSNode& node);

  void initializeState(ParticleSet& p) const override;
  void computeStressTensor(ParticleSet& p, const std::vector<Mat3>& L, const std::vector<Mat3>& Fnew,
                           double dt) const override;
  double dilatationalModulus() const override { return K_ + 4.0 * G_ / 3.0; }
  bool canYield() const override { return flow_.has_value(); }

  // One particle: returns the new lab-frame stress; ep/epdot are the plastic strain and its rate
  // (untouched for an elastic material).
  Mat3 updateStress(const Mat3& stress, const Mat3& Fold, const Mat3& Fnew, const Mat3& L, double dt,
                    double& ep, double& epdot) const;

 private:
  double K_, G_;
  std::optional<FlowModel> flow_;
};

}  // namespace anode

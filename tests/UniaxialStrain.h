// rf_elastic_plastic driven in uniaxial strain (test_constitutive, test_lithium_dependent_laws):
// to the logarithmic strain e in n increments of dt, D dt summing exactly to e.
#pragma once

#include <cmath>

#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"

namespace anode {

struct UniaxialStrainEnd {
  Mat3 stress;
  RFElasticPlastic::State<double> state;
};

inline UniaxialStrainEnd driveUniaxialStrain(const RFElasticPlastic& model, double e, int n,
                                             double dt) {
  UniaxialStrainEnd end{Mat3::Zero(), {Mat3::Identity(), 0, 0, 0}};
  Mat3 F = Mat3::Identity();
  for (int i = 0; i < n; ++i) {
    Mat3 Fnew = F;
    Fnew(0, 0) = std::exp(e * (i + 1) / n);
    Mat3 L = Mat3::Zero();
    L(0, 0) = std::log(Fnew(0, 0) / F(0, 0)) / dt;
    end.stress = model.updateStress(end.stress, Fnew, L, 0.0, dt, end.state);
    F = Fnew;
  }
  return end;
}

}  // namespace anode

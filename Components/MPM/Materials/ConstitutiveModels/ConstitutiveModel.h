// What the step needs to know of a constitutive model. The stress update itself is called on the
// concrete model inside the particle loop: the loop is compiled once per model type listed in
// ConcreteModels.h and dispatched once per material (std::visit), never per particle.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "Components/MPM/ParticleSet.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct ConcreteModel;  // ConcreteModels.h: the model as its own type

class ConstitutiveModel {
 public:
  virtual ~ConstitutiveModel() = default;
  // Declares the per-particle state this model keeps (ParticleSet::declareModelArray) and sets
  // its initial values; creates nothing else.
  virtual void initializeState(ParticleSet& p) const = 0;
  // True if the stress depends on the concentration (swelling).
  virtual bool swells() const = 0;
  // eta: the swelling rate of deformation is eta dc/dt I (0 without swelling), so free swelling
  // from c = 0 to 1 stretches each axis by exp(eta).
  virtual double swellingCoefficient() const = 0;
  // K and G, the <bulk_modulus> and <shear_modulus> the model read; with lithium-dependent laws
  // the largest over c in [0, c_max] (the stable time step's).
  virtual double bulkModulus() const = 0;
  virtual double shearModulus() const = 0;
  // Whether K, G or the flow stress depend on the concentration (the lithium-dependent laws).
  virtual bool lithiumDependent() const { return false; }
  // K and G at concentration c (the same at every c unless the laws depend on lithium).
  virtual double bulkModulusAt(double) const { return bulkModulus(); }
  virtual double shearModulusAt(double) const { return shearModulus(); }
  // The <max_concentration> of the material's diffusion model: the c at which lithium-dependent
  // laws take their lithiated values.
  virtual void setMaxConcentration(double) {}
  // K + 4G/3: the modulus of the dilatational wave speed (paper Eq. 41).
  double dilatationalModulus() const { return bulkModulus() + 4.0 * shearModulus() / 3.0; }
  // The elastic energy per unit current volume that the Cauchy stress sigma stores in isotropic
  // linear elasticity: p^2/(2K) + s:s/(4G), p the mean stress and s the deviator (exact for the
  // small elastic strains of rf_elastic_plastic, first order in the elastic strain for
  // comp_neo_hookean). history.csv's elastic_energy, the quasi-static check's denominator.
  // K and G are the model's (bulkModulus(), shearModulus()), passed in so a loop over particles
  // reads them once.
  static double elasticEnergyDensity(const Mat3& sigma, double K, double G) {
    const double p = sigma.trace() / 3.0;
    // s:s = sigma:sigma - 3 p^2 (no deviator built).
    return p * p / (2.0 * K) + (sigma.squaredNorm() - 3.0 * p * p) / (4.0 * G);
  }
  // The von Mises equivalent stress sqrt(3/2 s:s) of the Cauchy stress sigma, s its deviator.
  static double vonMises(const Mat3& sigma) {
    const double p = sigma.trace() / 3.0;
    return std::sqrt(std::max(0.0, 1.5 * (sigma.squaredNorm() - 3.0 * p * p)));
  }
  // The equivalent plastic strain rate of each particle over its last step (p.plasticStrainRate),
  // null for a model that does not yield.
  virtual const std::vector<double>* plasticStrainRate(const ParticleSet&) const { return nullptr; }
  // This model as its own type, for the particle update (dispatched once per material).
  virtual ConcreteModel concrete() const = 0;
};

// Factory keyed by <constitutive_model type="...">; `diffusion` tells whether concentration exists.
std::unique_ptr<ConstitutiveModel> createConstitutiveModel(const PSNode& node, bool diffusion);

// The tags every model reads alike: <bulk_modulus> K and <shear_modulus> G (> 0), and the
// swelling coefficient eta, <volume_expansion_coeff>, required with diffusion (it has nothing to
// act on without: then inert and 0).
struct ElasticConstants {
  double K, G, eta;
  static ElasticConstants fromInput(const PSNode& node, bool diffusion);
};

}  // namespace anode

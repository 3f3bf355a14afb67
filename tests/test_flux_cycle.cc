// Pins the lithiation/delithiation cycle machinery: do_auto_cycle_bc flips the flux sign when the
// mean concentration of the materials with do_conc_reduction crosses auto_cycle_max /
// auto_cycle_min; a sustained outflow is restricted as c -> 0 (the mirror of Eq. 17), so
// delithiation never drives c below 0.
#include <gtest/gtest.h>
#include <omp.h>

#include <sstream>
#include <string>

#include "Core/Util/Errors.h"
#include "StandAlone/Driver/Simulation.h"

namespace anode {
namespace {

// The slab's material: `extra` tags, its particles in [0, x1] x one cell, concentration c0.
std::string material(const std::string& extra, double x1, double c0) {
  std::ostringstream s;
  s << "<material><density>1e9</density>" << extra
    << "<constitutive_model "
       "type=\"rf_elastic_plastic\"><bulk_modulus>1e6</bulk_modulus><shear_modulus>1e6</"
       "shear_modulus>"
    << "<volume_expansion_coeff>0</volume_expansion_coeff></constitutive_model>"
    << "<diffusion_model "
       "type=\"jg\"><diffusivity>0.1</diffusivity><max_concentration>1</max_concentration></"
       "diffusion_model>"
    << "<geom_object><box><min>[0,0,0]</min><max>[" << x1 << ",0.1,0.1]</max></box>"
    << "<res>[2,1,1]</res><velocity>[0,0,0]</velocity><concentration>" << c0
    << "</concentration></geom_object></material>";
  return s.str();
}

// A slab [0,1] x one cell of `materials`, flux J(t) into x+ (load curve `loads` at times 0 and
// 1e6).
std::string slab(const std::string& mpmExtra, double load0, double load1,
                 const std::string& materials = material("", 1, 0)) {
  std::ostringstream s;
  s << "<Uintah_specification><SimulationComponent type=\"mpm\"/>"
    << "<Time><maxTime>100</maxTime><initTime>0</initTime><delt_min>0</delt_min><delt_max>1e-2</"
       "delt_max>"
    << "<timestep_multiplier>0.4</timestep_multiplier></Time>"
    << "<DataArchiver><filebase>c.uda</filebase><outputTimestepInterval>100000</"
       "outputTimestepInterval></DataArchiver>"
    << "<MPM><interpolator>linear</interpolator><do_scalar_diffusion>true</do_scalar_diffusion>"
    << "<use_load_curves>true</use_load_curves>" << mpmExtra << "</MPM>"
    << "<MaterialProperties><MPM>" << materials << "</MPM></MaterialProperties>"
    << "<PhysicalBC><MPM><scalar_flux><geom_object><box><min>[0.99,0,0]</min><max>[1.01,0.1,0.1]</"
       "max></box></geom_object>"
    << "<load_curve><id>1</id><time_point><time>0</time><load>" << load0 << "</load></time_point>"
    << "<time_point><time>1e6</time><load>" << load1
    << "</load></time_point></load_curve></scalar_flux></MPM></PhysicalBC>"
    << "<Grid><Level><Box><lower>[0,0,0]</lower><upper>[1,0.1,0.1]</upper><resolution>[10,1,1]</"
       "resolution>"
    << "<extraCells>[0,0,0]</extraCells></Box></Level><BoundaryConditions>"
    << "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
    << "<Face side=\"x+\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
    << "</BoundaryConditions></Grid></Uintah_specification>";
  return s.str();
}

const char* kAutoCycle =
    "<do_auto_cycle_bc>true</do_auto_cycle_bc><auto_cycle_max>0.3</auto_cycle_max>"
    "<auto_cycle_min>0.1</auto_cycle_min>";

double meanConcentration(Simulation& sim, size_t material = 0) {
  const ParticleSet& p = sim.mpm().materials()[material].particles;
  double sum = 0;
  for (double c : diffusionParticles(p).concentration) sum += c;
  return sum / p.count();
}

RunOptions quiet() {
  omp_set_num_threads(1);
  RunOptions o;
  o.progress = false;
  return o;
}

TEST(FluxCycle, AutoCycleFlipsAtTheMeanThresholds) {
  Simulation sim(
      slab(kAutoCycle, 0.05, 0.05, material("<do_conc_reduction>true</do_conc_reduction>", 1, 0)),
      "cycle.ups", quiet());
  // Lithiate until the mean passes 0.3, then delithiate until it falls below 0.1, then again.
  double peak = 0, trough = 1;
  int phase = 0;  // 0: rising, 1: falling, 2: rising again
  double previous = 0;
  while (phase < 2 && sim.step() < 200000) {
    sim.advance();
    const double mean = meanConcentration(sim);
    if (phase == 0 && mean < previous) phase = 1;
    if (phase == 1 && mean > previous) phase = 2;
    if (phase == 0) peak = std::max(peak, mean);
    if (phase == 1) trough = std::min(trough, mean);
    previous = mean;
  }
  ASSERT_EQ(phase, 2) << "the flux must reverse twice";
  EXPECT_GT(peak, 0.3);
  EXPECT_LT(peak, 0.3 + 0.01);  // flips within a step or two of crossing
  EXPECT_LT(trough, 0.1);
  EXPECT_GT(trough, 0.1 - 0.01);
}

// Uintah's cycle watches the materials with <do_conc_reduction>, whether or not they receive flux.
TEST(FluxCycle, AutoCycleWatchesTheMaterialsWithConcentrationReduction) {
  // The slab receives the flux; the watched second block (x < 0.2, no flux, no interface) stays
  // at c = 0, so the flux never reverses and the slab fills past auto_cycle_max.
  Simulation sim(
      slab(kAutoCycle, 0.05, 0.05,
           material("", 1, 0) + material("<do_conc_reduction>true</do_conc_reduction>", 0.2, 0)),
      "watched.ups", quiet());
  double previous = 0;
  while (meanConcentration(sim) < 0.4 && sim.step() < 200000) {
    sim.advance();
    ASSERT_GE(meanConcentration(sim), previous) << "the flux reversed at step " << sim.step();
    previous = meanConcentration(sim);
    ASSERT_EQ(meanConcentration(sim, 1), 0.0);
  }
  EXPECT_GE(meanConcentration(sim), 0.4);
}

TEST(FluxCycle, AutoCycleWithoutConcentrationReductionIsAnInputError) {
  // Uintah never reverses the flux then: the input asks for a cycle it would not run.
  try {
    Simulation sim(slab(kAutoCycle, 0.05, 0.05), "unwatched.ups", quiet());
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("do_conc_reduction"), std::string::npos) << e.what();
  }
}

TEST(FluxCycle, OutflowIsRestrictedAsConcentrationVanishes) {
  // Start full (c = 0.5 everywhere) and extract for a long time: lithium falls monotonically and
  // the face particle approaches the restriction's zero c = e^-4 from above, never below 0.
  Simulation sim(slab("", -0.05, -0.05, material("", 1, 0.5)), "outflow.ups", quiet());
  double lithium = 1e300;
  while (sim.time() < 60) {
    sim.advance();
    const StepSummary s = sim.mpm().summarize(Communicator::everyRank());
    EXPECT_LE(s.totalLithium, lithium);
    lithium = s.totalLithium;
    ASSERT_GE(s.minConcentration, 0.0);
  }
  const StepSummary s = sim.mpm().summarize(Communicator::everyRank());
  EXPECT_LT(s.minConcentration, 0.05) << "the surface is nearly drained";
  EXPECT_GT(s.minConcentration, std::exp(-4.0) * 0.5) << "extraction stops near c = e^-4";
}

}  // namespace
}  // namespace anode

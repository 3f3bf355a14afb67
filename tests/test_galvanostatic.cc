// Pins <scalar_flux><mode>galvanostatic: the lithium entering equals the prescribed rate times
// the time to round-off while the flagged surface can take it, and the current ends (nothing
// more enters) once the surface's mean restriction reaches <cutoff>; the state of charge follows.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/Util/Errors.h"
#include "StandAlone/Driver/Simulation.h"
#include "tests/TestFiles.h"

namespace anode {
namespace {

RunOptions quiet() {
  omp_set_num_threads(1);
  RunOptions o;
  o.progress = false;
  return o;
}

std::string readInput(const std::string& path) {
  return testing::readFile(std::string(ANODE_SOURCE_DIR) + "/" + path);
}

// `text` with every <scalar_flux> galvanostatic, its loads replaced by `rate` (the input's
// loads are constant in time), and `extra` tags in each block.
std::string galvanostatic(std::string text, const std::string& rate,
                          const std::string& extra = "") {
  text = std::regex_replace(text, std::regex("<load>[^<]*</load>"), "<load>" + rate + "</load>");
  return std::regex_replace(text, std::regex("<scalar_flux>"),
                            "<scalar_flux><mode>galvanostatic</mode>" + extra);
}

double totalLithium(Simulation& sim) {
  return sim.mpm().summarize(Communicator::everyRank()).totalLithium;
}

bool anyFluxRate(Simulation& sim) {
  for (const MPMMaterial& mat : sim.mpm().materials()) {
    const ConstDiffusionParticles d(mat.particles);
    for (double rate : d.externalScalarFlux)
      if (rate != 0) return true;
  }
  return false;
}

// Runs until the current ends or `maxSteps`; returns the largest |L - L0 - Q t| / (Q t) on the
// way, and leaves the simulation where the current ended.
double worstUptakeError(Simulation& sim, double rate, long maxSteps) {
  const double start = totalLithium(sim), t0 = sim.time();
  double worst = 0;
  while (anyFluxRate(sim) && sim.step() < maxSteps) {
    sim.advance();
    const double expected = rate * (sim.time() - t0);
    worst = std::max(worst, std::abs(totalLithium(sim) - start - expected) / expected);
  }
  return worst;
}

// The octant of a silicon nanosphere (its whole curved surface under one BC; 20^3 cells), at
// ten times the lithium rate a flux of 1e-8 m/s gives at the start (rho J A = 4.575e10 pg/us).
TEST(Galvanostatic, SphereTakesUpRateTimesTimeThenStopsAtTheCutoff) {
  std::string text =
      galvanostatic(readInput("inputs/Particles/SiliconSphereOctant.ups"), "4.575e11");
  text = std::regex_replace(text, std::regex("\\[40, 40, 40\\]"), "[20, 20, 20]");
  Simulation sim(text, "sphere.ups", quiet());
  const double rate = 4.575e11;
  EXPECT_LT(worstUptakeError(sim, rate, 100000), 1e-9);
  ASSERT_FALSE(anyFluxRate(sim)) << "the current did not end by step " << sim.step();
  // The cutoff: the flagged particles' mean restriction reached 0.25, so the surface is nearly
  // full (R = 0.25 at c = 0.950) while the inside is not.
  const StepSummary atEnd = sim.mpm().summarize(Communicator::everyRank());
  EXPECT_GT(atEnd.maxConcentration, 0.95);
  const double charge = atEnd.chargeableLithium / atEnd.lithiumCapacity;
  EXPECT_GT(charge, 0.05);
  EXPECT_LT(charge, 0.9);
  // From then on nothing enters: the lithium stays (diffusion moves it inside).
  for (int i = 0; i < 50; ++i) sim.advance();
  EXPECT_NEAR(totalLithium(sim), atEnd.totalLithium, 1e-12 * atEnd.totalLithium);
}

// Two turns on the sphere: charge at the rate above until 2e5 us, discharge until 4e5, charge
// again. Each half-cycle's cutoff ends its current (the surface nearly full on charge, nearly
// empty on discharge, where R(1 - c) restricts), and the next segment of the load curve resumes it.
TEST(Galvanostatic, CutoffEndsEachHalfCycleAndTheNextSegmentResumesIt) {
  const double rate = 4.575e11;
  std::string points;
  for (const auto& [time, load] : {std::pair{0.0, rate},
                                   {2e5, rate},
                                   {2.01e5, -rate},
                                   {4e5, -rate},
                                   {4.01e5, rate},
                                   {6e5, rate}})
    points += "<time_point><time>" + std::to_string(time) + "</time><load>" + std::to_string(load) +
              "</load></time_point>";
  std::string text = galvanostatic(readInput("inputs/Particles/SiliconSphereOctant.ups"), "0");
  text = std::regex_replace(text, std::regex("<load_curve><id>1</id>.*</load_curve>"),
                            "<load_curve><id>1</id>" + points + "</load_curve>");
  text = std::regex_replace(text, std::regex("\\[40, 40, 40\\]"), "[20, 20, 20]");
  Simulation sim(text, "sphere.ups", quiet());
  // Near each segment's end: the lithium, and whether the current had ended by then.
  std::vector<double> lithium;
  std::vector<bool> ended;
  std::string notes;
  for (double end : {1.95e5, 3.95e5, 4.9e5}) {
    while (sim.time() < end) {
      sim.advance();
      for (const std::string& note : sim.mpm().diffusion()->takeRunNotes()) notes += note + "\n";
    }
    lithium.push_back(totalLithium(sim));
    ended.push_back(!anyFluxRate(sim));
  }
  EXPECT_EQ(ended, std::vector<bool>({true, true, true})) << notes;
  EXPECT_LT(lithium[1], 0.5 * lithium[0]);
  EXPECT_GT(lithium[2], 2 * lithium[1]);
  // The notes, in this order.
  size_t at = 0;
  for (const char* note :
       {"(the surface is nearly full), until its load curve's next segment at t = 200000\n",
        "its current resumes at t = 20",
        "(the surface is nearly empty), until its load curve's "
        "next segment at t = 400000\n",
        "its current resumes at t = 40",
        "(the surface is nearly full), until its load curve's next segment at t = 600000\n"}) {
    at = notes.find(note, at);
    ASSERT_NE(at, std::string::npos) << "no \"" << note << "\" in order in:\n" << notes;
  }
}

// A C-rate load: n C is n times the sphere's lithium at max_concentration (sum m c_max) per
// hour, an hour being <hour> in the input's time unit.
TEST(Galvanostatic, CRateIsTheCapacityPerHour) {
  std::string text = galvanostatic(readInput("inputs/Particles/SiliconSphereOctant.ups"), "2",
                                   "<rate_unit>C</rate_unit><hour>3.6e9</hour>");
  text = std::regex_replace(text, std::regex("\\[40, 40, 40\\]"), "[20, 20, 20]");
  Simulation sim(text, "sphere.ups", quiet());
  const MPMMaterial& silicon = sim.mpm().materials()[0];
  double capacity = 0;
  for (size_t i = 0; i < silicon.particles.count(); ++i)
    capacity += silicon.particles.mass[i] * sim.mpm().diffusion()->model(0).maxConcentration;
  EXPECT_LT(worstUptakeError(sim, 2 * capacity / 3.6e9, 30), 1e-9);
  EXPECT_EQ(sim.step(), 30) << "the current ended early";
}

// <mode>potentiostatic on the sphere's curved surface, c_s = 0.8 through k = 1e-6 (100 times
// the input's flux at c_s - c = 1): the lithium rises every step, no particle passes c_s or falls
// below 0 (by more than round-off), and the surface comes near c_s (0.787 at 2e6 us, 717 steps).
TEST(Potentiostatic, SphereSurfaceApproachesTheHeldConcentration) {
  std::string text = readInput("inputs/Particles/SiliconSphereOctant.ups");
  text = std::regex_replace(text, std::regex("<load>[^<]*</load>"), "<load>0.8</load>");
  text = std::regex_replace(
      text, std::regex("<scalar_flux>"),
      "<scalar_flux><mode>potentiostatic</mode><surface_rate>1e-6</surface_rate>");
  text = std::regex_replace(text, std::regex("\\[40, 40, 40\\]"), "[20, 20, 20]");
  Simulation sim(text, "sphere.ups", quiet());
  double lithium = totalLithium(sim);
  while (sim.time() < sim.timeControl().maxTime) {
    sim.advance();
    const StepSummary s = sim.mpm().summarize(Communicator::everyRank());
    ASSERT_GT(s.totalLithium, lithium) << "step " << sim.step();
    ASSERT_LE(s.maxConcentration, 0.8) << "step " << sim.step();
    ASSERT_GE(s.minConcentration, -1e-15) << "step " << sim.step();  // round-off: -6e-19
    lithium = s.totalLithium;
  }
  EXPECT_GT(sim.mpm().summarize(Communicator::everyRank()).maxConcentration, 0.75);
}

// The CPDI pillar, side and top each under its own galvanostatic BC (corner particles take
// both): the uptake is the two rates together.
TEST(Galvanostatic, PillarTakesUpTheSumOfItsBCsRates) {
  // Side 3e9, top 1e9 lithium per us (the top's block is the last).
  const std::string text = readInput("inputs/Pillar/PillarLithiation.ups");
  const size_t top = text.find("<id>2</id>");
  ASSERT_NE(top, std::string::npos);
  const std::string both =
      galvanostatic(text.substr(0, top), "3e9") +
      std::regex_replace(text.substr(top), std::regex("<load>[^<]*</load>"), "<load>1e9</load>");
  Simulation sim(both, "pillar.ups", quiet());
  EXPECT_LT(worstUptakeError(sim, 4e9, 300), 1e-9);
  EXPECT_EQ(sim.step(), 300) << "the current ended early";
}

// The 2x2 pillar array under one <surface> BC for every pillar's free surface: the four take up
// the rate in all.
TEST(Galvanostatic, ArrayUnderOneSurfaceBCTakesUpTheRate) {
  std::string text = readInput("inputs/Pillar/PillarArray.ups");
  const size_t a = text.find("<PhysicalBC>"), b = text.find("</PhysicalBC>");
  text = text.substr(0, a) +
         "<PhysicalBC><MPM><scalar_flux><mode>galvanostatic</mode>"
         "<surface material=\"silicon\" exclude=\"substrate\"/><load_curve><id>1</id>"
         "<time_point><time>0</time><load>5.15e12</load></time_point></load_curve></scalar_flux>"
         "</MPM>" +
         text.substr(b);
  omp_set_num_threads(2);
  RunOptions o;
  o.progress = false;
  Simulation sim(text, "array.ups", o);
  EXPECT_LT(worstUptakeError(sim, 5.15e12, 20), 1e-9);
  EXPECT_EQ(sim.step(), 20) << "the current ended early";
}

// A quasi-static step retaken with a smaller dt starts from the flux state it had: the first try
// (dt 1) filled the slab's face to the cutoff in its diffusion sub-steps, and the current that
// ended there must not stay ended in the retaken steps (it did: no lithium entered at all).
TEST(Galvanostatic, RetakenQuasiStaticStepRestartsTheCurrent) {
  const std::string slab =
      "<Uintah_specification><SimulationComponent type=\"mpm\"/>"
      "<Time><maxTime>100</maxTime><initTime>0</initTime><delt_min>1e-8</delt_min><delt_max>1</"
      "delt_max>"
      "<timestep_multiplier>0.4</timestep_multiplier><max_Timesteps>3</max_Timesteps></Time>"
      "<DataArchiver><filebase>c.uda</filebase><outputTimestepInterval>100000</"
      "outputTimestepInterval></DataArchiver>"
      "<MPM><interpolator>linear</interpolator><do_scalar_diffusion>true</do_scalar_diffusion>"
      "<use_load_curves>true</use_load_curves><time_integrator>implicit</"
      "time_integrator><dynamic>false</dynamic>"
      "<max_concentration_change>0.05</max_concentration_change><error_tolerance>0"
      "</error_tolerance></MPM>"
      "<MaterialProperties><MPM><material><density>1e9</density>"
      "<constitutive_model "
      "type=\"rf_elastic_plastic\"><bulk_modulus>1e6</bulk_modulus><shear_modulus>1e6</"
      "shear_modulus>"
      "<volume_expansion_coeff>0</volume_expansion_coeff></constitutive_model>"
      "<diffusion_model "
      "type=\"jg\"><diffusivity>0.01</diffusivity><max_concentration>1</max_concentration></"
      "diffusion_model>"
      "<geom_object><box><min>[0,0,0]</min><max>[1,0.1,0.1]</max></box><res>[2,1,1]</"
      "res><velocity>[0,0,0]</velocity><concentration>0</concentration></geom_object></material></"
      "MPM></MaterialProperties>"
      "<PhysicalBC><MPM><scalar_flux><mode>galvanostatic</mode><geom_object><box><min>[0.99,0,0]</"
      "min><max>[1.01,0.1,0.1]</max></box></geom_object>"
      "<load_curve><id>1</id><time_point><time>0</time><load>1e7</load></time_point></load_curve></"
      "scalar_flux></MPM></PhysicalBC>"
      "<Grid><Level><Box><lower>[0,0,0]</lower><upper>[1,0.1,0.1]</upper><resolution>[10,1,1]</"
      "resolution>"
      "<extraCells>[0,0,0]</extraCells></Box></Level><BoundaryConditions>"
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"x+\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"y-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"y+\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"z-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"z+\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "</BoundaryConditions></Grid></Uintah_specification>";
  Simulation sim(slab, "slab.ups", quiet());
  EXPECT_LT(worstUptakeError(sim, 1e7, 3), 1e-9);
  EXPECT_EQ(sim.step(), 3);
  EXPECT_GE(sim.implicitStep().newtonCounts().retakes, 1);
}

TEST(Galvanostatic, UnknownModeUnitAndMisplacedTagsAreInputErrors) {
  const std::string text = readInput("inputs/Particles/SiliconSphereOctant.ups");
  for (const auto& [edited, message] :
       {std::pair{std::regex_replace(text, std::regex("<scalar_flux>"),
                                     "<scalar_flux><mode>galvanostatc</mode>"),
                  "<mode> must be flux"},
        {std::regex_replace(text, std::regex("<scalar_flux>"), "<scalar_flux><cutoff>0.1</cutoff>"),
         "<cutoff> belongs to <mode>galvanostatic</mode>"},
        {galvanostatic(text, "1e10", "<cutoff>1</cutoff>"), "must lie in (0, 1)"},
        {std::regex_replace(text, std::regex("<scalar_flux>"),
                            "<scalar_flux><rate_unit>C</rate_unit><hour>3.6e9</hour>"),
         "<rate_unit> belongs to <mode>galvanostatic</mode>"},
        {galvanostatic(text, "1", "<rate_unit>C</rate_unit>"), "needs <hour>"},
        {galvanostatic(text, "1", "<rate_unit>C</rate_unit><hour>-1</hour>"),
         "<hour> must be above 0"},
        {galvanostatic(text, "1", "<hour>3.6e9</hour>"),
         "<hour> belongs to <rate_unit>C</rate_unit>"},
        {galvanostatic(text, "1", "<rate_unit>mA</rate_unit>"), "<rate_unit> must be"},
        {std::regex_replace(text, std::regex("<scalar_flux>"),
                            "<scalar_flux><mode>potentiostatic</mode>"),
         "needs <surface_rate>"},
        {std::regex_replace(text, std::regex("<scalar_flux>"),
                            "<scalar_flux><surface_rate>1</surface_rate>"),
         "<surface_rate> belongs to <mode>potentiostatic</mode>"},
        {std::regex_replace(
             std::regex_replace(text, std::regex("<load>[^<]*</load>"), "<load>1.5</load>"),
             std::regex("<scalar_flux>"),
             "<scalar_flux><mode>potentiostatic</mode><surface_rate>1</surface_rate>"),
         "outside [min_concentration, max_concentration]"}}) {
    try {
      Simulation sim(edited, "bad.ups", quiet());
      ADD_FAILURE() << "expected an InputError: " << message;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace anode

// Pins the pillar on a substrate (issue 4, paper §4.6): two materials bonded by single_velocity
// contact; the substrate (diffusivity 0) receives no lithium even where a flux BC covers its
// surface, the pillar does, and the bonded interface moves as one.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "Core/Util/Errors.h"
#include "StandAlone/Driver/Simulation.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

// `saves`: <save> tags; `materialsExtra`: tags after the materials (an interface); `faces`: more
// <Face> blocks; `pillarConcentration`: the pillar's initial c (the substrate's is 0).
std::string pillarOnSubstrate(const std::string& saves = "", const std::string& materialsExtra = "",
                              const std::string& faces = "",
                              const std::string& pillarConcentration = "0") {
  auto material = [](const char* name, double K, double D0, const char* geom,
                     const std::string& c0) {
    std::ostringstream s;
    s << "<material name=\"" << name << "\"><density>2.33e21</density>"
      << "<constitutive_model type=\"rf_elastic_plastic\"><bulk_modulus>" << K << "</bulk_modulus>"
      << "<shear_modulus>31e6</shear_modulus><volume_expansion_coeff>0.56</"
         "volume_expansion_coeff></constitutive_model>"
      << "<diffusion_model type=\"jg\"><diffusivity>" << D0
      << "</diffusivity><max_concentration>1</max_concentration>"
      << "</diffusion_model><geom_object>" << geom
      << "<res>[2,2,2]</res><velocity>[0,0,0]</velocity>"
      << "<concentration>" << c0 << "</concentration></geom_object></material>";
    return s.str();
  };
  std::ostringstream s;
  s << "<Uintah_specification><SimulationComponent type=\"mpm\"/>"
    << "<Time><maxTime>1e12</maxTime><initTime>0</initTime><delt_min>0</delt_min><delt_max>1e12</"
       "delt_max>"
    << "<timestep_multiplier>0.2</timestep_multiplier><max_Timesteps>40</max_Timesteps></Time>"
    << "<DataArchiver><filebase>s.uda</filebase><outputTimestepInterval>1000</"
       "outputTimestepInterval>"
    << saves << "</DataArchiver>"
    << "<MPM><interpolator>cpdi</interpolator><do_scalar_diffusion>true</do_scalar_diffusion>"
    << "<use_load_curves>true</use_load_curves></MPM>"
    << "<MaterialProperties><MPM>"
    << material("pillar", 67e6, 1e-7,
                "<cylinder><bottom>[0,0,0.04]</bottom><top>[0,0,0.1]</top><radius>0.03</radius></"
                "cylinder>",
                pillarConcentration)
    << material("substrate", 180e6, 0.0,
                "<box><min>[-0.08,-0.08,0]</min><max>[0.08,0.08,0.04]</max></box>", "0")
    << materialsExtra
    << "<contact><type>single_velocity</type><materials>[0,1]</materials></contact></MPM></"
       "MaterialProperties>"
    // A flux on every face at z near 0.04..0.1 and on the whole side: it covers the substrate's
    // top surface around the pillar too.
    << "<PhysicalBC><MPM><scalar_flux><geom_object><box><min>[-0.1,-0.1,0.035]</"
       "min><max>[0.1,0.1,0.045]</max></box>"
    << "</geom_object><load_curve><id>1</id><time_point><time>0</time><load>1e-6</load></"
       "time_point></load_curve></scalar_flux>"
    << "<scalar_flux><geom_object><cylinder><bottom>[0,0,0.04]</bottom><top>[0,0,0.1]</"
       "top><radius>0.03</radius></cylinder>"
    << "</geom_object><load_curve><id>2</id><time_point><time>0</time><load>1e-6</load></"
       "time_point></load_curve></scalar_flux>"
    << "</MPM></PhysicalBC>"
    << "<Grid><Level><Box><lower>[-0.1,-0.1,0]</lower><upper>[0.1,0.1,0.15]</"
       "upper><resolution>[20,20,15]</resolution>"
    << "<extraCells>[1,1,1]</extraCells></Box></Level><BoundaryConditions>"
    << "<Face side=\"z-\"><BCType id=\"all\" label=\"Velocity\" "
       "var=\"Dirichlet\"><value>[0,0,0]</value></BCType></Face>"
    << faces << "</BoundaryConditions></Grid></Uintah_specification>";
  return s.str();
}

TEST(Substrate, BondedSubstrateReceivesNoLithium) {
  omp_set_num_threads(2);
  RunOptions o;
  o.progress = false;
  Simulation sim(pillarOnSubstrate(), "substrate.ups", o);
  const auto& mats = sim.mpm().materials();
  EXPECT_TRUE(diffusionParticles(mats[1].particles).loadCurveID.empty())
      << "no flux BC is assigned to a material without diffusivity";
  while (sim.step() < 40) sim.advance();
  double pillarLithium = 0, substrateMax = 0;
  for (size_t i = 0; i < mats[0].particles.count(); ++i)
    pillarLithium +=
        mats[0].particles.mass[i] * diffusionParticles(mats[0].particles).concentration[i];
  for (double c : diffusionParticles(mats[1].particles).concentration)
    substrateMax = std::max(substrateMax, std::abs(c));
  EXPECT_GT(pillarLithium, 0.0);
  EXPECT_EQ(substrateMax, 0.0);
  // Swelling pushes the bonded interface: both materials share nodal velocities there.
  const auto& g = sim.mpm().stepGrid().fields;
  int shared = 0;
  for (size_t n = 0; n < g[0].mass.size(); ++n)
    if (g[0].mass[n] > 0 && g[1].mass[n] > 0) {
      EXPECT_EQ(g[0].velocityStar[n], g[1].velocityStar[n]);
      ++shared;
    }
  EXPECT_GT(shared, 0);
}

// A pillar sunk 0.02 into its substrate: setup warns, naming both materials, and the overlap's
// volume (the pillar's 0.02 below the substrate's top, pi r^2 h on the particle lattice) from
// each side.
TEST(Substrate, OverlappingMaterialsAreAWarning) {
  RunOptions o;
  o.progress = false;
  Simulation apart(pillarOnSubstrate(), "apart.ups", o);
  for (const std::string& w : apart.warnings())
    EXPECT_EQ(w.find("overlaps"), std::string::npos) << w;
  std::string text = pillarOnSubstrate();
  const std::string bottom = "<bottom>[0,0,0.04]</bottom>";
  text.replace(text.find(bottom), bottom.size(), "<bottom>[0,0,0.02]</bottom>");
  Simulation sunk(text, "sunk.ups", o);
  std::string warning;
  for (const std::string& w : sunk.warnings())
    if (w.find("overlaps") != std::string::npos) warning = w;
  ASSERT_FALSE(warning.empty());
  EXPECT_NE(warning.find("material 1 (substrate) overlaps material 0 (pillar)"), std::string::npos)
      << warning;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      warning, m,
      std::regex(R"((\d+) of its particles \(volume (\S+)\).* (\d+) of .*\(volume (\S+)\))")))
      << warning;
  EXPECT_EQ(m[1], m[3]) << "the same lattice places both materials' particles alike";
  const double cylinder = M_PI * 0.03 * 0.03 * 0.02;
  EXPECT_NEAR(std::stod(m[2]), cylinder, 0.05 * cylinder) << warning;
  EXPECT_NEAR(std::stod(m[4]), cylinder, 0.05 * cylinder) << warning;
}

// history.csv's min_c, max_c and state of charge are of the pillar, which takes up lithium: the
// substrate's fixed c = 0 pins neither min_c nor the charge.
TEST(Substrate, ConcentrationRangeIsOfTheMaterialsThatTakeUpLithium) {
  omp_set_num_threads(2);
  RunOptions o;
  o.progress = false;
  Simulation sim(pillarOnSubstrate("", "", "", "0.2"), "substrate.ups", o);
  for (int s = 0; s < 5; ++s) sim.advance();
  const std::vector<double>& c =
      diffusionParticles(sim.mpm().materials()[0].particles).concentration;
  const StepSummary summary = sim.mpm().summarize(Communicator::everyRank());
  EXPECT_EQ(summary.minConcentration, *std::min_element(c.begin(), c.end()));
  EXPECT_EQ(summary.maxConcentration, *std::max_element(c.begin(), c.end()));
  EXPECT_GE(summary.minConcentration, 0.2 - 1e-9);
  EXPECT_GT(summary.maxConcentration, 0.2);  // the flux has raised the surface
  // The state of charge is the pillar's too (its max_concentration is 1).
  const ParticleSet& pillar = sim.mpm().materials()[0].particles;
  double lithium = 0, mass = 0;
  for (size_t i = 0; i < pillar.count(); ++i) {
    lithium += pillar.mass[i] * c[i];
    mass += pillar.mass[i];
  }
  EXPECT_NEAR(summary.chargeableLithium / summary.lithiumCapacity, lithium / mass,
              1e-12 * lithium / mass);
}

// With a substrate that diffuses too, history.csv gives each material's lithium and range of c
// (lithium_NAME, min_c_NAME, max_c_NAME), summing to the totals; with a substrate that takes up
// none, no per-material columns (the totals are the pillar's).
TEST(Substrate, HistoryHasColumnsPerMaterialThatTakesUpLithium) {
  omp_set_num_threads(2);
  RunOptions o;
  o.progress = false;
  const auto header = [](const fs::path& dir) {
    std::ifstream in(dir / "history.csv");
    std::string line;
    std::getline(in, line);
    return line;
  };
  const fs::path dir =
      fs::temp_directory_path() / ("anode_substrate_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto inputFile = [&](const std::string& name, const std::string& text) {
    o.input = (dir / (name + ".ups")).string();
    o.outputDir = (dir / name).string();
    std::ofstream(o.input) << text;
  };
  inputFile("dry", pillarOnSubstrate("", "", "", "0.2"));
  Simulation(o).run();
  EXPECT_EQ(header(o.outputDir).find("lithium_pillar"), std::string::npos) << header(o.outputDir);

  std::string text = pillarOnSubstrate("", "", "", "0.2");
  const std::string dry = "<diffusivity>0</diffusivity>";
  ASSERT_NE(text.find(dry), std::string::npos);
  text.replace(text.find(dry), dry.size(), "<diffusivity>1e-7</diffusivity>");
  inputFile("wet", text);
  Simulation wet(o);
  wet.run();
  const std::string columns = header(o.outputDir);
  EXPECT_NE(columns.find(",capacity_mAh_g,lithium_pillar,min_c_pillar,max_c_pillar,"
                         "lithium_substrate,min_c_substrate,max_c_substrate,volume_pillar,"),
            std::string::npos)
      << columns;
  EXPECT_NE(columns.find(",mean_von_mises_substrate,elastic_energy,dt_limit,wall_seconds"),
            std::string::npos)
      << columns;
  std::ifstream in(fs::path(o.outputDir) / "history.csv");
  std::string line, last;
  while (std::getline(in, line)) last = line;
  std::vector<double> row;
  std::stringstream cells(last);
  for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
  ASSERT_EQ(row.size(), 22u + 2 * 9) << last;  // and each material's 9 stress columns
  // Each material's sum and range, as its particles have them at the end (10 digits written).
  for (size_t m = 0; m < 2; ++m) {
    const ParticleSet& p = wet.mpm().materials()[m].particles;
    const std::vector<double>& c = diffusionParticles(p).concentration;
    double lithium = 0;
    for (size_t i = 0; i < p.count(); ++i) lithium += p.mass[i] * c[i];
    EXPECT_NEAR(row[13 + 3 * m], lithium, 1e-9 * lithium) << "material " << m;
    EXPECT_NEAR(row[14 + 3 * m], *std::min_element(c.begin(), c.end()), 1e-9) << m;
    EXPECT_NEAR(row[15 + 3 * m], *std::max_element(c.begin(), c.end()), 1e-9) << m;
  }
  EXPECT_NEAR(row[13] + row[16], row[7], 1e-9 * row[7]);  // total_lithium
  EXPECT_GT(row[18], 0.0) << "the flux covers the substrate's top: it takes up lithium";
  EXPECT_EQ(row[8], std::min(row[14], row[17]));
  EXPECT_EQ(row[9], std::max(row[15], row[18]));
  fs::remove_all(dir);
}

// The substrate takes up no lithium: its concentration is not computed (NoConcentration kernels,
// no nodal concentration fields), and the run is the same, bit for bit, as one whose output
// saves the nodal concentration and so computes the substrate's too.
TEST(Substrate, ConcentrationOfSubstrateIsNotComputed) {
  omp_set_num_threads(2);
  RunOptions o;
  o.progress = false;
  Simulation skipped(pillarOnSubstrate(), "substrate.ups", o);
  Simulation computed(pillarOnSubstrate("<save label=\"g.concentration\"/>"), "saved.ups", o);
  const ReactiveFlow& d = *skipped.mpm().diffusion();
  EXPECT_TRUE(d.computesConcentration(0));
  EXPECT_FALSE(d.computesConcentration(1));
  EXPECT_TRUE(d.gridFields()[1].concentration.empty());
  EXPECT_TRUE(computed.mpm().diffusion()->computesConcentration(1));
  const size_t nodes = computed.mpm().grid().numNodes();
  EXPECT_EQ(computed.mpm().diffusion()->gridFields()[1].concentration.size(), nodes);
  for (int s = 0; s < 10; ++s) {
    skipped.advance();
    computed.advance();
  }
  for (size_t m = 0; m < 2; ++m) {
    const ParticleSet& a = skipped.mpm().materials()[m].particles;
    const ParticleSet& b = computed.mpm().materials()[m].particles;
    ASSERT_EQ(a.count(), b.count());
    for (size_t i = 0; i < a.count(); ++i) {
      ASSERT_EQ(a.x[i], b.x[i]) << "material " << m << " particle " << i;
      ASSERT_EQ(a.stress[i], b.stress[i]) << "material " << m << " particle " << i;
      ASSERT_EQ(diffusionParticles(a).concentration[i], diffusionParticles(b).concentration[i])
          << "material " << m << " particle " << i;
      ASSERT_EQ(diffusionParticles(a).diffusivity[i], diffusionParticles(b).diffusivity[i])
          << "material " << m << " particle " << i;
    }
  }
  EXPECT_EQ(skipped.dt(), computed.dt());
}

// A scene that colours by p.concentrationGradient needs it of every material.
TEST(Substrate, SceneOfConcentrationGradientComputesSubstrate) {
  omp_set_num_threads(1);
  RunOptions o;
  o.progress = false;
  std::string text = pillarOnSubstrate();
  text.insert(text.find("<MPM>"),
              "<Visualization><scene name=\"g\"><times>[0]</times>"
              "<field>p.concentrationGradient:magnitude</field></scene></Visualization>");
  Simulation sim(text, "scene.ups", o);
  EXPECT_TRUE(sim.mpm().diffusion()->computesConcentration(1));
  EXPECT_EQ(sim.mpm().diffusion()->gridFields()[1].concentration.size(),
            static_cast<size_t>(sim.mpm().grid().numNodes()));
}

// What can change a concentration without diffusivity keeps it computed: a common interface,
// an SD-Type condition on the material.
TEST(Substrate, ConcentrationComputedWhereSomethingCanChangeIt) {
  omp_set_num_threads(1);
  RunOptions o;
  o.progress = false;
  Simulation common(
      pillarOnSubstrate("", "<diffusion_interface><type>common</type></diffusion_interface>"),
      "common.ups", o);
  EXPECT_TRUE(common.mpm().diffusion()->computesConcentration(1));
  Simulation dirichlet(pillarOnSubstrate("", "",
                                         "<Face side=\"x-\"><BCType id=\"1\" label=\"SD-Type\" "
                                         "var=\"Dirichlet\"><value>0.5</value></BCType></Face>"),
                       "dirichlet.ups", o);
  EXPECT_TRUE(dirichlet.mpm().diffusion()->computesConcentration(1));
}

// Uintah gives the common concentration only to the materials <materials> lists: a list of
// some of them is unsupported, a list of all is the same as none.
TEST(Substrate, CommonInterfaceBetweenSomeMaterialsIsUnsupported) {
  omp_set_num_threads(1);
  RunOptions o;
  o.progress = false;
  const auto common = [](const std::string& list) {
    return pillarOnSubstrate("", "<diffusion_interface><type>common</type><materials>" + list +
                                     "</materials></diffusion_interface>");
  };
  Simulation all(common("[1, 0]"), "all.ups", o);
  EXPECT_TRUE(all.mpm().diffusion()->computesConcentration(1));
  for (const char* some : {"[0]", "[1, 1]"}) {
    try {
      Simulation sim(common(some), "some.ups", o);
      ADD_FAILURE() << some << ": expected an InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("only some of the materials"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(Simulation(common("[0, 2]"), "beyond.ups", o), InputError);
}

}  // namespace
}  // namespace anode

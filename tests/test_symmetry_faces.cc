// Pins the squash watch (Components/MPM/SymmetryFaceWatch.h): a block swelling into Symmetric
// faces it did not start on gets a setup note and, when it reaches them, one warning per face
// naming step, time and particle; the same block with room to grow gets neither.
#include <gtest/gtest.h>

#include <sstream>

#include "Components/MPM/SymmetryFaceWatch.h"
#include "StandAlone/Driver/Simulation.h"
#include "tests/TestFiles.h"

namespace anode {
namespace {

// An octant block [0, 0.4]^3 on its symmetry planes x-, y-, z-, its concentration rising
// uniformly to 1 at t = 1 (constant_rate), swelling eta = 0.3 (exp(0.3) = 1.35: 0.4 -> 0.54
// per axis), Symmetric faces also at x+, y+, z+ = `upper`.
std::string swellingBlock(double upper) {
  std::ostringstream s;
  s << "<?xml version='1.0'?>\n<Uintah_specification><SimulationComponent type=\"mpm\"/>"
       "<Time><maxTime>1</maxTime><initTime>0</initTime><delt_min>0</delt_min><delt_max>1</"
       "delt_max>"
       "<timestep_multiplier>0.4</timestep_multiplier></Time>"
       "<DataArchiver><filebase>block.uda</filebase><outputTimestepInterval>100000</"
       "outputTimestepInterval>"
       "<save label=\"p.concentration\"/></DataArchiver>"
       "<MPM><interpolator>gimp</interpolator><do_scalar_diffusion>true</do_scalar_diffusion></MPM>"
       "<MaterialProperties><MPM><material name=\"block\"><density>1</density>"
       "<constitutive_model type=\"rf_elastic_plastic\"><bulk_modulus>1000</bulk_modulus>"
       "<shear_modulus>500</shear_modulus><volume_expansion_coeff>0.3</volume_expansion_coeff>"
       "<equation_of_state type=\"default_hypo\"/></constitutive_model>"
       "<diffusion_model "
       "type=\"constant_rate\"><diffusivity>0</diffusivity><max_concentration>1</max_concentration>"
       "<constant_rate>1</constant_rate></diffusion_model>"
       "<geom_object><box><min>[0,0,0]</min><max>[0.4,0.4,0.4]</max></box><res>[1,1,1]</res>"
       "<velocity>[0,0,0]</velocity><concentration>0</concentration></geom_object>"
       "</material></MPM></MaterialProperties><Grid><Level><spacing>[0.05,0.05,0.05]</spacing>"
       "<Box><lower>[0,0,0]</lower><upper>["
    << upper << "," << upper << "," << upper << "]</upper>"
    << "<extraCells>[1,1,1]</extraCells></Box></Level><BoundaryConditions>";
  for (const char* face : {"x-", "y-", "z-", "x+", "y+", "z+"})
    s << "<Face side=\"" << face
      << "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>";
  s << "</BoundaryConditions></Grid></Uintah_specification>\n";
  return s.str();
}

struct Watched {
  std::vector<std::string> notes, warnings;
};

Watched runWatched(double upper, double until) {
  RunOptions quiet;
  quiet.progress = false;
  Simulation sim(swellingBlock(upper), "block.ups", quiet);
  SymmetryFaceWatch watch;
  Watched w{watch.start(Communicator::everyRank(), sim.mpm()), {}};
  while (sim.time() < until) {
    sim.advance();
    for (const std::string& s :
         watch.afterStep(Communicator::everyRank(), sim.mpm(), sim.step(), sim.time()))
      w.warnings.push_back(s);
  }
  return w;
}

TEST(SymmetryFaceWatch, WarnsOncePerFaceABodyGrowsInto) {
  const Watched w = runWatched(0.5, 0.9);
  ASSERT_EQ(w.notes.size(), 1u);
  EXPECT_NE(w.notes[0].find("would reach the Symmetric face(s) x+, y+, z+"), std::string::npos)
      << w.notes[0];
  ASSERT_EQ(w.warnings.size(), 3u) << "one per face reached, never for the planes it starts on";
  for (const char* face : {"x+", "y+", "z+"}) {
    bool named = false;
    for (const std::string& s : w.warnings)
      named |= s.find("Symmetric face " + std::string(face)) != std::string::npos;
    EXPECT_TRUE(named) << face;
  }
  EXPECT_NE(w.warnings[0].find("warning: step "), std::string::npos) << w.warnings[0];
  EXPECT_NE(w.warnings[0].find("particle "), std::string::npos) << w.warnings[0];
}

TEST(SymmetryFaceWatch, SilentWithRoomToGrow) {
  const Watched w = runWatched(0.6, 0.9);
  EXPECT_TRUE(w.notes.empty()) << w.notes[0];
  EXPECT_TRUE(w.warnings.empty()) << w.warnings[0];
}

// The 2x2 pillar array on its substrate (inputs/Pillar/PillarArray.ups): each pillar swells about
// its own axis (the gaps take the growth, no x or y face is reached) and up from the substrate it
// rests on, so with the grid's top lowered from 0.45 to 0.3 every pillar would reach z+, which a
// note says, naming the four bodies; with the input's grid, no note.
TEST(SwellingRoom, EachBodyOfAnArrayGrowsFromWhatItRestsOn) {
  const std::string text =
      testing::readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Pillar/PillarArray.ups");
  RunOptions quiet;
  quiet.progress = false;
  Simulation roomy(text, "array.ups", quiet);
  EXPECT_TRUE(roomy.mpm().problem().swellingNotes.empty())
      << roomy.mpm().problem().swellingNotes[0];
  std::string low = text;
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"[0.4, 0.4, 0.45]", "[0.4, 0.4, 0.3]"},
        {"[40, 40, 45]", "[40, 40, 30]"}})
    low.replace(low.find(from), from.size(), to);
  Simulation tight(low, "low.ups", quiet);
  const std::vector<std::string>& notes = tight.mpm().problem().swellingNotes;
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("each of its 4 bodies"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("bodies 1 (centre [0.1, 0.1, 0.14]), 2"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("would reach z+"), std::string::npos) << notes[0];
  for (const char* face : {"x-", "x+", "y-", "y+"})
    EXPECT_EQ(notes[0].find(face), std::string::npos) << face << ": " << notes[0];
}

}  // namespace
}  // namespace anode

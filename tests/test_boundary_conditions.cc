// Pins the reading of <Grid><BoundaryConditions> (Components/MPM/GridBoundaryConditions.h) where
// it follows Uintah's MPM beyond the label: which var makes a Symmetric face.
#include <gtest/gtest.h>

#include "Components/MPM/GridBoundaryConditions.h"
#include "Components/MPM/ReactiveFlow/ConcentrationBCs.h"

namespace anode {
namespace {

struct ReadFaces {
  std::unique_ptr<ProblemSpec> spec;
  GridBoundaryConditions bcs;
};

ReadFaces readFaces(const std::string& bcTypes) {
  ReadFaces r;
  r.spec = ProblemSpec::fromText("<Uintah_specification><Grid><BoundaryConditions>" + bcTypes +
                                     "</BoundaryConditions></Grid></Uintah_specification>",
                                 "faces.ups");
  r.bcs = readGridBoundaryConditions(r.spec->root().requireChild("Grid"), 1,
                                     [](const BCType&) { ADD_FAILURE() << "no SD-Type here"; });
  return r;
}

// Uintah's MPMBoundCond applies "Symmetric" only with var="symmetry"; with another var the face
// stays free, so here it is left out, with a warning naming the line.
TEST(BoundaryConditions, SymmetricActsOnlyWithVarSymmetryAsInUintah) {
  const ReadFaces symmetric = readFaces(
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>");
  ASSERT_EQ(symmetric.bcs.symmetric.size(), 1u);
  EXPECT_EQ(symmetric.bcs.symmetric[0].axis, 0);
  EXPECT_TRUE(symmetric.spec->warnings().empty());

  const ReadFaces other = readFaces(
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"Dirichlet\"/></Face>");
  EXPECT_TRUE(other.bcs.symmetric.empty());
  ASSERT_EQ(other.spec->warnings().size(), 1u);
  EXPECT_NE(other.spec->warnings()[0].find("faces.ups:1: label=\"Symmetric\" var=\"Dirichlet\""),
            std::string::npos)
      << other.spec->warnings()[0];
}

// Each <BCType> is read once, by the component of its label: the mechanics ones here, SD-Type
// handed over (to the diffusion subcomponent in a run), in file order.
TEST(BoundaryConditions, SDTypeIsHandedToTheConcentrationReader) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification><Grid><BoundaryConditions>"
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Velocity\" var=\"Dirichlet\" "
      "value=\"[1,0,0]\"/></Face>"
      "<Face side=\"y+\"><BCType id=\"0\" label=\"SD-Type\" var=\"Neumann\">"
      "<value>2</value></BCType></Face>"
      "</BoundaryConditions></Grid></Uintah_specification>",
      "faces.ups");
  std::vector<ConcentrationBC> concentration;
  const GridBoundaryConditions bcs = readGridBoundaryConditions(
      spec->root().requireChild("Grid"), 1,
      [&](const BCType& bc) { concentration.push_back(ConcentrationBC::fromInput(bc)); });
  ASSERT_EQ(bcs.velocity.size(), 1u);
  EXPECT_EQ(bcs.velocity[0].velocity, Vec3(1, 0, 0));
  ASSERT_EQ(concentration.size(), 1u);
  EXPECT_EQ(concentration[0].kind, ConcentrationBC::Kind::Neumann);
  EXPECT_EQ(concentration[0].value, 2.0);
  EXPECT_EQ(concentration[0].face.axis, 1);
  EXPECT_EQ(concentration[0].face.side, 1);
  EXPECT_EQ(concentration[0].face.material, 0);
  spec->checkAllUsed();
}

}  // namespace
}  // namespace anode

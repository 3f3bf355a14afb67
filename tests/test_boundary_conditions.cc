// Pins the reading of <Grid><BoundaryConditions> (Core/Grid/BoundaryConditions.h) where it
// follows Uintah's MPM beyond the label: which var makes a Symmetric face.
#include <gtest/gtest.h>

#include "Core/Grid/BoundaryConditions.h"

namespace anode {
namespace {

struct ReadFaces {
  std::unique_ptr<ProblemSpec> spec;
  std::vector<FaceBC> faces;
};

ReadFaces readFaces(const std::string& bcTypes) {
  ReadFaces r;
  r.spec = ProblemSpec::fromText("<Uintah_specification><Grid><BoundaryConditions>" + bcTypes +
                                     "</BoundaryConditions></Grid></Uintah_specification>",
                                 "faces.ups");
  r.faces = readFaceBCs(r.spec->root().requireChild("Grid"), 1, false);
  return r;
}

// Uintah's MPMBoundCond applies "Symmetric" only with var="symmetry"; with another var the face
// stays free, so here it is left out, with a warning naming the line.
TEST(BoundaryConditions, SymmetricActsOnlyWithVarSymmetryAsInUintah) {
  const ReadFaces symmetric = readFaces(
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>");
  ASSERT_EQ(symmetric.faces.size(), 1u);
  EXPECT_EQ(symmetric.faces[0].kind, FaceBC::Kind::Symmetric);
  EXPECT_EQ(symmetric.faces[0].axis, 0);
  EXPECT_TRUE(symmetric.spec->warnings().empty());

  const ReadFaces other = readFaces(
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"Dirichlet\"/></Face>");
  EXPECT_TRUE(other.faces.empty());
  ASSERT_EQ(other.spec->warnings().size(), 1u);
  EXPECT_NE(other.spec->warnings()[0].find("faces.ups:1: label=\"Symmetric\" var=\"Dirichlet\""),
            std::string::npos)
      << other.spec->warnings()[0];
}

}  // namespace
}  // namespace anode

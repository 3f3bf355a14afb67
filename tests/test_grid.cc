// Pins the background grid (Core/Grid/Grid.h, UINTAH_UPS.md §2.10): node count, flat indices
// and positions with extra cells, index coordinates, dimensionality and <Grid> reading.
#include <gtest/gtest.h>

#include "Core/Grid/Grid.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"

namespace anode {
namespace {

Grid readGrid(const std::string& level) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n<Grid><Level>" + level + "</Level></Grid>\n</Uintah_specification>",
      "grid.ups");
  return Grid::fromInput(spec->root().requireChild("Grid"));
}

TEST(Grid, NodesIndicesAndPositionsWithExtraCells) {
  const Grid g = readGrid(
      "<Box><lower>[0,-1,2]</lower><upper>[4,1,3]</upper><resolution>[8,4,2]</resolution>"
      "<extraCells>[1,1,1]</extraCells></Box>");
  EXPECT_EQ(g.dx, Vec3(0.5, 0.5, 0.5));
  EXPECT_EQ(g.nodes(), Vec3i(11, 7, 5));  // cells + 1 + 2 extra per axis
  EXPECT_EQ(g.numNodes(), 11 * 7 * 5);
  EXPECT_EQ(g.nodeIndex(-1, -1, -1), 0);
  EXPECT_EQ(g.nodeIndex(0, 0, 0), 1 + 11 + 11 * 7);
  EXPECT_EQ(g.nodeIndex(9, 5, 3), g.numNodes() - 1);
  EXPECT_EQ(g.nodePosition(0, 0, 0), Vec3(0, -1, 2));
  EXPECT_EQ(g.nodePosition(-1, 4, 2), Vec3(-0.5, 1, 3));
  for (int n : {0, 17, 200, g.numNodes() - 1}) {
    const Vec3i ijk = g.nodeOf(n);
    EXPECT_EQ(g.nodeIndex(ijk.x(), ijk.y(), ijk.z()), n);
    EXPECT_TRUE(g.hasNode(ijk.x(), ijk.y(), ijk.z()));
  }
  EXPECT_FALSE(g.hasNode(-2, 0, 0));
  EXPECT_FALSE(g.hasNode(0, 6, 0));
  EXPECT_EQ(g.indexCoordinate(Vec3(1.25, 0, 2.5)), Vec3(2.5, 2, 1));
  EXPECT_EQ(g.ndim(), 3);
}

TEST(Grid, DimensionalityFollowsSingleCellAxes) {
  Grid g;
  g.cells = Vec3i(10, 10, 1);
  EXPECT_EQ(g.ndim(), 2);
  g.cells = Vec3i(10, 1, 1);
  EXPECT_EQ(g.ndim(), 1);
}

TEST(Grid, SpacingGivesTheCellCount) {
  const Grid g = readGrid(
      "<spacing>[0.25,0.5,1]</spacing><Box><lower>[0,0,0]</lower><upper>[1,1,2]</upper></Box>");
  EXPECT_EQ(g.cells, Vec3i(4, 2, 2));
  EXPECT_EQ(g.extra, Vec3i::Zero());
}

TEST(Grid, RejectsBoxesItCannotMesh) {
  EXPECT_THROW(readGrid("<Box><lower>[0,0,0]</lower><upper>[1,0,1]</upper><resolution>[2,2,2]</"
                        "resolution></Box>"),
               InputError);
  EXPECT_THROW(readGrid("<Box><lower>[0,0,0]</lower><upper>[1,1,1]</upper><resolution>[2,0,2]</"
                        "resolution></Box>"),
               InputError);
  EXPECT_THROW(readGrid("<spacing>[0.3,0.5,0.5]</spacing><Box><lower>[0,0,0]</"
                        "lower><upper>[1,1,1]</upper></Box>"),
               InputError);
}

}  // namespace
}  // namespace anode

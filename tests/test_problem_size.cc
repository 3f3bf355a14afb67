// Pins the size checks of setup: particle filling visits only the cells of a piece's bounding box
// yet places the same particles as a scan of the whole grid; grids and particle counts beyond the
// memory budget (or 32-bit node indices) are InputErrors at the tag responsible, before any large
// allocation; a smooth cylinder's count matches the particles it lays out; a piece reaching beyond
// the grid (where its particles would be dropped) is an InputError unless across a symmetry plane.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <string>

#include "Core/Geometry/ParticleFill.h"
#include "Core/Geometry/SmoothCylinder.h"
#include "Core/Util/MemoryBudget.h"
#include "StandAlone/Driver/Simulation.h"
#include "TestInputs.h"

namespace anode {
namespace {

using testing::BlockInput;

RunOptions quiet() {
  RunOptions o;
  o.progress = false;
  return o;
}

// Uintah's placement over every interior cell, as fillParticles did before it was limited to
// the bounding box.
std::vector<Vec3> fillWholeGrid(const Grid& grid, const GeometryPiece& piece, const Vec3i& res) {
  std::vector<Vec3> out;
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  for (int k = 0; k < grid.cells.z(); ++k)
    for (int j = 0; j < grid.cells.y(); ++j)
      for (int i = 0; i < grid.cells.x(); ++i)
        for (int c = 0; c < res.z(); ++c)
          for (int b = 0; b < res.y(); ++b)
            for (int a = 0; a < res.x(); ++a) {
              const Vec3 x = grid.nodePosition(i, j, k) +
                             Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z());
              if (piece.inside(x)) out.push_back(x);
            }
  return out;
}

// The InputError setup throws for `text`, or a failure.
InputError setupError(const std::string& text, const std::string& name) {
  try {
    Simulation sim(text, name, quiet());
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "setup of " << name << " succeeded";
  return InputError("", 0, "");
}

int lineOf(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  return at == std::string::npos
             ? -1
             : 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

// A 30 x 15 x 15-cell grid off the origin, for the fill tests.
Grid fillTestGrid() {
  Grid grid;
  grid.lower = Vec3(-1, 0, 0.5);
  grid.upper = Vec3(2, 1.5, 2);
  grid.cells = Vec3i(30, 15, 15);
  grid.dx = (grid.upper - grid.lower).cwiseQuotient(grid.cells.cast<double>());
  return grid;
}

// Pieces of the fill tests on fillTestGrid: a sphere inside it, a cylinder reaching beyond x-.
std::shared_ptr<SpherePiece> testSphere() {
  auto sphere = std::make_shared<SpherePiece>();
  sphere->origin = Vec3(0.3, 0.7, 1.1);
  sphere->radius = 0.45;
  return sphere;
}
std::shared_ptr<CylinderPiece> testCylinder() {
  auto cylinder = std::make_shared<CylinderPiece>();
  cylinder->bottom = Vec3(-2, 0.2, 0.9);
  cylinder->top = Vec3(1.7, 1.0, 1.6);
  cylinder->radius = 0.3;
  return cylinder;
}

TEST(ParticleFill, BoundingBoxFillPlacesTheSameParticlesAsAWholeGridScan) {
  const Grid grid = fillTestGrid();
  auto sphere = testSphere();
  auto cylinder = testCylinder();  // reaches beyond the grid
  auto box = std::make_shared<BoxPiece>();
  box->lo = Vec3(1.0, 0.0, 0.5);  // on the grid's lower faces
  box->hi = Vec3(2.0, 0.35, 0.8);
  auto difference = std::make_shared<DifferencePiece>();
  difference->first = cylinder;
  difference->second = sphere;
  auto both = std::make_shared<UnionPiece>();
  both->pieces = {sphere, box};
  auto disjoint = std::make_shared<IntersectionPiece>();
  disjoint->pieces = {sphere, box};
  const std::vector<std::shared_ptr<const GeometryPiece>> pieces = {sphere,     cylinder, box,
                                                                    difference, both,     disjoint};
  for (const auto& piece : pieces)
    for (const Vec3i& res : {Vec3i(1, 1, 1), Vec3i(2, 3, 2)}) {
      const std::vector<Vec3> expected = fillWholeGrid(grid, *piece, res);
      std::vector<Vec3> filled;
      std::vector<int64_t> place;
      const PieceLattice lattice(grid, piece, res);
      lattice.fill({Vec3i::Zero(), grid.cells}, filled, place);
      EXPECT_EQ(filled, expected) << piece->type();
      EXPECT_EQ(lattice.count(), static_cast<int64_t>(expected.size())) << piece->type();
      EXPECT_LE(static_cast<double>(expected.size()), fillCandidates(grid, *piece, res))
          << piece->type();
      if (piece->type() != "intersection") {
        EXPECT_GT(expected.size(), 0u) << piece->type();
      }
      // Pieces in a fraction of the grid: fewer candidates than a whole-grid scan.
      if (piece->type() == "sphere" || piece->type() == "box" || piece->type() == "union") {
        EXPECT_LT(fillCandidates(grid, *piece, res), grid.cells.prod() * res.prod())
            << piece->type();
      }
    }
  EXPECT_EQ(fillCandidates(grid, *disjoint, Vec3i(2, 2, 2)), 0.0);
}

// A rank fills only the cells of its box (docs/parallel.md, "Setup per box"): over boxes that
// tile the grid unevenly, each box's points are those of the whole fill lying in its cells, in
// the same order, each with its place in the whole fill; the counts per box and per cell (summed
// per cell plane) are those of the points. The box ends below x cell 13: the boxes beyond it in x
// but beside it in y and z hold none of its points (and read nothing past its cells: the
// sanitizer pass).
TEST(ParticleFill, FillsOfBoxesTilingTheGridAreTheWholeFillShared) {
  const Grid grid = fillTestGrid();
  auto lowX = std::make_shared<BoxPiece>();
  lowX->lo = Vec3(-0.9, 0.2, 0.7);
  lowX->hi = Vec3(-0.45, 1.3, 1.9);
  for (const GeometryPieceP& piece :
       std::vector<GeometryPieceP>{testSphere(), testCylinder(), lowX}) {
    const Vec3i res(2, 3, 2);
    const PieceLattice lattice(grid, piece, res);
    std::vector<Vec3> whole;
    std::vector<int64_t> wholePlace;
    lattice.fill({Vec3i::Zero(), grid.cells}, whole, wholePlace);
    ASSERT_GT(whole.size(), 100u);
    for (size_t k = 0; k < wholePlace.size(); ++k)
      EXPECT_EQ(wholePlace[k], static_cast<int64_t>(k));
    std::array<std::vector<double>, 3> planes, expectedPlanes;
    for (int d = 0; d < 3; ++d) {
      planes[d].assign(grid.cells[d], 0.0);
      expectedPlanes[d].assign(grid.cells[d], 0.0);
    }
    lattice.forEachOccupiedCell([&](const Vec3i& cell, double n) {
      for (int d = 0; d < 3; ++d) planes[d][cell[d]] += n;
    });
    for (const Vec3& x : whole)
      for (int d = 0; d < 3; ++d) expectedPlanes[d][grid.interiorCell(x)[d]] += 1;
    EXPECT_EQ(planes, expectedPlanes);
    const std::array<std::vector<int>, 3> cuts = {
        std::vector<int>{0, 7, 13, 30}, std::vector<int>{0, 9, 15}, std::vector<int>{0, 4, 5, 15}};
    std::vector<int> seen(whole.size(), 0);
    for (size_t a = 0; a + 1 < cuts[0].size(); ++a)
      for (size_t b = 0; b + 1 < cuts[1].size(); ++b)
        for (size_t c = 0; c + 1 < cuts[2].size(); ++c) {
          const CellBox box{Vec3i(cuts[0][a], cuts[1][b], cuts[2][c]),
                            Vec3i(cuts[0][a + 1], cuts[1][b + 1], cuts[2][c + 1])};
          std::vector<Vec3> x;
          std::vector<int64_t> place;
          lattice.fill(box, x, place);
          EXPECT_EQ(lattice.countIn(box), static_cast<int64_t>(x.size()));
          std::vector<int64_t> expected;
          for (size_t k = 0; k < whole.size(); ++k)
            if (box.contains(grid.interiorCell(whole[k])))
              expected.push_back(static_cast<int64_t>(k));
          EXPECT_EQ(place, expected);
          for (size_t k = 0; k < x.size(); ++k) {
            EXPECT_EQ(x[k], whole[place[k]]);
            ++seen[place[k]];
          }
        }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(whole.size()));
  }
}

TEST(ProblemSize, MoreNodesThan32BitIndicesIsAnInputErrorAtTheResolution) {
  BlockInput in;
  in.cells = "[2000, 2000, 1000]";
  const std::string text = in.text();
  const InputError e = setupError(text, "nodes.ups");
  EXPECT_EQ(e.line(), lineOf(text, "<resolution>")) << e.what();
  EXPECT_NE(std::string(e.what()).find("at most 2147483647 are supported"), std::string::npos)
      << e.what();
}

TEST(ProblemSize, GridBeyondTheMemoryBudgetIsAnInputErrorAtTheResolution) {
  BlockInput in;
  in.cells = "[400, 400, 400]";  // 6.6e7 nodes: at least 6.9 GB
  const std::string text = in.text();
  setMemoryBudget(size_t(1) << 30);
  const InputError e = setupError(text, "grid.ups");
  setMemoryBudget(0);
  EXPECT_EQ(e.line(), lineOf(text, "<resolution>")) << e.what();
  EXPECT_NE(std::string(e.what()).find("beyond the memory budget of 1.07 GB"), std::string::npos)
      << e.what();
}

TEST(ProblemSize, ParticlesBeyondTheMemoryBudgetAreAnInputErrorAtTheRes) {
  BlockInput in;
  in.res = "[40, 40, 40]";  // 125 cells x 64000: 8e6 particles, about 7 GB
  const std::string text = in.text();
  setMemoryBudget(size_t(64) << 20);
  const InputError e = setupError(text, "particles.ups");
  setMemoryBudget(0);
  EXPECT_EQ(e.line(), lineOf(text, "<res>")) << e.what();
  EXPECT_NE(std::string(e.what()).find("particles, beyond the memory budget of 67.1 MB"),
            std::string::npos)
      << e.what();
}

TEST(ProblemSize, GridAndParticlesTogetherBeyondTheBudgetAreAnInputError) {
  // Each alone fits 256 MB; together they do not.
  BlockInput in;
  in.cells = "[80, 80, 80]";  // 5.7e5 nodes: 59 MB for one material and one thread
  in.boxMin = "[0.1, 0.1, 0.1]";
  in.boxMax = "[0.9, 0.9, 0.9]";
  in.res = "[1, 1, 1]";  // 262k particles (linear): about 204 MB
  const std::string text = in.text();
  setMemoryBudget(size_t(256) << 20);
  const InputError e = setupError(text, "both.ups");
  setMemoryBudget(0);
  EXPECT_EQ(e.line(), lineOf(text, "<resolution>")) << e.what();
  EXPECT_NE(std::string(e.what()).find("particles ("), std::string::npos) << e.what();
}

TEST(ProblemSize, SmoothCylinderCountMatchesTheParticlesItLaysOut) {
  Grid grid;
  grid.cells = Vec3i(20, 20, 20);
  grid.dx = Vec3::Constant(0.05);
  for (auto scheme : {SmoothCylinderPiece::Scheme::PieSlices,
                      SmoothCylinderPiece::Scheme::ConstantParticleVolumes}) {
    SmoothCylinderPiece c;
    c.scheme = scheme;
    c.bottom = Vec3(0.5, 0.5, 0.1);
    c.top = Vec3(0.5, 0.5, 0.8);
    c.outerRadius = 0.3;
    c.innerRadius = 0.05;
    c.numRadial = 6;
    c.numAxial = 14;
    c.numAngular = 40;
    const double n = static_cast<double>(c.createParticles(grid).size());
    EXPECT_EQ(c.particleCount(grid, 1e9), n);
    EXPECT_GT(c.particleCount(grid, n / 3), n / 3);  // counting stops beyond the limit
    // Absurd ring counts are counted without a loop over them.
    c.numRadial = 2000000000;
    c.numAxial = 2000000000;
    EXPECT_GT(c.particleCount(grid, 1e7), 1e7);
  }
}

// Whether a point of Uintah's lattice, continued `margin` cells beyond the grid on every side,
// lies inside the piece but beyond a face `mirror` does not mark: the whole lattice, scanned.
bool outsideByScan(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                   const std::array<bool, 6>& mirror, int margin) {
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  for (int k = -margin; k < grid.cells.z() + margin; ++k)
    for (int j = -margin; j < grid.cells.y() + margin; ++j)
      for (int i = -margin; i < grid.cells.x() + margin; ++i) {
        const Vec3i cell(i, j, k);
        bool beyond = false;
        for (int d = 0; d < 3; ++d)
          beyond = beyond || (cell[d] < 0 && !mirror[2 * d]) ||
                   (cell[d] >= grid.cells[d] && !mirror[2 * d + 1]);
        if (!beyond) continue;
        for (int c = 0; c < res.z(); ++c)
          for (int b = 0; b < res.y(); ++b)
            for (int a = 0; a < res.x(); ++a)
              if (piece.inside(grid.nodePosition(i, j, k) +
                               Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z())))
                return true;
      }
  return false;
}

TEST(ParticleFill, PiecesBeyondTheGridAreFoundAsByAScanOfTheContinuedLattice) {
  const Grid grid = fillTestGrid();
  auto sphere = std::make_shared<SpherePiece>();  // inside
  sphere->origin = Vec3(0.3, 0.7, 1.1);
  sphere->radius = 0.45;
  auto cylinder = std::make_shared<CylinderPiece>();  // beyond x-, and y- where beyond x-
  cylinder->bottom = Vec3(-2, 0.2, 0.9);
  cylinder->top = Vec3(1.7, 1.0, 1.6);
  cylinder->radius = 0.3;
  auto onFaces = std::make_shared<BoxPiece>();  // on the grid's lower faces, not beyond them
  onFaces->lo = Vec3(1.0, 0.0, 0.5);
  onFaces->hi = Vec3(2.0, 0.35, 0.8);
  auto thin = std::make_shared<BoxPiece>();  // beyond y+ by less than half a particle spacing
  thin->lo = Vec3(0.0, 1.0, 1.0);
  thin->hi = Vec3(0.5, 1.5 + 0.2 * grid.dx.y(), 1.5);
  auto corner = std::make_shared<SpherePiece>();  // beyond x+, y+ and z+
  corner->origin = grid.upper;
  corner->radius = 0.3;
  auto far = std::make_shared<BoxPiece>();  // wholly beyond z-
  far->lo = Vec3(0, 0, 0);
  far->hi = Vec3(1, 1, 0.3);
  auto difference = std::make_shared<DifferencePiece>();  // the cylinder's part beyond x- cut away
  difference->first = cylinder;
  auto cut = std::make_shared<BoxPiece>();
  cut->lo = Vec3(-3, -1, 0);
  cut->hi = Vec3(-0.5, 2, 3);
  difference->second = cut;
  const std::vector<std::shared_ptr<const GeometryPiece>> pieces = {
      sphere, cylinder, onFaces, thin, corner, far, difference};
  std::array<bool, 6> none{}, lowerX{}, lowerXY{}, upperFaces{}, all{};
  lowerX[0] = true;
  lowerXY[0] = lowerXY[2] = true;
  upperFaces[1] = upperFaces[3] = upperFaces[5] = true;
  all.fill(true);
  for (const auto& mirror : {none, lowerX, lowerXY, upperFaces, all})
    for (const Vec3i& res : {Vec3i(1, 1, 1), Vec3i(2, 3, 2)})
      for (size_t n = 0; n < pieces.size(); ++n)
        EXPECT_EQ(placesParticlesOutside(grid, *pieces[n], res, mirror),
                  outsideByScan(grid, *pieces[n], res, mirror, 12))
            << "piece " << n << ", res " << res.transpose() << ", mirror " << mirror[0] << mirror[1]
            << mirror[2] << mirror[3] << mirror[4] << mirror[5];
  const Vec3i one(1, 1, 1);
  EXPECT_TRUE(placesParticlesOutside(grid, *cylinder, one, none));
  EXPECT_TRUE(placesParticlesOutside(grid, *cylinder, one, lowerX));
  EXPECT_FALSE(placesParticlesOutside(grid, *cylinder, one, lowerXY));
  EXPECT_FALSE(placesParticlesOutside(grid, *difference, one, none));
  EXPECT_FALSE(placesParticlesOutside(grid, *onFaces, one, none));
  EXPECT_FALSE(placesParticlesOutside(grid, *thin, one, none));
  EXPECT_TRUE(placesParticlesOutside(grid, *corner, one, none));
  EXPECT_FALSE(placesParticlesOutside(grid, *corner, one, upperFaces));
  EXPECT_TRUE(placesParticlesOutside(grid, *far, one, none));
  // A piece reaching far beyond: more candidates than the scan tests, outside without a test.
  auto huge = std::make_shared<BoxPiece>();
  huge->lo = Vec3::Constant(-1e6);
  huge->hi = Vec3::Constant(1e6);
  EXPECT_TRUE(placesParticlesOutside(grid, *huge, one, none));
}

TEST(ParticleFill, AFarReachAcrossASymmetryPlaneIsCheckedWithoutVisitingItsCells) {
  // Found by the fuzzer: a box reaching 1e9 beyond a symmetric face had its 1e12 rows of cells
  // visited one by one (a hang); only rows holding a cell that counts are visited now.
  const Grid grid = fillTestGrid();
  BoxPiece far;
  far.lo = Vec3(0, 0.5, 1.0);
  far.hi = Vec3(0.5, 1e9, 1.5);
  std::array<bool, 6> mirror{};
  mirror[3] = true;  // y+
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(placesParticlesOutside(grid, far, Vec3i(2, 2, 2), mirror));
  mirror[3] = false;
  EXPECT_TRUE(placesParticlesOutside(grid, far, Vec3i(2, 2, 2), mirror));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ParticleFill, APieceMayCrossASymmetryPlaneButNoOtherFace) {
  // Half a block cut by the symmetric x- face (Uintah's NanoPillar2D_FBC_Sym does this).
  BlockInput in;
  in.boxMin = "[-0.25, 0.25, 0.25]";
  in.faces = "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>";
  Simulation half(in.text(), "half.ups", quiet());
  EXPECT_EQ(countParticles(half.mpm().materials()),
            15u * 10 * 10);  // 2 per 0.1 cell in [0, 0.75] x [0.25, 0.75]^2
  for (const Vec3& x : half.mpm().materials()[0].particles.x) EXPECT_GT(x.x(), 0.0);
  // The same beyond a face that holds the velocity instead: the cut-off particles are an error.
  in.faces =
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Velocity\" "
      "var=\"Dirichlet\"><value>[0,0,0]</value></BCType></Face>";
  const std::string text = in.text();
  const InputError e = setupError(text, "cut.ups");
  EXPECT_EQ(e.line(), lineOf(text, "<box")) << e.what();
  EXPECT_NE(
      std::string(e.what()).find(
          "<box> places particles outside the grid domain [0, 0, 0] to [1, 1, 1], beyond a face "
          "without a Symmetric BC"),
      std::string::npos)
      << e.what();
}

}  // namespace
}  // namespace anode

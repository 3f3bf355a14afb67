// Pins the flux area of a curved <scalar_flux> face on a body filled on the grid
// (ReactiveFlow/FluxSurfaceArea.h, docs/diffusion.md "Flux area at the start"): the BC surface's
// samples add up to its area, a sphere's flagged particles carry its area whatever way the
// surface faces the grid, and the lithiation front moves in as fast along the diagonals as along
// the axes; a <surface> BC's particles carry the free surface of their body, less where another
// material lies against it.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "Components/MPM/ReactiveFlow/FluxSurfaceArea.h"
#include "Core/Util/Errors.h"
#include "StandAlone/Driver/Simulation.h"
#include "tests/TestFiles.h"

namespace anode {
namespace {

TEST(FluxSurfaceArea, SamplesAddUpToTheSurface) {
  ScalarFluxBC sphere;
  sphere.face = ScalarFluxBC::Face::Sphere;
  sphere.center = Vec3(1, 2, 3);
  sphere.radius = 0.7;
  double area = 0, farthest = 0;
  for (const SurfaceSample& s : sampleSurface(sphere, 0.05)) {
    area += s.area;
    farthest = std::max(farthest, std::abs((s.x - sphere.center).norm() - 0.7));
    EXPECT_NEAR((s.x - sphere.center).normalized().dot(s.normal), 1.0, 1e-12);
  }
  EXPECT_NEAR(area, 4 * M_PI * 0.49, 1e-12);
  EXPECT_LT(farthest, 1e-12);
  ScalarFluxBC cylinder;
  cylinder.face = ScalarFluxBC::Face::CylinderSide;
  cylinder.bottom = Vec3(0, 0, 0);
  cylinder.top = Vec3(0, 3, 4);  // length 5, tilted
  cylinder.radius = 0.5;
  area = 0;
  for (const SurfaceSample& s : sampleSurface(cylinder, 0.05)) area += s.area;
  EXPECT_NEAR(area, 2 * M_PI * 0.5 * 5, 1e-11);
  cylinder.face = ScalarFluxBC::Face::CylinderEnd;
  area = 0;
  for (const SurfaceSample& s : sampleSurface(cylinder, 0.05)) area += s.area;
  EXPECT_NEAR(area, 2 * M_PI * 0.25, 1e-12);  // both end disks
}

// An octant of a sphere of radius 1 (symmetry planes through its centre), filled on a lattice of
// spacing h = 0.05 (R/h = 20), taking up J = 1 through its curved surface; D = 1, rho = 1, no
// swelling. Units arbitrary but consistent.
std::string sphereOctant() {
  std::ostringstream s;
  s << "<?xml version='1.0'?>\n<Uintah_specification><SimulationComponent type=\"mpm\"/>"
       "<Time><maxTime>0.04</maxTime><initTime>0</initTime><delt_min>0</delt_min><delt_max>1</"
       "delt_max>"
       "<timestep_multiplier>0.25</timestep_multiplier></Time>"
       "<DataArchiver><filebase>sphere.uda</filebase><outputTimestepInterval>1000</"
       "outputTimestepInterval>"
       "<save label=\"p.concentration\"/></DataArchiver>"
       "<MPM><interpolator>gimp</interpolator><do_scalar_diffusion>true</do_scalar_diffusion>"
       "<use_load_curves>true</use_load_curves></MPM>"
       "<MaterialProperties><MPM><material name=\"sphere\"><density>1</density>"
       "<constitutive_model type=\"rf_elastic_plastic\"><bulk_modulus>100</bulk_modulus>"
       "<shear_modulus>50</shear_modulus><volume_expansion_coeff>0</volume_expansion_coeff>"
       "<equation_of_state type=\"default_hypo\"/></constitutive_model>"
       "<diffusion_model "
       "type=\"jg\"><diffusivity>1</diffusivity><max_concentration>1</max_concentration>"
       "</diffusion_model><geom_object><sphere><origin>[0,0,0]</origin><radius>1</radius></sphere>"
       "<res>[1,1,1]</res><velocity>[0,0,0]</velocity><concentration>0</concentration></"
       "geom_object>"
       "</material></MPM></MaterialProperties>"
       "<PhysicalBC><MPM><scalar_flux><geom_object><sphere><origin>[0,0,0]</origin><radius>1</"
       "radius></sphere>"
       "</geom_object><load_curve><id>1</id><time_point><time>0</time><load>1</load></time_point>"
       "<time_point><time>10</time><load>1</load></time_point></load_curve></scalar_flux></MPM></"
       "PhysicalBC>"
       "<Grid><Level><Box><lower>[0,0,0]</lower><upper>[1.2,1.2,1.2]</"
       "upper><resolution>[24,24,24]</resolution>"
       "<extraCells>[1,1,1]</extraCells></Box></Level><BoundaryConditions>"
       "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
       "<Face side=\"y-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
       "<Face side=\"z-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
       "</BoundaryConditions></Grid></Uintah_specification>\n";
  return s.str();
}

// The radius at which c falls to `level` along direction d: particles within h of the ray,
// ordered by radius, interpolated linearly between the last one below and the first above it.
double frontRadius(const ParticleSet& p, const Vec3& d, double level, double h) {
  std::vector<std::pair<double, double>> ray;  // radius, c
  for (size_t i = 0; i < p.count(); ++i)
    if (p.x[i].cross(d).norm() < h)
      ray.emplace_back(p.x[i].dot(d), diffusionParticles(p).concentration[i]);
  std::sort(ray.begin(), ray.end());
  for (size_t k = 1; k < ray.size(); ++k)
    if (ray[k - 1].second < level && ray[k].second >= level)
      return ray[k - 1].first + (level - ray[k - 1].second) / (ray[k].second - ray[k - 1].second) *
                                    (ray[k].first - ray[k - 1].first);
  return -1;
}

TEST(FluxSurfaceArea, SphereTakesUpItsAreaAndTheFrontIsRound) {
  RunOptions quiet;
  quiet.progress = false;
  Simulation sim(sphereOctant(), "sphere.ups", quiet);
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  double area = 0;
  for (size_t i = 0; i < p.count(); ++i) area += diffusionParticles(p).area[i].sum();
  const double octant = M_PI / 2;  // 4 pi R^2 / 8
  EXPECT_NEAR(area / octant, 1.0, 0.02);
  // The first step takes up rho J A dt (R(0) = 1).
  sim.advance();
  EXPECT_NEAR(sim.mpm().summarize(Communicator::everyRank()).totalLithium / (sim.dt() * octant),
              1.0, 0.02);
  while (sim.time() < 0.04 - 1e-9) sim.advance();
  // The front (c = 0.1, about half the surface value) 4.4 cells deep: as deep along the diagonal
  // as along each axis, within a quarter of the particle spacing (it is within 0.02 of it; with
  // the particle face as the area the diagonal lagged 0.86 of a spacing behind).
  const double h = 0.05;
  const double diagonal = frontRadius(p, Vec3(1, 1, 1).normalized(), 0.1, h);
  ASSERT_GT(diagonal, 0);
  EXPECT_LT(diagonal, 1 - 2 * h) << "the front must be a few cells deep";
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) {
    const double along = frontRadius(p, axis, 0.1, h);
    ASSERT_GT(along, 0);
    EXPECT_LT(std::abs(along - diagonal), 0.25 * h)
        << "axis " << axis.transpose() << ": " << along << " against " << diagonal;
  }
}

// Uintah's rules for the flux source (docs/differences-from-uintah.md, for the study of the sharp
// front): <flux_source_receivers>weights shares a node's source by S instead of m S R(c), and
// <flux_source_in_cstar>false leaves it out of c*. Each leaves the first step as ours (c = 0:
// R = 1, and c* first feeds the next step's gradient) and changes the particles' c after it;
// the lithium taken up stays that of the flux within a few per cent.
TEST(FluxSurfaceArea, UintahsFluxSourceRulesChangeOnlyWhatTheyName) {
  RunOptions quiet;
  quiet.progress = false;
  const auto withFlags = [](const std::string& flags) {
    std::string text = sphereOctant();
    const std::string tag = "<use_load_curves>true</use_load_curves>";
    text.insert(text.find(tag) + tag.size(), flags);
    return text;
  };
  const auto concentrations = [](Simulation& sim) {
    return diffusionParticles(sim.mpm().materials()[0].particles).concentration;
  };
  Simulation ours(withFlags(""), "ours.ups", quiet);
  ours.advance();
  const std::vector<double> first = concentrations(ours);
  for (int k = 1; k < 10; ++k) ours.advance();
  const double lithium = ours.mpm().summarize(Communicator::everyRank()).totalLithium;
  for (const std::string flags : {"<flux_source_receivers>weights</flux_source_receivers>",
                                  "<flux_source_in_cstar>false</flux_source_in_cstar>"}) {
    Simulation uintah(withFlags(flags), "uintah.ups", quiet);
    uintah.advance();
    EXPECT_EQ(concentrations(uintah), first) << flags;
    for (int k = 1; k < 10; ++k) uintah.advance();
    double largest = 0;
    const std::vector<double> a = concentrations(ours), b = concentrations(uintah);
    for (size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
    EXPECT_GT(largest, 1e-6) << flags;
    EXPECT_NEAR(uintah.mpm().summarize(Communicator::everyRank()).totalLithium / lithium, 1.0, 0.05)
        << flags;
  }
}

// The 2x2 pillar array (inputs/Pillar/PillarArray.ups) with one <surface material="silicon"
// exclude="substrate"/> BC for its five: the flagged particles carry the four pillars' sides and
// tops, 4 (2 pi r h + pi r^2), to round-off, not their bottoms on the substrate.
std::string arrayWithOneSurfaceBC(const std::string& surface) {
  std::string text =
      testing::readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Pillar/PillarArray.ups");
  const size_t a = text.find("<PhysicalBC>"), b = text.find("</PhysicalBC>");
  return text.substr(0, a) + "<PhysicalBC><MPM><scalar_flux><mode>galvanostatic</mode>" + surface +
         "<load_curve><id>1</id><time_point><time>0</time><load>5.15e12</load></time_point>"
         "</load_curve></scalar_flux></MPM>" +
         text.substr(b);
}

TEST(FluxSurfaceArea, SurfaceBCCarriesTheFreeSurfaceOfItsBody) {
  RunOptions o;
  o.progress = false;
  Simulation sim(arrayWithOneSurfaceBC("<surface material=\"silicon\" exclude=\"substrate\"/>"),
                 "array.ups", o);
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  const ConstDiffusionParticles d(p);
  double area = 0;
  size_t flagged = 0;
  for (size_t i = 0; i < p.count(); ++i)
    if (d.loadCurveID[i][0] > 0) area += d.area[i][0], ++flagged;
  const double r = 0.04, h = 0.2;
  EXPECT_NEAR(area, 4 * (2 * M_PI * r * h + M_PI * r * r), 1e-12);
  EXPECT_GT(flagged, 0u);
  // The substrate takes up no lithium and is not flagged.
  EXPECT_TRUE(diffusionParticles(sim.mpm().materials()[1].particles).loadCurveID.empty() ||
              diffusionParticles(sim.mpm().materials()[1].particles).loadCurveID[0][0] == 0);
  // Without the exclusion the pillars' bottoms count too.
  Simulation whole(arrayWithOneSurfaceBC("<surface material=\"silicon\"/>"), "whole.ups", o);
  const ParticleSet& q = whole.mpm().materials()[0].particles;
  const ConstDiffusionParticles e(q);
  double wholeArea = 0;
  for (size_t i = 0; i < q.count(); ++i)
    if (e.loadCurveID[i][0] > 0) wholeArea += e.area[i][0];
  EXPECT_NEAR(wholeArea, 4 * (2 * M_PI * r * h + 2 * M_PI * r * r), 1e-12);
}

TEST(FluxSurfaceArea, SurfaceBCErrorsNameTheTag) {
  RunOptions o;
  o.progress = false;
  for (const auto& [surface, message] :
       {std::pair<std::string, std::string>{"<surface material=\"silcon\"/>",
                                            "<surface material=\"silcon\">: no material has"},
        {"<surface material=\"silicon\" exclude=\"base\"/>", "<surface exclude=\"base\">"},
        {"<surface material=\"silicon\" exlude=\"substrate\"/>",
         "takes the attributes material and exclude, found exlude"},
        {"<surface/>", "material"}}) {
    try {
      Simulation sim(arrayWithOneSurfaceBC(surface), "bad.ups", o);
      ADD_FAILURE() << "expected an InputError: " << message;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace anode

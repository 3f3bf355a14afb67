// Pins <MPM>/<PhysicalConstants> reading (Components/MPM/MPMFlags.h) where Uintah has a fallback:
// gravity from <MPM> without <PhysicalConstants>, and the splitting criterion without matl=; and
// <swelling_strain> on each path.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "Components/MPM/MPMFlags.h"

namespace anode {
namespace {

struct Read {
  std::unique_ptr<ProblemSpec> spec;
  MPMFlags flags;
};

Read read(const std::string& body) {
  Read r;
  r.spec = ProblemSpec::fromText("<Uintah_specification><SimulationComponent type=\"mpm\"/>" +
                                     body + "</Uintah_specification>",
                                 "flags.ups");
  r.flags = MPMFlags::fromInput(r.spec->root());
  return r;
}

TEST(MPMFlags, GravityFromTheMPMBlockOnlyWithoutPhysicalConstants) {
  EXPECT_EQ(read("<MPM><gravity>[0, 0, -9.8]</gravity></MPM>").flags.gravity, Vec3(0, 0, -9.8));
  EXPECT_EQ(read("<PhysicalConstants><gravity>[1, 0, 0]</gravity></PhysicalConstants>"
                 "<MPM><gravity>[0, 0, -9.8]</gravity></MPM>")
                .flags.gravity,
            Vec3(1, 0, 0));
  EXPECT_EQ(read("<MPM></MPM>").flags.gravity, Vec3::Zero());
}

TEST(MPMFlags, FluxSourceRulesDefaultToOursAndNameABadValue) {
  EXPECT_TRUE(read("<MPM></MPM>").flags.restrictedFluxReceivers);
  EXPECT_TRUE(read("<MPM></MPM>").flags.fluxSourceInCStar);
  EXPECT_FALSE(read("<MPM><flux_source_receivers>weights</flux_source_receivers></MPM>")
                   .flags.restrictedFluxReceivers);
  EXPECT_FALSE(read("<MPM><flux_source_in_cstar>false</flux_source_in_cstar></MPM>")
                   .flags.fluxSourceInCStar);
  try {
    read("<MPM><flux_source_receivers>uintah</flux_source_receivers></MPM>");
    FAIL() << "a bad value must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flags.ups:1: <flux_source_receivers> must be restricted "
                                         "or weights, found \"uintah\""),
              std::string::npos)
        << e.what();
  }
}

// The implicit path takes either swelling; the explicit one its own (particle) only; anything else
// is an error naming the tag's line.
TEST(MPMFlags, SwellingStrainIsParticleByDefaultAndCellMeanOnlyImplicit) {
  using S = ImplicitOptions::SwellingStrain;
  const std::string implicit =
      "<time_integrator>implicit</time_integrator><dynamic>false</dynamic>";
  EXPECT_EQ(read("<MPM>" + implicit + "</MPM>").flags.implicit->swellingStrain, S::Particle);
  EXPECT_EQ(read("<MPM>" + implicit + "<swelling_strain>cell_mean</swelling_strain></MPM>")
                .flags.implicit->swellingStrain,
            S::CellMean);
  EXPECT_FALSE(read("<MPM><swelling_strain>particle</swelling_strain></MPM>").flags.implicit);
  const auto message = [&](const std::string& mpm) -> std::string {
    try {
      read("<MPM>" + mpm + "</MPM>");
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(message("<swelling_strain>cell_mean</swelling_strain>")
                .find("flags.ups:1: <swelling_strain>cell_mean with <time_integrator>explicit"),
            std::string::npos);
  EXPECT_NE(
      message(implicit + "<swelling_strain>cells</swelling_strain>")
          .find("flags.ups:1: <swelling_strain> must be cell_mean or particle, found \"cells\""),
      std::string::npos);
}

TEST(MPMFlags, SplittingWithoutMatlIsMaterialZeroWithAWarning) {
  const auto splitting = [](const std::string& matl) {
    return read(
        "<MPM><refine_particles>true</refine_particles></MPM><AMR><MPM>"
        "<Refinement_Criteria_Thresholds><Variable name=\"stretchRatio\" value=\"2\"" +
        matl + "/></Refinement_Criteria_Thresholds></MPM></AMR>");
  };
  const Read none = splitting("");
  EXPECT_EQ(none.flags.refineMaterial, 0);
  ASSERT_EQ(none.spec->warnings().size(), 1u);
  EXPECT_NE(none.spec->warnings()[0].find("without matl="), std::string::npos);
  const Read all = splitting(" matl=\"all\"");
  EXPECT_EQ(all.flags.refineMaterial, -1);
  EXPECT_TRUE(all.spec->warnings().empty());
  EXPECT_EQ(splitting(" matl=\"1\"").flags.refineMaterial, 1);
}

}  // namespace
}  // namespace anode

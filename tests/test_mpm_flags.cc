// Pins <MPM>/<PhysicalConstants> reading (Components/MPM/MPMFlags.h) where Uintah has a fallback:
// gravity from <MPM> without <PhysicalConstants>, and the splitting criterion without matl=.
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

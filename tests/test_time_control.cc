// Pins <Time> (Core/Grid/TimeControl.h) and the time-step controller
// (Components/MPM/TimestepController.h): the step's dt from the stable one, clamped in Uintah's
// order, the implicit step's rules and retakes, which limit set each dt, and the tags <Time>
// accepts, refuses or leaves to a restart.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "Components/MPM/ImplicitOptions.h"
#include "Components/MPM/TimestepController.h"
#include "Core/Grid/TimeControl.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"

namespace anode {
namespace {

TimeControl read(const std::string& extra) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n<Time>\n<maxTime>1</maxTime><initTime>0</initTime>\n"
      "<delt_min>1e-6</delt_min><delt_max>0.1</delt_max>\n"
      "<timestep_multiplier>0.5</timestep_multiplier>\n" +
          extra + "\n</Time>\n</Uintah_specification>",
      "time.ups");
  return TimeControl::fromInput(spec->root().requireChild("Time"));
}

// An explicit run's limits with `stable` the smallest, set by `limit`.
StableTimestep limits(double stable, StableTimestep::Limit limit = StableTimestep::Mechanics) {
  StableTimestep s;
  s.bound[limit] = stable;
  return s;
}

// The dt an explicit run's controller plans from the stable dt, after a step of previousDt.
double explicitDt(const TimeControl& tc, double stable, double previousDt, double t) {
  return TimestepController(tc, nullptr).plan(limits(stable), previousDt, t, std::nullopt).dt;
}

TEST(TimeControl, TheStableStepTimesTheMultiplierWithinDeltMinAndDeltMax) {
  const TimeControl tc = read("");
  EXPECT_EQ(explicitDt(tc, 0.02, 0, 0), 0.01);
  EXPECT_EQ(explicitDt(tc, 1.0, 0, 0), 0.1);    // delt_max
  EXPECT_EQ(explicitDt(tc, 1e-8, 0, 0), 1e-6);  // delt_min
}

TEST(TimestepController, SaysWhichLimitSetTheDt) {
  const TimestepController explicitRun(read(""), nullptr);
  TimestepController::Plan p = explicitRun.plan(limits(0.02, StableTimestep::Diffusion), 0, 0, {});
  EXPECT_EQ(p.limit, StableTimestep::Diffusion);
  EXPECT_FALSE(p.setByTimeControl);
  p = explicitRun.plan(limits(1.0, StableTimestep::Flux), 0, 0, {});
  EXPECT_EQ(p.limit, StableTimestep::Flux);
  EXPECT_TRUE(p.setByTimeControl);  // delt_max
  EXPECT_EQ(p.dt, 0.1);
}

TEST(TimestepController, AnOutputTimeShortensTheStepButNotTheRuleDt) {
  const TimestepController clamped(read("<clamp_time_to_output>true</clamp_time_to_output>"),
                                   nullptr);
  TimestepController::Plan p = clamped.plan(limits(0.02), 0, 0.3, 0.305);
  EXPECT_EQ(p.dt, 0.305 - 0.3);  // ends on the output
  EXPECT_EQ(p.ruleDt, 0.01);
  EXPECT_TRUE(p.setByTimeControl);
  p = clamped.plan(limits(0.02), 0, 0.3, 0.5);  // the output lies beyond the step
  EXPECT_EQ(p.dt, 0.01);
  EXPECT_FALSE(p.setByTimeControl);
  const TimestepController unclamped(read(""), nullptr);
  EXPECT_EQ(unclamped.plan(limits(0.02), 0, 0.3, 0.305).dt, 0.01);
}

ImplicitOptions readImplicit(const std::string& mpm, bool diffusion = false) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n<MPM>\n" + mpm + "\n</MPM>\n</Uintah_specification>", "mpm.ups");
  return ImplicitOptions::fromInput(spec->root().requireChild("MPM"), diffusion);
}

// Quasi-static steps with diffusion are error-controlled by default (tolerance 0.01, trapezoidal
// coupling, Newton's criteria and a Jacobian without round-off couplings from it); not without
// diffusion, not on dynamic steps, not when the input asks for a staggered coupling or gives
// <error_tolerance>0.
TEST(TimestepController, ErrorControlIsTheDefaultWithDiffusion) {
  const std::string quasiStatic = "<dynamic>false</dynamic>";
  const ImplicitOptions lithiated = readImplicit(quasiStatic, true);
  EXPECT_EQ(lithiated.errorTolerance, ImplicitOptions::kDefaultErrorTolerance);
  EXPECT_EQ(lithiated.concentrationCoupling, ImplicitOptions::ConcentrationCoupling::Trapezoidal);
  EXPECT_EQ(lithiated.maxConcentrationChange, 0);
  EXPECT_DOUBLE_EQ(lithiated.convergenceDisp, 1e-6);
  EXPECT_EQ(lithiated.jacobianCouplingShare, ImplicitOptions::kErrorControlCouplingShare);
  EXPECT_EQ(readImplicit(quasiStatic + "<jacobian_coupling_share>0</jacobian_coupling_share>", true)
                .jacobianCouplingShare,
            0);
  EXPECT_EQ(readImplicit(quasiStatic, false).errorTolerance, 0);
  EXPECT_EQ(readImplicit("<dynamic>true</dynamic>", true).errorTolerance, 0);
  const ImplicitOptions staggered = readImplicit(
      quasiStatic + "<concentration_coupling>staggered</concentration_coupling>", true);
  EXPECT_EQ(staggered.errorTolerance, 0);
  EXPECT_EQ(staggered.concentrationCoupling, ImplicitOptions::ConcentrationCoupling::Staggered);
  const ImplicitOptions off =
      readImplicit(quasiStatic + "<error_tolerance>0</error_tolerance>", true);
  EXPECT_EQ(off.errorTolerance, 0);
  EXPECT_EQ(off.concentrationCoupling, ImplicitOptions::ConcentrationCoupling::Staggered);
  EXPECT_EQ(off.convergenceDisp, 1e-10);
  EXPECT_EQ(off.jacobianCouplingShare, 0);
}

// Under <error_tolerance> Newton's criteria the input leaves out are (tol / 10)^2 and 4x that,
// never below ImpMPM's defaults (1e-10, 4e-10); criteria given are kept.
TEST(TimestepController, ErrorToleranceSetsNewtonsCriteria) {
  const ImplicitOptions none = readImplicit("<dynamic>false</dynamic>");
  EXPECT_EQ(none.convergenceDisp, 1e-10);
  EXPECT_EQ(none.convergenceEnergy, 4e-10);
  const ImplicitOptions loose =
      readImplicit("<dynamic>false</dynamic><error_tolerance>0.01</error_tolerance>");
  EXPECT_DOUBLE_EQ(loose.convergenceDisp, 1e-6);
  EXPECT_DOUBLE_EQ(loose.convergenceEnergy, 4e-6);
  const ImplicitOptions tight =
      readImplicit("<dynamic>false</dynamic><error_tolerance>1e-6</error_tolerance>");
  EXPECT_EQ(tight.convergenceDisp, 1e-10);
  EXPECT_EQ(tight.convergenceEnergy, 4e-10);
  const ImplicitOptions given = readImplicit(
      "<dynamic>false</dynamic><error_tolerance>0.01</"
      "error_tolerance><convergence_criteria_disp>1e-9"
      "</convergence_criteria_disp>");
  EXPECT_EQ(given.convergenceDisp, 1e-9);
  EXPECT_DOUBLE_EQ(given.convergenceEnergy, 4e-6);
}

// <error_tolerance>: a step's estimate (of order dt^3) above it is retaken at
// dt x 0.9 (tol / e)^(1/3), at least a fifth of dt; after the first estimate dt grows by
// 0.9 (tol / e)^(1/3), at most 5 times; a step shortened to end on an output time counts as the
// one it was cut from, while the dt it took is kept for the next estimate; Newton's iterations
// only shrink dt; steps end on the output times.
TEST(TimestepController, ErrorEstimatesChooseTheSteps) {
  ImplicitOptions options;
  options.errorTolerance = 0.01;
  TimeControl time = read("");
  time.deltMax = 100;
  time.maxTime = 1000;
  TimestepController c(time, &options);
  ASSERT_TRUE(c.controlsError());
  EXPECT_TRUE(c.endsStepsOnOutputs());
  EXPECT_TRUE(c.rejectsErrorEstimate(0.0101));
  EXPECT_FALSE(c.rejectsErrorEstimate(0.01));
  EXPECT_DOUBLE_EQ(c.retakeForError(1, 0.08), 0.45);
  EXPECT_DOUBLE_EQ(c.retakeForError(1, 100), 0.2);
  EXPECT_EQ(c.afterNewton(1, options.itersToIncrease), std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.afterNewton(1, options.itersToDecrease), options.decreaseFactor);
  // Before any estimate the controller sets no limit.
  EXPECT_EQ(c.plan(limits(3, StableTimestep::Newton), 0, 0, std::nullopt).dt, 3);
  c.recordStep(0.00125, 1, 1);  // first estimate: 0.9 x 2
  TimestepController::Plan p = c.plan(limits(100, StableTimestep::Newton), 1, 1, std::nullopt);
  EXPECT_DOUBLE_EQ(p.dt, 1.8);
  EXPECT_EQ(p.limit, StableTimestep::ErrorEstimate);
  // A step of 0.5 cut from 1 by an output time, its estimate an eighth of the same step's.
  TimestepController cut(time, &options);
  cut.recordStep(0.00125 / 8, 0.5, 1);
  EXPECT_DOUBLE_EQ(cut.plan(limits(100), 1, 1, std::nullopt).dt, 1.8);
  EXPECT_DOUBLE_EQ(cut.errorControl().takenDt, 0.5);
  // PI: 0.9 (tol / e_n)^(1/3 - 0.03) (e_{n-1} / tol)^0.04; growth at most 5x.
  c.recordStep(0.01, 1.8, 1.8);
  EXPECT_DOUBLE_EQ(c.plan(limits(100), 1.8, 2.8, std::nullopt).dt,
                   1.8 * 0.9 * std::pow(0.00125 / 0.01, 0.04));
  c.recordStep(1e-9, 1, 1);
  EXPECT_DOUBLE_EQ(c.plan(limits(100), 1, 3.8, std::nullopt).dt, 5);
  // A step without an estimate (no diffusion in it) changes nothing.
  c.recordStep(-1, 1, 1);
  EXPECT_DOUBLE_EQ(c.errorControl().lastEstimate, 1e-9);
  // Steps end on the output times without <clamp_time_to_output>, and the steps to an output time
  // are of one length: 1.0 to go in steps of at most 0.4 is three of 1/3.
  EXPECT_EQ(c.plan(limits(0.5, StableTimestep::Newton), 0.5, 0, 0.2).dt, 0.2);
  const TimestepController::Plan even = c.plan(limits(0.4, StableTimestep::Newton), 0.4, 0, 1.0);
  EXPECT_DOUBLE_EQ(even.dt, 1.0 / 3);
  EXPECT_DOUBLE_EQ(even.ruleDt, 0.4);
  EXPECT_EQ(even.limit, StableTimestep::Newton);  // the pace is the limit's
  EXPECT_FALSE(even.setByTimeControl);
  EXPECT_DOUBLE_EQ(c.plan(limits(0.5, StableTimestep::Newton), 0.5, 0, 1.0).dt, 0.5);
}

TEST(TimestepController, AnImplicitRunsMultiplierIsItsSubstepsNotItsDt) {
  const ImplicitOptions options;
  const TimestepController implicitRun(read(""), &options);
  // ImpMPM's rule sets the dt: no multiplier (0.5 in <Time>) on it.
  const TimestepController::Plan p =
      implicitRun.plan(limits(0.02, StableTimestep::Newton), 0.01, 0.3, std::nullopt);
  EXPECT_EQ(p.dt, 0.02);
  EXPECT_EQ(p.limit, StableTimestep::Newton);
  EXPECT_FALSE(p.setByTimeControl);
  EXPECT_EQ(implicitRun.substepMultiplier(), 0.5);
}

TEST(TimestepController, ImpMPMsRuleGrowsAfterFewIterationsAndShrinksAfterMany) {
  ImplicitOptions options;  // ImpMPM's defaults: x2 at <= 4 iterations, x0.6 at >= 12
  const TimestepController c(read(""), &options);
  EXPECT_EQ(c.afterNewton(1.0, 4), 2.0);
  EXPECT_EQ(c.afterNewton(1.0, 5), 1.0);
  EXPECT_EQ(c.afterNewton(1.0, 11), 1.0);
  EXPECT_EQ(c.afterNewton(1.0, 12), 0.6);
}

TEST(TimestepController, TheConcentrationChangeBoundsTheNextDtAndRetakesPastTwiceIt) {
  ImplicitOptions options;
  options.maxConcentrationChange = 0.05;
  const TimestepController c(read(""), &options);
  EXPECT_DOUBLE_EQ(c.forConcentrationChange(1.0, 0.1), 0.5);
  EXPECT_FALSE(c.retakesConcentrationChange(0.1));
  EXPECT_TRUE(c.retakesConcentrationChange(0.1001));
  EXPECT_DOUBLE_EQ(c.retakeDt(1.0, 0.2), 0.25);  // the dt the bound allows
  EXPECT_DOUBLE_EQ(c.retakeDt(1.0, 5.0), 0.1);   // but no less than a tenth
  EXPECT_DOUBLE_EQ(c.retakeDt(1.0, 0), 0.6);     // Newton failed: <delT_decrease_factor>
}

TEST(TimestepController, ARetakeStopsBelowDeltMinOrAfterTwentyRetakes) {
  const ImplicitOptions options;
  const TimestepController c(read(""), &options);
  EXPECT_EQ(c.refusesRetake(1e-3, 0), "");
  EXPECT_NE(c.refusesRetake(1e-7, 0).find("below <delt_min>"), std::string::npos);
  EXPECT_EQ(c.refusesRetake(1e-3, 19), "");
  EXPECT_NE(c.refusesRetake(1e-3, 20).find("20 retakes"), std::string::npos);
}

// Newton stalling at the same ratios however small dt becomes stops the retakes once the
// attempts span 3 retakes and 8x in dt; ratios that move, or too small a span, do not.
TEST(TimestepController, ANewtonThatStallsWhateverDtStopsTheRetakes) {
  using Failed = TimestepController::FailedNewton;
  std::vector<Failed> failed;
  for (double dt = 17; failed.size() < 6; dt *= 0.6) failed.push_back({dt, 0.1, 6.7e-5});
  // 17 x 0.6^4 = 2.2: five attempts span 7.7x, six 12.9x.
  EXPECT_EQ(TimestepController::refusesStalledNewton({failed.begin(), failed.begin() + 5}), "");
  const std::string refusal = TimestepController::refusesStalledNewton(failed);
  EXPECT_NE(refusal.find("Newton stalls whatever dt"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("over 6 attempts"), std::string::npos) << refusal;
  // Ratios 4% apart still stall; one 6% off the newest does not.
  failed[2].dispRatio = 0.104;
  EXPECT_NE(TimestepController::refusesStalledNewton(failed), "");
  failed[0].energyRatio = 6.7e-5 * 1.06;
  failed[1].energyRatio = 6.7e-5 * 1.06;
  EXPECT_EQ(TimestepController::refusesStalledNewton(failed), "");
  // The newest attempts alone can span 8x with a sharper cut: four attempts at 0.5 do.
  std::vector<Failed> halved;
  for (double dt = 16; halved.size() < 4; dt /= 2) halved.push_back({dt, 0.3, 0.01});
  EXPECT_NE(TimestepController::refusesStalledNewton(halved), "");
  halved.pop_back();
  EXPECT_EQ(TimestepController::refusesStalledNewton(halved), "");
}

TEST(TimeControl, ClampsInUintahsOrder) {
  const TimeControl tc = read(
      "<max_delt_increase>0.5</max_delt_increase><delt_init>0.004</delt_init>"
      "<initial_delt_range>0.2</initial_delt_range>"
      "<end_at_max_time_exactly>true</end_at_max_time_exactly>");
  EXPECT_DOUBLE_EQ(explicitDt(tc, 0.1, 0.002, 0.5), 0.003);  // at most 1.5 x the previous step
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 0.1), 0.004);             // delt_init within the initial range
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 0.99), 1 - 0.99);         // ends at maxTime
  // A round-off remainder joins the step before it.
  const double almost = 1 - 0.05 - 1e-15;
  EXPECT_EQ(explicitDt(tc, 0.1, 0, almost), 1 - almost);
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 1 - 0.05 - 1e-6), 0.05);
}

TEST(TimeControl, InitialRangeEndsAtAnAbsoluteTimeAndZeroDeltInitCapsNothing) {
  TimeControl tc = read("<delt_init>0.004</delt_init><initial_delt_range>0.2</initial_delt_range>");
  tc.initTime = 0.5;  // a run starting after the range: no cap (Uintah: t + dt <= range)
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 0.6), 0.05);
  tc.initTime = 0;
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 0.2), 0.004);
  EXPECT_EQ(explicitDt(tc, 0.1, 0, 0.21), 0.05);
  EXPECT_EQ(explicitDt(read("<delt_init>0</delt_init>"), 0.02, 0, 0), 0.01);
  EXPECT_THROW(read("<delt_init>-1</delt_init>"), InputError);
}

TEST(TimeControl, OverrideRestartDeltOnlyAsZero) {
  EXPECT_NO_THROW(read("<override_restart_delt>0</override_restart_delt>"));
  try {
    read("<override_restart_delt>1e-5</override_restart_delt>");
    FAIL() << "a nonzero <override_restart_delt> was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 6);
    EXPECT_NE(std::string(e.what()).find("<override_restart_delt> other than 0"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace anode

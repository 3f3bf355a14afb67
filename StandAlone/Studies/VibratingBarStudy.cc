// vibrating_bar_study [--quick] [--csv FILE] [--amplitude R] [--timestep-multiplier M] [--periods
// P] [--implicit N]: convergence study of the axial vibrating bar
// (StandAlone/Studies/VibratingBar.h) for the linear, GIMP and CPDI interpolators, by default over
// one period. Prints a table and writes a CSV (default verification/vibrating_bar.csv, relative to
// the working directory). Orders are log(error ratio)/log(resolution ratio) between successive
// resolutions. "stag" and "leapfrog" are the staggered metrics of VibratingBarResult. --implicit N:
// implicit dynamics (Newmark) in N steps a period instead of explicit steps.
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/VibratingBar.h"

namespace {

void usage(FILE* out) {
  std::fprintf(out,
               "usage: vibrating_bar_study [--quick] [--csv FILE] [--amplitude R] "
               "[--timestep-multiplier M] [--periods P] [--implicit N]\n"
               "  --quick     the test's resolutions (8, 16, 32 cells) only\n"
               "  --csv FILE  where to write the results (default verification/vibrating_bar.csv)\n"
               "  --amplitude R               v0/c (default 1e-4)\n"
               "  --timestep-multiplier M     <timestep_multiplier> (default 0.2)\n"
               "  --periods P                 run length in periods (default 1)\n"
               "  --implicit N                implicit dynamics (Newmark), N steps a period\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csvPath = "verification/vibrating_bar.csv";
  anode::VibratingBarCase base;
  anode::StudyCommandLine args("vibrating_bar_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.positiveNumber("--amplitude", base.amplitudeRatio);
  args.positiveNumber("--timestep-multiplier", base.timestepMultiplier);
  args.positiveNumber("--periods", base.periods);
  args.positiveInteger("--implicit", base.implicitStepsPerPeriod);
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;

  try {
    const std::vector<int> cells =
        quick ? anode::vibratingBarQuickCells() : anode::vibratingBarStudyCells();
    std::printf(
        "Axial vibrating bar: L = %g m, c = %g m/s, v0/c = %g, T = %g s, %s, %g period(s)\n",
        base.length, base.waveSpeed(), base.amplitudeRatio, base.period(),
        base.implicitStepsPerPeriod > 0
            ? ("implicit dynamics, " + std::to_string(base.implicitStepsPerPeriod) +
               " steps a period")
                  .c_str()
            : ("timestep_multiplier " + std::to_string(base.timestepMultiplier)).c_str(),
        base.periods);
    std::printf("%-6s %5s %5s %6s %8s | %9s %5s | %9s %5s | %9s %5s | %9s %5s | %9s\n", "interp",
                "cells", "parts", "steps", "wall [s]", "vcm err", "order", "vcm stag", "order",
                "L2 v err", "order", "E drift", "order", "leapfrog");

    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "interpolator,cells,particles,steps,wall_seconds,vcm_error,vcm_order,vcm_error_"
           "staggered,"
           "vcm_staggered_order,velocity_l2_error,velocity_l2_order,energy_drift,energy_drift_"
           "order,"
           "leapfrog_energy_drift,max_transverse_velocity\n";
    char line[512];
    using anode::VibratingBarResult;
    anode::runEachResolution(
        base, cells, anode::runVibratingBar,
        [&](const VibratingBarResult& r, const VibratingBarResult* coarser) {
          auto order = [&](double VibratingBarResult::*metric) {
            return anode::convergenceOrder(coarser, r, metric);
          };
          const std::string o1 = order(&VibratingBarResult::centreOfMassError);
          const std::string o2 = order(&VibratingBarResult::centreOfMassErrorStaggered);
          const std::string o3 = order(&VibratingBarResult::velocityL2Error);
          const std::string o4 = order(&VibratingBarResult::energyDrift);
          const char* interpolator = r.interpolator.c_str();
          std::printf(
              "%-6s %5d %5zu %6ld %8.3f | %9.3e %5s | %9.3e %5s | %9.3e %5s | %9.3e %5s | %9.3e\n",
              interpolator, r.cells, r.particles, r.steps, r.wallSeconds, r.centreOfMassError,
              o1.c_str(), r.centreOfMassErrorStaggered, o2.c_str(), r.velocityL2Error, o3.c_str(),
              r.energyDrift, o4.c_str(), r.leapfrogEnergyDrift);
          std::fflush(stdout);
          std::snprintf(
              line, sizeof line, "%s,%d,%zu,%ld,%.4f,%.6e,%s,%.6e,%s,%.6e,%s,%.6e,%s,%.6e,%.3e\n",
              interpolator, r.cells, r.particles, r.steps, r.wallSeconds, r.centreOfMassError,
              o1.c_str(), r.centreOfMassErrorStaggered, o2.c_str(), r.velocityL2Error, o3.c_str(),
              r.energyDrift, o4.c_str(), r.leapfrogEnergyDrift, r.transverseVelocity);
          csv << line;
        });
    std::printf("wrote %s\n", csvPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vibrating_bar_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

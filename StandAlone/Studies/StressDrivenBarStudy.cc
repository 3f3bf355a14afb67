// stress_driven_bar_study [--quick] [--csv FILE] [--interpolator I] [--dt DT] [--threads N]:
// stress-driven diffusion on the quasi-static path (StandAlone/Studies/StressDrivenBar.h): a bar
// under gravity held laterally, at equilibrium against the closed form c / (1 - c) = A exp(phi),
// and in its transient (t = 0.05) against a finite-volume solution of the same equation; per
// resolution the particles, h, the largest and mean |c - reference| with their orders, the steps,
// Newton's iterations and the wall time. Writes a CSV (default verification/stress_driven_bar.csv).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "StandAlone/Studies/StressDrivenBar.h"
#include "StandAlone/Studies/StudyTools.h"

namespace {

void usage(FILE* out) {
  std::fprintf(out,
               "usage: stress_driven_bar_study [--quick] [--csv FILE] [--interpolator I] [--dt DT] "
               "[--threads N]\n"
               "  --quick            the test's resolutions (12 and 24 cells) only\n"
               "  --csv FILE         where to write the results (default "
               "verification/stress_driven_bar.csv)\n"
               "  --interpolator I   linear, gimp (default) or cpdi\n"
               "  --dt DT            the transient's steps (default 0.001)\n"
               "  --threads N        OpenMP threads per run (default 1; 0: OpenMP's default)\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csvPath = "verification/stress_driven_bar.csv";
  anode::StressDrivenBarCase base;
  base.threads = 1;
  double transientDt = 0.001;
  anode::StudyCommandLine args("stress_driven_bar_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.option("--interpolator", [&](const char* name) { base.interpolator = name; });
  args.option("--dt", [&](const char* dt) {
    transientDt = std::atof(dt);
    if (!(transientDt > 0)) args.fail("--dt needs a number > 0");
  });
  args.option("--threads", [&](const char* n) {
    base.threads = std::atoi(n);
    if (base.threads < 0) args.fail("--threads needs a number >= 0");
  });
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;

  try {
    const std::vector<int> cells =
        quick ? std::vector<int>{12, 24} : std::vector<int>{12, 24, 48, 96};
    std::printf(
        "Stress-driven bar: L = %g, D = %g, rho g = %g, K = %g, G = %g, k = %g, c0 = %g, %s\n",
        base.length, base.diffusivity, base.density * base.gravity, base.bulkModulus,
        base.shearModulus, base.stressCoupling / base.cmaxRT, base.initialConcentration,
        base.interpolator.c_str());
    std::printf("%-11s %6s %5s %6s | %9s %5s | %9s %5s | %5s %6s %8s\n", "reference", "t", "cells",
                "parts", "max err", "order", "mean err", "order", "steps", "Newton", "wall [s]");
    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "reference,end_time,max_dt,interpolator,cells,h,particles,steps,newton,wall_seconds,"
           "largest_error,mean_error,concentration_range\n";
    using R = anode::StressDrivenBarResult;
    for (const bool equilibrium : {true, false}) {
      R coarser;
      for (size_t i = 0; i < cells.size(); ++i) {
        anode::StressDrivenBarCase c = base;
        c.cells = cells[i];
        if (!equilibrium) c.endTime = 0.05, c.maxDt = transientDt;
        const R r = anode::runStressDrivenBar(c, equilibrium);
        const R* before = i == 0 ? nullptr : &coarser;
        const char* name = equilibrium ? "closed form" : "1-D FV";
        std::printf("%-11s %6g %5d %6zu | %9.3e %5s | %9.3e %5s | %5ld %6ld %8.2f\n", name,
                    c.endTime, r.cells, r.particles, r.largestError,
                    anode::convergenceOrder(before, r, &R::largestError).c_str(), r.meanError,
                    anode::convergenceOrder(before, r, &R::meanError).c_str(), r.steps,
                    r.newtonIterations, r.wallSeconds);
        std::fflush(stdout);
        char line[512];
        std::snprintf(line, sizeof line, "%s,%g,%g,%s,%d,%.6g,%zu,%ld,%ld,%.4f,%.6e,%.6e,%.6e\n",
                      equilibrium ? "closed_form" : "finite_volume", c.endTime, c.maxDt,
                      r.interpolator.c_str(), r.cells, r.h, r.particles, r.steps,
                      r.newtonIterations, r.wallSeconds, r.largestError, r.meanError,
                      r.concentrationRange);
        csv << line;
        coarser = r;
      }
    }
    std::printf("wrote %s\n", csvPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stress_driven_bar_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

// flux_slab_study [--quick] [--csv FILE] [--profile FILE] [--threads N] [--timestep-multiplier M]
// [--flux J] [--fourier F] [--potentiostatic K] [--held C]:
// convergence study of the flux-BC slab (StandAlone/Studies/FluxSlab.h, Carslaw & Jaeger) for the
// linear, GIMP and CPDI interpolators. Prints a table and writes a CSV (default
// verification/flux_slab.csv, relative to the working directory). Orders are log(error
// ratio)/log(resolution ratio) between successive resolutions. The lithium balance column is |sum m
// c(t) - sum m c(0) - sum_steps dt sum_p m_p rate_p| / sum_steps(...), rate_p the flux rate of the
// step's start. --profile writes the final particle profiles (x, c_p, analytic c) of every run.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "StandAlone/Studies/FluxSlab.h"
#include "StandAlone/Studies/StudyTools.h"

namespace {

void usage(FILE* out) {
  std::fprintf(
      out,
      "usage: flux_slab_study [--quick] [--csv FILE] [--profile FILE] [--threads N]\n"
      "                       [--timestep-multiplier M] [--flux J] [--fourier F]\n"
      "                       [--potentiostatic K] [--held C]\n"
      "  --quick     the test's resolutions (8, 16, 32 cells) only\n"
      "  --csv FILE  where to write the results (default verification/flux_slab.csv)\n"
      "  --profile FILE              also write the final particle profiles\n"
      "  --threads N                 OpenMP threads per run (default 1; 0: OpenMP's default)\n"
      "  --timestep-multiplier M     <timestep_multiplier> (default 0.2)\n"
      "  --flux J                    the flux into the x+ face (default 1e-6)\n"
      "  --fourier F                 run length D t / L^2 (default 0.25)\n"
      "  --potentiostatic K          hold the x+ face at c_s through J = K (c_s - c) instead\n"
      "                              (against the plane wall's series, Bi = K L / D)\n"
      "  --held C                    c_s of --potentiostatic (default 0.5)\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csvPath = "verification/flux_slab.csv", profilePath;
  anode::FluxSlabCase base;
  base.threads = 1;
  anode::StudyCommandLine args("flux_slab_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.option("--profile", [&](const char* path) { profilePath = path; });
  args.option("--threads", [&](const char* n) {
    base.threads = std::atoi(n);
    if (base.threads < 0) args.fail("--threads needs a number >= 0");
  });
  args.positiveNumber("--timestep-multiplier", base.timestepMultiplier);
  args.positiveNumber("--flux", base.flux);
  args.positiveNumber("--fourier", base.fourier);
  args.positiveNumber("--potentiostatic", base.surfaceRate);
  args.positiveNumber("--held", base.heldConcentration);
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;

  try {
    const std::vector<int> cells =
        quick ? anode::fluxSlabQuickCells() : anode::fluxSlabStudyCells();
    if (base.surfaceRate > 0)
      std::printf(
          "Potentiostatic slab (plane wall, Robin): L = %g, D = %g, c_s = %g, k = %g (Bi = %g), "
          "t = %g (D t/L^2 = %g), timestep_multiplier %g\n",
          base.length, base.diffusivity, base.heldConcentration, base.surfaceRate,
          base.surfaceRate * base.length / base.diffusivity, base.endTime(), base.fourier,
          base.timestepMultiplier);
    else
      std::printf(
          "Flux slab (Carslaw & Jaeger): L = %g, D = %g, J = %g, t = %g (D t/L^2 = %g), "
          "timestep_multiplier %g\n",
          base.length, base.diffusivity, base.flux, base.endTime(), base.fourier,
          base.timestepMultiplier);
    std::printf("%-6s %5s %5s %7s %8s | %9s %5s | %9s %5s | %9s %5s | %9s %9s %9s | %9s %9s\n",
                "interp", "cells", "parts", "steps", "wall [s]", "L2 err", "order", "max err",
                "order", "x<=L/2", "order", "max c", "min c", "1-R(c)", "Li bal.", "inj/exact-1");

    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "interpolator,cells,h,particles,steps,dt,wall_seconds,l2_error,l2_order,max_error,max_"
           "order,interior_max_error,interior_max_order,max_error_at,max_concentration,min_"
           "concentration,restriction_deviation,lithium_balance_error,injected_vs_exact\n";
    std::ofstream profile;
    if (!profilePath.empty()) {
      profile = anode::createOutputFile(profilePath);
      profile << "interpolator,cells,x,c,c_exact,error\n";
    }
    char line[512];
    using anode::FluxSlabResult;
    anode::runEachResolution(
        base, cells, anode::runFluxSlab,
        [&](const FluxSlabResult& r, const FluxSlabResult* coarser) {
          const std::string o1 = anode::convergenceOrder(coarser, r, &FluxSlabResult::l2Error);
          const std::string o2 = anode::convergenceOrder(coarser, r, &FluxSlabResult::maxError);
          const std::string o3 =
              anode::convergenceOrder(coarser, r, &FluxSlabResult::interiorMaxError);
          const char* interpolator = r.interpolator.c_str();
          std::printf(
              "%-6s %5d %5zu %7ld %8.3f | %9.3e %5s | %9.3e %5s | %9.3e %5s | %9.3e %9.2e %9.2e "
              "| %9.2e %9.2e\n",
              interpolator, r.cells, r.particles, r.steps, r.wallSeconds, r.l2Error, o1.c_str(),
              r.maxError, o2.c_str(), r.interiorMaxError, o3.c_str(), r.maxConcentration,
              r.minConcentration, r.maxRestrictionDeviation, r.balanceError(), r.injectedVsExact);
          std::fflush(stdout);
          std::snprintf(line, sizeof line,
                        "%s,%d,%.6g,%zu,%ld,%.6e,%.4f,%.6e,%s,%.6e,%s,%.6e,%s,%.8g,"
                        "%.6e,%.6e,%.6e,%.3e,%.3e\n",
                        interpolator, r.cells, base.length / r.cells, r.particles, r.steps, r.dt,
                        r.wallSeconds, r.l2Error, o1.c_str(), r.maxError, o2.c_str(),
                        r.interiorMaxError, o3.c_str(), r.maxErrorAt, r.maxConcentration,
                        r.minConcentration, r.maxRestrictionDeviation, r.balanceError(),
                        r.injectedVsExact);
          csv << line;
          for (size_t k = 0; profile.is_open() && k < r.x.size(); ++k) {
            std::snprintf(line, sizeof line, "%s,%d,%.10g,%.10e,%.10e,%.4e\n", interpolator,
                          r.cells, r.x[k], r.c[k], r.exact[k], r.c[k] - r.exact[k]);
            profile << line;
          }
        });
    std::printf("wrote %s\n", csvPath.c_str());
    if (profile.is_open()) std::printf("wrote %s\n", profilePath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flux_slab_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

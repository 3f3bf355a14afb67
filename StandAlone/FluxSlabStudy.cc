// flux_slab_study [--quick] [--csv FILE] [--profile FILE] [--threads N] [--timestep-multiplier M]
// [--flux J] [--fourier F]:
// convergence study of the flux-BC slab (StandAlone/FluxSlab.h, Carslaw & Jaeger) for the linear,
// GIMP and CPDI interpolators. Prints a table and writes a CSV (default verification/flux_slab.csv,
// relative to the working directory). Orders are log(error ratio)/log(resolution ratio) between
// successive resolutions. The lithium balance column is |sum m c(t) - sum m c(0) - sum_steps dt
// sum_p m_p rate_p| / sum_steps(...), rate_p the flux rate of the step's start. --profile writes
// the final particle profiles (x, c_p, analytic c) of every run.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "StandAlone/FluxSlab.h"

namespace {

void usage(FILE* out) {
  std::fprintf(
      out,
      "usage: flux_slab_study [--quick] [--csv FILE] [--profile FILE] [--threads N]\n"
      "                       [--timestep-multiplier M] [--flux J] [--fourier F]\n"
      "  --quick     the test's resolutions (8, 16, 32 cells) only\n"
      "  --csv FILE  where to write the results (default verification/flux_slab.csv)\n"
      "  --profile FILE              also write the final particle profiles\n"
      "  --threads N                 OpenMP threads per run (default 1; 0: OpenMP's default)\n"
      "  --timestep-multiplier M     <timestep_multiplier> (default 0.2)\n"
      "  --flux J                    the flux into the x+ face (default 1e-6)\n"
      "  --fourier F                 run length D t / L^2 (default 0.25)\n");
}

std::string order(double coarse, double fine, double ratio) {
  if (!(coarse > 0) || !(fine > 0)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", std::log(coarse / fine) / std::log(ratio));
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csvPath = "verification/flux_slab.csv", profilePath;
  anode::FluxSlabCase base;
  base.threads = 1;
  auto positive = [&](int& i) {
    const double v = std::atof(argv[++i]);
    if (!(v > 0)) {
      std::fprintf(stderr, "flux_slab_study: %s needs a positive number\n", argv[i - 1]);
      std::exit(2);
    }
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) {
      csvPath = argv[++i];
    } else if (!std::strcmp(argv[i], "--profile") && i + 1 < argc) {
      profilePath = argv[++i];
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      base.threads = std::atoi(argv[++i]);
      if (base.threads < 0) {
        std::fprintf(stderr, "flux_slab_study: --threads needs a number >= 0\n");
        return 2;
      }
    } else if (!std::strcmp(argv[i], "--timestep-multiplier") && i + 1 < argc) {
      base.timestepMultiplier = positive(i);
    } else if (!std::strcmp(argv[i], "--flux") && i + 1 < argc) {
      base.flux = positive(i);
    } else if (!std::strcmp(argv[i], "--fourier") && i + 1 < argc) {
      base.fourier = positive(i);
    } else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      usage(stdout);
      return 0;
    } else {
      usage(stderr);
      return 2;
    }
  }

  try {
    const std::vector<int> cells =
        quick ? anode::fluxSlabQuickCells() : anode::fluxSlabStudyCells();
    std::printf(
        "Flux slab (Carslaw & Jaeger): L = %g, D = %g, J = %g, t = %g (D t/L^2 = %g), "
        "timestep_multiplier %g\n",
        base.length, base.diffusivity, base.flux, base.endTime(), base.fourier,
        base.timestepMultiplier);
    std::printf("%-6s %5s %5s %7s %8s | %9s %5s | %9s %5s | %9s %5s | %9s %9s %9s | %9s %9s\n",
                "interp", "cells", "parts", "steps", "wall [s]", "L2 err", "order", "max err",
                "order", "x<=L/2", "order", "max c", "min c", "1-R(c)", "Li bal.", "inj/exact-1");

    const std::filesystem::path path(csvPath);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream csv(path);
    if (!csv) throw std::runtime_error("cannot write " + csvPath);
    csv << "interpolator,cells,h,particles,steps,dt,wall_seconds,l2_error,l2_order,max_error,max_"
           "order,interior_max_error,interior_max_order,max_error_at,max_concentration,min_"
           "concentration,restriction_deviation,lithium_balance_error,injected_vs_exact\n";
    std::ofstream profile;
    if (!profilePath.empty()) {
      const std::filesystem::path pp(profilePath);
      if (pp.has_parent_path()) std::filesystem::create_directories(pp.parent_path());
      profile.open(pp);
      if (!profile) throw std::runtime_error("cannot write " + profilePath);
      profile << "interpolator,cells,x,c,c_exact,error\n";
    }
    char line[512];
    for (const char* interpolator : {"linear", "gimp", "cpdi"}) {
      anode::FluxSlabResult previous;
      for (size_t i = 0; i < cells.size(); ++i) {
        anode::FluxSlabCase c = base;
        c.cells = cells[i];
        c.interpolator = interpolator;
        const anode::FluxSlabResult r = anode::runFluxSlab(c);
        const bool first = i == 0;
        const double ratio = first ? 0 : double(cells[i]) / cells[i - 1];
        const std::string o1 = first ? "" : order(previous.l2Error, r.l2Error, ratio);
        const std::string o2 = first ? "" : order(previous.maxError, r.maxError, ratio);
        const std::string o3 =
            first ? "" : order(previous.interiorMaxError, r.interiorMaxError, ratio);
        std::printf(
            "%-6s %5d %5zu %7ld %8.3f | %9.3e %5s | %9.3e %5s | %9.3e %5s | %9.3e %9.2e %9.2e | "
            "%9.2e %9.2e\n",
            interpolator, r.cells, r.particles, r.steps, r.wallSeconds, r.l2Error, o1.c_str(),
            r.maxError, o2.c_str(), r.interiorMaxError, o3.c_str(), r.maxConcentration,
            r.minConcentration, r.maxRestrictionDeviation, r.balanceError(), r.injectedVsExact);
        std::fflush(stdout);
        std::snprintf(
            line, sizeof line,
            "%s,%d,%.6g,%zu,%ld,%.6e,%.4f,%.6e,%s,%.6e,%s,%.6e,%s,%.8g,%.6e,%.6e,%.6e,%.3e,%.3e\n",
            interpolator, r.cells, c.length / r.cells, r.particles, r.steps, r.dt, r.wallSeconds,
            r.l2Error, o1.c_str(), r.maxError, o2.c_str(), r.interiorMaxError, o3.c_str(),
            r.maxErrorAt, r.maxConcentration, r.minConcentration, r.maxRestrictionDeviation,
            r.balanceError(), r.injectedVsExact);
        csv << line;
        for (size_t k = 0; profile.is_open() && k < r.x.size(); ++k) {
          std::snprintf(line, sizeof line, "%s,%d,%.10g,%.10e,%.10e,%.4e\n", interpolator, r.cells,
                        r.x[k], r.c[k], r.exact[k], r.c[k] - r.exact[k]);
          profile << line;
        }
        previous = r;
      }
    }
    std::printf("wrote %s\n", csvPath.c_str());
    if (profile.is_open()) std::printf("wrote %s\n", profilePath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flux_slab_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

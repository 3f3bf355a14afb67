// vibrating_bar_study [--quick] [--csv FILE] [--amplitude R] [--timestep-multiplier M] [--periods
// P]: convergence study of the axial vibrating bar (StandAlone/VibratingBar.h) for the linear, GIMP
// and CPDI interpolators, by default over one period. Prints a table and writes a CSV (default
// verification/vibrating_bar.csv, relative to the working directory). Orders are log(error
// ratio)/log(resolution ratio) between successive resolutions. "stag" and "leapfrog" are the
// staggered metrics of VibratingBarResult.
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

#include "StandAlone/VibratingBar.h"

namespace {

void usage(FILE* out) {
  std::fprintf(out,
               "usage: vibrating_bar_study [--quick] [--csv FILE] [--amplitude R] "
               "[--timestep-multiplier M] [--periods P]\n"
               "  --quick     the test's resolutions (8, 16, 32 cells) only\n"
               "  --csv FILE  where to write the results (default verification/vibrating_bar.csv)\n"
               "  --amplitude R               v0/c (default 1e-4)\n"
               "  --timestep-multiplier M     <timestep_multiplier> (default 0.2)\n"
               "  --periods P                 run length in periods (default 1)\n");
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
  std::string csvPath = "verification/vibrating_bar.csv";
  anode::VibratingBarCase base;
  auto positive = [&](int& i) {
    const double v = std::atof(argv[++i]);
    if (!(v > 0)) {
      std::fprintf(stderr, "vibrating_bar_study: %s needs a positive number\n", argv[i - 1]);
      std::exit(2);
    }
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) {
      csvPath = argv[++i];
    } else if (!std::strcmp(argv[i], "--amplitude") && i + 1 < argc) {
      base.amplitudeRatio = positive(i);
    } else if (!std::strcmp(argv[i], "--timestep-multiplier") && i + 1 < argc) {
      base.timestepMultiplier = positive(i);
    } else if (!std::strcmp(argv[i], "--periods") && i + 1 < argc) {
      base.periods = positive(i);
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
        quick ? anode::vibratingBarQuickCells() : anode::vibratingBarStudyCells();
    std::printf(
        "Axial vibrating bar: L = %g m, c = %g m/s, v0/c = %g, T = %g s, timestep_multiplier %g, "
        "%g period(s)\n",
        base.length, base.waveSpeed(), base.amplitudeRatio, base.period(), base.timestepMultiplier,
        base.periods);
    std::printf("%-6s %5s %5s %6s %8s | %9s %5s | %9s %5s | %9s %5s | %9s %5s | %9s\n", "interp",
                "cells", "parts", "steps", "wall [s]", "vcm err", "order", "vcm stag", "order",
                "L2 v err", "order", "E drift", "order", "leapfrog");

    const std::filesystem::path path(csvPath);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream csv(path);
    if (!csv) throw std::runtime_error("cannot write " + csvPath);
    csv << "interpolator,cells,particles,steps,wall_seconds,vcm_error,vcm_order,vcm_error_"
           "staggered,"
           "vcm_staggered_order,velocity_l2_error,velocity_l2_order,energy_drift,energy_drift_"
           "order,"
           "leapfrog_energy_drift,max_transverse_velocity\n";
    char line[512];
    for (const char* interpolator : {"linear", "gimp", "cpdi"}) {
      anode::VibratingBarResult previous;
      for (size_t i = 0; i < cells.size(); ++i) {
        anode::VibratingBarCase c = base;
        c.cells = cells[i];
        c.interpolator = interpolator;
        const anode::VibratingBarResult r = anode::runVibratingBar(c);
        const bool first = i == 0;
        const double ratio = first ? 0 : double(cells[i]) / cells[i - 1];
        auto ord = [&](double anode::VibratingBarResult::*metric) {
          return first ? std::string() : order(previous.*metric, r.*metric, ratio);
        };
        const std::string o1 = ord(&anode::VibratingBarResult::centreOfMassError);
        const std::string o2 = ord(&anode::VibratingBarResult::centreOfMassErrorStaggered);
        const std::string o3 = ord(&anode::VibratingBarResult::velocityL2Error);
        const std::string o4 = ord(&anode::VibratingBarResult::energyDrift);
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
        previous = r;
      }
    }
    std::printf("wrote %s\n", csvPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vibrating_bar_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

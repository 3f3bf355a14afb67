// swelling_sphere_study [--quick] [--csv FILE] [--profile FILE] [--radius B]
// [--particles-per-cell P] [--hourglass E] [--interpolator I] [--threads N] [--explicit CELLS]
// [--damping A] [--settle T]: convergence of the quasi-static (implicit) step on
// the swelling sphere (StandAlone/Studies/SwellingSphere.h, Timoshenko & Goodier): per
// resolution the particles, h, the L2 errors of u_r, sigma_rr and sigma_tt with their orders,
// the wall time and Newton's and the Krylov iterations. Writes a CSV (default
// verification/swelling_sphere.csv). --explicit CELLS also runs the explicit path at that
// resolution (grid damping A c/b, to the times T b/c) and compares it with the implicit run
// and the closed form.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/SwellingSphere.h"

namespace {

void usage(FILE* out) {
  std::fprintf(
      out,
      "usage: swelling_sphere_study [--quick] [--csv FILE] [--profile FILE] [--radius B]\n"
      "                             [--particles-per-cell P] [--hourglass E] [--interpolator I]\n"
      "                             [--threads N] [--explicit CELLS] [--damping A] [--settle T]\n"
      "  --quick            the test's resolutions (4, 8, 16 cells per radius) only\n"
      "  --csv FILE         where to write the results (default verification/swelling_sphere.csv)\n"
      "  --profile FILE     also write each particle's r, u_r, sigma_rr, sigma_tt, exact values\n"
      "  --radius B         the sphere's radius (default 1000)\n"
      "  --particles-per-cell P  per cell and axis (default 2)\n"
      "  --hourglass E      <hourglass_stabilization> of the implicit runs (default 0.1)\n"
      "  --interpolator I   linear (default), gimp or cpdi\n"
      "  --threads N        OpenMP threads per run (default 1; 0: OpenMP's default)\n"
      "  --explicit CELLS   also run the explicit path at CELLS cells per radius\n"
      "  --damping A        its <artificial_damping_coeff> in units of c/b (default 5)\n"
      "  --settle T         its run length in units of b/c (default: 5, 10, 20 and 40 in turn)\n");
}

// One CSV row; the orders are empty for the explicit runs and the coarsest implicit one.
void writeRow(const anode::SwellingSphereResult& r, std::ofstream& csv, const std::string& ou = "",
              const std::string& orr = "", const std::string& ott = "") {
  char line[512];
  std::snprintf(line, sizeof line,
                "%s,%s,%d,%.6g,%zu,%ld,%.6g,%.4f,%.6e,%s,%.6e,%s,%.6e,%s,%.3e,%ld,%ld\n",
                r.integrator.c_str(), r.interpolator.c_str(), r.cells, r.h, r.particles, r.steps,
                r.finalTime, r.wallSeconds, r.radialDisplacementError, ou.c_str(),
                r.radialStressError, orr.c_str(), r.hoopStressError, ott.c_str(),
                r.tangentialDisplacement, r.newtonIterations, r.krylovIterations);
  csv << line;
}

// One implicit resolution: a line of the table and a CSV row.
void printRow(const anode::SwellingSphereResult& r, const anode::SwellingSphereResult* coarser,
              std::ofstream& csv) {
  using R = anode::SwellingSphereResult;
  auto order = [&](double R::*metric) {
    return coarser ? anode::convergenceOrder(coarser->*metric, r.*metric, coarser->h / r.h)
                   : std::string();
  };
  const std::string ou = order(&R::radialDisplacementError), orr = order(&R::radialStressError),
                    ott = order(&R::hoopStressError);
  std::printf("%5d %7.4g %8zu | %9.3e %5s | %9.3e %5s | %9.3e %5s | %8.1e | %8.3f | %6ld %7ld\n",
              r.cells, r.h, r.particles, r.radialDisplacementError, ou.c_str(), r.radialStressError,
              orr.c_str(), r.hoopStressError, ott.c_str(), r.tangentialDisplacement, r.wallSeconds,
              r.newtonIterations, r.krylovIterations);
  std::fflush(stdout);
  writeRow(r, csv, ou, orr, ott);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int explicitCells = 0;
  double damping = 5, settle = 0;
  std::string csvPath = "verification/swelling_sphere.csv", profilePath;
  anode::SwellingSphereCase base;
  base.threads = 1;
  anode::StudyCommandLine args("swelling_sphere_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.option("--profile", [&](const char* path) { profilePath = path; });
  args.option("--interpolator", [&](const char* name) { base.interpolator = name; });
  args.option("--threads", [&](const char* n) {
    base.threads = std::atoi(n);
    if (base.threads < 0) args.fail("--threads needs a number >= 0");
  });
  args.positiveInteger("--explicit", explicitCells);
  args.positiveInteger("--particles-per-cell", base.particlesPerCell);
  args.positiveNumber("--radius", base.radius);
  args.option("--hourglass", [&](const char* v) {
    base.hourglassStabilization = std::atof(v);
    if (!(base.hourglassStabilization >= 0)) args.fail("--hourglass needs a number >= 0");
  });
  args.positiveNumber("--damping", damping);
  args.positiveNumber("--settle", settle);
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;

  try {
    const std::vector<int> cells =
        quick ? anode::swellingSphereQuickCells() : anode::swellingSphereStudyCells();
    std::printf(
        "Swelling sphere (Timoshenko & Goodier): b = %g, K = %g, G = %g (E = %g, nu = %.4f), "
        "beta = %g, %s, %d particles per cell and axis\n",
        base.radius, base.bulkModulus, base.shearModulus, base.youngsModulus(),
        base.poissonsRatio(), base.surfaceStrain, base.interpolator.c_str(), base.particlesPerCell);
    std::printf("%5s %7s %8s | %9s %5s | %9s %5s | %9s %5s | %8s | %8s | %6s %7s\n", "cells", "h",
                "parts", "L2 u_r", "order", "L2 s_rr", "order", "L2 s_tt", "order", "u_t/u",
                "wall [s]", "Newton", "Krylov");
    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "integrator,interpolator,cells,h,particles,steps,final_time,wall_seconds,ur_error,"
           "ur_order,"
           "srr_error,srr_order,stt_error,stt_order,tangential_displacement,newton,krylov\n";
    std::ofstream profile;
    if (!profilePath.empty()) {
      profile = anode::createOutputFile(profilePath);
      profile << "integrator,cells,r,ur,ur_exact,srr,srr_exact,stt,stt_exact\n";
    }
    auto writeProfile = [&](const anode::SwellingSphereCase& c,
                            const anode::SwellingSphereResult& r) {
      char line[256];
      for (size_t k = 0; profile.is_open() && k < r.r.size(); ++k) {
        const anode::SwellingSphereExact x = anode::swellingSphereExact(c, r.r[k]);
        std::snprintf(line, sizeof line, "%s,%d,%.10g,%.8e,%.8e,%.8e,%.8e,%.8e,%.8e\n",
                      r.integrator.c_str(), r.cells, r.r[k], r.ur[k], x.radialDisplacement,
                      r.srr[k], x.radialStress, r.stt[k], x.hoopStress);
        profile << line;
      }
    };
    anode::SwellingSphereResult coarser, implicitAtExplicitCells;
    for (size_t i = 0; i < cells.size(); ++i) {
      anode::SwellingSphereCase c = base;
      c.cells = cells[i];
      const anode::SwellingSphereResult r = anode::runSwellingSphere(c);
      printRow(r, i == 0 ? nullptr : &coarser, csv);
      writeProfile(c, r);
      coarser = r;
      if (c.cells == explicitCells) implicitAtExplicitCells = r;
    }
    if (explicitCells > 0) {
      anode::SwellingSphereCase c = base;
      c.cells = explicitCells;
      if (implicitAtExplicitCells.particles == 0)
        implicitAtExplicitCells = anode::runSwellingSphere(c);
      const anode::SwellingSphereResult& q = implicitAtExplicitCells;
      c.integrator = "explicit";
      const double bOverC = c.radius / c.waveSpeed();
      c.damping = damping / bOverC;
      std::printf(
          "explicit at %d cells, damping %g c/b, against the implicit run (%.3f s, Newton %ld, "
          "Krylov %ld):\n%8s %6s %8s | %9s %9s %9s | %9s %9s %9s\n",
          explicitCells, damping, q.wallSeconds, q.newtonIterations, q.krylovIterations, "t [b/c]",
          "steps", "wall [s]", "L2 u_r", "L2 s_rr", "L2 s_tt", "diff u_r", "diff s_rr",
          "diff s_tt");
      const std::vector<double> settleTimes =
          settle > 0 ? std::vector<double>{settle} : std::vector<double>{5, 10, 20, 40};
      for (double T : settleTimes) {
        c.endTime = T * bOverC;
        const anode::SwellingSphereResult e = anode::runSwellingSphere(c);
        std::printf("%8g %6ld %8.3f | %9.3e %9.3e %9.3e | %9.3e %9.3e %9.3e\n", T, e.steps,
                    e.wallSeconds, e.radialDisplacementError, e.radialStressError,
                    e.hoopStressError, anode::relativeDifference(e.ur, q.ur),
                    anode::relativeDifference(e.srr, q.srr),
                    anode::relativeDifference(e.stt, q.stt));
        std::fflush(stdout);
        writeRow(e, csv);
        writeProfile(c, e);
      }
    }
    std::printf("wrote %s\n", csvPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swelling_sphere_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

// lithiated_sphere_study [--quick] [--csv FILE] [--interpolator I] [--cmax-rt X] [--threads N]:
// the quasi-static path's diffusion and swelling on the lithiated sphere
// (StandAlone/Studies/LithiatedSphere.h, Crank's constant-flux sphere and Timoshenko & Goodier's
// stresses; with --cmax-rt, stress-driven diffusion against its radial solution) with each
// <swelling_strain>:
// per resolution the particles, h, the L2 errors of c, sigma_rr and sigma_tt with their orders,
// the largest particle stress error, the steps, Newton's iterations and the wall time. Writes a
// CSV (default verification/lithiated_sphere.csv).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "StandAlone/Studies/LithiatedSphere.h"
#include "StandAlone/Studies/StudyTools.h"

namespace {

void usage(FILE* out) {
  std::fprintf(out,
               "usage: lithiated_sphere_study [--quick] [--csv FILE] [--interpolator I] "
               "[--cmax-rt X] [--threads N]\n"
               "  --quick            the test's resolutions (4 and 8 cells per radius) only\n"
               "  --csv FILE         where to write the results (default "
               "verification/lithiated_sphere.csv)\n"
               "  --interpolator I   linear, gimp or cpdi (default)\n"
               "  --cmax-rt X        stress-driven diffusion (chemical_potential) with this "
               "<cmax_RT>\n"
               "  --threads N        OpenMP threads per run (default 1; 0: OpenMP's default)\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csvPath = "verification/lithiated_sphere.csv";
  anode::LithiatedSphereCase base;
  base.threads = 1;
  anode::StudyCommandLine args("lithiated_sphere_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.option("--interpolator", [&](const char* name) { base.interpolator = name; });
  args.option("--cmax-rt", [&](const char* x) {
    base.cmaxRT = std::atof(x);
    if (!(base.cmaxRT > 0)) args.fail("--cmax-rt needs a number > 0");
  });
  args.option("--threads", [&](const char* n) {
    base.threads = std::atoi(n);
    if (base.threads < 0) args.fail("--threads needs a number >= 0");
  });
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;

  try {
    const std::vector<int> cells = quick ? std::vector<int>{4, 8} : std::vector<int>{4, 8, 16};
    std::printf(
        "Lithiated sphere (Crank, Timoshenko & Goodier): b = %g, D = %g, J = %g to t = %g, "
        "eta = %g, K = %g, G = %g, %s, %d particles per cell and axis, error_tolerance %g\n",
        base.radius, base.diffusivity, base.flux, base.endTime, base.expansion, base.bulkModulus,
        base.shearModulus, base.interpolator.c_str(), base.particlesPerCell, base.errorTolerance);
    if (base.cmaxRT > 0)
      std::printf("stress-driven diffusion: cmax_RT = %g, s = %g (against the radial solution)\n",
                  base.cmaxRT, base.stabilization());
    std::printf("%-9s %5s %8s | %9s %5s | %9s %5s | %9s %5s | %8s | %5s %6s %8s\n", "swelling",
                "cells", "parts", "L2 c", "order", "L2 s_rr", "order", "L2 s_tt", "order", "max s",
                "steps", "Newton", "wall [s]");
    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "swelling_strain,interpolator,cmax_rt,cells,h,particles,steps,newton,wall_seconds,"
           "c_error,srr_error,stt_error,largest_stress_error\n";
    using R = anode::LithiatedSphereResult;
    for (const char* swelling : {"particle", "cell_mean"}) {
      R coarser;
      for (size_t i = 0; i < cells.size(); ++i) {
        anode::LithiatedSphereCase c = base;
        c.cells = cells[i];
        c.swellingStrain = swelling;
        const R r = anode::runLithiatedSphere(c);
        const R* before = i == 0 ? nullptr : &coarser;
        std::printf(
            "%-9s %5d %8zu | %9.3e %5s | %9.3e %5s | %9.3e %5s | %8.3e | %5ld %6ld %8.2f\n",
            swelling, r.cells, r.particles, r.concentrationError,
            anode::convergenceOrder(before, r, &R::concentrationError).c_str(), r.radialStressError,
            anode::convergenceOrder(before, r, &R::radialStressError).c_str(), r.hoopStressError,
            anode::convergenceOrder(before, r, &R::hoopStressError).c_str(), r.largestStressError,
            r.steps, r.newtonIterations, r.wallSeconds);
        std::fflush(stdout);
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%g,%d,%.6g,%zu,%ld,%ld,%.4f,%.6e,%.6e,%.6e,%.6e\n",
                      swelling, r.interpolator.c_str(), r.cmaxRT, r.cells, r.h, r.particles,
                      r.steps, r.newtonIterations, r.wallSeconds, r.concentrationError,
                      r.radialStressError, r.hoopStressError, r.largestStressError);
        csv << line;
        coarser = r;
      }
    }
    std::printf("wrote %s\n", csvPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lithiated_sphere_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

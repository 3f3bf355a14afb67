// diffusion_1d_study [--quick] [--csv FILE] [--plots DIR] [--no-plots] [--replot] [--finest-all]
// [--interpolators LIST] [--variants LIST] [--cells LIST] [--jobs N] [--threads N]: the paper's
// 1-D diffusion verification (§2.2, StandAlone/Studies/DiffusionSlab1D.h) for the linear, GIMP and
// CPDI interpolators and the SD-Type Dirichlet treatments (variants particle, nodal, particle-wide,
// nodal-wide, nodal-clamp; see setDiffusionSlabVariant). Prints a table, writes a CSV (default
// verification/diffusion_1d.csv, relative to the working directory) and, with gnuplot, PNG plots
// of the errors against h and against the wall time (default docs/images; the quick run plots
// only with --plots). Orders are log(error ratio)/log(h ratio) between successive resolutions of
// the same interpolator and variant. The runs are small (at most 2000 particles): each uses one
// OpenMP thread by default, and two runs go side by side (--jobs).
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "StandAlone/Studies/DiffusionSlab1D.h"
#include "StandAlone/Studies/StudyTools.h"

namespace {

using anode::DiffusionSlabResult;

void usage(FILE* out) {
  std::fprintf(
      out,
      "usage: diffusion_1d_study [--quick] [--csv FILE] [--plots DIR] [--no-plots] [--replot]\n"
      "                          [--finest-all]\n"
      "                          [--interpolators LIST] [--variants LIST] [--cells LIST]\n"
      "                          [--jobs N] [--threads N]\n"
      "  --quick              the test's resolutions (h = 1/20, 1/40, 1/80) only; no plots\n"
      "                       unless --plots is given\n"
      "  --csv FILE           results (default verification/diffusion_1d.csv, quick:\n"
      "                       verification/diffusion_1d_quick.csv)\n"
      "  --plots DIR          where the PNGs go (default docs/images for the full study)\n"
      "  --no-plots           do not run gnuplot\n"
      "  --replot             no runs: only the plots, from the CSV (--csv) of an earlier run\n"
      "  --finest-all         run h = 0.001 for gimp and cpdi too (by default only for linear:\n"
      "                       ~3 CPU minutes per run, and gimp and cpdi equal linear here)\n"
      "  --interpolators L    comma-separated (default linear,gimp,cpdi)\n"
      "  --variants L         comma-separated Dirichlet variants (default\n"
      "                       particle,nodal,particle-wide,nodal-wide; also nodal-clamp)\n"
      "  --cells L            comma-separated cell counts 1/h, run for every interpolator\n"
      "                       (default 10,20,50,100,200,500,1000)\n"
      "  --jobs N             runs side by side (default 2)\n"
      "  --threads N          OpenMP threads per run (default 1)\n");
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", v);
  return buf;
}

std::string conc(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.8g", v);
  return buf;
}

// The reference (an independent implementation of Eqs. 4-8, Uintah's nodal Dirichlet, linear
// shape functions, D = 0.1, dt = 0.4 h^2/(2D)): h, RMS absolute error, Eq. 15.
struct Reference {
  double h, rmsAbsolute, paperNorm;
};
const Reference kReference[] = {{0.05, 1.57e-2, 1.02e-1},
                                {0.02, 3.81e-3, 2.29e-2},
                                {0.01, 1.34e-3, 1.02e-2},
                                {0.005, 4.74e-4, 5.03e-3},
                                {0.001, 4.23e-5, 1.00e-3}};

// gnuplot commands for the two figures, reading `csv` (columns as written below).
std::string plotScript(const std::string& csv, const std::string& dir,
                       const std::vector<std::string>& interpolators,
                       const std::vector<std::string>& variants) {
  std::ostringstream g;
  g << "set datafile separator ','\n"
    << "set datafile missing ''\n"
    << "set terminal pngcairo size 1400,1000 font ',10'\n"
    << "set logscale xy\n"
    << "set format y '10^{%L}'\n"
    << "set grid\n"
    << "set key bottom right font ',8'\n"
    << "sel(i, v, col) = (strcol(1) eq i && strcol(2) eq v) ? column(col) : NaN\n"
    << "$REF << EOD\n";
  for (const Reference& r : kReference)
    g << r.h << ',' << r.rmsAbsolute << ',' << r.paperNorm << '\n';
  g << "EOD\n";
  // Colour by Dirichlet variant; line and symbol by interpolator, so that the three (which
  // coincide in this problem) stay visible on top of each other.
  const std::map<std::string, std::string> colour = {
      {"particle-wide", "#1f77b4"}, {"nodal-wide", "#d62728"}, {"nodal-clamp", "#2ca02c"}};
  const std::map<std::string, std::string> style = {{"linear", "dt 1 lw 2 pt 7 ps 1.0"},
                                                    {"gimp", "dt 2 lw 1 pt 4 ps 1.8"},
                                                    {"cpdi", "dt 3 lw 1 pt 2 ps 1.4"}};
  // Curves of one metric (CSV column) against column x for every interpolator and variant that
  // finishes (the [0, 1] variants "particle" and "nodal" stop on the range check).
  auto curves = [&](int x, int col) {
    std::string s;
    bool first = true;
    for (const std::string& v : variants) {
      if (!colour.count(v)) continue;
      for (const std::string& i : interpolators) {
        s += first ? "'" + csv + "'" : std::string(", ''");
        first = false;
        s += " every ::1 using " + std::to_string(x) + ":(sel('" + i + "','" + v + "'," +
             std::to_string(col) + ")) w lp lc rgb '" + colour.at(v) + "' " + style.at(i) +
             " title '" + i + ", " + v + "'";
      }
    }
    return s;
  };
  // Columns: 1 interpolator, 2 variant, 3 h, 7 wall s, 12 Eq. 15, 14 RMS rel, 16 RMS abs,
  // 18 interior RMS abs, 21 max abs.
  g << "set output '" << dir << "/diffusion_1d_error_vs_h.png'\n"
    << "set multiplot layout 2,2 title '1-D diffusion, paper §2.2: errors at t = 0.25 against Eq. "
       "13 "
       "(D = 0.1, dt = 0.4 h^2/(2D), 2 particles per cell)'\n"
    << "set xlabel 'h'\n"
    << "set xrange [0.0007:0.15]\n";
  g << "set title \"Eq. 15: sqrt(sum e_p^2)/N, e_p relative\"\nset ylabel 'error'\n"
    << "plot " << curves(3, 12)
    << ", $REF using 1:3 w p pt 12 ps 2.2 lw 1.5 lc rgb 'black' title 'reference (nodal, linear)', "
       "x "
       "lc rgb 'gray' dt 4 title 'slope 1'\n";
  g << "set title 'RMS relative error sqrt(sum e_p^2/N)'\n"
    << "plot " << curves(3, 14) << ", 1.4*x**0.5 lc rgb 'gray' dt 4 title 'slope 1/2'\n";
  g << "set title 'RMS absolute error (all particles)'\n"
    << "plot " << curves(3, 16)
    << ", $REF using 1:2 w p pt 12 ps 2.2 lw 1.5 lc rgb 'black' title 'reference (nodal, linear)', "
       "1.3*x**1.5 lc rgb 'gray' dt 4 title 'slope 1.5', 2*x**2 lc rgb 'black' dt 4 title 'slope "
       "2'\n";
  g << "set title 'RMS absolute error, interior particles 0.1 <= x <= 0.9'\n"
    << "plot " << curves(3, 18) << ", x**2 lc rgb 'black' dt 4 title 'slope 2'\n";
  g << "unset multiplot\n";
  g << "set output '" << dir << "/diffusion_1d_error_vs_time.png'\n"
    << "set terminal pngcairo size 1400,550 font ',10'\n"
    << "set multiplot layout 1,2 title '1-D diffusion: error against wall time (one run, building "
       "the Simulation included)'\n"
    << "set xlabel 'wall time [s]'\n"
    << "set autoscale x\n"
    << "set format x '10^{%L}'\n"
    << "set key top right font ',8'\n";
  g << "set title 'Eq. 15'\nset ylabel 'error'\nplot " << curves(7, 12) << "\n";
  g << "set title 'RMS absolute error'\nplot " << curves(7, 16) << "\n";
  g << "unset multiplot\n";
  return g.str();
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, plots = true, plotsGiven = false, finestAll = false, replot = false;
  std::string csvPath, plotDir = "docs/images";
  std::vector<std::string> interpolators = {"linear", "gimp", "cpdi"};
  std::vector<std::string> variants = {"particle", "nodal", "particle-wide", "nodal-wide"};
  std::vector<int> cells;
  int threads = 1, jobs = 2;
  anode::StudyCommandLine args("diffusion_1d_study", usage);
  args.flag("--quick", [&] { quick = true; });
  args.option("--csv", [&](const char* path) { csvPath = path; });
  args.option("--plots", [&](const char* dir) {
    plotDir = dir;
    plotsGiven = true;
  });
  args.flag("--no-plots", [&] { plots = false; });
  args.flag("--replot", [&] { replot = true; });
  args.flag("--finest-all", [&] { finestAll = true; });
  args.option("--interpolators", [&](const char* list) { interpolators = split(list); });
  args.option("--variants", [&](const char* list) { variants = split(list); });
  args.option("--cells", [&](const char* list) {
    for (const std::string& item : split(list)) {
      const int n = std::atoi(item.c_str());
      if (n < 2) args.fail("--cells needs integers >= 2");
      cells.push_back(n);
    }
    finestAll = true;  // explicit resolutions are run for every interpolator
  });
  args.positiveInteger("--threads", threads);
  args.positiveInteger("--jobs", jobs);
  if (const auto exitCode = args.parse(argc, argv)) return *exitCode;
  if (cells.empty())
    cells = quick ? anode::diffusionSlabQuickCells() : anode::diffusionSlabStudyCells();
  if (csvPath.empty())
    csvPath = quick ? "verification/diffusion_1d_quick.csv" : "verification/diffusion_1d.csv";
  if (quick && !plotsGiven) plots = false;

  // Plots only, from an existing CSV.
  auto plot = [&] {
    std::filesystem::create_directories(plotDir);
    const std::string script = plotScript(csvPath, plotDir, interpolators, variants);
    FILE* gp = popen("gnuplot", "w");
    if (!gp) throw std::runtime_error("cannot run gnuplot");
    std::fwrite(script.data(), 1, script.size(), gp);
    const int status = pclose(gp);
    if (status != 0)
      throw std::runtime_error("gnuplot failed (status " + std::to_string(status) + ")");
    std::printf("wrote %s/diffusion_1d_error_vs_h.png and %s/diffusion_1d_error_vs_time.png\n",
                plotDir.c_str(), plotDir.c_str());
  };
  if (replot) {
    try {
      if (!std::filesystem::exists(csvPath)) throw std::runtime_error(csvPath + " does not exist");
      plot();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "diffusion_1d_study: %s\n", e.what());
      return 3;
    }
    return 0;
  }

  try {
    // Every case, in table order; the finest resolution only for linear unless --finest-all.
    const int finest = *std::max_element(cells.begin(), cells.end());
    std::vector<anode::DiffusionSlabCase> cases;
    for (const std::string& interpolator : interpolators)
      for (const std::string& variant : variants)
        for (int n : cells) {
          if (n == finest && cells.size() > 1 && interpolator != "linear" && !finestAll && !quick)
            continue;
          anode::DiffusionSlabCase c;
          c.cells = n;
          c.interpolator = interpolator;
          anode::setDiffusionSlabVariant(c, variant);
          cases.push_back(c);
        }

    const anode::DiffusionSlabCase base;
    std::printf(
        "1-D diffusion (paper section 2.2): D = %g, c(0) = 1, c(1) = 0, t = %g, "
        "timestep_multiplier "
        "%g, 2 particles per cell, Eq. 13 with %d terms; %zu runs, %d at a time, %d OpenMP "
        "thread(s) each\n",
        base.diffusivity, base.endTime, base.timestepMultiplier, base.fourierTerms, cases.size(),
        jobs, threads);
    std::fflush(stdout);

    // Run the cases, the most expensive (~ cells^3) first, `jobs` at a time; each run is
    // single-threaded by default, so the wall time of a run is its own.
    std::vector<size_t> byCost(cases.size());
    for (size_t i = 0; i < cases.size(); ++i) byCost[i] = i;
    std::stable_sort(byCost.begin(), byCost.end(),
                     [&](size_t a, size_t b) { return cases[a].cells > cases[b].cells; });
    std::vector<DiffusionSlabResult> results(cases.size());
    std::vector<std::string> failures(cases.size());
    std::atomic<size_t> next{0};
    std::mutex printing;
    size_t done = 0;
    auto worker = [&] {
      omp_set_num_threads(threads);
      for (size_t k; (k = next++) < cases.size();) {
        const size_t i = byCost[k];
        try {
          results[i] = anode::runDiffusionSlab(cases[i]);
        } catch (const std::exception& e) {
          failures[i] = e.what();
        }
        std::lock_guard<std::mutex> lock(printing);
        const DiffusionSlabResult& r = results[i];
        std::printf("  [%zu/%zu] %s %s h = %g: %ld steps, %.2f s, %s\n", ++done, cases.size(),
                    cases[i].interpolator.c_str(), cases[i].variant().c_str(), cases[i].h(),
                    r.steps, r.wallSeconds,
                    !failures[i].empty() ? failures[i].c_str()
                    : r.completed        ? "completed"
                                         : r.stopMessage.c_str());
        std::fflush(stdout);
      }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < std::min<int>(jobs, static_cast<int>(cases.size())); ++j)
      pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
    for (size_t i = 0; i < cases.size(); ++i)
      if (!failures[i].empty()) throw std::runtime_error(failures[i]);

    std::printf(
        "\n%-6s %-13s %6s %5s %6s %8s | %9s %5s | %9s %5s | %9s %5s | %9s %5s | %9s %5s | %10s "
        "%10s\n",
        "interp", "variant", "h", "parts", "steps", "wall [s]", "Eq. 15", "order", "RMS rel",
        "order", "RMS abs", "order", "interior", "order", "max abs", "order", "min c", "max c");
    std::ofstream csv = anode::createOutputFile(csvPath);
    csv << "interpolator,variant,h,cells,particles,steps,wall_seconds,first_dt,final_time,"
           "completed,"
           "status,paper_norm,paper_norm_order,rms_relative,rms_relative_order,rms_absolute,"
           "rms_absolute_order,interior_rms_absolute,interior_order,interior_rms_relative,"
           "max_abs_error,max_abs_error_order,max_abs_error_x,min_c,min_c_time,max_c,max_c_time,"
           "final_min_c,final_max_c,max_displacement\n";
    double total = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
      const DiffusionSlabResult& r = results[i];
      total += r.wallSeconds;
      // The previous row of the same interpolator and variant, if it finished.
      const DiffusionSlabResult* previous = nullptr;
      if (i > 0 && results[i - 1].interpolator == r.interpolator &&
          results[i - 1].variant == r.variant && results[i - 1].completed)
        previous = &results[i - 1];
      const bool ok = r.completed;
      auto ord = [&](double DiffusionSlabResult::*metric) {
        return ok && previous
                   ? anode::convergenceOrder(previous->*metric, r.*metric, previous->h / r.h)
                   : std::string();
      };
      const std::string o1 = ord(&DiffusionSlabResult::paperNorm);
      const std::string o2 = ord(&DiffusionSlabResult::rmsRelative);
      const std::string o3 = ord(&DiffusionSlabResult::rmsAbsolute);
      const std::string o4 = ord(&DiffusionSlabResult::interiorRmsAbsolute);
      const std::string o5 = ord(&DiffusionSlabResult::maxAbsolute);
      if (ok) {
        std::printf(
            "%-6s %-13s %6g %5zu %6ld %8.3f | %9.3e %5s | %9.3e %5s | %9.3e %5s | %9.3e %5s | "
            "%9.3e "
            "%5s | %10.3e %10.6f\n",
            r.interpolator.c_str(), r.variant.c_str(), r.h, r.particles, r.steps, r.wallSeconds,
            r.paperNorm, o1.c_str(), r.rmsRelative, o2.c_str(), r.rmsAbsolute, o3.c_str(),
            r.interiorRmsAbsolute, o4.c_str(), r.maxAbsolute, o5.c_str(), r.minConcentration,
            r.maxConcentration);
      } else {
        std::printf("%-6s %-13s %6g %5zu %6ld %8.3f | %s\n", r.interpolator.c_str(),
                    r.variant.c_str(), r.h, r.particles, r.steps, r.wallSeconds,
                    r.stopMessage.c_str());
      }
      auto val = [&](double v) { return ok ? sci(v) : std::string(); };
      char hs[32];
      std::snprintf(hs, sizeof hs, "%g", r.h);
      csv << r.interpolator << ',' << r.variant << ',' << hs << ',' << r.cells << ',' << r.particles
          << ',' << r.steps << ',' << r.wallSeconds << ',' << sci(r.firstDt) << ',' << r.finalTime
          << ',' << (ok ? 1 : 0) << ',' << (ok ? "completed" : r.stopMessage) << ','
          << val(r.paperNorm) << ',' << o1 << ',' << val(r.rmsRelative) << ',' << o2 << ','
          << val(r.rmsAbsolute) << ',' << o3 << ',' << val(r.interiorRmsAbsolute) << ',' << o4
          << ',' << val(r.interiorRmsRelative) << ',' << val(r.maxAbsolute) << ',' << o5 << ','
          << (ok ? std::to_string(r.maxAbsoluteAt) : std::string()) << ','
          << conc(r.minConcentration) << ',' << r.minConcentrationTime << ','
          << conc(r.maxConcentration) << ',' << r.maxConcentrationTime << ','
          << (ok ? conc(r.finalMinConcentration) : std::string()) << ','
          << (ok ? conc(r.finalMaxConcentration) : std::string()) << ',' << val(r.maxDisplacement)
          << '\n';
    }
    csv.close();
    std::printf("wrote %s (%.1f s of runs)\n", csvPath.c_str(), total);

    // Linear against the reference implementation.
    std::printf(
        "\nlinear vs the reference (independent Eqs. 4-8, nodal Dirichlet): RMS abs, Eq. 15\n");
    std::printf("%6s | %19s", "h", "reference");
    for (const std::string& v : variants)
      if (v.find('-') != std::string::npos) std::printf(" | %19s", v.c_str());
    std::printf("\n");
    for (const Reference& ref : kReference) {
      std::printf("%6g | %9.3e %9.3e", ref.h, ref.rmsAbsolute, ref.paperNorm);
      for (const std::string& v : variants) {
        if (v.find('-') == std::string::npos) continue;
        const DiffusionSlabResult* hit = nullptr;
        for (const DiffusionSlabResult& r : results)
          if (r.interpolator == "linear" && r.variant == v && r.completed &&
              std::abs(r.h - ref.h) < 1e-9)
            hit = &r;
        if (hit)
          std::printf(" | %9.3e %9.3e", hit->rmsAbsolute, hit->paperNorm);
        else
          std::printf(" | %19s", "-");
      }
      std::printf("\n");
    }

    if (plots) plot();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "diffusion_1d_study: %s\n", e.what());
    return 3;
  }
  return 0;
}

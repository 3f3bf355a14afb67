// Pins the film study (inputs/Films/SiliconFilm.ups), read from history.csv and report.html
// alone: its first turn at 1C (charge, discharge, the next charge begun) on the quasi-static path
// at the real density. The cutoffs end each half-cycle in its direction and the next segment
// resumes the current; the load's reversal does not stop the run; the stress columns hold the
// closed form of the elastic start (biaxial modulus times the swelling strain) and the traction-
// free normal; stress x thickness is the in-plane mean times volume over plan area; the plastic
// work is 0 while elastic and grows once the film yields, in both directions; report.html plots
// the stress x thickness against the state of charge. <swelling_strain>cell_mean takes the
// layer-to-layer alternation out of the normal stress, to 0 at first order in the cell size; each
// particle's own dc leaves it at the order of the yield stress. The film with the chemical
// potential and a surface reaction runs three turns between potential cutoffs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "HistoryFile.h"
#include "RunSus.h"
#include "StandAlone/Driver/Simulation.h"
#include "TestFiles.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

using testing::History;
using testing::readFile;
using testing::readHistory;
using testing::runSus;

TEST(FilmStudy, FirstTurnFromTheHistoryAlone) {
  const fs::path dir = fs::temp_directory_path() / ("anode_film_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The input's first turn and the start of the next charge: 2.1 of its 6 hours.
  std::string text = readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Films/SiliconFilm.ups");
  text =
      std::regex_replace(text, std::regex("<maxTime>[^<]*</maxTime>"), "<maxTime>7.56e9</maxTime>");
  const fs::path input = dir / "film.ups";
  std::ofstream(input) << text;
  const auto run = runSus({"--threads", "1", "-o", (dir / "out").string(), input.string()});
  ASSERT_EQ(run.exitCode, 0) << run.output;

  // The notes of the cutoffs and resumptions, in order.
  size_t at = 0;
  for (const char* note : {"(the surface is nearly full), until its load curve's next segment",
                           "its current resumes at t = 3.60", "(discharging,",
                           "(the surface is nearly empty), until its load curve's next segment",
                           "its current resumes at t = 7.20", "(charging,"}) {
    at = run.output.find(note, at);
    ASSERT_NE(at, std::string::npos) << "no \"" << note << "\" in order in:\n" << run.output;
  }

  const History h = readHistory(dir / "out" / "history.csv");
  const std::vector<double> soc = h.column("state_of_charge"), sxx = h.column("mean_sxx_silicon"),
                            syy = h.column("mean_syy_silicon"), szz = h.column("mean_szz_silicon"),
                            volume = h.column("volume_silicon"),
                            thickness = h.column("stress_thickness_silicon"),
                            work = h.column("plastic_work_silicon"),
                            workRate = h.column("plastic_work_rate_silicon");
  ASSERT_GT(soc.size(), 20u);
  ASSERT_EQ(thickness.size(), soc.size());
  ASSERT_EQ(work.size(), soc.size());
  // The elastic start: sigma_xx = -E / (1 - nu) eta c (in-plane strain held at 0, the swelling
  // rate eta dc/dt on each normal), E / (1 - nu) = 9 K G / (3 K + G) / (1 - nu) from the input's
  // K = 67 GPa and G = 31 GPa, eta = 0.56; c its mean, the state of charge (c_max = 1).
  const double K = 6.7e7, G = 3.1e7, eta = 0.56;
  const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));
  ASSERT_GT(soc[1], 0);
  ASSERT_LT(-sxx[1], 1.4e6) << "the first step already yields: no elastic start to check";
  EXPECT_NEAR(sxx[1] / (-E / (1 - nu) * eta * soc[1]), 1.0, 0.01);
  EXPECT_EQ(work[1], 0.0);
  const double plan = 0.02 * 0.02;  // the grid's plan, um^2
  double largestStress = 0, largestNormal = 0;
  for (size_t r = 1; r < soc.size(); ++r) {
    largestStress = std::max(largestStress, std::abs(sxx[r]));
    largestNormal = std::max(largestNormal, std::abs(szz[r]));
    EXPECT_NEAR(thickness[r], 0.5 * (sxx[r] + syy[r]) * volume[r] / plan,
                1e-9 * std::abs(thickness[r]))
        << "row " << r;
    EXPECT_GE(work[r], work[r - 1]) << "row " << r;  // sigma_e dep >= 0
    EXPECT_GE(workRate[r], 0.0) << "row " << r;
  }
  // The film's normal stress is the free surface's, 0, against GPa in plane.
  EXPECT_GT(largestStress, 1.4e6);
  EXPECT_LT(largestNormal, 1e-3 * largestStress);
  // It yields in compression on charge and in tension on discharge: the work grows in both.
  size_t turn = 0;
  while (turn + 1 < soc.size() && soc[turn + 1] >= soc[turn]) ++turn;
  ASSERT_LT(turn + 1, soc.size()) << "the charge did not turn";
  EXPECT_GT(work[turn], 0.0);
  EXPECT_GT(*std::max_element(sxx.begin(), sxx.end()), 1.4e6);  // tensile flow
  EXPECT_GT(work.back(), work[turn]);

  // report.html plots the stress x thickness against the state of charge.
  const std::string report = readFile(dir / "out" / "report.html");
  EXPECT_NE(report.find("id=\"stress_soc_silicon\""), std::string::npos);
  EXPECT_NE(report.find("id=\"plastic_work_silicon\""), std::string::npos);
  EXPECT_NE(report.find("id=\"current\""), std::string::npos);
  fs::remove_all(dir);
}

// inputs/Films/SiliconFilmPotential.ups: the film with the chemical potential in its flux and a
// Butler-Volmer surface, three turns each ended by a potential cutoff (charge at 0.25 V,
// discharge at 0.55 V), the potential in history.csv and plotted against the state of charge.
TEST(FilmStudy, ThreeTurnsBetweenPotentialCutoffs) {
  const fs::path dir = fs::temp_directory_path() / ("anode_film_phi_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto run =
      runSus({"--one-process", "--threads", "1", "-o", (dir / "out").string(),
              std::string(ANODE_SOURCE_DIR) + "/inputs/Films/SiliconFilmPotential.ups"});
  ASSERT_EQ(run.exitCode, 0) << run.output;
  size_t at = 0;
  for (int turn = 0; turn < 3; ++turn)
    for (const char* cutoff :
         {"or below <lower_cutoff_potential> 0.25 V", "or above <upper_cutoff_potential> 0.55 V"}) {
      at = run.output.find(cutoff, at);
      ASSERT_NE(at, std::string::npos)
          << "turn " << turn + 1 << ": no \"" << cutoff << "\" in order in:\n"
          << run.output;
    }
  const History h = readHistory(dir / "out" / "history.csv");
  const std::vector<double> phi = h.column("potential_1"), soc = h.column("state_of_charge");
  ASSERT_EQ(phi.size(), soc.size());
  // Between the cutoffs, overshooting by at most a step's change.
  EXPECT_GT(*std::min_element(phi.begin() + 1, phi.end()), 0.24);
  EXPECT_LT(*std::max_element(phi.begin() + 1, phi.end()), 0.57);
  const std::string report = readFile(dir / "out" / "report.html");
  EXPECT_NE(report.find("id=\"potential_1_soc\""), std::string::npos);
  EXPECT_NE(report.find("id=\"stress_soc_silicon\""), std::string::npos);
  fs::remove_all(dir);
}

// <film_normal> names an axis: anything else is an input error naming the file and line.
TEST(FilmStudy, FilmNormalOtherThanAnAxisIsAnInputError) {
  const fs::path dir = fs::temp_directory_path() / ("anode_film_bad_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text = readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Films/SiliconFilm.ups");
  for (const char* bad : {"w", "", "[0,0,1]"}) {
    const std::string edited =
        std::regex_replace(text, std::regex("<film_normal>z</film_normal>"),
                           std::string("<film_normal>") + bad + "</film_normal>");
    const fs::path input = dir / "film.ups";
    std::ofstream(input) << edited;
    const auto run = runSus({"-o", (dir / "out").string(), input.string()});
    EXPECT_EQ(run.exitCode, 2) << bad << ": " << run.output;
    EXPECT_TRUE(std::regex_search(run.output, std::regex("film\\.ups:[0-9]+: <film_normal> must be "
                                                         "x, y or z")))
        << bad << ": " << run.output;
  }
  fs::remove_all(dir);
}

// The largest |sigma_zz| of a particle after 72 s of 10C charge (c up to about 0.35 at the surface)
// on `cells` layers of cells through the 0.3 um grid, with <swelling_strain> `swelling`.
double largestNormalStress(int cells, const std::string& swelling) {
  std::string text = readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Films/SiliconFilm.ups");
  text =
      std::regex_replace(text, std::regex("<maxTime>[^<]*</maxTime>"), "<maxTime>7.2e7</maxTime>");
  text = std::regex_replace(text, std::regex("<load_curve>.*</load_curve>"),
                            "<load_curve><id>1</id><time_point><time>0</time><load>10</load>"
                            "</time_point><time_point><time>1e12</time><load>10</load>"
                            "</time_point></load_curve>");
  text = std::regex_replace(text, std::regex("<swelling_strain>[^<]*</swelling_strain>"), "");
  text = std::regex_replace(text, std::regex("<time_integrator>implicit</time_integrator>"),
                            "<time_integrator>implicit</time_integrator><swelling_strain>" +
                                swelling + "</swelling_strain>");
  text = std::regex_replace(text, std::regex("<resolution>\\[2, 2, 30\\]</resolution>"),
                            "<resolution>[2, 2, " + std::to_string(cells) + "]</resolution>");
  RunOptions o;
  o.progress = false;
  Simulation sim(text, "film.ups", o);
  while (sim.time() < 7.2e7 * (1 - 1e-12) && sim.step() < 100) sim.advance();
  EXPECT_NEAR(sim.time(), 7.2e7, 1) << cells << " cells, " << swelling;
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  EXPECT_EQ(p.count(), static_cast<size_t>(16 * cells / 3)) << "the film fills 5/30 of the grid";
  double largest = 0;
  for (size_t i = 0; i < p.count(); ++i) largest = std::max(largest, std::abs(p.stress[i](2, 2)));
  return largest;
}

// Measured: 2.07 GPa with each particle's own dc on 30 layers; 0.038 and 0.027 GPa with the cell
// means on 30 and 60 (against in-plane stresses of 1.5-1.8 GPa). The cell means' values depend on
// the steps as much as on the cells (docs/film.md: 0.093 and 0.0155 GPa in steps of 0.2 s), so
// the test asks only that they stay small and fall from 30 to 60 layers at these steps.
TEST(FilmStudy, CellMeanSwellingTakesTheLayersOutOfTheNormalStress) {
  const double own = largestNormalStress(30, "particle");
  const double coarse = largestNormalStress(30, "cell_mean"),
               fine = largestNormalStress(60, "cell_mean");
  EXPECT_GT(own, 1e6);  // kPa: the alternation is of the order of the yield stress
  EXPECT_LT(coarse, 0.05e6);
  EXPECT_LT(fine, coarse) << coarse << " kPa on 30 layers, " << fine << " on 60";
}

}  // namespace
}  // namespace anode

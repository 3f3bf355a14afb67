// The surface reaction of a galvanostatic <scalar_flux> (<surface_reaction>, SurfaceReaction.h):
// inputs/Verification/SurfaceReactionBar.ups, a bar kept uniform by a large D, charged,
// discharged and charged again at 1C through a Butler-Volmer surface. The electrode's potential
// in history.csv against the closed form phi = U0 - (RT/F) ln(c / (1 - c)) - 2 (RT/F) asinh(j /
// (2 J0)) (alpha = 1/2; j = +-1, the flux per area of 1C; c the state of charge), the potential
// cutoffs ending each half-cycle where the closed form reaches them, the next segments resuming
// the current, report.html's plots; and the bad values, each an input error naming its line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "Components/MPM/ReactiveFlow/SurfaceReaction.h"
#include "HistoryFile.h"
#include "RunSus.h"
#include "TestFiles.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

using testing::History;
using testing::readFile;
using testing::readHistory;
using testing::runSus;

const double kThermalVoltage = 8.617333262e-5 * 298.15;  // RT / F at the input's 298.15 K
const double kU0 = 0.4, kExchangeFlux = 0.5;             // the input's U0 and J0

double openCircuit(double c) {
  return kU0 - kThermalVoltage * std::log(c / (1 - c));
}
double overpotential(double j) {
  return -2 * kThermalVoltage * std::asinh(j / (2 * kExchangeFlux));
}

std::string barInput() {
  return readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Verification/SurfaceReactionBar.ups");
}

struct BarRun {
  fs::path dir;
  testing::SusResult result;
};

BarRun runBar(const std::string& name, const std::string& text) {
  BarRun run;
  run.dir = fs::temp_directory_path() / ("anode_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(run.dir);
  fs::create_directories(run.dir);
  const fs::path input = run.dir / "bar.ups";
  std::ofstream(input) << text;
  run.result =
      runSus({"--one-process", "--threads", "1", "-o", (run.dir / "out").string(), input.string()});
  return run;
}

TEST(SurfaceReaction, PotentialFollowsButlerVolmerAndItsCutoffsEndEachHalfCycle) {
  const BarRun run = runBar("surface_reaction", barInput());
  ASSERT_EQ(run.result.exitCode, 0) << run.result.output;
  size_t at = 0;
  for (const char* note :
       {"its current ends at t = 0.59", "<lower_cutoff_potential> 0.333 V",
        "its current resumes at t = 1.0", "(discharging", "its current ends at t = 1.59",
        "<upper_cutoff_potential> 0.5 V", "its current resumes at t = 2.0", "(charging"}) {
    at = run.result.output.find(note, at);
    ASSERT_NE(at, std::string::npos) << "no \"" << note << "\" in order in:\n" << run.result.output;
  }
  const History h = readHistory(run.dir / "out" / "history.csv");
  const std::vector<double> t = h.column("time"), soc = h.column("state_of_charge"),
                            rate = h.column("lithium_rate"), phi = h.column("potential_1");
  ASSERT_EQ(phi.size(), t.size());
  ASSERT_GT(t.size(), 50u);
  // The closed form under a steady current (the row and the one before at +-1C: 0.01 of lithium
  // per hour) and at rest (no current in the row, the one before and the one after). The rows
  // where the current starts or stops are left out: their potential is of the state's current,
  // their rate the step's mean.
  size_t loaded = 0, resting = 0;
  double largest = 0;
  for (size_t r = 2; r < t.size(); ++r) {
    const double j = rate[r] / 0.01, before = rate[r - 1] / 0.01;
    double exact;
    if (std::abs(std::abs(j) - 1) < 1e-6 && std::abs(j - before) < 1e-6) {
      exact = openCircuit(soc[r]) + overpotential(j);
      ++loaded;
    } else if (std::abs(j) < 1e-9 && std::abs(before) < 1e-9 &&
               (r + 1 == t.size() || std::abs(rate[r + 1]) < 1e-9)) {
      exact = openCircuit(soc[r]);
      ++resting;
    } else {
      continue;
    }
    largest = std::max(largest, std::abs(phi[r] - exact));
  }
  EXPECT_GT(loaded, 100u);
  EXPECT_GT(resting, 20u);
  EXPECT_LT(largest, 2e-4) << "V";  // c's nonuniformity (about 3e-4) through U
  // Each cutoff where the closed form reaches it: the charge at c = 0.6995 (phi = 0.333 V), the
  // discharge at c = 0.1054 (0.5 V): the first rest row's state of charge.
  const auto cutoffCharge = [](double cutoff, double j) {
    const double x = (kU0 + overpotential(j) - cutoff) / kThermalVoltage;  // ln(c / (1 - c))
    return 1 / (1 + std::exp(-x));
  };
  double firstRest[2] = {NAN, NAN};
  for (size_t r = 1, k = 0; r < t.size() && k < 2; ++r)
    if (std::abs(rate[r]) < 1e-9 && std::abs(rate[r - 1]) > 1e-3) firstRest[k++] = soc[r];
  EXPECT_NEAR(firstRest[0], cutoffCharge(0.333, 1), 2e-3);
  EXPECT_NEAR(firstRest[1], cutoffCharge(0.5, -1), 2e-3);
  // Lithium = current x time while the first charge runs.
  for (size_t r = 1; r < t.size() && t[r] < 0.59; ++r)
    EXPECT_NEAR(soc[r], 0.1 + t[r], 1e-9) << "row " << r;
  const std::string report = readFile(run.dir / "out" / "report.html");
  EXPECT_NE(report.find("id=\"potential_1\""), std::string::npos);
  EXPECT_NE(report.find("id=\"potential_1_soc\""), std::string::npos);
  fs::remove_all(run.dir);
}

// The law itself: U at c = 1/2 is U0, a tensile stress part raises it by RT/F per unit phi_s;
// no flux at phi = U, lithiation below it, symmetric for alpha = 1/2; fluxSlope is |dj/dc|.
TEST(SurfaceReaction, OpenCircuitPotentialAndButlerVolmerFlux) {
  SurfaceReaction r;
  r.temperature = 298.15;
  r.openCircuitPotential = kU0;
  r.exchangeFlux = kExchangeFlux;
  EXPECT_NEAR(r.thermalVoltage(), kThermalVoltage, 1e-15);
  EXPECT_DOUBLE_EQ(r.openCircuit(0.5, 0.0), kU0);
  EXPECT_NEAR(r.openCircuit(0.3, 1.5) - r.openCircuit(0.3, 0.0), 1.5 * kThermalVoltage, 1e-15);
  EXPECT_GT(r.openCircuit(0.2, 0.0), r.openCircuit(0.8, 0.0));  // a fuller particle: lower U
  const double U = r.openCircuit(0.3, 0.0);
  EXPECT_EQ(r.flux(U, U), 0.0);
  EXPECT_GT(r.flux(U - 0.01, U), 0.0);
  EXPECT_NEAR(r.flux(U + 0.01, U), -r.flux(U - 0.01, U), 1e-14);
  EXPECT_NEAR(r.flux(U - 0.05, U), 2 * kExchangeFlux * std::sinh(0.05 / (2 * kThermalVoltage)),
              1e-12);
  const double phi = U - 0.02, c = 0.3, dc = 1e-6;
  const double numeric =
      (r.flux(phi, r.openCircuit(c + dc, 0.0)) - r.flux(phi, r.openCircuit(c - dc, 0.0))) /
      (2 * dc);
  EXPECT_NEAR(r.fluxSlope(phi, U, c), std::abs(numeric), 1e-6 * std::abs(numeric));
}

// Each bad value an input error (exit code 2) naming the file and the line of the tag at fault.
TEST(SurfaceReaction, BadValuesAreInputErrorsNamingTheirLine) {
  struct Case {
    std::string from, to, message, at;  // `at`: the tag whose line the error names
  };
  const std::vector<Case> cases = {
      {"<exchange_flux>0.5", "<exchange_flux>-1", "<exchange_flux> must be above 0",
       "<exchange_flux>"},
      {"<temperature>298.15", "<temperature>0", "<temperature> must be above 0", "<temperature>"},
      {"<transfer_coefficient>0.5", "<transfer_coefficient>1",
       "<transfer_coefficient> must lie in (0, 1)", "<transfer_coefficient>"},
      {"<upper_cutoff_potential>0.5", "<upper_cutoff_potential>0.3",
       "<upper_cutoff_potential> must lie above", "<upper_cutoff_potential>"},
      {"<mode>galvanostatic</mode>[\\s\\S]*?<hour>1</hour>", "<mode>flux</mode>",
       "<surface_reaction> belongs to <mode>galvanostatic</mode>", "  <surface_reaction>"},
      {"<hour>1</hour>", "<hour>1</hour><cutoff>0.2</cutoff>",
       "does not go with <surface_reaction>", "<cutoff>"},
      {"<concentration>0.1</concentration>", "<concentration>0</concentration>",
       "needs its particles' c inside (0, max_concentration)", "<scalar_flux>\n"},
  };
  for (const Case& c : cases) {
    const std::string text = std::regex_replace(barInput(), std::regex(c.from), c.to);
    const long at = static_cast<long>(text.find(c.at));
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
    const BarRun run = runBar("surface_reaction_bad", text);
    EXPECT_EQ(run.result.exitCode, 2) << c.to << "\n" << run.result.output;
    EXPECT_NE(run.result.output.find("bar.ups:" + std::to_string(line) + ": "), std::string::npos)
        << c.to << "\n"
        << run.result.output;
    EXPECT_NE(run.result.output.find(c.message), std::string::npos) << c.to << "\n"
                                                                    << run.result.output;
    fs::remove_all(run.dir);
  }
}

}  // namespace
}  // namespace anode

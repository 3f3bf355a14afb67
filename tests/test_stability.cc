// The stiff and extreme cases in inputs/Stability (docs/stability.md), each a run of seconds: each
// runs through sus as it is and either completes with bounded energy and c in range, stops with
// exit code 3 and the expected diagnostic, having written the last good state, or is refused at
// setup (exit code 2, file:line: message, nothing written). Also unit checks of the instability
// diagnostics (StateChecks) on states made bad on purpose.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "Components/MPM/StateChecks.h"
#include "RunSus.h"
#include "StandAlone/Driver/Simulation.h"
#include "TestInputs.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

const std::string kDir = std::string(ANODE_SOURCE_DIR) + "/inputs/Stability";

struct SusRun : testing::SusResult {
  fs::path dir;
};

// sus on one thread, so the step a diagnostic fires at does not depend on the machine.
SusRun runOnOneThread(const std::string& input) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("anode_stability_" + fs::path(input).stem().string() + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  return {testing::runSus({"--threads", "1", "-o", dir.string(), input}), dir};
}

// history.csv as rows of named columns.
std::vector<std::map<std::string, double>> readHistory(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::map<std::string, double> row;
    size_t k = 0;
    for (std::string f; std::getline(fields, f, ',') && k < names.size(); ++k)
      row[names[k]] = std::stod(f);
    rows.push_back(row);
  }
  return rows;
}

double column(const std::vector<std::map<std::string, double>>& h, const std::string& name,
              bool largest) {
  double v = largest ? -HUGE_VAL : HUGE_VAL;
  for (const auto& row : h) v = largest ? std::max(v, row.at(name)) : std::min(v, row.at(name));
  return v;
}

struct Expectation {
  long endStep;         // the step a completed run ends at (its max_Timesteps; 0: maxTime ends it)
  int exitCode;         // 0, 2 or 3
  std::string message;  // exit 3 or 2: a regular expression the diagnostic matches (exit 2:
                        // it starts with the tag whose line the error names)
  long stopStep;        // exit 3: the step it stops at (within +-2)
  std::function<void(const std::vector<std::map<std::string, double>>&)> check;  // on history.csv
};

// Silicon of every case (ARL units): K = 67 GPa, G = 31 GPa; dx = 0.01 um.
constexpr double kDx = 0.01, kModulus = 6.7e7 + 4.0 / 3.0 * 3.1e7;

void cInRange(const std::vector<std::map<std::string, double>>& h) {
  EXPECT_GE(column(h, "min_c", false), 0.0);
  EXPECT_LE(column(h, "max_c", true), 1.0);
}

void energyBelowInitial(const std::vector<std::map<std::string, double>>& h) {
  EXPECT_LE(column(h, "kinetic_energy", true), h.front().at("kinetic_energy") * (1 + 1e-9));
  EXPECT_GT(h.back().at("kinetic_energy"), 0.0);
  EXPECT_GE(column(h, "min_J", false), 0.99);
  EXPECT_LE(column(h, "max_J", true), 1.01);
}

// The implicit cases' silicon swells uniformly to c = 0.5 (e^(3 x 0.56 x 0.5) = 2.32 free).
void swollenToHalf(const std::vector<std::map<std::string, double>>& h) {
  cInRange(h);
  EXPECT_NEAR(h.back().at("max_c"), 0.5, 1e-9);
  EXPECT_GT(h.back().at("max_J"), 1.8);
  EXPECT_LT(column(h, "max_J", true), 3.0);
  EXPECT_GT(column(h, "min_J", false), 0.5);
}

const std::map<std::string, Expectation>& expectations() {
  static const std::map<std::string, Expectation> e = {
      {"Density_2.33e3",
       {300, 0, "", 0,
        [](const auto& h) {
          // Mechanics-limited: dt = 0.4 dx / c (Eq. 43), c = sqrt((K + 4G/3) / rho).
          EXPECT_NEAR(h[1].at("dt"), 0.4 * kDx / std::sqrt(kModulus / 2.33), 1e-9 * h[1].at("dt"));
          cInRange(h);
        }}},
      {"Density_2.33e24",
       {300, 0, "", 0,
        [](const auto& h) {
          // Diffusion-limited: dt = 0.4 dx^2 / (2 D0) (Eq. 44), D0 = 1e-4 um^2/us, far below
          // Eq. 43.
          EXPECT_NEAR(h[1].at("dt"), 0.4 * kDx * kDx / (2 * 1e-4), 1e-12);
          EXPECT_LT(h[1].at("dt"), 1e-3 * kDx / std::sqrt(kModulus / 2.33e21));
          cInRange(h);
        }}},
      {"Alpha_0", {600, 0, "", 0, cInRange}},
      {"Alpha_10",
       {600, 0, "", 0,
        [](const auto& h) {
          cInRange(h);
          // D_max = D0 e^(10 c_max) (less the pressure term): dt falls several-fold as c_max
          // reaches 0.4.
          EXPECT_GT(column(h, "max_c", true), 0.3);
          EXPECT_LT(h.back().at("dt"), h[1].at("dt") / 3);
        }}},
      {"Beta_0.5_confined", {600, 0, "", 0, cInRange}},
      {"Beta_2_confined",
       {0, 3, "has concentration -[0-9.e-]+ at t = .*outside \\[0, 1\\]", 20, cInRange}},
      {"Flux_1e-10",
       {300, 0, "", 0,
        [](const auto& h) {
          cInRange(h);
          EXPECT_LT(column(h, "max_c", true), 0.01);
        }}},
      {"Flux_1e-6",
       {0, 3, "the particle concentrations oscillate with growing amplitude", 1506,
        [](const auto& h) {
          // The flux fills the surface up to the restriction's root 1 - e^-4 = 0.98168 and no
          // further: each particle receives the source restricted by its own c. The stop comes
          // later, from the diffusion update in a body swollen 8-fold (max J in the history), at
          // about the same time at any multiplier (docs/stability.md); the diagnostic confirms
          // the oscillation over up to 10 steps, in which c may pass the root.
          cInRange(h);
          const std::vector<std::map<std::string, double>> before(h.begin(), h.end() - 10);
          EXPECT_GT(column(before, "max_c", true), 0.979);
          EXPECT_LT(column(before, "max_c", true), 1 - std::exp(-4.0));
          EXPECT_GT(column(h, "max_J", true), 8);
        }}},
      {"Flux_out_1e-6",
       {2000, 0, "", 0,
        [](const auto& h) {
          // The outflow restriction R(1 - c) empties the surface down to its root e^-4 and no
          // further: an emptied particle receives none of its neighbours' sinks.
          cInRange(h);
          EXPECT_GT(column(h, "min_c", false), std::exp(-4.0));
          EXPECT_LT(column(h, "min_c", false), 0.019);
        }}},
      {"Concentration_0.999",
       {300, 0, "", 0,
        [](const auto& h) {
          EXPECT_EQ(column(h, "min_c", false), 0.999);
          EXPECT_EQ(column(h, "max_c", true), 0.999);
        }}},
      {"Multiplier_0.1", {1500, 0, "", 0, energyBelowInitial}},
      {"Multiplier_0.75", {0, 0, "", 0, energyBelowInitial}},
      {"Multiplier_0.8",
       {0, 3, "the particle velocities oscillate with growing amplitude", 33,
        [](const auto& h) {
          // Stopped before the oscillation shows in the energy: the last good state is still close.
          EXPECT_LT(column(h, "kinetic_energy", true), 2 * h.front().at("kinetic_energy"));
        }}},
      {"Multiplier_1.5",
       {0, 2, "<timestep_multiplier> must be in \\(0, 1\\]: found 1\\.5; .*beyond the stable one",
        0, nullptr}},
      {"Multiplier_diffusion_0.5",
       {1000, 0, "", 0,
        [](const auto& h) {
          EXPECT_GE(column(h, "min_c", false), 0.5 - 1e-9);
          EXPECT_LE(column(h, "max_c", true), 0.6);
        }}},
      {"Multiplier_diffusion_0.6",
       {0, 3, "the particle concentrations oscillate with growing amplitude", 136,
        [](const auto& h) {
          EXPECT_GE(column(h, "min_c", false), 0.5 - 1e-9);
          EXPECT_LE(column(h, "max_c", true), 0.6);
        }}},
      {"Multiplier_diffusion_1.0",
       {0, 3, "the particle concentrations oscillate with growing amplitude", 11,
        [](const auto& h) {
          EXPECT_GE(column(h, "min_c", false), 0.49);
          EXPECT_LE(column(h, "max_c", true), 0.51);
        }}},
      {"Swelling_eta_1",
       {0, 0, "", 0,
        [](const auto& h) {
          EXPECT_GE(h.back().at("time"), 300.0);
          EXPECT_GT(column(h, "max_c", true), 0.98);
          EXPECT_LE(column(h, "max_c", true), 1.0);
          EXPECT_GT(column(h, "max_J", true), 10.0);
          EXPECT_LT(column(h, "max_J", true), 25.0);
        }}},
      {"Elastic_compression_5km_s",
       {0, 0, "", 0,
        [](const auto& h) {
          EXPECT_LE(column(h, "kinetic_energy", true), h.front().at("kinetic_energy") * (1 + 1e-9));
          EXPECT_LT(column(h, "min_J", false), 0.3);
          EXPECT_GT(column(h, "min_J", false), 0.1);
        }}},
      {"Elastic_compression_12km_s",
       {0, 3, "has J = V rho0 / m = [0-9.e-]+, below 1e-05", 66, nullptr}},
      // Quasi-static (implicit) variants; each completed run also reports its Newton iterations
      // (QuickVersionEndsAsExpected).
      {"Implicit_swelling_eta_0.56",
       {0, 0, "", 0,
        [](const auto& h) {
          // c reaches 1 everywhere at maxTime (the last step ends there); J about free swelling's
          // e^(3 eta) = 5.37.
          cInRange(h);
          EXPECT_NEAR(h.back().at("min_c"), 1.0, 1e-9);
          EXPECT_GT(h.back().at("min_J"), 4.5);
          EXPECT_LT(column(h, "max_J", true), 6.5);
        }}},
      {"Implicit_swelling_eta_0.56_past_c_1",
       {0, 3, "has concentration 1\\.[0-9]+ at t = .*outside \\[0, 1\\]", 6,
        [](const auto& h) {
          cInRange(h);
          EXPECT_NEAR(h.back().at("max_c"), 1.0, 1e-9);
        }}},
      {"Implicit_yield_0.14_walls", {0, 0, "", 0, swollenToHalf}},
      {"Implicit_hardening_11.5_walls", {0, 0, "", 0, swollenToHalf}},
      {"Implicit_contact_single_velocity",
       {0, 0, "", 0,
        [](const auto& h) {
          swollenToHalf(h);
          // The bonded substrate (no lithium) is strained by the silicon.
          EXPECT_LT(h.back().at("min_J"), 0.99);
        }}},
      {"Implicit_contact_null",
       {0, 0, "", 0,
        [](const auto& h) {
          swollenToHalf(h);
          // Separate bodies: nothing strains the substrate.
          EXPECT_NEAR(column(h, "min_J", false), 1.0, 1e-9);
          EXPECT_NEAR(h.back().at("min_J"), 1.0, 1e-9);
        }}},
      {"Implicit_contact_exclude",
       {0, 2, "<ExcludeMaterial> with <time_integrator>implicit is not supported", 0, nullptr}},
  };
  return e;
}

std::vector<std::string> stabilityInputs() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kDir))
    if (entry.path().extension() == ".ups") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

std::string readInput(const std::string& name) {
  std::ifstream in(kDir + "/" + name + ".ups");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

double readMaxTime(const std::string& name) {
  std::ifstream in(kDir + "/" + name + ".ups");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::smatch m;
  return std::regex_search(text, m, std::regex("<maxTime>([^<]+)</maxTime>")) ? std::stod(m[1])
                                                                              : HUGE_VAL;
}

class StabilityCase : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityCase, QuickVersionEndsAsExpected) {
  const auto it = expectations().find(GetParam());
  ASSERT_NE(it, expectations().end())
      << GetParam() << ".ups has no expectation in test_stability.cc";
  const Expectation& e = it->second;
  const std::string input = kDir + "/" + GetParam() + ".ups";
  const SusRun r = runOnOneThread(input);
  ASSERT_EQ(r.exitCode, e.exitCode) << r.output;
  if (e.exitCode == 2) {
    // Refused at setup: file:line: message, the line of the tag the message starts with, and
    // nothing written.
    const std::string tag = e.message.substr(0, e.message.find('>') + 1);
    std::ifstream in(input);
    int line = 0, tagLine = 0;
    for (std::string text; tagLine == 0 && std::getline(in, text);) {
      ++line;
      const size_t p = text.find(tag);
      if (p != std::string::npos && p == text.find_first_not_of(' ')) tagLine = line;
    }
    const std::string where = input + ":" + std::to_string(tagLine) + ": ";
    const size_t at = r.output.find(where);
    ASSERT_NE(at, std::string::npos) << "expected '" << where << "' in\n" << r.output;
    EXPECT_TRUE(std::regex_search(r.output.substr(at + where.size()), std::regex("^" + e.message)))
        << "expected /" << e.message << "/ after '" << where << "' in\n"
        << r.output;
    EXPECT_FALSE(fs::exists(r.dir)) << r.output;
    return;
  }
  const auto history = readHistory(r.dir / "history.csv");
  ASSERT_GE(history.size(), 2u) << r.output;
  for (const auto& row : history) ASSERT_TRUE(std::isfinite(row.at("kinetic_energy"))) << r.output;
  if (e.exitCode == 3) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        r.output, m, std::regex("simulation stopped: step ([0-9]+), t = [-0-9.e+]+: (.*)")))
        << r.output;
    const long step = std::stol(m[1]);
    EXPECT_NEAR(step, e.stopStep, 2) << r.output;
    EXPECT_TRUE(std::regex_search(std::string(m[2]), std::regex(e.message)))
        << "expected /" << e.message << "/ in\n"
        << r.output;
    // The diagnostic names a particle and its material, and the last good state is written.
    EXPECT_TRUE(std::regex_search(r.output,
                                  std::regex("particle [0-9]+ of material 0 \\(silicon\\) at \\[")))
        << r.output;
    EXPECT_EQ(history.back().at("step"), step - 1);
    char last[64], failed[64];
    std::snprintf(last, sizeof last, "particles/step_%06ld.vtu", step - 1);
    std::snprintf(failed, sizeof failed, "particles/failed_step_%06ld.vtu", step);
    std::ifstream pvd(r.dir / "particles.pvd");
    const std::string series((std::istreambuf_iterator<char>(pvd)),
                             std::istreambuf_iterator<char>());
    EXPECT_NE(series.find(last), std::string::npos) << series;
    EXPECT_EQ(series.find("file=", series.find(last) + 1), std::string::npos)
        << "not the last entry:\n"
        << series;
    EXPECT_EQ(series.find("failed_step"), std::string::npos);
    EXPECT_TRUE(fs::exists(r.dir / last));
    EXPECT_TRUE(fs::exists(r.dir / failed));
  } else {
    EXPECT_NE(r.output.find("sus: " + std::to_string(static_cast<long>(history.back().at("step"))) +
                            " steps"),
              std::string::npos)
        << r.output;
    if (e.endStep > 0) {
      EXPECT_EQ(history.back().at("step"), e.endStep);
    } else {
      EXPECT_GE(history.back().at("time"), readMaxTime(GetParam()));
    }
    if (readInput(GetParam()).find("<time_integrator>implicit") != std::string::npos) {
      // Every step's Newton converged within ImpMPM's default 25 iterations.
      std::smatch m;
      ASSERT_TRUE(std::regex_search(
          r.output, m, std::regex("Newton iterations ([0-9]+) \\(([0-9.]+) per step\\)")))
          << r.output;
      EXPECT_GE(std::stol(m[1]), static_cast<long>(history.back().at("step"))) << r.output;
      EXPECT_LE(std::stod(m[2]), 25.0) << r.output;
    }
  }
  if (e.check) e.check(history);
  if (!::testing::Test::HasFailure()) fs::remove_all(r.dir);
}

INSTANTIATE_TEST_SUITE_P(Inputs, StabilityCase, ::testing::ValuesIn(stabilityInputs()), testName);

TEST(StabilityInputs, EveryExpectationHasItsInput) {
  const auto inputs = stabilityInputs();
  for (const auto& [name, e] : expectations())
    EXPECT_TRUE(std::find(inputs.begin(), inputs.end(), name) != inputs.end()) << name;
}

RunOptions quiet() {
  RunOptions o;
  o.progress = false;
  return o;
}

TEST(BetaBeyondPmax, TheClampHoldsTheDiffusivityWherePressureExceedsPmax) {
  // D = D0 exp(alpha c - beta min(p, p_max)) with D0 = 1e-4, alpha = 6, beta = 0.5, p_max = 3 GPa.
  Simulation sim(readInput("Beta_0.5_confined"), "Beta_0.5_confined.ups", quiet());
  while (sim.step() < 300) sim.advance();
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  double maxPressure = 0, smallestRatio = HUGE_VAL;
  for (size_t i = 0; i < p.count(); ++i) {
    maxPressure = std::max(maxPressure, -p.stress[i].trace() / 3 * 1e-6);  // GPa
    smallestRatio =
        std::min(smallestRatio, diffusionParticles(p).diffusivity[i] /
                                    (1e-4 * std::exp(6 * diffusionParticles(p).concentration[i])));
  }
  EXPECT_GT(maxPressure, 10 * 3.0);
  EXPECT_NEAR(smallestRatio, std::exp(-0.5 * 3.0), 1e-9);
}

// One elastic block at rest: the StateChecks see what the test does to its particles.
class StateChecksTest : public ::testing::Test {
 protected:
  explicit StateChecksTest(const testing::BlockInput& in = block())
      : sim(in.text(), "block.ups", quiet()) {}
  static testing::BlockInput block() {
    testing::BlockInput in;
    in.velocity = "[1, 0, 0]";
    return in;
  }
  ParticleSet& particles() { return sim.mpm().materials()[0].particles; }
  std::string failure() {
    try {
      checks.afterStep(Communicator::everyRank(), sim.mpm(), sim.dt());
    } catch (const SimulationError& e) {
      return e.what();
    }
    return "";
  }
  // For k = 0, 1, ..., n - 1: gives particle i the velocity velocity(k, i) and checks. Returns
  // the step (from 1) the checks stopped, or 0; their message in *message.
  int stepsUntilStopped(int n, const std::function<Vec3(int k, size_t i)>& velocity,
                        std::string* message = nullptr) {
    for (int k = 0; k < n; ++k) {
      for (size_t i = 0; i < particles().count(); ++i) particles().velocity[i] = velocity(k, i);
      const std::string f = failure();
      if (message) *message = f;
      if (!f.empty()) return k + 1;
    }
    return 0;
  }
  // stepsUntilStopped with the starting velocities plus one that flips sign every step along
  // `axis`, of amplitude 1e-3 growing by `growth` per step.
  int stepsOfAnAlternation(int axis, double growth, int n) {
    const std::vector<Vec3> base = particles().velocity;
    return stepsUntilStopped(n, [&](int k, size_t i) -> Vec3 {
      return base[i] + (k % 2 ? -1 : 1) * 1e-3 * std::pow(growth, k) * Vec3::Unit(axis);
    });
  }
  Simulation sim;
  StateChecks checks;
};

TEST_F(StateChecksTest, AcceptsAGoodState) {
  EXPECT_EQ(failure(), "");
}

TEST_F(StateChecksTest, NamesANonFiniteVelocityWithTheParticle) {
  particles().velocity[3].y() = std::nan("");
  const std::string f = failure();
  EXPECT_NE(f.find("particle 3 of material 0 (block) at ["), std::string::npos) << f;
  EXPECT_NE(f.find("has a non-finite velocity p.velocity = [1, nan, 0]"), std::string::npos) << f;
}

TEST_F(StateChecksTest, NamesANonFinitePositionAndStress) {
  particles().stress[5](1, 2) = HUGE_VAL;
  std::string f = failure();
  EXPECT_NE(f.find("particle 5 of material 0 (block) at ["), std::string::npos) << f;
  EXPECT_NE(f.find("] has a non-finite stress p.stress = [0, 0, 0, 0, 0, inf, 0, 0, 0]"),
            std::string::npos)
      << f;
  particles().x[2].z() = -HUGE_VAL;
  f = failure();
  EXPECT_NE(f.find("particle 2 of material 0 (block) at ["), std::string::npos) << f;
  EXPECT_NE(f.find(", -inf] has a non-finite position"), std::string::npos) << f;
}

TEST_F(StateChecksTest, NamesJOutsideItsBounds) {
  particles().volume[7] *= 2e5;
  EXPECT_NE(failure().find("particle 7 of material 0 (block) at ["), std::string::npos)
      << failure();
  EXPECT_NE(failure().find("has J = V rho0 / m = 200000, above 100000"), std::string::npos)
      << failure();
  particles().volume[7] = particles().mass[7] / 1000 * 2e-6;
  EXPECT_NE(failure().find("has J = V rho0 / m = 2e-06, below 1e-05"), std::string::npos)
      << failure();
  particles().volume[7] = -1;
  EXPECT_NE(failure().find("(inverted, degenerate or not a number)"), std::string::npos)
      << failure();
}

TEST_F(StateChecksTest, StopsAnOscillationThatGrowsButNotOneThatDoesNot) {
  // Velocities that flip sign every step: growing by 1.5 per step trips the check once the
  // energy of two increments grew 100-fold (about 6 steps); a constant amplitude never does.
  EXPECT_EQ(stepsOfAnAlternation(1, 1.0, 200), 0);
  checks = StateChecks();
  const int at = stepsOfAnAlternation(1, 1.5, 200);
  EXPECT_GE(at, 5);
  EXPECT_LE(at, 10);
}

TEST_F(StateChecksTest, StopsASlowOscillationThatPersistsTenSteps) {
  // Energy growing 1.1-fold per step: past 2 after 8 steps, stopped once the run is 10 long;
  // the same oscillation decaying 0.9-fold per step is never stopped.
  EXPECT_EQ(stepsOfAnAlternation(2, std::sqrt(0.9), 100), 0);
  checks = StateChecks();
  const int at = stepsOfAnAlternation(2, std::sqrt(1.1), 100);
  EXPECT_GE(at, 10);
  EXPECT_LE(at, 14);
}

TEST_F(StateChecksTest, StopsOneParticleWhoseVelocityOscillatesWithGrowingAmplitude) {
  // The body accelerates steadily (its increments agree from step to step, so the whole-body
  // watch stays quiet at first) while particle 4 flips sign every step with amplitude growing by
  // `growth` from `start`: the local watch stops it once it reversed and grew 5 steps in a row,
  // unless it grows by less than 1.2 or stays round-off (below 1e-3 of the rms speed, about 1).
  const std::vector<Vec3> base = particles().velocity;
  auto steps = [&](double growth, double start, int n, std::string* f) {
    return stepsUntilStopped(
        n,
        [&](int k, size_t i) -> Vec3 {
          const double flip = i == 4 ? (k % 2 ? -1 : 1) * start * std::pow(growth, k) : 0.0;
          return base[i] + Vec3(0.01 * k, flip, 0);
        },
        f);
  };
  std::string f;
  // Growing by 1.1, it is left to the whole-body watch (which stops it once it dominates).
  steps(1.1, 1e-2, 60, &f);
  EXPECT_EQ(f.find("the velocity of particle"), std::string::npos) << f;
  checks = StateChecks();
  EXPECT_EQ(steps(1.3, 1e-9, 20, &f), 0) << f;  // 1.3^20 x 1e-9 = 2e-7: round-off all along
  checks = StateChecks();
  // Streaks count from the third step (the first increment that can reverse one before it).
  EXPECT_EQ(steps(1.3, 1e-2, 60, &f), 7) << f;
  EXPECT_NE(f.find("the velocity of particle 4 of material 0 (block) at ["), std::string::npos)
      << f;
  EXPECT_NE(
      f.find(
          "for 5 steps in a row its increment reversed the previous one and grew by 1.2 or more"),
      std::string::npos)
      << f;
}

// The same block whose particles split when stretched 2-fold.
class SplittingStateChecksTest : public StateChecksTest {
 protected:
  SplittingStateChecksTest() : StateChecksTest(splittingBlock()) {}
  static testing::BlockInput splittingBlock() {
    testing::BlockInput in = block();
    in.mpmFlags = "<refine_particles>true</refine_particles>";
    in.amr =
        "<AMR><MPM><Refinement_Criteria_Thresholds><Variable name=\"stretchRatio\" value=\"2\"/>"
        "</Refinement_Criteria_Thresholds></MPM></AMR>\n";
    return in;
  }
  // An alternation on every particle, each about a velocity of its own (a child about its
  // parent's), growing by 1.15 per step: too slowly for the local watch, so the whole-body watch
  // stops it once it persisted 10 steps. Watched by fresh checks; before its step `splitAt` (none
  // if negative), particle `splitAt` is stretched 3-fold and a step of the MPM splits it. Returns
  // the step the checks stopped, or 0.
  int stepsOfAnAlternationWithASplit(int splitAt) {
    checks = StateChecks();
    const size_t count = particles().count();
    const Vec3 start = particles().velocity[0];
    // Its own velocity along z, 0.3 apart from its neighbours': a child given another
    // particle's history would see a jump that outweighs the alternation of the whole body.
    auto own = [&](size_t i) {
      const size_t owner = i < count ? i : static_cast<size_t>(splitAt);
      return Vec3(start + 0.3 * static_cast<double>(owner % 7) * Vec3::UnitZ());
    };
    for (int k = 0; k < 40; ++k) {
      if (k == splitAt) {
        particles().F[splitAt] = Vec3(3, 1, 1).asDiagonal();
        sim.integrator().advance(Communicator::everyRank(), 0, sim.dt(), sim.dt());
        EXPECT_EQ(particles().count(), count + 3);
      }
      for (size_t i = 0; i < particles().count(); ++i)
        particles().velocity[i] =
            own(i) + (k % 2 ? -1 : 1) * 1e-3 * std::pow(1.15, k) * Vec3::UnitY();
      if (!failure().empty()) return k + 1;
    }
    return 0;
  }
};

TEST_F(SplittingStateChecksTest, TheChildrenOfASplitParticleContinueItsHistory) {
  // Their velocity and share of its mass are the parent's, so the watches go on through a split
  // and stop the alternation at the step they stop it without one.
  const int unsplit = stepsOfAnAlternationWithASplit(-1);
  ASSERT_GE(unsplit, 10);
  for (int splitAt = 1; splitAt < unsplit; ++splitAt)
    EXPECT_EQ(stepsOfAnAlternationWithASplit(splitAt), unsplit) << "split at step " << splitAt;
}

TEST_F(StateChecksTest, StopsAKineticEnergyThatDoublesTwentyStepsInARow) {
  const std::vector<Vec3> base = particles().velocity;
  std::string f;
  // Same direction every step (no oscillation): the energy grows by 2.25 per step.
  const int stopped = stepsUntilStopped(
      40, [&](int k, size_t i) -> Vec3 { return base[i] * std::pow(1.5, k + 1); }, &f);
  EXPECT_EQ(stopped, 21) << f;
  EXPECT_NE(
      f.find("the kinetic energy grew by a factor of at least 2 at each of the last 20 steps"),
      std::string::npos)
      << f;
  EXPECT_NE(f.find("; the fastest is particle "), std::string::npos) << f;
}

TEST_F(StateChecksTest, PowerLawGrowthFromRestIsNotABlowUp) {
  // A body starting from rest under a load that grows linearly: v ~ t^3, KE ~ t^6.
  std::string f;
  EXPECT_EQ(stepsUntilStopped(
                500, [](int k, size_t) -> Vec3 { return Vec3(std::pow(k + 1, 3.0), 0, 0); }, &f),
            0)
      << f;
}

}  // namespace
}  // namespace anode

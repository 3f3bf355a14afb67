// Pins report.html (RunReport.h): written at the end of a run, at a stop and by render_vtu
// --report, a well-formed page holding the history's plots, the numbers and the pictures; the
// history columns it reads (elastic energy, dt rule, Newton and Krylov iterations); its thinning
// of a long history; the elastic energy density it divides by.
#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"
#include "RunSus.h"
#include "StandAlone/Driver/HistoryDigest.h"
#include "StandAlone/Driver/RunReport.h"
#include "TestFiles.h"
#include "vis/SvgPlot.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

using testing::readFile;
using testing::runSus;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("anode_report_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

// What a test reads of a report: the ids of its plots, its table, its pictures and the class of
// its quasi-static verdict.
struct ParsedReport {
  std::set<std::string> plots;
  std::vector<std::pair<std::string, std::string>> table;
  int pictures = 0;
  std::string verdict, status;
  std::string value(const std::string& row) const {
    for (const auto& [what, value] : table)
      if (what == row) return value;
    return "";
  }
};

void walk(const tinyxml2::XMLElement* e, ParsedReport& r) {
  for (; e; e = e->NextSiblingElement()) {
    const std::string name = e->Name();
    if (name == "svg" && e->Attribute("id")) r.plots.insert(e->Attribute("id"));
    if (name == "img" && std::string(e->Attribute("src")).rfind("data:image/png;base64,", 0) == 0)
      ++r.pictures;
    if (name == "tr") {
      const auto* th = e->FirstChildElement("th");
      const auto* td = e->FirstChildElement("td");
      r.table.emplace_back(th && th->GetText() ? th->GetText() : "",
                           td && td->GetText() ? td->GetText() : "");
    }
    if (name == "p" && e->Attribute("class") && e->GetText()) r.verdict = e->Attribute("class");
    if (name == "p" && r.status.empty() && e->GetText()) r.status = e->GetText();
    walk(e->FirstChildElement(), r);
  }
}

// Parses the page as XML (it is written well-formed): a page a browser would have to guess at
// fails here.
ParsedReport parseReport(const fs::path& file) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(file.string().c_str()), tinyxml2::XML_SUCCESS) << file;
  ParsedReport r;
  if (doc.RootElement()) walk(doc.RootElement(), r);
  return r;
}

TEST(RunReport, ElasticEnergyDensityIsThatOfLinearElasticity) {
  const double K = 10.0, G = 4.0, s = 3.0;
  const RFElasticPlastic rf(K, G, std::nullopt);
  const auto density = [&](const Mat3& sigma) {
    return ConstitutiveModel::elasticEnergyDensity(sigma, rf.bulkModulus(), rf.shearModulus());
  };
  Mat3 uniaxial = Mat3::Zero();
  uniaxial(0, 0) = s;
  const double E = 9 * K * G / (3 * K + G);
  EXPECT_NEAR(density(uniaxial), s * s / (2 * E), 1e-14);
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = s;
  EXPECT_NEAR(density(shear), s * s / (2 * G), 1e-14);
  EXPECT_NEAR(density(-s * Mat3::Identity()), s * s / (2 * K), 1e-14);
}

// A long history keeps at most 2 x bins points per column, each bin's extremes (a one-row spike
// survives the thinning), the counts of every row, and skips a last line a kill cut short.
TEST(RunReport, DigestThinsALongHistoryKeepingExtremes) {
  const fs::path dir = scratch("digest");
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "history.csv");
    csv << "step,time,dt,kinetic_energy,elastic_energy,dt_limit,wall_seconds\n";
    csv << "0,0,0,0,0,-1,0\n";
    for (int k = 1; k <= 10000; ++k)
      csv << k << ',' << 0.5 * k << ",0.5," << (k == 4321 ? 50.0 : 1e-3) << ",1," << k % 2 << ','
          << k << '\n';
    csv << "10001,5000.5,0.";  // cut short
  }
  const HistoryDigest d = digestHistory((dir / "history.csv").string(), 100, 1e-2);
  EXPECT_EQ(d.steps, 10000);
  EXPECT_LE(d.binTime.size(), 200u);
  EXPECT_GE(d.binTime.size(), 100u);
  const int ratio = d.column("kinetic_to_elastic");
  ASSERT_GE(ratio, 0);
  EXPECT_DOUBLE_EQ(d.maximum[ratio], 50.0);
  EXPECT_DOUBLE_EQ(*std::max_element(d.high[ratio].begin(), d.high[ratio].end()), 50.0);
  EXPECT_EQ(d.ratioSteps, 10000);
  EXPECT_EQ(d.ratioAbove, 1);
  EXPECT_EQ(d.stepsByRule[0], 5000);
  EXPECT_EQ(d.stepsByRule[1], 5000);
  EXPECT_DOUBLE_EQ(d.last[d.column("time")], 5000.0);
  EXPECT_DOUBLE_EQ(d.binTime.back(), 5000.0);
  EXPECT_DOUBLE_EQ(d.smallestStepDt, 0.5);
  fs::remove_all(dir);
}

// The explicit pillar example stopped early: the report of the stop holds every plot of a
// diffusion run,
// the picture of t = 0 and the run's numbers as history.csv has them; render_vtu --report writes
// the same page but for its status line.
TEST(RunReport, WrittenAtAStopAndByRenderVtu) {
  const fs::path dir = scratch("pillar");
  const auto run = runSus({"--max-timesteps", "30", "-o", dir.string(),
                           std::string(ANODE_SOURCE_DIR) + "/inputs/Pillar/PillarLithiation.ups"});
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const ParsedReport r = parseReport(dir / "report.html");
  EXPECT_EQ(r.plots,
            (std::set<std::string>{"lithium", "state_of_charge", "current", "dt", "energy_ratio",
                                   "concentration", "jacobian", "stress_silicon",
                                   "plastic_work_silicon", "stress_soc_silicon"}));
  EXPECT_EQ(r.pictures, 1);  // cutaway at t = 0
  EXPECT_NE(r.status.find("stopped before its end, after step 30"), std::string::npos) << r.status;
  EXPECT_EQ(r.value("steps"), "30");
  EXPECT_EQ(r.value("particles (last step)"), "12660");
  EXPECT_NE(r.value("steps whose dt was set by: mechanics (Eq. 43)"), "");
  // The explicit pillar at its raised density moves: the check cannot vouch for it.
  EXPECT_EQ(r.verdict, "warn");

  const std::string before = readFile(dir / "report.html");
  fs::remove(dir / "report.html");
  const std::string command =
      std::string(ANODE_RENDER_VTU) + " --report " + dir.string() + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::string after = readFile(dir / "report.html");
  const auto withoutStatus = [](const std::string& page) {
    const size_t from = page.find("<p>Written"), to = page.find("</p>", from);
    return page.substr(0, from) + page.substr(to);
  };
  EXPECT_EQ(withoutStatus(before), withoutStatus(after));
  EXPECT_NE(after.find("Written by render_vtu --report."), std::string::npos);
  fs::remove_all(dir);
}

// An implicit quasi-static run: the history's Newton and Krylov columns, their plots and totals
// (the sums of the columns; with no step retaken, the end summary's totals), the quasi-static
// verdict.
TEST(RunReport, ImplicitRunGivesNewtonAndKrylov) {
  const fs::path dir = scratch("implicit");
  const auto run =
      runSus({"-o", dir.string(), "--max-timesteps", "3",
              std::string(ANODE_SOURCE_DIR) + "/inputs/Stability/Implicit_swelling_eta_0.56.ups"});
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const HistoryDigest d = digestHistory((dir / "history.csv").string(), 100, 1e-2);
  ASSERT_GE(d.column("newton_iterations"), 0);
  ASSERT_GE(d.column("krylov_iterations"), 0);
  EXPECT_GT(d.newtonIterations, 3);
  EXPECT_GT(d.krylovIterations, d.newtonIterations);
  EXPECT_NE(run.output.find("Newton iterations " + std::to_string(long(d.newtonIterations)) + " "),
            std::string::npos)
      << run.output;
  const ParsedReport r = parseReport(dir / "report.html");
  EXPECT_TRUE(r.plots.count("newton") && r.plots.count("krylov"));
  EXPECT_EQ(r.verdict, "ok");  // <dynamic>false: quasi-static by construction
  EXPECT_EQ(r.value("Newton iterations").rfind(std::to_string(long(d.newtonIterations)) + " (", 0),
            0u)
      << r.value("Newton iterations");
  fs::remove_all(dir);
}

// A quasi-static run with <concentration_coupling>trapezoidal: the history's coupling_correction
// (0 at step 0, above 0 at each step that diffuses) and its plot; a staggered input has neither.
TEST(RunReport, TrapezoidalRunPlotsItsCouplingCorrection) {
  const fs::path dir = scratch("trapezoidal");
  const auto run =
      runSus({"-o", dir.string(), "--max-timesteps", "2",
              std::string(ANODE_SOURCE_DIR) + "/tests/parallel/ImplicitLithiation.ups"});
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const HistoryDigest d = digestHistory((dir / "history.csv").string(), 100, 1e-2);
  const int c = d.column("coupling_correction");
  ASSERT_GE(c, 0);
  EXPECT_EQ(d.minimum[c], 0.0);  // step 0
  EXPECT_GT(d.last[c], 0.0);
  EXPECT_TRUE(parseReport(dir / "report.html").plots.count("coupling"));
  fs::remove_all(dir);

  const fs::path staggered = scratch("staggered");
  ASSERT_EQ(runSus({"-o", staggered.string(), "--max-timesteps", "1",
                    std::string(ANODE_SOURCE_DIR) + "/tests/parallel/ImplicitSwelling.ups"})
                .exitCode,
            0);
  EXPECT_LT(
      digestHistory((staggered / "history.csv").string(), 100, 1e-2).column("coupling_correction"),
      0);
  EXPECT_FALSE(parseReport(staggered / "report.html").plots.count("coupling"));
  fs::remove_all(staggered);
}

// The default input (quasi-static, <error_tolerance> 0.01) after 4 steps: history.csv's error
// columns, their plots, and the largest estimate of a step within the tolerance.
TEST(RunReport, ErrorControlledRunReportsItsEstimates) {
  const fs::path dir = scratch("error_control");
  const auto run = runSus({"-o", dir.string(), "--max-timesteps", "4",
                           std::string(ANODE_SOURCE_DIR) + "/inputs/Pillar/PillarQuasiStatic.ups"});
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const HistoryDigest d = digestHistory((dir / "history.csv").string(), 100, 1e-2);
  for (const char* column : {"error_estimate", "accumulated_error_estimate", "rejected_attempts"})
    EXPECT_GE(d.column(column), 0) << column;
  const ParsedReport r = parseReport(dir / "report.html");
  EXPECT_TRUE(r.plots.count("error") && r.plots.count("rejected"));
  const double largest =
      std::stod(r.value("error estimate of a step, largest (c / c_max of a particle)"));
  EXPECT_GT(largest, 0);
  EXPECT_LE(largest, 0.01);
  EXPECT_NE(r.value("steps whose dt was set by: error estimate"), "");
  fs::remove_all(dir);
}

// A run that fails (a time step beyond the stable one: exit 3) leaves the page of its last good
// state, saying which step failed.
TEST(RunReport, WrittenWhenAStepFails) {
  const fs::path dir = scratch("failed");
  const auto run = runSus(
      {"-o", dir.string(), std::string(ANODE_SOURCE_DIR) + "/inputs/Stability/Multiplier_0.8.ups"});
  ASSERT_EQ(run.exitCode, 3) << run.output;
  const ParsedReport r = parseReport(dir / "report.html");
  const std::string lastGood = r.value("steps");
  EXPECT_NE(
      r.status.find("Written when step " + std::to_string(std::stol(lastGood) + 1) + " failed"),
      std::string::npos)
      << r.status;
  fs::remove_all(dir);
}

// Plots of a range too narrow to count ticks in (a few units in the last place), of one value
// and of nothing are drawn (a loop over ticks once never ended on the first).
TEST(RunReport, PlotsOfDegenerateRangesAreDrawn) {
  for (const std::vector<double>& y :
       {std::vector<double>{0.5, std::nextafter(0.5, 1.0)}, std::vector<double>{1.0, 1.0},
        std::vector<double>{0.0, 0.0}, std::vector<double>{}}) {
    PlotSpec plot;
    plot.id = "p";
    plot.series.push_back({"line", "#000000", std::vector<double>(y.size(), 1.0), y});
    const std::string svg = svgPlot(plot);
    tinyxml2::XMLDocument doc;
    EXPECT_EQ(doc.Parse(svg.c_str()), tinyxml2::XML_SUCCESS) << svg;
    EXPECT_LT(svg.size(), 20000u);
  }
}

// An output directory without history.csv: render_vtu --report says so and exits 1.
TEST(RunReport, RenderVtuNamesAMissingHistory) {
  const fs::path dir = scratch("empty");
  fs::create_directories(dir);
  const std::string command = std::string(ANODE_RENDER_VTU) + " --report " + dir.string() + " > " +
                              (dir / "log").string() + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(command.c_str())), 1);
  EXPECT_NE(readFile(dir / "log").find("no history.csv"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace anode

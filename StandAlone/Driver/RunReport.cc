#include "StandAlone/Driver/RunReport.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/AtomicFile.h"
#include "StandAlone/Driver/HistoryDigest.h"
#include "vis/SvgPlot.h"

namespace fs = std::filesystem;

namespace anode {

namespace {

constexpr size_t kPlotBins = 600;        // a plotted line: one point per bin, 600 to 1,200 bins
constexpr size_t kPicturesPerScene = 6;  // the first, the last and evenly between

std::string base64(const std::string& bytes) {
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    unsigned v = 0;
    for (size_t k = 0; k < 3; ++k)
      v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string number(double v, const char* format = "%.4g") {
  if (std::isnan(v)) return "-";
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// What the report takes from the run's copy of its input: the title, the end time and whether
// the run solves equilibrium every step (<time_integrator>implicit with <dynamic>false).
struct InputFacts {
  std::string title, maxTime;
  bool quasiStatic = false;
};

std::string textOf(const tinyxml2::XMLElement* parent, const char* tag) {
  const tinyxml2::XMLElement* e = parent ? parent->FirstChildElement(tag) : nullptr;
  if (!e || !e->GetText()) return "";
  std::string text = e->GetText();
  const size_t first = text.find_first_not_of(" \t\n"), last = text.find_last_not_of(" \t\n");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

InputFacts readInputFacts(const fs::path& input) {
  InputFacts facts;
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(input.string().c_str()) != tinyxml2::XML_SUCCESS) return facts;
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root) return facts;
  facts.title = textOf(root->FirstChildElement("Meta"), "title");
  facts.maxTime = textOf(root->FirstChildElement("Time"), "maxTime");
  const tinyxml2::XMLElement* mpm = root->FirstChildElement("MPM");
  // As sus reads them (parseValue): <dynamic> absent is ImpMPM's default, true.
  const std::string dynamic = textOf(mpm, "dynamic");
  try {
    facts.quasiStatic = textOf(mpm, "time_integrator") == "implicit" && !dynamic.empty() &&
                        !parseValue<bool>(dynamic);
  } catch (const std::invalid_argument&) {
    facts.quasiStatic = false;  // sus would not have run it
  }
  return facts;
}

// A column's bin extremes as two lines (they coincide where a bin holds one row).
void addEnvelope(PlotSpec& plot, const HistoryDigest& d, const std::string& column,
                 const std::string& label, const std::string& colour, double scale = 1) {
  const int c = d.column(column);
  if (c < 0) return;
  PlotSeries low{label, colour, d.binTime, d.low[c]}, high{"", colour, d.binTime, d.high[c]};
  for (double& v : low.y) v *= scale;
  for (double& v : high.y) v *= scale;
  plot.series.push_back(std::move(low));
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  if (!std::equal(d.low[c].begin(), d.low[c].end(), d.high[c].begin(), same))
    plot.series.push_back(std::move(high));
}

PlotSpec timePlot(const std::string& id, const std::string& title, const std::string& yLabel,
                  bool logY = false) {
  PlotSpec p;
  p.id = id;
  p.title = title;
  p.xLabel = "t (the input's time unit)";
  p.yLabel = yLabel;
  p.logY = logY;
  return p;
}

// One column's bin-last values against another's (a curve that may turn back: a cycle).
void addCurve(PlotSpec& plot, const HistoryDigest& d, const std::string& x, const std::string& y,
              const std::string& label, const std::string& colour, double xScale = 1) {
  const int cx = d.column(x), cy = d.column(y);
  if (cx < 0 || cy < 0) return;
  PlotSeries series{label, colour, d.binLast[cx], d.binLast[cy]};
  for (double& v : series.x) v *= xScale;
  plot.series.push_back(std::move(series));
}

// Per material with stress columns: its mean pressure and von Mises stress and its plastic work
// against time, and against the state of charge its stress x thickness (with <film_normal>) or
// its mean pressure.
void addStressPlots(std::vector<PlotSpec>& out, const HistoryDigest& d) {
  const std::string prefix = "mean_pressure_";
  for (const std::string& column : d.columns) {
    if (column.rfind(prefix, 0) != 0) continue;
    const std::string name = column.substr(prefix.size());
    PlotSpec stress = timePlot("stress_" + name, "Mean stress of " + name + " (volume means)",
                               "stress (the input's unit)");
    addEnvelope(stress, d, column, "pressure -tr(sigma)/3", "#1f77b4");
    addEnvelope(stress, d, "mean_von_mises_" + name, "von Mises", "#d62728");
    out.push_back(std::move(stress));
    if (d.column("plastic_work_" + name) >= 0) {
      PlotSpec work =
          timePlot("plastic_work_" + name, "Plastic work of " + name, "sum V sigma_e dep (energy)");
      addEnvelope(work, d, "plastic_work_" + name, "plastic work", "#9467bd");
      out.push_back(std::move(work));
    }
    if (d.column("state_of_charge") < 0) continue;
    const bool film = d.column("stress_thickness_" + name) >= 0;
    PlotSpec against;
    against.id = "stress_soc_" + name;
    against.title = film ? "Stress x thickness of " + name + " against the state of charge"
                         : "Mean pressure of " + name + " against the state of charge";
    against.xLabel = "state of charge (%)";
    against.yLabel = film ? "in-plane stress x thickness" : "pressure";
    addCurve(against, d, "state_of_charge", film ? "stress_thickness_" + name : column,
             film ? "stress x thickness" : "pressure", "#2ca02c", 100);
    out.push_back(std::move(against));
  }
}

// Per <scalar_flux> with a <surface_reaction> (potential_N): the electrode's potential against
// time and against the state of charge.
void addPotentialPlots(std::vector<PlotSpec>& out, const HistoryDigest& d) {
  const std::string prefix = "potential_";
  for (const std::string& column : d.columns) {
    if (column.rfind(prefix, 0) != 0) continue;
    const std::string bc = column.substr(prefix.size());
    PlotSpec potential =
        timePlot(column, "Electrode potential of <scalar_flux> " + bc, "potential (V)");
    addEnvelope(potential, d, column, "potential", "#1f77b4");
    out.push_back(std::move(potential));
    PlotSpec against;
    against.id = column + "_soc";
    against.title = "Electrode potential of <scalar_flux> " + bc + " against the state of charge";
    against.xLabel = "state of charge (%)";
    against.yLabel = "potential (V)";
    addCurve(against, d, "state_of_charge", column, "potential", "#1f77b4", 100);
    out.push_back(std::move(against));
  }
}

std::vector<PlotSpec> plots(const HistoryDigest& d) {
  std::vector<PlotSpec> out;
  if (d.column("total_lithium") >= 0) {
    PlotSpec lithium = timePlot("lithium", "Lithium: sum of m c", "sum m c");
    addEnvelope(lithium, d, "total_lithium", "total lithium", "#1f77b4");
    out.push_back(std::move(lithium));
    PlotSpec soc = timePlot("state_of_charge", "State of charge", "%");
    addEnvelope(soc, d, "state_of_charge", "state of charge", "#2ca02c", 100);
    out.push_back(std::move(soc));
  }
  if (d.column("lithium_rate") >= 0) {
    PlotSpec current =
        timePlot("current", "Current: the rate of change of the lithium", "sum m c per time unit");
    addEnvelope(current, d, "lithium_rate", "d(sum m c)/dt", "#1f77b4");
    out.push_back(std::move(current));
  }
  addPotentialPlots(out, d);
  addStressPlots(out, d);
  PlotSpec dt = timePlot("dt", "Time step", "dt", true);
  addEnvelope(dt, d, "dt", "dt", "#333333");
  out.push_back(std::move(dt));
  PlotSpec ratio =
      timePlot("energy_ratio", "Quasi-static check: kinetic / elastic energy", "KE / E_el", true);
  addEnvelope(ratio, d, "kinetic_to_elastic", "kinetic / elastic", "#d62728");
  ratio.references.push_back({kQuasiStaticEnergyRatio, "bound " + number(kQuasiStaticEnergyRatio)});
  out.push_back(std::move(ratio));
  if (d.column("min_c") >= 0) {
    PlotSpec c = timePlot("concentration", "Concentration: smallest and largest", "c");
    addEnvelope(c, d, "max_c", "largest c", "#9467bd");
    addEnvelope(c, d, "min_c", "smallest c", "#8c564b");
    out.push_back(std::move(c));
  }
  PlotSpec J = timePlot("jacobian", "Volume ratio J: smallest and largest", "J");
  addEnvelope(J, d, "max_J", "largest J", "#ff7f0e");
  addEnvelope(J, d, "min_J", "smallest J", "#17becf");
  out.push_back(std::move(J));
  if (d.column("newton_iterations") >= 0) {
    PlotSpec newton = timePlot("newton", "Newton iterations per step", "iterations");
    addEnvelope(newton, d, "newton_iterations", "Newton", "#1f77b4");
    out.push_back(std::move(newton));
    PlotSpec krylov = timePlot("krylov", "Krylov iterations per step", "iterations");
    addEnvelope(krylov, d, "krylov_iterations", "Krylov", "#ff7f0e");
    out.push_back(std::move(krylov));
  }
  if (d.column("coupling_correction") >= 0) {
    PlotSpec coupling = timePlot(
        "coupling", "Coupling correction per step: the two diffusion passes' difference / 2",
        "share of the capacity");
    addEnvelope(coupling, d, "coupling_correction", "coupling correction", "#2ca02c");
    out.push_back(std::move(coupling));
  }
  if (d.column("error_estimate") >= 0) {
    PlotSpec error =
        timePlot("error", "Error estimate: each step's, and accumulated over the steps",
                 "c / c_max of a particle", true);
    addEnvelope(error, d, "error_estimate", "step's estimate", "#1f77b4");
    addEnvelope(error, d, "accumulated_error_estimate", "accumulated (a particle's largest)",
                "#d62728");
    out.push_back(std::move(error));
    PlotSpec rejected = timePlot("rejected", "Attempts rejected before each step", "attempts");
    addEnvelope(rejected, d, "rejected_attempts", "rejected attempts", "#7f7f7f");
    out.push_back(std::move(rejected));
  }
  return out;
}

void row(std::ostream& html, const std::string& what, const std::string& value) {
  html << "<tr><th>" << escapeXml(what) << "</th><td>" << escapeXml(value) << "</td></tr>\n";
}

// The run in numbers.
void numbersTable(std::ostream& html, const HistoryDigest& d) {
  const auto at = [&](const std::vector<double>& v, const char* name) {
    const int c = d.column(name);
    return c < 0 ? NAN : v[c];
  };
  html << "<table>\n";
  row(html, "steps", std::to_string(d.steps));
  row(html, "time reached", number(at(d.last, "time")));
  row(html, "particles (last step)", number(at(d.last, "particles"), "%.0f"));
  row(html, "wall time (s)", number(at(d.last, "wall_seconds"), "%.1f"));
  if (d.column("total_lithium") >= 0) {
    row(html, "lithium, sum of m c (last step)", number(at(d.last, "total_lithium")));
    row(html, "state of charge (last step)",
        number(100 * at(d.last, "state_of_charge"), "%.2f") +
            "% = " + number(at(d.last, "capacity_mAh_g"), "%.0f") + " mAh/g of silicon");
    row(html, "c over the run",
        "[" + number(at(d.minimum, "min_c")) + ", " + number(at(d.maximum, "max_c")) + "]");
    row(html, "c at the last step",
        "[" + number(at(d.last, "min_c")) + ", " + number(at(d.last, "max_c")) + "]");
  }
  row(html, "J over the run",
      "[" + number(at(d.minimum, "min_J")) + ", " + number(at(d.maximum, "max_J")) + "]");
  row(html, "J at the last step",
      "[" + number(at(d.last, "min_J")) + ", " + number(at(d.last, "max_J")) + "]");
  if (d.steps > 0)
    row(html, "dt over the run (smallest, largest)",
        number(d.smallestStepDt) + ", " + number(at(d.maximum, "dt")));
  for (int r = 0; r < kDtRules; ++r)
    if (d.stepsByRule[r] > 0)
      row(html, std::string("steps whose dt was set by: ") + dtRuleName(r),
          std::to_string(d.stepsByRule[r]) + " (" +
              number(100.0 * d.stepsByRule[r] / std::max(d.steps, 1L), "%.1f") + "%)");
  if (d.column("newton_iterations") >= 0 && d.steps > 0) {
    row(html, "Newton iterations",
        number(d.newtonIterations, "%.0f") + " (" + number(d.newtonIterations / d.steps, "%.2f") +
            " a step)");
    row(html, "Krylov iterations",
        number(d.krylovIterations, "%.0f") + " (" +
            number(d.newtonIterations > 0 ? d.krylovIterations / d.newtonIterations : NAN, "%.1f") +
            " a Newton iteration)");
  }
  if (d.column("error_estimate") >= 0) {
    row(html, "error estimate of a step, largest (c / c_max of a particle)",
        number(at(d.maximum, "error_estimate"), "%.3g"));
    row(html, "accumulated error estimate (c / c_max of a particle)",
        number(at(d.last, "accumulated_error_estimate"), "%.3g"));
  }
  row(html, "kinetic / elastic energy, largest",
      number(at(d.maximum, "kinetic_to_elastic"), "%.3g"));
  row(html, "steps above the bound " + number(kQuasiStaticEnergyRatio),
      std::to_string(d.ratioAbove) + " of " + std::to_string(d.ratioSteps));
  html << "</table>\n";
}

void quasiStaticVerdict(std::ostream& html, const HistoryDigest& d, bool quasiStatic) {
  if (quasiStatic) {
    html << "<p class=\"ok\">Quasi-static by construction: an implicit run with "
            "&lt;dynamic&gt;false solves for equilibrium every step; the particles' velocity "
            "(displacement over dt) and its kinetic energy enter no equation.</p>\n";
  } else if (d.ratioSteps == 0) {
    html << "<p class=\"note\">Quasi-static check: no step of history.csv has an elastic energy "
            "above 0 (or the column: a run of an older version).</p>\n";
  } else if (d.ratioAbove == 0) {
    html << "<p class=\"ok\">Quasi-static check passed: kinetic / elastic energy stayed at or "
            "below "
         << number(kQuasiStaticEnergyRatio) << " at every step, so the stress that accelerates "
         << "the material is under 10% of the stress.</p>\n";
  } else {
    html << "<p class=\"warn\">Warning: kinetic / elastic energy exceeded "
         << number(kQuasiStaticEnergyRatio) << " at " << d.ratioAbove << " of " << d.ratioSteps
         << " steps (largest " << number(d.maximum[d.column("kinetic_to_elastic")], "%.3g")
         << "): this check cannot vouch that the answer is quasi-static (the dynamic part of "
            "the stress may reach sqrt of the ratio). An explicit run with a raised density "
            "shows whether it matters by a run at another density; an implicit quasi-static "
            "run (&lt;dynamic&gt;false) has none.</p>\n";
  }
}

// The pictures of images/, per scene (the name before the time), the first, the last and
// evenly spaced between, in time order.
void scenes(std::ostream& html, const fs::path& images) {
  std::map<std::string, std::vector<std::pair<double, fs::path>>> byScene;
  if (fs::is_directory(images))
    for (const fs::directory_entry& e : fs::directory_iterator(images)) {
      const std::string name = e.path().stem().string();
      const size_t cut = name.rfind('_');
      if (e.path().extension() != ".png" || cut == std::string::npos) continue;
      char* end = nullptr;
      const double t = std::strtod(name.c_str() + cut + 1, &end);
      if (*end != '\0') continue;
      byScene[name.substr(0, cut)].emplace_back(t, e.path());
    }
  html << "<h2>Scenes</h2>\n";
  if (byScene.empty())
    html << "<p>No pictures in images/ (scenes come from the input&apos;s "
            "&lt;Visualization&gt;).</p>\n";
  for (auto& [scene, pictures] : byScene) {
    std::sort(pictures.begin(), pictures.end());
    const size_t n = pictures.size(), shown = std::min(n, kPicturesPerScene);
    html << "<h3>" << escapeXml(scene) << "</h3>\n<p>" << n << " picture" << (n == 1 ? "" : "s")
         << " in images/" << (shown < n ? ", " + std::to_string(shown) + " of them here" : "")
         << "</p>\n<div class=\"scene\">\n";
    for (size_t k = 0; k < shown; ++k) {
      const size_t i = shown == 1 ? 0 : k * (n - 1) / (shown - 1);
      html << "<figure><img alt=\"" << escapeXml(pictures[i].second.filename().string())
           << "\" src=\"data:image/png;base64," << base64(readBytes(pictures[i].second))
           << "\"/><figcaption>t = " << number(pictures[i].first) << "</figcaption></figure>\n";
    }
    html << "</div>\n";
  }
}

}  // namespace

std::string writeRunReport(const std::string& dir, const std::string& status) {
  const fs::path root(dir);
  const HistoryDigest d =
      digestHistory((root / "history.csv").string(), kPlotBins, kQuasiStaticEnergyRatio);
  const InputFacts input = readInputFacts(root / "input.ups");
  const std::string title = input.title.empty() ? root.filename().string() : input.title;
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
          "<meta charset=\"utf-8\"/>\n<title>"
       << escapeXml(title)
       << "</title>\n<style>body{font-family:sans-serif;max-width:1180px;margin:1em auto;}"
          "table{border-collapse:collapse}th,td{border:1px solid #ccc;padding:2px 8px;"
          "text-align:left}.warn{color:#a00;font-weight:bold}.ok{color:#060}"
          ".plots svg{margin:4px}.scene figure{display:inline-block;margin:4px}"
          ".scene img{max-width:360px}</style>\n</head>\n<body>\n<h1>"
       << escapeXml(title) << "</h1>\n<p>" << escapeXml(status) << " Output directory "
       << escapeXml(fs::absolute(root).string()) << "; the run's time "
       << number(d.last[d.column("time")]) << " of maxTime "
       << escapeXml(input.maxTime.empty() ? "?" : input.maxTime) << ".</p>\n";
  quasiStaticVerdict(html, d, input.quasiStatic);
  html << "<h2>The run in numbers</h2>\n";
  numbersTable(html, d);
  html << "<h2>History</h2>\n<p>From history.csv (" << d.steps
       << " steps); where a line holds more steps than points, it draws each run of steps' "
          "smallest and largest value.</p>\n<div class=\"plots\">\n";
  for (const PlotSpec& plot : plots(d)) html << svgPlot(plot);
  html << "</div>\n";
  scenes(html, root / "images");
  html << "</body>\n</html>\n";
  const std::string path = (root / "report.html").string();
  writeFileAtomically(path, html.str());
  return path;
}

}  // namespace anode

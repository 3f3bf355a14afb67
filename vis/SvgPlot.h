// Line plots as inline SVG, for pages that must open with no server and no script (report.html):
// axes with ticks at round numbers (decades on a log axis), one polyline per series, a legend,
// and optional horizontal reference lines.
#pragma once

#include <string>
#include <vector>

namespace anode {

struct PlotSeries {
  std::string label;
  std::string colour;  // an SVG colour: "#1f77b4"
  std::vector<double> x, y;
  bool dashed = false;
};

struct PlotSpec {
  std::string id;  // the <svg> element's id
  std::string title, xLabel, yLabel;
  bool logY = false;  // points with y <= 0 are left out of a log axis
  std::vector<PlotSeries> series;
  struct Reference {
    double y;
    std::string label;
  };
  std::vector<Reference> references;  // dashed grey lines across the plot
  int width = 560, height = 300;
};

// The plot as an <svg> element (well-formed XML; text escaped). With no point to draw it says so.
std::string svgPlot(const PlotSpec& spec);

// Escapes &, <, >, " and ' for XML text and attributes.
std::string escapeXml(const std::string& text);

}  // namespace anode

#include "vis/SvgPlot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace anode {

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

struct Range {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  bool empty() const { return !(low <= high); }
  // A range too narrow to draw (zero width, or a few units in the last place, where ticks
  // cannot be counted in doubles) widened around its middle.
  void widen() {
    const double scale = std::max(std::abs(low), std::abs(high));
    if (high - low > 1e-9 * scale) return;
    const double middle = 0.5 * (low + high), pad = scale > 0 ? 0.1 * scale : 1.0;
    low = middle - pad;
    high = middle + pad;
  }
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// Ticks at 1, 2 or 5 times a power of ten, about five within the range (at most 12).
std::vector<double> linearTicks(const Range& r) {
  const double raw = (r.high - r.low) / 5;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / power < 1.5 ? power : raw / power < 3.5 ? 2 * power : 5 * power;
  const double first = std::ceil(r.low / step - 1e-9);
  std::vector<double> ticks;
  for (int k = 0; k < 12 && (first + k) * step <= r.high + 1e-9 * step; ++k)
    ticks.push_back(first + k == 0 ? 0.0 : (first + k) * step);
  return ticks;
}

// Decades (every k-th when there are more than eight), in log10 units.
std::vector<double> decadeTicks(Range& r) {
  r.low = std::floor(r.low);
  r.high = std::max(std::ceil(r.high), r.low + 1);
  const int every = static_cast<int>(std::ceil((r.high - r.low) / 8));
  r.low = std::floor(r.low / every) * every;
  r.high = std::ceil(r.high / every) * every;
  std::vector<double> ticks;
  for (double t = r.low; t <= r.high + 0.5; t += every) {
    ticks.push_back(t);
    // Over one or two decades also 2 and 5 times each.
    if (r.high - r.low <= 2 && t + 0.5 < r.high)
      ticks.insert(ticks.end(), {t + std::log10(2.0), t + std::log10(5.0)});
  }
  return ticks;
}

// 1e-3, 2e-3, 5e-3 for log10 values -3, -2.7, -2.3.
std::string logLabel(double t) {
  const double decade = std::floor(t + 1e-9);
  return number(std::round(std::pow(10.0, t - decade))) + "e" + number(decade);
}

}  // namespace

std::string svgPlot(const PlotSpec& spec) {
  const auto yOf = [&](double y) { return spec.logY ? std::log10(y) : y; };
  const auto drawn = [&](double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!spec.logY || y > 0);
  };
  Range xr, yr;
  for (const PlotSeries& s : spec.series)
    for (size_t i = 0; i < s.x.size(); ++i)
      if (drawn(s.x[i], s.y[i])) xr.add(s.x[i]), yr.add(yOf(s.y[i]));
  for (const PlotSpec::Reference& ref : spec.references)
    if (!yr.empty() && drawn(xr.low, ref.y)) yr.add(yOf(ref.y));

  // The right margin holds half of the last x tick's label (labels are centred on their tick).
  const int left = 78, right = 36, top = 28, bottom = 46;
  const int w = spec.width, h = spec.height;
  const double plotW = w - left - right, plotH = h - top - bottom;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"" << escapeXml(spec.id) << "\" width=\""
      << w << "\" height=\"" << h << "\" viewBox=\"0 0 " << w << ' ' << h
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
      << "<text x=\"" << w / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">"
      << escapeXml(spec.title) << "</text>\n";
  if (xr.empty()) {
    svg << "<text x=\"" << w / 2 << "\" y=\"" << h / 2
        << "\" text-anchor=\"middle\">no values to draw</text>\n</svg>\n";
    return svg.str();
  }
  xr.widen();
  yr.widen();
  const std::vector<double> xTicks = linearTicks(xr);
  const std::vector<double> yTicks = spec.logY ? decadeTicks(yr) : linearTicks(yr);
  const auto px = [&](double x) { return left + plotW * (x - xr.low) / (xr.high - xr.low); };
  const auto py = [&](double y) { return top + plotH * (1 - (y - yr.low) / (yr.high - yr.low)); };
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plotW << "\" height=\""
      << plotH << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (const double t : xTicks)
    svg << "<line x1=\"" << px(t) << "\" y1=\"" << top + plotH << "\" x2=\"" << px(t) << "\" y2=\""
        << top + plotH + 4 << "\" stroke=\"#444\"/><text x=\"" << px(t) << "\" y=\""
        << top + plotH + 16 << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
  for (const double t : yTicks)
    svg << "<line x1=\"" << left << "\" y1=\"" << py(t) << "\" x2=\"" << left + plotW << "\" y2=\""
        << py(t) << "\" stroke=\"#e4e4e4\"/><text x=\"" << left - 4 << "\" y=\"" << py(t) + 4
        << "\" text-anchor=\"end\">" << (spec.logY ? logLabel(t) : number(t)) << "</text>\n";
  svg << "<text x=\"" << left + plotW / 2 << "\" y=\"" << h - 8 << "\" text-anchor=\"middle\">"
      << escapeXml(spec.xLabel) << "</text>\n<text transform=\"translate(14," << top + plotH / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escapeXml(spec.yLabel) << "</text>\n";
  for (const PlotSpec::Reference& ref : spec.references) {
    if (!drawn(xr.low, ref.y)) continue;
    const double y = py(yOf(ref.y));
    svg << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plotW << "\" y2=\"" << y
        << "\" stroke=\"#888\" stroke-dasharray=\"6,4\"/><text x=\"" << left + plotW - 4
        << "\" y=\"" << y - 4 << "\" text-anchor=\"end\" fill=\"#666\">" << escapeXml(ref.label)
        << "</text>\n";
  }
  int legendY = top + 14;
  for (const PlotSeries& s : spec.series) {
    svg << "<polyline fill=\"none\" stroke=\"" << escapeXml(s.colour) << "\" stroke-width=\"1.4\""
        << (s.dashed ? " stroke-dasharray=\"4,3\"" : "") << " points=\"";
    for (size_t i = 0; i < s.x.size(); ++i)
      if (drawn(s.x[i], s.y[i])) svg << px(s.x[i]) << ',' << py(yOf(s.y[i])) << ' ';
    svg << "\"/>\n";
    if (s.label.empty()) continue;  // a second line of a series already named
    svg << "<text x=\"" << left + 8 << "\" y=\"" << legendY << "\" fill=\"" << escapeXml(s.colour)
        << "\">" << escapeXml(s.label) << "</text>\n";
    legendY += 14;
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace anode

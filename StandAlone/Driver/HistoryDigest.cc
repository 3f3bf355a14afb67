#include "StandAlone/Driver/HistoryDigest.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace anode {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double smaller(double a, double b) {
  return std::isnan(a) ? b : std::isnan(b) ? a : std::min(a, b);
}
double larger(double a, double b) {
  return std::isnan(a) ? b : std::isnan(b) ? a : std::max(a, b);
}

// Splits a row into numbers; false if it has another count than `fields` or a field that is
// not one.
bool parseRow(const std::string& line, size_t fields, std::vector<double>& values) {
  values.clear();
  const char* at = line.c_str();
  while (true) {
    char* end = nullptr;
    values.push_back(std::strtod(at, &end));
    if (end == at) return false;
    if (*end == '\0') break;
    if (*end != ',') return false;
    at = end + 1;
  }
  return values.size() == fields;
}

}  // namespace

int HistoryDigest::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

HistoryDigest digestHistory(const std::string& path, size_t bins, double ratioThreshold) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ": no header");
  HistoryDigest d;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) d.columns.push_back(name);
  const size_t fields = d.columns.size();
  d.columns.push_back("kinetic_to_elastic");
  const size_t n = d.columns.size();
  const int step = d.column("step"), time = d.column("time"), dt = d.column("dt");
  const int kinetic = d.column("kinetic_energy");
  const int elastic = d.column("elastic_energy"), rule = d.column("dt_limit");
  const int newton = d.column("newton_iterations"), krylov = d.column("krylov_iterations");
  if (step < 0 || time < 0 || dt < 0)
    throw std::runtime_error(path + ": no step, time or dt column");
  d.low.assign(n, {});
  d.high.assign(n, {});
  d.binLast.assign(n, {});
  d.last.assign(n, kNaN);
  d.minimum.assign(n, kNaN);
  d.maximum.assign(n, kNaN);
  // Bins of `stride` rows; at 2 x bins, neighbours merge and the stride doubles.
  size_t stride = 1, inBin = 0;
  std::vector<double> values;
  while (std::getline(in, line)) {
    if (!parseRow(line, fields, values)) continue;
    values.push_back(elastic >= 0 && kinetic >= 0 && values[elastic] > 0
                         ? values[kinetic] / values[elastic]
                         : kNaN);
    if (values[step] > 0) {
      d.smallestStepDt = d.steps++ == 0 ? values[dt] : std::min(d.smallestStepDt, values[dt]);
      const double r = values.back();
      if (!std::isnan(r)) ++d.ratioSteps, d.ratioAbove += r > ratioThreshold;
      if (rule >= 0 && values[rule] >= 0 && values[rule] < kDtRules)
        ++d.stepsByRule[static_cast<size_t>(values[rule])];
      if (newton >= 0) d.newtonIterations += values[newton];
      if (krylov >= 0) d.krylovIterations += values[krylov];
    }
    if (inBin == 0) {
      d.binTime.push_back(values[time]);
      for (size_t c = 0; c < n; ++c) {
        d.low[c].push_back(values[c]);
        d.high[c].push_back(values[c]);
        d.binLast[c].push_back(values[c]);
      }
    }
    d.binTime.back() = values[time];
    for (size_t c = 0; c < n; ++c) {
      d.low[c].back() = smaller(d.low[c].back(), values[c]);
      d.high[c].back() = larger(d.high[c].back(), values[c]);
      d.binLast[c].back() = values[c];
      d.last[c] = values[c];
      d.minimum[c] = smaller(d.minimum[c], values[c]);
      d.maximum[c] = larger(d.maximum[c], values[c]);
    }
    if (++inBin < stride) continue;
    inBin = 0;
    if (d.binTime.size() < 2 * bins) continue;
    const size_t half = d.binTime.size() / 2;
    for (size_t b = 0; b < half; ++b) {
      d.binTime[b] = d.binTime[2 * b + 1];
      for (size_t c = 0; c < n; ++c) {
        d.low[c][b] = smaller(d.low[c][2 * b], d.low[c][2 * b + 1]);
        d.high[c][b] = larger(d.high[c][2 * b], d.high[c][2 * b + 1]);
        d.binLast[c][b] = d.binLast[c][2 * b + 1];
      }
    }
    d.binTime.resize(half);
    for (size_t c = 0; c < n; ++c)
      d.low[c].resize(half), d.high[c].resize(half), d.binLast[c].resize(half);
    stride *= 2;
  }
  return d;
}

}  // namespace anode

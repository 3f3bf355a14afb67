#include "StandAlone/Driver/StepForecast.h"

#include <cmath>
#include <cstdio>

namespace anode {

namespace {

std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, pattern, a, b, c);
  return buf;
}

}  // namespace

std::vector<std::string> forecastSteps(const StepForecastInput& in) {
  std::vector<std::string> lines;
  if (!(in.dt > 0) || !(in.maxTime > in.startTime)) return lines;
  double steps = std::ceil((in.maxTime - in.startTime) / in.dt);
  const bool stepLimited = in.maxTimesteps > 0 && in.maxTimesteps < steps;
  std::string line = format("first dt %.4g", in.dt) + " (" + in.limit + "): ";
  if (stepLimited)
    line += format("the step limit %.0f ends the run first (at that dt, t = %.4g)",
                   double(in.maxTimesteps), in.startTime + in.maxTimesteps * in.dt);
  else
    line += format("about %.3g steps to maxTime %.4g at that dt", steps, in.maxTime);
  if (in.errorControlled)
    line += " (dt then follows the error estimates)";
  else if (in.implicit)
    line += " (dt then follows Newton's iterations)";
  lines.push_back(line);
  if (stepLimited || in.implicit || steps < kStepsOutOfReach || !in.mechanicsLimited) return lines;
  std::string note = format(
      "note: %.3g steps is beyond reach (about a day at 1e6 steps an hour): mechanics (Eq. 43) "
      "sets dt, through the sound speed sqrt(K / rho)",
      steps);
  // Lengths of about a um to a mm per cell suggest um, and then pg/um^3 for density; steel to
  // water in kg/m^3 (1e2 to 3e4) would then be a unit slip (2330 kg/m^3 = 2.33 pg/um^3).
  const bool lengthsInMicrometres = in.cellSize >= 1e-4 && in.cellSize <= 1e3;
  for (const auto& [name, rho] : in.densities)
    if (lengthsInMicrometres && rho >= 1e2 && rho <= 3e4)
      note += format("; a guess: the density %.6g", rho) + " of " + name +
              format(" looks like kg/m^3 in an input in um, us, pg, where it is %.4g pg/um^3",
                     rho * 1e-3);
  note +=
      "; the paper's inputs raise the density (1e15 to 1e21-fold), or <time_integrator>implicit "
      "solves the mechanics quasi-statically at the real density (docs/quasi-static.md)";
  lines.push_back(note);
  return lines;
}

}  // namespace anode

// history.csv read once as a stream (a run of millions of steps writes a gigabyte) into what a
// one-page report shows: every column thinned to at most about `bins` points for plots, whole-run
// extremes, the steps each dt rule set, and the quasi-static check, kinetic over elastic energy.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "StandAlone/Driver/DataArchiver.h"

namespace anode {

struct HistoryDigest {
  // history.csv's columns, then the derived "kinetic_to_elastic" (kinetic_energy /
  // elastic_energy where the elastic energy is above 0, else NaN).
  std::vector<std::string> columns;
  long steps = 0;  // rows after the start's (step 0)
  // The rows in runs of consecutive rows (bins), each bin's time that of its last row and each
  // column's smallest and largest value in it: low[column][bin], high[column][bin].
  std::vector<double> binTime;
  std::vector<std::vector<double>> low, high;
  // Each column's value in each bin's last row (binLast[column][bin]): for plotting one column
  // against another (stress against the state of charge).
  std::vector<std::vector<double>> binLast;
  // Per column over every row: the last row's value, the smallest and largest (NaN ignored).
  std::vector<double> last, minimum, maximum;
  double smallestStepDt = 0;                 // of the steps after step 0 (whose dt is 0)
  std::array<long, kDtRules> stepsByRule{};  // the steps whose dt each DtRule set
  long ratioSteps = 0, ratioAbove = 0;       // steps with a ratio; of them, above the threshold
  double newtonIterations = 0, krylovIterations = 0;  // sums over the steps (implicit runs)

  // The column's index, -1 if the file has none of that name.
  int column(const std::string& name) const;
};

// Reads `path`; rows with another number of fields than the header (a last line a kill cut
// short) are skipped. `ratioThreshold` is the quasi-static check's bound (ratioAbove).
HistoryDigest digestHistory(const std::string& path, size_t bins, double ratioThreshold);

}  // namespace anode

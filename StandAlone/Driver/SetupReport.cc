#include "StandAlone/Driver/SetupReport.h"

#include <cstdio>

#include "Components/MPM/MPM.h"

namespace anode {

void printSetupReport(Collective every, const MPM& mpm, const SetupFigures& figures,
                      const std::vector<std::string>& forecast) {
  // Setup's wall time and the memory it left (the peak so far), of the slowest and the largest
  // rank and of the smallest.
  double setup[4] = {figures.seconds, figures.peakBytes, -figures.seconds, -figures.peakBytes};
  if (Communicator::size() > 1) collective::maximum(every, setup, 4);
  if (!Communicator::isRoot()) return;
  if (Communicator::size() > 1)
    std::fprintf(stderr,
                 "sus: setup %.2f s on the slowest rank (%.2f s on the fastest), peak memory "
                 "%.1f MB on the largest rank (%.1f MB on the smallest)\n",
                 setup[0], -setup[2], setup[1] / 1e6, -setup[3] / 1e6);
  else
    std::fprintf(stderr, "sus: setup %.2f s, peak memory %.1f MB\n", setup[0], setup[1] / 1e6);
  std::fprintf(stderr, "sus: %zu particles in %zu material(s), grid %dx%dx%d cells, output in %s\n",
               figures.particles, mpm.materials().size(), mpm.grid().cells.x(),
               mpm.grid().cells.y(), mpm.grid().cells.z(), figures.directory.c_str());
  if (Communicator::size() > 1)
    std::fprintf(stderr,
                 "sus: %d ranks: %s, ghost layers %d cells; particles per rank max/mean %.3f\n",
                 Communicator::size(), mpm.layout().boxes().describe().c_str(),
                 mpm.layout().ghostWidth(), figures.imbalance);
  for (const std::string& line : mpm.problem().diffusionNotes)
    std::fprintf(stderr, "sus: %s\n", line.c_str());
  for (const std::string& line : forecast)
    std::fprintf(stderr, "%s%s\n", line.rfind("note:", 0) == 0 ? "" : "sus: ", line.c_str());
}

}  // namespace anode

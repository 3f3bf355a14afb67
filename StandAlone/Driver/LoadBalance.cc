#include "StandAlone/Driver/LoadBalance.h"

#include <cstdio>

#include "Components/MPM/MPM.h"

namespace anode {

double LoadBalance::start(Collective every, const MPM& mpm) {
  layoutImbalance_ = mpm.layout().imbalance(every);
  return layoutImbalance_;
}

bool LoadBalance::rebalance(Collective every, MPM& mpm, long step) {
  if (Communicator::size() == 1) return false;
  const double before = mpm.layout().imbalance(every);
  const double growth =
      mpm.problem().flags.implicit ? kRebalanceImbalanceImplicit : kRebalanceImbalance;
  if (before <= growth * layoutImbalance_) return false;
  ScopedTimer timer(mpm.timers(), mpm.timers().task("rebalance"));
  mpm.layout().redistributeParticles(every);
  const double after = mpm.layout().imbalance(every);
  if (Communicator::isRoot())
    std::fprintf(stderr,
                 "sus: step %ld: particles per rank max/mean %.3f, %.2f times the %.3f the boxes "
                 "started with: boxes drawn anew (%s), now %.3f\n",
                 step, before, before / layoutImbalance_, layoutImbalance_,
                 mpm.layout().boxes().describe().c_str(), after);
  layoutImbalance_ = after;
  return true;
}

}  // namespace anode

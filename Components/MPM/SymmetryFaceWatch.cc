#include "Components/MPM/SymmetryFaceWatch.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Core/Parallel/Communicator.h"

namespace anode {

std::vector<std::string> SymmetryFaceWatch::start(Collective every, const MPM& mpm) {
  const Grid& g = mpm.grid();
  watched_.clear();
  for (size_t m = 0; m < mpm.materials().size(); ++m) {
    const MPMMaterial& mat = mpm.materials()[m];
    const ParticleSet& p = mat.particles;
    Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
    for (const Vec3& x : p.x) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    collective::minimum(every, lo.data(), 3);
    collective::maximum(every, hi.data(), 3);
    bool startsOn[3][2] = {};
    for (const BCFace& bc : mpm.problem().gridBCs.symmetric)
      if (bc.appliesTo(static_cast<int>(m)))
        startsOn[bc.axis][bc.side] =
            distanceToFace(g, bc.side == 0 ? lo : hi, bc.axis, bc.side) < g.dx[bc.axis];
    for (const BCFace& bc : mpm.problem().gridBCs.symmetric)
      if (bc.appliesTo(static_cast<int>(m)) && !startsOn[bc.axis][bc.side])
        watched_.push_back({m, bc.axis, bc.side});
  }
  return mpm.problem().swellingNotes;
}

std::vector<std::string> SymmetryFaceWatch::afterStep(Collective every, const MPM& mpm, long step,
                                                      double t) {
  std::vector<std::string> warnings;
  if (watched_.empty()) return warnings;
  const Grid& g = mpm.grid();
  // Each watched material's extent, in one parallel pass (the particles are searched only when
  // it has come within a cell of a watched face).
  std::vector<Vec3> lo(mpm.materials().size()), hi(mpm.materials().size());
  std::vector<bool> measured(mpm.materials().size(), false);
  for (const Face& f : watched_) {
    if (measured[f.material]) continue;
    measured[f.material] = true;
    const ParticleSet& p = mpm.materials()[f.material].particles;
    const long n = static_cast<long>(p.count());
    double x0 = INFINITY, y0 = INFINITY, z0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY,
           z1 = -INFINITY;
#pragma omp parallel for schedule(static) reduction(min : x0, y0, z0) reduction(max : x1, y1, z1)
    for (long i = 0; i < n; ++i) {
      x0 = std::min(x0, p.x[i].x()), y0 = std::min(y0, p.x[i].y()), z0 = std::min(z0, p.x[i].z());
      x1 = std::max(x1, p.x[i].x()), y1 = std::max(y1, p.x[i].y()), z1 = std::max(z1, p.x[i].z());
    }
    lo[f.material] = Vec3(x0, y0, z0);
    hi[f.material] = Vec3(x1, y1, z1);
    collective::minimum(every, lo[f.material].data(), 3);
    collective::maximum(every, hi[f.material].data(), 3);
  }
  for (size_t w = 0; w < watched_.size();) {
    const Face f = watched_[w];
    const Vec3& extent = f.side == 0 ? lo[f.material] : hi[f.material];
    if (distanceToFace(g, extent, f.axis, f.side) >= g.dx[f.axis]) {
      ++w;
      continue;
    }
    const MPMMaterial& mat = mpm.materials()[f.material];
    const ParticleSet& p = mat.particles;
    size_t reached = 0;
    while (reached < p.count() && distanceToFace(g, p.x[reached], f.axis, f.side) >= g.dx[f.axis])
      ++reached;
    watched_.erase(watched_.begin() + static_cast<long>(w));  // once per face and material
    // The lowest rank holding such a particle reports it.
    if (collective::firstRankWith(every, reached < p.count()) != Communicator::rank()) continue;
    std::ostringstream s;
    s << "warning: step " << step << ", t = " << t << ": "
      << describeParticle(mat, f.material, reached)
      << " has come within a cell of the Symmetric face " << faceName(f.axis, f.side)
      << ", which the body did not start on: the face holds its normal velocity at zero, so a body "
         "growing into it is squashed (enlarge the grid if the face is not a symmetry plane of the "
         "body)";
    warnings.push_back(s.str());
  }
  return warnings;
}

}  // namespace anode

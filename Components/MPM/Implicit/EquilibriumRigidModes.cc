// The rigid modes of a quasi-static body its faces do not hold (EquilibriumSolver.h,
// removeRigidMotionOfFreeBodies): removed from each Newton correction, by mass.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>

#include "Components/MPM/Implicit/EquilibriumSolver.h"

namespace anode {

void EquilibriumSolver::removeRigidMotionOfFreeBodies(Collective every,
                                                      const EquilibriumProblem& problem,
                                                      std::vector<double>& du) const {
  if (!problem.velocity.empty()) return;  // implicit dynamics: the inertia sets them
  // The six rigid modes at a node: translations, then rotations about the grid's centre (in
  // units of its half diagonal, so all six are of one size).
  const Vec3 centre = problem.grid.lower + 0.5 * (problem.grid.upper - problem.grid.lower);
  const double length = 0.5 * (problem.grid.upper - problem.grid.lower).norm();
  using Modes = Eigen::Matrix<double, 3, 6>;
  const auto modesAt = [&](int k) {
    const Vec3i ijk = problem.grid.nodeOf(k);
    const Vec3 x = (problem.grid.nodePosition(ijk.x(), ijk.y(), ijk.z()) - centre) / length;
    Modes phi;
    for (int a = 0; a < 3; ++a) {
      phi.col(a) = Vec3::Unit(a);
      phi.col(3 + a) = Vec3::Unit(a).cross(x);
    }
    return phi;
  };
  std::vector<char> isFixed(du.size(), 0);
  for (int i : fixed_) isFixed[i] = 1;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  for (size_t f = 0; f < row_.size(); ++f) {
    // Over the owned rows of the field: the modes' products on the fixed components, their
    // mass-weighted products, and du's mass-weighted part along each.
    double values[78] = {};
    struct {
      Eigen::Map<Mat6> fixed, mass;
      Eigen::Map<Vec6> du;
    } sums{Eigen::Map<Mat6>(values), Eigen::Map<Mat6>(values + 36), Eigen::Map<Vec6>(values + 72)};
    for (int r = 0; r < rows_.owned; ++r) {
      if (unknown_[r].first != static_cast<int>(f)) continue;
      const int k = unknown_[r].second;
      const Modes phi = modesAt(k);
      const double m = problem.mass[f][k];
      sums.mass += m * phi.transpose() * phi;
      sums.du += m * phi.transpose() * Vec3(du[3 * r], du[3 * r + 1], du[3 * r + 2]);
      for (int a = 0; a < 3; ++a)
        if (isFixed[3 * r + a]) sums.fixed += phi.row(a).transpose() * phi.row(a);
    }
    collective::sum(every, values, 78);
    if (!(sums.mass.trace() > 0)) continue;
    // The rigid modes the fixed components do not hold (those vanishing on every one of them).
    Eigen::SelfAdjointEigenSolver<Mat6> held(sums.fixed);
    const double scale = std::max(1.0, held.eigenvalues().maxCoeff());
    std::vector<int> free;
    for (int a = 0; a < 6; ++a)
      if (held.eigenvalues()[a] <= 1e-12 * scale) free.push_back(a);
    if (free.empty()) continue;
    Eigen::MatrixXd Z(6, free.size());
    for (size_t a = 0; a < free.size(); ++a) Z.col(a) = held.eigenvectors().col(free[a]);
    // du's part in them, by mass (least squares where the nodes do not tell the modes apart).
    const Eigen::MatrixXd inZ = Z.transpose() * sums.mass * Z;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> principal(inZ);
    const Eigen::VectorXd along = Z.transpose() * sums.du;
    Eigen::VectorXd amounts = Eigen::VectorXd::Zero(free.size());
    for (int a = 0; a < static_cast<int>(free.size()); ++a) {
      const double moment = principal.eigenvalues()[a];
      if (moment > 1e-12 * principal.eigenvalues().maxCoeff())
        amounts +=
            principal.eigenvectors().col(a) * (principal.eigenvectors().col(a).dot(along) / moment);
    }
    const Vec6 rigid = Z * amounts;
    for (size_t r = 0; r < unknown_.size(); ++r) {
      if (unknown_[r].first != static_cast<int>(f)) continue;
      const Vec3 motion = modesAt(unknown_[r].second) * rigid;
      for (int a = 0; a < 3; ++a) du[3 * r + a] -= motion[a];
    }
  }
}

}  // namespace anode

// Second-order Runge-Kutta-Legendre steps (RKL2: Meyer, Balsara and Aslam, J. Comput. Phys. 257
// (2014) 594-626) for the diffusion of a quasi-static step (docs/quasi-static.md): an explicit
// method of s stages whose stability interval grows as s^2, so that one step of length tau is
// stable where tau <= (s^2 + s - 2) / 4 forward-Euler limits, for the cost of s rate evaluations
// instead of that many forward-Euler steps. Y_0 = y, Y_1 = Y_0 + mu~_1 tau F(Y_0), and for
// j = 2..s
//   Y_j = mu_j Y_(j-1) + nu_j Y_(j-2) + (1 - mu_j - nu_j) Y_0 + mu~_j tau F(Y_(j-1))
//         + gamma~_j tau F(Y_0),
// with b_j = (j^2 + j - 2) / (2 j (j + 1)) (b_0 = b_1 = b_2), w_1 = 4 / (s^2 + s - 2),
// mu~_1 = b_1 w_1, mu_j = (2j - 1)/j b_j/b_(j-1), nu_j = -(j - 1)/j b_j/b_(j-2),
// mu~_j = mu_j w_1, gamma~_j = -(1 - b_(j-1)) mu~_j. Y_s is the step's end.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace anode {

// The fewest stages (at least 2) for a step of `ratio` forward-Euler limits. A ratio within 1e-12
// above a count's reach takes that count, so that a step of limit x (s^2 + s - 2)/4 takes s
// stages whatever the rounding of the product and the quotient (DiffusionPass's cap).
inline int rkl2Stages(double ratio) {
  const double r = std::max(ratio * (1 - 1e-12), 0.0);
  const int s = static_cast<int>(std::ceil((-1 + std::sqrt(9 + 16 * r)) / 2));
  return std::max(s, 2);
}

// One RKL2 step of y over a time tau in s stages: rate(Y, F) sets F = dy/dt at Y (F comes zeroed,
// the size of y).
template <class Rate>
void stepRkl2(std::vector<double>& y, double tau, int s, Rate&& rate) {
  const size_t n = y.size();
  std::vector<double> b(s + 1, 0.0);
  for (int j = 2; j <= s; ++j) b[j] = (j * j + j - 2.0) / (2.0 * j * (j + 1));
  b[0] = b[1] = b[2];
  const double w1 = 4.0 / (s * s + s - 2.0);
  const std::vector<double> y0 = y;
  std::vector<double> f0(n, 0.0), f(n);
  rate(y0, f0);
  std::vector<double> before = y0, last = y0;  // Y_(j-2), Y_(j-1)
  for (size_t i = 0; i < n; ++i) last[i] += b[1] * w1 * tau * f0[i];
  for (int j = 2; j <= s; ++j) {
    const double mu = (2.0 * j - 1) / j * b[j] / b[j - 1];
    const double nu = -(j - 1.0) / j * b[j] / b[j - 2];
    const double muTau = mu * w1 * tau, gammaTau = -(1 - b[j - 1]) * mu * w1 * tau;
    std::fill(f.begin(), f.end(), 0.0);
    rate(last, f);
    for (size_t i = 0; i < n; ++i) {
      const double next =
          mu * last[i] + nu * before[i] + (1 - mu - nu) * y0[i] + muTau * f[i] + gammaTau * f0[i];
      before[i] = last[i];
      last[i] = next;
    }
  }
  y = std::move(last);
}

}  // namespace anode

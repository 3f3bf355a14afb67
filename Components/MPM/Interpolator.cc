#include "Components/MPM/Interpolator.h"

#include <algorithm>
#include <cmath>

#include "Components/MPM/CpdiCorners.h"

namespace anode {

int maxNodesPerParticle(InterpolatorKind kind) {
  switch (kind) {
    case InterpolatorKind::Linear:
      return 8;
    case InterpolatorKind::GIMP:
      return 27;
    case InterpolatorKind::CPDI:
      return 64;
  }
  return 0;
}

std::string interpolatorName(InterpolatorKind kind) {
  switch (kind) {
    case InterpolatorKind::Linear:
      return "linear";
    case InterpolatorKind::GIMP:
      return "gimp";
    case InterpolatorKind::CPDI:
      return "cpdi";
  }
  return "";
}

namespace {

// Tensor product of per-axis 1-D weights `n[d][a]` and slopes `dn[d][a]` (index space) over
// `len[d]` nodes starting at `first[d]`.
int tensorProduct(const Grid& g, const int first[3], const int len[3], const double n[3][3],
                  const double dn[3][3], int32_t* nodes, double* w, Vec3* grad) {
  int count = 0;
  for (int c = 0; c < len[2]; ++c)
    for (int b = 0; b < len[1]; ++b)
      for (int a = 0; a < len[0]; ++a) {
        const double wt = n[0][a] * n[1][b] * n[2][c];
        if (wt <= 0) continue;
        const int i = first[0] + a, j = first[1] + b, k = first[2] + c;
        if (!g.hasNode(i, j, k)) return -1;
        nodes[count] = g.nodeIndex(i, j, k);
        w[count] = wt;
        grad[count] =
            Vec3(dn[0][a] * n[1][b] * n[2][c] / g.dx.x(), n[0][a] * dn[1][b] * n[2][c] / g.dx.y(),
                 n[0][a] * n[1][b] * dn[2][c] / g.dx.z());
        ++count;
      }
  return count;
}

}  // namespace

int linearWeights(const Grid& g, const Vec3& x, int32_t* nodes, double* w, Vec3* grad) {
  const Vec3 xi = g.indexCoordinate(x);
  int first[3], len[3] = {2, 2, 2};
  double n[3][3], dn[3][3];
  for (int d = 0; d < 3; ++d) {
    first[d] = floorIndex(xi[d]);
    const double f = xi[d] - first[d];
    n[d][0] = 1 - f;
    n[d][1] = f;
    dn[d][0] = -1;
    dn[d][1] = 1;
  }
  return tensorProduct(g, first, len, n, dn, nodes, w, grad);
}

int gimpWeights(const Grid& g, const Vec3& x, const Mat3& size, int32_t* nodes, double* w,
                Vec3* grad) {
  const Vec3 xi = g.indexCoordinate(x);
  int first[3], len[3] = {3, 3, 3};
  double n[3][3], dn[3][3];
  for (int d = 0; d < 3; ++d) {
    const double l = 0.5 * size(d, d);  // half-width of the particle in cell units
    first[d] = floorIndex(xi[d] + 0.5) - 1;
    for (int a = 0; a < 3; ++a) {
      const double r = xi[d] - (first[d] + a);
      const double ar = std::abs(r), sign = r < 0 ? -1.0 : 1.0;
      // Uniform GIMP: convolution of the hat function with a box of half-width l.
      if (ar < l) {
        n[d][a] = 1 - (r * r + l * l) / (2 * l);
        dn[d][a] = -r / l;
      } else if (ar <= 1 - l) {
        n[d][a] = 1 - ar;
        dn[d][a] = -sign;
      } else if (ar < 1 + l) {
        n[d][a] = (1 + l - ar) * (1 + l - ar) / (4 * l);
        dn[d][a] = -sign * (1 + l - ar) / (2 * l);
      } else {
        n[d][a] = 0;
        dn[d][a] = 0;
      }
    }
  }
  return tensorProduct(g, first, len, n, dn, nodes, w, grad);
}

void supportBounds(InterpolatorKind kind, const Grid& g, const Vec3& x, const Mat3& size,
                   const Mat3& F, Vec3i& first, Vec3i& last) {
  // Nodes floor(xi - r) to floor(xi + r) + 1 per axis: r = 0 for linear, 1 for GIMP (its three
  // nodes about the nearest one), the domain's half extent for CPDI.
  const Vec3 xi = g.indexCoordinate(x);
  Vec3 r = Vec3::Zero();
  if (kind == InterpolatorKind::GIMP) r = Vec3::Ones();
  if (kind == InterpolatorKind::CPDI) r = 0.5 * (F * size).cwiseAbs().rowwise().sum();
  for (int d = 0; d < 3; ++d) {
    first[d] = floorIndex(xi[d] - r[d]);
    last[d] = floorIndex(xi[d] + r[d]) + 1;
  }
}

int cpdiCapacity(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F) {
  // Per axis only the lowest and the highest of the 8 corners matter: summed in cpdiWeights'
  // order, xi + s1 r1 + s2 r2 + s3 r3 with each s_j taking the sign that lowers (raises) the sum,
  // they are those corners bit for bit (s_j r_j is exact and rounding is monotone).
  const Mat3 A = F * size;
  const Vec3 xi = g.indexCoordinate(x);
  long span = 1;
  for (int d = 0; d < 3; ++d) {
    const double h0 = 0.5 * std::abs(A(d, 0)), h1 = 0.5 * std::abs(A(d, 1)),
                 h2 = 0.5 * std::abs(A(d, 2));
    const double lowest = xi[d] - h0 - h1 - h2, highest = xi[d] + h0 + h1 + h2;
    span *= floorIndex(highest) - floorIndex(lowest) + 2;
  }
  return static_cast<int>(std::min(span, 64L));
}

void cpdiCorners(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, CpdiCorners& out) {
  computeCorners(g, x, F, size, out);
}

void cpdiCornersOfPack(const Grid& g, const Vec3* x, const Mat3* size, const Mat3* F,
                       CpdiCorners* out) {
  constexpr int lanes = static_cast<int>(Pack::size());
  Vec3Of<Pack> xs;
  Mat3Pack Fs, sizes;
  for (int l = 0; l < lanes; ++l) {
    setLane(xs, l, x[l]);
    setLane(Fs, l, F[l]);
    setLane(sizes, l, size[l]);
  }
  CpdiCornersPack pack;
  computeCorners(g, xs, Fs, sizes, pack);
  for (int l = 0; l < lanes; ++l) {
    CpdiCorners& one = out[l];
    for (int c = 0; c < 8; ++c)
      for (int d = 0; d < 3; ++d) {
        one.cell[c][d] = pack.cell[c][d][l];
        one.inCell[c][d] = pack.inCell[c][d][l];
        one.alpha[c][d] = pack.alpha[c][d][l];
      }
    for (int d = 0; d < 3; ++d) {
      one.lowest[d] = pack.lowest[d][l];
      one.highest[d] = pack.highest[d][l];
    }
  }
}

int cpdiWeights(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, int32_t* nodes,
                double* w, Vec3* grad) {
  CpdiCorners corners;
  cpdiCorners(g, x, size, F, corners);
  return cpdiWeights(g, corners, nodes, w, grad);
}

int cpdiWeights(const Grid& g, const CpdiCorners& corners, int32_t* nodes, double* w, Vec3* grad) {
  // Weights average the linear shape functions over the 8 corners; gradients sum each corner's
  // factor alpha times its linear weight.
  const auto& f = corners.cell;
  const auto& fr = corners.inCell;
  const int* lo = corners.lowest;
  const int* hi = corners.highest;
  if (!g.hasNode(lo[0], lo[1], lo[2]) || !g.hasNode(hi[0], hi[1], hi[2])) return -1;
  const int sx = hi[0] - lo[0] + 1, sy = hi[1] - lo[1] + 1, sz = hi[2] - lo[2] + 1;

  if (sx * sy * sz > 64) {
    // A domain stretched over more than 3 cells: one entry per corner and node.
    int count = 0;
    for (int c = 0; c < 8; ++c)
      for (int e = 0; e < 8; ++e) {
        const int a = e & 1, b = (e >> 1) & 1, cc = e >> 2;
        const double nl = (a ? fr[c][0] : 1 - fr[c][0]) * (b ? fr[c][1] : 1 - fr[c][1]) *
                          (cc ? fr[c][2] : 1 - fr[c][2]);
        if (nl <= 0) continue;
        nodes[count] = g.nodeIndex(f[c][0] + a, f[c][1] + b, f[c][2] + cc);
        w[count] = 0.125 * nl;
        grad[count] = nl * Vec3(corners.alpha[c][0], corners.alpha[c][1], corners.alpha[c][2]);
        ++count;
      }
    return count;
  }
  // Corners of one particle share nodes: sum into a dense block so each node appears once. A
  // slot holds the weight and the gradient side by side, so a corner adds to a node in one
  // 4-wide operation ((1, alpha) times the node's linear weight).
  alignas(32) double block[64][4];
  const int slots = sx * sy * sz;
  std::fill_n(&block[0][0], 4 * slots, 0.0);
  for (int c = 0; c < 8; ++c) {
    const int base = ((f[c][2] - lo[2]) * sy + (f[c][1] - lo[1])) * sx + (f[c][0] - lo[0]);
    const double wx[2] = {1 - fr[c][0], fr[c][0]}, wy[2] = {1 - fr[c][1], fr[c][1]},
                 wz[2] = {1 - fr[c][2], fr[c][2]};
    // Built in registers: three scalar stores read back as one vector would wait for the
    // stores (a failed store-to-load forwarding, a quarter of this function's time).
    const double* alpha = corners.alpha[c];
    const Quad factor([alpha](auto lane) {
      if constexpr (lane == 0)
        return 1.0;
      else
        return alpha[lane - 1];
    });
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j) {
        const int row = base + (k * sy + j) * sx;
        for (int i = 0; i < 2; ++i) {
          double* slot = block[row + i];
          Quad sum(slot, stdx::vector_aligned);
          sum += (wx[i] * wy[j] * wz[k]) * factor;
          sum.copy_to(slot, stdx::vector_aligned);
        }
      }
  }
  // Every slot is written and only those with weight kept (no branch): entry `count` is at most
  // the slot's index, below the capacity cpdiCapacity gave (the slots' count).
  const Vec3i n = g.nodes();
  const int first = g.nodeIndex(lo[0], lo[1], lo[2]);
  int count = 0;
  for (int k = 0, slot = 0; k < sz; ++k)
    for (int j = 0; j < sy; ++j)
      for (int i = 0; i < sx; ++i, ++slot) {
        const double* b = block[slot];
        nodes[count] = first + (k * n.y() + j) * n.x() + i;
        w[count] = 0.125 * b[0];
        grad[count] = Vec3(b[1], b[2], b[3]);
        count += b[0] > 0;
      }
  return count;
}

}  // namespace anode

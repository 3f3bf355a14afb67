#include "Components/MPM/Interpolator.h"

#include <cmath>

namespace anode {

int maxNodesPerParticle(InterpolatorKind kind) {
  switch (kind) {
    case InterpolatorKind::Linear: return 8;
    case InterpolatorKind::GIMP: return 27;
    case InterpolatorKind::CPDI: return 64;
  }
  return 0;
}

std::string interpolatorName(InterpolatorKind kind) {
  switch (kind) {
    case InterpolatorKind::Linear: return "linear";
    case InterpolatorKind::GIMP: return "gimp";
    case InterpolatorKind::CPDI: return "cpdi";
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
        grad[count] = Vec3(dn[0][a] * n[1][b] * n[2][c] / g.dx.x(), n[0][a] * dn[1][b] * n[2][c] / g.dx.y(),
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
    first[d] = static_cast<int>(std::floor(xi[d]));
    const double f = xi[d] - first[d];
    n[d][0] = 1 - f;
    n[d][1] = f;
    dn[d][0] = -1;
    dn[d][1] = 1;
  }
  return tensorProduct(g, first, len, n, dn, nodes, w, grad);
}

int gimpWeights(const Grid& g, const Vec3& x, const Mat3& size, int32_t* nodes, double* w, Vec3* grad) {
  const Vec3 xi = g.indexCoordinate(x);
  int first[3], len[3] = {3, 3, 3};
  double n[3][3], dn[3][3];
  for (int d = 0; d < 3; ++d) {
    const double l = 0.5 * size(d, d);  // half-width of the particle in cell units
    first[d] = static_cast<int>(std::lround(xi[d])) - 1;
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

int cpdiWeights(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, int32_t* nodes,
                double* w, Vec3* grad) {
  // Sadeghirad et al. 2011: the particle domain is the parallelepiped spanned by the columns of
  // A = F*size (index space); weights average the linear shape functions over its 8 corners and
  // gradients follow from the divergence theorem over its faces.
  const Mat3 A = F * size;
  const Vec3 r1 = A.col(0), r2 = A.col(1), r3 = A.col(2);
  const double detA = A.determinant();
  const Vec3 c23 = r2.cross(r3), c31 = r3.cross(r1), c12 = r1.cross(r2);
  const Vec3 xi = g.indexCoordinate(x);

  Vec3 corner[8], alpha[8];
  Vec3i lo(1 << 30, 1 << 30, 1 << 30), hi(-(1 << 30), -(1 << 30), -(1 << 30));
  for (int c = 0; c < 8; ++c) {
    const double s1 = (c & 1) ? 1 : -1, s2 = (c & 2) ? 1 : -1, s3 = (c & 4) ? 1 : -1;
    corner[c] = xi + 0.5 * (s1 * r1 + s2 * r2 + s3 * r3);
    alpha[c] = (s1 * c23 + s2 * c31 + s3 * c12) / (4 * detA);
    for (int d = 0; d < 3; ++d) {
      const int f = static_cast<int>(std::floor(corner[c][d]));
      lo[d] = std::min(lo[d], f);
      hi[d] = std::max(hi[d], f + 1);
    }
  }
  const Vec3i span = hi - lo + Vec3i::Ones();
  if (!g.hasNode(lo[0], lo[1], lo[2]) || !g.hasNode(hi[0], hi[1], hi[2])) return -1;

  // Corners of one particle share nodes: sum into a dense block (at most 64 nodes) when it fits,
  // so each node appears once; a domain stretched over more cells keeps one entry per corner-node.
  const bool dense = span.prod() <= 64;
  double bw[64] = {0};
  Vec3 bg[64];
  if (dense)
    for (int b = 0; b < span.prod(); ++b) bg[b].setZero();
  int count = 0;
  for (int c = 0; c < 8; ++c) {
    int f[3];
    double fr[3];
    for (int d = 0; d < 3; ++d) {
      f[d] = static_cast<int>(std::floor(corner[c][d]));
      fr[d] = corner[c][d] - f[d];
    }
    for (int e = 0; e < 8; ++e) {
      const int a = e & 1, b = (e >> 1) & 1, cc = (e >> 2) & 1;
      const double nl = (a ? fr[0] : 1 - fr[0]) * (b ? fr[1] : 1 - fr[1]) * (cc ? fr[2] : 1 - fr[2]);
      if (nl <= 0) continue;
      const int i = f[0] + a, j = f[1] + b, k = f[2] + cc;
      if (dense) {
        const int slot = ((k - lo[2]) * span[1] + (j - lo[1])) * span[0] + (i - lo[0]);
        bw[slot] += 0.125 * nl;
        bg[slot] += nl * alpha[c];
      } else {
        nodes[count] = g.nodeIndex(i, j, k);
        w[count] = 0.125 * nl;
        grad[count] = nl * alpha[c];
        ++count;
      }
    }
  }
  if (dense) {
    for (int k = 0; k < span[2]; ++k)
      for (int j = 0; j < span[1]; ++j)
        for (int i = 0; i < span[0]; ++i) {
          const int slot = (k * span[1] + j) * span[0] + i;
          if (bw[slot] <= 0) continue;
          nodes[count] = g.nodeIndex(lo[0] + i, lo[1] + j, lo[2] + k);
          w[count] = bw[slot];
          grad[count] = bg[slot];
          ++count;
        }
  }
  for (int e = 0; e < count; ++e) grad[e] = grad[e].cwiseQuotient(g.dx);
  return count;
}

}  // namespace anode

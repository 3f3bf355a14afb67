// The corners of CPDI particle domains (Sadeghirad et al. 2011), written once for one particle
// (S = double) or a pack of them (S = Pack, docs/performance.md "SIMD across particles"): the
// domain is the parallelepiped spanned by the columns of A = F size (index space); each corner
// gets its cell and its place in it (for the linear weights averaged over the corners) and the
// factor its weight's gradient takes from the divergence theorem over the domain's faces.
#pragma once

#include <algorithm>

#include "Core/Grid/Grid.h"
#include "Core/Math/Simd.h"

namespace anode {

using IntPack = stdx::rebind_simd_t<int, Pack>;

// floor for index coordinates (> -1024): a conversion instead of a libm call, since the
// portable x86-64 baseline has no SSE4.1 rounding instruction.
inline int floorIndex(double x) {
  return static_cast<int>(x + 1024.0) - 1024;
}
inline IntPack floorIndex(const Pack& x) {
  return stdx::static_simd_cast<IntPack>(x + 1024.0) - 1024;
}
inline double realOf(int i) {
  return i;
}
inline Pack realOf(const IntPack& i) {
  return stdx::static_simd_cast<Pack>(i);
}
inline int minOf(int a, int b) {
  return std::min(a, b);
}
inline IntPack minOf(const IntPack& a, const IntPack& b) {
  return stdx::min(a, b);
}
inline int maxOf(int a, int b) {
  return std::max(a, b);
}
inline IntPack maxOf(const IntPack& a, const IntPack& b) {
  return stdx::max(a, b);
}

template <class S, class I>
struct CornersOf {
  I cell[8][3];    // the cell holding corner c (its lower node), per axis
  S inCell[8][3];  // the corner's place in that cell, in [0, 1)
  S alpha[8][3];   // the corner's gradient factor, physical units
  I lowest[3];     // per axis the lowest node a corner's cell has
  I highest[3];    // and the highest
};
using CpdiCorners = CornersOf<double, int>;
using CpdiCornersPack = CornersOf<Pack, IntPack>;

// The corners of the domain at x (size: reference edge vectors in cell units, as columns; F the
// deformation gradient at the start of the step). Each sum is taken in the same order for every
// S, so a particle's corners do not depend on the pack it is in.
template <class S, class I>
void computeCorners(const Grid& g, const S x[3], const S F[3][3], const S size[3][3],
                    CornersOf<S, I>& out) {
  S A[3][3];  // F size: its columns r1, r2, r3 span the domain
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      A[i][j] = F[i][0] * size[0][j] + F[i][1] * size[1][j] + F[i][2] * size[2][j];
  S c23[3], c31[3], c12[3];  // r2 x r3, r3 x r1, r1 x r2
  for (int d = 0; d < 3; ++d) {
    const int e = (d + 1) % 3, h = (d + 2) % 3;
    c23[d] = A[e][1] * A[h][2] - A[h][1] * A[e][2];
    c31[d] = A[e][2] * A[h][0] - A[h][2] * A[e][0];
    c12[d] = A[e][0] * A[h][1] - A[h][0] * A[e][1];
  }
  const S det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  S toPhysical[3], xi[3];
  for (int d = 0; d < 3; ++d) {
    toPhysical[d] = (1.0 / g.dx[d]) / (4 * det);
    xi[d] = (x[d] - g.lower[d]) / g.dx[d];
  }
  for (int d = 0; d < 3; ++d) {
    out.lowest[d] = I(1 << 30);
    out.highest[d] = I(-(1 << 30));
  }
  for (int c = 0; c < 8; ++c) {
    const double s1 = (c & 1) ? 0.5 : -0.5, s2 = (c & 2) ? 0.5 : -0.5, s3 = (c & 4) ? 0.5 : -0.5;
    for (int d = 0; d < 3; ++d) {
      const S corner = xi[d] + s1 * A[d][0] + s2 * A[d][1] + s3 * A[d][2];
      out.alpha[c][d] = 2 * (s1 * c23[d] + s2 * c31[d] + s3 * c12[d]) * toPhysical[d];
      out.cell[c][d] = floorIndex(corner);
      out.inCell[c][d] = corner - realOf(out.cell[c][d]);
      out.lowest[d] = minOf(out.lowest[d], out.cell[c][d]);
      out.highest[d] = maxOf(out.highest[d], out.cell[c][d] + 1);
    }
  }
}

}  // namespace anode

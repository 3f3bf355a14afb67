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
// deformation gradient at the start of the step). Written once for double and Pack, so a
// particle's corners do not depend on the pack it is in.
template <class S, class I>
void computeCorners(const Grid& g, const Vec3Of<S>& x, const Mat3Of<S>& F, const Mat3Of<S>& size,
                    CornersOf<S, I>& out) {
  const Mat3Of<S> A = F * size;  // its columns r1, r2, r3 span the domain
  const Vec3Of<S> r1 = A.col(0), r2 = A.col(1), r3 = A.col(2);
  const Vec3Of<S> c23 = r2.cross(r3), c31 = r3.cross(r1), c12 = r1.cross(r2);
  const S fourDet = 4 * A.determinant();
  for (int d = 0; d < 3; ++d) {
    out.lowest[d] = I(1 << 30);
    out.highest[d] = I(-(1 << 30));
  }
  for (int d = 0; d < 3; ++d) {
    const S xi = (x[d] - g.lower[d]) / g.dx[d];  // index coordinate
    const S toPhysical = (1.0 / g.dx[d]) / fourDet;
    for (int c = 0; c < 8; ++c) {
      const double s1 = (c & 1) ? 0.5 : -0.5, s2 = (c & 2) ? 0.5 : -0.5, s3 = (c & 4) ? 0.5 : -0.5;
      const S corner = xi + s1 * r1[d] + s2 * r2[d] + s3 * r3[d];
      out.alpha[c][d] = 2 * (s1 * c23[d] + s2 * c31[d] + s3 * c12[d]) * toPhysical;
      out.cell[c][d] = floorIndex(corner);
      out.inCell[c][d] = corner - realOf(out.cell[c][d]);
      out.lowest[d] = minOf(out.lowest[d], out.cell[c][d]);
      out.highest[d] = maxOf(out.highest[d], out.cell[c][d] + 1);
    }
  }
}

}  // namespace anode

// The single-level background grid: interior box [lower, upper] split into `cells`, plus
// `extra` layers of cells on every side. Node (i,j,k) sits at lower + (i,j,k)*dx and i runs from
// -extra.x to cells.x + extra.x (UINTAH_UPS.md §2.10).
#pragma once

#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct Grid {
  // Limits setup enforces: cells per axis, and the bytes one material's nodal fields take per
  // node at least (mass, velocity, internal force, velocity*, acceleration).
  static constexpr int kMaxCellsPerAxis = 1 << 20;
  static constexpr double kMinBytesPerNode = 8 + 4 * 24;

  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Ones();
  Vec3i cells = Vec3i::Ones();
  Vec3i extra = Vec3i::Zero();
  Vec3 dx = Vec3::Ones();

  // Reads <Grid><Level><Box> (one level, one box).
  static Grid fromInput(const PSNode& gridNode);

  // Uintah's dimensionality: 1 with one cell in y and z, 2 with one cell in z, else 3.
  int ndim() const { return cells.z() == 1 ? (cells.y() == 1 ? 1 : 2) : 3; }
  Vec3i nodes() const { return cells + Vec3i::Ones() + 2 * extra; }
  int numNodes() const { return nodes().prod(); }
  // Flat index of node (i,j,k) in grid index space (interior node 0 is the lower corner).
  int nodeIndex(int i, int j, int k) const {
    const Vec3i n = nodes();
    return ((k + extra.z()) * n.y() + (j + extra.y())) * n.x() + (i + extra.x());
  }
  bool hasNode(int i, int j, int k) const {
    return i >= -extra.x() && j >= -extra.y() && k >= -extra.z() && i <= cells.x() + extra.x() &&
           j <= cells.y() + extra.y() && k <= cells.z() + extra.z();
  }
  Vec3 nodePosition(int i, int j, int k) const {
    return lower + Vec3(i * dx.x(), j * dx.y(), k * dx.z());
  }
  // Index-space coordinate (x - lower)/dx.
  Vec3 indexCoordinate(const Vec3& x) const { return (x - lower).cwiseQuotient(dx); }
  // Grid index (i,j,k) of flat node index n.
  Vec3i nodeOf(int n) const {
    const Vec3i s = nodes();
    return Vec3i(n % s.x() - extra.x(), (n / s.x()) % s.y() - extra.y(),
                 n / (s.x() * s.y()) - extra.z());
  }
};

}  // namespace anode

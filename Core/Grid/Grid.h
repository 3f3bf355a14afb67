// The single-level background grid: interior box [lower, upper] split into `cells`, plus
// `extra` layers of cells on every side. Node (i,j,k) sits at lower + (i,j,k)*dx and i runs from
// -extra.x to cells.x + extra.x (UINTAH_UPS.md §2.10). A rank of a distributed run stores only a
// window of the nodes (its box of cells and the ghost layers around it, docs/parallel.md): the
// node arrays and flat indices cover that window, grid indices (i,j,k) stay global.
#pragma once

#include <algorithm>
#include <cmath>

#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

// Cells [lower, upper) in grid index space.
struct CellBox {
  Vec3i lower = Vec3i::Zero(), upper = Vec3i::Zero();
  long cellCount() const { return static_cast<long>((upper - lower).cast<long>().prod()); }
  bool contains(const Vec3i& c) const {
    return (c.array() >= lower.array()).all() && (c.array() < upper.array()).all();
  }
};

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
  // Node layers left out of the stored window below and above on each axis (0: the whole grid).
  Vec3i trimLower = Vec3i::Zero(), trimUpper = Vec3i::Zero();

  // Reads <Grid><Level><Box> (one level, one box).
  static Grid fromInput(const PSNode& gridNode);

  // Uintah's dimensionality: 1 with one cell in y and z, 2 with one cell in z, else 3.
  int ndim() const { return cells.z() == 1 ? (cells.y() == 1 ? 1 : 2) : 3; }
  // The stored nodes: their count per axis, the first and last grid index of each axis.
  Vec3i nodes() const { return cells + Vec3i::Ones() + 2 * extra - trimLower - trimUpper; }
  int numNodes() const { return nodes().prod(); }
  Vec3i firstNode() const { return trimLower - extra; }
  Vec3i lastNode() const { return cells + extra - trimUpper; }
  // Flat index of stored node (i,j,k) (grid index space: interior node 0 is the lower corner).
  int nodeIndex(int i, int j, int k) const {
    const Vec3i n = nodes();
    const Vec3i o = extra - trimLower;
    return ((k + o.z()) * n.y() + (j + o.y())) * n.x() + (i + o.x());
  }
  // Whether node (i,j,k) is stored here (for a distributed run: within this rank's window).
  bool hasNode(int i, int j, int k) const {
    const Vec3i lo = firstNode(), hi = lastNode();
    return i >= lo.x() && j >= lo.y() && k >= lo.z() && i <= hi.x() && j <= hi.y() && k <= hi.z();
  }
  // Whether node (i,j,k) belongs to the grid, stored here or not.
  bool inGrid(int i, int j, int k) const {
    return i >= -extra.x() && j >= -extra.y() && k >= -extra.z() && i <= cells.x() + extra.x() &&
           j <= cells.y() + extra.y() && k <= cells.z() + extra.z();
  }
  // The same grid with every node stored.
  Grid whole() const {
    Grid g = *this;
    g.trimLower = g.trimUpper = Vec3i::Zero();
    return g;
  }
  Vec3 nodePosition(int i, int j, int k) const {
    return lower + Vec3(i * dx.x(), j * dx.y(), k * dx.z());
  }
  // Index-space coordinate (x - lower)/dx.
  Vec3 indexCoordinate(const Vec3& x) const { return (x - lower).cwiseQuotient(dx); }
  // The interior cell holding x; a point outside counts as the nearest interior cell (clamped
  // as a double: no int cast beyond its range), a NaN coordinate as the first.
  Vec3i interiorCell(const Vec3& x) const {
    Vec3i c;
    for (int d = 0; d < 3; ++d) {
      const double index = std::floor(indexCoordinate(x)[d]);
      c[d] = std::isnan(index) ? 0 : static_cast<int>(std::clamp(index, 0.0, cells[d] - 1.0));
    }
    return c;
  }
  // Grid index (i,j,k) of flat node index n.
  Vec3i nodeOf(int n) const {
    const Vec3i s = nodes();
    return Vec3i(n % s.x(), (n / s.x()) % s.y(), n / (s.x() * s.y())) + firstNode();
  }
};

}  // namespace anode

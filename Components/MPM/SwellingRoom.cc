#include "Components/MPM/SwellingRoom.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace anode {

namespace {

// The cell holding x, extra cells included (a point beyond them, which setup never leaves, in
// the outermost), and its flat key.
Vec3i cellOf(const Grid& g, const Vec3& x) {
  Vec3i c;
  for (int a = 0; a < 3; ++a) {
    const double index = std::floor((x[a] - g.lower[a]) / g.dx[a]);
    const double first = -g.extra[a], last = g.cells[a] + g.extra[a] - 1;
    c[a] = static_cast<int>(std::isnan(index) ? first : std::clamp(index, first, last));
  }
  return c;
}

long long keyOf(const Grid& g, const Vec3i& c) {
  const Vec3i e = g.extra + Vec3i::Ones();  // a margin of one cell beyond the extra cells
  const long long nx = g.cells.x() + 2 * e.x(), ny = g.cells.y() + 2 * e.y();
  return ((static_cast<long long>(c.z()) + e.z()) * ny + (c.y() + e.y())) * nx + (c.x() + e.x());
}

// Union-find over the occupied cells.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

bool swells(const MPMMaterial& mat, size_t m, const ReactiveFlow* diffusion) {
  return diffusion && std::exp(mat.model->swellingCoefficient()) > 1 &&
         (diffusion->model(m).diffuses() || diffusion->model(m).constantRate() != 0);
}

// Calls visit(cell) for the cell of each of material m's particles (a cell of a grid-filled
// object once, from its count).
void forEachOccupiedCell(const Grid& g, const MaterialSeeds& seeds,
                         const std::function<void(const Vec3i&)>& visit) {
  for (const MaterialSeeds::Object& object : seeds.objects)
    if (object.smooth)
      for (const SmoothParticle& s : object.smoothLayout) visit(cellOf(g, s.x));
    else
      object.lattice->forEachOccupiedCell([&](const Vec3i& cell, double) { visit(cell); });
}

}  // namespace

std::vector<Body> findBodies(const Grid& g, const std::vector<MaterialSeeds>& seeds, size_t m) {
  std::unordered_map<long long, int> cellIndex;
  std::vector<Vec3i> cells;
  forEachOccupiedCell(g, seeds[m], [&](const Vec3i& c) {
    if (cellIndex.emplace(keyOf(g, c), static_cast<int>(cells.size())).second) cells.push_back(c);
  });
  std::vector<int> parent(cells.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t k = 0; k < cells.size(); ++k)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cellIndex.find(keyOf(g, cells[k] + Vec3i(dx, dy, dz)));
          if (it == cellIndex.end()) continue;
          const int a = root(parent, static_cast<int>(k)), b = root(parent, it->second);
          if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
  std::vector<Body> bodies;
  std::unordered_map<int, size_t> bodyOfRoot;
  seeds[m].forEachPosition(g, [&](const Vec3& x) {
    const int cell = cellIndex.at(keyOf(g, cellOf(g, x)));
    const auto [it, added] = bodyOfRoot.emplace(root(parent, cell), bodies.size());
    if (added) bodies.push_back({0, x, x, {}, {}});
    Body& b = bodies[it->second];
    ++b.particles;
    b.lo = b.lo.cwiseMin(x);
    b.hi = b.hi.cwiseMax(x);
  });
  // Where another material occupies the cell next to one of the body's cells.
  std::unordered_set<long long> others;
  for (size_t o = 0; o < seeds.size(); ++o)
    if (o != m)
      forEachOccupiedCell(g, seeds[o], [&](const Vec3i& c) { others.insert(keyOf(g, c)); });
  for (size_t k = 0; k < cells.size(); ++k) {
    Body& b = bodies[bodyOfRoot.at(root(parent, static_cast<int>(k)))];
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side)
        if (!b.restsOnOther[a][side] &&
            others.count(keyOf(g, cells[k] + (side == 0 ? -1 : 1) * Vec3i::Unit(a))))
          b.restsOnOther[a][side] = true;
  }
  return bodies;
}

std::vector<std::string> swellingRoomNotes(const Grid& g, const GridBoundaryConditions& bcs,
                                           const std::vector<MPMMaterial>& materials,
                                           const std::vector<MaterialSeeds>& seeds,
                                           const ReactiveFlow* diffusion) {
  std::vector<std::string> notes;
  for (size_t m = 0; m < materials.size(); ++m) {
    const MPMMaterial& mat = materials[m];
    if (!swells(mat, m, diffusion)) continue;
    const double eta = mat.model->swellingCoefficient(), growth = std::exp(eta);
    std::vector<Body> bodies = findBodies(g, seeds, m);
    // Which faces each body reaches, grouped by the faces: "x+, z+" -> bodies 1, 3.
    std::map<std::string, std::vector<size_t>> reaching;
    for (size_t n = 0; n < bodies.size(); ++n) {
      Body& b = bodies[n];
      bool startsOn[3][2] = {}, anchored[3][2] = {};
      for (const BCFace& bc : bcs.symmetric)
        if (bc.appliesTo(static_cast<int>(m)) &&
            distanceToFace(g, bc.side == 0 ? b.lo : b.hi, bc.axis, bc.side) < g.dx[bc.axis])
          startsOn[bc.axis][bc.side] = true;
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side)
          anchored[a][side] = startsOn[a][side] || b.restsOnOther[a][side];
      for (const BCFace& bc : bcs.symmetric) {
        const int a = bc.axis;
        if (!bc.appliesTo(static_cast<int>(m)) || startsOn[a][bc.side]) continue;
        // Free growth away from the side it rests on, or about its middle (both or neither).
        const double length = growth * (b.hi[a] - b.lo[a]);
        const bool fromLow = anchored[a][0] && !anchored[a][1];
        const bool fromHigh = anchored[a][1] && !anchored[a][0];
        const double from = fromLow    ? b.lo[a]
                            : fromHigh ? b.hi[a] - length
                                       : 0.5 * (b.lo[a] + b.hi[a] - length);
        Vec3 edge = Vec3::Zero();
        edge[a] = bc.side == 0 ? from : from + length;
        if (distanceToFace(g, edge, a, bc.side) < 0.5 * g.dx[a])
          b.faces.push_back(faceName(a, bc.side));
      }
      std::string faces;
      for (const std::string& f : b.faces) faces += (faces.empty() ? "" : ", ") + f;
      if (!faces.empty()) reaching[faces].push_back(n);
    }
    if (reaching.empty()) continue;
    std::ostringstream s;
    s << "note: " << describeMaterial(mat, m) << " swelling freely to c = 1 grows " << growth
      << "-fold along each axis (exp(eta), eta = " << eta << ")";
    if (bodies.size() == 1) {
      s << " and would reach the Symmetric face(s) " << reaching.begin()->first
        << ", which would squash it";
    } else {
      s << ", each of its " << bodies.size()
        << " bodies (connected particles) away from what it rests on or about its middle:";
      bool first = true;
      for (const auto& [faces, which] : reaching) {
        s << (first ? " " : "; ") << (which.size() == 1 ? "body" : "bodies");
        for (size_t k = 0; k < which.size() && k < 8; ++k) {
          const Body& b = bodies[which[k]];
          const Vec3 centre = 0.5 * (b.lo + b.hi);
          s << (k ? ", " : " ") << which[k] + 1 << " (centre [" << centre.x() << ", " << centre.y()
            << ", " << centre.z() << "])";
        }
        if (which.size() > 8) s << " and " << which.size() - 8 << " more";
        s << " would reach " << faces;
        first = false;
      }
      s << ", which would squash them";
    }
    s << ": the grid leaves less room than that (enlarge it where a face is not a symmetry "
         "plane of the body)";
    notes.push_back(s.str());
  }
  return notes;
}

}  // namespace anode

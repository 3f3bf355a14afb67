#include "Components/MPM/ReactiveFlow/ConcentrationBCs.h"

namespace anode {

ConcentrationBC ConcentrationBC::fromInput(const BCType& bc) {
  if (bc.var != "Dirichlet" && bc.var != "Neumann")
    bc.node.fail("SD-Type var=\"" + bc.var + "\": accepted Dirichlet, Neumann");
  ConcentrationBC c;
  c.face = bc.face;
  c.kind = bc.var == "Dirichlet" ? Kind::Dirichlet : Kind::Neumann;
  c.value = bc.value<double>();
  return c;
}

void ConcentrationBC::rejectWithoutDiffusion(const BCType& bc) {
  bc.node.fail("label=\"SD-Type\" (concentration) needs <MPM><do_scalar_diffusion>true");
}

void applyConcentrationBCs(const Grid& g, const std::vector<ConcentrationBC>& bcs, int matl,
                           std::vector<double>& field) {
  for (const ConcentrationBC& bc : bcs) {
    if (!bc.face.appliesTo(matl)) continue;
    if (bc.kind == ConcentrationBC::Kind::Dirichlet) {
      forFaceNodes(g, bc.face, [&](int n) { field[n] = bc.value; });
    } else {
      // Outermost layer last, so each node copies an already-updated inward neighbour.
      const int axis = bc.face.axis;
      const int inward = bc.face.side == 0 ? 1 : -1;
      Vec3i offset = Vec3i::Zero();
      offset[axis] = inward;
      const int lo = bc.face.side == 0 ? 0 : g.cells[axis];
      const int layers = g.extra[axis] + 1;
      for (int layer = 0; layer < layers; ++layer) {
        const int plane = lo - inward * layer;
        Vec3i from = g.firstNode(), to = g.lastNode();
        // A rank's window holds a face plane and its inward neighbour, or neither.
        if (plane < from[axis] || plane > to[axis] || plane + inward < from[axis] ||
            plane + inward > to[axis])
          continue;
        from[axis] = to[axis] = plane;
        for (int k = from.z(); k <= to.z(); ++k)
          for (int j = from.y(); j <= to.y(); ++j)
            for (int i = from.x(); i <= to.x(); ++i)
              field[g.nodeIndex(i, j, k)] =
                  field[g.nodeIndex(i + offset.x(), j + offset.y(), k + offset.z())] -
                  bc.value * g.dx[axis];
      }
    }
  }
}

std::vector<std::vector<double>> dirichletNodeMasks(const Grid& g,
                                                    const std::vector<ConcentrationBC>& bcs,
                                                    size_t materials) {
  std::vector<ConcentrationBC> dirichlet;
  for (ConcentrationBC b : bcs)
    if (b.kind == ConcentrationBC::Kind::Dirichlet) {
      b.value = 1.0;
      dirichlet.push_back(b);
    }
  if (dirichlet.empty()) return {};
  std::vector<std::vector<double>> masks(materials, std::vector<double>(g.numNodes(), 0.0));
  for (size_t m = 0; m < materials; ++m)
    applyConcentrationBCs(g, dirichlet, static_cast<int>(m), masks[m]);
  return masks;
}

}  // namespace anode

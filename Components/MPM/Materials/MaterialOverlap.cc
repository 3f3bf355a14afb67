#include "Components/MPM/Materials/MaterialOverlap.h"

#include <sstream>

namespace anode {

namespace {

// The particles of `inner` lying inside a geom_object of `outer`: count, volume, and the first
// geom_object of `inner` holding one.
struct Inside {
  size_t count = 0;
  double volume = 0;
  const MaterialSeeds::Object* object = nullptr;
};

Inside particlesInside(const Grid& grid, const MaterialSeeds& innerSeeds,
                       const MaterialSeeds& outer) {
  Inside in;
  for (const MaterialSeeds::Object& object : innerSeeds.objects)
    object.forEachParticle(grid, [&](const Vec3& x, double volume) {
      for (const MaterialSeeds::Object& other : outer.objects)
        if (other.piece->inside(x)) {
          ++in.count;
          in.volume += volume;
          if (!in.object) in.object = &object;
          break;
        }
    });
  return in;
}

}  // namespace

std::vector<MaterialOverlap> findOverlaps(const Grid& grid,
                                          const std::vector<MaterialSeeds>& seeds) {
  std::vector<MaterialOverlap> found;
  for (size_t a = 0; a < seeds.size(); ++a)
    for (size_t b = a + 1; b < seeds.size(); ++b) {
      const Inside aInB = particlesInside(grid, seeds[a], seeds[b]);
      const Inside bInA = particlesInside(grid, seeds[b], seeds[a]);
      if (aInB.count + bInA.count > 0)
        found.push_back({a, b, aInB.count, bInA.count, aInB.volume, bInA.volume,
                         bInA.object ? bInA.object->node : seeds[b].objects.front().node});
    }
  return found;
}

void warnOfOverlaps(const Grid& grid, const std::vector<MPMMaterial>& materials,
                    const std::vector<MaterialSeeds>& seeds) {
  for (const MaterialOverlap& o : findOverlaps(grid, seeds)) {
    const std::string a = describeMaterial(materials[o.first], o.first),
                      b = describeMaterial(materials[o.second], o.second);
    std::ostringstream s;
    s << b << " overlaps " << a << " at the start: " << o.secondInFirst << " of its particles "
      << "(volume " << o.secondVolume << ") lie inside " << a << "'s geom_objects and "
      << o.firstInSecond << " of " << a << "'s (volume " << o.firstVolume
      << ") inside its own; both are filled there, so that space holds both masses";
    o.at.warn(s.str());
  }
}

}  // namespace anode

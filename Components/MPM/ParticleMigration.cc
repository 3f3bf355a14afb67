#include "Components/MPM/ParticleMigration.h"

#include <cstring>

namespace anode {

void packParticles(const ParticleSet& p, const std::vector<long>& which, std::string& out) {
  const uint64_t n = which.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  p.forEachField([&](const auto& v, const auto& field) {
    if (!p.has(field.physics)) return;
    using T = typename std::decay_t<decltype(v)>::value_type;
    const size_t at = out.size();
    out.resize(at + n * sizeof(T));
    char* to = out.data() + at;
    for (long i : which) {
      std::memcpy(to, &v[i], sizeof(T));
      to += sizeof(T);
    }
  });
}

void unpackParticles(const char*& in, ParticleSet& p) {
  uint64_t n = 0;
  std::memcpy(&n, in, sizeof n);
  in += sizeof n;
  p.forEachField([&](auto& v, const auto& field) {
    if (!p.has(field.physics)) return;
    using T = typename std::decay_t<decltype(v)>::value_type;
    if (n == 0) return;
    const size_t at = v.size();
    v.resize(at + n);
    std::memcpy(static_cast<void*>(v.data() + at), in, n * sizeof(T));
    in += n * sizeof(T);
  });
}

void keepParticles(ParticleSet& p, const std::vector<long>& keep) {
  if (keep.size() == p.count()) return;  // ascending: every particle, in place
  p.forEachArray([&](auto& v) {
    if (v.empty()) return;
    size_t to = 0;
    for (long i : keep) v[to++] = v[i];
    v.resize(to);
  });
}

void reorderParticles(ParticleSet& p, const std::vector<long>& order) {
  p.forEachArray([&](auto& v) {
    if (v.empty()) return;
    std::decay_t<decltype(v)> sorted;
    sorted.reserve(v.size());
    for (long i : order) sorted.push_back(v[i]);
    v.swap(sorted);
  });
}

}  // namespace anode

// Particles moving between ranks (docs/parallel.md): every array a material has, through
// ParticleSet's one list of them, so a new array moves without new code here.
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/ParticleSet.h"

namespace anode {

// Appends particles `which` of p (every array p has) to `out`, after their count.
void packParticles(const ParticleSet& p, const std::vector<long>& which, std::string& out);
// Appends to p the particles one packParticles call wrote at `in`; advances `in` past them.
void unpackParticles(const char*& in, ParticleSet& p);
// Keeps the particles `keep` (ascending indices), in their order, and drops the others.
void keepParticles(ParticleSet& p, const std::vector<long>& keep);
// Puts the particles in the order `order` (a permutation of their indices).
void reorderParticles(ParticleSet& p, const std::vector<long>& order);

}  // namespace anode

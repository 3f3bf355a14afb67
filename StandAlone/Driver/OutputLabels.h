// The Uintah labels this code can save, and how each is gathered from the MPM state.
#pragma once

#include <functional>
#include <string>

#include "Components/MPM/MPM.h"
#include "vis/PointData.h"

namespace anode {

enum class LabelStatus { Particle, Grid, NeedsDiffusion, Unsupported, Unknown };

// Whether `label` names a particle or grid quantity this code writes, a diffusion quantity of a
// run without diffusion, a known Uintah quantity of a feature this code lacks, or nothing known.
LabelStatus classifyLabel(const std::string& label, bool diffusion);
// Whether `label` is one of the nodal concentration fields (g.concentration*).
bool isNodalConcentrationLabel(const std::string& label);

// Gathers the saved particle labels (plus the material index) over all materials.
ParticleData gatherParticles(const MPM& mpm, const std::vector<std::string>& labels);
// The number of components of a particle label gatherParticles writes as real numbers (0: none).
int particleLabelComponents(const std::string& label);
// Gathers what a picture needs (DESIGN.md §7): only the particles `keep` accepts (material index,
// position) and only the given labels; no material array.
ParticleData gatherParticlesWhere(
    const MPM& mpm, const std::vector<std::string>& labels,
    const std::function<bool(size_t material, const double* x)>& keep);
// Gathers the saved grid labels, one array per material (suffix _m<index> when several).
GridData gatherGrid(const MPM& mpm, const std::vector<std::string>& labels);

}  // namespace anode

// MPM::saveState / loadState: what a restarted run needs to take the same steps as the run that
// wrote the checkpoint. Grid fields are not saved: every step rebuilds them from the particles.
#include <stdexcept>

#include "Components/MPM/MPM.h"
#include "Components/MPM/ParticleMigration.h"

namespace anode {

void MPM::saveState(BinaryWriter& out) const {
  out.value<uint64_t>(materials_.size());
  for (const MPMMaterial& mat : materials_)
    mat.particles.forEachArray([&](const auto& array) { out.array(array); });
  out.value(nextParticleId_);
  if (diffusion_) diffusion_->saveState(out);
}

void MPM::loadState(BinaryReader& in, ReadParticles particles) {
  const bool append = particles == ReadParticles::Append;
  if (in.value<uint64_t>() != materials_.size())
    throw std::runtime_error("the checkpoint has another number of materials than the input");
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    // An array the input's setup creates must come back with the particle count, and one it
    // does not create must stay empty: otherwise the checkpoint is of another input.
    size_t n = 0;
    bool first = true, fits = true;
    p.forEachField([&](auto& array, const auto& field) {
      std::decay_t<decltype(array)> read;
      in.array(read);
      if (first) n = read.size(), first = false;
      fits = fits && (p.has(field.physics) ? read.size() == n : read.empty());
      if (append)
        array.insert(array.end(), read.begin(), read.end());
      else
        array.swap(read);
    });
    if (!fits)
      throw std::runtime_error("material " + std::to_string(m) +
                               ": the checkpoint's particle arrays do not match the input");
  }
  nextParticleId_ = in.value<int64_t>();
  if (diffusion_) diffusion_->loadState(in, append);
  if (particles == ReadParticles::Drop)
    for (MPMMaterial& mat : materials_) keepParticles(mat.particles, {});
}

}  // namespace anode

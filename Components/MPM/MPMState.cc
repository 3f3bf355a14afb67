// MPM::saveState / loadState: what a restarted run needs to take the same steps as the run that
// wrote the checkpoint. Grid fields are not saved: every step rebuilds them from the particles.
#include <algorithm>
#include <numeric>
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

void MPM::loadState(BinaryReader& in) {
  readState(in, false);
}

void MPM::appendState(BinaryReader& in) {
  readState(in, true);
}

void MPM::readState(BinaryReader& in, bool append) {
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
}

void MPM::saveLayout(BinaryWriter& out) const {
  decomposition_.save(out);
  out.value<int32_t>(ghostWidth_);
}

MPM::Layout MPM::readLayout(BinaryReader& in) {
  Layout layout;
  layout.boxes = Decomposition::load(in);
  layout.ghostWidth = in.value<int32_t>();
  return layout;
}

void MPM::adoptLayout(Collective, const Layout& layout) {
  ghostWidth_ = layout.ghostWidth;
  if (layout.boxes.cells() != whole_.cells || layout.boxes.ranks() != Communicator::size())
    throw std::runtime_error("the checkpoint's boxes are for another grid or rank count");
  decomposition_ = layout.boxes;
  layOutWindow();
}

namespace {

void putInIdOrder(std::vector<MPMMaterial>& materials) {
  for (MPMMaterial& mat : materials) {
    ParticleSet& p = mat.particles;
    std::vector<long> order(p.count());
    std::iota(order.begin(), order.end(), 0L);
    std::sort(order.begin(), order.end(), [&p](long a, long b) { return p.id[a] < p.id[b]; });
    reorderParticles(p, order);
  }
}

}  // namespace

void MPM::keepOwnShare(Collective) {
  putInIdOrder(materials_);
  decompose(true);
}

void MPM::shareOutAnew(Collective) {
  decompose(false);
  putInIdOrder(materials_);
}

void MPM::dropParticles() {
  for (MPMMaterial& mat : materials_) keepParticles(mat.particles, {});
}

}  // namespace anode

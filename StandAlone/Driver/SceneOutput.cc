#include "StandAlone/Driver/SceneOutput.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "Core/Parallel/Communicator.h"
#include "StandAlone/Driver/OutputLabels.h"
#include "vis/SceneRenderer.h"

namespace anode {

SceneOutput::SceneOutput() = default;
SceneOutput::~SceneOutput() = default;
SceneOutput::SceneOutput(SceneOutput&&) noexcept = default;
SceneOutput& SceneOutput::operator=(SceneOutput&&) noexcept = default;

SceneOutput SceneOutput::fromInput(const PSNode& root, const TimeControl& time, const MPM& mpm) {
  SceneOutput out;
  const PSNode visualization = root.child("Visualization");
  if (!visualization) return out;
  SceneContext context;
  context.initTime = time.initTime;
  context.maxTime = time.maxTime;
  context.materials = static_cast<int>(mpm.materials().size());
  const bool diffusion = mpm.flags().doScalarDiffusion;
  context.lookup = [diffusion](const std::string& label) -> SceneContext::LabelInfo {
    switch (classifyLabel(label, diffusion)) {
      case LabelStatus::Particle:
        if (const int n = particleLabelComponents(label)) return {n, ""};
        return {0, label + " is not a real-valued particle quantity"};
      case LabelStatus::NeedsDiffusion:
        return {0, label + " is a diffusion quantity, but <do_scalar_diffusion> is off"};
      default:
        return {0, label + " is not a particle quantity this code computes"};
    }
  };
  out.scenes_ = readScenes(visualization, context);
  for (const Scene& s : out.scenes_)
    out.times_.push_back(s.renderTimes(time.initTime, time.maxTime));
  out.next_.assign(out.scenes_.size(), 0);
  return out;
}

bool SceneOutput::draws(const std::string& label) const {
  return std::any_of(scenes_.begin(), scenes_.end(),
                     [&label](const Scene& s) { return s.field.label == label; });
}

namespace {

// A distributed run draws on rank 0 what every rank holds of a scene (its position and the few
// arrays it needs; docs/parallel.md), in rank order; one rank keeps its own.
ParticleData gatherToRoot(ParticleData data) {
  if (Communicator::size() == 1) return data;
  std::string bytes;
  auto append = [&bytes](const std::vector<double>& v) {
    const uint64_t n = v.size();
    bytes.append(reinterpret_cast<const char*>(&n), sizeof n);
    bytes.append(reinterpret_cast<const char*>(v.data()), n * sizeof(double));
  };
  append(data.points);
  for (const NamedArray& a : data.arrays) append(a.real);
  // To rank 0 only: the other ranks receive nothing (an all-gather would give each of them
  // every drawn particle).
  std::vector<std::string> send(Communicator::size());
  send[0] = std::move(bytes);
  const std::vector<std::string> all = collective::exchangeWithAll(send);
  if (!Communicator::isRoot()) return {};
  ParticleData out = data;
  out.points.clear();
  for (NamedArray& a : out.arrays) a.real.clear();
  for (const std::string& piece : all) {
    const char* in = piece.data();
    auto take = [&in](std::vector<double>& v) {
      uint64_t n = 0;
      std::memcpy(&n, in, sizeof n);
      in += sizeof n;
      const size_t at = v.size();
      v.resize(at + n);
      if (n > 0) std::memcpy(v.data() + at, in, n * sizeof(double));
      in += n * sizeof(double);
    };
    take(out.points);
    for (NamedArray& a : out.arrays) take(a.real);
  }
  return out;
}

// The first state at or after a scene time renders it (as <outputInterval> output steps).
bool crossed(double time, double t) {
  return time <= t + 1e-12 * std::max(std::abs(time), std::abs(t));
}

}  // namespace

void SceneOutput::skipTimesUpTo(double t) {
  for (size_t k = 0; k < scenes_.size(); ++k)
    while (next_[k] < times_[k].size() && crossed(times_[k][next_[k]], t)) ++next_[k];
}

void SceneOutput::renderDue(double t, MPM& mpm, const std::string& outputDir) {
  for (size_t k = 0; k < scenes_.size(); ++k) {
    const Scene& scene = scenes_[k];
    const std::vector<double>& times = times_[k];
    if (next_[k] >= times.size() || !crossed(times[next_[k]], t)) continue;
    ScopedTimer timer(mpm.timers(), mpm.timers().task("render"));
    std::vector<std::string> labels = {scene.field.label};
    if (scene.field.label != "p.volume") labels.push_back("p.volume");
    const ParticleData data =
        gatherToRoot(gatherParticlesWhere(mpm, labels, [&](size_t m, const double* x) {
          return scene.drawsMaterial(static_cast<int>(m)) && scene.keeps(x);
        }));
    if (!Communicator::isRoot()) {
      while (next_[k] < times.size() && crossed(times[next_[k]], t)) ++next_[k];
      continue;
    }
    if (!renderer_) renderer_ = std::make_unique<SceneRenderer>();
    const RenderedScene picture = renderer_->render(scene, makeSprites(scene, data), t);
    std::filesystem::create_directories(std::filesystem::path(outputDir) / "images");
    // One picture for every scene time this step crossed, each under its own name.
    for (; next_[k] < times.size() && crossed(times[next_[k]], t); ++next_[k]) {
      writePNG(picture.canvas,
               (std::filesystem::path(outputDir) / scene.imageFile(times[next_[k]])).string());
      ++imagesWritten_;
    }
  }
}

}  // namespace anode

#include "StandAlone/Driver/SceneOutput.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

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
  const bool diffusion = mpm.problem().flags.doScalarDiffusion;
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

// A distributed run's picture (docs/parallel.md, "Pictures"): every rank draws its own sprites
// into a layer with the camera and colours of all of them (one reduction of their extent), and
// the layers' pixel-wise minimum, the nearest sphere at each pixel, reaches rank 0, which adds
// the title and colour bar. One rank draws its sprites as they are.
std::optional<RenderedScene> drawTogether(Collective every, SceneRenderer& renderer,
                                          const Scene& scene, const SpriteSet& sprites, double t) {
  if (Communicator::size() == 1) return renderer.render(scene, sprites, t);
  SpriteExtent extent = SpriteExtent::of(sprites);
  double lows[8] = {extent.lo.x(),  extent.lo.y(),  extent.lo.z(),  extent.valueLo,
                    -extent.hi.x(), -extent.hi.y(), -extent.hi.z(), -extent.valueHi};
  collective::minimum(every, lows, 8);
  extent.lo = Vec3(lows[0], lows[1], lows[2]);
  extent.hi = -Vec3(lows[4], lows[5], lows[6]);
  extent.valueLo = lows[3];
  extent.valueHi = -lows[7];
  PixelLayer layer = renderer.drawLayer(scene, sprites, extent);
  collective::minimumOnRoot(every, layer.data(), layer.size());
  if (!Communicator::isRoot()) return std::nullopt;
  return SceneRenderer::finish(scene, layer, extent, t);
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

void SceneOutput::renderDue(Collective every, double t, MPM& mpm, const std::string& outputDir) {
  for (size_t k = 0; k < scenes_.size(); ++k) {
    const Scene& scene = scenes_[k];
    const std::vector<double>& times = times_[k];
    if (next_[k] >= times.size() || !crossed(times[next_[k]], t)) continue;
    ScopedTimer timer(mpm.timers(), mpm.timers().task("render"));
    std::vector<std::string> labels = {scene.field.label};
    if (scene.field.label != "p.volume") labels.push_back("p.volume");
    const ParticleData data = gatherParticlesWhere(mpm, labels, [&](size_t m, const double* x) {
      return scene.drawsMaterial(static_cast<int>(m)) && scene.keeps(x);
    });
    if (!renderer_) renderer_ = std::make_unique<SceneRenderer>();
    const std::optional<RenderedScene> picture =
        drawTogether(every, *renderer_, scene, makeSprites(scene, data), t);
    if (!picture) {
      while (next_[k] < times.size() && crossed(times[next_[k]], t)) ++next_[k];
      continue;
    }
    std::filesystem::create_directories(std::filesystem::path(outputDir) / "images");
    // One picture for every scene time this step crossed, each under its own name.
    for (; next_[k] < times.size() && crossed(times[next_[k]], t); ++next_[k]) {
      writePNG(picture->canvas,
               (std::filesystem::path(outputDir) / scene.imageFile(times[next_[k]])).string());
      ++imagesWritten_;
    }
  }
}

}  // namespace anode

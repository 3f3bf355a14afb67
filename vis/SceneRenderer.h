// Offscreen pictures of particles (RENDERING.md): an OSMesa context (no X server, no DISPLAY, no
// libGL) draws the sprites of a scene as depth-tested shaded spheres; the title and the colour
// bar are drawn on the CPU with VTK's text rasteriser; VTK writes the PNG. Render from one
// thread only.
#pragma once

#include <array>
#include <memory>
#include <utility>

#include "Core/Math/Types.h"
#include "vis/Canvas.h"
#include "vis/SceneSpec.h"
#include "vis/Sprites.h"

namespace anode {

// A rendered scene and where things landed in it.
struct RenderedScene {
  explicit RenderedScene(Canvas c) : canvas(std::move(c)) {}
  Canvas canvas;
  Eigen::Matrix4d worldToClip = Eigen::Matrix4d::Identity();
  std::array<int, 4> viewport{};          // x, y, width, height of the particle area
  std::array<int, 4> colourBar{};         // x0, y0, x1, y1 (exclusive) of the bar's colours
  std::pair<double, double> range{0, 1};  // of the colour bar

  // Pixel (x from the left, y from the bottom) where a world point is drawn.
  std::array<double, 2> project(const Vec3& x) const;
};

class SceneRenderer {
 public:
  // Creates no OpenGL context yet: the first render does.
  SceneRenderer();
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Draws the sprites with the scene's camera, colour map and range, and the title with `time`.
  RenderedScene render(const Scene& scene, const SpriteSet& sprites, double time);

  // OSMesa contexts created by this process so far (a run without scenes creates none).
  static int contextsCreated();

 private:
  struct GLState;
  std::unique_ptr<GLState> gl_;
};

// Colour-bar ticks: round numbers within [lo, hi], about `target` of them.
std::vector<double> niceTicks(double lo, double hi, int target = 5);

}  // namespace anode

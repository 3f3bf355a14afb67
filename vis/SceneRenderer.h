// Offscreen pictures of particles (RENDERING.md): an OSMesa context (no X server, no DISPLAY, no
// libGL) draws the sprites of a scene as depth-tested shaded spheres; the title and the colour
// bar are drawn on the CPU with VTK's text rasteriser; VTK writes the PNG. Render from one
// thread only.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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
  double pixelsPerUnit = 0;  // a length across the view at the focal point's depth, per unit

  // Pixel (x from the left, y from the bottom) where a world point is drawn.
  std::array<double, 2> project(const Vec3& x) const;
};

// What a rendered scene holds besides the particles: the title with the time and the colour bar
// (a run's pictures), or nothing (the panels of a figure, which draws them once for all).
enum class Overlay { TitleAndColourBar, None };

// What the camera and the colours of a scene depend on besides the scene: the box around the
// drawn spheres and the range of their finite values. The extent of several sets of sprites
// (each rank's in a distributed run) is the smallest of their lows and the largest of their
// highs.
struct SpriteExtent {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  double valueLo = std::numeric_limits<double>::infinity();
  double valueHi = -std::numeric_limits<double>::infinity();
  static SpriteExtent of(const SpriteSet& sprites);
};

// The particles of a picture, pixel by pixel (rows from the bottom): depth << 24 | r << 16 |
// g << 8 | b, the background at the farthest depth. Sprites drawn in layers by several processes
// with the same scene and extent make, pixel by pixel, the minimum of their layers: the nearest
// sphere at each pixel, as one process drawing them all (sort-last compositing).
using PixelLayer = std::vector<uint64_t>;

class SceneRenderer {
 public:
  // Creates no OpenGL context yet: the first render does.
  SceneRenderer();
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Draws the sprites with the scene's camera, colour map and range, and the title with `time`
  // (drawLayer, then finish).
  RenderedScene render(const Scene& scene, const SpriteSet& sprites, double time,
                       Overlay overlay = Overlay::TitleAndColourBar);
  // The layer of these sprites, drawn with the camera and colours of `extent` (all the sprites
  // of the picture).
  PixelLayer drawLayer(const Scene& scene, const SpriteSet& sprites, const SpriteExtent& extent,
                       Overlay overlay = Overlay::TitleAndColourBar);
  // The sprites that colour at least one pixel of the picture drawLayer makes of them (by index,
  // ascending). Drawing only those gives the same picture, pixel for pixel: each pixel shows the
  // first-drawn nearest sphere, and none of the others is that anywhere.
  std::vector<size_t> visibleSprites(const Scene& scene, const SpriteSet& sprites,
                                     const SpriteExtent& extent,
                                     Overlay overlay = Overlay::TitleAndColourBar);
  // The picture of a layer (of all the sprites): its colours, and the title and colour bar.
  static RenderedScene finish(const Scene& scene, const PixelLayer& layer,
                              const SpriteExtent& extent, double time,
                              Overlay overlay = Overlay::TitleAndColourBar);

  // OSMesa contexts created by this process so far (a run without scenes creates none).
  static int contextsCreated();

 private:
  struct GLState;
  std::unique_ptr<GLState> gl_;
  // Draws the sprites into the context's buffers: their colours, or (`identify`) their indices.
  void drawSprites(const Scene& scene, const SpriteSet& sprites, const SpriteExtent& extent,
                   Overlay overlay, bool identify);
};

// Colour-bar ticks: round numbers within [lo, hi], about `target` of them.
std::vector<double> niceTicks(double lo, double hi, int target = 5);

// The values the scene's colours span for sprites of this extent: its <range>, else the drawn
// values'.
std::pair<double, double> colourRange(const Scene& scene, const SpriteExtent& extent);
inline std::pair<double, double> colourRange(const Scene& scene, const SpriteSet& sprites) {
  return colourRange(scene, SpriteExtent::of(sprites));
}

// Black on a light background, white on a dark one.
RGB inkOn(const Vec3& background);

// A number as the overlay writes it (4 significant digits).
std::string formatNumber(double v);

// The size of the labels of a figure's panels of this height.
inline int panelLabelSize(int height) {
  return std::max(12, height / 22);
}

// A scale bar in the particle area `area` (x, y, width, height): a round length (1, 2 or 5 times
// a power of ten of a metre) of about a fifth of the area's width at `pixelsPerUnit` pixels per
// length unit `unit` (m, mm, um or nm), drawn at the area's bottom right with its length above it.
void drawScaleBar(Canvas& canvas, const std::array<int, 4>& area, double pixelsPerUnit,
                  const std::string& unit, int labelSize, const RGB& ink);

// A vertical colour bar filling `bar` (x0, y0, x1, y1, exclusive), framed, with ticks and values
// to its right and the units and field name above it.
void drawColourBar(Canvas& canvas, const std::array<int, 4>& bar, std::pair<double, double> range,
                   ColourMapKind map, const std::string& name, const std::string& units,
                   const RGB& ink, int labelSize);

}  // namespace anode

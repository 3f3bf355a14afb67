// Offscreen scenes (DESIGN.md §7, RENDERING.md), checked on their pixels: how much of the picture
// the particles cover, the colour at particles of known value against the colour map, the colour
// bar, the clip plane, materials; the render tool under an empty environment (no DISPLAY); no
// libGL linked; the run's pictures at the scene times, and none (no OSMesa context) without scenes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "StandAlone/Driver/OutputLabels.h"
#include "StandAlone/Driver/Simulation.h"
#include "TestInputs.h"
#include "vis/ColourMap.h"
#include "vis/SceneRenderer.h"
#include "vis/VTKReaders.h"
#include "vis/VTKWriters.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

// n x n x n particles of spacing h filling [-n h/2, n h/2]^3 with c = the fraction of x across
// the block (particle centres at (i + 1/2) / n), and material 0 for x < 0, 1 for x > 0.
ParticleData block(int n, double h) {
  ParticleData d;
  NamedArray c{"p.concentration", 1, {}, {}}, volume{"p.volume", 1, {}, {}},
      material{"material", 1, {}, {}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        d.points.insert(d.points.end(), {(i + 0.5 - n / 2.0) * h, (j + 0.5 - n / 2.0) * h,
                                         (k + 0.5 - n / 2.0) * h});
        c.real.push_back((i + 0.5) / n);
        volume.real.push_back(h * h * h);
        material.integer.push_back(2 * i < n ? 0 : 1);
      }
  d.arrays = {c, volume, material};
  return d;
}

Scene frontScene() {
  Scene s;
  s.name = "test";
  s.times = {0};
  s.range = std::make_pair(0.0, 1.0);
  s.camera.preset = CameraPreset::Front;
  return s;
}

bool isBackground(const Canvas& c, int x, int y, const Vec3& background) {
  const unsigned char* p = c.pixel(x, y);
  for (int k = 0; k < 3; ++k)
    if (std::abs(p[k] - 255 * background[k]) > 1) return false;
  return true;
}

// Fraction of the particle area (the viewport) that is not background.
double coveredFraction(const RenderedScene& r, const Vec3& background) {
  long covered = 0;
  for (int y = r.viewport[1]; y < r.viewport[1] + r.viewport[3]; ++y)
    for (int x = r.viewport[0]; x < r.viewport[0] + r.viewport[2]; ++x)
      covered += !isBackground(r.canvas, x, y, background);
  return static_cast<double>(covered) / (static_cast<double>(r.viewport[2]) * r.viewport[3]);
}

double colourDistance(const unsigned char* pixel, const std::array<double, 3>& rgb) {
  double d = 0;
  for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(pixel[k] - 255 * rgb[k]));
  return d;
}

const unsigned char* pixelAt(const RenderedScene& r, const Vec3& x) {
  const auto p = r.project(x);
  return r.canvas.pixel(static_cast<int>(p[0]), static_cast<int>(p[1]));
}

TEST(Render, ParticlesCoverTheirProjectedArea) {
  const int n = 20;
  const double h = 0.01;
  const ParticleData data = block(n, h);
  const Scene scene = frontScene();
  SceneRenderer renderer;
  const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
  // The silhouette of the front row of spheres (they reach r - h/2 beyond the block's faces).
  const double rs = spriteRadius(h * h * h), reach = n * h / 2 - h / 2 + rs,
               front = -(n * h / 2 - h / 2);
  const auto a = r.project(Vec3(-reach, front, -reach)), b = r.project(Vec3(reach, front, reach));
  const double faceArea = std::abs((b[0] - a[0]) * (b[1] - a[1]));
  const double fraction = coveredFraction(r, scene.background);
  const double expected = faceArea / (static_cast<double>(r.viewport[2]) * r.viewport[3]);
  EXPECT_GT(fraction, 0.2);
  EXPECT_LT(fraction, 0.9);
  EXPECT_NEAR(fraction / expected, 1.0, 0.08) << "covered " << fraction << ", face " << expected;
}

// A solid block seen face-on, from above and at an angle: no background shows through inside
// its silhouette (spheres of the particles' own volume left it at every lattice corner).
TEST(Render, SolidBlockShowsNoSpeckles) {
  const int n = 16;
  const double h = 0.01;
  const ParticleData data = block(n, h);
  for (const CameraPreset preset : {CameraPreset::Front, CameraPreset::Top, CameraPreset::Iso}) {
    Scene scene = frontScene();
    scene.camera.preset = preset;
    SceneRenderer renderer;
    const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
    // The projections of the block's inner core (a margin of two particles) are covered.
    const double inner = n * h / 2 - 2 * h;
    double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 x((corner & 1 ? 1 : -1) * inner, (corner & 2 ? 1 : -1) * inner,
                   (corner & 4 ? 1 : -1) * inner);
      const auto p = r.project(x);
      for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    // For the oblique view the core's projection is a hexagon: its inscribed box, about the
    // centre, half the size.
    const double shrink = preset == CameraPreset::Iso ? 0.25 : 0.0;
    long holes = 0, pixels = 0;
    for (int y = static_cast<int>(lo[1] + shrink * (hi[1] - lo[1]));
         y < static_cast<int>(hi[1] - shrink * (hi[1] - lo[1])); ++y)
      for (int x = static_cast<int>(lo[0] + shrink * (hi[0] - lo[0]));
           x < static_cast<int>(hi[0] - shrink * (hi[0] - lo[0])); ++x) {
        holes += isBackground(r.canvas, x, y, scene.background);
        ++pixels;
      }
    EXPECT_GT(pixels, 1000) << static_cast<int>(preset);
    EXPECT_EQ(holes, 0) << "camera " << static_cast<int>(preset) << ": " << holes << " of "
                        << pixels << " pixels show the background";
  }
}

// A camera close to the data, which then fills the whole view: the colour bar's column and the
// title band stay clear of it (only the bar and the text are drawn there).
TEST(Render, DataStaysOutOfTheColourBarAndTitle) {
  const ParticleData data = block(20, 0.01);
  Scene scene = frontScene();
  scene.camera.preset = CameraPreset::Custom;
  scene.camera.position = Vec3(0.02, -0.15, 0.01);
  scene.camera.focalPoint = Vec3(0.02, 0, 0.01);
  SceneRenderer renderer;
  const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
  const int W = scene.width, H = scene.height;
  const int right = r.viewport[0] + r.viewport[2], top = r.viewport[1] + r.viewport[3];
  ASSERT_LT(right, W);
  long spilled = 0;
  for (int y = 0; y < r.colourBar[1] / 2; ++y)  // the bar's column, well below the bar
    for (int x = right; x < W; ++x) spilled += !isBackground(r.canvas, x, y, scene.background);
  for (int y = top; y < H; ++y)  // the title band's right half
    for (int x = W / 2; x < right; ++x) spilled += !isBackground(r.canvas, x, y, scene.background);
  EXPECT_EQ(spilled, 0);
  EXPECT_GT(coveredFraction(r, scene.background), 0.99);  // the data fills the view
}

// A scene that holds its frame: with <camera><position> and <focal_point> the camera stays where
// the input put it, so a body twice as large covers more of the view as perspective says (its
// front face, half-width a, seen from 0.6 - a: (0.2 / 0.5)^2 / (0.1 / 0.55)^2 = 4.84 times),
// where a preset frames each picture afresh and the two look alike.
TEST(Render, PositionedCameraHoldsItsFrameWhereAPresetReframes) {
  const auto covered = [](const Scene& scene, double h) {
    SceneRenderer renderer;
    return coveredFraction(renderer.render(scene, makeSprites(scene, block(10, h)), 0.0),
                           scene.background);
  };
  Scene fixed = frontScene();
  fixed.camera.preset = CameraPreset::Custom;
  fixed.camera.position = Vec3(0, -0.6, 0);
  fixed.camera.focalPoint = Vec3::Zero();
  const double small = covered(fixed, 0.01), large = covered(fixed, 0.02);
  EXPECT_GT(small, 0.02);
  EXPECT_NEAR(large / small, (0.4 * 0.4) / (0.1 / 0.55 * 0.1 / 0.55), 0.25);
  const Scene preset = frontScene();
  EXPECT_NEAR(covered(preset, 0.02) / covered(preset, 0.01), 1.0, 0.05);
}

// The scale bar: the pixels a length takes at the focal point's depth, as the perspective camera
// gives them (the viewport's height spans 2 d tan(view angle / 2) there, d the focal distance),
// and a bar of a round length of about a fifth of the width, labelled above.
TEST(Render, ScaleBarIsARoundLengthAtTheFocalDepth) {
  Scene scene = frontScene();
  scene.camera.preset = CameraPreset::Custom;
  scene.camera.position = Vec3(0, -0.6, 0);
  scene.camera.focalPoint = Vec3::Zero();
  scene.scaleBar = "um";
  const ParticleData data = block(10, 0.01);
  for (const Overlay overlay : {Overlay::TitleAndColourBar, Overlay::None}) {
    SceneRenderer renderer;
    const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0, overlay);
    const double expected = r.viewport[3] / (2 * 0.6 * std::tan(15 * M_PI / 180));
    EXPECT_NEAR(r.pixelsPerUnit / expected, 1.0, 1e-9);
    // A fifth of the width is 0.076 (um) with the overlay and 0.086 without: bars of 0.05 um.
    const int length = static_cast<int>(std::lround(0.05 * r.pixelsPerUnit));
    const int size =
        overlay == Overlay::None ? panelLabelSize(scene.height) : std::max(10, scene.height / 44);
    const int x1 = r.viewport[0] + r.viewport[2] - size, y = r.viewport[1] + size;
    int dark = 0;
    for (int x = r.viewport[0]; x < r.viewport[0] + r.viewport[2]; ++x)
      dark += !isBackground(r.canvas, x, y, scene.background);
    EXPECT_EQ(dark, length);
    EXPECT_FALSE(isBackground(r.canvas, x1 - 1, y, scene.background));
    EXPECT_TRUE(isBackground(r.canvas, x1, y, scene.background));
    // Its label, "50 nm", above it.
    int text = 0;
    for (int yy = y + size / 2; yy < y + 2 * size; ++yy)
      for (int x = x1 - length; x < x1; ++x)
        text += !isBackground(r.canvas, x, yy, scene.background);
    EXPECT_GT(text, 20);
  }
  scene.scaleBar.clear();
  SceneRenderer renderer;
  const RenderedScene none = renderer.render(scene, makeSprites(scene, data), 0.0, Overlay::None);
  const int y = none.viewport[1] + panelLabelSize(scene.height);
  for (int x = none.viewport[0]; x < none.viewport[0] + none.viewport[2]; ++x)
    ASSERT_TRUE(isBackground(none.canvas, x, y, scene.background)) << x;
}

TEST(Render, ColourAtParticlesMatchesTheColourMap) {
  const int n = 10;
  const double h = 0.01;
  const ParticleData data = block(n, h);
  for (ColourMapKind kind : {ColourMapKind::Viridis, ColourMapKind::BlueRed, ColourMapKind::Grey}) {
    Scene scene = frontScene();
    scene.colourMap = kind;
    SceneRenderer renderer;
    const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
    const ColourMap map(kind);
    // The centre of each sphere of the front row (j = 0) in the middle layer shows its value.
    for (int i = 0; i < n; ++i) {
      const double c = (i + 0.5) / n;
      const Vec3 centre((i + 0.5 - n / 2.0) * h, (0.5 - n / 2.0) * h, 0.5 * h);
      EXPECT_LE(colourDistance(pixelAt(r, centre), map.colour(c)), 3.0)
          << "map " << static_cast<int>(kind) << " c = " << c;
    }
  }
}

TEST(Render, FixedAndDataRanges) {
  const ParticleData data = block(10, 0.01);
  Scene scene = frontScene();
  SceneRenderer renderer;
  scene.range.reset();
  // The data's span, as single precision holds it (makeSprites).
  EXPECT_EQ(renderer.render(scene, makeSprites(scene, data), 0.0).range,
            std::make_pair(double{0.05f}, double{0.95f}));
  scene.range = std::make_pair(-1.0, 2.0);
  const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
  EXPECT_EQ(r.range, std::make_pair(-1.0, 2.0));
  // c = 0.05 at a third of the way from -1 to 2 on the map.
  const Vec3 first((0.5 - 5) * 0.01, (0.5 - 5) * 0.01, 0.005);
  EXPECT_LE(colourDistance(pixelAt(r, first), ColourMap(ColourMapKind::Viridis).colour(1.05 / 3)),
            3.0);
}

TEST(Render, ColourBarShowsTheMapTicksAndName) {
  const ParticleData data = block(10, 0.01);
  Scene scene = frontScene();
  scene.units = "mol/m^3";
  SceneRenderer renderer;
  const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 1.5);
  const ColourMap map(ColourMapKind::Viridis);
  const auto [x0, y0, x1, y1] = r.colourBar;
  ASSERT_GT(x1 - x0, 5);
  ASSERT_GT(y1 - y0, 100);
  for (int y = y0; y < y1; y += 7) {
    const double t = (y - y0 + 0.5) / (y1 - y0);
    EXPECT_LE(colourDistance(r.canvas.pixel((x0 + x1) / 2, y), map.colour(t)), 1.0)
        << "bar row " << y;
  }
  // Dark text: the tick values right of the bar and the field name and units above it.
  auto darkPixels = [&](int xa, int ya, int xb, int yb) {
    int dark = 0;
    for (int y = std::max(ya, 0); y < std::min(yb, r.canvas.height()); ++y)
      for (int x = std::max(xa, 0); x < std::min(xb, r.canvas.width()); ++x) {
        const unsigned char* p = r.canvas.pixel(x, y);
        dark += p[0] < 100 && p[1] < 100 && p[2] < 100;
      }
    return dark;
  };
  EXPECT_GT(darkPixels(x1 + 2, y0 - 10, r.canvas.width(), y1 + 10), 200) << "tick labels";
  EXPECT_GT(darkPixels(x0 - 20, y1 + 4, r.canvas.width(), y1 + 80), 200) << "field name and units";
  EXPECT_GT(darkPixels(0, r.canvas.height() - 60, r.canvas.width() / 2, r.canvas.height()), 100)
      << "title";
  // Nothing of the bar area is drawn over by particles.
  EXPECT_GE(x0, r.viewport[0] + r.viewport[2]);
  EXPECT_EQ(niceTicks(0, 1), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(niceTicks(0.05, 0.95), (std::vector<double>{0.25, 0.5, 0.75}));
  EXPECT_EQ(niceTicks(0, 2e6), (std::vector<double>{0, 5e5, 1e6, 1.5e6, 2e6}));
}

TEST(Render, ClipPlaneRemovesOneSide) {
  const int n = 20;
  const double h = 0.01;
  const ParticleData data = block(n, h);
  Scene scene = frontScene();
  // A fixed camera, so that both pictures frame the same region.
  scene.camera.preset = CameraPreset::Custom;
  scene.camera.position = Vec3(0, -0.6, 0);
  scene.camera.focalPoint = Vec3::Zero();
  SceneRenderer renderer;
  const RenderedScene whole = renderer.render(scene, makeSprites(scene, data), 0.0);
  scene.clip = ClipPlane{Vec3::Zero(), Vec3(1, 0, 0)};  // cuts away x > 0
  const SpriteSet kept = makeSprites(scene, data);
  EXPECT_EQ(kept.count(), static_cast<size_t>(n * n * n / 2));
  const RenderedScene clipped = renderer.render(scene, kept, 0.0);
  const double rs = spriteRadius(h * h * h);
  const double edge =
      clipped.project(Vec3(rs, -n * h / 2, 0))[0];  // the last kept spheres reach here
  long left = 0, right = 0, leftWhole = 0;
  for (int y = clipped.viewport[1]; y < clipped.viewport[1] + clipped.viewport[3]; ++y)
    for (int x = clipped.viewport[0]; x < clipped.viewport[0] + clipped.viewport[2]; ++x) {
      const bool covered = !isBackground(clipped.canvas, x, y, scene.background);
      (x > edge + 1 ? right : left) += covered;
      if (x <= edge + 1) leftWhole += !isBackground(whole.canvas, x, y, scene.background);
    }
  EXPECT_EQ(right, 0) << "particles drawn on the cut-away side";
  EXPECT_GT(left, 0.9 * leftWhole);
  EXPECT_TRUE(
      isBackground(clipped.canvas, static_cast<int>(clipped.project(Vec3(n * h / 4, 0, 0))[0]),
                   static_cast<int>(clipped.project(Vec3(n * h / 4, 0, 0))[1]), scene.background));
}

// A solid block seen from the front shows its front faces only: the visible sprites are a small
// part of them, every one of them is drawn where the picture shows it, and drawing them alone
// (with the whole set's extent) gives the same picture, pixel for pixel.
TEST(Render, VisibleSpritesAloneDrawTheSamePicture) {
  const int n = 16;
  const ParticleData data = block(n, 0.01);
  Scene scene = frontScene();
  scene.camera.preset = CameraPreset::Custom;
  scene.camera.position = Vec3(0.3, -0.5, 0.2);
  scene.camera.focalPoint = Vec3::Zero();
  scene.clip = ClipPlane{Vec3::Zero(), Vec3(0, 1, 0)};  // a cut-away: y > 0 removed
  std::vector<size_t> drawn;
  const SpriteSet all = makeSprites(scene, data, &drawn);
  ASSERT_EQ(all.count(), static_cast<size_t>(n * n * n / 2));
  ASSERT_EQ(drawn.size(), all.count());
  for (size_t s = 0; s < all.count(); ++s)  // each sprite knows its particle
    EXPECT_EQ(all.position[3 * s + 1], static_cast<float>(data.points[3 * drawn[s] + 1]));
  const SpriteExtent extent = SpriteExtent::of(all);
  SceneRenderer renderer;
  const PixelLayer whole = renderer.drawLayer(scene, all, extent, Overlay::None);
  const std::vector<size_t> visible = renderer.visibleSprites(scene, all, extent, Overlay::None);
  ASSERT_FALSE(visible.empty());
  EXPECT_TRUE(std::is_sorted(visible.begin(), visible.end()));
  // The faces towards the camera: about 3 n^2 / 2 of the n^3 / 2 sprites, none from the inside.
  EXPECT_LT(visible.size(), all.count() / 3);
  EXPECT_GT(visible.size(), static_cast<size_t>(n * n));
  for (size_t s : visible) {
    const double* x = &all.position[3 * s];
    const double h = 0.01, face = n * h / 2 - h;  // the outermost particles' centres, less one
    EXPECT_TRUE(x[0] > face || x[1] < -face || x[2] > face || x[1] > -h) << "an inner sprite " << s;
  }
  SpriteSet shown;
  for (size_t s : visible) {
    shown.position.insert(shown.position.end(), &all.position[3 * s], &all.position[3 * s + 3]);
    shown.value.push_back(all.value[s]);
    shown.radius.push_back(all.radius[s]);
  }
  EXPECT_EQ(renderer.drawLayer(scene, shown, extent, Overlay::None), whole);
  // Without one visible sprite the picture changes.
  shown.position.erase(shown.position.begin(), shown.position.begin() + 3);
  shown.value.erase(shown.value.begin());
  shown.radius.erase(shown.radius.begin());
  EXPECT_NE(renderer.drawLayer(scene, shown, extent, Overlay::None), whole);
}

// A distributed run's output (.pvtu) reads as its pieces one after the other, as one .vtu.
TEST(Render, ParticlesOfADistributedOutputReadInPieceOrder) {
  const fs::path dir = fs::temp_directory_path() / ("anode_pvtu_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const ParticleData first = block(3, 0.01), second = block(2, 0.02);
  writeParticlesVTU((dir / "step.r0000.vtu").string(), first);
  writeParticlesVTU((dir / "step.r0001.vtu").string(), second);
  writeParticlesPVTU((dir / "step.pvtu").string(), {"step.r0000.vtu", "step.r0001.vtu"}, first);
  const ParticleData read =
      readParticlesVTU((dir / "step.pvtu").string(), {"p.concentration", "material", "p.nothing"});
  ASSERT_EQ(read.count(), first.count() + second.count());
  std::vector<double> points = first.points;
  points.insert(points.end(), second.points.begin(), second.points.end());
  EXPECT_EQ(read.points, points);
  ASSERT_EQ(read.arrays.size(), 2u);  // the arrays asked for that the file holds
  EXPECT_EQ(read.arrays[0].name, "p.concentration");
  EXPECT_EQ(read.arrays[0].real.back(), second.arrays[0].real.back());
  EXPECT_EQ(read.arrays[1].integer.size(), read.count());
  fs::remove_all(dir);
}

TEST(Render, MaterialsNotDrawnAreLeftOut) {
  const ParticleData data = block(10, 0.01);
  Scene scene = frontScene();
  scene.materials = {1};
  const SpriteSet s = makeSprites(scene, data);
  ASSERT_EQ(s.count(), 500u);
  for (size_t i = 0; i < s.count(); ++i) EXPECT_GT(s.position[3 * i], 0);
}

TEST(Render, ScaleMultipliesTheDrawnValues) {
  const ParticleData data = block(10, 0.01);
  Scene scene = frontScene();
  const SpriteSet plain = makeSprites(scene, data);
  setSceneValue(scene, "scale", "-1e-6");
  const SpriteSet scaled = makeSprites(scene, data);
  ASSERT_EQ(scaled.count(), plain.count());
  for (size_t i = 0; i < plain.count(); ++i) EXPECT_EQ(scaled.value[i], -1e-6 * plain.value[i]);
}

TEST(Render, DarkBackgroundAndOtherCameras) {
  const ParticleData data = block(10, 0.01);
  for (const char* camera : {"iso", "front", "back", "side", "top"}) {
    Scene scene = frontScene();
    setSceneValue(scene, "camera", camera);
    setSceneValue(scene, "background", "[0, 0, 0]");
    setSceneValue(scene, "size", "[400, 300]");
    SceneRenderer renderer;
    const RenderedScene r = renderer.render(scene, makeSprites(scene, data), 0.0);
    const double fraction = coveredFraction(r, scene.background);
    EXPECT_GT(fraction, 0.15) << camera;
    EXPECT_LT(fraction, 0.9) << camera;
    // White text on black.
    int white = 0;
    for (int y = r.canvas.height() - 30; y < r.canvas.height(); ++y)
      for (int x = 0; x < 150; ++x) white += r.canvas.pixel(x, y)[0] > 200;
    EXPECT_GT(white, 30) << camera;
  }
}

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& tag)
      : path(fs::temp_directory_path() /
             ("anode_render_" + tag + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

vtkSmartPointer<vtkImageData> readPNG(const fs::path& file) {
  auto reader = vtkSmartPointer<vtkPNGReader>::New();
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

// Fraction of the pixels of a PNG that differ from its corner pixel (the background).
double nonBackgroundFraction(vtkImageData* image) {
  int dims[3];
  image->GetDimensions(dims);
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int channels = image->GetNumberOfScalarComponents();
  long differ = 0;
  for (long i = 0; i < static_cast<long>(dims[0]) * dims[1]; ++i)
    for (int c = 0; c < 3; ++c)
      if (p[channels * i + c] != p[c]) {
        ++differ;
        break;
      }
  return static_cast<double>(differ) / (static_cast<double>(dims[0]) * dims[1]);
}

std::string run(const std::string& command) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  size_t n;
  while (pipe && (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = pipe ? pclose(pipe) : -1;
  if (status != 0) output += "\n[exit status " + std::to_string(status) + "]";
  return output;
}

// Sprites take the particles' data as single precision holds it, so the same particles written as
// Float32 (VTUData::Picture, what a carried figure's panels are) draw the very same sprites as
// the run's Float64: positions, values and radii equal to the bit.
TEST(Render, Float32DataDrawsTheSpritesOfFloat64) {
  ParticleData data = block(6, 0.01);
  for (size_t k = 0; k < data.points.size(); ++k)  // no value a float holds exactly
    data.points[k] += 1e-9 * std::sin(1.0 + static_cast<double>(k));
  for (NamedArray& a : data.arrays)
    for (size_t k = 0; k < a.real.size(); ++k) a.real[k] *= 1 + 1e-9 * std::cos(double(k));
  TempDir dir("float32");
  const std::string full = (dir.path / "double.vtu").string(),
                    half = (dir.path / "single.vtu").string();
  writeParticlesVTU(full, data);
  writeParticlesVTU(half, data, VTUData::Picture);
  std::ifstream head(half);
  const std::string text((std::istreambuf_iterator<char>(head)), std::istreambuf_iterator<char>());
  const std::string xml = text.substr(0, text.find("<AppendedData"));
  EXPECT_EQ(xml.find("type=\"Float64\""), std::string::npos);
  EXPECT_EQ(xml.find("type=\"Int64\""), std::string::npos);
  EXPECT_NE(xml.find("type=\"Float32\" Name=\"Points\""), std::string::npos);
  EXPECT_EQ(xml.find("compressor"), std::string::npos);
  // Uncompressed: per particle 4 (c) + 4 (volume) + 4 (material) + 12 (x) + 4 + 4 (its cell) +
  // 1 (cell type) bytes, and a byte count of 8 for each of the 7 arrays; Full would need 65.
  const size_t section = text.size() - text.find("_", text.find("<AppendedData")) - 1;
  EXPECT_EQ(section,
            33 * data.count() + 7 * 8 + std::string("\n  </AppendedData>\n</VTKFile>\n").size());
  const std::vector<std::string> arrays = {"p.concentration", "p.volume", "material"};
  const SpriteSet a = makeSprites(frontScene(), readParticlesVTU(full, arrays));
  const SpriteSet b = makeSprites(frontScene(), readParticlesVTU(half, arrays));
  ASSERT_EQ(a.count(), data.count());
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(a.radius, b.radius);
  for (size_t k = 0; k < a.position.size(); ++k)  // as a float holds them
    ASSERT_EQ(a.position[k], static_cast<double>(static_cast<float>(data.points[k]))) << k;
}

TEST(Render, Float32RefusesWhatItCannotHold) {
  TempDir dir("float32");
  ParticleData data = block(2, 0.01);
  data.arrays[1].real[3] = 1e60;  // a volume beyond a float
  EXPECT_THROW(writeParticlesVTU((dir.path / "v.vtu").string(), data, VTUData::Picture),
               std::runtime_error);
  data = block(2, 0.01);
  data.arrays[2].integer[0] = int64_t{1} << 40;
  EXPECT_THROW(writeParticlesVTU((dir.path / "m.vtu").string(), data, VTUData::Picture),
               std::runtime_error);
}

TEST(RenderTool, RendersAVTUInAnEmptyEnvironment) {
  TempDir dir("env");
  writeParticlesVTU((dir.path / "block.vtu").string(), block(16, 0.01));
  const std::string output =
      run("env -i " + std::string(ANODE_RENDER_VTU) +
          " --name plain --field p.concentration --time 2 --size '[320, 240]' -o " +
          dir.path.string() + " " + (dir.path / "block.vtu").string());
  EXPECT_EQ(output.find("exit status"), std::string::npos) << output;
  const fs::path png = dir.path / "images" / "plain_2.png";
  ASSERT_TRUE(fs::exists(png)) << output;
  vtkSmartPointer<vtkImageData> image = readPNG(png);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 320);
  EXPECT_EQ(dims[1], 240);
  const double fraction = nonBackgroundFraction(image);
  EXPECT_GT(fraction, 0.1);
  EXPECT_LT(fraction, 0.8);
}

TEST(RenderTool, BadOptionsExitWith2) {
  const std::string output = run(std::string(ANODE_RENDER_VTU) + " --colormap jet some.vtu");
  EXPECT_NE(output.find("--colormap: unknown colour map 'jet'"), std::string::npos) << output;
  EXPECT_NE(output.find("[exit status " + std::to_string(2 << 8) + "]"), std::string::npos)
      << output;
}

// The renderer, the render tool and sus link OSMesa only: no libGL, GLX, OpenGL or GLEW.
TEST(RenderLinking, NoGLLibraries) {
  for (const std::string& binary : {std::string(ANODE_RENDER_VTU), std::string(ANODE_SUS)}) {
    const std::string libraries = run("ldd " + binary);
    EXPECT_NE(libraries.find("libOSMesa"), std::string::npos) << binary << ":\n" << libraries;
    static const std::regex gl(R"(lib(GL|GLX|OpenGL|GLEW|GLdispatch)[.-])");
    EXPECT_FALSE(std::regex_search(libraries, gl)) << binary << ":\n" << libraries;
  }
}

// A small run with a scene: pictures at the scene times, named by them; the render tool
// regenerates the same picture from the run's output.
TEST(RunScenes, ImagesAtTheSceneTimes) {
  TempDir dir("run");
  testing::BlockInput in;
  in.velocity = "[0, 0, -1]";
  in.maxSteps = 1000;
  in.maxTime = 0.02;
  in.outputEvery = 1000;
  in.saves = "<save label=\"p.x\"/><save label=\"p.volume\"/><save label=\"p.velocity\"/>";
  std::string text = in.text();
  text.insert(text.find("<MPM>"), R"(<Visualization>
  <scene name="vz"><times>[0, 0.005, 0.0051]</times><field>p.velocity:z</field><size>[320, 240]</size>
    <range>[-1.5, 0]</range></scene>
  <scene name="cut"><interval>0.01</interval><field>p.volume</field><size>[320, 240]</size>
    <clip><point>[0.5, 0.5, 0.5]</point><normal>[0, -1, 0]</normal></clip></scene>
</Visualization>
)");
  std::ofstream(dir.path / "scene.ups") << text;
  RunOptions options;
  options.input = (dir.path / "scene.ups").string();
  options.outputDir = (dir.path / "out").string();
  options.progress = false;
  Simulation sim(options);
  sim.run();
  const fs::path images = dir.path / "out" / "images";
  for (const char* name :
       {"vz_0.png", "vz_0.005.png", "vz_0.0051.png", "cut_0.png", "cut_0.01.png", "cut_0.02.png"}) {
    ASSERT_TRUE(fs::exists(images / name)) << name;
    EXPECT_GT(nonBackgroundFraction(readPNG(images / name)), 0.05) << name;
  }
  EXPECT_EQ(sim.scenes().imagesWritten(), 6);

  // From the run's first output (step 0), the tool draws the picture the run drew at t = 0.
  const std::string output =
      run(std::string(ANODE_RENDER_VTU) + " --scene vz -o " + (dir.path / "again").string() + " " +
          (dir.path / "out" / "particles.pvd").string());
  EXPECT_EQ(output.find("exit status"), std::string::npos) << output;
  vtkSmartPointer<vtkImageData> a = readPNG(images / "vz_0.png"),
                                b = readPNG(dir.path / "again" / "images" / "vz_0.png");
  ASSERT_TRUE(b->GetScalarPointer()) << output;
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  long same = 0;
  const long values = 320L * 240 * a->GetNumberOfScalarComponents();
  for (long i = 0; i < values; ++i) same += pa[i] == pb[i];
  EXPECT_GT(static_cast<double>(same) / values, 0.999);
}

// The README's main-job command (line 1 of its Quick start block) runs an input that draws at
// least one picture; here its first step.
TEST(RunScenes, ReadmeDefaultInputDrawsAPicture) {
  std::ifstream readme(std::string(ANODE_SOURCE_DIR) + "/README.md");
  std::string line, command;
  bool quickStart = false, block = false;
  while (std::getline(readme, line) && command.empty()) {
    if (line.rfind("## Quick start", 0) == 0) quickStart = true;
    if (quickStart && block) command = line;
    if (quickStart && line.rfind("```sh", 0) == 0) block = true;
  }
  std::smatch m;
  ASSERT_TRUE(std::regex_search(command, m, std::regex(R"(sus .*?(inputs/\S+\.ups)\s*$)")))
      << command;
  TempDir dir("readme");
  const std::string output =
      run("OMP_WAIT_POLICY=passive " + std::string(ANODE_SUS) + " --max-timesteps 1 -o " +
          (dir.path / "out").string() + " " + std::string(ANODE_SOURCE_DIR) + "/" + m[1].str());
  EXPECT_EQ(output.find("exit status"), std::string::npos) << output;
  int pictures = 0;
  if (fs::exists(dir.path / "out" / "images"))
    for (const auto& entry : fs::directory_iterator(dir.path / "out" / "images")) {
      ++pictures;
      EXPECT_GT(nonBackgroundFraction(readPNG(entry.path())), 0.05) << entry.path();
    }
  EXPECT_GE(pictures, 1) << m[1].str() << " drew no picture at its first step";
}

TEST(RunScenes, NoScenesNoRendererNoImages) {
  TempDir dir("plain");
  testing::BlockInput in;
  in.maxSteps = 3;
  std::ofstream(dir.path / "plain.ups") << in.text();
  RunOptions options;
  options.input = (dir.path / "plain.ups").string();
  options.outputDir = (dir.path / "out").string();
  options.progress = false;
  const int contextsBefore = SceneRenderer::contextsCreated();
  Simulation sim(options);
  sim.run();
  EXPECT_EQ(SceneRenderer::contextsCreated(), contextsBefore);
  EXPECT_FALSE(fs::exists(dir.path / "out" / "images"));
  EXPECT_EQ(sim.scenes().imagesWritten(), 0);
}

// The driver's gather copies only the particles and arrays a scene draws.
TEST(RunScenes, GatherKeepsOnlyWhatTheSceneDraws) {
  testing::BlockInput in;
  in.extraMaterials =
      "<material name=\"second\"><density>1000</density><constitutive_model "
      "type=\"rf_elastic_plastic\">"
      "<bulk_modulus>1e6</bulk_modulus><shear_modulus>5e5</shear_modulus><equation_of_state "
      "type=\"default_hypo\"/>"
      "</constitutive_model><geom_object><box label=\"c\"><min>[0.25, 0.25, 0.8]</min><max>[0.75, "
      "0.75, 0.9]</max></box>"
      "<res>[2,2,2]</res><velocity>[0,0,0]</velocity><temperature>298</temperature></geom_object></"
      "material>";
  Simulation sim(in.text(), "two.ups", RunOptions());
  const size_t first = sim.mpm().materials()[0].particles.count();
  ASSERT_GT(sim.mpm().materials()[1].particles.count(), 0u);
  Scene scene = frontScene();
  scene.materials = {0};
  scene.clip = ClipPlane{Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 1)};  // cuts away z > 0.5
  const ParticleData d =
      gatherParticlesWhere(sim.mpm(), {"p.stress"}, [&](size_t m, const double* x) {
        return scene.drawsMaterial(static_cast<int>(m)) && scene.keeps(x);
      });
  EXPECT_EQ(d.count(), first / 2);
  ASSERT_EQ(d.arrays.size(), 1u);
  EXPECT_EQ(d.arrays[0].name, "p.stress");
  EXPECT_EQ(d.arrays[0].real.size(), 9 * d.count());
  for (size_t i = 0; i < d.count(); ++i) EXPECT_LE(d.points[3 * i + 2], 0.5);
}

}  // namespace
}  // namespace anode

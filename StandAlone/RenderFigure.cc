// render_figure: draws a <figure> file (docs/rendering.md, "Figures") from finished runs' output:
// each panel the output nearest its time, all with the figure's scene and one colour range (its
// <range>, else the span of every panel's values), laid out with letters and one colour bar.
// Exit codes: 0 done, 1 I/O or rendering error, 2 bad options or figure file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"
#include "vis/Figure.h"
#include "vis/SceneRenderer.h"
#include "vis/Sprites.h"
#include "vis/VTKReaders.h"

namespace fs = std::filesystem;
using namespace anode;

namespace {

const char* kUsage =
    "usage: render_figure -o OUT.png FIGURE.xml\n"
    "  FIGURE.xml   a <figure>: <title>, <columns>, <time_scale>, <time_unit>, one <scene>\n"
    "               (the tags of docs/input-reference.md) and <panel>s of <data> (a run's\n"
    "               particles.pvd), <time> and <label>; see docs/rendering.md\n";

// The entry of a .pvd whose time is nearest to t.
std::pair<double, std::string> nearestOutput(
    const std::vector<std::pair<double, std::string>>& files, double t) {
  return *std::min_element(files.begin(), files.end(), [t](const auto& a, const auto& b) {
    return std::abs(a.first - t) < std::abs(b.first - t);
  });
}

int draw(const std::string& figureFile, const std::string& png) {
  ProblemSpec spec(figureFile, false, "figure");
  const Figure figure = readFigure(spec.root());
  spec.checkAllUsed();
  const fs::path folder = fs::path(figureFile).parent_path();
  std::map<std::string, std::vector<std::pair<double, std::string>>> series;
  std::vector<SpriteSet> sprites;
  std::vector<double> times;
  const std::vector<std::string> arrays = {figure.scene.field.label, "p.volume", "material"};
  for (const FigurePanel& panel : figure.panels) {
    const std::string data = (folder / panel.data).lexically_normal().string();
    if (!series.count(data)) series[data] = readPVD(data);
    if (series[data].empty()) throw std::runtime_error(data + " lists no files");
    const auto [time, file] = nearestOutput(series[data], panel.time);
    sprites.push_back(makeSprites(figure.scene, readParticlesVTU(file, arrays)));
    times.push_back(time);
    std::printf("%s %s (t = %g for %g)\n", panelLetter(times.size() - 1).c_str(), file.c_str(),
                time, panel.time);
  }
  Scene scene = figure.scene;
  if (!scene.range) {  // the span of every panel's values together
    SpriteSet all;
    for (const SpriteSet& s : sprites)
      all.value.insert(all.value.end(), s.value.begin(), s.value.end());
    scene.range = colourRange(scene, all);
  }
  SceneRenderer renderer;
  std::vector<Canvas> panels;
  for (size_t k = 0; k < sprites.size(); ++k)
    panels.push_back(renderer.render(scene, sprites[k], times[k], Overlay::None).canvas);
  if (!png.empty() && fs::path(png).has_parent_path())
    fs::create_directories(fs::path(png).parent_path());
  writePNG(composeFigure(figure, panels, times, *scene.range), png);
  std::printf("%s\n", png.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string figure, png;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("%s", kUsage);
      return 0;
    } else if (a == "-o" && i + 1 < argc) {
      png = argv[++i];
    } else if (figure.empty() && !a.empty() && a[0] != '-') {
      figure = a;
    } else {
      std::fprintf(stderr, "render_figure: unexpected argument '%s'\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  if (figure.empty() || png.empty()) {
    std::fprintf(stderr, "render_figure: needs -o OUT.png and a figure file\n%s", kUsage);
    return 2;
  }
  try {
    return draw(figure, png);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_figure: error: %s\n", e.what());
    return 1;
  }
}

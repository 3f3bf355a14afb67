// render_figure: draws a <figure> file (docs/rendering.md, "Figures") from finished runs' output:
// each panel the output nearest its time, all with the figure's scene and one colour range (its
// <range>, else the span of every panel's values), laid out with letters and one colour bar.
// With --visible-only DIR it also writes into DIR the particles each panel shows and a figure of
// them that draws the same picture (docs/rendering.md, "Figures").
// Exit codes: 0 done, 1 I/O or rendering error, 2 bad options or figure file.
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/ProblemSpec/UpsText.h"
#include "Core/Util/Errors.h"
#include "vis/Figure.h"
#include "vis/SceneRenderer.h"
#include "vis/Sprites.h"
#include "vis/VTKReaders.h"
#include "vis/VTKWriters.h"

namespace fs = std::filesystem;
using namespace anode;

namespace {

const char* kUsage =
    "usage: render_figure -o OUT.png [--visible-only DIR] FIGURE.xml\n"
    "  FIGURE.xml   a <figure>: <title>, <columns>, <time_scale>, <time_unit>, one <scene>\n"
    "               (the tags of docs/input-reference.md) and <panel>s of <data> (a run's\n"
    "               particles.pvd), <time> and <label>; see docs/rendering.md\n"
    "  --visible-only DIR  also writes DIR/figure.xml, which draws the same picture from\n"
    "               DIR/panel_*.vtu: each panel's particles that colour a pixel, nothing else\n";

// The entry of a .pvd whose time is nearest to t.
std::pair<double, std::string> nearestOutput(
    const std::vector<std::pair<double, std::string>>& files, double t) {
  return *std::min_element(files.begin(), files.end(), [t](const auto& a, const auto& b) {
    return std::abs(a.first - t) < std::abs(b.first - t);
  });
}

// One child element of `parent` named `tag` holding `text` (replacing any it had).
void setChildText(tinyxml2::XMLElement* parent, const char* tag, const std::string& text) {
  tinyxml2::XMLElement* e = parent->FirstChildElement(tag);
  if (!e) e = parent->InsertNewChildElement(tag);
  e->SetText(text.c_str());
}

// A field drawn from a vector or tensor ("p.stress:von_mises") is carried as the scalar it draws,
// in an array of this name ("p.stress.von_mises").
std::string reducedLabel(const FieldSpec& field) {
  return field.label + "." + field.text.substr(field.text.find(':') + 1);
}

// What --visible-only writes: per panel the particles it shows (in their order, in single
// precision: makeSprites draws the same from it; a reduced field as its scalar) as
// DIR/panel_X.vtu with a one-entry DIR/panel_X.pvd at the drawn output's time, and
// DIR/figure.xml, the figure file with those panels, each with the box its camera was made from,
// the colour range of all the particles and (a reduced field) the scalar's array, under the
// field's name.
struct VisibleOnly {
  std::string folder;
  std::vector<ParticleData> shown;
  std::vector<SpriteExtent> extents;

  void write(const std::string& figureFile, const std::vector<double>& times,
             std::pair<double, double> range, const Scene& scene) const {
    fs::create_directories(folder);
    tinyxml2::XMLDocument doc;
    if (doc.LoadFile(figureFile.c_str()) != tinyxml2::XML_SUCCESS)
      throw std::runtime_error("cannot read " + figureFile);
    tinyxml2::XMLElement* root = doc.RootElement();
    tinyxml2::XMLElement* figure =
        !root || std::string(root->Name()) == "figure" ? root : root->FirstChildElement("figure");
    if (!figure) throw std::runtime_error(figureFile + " holds no <figure>");
    tinyxml2::XMLElement* sceneSpec = figure->FirstChildElement("scene");
    setChildText(sceneSpec, "range",
                 "[" + upsNumber(range.first) + "," + upsNumber(range.second) + "]");
    if (scene.field.reduce != FieldSpec::Reduce::Scalar) {
      setChildText(sceneSpec, "field", reducedLabel(scene.field));
      setChildText(sceneSpec, "field_name", scene.barName());
    }
    size_t k = 0;
    for (tinyxml2::XMLElement* panel = figure->FirstChildElement("panel"); panel;
         panel = panel->NextSiblingElement("panel"), ++k) {
      const std::string letter = panelLetter(k).substr(1, panelLetter(k).size() - 2);
      const std::string vtu = "panel_" + letter + ".vtu", pvd = "panel_" + letter + ".pvd";
      writeParticlesVTU((fs::path(folder) / vtu).string(), shown[k], VTUData::Picture);
      PVDSeries series;
      series.add(times[k], vtu);
      series.write((fs::path(folder) / pvd).string());
      setChildText(panel, "data", pvd);
      setChildText(panel, "time", upsNumber(times[k]));
      setChildText(panel, "box_min",
                   upsVector(extents[k].lo[0], extents[k].lo[1], extents[k].lo[2]));
      setChildText(panel, "box_max",
                   upsVector(extents[k].hi[0], extents[k].hi[1], extents[k].hi[2]));
    }
    const std::string out = (fs::path(folder) / "figure.xml").string();
    if (doc.SaveFile(out.c_str()) != tinyxml2::XML_SUCCESS)
      throw std::runtime_error("cannot write " + out);
    std::printf("%s\n", out.c_str());
  }
};

// The particles of `data` with these indices (ascending), every array with them; `field`'s array,
// when the field reduces it (a component, a magnitude, von Mises), as the scalar a picture draws.
ParticleData subset(const ParticleData& data, const std::vector<size_t>& keep,
                    const FieldSpec& field) {
  ParticleData out;
  for (size_t i : keep) {
    const auto first = data.points.begin() + 3 * static_cast<std::ptrdiff_t>(i);
    out.points.insert(out.points.end(), first, first + 3);
  }
  for (const NamedArray& a : data.arrays) {
    if (a.name == field.label && field.reduce != FieldSpec::Reduce::Scalar) {
      NamedArray b{reducedLabel(field), 1, {}, {}};
      for (size_t i : keep) b.real.push_back(pictureValue(field, &a.real[i * a.components]));
      out.arrays.push_back(std::move(b));
      continue;
    }
    NamedArray b{a.name, a.components, {}, {}};
    for (size_t i : keep) {
      const size_t first = i * a.components;
      if (a.isInteger())
        b.integer.insert(b.integer.end(), a.integer.begin() + first,
                         a.integer.begin() + first + a.components);
      else
        b.real.insert(b.real.end(), a.real.begin() + first, a.real.begin() + first + a.components);
    }
    out.arrays.push_back(std::move(b));
  }
  return out;
}

int draw(const std::string& figureFile, const std::string& png, const std::string& visibleOnly) {
  ProblemSpec spec(figureFile, false, "figure");
  const Figure figure = readFigure(spec.root());
  spec.checkAllUsed();
  const fs::path folder = fs::path(figureFile).parent_path();
  std::map<std::string, std::vector<std::pair<double, std::string>>> series;
  std::vector<ParticleData> data;
  std::vector<SpriteSet> sprites;
  std::vector<std::vector<size_t>> drawn;  // --visible-only: each sprite's particle
  std::vector<SpriteExtent> extents;
  std::vector<double> times;
  const std::vector<std::string> arrays = {figure.scene.field.label, "p.volume", "material"};
  for (const FigurePanel& panel : figure.panels) {
    const std::string pvd = (folder / panel.data).lexically_normal().string();
    if (!series.count(pvd)) series[pvd] = readPVD(pvd);
    if (series[pvd].empty()) throw std::runtime_error(pvd + " lists no files");
    const auto [time, file] = nearestOutput(series[pvd], panel.time);
    data.push_back(readParticlesVTU(file, arrays));
    drawn.emplace_back();
    sprites.push_back(
        makeSprites(figure.scene, data.back(), visibleOnly.empty() ? nullptr : &drawn.back()));
    extents.push_back(SpriteExtent::of(sprites.back()));
    if (panel.box) std::tie(extents.back().lo, extents.back().hi) = *panel.box;
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
  VisibleOnly visible{visibleOnly, {}, extents};
  for (size_t k = 0; k < sprites.size(); ++k) {
    const PixelLayer layer = renderer.drawLayer(scene, sprites[k], extents[k], Overlay::None);
    panels.push_back(
        SceneRenderer::finish(scene, layer, extents[k], times[k], Overlay::None).canvas);
    if (visibleOnly.empty()) continue;
    // Without volumes a sprite's radius comes from all the particles' box: a subset's differs.
    if (std::none_of(data[k].arrays.begin(), data[k].arrays.end(),
                     [](const NamedArray& a) { return a.name == "p.volume"; }))
      throw std::runtime_error("--visible-only needs p.volume in every panel's data");
    std::vector<size_t> shown;
    for (size_t s : renderer.visibleSprites(scene, sprites[k], extents[k], Overlay::None))
      shown.push_back(drawn[k][s]);
    visible.shown.push_back(subset(data[k], shown, scene.field));
  }
  if (!png.empty() && fs::path(png).has_parent_path())
    fs::create_directories(fs::path(png).parent_path());
  writePNG(composeFigure(figure, panels, times, *scene.range), png);
  std::printf("%s\n", png.c_str());
  if (!visibleOnly.empty()) visible.write(figureFile, times, *scene.range, scene);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string figure, png, visibleOnly;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("%s", kUsage);
      return 0;
    } else if (a == "-o" && i + 1 < argc) {
      png = argv[++i];
    } else if (a == "--visible-only" && i + 1 < argc) {
      visibleOnly = argv[++i];
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
    return draw(figure, png, visibleOnly);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_figure: error: %s\n", e.what());
    return 1;
  }
}

#include "vis/Figure.h"

#include <algorithm>
#include <stdexcept>

#include "vis/SceneRenderer.h"

namespace anode {

Figure readFigure(const PSNode& node) {
  if (node.name() != "figure")
    node.fail("expected a <figure> element, found <" + node.name() + ">");
  Figure f;
  f.title = node.get<std::string>("title", "");
  f.columns = node.get<int>("columns", 1);
  if (f.columns < 1) node.requireChild("columns").fail("<columns> must be at least 1");
  f.timeScale = node.get<double>("time_scale", 1.0);
  if (!(f.timeScale > 0)) node.requireChild("time_scale").fail("<time_scale> must be positive");
  f.timeUnit = node.get<std::string>("time_unit", "");
  f.scene.name = "figure";
  f.scene.times = {0};
  const PSNode scene = node.requireChild("scene");
  for (const char* tag : {"times", "interval"})
    if (const PSNode t = scene.child(tag))
      t.fail(std::string("<") + tag +
             "> has no place in a figure's scene: each <panel> has its <time>");
  readSceneTags(scene, f.scene);
  try {
    checkScene(f.scene, SceneContext());
  } catch (const std::invalid_argument& e) {
    node.requireChild("scene").fail(std::string("<scene>: ") + e.what());
  }
  for (const PSNode& p : node.children("panel")) {
    FigurePanel panel;
    panel.data = p.require<std::string>("data");
    panel.time = p.require<double>("time");
    panel.label = p.get<std::string>("label", "");
    const PSNode lo = p.child("box_min"), hi = p.child("box_max");
    if (static_cast<bool>(lo) != static_cast<bool>(hi))
      p.fail("a <panel> gives both <box_min> and <box_max> or neither");
    if (lo) {
      panel.box = std::make_pair(p.require<Vec3>("box_min"), p.require<Vec3>("box_max"));
      for (int d = 0; d < 3; ++d)
        if (!(panel.box->first[d] <= panel.box->second[d]))
          lo.fail("<box_min> must not exceed <box_max> in any coordinate");
    }
    f.panels.push_back(panel);
  }
  if (f.panels.empty()) node.fail("a <figure> needs at least one <panel>");
  return f;
}

std::string panelLetter(size_t index) {
  std::string letters;
  for (size_t k = index + 1; k > 0; k = (k - 1) / 26)
    letters.insert(letters.begin(), static_cast<char>('a' + (k - 1) % 26));
  return "(" + letters + ")";
}

Canvas composeFigure(const Figure& figure, const std::vector<Canvas>& panels,
                     const std::vector<double>& times, std::pair<double, double> range) {
  const Scene& scene = figure.scene;
  const int W = scene.width, H = scene.height;
  const int columns = std::min<int>(figure.columns, static_cast<int>(panels.size()));
  const int rows = static_cast<int>((panels.size() + columns - 1) / columns);
  const int labelSize = panelLabelSize(H);
  const int barWidth = std::max(12, W / 20);
  // Room for the colour bar with its values, and for the field's name and units above it.
  const int barArea =
      std::max({std::clamp(W * 35 / 100, 150, 400),
                Canvas::textSize(scene.barName(), labelSize)[0] + barWidth,
                Canvas::textSize("[" + scene.units + "]", labelSize)[0] + barWidth});
  const int width = columns * W + barArea;
  // The title's size: H/16, smaller where that would not fit the figure's width.
  int titleSize = std::max(14, H / 16);
  while (titleSize > 8 && Canvas::textSize(figure.title, titleSize)[0] + titleSize > width)
    --titleSize;
  const int titleBand = figure.title.empty() ? 0 : 2 * titleSize;
  const RGB background = {scene.background[0], scene.background[1], scene.background[2]};
  const RGB ink = inkOn(scene.background);
  Canvas out(width, rows * H + titleBand, background);

  for (size_t k = 0; k < panels.size(); ++k) {
    const Canvas& panel = panels[k];
    if (panel.width() != W || panel.height() != H)
      throw std::invalid_argument("panel " + panelLetter(k) + " is not of the scene's size");
    const int x0 = static_cast<int>(k % columns) * W;
    const int y0 = (rows - 1 - static_cast<int>(k / columns)) * H;  // row 0 of a canvas: bottom
    for (int y = 0; y < H; ++y)
      std::copy(panel.pixel(0, y), panel.pixel(0, y) + 3 * W, out.pixel(x0, y0 + y));
    std::string text = panelLetter(k);
    if (!figure.panels[k].label.empty()) text += " " + figure.panels[k].label;
    text += ", t = " + formatNumber(times[k] * figure.timeScale);
    if (!figure.timeUnit.empty()) text += " " + figure.timeUnit;
    out.text(text, x0 + labelSize / 2, y0 + H - labelSize / 2, labelSize, ink, Canvas::Align::Start,
             Canvas::Align::End);
  }
  if (titleBand > 0)
    out.text(figure.title, titleSize / 2, out.height() - titleSize / 2, titleSize, ink,
             Canvas::Align::Start, Canvas::Align::End);

  const int x0 = columns * W + barWidth / 2;
  const int panelsHeight = rows * H;
  drawColourBar(out, {x0, panelsHeight * 15 / 100, x0 + barWidth, panelsHeight * 75 / 100}, range,
                scene.colourMap, scene.barName(), scene.units, ink, labelSize);
  return out;
}

}  // namespace anode

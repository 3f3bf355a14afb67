// A figure as a paper lays it out: panels of one scene (the same field, colour range and camera)
// at chosen times of chosen runs, in a grid, each with its letter, label and time, and one colour
// bar for all. Read from a <figure> file (docs/rendering.md, "Figures"); drawn by render_figure.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "vis/Canvas.h"
#include "vis/SceneSpec.h"

namespace anode {

struct FigurePanel {
  std::string data;   // a run's particles.pvd (relative paths: from the figure file's folder)
  double time = 0;    // the output nearest to this time is drawn
  std::string label;  // written after the panel's letter
  // The box the camera's origin and depth range are made from: the one around the drawn
  // spheres (SpriteExtent) unless given (<box_min>, <box_max>: a panel of a figure's visible
  // particles only, drawn as the figure of all of them was).
  std::optional<std::pair<Vec3, Vec3>> box;
};

struct Figure {
  std::string title;
  int columns = 1;
  double timeScale = 1;  // a panel's time is written times this, followed by timeUnit
  std::string timeUnit;
  Scene scene;  // every panel's view; its size is one panel's
  std::vector<FigurePanel> panels;
};

// Reads a <figure> element; errors name the file and line of the tag.
Figure readFigure(const PSNode& figure);

// "(a)", "(b)", ... "(z)", "(aa)", ...
std::string panelLetter(size_t index);

// Lays out the panels (each drawn at the scene's size without overlay, in the figure's order,
// `times[k]` the time panel k shows) row by row, writes each one's letter, label and time on it,
// the title above and one colour bar of `range` at the right.
Canvas composeFigure(const Figure& figure, const std::vector<Canvas>& panels,
                     const std::vector<double>& times, std::pair<double, double> range);

}  // namespace anode

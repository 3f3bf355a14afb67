// A scene (DESIGN.md §7): what one picture of the particles shows and how. Read from the
// <Visualization><scene name="..."> block of an input, or set option by option by the render
// tool; every tag is parsed here, in one place.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

// The quantity that colours the particles: a particle array, reduced to one number per particle.
// Written "p.concentration", "p.stress:zz" (a tensor component, row-major as saved),
// "p.stress:von_mises", "p.velocity:z", "p.velocity:magnitude".
struct FieldSpec {
  enum class Reduce { Scalar, Component, Magnitude, VonMises };
  std::string text = "p.concentration";   // as written: the name on the colour bar
  std::string label = "p.concentration";  // the particle array
  Reduce reduce = Reduce::Scalar;
  int component = 0;   // Reduce::Component: index into the tuple
  int components = 1;  // components the array must have: 1, 3 or 9

  // The value of one particle from its tuple of `components` numbers.
  double evaluate(const double* tuple) const;
};

enum class ColourMapKind { Viridis, BlueRed, Grey };
enum class CameraPreset { Iso, Front, Back, Side, Top, Custom };

struct Camera {
  CameraPreset preset = CameraPreset::Iso;
  std::optional<Vec3> position, focalPoint;  // CameraPreset::Custom
  Vec3 up = Vec3(0, 0, 1);
  double viewAngle = 30;  // vertical, degrees
};

// Particles on the side the normal points to are cut away (ParaView's Clip default); with a
// thickness, a section: only the particles within thickness/2 of the plane are kept.
struct ClipPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double thickness = 0;  // 0: a cut-away
};

struct Scene {
  std::string name;
  std::vector<double> times;  // explicit times, ascending
  double interval = 0;        // > 0: every `interval` from the first time of the run
  FieldSpec field;
  double scale = 1;  // the field's values are drawn times this (1e-6: the code's stress in GPa)
  std::optional<std::pair<double, double>> range;  // of the scaled values; empty: from the data
  ColourMapKind colourMap = ColourMapKind::Viridis;
  std::vector<int> materials;  // empty: all
  std::optional<ClipPlane> clip;
  Camera camera;
  int width = 1024, height = 768;
  Vec3 background = Vec3(1, 1, 1);
  std::string title;      // empty: the scene name
  std::string units;      // shown with the field name on the colour bar
  std::string fieldName;  // the field's name on the colour bar; empty: the field as written
  std::string scaleBar;   // the positions' length unit (m, mm, um, nm) for a scale bar; empty: none
  std::string timeUnit;   // shown after the time in the title
  double timeScale = 1;   // the title's time is the simulation time times this (1e-6: us in s)

  bool drawsMaterial(int material) const;
  const std::string& barName() const { return fieldName.empty() ? field.text : fieldName; }
  // False for a point on the cut-away side of the clip plane (of a section: off its slab).
  bool keeps(const double* x) const {
    if (!clip) return true;
    const double along = (x[0] - clip->point[0]) * clip->normal[0] +
                         (x[1] - clip->point[1]) * clip->normal[1] +
                         (x[2] - clip->point[2]) * clip->normal[2];
    if (clip->thickness > 0) return std::abs(along) <= 0.5 * clip->thickness * clip->normal.norm();
    return along <= 0;
  }
  // The times to render within [first, last]: the explicit ones, or every interval from `first`.
  std::vector<double> renderTimes(double first, double last) const;
  // DIR/images/<name>_<time>.png relative to DIR (the simulation time, unscaled).
  std::string imageFile(double time) const;
  // The title over the picture of simulation time `time`: "<title>    t = <scaled time> <unit>".
  std::string titleAt(double time) const;
};

// What the caller knows to check a scene against.
struct SceneContext {
  double initTime = 0;
  double maxTime = std::numeric_limits<double>::infinity();
  int materials = -1;  // -1: unknown
  // For a particle label: its component count, or 0 with the reason it cannot be drawn.
  struct LabelInfo {
    int components = 0;
    std::string unavailable;
  };
  std::function<LabelInfo(const std::string& label)> lookup;  // null: checked later, on the data
};

// Sets one scene tag from its text (tags as in the input; nested ones as "clip/point",
// "camera/position"). Throws std::invalid_argument saying what is accepted.
void setSceneValue(Scene& scene, const std::string& tag, const std::string& value);
// The tags setSceneValue accepts.
const std::vector<std::string>& sceneTags();
// Checks a scene as a whole (names, clip, camera, times, field against the context).
// Throws std::invalid_argument.
void checkScene(const Scene& scene, const SceneContext& context);

// Sets the scene's tags from the children of `node` (each once; errors name the file and line).
void readSceneTags(const PSNode& node, Scene& scene);

// Reads every <scene> of a <Visualization> block; errors name the file and line of the tag.
std::vector<Scene> readScenes(const PSNode& visualization, const SceneContext& context);

FieldSpec parseField(const std::string& text);

// The length units a scale bar knows, largest first: (name, metres).
const std::vector<std::pair<std::string, double>>& lengthUnits();
// Metres in one of lengthUnits(); 0 for any other name.
double metresPerLengthUnit(const std::string& unit);

}  // namespace anode

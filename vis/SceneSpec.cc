#include "vis/SceneSpec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

#include "vis/SceneRenderer.h"

namespace anode {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// "[a, b, ...]" of numbers.
std::vector<double> parseNumberList(const std::string& raw) {
  const std::string s = trim(raw);
  if (s.size() < 2 || s.front() != '[' || s.back() != ']')
    throw std::invalid_argument("expected a list [a, b, ...], found '" + s + "'");
  std::vector<double> out;
  std::stringstream in(s.substr(1, s.size() - 2));
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(parseValue<double>(field));
  if (out.empty()) throw std::invalid_argument("the list is empty");
  return out;
}

double parseNumber(const std::string& raw) {
  return parseValue<double>(raw);
}

const char* const kTensorComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

}  // namespace

FieldSpec parseField(const std::string& raw) {
  FieldSpec f;
  f.text = trim(raw);
  const auto colon = f.text.find(':');
  f.label = trim(f.text.substr(0, colon));
  if (f.label.size() < 3 || f.label.rfind("p.", 0) != 0)
    throw std::invalid_argument("field '" + f.text +
                                "': expected a particle label such as p.concentration");
  if (colon == std::string::npos) return f;
  const std::string part = trim(f.text.substr(colon + 1));
  if (part == "x" || part == "y" || part == "z") {
    f.reduce = FieldSpec::Reduce::Component;
    f.component = part[0] - 'x';
    f.components = 3;
  } else if (part == "magnitude") {
    f.reduce = FieldSpec::Reduce::Magnitude;
    f.components = 3;
  } else if (part == "von_mises") {
    f.reduce = FieldSpec::Reduce::VonMises;
    f.components = 9;
  } else {
    const auto* it = std::find(std::begin(kTensorComponents), std::end(kTensorComponents), part);
    if (it == std::end(kTensorComponents))
      throw std::invalid_argument(
          "field '" + f.text + "': unknown part ':" + part +
          "'; accepted: x, y, z, magnitude (vectors); xx, xy, ..., zz, von_mises (tensors)");
    f.reduce = FieldSpec::Reduce::Component;
    f.component = static_cast<int>(it - std::begin(kTensorComponents));
    f.components = 9;
  }
  return f;
}

double FieldSpec::evaluate(const double* v) const {
  switch (reduce) {
    case Reduce::Scalar:
      return v[0];
    case Reduce::Component:
      return v[component];
    case Reduce::Magnitude:
      return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    case Reduce::VonMises: {
      // sqrt(3/2 s:s) with s the deviator, as p.equivalentStress_t1 (StandAlone/OutputLabels.cc).
      const double p = (v[0] + v[4] + v[8]) / 3;
      double ss = 0;
      for (int k = 0; k < 9; ++k) {
        const double s = v[k] - (k % 4 == 0 ? p : 0.0);
        ss += s * s;
      }
      return std::sqrt(1.5 * ss);
    }
  }
  return 0;
}

const std::vector<std::pair<std::string, double>>& lengthUnits() {
  static const std::vector<std::pair<std::string, double>> units = {
      {"m", 1}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}};
  return units;
}

double metresPerLengthUnit(const std::string& unit) {
  for (const auto& [name, metres] : lengthUnits())
    if (name == unit) return metres;
  return 0;
}

bool Scene::drawsMaterial(int material) const {
  return materials.empty() ||
         std::find(materials.begin(), materials.end(), material) != materials.end();
}

std::vector<double> Scene::renderTimes(double first, double last) const {
  if (interval <= 0) return times;
  std::vector<double> out;
  for (long k = 0;; ++k) {
    const double t = first + static_cast<double>(k) * interval;
    if (t > last + 1e-9 * interval) break;
    out.push_back(t);
  }
  return out;
}

std::string Scene::imageFile(double time) const {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", time);
  return "images/" + name + "_" + buffer + ".png";
}

std::string Scene::titleAt(double time) const {
  std::string text = (title.empty() ? name : title) + "    t = " + formatNumber(time * timeScale);
  if (!timeUnit.empty()) text += " " + timeUnit;
  return text;
}

const std::vector<std::string>& sceneTags() {
  static const std::vector<std::string> tags = {"times",
                                                "interval",
                                                "field",
                                                "scale",
                                                "range",
                                                "colormap",
                                                "materials",
                                                "clip/point",
                                                "clip/normal",
                                                "clip/thickness",
                                                "camera",
                                                "camera/position",
                                                "camera/focal_point",
                                                "camera/up",
                                                "camera/view_angle",
                                                "size",
                                                "background",
                                                "title",
                                                "units",
                                                "field_name",
                                                "scale_bar",
                                                "time_unit",
                                                "time_scale"};
  return tags;
}

void setSceneValue(Scene& s, const std::string& tag, const std::string& raw) {
  const std::string v = trim(raw);
  if (tag == "times") {
    s.times = parseNumberList(v);
    std::sort(s.times.begin(), s.times.end());
  } else if (tag == "interval") {
    s.interval = parseNumber(v);
    if (!(s.interval > 0)) throw std::invalid_argument("the interval must be positive");
  } else if (tag == "field") {
    s.field = parseField(v);
  } else if (tag == "scale") {
    s.scale = parseNumber(v);
    if (!std::isfinite(s.scale) || s.scale == 0)
      throw std::invalid_argument("<scale> multiplies the field's values: a finite number, not 0");
  } else if (tag == "range") {
    if (v == "data") {
      s.range.reset();
      return;
    }
    const std::vector<double> r = parseNumberList(v);
    if (r.size() != 2 || !(r[0] < r[1]))
      throw std::invalid_argument("expected data or [min, max] with min < max, found '" + v + "'");
    s.range = std::make_pair(r[0], r[1]);
  } else if (tag == "colormap") {
    if (v == "viridis") {
      s.colourMap = ColourMapKind::Viridis;
    } else if (v == "blue_red") {
      s.colourMap = ColourMapKind::BlueRed;
    } else if (v == "grey" || v == "gray") {
      s.colourMap = ColourMapKind::Grey;
    } else {
      throw std::invalid_argument("unknown colour map '" + v +
                                  "'; accepted: viridis, blue_red, grey");
    }
  } else if (tag == "materials") {
    s.materials.clear();
    if (v == "all") return;
    for (int m : parseValue<std::vector<int>>(v)) {
      if (m < 0)
        throw std::invalid_argument("material indices are >= 0, found " + std::to_string(m));
      s.materials.push_back(m);
    }
    if (s.materials.empty()) throw std::invalid_argument("expected all or a list [0, 1, ...]");
  } else if (tag == "clip/point" || tag == "clip/normal") {
    if (!s.clip) s.clip = ClipPlane();
    (tag == "clip/point" ? s.clip->point : s.clip->normal) = parseValue<Vec3>(v);
  } else if (tag == "clip/thickness") {
    if (!s.clip) s.clip = ClipPlane();
    s.clip->thickness = parseNumber(v);
    if (!std::isfinite(s.clip->thickness) || !(s.clip->thickness > 0))
      throw std::invalid_argument(
          "<thickness> is the section's width about the plane: a positive length");
  } else if (tag == "camera") {
    static const std::pair<const char*, CameraPreset> presets[] = {{"iso", CameraPreset::Iso},
                                                                   {"front", CameraPreset::Front},
                                                                   {"back", CameraPreset::Back},
                                                                   {"side", CameraPreset::Side},
                                                                   {"top", CameraPreset::Top}};
    for (const auto& [name, preset] : presets)
      if (v == name) {
        s.camera = Camera();
        s.camera.preset = preset;
        return;
      }
    throw std::invalid_argument(
        "unknown camera '" + v +
        "'; accepted: iso, front, back, side, top, or <position>, <focal_point>, <up>, "
        "<view_angle> inside <camera>");
  } else if (tag == "camera/position" || tag == "camera/focal_point") {
    s.camera.preset = CameraPreset::Custom;
    (tag == "camera/position" ? s.camera.position : s.camera.focalPoint) = parseValue<Vec3>(v);
  } else if (tag == "camera/up") {
    s.camera.up = parseValue<Vec3>(v);
    if (s.camera.up.norm() == 0) throw std::invalid_argument("<up> must not be zero");
  } else if (tag == "camera/view_angle") {
    s.camera.viewAngle = parseNumber(v);
    if (!(s.camera.viewAngle > 0 && s.camera.viewAngle < 180))
      throw std::invalid_argument("<view_angle> is in degrees, between 0 and 180");
  } else if (tag == "size") {
    const std::vector<int> size = parseValue<std::vector<int>>(v);
    if (size.size() != 2 || size[0] < 64 || size[1] < 64 || size[0] > 8192 || size[1] > 8192)
      throw std::invalid_argument("expected [width, height] in pixels, each 64 to 8192, found '" +
                                  v + "'");
    s.width = size[0];
    s.height = size[1];
  } else if (tag == "background") {
    s.background = parseValue<Vec3>(v);
    if (s.background.minCoeff() < 0 || s.background.maxCoeff() > 1)
      throw std::invalid_argument("<background> is [r, g, b] with each in [0, 1]");
  } else if (tag == "title") {
    s.title = v;
  } else if (tag == "units") {
    s.units = v;
  } else if (tag == "field_name") {
    s.fieldName = v;
  } else if (tag == "scale_bar") {
    if (metresPerLengthUnit(v) == 0)
      throw std::invalid_argument("<scale_bar> names the positions' length unit: m, mm, um or nm");
    s.scaleBar = v;
  } else if (tag == "time_unit") {
    s.timeUnit = v;
  } else if (tag == "time_scale") {
    s.timeScale = parseNumber(v);
    if (!std::isfinite(s.timeScale) || !(s.timeScale > 0))
      throw std::invalid_argument(
          "<time_scale> multiplies the simulation time for the title: a positive number");
  } else {
    std::string accepted;
    for (const std::string& t : sceneTags())
      if (t.find('/') == std::string::npos) accepted += (accepted.empty() ? "" : ", ") + t;
    throw std::invalid_argument("unknown tag <" + tag + "> in <scene>; accepted: " + accepted +
                                ", clip");
  }
}

void checkScene(const Scene& s, const SceneContext& context) {
  if (s.name.empty() ||
      s.name.find_first_not_of(
          "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") != std::string::npos)
    throw std::invalid_argument("the scene name '" + s.name +
                                "' must be letters, digits, '_', '.' or '-' (it names files)");
  if (s.times.empty() == (s.interval <= 0))
    throw std::invalid_argument("give <times> or <interval> (exactly one)");
  // Each time is a picture (and an entry in memory): the fuzzer found an interval that asked for
  // 4.7e15 of them. (Without a run, as in render_vtu, maxTime is infinite and the data's times
  // are drawn instead.)
  constexpr double kMaxPictures = 1e5;
  if (s.interval > 0 && std::isfinite(context.maxTime) &&
      !((context.maxTime - context.initTime) / s.interval < kMaxPictures)) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g",
                  (context.maxTime - context.initTime) / s.interval + 1);
    throw std::invalid_argument("<interval> asks for " + std::string(count) +
                                " pictures between initTime and maxTime; at most 100000");
  }
  for (double t : s.times) {
    if (t < context.initTime)
      throw std::invalid_argument("time " + std::to_string(t) + " is before initTime " +
                                  std::to_string(context.initTime));
    if (t > context.maxTime)
      throw std::invalid_argument("time " + std::to_string(t) + " is after maxTime " +
                                  std::to_string(context.maxTime) + ": the run never reaches it");
  }
  for (int m : s.materials)
    if (context.materials >= 0 && m >= context.materials)
      throw std::invalid_argument("material " + std::to_string(m) +
                                  " does not exist (the input has " +
                                  std::to_string(context.materials) + ")");
  if (s.clip && s.clip->normal.norm() == 0)
    throw std::invalid_argument("<clip> needs a non-zero <normal>");
  if (s.camera.preset == CameraPreset::Custom) {
    if (!s.camera.position || !s.camera.focalPoint)
      throw std::invalid_argument(
          "<camera> needs both <position> and <focal_point> (or a preset: iso, front, ...)");
    const Vec3 view = *s.camera.focalPoint - *s.camera.position;
    if (view.norm() == 0)
      throw std::invalid_argument("<camera>: <position> and <focal_point> coincide");
    if (view.normalized().cross(s.camera.up.normalized()).norm() < 1e-6)
      throw std::invalid_argument("<camera>: <up> is parallel to the view direction");
  }
  if (context.lookup) {
    const SceneContext::LabelInfo info = context.lookup(s.field.label);
    if (info.components == 0)
      throw std::invalid_argument("field " + s.field.text + ": " + info.unavailable);
    if (info.components != s.field.components) {
      const std::string kind = info.components == 1   ? "a scalar"
                               : info.components == 3 ? "a vector"
                                                      : "a tensor";
      throw std::invalid_argument("field " + s.field.text + ": " + s.field.label + " is " + kind +
                                  (info.components == 1 ? " (no ':' part)"
                                   : info.components == 3
                                       ? " (accepted parts: x, y, z, magnitude)"
                                       : " (accepted parts: xx, xy, ..., zz, von_mises)"));
    }
  }
}

void readSceneTags(const PSNode& node, Scene& scene) {
  std::set<std::string> given;
  auto set = [&](const PSNode& tagNode, const std::string& tag) {
    if (tagNode.hasChildren()) tagNode.fail("<" + tagNode.name() + "> takes a value, not tags");
    if (!given.insert(tag).second) tagNode.fail("<" + tagNode.name() + "> is given twice");
    try {
      setSceneValue(scene, tag, tagNode.text());
    } catch (const std::invalid_argument& e) {
      tagNode.fail("<" + tagNode.name() + ">: " + e.what());
    }
  };
  for (const PSNode& child : node.children()) {
    const std::string tag = child.name();
    if ((tag == "clip" || tag == "camera") && child.hasChildren()) {
      if (!trim(child.text()).empty())
        child.fail("<" + tag + "> holds either a preset name or tags, not both");
      if (!given.insert(tag).second) child.fail("<" + tag + "> is given twice");
      for (const PSNode& part : child.children()) set(part, tag + "/" + part.name());
    } else if (tag == "clip") {
      child.fail("<clip> needs <point> and <normal>");
    } else {
      set(child, tag);
    }
  }
}

std::vector<Scene> readScenes(const PSNode& visualization, const SceneContext& context) {
  std::vector<Scene> scenes;
  std::set<std::string> names;
  for (const PSNode& node : visualization.children()) {
    if (node.name() != "scene")
      node.fail("unknown tag <" + node.name() + "> in <Visualization>; accepted: scene");
    Scene scene;
    scene.name = node.requireAttribute("name");
    if (!names.insert(scene.name).second) node.fail("a second scene named \"" + scene.name + "\"");
    readSceneTags(node, scene);
    try {
      checkScene(scene, context);
    } catch (const std::invalid_argument& e) {
      node.fail("<scene name=\"" + scene.name + "\">: " + e.what());
    }
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

}  // namespace anode

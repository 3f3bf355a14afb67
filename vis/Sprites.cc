#include "vis/Sprites.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace anode {

namespace {

// A value as single precision holds it: pictures are drawn from single-precision data. Through a
// volatile: Debian's GCC 12 at -O3 -march=native vectorizes the round trip of a position's x and
// y away (seen in its assembly), and pictures of Float32 and Float64 data then differ.
double single(double v) {
  const volatile float f = static_cast<float>(v);
  return static_cast<double>(f);
}

const NamedArray* findArray(const ParticleData& data, const std::string& name) {
  for (const NamedArray& a : data.arrays)
    if (a.name == name) return &a;
  return nullptr;
}

// Radius for data without volumes: the bounding box shared equally (a flat set: its area).
double radiusFromBounds(const std::vector<double>& points) {
  const size_t n = points.size() / 3;
  if (n == 0) return 0;
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = single(points[d]);
  for (size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], single(points[3 * i + d]));
      hi[d] = std::max(hi[d], single(points[3 * i + d]));
    }
  double extents[3];
  for (int d = 0; d < 3; ++d) extents[d] = hi[d] - lo[d];
  std::sort(extents, extents + 3);
  const double spacing =
      extents[0] > 0   ? std::cbrt(extents[0] * extents[1] * extents[2] / static_cast<double>(n))
      : extents[1] > 0 ? std::sqrt(extents[1] * extents[2] / static_cast<double>(n))
      : extents[2] > 0 ? extents[2] / static_cast<double>(n)
                       : 1.0;
  return spriteRadius(spacing * spacing * spacing);
}

}  // namespace

double sphereRadius(double volume) {
  return std::cbrt(3.0 * std::max(volume, 0.0) / (4.0 * M_PI));
}

double spriteRadius(double volume) {
  return 0.5 * std::sqrt(3.0) * std::cbrt(std::max(volume, 0.0));
}

double pictureValue(const FieldSpec& field, const double* tuple) {
  double components[9];
  for (int c = 0; c < field.components; ++c) components[c] = single(tuple[c]);
  return single(field.evaluate(components));
}

SpriteSet makeSprites(const Scene& scene, const ParticleData& data, std::vector<size_t>* drawn) {
  if (drawn) drawn->clear();
  if (data.points.empty()) return {};  // a rank holding none of the scene's particles
  const FieldSpec& field = scene.field;
  const NamedArray* values = findArray(data, field.label);
  if (!values || values->isInteger())
    throw std::runtime_error("the data holds no real array " + field.label + " for the field " +
                             field.text);
  if (values->components != field.components)
    throw std::runtime_error("field " + field.text + ": " + field.label + " has " +
                             std::to_string(values->components) +
                             " component(s), the field needs " + std::to_string(field.components));
  const NamedArray* volume = findArray(data, "p.volume");
  const NamedArray* material = findArray(data, "material");
  if (material && !material->isInteger())
    throw std::runtime_error("the material array does not hold integers");
  const double fallbackRadius = volume ? 0.0 : radiusFromBounds(data.points);

  SpriteSet s;
  const size_t n = data.count();
  for (size_t i = 0; i < n; ++i) {
    const double x[3] = {single(data.points[3 * i]), single(data.points[3 * i + 1]),
                         single(data.points[3 * i + 2])};
    if (material && !scene.drawsMaterial(static_cast<int>(material->integer[i]))) continue;
    if (!scene.keeps(x)) continue;
    s.position.insert(s.position.end(), x, x + 3);
    s.value.push_back(scene.scale * pictureValue(field, &values->real[i * field.components]));
    s.radius.push_back(volume ? spriteRadius(single(volume->real[i])) : fallbackRadius);
    if (drawn) drawn->push_back(i);
  }
  return s;
}

}  // namespace anode

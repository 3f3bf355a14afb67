#include "vis/SceneRenderer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "vis/ColourMap.h"

namespace anode {

namespace {

std::atomic<int> contextCount{0};

// Sprites: the vertex shader sizes each point to its sphere's projected diameter; the fragment
// shader keeps the unit disc, lights it as a sphere under a headlight (full colour at the centre,
// so the centre shows the colour map exactly) and writes the depth of the sphere's surface. With
// `identify` set it writes instead each sprite's index + 1 in the four bytes of the pixel (the
// same depth, so the same sprite wins each pixel as in the picture).
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in float fraction;
layout(location = 2) in float radius;
uniform mat4 view;
uniform mat4 projection;
uniform float pointScale;
out float vFraction;
out float vRadius;
out vec3 vCentre;
flat out int vIndex;
void main() {
  vec4 eye = view * vec4(position, 1.0);
  vCentre = eye.xyz;
  vIndex = gl_VertexID;
  vFraction = fraction;
  vRadius = radius;
  gl_Position = projection * eye;
  gl_PointSize = max(radius * pointScale / -eye.z, 1.0);
}
)";

const char* kFragmentShader = R"(#version 330 core
in float vFraction;
in float vRadius;
in vec3 vCentre;
flat in int vIndex;
uniform mat4 projection;
uniform sampler2D colours;
uniform int identify;
out vec4 colour;
void main() {
  vec2 p = 2.0 * gl_PointCoord - 1.0;
  p.y = -p.y;
  float rr = dot(p, p);
  if (rr > 1.0) discard;
  float nz = sqrt(1.0 - rr);
  vec3 base = texture(colours, vec2(vFraction, 0.5)).rgb;
  colour = vec4(base * (0.3 + 0.7 * nz), 1.0);
  if (identify != 0) {
    uint k = uint(vIndex) + 1u;
    colour = vec4(float(k & 255u), float((k >> 8) & 255u), float((k >> 16) & 255u),
                  float(k >> 24)) / 255.0;
  }
  vec4 surface = projection * vec4(vCentre + vRadius * vec3(p, nz), 1.0);
  gl_FragDepth = 0.5 + 0.5 * surface.z / surface.w;
}
)";

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("sprite shader does not compile: ") + log);
  }
  return shader;
}

Eigen::Matrix4d lookAt(const Vec3& eye, const Vec3& centre, const Vec3& up) {
  const Vec3 f = (centre - eye).normalized();
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m.block<3, 1>(0, 3) = -m.block<3, 3>(0, 0) * eye;
  return m;
}

Eigen::Matrix4d perspective(double fovy, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(fovy / 2);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect;
  p(1, 1) = f;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2 * far * near / (near - far);
  p(3, 2) = -1;
  return p;
}

// Direction from the focal point to the eye, and the up vector, of a preset (the pillar axis is z).
std::pair<Vec3, Vec3> presetDirection(CameraPreset preset) {
  switch (preset) {
    case CameraPreset::Front:
      return {Vec3(0, -1, 0), Vec3(0, 0, 1)};
    case CameraPreset::Back:
      return {Vec3(0, 1, 0), Vec3(0, 0, 1)};
    case CameraPreset::Side:
      return {Vec3(1, 0, 0), Vec3(0, 0, 1)};
    case CameraPreset::Top:
      return {Vec3(0, 0, 1), Vec3(0, 1, 0)};
    case CameraPreset::Iso:
    case CameraPreset::Custom:
      break;
  }
  return {Vec3(1, -1.25, 0.9).normalized(), Vec3(0, 0, 1)};
}

struct Bounds {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  Bounds() = default;
  explicit Bounds(const SpriteExtent& e) : lo(e.lo), hi(e.hi) {}
  bool empty() const { return !(lo.x() <= hi.x()); }
  Vec3 centre() const { return empty() ? Vec3(Vec3::Zero()) : Vec3(0.5 * (lo + hi)); }
  // Corner k of 8: bit 0 picks x, bit 1 y, bit 2 z from hi.
  Vec3 corner(int k) const {
    return Vec3((k & 1 ? hi : lo).x(), (k & 2 ? hi : lo).y(), (k & 4 ? hi : lo).z());
  }
};

// Where things go in a picture of the scene: the title's and labels' text sizes, the title band
// along the top and the colour bar's area on the right (none without the overlay), and the
// viewport (x, y, width, height) of the particles beside them.
struct PictureLayout {
  int titleSize, labelSize, titleBand, barArea;
  std::array<int, 4> viewport;
};

PictureLayout pictureLayout(const Scene& scene, Overlay overlay) {
  const int W = scene.width, H = scene.height;
  PictureLayout l;
  l.titleSize = std::max(12, H / 30);
  l.labelSize = std::max(10, H / 44);
  const bool overlaid = overlay == Overlay::TitleAndColourBar;
  l.titleBand = overlaid ? 2 * l.titleSize : 0;
  l.barArea = overlaid ? std::clamp(W * 17 / 100, 110, 400) : 0;
  l.viewport = {0, 0, W - l.barArea, H - l.titleBand};
  return l;
}

// A layer's pixel: depth in the bits above 24, the colour below.
uint64_t packPixel(uint64_t depth, const unsigned char* rgb) {
  return depth << 24 | uint64_t{rgb[0]} << 16 | uint64_t{rgb[1]} << 8 | rgb[2];
}

struct View {
  Eigen::Matrix4d view, projection;  // view acts on positions relative to `origin`
  Vec3 origin;
};

// The camera of the scene; a preset looks at the centre of the drawn particles from the nearest
// distance at which all of their box fits the particle area.
View makeView(const Camera& camera, const Bounds& bounds, double aspect) {
  const double fovy = camera.viewAngle * M_PI / 180;
  const double tanY = std::tan(fovy / 2), tanX = tanY * aspect;
  View v;
  v.origin = bounds.centre();
  Vec3 eye, focal, up;
  if (camera.preset == CameraPreset::Custom) {
    eye = *camera.position - v.origin;
    focal = *camera.focalPoint - v.origin;
    up = camera.up;
  } else {
    const auto [direction, presetUp] = presetDirection(camera.preset);
    focal = Vec3::Zero();
    up = presetUp;
    const Eigen::Matrix4d orient = lookAt(direction, Vec3::Zero(), up);  // eye at unit distance
    double distance = 0;
    for (int corner = 0; corner < 8 && !bounds.empty(); ++corner) {
      const Vec3 q = orient.block<3, 3>(0, 0) *
                     (bounds.corner(corner) - v.origin);  // x right, y up, z towards the eye
      distance =
          std::max({distance, q.z() + std::abs(q.x()) / tanX, q.z() + std::abs(q.y()) / tanY});
    }
    if (distance <= 0) distance = 1;
    eye = direction * distance * 1.08;
  }
  v.view = lookAt(eye, focal, up);
  double near = std::numeric_limits<double>::infinity(), far = 0;
  for (int corner = 0; corner < 8 && !bounds.empty(); ++corner) {
    const double depth =
        -(v.view.block<3, 3>(0, 0) * (bounds.corner(corner) - v.origin) + v.view.block<3, 1>(0, 3))
             .z();
    near = std::min(near, depth);
    far = std::max(far, depth);
  }
  if (!(far > 0)) far = (eye - focal).norm() * 2 + 1;
  far *= 1.05;
  near = std::max(near * 0.95, far * 1e-4);
  v.projection = perspective(fovy, aspect, near, far);
  return v;
}

}  // namespace

SpriteExtent SpriteExtent::of(const SpriteSet& s) {
  SpriteExtent e;
  // A set of values alone (a figure's panels together, for their colour range) has no box.
  for (size_t i = 0; i < s.position.size() / 3; ++i)
    for (int d = 0; d < 3; ++d) {
      e.lo[d] = std::min(e.lo[d], s.position[3 * i + d] - s.radius[i]);
      e.hi[d] = std::max(e.hi[d], s.position[3 * i + d] + s.radius[i]);
    }
  for (double v : s.value)
    if (std::isfinite(v)) {
      e.valueLo = std::min(e.valueLo, v);
      e.valueHi = std::max(e.valueHi, v);
    }
  return e;
}

std::pair<double, double> colourRange(const Scene& scene, const SpriteExtent& e) {
  if (scene.range) return *scene.range;
  const double lo = e.valueLo, hi = e.valueHi;
  if (!(lo <= hi)) return {0, 1};
  if (hi > lo) return {lo, hi};
  return lo == 0 ? std::make_pair(0.0, 1.0)
                 : std::make_pair(lo - 0.05 * std::abs(lo), hi + 0.05 * std::abs(hi));
}

std::string formatNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v == 0 ? 0.0 : v);
  return buffer;
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  const double raw = (hi - lo) / std::max(target - 1, 1);
  if (!(raw > 0)) return {lo};
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * magnitude;
  for (double m : {1.0, 2.0, 2.5, 5.0})
    if (m * magnitude >= raw * 0.999) {
      step = m * magnitude;
      break;
    }
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1)
    ticks.push_back(k * step);
  return ticks;
}

std::array<double, 2> RenderedScene::project(const Vec3& x) const {
  const Eigen::Vector4d c = worldToClip * Eigen::Vector4d(x.x(), x.y(), x.z(), 1.0);
  return {viewport[0] + (c.x() / c.w() + 1) / 2 * viewport[2],
          viewport[1] + (c.y() / c.w() + 1) / 2 * viewport[3]};
}

struct SceneRenderer::GLState {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;
  GLuint program = 0, vao = 0, vbo = 0, texture = 0;
  GLint uView = -1, uProjection = -1, uPointScale = -1, uColours = -1, uIdentify = -1;

  GLState() {
    // Mesa keeps a shader cache under the home directory unless told otherwise.
    if (!std::getenv("MESA_SHADER_CACHE_DIR"))
      setenv("MESA_SHADER_CACHE_DIR",
             (std::filesystem::temp_directory_path() / "anode-mpm-mesa-cache").c_str(), 1);
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context) throw std::runtime_error("OSMesa could not create an OpenGL 3.3 core context");
    ++contextCount;
  }

  ~GLState() { OSMesaDestroyContext(context); }

  void makeCurrent(int width, int height) {
    buffer.resize(4 * static_cast<size_t>(width) * height);
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height))
      throw std::runtime_error("OSMesa could not make its context current");
    if (program) return;
    program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader),
                 fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("sprite shaders do not link");
    uView = glGetUniformLocation(program, "view");
    uProjection = glGetUniformLocation(program, "projection");
    uPointScale = glGetUniformLocation(program, "pointScale");
    uColours = glGetUniformLocation(program, "colours");
    uIdentify = glGetUniformLocation(program, "identify");
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    const GLsizei stride = 5 * sizeof(float);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(4 * sizeof(float)));
    for (GLuint a = 0; a < 3; ++a) glEnableVertexAttribArray(a);
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    // Nearest texel: the same entry of the table the colour bar shows.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
};

SceneRenderer::SceneRenderer() = default;
SceneRenderer::~SceneRenderer() = default;

int SceneRenderer::contextsCreated() {
  return contextCount;
}

RGB inkOn(const Vec3& background) {
  const double luminance = 0.2126 * background[0] + 0.7152 * background[1] + 0.0722 * background[2];
  return luminance > 0.5 ? RGB{0, 0, 0} : RGB{1, 1, 1};
}

void drawColourBar(Canvas& canvas, const std::array<int, 4>& bar, std::pair<double, double> range,
                   ColourMapKind map, const std::string& name, const std::string& units,
                   const RGB& ink, int labelSize) {
  const ColourMap colours(map);
  const auto [x0, y0, x1, y1] = bar;
  const int barWidth = x1 - x0;
  for (int y = y0; y < y1; ++y) {
    const auto c = colours.colour((y - y0 + 0.5) / (y1 - y0));
    canvas.fillRect(x0, y, x1, y + 1, {c[0], c[1], c[2]});
  }
  canvas.fillRect(x0 - 1, y0 - 1, x1 + 1, y0, ink);
  canvas.fillRect(x0 - 1, y1, x1 + 1, y1 + 1, ink);
  canvas.fillRect(x0 - 1, y0, x0, y1, ink);
  canvas.fillRect(x1, y0, x1 + 1, y1, ink);
  const auto [lo, hi] = range;
  for (double tick : niceTicks(lo, hi)) {
    const int y = y0 + static_cast<int>(std::lround((tick - lo) / (hi - lo) * (y1 - y0 - 1)));
    canvas.fillRect(x1, y, x1 + barWidth / 3, y + 1, ink);
    canvas.text(formatNumber(tick), x1 + barWidth / 3 + 4, y, labelSize, ink, Canvas::Align::Start,
                Canvas::Align::Centre);
  }
  int labelY = y1 + labelSize;
  if (!units.empty()) {
    canvas.text("[" + units + "]", x0, labelY, labelSize, ink);
    labelY += labelSize * 3 / 2;
  }
  const int nameWidth = Canvas::textSize(name, labelSize)[0];
  canvas.text(name, std::min(x0, canvas.width() - 4 - nameWidth), labelY, labelSize, ink);
}

void drawScaleBar(Canvas& canvas, const std::array<int, 4>& area, double pixelsPerUnit,
                  const std::string& unit, int labelSize, const RGB& ink) {
  const double metresPerUnit = metresPerLengthUnit(unit);
  if (!(pixelsPerUnit > 0) || !std::isfinite(pixelsPerUnit) || metresPerUnit == 0)
    throw std::invalid_argument("a scale bar needs a view and a length unit (m, mm, um, nm)");
  const double wanted = area[2] / 5.0 / pixelsPerUnit * metresPerUnit;  // metres
  const double decade = std::pow(10.0, std::floor(std::log10(wanted)));
  const double mantissa = wanted / decade;
  const double metres = (mantissa >= 5 ? 5 : mantissa >= 2 ? 2 : 1) * decade;
  const int pixels = static_cast<int>(std::lround(metres / metresPerUnit * pixelsPerUnit));
  // Labelled in the largest unit that gives at least 1 (else the smallest).
  auto label = lengthUnits().back();
  for (const auto& u : lengthUnits())
    if (metres >= u.second * (1 - 1e-9)) {
      label = u;
      break;
    }
  const std::string shown = formatNumber(metres / label.second) + " " + label.first;
  const int thickness = std::max(3, labelSize / 5);
  const int x1 = area[0] + area[2] - labelSize, x0 = x1 - pixels;
  const int y0 = area[1] + labelSize;
  canvas.fillRect(x0, y0, x1, y0 + thickness, ink);
  canvas.text(shown, (x0 + x1) / 2, y0 + thickness + labelSize / 4, labelSize, ink,
              Canvas::Align::Centre, Canvas::Align::Start);
}

RenderedScene SceneRenderer::render(const Scene& scene, const SpriteSet& sprites, double time,
                                    Overlay overlay) {
  const SpriteExtent extent = SpriteExtent::of(sprites);
  return finish(scene, drawLayer(scene, sprites, extent, overlay), extent, time, overlay);
}

namespace {

// The camera of a picture of the scene, for sprites of this extent.
View viewOf(const Scene& scene, const SpriteExtent& extent, Overlay overlay) {
  const std::array<int, 4> viewport = pictureLayout(scene, overlay).viewport;
  return makeView(scene.camera, Bounds(extent), static_cast<double>(viewport[2]) / viewport[3]);
}

}  // namespace

void SceneRenderer::drawSprites(const Scene& scene, const SpriteSet& sprites,
                                const SpriteExtent& extent, Overlay overlay, bool identify) {
  const int W = scene.width, H = scene.height;
  const std::array<int, 4> viewport = pictureLayout(scene, overlay).viewport;
  const std::pair<double, double> range = colourRange(scene, extent);
  const ColourMap colours(scene.colourMap);
  if (identify && sprites.count() >= std::numeric_limits<uint32_t>::max())
    throw std::runtime_error("too many sprites to tell apart in a picture's four bytes");
  if (!gl_) gl_ = std::make_unique<GLState>();
  gl_->makeCurrent(W, H);
  const View view = viewOf(scene, extent, overlay);

  glViewport(0, 0, W, H);
  if (identify)
    glClearColor(0, 0, 0, 0);
  else
    glClearColor(static_cast<float>(scene.background[0]), static_cast<float>(scene.background[1]),
                 static_cast<float>(scene.background[2]), 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (sprites.count() > 0) {
    std::vector<float> vertices(5 * sprites.count());
    const double lo = range.first, span = range.second - range.first;
    for (size_t i = 0; i < sprites.count(); ++i) {
      float* v = &vertices[5 * i];
      for (int d = 0; d < 3; ++d)
        v[d] = static_cast<float>(sprites.position[3 * i + d] - view.origin[d]);
      const double t = (sprites.value[i] - lo) / span;
      v[3] = static_cast<float>(std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0));
      v[4] = static_cast<float>(sprites.radius[i]);
    }
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(gl_->program);
    const Eigen::Matrix4f viewF = view.view.cast<float>(),
                          projectionF = view.projection.cast<float>();
    glUniformMatrix4fv(gl_->uView, 1, GL_FALSE, viewF.data());  // Eigen is column-major, as GL
    glUniformMatrix4fv(gl_->uProjection, 1, GL_FALSE, projectionF.data());
    glUniform1f(gl_->uPointScale, static_cast<float>(view.projection(1, 1) * viewport[3]));
    glUniform1i(gl_->uIdentify, identify ? 1 : 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl_->texture);
    const std::vector<unsigned char> table = colours.rgba8();
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, ColourMap::kEntries, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 table.data());
    glUniform1i(gl_->uColours, 0);
    glBindVertexArray(gl_->vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                 vertices.data(), GL_STREAM_DRAW);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(sprites.count()));
  }
  glFinish();
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw std::runtime_error("OpenGL error " + std::to_string(error) +
                             " while drawing the particles");
}

PixelLayer SceneRenderer::drawLayer(const Scene& scene, const SpriteSet& sprites,
                                    const SpriteExtent& extent, Overlay overlay) {
  drawSprites(scene, sprites, extent, overlay, false);
  const int W = scene.width, H = scene.height;
  GLint depthWidth = 0, depthHeight = 0, bytesPerValue = 0;
  void* depth = nullptr;
  if (!OSMesaGetDepthBuffer(gl_->context, &depthWidth, &depthHeight, &bytesPerValue, &depth) ||
      depthWidth != W || depthHeight != H || (bytesPerValue != 2 && bytesPerValue != 4))
    throw std::runtime_error("OSMesa gives no depth buffer of the picture's size");
  const size_t pixels = static_cast<size_t>(W) * H;
  PixelLayer layer(pixels);
  const unsigned char* rgba = gl_->buffer.data();
  for (size_t p = 0; p < pixels; ++p) {
    const uint64_t z = bytesPerValue == 4 ? static_cast<const uint32_t*>(depth)[p]
                                          : static_cast<const uint16_t*>(depth)[p];
    layer[p] = packPixel(z, rgba + 4 * p);
  }
  return layer;
}

std::vector<size_t> SceneRenderer::visibleSprites(const Scene& scene, const SpriteSet& sprites,
                                                  const SpriteExtent& extent, Overlay overlay) {
  drawSprites(scene, sprites, extent, overlay, true);
  std::vector<char> seen(sprites.count(), 0);
  const unsigned char* rgba = gl_->buffer.data();
  for (size_t p = 0; p < gl_->buffer.size() / 4; ++p) {
    const unsigned char* b = rgba + 4 * p;
    const uint32_t k =
        uint32_t{b[0]} | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16 | uint32_t{b[3]} << 24;
    if (k == 0) continue;  // the background
    if (k > sprites.count())
      throw std::runtime_error("a pixel names sprite " + std::to_string(k - 1) + " of " +
                               std::to_string(sprites.count()));
    seen[k - 1] = 1;
  }
  std::vector<size_t> visible;
  for (size_t i = 0; i < seen.size(); ++i)
    if (seen[i]) visible.push_back(i);
  return visible;
}

RenderedScene SceneRenderer::finish(const Scene& scene, const PixelLayer& layer,
                                    const SpriteExtent& extent, double time, Overlay overlay) {
  const int W = scene.width, H = scene.height;
  const RGB background = {scene.background[0], scene.background[1], scene.background[2]};
  const RGB ink = inkOn(scene.background);
  const PictureLayout layout = pictureLayout(scene, overlay);
  const int titleSize = layout.titleSize, labelSize = layout.labelSize, barArea = layout.barArea;

  RenderedScene out(Canvas(W, H, background));
  out.viewport = layout.viewport;
  out.range = colourRange(scene, extent);
  const View view = viewOf(scene, extent, overlay);
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.block<3, 1>(0, 3) = -view.origin;
  out.worldToClip = view.projection * view.view * shift;
  unsigned char* dst = out.canvas.data().data();
  for (size_t p = 0; p < layer.size(); ++p)
    for (int c = 0; c < 3; ++c)
      dst[3 * p + c] = static_cast<unsigned char>(layer[p] >> (16 - 8 * c));
  // The camera's right, one length unit long, at the focal point.
  const Vec3 focal =
      scene.camera.preset == CameraPreset::Custom ? *scene.camera.focalPoint : view.origin;
  const Vec3 right = view.view.block<1, 3>(0, 0).transpose();
  const auto [ax, ay] = out.project(focal);
  const auto [bx, by] = out.project(focal + right);
  out.pixelsPerUnit = std::hypot(bx - ax, by - ay);
  if (!scene.scaleBar.empty())
    drawScaleBar(out.canvas, out.viewport, out.pixelsPerUnit, scene.scaleBar,
                 overlay == Overlay::None ? panelLabelSize(H) : labelSize, ink);

  if (overlay != Overlay::TitleAndColourBar) return out;

  // Title with the time.
  const std::string title = scene.titleAt(time);
  out.canvas.text(title, titleSize / 2, H - titleSize / 2, titleSize, ink, Canvas::Align::Start,
                  Canvas::Align::End);

  // Colour bar: the table's colours, a frame, ticks with values, the field name and units above.
  const int barWidth = std::max(10, W / 48);
  const int x0 = W - barArea + barWidth / 2;
  out.colourBar = {x0, H * 12 / 100, x0 + barWidth, H * 70 / 100};
  drawColourBar(out.canvas, out.colourBar, out.range, scene.colourMap, scene.barName(), scene.units,
                ink, labelSize);
  return out;
}

}  // namespace anode

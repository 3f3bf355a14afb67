// render_vtu: renders the scenes of a finished run from its particle output (.pvd or one .vtu),
// so pictures for a report are regenerated without re-running, and (--report) a run's
// report.html from its files (RunReport.h). Exit codes: 0 done, 1 I/O or
// rendering error, 2 bad options or scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "StandAlone/Driver/RunReport.h"
#include "vis/SceneRenderer.h"
#include "vis/SceneSpec.h"
#include "vis/Sprites.h"
#include "vis/VTKReaders.h"

namespace fs = std::filesystem;

namespace {

using namespace anode;

const char* kUsage =
    "usage: render_vtu [options] DATA\n"
    "       render_vtu --report DIR\n"
    "  DATA             a run's particles.pvd, or one .vtu\n"
    "  --ups FILE       the scenes of the <Visualization> block of FILE (scene options\n"
    "                   change them). Without --ups: with scene options, one new scene\n"
    "                   made of them; without, the scenes of the run's input.ups beside\n"
    "                   a .pvd (or a default scene)\n"
    "  --scene NAME     render only this scene (of --ups or of the run's input.ups)\n"
    "  --times all      every file of the .pvd (default: each scene time, from the first\n"
    "                   file at or after it; a default scene: every file)\n"
    "  --time T         the time of a .vtu given alone (default 0)\n"
    "  -o DIR           write DIR/images/<scene>_<time>.png (default DIR: DATA's folder)\n"
    "  --name NAME      the name of a scene made of options (default view)\n"
    "  --TAG VALUE      a scene option: sets that tag, written as in the input\n"
    "                   (docs/input-reference.md): --field, --scale, --range, --colormap,\n"
    "                   --materials, --clip-point, --clip-normal, --camera,\n"
    "                   --camera-position, --camera-focal-point, --camera-up,\n"
    "                   --camera-view-angle, --size, --background, --title, --units,\n"
    "                   --time-unit, --times, --interval\n"
    "  --report DIR     write DIR/report.html from the run's history.csv, input.ups and\n"
    "                   images/ (sus writes it at each checkpoint and at the end)\n"
    "  --benchmark N    render a synthetic pillar of N particles at --size (default\n"
    "                   [1024, 768]) five times and print the seconds per image\n"
    "example: render_vtu --field p.stress:von_mises --camera front\n"
    "             --clip-normal \"[0,-1,0]\" out/run/particles.pvd\n";

[[noreturn]] void usageError(const std::string& message) {
  std::fprintf(stderr, "render_vtu: %s\n%s", message.c_str(), kUsage);
  std::exit(2);
}

// "--clip-point" -> "clip/point", "--time-unit" -> "time_unit"; empty if not a scene tag.
std::string sceneTagOf(const std::string& option) {
  for (const std::string& tag : sceneTags()) {
    std::string spelled = "--" + tag;
    for (char& c : spelled)
      if (c == '/' || c == '_') c = '-';
    if (spelled == option) return tag;
  }
  return "";
}

struct Options {
  std::string data, ups, only, outputDir, name = "view", report;
  bool allTimes = false;
  double vtuTime = 0;
  long benchmark = 0;
  std::vector<std::pair<std::string, std::string>> tags;  // scene tag, value
};

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--ups") {
      o.ups = value();
    } else if (a == "--report") {
      o.report = value();
    } else if (a == "--scene") {
      o.only = value();
    } else if (a == "-o") {
      o.outputDir = value();
    } else if (a == "--name") {
      o.name = value();
    } else if (a == "--time") {
      try {
        o.vtuTime = parseValue<double>(value());
      } catch (const std::invalid_argument& e) {
        usageError(std::string("--time: ") + e.what());
      }
    } else if (a == "--benchmark") {
      const std::string v = value();
      char* end = nullptr;
      o.benchmark = std::strtol(v.c_str(), &end, 10);
      if (*end != '\0' || o.benchmark < 1)
        usageError("--benchmark needs a positive particle count");
    } else if (const std::string tag = sceneTagOf(a); !tag.empty()) {
      const std::string v = value();
      if (tag == "times" && v == "all")
        o.allTimes = true;
      else
        o.tags.emplace_back(tag, v);
    } else if (!a.empty() && a[0] == '-') {
      usageError("unknown option " + a);
    } else if (o.data.empty()) {
      o.data = a;
    } else {
      usageError("more than one DATA given");
    }
  }
  if (!o.report.empty() && (!o.data.empty() || o.benchmark > 0 || !o.tags.empty()))
    usageError("--report DIR takes no DATA and no other option");
  if (o.data.empty() && o.benchmark == 0 && o.report.empty()) usageError("no DATA given");
  return o;
}

// The scenes of an input's <Visualization> block (the rest of the input is not looked at).
std::vector<Scene> scenesFromInput(const std::string& file) {
  ProblemSpec spec(file, false);
  const PSNode root = spec.root();
  for (const PSNode& block : root.children())
    if (block.name() != "Visualization") block.markSubtreeUsed();
  const PSNode visualization = root.child("Visualization");
  if (!visualization) throw InputError(file, root.line(), "the input has no <Visualization> block");
  return readScenes(visualization, SceneContext());
}

bool hasScenes(const std::string& file) {
  ProblemSpec spec(file, false);
  return static_cast<bool>(spec.root().child("Visualization"));
}

struct Chosen {
  std::vector<Scene> scenes;
  bool everyFile = false;  // render every file, not the scenes' times
};

Chosen chooseScenes(const Options& o) {
  std::string ups = o.ups;
  // Options that describe a scene make a new one, unless an input's scenes are asked for.
  if (ups.empty() && fs::path(o.data).extension() == ".pvd" &&
      (o.tags.empty() || !o.only.empty())) {
    const fs::path beside = fs::path(o.data).parent_path() / "input.ups";
    if (fs::exists(beside) && hasScenes(beside.string())) ups = beside.string();
  }
  std::vector<Scene> scenes;
  Chosen chosen;
  chosen.everyFile = o.allTimes || fs::path(o.data).extension() != ".pvd";
  if (!ups.empty()) {
    scenes = scenesFromInput(ups);
    std::fprintf(stderr, "render_vtu: scenes from %s\n", ups.c_str());
  } else {
    Scene s;
    s.name = o.name;
    s.times = {0};  // replaced by --times or --interval; without them every file is rendered
    scenes.push_back(s);
    chosen.everyFile |= std::none_of(o.tags.begin(), o.tags.end(), [](const auto& t) {
      return t.first == "times" || t.first == "interval";
    });
  }
  for (Scene& s : scenes) {
    if (!o.only.empty() && s.name != o.only) continue;
    for (const auto& [tag, value] : o.tags) {
      if (tag == "times") s.interval = 0;
      if (tag == "interval") s.times.clear();
      try {
        setSceneValue(s, tag, value);
      } catch (const std::invalid_argument& e) {
        usageError("--" + tag + ": " + e.what());
      }
    }
    try {
      checkScene(s, SceneContext());
    } catch (const std::invalid_argument& e) {
      usageError("scene " + s.name + ": " + e.what());
    }
    chosen.scenes.push_back(s);
  }
  if (chosen.scenes.empty()) usageError("no scene named " + o.only);
  return chosen;
}

// A pillar of about n particles (radius 0.05, height 0.1, as the paper's small pillar) with a
// lithiation front: c = 1 within a shell of the surface, falling to 0 inside.
ParticleData syntheticPillar(long n) {
  const double radius = 0.05, height = 0.1;
  const double cellVolume = M_PI * radius * radius * height / static_cast<double>(n);
  const double h = std::cbrt(cellVolume);
  ParticleData d;
  NamedArray c{"p.concentration", 1, {}, {}}, volume{"p.volume", 1, {}, {}};
  for (double z = h / 2; z < height; z += h)
    for (double y = -radius + h / 2; y < radius; y += h)
      for (double x = -radius + h / 2; x < radius; x += h) {
        const double r = std::hypot(x, y);
        if (r > radius) continue;
        d.points.insert(d.points.end(), {x, y, z});
        const double depth = std::min(radius - r, height - z);
        c.real.push_back(1 / (1 + std::exp((depth - 0.015) / 0.003)));
        volume.real.push_back(h * h * h);
      }
  d.arrays.push_back(std::move(c));
  d.arrays.push_back(std::move(volume));
  return d;
}

int benchmark(const Options& o) {
  Scene scene;
  scene.name = "benchmark";
  scene.times = {0};
  scene.range = std::make_pair(0.0, 1.0);
  for (const auto& [tag, value] : o.tags) setSceneValue(scene, tag, value);
  const ParticleData data = syntheticPillar(o.benchmark);
  const SpriteSet sprites = makeSprites(scene, data);
  SceneRenderer renderer;
  using clock = std::chrono::steady_clock;
  const auto seconds = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto first = clock::now();
  RenderedScene picture = renderer.render(scene, sprites, 0.0);
  const double firstSeconds = seconds(first, clock::now());
  const int repeats = 5;
  const auto start = clock::now();
  for (int k = 0; k < repeats; ++k) picture = renderer.render(scene, sprites, 0.0);
  const double perImage = seconds(start, clock::now()) / repeats;
  const auto pngStart = clock::now();
  const std::string dir = o.outputDir.empty() ? fs::temp_directory_path().string() : o.outputDir;
  const std::string png =
      (fs::path(dir) / "images" / ("benchmark_" + std::to_string(o.benchmark) + ".png")).string();
  fs::create_directories(fs::path(png).parent_path());
  writePNG(picture.canvas, png);
  const double pngSeconds = seconds(pngStart, clock::now());
  std::printf("render_vtu: %zu particles in the pillar, %zu drawn, %dx%d\n", data.count(),
              sprites.count(), scene.width, scene.height);
  std::printf("  first image (with context and shader setup) %.3f s\n", firstSeconds);
  std::printf("  per image (mean of %d)                      %.3f s\n", repeats, perImage);
  std::printf("  PNG writing                                 %.3f s  (%s)\n", pngSeconds,
              png.c_str());
  return 0;
}

int render(const Options& o) {
  const Chosen chosen = chooseScenes(o);
  std::vector<std::pair<double, std::string>> files;
  if (fs::path(o.data).extension() == ".pvd")
    files = readPVD(o.data);
  else
    files = {{o.vtuTime, o.data}};
  if (files.empty()) throw std::runtime_error(o.data + " lists no files");
  const fs::path outputDir =
      o.outputDir.empty() ? fs::path(o.data).parent_path() : fs::path(o.outputDir);
  fs::create_directories(outputDir / "images");
  SceneRenderer renderer;
  for (const Scene& scene : chosen.scenes) {
    // (name time, file) pairs: each scene time from the first file at or after it.
    std::vector<std::pair<double, size_t>> jobs;
    if (chosen.everyFile) {
      for (size_t f = 0; f < files.size(); ++f) jobs.emplace_back(files[f].first, f);
    } else {
      for (double t : scene.renderTimes(files.front().first, files.back().first)) {
        size_t f = 0;
        while (f < files.size() &&
               files[f].first < t - 1e-12 * std::max(std::abs(t), std::abs(files[f].first)))
          ++f;
        if (f == files.size()) {
          std::fprintf(
              stderr,
              "render_vtu: scene %s: no output at or after t = %g (the last is %g); skipped\n",
              scene.name.c_str(), t, files.back().first);
          continue;
        }
        jobs.emplace_back(t, f);
      }
    }
    const std::vector<std::string> arrays = {scene.field.label, "p.volume", "material"};
    for (const auto& [t, f] : jobs) {
      const ParticleData data = readParticlesVTU(files[f].second, arrays);
      const RenderedScene picture =
          renderer.render(scene, makeSprites(scene, data), files[f].first);
      const std::string png = (outputDir / scene.imageFile(t)).string();
      writePNG(picture.canvas, png);
      std::printf("%s\n", png.c_str());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parseOptions(argc, argv);
  try {
    if (!options.report.empty()) {
      if (!fs::is_regular_file(fs::path(options.report) / "history.csv"))
        throw std::runtime_error(options.report +
                                 ": no history.csv (not a run's output directory)");
      std::printf("%s\n",
                  writeRunReport(options.report, "Written by render_vtu --report.").c_str());
      return 0;
    }
    return options.benchmark > 0 ? benchmark(options) : render(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "render_vtu: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_vtu: error: %s\n", e.what());
    return 1;
  }
}

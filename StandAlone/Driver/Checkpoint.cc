#include "StandAlone/Driver/Checkpoint.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace anode {

namespace {

template <class T>
std::optional<T> numberAttribute(const PSNode& node, const char* name) {
  const std::optional<std::string> text = node.attribute(name);
  if (!text) return std::nullopt;
  try {
    return parseValue<T>(*text);
  } catch (const std::invalid_argument& e) {
    node.fail(std::string("<checkpoint ") + name + "=\"" + *text + "\">: " + e.what());
  }
}

}  // namespace

CheckpointSchedule CheckpointSchedule::fromInput(const PSNode& archiver) {
  CheckpointSchedule s;
  const PSNode node = archiver.child("checkpoint");
  if (!node) return s;
  bool byWallTime = false;
  for (const std::string& a : node.attributeNames()) {
    if (a == "cycle" || a == "interval" || a == "timestepInterval") continue;
    if (a != "walltimeStart" && a != "walltimeInterval")
      node.fail("<checkpoint>: unknown attribute " + a +
                "; accepted: cycle, interval, timestepInterval");
    node.unsupported("<checkpoint " + a + ">: checkpoints by wall time");
    byWallTime = true;
  }
  if (byWallTime && !node.attribute("interval") && !node.attribute("timestepInterval")) return s;
  const int cycle = numberAttribute<int>(node, "cycle").value_or(2);  // Uintah's default
  s.interval = numberAttribute<double>(node, "interval");
  const std::optional<int> steps = numberAttribute<int>(node, "timestepInterval");
  if (cycle < 1)
    node.fail("<checkpoint cycle=\"" + std::to_string(cycle) + "\">: must be at least 1");
  if (s.interval && steps) node.fail("<checkpoint>: give interval or timestepInterval, not both");
  if (!s.interval && !steps)
    node.fail("<checkpoint> needs interval=\"T\" (simulation time) or timestepInterval=\"N\"");
  if (s.interval && !(*s.interval > 0 && std::isfinite(*s.interval)))
    node.fail("<checkpoint interval=\"" + *node.attribute("interval") +
              "\">: must be a positive time");
  if (steps && *steps < 1)
    node.fail("<checkpoint timestepInterval=\"" + std::to_string(*steps) +
              "\">: must be at least 1");
  s.cycle = cycle;
  s.stepInterval = steps.value_or(0);
  return s;
}

bool CheckpointSchedule::isDue(long step, double time, double lastTime) const {
  if (!enabled()) return false;
  if (stepInterval > 0) return step % stepInterval == 0;
  // As output: the first step at or after each multiple of the interval.
  const double next = (std::floor(lastTime / *interval + 1e-9) + 1) * *interval;
  return time >= next * (1 - 1e-12);
}

namespace {

const std::regex& checkpointName() {
  static const std::regex name(R"((auto_)?step_(\d+)\.ckpt)");
  return name;
}

// Checkpoints of the kinds asked for, newest first.
std::vector<std::string> checkpoints(const std::string& dir, bool scheduled, bool automatic) {
  std::vector<std::pair<long, std::string>> found;
  const fs::path folder = fs::path(dir) / "checkpoints";
  if (!fs::is_directory(folder)) return {};
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    std::smatch m;
    const std::string file = e.path().filename().string();
    if (!std::regex_match(file, m, checkpointName())) continue;
    if (m[1].matched ? automatic : scheduled)
      found.emplace_back(std::stol(m[2].str()), e.path().string());
  }
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::string> paths;
  for (const auto& f : found) paths.push_back(f.second);
  return paths;
}

}  // namespace

std::string checkpointPath(const std::string& dir, long step, CheckpointKind kind) {
  std::ostringstream name;
  name << (kind == CheckpointKind::Automatic ? "auto_" : "") << "step_" << std::setw(6)
       << std::setfill('0') << step << ".ckpt";
  return (fs::path(dir) / "checkpoints" / name.str()).string();
}

std::string checkpointParts(const std::string& checkpoint) {
  return checkpoint + ".parts";
}

std::string checkpointPart(const std::string& checkpoint, int rank) {
  std::ostringstream name;
  name << "rank_" << std::setw(4) << std::setfill('0') << rank << ".part";
  return (fs::path(checkpointParts(checkpoint)) / name.str()).string();
}

std::vector<std::string> listCheckpoints(const std::string& dir) {
  return checkpoints(dir, true, true);
}

void removeOldCheckpoints(const std::string& dir, CheckpointKind kind, int keep) {
  const std::vector<std::string> all =
      checkpoints(dir, kind == CheckpointKind::Scheduled, kind == CheckpointKind::Automatic);
  // The manifest first: a checkpoint without it is no checkpoint, whatever parts remain.
  for (size_t i = static_cast<size_t>(std::max(keep, 0)); i < all.size(); ++i) {
    fs::remove(all[i]);
    fs::remove_all(checkpointParts(all[i]));
  }
}

void removeAutomaticCheckpoints(const std::string& dir) {
  removeOldCheckpoints(dir, CheckpointKind::Automatic, 0);
  std::error_code notEmpty;
  fs::remove(fs::path(dir) / "checkpoints", notEmpty);
}

void removeUnfinishedCheckpointParts(const std::string& dir) {
  const fs::path folder = fs::path(dir) / "checkpoints";
  if (!fs::is_directory(folder)) return;
  std::vector<fs::path> unfinished;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    const std::string suffix = ".parts";
    if (e.is_directory() && name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        !fs::exists(folder / name.substr(0, name.size() - suffix.size())))
      unfinished.push_back(e.path());
  }
  for (const fs::path& p : unfinished) fs::remove_all(p);
}

int removeTemporaryFiles(const std::string& dir) {
  static const std::regex temporary(R"(.*\.tmp\d+)");
  std::vector<fs::path> leftovers;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && std::regex_match(e.path().filename().string(), temporary))
      leftovers.push_back(e.path());
  for (const fs::path& p : leftovers) fs::remove(p);
  return static_cast<int>(leftovers.size());
}

}  // namespace anode

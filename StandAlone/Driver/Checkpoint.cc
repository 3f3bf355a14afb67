#include "StandAlone/Driver/Checkpoint.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "Components/MPM/MPM.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Util/AtomicFile.h"
#include "Core/Util/BinaryStream.h"
#include "StandAlone/Driver/DataArchiver.h"

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

namespace {

constexpr char kCheckpointMagic[] = "anode-mpm checkpoint";
// A distributed run's checkpoint: the manifest under the checkpoint's name, one part per rank.
constexpr char kDistributedCheckpointMagic[] = "anode-mpm distributed checkpoint";
constexpr char kCheckpointPartMagic[] = "anode-mpm checkpoint part";
constexpr uint32_t kCheckpointVersion = 14;

// This rank's part of a distributed checkpoint; returns its hash.
uint64_t writePart(const std::string& checkpoint, const MPM& mpm) {
  std::error_code exists;
  fs::create_directories(checkpointParts(checkpoint), exists);
  uint64_t hash = 0;
  writeAtomically(
      checkpointPart(checkpoint, Communicator::rank()),
      [&](const std::string& tmp) {
        BinaryWriter out(tmp);
        out.string(kCheckpointPartMagic);
        mpm.saveState(out);
        hash = out.finish();
      },
      Durability::Synced);
  return hash;
}

// Reads the checkpoint on this rank only; `layout` receives a distributed one's boxes.
CheckpointHeader readCheckpoint(const std::string& path, DataArchiver* outputs, MPM& mpm,
                                RankLayout::Saved& layout) {
  CheckpointHeader header;
  BinaryReader in(path);
  const std::string magic = in.string();
  const bool distributed = magic == kDistributedCheckpointMagic;
  if (magic != kCheckpointMagic && !distributed)
    throw std::runtime_error(path + ": not a checkpoint of this code");
  const auto version = in.value<uint32_t>();
  if (version != kCheckpointVersion)
    throw std::runtime_error(path + ": checkpoint format " + std::to_string(version) +
                             ", this code reads " + std::to_string(kCheckpointVersion));
  header.threads = in.value<int32_t>();
  header.inputHash = in.value<uint64_t>();
  header.t = in.value<double>();
  header.dt = in.value<double>();
  header.ruleDt = in.value<double>();
  header.dtLimit = static_cast<StableTimestep::Limit>(in.value<int32_t>());
  if (header.dtLimit < 0 || header.dtLimit >= StableTimestep::kLimits)
    throw std::runtime_error(path + ": unknown time-step limit " + std::to_string(header.dtLimit));
  header.dtSetByTimeControl = in.value<int32_t>() != 0;
  TimestepController::ErrorControl& error = header.errorControl;
  for (double* v : {&error.lastEstimate, &error.previousEstimate, &error.lastDt, &error.takenDt})
    *v = in.value<double>();
  header.step = in.value<long>();
  header.particleSteps = in.value<double>();
  header.wallSeconds = in.value<double>();
  header.lastScheduledTime = in.value<double>();
  if (outputs) {
    outputs->loadState(in);
  } else {
    DataArchiver unused;
    unused.loadState(in);
  }
  if (!distributed) {
    mpm.loadState(in);
    in.finish();
    header.bytesRead = header.bytesInAll = static_cast<double>(fs::file_size(path));
    return header;
  }
  header.ranks = in.value<int32_t>();
  if (header.ranks < 1) throw std::runtime_error(path + ": a checkpoint of no rank");
  layout = RankLayout::read(in);
  std::vector<uint64_t> hashes(header.ranks);
  for (uint64_t& h : hashes) h = in.value<uint64_t>();
  in.finish();
  // The same rank count continues with the same boxes, each rank from its own part; with another
  // each rank reads the parts r = rank (mod ranks) and the particles are shared out anew. A rank
  // with no such part reads one for the state every part holds (the next ID, the flux BCs'),
  // keeping none of its particles.
  std::vector<int> parts;
  const int me = Communicator::rank(), size = Communicator::size();
  if (header.ranks == size)
    parts.push_back(me);
  else
    for (int r = me; r < header.ranks; r += size) parts.push_back(r);
  const bool forStateOnly = parts.empty();
  if (forStateOnly) parts.push_back(me % header.ranks);
  header.bytesRead = static_cast<double>(fs::file_size(path));
  header.bytesInAll = header.bytesRead;
  for (int r = 0; r < header.ranks; ++r) {
    std::error_code missing;
    const auto bytes = fs::file_size(checkpointPart(path, r), missing);
    if (!missing) header.bytesInAll += static_cast<double>(bytes);
  }
  for (int r : parts) {
    const std::string partPath = checkpointPart(path, r);
    BinaryReader part(partPath);
    header.bytesRead += static_cast<double>(fs::file_size(partPath));
    if (part.string() != kCheckpointPartMagic)
      throw std::runtime_error(partPath + ": not a part of a checkpoint of this code");
    mpm.loadState(part, forStateOnly         ? MPM::ReadParticles::Drop
                        : r == parts.front() ? MPM::ReadParticles::Replace
                                             : MPM::ReadParticles::Append);
    if (part.finish() != hashes[r])
      throw std::runtime_error(partPath + ": not the part " + path + " names (another hash)");
  }
  return header;
}

}  // namespace

uint64_t fileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  StreamHash h;
  h.add(text.data(), text.size());
  return h.value();
}

void writeCheckpoint(Collective every, const std::string& path, const CheckpointHeader& header,
                     const DataArchiver& archiver, const MPM& mpm) {
  const bool distributed = header.ranks > 1;
  std::vector<std::string> partHashes;
  if (distributed) {
    const uint64_t hash = writePart(path, mpm);
    partHashes = collective::allGather(every, std::string(reinterpret_cast<const char*>(&hash), 8));
  } else {
    fs::create_directories(fs::path(path).parent_path());
  }
  if (!Communicator::isRoot()) return;
  writeAtomically(
      path,
      [&](const std::string& tmp) {
        BinaryWriter out(tmp);
        out.string(distributed ? kDistributedCheckpointMagic : kCheckpointMagic);
        out.value(kCheckpointVersion);
        out.value<int32_t>(header.threads);
        out.value(header.inputHash);
        out.value(header.t);
        out.value(header.dt);
        out.value(header.ruleDt);
        out.value<int32_t>(header.dtLimit);
        out.value<int32_t>(header.dtSetByTimeControl ? 1 : 0);
        const TimestepController::ErrorControl& error = header.errorControl;
        for (double v : {error.lastEstimate, error.previousEstimate, error.lastDt, error.takenDt})
          out.value(v);
        out.value(header.step);
        out.value(header.particleSteps);
        out.value(header.wallSeconds);
        out.value(header.lastScheduledTime);
        archiver.saveState(out);
        if (distributed) {
          out.value<int32_t>(header.ranks);
          mpm.layout().save(out);
          for (const std::string& h : partHashes) out.bytes(h.data(), h.size());
        } else {
          mpm.saveState(out);
        }
        out.finish();
      },
      Durability::Synced);
}

CheckpointHeader loadCheckpoint(Collective every, const std::string& path, DataArchiver* outputs,
                                MPM& mpm) {
  // Read on every rank, then agreed on, before any collective step of laying the particles out.
  CheckpointHeader header;
  RankLayout::Saved layout;
  std::string error;
  try {
    header = readCheckpoint(path, outputs, mpm, layout);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  const int failed = collective::firstRankWith(every, !error.empty());
  if (failed >= 0)
    throw std::runtime_error(failed == Communicator::rank()
                                 ? error
                                 : path + ": unreadable on rank " + std::to_string(failed));
  if (header.ranks == Communicator::size()) {
    if (header.ranks > 1) mpm.layout().adopt(every, layout);
  } else if (header.ranks > 1) {
    mpm.layout().shareOutAnew(every);
  } else {
    mpm.layout().keepOwnShare(every);
  }
  return header;
}

}  // namespace anode

#include "StandAlone/Driver/DataArchiver.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <regex>
#include <sstream>

#include "Core/Util/AtomicFile.h"
#include "StandAlone/Driver/OutputLabels.h"

namespace fs = std::filesystem;

namespace anode {

DataArchiver DataArchiver::fromInput(const PSNode& a, bool diffusion) {
  DataArchiver d;
  d.filebase_ = a.get<std::string>("filebase", "output.uda");
  if (d.filebase_.empty()) a.requireChild("filebase").fail("<filebase> is empty");
  const PSNode interval = a.child("outputInterval");
  const PSNode steps = a.child("outputTimestepInterval");
  if (interval && steps) steps.fail("give <outputInterval> or <outputTimestepInterval>, not both");
  if (!interval && !steps)
    a.fail("<DataArchiver> needs <outputInterval> or <outputTimestepInterval>");
  if (interval) {
    d.interval_ = interval.value<double>();
    if (!(*d.interval_ > 0)) interval.fail("<outputInterval> must be positive");
  } else {
    d.stepInterval_ = steps.value<int>();
    if (d.stepInterval_ < 1) steps.fail("<outputTimestepInterval> must be >= 1");
  }
  for (const char* inert :
       {"outputInitTimestep", "outputLastTimestep", "compression", "outputDoubleAsFloat"})
    a.acceptInert(
        inert);  // the first and last steps are always written; files are always compressed
  for (const PSNode& save : a.children("save")) {
    const std::string label = save.requireAttribute("label");
    switch (classifyLabel(label, diffusion)) {
      case LabelStatus::Particle:
        if (label != "p.x") d.particleLabels_.push_back(label);
        break;
      case LabelStatus::Grid:
        d.gridLabels_.push_back(label);
        break;
      case LabelStatus::NeedsDiffusion:
        save.fail("<save label=\"" + label +
                  "\">: a diffusion quantity, but <do_scalar_diffusion> is off");
      case LabelStatus::Unsupported:
        save.unsupported("<save label=\"" + label + "\">: a quantity of a feature this code lacks");
        break;
      case LabelStatus::Unknown:
        save.fail("<save label=\"" + label + "\">: unknown label");
    }
  }
  return d;
}

std::string chooseOutputDirectory(const std::string& requested, const std::string& filebase) {
  if (!requested.empty()) return requested;
  if (!fs::exists(filebase)) return filebase;
  for (int v = 0; v < 1000; ++v) {
    std::ostringstream name;
    name << filebase << "." << std::setw(3) << std::setfill('0') << v;
    if (!fs::exists(name.str())) return name.str();
  }
  throw std::runtime_error("no free output directory name for " + filebase);
}

void DataArchiver::open(const std::string& dir, const std::string& inputFile) {
  dir_ = dir;
  fs::create_directories(fs::path(dir_) / "particles");
  if (wantsGrid()) fs::create_directories(fs::path(dir_) / "grid");
  writeAtomically((fs::path(dir_) / "input.ups").string(), [&](const std::string& tmp) {
    fs::copy_file(inputFile, tmp, fs::copy_options::overwrite_existing);
  });
}

bool DataArchiver::isOutputStep(long step, double time) const {
  if (stepInterval_ > 0) return step % stepInterval_ == 0;
  // The first step at or after each multiple of the interval (Uintah, UINTAH_UPS.md P21).
  const double next = (std::floor(lastOutputTime_ / *interval_ + 1e-9) + 1) * *interval_;
  return time >= next * (1 - 1e-12);
}

void DataArchiver::writeOutput(long step, double time, const MPM& mpm) {
  std::ostringstream name;
  name << "step_" << std::setw(6) << std::setfill('0') << step;
  const std::string particleFile = "particles/" + name.str() + ".vtu";
  writeParticlesVTU((fs::path(dir_) / particleFile).string(),
                    gatherParticles(mpm, particleLabels_));
  particleSeries_.add(time, particleFile);
  particleSeries_.write((fs::path(dir_) / "particles.pvd").string());
  if (wantsGrid()) {
    const std::string gridFile = "grid/" + name.str() + ".vti";
    writeGridVTI((fs::path(dir_) / gridFile).string(), gatherGrid(mpm, gridLabels_));
    gridSeries_.add(time, gridFile);
    gridSeries_.write((fs::path(dir_) / "grid.pvd").string());
  }
  lastOutputTime_ = time;
  lastOutputStep_ = step;
  writeHistory();
}

std::string DataArchiver::writeFailedState(long step, const MPM& mpm) const {
  std::ostringstream name;
  name << "particles/failed_step_" << std::setw(6) << std::setfill('0') << step << ".vtu";
  const std::string path = (fs::path(dir_) / name.str()).string();
  writeParticlesVTU(path, gatherParticles(mpm, particleLabels_));
  return path;
}

void DataArchiver::writeHistory() const {
  std::ostringstream s;
  const bool diffusion = !history_.empty() && history_.front().diffusion;
  s << "step,time,dt,particles,kinetic_energy,min_J,max_J,"
    << (diffusion ? "total_lithium,min_c,max_c," : "") << "wall_seconds\n"
    << std::setprecision(10);
  for (const HistoryRow& r : history_) {
    s << r.step << ',' << r.time << ',' << r.dt << ',' << r.particles << ',' << r.kineticEnergy
      << ',' << r.minJ << ',' << r.maxJ << ',';
    if (diffusion)
      s << r.totalLithium << ',' << r.minConcentration << ',' << r.maxConcentration << ',';
    s << r.wallSeconds << '\n';
  }
  writeFileAtomically((fs::path(dir_) / "history.csv").string(), s.str());
}

namespace {

void saveSeries(BinaryWriter& out, const PVDSeries& series) {
  out.value<uint64_t>(series.entries().size());
  for (const auto& [time, file] : series.entries()) {
    out.value(time);
    out.string(file);
  }
}

PVDSeries loadSeries(BinaryReader& in) {
  PVDSeries series;
  for (uint64_t n = in.value<uint64_t>(); n > 0; --n) {
    const double time = in.value<double>();
    series.add(time, in.string());
  }
  return series;
}

}  // namespace

void DataArchiver::saveState(BinaryWriter& out) const {
  out.value(lastOutputTime_);
  out.value(lastOutputStep_);
  saveSeries(out, particleSeries_);
  saveSeries(out, gridSeries_);
  out.array(history_);
}

void DataArchiver::loadState(BinaryReader& in) {
  lastOutputTime_ = in.value<double>();
  lastOutputStep_ = in.value<long>();
  particleSeries_ = loadSeries(in);
  gridSeries_ = loadSeries(in);
  in.array(history_);
}

void DataArchiver::removeOutputsAfter(long step) const {
  static const std::regex output(R"(step_(\d+)\.vt[ui])");
  for (const char* folder : {"particles", "grid"}) {
    const fs::path path = fs::path(dir_) / folder;
    if (!fs::is_directory(path)) continue;
    std::vector<fs::path> later;
    for (const fs::directory_entry& e : fs::directory_iterator(path)) {
      std::smatch m;
      const std::string name = e.path().filename().string();
      if (std::regex_match(name, m, output) && std::stol(m[1].str()) > step)
        later.push_back(e.path());
    }
    for (const fs::path& p : later) fs::remove(p);
  }
}

void DataArchiver::writeIndexFiles() const {
  particleSeries_.write((fs::path(dir_) / "particles.pvd").string());
  if (wantsGrid()) gridSeries_.write((fs::path(dir_) / "grid.pvd").string());
  writeHistory();
}

}  // namespace anode

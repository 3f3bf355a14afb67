#include "StandAlone/Driver/DataArchiver.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/AtomicFile.h"
#include "StandAlone/Driver/OutputLabels.h"

namespace fs = std::filesystem;

namespace anode {

namespace {

// A set of indices as Uintah writes one in an attribute: "0", "0-2", "1, 3-5", "-3--1"; empty
// means every index.
struct IndexSet {
  std::vector<std::pair<int, int>> ranges;
  bool contains(int i) const {
    if (ranges.empty()) return true;
    for (const auto& [low, high] : ranges)
      if (low <= i && i <= high) return true;
    return false;
  }
  bool containsAll(int first, int last) const {
    for (int i = first; i <= last; ++i)
      if (!contains(i)) return false;
    return true;
  }
};

IndexSet parseIndexSet(const PSNode& node, const std::string& attribute) {
  const std::string text = *node.attribute(attribute.c_str());
  static const std::regex item(R"(\s*(-?\d{1,9})\s*(?:-\s*(-?\d{1,9}))?\s*,?)");
  IndexSet set;
  auto at = text.cbegin();
  std::smatch m;
  while (at != text.cend() &&
         std::regex_search(at, text.cend(), m, item, std::regex_constants::match_continuous)) {
    const int low = std::stoi(m[1]);
    const int high = m[2].matched ? std::stoi(m[2]) : low;
    set.ranges.emplace_back(std::min(low, high), std::max(low, high));
    at = m[0].second;
  }
  if (std::string(at, text.cend()).find_first_not_of(" \t\n") != std::string::npos)
    node.fail("<save " + attribute + "=\"" + text +
              "\">: not a set of indices such as \"0\", \"0-2\" or \"1, 3-5\"");
  return set;
}

}  // namespace

DataArchiver DataArchiver::fromInput(const PSNode& a, bool diffusion, int numMaterials) {
  DataArchiver d;
  d.filebase_ = a.get<std::string>("filebase", "output.uda");
  if (d.filebase_.empty()) a.requireChild("filebase").fail("<filebase> is empty");
  const PSNode interval = a.child("outputInterval");
  const PSNode steps = a.child("outputTimestepInterval");
  // Absent or 0 (Uintah's default) asks for no periodic output: only the first and last steps.
  const double t = interval ? interval.value<double>() : 0.0;
  if (!(t >= 0)) interval.fail("<outputInterval> must be >= 0");
  d.stepInterval_ = steps ? steps.value<int>() : 0;
  if (d.stepInterval_ < 0) steps.fail("<outputTimestepInterval> must be >= 0");
  if (t > 0 && d.stepInterval_ > 0)
    steps.fail("give <outputInterval> or <outputTimestepInterval> above 0, not both");
  if (t > 0) d.interval_ = t;
  if (const PSNode normal = a.child("film_normal")) {
    const std::string axis = normal.value<std::string>();
    if (axis != "x" && axis != "y" && axis != "z")
      normal.fail("<film_normal> must be x, y or z, found \"" + axis + "\"");
    d.filmNormal_ = axis[0] - 'x';
  }
  for (const char* inert :
       {"outputInitTimestep", "outputLastTimestep", "compression", "outputDoubleAsFloat"})
    a.acceptInert(
        inert);  // the first and last steps are always written; files are always compressed
  for (const PSNode& save : a.children("save")) {
    const std::string label = save.requireAttribute("label");
    for (const std::string& attribute : save.attributeNames()) {
      if (attribute == "label" || attribute == "compression") continue;  // always compressed
      if (attribute != "material" && attribute != "levels")
        save.fail("<save>: unknown attribute " + attribute +
                  "; accepted: label, compression, material, levels");
      const IndexSet set = parseIndexSet(save, attribute);
      // Uintah's "levels" counts negative values from the finest level: -1 is the only one here.
      const bool everything = attribute == "material" ? set.containsAll(0, numMaterials - 1)
                                                      : set.contains(0) || set.contains(-1);
      if (!everything)
        save.unsupported("<save " + attribute + "=\"" + *save.attribute(attribute.c_str()) +
                         "\">: saving a label for some materials or levels only (every "
                         "material of the one level is written)");
    }
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

bool DataArchiver::savesConcentrationFields() const {
  return std::any_of(gridLabels_.begin(), gridLabels_.end(), isNodalConcentrationLabel) ||
         std::find(particleLabels_.begin(), particleLabels_.end(), "p.concentrationGradient") !=
             particleLabels_.end();
}

StepRecord stepRecord(const StepSummary& s, int dtRule, const StepCounts& counts, bool trapezoidal,
                      const TimestepController::ErrorControl* error) {
  StepRecord record;
  record.elasticEnergy = s.elasticEnergy;
  record.dtRule = dtRule;
  record.newtonIterations = counts.newtonIterations;
  record.krylovIterations = counts.krylovIterations;
  record.electrodePotentials = s.electrodePotentials;
  if (trapezoidal && s.diffusion && s.lithiumCapacity > 0)
    record.couplingCorrection = std::max(0.0, counts.couplingCorrection) / s.lithiumCapacity;
  if (error && s.diffusion) {
    record.errorEstimate = std::max(0.0, counts.errorEstimate);
    record.accumulatedErrorEstimate = std::max(0.0, counts.accumulatedErrorEstimate);
    record.rejectedAttempts = std::max(0, counts.rejectedAttempts);
  }
  return record;
}

const char* dtRuleName(int rule) {
  if (rule >= 0 && rule < kDtSetByTimeControl)
    return StableTimestep::name(static_cast<StableTimestep::Limit>(rule));
  if (rule == kDtDiffusionPassCap) return StableTimestep::name(StableTimestep::DiffusionPassCap);
  if (rule == kDtErrorEstimate) return StableTimestep::name(StableTimestep::ErrorEstimate);
  if (rule == kDtSetByTimeControl)
    return "time control (<delt_max>, <delt_init>, <delt_min>, <max_delt_increase>, <maxTime>, "
           "<clamp_time_to_output>)";
  if (rule == kDtRetaken)
    return "retaken with a smaller dt (Newton did not converge, c changed too much, the diffusion "
           "pass needed more sub-steps than its cap, or the error estimate was above the "
           "tolerance)";
  return "unknown";
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

void DataArchiver::open(Collective every, const std::string& dir, const std::string& inputFile) {
  dir_ = dir;
  if (Communicator::isRoot()) {
    fs::create_directories(fs::path(dir_) / "particles");
    if (wantsGrid()) fs::create_directories(fs::path(dir_) / "grid");
    writeAtomically((fs::path(dir_) / "input.ups").string(), [&](const std::string& tmp) {
      fs::copy_file(inputFile, tmp, fs::copy_options::overwrite_existing);
    });
  }
  collective::barrier(every);
}

namespace {

std::string stepName(const char* prefix, long step) {
  std::ostringstream name;
  name << prefix << std::setw(6) << std::setfill('0') << step;
  return name.str();
}

std::string pieceName(const std::string& base, int rank, const char* extension) {
  std::ostringstream name;
  name << base << ".r" << std::setw(4) << std::setfill('0') << rank << extension;
  return name.str();
}

// 'I' or 'F' per array: the types of a rank's arrays (all integer-looking when it holds none).
std::string arrayTypes(const std::vector<NamedArray>& arrays) {
  std::string t;
  for (const NamedArray& a : arrays) t += a.isInteger() ? 'I' : 'F';
  return t;
}

}  // namespace

std::string DataArchiver::writeParticles(Collective every, const std::string& base,
                                         const ParticleData& data) const {
  if (Communicator::size() == 1) {
    writeParticlesVTU((fs::path(dir_) / (base + ".vtu")).string(), data);
    return base + ".vtu";
  }
  // The pieces of the ranks holding particles (rank 0's when none does), then the .pvtu: every
  // piece is in place when the gather returns.
  const bool anyHeld = collective::any(every, data.count() > 0);
  const bool writes = data.count() > 0 || (!anyHeld && Communicator::isRoot());
  if (writes)
    writeParticlesVTU((fs::path(dir_) / pieceName(base, Communicator::rank(), ".vtu")).string(),
                      data);
  const std::vector<std::string> types =
      collective::allGather(every, writes ? "+" + arrayTypes(data.arrays) : "");
  if (Communicator::isRoot()) {
    std::vector<std::string> pieces;
    ParticleData sample;
    for (int r = 0; r < Communicator::size(); ++r) {
      if (types[r].empty()) continue;
      pieces.push_back(fs::path(pieceName(base, r, ".vtu")).filename().string());
      if (!sample.arrays.empty() || types[r].size() != data.arrays.size() + 1) continue;
      for (size_t a = 0; a < data.arrays.size(); ++a) {
        NamedArray& typed = sample.arrays.emplace_back();
        typed.name = data.arrays[a].name;
        typed.components = data.arrays[a].components;
        if (types[r][a + 1] == 'F') typed.real = {0.0};
      }
    }
    writeParticlesPVTU((fs::path(dir_) / (base + ".pvtu")).string(), pieces, sample);
  }
  return base + ".pvtu";
}

std::string DataArchiver::writeGrid(Collective every, const std::string& base,
                                    const GridData& data) const {
  if (Communicator::size() == 1) {
    writeGridVTI((fs::path(dir_) / (base + ".vti")).string(), data);
    return base + ".vti";
  }
  writeGridVTI((fs::path(dir_) / pieceName(base, Communicator::rank(), ".vti")).string(), data);
  std::ostringstream extent;
  for (int d = 0; d < 3; ++d)
    extent << data.first[d] << " " << data.first[d] + data.dims[d] - 1 << " ";
  const std::vector<std::string> extents = collective::allGather(every, extent.str());
  if (Communicator::isRoot()) {
    std::vector<std::string> pieces;
    std::vector<std::array<int, 6>> pieceExtents;
    std::array<int, 6> whole{0, 0, 0, 0, 0, 0};
    for (int r = 0; r < Communicator::size(); ++r) {
      pieces.push_back(fs::path(pieceName(base, r, ".vti")).filename().string());
      std::istringstream in(extents[r]);
      std::array<int, 6>& e = pieceExtents.emplace_back();
      for (int& v : e) in >> v;
      for (int d = 0; d < 3; ++d) whole[2 * d + 1] = std::max(whole[2 * d + 1], e[2 * d + 1]);
    }
    writeGridPVTI((fs::path(dir_) / (base + ".pvti")).string(), pieces, pieceExtents, whole, data);
  }
  return base + ".pvti";
}

bool DataArchiver::isOutputStep(long step, double time) const {
  if (stepInterval_ > 0) return step % stepInterval_ == 0;
  if (!interval_) return false;
  // The first step at or after each multiple of the interval (Uintah, UINTAH_UPS.md P21).
  return time >= *nextOutputTimeAfter(lastOutputTime_) * (1 - 1e-12);
}

std::string chargeText(double stateOfCharge) {
  char text[64];
  std::snprintf(text, sizeof text, "%.2f%% = %.0f mAh/g", 100 * stateOfCharge,
                stateOfCharge * kSiliconCapacityAtFull);
  return text;
}

std::optional<double> DataArchiver::nextOutputTimeAfter(double time) const {
  if (!outputsByTime()) return std::nullopt;
  return (std::floor(time / *interval_ + 1e-9) + 1) * *interval_;
}

void DataArchiver::writeOutput(Collective every, long step, double time, const MPM& mpm) {
  const std::string name = stepName("step_", step);
  const std::string particleFile =
      writeParticles(every, "particles/" + name, gatherParticles(mpm, particleLabels_));
  particleSeries_.add(time, particleFile);
  if (Communicator::isRoot()) particleSeries_.write((fs::path(dir_) / "particles.pvd").string());
  if (wantsGrid()) {
    const std::string gridFile = writeGrid(every, "grid/" + name, gatherGrid(mpm, gridLabels_));
    gridSeries_.add(time, gridFile);
    if (Communicator::isRoot()) gridSeries_.write((fs::path(dir_) / "grid.pvd").string());
  }
  lastOutputTime_ = time;
  lastOutputStep_ = step;
  writeHistory();
}

std::string DataArchiver::writeFailedState(Collective every, long step, const MPM& mpm) const {
  const std::string file = writeParticles(every, "particles/" + stepName("failed_step_", step),
                                          gatherParticles(mpm, particleLabels_));
  return (fs::path(dir_) / file).string();
}

void DataArchiver::setMaterialColumns(const std::vector<MPMMaterial>& materials, const Grid& grid) {
  if (filmNormal_ >= 0) {
    const Vec3 extent = grid.upper - grid.lower;
    filmArea_ = extent.prod() / extent[filmNormal_];
  }

  const auto column = [](std::string name) {
    for (char& ch : name)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
    return name;
  };
  materialColumns_.clear();
  for (size_t m = 0; m < materials.size(); ++m) {
    const std::string name = column(materials[m].name);
    const bool shared = std::count_if(materials.begin(), materials.end(), [&](const auto& other) {
                          return column(other.name) == name;
                        }) > 1;
    materialColumns_.push_back(name.empty() || shared ? "material" + std::to_string(m) : name);
  }
}

void DataArchiver::writeHistory() {
  if (!Communicator::isRoot() || unwritten_.empty()) {
    unwritten_.clear();
    return;
  }
  std::ostringstream s;
  if (!historyStarted_) {
    s << "step,time,dt,particles,kinetic_energy,min_J,max_J,";
    if (unwritten_.front().row.diffusion) {
      s << "total_lithium,min_c,max_c,lithium_rate,state_of_charge,capacity_mAh_g,";
      for (const auto& [bc, phi] : unwritten_.front().record.electrodePotentials)
        s << "potential_" << bc << ',';
      for (const StepSummary::MaterialLithium& m : unwritten_.front().perMaterial) {
        const std::string& name = materialColumns_[m.material];
        s << "lithium_" << name << ",min_c_" << name << ",max_c_" << name << ',';
      }
    }
    for (size_t m = 0; m < unwritten_.front().stress.size(); ++m) {
      const std::string& name = materialColumns_[m];
      s << "volume_" << name;
      for (const char* component : {"sxx", "syy", "szz", "syz", "sxz", "sxy"})
        s << ",mean_" << component << '_' << name;
      s << ",mean_pressure_" << name << ",mean_von_mises_" << name << ',';
      if (unwritten_.front().stress[m].yields)
        s << "plastic_work_" << name << ",plastic_work_rate_" << name << ',';
      if (filmNormal_ >= 0) s << "stress_thickness_" << name << ',';
    }
    s << "elastic_energy,dt_limit,";
    if (unwritten_.front().record.newtonIterations >= 0)
      s << "newton_iterations,krylov_iterations,";
    if (unwritten_.front().record.couplingCorrection >= 0) s << "coupling_correction,";
    if (unwritten_.front().record.errorEstimate >= 0)
      s << "error_estimate,accumulated_error_estimate,rejected_attempts,";
    s << "wall_seconds\n";
  }
  s << std::setprecision(10);
  for (const auto& [r, record, perMaterial, stress, plasticWork] : unwritten_) {
    s << r.step << ',' << r.time << ',' << r.dt << ',' << r.particles << ',' << r.kineticEnergy
      << ',' << r.minJ << ',' << r.maxJ << ',';
    if (r.diffusion) {
      s << r.totalLithium << ',' << r.minConcentration << ',' << r.maxConcentration << ','
        << r.lithiumRate << ',' << r.stateOfCharge << ','
        << r.stateOfCharge * kSiliconCapacityAtFull << ',';
      for (const auto& [bc, phi] : record.electrodePotentials) s << phi << ',';
      for (const StepSummary::MaterialLithium& m : perMaterial)
        s << m.lithium << ',' << m.minConcentration << ',' << m.maxConcentration << ',';
    }
    for (size_t m = 0; m < stress.size(); ++m) {
      const StepSummary::MaterialStress& st = stress[m];
      const double V = st.volume > 0 ? st.volume : std::numeric_limits<double>::quiet_NaN();
      s << st.volume;
      for (double integral : st.stressIntegral) s << ',' << integral / V;
      const double mean =
          (st.stressIntegral[0] + st.stressIntegral[1] + st.stressIntegral[2]) / (3 * V);
      s << ',' << -mean << ',' << st.vonMisesIntegral / V << ',';
      if (st.yields) s << plasticWork[m] << ',' << st.plasticWorkRate << ',';
      if (filmNormal_ >= 0) {
        // The in-plane mean stress times the thickness: sum V (sigma_a + sigma_b) / 2 over the
        // plan area, a and b the axes across the normal.
        const int a = (filmNormal_ + 1) % 3, b = (filmNormal_ + 2) % 3;
        s << 0.5 * (st.stressIntegral[a] + st.stressIntegral[b]) / filmArea_ << ',';
      }
    }
    s << record.elasticEnergy << ',' << record.dtRule << ',';
    if (record.newtonIterations >= 0)
      s << record.newtonIterations << ',' << record.krylovIterations << ',';
    if (record.couplingCorrection >= 0) s << record.couplingCorrection << ',';
    if (record.errorEstimate >= 0)
      s << record.errorEstimate << ',' << record.accumulatedErrorEstimate << ','
        << record.rejectedAttempts << ',';
    s << r.wallSeconds << '\n';
  }
  const std::string path = (fs::path(dir_) / "history.csv").string();
  std::ofstream file(path, historyStarted_ ? std::ios::app : std::ios::trunc);
  file << s.str() << std::flush;
  if (!file) throw std::runtime_error(path + ": cannot write the history");
  historyStarted_ = true;
  unwritten_.clear();
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
  // The row's bytes with its padding (after `diffusion`) zero: a row built on the stack carries
  // there whatever the stack held, and a checkpoint's bytes are to depend on the state only.
  HistoryRow row = lastRow_;
  const size_t padding = offsetof(HistoryRow, diffusion) + sizeof row.diffusion;
  std::memset(reinterpret_cast<unsigned char*>(&row) + padding, 0,
              offsetof(HistoryRow, totalLithium) - padding);
  out.value(row);
  out.value<uint64_t>(plasticWork_.size());
  for (double w : plasticWork_) out.value(w);
}

void DataArchiver::loadState(BinaryReader& in) {
  lastOutputTime_ = in.value<double>();
  lastOutputStep_ = in.value<long>();
  particleSeries_ = loadSeries(in);
  gridSeries_ = loadSeries(in);
  lastRow_ = in.value<HistoryRow>();
  plasticWork_.resize(in.value<uint64_t>());
  for (double& w : plasticWork_) w = in.value<double>();
  unwritten_.clear();
}

namespace {

// history.csv without the rows after `step` (and without a last line a kill cut short); returns
// an error message, empty on success.
// The rows of history.csv at `path` up to `step` into `kept`; an error message (empty: none).
std::string historyUpTo(const std::string& path, long step, std::string& kept) {
  std::ifstream in(path);
  std::string header;
  if (!std::getline(in, header))
    return path + ": missing or empty; a restart continues the history its run wrote";
  const auto fields = std::count(header.begin(), header.end(), ',');
  kept = header + '\n';
  std::string line;
  while (std::getline(in, line) && !in.eof()) {  // a last line with no newline was cut short
    char* end = nullptr;
    const long rowStep = std::strtol(line.c_str(), &end, 10);
    if (std::count(line.begin(), line.end(), ',') != fields || *end != ',' || rowStep > step) break;
    kept += line + '\n';
  }
  return "";
}

}  // namespace

void DataArchiver::restoreOutputsTo(Collective every, long step) {
  unwritten_.clear();
  historyStarted_ = true;
  // On rank 0: history.csv read, then the .pvd files and history.csv written (each replaced
  // whole), and only then the outputs after the checkpoint removed, so that an error (a file
  // that cannot be read or written) stops the restart with every output file kept. Its errors
  // reach every rank.
  collective::onRootTogether(
      every,
      [&] {
        const std::string history = (fs::path(dir_) / "history.csv").string();
        std::string kept;
        const std::string error = historyUpTo(history, step, kept);
        if (error.empty()) {
          writeIndexFiles();
          writeFileAtomically(history, kept);
          removeOutputFilesAfter(step);
        }
        return error;
      },
      "rank 0 could not restore the outputs");
}

void DataArchiver::removeOutputFilesAfter(long step) const {
  static const std::regex output(R"(step_(\d+)(\.r\d+)?\.p?vt[ui])");
  for (const char* folder : {"particles", "grid"}) {
    const fs::path path = fs::path(dir_) / folder;
    if (!fs::is_directory(path)) continue;
    const PVDSeries& series = std::string(folder) == "grid" ? gridSeries_ : particleSeries_;
    const bool seriesHasStep =
        !series.entries().empty() &&
        fs::path(series.entries().back().second).stem() == stepName("step_", step);
    std::vector<fs::path> later;
    for (const fs::directory_entry& e : fs::directory_iterator(path)) {
      std::smatch m;
      const std::string name = e.path().filename().string();
      if (!std::regex_match(name, m, output)) continue;
      const long fileStep = std::stol(m[1].str());
      if (fileStep > step || (fileStep == step && !seriesHasStep)) later.push_back(e.path());
    }
    for (const fs::path& p : later) fs::remove(p);
  }
}

void DataArchiver::writeIndexFiles() {
  for (auto [series, name] : {std::pair{&particleSeries_, "particles"}, {&gridSeries_, "grid"}})
    if (const size_t missing = series->dropMissing(dir_))
      std::fprintf(
          stderr,
          "sus: %zu %s output(s) of the checkpoint's series are not in %s: left out of %s.pvd\n",
          missing, name, dir_.c_str(), name);
  particleSeries_.write((fs::path(dir_) / "particles.pvd").string());
  if (wantsGrid()) gridSeries_.write((fs::path(dir_) / "grid.pvd").string());
}

}  // namespace anode

// <DataArchiver> (UINTAH_UPS.md §2.3, DESIGN.md §6): what is saved, when, and where.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"
#include "Components/MPM/StableTimestep.h"
#include "Components/MPM/TimestepController.h"
#include "Core/Util/BinaryStream.h"
#include "vis/VTKWriters.h"

namespace anode {

struct HistoryRow {
  long step;
  size_t particles;
  double time, dt, kineticEnergy, minJ, maxJ, wallSeconds;
  bool diffusion;
  double totalLithium, minConcentration, maxConcentration;
  // d(total lithium)/dt over the step (the current, in lithium per time), and the state of
  // charge: sum m c / sum m c_max over the materials whose c can change.
  double lithiumRate, stateOfCharge;
};

// What history.csv gives of a step besides its state: the elastic energy (StepSummary), the
// rule that set dt (a DtRule) and, for an implicit step, its Newton and Krylov iterations. Not
// kept in checkpoints (a restart needs none of it).
struct StepRecord {
  double elasticEnergy = 0;
  int dtRule = 0;
  // Of the attempt kept (a retaken step's earlier attempts are in the end summary's totals
  // only); -1: an explicit run (no columns).
  int newtonIterations = -1, krylovIterations = -1;
  // A trapezoidal quasi-static step's coupling correction over the capacity of the materials
  // whose c changes (MPM::NewtonCounts::lastCouplingCorrection; 0 before the first step); -1:
  // no column.
  double couplingCorrection = -1;
  // With <error_tolerance>: the step's error estimate (ImplicitStep's), the particles' largest
  // accumulated estimate up to it, and the attempts rejected before it was taken; -1: no columns.
  double errorEstimate = -1, accumulatedErrorEstimate = -1;
  int rejectedAttempts = -1;
  // Per <scalar_flux> with a <surface_reaction>: its number and the electrode's potential (V),
  // history.csv's potential_N.
  std::vector<std::pair<int, double>> electrodePotentials;
};

// The record of a step from its summary and its integrator's counts: with diffusion, the coupling
// correction over the capacity (`trapezoidal` quasi-static steps) and the error estimates
// (`error`: the controller's state under <error_tolerance>, else null); 0 in row 0.
StepRecord stepRecord(const StepSummary& s, int dtRule, const StepCounts& counts, bool trapezoidal,
                      const TimestepController::ErrorControl* error);

// history.csv's dt_limit: StableTimestep::Limit's codes (0 mechanics, Eq. 43; 1 diffusion, Eq.
// 44; 2 flux restriction; 3 Newton iterations; 4 change of c per step), then these four (the
// limits after the two older codes, which keep their numbers).
enum DtRule {
  kDtSetByTimeControl = StableTimestep::DiffusionPassCap,  // <delt_max>, <delt_init>, <delt_min>,
                                                           // <max_delt_increase>, the end at
                                                           // <maxTime>, or <clamp_time_to_output>
  kDtRetaken,           // an implicit step retaken with a smaller dt (Newton did not converge, or c
                        // changed by more than twice <max_concentration_change>, or its diffusion
                        // pass needed more than its cap of sub-steps, or its error estimate was
                        // above <error_tolerance>)
  kDtDiffusionPassCap,  // StableTimestep::DiffusionPassCap
  kDtErrorEstimate,     // StableTimestep::ErrorEstimate
  kDtRules
};
// The code of a limit.
inline int dtRule(StableTimestep::Limit limit) {
  if (limit == StableTimestep::DiffusionPassCap) return kDtDiffusionPassCap;
  if (limit == StableTimestep::ErrorEstimate) return kDtErrorEstimate;
  return limit;
}
// The rule's name, as the end summary and report.html write it.
const char* dtRuleName(int rule);

// The specific capacity at c = max_concentration of silicon normalised as the paper (c = 1 at
// Li15Si4, 3.75 Li per Si): 3.75 F / M_Si, in mAh per gram of silicon.
constexpr double kSiliconCapacityAtFull = 3.75 * 96485.33212 / 28.0855 / 3.6;
// "56.30% = 2011 mAh/g": the state of charge as the progress line shows it.
std::string chargeText(double stateOfCharge);

class DataArchiver {
 public:
  // Reads the block and checks every saved label against what the run computes.
  static DataArchiver fromInput(const PSNode& archiver, bool diffusion, int numMaterials);

  const std::string& filebase() const { return filebase_; }
  bool wantsGrid() const { return !gridLabels_.empty(); }
  // Whether it saves what the materials that take up no lithium do not compute unless asked
  // (ReactiveFlow::computesConcentration): a nodal concentration (g.concentration*) or
  // p.concentrationGradient.
  bool savesConcentrationFields() const;

  // Creates the output directory and copies the input into it.
  void open(Collective, const std::string& dir, const std::string& inputFile);
  // Continues in the directory of an earlier run (restart): loadState then sets the series.
  void reopen(const std::string& dir) { dir_ = dir; }
  const std::string& directory() const { return dir_; }

  // True if the step that ended at `time` (number `step`) is an output step.
  bool isOutputStep(long step, double time) const;
  // Outputs fall at times (<outputInterval>), not every N steps.
  bool outputsByTime() const { return stepInterval_ == 0 && interval_.has_value(); }
  // With <outputInterval>: the first multiple of the interval after `time` (a multiple within
  // round-off of it excluded).
  std::optional<double> nextOutputTimeAfter(double time) const;
  // Writes particles (and grid, if asked) for this state and records it in the .pvd series; in a
  // distributed run every rank writes its piece and rank 0 the .pvtu (.pvti) over them, then the
  // .pvd.
  void writeOutput(Collective, long step, double time, const MPM& mpm);
  // The step of the last writeOutput (-1 before the first).
  long lastOutputStep() const { return lastOutputStep_; }
  // Writes the particles of a step that failed a check to particles/failed_step_NNNNNN.vtu (or
  // .pvtu), outside the .pvd series; returns that path.
  std::string writeFailedState(Collective, long step, const MPM& mpm) const;
  // The names of history.csv's per-material columns (lithium_NAME, min_c_NAME, max_c_NAME),
  // which the materials of the first row's perMaterial have, in its order. NAME is the material's
  // name attribute with characters other than letters, digits, '-' and '_' as '_', or
  // "material<index>" when it has none or another material's comes out the same.
  // The per-material stress columns (volume_NAME, mean_sxx_NAME ... mean_sxy_NAME,
  // mean_pressure_NAME, mean_von_mises_NAME; plastic_work_NAME and plastic_work_rate_NAME for a
  // material that yields; with <film_normal> stress_thickness_NAME) take the same names; the
  // grid's plan area across <film_normal> is the film's.
  void setMaterialColumns(const std::vector<MPMMaterial>& materials, const Grid& grid);
  // A step's row: its state, its record, and the summary's per-material lithium and stress; the
  // plastic work accumulates the step's rate times its dt.
  void recordHistory(const HistoryRow& row, const StepRecord& record,
                     std::vector<StepSummary::MaterialLithium> perMaterial = {},
                     std::vector<StepSummary::MaterialStress> stress = {}) {
    plasticWork_.resize(std::max(plasticWork_.size(), stress.size()), 0.0);
    for (size_t m = 0; m < stress.size(); ++m)
      plasticWork_[m] += stress[m].plasticWorkRate * row.dt;
    unwritten_.push_back({row, record, std::move(perMaterial), std::move(stress), plasticWork_});
    lastRow_ = row;
  }
  // Appends the rows recorded since the last call to history.csv (the header first), so a long
  // run's history costs neither memory nor checkpoint space in proportion to its steps. The file
  // grows in whole lines; a kill during the append can cut its last line short, and a restart
  // drops every row after its checkpoint's step (restoreOutputsTo).
  void writeHistory();
  const HistoryRow& lastHistoryRow() const { return lastRow_; }

  // The output schedule, the .pvd series and the last history row, for checkpoints: history.csv
  // holds the rows up to the checkpoint's step (Simulation writes it first).
  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in);
  // A restart from the checkpoint at `step` (loadState first), on rank 0: removes what the
  // interrupted run wrote beyond it, the history rows after `step` (history.csv is rewritten
  // whole, atomically, once, before any file is removed), the particle and grid files of later
  // steps and those of `step` itself that the checkpoint's series lacks (a stop's output, written
  // after its checkpoint); then writes the .pvd files as the state has them. An error stops the
  // restart on every rank, before any output is removed when it is history.csv's.
  void restoreOutputsTo(Collective, long step);

 private:
  // The particle and grid files restoreOutputsTo removes.
  void removeOutputFilesAfter(long step) const;
  // The .pvd files as the state has them: outputs the interrupted run wrote after its checkpoint
  // leave the series (the continued run writes them again under the same names), and so do
  // outputs whose files are gone (removed by hand, or not carried with the checkpoint to another
  // machine), with a note of how many.
  void writeIndexFiles();
  // This rank's particles (grid nodes) under `base` (relative to the directory): base.vtu on one
  // rank, else its piece base.rNNNN.vtu and, from rank 0, base.pvtu; returns the file to list.
  std::string writeParticles(Collective, const std::string& base, const ParticleData& data) const;
  std::string writeGrid(Collective, const std::string& base, const GridData& data) const;

  std::string filebase_;
  std::optional<double> interval_;
  long stepInterval_ = 0;
  std::vector<std::string> particleLabels_, gridLabels_;
  std::string dir_;
  double lastOutputTime_ = 0;
  long lastOutputStep_ = -1;
  PVDSeries particleSeries_, gridSeries_;
  struct UnwrittenRow {
    HistoryRow row;
    StepRecord record;
    std::vector<StepSummary::MaterialLithium> perMaterial;
    std::vector<StepSummary::MaterialStress> stress;
    std::vector<double> plasticWork;  // per material, up to the row's step
  };
  std::vector<UnwrittenRow> unwritten_;  // recorded, not yet in history.csv
  std::vector<std::string> materialColumns_;
  HistoryRow lastRow_{};
  // Per material, sum over the steps of the plastic work rate times dt (in the checkpoints).
  std::vector<double> plasticWork_;
  int filmNormal_ = -1;          // <film_normal>: 0, 1, 2 for x, y, z; -1 none
  double filmArea_ = 0;          // the grid's plan area across it
  bool historyStarted_ = false;  // history.csv exists with its header
};

// Chooses the output directory: `requested` if given, else the filebase, versioned .000, .001, ...
// when it already exists.
std::string chooseOutputDirectory(const std::string& requested, const std::string& filebase);

}  // namespace anode

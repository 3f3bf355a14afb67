// The run's side of the scenes of <Visualization> (DESIGN.md §7): read and checked in setup,
// rendered when the simulation crosses each scene time (the step is not shortened for it), into
// DIR/images/<scene>_<time>.png. An input without scenes creates no renderer and no OSMesa context.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/MPM.h"
#include "Core/Grid/TimeControl.h"
#include "vis/SceneSpec.h"

namespace anode {

class SceneRenderer;

class SceneOutput {
 public:
  SceneOutput();
  ~SceneOutput();
  SceneOutput(SceneOutput&&) noexcept;
  SceneOutput& operator=(SceneOutput&&) noexcept;

  // Reads <Visualization> if the input has one; checks every scene against the run.
  static SceneOutput fromInput(const PSNode& root, const TimeControl& time, const MPM& mpm);

  // Renders every scene time in (last call's time, t]; at the first call, every time <= t.
  void renderDue(Collective, double t, MPM& mpm, const std::string& outputDir);
  // Marks every scene time <= t as rendered (a restarted run rendered them before).
  void skipTimesUpTo(double t);
  int imagesWritten() const { return imagesWritten_; }
  // Whether a scene colours its particles by `label` (a particle array).
  bool draws(const std::string& label) const;

 private:
  std::vector<Scene> scenes_;
  std::vector<std::vector<double>> times_;  // per scene, ascending
  std::vector<size_t> next_;                // per scene: the first time not rendered yet
  std::unique_ptr<SceneRenderer> renderer_;
  int imagesWritten_ = 0;
};

}  // namespace anode

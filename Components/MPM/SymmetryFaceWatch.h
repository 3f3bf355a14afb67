// A body that grows into a Symmetric face it did not start on is squashed there without a word:
// the face holds the normal velocity at zero, as a frictionless wall would. This watch says so:
// at setup, a note for each material whose bodies' free swelling (exp(eta) per axis at c = 1)
// would carry them into such a face (SwellingRoom.h); during the run, a warning the first time a
// material reaches one.
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/MPM.h"

namespace anode {

class SymmetryFaceWatch {
 public:
  // Finds the Symmetric faces each material starts on (a particle within one cell of the face)
  // and returns setup's notes on bodies that would swell into the others (SwellingRoom.h).
  std::vector<std::string> start(Collective, const MPM& mpm);
  // The warnings of the step that ended at (step, t): a material's particle within one cell of
  // a Symmetric face it did not start on, once per face and material.
  std::vector<std::string> afterStep(Collective, const MPM& mpm, long step, double t);

 private:
  struct Face {
    size_t material;
    int axis, side;
  };
  std::vector<Face> watched_;
};

}  // namespace anode

// Colour maps of the scenes: a vtkColorTransferFunction through the map's control points,
// sampled into a 256-entry vtkLookupTable that both the sprites (as a texture) and the colour
// bar use, so the picture and its legend agree exactly.
#pragma once

#include <vtkLookupTable.h>
#include <vtkSmartPointer.h>

#include <array>
#include <vector>

#include "vis/SceneSpec.h"

namespace anode {

class ColourMap {
 public:
  static constexpr int kEntries = 256;

  explicit ColourMap(ColourMapKind kind);
  // The colour (r, g, b in [0, 1]) at a fraction t of the range; t is clamped to [0, 1].
  std::array<double, 3> colour(double t) const;
  // The table as 8-bit RGBA, kEntries entries.
  std::vector<unsigned char> rgba8() const;

 private:
  vtkSmartPointer<vtkLookupTable> table_;
};

}  // namespace anode

// A square sparse matrix of 3x3 blocks, rows of blocks in compressed form (one block row per
// unknown node): the stiffness of the equilibrium step, assembled here and handed to PETSc.
#pragma once

#include <algorithm>
#include <vector>

#include "Core/Math/Types.h"

namespace anode {

struct BlockMatrix {
  std::vector<int> rowStart{0};  // block row r holds entries [rowStart[r], rowStart[r + 1])
  std::vector<int> column;       // sorted within each row
  std::vector<Mat3> block;

  int rows() const { return static_cast<int>(rowStart.size()) - 1; }
  // The index of the block (r, c), which the pattern must hold.
  int indexOf(int r, int c) const {
    const auto first = column.begin() + rowStart[r], last = column.begin() + rowStart[r + 1];
    return static_cast<int>(std::lower_bound(first, last, c) - column.begin());
  }
  Mat3& at(int r, int c) { return block[indexOf(r, c)]; }
  void clearValues() { std::fill(block.begin(), block.end(), Mat3::Zero()); }
};

}  // namespace anode

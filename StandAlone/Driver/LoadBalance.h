// A distributed run's balance of particles over its ranks: the boxes are drawn anew (at an output
// step) when the particles per rank, max over mean, have grown by a factor since they were drawn.
#pragma once

#include "Core/Parallel/Communicator.h"

namespace anode {

class MPM;

// A distributed run draws its boxes anew (at an output step) when the particles per rank, max
// over mean, have grown by this factor since the boxes were drawn. An implicit step costs seconds
// of Newton and linear solves and a redraw milliseconds, so implicit runs redraw sooner (Figure
// 4's swelling pillar on 2 ranks: its particles crossed a cut across the axis until one rank
// held 1.5 times the other's, and the solves ran at half speed).
constexpr double kRebalanceImbalance = 1.2, kRebalanceImbalanceImplicit = 1.05;

class LoadBalance {
 public:
  // The boxes the run starts with: returns their particles per rank (max/mean).
  double start(Collective, const MPM& mpm);
  // At an output step of a distributed run, after `step`: draws the boxes anew from the particle
  // counts when the particles per rank (max/mean) grew by kRebalanceImbalance (implicit runs:
  // kRebalanceImbalanceImplicit) since they were drawn; true if it did.
  bool rebalance(Collective, MPM& mpm, long step);

 private:
  double layoutImbalance_ = 1;  // particles per rank, max/mean, when the boxes were drawn
};

}  // namespace anode

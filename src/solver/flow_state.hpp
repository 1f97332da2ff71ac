#pragma once
// The velocity (staggered faces) and pressure (cell centres) on the local slab.
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "kernels/time_update.hpp"

namespace eulerfsi {

struct FlowState {
  kernels::Velocity vel;  // u on x-faces, v on y-faces, w on z-faces
  Field3 p;               // pressure (the projection potential) at cell centres

  explicit FlowState(const Grid& g)
      : vel{{g.make_field("u"), g.make_field("v"), g.make_field("w")}}, p(g.make_field("p")) {}
  Field3 u() const { return vel.c[0]; }
  Field3 v() const { return vel.c[1]; }
  Field3 w() const { return vel.c[2]; }
};

// The pipe wall as a penalization mask at each velocity component's location (empty if none).
struct WallMasks {
  kernels::Mask2 chi[3];
};

}  // namespace eulerfsi

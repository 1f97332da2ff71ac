#pragma once
// The velocity (staggered faces) and pressure (cell centres) on the local slab.
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "kernels/time_update.hpp"

namespace eulerfsi {

struct FlowState {
  kernels::Velocity vel;  // u on x-faces, v on y-faces, w on z-faces
  Field3 p;               // pressure (the projection potential) at cell centres
  // The last step's mean pressure sum_s alpha_s p_s (ghosts included): the projections changed u
  // by exactly -dt grad p_step over that step (p alone is the last substep's, an extrapolation).
  Field3 p_step;

  explicit FlowState(const Grid& g)
      : vel{{g.make_field("u"), g.make_field("v"), g.make_field("w")}}, p(g.make_field("p")),
        p_step(g.make_field("p_step")) {}
  Field3 u() const { return vel.c[0]; }
  Field3 v() const { return vel.c[1]; }
  Field3 w() const { return vel.c[2]; }
};

// The pipe wall at each velocity component's staggered location (all empty without a pipe).
struct WallMasks {
  kernels::Mask2 chi[3];          // 1 where the component is penalized
  kernels::Mask2 weight[3];       // interpolated wall: the target's weight on the inner neighbour
  kernels::Offset2 neighbour[3];  // interpolated wall: (dj, dk) of that neighbour
  kernels::Mask2 chi_wall[3];     // interpolated wall: 1 where the target is u_wall itself (outside the pipe)
  kernels::WallLayer layer[3];    // interpolated wall: the (j, k) of the forced first fluid layer
  kernels::Mask2 outside_u;       // 1 at the x-faces outside the pipe (r >= R): no flow rate there
  kernels::Mask2 open_u;          // share of the flow-rate correction each x-face takes (1 - chi + chi weight)
};

}  // namespace eulerfsi

#pragma once
// Ghost layers of every field: x by the periodic halo exchange across ranks, then y and z by
// the geometry's rule (periodic, or no-slip walls possibly moving in x).
#include "parallel/mpi.hpp"

#include "config/case_config.hpp"
#include "core/window_field.hpp"
#include "grid/grid.hpp"
#include "solver/flow_state.hpp"

namespace eulerfsi {

struct WallVelocity {
  double u_lo = 0.0;  // x-velocity of the wall at y = -Ly/2
  double u_hi = 0.0;  // x-velocity of the wall at y = +Ly/2
};

class BoundaryConditions {
 public:
  BoundaryConditions(const CaseConfig& cfg, const Grid& grid, MPI_Comm comm);
  // Moving-wall velocity at time t (Couette, optionally oscillating).
  WallVelocity walls_at(double t) const;
  // Velocity component c of the wall across direction dir (1 or 2), low or high side, at time t,
  // in the grid's frame (c != dir: the wall-normal component is zero).
  double wall_velocity(int c, int dir, bool high, double t) const;
  void fill_velocity(const kernels::Velocity& vel, double t) const;
  // Only what div_h u reads beyond the owned cells, for a velocity whose ghosts were filled before
  // its owned cells changed: the low x-halo of u, the periodic ghosts of the normal component
  // along a periodic y or z, and the owned face on a high wall set to zero again (the low wall's
  // face is a ghost, still zero). The other ghosts stay stale until the next fill_velocity.
  void fill_divergence_stencil(const kernels::Velocity& vel) const;
  // The grid's x-velocity in the laboratory: every wall moves with -frame_u relative to it.
  void set_frame_velocity(double frame_u) { frame_u_ = frame_u; }
  // Cell-centred scalar with zero normal gradient at walls (pressure, psi, B components).
  void fill_scalar(const Field3& f) const;
  // The same for a field that changed only inside `changed` (storage indices) since its ghosts were
  // last filled: the y/z ghosts are refreshed only on the x-planes of `changed`, and only along a
  // direction whose boundary `changed` comes within a ghost width of. Empty: a full fill.
  void fill_scalar(const Field3& f, const Box& changed) const;
  // The same for a field stored on a window of the slab (src/solid/solid_window.hpp): a window
  // reaches the y or z ghosts only when it holds that whole direction, and only those are filled.
  void fill_scalar(const WindowField& f, const Box& changed) const;

 private:
  Grid grid_;
  MPI_Comm comm_;
  double wall_u_[2];
  double wall_frequency_;
  double frame_u_ = 0.0;
};

}  // namespace eulerfsi

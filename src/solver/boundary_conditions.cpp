#include "solver/boundary_conditions.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/boundary.hpp"
#include "parallel/halo.hpp"

namespace eulerfsi {

using kernels::GhostRule;

BoundaryConditions::BoundaryConditions(const CaseConfig& cfg, const Grid& grid, MPI_Comm comm)
    : grid_(grid), comm_(comm), wall_u_{cfg.flow.wall_velocity[0], cfg.flow.wall_velocity[1]},
      wall_frequency_(cfg.flow.wall_frequency) {}

WallVelocity BoundaryConditions::walls_at(double t) const {
  const double s = wall_frequency_ > 0.0 ? std::sin(wall_frequency_ * t) : 1.0;
  return {wall_u_[0] * s, wall_u_[1] * s};
}

double BoundaryConditions::wall_velocity(int c, int dir, bool high, double t) const {
  if (c != 0) return 0.0;
  // only u on the y walls moves in the laboratory (Couette); in the grid's frame every wall
  // also moves with -frame_u in x
  const WallVelocity walls = walls_at(t);
  return (dir == 1 ? (high ? walls.u_hi : walls.u_lo) : 0.0) - frame_u_;
}

void BoundaryConditions::fill_velocity(const kernels::Velocity& vel, double t) const {
  for (int c = 0; c < 3; ++c) exchange_x(vel.c[c], grid_, comm_);
  for (int dir = 1; dir <= 2; ++dir) {
    for (int c = 0; c < 3; ++c) {
      if (grid_.bc[dir] == Boundary::Periodic) {
        kernels::fill_ghosts(vel.c[c], dir, grid_.n[dir], GhostRule::Periodic, 0.0, 0.0);
      } else if (c == dir) {
        kernels::fill_ghosts(vel.c[c], dir, grid_.n[dir], GhostRule::Normal, 0.0, 0.0);
      } else {
        kernels::fill_ghosts(vel.c[c], dir, grid_.n[dir], GhostRule::Tangent, wall_velocity(c, dir, false, t),
                             wall_velocity(c, dir, true, t));
      }
    }
  }
}

void BoundaryConditions::fill_divergence_stencil(const kernels::Velocity& vel) const {
  exchange_x(vel.c[0], grid_, comm_);
  for (int dir = 1; dir <= 2; ++dir) {
    if (grid_.bc[dir] == Boundary::Periodic) {
      kernels::fill_ghosts(vel.c[dir], dir, grid_.n[dir], GhostRule::Periodic, 0.0, 0.0);
    } else {
      kernels::fill_ghosts(vel.c[dir], dir, grid_.n[dir], GhostRule::WallFace, 0.0, 0.0);
    }
  }
}

void BoundaryConditions::fill_scalar(const Field3& f) const {
  exchange_x(f, grid_, comm_);
  for (int dir = 1; dir <= 2; ++dir) {
    const GhostRule rule = grid_.bc[dir] == Boundary::Periodic ? GhostRule::Periodic : GhostRule::Even;
    kernels::fill_ghosts(f, dir, grid_.n[dir], rule, 0.0, 0.0);
  }
}

void BoundaryConditions::fill_scalar(const Field3& f, const Box& changed) const {
  if (changed.empty()) {
    fill_scalar(f);
    return;
  }
  exchange_x(f, grid_, comm_);
  // the x-ghost planes mirror the first and last kGhost owned planes (here or on a neighbour)
  const int x_end = kGhost + grid_.nx_local;
  const bool x_edge = changed.lo[0] < 2 * kGhost || changed.hi[0] > x_end - kGhost;
  const int x_lo = x_edge ? 0 : changed.lo[0], x_hi = x_edge ? int(f.extent(0)) : changed.hi[0];
  for (int dir = 1; dir <= 2; ++dir) {
    // the ghosts along dir mirror the first and last kGhost owned cells
    const bool near = changed.lo[dir] < 2 * kGhost || changed.hi[dir] > grid_.n[dir];
    if (!near) continue;
    const GhostRule rule = grid_.bc[dir] == Boundary::Periodic ? GhostRule::Periodic : GhostRule::Even;
    kernels::fill_ghosts(f, dir, grid_.n[dir], rule, 0.0, 0.0, x_lo, x_hi);
  }
}

void BoundaryConditions::fill_scalar(const WindowField& f, const Box& changed) const {
  const Box w = f.window(), all = grid_.all();
  auto whole_along = [w, all](int d) { return w.lo[d] == all.lo[d] && w.hi[d] == all.hi[d]; };
  if (whole_along(0) && whole_along(1) && whole_along(2)) {
    fill_scalar(f.data, changed);
    return;
  }
  exchange_x(f, grid_, comm_);
  const int x_end = kGhost + grid_.nx_local;
  const bool x_edge = changed.empty() || changed.lo[0] < 2 * kGhost || changed.hi[0] > x_end - kGhost;
  const int x_lo = x_edge ? w.lo[0] : std::max(changed.lo[0], w.lo[0]);
  const int x_hi = x_edge ? w.hi[0] : std::min(changed.hi[0], w.hi[0]);
  for (int dir = 1; dir <= 2; ++dir) {
    // the window holds the ghosts of a side only where it reaches them (src/solid/solid_window.hpp)
    const bool low = w.lo[dir] == 0, high = w.hi[dir] == all.hi[dir];
    const bool near_low = changed.empty() || changed.lo[dir] < 2 * kGhost;
    const bool near_high = changed.empty() || changed.hi[dir] > grid_.n[dir];
    // a periodic direction's ghosts are images of the far end (the window then holds both ends):
    // a change near either end reaches both; a wall's ghosts mirror the cells next to them
    const bool periodic = grid_.bc[dir] == Boundary::Periodic;
    const bool fill_low = periodic ? low && high && (near_low || near_high) : low && near_low;
    const bool fill_high = periodic ? fill_low : high && near_high;
    if (fill_low || fill_high)
      kernels::fill_window_ghosts(f.data, dir, grid_.n[dir], periodic ? GhostRule::Periodic : GhostRule::Even, w.lo[dir],
                                  fill_low, fill_high, x_lo - w.lo[0], x_hi - w.lo[0]);
  }
}

}  // namespace eulerfsi

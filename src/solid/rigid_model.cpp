#include "solid/rigid_model.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kernels/elastic_force.hpp"
#include "solid/paper_model.hpp"
#include "solid/rigid_fit.hpp"
#include "solver/rk3.hpp"

namespace eulerfsi {

namespace {

// psi's smoothed edge: the reference map's half-width, so both models' spheres look alike
constexpr double kHalfWidthCells = 1.5;
// cells the window holds beyond psi's: the reach of the stencils that read around the active box
constexpr int kWindowReach = kGhost + 1;

double wrap(double x, double period) {
  if (period <= 0.0) return x;
  x = std::fmod(x, period);
  return x < 0.0 ? x + period : x;
}

}  // namespace

RigidModel::RigidModel(const SolidConfig& solid, const CaseConfig&, const Grid& grid, const Comm& comm)
    : cfg_solid_(solid), grid_(grid), comm_(comm), window_(grid, comm) {
  for (int d = 0; d < 3; ++d) centre_[d] = solid.center[d];
  centre_[0] = wrap(centre_[0], grid.length[0]);
}

std::array<bool, 6> RigidModel::held() const {
  std::array<bool, 6> h{false, false, false, false, false, false};
  if (cfg_solid_.constraint == SolidConstraint::Fixed) h.fill(true);
  if (cfg_solid_.constraint == SolidConstraint::Radial) h[1] = h[2] = true;
  return h;
}

kernels::RigidGeometry RigidModel::geometry() const {
  kernels::RigidGeometry g;
  for (int d = 0; d < 3; ++d) {
    g.xc.x0[d] = grid_.centre(d, 0);
    g.xc.h[d] = grid_.h[d];
    g.centre[d] = centre_[d];
    g.period[d] = grid_.bc[d] == Boundary::Periodic ? grid_.length[d] : 0.0;
  }
  g.radius = 0.5 * cfg_solid_.diameter;
  g.eps = kHalfWidthCells * std::fmax(grid_.h[0], std::fmax(grid_.h[1], grid_.h[2]));
  return g;
}

// psi (0 outside), B and B_prev (I outside): B is I everywhere, stored because the shared kernels read it.
std::vector<SolidWindow::Member> RigidModel::window_members(SolidBody& body) const {
  std::vector<SolidWindow::Member> m = {{&body.psi, 0.0, "psi"}};
  for (int c = 0; c < kernels::kTensorComponents; ++c) {
    const double identity = c < 3 ? 1.0 : 0.0;
    m.push_back({&body.b.c[c], identity, "B"});
    m.push_back({&body.b_prev.c[c], identity, "B_prev"});
  }
  return m;
}

void RigidModel::allocate(SolidBody& body, const Grid&) { place(body); }

double RigidModel::window_cells(const SolidConfig& s, const Grid& g, bool x_whole) {
  const double reach = 0.5 * s.diameter + kHalfWidthCells * std::fmax(g.h[0], std::fmax(g.h[1], g.h[2]));
  Box need;
  for (int d = 0; d < 3; ++d) {  // place()'s cells grown by the window's reach, x in global storage indices
    const double lo = s.center[d] - reach - g.domain_lo(d), hi = s.center[d] + reach - g.domain_lo(d);
    need.lo[d] = int(std::floor(lo / g.h[d])) - 1 - kWindowReach + kGhost;
    need.hi[d] = int(std::floor(hi / g.h[d])) + 2 + kWindowReach + kGhost;
  }
  Box w = SolidWindow::placement(g, need);
  if (x_whole) {
    w.lo[0] = 0;
    w.hi[0] = g.n[0] + 2 * kGhost;
  }
  return double(SolidWindow::local_part(g, w).size());
}

// psi differs from 0 only within a + eps of the centre: its storage cells there (a whole direction
// where the reach wraps around a periodic end), ghosts included; the active box is their owned part.
// The window holds them and the reach of every stencil read around the active box (the
// diagnostics' force terms read psi and B up to kGhost + 1 cells away); psi is written on the whole
// window, so a move leaves nothing stale.
void RigidModel::place(SolidBody& body, bool always_move) {
  const kernels::RigidGeometry g = geometry();
  const double reach = g.radius + g.eps;
  Box psi_cells = grid_.all();
  for (int d = 0; d < 3; ++d) {
    const double lo = centre_[d] - reach - grid_.domain_lo(d), hi = centre_[d] + reach - grid_.domain_lo(d);
    if (g.period[d] > 0.0 && (lo < 0.0 || hi > grid_.length[d])) continue;  // wraps: the whole direction
    const int offset = kGhost - (d == 0 ? grid_.x_offset : 0);  // storage = global + offset
    const int first = int(std::floor(lo / grid_.h[d])) - 1 + offset, last = int(std::floor(hi / grid_.h[d])) + 2 + offset;
    psi_cells.lo[d] = std::max(0, std::min(first, grid_.ext(d)));
    psi_cells.hi[d] = std::max(psi_cells.lo[d], std::min(last, grid_.ext(d)));
  }
  window_.hold(psi_cells.grown(kWindowReach, grid_.all()), window_members(body), always_move);
  kernels::rigid_sphere_psi(body.psi, g, window_.local());
  psi_box_ = psi_cells;
  active_ = intersection(psi_cells, grid_.interior());
}

// the configured centre is where the constructor put it
void RigidModel::set_initial_condition(SolidBody& body) { fill_ghosts(body); }

// x_c^(k+1) = x_c^k + dt (gamma_k U^k + zeta_k U^(k-1)), U^k the translation the last correction
// imposed (its held components zero); before the first correction, the fit of the velocity now.
void RigidModel::advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  if (!imposed_known_) {
    imposed_ = fit_rigid_motion(kernels::rigid_moments(body.psi, vel, geometry(), grid_.cell_volume(), active_), comm_,
                                held());
    imposed_known_ = true;
  }
  const double* U = imposed_.U;
  const double a = dt * Rk3::gamma[substep], b = dt * Rk3::zeta[substep];
  for (int d = 0; d < 3; ++d) {
    centre_[d] += a * U[d] + b * velocity_[d];
    if (grid_.bc[d] == Boundary::Periodic) centre_[d] = wrap(centre_[d] - grid_.domain_lo(d), grid_.length[d]) + grid_.domain_lo(d);
    velocity_[d] = U[d];
  }
  place(body);
}

void RigidModel::constrain_velocity(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  const kernels::RigidGeometry g = geometry();
  const double dv = grid_.cell_volume();
  const kernels::RigidMoments m = kernels::rigid_moments(body.psi, vel, g, dv, active_);
  const RigidMotion fit = fit_rigid_motion(m, comm_, held());
  imposed_ = fit;
  imposed_known_ = true;
  double impulse[3];
  kernels::rigid_blend(vel, body.psi, g, fit.U, fit.w, dv, active_, impulse);
  if (substep == 0) impulse_[0] = impulse_[1] = impulse_[2] = 0.0;
  for (int d = 0; d < 3; ++d) impulse_[d] += comm_.sum(impulse[d]);
  if (substep + 1 == Rk3::stages)
    for (int d = 0; d < 3; ++d) force_[d] = held()[d] ? impulse_[d] / dt : 0.0;  // a free direction's is round-off
}

std::map<std::string, double> RigidModel::checkpoint_scalars() const {
  // the translation of the last correction moves the centre in the next substep: a restart needs it
  return {{"centre_x", centre_[0]}, {"centre_y", centre_[1]}, {"centre_z", centre_[2]},
          {"hold_fx", force_[0]},   {"hold_fy", force_[1]},   {"hold_fz", force_[2]},
          {"imposed_u", imposed_.U[0]}, {"imposed_v", imposed_.U[1]}, {"imposed_w", imposed_.U[2]}};
}

void RigidModel::restore_scalars(const std::map<std::string, double>& s) {
  const char* names[9] = {"centre_x", "centre_y", "centre_z", "hold_fx",  "hold_fy",
                          "hold_fz",  "imposed_u", "imposed_v", "imposed_w"};
  for (int n = 0; n < 9; ++n) {
    const auto it = s.find(names[n]);
    if (it == s.end()) throw std::runtime_error(std::string("checkpoint: the rigid body has no '") + names[n] + "'");
    (n < 3 ? centre_[n] : n < 6 ? force_[n - 3] : imposed_.U[n - 6]) = it->second;
  }
  imposed_known_ = true;
}

void RigidModel::fill_ghosts(SolidBody& body) {
  // a read leaves the fields on the whole slab: back onto the window, psi from the centre, B = I
  place(body, true);
  set_identity(body.b);
  set_identity(body.b_prev);
}

}  // namespace eulerfsi

#include "solver/flow_solver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "kernels/flow_reductions.hpp"
#include "kernels/momentum.hpp"
#include "kernels/projection.hpp"
#include "kernels/time_update.hpp"
#include "solver/initial_conditions.hpp"

namespace eulerfsi {

FlowSolver::FlowSolver(const CaseConfig& cfg, const Grid& grid, const Comm& comm)
    : cfg_(cfg), grid_(grid), comm_(comm), bc_(cfg, grid, comm.comm), state_(grid),
      rhs_new_{{grid.make_field("rhs_u"), grid.make_field("rhs_v"), grid.make_field("rhs_w")}},
      rhs_old_{{grid.make_field("rhs_u_old"), grid.make_field("rhs_v_old"), grid.make_field("rhs_w_old")}},
      mu_(grid.make_field("mu")), poisson_(make_poisson_solver(grid, comm.comm)), mu_fluid_(1.0 / cfg.flow.Re) {
  const Geometry geo = cfg.domain.geometry;
  impose_flow_rate_ = geo == Geometry::Pipe || geo == Geometry::Duct || geo == Geometry::Channel;
  Kokkos::deep_copy(mu_, mu_fluid_);
  build_wall_masks();
  // the open cross-section never changes: count its x-faces once
  open_faces_ = double(grid.global_cells());
  if (masks_.chi[0].extent(0) > 0) {
    // the mask is x-independent: open faces = Nx times the open (j, k) of the cross-section
    auto chi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), masks_.chi[0]);
    const Box b = grid.interior();
    double open = 0.0;
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) open += 1.0 - chi(j, k);
    open_faces_ = open * grid.n[0];
  }
}

FlowSolver::~FlowSolver() = default;

// chi = 1 outside the pipe (r >= R = 1/2) at each component's own staggered point.
void FlowSolver::build_wall_masks() {
  if (cfg_.domain.geometry != Geometry::Pipe) return;
  const int e1 = grid_.ext(1), e2 = grid_.ext(2);
  const double y0 = grid_.domain_lo(1), z0 = grid_.domain_lo(2), dy = grid_.h[1], dz = grid_.h[2];
  for (int c = 0; c < 3; ++c) {
    masks_.chi[c] = kernels::Mask2("chi", e1, e2);
    auto chi = masks_.chi[c];
    const double sy = c == 1 ? 1.0 : 0.5, sz = c == 2 ? 1.0 : 0.5;  // face or centre offset
    Kokkos::parallel_for("eulerfsi::penalization::mask", Policy2({0, 0}, {e1, e2}), KOKKOS_LAMBDA(int j, int k) {
      const double y = y0 + (j - kGhost + sy) * dy;
      const double z = z0 + (k - kGhost + sz) * dz;
      chi(j, k) = (y * y + z * z >= 0.25) ? 1.0 : 0.0;
    });
  }
}

void FlowSolver::set_initial_condition() {
  fill_initial_velocity(cfg_, grid_, state_.vel);
  make_solenoidal();
}

void FlowSolver::make_solenoidal() {
  bc_.fill_velocity(state_.vel, 0.0);
  // a sampled profile, the penalized wall or a particle at rest need not be divergence free
  project(1.0);
  if (impose_flow_rate_) correct_flow_rate();
  bc_.fill_velocity(state_.vel, 0.0);
  Kokkos::deep_copy(state_.p, 0.0);
  dpdx_ = 0.0;
}

double FlowSolver::stable_dt(double extra_wave_speed) const {
  const auto& u = state_.vel.c;
  const double rate = comm_.max(kernels::max_signal_rate(u[0], u[1], u[2], grid_.h, extra_wave_speed, grid_.interior()));
  const double dt_conv = rate > 0.0 ? cfg_.time.cfl / rate : 1e300;
  // RK3 is stable on the negative real axis to 2.51; 1.65 keeps a margin (as CaNS does)
  double inv_h2 = 0.0;
  for (int d = 0; d < 3; ++d) inv_h2 += 1.0 / (grid_.h[d] * grid_.h[d]);
  double mu_max = mu_fluid_;
  for (const auto& s : cfg_.solids) mu_max = std::max(mu_max, s.viscosity_ratio * mu_fluid_);
  const double dt_visc = 1.65 / (4.0 * mu_max * inv_h2);
  return std::min(dt_conv, dt_visc);
}

void FlowSolver::advance(double t, double dt, SolidCoupling* solids) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  double dpdx_step = 0.0;
  for (int s = 0; s < Rk3::stages; ++s) {
    const double gamma = Rk3::gamma[s], zeta = Rk3::zeta[s], alpha_dt = Rk3::alpha(s) * dt;
    const double t_next = t + (s + 1 < Rk3::stages ? Rk3::start(s + 1) : 1.0) * dt;
    // (i) advance psi and B with the current velocity; mixture viscosity from the new psi
    if (solids) {
      solids->advance_substep(vel, dt, s);
      solids->mixture_viscosity(mu_, mu_fluid_);
    }
    // (ii) explicit momentum right-hand side: advection + viscous (+ elastic stress)
    kernels::momentum_rhs(rhs_new_, vel, mu_, grid_.h, box, solids == nullptr);
    if (solids) solids->add_elastic_force(rhs_new_);
    // (iii) predictor with implicit penalization of the pipe wall
    const double penal = alpha_dt / cfg_.flow.penalization_eta;
    static const char* labels[3] = {"eulerfsi::rk3::update_u", "eulerfsi::rk3::update_v", "eulerfsi::rk3::update_w"};
    for (int c = 0; c < 3; ++c) {
      // the wall is at rest in the laboratory: u_wall = -frame_u in the grid's frame
      kernels::rk3_update(vel.c[c], rhs_new_.c[c], rhs_old_.c[c], masks_.chi[c], dt, gamma, zeta, penal, box, labels[c],
                          c == 0 ? -frame_u_ : 0.0);
      std::swap(rhs_new_.c[c], rhs_old_.c[c]);
    }
    bc_.fill_velocity(vel, t_next);
    // (iv) projection
    project(alpha_dt);
    // (v) constant flow rate: the uniform correction is the mean pressure gradient times alpha dt
    if (impose_flow_rate_) dpdx_step -= correct_flow_rate() / dt;
    bc_.fill_velocity(vel, t_next);
  }
  if (impose_flow_rate_) dpdx_ = dpdx_step;
  frame_x_ += frame_u_ * dt;
}

void FlowSolver::set_frame_velocity(double u_frame, double t) {
  const double du = u_frame - frame_u_;
  if (du == 0.0) return;
  // u_lab = u + frame_u is unchanged: u -= du on every x-face, walls included
  kernels::add_open_x_velocity(state_.vel.c[0], kernels::Mask2(), -du, grid_.interior());
  frame_u_ = u_frame;
  bc_.set_frame_velocity(u_frame);
  bc_.fill_velocity(state_.vel, t);
}

// Leaves the ghosts of the velocity stale: the caller refills them once it is done with it.
void FlowSolver::project(double alpha_dt) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  kernels::divergence(state_.p, vel.c[0], vel.c[1], vel.c[2], grid_.h, 1.0 / alpha_dt, box);
  poisson_->solve(state_.p);
  bc_.fill_scalar(state_.p);
  kernels::subtract_gradient(vel.c[0], vel.c[1], vel.c[2], state_.p, grid_.h, alpha_dt, box);
}

// Adds du to u on the open faces so the bulk velocity is U_b again (U_b - frame_u in the grid's
// frame); returns du.
double FlowSolver::correct_flow_rate() {
  const double bulk = bulk_velocity();
  const double du = cfg_.flow.bulk_velocity - frame_u_ - bulk;
  kernels::add_open_x_velocity(state_.vel.c[0], masks_.chi[0], du, grid_.interior());
  return du;
}

double FlowSolver::bulk_velocity() const {
  return comm_.sum(kernels::open_face_sum(state_.vel.c[0], masks_.chi[0], grid_.interior())) / open_faces_;
}

FlowDiagnostics FlowSolver::diagnostics(double dt, double wave_speed) const {
  const Box box = grid_.interior();
  const auto& u = state_.vel.c;
  FlowDiagnostics d;
  d.cfl = dt * comm_.max(kernels::max_signal_rate(u[0], u[1], u[2], grid_.h, wave_speed, box));
  d.bulk_u = bulk_velocity() + frame_u_;
  d.dpdx = dpdx_;
  d.max_div = comm_.max(kernels::max_abs_divergence(u[0], u[1], u[2], grid_.h, box));
  d.kinetic_energy = comm_.sum(kernels::kinetic_energy_sum(u[0], u[1], u[2], box, frame_u_)) / double(grid_.global_cells());
  bool ok = true;
  for (int c = 0; c < 3; ++c) ok = ok && kernels::all_finite(u[c], box);
  d.finite = !comm_.any(!ok);
  return d;
}

}  // namespace eulerfsi

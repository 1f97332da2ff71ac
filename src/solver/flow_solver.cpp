#include "solver/flow_solver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "kernels/flow_reductions.hpp"
#include "kernels/elastic_force.hpp"
#include "kernels/momentum.hpp"
#include "kernels/momentum_predictor.hpp"
#include "kernels/projection.hpp"
#include "kernels/time_update.hpp"
#include "solver/initial_conditions.hpp"

namespace eulerfsi {

FlowSolver::FlowSolver(const CaseConfig& cfg, const Grid& grid, const Comm& comm)
    : cfg_(cfg), grid_(grid), comm_(comm), bc_(cfg, grid, comm.comm), state_(grid),
      rhs_new_{{grid.make_field("rhs_u"), grid.make_field("rhs_v"), grid.make_field("rhs_w")}},
      rhs_old_{{grid.make_field("rhs_u_old"), grid.make_field("rhs_v_old"), grid.make_field("rhs_w_old")}},
      mu_(grid.make_field("mu")), no_wall_("no_wall", 1, grid.n[2] + 2 * kGhost), poisson_(make_poisson_solver(grid, comm.comm, cfg.solver.fft_planning)), mu_fluid_(1.0 / cfg.flow.Re) {
  const Geometry geo = cfg.domain.geometry;
  impose_flow_rate_ = geo == Geometry::Pipe || geo == Geometry::Duct || geo == Geometry::Channel ||
                      (geo == Geometry::Periodic && cfg.flow.periodic_flow_rate);
  mu_explicit_ = mu_fluid_;
  if (cfg.time.implicit_viscosity) {
    helmholtz_ = make_helmholtz_solver(grid, comm.comm, cfg.solver.fft_planning);
    implicit_rhs_ = grid.make_field("implicit_viscosity_rhs");
    mu_explicit_ = 0.0;
  }
  Kokkos::deep_copy(mu_, mu_explicit_);
  build_wall_masks();
}

FlowSolver::~FlowSolver() = default;

namespace {

// The pipe's cross-section seen from one staggered location (sy, sz: 0.5 at a cell centre, 1 at a
// face); storage indices beyond the array are allowed (only positions are computed there).
struct PipeSection {
  double lo[2], h[2], shift[2];
  double r2 = 0.25;  // R^2
  double pos(int j, int k, int d) const { return lo[d] + ((d == 0 ? j : k) - kGhost + shift[d]) * h[d]; }
  bool inside(int j, int k) const {
    const double y = pos(j, k, 0), z = pos(j, k, 1);
    return y * y + z * z < r2;
  }
  // first fluid layer: inside, with a face neighbour outside
  bool next_to_wall(int j, int k) const {
    return inside(j, k) && (!inside(j + 1, k) || !inside(j - 1, k) || !inside(j, k + 1) || !inside(j, k - 1));
  }
  // The interpolated wall at a first-layer point: along each grid line that leaves the pipe within
  // one cell, the wall is at distance t = sqrt(R^2 - other^2) - s x; the nearest crossing whose
  // inner neighbour is free (not itself on the layer) gives w = t / (t + h) and the neighbour's
  // offset. False where there is none (the tips where the pipe touches the duct): left unforced.
  bool forcing(int j, int k, double& w, int off[2]) const {
    double best_t = 1e300;
    for (int d = 0; d < 2; ++d)
      for (int s = -1; s <= 1; s += 2) {
        const int dj = d == 0 ? s : 0, dk = d == 1 ? s : 0;
        if (inside(j + dj, k + dk) || !inside(j - dj, k - dk) || next_to_wall(j - dj, k - dk)) continue;
        const double other = pos(j, k, 1 - d);
        const double t = std::sqrt(r2 - other * other) - s * pos(j, k, d);
        if (t >= best_t) continue;
        best_t = t;
        w = t / (t + h[d]);
        off[0] = -dj;
        off[1] = -dk;
      }
    return best_t < 1e300;
  }
};

}  // namespace

// chi = 1 outside the pipe (r >= R = 1/2) at each component's own staggered point; with the
// interpolated wall also on the first fluid layer, with its interpolation weight and neighbour.
// Built on the host once (the wall never moves), then copied to the device.
void FlowSolver::build_wall_masks() {
  open_faces_ = inside_faces_ = flow_faces_ = double(grid_.global_cells());
  if (cfg_.domain.geometry != Geometry::Pipe) return;
  const bool interpolated = cfg_.flow.pipe_wall == PipeWall::Interpolated;
  const int e1 = grid_.ext(1), e2 = grid_.ext(2);
  for (int c = 0; c < 3; ++c) {
    const PipeSection pipe{{grid_.domain_lo(1), grid_.domain_lo(2)},
                           {grid_.h[1], grid_.h[2]},
                           {c == 1 ? 1.0 : 0.5, c == 2 ? 1.0 : 0.5}};
    kernels::Mask2 chi("chi", e1, e2), weight("wall_weight", e1, e2);
    kernels::Offset2 nb("wall_neighbour", e1, e2);
    auto chi_h = Kokkos::create_mirror_view(chi);
    auto w_h = Kokkos::create_mirror_view(weight);
    auto nb_h = Kokkos::create_mirror_view(nb);
    for (int j = 0; j < e1; ++j)
      for (int k = 0; k < e2; ++k) {
        double w = 0.0;
        int off[2] = {0, 0};
        const bool forced = interpolated && pipe.next_to_wall(j, k) && pipe.forcing(j, k, w, off);
        chi_h(j, k) = forced || !pipe.inside(j, k) ? 1.0 : 0.0;
        w_h(j, k) = w;
        nb_h(j, k, 0) = off[0];
        nb_h(j, k, 1) = off[1];
      }
    Kokkos::deep_copy(chi, chi_h);
    Kokkos::deep_copy(weight, w_h);
    Kokkos::deep_copy(nb, nb_h);
    masks_.chi[c] = chi;
    masks_.weight[c] = weight;
    masks_.neighbour[c] = nb;
    // the same split for the update: the layer (w > 0) as a list, the rest a mask towards u_wall
    kernels::Mask2 chi_wall("chi_wall", e1, e2);
    auto chi_wall_h = Kokkos::create_mirror_view(chi_wall);
    std::vector<std::pair<int, int>> layer;
    for (int j = 0; j < e1; ++j)
      for (int k = 0; k < e2; ++k) {
        const bool on_layer = chi_h(j, k) > 0.0 && w_h(j, k) > 0.0;
        chi_wall_h(j, k) = on_layer ? 0.0 : chi_h(j, k);
        if (on_layer) layer.emplace_back(j, k);
      }
    kernels::WallLayer points("wall_layer", layer.size());
    auto points_h = Kokkos::create_mirror_view(points);
    for (size_t n = 0; n < layer.size(); ++n) {
      points_h(n, 0) = layer[n].first;
      points_h(n, 1) = layer[n].second;
    }
    Kokkos::deep_copy(chi_wall, chi_wall_h);
    Kokkos::deep_copy(points, points_h);
    masks_.chi_wall[c] = chi_wall;
    masks_.layer[c] = points;
    if (c != 0) continue;
    // x-faces inside the pipe carry the flow rate. The correction du moves the open faces by du and
    // the forced layer by w du, which keeps u_f = w u_nb + (1 - w) u_wall exact after it
    kernels::Mask2 outside("outside_u", e1, e2), open("open_u", e1, e2);
    auto out_h = Kokkos::create_mirror_view(outside);
    auto open_h = Kokkos::create_mirror_view(open);
    const Box b = grid_.interior();
    double in = 0.0, moved = 0.0;
    for (int j = 0; j < e1; ++j)
      for (int k = 0; k < e2; ++k) {
        out_h(j, k) = pipe.inside(j, k) ? 0.0 : 1.0;
        open_h(j, k) = 1.0 - chi_h(j, k) + chi_h(j, k) * w_h(j, k);
        if (j < b.lo[1] || j >= b.hi[1] || k < b.lo[2] || k >= b.hi[2]) continue;
        in += 1.0 - out_h(j, k);
        moved += open_h(j, k);
      }
    Kokkos::deep_copy(outside, out_h);
    Kokkos::deep_copy(open, open_h);
    masks_.outside_u = outside;
    masks_.open_u = open;
    inside_faces_ = in * grid_.n[0];
    open_faces_ = moved * grid_.n[0];
    // the flow rate is over the true circle (second order) or over the staircase of open faces
    // (the sharp mask's own wall), in units of one face's area
    flow_faces_ = interpolated ? grid_.n[0] * M_PI * pipe.r2 / (pipe.h[0] * pipe.h[1]) : inside_faces_;
  }
}

void FlowSolver::set_initial_condition() {
  fill_initial_velocity(cfg_, grid_, state_.vel);
  make_solenoidal();
}

void FlowSolver::make_solenoidal() {
  bc_.fill_velocity(state_.vel, 0.0);
  // a sampled profile, the penalized wall or a particle at rest need not be divergence free
  project(1.0);  // with a constant flow rate, its correction too
  bc_.fill_velocity(state_.vel, 0.0);
  Kokkos::deep_copy(state_.p, 0.0);
  dpdx_ = 0.0;
}

double FlowSolver::stable_dt(double extra_wave_speed) const {
  const auto& u = state_.vel.c;
  const double rate = comm_.max(kernels::max_signal_rate(u[0], u[1], u[2], grid_.h, extra_wave_speed, grid_.interior()));
  const double dt_conv = rate > 0.0 ? cfg_.time.cfl / rate : 1e300;
  last_speed_bound_ = std::max(0.0, rate * std::min(grid_.h[0], std::min(grid_.h[1], grid_.h[2])) - extra_wave_speed);
  // RK3 is stable on the negative real axis to 2.51; 1.65 keeps a margin (as CaNS does)
  double inv_h2 = 0.0;
  for (int d = 0; d < 3; ++d) inv_h2 += 1.0 / (grid_.h[d] * grid_.h[d]);
  // the largest viscosity taken explicitly: the mixture's, or only its part beyond mu_f
  const double mu_implicit = mu_fluid_ - mu_explicit_;  // 0, or mu_f with time.implicit_viscosity
  double mu_max = mu_explicit_;
  for (const auto& s : cfg_.solids) {
    mu_max = std::max(mu_max, std::fabs(s.viscosity_ratio * mu_fluid_ - mu_implicit));
    // a rigid body's correction follows the viscous step: beyond the explicit limit the implicit
    // step diffuses across the body between corrections, a splitting error of order mu dt / h^2
    // (a sphere on a tube's axis: 1.3 % faster at 24 explicit limits; docs/VALIDATION.md)
    if (s.model == SolidModelKind::Rigid) mu_max = std::max(mu_max, mu_fluid_);
  }
  const double dt_visc = mu_max > 0.0 ? 1.65 / (4.0 * mu_max * inv_h2) : 1e300;
  return std::min(dt_conv, dt_visc);
}

void FlowSolver::advance(double t, double dt, SolidCoupling* solids) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  // With the implicit viscosity the last step's mean pressure gradient drives the predictor and the
  // flow-rate correction takes only its change: a uniform correction is not a steady state of the
  // Crank-Nicolson half (its Laplacian is not zero at the walls), so it must vanish at one.
  dpdx_applied_ = helmholtz_ && impose_flow_rate_ ? dpdx_ : 0.0;
  double dpdx_step = dpdx_applied_;
  for (int s = 0; s < Rk3::stages; ++s) {
    const double alpha_dt = Rk3::alpha(s) * dt;
    const double t_next = t + (s + 1 < Rk3::stages ? Rk3::start(s + 1) : 1.0) * dt;
    // (i) advance psi and B with the current velocity; mixture viscosity from the new psi
    if (solids) {
      solids->advance_substep(vel, dt, s);
      solids->mixture_viscosity(mu_, mu_fluid_, mu_explicit_);
    }
    // (ii) explicit momentum right-hand side: advection + viscous (+ elastic stress); the
    // mixture viscosity only where it differs from mu_f (a face's stencil reads mu one cell away)
    // (iii) predictor with implicit penalization of the pipe wall
    const Box mixture = solids ? solids->viscosity_region().grown(1, box) : Box{{0, 0, 0}, {0, 0, 0}};
    if (helmholtz_) {
      if (mixture.size() < box.size()) kernels::momentum_rhs(rhs_new_, vel, mu_explicit_, grid_.h, box);
      if (!mixture.empty()) kernels::momentum_rhs(rhs_new_, vel, mu_, grid_.h, mixture);
      if (solids) solids->add_elastic_force(rhs_new_);
      predict_implicit_viscosity(t_next, dt, s);
      // the implicit predictor wrote the ghosts too (a whole-field copy): they need a full fill
      bc_.fill_velocity(vel, t_next);
    } else {
      predict(dt, s, solids, mixture);  // (ii) and (iii) in one pass
      bc_.fill_divergence_stencil(vel);
    }
    // (iv) projection, (v) with a constant flow rate its uniform correction: the mean pressure
    // gradient times alpha dt
    double du = project(alpha_dt, {state_.p_step, Rk3::alpha(s), s == 0});
    // rigid bodies: the velocity inside made rigid, then divergence-free again (its pressure, the
    // rigidity's, joins the step's) unless solver.reproject_constrained = false
    if (solids && solids->constrain_velocity(vel, dt, s) && cfg_.solver.reproject_constrained) {
      bc_.fill_divergence_stencil(vel);
      du += project(alpha_dt, {state_.p_step, Rk3::alpha(s), false});
    }
    if (impose_flow_rate_) dpdx_step -= du / dt;
    bc_.fill_velocity(vel, t_next);
  }
  if (impose_flow_rate_) dpdx_ = dpdx_step;
  bc_.fill_scalar(state_.p_step);  // the projections summed it on the interior
  frame_x_ += frame_u_ * dt;
}

namespace {
const char* const kUpdateLabels[3] = {"eulerfsi::rk3::update_u", "eulerfsi::rk3::update_v", "eulerfsi::rk3::update_w"};
const char* const kWallLabels[3] = {"eulerfsi::penalization::wall_u", "eulerfsi::penalization::wall_v",
                                    "eulerfsi::penalization::wall_w"};
}  // namespace

// u* = u + dt (gamma rhs + zeta rhs_old), the pipe wall penalized implicitly, with rhs computed in
// the same pass (kernels/momentum_predictor.hpp). With one viscosity the elastic force is added to
// rhs^k and u* after that pass, on the bodies' faces only (u* is linear in rhs^k). With a mixture
// viscosity its region (with the force's faces) is a pass of its own, the force written into rhs
// first, and the rest of the box takes the constant-viscosity pass.
void FlowSolver::predict(double dt, int s, const SolidCoupling* solids, const Box& mixture) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  const bool interpolated = cfg_.flow.pipe_wall == PipeWall::Interpolated && masks_.chi[0].extent(0) > 0;
  kernels::PredictorTerms terms;
  terms.a = dt * Rk3::gamma[s];
  terms.b = dt * Rk3::zeta[s];
  terms.penal = Rk3::alpha(s) * dt / cfg_.flow.penalization_eta;
  for (int c = 0; c < 3; ++c) {
    const kernels::Mask2& chi = interpolated ? masks_.chi_wall[c] : masks_.chi[c];
    terms.rhs_old_to_star[c] = rhs_old_.c[c].data();
    terms.chi[c] = chi.extent(0) > 0 ? chi.data() : no_wall_.data();
    terms.chi_stride[c] = chi.extent(0) > 0 ? long(chi.stride(0)) : 0;
  }
  terms.u_wall[0] = -frame_u_;  // the wall is at rest in the laboratory: u_wall = -frame_u in the grid's frame
  if (mixture.empty()) {
    // one viscosity: the whole grid in one pass, the elastic force added after it on the bodies' faces
    kernels::momentum_predict(rhs_new_, vel, mu_explicit_, grid_.h, terms, box);
    if (solids) solids->add_elastic_force_to_predictor(rhs_new_, rhs_old_, terms);
  } else {
    // the mixture's viscosity region (with the force's faces) takes the variable-viscosity pass
    const Box forced = intersection(bounding_box(mixture, solids->elastic_force_region()), box);
    for (int c = 0; c < 3; ++c) kernels::fill_box(rhs_new_.c[c], 0.0, forced);
    solids->add_elastic_force(rhs_new_);
    Box parts[6];
    const int n = difference(box, forced, parts);
    for (int p = 0; p < n; ++p) kernels::momentum_predict(rhs_new_, vel, mu_explicit_, grid_.h, terms, parts[p]);
    kernels::momentum_predict(rhs_new_, vel, mu_, grid_.h, terms, forced);
  }
  // u* is in rhs_old, rhs^k in rhs_new: u* becomes the velocity, rhs^k the next rhs^(k-1), u^k the scratch
  for (int c = 0; c < 3; ++c) {
    Field3 u_start = vel.c[c];
    vel.c[c] = rhs_old_.c[c];
    rhs_old_.c[c] = rhs_new_.c[c];
    rhs_new_.c[c] = u_start;
  }
  // the interpolated wall reads the predicted velocity of its inner neighbours: a second pass
  if (interpolated)
    for (int c = 0; c < 3; ++c)
      kernels::penalize_wall_layer(vel.c[c], masks_.layer[c], masks_.weight[c], masks_.neighbour[c], terms.penal, box,
                                   kWallLabels[c], c == 0 ? -frame_u_ : 0.0);
}

// The same with mu_f by Crank-Nicolson: (I - c L_h) u* = u + dt (gamma rhs + zeta rhs_old) + c L_h u
// with c = alpha dt mu_f / 2, the wall's velocity at t_next in the right-hand side; the pipe wall
// is a direct forcing in that right-hand side (kernels::force_implicit_wall: the penalization is
// not part of the operator the transforms invert).
void FlowSolver::predict_implicit_viscosity(double t_next, double dt, int s) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  const double penal = Rk3::alpha(s) * dt / cfg_.flow.penalization_eta;
  const double c_imp = 0.5 * Rk3::alpha(s) * dt * mu_fluid_;
  const bool interpolated = cfg_.flow.pipe_wall == PipeWall::Interpolated && masks_.chi[0].extent(0) > 0;
  for (int c = 0; c < 3; ++c) {
    kernels::implicit_viscosity_rhs(implicit_rhs_, vel.c[c], rhs_new_.c[c], rhs_old_.c[c], dt, Rk3::gamma[s],
                                    Rk3::zeta[s], c_imp, grid_.h, box);
    if (c == 0 && dpdx_applied_ != 0.0)
      kernels::add_open_x_velocity(implicit_rhs_, masks_.open_u, -Rk3::alpha(s) * dt * dpdx_applied_, box);
    // the pipe's forcing first: its explicit estimate w + c L_h u reads the walls through u's ghosts,
    // so w must not hold the solver's wall term yet (in a moving frame it would count twice)
    const double u_wall = c == 0 ? -frame_u_ : 0.0;
    kernels::force_implicit_wall(implicit_rhs_, vel.c[c], interpolated ? masks_.chi_wall[c] : masks_.chi[c], penal,
                                 u_wall, c_imp, grid_.h, box, kUpdateLabels[c]);
    if (interpolated)
      kernels::force_implicit_wall_layer(implicit_rhs_, vel.c[c], masks_.layer[c], masks_.weight[c],
                                         masks_.neighbour[c], penal, u_wall, c_imp, grid_.h, box, kWallLabels[c]);
    for (int dir = 1; dir <= 2; ++dir) {
      if (grid_.bc[dir] != Boundary::Wall || c == dir) continue;  // the wall-normal component is zero there
      const double k = 2.0 * c_imp / (grid_.h[dir] * grid_.h[dir]);
      kernels::add_wall_velocity_term(implicit_rhs_, dir, grid_.n[dir], k * bc_.wall_velocity(c, dir, false, t_next),
                                      k * bc_.wall_velocity(c, dir, true, t_next), box);
    }
    helmholtz_->solve(c, implicit_rhs_, c_imp);
    Kokkos::deep_copy(vel.c[c], implicit_rhs_);  // ghosts too: refilled by the caller
    std::swap(rhs_new_.c[c], rhs_old_.c[c]);
  }
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
// step: the step pressure that gathers alpha_s p_s in the same pass (none: not gathered).
// The flow rate is taken from u* in the divergence's pass: the correction leaves it unchanged to
// round-off (kernels::subtract_gradient), so du is known before the correction and added in its pass.
double FlowSolver::project(double alpha_dt, const kernels::StepPressure& step) {
  const Box box = grid_.interior();
  auto& vel = state_.vel;
  const double open_sum = poisson_->solve_divergence(state_.p, vel.c[0], vel.c[1], vel.c[2], grid_.h, 1.0 / alpha_dt,
                                                     box, {masks_.outside_u, impose_flow_rate_});
  const double du = impose_flow_rate_ ? flow_rate_correction(open_sum) : 0.0;
  bc_.fill_scalar(state_.p);
  kernels::subtract_gradient(vel.c[0], vel.c[1], vel.c[2], state_.p, grid_.h, alpha_dt, box, step, {masks_.open_u, du});
  return du;
}

// du added to u on the open faces (w du on the forced layer) brings the bulk velocity to U_b
// (U_b - frame_u in the grid's frame): du = (U_b - bulk) A_flow / A_open, the mean pressure
// gradient times alpha dt. open_sum: this rank's open-face sum of u before the correction.
double FlowSolver::flow_rate_correction(double open_sum) const {
  const double bulk = lab_bulk_velocity(open_sum) - frame_u_;
  return (cfg_.flow.bulk_velocity - frame_u_ - bulk) * (flow_faces_ / open_faces_);
}

// Q / A in the grid's frame: Q = sum over the faces inside the pipe of (u - u_wall) dA, plus
// u_wall A. The velocity relative to the wall (-frame_u) is what the quadrature integrates to
// second order (it vanishes on the circle), and the same in every frame.
double FlowSolver::bulk_velocity() const { return lab_bulk_velocity() - frame_u_; }

double FlowSolver::lab_bulk_velocity() const {
  return lab_bulk_velocity(kernels::open_face_sum(state_.vel.c[0], masks_.outside_u, grid_.interior()));
}

double FlowSolver::lab_bulk_velocity(double open_sum) const {
  const double sum = comm_.sum(open_sum);
  if (flow_faces_ == inside_faces_) return sum / inside_faces_ + frame_u_;
  return (sum + frame_u_ * inside_faces_) / flow_faces_;
}

FlowDiagnostics FlowSolver::diagnostics(double dt, double wave_speed) const {
  const Box box = grid_.interior();
  const auto& u = state_.vel.c;
  FlowDiagnostics d;
  d.cfl = dt * comm_.max(kernels::max_signal_rate(u[0], u[1], u[2], grid_.h, wave_speed, box));
  d.bulk_u = lab_bulk_velocity();
  d.dpdx = dpdx_;
  d.max_div = comm_.max(kernels::max_abs_divergence(u[0], u[1], u[2], grid_.h, box));
  d.kinetic_energy = comm_.sum(kernels::kinetic_energy_sum(u[0], u[1], u[2], box, frame_u_)) / double(grid_.global_cells());
  bool ok = true;
  for (int c = 0; c < 3; ++c) ok = ok && kernels::all_finite(u[c], box);
  d.finite = !comm_.any(!ok);
  return d;
}

}  // namespace eulerfsi

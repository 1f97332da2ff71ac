#include "solid/particle_diagnostics.hpp"

#include <array>

#include <algorithm>
#include <cmath>

#include "kernels/particle_moments.hpp"
#include "solid/rigid_fit.hpp"

namespace eulerfsi {

void symmetric_eigen3(const double a_in[3][3], double values[3], double vectors[3][3]) {
  double a[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = a_in[r][c];
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off < 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2] + 1e-300)) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // classic Jacobi rotation zeroing a[p][q]
        const double theta = 0.5 * (a[q][q] - a[p][p]) / a[p][q];
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&a](int x, int y) { return a[x][x] < a[y][y]; });
  for (int n = 0; n < 3; ++n) {
    values[n] = a[order[n]][order[n]];
    for (int k = 0; k < 3; ++k) vectors[k][n] = v[k][order[n]];
  }
}

ParticleTracker::ParticleTracker(const CaseConfig& cfg, const Grid& grid, const Comm& comm)
    : cfg_(cfg), grid_(grid), comm_(comm) {
  for (const auto& s : cfg.solids) last_x_.push_back(s.center[0]);
  impulse_.assign(cfg.solids.size(), {});
}

namespace {

// The (y, z) part of a vector v along the radial direction e_r = (0, e_y, e_z).
double radial_part(const double v[3], const double e_r[3]) { return v[1] * e_r[1] + v[2] * e_r[2]; }

template <size_t N>
void sum_all(const Comm& comm, double (&a)[N]) {
  MPI_Allreduce(MPI_IN_PLACE, a, int(N), MPI_DOUBLE, MPI_SUM, comm.comm);
}

// Where psi carries a diffused halo (SolidModel::diffuse_halo, the paper model), position,
// velocity and shape are psi-weighted moments over the cells with psi >= 0.05: the
// interface cells keep their sub-cell information (psi >= 1/2 alone gave a staircase: D +20% in
// the shear test), while the faint halo that numerical diffusion leaves (psi < 0.05, a few % of
// the volume over thousands of cells) and that the fluid stretches into long tails is left out
// (it made the psi-moment D 0.31 where the psi >= 1/2 shape had 0.03). The volume column and
// the forces keep the whole psi.
constexpr double kCore = 0.05;
// The cut for a body (kernels::core_weight): sharp where psi has a halo; where psi is derived from
// a sharp shape, a ramp over psi = 0.025-0.075, so that neither the cut's edge nor a cell entering
// the derived band with a small psi makes the moments jump (no cut at all let the latter through:
// the centroid's acceleration in test_particle_force lost its sign).
double core_cut(const SolidBody& body) { return body.model && body.model->diffuse_halo() ? kCore : -kCore; }
// The second edge width of the zero-width extrapolation, as a fraction of psi's own: 1 cell for
// the map's 1.5 (narrower edges sample the shape on the grid with growing noise).
constexpr double kNarrowEdgeFraction = 2.0 / 3.0;

// The cells a body's reductions run on: its model's active box (psi = 0 and B = I outside it, and
// every integrand below is psi-weighted or reads psi within a cell of where psi > 0, well inside
// that box), so the diagnostics cost what the body's size costs.
Box body_box(const SolidBody& body, const Grid& grid) { return body.model ? body.model->active_box() : grid.interior(); }

}  // namespace

void ParticleTracker::force_vectors(const SolidBody& body, const FlowState& flow, const GridFrame& frame,
                                    double (&out)[kForceValues]) const {
  const Box box = body_box(body, grid_);
  // both decompositions take the pressure that moved u over the last step (sum alpha_s p_s), not
  // the last substep's, which extrapolates beyond the step
  const SolidModel::StepStart start = body.model ? body.model->psi_at_step_start() : SolidModel::StepStart{};
  auto budget = kernels::body_momentum(body.psi, flow.p_step, flow.vel, body.b, body.b_prev, body.G, 1.0 / cfg_.flow.Re,
                                       body.mu_s, grid_.h, box, start.psi, start.inv_dt);
  auto paper = kernels::body_forces(body.psi, flow.p_step, flow.vel, body.b, body.G, body.mu_s, frame.velocity,
                                    grid_.h, box);
  const double* parts[9] = {budget.momentum, budget.pressure, budget.inertia, budget.viscous, budget.elastic,
                            paper.pressure,  paper.inertia,   paper.viscous,  paper.elastic};
  for (int q = 0; q < 9; ++q)
    for (int a = 0; a < 3; ++a) out[3 * q + a] = parts[q][a];
  sum_all(comm_, out);
}

void ParticleTracker::add_to_interval(size_t n, const double (&v)[kForceValues], double dt) {
  for (int q = 0; q < kImpulseValues - 1; ++q) impulse_[n][q] += dt * v[3 + q];
  impulse_[n][kImpulseValues - 1] += dt;
}

void ParticleTracker::accumulate_forces(const SolidPhase& solids, const FlowState& flow, const GridFrame& frame,
                                        double dt) {
  for (size_t n = 0; n < solids.bodies().size(); ++n) {
    double v[kForceValues];
    force_vectors(solids.bodies()[n], flow, frame, v);
    add_to_interval(n, v, dt);
  }
}

std::vector<double> ParticleTracker::force_impulse() const {
  std::vector<double> out;
  for (const auto& a : impulse_) out.insert(out.end(), a.begin(), a.end());
  return out;
}

void ParticleTracker::set_force_impulse(const std::vector<double>& values) {
  for (size_t n = 0; n < impulse_.size(); ++n)
    for (int q = 0; q < kImpulseValues; ++q) {
      const size_t at = n * kImpulseValues + q;
      impulse_[n][q] = at < values.size() ? values[at] : 0.0;
    }
}

double ParticleTracker::mean_x_velocity(const SolidPhase& solids, const FlowState& flow, size_t body,
                                        double frame_velocity) const {
  double m[2];
  const SolidBody& b = solids.bodies().at(body);
  const Box box = body_box(b, grid_);
  kernels::body_x_momentum(b.psi, flow.vel, box, m, core_cut(b));
  sum_all(comm_, m);
  if (m[0] <= 0.0) {  // no core left: the whole psi
    kernels::body_x_momentum(b.psi, flow.vel, box, m);
    sum_all(comm_, m);
  }
  return (m[0] > 0.0 ? m[1] / m[0] : 0.0) + frame_velocity;
}

// The shape of a body whose psi is a smoothed Heaviside of a sharp shape (the reference map):
// psi's moments carry the edge's width eps as M(eps) = M(0) + c eps^2 + O(eps^4) (the edge profile
// is odd about the surface, so the first order cancels). At 8 cells per diameter that bias is
// real: an exact ellipsoid of D = 0.0163 reads 0.0153 (eps = 1.5 cells, no cut) and 0.0131 with the
// psi >= 0.05 cut, and D = 0.125 reads 0.117. Two widths (psi's own and 2/3 of it) extrapolated
// to zero width read 0.0160-0.0164 and 0.1248-0.1254 (docs/REFERENCE_MAP.md). No cut: the map's
// psi has no diffused halo, and the cut's on/off edge adds grid-sampling noise.
void ParticleTracker::sharp_shape_moments(const SolidBody& body, const double ref[3], const double period[3],
                                          double out[10]) const {
  const Box box = body_box(body, grid_);
  const kernels::CellCentres xc{{grid_.centre(0, 0), grid_.centre(1, 0), grid_.centre(2, 0)},
                                {grid_.h[0], grid_.h[1], grid_.h[2]}};
  const double w1 = body.model->edge_half_width_cells(), w2 = kNarrowEdgeFraction * w1;
  const WindowField fields[2] = {body.psi, body.model->psi_at_half_width(body, w2)};
  double mom[2][10];
  for (int f = 0; f < 2; ++f) {
    auto second = kernels::body_second_moments(fields[f], xc, ref, period, box, 0.0);
    mom[f][0] = kernels::body_volume(fields[f], box) * xc.h[0] * xc.h[1] * xc.h[2];
    for (int a = 0; a < 3; ++a) mom[f][1 + a] = second.m1[a];
    for (int a = 0; a < 6; ++a) mom[f][4 + a] = second.m2[a];
    sum_all(comm_, mom[f]);
  }
  // M(0) = (w1^2 M(w2) - w2^2 M(w1)) / (w1^2 - w2^2)
  for (int a = 0; a < 10; ++a) out[a] = (w1 * w1 * mom[1][a] - w2 * w2 * mom[0][a]) / (w1 * w1 - w2 * w2);
}

std::vector<ParticleState> ParticleTracker::measure(const SolidPhase& solids, const FlowState& flow,
                                                    const GridFrame& frame, double last_dt) {
  const kernels::CellCentres xc{{grid_.centre(0, 0), grid_.centre(1, 0), grid_.centre(2, 0)},
                                {grid_.h[0], grid_.h[1], grid_.h[2]}};
  const double lx = grid_.length[0];
  const double half_width = 0.5 * grid_.length[1];
  std::vector<ParticleState> out;
  for (size_t n = 0; n < solids.bodies().size(); ++n) {
    const SolidBody& body = solids.bodies()[n];
    const Box box = body_box(body, grid_);
    ParticleState s;
    const std::array<double, 3> hold = holding_force(body);
    for (int d = 0; d < 3; ++d) s.hold_force[d] = hold[d];
    double whole[2];
    kernels::body_x_momentum(body.psi, flow.vel, box, whole);
    sum_all(comm_, whole);
    s.volume = whole[0] * grid_.h[0] * grid_.h[1] * grid_.h[2];
    if (s.volume <= 0.0) {
      if (last_dt > 0.0) impulse_[n] = {};  // the next row's interval starts here
      out.push_back(s);
      continue;
    }
    double cut = core_cut(body);
    auto first = kernels::body_first_moments(body.psi, flow.vel, xc, lx, box, cut);
    sum_all(comm_, first.s);
    using F = kernels::BodyFirstMoments;
    if (first.s[F::Volume] <= 0.0) {  // no core left: the whole psi
      cut = 0.0;
      first = kernels::body_first_moments(body.psi, flow.vel, xc, lx, box, cut);
      sum_all(comm_, first.s);
    }
    const double core_volume = first.s[F::Volume];
    // reference point: circular mean in x and in periodic y, z (a body may straddle their
    // boundaries), plain mean across walls; then the exact moments about it
    const double period[3] = {lx, grid_.bc[1] == Boundary::Periodic ? grid_.length[1] : 0.0,
                              grid_.bc[2] == Boundary::Periodic ? grid_.length[2] : 0.0};
    double ref[3] = {kernels::circular_mean_x(first.s[F::Cos], first.s[F::Sin], lx), first.s[F::Y] / core_volume,
                     first.s[F::Z] / core_volume};
    for (int d = 1; d < 3; ++d) {
      if (period[d] == 0.0) continue;
      double cs[2];
      kernels::body_circular_moments(body.psi, xc, d, period[d], box, cut, cs);
      sum_all(comm_, cs);
      ref[d] = std::atan2(cs[1], cs[0]) * period[d] / (2.0 * M_PI);  // in (-L/2, L/2], the domain's range
    }
    auto second = kernels::body_second_moments(body.psi, xc, ref, period, box, cut);
    double m[9];
    for (int a = 0; a < 3; ++a) m[a] = second.m1[a];
    for (int a = 0; a < 6; ++a) m[3 + a] = second.m2[a];
    sum_all(comm_, m);
    double c_local[3];
    for (int a = 0; a < 3; ++a) c_local[a] = ref[a] + m[a] / core_volume;
    // unwrap x: move by whole periods to stay nearest the previous centroid
    const double prev = last_x_[n];
    last_x_[n] = c_local[0] + lx * std::round((prev - c_local[0]) / lx);
    s.centre[0] = last_x_[n] + frame.offset;
    // y, z back into the domain [-L/2, L/2) where periodic
    for (int d = 1; d < 3; ++d)
      if (period[d] > 0.0) c_local[d] -= period[d] * std::floor(c_local[d] / period[d] + 0.5);
    s.centre[1] = c_local[1];
    s.centre[2] = c_local[2];
    for (int a = 0; a < 3; ++a) s.velocity[a] = first.s[F::U + a] / core_volume;
    {
      kernels::RigidGeometry g;
      for (int d = 0; d < 3; ++d) {
        g.xc.x0[d] = xc.x0[d];
        g.xc.h[d] = xc.h[d];
        g.centre[d] = c_local[d];
        g.period[d] = period[d];
      }
      g.radius = g.eps = 0.0;  // not used by the moments
      const RigidMotion fit =
          fit_rigid_motion(kernels::rigid_moments(body.psi, flow.vel, g, grid_.cell_volume(), box), comm_);
      for (int a = 0; a < 3; ++a) s.spin[a] = fit.w[a];
    }
    s.velocity[0] += frame.velocity;
    // covariance about the centroid; an ellipsoid with semi-axis a has <x^2> = a^2 / 5
    const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
    double cov[3][3];
    double shape_m[10] = {core_volume};  // volume, first and second moments that define the shape
    for (int a = 0; a < 9; ++a) shape_m[1 + a] = m[a];
    if (body.model && body.model->edge_half_width_cells() > 0.0) sharp_shape_moments(body, ref, period, shape_m);
    for (int q = 0; q < 6; ++q) {
      const double v = shape_m[0];
      const double val = shape_m[4 + q] / v - (shape_m[1 + ra[q]] / v) * (shape_m[1 + rb[q]] / v);
      cov[ra[q]][rb[q]] = cov[rb[q]][ra[q]] = val;
    }
    double eval[3], evec[3][3];
    symmetric_eigen3(cov, eval, evec);
    for (int a = 0; a < 3; ++a) s.semi_axes[a] = std::sqrt(std::max(0.0, 5.0 * eval[a]));
    s.taylor_D = (s.semi_axes[2] - s.semi_axes[0]) / (s.semi_axes[2] + s.semi_axes[0]);
    // radial direction: from the axis to the centroid (pipe, duct), the wall normal y otherwise
    const bool axial = cfg_.domain.geometry == Geometry::Pipe || cfg_.domain.geometry == Geometry::Duct;
    const double r = std::hypot(s.centre[1], s.centre[2]);
    if (axial && r > 1e-12) {
      s.radial_dir[1] = s.centre[1] / r;
      s.radial_dir[2] = s.centre[2] / r;
    }
    s.r_over_R = (axial ? r : std::fabs(s.centre[1])) / half_width;
    // orientation of the major axis in the (x, radial) plane, folded into (-pi/2, pi/2]
    const double ax = evec[0][2], ar = evec[1][2] * s.radial_dir[1] + evec[2][2] * s.radial_dir[2];
    double angle = std::atan2(ar, ax);
    if (angle > M_PI / 2) angle -= M_PI;
    // a major axis along the radial direction is +pi/2 however round-off tilts it
    if (angle <= -M_PI / 2 + 1e-9) angle += M_PI;
    s.angle = angle;
    if (!body.model->elastic()) {
      // a body without elastic stress is rigid and keeps its shape: what psi's moments show is the
      // grid's imprint (D ~ 3e-3 at 8 cells per d), and a sphere's "major axis" is round-off
      s.taylor_D = 0.0;
      s.angle = 0.0;
      for (double& a : s.semi_axes) a = 0.5 * body.cfg.diameter;
    }
    double v[kForceValues];
    force_vectors(body, flow, frame, v);
    if (last_dt > 0.0) {  // a row: the mean over the interval that this step closes
      add_to_interval(n, v, last_dt);
      auto& acc = impulse_[n];
      for (int q = 0; q < kImpulseValues - 1; ++q) v[3 + q] = acc[q] / acc[kImpulseValues - 1];
      acc = {};
    }
    s.momentum_r = radial_part(v, s.radial_dir);
    for (int term = 0; term < 4; ++term) s.force[term] = radial_part(v + 3 * (term + 1), s.radial_dir);
    for (int term = 0; term < 4; ++term) s.force_paper[term] = radial_part(v + 15 + 3 * term, s.radial_dir);
    out.push_back(s);
  }
  return out;
}

const std::vector<std::string>& particle_columns() {
  static const std::vector<std::string> cols = {
      "step", "t", "solid", "xc", "yc", "zc", "r_over_R", "up", "vp", "wp", "volume", "taylor_D", "angle",
      "F_r", "F_r_pressure", "F_r_inertia", "F_r_viscous", "F_r_elastic", "P_r",
      "F_r_paper", "F_r_paper_inertia", "F_r_paper_viscous", "F_r_paper_elastic", "hold_Fx", "hold_Fy", "hold_Fz", "spin_x", "spin_y", "spin_z"};
  return cols;
}

std::vector<double> particle_row(long step, double t, int body, const ParticleState& s) {
  return {double(step), t, double(body), s.centre[0], s.centre[1], s.centre[2], s.r_over_R, s.velocity[0],
          s.velocity[1], s.velocity[2], s.volume, s.taylor_D, s.angle, s.force_total(), s.force[0], s.force[1],
          s.force[2], s.force[3], s.momentum_r, s.force_paper_total(), s.force_paper[1], s.force_paper[2],
          s.force_paper[3], s.hold_force[0], s.hold_force[1], s.hold_force[2], s.spin[0], s.spin[1], s.spin[2]};
}

}  // namespace eulerfsi

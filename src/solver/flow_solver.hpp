#pragma once
// The single-continuum momentum solver: low-storage RK3 with a projection in every substep
// (Kim & Moin 1985), implicit volume penalization of the pipe wall, constant flow rate.
#include <memory>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "parallel/comm.hpp"
#include "kernels/projection.hpp"
#include "poisson/helmholtz_solver.hpp"
#include "poisson/poisson_solver.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/flow_state.hpp"
#include "solver/rk3.hpp"
#include "solver/solid_coupling.hpp"

namespace eulerfsi {

struct FlowDiagnostics {
  double cfl = 0.0;
  double bulk_u = 0.0;
  double dpdx = 0.0;
  double max_div = 0.0;
  double kinetic_energy = 0.0;  // volume average of |u|^2 / 2 (laboratory frame)
  bool finite = true;
};

class FlowSolver {
 public:
  FlowSolver(const CaseConfig& cfg, const Grid& grid, const Comm& comm);
  ~FlowSolver();

  void set_initial_condition();
  // Projects the current velocity onto divergence-free fields with the imposed flow rate.
  void make_solenoidal();
  // Largest stable step: the CFL limit on (|u| + sqrt(G)) / h and the explicit viscous limit.
  double stable_dt(double extra_wave_speed = 0.0) const;
  // The largest speed the last stable_dt saw, at least: max (|u_d| + c) / h_d times the finest h,
  // less c (the driver's runaway test reads it without a second reduction over the grid).
  double last_speed_bound() const { return last_speed_bound_; }
  // One RK3 step of size dt from time t; the solids (if any) advance inside each substep.
  void advance(double t, double dt, SolidCoupling* solids = nullptr);
  FlowDiagnostics diagnostics(double dt, double wave_speed = 0.0) const;

  FlowState& state() { return state_; }
  const FlowState& state() const { return state_; }
  const Grid& grid() const { return grid_; }
  const BoundaryConditions& boundaries() const { return bc_; }
  const WallMasks& masks() const { return masks_; }
  Field3 viscosity() const { return mu_; }
  double dpdx() const { return dpdx_; }
  void set_dpdx(double v) { dpdx_ = v; }
  bool has_flow_rate() const { return impose_flow_rate_; }
  // bulk velocity over the open cross-section, in the grid's frame and in the laboratory
  double bulk_velocity() const;
  double lab_bulk_velocity() const;

  // The grid's frame moves along x with frame_velocity(); the state holds u - frame_velocity.
  // Changing it shifts u (a Galilean transformation: the laboratory flow is unchanged).
  double frame_velocity() const { return frame_u_; }
  void set_frame_velocity(double u_frame, double t);
  // x of the grid's origin in the laboratory (integral of the frame velocity)
  double frame_offset() const { return frame_x_; }
  // A checkpoint's frame: the stored velocity is already relative to it (no shift).
  void restore_frame(double u_frame, double offset) {
    frame_u_ = u_frame;
    frame_x_ = offset;
    bc_.set_frame_velocity(u_frame);
  }

 private:
  void build_wall_masks();
  // The projection, and with a constant flow rate its uniform correction in the same pass;
  // returns that correction du (0 without one).
  double project(double alpha_dt, const kernels::StepPressure& step = {});
  void predict(double dt, int substep, const SolidCoupling* solids, const Box& mixture);
  void predict_implicit_viscosity(double t_next, double dt, int substep);
  // du that brings the bulk velocity back to U_b, from this rank's open-face sum of u
  double flow_rate_correction(double open_sum) const;
  // lab_bulk_velocity from this rank's open-face sum of u
  double lab_bulk_velocity(double open_sum) const;

  CaseConfig cfg_;
  Grid grid_;
  Comm comm_;
  BoundaryConditions bc_;
  FlowState state_;
  kernels::Velocity rhs_new_, rhs_old_;
  Field3 mu_;
  WallMasks masks_;
  kernels::Mask2 no_wall_;  // one row of zeros: the mask of a component without a wall (stride 0)
  std::unique_ptr<PoissonSolver> poisson_;
  double mu_fluid_;
  // time.implicit_viscosity: mu_f by Crank-Nicolson (the solver and its right-hand side), the
  // explicit momentum then carries only mu - mu_f (mu_explicit_ is its value in the fluid)
  std::unique_ptr<HelmholtzSolver> helmholtz_;
  Field3 implicit_rhs_;
  double mu_explicit_ = 0.0;
  double dpdx_applied_ = 0.0;  // the mean pressure gradient in this step's predictor
  double open_faces_ = 1.0;    // x-faces the flow-rate correction moves, weighted by their share
  double inside_faces_ = 1.0;  // global count of x-faces inside the pipe (the flow-rate sum)
  double flow_faces_ = 1.0;    // the cross-section the bulk velocity is over, in face areas (times Nx)
  bool impose_flow_rate_ = false;
  double dpdx_ = 0.0;
  double frame_u_ = 0.0, frame_x_ = 0.0;
  mutable double last_speed_bound_ = 0.0;  // a by-product of stable_dt (see last_speed_bound)
};

}  // namespace eulerfsi

#pragma once
// What the paper reports about each particle, per output step: unwrapped centroid, radial
// position, velocity, volume, Taylor deformation and orientation, radial force and its parts.
#include <array>
#include <string>
#include <vector>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_phase.hpp"
#include "solver/flow_state.hpp"

namespace eulerfsi {

struct ParticleState {
  double centre[3] = {0, 0, 0};  // x unwrapped across the periodic boundary
  double velocity[3] = {0, 0, 0};
  double volume = 0.0;
  double r_over_R = 0.0;         // distance from the axis (pipe, duct) or mid-plane (channel, couette) over Ly/2
  double taylor_D = 0.0;         // (L - B) / (L + B) of the equivalent ellipsoid
  double angle = 0.0;            // major axis against x, in the plane of x and the radial direction [rad]
  double semi_axes[3] = {0, 0, 0};
  double radial_dir[3] = {0, 1, 0};
  // Radial force that changes the radial momentum P_r = int psi u . e_r (e_r at this instant):
  // pressure, inertia (with the momentum psi's transport carries, int u_r dpsi/dt), viscous
  // (mixture viscosity), elastic (the solver's stress divergence, interface included). The last
  // step's, or on an output row the mean over the steps since the previous row (measure).
  double force[4] = {0, 0, 0, 0};
  double momentum_r = 0.0;
  // The paper's eq. (force): pressure (as above), -int psi div(u u) at fixed laboratory points,
  // int psi mu_s div(2E), int psi G div B; their sum is int psi du_r/dt, not dP_r/dt.
  double force_paper[4] = {0, 0, 0, 0};
  // The force that holds a constrained body (solid.constraint), mean over the last step; 0 when free.
  double hold_force[3] = {0, 0, 0};
  // Angular velocity: the rigid motion that fits the body's velocity about its centroid, weighted by
  // psi (src/solid/rigid_fit.hpp); a rigid body's own, a soft body's mean spin.
  double spin[3] = {0, 0, 0};
  double force_total() const { return force[0] + force[1] + force[2] + force[3]; }
  double force_paper_total() const { return force_paper[0] + force_paper[1] + force_paper[2] + force_paper[3]; }
};

// The grid's frame in the laboratory: it moves along x with `velocity` and has moved by `offset`.
struct GridFrame {
  double velocity = 0.0;
  double offset = 0.0;
};

class ParticleTracker {
 public:
  ParticleTracker(const CaseConfig& cfg, const Grid& grid, const Comm& comm);
  // Measures every body in the laboratory frame; keeps the unwrapped x-centroid continuous
  // between calls. last_dt > 0 (an output row): the forces of the step just taken, last_dt long,
  // close the interval since the previous row and the state reports the interval's mean forces
  // (accumulate_forces), which then start anew; 0: the last step's forces alone.
  std::vector<ParticleState> measure(const SolidPhase& solids, const FlowState& flow, const GridFrame& frame = {},
                                     double last_dt = 0.0);
  // The forces of the step just taken, dt long, join the impulse of the interval that the next
  // row reports as its mean: a row then neither samples one step's spike (a cell joining or
  // leaving the solid, docs/REFERENCE_MAP.md) nor loses the impulse between rows, so the rows'
  // sum of F dt is the change of P_r, as the steps' is.
  void accumulate_forces(const SolidPhase& solids, const FlowState& flow, const GridFrame& frame, double dt);
  // The interval's impulse so far (kImpulseValues per body), for checkpoints.
  static constexpr int kImpulseValues = 25;
  std::vector<double> force_impulse() const;
  void set_force_impulse(const std::vector<double>& values);
  // Mean x-velocity of one body in the laboratory (two reductions; for a frame that follows it).
  double mean_x_velocity(const SolidPhase& solids, const FlowState& flow, size_t body, double frame_velocity) const;
  // The unwrapped x of each body in the grid's frame so far (for checkpoints).
  std::vector<double> unwrapped_x() const { return last_x_; }
  void set_unwrapped_x(std::vector<double> x) { last_x_ = std::move(x); }

 private:
  // The body's momentum (3) and the force vectors that change it (budget: pressure, inertia,
  // viscous, elastic, 12) and the paper's decomposition (12), summed over the ranks.
  static constexpr int kForceValues = 27;
  void force_vectors(const SolidBody& body, const FlowState& flow, const GridFrame& frame,
                     double (&out)[kForceValues]) const;
  // Adds the step's force vectors (force_vectors' after the momentum), dt long, to body n's interval.
  void add_to_interval(size_t n, const double (&v)[kForceValues], double dt);
  // Volume, first and second moments about `ref` of the body's sharp shape (edge width -> 0).
  void sharp_shape_moments(const SolidBody& body, const double ref[3], const double period[3], double out[10]) const;

  CaseConfig cfg_;
  Grid grid_;
  Comm comm_;
  std::vector<double> last_x_;  // unwrapped x-centroid at the previous measurement
  // per body: sum of dt times the 24 force vectors of force_vectors (after the momentum) over the
  // steps since the last row, then the sum of dt
  std::vector<std::array<double, kImpulseValues>> impulse_;
};

// particle.csv columns, one row per body per output step.
const std::vector<std::string>& particle_columns();
std::vector<double> particle_row(long step, double t, int body, const ParticleState& s);

// Eigen-decomposition of a symmetric 3x3 matrix (Jacobi rotations): values ascending, vectors as columns.
void symmetric_eigen3(const double a[3][3], double values[3], double vectors[3][3]);

}  // namespace eulerfsi

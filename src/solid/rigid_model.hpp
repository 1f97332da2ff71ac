#pragma once
// A rigid sphere in the one continuum: the limit G -> infinity done directly (the fictitious-domain
// method of Sharma & Patankar 2005, J. Comput. Phys. 205). Each substep the flow is predicted and
// projected on the whole domain as for a soft body; then the velocity inside the body is replaced,
// blended by psi, by the rigid motion that carries the body's psi-weighted linear and angular
// momentum (U = sum psi u / sum psi, w = I^-1 sum psi r x u), which conserves both exactly, and
// projected again so that the flow stays divergence-free (the second projection is what keeps the
// edge cells from a divergence of order U h / eps; it bends the rigid motion by as much).
// The shape never changes: psi = H_eps(a - |x - c|) from the centre c, moved by the body's velocity
// with the RK3 weights, x_c^(k+1) = x_c^k + dt (gamma_k U^k + zeta_k U^(k-1)). B = I: no elastic
// stress. psi, B and B_prev live on a window that follows the body (src/solid/solid_window.hpp).
// Constraints (solid.constraint): "fixed" removes U and w, "radial" the cross-section components
// U_y, U_z; the momentum they remove per unit time is the force that holds the body, written to
// particle.csv (hold_Fx, hold_Fy, hold_Fz): at a steady state the fluid's force is its opposite,
// so the lift on a body held at (y, z) is -hold_F.
#include <array>
#include <vector>

#include "kernels/rigid_body.hpp"
#include "solid/rigid_fit.hpp"
#include "solid/solid_model.hpp"
#include "solid/solid_window.hpp"

namespace eulerfsi {

class RigidModel final : public SolidModel {
 public:
  RigidModel(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid, const Comm& comm);
  void allocate(SolidBody& body, const Grid& grid) override;
  void set_initial_condition(SolidBody& body) override;
  void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  std::map<std::string, double> checkpoint_scalars() const override;
  void restore_scalars(const std::map<std::string, double>& s) override;
  void fill_ghosts(SolidBody& body) override;
  Box active_box() const override { return active_; }
  Box psi_box() const override { return psi_box_; }
  // no elastic force reads it: nothing allocated
  kernels::Scratch3 scratch() override { return {{scratch_[0], scratch_[1], scratch_[2]}}; }
  bool elastic() const override { return false; }
  bool constrains_velocity() const override { return true; }
  void constrain_velocity(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  std::array<double, 3> holding_force() const override { return force_; }
  // This rank's cells of a sphere's window at its initial position (x_whole: the window spans x,
  // as once the body crosses the periodic x end), for estimates made before a run.
  static double window_cells(const SolidConfig& s, const Grid& g, bool x_whole);

 private:
  kernels::RigidGeometry geometry() const;
  std::array<bool, 6> held() const;  // (U_x, U_y, U_z, w_x, w_y, w_z) held by the constraint
  void place(SolidBody& body, bool always_move = false);  // psi, its window and the active box from the centre
  std::vector<SolidWindow::Member> window_members(SolidBody& body) const;

  SolidConfig cfg_solid_;
  Grid grid_;
  Comm comm_;
  double centre_[3];        // grid frame; x in [0, Lx)
  double velocity_[3] = {0, 0, 0};       // U at the last substep's start (RK3 memory)
  double impulse_[3] = {0, 0, 0};        // the constraint's impulse summed over this step's substeps
  std::array<double, 3> force_{0, 0, 0};  // its mean force over the last step
  SolidWindow window_;
  Box active_, psi_box_;
  RigidMotion imposed_;         // the rigid motion of the last correction
  bool imposed_known_ = false;  // false until the first correction (and after a restart)
  Field3 scratch_[3];
};

}  // namespace eulerfsi

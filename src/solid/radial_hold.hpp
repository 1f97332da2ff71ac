#pragma once
// solid.constraint = "radial" for a soft body: its centroid held at the configured (y, z) by a
// uniform acceleration over the body (kernels/radial_hold.hpp), so that the same lift map can be
// drawn for a soft particle as for a rigid one. After each projection the body's psi-weighted
// cross-stream momentum is set to bring its centroid's offset e_D back, critically damped over tau
// (a proportional-integral law: the projection that follows gives part of the push to the fluid
// around the body, and the integral E_D = int e_D dt takes up what it keeps from the body):
//   sum psi_D u'_D = -mass_D (2 e_D / tau + E_D / tau^2),  u'_D = u_D + psi_D V_D
//   =>  V_D = (-mass_D (2 e_D / tau + E_D / tau^2) - sum psi_D u_D) / sum psi_D^2   (D = y, z)
// and the flow is projected again. The impulse V_D mass_D summed over a step's substeps, over dt,
// is the holding force (particle.csv hold_Fy, hold_Fz); at a steady state the fluid's lift on the
// body is its opposite. The body's deformation, its x-motion and its spin stay free.
#include <array>
#include <map>
#include <string>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_body.hpp"

namespace eulerfsi {

class RadialHold {
 public:
  RadialHold(const SolidConfig& solid, const Grid& grid, const Comm& comm);
  // The substep's correction on the faces of the body's window (collective).
  void apply(const SolidBody& body, const kernels::Velocity& vel, double dt, int substep);
  // The mean force over the last step (x: 0, the body is free along x).
  std::array<double, 3> force() const { return {0.0, force_[0], force_[1]}; }
  std::map<std::string, double> checkpoint_scalars() const;
  void restore_scalars(const std::map<std::string, double>& s);

 private:
  Grid grid_;
  Comm comm_;
  double target_[2];             // the held (y, z)
  double impulse_[2] = {0, 0};   // summed over this step's substeps
  double force_[2] = {0, 0};     // its mean over the last step
  double integral_[2] = {0, 0};  // E_D = int e_D dt
};

}  // namespace eulerfsi

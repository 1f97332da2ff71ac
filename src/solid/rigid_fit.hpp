#pragma once
// The rigid motion that fits a body's velocity: the psi-weighted least squares over the faces
// (kernels/rigid_body.hpp, RigidMoments), whose blend changes neither the flow's momentum nor its
// angular momentum about the reference point:
//   mass_D U_D + (w x first_D)_D = momentum_D,   sum_D U_D (first_D x e_D) + inertia w = angular.
// The rigid body uses it to make its velocity rigid; the diagnostics to measure every body's spin.
#include <array>

#include "kernels/rigid_body.hpp"
#include "parallel/comm.hpp"

namespace eulerfsi {

struct RigidMotion {
  double U[3] = {0, 0, 0};  // translation of the reference point
  double w[3] = {0, 0, 0};  // angular velocity
};

// `local`: this rank's sums (MPI-summed here, collective); held[q] = true: component q of
// (U_x, U_y, U_z, w_x, w_y, w_z) is 0 and its row dropped.
RigidMotion fit_rigid_motion(const kernels::RigidMoments& local, const Comm& comm,
                             const std::array<bool, 6>& held = {false, false, false, false, false, false});

}  // namespace eulerfsi

#include "solid/radial_hold.hpp"

#include <stdexcept>

#include "kernels/radial_hold.hpp"
#include "solver/rk3.hpp"

namespace eulerfsi {

namespace {

// tau in time steps: slow enough that the feedback adds little to a step's force, fast enough
// that the body stays within ~1e-3 d of its place while the lift builds up
constexpr double kRelaxSteps = 10.0;

}  // namespace

RadialHold::RadialHold(const SolidConfig& solid, const Grid& grid, const Comm& comm)
    : grid_(grid), comm_(comm), target_{solid.center[1], solid.center[2]} {}

void RadialHold::apply(const SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  // faces whose two cells the window holds (psi = 0 on the window's outer cells), owned cells only
  Box faces = body.psi.window();
  for (int d = 0; d < 3; ++d) faces.hi[d] -= 1;
  faces = intersection(faces, grid_.interior());
  const kernels::CellCentres xc{{grid_.centre(0, 0), grid_.centre(1, 0), grid_.centre(2, 0)},
                                {grid_.h[0], grid_.h[1], grid_.h[2]}};
  double period[2];
  for (int d = 0; d < 2; ++d) period[d] = grid_.bc[d + 1] == Boundary::Periodic ? grid_.length[d + 1] : 0.0;
  kernels::RadialHoldSums s = kernels::radial_hold_sums(body.psi, vel, xc, target_, period, grid_.cell_volume(), faces);
  double* all = &s.mass[0];
  for (int n = 0; n < kernels::RadialHoldSums::Count; ++n) all[n] = comm_.sum(all[n]);
  double V[2] = {0.0, 0.0}, offset[2] = {0.0, 0.0};
  const double tau = kRelaxSteps * dt;
  for (int d = 0; d < 2; ++d) {
    if (s.square[d] <= 0.0) continue;  // no body (cannot happen while it is inside the domain)
    offset[d] = s.offset[d] / s.mass[d];
    V[d] = (-s.mass[d] * (2.0 * offset[d] / tau + integral_[d] / (tau * tau)) - s.momentum[d]) / s.square[d];
  }
  kernels::radial_hold_push(vel, body.psi, V, faces);
  if (substep == 0) impulse_[0] = impulse_[1] = 0.0;
  for (int d = 0; d < 2; ++d) impulse_[d] += V[d] * s.mass[d];
  if (substep + 1 == Rk3::stages)
    for (int d = 0; d < 2; ++d) {
      force_[d] = impulse_[d] / dt;
      integral_[d] += offset[d] * dt;
    }
}

std::map<std::string, double> RadialHold::checkpoint_scalars() const {
  return {{"hold_fy", force_[0]}, {"hold_fz", force_[1]}, {"hold_iy", integral_[0]}, {"hold_iz", integral_[1]}};
}

void RadialHold::restore_scalars(const std::map<std::string, double>& s) {
  const char* names[4] = {"hold_fy", "hold_fz", "hold_iy", "hold_iz"};
  double* values[4] = {&force_[0], &force_[1], &integral_[0], &integral_[1]};
  for (int n = 0; n < 4; ++n) {
    const auto it = s.find(names[n]);
    if (it == s.end()) throw std::runtime_error(std::string("checkpoint: the held body has no '") + names[n] + "'");
    *values[n] = it->second;
  }
}

}  // namespace eulerfsi

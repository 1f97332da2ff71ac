#pragma once
// The soft bodies of a case: each carries psi and B; together they give the mixture viscosity
// and the elastic stress div[ sum_s psi_s G_s (B_s - I) ] that the momentum equation feels.
#include <vector>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "kernels/solid_fields.hpp"
#include "parallel/comm.hpp"
#include "solver/boundary_conditions.hpp"

namespace eulerfsi {

struct SolidBody {
  SolidConfig cfg;
  double G = 1.0;      // shear modulus 1/We
  double mu_s = 0.0;   // solid viscosity (viscosity_ratio / Re)
  Field3 psi;          // volume fraction
  kernels::Tensor6 b;        // B at the current substep
  kernels::Tensor6 b_prev;   // B before the latest update (Crank-Nicolson average with b)
  Field3 psi_rhs_old;        // RK3 memory (zeta term)
  kernels::Tensor6 b_rhs_old;
  Field3 psi_rhs;            // scratch for the current substep
  kernels::Tensor6 b_rhs;
};

class SolidPhase {
 public:
  SolidPhase(const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc, const Comm& comm);
  bool empty() const { return bodies_.empty(); }
  std::vector<SolidBody>& bodies() { return bodies_; }
  const std::vector<SolidBody>& bodies() const { return bodies_; }

  // psi from the initial shape (cell volume fraction by sub-sampling), B = I.
  void set_initial_condition();
  // Initial velocity "rest": u_face *= 1 - psi_face for the bodies that start at rest.
  void stop_bodies_at_rest(const kernels::Velocity& vel) const;
  // Sum of every body's psi (for output), into `out`.
  void total_volume_fraction(const Field3& out) const;
  // (i) of the substep: psi and B of every body advanced by one RK3 substep.
  void advance_substep(const kernels::Velocity& vel, double dt, int substep);
  // mu = mu_f + sum_s psi_s (mu_s - mu_f), ghosts included.
  void mixture_viscosity(const Field3& mu, double mu_fluid) const;
  // rhs_D += d/dx_E [ psi G ((B^k + B^(k-1))/2 - I)_DE ] for every body.
  void add_elastic_force(const kernels::Velocity& rhs) const;
  // Fastest elastic shear-wave speed sqrt(G) among the bodies (0 without bodies).
  double max_wave_speed() const;

 private:
  void sharpen(SolidBody& body);
  void extend_tensor(SolidBody& body) const;
  void clip_conserving(const Field3& psi) const;

  CaseConfig cfg_;
  Grid grid_;
  const BoundaryConditions* bc_;
  Comm comm_;
  std::vector<SolidBody> bodies_;
};

}  // namespace eulerfsi

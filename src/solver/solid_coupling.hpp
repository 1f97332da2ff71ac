#pragma once
// What the momentum equation needs from the soft bodies, whatever model carries them
// (src/solid/): the solver calls these and knows nothing else about solids.
//   du/dt + div(u u) = -grad p + div[2 mu(psi) E] + div[sum_s psi_s G_s (B_s - I)] + ...
#include "kernels/momentum.hpp"
#include "kernels/predictor_terms.hpp"

namespace eulerfsi {

class SolidCoupling {
 public:
  virtual ~SolidCoupling() = default;
  // (i) of the substep: every body's shape and deformation advanced with the current velocity.
  virtual void advance_substep(const kernels::Velocity& vel, double dt, int substep) = 0;
  // mu = background + sum_s psi_s (mu_s - mu_f), ghosts included: background = mu_f gives the
  // mixture viscosity, 0 its part beyond mu_f (when mu_f is taken implicitly). `mu` must hold
  // `background` outside viscosity_region() on entry (the solver's mu is written by this call only).
  virtual void mixture_viscosity(const Field3& mu, double mu_fluid, double background) = 0;
  // Where the last mixture_viscosity() call left mu != background possible (storage indices,
  // ghosts included); outside it the momentum equation takes the constant-viscosity path.
  virtual Box viscosity_region() const = 0;
  // rhs_D += d/dx_E [ psi G ((B^k + B^(k-1))/2 - I)_DE ] for every body.
  virtual void add_elastic_force(const kernels::Velocity& rhs) const = 0;
  // The same force after a predictor that left it out (kernels::ElasticForces<true>): rhs^k
  // += f and u* (`star`) += terms.a f / (1 + pen), with the predictor's terms.
  virtual void add_elastic_force_to_predictor(const kernels::Velocity& rhs, const kernels::Velocity& star,
                                              const kernels::PredictorTerms& terms) const = 0;
  // A box holding every face add_elastic_force() writes (storage indices; empty: none).
  virtual Box elastic_force_region() const = 0;
  // Fastest elastic shear-wave speed sqrt(G) among the bodies (enters the CFL condition).
  virtual double max_wave_speed() const = 0;
  // After the projection (iv): bodies that constrain the velocity (rigid ones) act on it; true if
  // one did, and the flow must be projected again.
  virtual bool constrain_velocity(const kernels::Velocity&, double /*dt*/, int /*substep*/) { return false; }
};

}  // namespace eulerfsi

#pragma once
// One soft body as the momentum equation and the diagnostics see it, whatever model carries it:
// the volume fraction psi, the left Cauchy-Green tensor B (before and after the latest update),
// the shear modulus and the solid viscosity. How psi and B move is the model's business
// (src/solid/solid_model.hpp).
#include <memory>

#include "config/case_config.hpp"
#include "core/types.hpp"
#include "kernels/solid_fields.hpp"

namespace eulerfsi {

class SolidModel;
class RadialHold;

struct SolidBody {
  SolidConfig cfg;
  double G = 1.0;      // shear modulus 1/We
  double mu_s = 0.0;   // solid viscosity (viscosity_ratio / Re)
  WindowField psi;     // volume fraction (on the body's window, src/solid/solid_window.hpp)
  kernels::Tensor6 b;        // B at the current substep
  kernels::Tensor6 b_prev;   // B before the latest update (Crank-Nicolson average with b)
  std::shared_ptr<SolidModel> model;  // how psi and B are carried (paper, reference map or rigid)
  std::shared_ptr<RadialHold> hold;   // a soft body held at its (y, z) (constraint "radial"); else none
};

}  // namespace eulerfsi

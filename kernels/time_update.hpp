#pragma once
// Low-storage RK3 substep with implicit volume penalization (Kadoch et al. 2012):
//   u* = [u^k + dt (gamma rhs^k + zeta rhs^(k-1))] / (1 + alpha dt chi / eta)
// chi(j,k) is the x-independent solid-wall mask at the component's staggered location.
#include "core/types.hpp"

namespace eulerfsi::kernels {

using Mask2 = Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>;

inline void rk3_update(const Field3& u, const Field3& rhs_new, const Field3& rhs_old, const Mask2& chi, double dt,
                       double gamma, double zeta, double penal_factor, const Box& box, const char* label) {
  // penal_factor = alpha dt / eta; chi empty means no penalization
  const bool has_mask = chi.extent(0) > 0;
  Kokkos::parallel_for(label, box.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    double val = u(i, j, k) + dt * (gamma * rhs_new(i, j, k) + zeta * rhs_old(i, j, k));
    if (has_mask) val /= 1.0 + penal_factor * chi(j, k);
    u(i, j, k) = val;
  });
}

}  // namespace eulerfsi::kernels

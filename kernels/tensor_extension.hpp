#pragma once
// B outside the solid: constant extension from the solid into a band, identity beyond it.
//
// B means something only where there is solid. In the cells round a particle that numerical
// diffusion gives a small psi, B transported with the fluid's velocity accumulates the fluid's
// strain without bound (tr(B - I) ~ 10..500 measured at psi < 0.1), and psi G (B - I) there
// becomes an elastic skin stiffer than the particle itself. Instead, as level-set and
// reference-map methods do with quantities defined on one side of an interface (e.g. Aslam 2004;
// Valkov, Rycroft & Kamrin 2015), B is extended: cells with psi >= psi_solid (and B positive
// definite) are "known"; each sweep gives every unknown cell with known neighbours the mean of
// their B (so B outside never exceeds the solid's own range and stays positive definite); after
// `band` sweeps the cells still unknown get B = I. The WENO5 stencils (3 cells) at the edge
// then see the solid's own B upwind instead of the fluid's strain.
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/solid_fields.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

// known = 1 where psi >= psi_solid and B is positive definite (the solid's own B), else 0.
inline void mark_solid_tensor(const Field3& known, const Field3& psi, const Tensor6& b, double psi_solid,
                              const Box& box) {
  for_each_cell("eulerfsi::solid::b_mark", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const bool spd = positive_definite(b.c[XX](i, j, k), b.c[YY](i, j, k), b.c[ZZ](i, j, k), b.c[XY](i, j, k),
                                       b.c[XZ](i, j, k), b.c[YZ](i, j, k));
    known(i, j, k) = (psi(i, j, k) >= psi_solid && spd) ? 1.0 : 0.0;
  });
}

// Sweep s (1, 2, ...): an unknown cell with neighbours known before this sweep (0 < known <= s)
//   B = (1/n) sum over those n face neighbours of B,   known = s + 1.
// In place: the cells written are unknown, the cells read were known before the sweep, so no
// cell is both read and written and the result does not depend on the order.
inline void extend_tensor_sweep(const Tensor6& b, const Field3& known, int sweep, const Box& box) {
  const double s = double(sweep);
  for_each_cell("eulerfsi::solid::b_extend", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (known(i, j, k) != 0.0) return;
    const int ni[6] = {i - 1, i + 1, i, i, i, i}, nj[6] = {j, j, j - 1, j + 1, j, j}, nk[6] = {k, k, k, k, k - 1, k + 1};
    double sum[kTensorComponents] = {0, 0, 0, 0, 0, 0};
    int n = 0;
    for (int q = 0; q < 6; ++q) {
      const double kn = known(ni[q], nj[q], nk[q]);
      if (kn <= 0.0 || kn > s) continue;
      ++n;
      for (int c = 0; c < kTensorComponents; ++c) sum[c] += b.c[c](ni[q], nj[q], nk[q]);
    }
    if (n == 0) return;
    for (int c = 0; c < kTensorComponents; ++c) b.c[c](i, j, k) = sum[c] / n;
    known(i, j, k) = s + 1.0;
  });
}

// Beyond the band: B = I.
inline void reset_unknown_tensor(const Tensor6& b, const Field3& known, const Box& box) {
  for_each_cell("eulerfsi::solid::b_reset_far", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (known(i, j, k) == 0.0)
      for (int c = 0; c < kTensorComponents; ++c) b.c[c](i, j, k) = c < 3 ? 1.0 : 0.0;
  });
}

}  // namespace eulerfsi::kernels

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
#include "kernels/bounding_box.hpp"
#include "kernels/solid_fields.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

// known = 1 where psi >= psi_solid and B is positive definite (the solid's own B), else 0.
inline void mark_solid_tensor(const WindowField& known, const WindowField& psi, const Tensor6& b, double psi_solid,
                              const Box& box) {
  for_each_cell("eulerfsi::solid::b_mark", box, KOKKOS_LAMBDA(int i, int j, int k) {
    // most cells are fluid: B is read only inside the solid
    known(i, j, k) = (psi(i, j, k) >= psi_solid &&
                      positive_definite(b.c[XX](i, j, k), b.c[YY](i, j, k), b.c[ZZ](i, j, k), b.c[XY](i, j, k),
                                        b.c[XZ](i, j, k), b.c[YZ](i, j, k)))
                         ? 1.0
                         : 0.0;
  });
}

// Sweep s (1, 2, ...): an unknown cell with neighbours known before this sweep (0 < known <= s)
//   B = (1/n) sum over those n face neighbours of B,   known = s + 1.
// In place: the cells written are unknown, the cells read were known before the sweep, so no
// cell is both read and written and the result does not depend on the order.
inline void extend_tensor_sweep(const Tensor6& b, const WindowField& known, int sweep, const Box& box) {
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

// Beyond the band: B = I (written only where it is not I already: far from the solid B stays I
// from one substep to the next, and a read costs less than a write).
inline void reset_unknown_tensor(const Tensor6& b, const WindowField& known, const Box& box) {
  for_each_cell("eulerfsi::solid::b_reset_far", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (known(i, j, k) != 0.0) return;
    bool identity = true;
    for (int c = 0; c < kTensorComponents; ++c) identity = identity && b.c[c](i, j, k) == (c < 3 ? 1.0 : 0.0);
    if (!identity)
      for (int c = 0; c < kTensorComponents; ++c) b.c[c](i, j, k) = c < 3 ? 1.0 : 0.0;
  });
}

// B = I on `box` (written only where it is not I already).
inline void reset_tensor(const Tensor6& b, const Box& box) {
  for_each_cell("eulerfsi::solid::b_reset", box, KOKKOS_LAMBDA(int i, int j, int k) {
    bool identity = true;
    for (int c = 0; c < kTensorComponents; ++c) identity = identity && b.c[c](i, j, k) == (c < 3 ? 1.0 : 0.0);
    if (!identity)
      for (int c = 0; c < kTensorComponents; ++c) b.c[c](i, j, k) = c < 3 ? 1.0 : 0.0;
  });
}

// The whole extension on `box` from valid ghosts of psi and B (band <= kGhost): the mark covers
// the ghosts too and sweep s runs on box grown by band - s cells, so the cells a later sweep reads
// across a rank boundary or a wall are computed here from the same inputs as on their owner (or
// as their mirror image), and no exchange is needed between sweeps.
// Sweep s can only reach cells within s face steps of a known one, so the sweeps run on the
// bounding box of the known cells grown by s (the particle, not the whole domain).
inline void extend_tensor(const Tensor6& b, const WindowField& known, const WindowField& psi, double psi_solid, int band,
                          const Box& box) {
  auto grown = [](const Box& x, int g) {
    return Box{{x.lo[0] - g, x.lo[1] - g, x.lo[2] - g}, {x.hi[0] + g, x.hi[1] + g, x.hi[2] + g}};
  };
  mark_solid_tensor(known, psi, b, psi_solid, grown(box, band));
  Box solid;
  const bool any = known_bounding_box(known, grown(box, band), solid);
  for (int sweep = 1; any && sweep <= band; ++sweep) {
    const Box reach = grown(solid, sweep), limit = grown(box, band - sweep);
    Box x;
    bool empty = false;
    for (int d = 0; d < 3; ++d) {
      x.lo[d] = reach.lo[d] > limit.lo[d] ? reach.lo[d] : limit.lo[d];
      x.hi[d] = reach.hi[d] < limit.hi[d] ? reach.hi[d] : limit.hi[d];
      empty = empty || x.lo[d] >= x.hi[d];
    }
    if (!empty) extend_tensor_sweep(b, known, sweep, x);
  }
  reset_unknown_tensor(b, known, box);
}

}  // namespace eulerfsi::kernels

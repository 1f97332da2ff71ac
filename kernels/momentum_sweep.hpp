#pragma once
// The host path of momentum_rhs (kernels/momentum.hpp) with every flux computed once:
//   rhs_D(c) = -sum_X [U_DX(c) - U_DX(c - e_X)] / h_X,   X = D, E1, E2 in that order,
// U_DX(c) the flux of D-momentum through the upper X-face of the cell at c: the normal flux at the
// centre c + e_D/2 for X = D, the shear flux at the edge c + e_D/2 + e_X/2 otherwise (the same
// expressions as MomentumRhs, so the same numbers). The per-cell form evaluates each flux twice,
// once for each cell it separates. Here a thread walks its x-slab plane by plane and each plane row
// by row, and keeps the fluxes it just computed: the x-faces of the previous plane and the y-faces
// of the previous row (one extra plane per slab and one extra row per plane at the start): 4 flux
// evaluations per component and cell instead of 6. GPUs keep the per-cell form (one thread per
// cell, no order).
#include <algorithm>
#include <vector>

#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum_fluxes.hpp"
#include "kernels/predictor_terms.hpp"

namespace eulerfsi::kernels {

// Predict: the RK3 predictor of kernels/momentum_predictor.hpp in the same pass (rhs, then u*
// over rhs_old); Force: rhs holds the elastic force on entry, added to the momentum terms.
template <bool Uniform, bool Predict = false, bool Force = false>
struct MomentumSweep {
  double* rhs[3];
  const double* u[3];
  const double* mu;  // null when Uniform
  double mu_uniform;
  double ih[3];
  long st[3];  // strides of the shared layout (st[2] = 1)
  PredictorTerms predictor{};  // read only when Predict

  // U_DX(c) on local copies of the pointers: the loops below then see no stores that could change them.
  template <int D, int X>
  KOKKOS_FORCEINLINE_FUNCTION static double flux(const double* KOKKOS_RESTRICT uD, const double* KOKKOS_RESTRICT uX,
                                                 const double* KOKKOS_RESTRICT m, double mu0, long c, long sD,
                                                 long sX, double ihD, double ihX) {
    if constexpr (X == D) {
      return normal_flux_at<Uniform>(uD, m, mu0, c + sD, sD, ihD);
    } else {
      return shear_flux_at<D, X, Uniform>(uD, uX, m, mu0, c, sD, sX, ihD, ihX);
    }
  }
  template <int D, int X>
  KOKKOS_FORCEINLINE_FUNCTION double upper_flux(long c) const {
    return flux<D, X>(u[D], u[X], mu, mu_uniform, c, st[D], st[X], ih[D], ih[X]);
  }

  // One row (i, j) of component D. plane[k]: U_D0 of the previous plane, row[k]: U_D1 of the
  // previous row, both replaced by this row's. The z-faces are computed twice, in one loop: a
  // separate pass that kept them cost more than it saved where the loop runs 8 wide (AVX-512).
  template <int D>
  void row_of(long base, int j, int k0, int k1, double* KOKKOS_RESTRICT plane, double* KOKKOS_RESTRICT row) const {
    const double* KOKKOS_RESTRICT uD = u[D] + base;
    const double* KOKKOS_RESTRICT ux = u[0] + base;
    const double* KOKKOS_RESTRICT uy = u[1] + base;
    const double* KOKKOS_RESTRICT uz = u[2] + base;
    const double* KOKKOS_RESTRICT m = Uniform ? nullptr : mu + base;
    double* KOKKOS_RESTRICT out = rhs[D] + base;
    // Predict: u* is written over rhs_old at the cell just read (no other cell reads either); the
    // terms copied to a local, which the stores cannot change (so the loop keeps them in registers)
    const PredictorTerms t = predictor;
    double* KOKKOS_RESTRICT star = Predict ? t.rhs_old_to_star[D] + base : nullptr;
    const double* KOKKOS_RESTRICT chi = Predict ? t.chi_row(D, j) : nullptr;
    const double mu0 = mu_uniform, i0 = ih[0], i1 = ih[1], i2 = ih[2], iD = ih[D];
    const long s0 = st[0], s1 = st[1], s2 = st[2], sD = st[D];
    EULERFSI_INDEPENDENT_LOOP
    for (int k = k0; k < k1; ++k) {
      const double fz = flux<D, 2>(uD, uz, m, mu0, k, sD, s2, iD, i2);
      const double fz_lo = flux<D, 2>(uD, uz, m, mu0, k - 1, sD, s2, iD, i2);
      const double fx = flux<D, 0>(uD, ux, m, mu0, k, sD, s0, iD, i0);
      const double fy = flux<D, 1>(uD, uy, m, mu0, k, sD, s1, iD, i1);
      const double tx = (fx - plane[k]) * i0, ty = (fy - row[k]) * i1, tz = (fz - fz_lo) * i2;
      plane[k] = fx;
      row[k] = fy;
      // summed in MomentumRhs::value's order: normal, then E1, then E2
      const double r = -(D == 0 ? tx + ty + tz : (D == 1 ? ty + tz + tx : tz + tx + ty));
      if constexpr (Predict) {
        const double full = Force ? r + out[k] : r;
        out[k] = full;
        star[k] = t.star<D>(uD[k], full, star[k], chi[k]);
      } else {
        out[k] = r;
      }
    }
  }

  // dst[k - k0] = U_DX at the row starting at base (the faces below a slab's first plane or row).
  template <int D, int X>
  void upper_fluxes(double* dst, long base, int k0, int k1) const {
    for (int k = k0; k < k1; ++k) dst[k - k0] = upper_flux<D, X>(base + k);
  }

  // The planes [i0, i1) of the box.
  void slab(int i0, int i1, const Box& b) const {
    const int j0 = b.lo[1], j1 = b.hi[1], k0 = b.lo[2], k1 = b.hi[2], nk = k1 - k0;
    std::vector<double> buf(size_t(3) * (j1 - j0 + 1) * nk);
    // planes[D] + (j - j0) nk - k0 and rows[D] - k0: indexed with the storage k
    double* planes[3];
    double* rows[3];
    for (int d = 0; d < 3; ++d) planes[d] = buf.data() + size_t(d) * (j1 - j0) * nk;
    for (int d = 0; d < 3; ++d) rows[d] = buf.data() + size_t(3) * (j1 - j0) * nk + size_t(d) * nk;
    for (int j = j0; j < j1; ++j) {  // the x-faces below the first plane
      const long base = (i0 - 1) * st[0] + j * st[1];
      const size_t p = size_t(j - j0) * nk;
      upper_fluxes<0, 0>(planes[0] + p, base, k0, k1);
      upper_fluxes<1, 0>(planes[1] + p, base, k0, k1);
      upper_fluxes<2, 0>(planes[2] + p, base, k0, k1);
    }
    for (int i = i0; i < i1; ++i) {
      const long below = i * st[0] + (j0 - 1) * st[1];  // the y-faces below the first row
      upper_fluxes<0, 1>(rows[0], below, k0, k1);
      upper_fluxes<1, 1>(rows[1], below, k0, k1);
      upper_fluxes<2, 1>(rows[2], below, k0, k1);
      for (int j = j0; j < j1; ++j) {
        const long base = i * st[0] + j * st[1];
        const size_t p = size_t(j - j0) * nk;
        row_of<0>(base, j, k0, k1, planes[0] + p - k0, rows[0] - k0);
        row_of<1>(base, j, k0, k1, planes[1] + p - k0, rows[1] - k0);
        row_of<2>(base, j, k0, k1, planes[2] + p - k0, rows[2] - k0);
      }
    }
  }
};

// rhs over the box on host backends: the x-extent split into one slab per thread.
template <bool Uniform, bool Predict, bool Force>
void momentum_sweep(const MomentumSweep<Uniform, Predict, Force>& f, const Box& b, const char* label) {
  if (b.empty()) return;
  const int ni = b.hi[0] - b.lo[0];
  const int slabs = std::max(1, std::min(ni, int(ExecSpace().concurrency())));
  Kokkos::parallel_for(label, Kokkos::RangePolicy<ExecSpace>(0, slabs), KOKKOS_LAMBDA(int s) {
    const int i0 = b.lo[0] + int(long(ni) * s / slabs), i1 = b.lo[0] + int(long(ni) * (s + 1) / slabs);
    if (i1 > i0) f.slab(i0, i1, b);
  });
}

}  // namespace eulerfsi::kernels

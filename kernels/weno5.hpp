#pragma once
// Fifth-order WENO reconstruction (Jiang & Shu 1996, J. Comput. Phys. 126, 202) of the value at
// the face i+1/2 from five point values, used in finite-difference flux form for psi and B.
#include "core/compat.hpp"
#include "core/types.hpp"
#include "kernels/offsets.hpp"

namespace eulerfsi::kernels {

// eps keeps the weights finite on flat data. 1e-6 is Jiang & Shu's choice; psi and B are O(1),
// so it is small against the smoothness indicators of any resolved jump yet above round-off.
constexpr double kWenoEps = 1e-6;

// q_{i+1/2}^- from q_{i-2..i+2}, biased to the left (upwind for a positive face velocity).
KOKKOS_FORCEINLINE_FUNCTION double weno5(double vm2, double vm1, double v0, double vp1, double vp2) {
  // flat stencil (psi = 0 in the fluid, B = I around it: most of the domain): exact and cheap
  if (vm2 == v0 && vm1 == v0 && vp1 == v0 && vp2 == v0) return v0;
  // third-order candidates on the stencils {i-2,i-1,i}, {i-1,i,i+1}, {i,i+1,i+2}
  const double q0 = (2.0 * vm2 - 7.0 * vm1 + 11.0 * v0) * (1.0 / 6.0);
  const double q1 = (-vm1 + 5.0 * v0 + 2.0 * vp1) * (1.0 / 6.0);
  const double q2 = (2.0 * v0 + 5.0 * vp1 - vp2) * (1.0 / 6.0);
  // smoothness indicators
  const double d0a = vm2 - 2.0 * vm1 + v0, d0b = vm2 - 4.0 * vm1 + 3.0 * v0;
  const double d1a = vm1 - 2.0 * v0 + vp1, d1b = vm1 - vp1;
  const double d2a = v0 - 2.0 * vp1 + vp2, d2b = 3.0 * v0 - 4.0 * vp1 + vp2;
  const double b0 = (13.0 / 12.0) * d0a * d0a + 0.25 * d0b * d0b;
  const double b1 = (13.0 / 12.0) * d1a * d1a + 0.25 * d1b * d1b;
  const double b2 = (13.0 / 12.0) * d2a * d2a + 0.25 * d2b * d2b;
  // nonlinear weights from the ideal ones 1/10, 6/10, 3/10
  const double e0 = kWenoEps + b0, e1 = kWenoEps + b1, e2 = kWenoEps + b2;
  const double a0 = 0.1 / (e0 * e0), a1 = 0.6 / (e1 * e1), a2 = 0.3 / (e2 * e2);
  return (a0 * q0 + a1 * q1 + a2 * q2) / (a0 + a1 + a2);
}

// Value of q at the face between cells i and i+e_D, upwinded by the sign of the face velocity:
// u >= 0 reads q_{i-2..i+2}, u < 0 the mirror image q_{i+3..i-1}.
template <int D, class V>
KOKKOS_FORCEINLINE_FUNCTION double face_value_upwind(const V& q, double u_face, int i, int j, int k) {
  if (u_face >= 0.0)
    return weno5(shifted<D>(q, i, j, k, -2), shifted<D>(q, i, j, k, -1), q(i, j, k), shifted<D>(q, i, j, k, 1),
                 shifted<D>(q, i, j, k, 2));
  return weno5(shifted<D>(q, i, j, k, 3), shifted<D>(q, i, j, k, 2), shifted<D>(q, i, j, k, 1), q(i, j, k),
               shifted<D>(q, i, j, k, -1));
}

// The same from a row's pointer: the face between p[0] and p[e] (e: the stride along the face's
// normal), the values p[-2e..2e] or p[-e..3e].
KOKKOS_FORCEINLINE_FUNCTION double face_value_upwind(const double* p, long e, double u_face) {
  if (u_face >= 0.0) return weno5(p[-2 * e], p[-e], p[0], p[e], p[2 * e]);
  return weno5(p[3 * e], p[2 * e], p[e], p[0], p[-e]);
}

}  // namespace eulerfsi::kernels

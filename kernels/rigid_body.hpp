#pragma once
// A rigid sphere in the one continuum (src/solid/rigid_model.hpp): its volume fraction from its
// centre, the psi-weighted moments that give its rigid motion, and the rigid velocity blended into
// the flow. Positions are relative to the centre c, with the minimum image along periodic
// directions; the face of component D at (i, j, k) lies between cell (i, j, k) and the next cell
// along D, psi there is the mean of the two.
#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/particle_moments.hpp"
#include "kernels/reference_map.hpp"
#include "kernels/solid_fields.hpp"

namespace eulerfsi::kernels {

struct RigidGeometry {
  CellCentres xc;
  double centre[3];
  double period[3];  // 0 where not periodic
  double radius;
  double eps;  // half-width of psi's smoothed edge
};

// psi = H_eps(a - |x - c|) on every cell of `box` (ghosts included: psi is exact wherever it is
// evaluated, so it needs no halo exchange).
inline void rigid_sphere_psi(const WindowField& psi, const RigidGeometry& g, const Box& box) {
  for_each_cell("eulerfsi::rigid::psi", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double dx = detail::min_image(g.xc(0, i) - g.centre[0], g.period[0]);
    const double dy = detail::min_image(g.xc(1, j) - g.centre[1], g.period[1]);
    const double dz = detail::min_image(g.xc(2, k) - g.centre[2], g.period[2]);
    psi(i, j, k) = smoothed_heaviside(g.radius - compat::sqrt(dx * dx + dy * dy + dz * dz), g.eps);
  });
}

// The sums of the rigid-motion fit, each times dV, over the faces of each component D (psi_D the
// face's psi, r its position relative to the centre, q_D = r x e_D):
//   mass[D] = sum psi_D, momentum[D] = sum psi_D u_D, first[D] = sum psi_D r,
//   angular = sum_D sum psi_D q_D u_D, inertia = sum_D sum psi_D q_D q_D^T (XX, YY, ZZ, XY, XZ, YZ).
// The rigid motion (U, w) that solves the psi-weighted least-squares fit these sums define
// (src/solid/rigid_model.cpp) changes neither the flow's momentum nor its angular momentum about the
// centre when it is blended in (rigid_blend): sum psi_D ((U + w x r)_D - u_D) = 0, and the same times q_D.
struct RigidMoments {
  enum { Count = 24 };
  double mass[3], momentum[3], angular[3], inertia[kTensorComponents], first[3][3];
};
static_assert(sizeof(RigidMoments) == RigidMoments::Count * sizeof(double), "RigidMoments: doubles in a row");

namespace detail {

KOKKOS_INLINE_FUNCTION void face_offset(const RigidGeometry& g, int comp, int i, int j, int k, double r[3]) {
  const int ix[3] = {i, j, k};
  for (int d = 0; d < 3; ++d) {
    const double x = g.xc(d, ix[d]) + (d == comp ? 0.5 * g.xc.h[d] : 0.0);
    r[d] = min_image(x - g.centre[d], g.period[d]);
  }
}

KOKKOS_INLINE_FUNCTION double face_psi(const WindowField& psi, int comp, int i, int j, int k) {
  return 0.5 * (psi(i, j, k) + psi(i + (comp == 0), j + (comp == 1), k + (comp == 2)));
}

// q = r x e_D
KOKKOS_INLINE_FUNCTION void lever(const double r[3], int comp, double q[3]) {
  q[0] = comp == 2 ? r[1] : (comp == 1 ? -r[2] : 0.0);
  q[1] = comp == 0 ? r[2] : (comp == 2 ? -r[0] : 0.0);
  q[2] = comp == 1 ? r[0] : (comp == 0 ? -r[1] : 0.0);
}

// Kokkos custom reducer summing RigidMoments field by field (one pass over the box instead of one
// per sum). Kokkos 3.4 joins through volatile references and 4.x rejects them: both overloads
// (docs: STYLE, "custom reducers").
struct RigidMomentsReducer {
  using reducer = RigidMomentsReducer;
  using value_type = RigidMoments;
  using result_view_type = Kokkos::View<value_type, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;

  value_type* value;
  explicit RigidMomentsReducer(value_type& v) : value(&v) {}

  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void add(D& dst, const S& src) {
    for (int d = 0; d < 3; ++d) {
      dst.mass[d] += src.mass[d];
      dst.momentum[d] += src.momentum[d];
      dst.angular[d] += src.angular[d];
      for (int a = 0; a < 3; ++a) dst.first[d][a] += src.first[d][a];
    }
    for (int t = 0; t < kTensorComponents; ++t) dst.inertia[t] += src.inertia[t];
  }
  KOKKOS_INLINE_FUNCTION void join(value_type& dst, const value_type& src) const { add(dst, src); }
  KOKKOS_INLINE_FUNCTION void join(volatile value_type& dst, const volatile value_type& src) const { add(dst, src); }
  KOKKOS_INLINE_FUNCTION void init(value_type& v) const {
    for (int d = 0; d < 3; ++d) {
      v.mass[d] = v.momentum[d] = v.angular[d] = 0.0;
      for (int a = 0; a < 3; ++a) v.first[d][a] = 0.0;
    }
    for (int t = 0; t < kTensorComponents; ++t) v.inertia[t] = 0.0;
  }
  KOKKOS_INLINE_FUNCTION value_type& reference() const { return *value; }
  result_view_type view() const { return result_view_type(value); }
  KOKKOS_INLINE_FUNCTION bool references_scalar() const { return true; }
};

// Every sum of RigidMoments from the three faces of one cell (faces where psi = 0 add nothing).
struct RigidMomentTerms {
  WindowField psi;
  Field3 u[3];
  RigidGeometry g;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, RigidMoments& acc) const {
    const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
    for (int comp = 0; comp < 3; ++comp) {
      const double p = face_psi(psi, comp, i, j, k);
      if (p == 0.0) continue;
      double r[3], q[3];
      face_offset(g, comp, i, j, k, r);
      lever(r, comp, q);
      const double uc = u[comp](i, j, k);
      acc.mass[comp] += p;
      acc.momentum[comp] += p * uc;
      for (int a = 0; a < 3; ++a) {
        acc.angular[a] += p * q[a] * uc;
        acc.first[comp][a] += p * r[a];
      }
      for (int t = 0; t < kTensorComponents; ++t) acc.inertia[t] += p * q[ra[t]] * q[rb[t]];
    }
  }
};

}  // namespace detail

// This rank's sums over the owned faces of `box` (the caller MPI-sums them).
inline RigidMoments rigid_moments(const WindowField& psi, const Velocity& vel, const RigidGeometry& g, double dv,
                                  const Box& box) {
  RigidMoments m;
  reduce_cells("eulerfsi::rigid::moments", box, detail::RigidMomentTerms{psi, {vel.c[0], vel.c[1], vel.c[2]}, g},
               detail::RigidMomentsReducer(m));
  double* all = &m.mass[0];  // 24 doubles in a row (the struct holds nothing else)
  for (int n = 0; n < RigidMoments::Count; ++n) all[n] *= dv;
  return m;
}

// The rigid motion blended in by psi on every face of `box`, u_D <- u_D + psi_D ((U + w x r)_D - u_D)
// (Sharma & Patankar 2005); returns this rank's impulse sum psi_D ((U + w x r)_D - u_D) dV per D:
// zero for a free body (U and w from RigidMoments), the constraint's impulse for a held one.
// psi_D ((U + w x r)_D - u_D) on the face of component D at (i, j, k)
KOKKOS_INLINE_FUNCTION double rigid_difference(const Field3& u, const WindowField& psi, const RigidGeometry& g,
                                               int comp, double Uc, double w0, double w1, double w2, int i, int j,
                                               int k) {
  double r[3];
  detail::face_offset(g, comp, i, j, k, r);
  const double wxr[3] = {w1 * r[2] - w2 * r[1], w2 * r[0] - w0 * r[2], w0 * r[1] - w1 * r[0]};
  return detail::face_psi(psi, comp, i, j, k) * (Uc + wxr[comp] - u(i, j, k));
}

inline void rigid_blend(const Velocity& vel, const WindowField& psi, const RigidGeometry& g, const double U[3],
                        const double w[3], double dv, const Box& box, double impulse[3]) {
  for (int comp = 0; comp < 3; ++comp) {
    const Field3 u = vel.c[comp];
    const double Uc = U[comp], w0 = w[0], w1 = w[1], w2 = w[2];
    double j_sum = 0.0;
    reduce_cells("eulerfsi::rigid::impulse", box, KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
      acc += rigid_difference(u, psi, g, comp, Uc, w0, w1, w2, i, j, k);
    }, Kokkos::Sum<double>(j_sum));
    impulse[comp] = dv * j_sum;
    for_each_cell("eulerfsi::rigid::blend", box, KOKKOS_LAMBDA(int i, int j, int k) {
      u(i, j, k) += rigid_difference(u, psi, g, comp, Uc, w0, w1, w2, i, j, k);
    });
  }
}

}  // namespace eulerfsi::kernels

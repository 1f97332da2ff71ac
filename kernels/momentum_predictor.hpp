#pragma once
// The explicit momentum right-hand side and the RK3 predictor in one pass over the velocity:
//   rhs^k_D = -d/dx_E (u_E u_D) + d/dx_E [ mu (du_D/dx_E + du_E/dx_D) ] (+ f_D)   (kernels/momentum.hpp)
//   u*_D    = [u^k_D + dt (gamma rhs^k_D + zeta rhs^(k-1)_D) + pen u_wall] / (1 + pen)   (predictor_terms.hpp)
// u* is written over rhs^(k-1) (each cell reads its own value first), rhs^k into rhs; the caller
// then rotates the fields (u* becomes the velocity, rhs^k the next substep's rhs^(k-1), u^k the
// scratch for the next rhs). One read of u^k and rhs^(k-1) and no separate update sweep: the
// update kernels streamed u, rhs^k and rhs^(k-1) once more for each component.
// With `force`, rhs holds f (the elastic force) on entry, added in the order rhs = momentum + f.
#include "kernels/momentum.hpp"
#include "kernels/predictor_terms.hpp"

namespace eulerfsi::kernels {

// The per-cell form (GPUs; hosts run the sweep with the same expressions).
template <bool Uniform, bool Force>
struct MomentumPredictCell {
  double* rhs[3];
  const double* u[3];
  const double* mu;
  double mu_uniform;
  double ih[3];
  long st[3];
  PredictorTerms terms;

  template <int D>
  KOKKOS_FORCEINLINE_FUNCTION void component(long c, int j, int k) const {
    constexpr int E1 = (D + 1) % 3, E2 = (D + 2) % 3;
    const double r = MomentumRhs<D, Uniform>::value(u[D], u[E1], u[E2], mu, mu_uniform, c, st[D], st[E1], st[E2],
                                                    ih[D], ih[E1], ih[E2]);
    const double full = Force ? r + rhs[D][c] : r;
    rhs[D][c] = full;
    terms.rhs_old_to_star[D][c] = terms.star<D>(u[D][c], full, terms.rhs_old_to_star[D][c], terms.chi_row(D, j)[k]);
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const long c = i * st[0] + j * st[1] + k;
    component<0>(c, j, k);
    component<1>(c, j, k);
    component<2>(c, j, k);
  }
};

template <bool Uniform, bool Force>
inline void momentum_predict_impl(const Velocity& rhs, const Velocity& u, const Field3& mu, double mu_uniform,
                                  const double h[3], const PredictorTerms& terms, const Box& box, const char* label) {
  if (box.empty()) return;
  const long st[3] = {long(rhs.c[0].stride(0)), long(rhs.c[0].stride(1)), 1};
  double* r[3] = {rhs.c[0].data(), rhs.c[1].data(), rhs.c[2].data()};
  const double* v[3] = {u.c[0].data(), u.c[1].data(), u.c[2].data()};
  const double ih[3] = {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]};
  if constexpr (kHostKernels) {
    const MomentumSweep<Uniform, true, Force> f{{r[0], r[1], r[2]},   {v[0], v[1], v[2]},    Uniform ? nullptr : mu.data(),
                                                mu_uniform,           {ih[0], ih[1], ih[2]}, {st[0], st[1], st[2]},
                                                terms};
    momentum_sweep(f, box, label);
  } else {
    const MomentumPredictCell<Uniform, Force> f{{r[0], r[1], r[2]},   {v[0], v[1], v[2]},    Uniform ? nullptr : mu.data(),
                                                mu_uniform,           {ih[0], ih[1], ih[2]}, {st[0], st[1], st[2]},
                                                terms};
    Kokkos::parallel_for(label, box.policy(), f);
  }
}

// rhs^k and u* on `box` with the constant viscosity mu (the elastic force, if any, is added after:
// SolidCoupling::add_elastic_force_to_predictor).
inline void momentum_predict(const Velocity& rhs, const Velocity& u, double mu, const double h[3],
                             const PredictorTerms& terms, const Box& box) {
  momentum_predict_impl<true, false>(rhs, u, Field3(), mu, h, terms, box, "eulerfsi::momentum::predict");
}

// The same with the viscosity field mu (cell centres, ghosts filled); rhs holds f on entry.
inline void momentum_predict(const Velocity& rhs, const Velocity& u, const Field3& mu, const double h[3],
                             const PredictorTerms& terms, const Box& box) {
  momentum_predict_impl<false, true>(rhs, u, mu, 0.0, h, terms, box, "eulerfsi::momentum::predict_mixture");
}

}  // namespace eulerfsi::kernels

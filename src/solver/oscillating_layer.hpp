#pragma once
// Exact periodic solution of the oscillating fluid/solid layer problem (Sugiyama, Ii, Takeuchi,
// Takagi & Matsumoto 2011, J. Comput. Phys. 230, 596): a viscous neo-Hookean layer 0 < Y < a on
// a fixed wall, fluid a < Y < H, the wall at Y = H moving with u = V sin(w t). In this 1-D shear
// flow the neo-Hookean shear stress G B_xy is linear in the displacement, so
//   solid: f = A sinh(k Y),                       k^2 = i w rho / (mu_s + G / (i w))
//   fluid: f = B e^{l (Y-a)} + C e^{-l (Y-a)},     l^2 = i w rho / mu_f
// with f(H) = V, continuity of f and of the shear stress at Y = a; u(Y, t) = Im[f(Y) e^{i w t}].
#include <complex>

namespace eulerfsi::exact {

class OscillatingLayer {
 public:
  OscillatingLayer(double a, double H, double V, double w, double rho, double mu_f, double mu_s, double G)
      : a_(a), H_(H), w_(w) {
    using C = std::complex<double>;
    const C i(0.0, 1.0);
    ms_ = mu_s + G / (i * w);
    k_ = std::sqrt(i * w * rho / ms_);
    l_ = std::sqrt(i * w * rho / mu_f);
    // unknowns A, B, C from: A sinh(ka) = B + C;  ms A k cosh(ka) = mu_f l (B - C);  B e^{l(H-a)} + C e^{-l(H-a)} = V
    const C s = std::sinh(k_ * a), c = std::cosh(k_ * a);
    const C bc_sum_per_A = s, bc_diff_per_A = ms_ * k_ * c / (mu_f * l_);
    const C b_per_A = 0.5 * (bc_sum_per_A + bc_diff_per_A), c_per_A = 0.5 * (bc_sum_per_A - bc_diff_per_A);
    const C e = std::exp(l_ * (H - a));
    A_ = V / (b_per_A * e + c_per_A / e);
    B_ = b_per_A * A_;
    C_ = c_per_A * A_;
  }
  // Velocity at height Y above the fixed wall and time t.
  double velocity(double Y, double t) const {
    const std::complex<double> i(0.0, 1.0);
    const auto f = Y < a_ ? A_ * std::sinh(k_ * Y) : B_ * std::exp(l_ * (Y - a_)) + C_ * std::exp(-l_ * (Y - a_));
    return std::imag(f * std::exp(i * w_ * t));
  }

 private:
  double a_, H_, w_;
  std::complex<double> ms_, k_, l_, A_, B_, C_;
};

}  // namespace eulerfsi::exact

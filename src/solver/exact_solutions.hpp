#pragma once
// Exact steady laminar solutions, used for initial conditions and for validation.
// Lengths in units of the pipe diameter D (or duct side), velocities in units of U_b.
#include <cmath>

namespace eulerfsi::exact {

constexpr double kPi = 3.14159265358979323846;

// Hagen-Poiseuille: u = 2 U_b (1 - 4 r^2) for r < R = 1/2; dp/dx = -32 mu U_b / D^2.
inline double pipe_velocity(double y, double z, double ub) {
  const double r2 = y * y + z * z;
  return r2 < 0.25 ? 2.0 * ub * (1.0 - 4.0 * r2) : 0.0;
}
inline double pipe_dpdx(double mu, double ub) { return -32.0 * mu * ub; }

// Plane Poiseuille in y in [-Ly/2, Ly/2]: u = 1.5 U_b (1 - 4 y^2 / Ly^2); dp/dx = -12 mu U_b / Ly^2.
inline double channel_velocity(double y, double ly, double ub) { return 1.5 * ub * (1.0 - 4.0 * y * y / (ly * ly)); }
inline double channel_dpdx(double mu, double ly, double ub) { return -12.0 * mu * ub / (ly * ly); }

// Rectangular duct [-a/2,a/2] x [-b/2,b/2] driven by -dp/dx = g (White, Viscous Fluid Flow, eq. 3-48):
//   u = (4 g a^2 / (mu pi^3)) sum_{n odd} (-1)^((n-1)/2) / n^3
//       [1 - cosh(n pi z / a) / cosh(n pi b / (2a))] cos(n pi y / a)
// (White writes it for half-widths; this is the same series in full widths.)
inline double duct_velocity_per_gradient(double y, double z, double a, double b, double mu, int terms = 201) {
  double s = 0.0;
  for (int n = 1; n <= terms; n += 2) {
    const double sign = ((n - 1) / 2) % 2 == 0 ? 1.0 : -1.0;
    const double arg = n * kPi * b / (2.0 * a);
    // cosh ratio written with exponentials to avoid overflow for large n
    const double ratio = std::exp(n * kPi * std::fabs(z) / a - arg) * (1.0 + std::exp(-2.0 * n * kPi * std::fabs(z) / a)) /
                         (1.0 + std::exp(-2.0 * arg));
    s += sign / (n * n * n) * (1.0 - ratio) * std::cos(n * kPi * y / a);
  }
  return 4.0 * a * a / (mu * kPi * kPi * kPi) * s;
}
// Mean velocity per unit gradient: Q / (a b) with Q = (g a^3 b / (12 mu)) [1 - (192 a / (pi^5 b)) sum tanh(n pi b / 2a) / n^5].
inline double duct_mean_per_gradient(double a, double b, double mu, int terms = 201) {
  double s = 0.0;
  for (int n = 1; n <= terms; n += 2) s += std::tanh(n * kPi * b / (2.0 * a)) / std::pow(n, 5);
  return a * a / (12.0 * mu) * (1.0 - 192.0 * a / (std::pow(kPi, 5) * b) * s);
}
inline double duct_velocity(double y, double z, double a, double b, double mu, double ub) {
  return ub * duct_velocity_per_gradient(y, z, a, b, mu) / duct_mean_per_gradient(a, b, mu);
}
inline double duct_dpdx(double a, double b, double mu, double ub) { return -ub / duct_mean_per_gradient(a, b, mu); }

}  // namespace eulerfsi::exact

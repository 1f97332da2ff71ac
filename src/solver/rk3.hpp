#pragma once
// Low-storage RK3 (Wray; Rai & Moin 1991): gamma, zeta, and alpha = gamma + zeta. Shared by the
// momentum update and the transport of psi and B, which advance in the same substeps.
namespace eulerfsi {

struct Rk3 {
  static constexpr int stages = 3;
  static constexpr double gamma[3] = {8.0 / 15.0, 5.0 / 12.0, 3.0 / 4.0};
  static constexpr double zeta[3] = {0.0, -17.0 / 60.0, -5.0 / 12.0};
  static constexpr double alpha(int s) { return gamma[s] + zeta[s]; }
  // time at the start of substep s, as a fraction of dt
  static constexpr double start(int s) { return s == 0 ? 0.0 : (s == 1 ? 8.0 / 15.0 : 2.0 / 3.0); }
};

}  // namespace eulerfsi

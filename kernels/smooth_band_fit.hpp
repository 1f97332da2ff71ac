#pragma once
// The reference map's inner band (levels 2..max_level: the cells one and two cells outside the
// solid, where psi's edge lies) fitted in one step through the solid cells around each, instead of
// the sweeps' cascade (each level through the levels below it):
//   q(x_c) = c0,  (c0, c) = argmin sum_n w_n |q_n - c0 - c . r_n|^2  over solid cells n, |r_n| < 3.5
//   w_n = E(depth_n) (1 - |r_n|^2 / 3.5^2)^2,  E = smoothstep(depth / edge_ramp)
// r_n in cells. The offsets form a fixed stencil, so the fit changes only as cells join or leave the
// solid, and E makes that continuous: a cell that leaves, or a band cell that changes level, moves
// the band continuously, not by a jump (no cascade). Where the stencil holds too few solid cells for
// a trusted fit (cells two cells out along a diagonal) the fit blends with the sweeps' value by its
// trust (ExtrapolationSweep::fit_trust), and there the cascade still shows. The stencil stays within
// the kGhost = 3 layers a rank's window holds of its neighbour's cells. Exact for a rigid motion (q
// linear), as the sweeps are.
#include "kernels/reference_map.hpp"

namespace eulerfsi::kernels {

// The stencil: the cells within kBandFitRadius cells (r^2 < 12.25 keeps |a|, |b|, |c| <= 3 =
// kGhost). The distance weight (1 - r^2 / rho^2)^2 puts the fit on the surface layer: over the whole
// 7^3 cube with weights (1 - r^2 / 28)^2 the band followed the deeper cells and the Re = 400 sphere's
// oscillation grew (D 0.014 -> 0.019 over t = 0.5-2).
constexpr int kBandFitReach = 3;
constexpr double kBandFitRadius = 3.5;
// The edge ramp E's width in cells. Thin: with E over the surface blend's 0.5 cells the band follows
// the deeper cells and a very stiff sphere's elastic oscillation grows at Re = 400 (D 0.018 -> 0.084
// over t = 0.5-4; over 0.1 cells it decays as with the sweeps: docs/REFERENCE_MAP.md, "Smooth forces").
constexpr double kBandFitEdgeRamp = 0.1;

// A solid cell's weight at the classification's edge over a thinner ramp than the surface blend's:
// classify_solid stores w = smoothstep(depth / ramp), so depth / ramp = 1/2 - sin(asin(1 - 2w) / 3)
// (the inverse of 3t^2 - 2t^3 on [0, 1]); `ratio` = edge_ramp / ramp <= 1.
KOKKOS_INLINE_FUNCTION double edge_weight(double w, double ratio) {
  if (w >= 1.0) return 1.0;
  if (w <= 0.0) return 0.0;
  const double t = 0.5 - compat::sin(compat::asin(1.0 - 2.0 * w) / 3.0);
  return surface_weight(t, ratio);
}

struct SmoothBandFit {
  Vector3 q;
  WindowField level, weight;
  double max_level, edge_ratio;

  // The fit's value at (i, j, k) in out, and its trust (ExtrapolationSweep::fit_trust; 0: no fit,
  // out not written). A solid cell's own point enters at its own edge weight.
  KOKKOS_INLINE_FUNCTION double fit_at(int i, int j, int k, double out[3]) const {
    constexpr int R = kBandFitReach;
    constexpr double rho2 = kBandFitRadius * kBandFitRadius;
    double S = 0, m[3] = {}, A[6] = {}, b0[3] = {}, b[3][3] = {};
    for (int a = -R; a <= R; ++a)
      for (int bb = -R; bb <= R; ++bb)
        for (int c = -R; c <= R; ++c) {
          const double r2 = a * a + bb * bb + c * c;
          if (r2 >= rho2 || level(i + a, j + bb, k + c) != kLevelSolid) continue;
          const double s = 1.0 - r2 / rho2;
          const double w = edge_weight(weight(i + a, j + bb, k + c), edge_ratio) * s * s;
          if (w <= 0.0) continue;
          const double r[3] = {double(a), double(bb), double(c)};
          S += w;
          for (int d = 0; d < 3; ++d) m[d] += w * r[d];
          A[0] += w * r[0] * r[0], A[1] += w * r[1] * r[1], A[2] += w * r[2] * r[2];
          A[3] += w * r[0] * r[1], A[4] += w * r[0] * r[2], A[5] += w * r[1] * r[2];
          for (int d = 0; d < 3; ++d) {
            const double qv = q.c[d](i + a, j + bb, k + c);
            b0[d] += w * qv;
            for (int e = 0; e < 3; ++e) b[e][d] += w * r[e] * qv;
          }
        }
    if (!(S > 0.0)) return 0.0;
    return ExtrapolationSweep::fit_centre(S, m, A, b0, b, out);
  }

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const double l = level(i, j, k);
    if (l <= kLevelSolid || l > max_level) return;
    double fit[3];
    const double trust = fit_at(i, j, k, fit);
    // a starved fit goes over to the sweeps' value (the cascade) rather than to a mean
    if (trust > 0.0)
      for (int d = 0; d < 3; ++d) q.c[d](i, j, k) += trust * (fit[d] - q.c[d](i, j, k));
  }
};

// In place: it writes band cells and reads only solid ones.
inline void smooth_band_fit(const Vector3& q, const WindowField& level, const WindowField& weight, double max_level,
                            double edge_ratio, const Box& box) {
  if (!same_window(q, level) || !same_window(weight, level))
    throw std::logic_error("smooth_band_fit: q, its level and weight are on different windows");
  for_each_cell("eulerfsi::refmap::smooth_band_fit", box, SmoothBandFit{q, level, weight, max_level, edge_ratio});
}

// kernels::surface_fits with the ramp cells' target the same single fit (their own point at their
// own edge weight), so a cell leaving the solid holds, at weight 0, what the band fit then gives it.
inline void smooth_surface_fits(const Vector3& q, const WindowField& level, const WindowField& weight,
                                const Vector3& out, const Box& box, double rate, double edge_ratio) {
  if (!same_window(q, level) || !same_window(weight, level))
    throw std::logic_error("smooth_surface_fits: q, its level and weight are on different windows");
  const ExtrapolationSweep solid{q, level, weight, kLevelSolid};
  const SmoothBandFit band{q, level, weight, kLevelSolid, edge_ratio};
  const Vector3 o = out;
  for_each_cell("eulerfsi::refmap::smooth_surface_fits", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double w = solid.weight(i, j, k);
    if (solid.level(i, j, k) != kLevelSolid || w >= 1.0) return;
    double fitted[3], smooth[3];
    solid.fit_value(i, j, k, fitted);
    const double trust = band.fit_at(i, j, k, smooth);
    if (trust > 0.0)
      for (int d = 0; d < 3; ++d) fitted[d] += trust * (smooth[d] - fitted[d]);
    const double b = rate * (1.0 - w), a = rate == 1.0 ? w : 1.0 - b;
    for (int d = 0; d < 3; ++d) o.c[d](i, j, k) = a * solid.q.c[d](i, j, k) + b * fitted[d];
  });
}

}  // namespace eulerfsi::kernels

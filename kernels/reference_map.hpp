#pragma once
// The reference map (Kamrin, Rycroft & Nave 2012, J. Mech. Phys. Solids 60, 1952; Valkov, Rycroft
// & Kamrin 2015, Proc. R. Soc. A 471; Rycroft et al. 2020, J. Fluid Mech. 898, A9): every point
// carries the reference position xi(x, t) of the material there. We store the reference
// displacement q = xi - x at cell centres, which is periodic wherever the domain is and zero for
// a body at rest:
//   d xi/dt + u . grad xi = 0   <=>   dq/dt = -u - u . grad q
//   F = (grad xi)^-1 = (I + grad q)^-1,   B = F F^T
//   psi = H_eps(-phi0(xi) / |grad_x phi0(xi)|)   (phi0: signed distance of the reference shape)
// u . grad q is the WENO5 flux difference minus q div_h u, which is exact for a linear q (a rigid
// motion) because WENO5 reconstructs a linear function exactly at every face.
#include <stdexcept>

#include "core/compat.hpp"
#include "core/launch.hpp"
#include "core/types.hpp"
#include "kernels/momentum.hpp"
#include "kernels/solid_fields.hpp"
#include "kernels/solid_transport.hpp"

namespace eulerfsi::kernels {

struct Vector3 {
  WindowField c[3];
};

// Whether two fields are stored alike (one window, one layout): the host rows of the extrapolation
// and of the advection index several with one offset.
inline bool same_window(const WindowField& a, const WindowField& b) {
  for (int d = 0; d < 3; ++d)
    if (a.lo[d] != b.lo[d] || a.data.extent(d) != b.data.extent(d) || a.data.stride(d) != b.data.stride(d)) return false;
  return true;
}
inline bool same_window(const Vector3& q, const WindowField& level) {
  return same_window(q.c[0], level) && same_window(q.c[1], level) && same_window(q.c[2], level);
}

// The reference shape: a sphere (nearest periodic image of its centre) or the layer y < y_top.
struct ReferenceShape {
  bool sphere = true;
  double centre[3] = {0, 0, 0};
  double radius = 0.0;
  double period[3] = {0, 0, 0};  // 0: no periodic images in that direction
  double top = 0.0;              // layer: y of its upper surface
  double shift = 0.0;            // phi0 - shift: the level moved to keep the volume

  // phi0(X) + shift (the level before the volume correction moves it) and its gradient in the
  // reference configuration.
  KOKKOS_INLINE_FUNCTION double unshifted(const double X[3], double grad[3]) const {
    if (!sphere) {
      grad[0] = 0.0, grad[1] = 1.0, grad[2] = 0.0;
      return X[1] - top;
    }
    double d[3], r2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      d[a] = X[a] - centre[a];
      if (period[a] > 0.0) d[a] -= period[a] * compat::floor(d[a] / period[a] + 0.5);
      r2 += d[a] * d[a];
    }
    const double r = compat::sqrt(r2);
    for (int a = 0; a < 3; ++a) grad[a] = r > 0.0 ? d[a] / r : (a == 0 ? 1.0 : 0.0);
    return r - radius;
  }
  // phi0(X) and its gradient.
  KOKKOS_INLINE_FUNCTION double phi(const double X[3], double grad[3]) const { return unshifted(X, grad) - shift; }
};

// Where the map is known, by distance from the solid ("levels"): 0 unknown, 1 solid (cell centre
// inside the body), s + 1 filled by extrapolation sweep s.
constexpr double kLevelSolid = 1.0;
// Whether psi is derived at a cell of this level (else psi = 0 and B = I).
KOKKOS_INLINE_FUNCTION bool derived_level(double l, double max_level) { return l >= kLevelSolid && l <= max_level; }
// Whether reference_map_rhs advects q at a cell of level l: the solid, and known cells where psi != 0.
KOKKOS_INLINE_FUNCTION bool advected(double l, double psi) { return l == kLevelSolid || (l > kLevelSolid && psi != 0.0); }

// grad q at the cell centre by central differences: G[a][b] = dq_a/dx_b.
KOKKOS_INLINE_FUNCTION void displacement_gradient(const Vector3& q, const double inv_2h[3], int i, int j, int k,
                                                  double G[3][3]) {
  for (int a = 0; a < 3; ++a) {
    G[a][0] = (q.c[a](i + 1, j, k) - q.c[a](i - 1, j, k)) * inv_2h[0];
    G[a][1] = (q.c[a](i, j + 1, k) - q.c[a](i, j - 1, k)) * inv_2h[1];
    G[a][2] = (q.c[a](i, j, k + 1) - q.c[a](i, j, k - 1)) * inv_2h[2];
  }
}

// What psi's edge at a cell takes from the map, apart from the level shift: phi0(xi) + shift,
// |grad_x phi0| with grad_x phi0 = (grad xi)^T grad_X phi0 and grad xi = I + grad q (1 where it
// vanishes: no division then), and the grid spacing along the surface normal, |n . diag(h)|, which
// sets the width of psi's edge. The signed distance is (phi0 + shift - shift) / |grad_x phi0|.
struct EdgeGeometry {
  double unshifted_phi, gradient_norm, normal_h;
  KOKKOS_INLINE_FUNCTION double distance(double shift) const { return (unshifted_phi - shift) / gradient_norm; }
};

// The same from phi0(X) + shift and n = grad_X phi0 at the cell's reference position X = x + q.
KOKKOS_INLINE_FUNCTION EdgeGeometry edge_geometry_at(double phi0, const double n[3], const double inv_2h[3],
                                                     const double G[3][3]) {
  double g2 = 0.0, gh2 = 0.0;
  for (int b = 0; b < 3; ++b) {
    double gb = n[b];
    for (int a = 0; a < 3; ++a) gb += n[a] * G[a][b];
    g2 += gb * gb;
    const double hb = 0.5 / inv_2h[b];
    gh2 += gb * gb * hb * hb;
  }
  return {phi0, g2 > 0.0 ? compat::sqrt(g2) : 1.0, g2 > 0.0 ? compat::sqrt(gh2 / g2) : 0.5 / inv_2h[0]};
}

// G: grad q at the cell (displacement_gradient).
KOKKOS_INLINE_FUNCTION EdgeGeometry edge_geometry(const Vector3& q, const ReferenceShape& shape, const double x[3],
                                                  const double inv_2h[3], int i, int j, int k, const double G[3][3]) {
  const double X[3] = {x[0] + q.c[0](i, j, k), x[1] + q.c[1](i, j, k), x[2] + q.c[2](i, j, k)};
  double n[3];
  const double phi0 = shape.unshifted(X, n);
  return edge_geometry_at(phi0, n, inv_2h, G);
}

// Smoothed Heaviside of half-width eps (Sussman, Smereka & Osher 1994): 0 below -eps, 1 above eps,
//   H(s) = (1 + s/eps + sin(pi s/eps)/pi) / 2   in between (continuous derivative, zero mean error).
KOKKOS_INLINE_FUNCTION double smoothed_heaviside(double s, double eps) {
  if (s <= -eps) return 0.0;
  if (s >= eps) return 1.0;
  constexpr double pi = 3.14159265358979323846;
  return 0.5 * (1.0 + s / eps + compat::sin(pi * s / eps) / pi);
}
KOKKOS_INLINE_FUNCTION double smoothed_delta(double s, double eps) {
  if (s <= -eps || s >= eps) return 0.0;
  constexpr double pi = 3.14159265358979323846;
  return 0.5 * (1.0 + compat::cos(pi * s / eps)) / eps;
}

// rhs_a = -u_a - u . grad q_a on the solid (level 1) and on the known cells where psi > 0, 0
// elsewhere; u . grad q = div_h^WENO(u q) - q div_h(u), u_a at the centre = mean of the two a-faces.
// A known cell outside the solid keeps its advected q only if it turns solid, and one with psi = 0
// is at least psi's half-width (1.5 cells) outside the surface, which moves less than a cell per
// step: it is extrapolated anew instead.
struct MapAdvectionRhs {
  Vector3 rhs, q;
  WindowField level, psi;
  Field3 u, v, w;
  double inv_h[3];

  // Per cell (GPUs).
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (!advected(level(i, j, k), psi(i, j, k))) {
      for (int a = 0; a < 3; ++a) rhs.c[a](i, j, k) = 0.0;
      return;
    }
    const double div = (u(i, j, k) - u(i - 1, j, k)) * inv_h[0] + (v(i, j, k) - v(i, j - 1, k)) * inv_h[1] +
                       (w(i, j, k) - w(i, j, k - 1)) * inv_h[2];
    const double uc[3] = {0.5 * (u(i, j, k) + u(i - 1, j, k)), 0.5 * (v(i, j, k) + v(i, j - 1, k)),
                          0.5 * (w(i, j, k) + w(i, j, k - 1))};
    for (int a = 0; a < 3; ++a)
      rhs.c[a](i, j, k) = -uc[a] - (weno_divergence(q.c[a], u, v, w, inv_h, i, j, k) - q.c[a](i, j, k) * div);
  }

  // Each cell's flux through its upper y-face, carried to the next row of the plane (hosts), and
  // whether the cell was advected (else the next row computes its lower face itself).
  static constexpr int kCarriedCells = 256;
  struct CarriedY {
    double flux[3][kCarriedCells];
    bool valid[kCarriedCells];
  };

  // A plane (hosts): its rows in order, the y-face fluxes carried from each row to the next
  // (rows longer than kCarriedCells compute both y-faces).
  void plane(int i, int j0, int j1, int k0, int k1) const {
    CarriedY carried;
    CarriedY* y = k1 - k0 <= kCarriedCells ? &carried : nullptr;
    if (y)
      for (int n = 0; n < k1 - k0; ++n) y->valid[n] = false;
    for (int j = j0; j < j1; ++j) row(i, j, k0, k1, y);
  }

  // A row: the same sums as per cell, with one offset for the window fields and one for the
  // velocity (the accessors computed one per read), and the flux through a face between two
  // advected cells computed once: along the row (z) and, with `y`, from the row below.
  void row(int i, int j, int k0, int k1, CarriedY* y) const {
    const WindowField& q0 = q.c[0];  // q, rhs, level and psi share one window (same_window)
    const long s0 = long(q0.data.stride(0)), s1 = long(q0.data.stride(1));
    const long cell = long(i - q0.lo[0]) * s0 + long(j - q0.lo[1]) * s1 + long(k0 - q0.lo[2]);
    const long t0 = long(u.stride(0)), t1 = long(u.stride(1));
    const long face0 = long(i) * t0 + long(j) * t1 + k0;
    const double *lv = level.data.data() + cell, *ps = psi.data.data() + cell;
    const double* qa[3] = {q.c[0].data.data() + cell, q.c[1].data.data() + cell, q.c[2].data.data() + cell};
    double* ra[3] = {rhs.c[0].data.data() + cell, rhs.c[1].data.data() + cell, rhs.c[2].data.data() + cell};
    const double *up = u.data() + face0, *vp = v.data() + face0, *wp = w.data() + face0;
    double upper_z[3] = {0.0, 0.0, 0.0};  // the previous cell's F_z at its upper face
    bool previous_advected = false;
    for (int n = 0; n < k1 - k0; ++n) {
      if (!advected(lv[n], ps[n])) {
        for (int a = 0; a < 3; ++a) ra[a][n] = 0.0;
        previous_advected = false;
        if (y) y->valid[n] = false;
        continue;
      }
      const double uP = up[n], uM = up[n - t0], vP = vp[n], vM = vp[n - t1], wP = wp[n], wM = wp[n - 1];
      const double div = (uP - uM) * inv_h[0] + (vP - vM) * inv_h[1] + (wP - wM) * inv_h[2];
      const double uc[3] = {0.5 * (uP + uM), 0.5 * (vP + vM), 0.5 * (wP + wM)};
      const bool below_advected = y && y->valid[n];
      for (int a = 0; a < 3; ++a) {
        const double* p = qa[a] + n;
        const double fx = (uP * face_value_upwind(p, s0, uP) - uM * face_value_upwind(p - s0, s0, uM)) * inv_h[0];
        const double lower_y = below_advected ? y->flux[a][n] : vM * face_value_upwind(p - s1, s1, vM);
        const double upper_y = vP * face_value_upwind(p, s1, vP);
        if (y) y->flux[a][n] = upper_y;
        const double fy = (upper_y - lower_y) * inv_h[1];
        const double lower_z = previous_advected ? upper_z[a] : wM * face_value_upwind(p - 1, 1, wM);
        upper_z[a] = wP * face_value_upwind(p, 1, wP);
        const double fz = (upper_z[a] - lower_z) * inv_h[2];
        ra[a][n] = -uc[a] - (fx + fy + fz - p[0] * div);
      }
      previous_advected = true;
      if (y) y->valid[n] = true;
    }
  }
};

inline void reference_map_rhs(const Vector3& rhs, const Vector3& q, const WindowField& level, const WindowField& psi,
                              const Velocity& vel, const double h[3], const Box& box) {
  if (!same_window(q, level) || !same_window(rhs, level) || !same_window(psi, level))
    throw std::logic_error("reference_map_rhs: q, rhs, psi and the level are on different windows");
  for_each_plane("eulerfsi::refmap::rhs", box,
                 MapAdvectionRhs{rhs, q, level, psi, vel.c[0], vel.c[1], vel.c[2], {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]}});
}

// Low-storage RK3 substep on the three components: q += dt (gamma rhs + zeta rhs_old).
inline void rk3_vector_update(const Vector3& q, const Vector3& rhs, const Vector3& rhs_old, double dt, double gamma,
                              double zeta, const Box& box) {
  const double a = dt * gamma, c = dt * zeta;
  const Vector3 m = q, r = rhs, ro = rhs_old;
  for_each_cell("eulerfsi::refmap::update", box, KOKKOS_LAMBDA(int i, int j, int k) {
    for (int s = 0; s < 3; ++s) m.c[s](i, j, k) += a * r.c[s](i, j, k) + c * ro.c[s](i, j, k);
  });
}

// The solid after a substep: level = 1 where the cell centre lies deeper than `margin` inside the
// body (d < -margin) and the cell was known before (level in [1, reach]: the body moves less than a
// cell per step, and an unknown cell's q is stale), else 0. Cells of the outer layer (-margin <= d)
// are extrapolated from the deeper ones like the fluid side (solid.map_margin, src/solid/reference_map_model.cpp).
// A solid cell's weight in the extension's fits, by its depth below the classification's edge
// (depth = -d - margin >= 0): 0 at the edge, rising as a C1 smoothstep to 1 at `ramp` (a length;
// 0: every solid cell weighs 1). A cell that leaves or joins the solid then leaves or enters every
// fit with weight 0, so the extension, and psi, B and the forces it feeds, change continuously.
KOKKOS_INLINE_FUNCTION double surface_weight(double depth, double ramp) {
  if (depth >= ramp) return 1.0;
  if (depth <= 0.0) return 0.0;
  const double t = depth / ramp;
  return t * t * (3.0 - 2.0 * t);
}

// weight: each solid cell's surface_weight (0 elsewhere).
inline void classify_solid(const WindowField& level, const WindowField& weight, const Vector3& q,
                           const ReferenceShape& shape, const CellCentres& xc, double reach, double margin, double ramp,
                           bool initial, const double h[3], const Box& box) {
  const double i2h[3] = {0.5 / h[0], 0.5 / h[1], 0.5 / h[2]};
  const double i0 = i2h[0], i1 = i2h[1], i2 = i2h[2];
  const Vector3 m = q;
  for_each_cell("eulerfsi::refmap::classify", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double old = level(i, j, k);
    weight(i, j, k) = 0.0;
    if (!initial && (old < kLevelSolid || old > reach)) {
      level(i, j, k) = 0.0;
      return;
    }
    // the signed distance d = (phi0(xi) + shift - shift) / |grad_x phi0| (EdgeGeometry's): the norm is
    // positive, so where the numerator is not negative d >= 0 >= -margin, and the map's gradient is
    // not needed (about two thirds of these cells lie outside the body)
    const double X[3] = {xc(0, i) + m.c[0](i, j, k), xc(1, j) + m.c[1](i, j, k), xc(2, k) + m.c[2](i, j, k)};
    double n[3];
    const double phi0 = shape.unshifted(X, n);
    if (!(phi0 - shape.shift < 0.0)) {
      level(i, j, k) = 0.0;
      return;
    }
    const double inv_2h[3] = {i0, i1, i2};
    double G[3][3];
    displacement_gradient(m, inv_2h, i, j, k, G);
    const double depth = -edge_geometry_at(phi0, n, inv_2h, G).distance(shape.shift) - margin;
    level(i, j, k) = depth > 0.0 ? kLevelSolid : 0.0;
    if (depth > 0.0) weight(i, j, k) = surface_weight(depth, ramp);
  });
}

// The conditioning at and above which an extension fit is trusted whole, and at and below which
// not at all (ExtrapolationSweep::fit_trust).
constexpr double kFitTrusted = 1e-3, kFitUntrusted = 1e-5;

// Extrapolation sweep s (Rycroft et al. 2020, sec. 2.4): every unknown cell next to a cell known
// before this sweep (1 <= level <= s, 26 neighbours) takes the value at its centre of the
// least-squares linear fit q ~ c0 + c . r through the known cells within two cells (r in cells,
// weight 1/|r|^2), and level = s + 1. Exact for a rigid motion (q linear). In place: the cells
// written were unknown and are not read in this sweep (level s + 1 > s), so the order is free.
// Fewer than four points or a degenerate set fall back to the weighted mean.
struct ExtrapolationSweep {
  Vector3 q;
  WindowField level;
  WindowField weight;  // a solid cell's surface_weight (classify_solid); band cells weigh 1
  double s;
  // The last sweep: a cell with no known cell among its 6 face neighbours is only marked
  // (pending_level) and fitted later, if a WENO stencil will read it (DeferredFits).
  bool defer_off_axis = false;
  // Whether the solid cells weigh surface_weight in the fits (solid.map_ramp_in_extension); false:
  // every known cell weighs 1, so the extension continues the surface layer's own motion (a stiff
  // sphere's elastic oscillation at Re = 400 grows when it follows the deeper cells instead)
  bool ramp_weights = true;

  // How far a fit is trusted, from its conditioning cond = min(det A / (tr A / 3)^3, schur / S): 1
  // at or above kFitTrusted, 0 at or below kFitUntrusted, a smoothstep in cond between (fit_value
  // blends a starved fit towards the full-weight one). Sets of whole cells (weights >= 1/12) give cond >=
  // 0.02 (the Re = 400, We = 0.125 desk case) or exactly 0; the surface ramp's weights
  // (solid.map_ramp) reach any value between, and a fit resting on cells of weight ~1e-9 (cond
  // 1e-10) sent a gradient from nothing into the band: a stiff sphere blew up so at Re = 400.
  KOKKOS_INLINE_FUNCTION static double fit_trust(double cond) {
    if (cond >= kFitTrusted) return 1.0;
    if (!(cond > kFitUntrusted)) return 0.0;
    const double x = (cond - kFitUntrusted) / (kFitTrusted - kFitUntrusted);
    return x * x * (3.0 - 2.0 * x);
  }

  // c0 of the normal equations [[S, m^T], [m, A]] (c0, c) = (b0, b) of the basis (1, r), by the
  // Schur complement: c0 = (b0 - m^T A^-1 b) / (S - m^T A^-1 m), with A^-1 m by cofactors (A, the
  // weighted second moments of the offsets, is symmetric positive definite unless the points lie
  // in a plane through the cell). Returns fit_trust (0 where A or the complement is singular: the
  // points do not span a linear fit; out is then not written).
  KOKKOS_INLINE_FUNCTION static double fit_centre(double S, const double m[3], const double A[6], const double b0[3],
                                                  const double b[3][3], double out[3]) {
    // A = [[A0, A3, A4], [A3, A1, A5], [A4, A5, A2]]: cofactors of the symmetric matrix
    const double c00 = A[1] * A[2] - A[5] * A[5], c01 = A[4] * A[5] - A[3] * A[2], c02 = A[3] * A[5] - A[4] * A[1];
    const double c11 = A[0] * A[2] - A[4] * A[4], c12 = A[3] * A[4] - A[0] * A[5], c22 = A[0] * A[1] - A[3] * A[3];
    const double det = A[0] * c00 + A[3] * c01 + A[4] * c02;
    const double scale = (A[0] + A[1] + A[2]) * (1.0 / 3.0);
    if (!(det > 1e-12 * scale * scale * scale)) return 0.0;
    const double inv = 1.0 / det;
    const double y[3] = {(c00 * m[0] + c01 * m[1] + c02 * m[2]) * inv, (c01 * m[0] + c11 * m[1] + c12 * m[2]) * inv,
                         (c02 * m[0] + c12 * m[1] + c22 * m[2]) * inv};
    const double schur = S - (y[0] * m[0] + y[1] * m[1] + y[2] * m[2]);
    if (!(schur > 1e-10 * S)) return 0.0;
    const double inv_schur = 1.0 / schur;
    for (int d = 0; d < 3; ++d) out[d] = (b0[d] - (y[0] * b[0][d] + y[1] * b[1][d] + y[2] * b[2][d])) * inv_schur;
    const double det_rel = det / (scale * scale * scale), schur_rel = schur / S;
    return fit_trust(det_rel < schur_rel ? det_rel : schur_rel);
  }

  // A level known before this sweep: the solid (1) or a band level up to s.
  KOKKOS_INLINE_FUNCTION bool known_level(double l) const { return l >= kLevelSolid && l <= s; }
  KOKKOS_INLINE_FUNCTION bool known(int i, int j, int k) const { return known_level(level(i, j, k)); }

  // Per cell (GPUs): an unknown cell with a known one among its 26 neighbours is fitted.
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (level(i, j, k) != 0.0) return;
    bool touches = false;
    for (int a = -1; a <= 1 && !touches; ++a)
      for (int b = -1; b <= 1 && !touches; ++b)
        for (int c = -1; c <= 1 && !touches; ++c) touches = known(i + a, j + b, k + c);
    if (touches) visit(i, j, k);
  }

  // The level of a cell the last sweep leaves for DeferredFits.
  KOKKOS_INLINE_FUNCTION double pending_level() const { return s + 1.5; }

  // Whether one of the cell's 6 face neighbours is known: the central differences of psi, B and
  // the classification at known cells read exactly these.
  KOKKOS_INLINE_FUNCTION bool face_neighbour_known(int i, int j, int k) const {
    return known(i - 1, j, k) || known(i + 1, j, k) || known(i, j - 1, k) || known(i, j + 1, k) ||
           known(i, j, k - 1) || known(i, j, k + 1);
  }

  // An unknown cell next to a known one: fitted now, or marked for DeferredFits.
  KOKKOS_INLINE_FUNCTION void visit(int i, int j, int k) const {
    if (defer_off_axis && !face_neighbour_known(i, j, k)) {
      level(i, j, k) = pending_level();
      return;
    }
    fit(i, j, k);
  }

  // Whether any of the 9 cells (i + a, j + b, k), |a|, |b| <= 1, is known.
  KOKKOS_INLINE_FUNCTION bool known_column(int i, int j, int k) const {
    bool any = false;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b) any |= known(i + a, j + b, k);
    return any;
  }

  // A row (hosts): the same cells, each column of 9 neighbours read once for the three cells
  // beside it (the per-cell search read up to 27 levels for every unknown cell). A cell this
  // sweep fills gets level s + 1, which is not known, so the columns ahead stay valid.
  KOKKOS_INLINE_FUNCTION void row(int i, int j, int k0, int k1) const {
    bool before = known_column(i, j, k0 - 1), here = known_column(i, j, k0);
    for (int k = k0; k < k1; ++k) {
      const bool after = known_column(i, j, k + 1);
      if (level(i, j, k) == 0.0 && (before || here || after)) visit(i, j, k);
      before = here;
      here = after;
    }
  }

  // The fitted value at the unknown cell (i, j, k), and its level s + 1.
  KOKKOS_INLINE_FUNCTION void fit(int i, int j, int k) const {
    double value[3];
    fit_value(i, j, k, value);
    for (int d = 0; d < 3; ++d) q.c[d](i, j, k) = value[d];
    level(i, j, k) = s + 1.0;
  }

  // A fit through the known cells around a cell: its value there (where trust > 0), the cells'
  // weighted mean (where trust < 1), its fit_trust, and whether a surface weight below 1 entered it.
  struct Fit {
    double value[3], mean[3], trust;
    bool ramped;
  };

  // The least-squares value at (i, j, k) through the known cells around it (the cell itself weighs 0),
  // the solid cells weighted by their surface_weight. Where those weights starve the fit (trust < 1:
  // the cells that span it weigh next to nothing) it goes over to the fit through the same cells at
  // full weight, which is as exact for a rigid motion; to the weighted mean only where no linear fit
  // exists (a rotating body's map has gradients of order 1: a mean beside it inverts the map).
  KOKKOS_INLINE_FUNCTION void fit_value(int i, int j, int k, double value[3]) const {
    const Fit f = weighted_fit(i, j, k, ramp_weights);
    if (f.trust >= 1.0) {
      for (int d = 0; d < 3; ++d) value[d] = f.value[d];
      return;
    }
    const Fit full = f.ramped ? weighted_fit(i, j, k, false) : f;  // every cell at full weight
    for (int d = 0; d < 3; ++d) {
      double fallback = full.value[d];  // exactly the full-weight fit where it is trusted
      if (full.trust < 1.0)
        fallback = full.trust > 0.0 ? full.mean[d] + full.trust * (full.value[d] - full.mean[d]) : full.mean[d];
      value[d] = f.trust > 0.0 && f.ramped ? fallback + f.trust * (f.value[d] - fallback) : fallback;
    }
  }

  // The fit through the known cells, the solid ones weighted by surface_weight if `ramp` (else 1).
  KOKKOS_INLINE_FUNCTION Fit weighted_fit(int i, int j, int k, bool ramp) const {
    // weights 1/|r|^2 by |r|^2 = 1..12 (the centre, r = 0, is the unknown cell itself)
    const double inv_r2[13] = {0.0,       1.0,       1.0 / 2,  1.0 / 3,  1.0 / 4,  1.0 / 5, 1.0 / 6,
                               1.0 / 7,   1.0 / 8,   1.0 / 9,  1.0 / 10, 1.0 / 11, 1.0 / 12};
    // normal equations M c = rhs of the basis (1, a, b, c): M holds the weighted moments
    // sum w a^m b^n c^l (m + n + l <= 2) of the known offsets, rhs sum w (1, a, b, c) q. Each line
    // along c is summed first (its moments in c and q), then weighted by a and b: 9 multiply-adds
    // per known point instead of 22.
    double S = 0, Sa = 0, Sb = 0, Sc = 0, Saa = 0, Sab = 0, Sac = 0, Sbb = 0, Sbc = 0, Scc = 0;
    double rhs[4][3] = {};
    bool ramped = false;
    // level and q share one window (same_window): one offset serves the four fields (the window
    // accessor computed it for each, 100 times per fit)
    const long s0 = long(level.data.stride(0)), s1 = long(level.data.stride(1));
    const long centre = long(i - level.lo[0]) * s0 + long(j - level.lo[1]) * s1 + long(k - level.lo[2]);
    const double *const l0 = level.data.data(), *const q0 = q.c[0].data.data(), *const q1 = q.c[1].data.data(),
                        *const q2 = q.c[2].data.data(), *const wt0 = weight.data.data();
    for (int a = -2; a <= 2; ++a)
      for (int b = -2; b <= 2; ++b) {
        double sw = 0, swc = 0, swcc = 0, swq[3] = {}, swcq[3] = {};
        // the line's five cells are contiguous (z is the fastest index)
        const long line = centre + a * s0 + b * s1 - 2;
        const double* lv = l0 + line;
        const double* wt = wt0 + line;
        const double* ql[3] = {q0 + line, q1 + line, q2 + line};
        const double* w_line = inv_r2 + a * a + b * b;  // w = w_line[c^2]
        for (int c = -2; c <= 2; ++c) {
          if (!known_level(lv[c + 2])) continue;
          const double surface = ramp && lv[c + 2] == kLevelSolid ? wt[c + 2] : 1.0;
          ramped |= surface < 1.0;
          const double w = w_line[c * c] * surface, wc = w * c;
          sw += w;
          swc += wc;
          swcc += wc * c;
          for (int d = 0; d < 3; ++d) {
            const double qv = ql[d][c + 2];
            swq[d] += w * qv;
            swcq[d] += wc * qv;
          }
        }
        S += sw, Sa += a * sw, Sb += b * sw, Sc += swc;
        Saa += a * a * sw, Sab += a * b * sw, Sac += a * swc, Sbb += b * b * sw, Sbc += b * swc, Scc += swcc;
        for (int d = 0; d < 3; ++d) {
          rhs[0][d] += swq[d];
          rhs[1][d] += a * swq[d];
          rhs[2][d] += b * swq[d];
          rhs[3][d] += swcq[d];
        }
      }
    const double m[3] = {Sa, Sb, Sc}, A[6] = {Saa, Sbb, Scc, Sab, Sac, Sbc};
    const double b[3][3] = {{rhs[1][0], rhs[1][1], rhs[1][2]}, {rhs[2][0], rhs[2][1], rhs[2][2]},
                            {rhs[3][0], rhs[3][1], rhs[3][2]}};
    Fit f;
    f.trust = fit_centre(S, m, A, rhs[0], b, f.value);
    f.ramped = ramped;
    if (f.trust < 1.0)  // the mean is read only where the fit is not trusted whole
      for (int d = 0; d < 3; ++d) f.mean[d] = S > 0.0 ? rhs[0][d] / S : q.c[d](i, j, k);
    return f;
  }
};

// defer_off_axis: the last sweep, whose cells without a known face neighbour wait for
// finish_deferred_fits(). ramp_weights: ExtrapolationSweep::ramp_weights.
inline void extrapolation_sweep(const Vector3& q, const WindowField& level, const WindowField& weight, int sweep,
                                const Box& box, bool defer_off_axis = false, bool ramp_weights = true) {
  if (!same_window(q, level) || !same_window(weight, level))
    throw std::logic_error("extrapolation_sweep: q, its level and weight are on different windows");
  for_each_row("eulerfsi::refmap::extrapolate", box, ExtrapolationSweep{q, level, weight, double(sweep), defer_off_axis, ramp_weights});
}

// The surface ramp's solid cells (surface_weight < 1) blend their carried map with the fit through
// the solid around them,  q <- q + rate (1 - w) (q_fit - q)  (rate 1: q <- w q + (1 - w) q_fit, so a
// cell's q reaches the extension's value as it leaves the solid; rate = dt / solid.map_relax_time
// < 1 relaxes it over that time instead). The fits read the carried values, as the extrapolation
// sweeps do: first surface_fits (before the sweeps) writes the blend to `out`, then
// store_surface_blend (after them) moves it into q; at w = 0 and rate 1 the cell then holds what
// the first sweep gives it once it has left.
inline void surface_fits(const Vector3& q, const WindowField& level, const WindowField& weight, const Vector3& out,
                         const Box& box, double rate = 1.0) {
  if (!same_window(q, level) || !same_window(weight, level))
    throw std::logic_error("surface_fits: q, its level and weight are on different windows");
  const ExtrapolationSweep solid{q, level, weight, kLevelSolid};
  const Vector3 o = out;
  for_each_cell("eulerfsi::refmap::surface_fits", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double w = solid.weight(i, j, k);
    if (solid.level(i, j, k) != kLevelSolid || w >= 1.0) return;
    double fitted[3];
    solid.fit_value(i, j, k, fitted);
    const double b = rate * (1.0 - w), a = rate == 1.0 ? w : 1.0 - b;  // rate 1: w q + (1 - w) q_fit exactly
    for (int d = 0; d < 3; ++d) o.c[d](i, j, k) = a * solid.q.c[d](i, j, k) + b * fitted[d];
  });
}

inline void store_surface_blend(const Vector3& q, const WindowField& level, const WindowField& weight, const Vector3& out,
                                const Box& box) {
  const Vector3 m = q, o = out;
  const WindowField l = level, w = weight;
  for_each_cell("eulerfsi::refmap::surface_blend", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (l(i, j, k) != kLevelSolid || w(i, j, k) >= 1.0) return;
    for (int d = 0; d < 3; ++d) m.c[d](i, j, k) = o.c[d](i, j, k);
  });
}

// The last sweep's pending cells once psi is known: fitted exactly as that sweep would have (the
// known cells it reads, levels 1..s, have not changed since) where the WENO5 stencil of an advected
// cell reads them, 3 cells either way along each axis; the others (about a third of that sweep's
// cells around a sphere) are read by nothing before the next classification forgets them, and
// keep their stale q. Every pending cell gets the level s + 1 the sweep would have given it.
struct DeferredFits {
  ExtrapolationSweep sweep;
  WindowField psi;

  KOKKOS_INLINE_FUNCTION bool read_by_advection(int i, int j, int k) const {
    const WindowField& l = sweep.level;
    for (int r = 1; r <= 3; ++r)
      if (advected(l(i - r, j, k), psi(i - r, j, k)) || advected(l(i + r, j, k), psi(i + r, j, k)) ||
          advected(l(i, j - r, k), psi(i, j - r, k)) || advected(l(i, j + r, k), psi(i, j + r, k)) ||
          advected(l(i, j, k - r), psi(i, j, k - r)) || advected(l(i, j, k + r), psi(i, j, k + r)))
        return true;
    return false;
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (sweep.level(i, j, k) != sweep.pending_level()) return;
    if (read_by_advection(i, j, k)) {
      sweep.fit(i, j, k);
    } else {
      sweep.level(i, j, k) = sweep.s + 1.0;
    }
  }
};

inline void finish_deferred_fits(const Vector3& q, const WindowField& level, const WindowField& weight,
                                 const WindowField& psi, int last_sweep, const Box& box, bool ramp_weights = true) {
  if (!same_window(q, level)) throw std::logic_error("finish_deferred_fits: q and its level are on different windows");
  for_each_cell("eulerfsi::refmap::deferred_fits", box, DeferredFits{ExtrapolationSweep{q, level, weight, double(last_sweep), false, ramp_weights}, psi});
}

// psi and B from the map on the known cells whose central differences read known cells
// (1 <= level <= max_level); psi = 0 and B = I elsewhere.
//   psi = H_eps(-d),  eps = width x (grid spacing along the normal),  B = F F^T,  F = (I + grad q)^-1
// psi at a cell: H_eps(-d) with eps = width x (spacing along the normal), on the known cells whose
// central differences read known cells (1 <= level <= max_level); -1 elsewhere (psi = 0 and B = I there).
// G gets grad q where psi is derived.
// `edge` (if given) gets the cell's EdgeGeometry where psi is derived.
KOKKOS_INLINE_FUNCTION double psi_of_map(const Vector3& q, const WindowField& level, const ReferenceShape& shape,
                                         const CellCentres& xc, const double inv_2h[3], double width, double max_level,
                                         int i, int j, int k, double G[3][3], EdgeGeometry* edge = nullptr) {
  if (!derived_level(level(i, j, k), max_level)) return -1.0;
  const double x[3] = {xc(0, i), xc(1, j), xc(2, k)};
  displacement_gradient(q, inv_2h, i, j, k, G);
  const EdgeGeometry e = edge_geometry(q, shape, x, inv_2h, i, j, k, G);
  if (edge) *edge = e;
  return smoothed_heaviside(-e.distance(shape.shift), width * e.normal_h);
}

// Where solid_from_map() leaves the EdgeGeometry of the cells where it derives psi, for
// psi_at_shift(): phi0 + shift, the gradient's norm and the edge's half-width eps = width x normal_h.
struct EdgeFields {
  Scratch3 f;
  KOKKOS_FORCEINLINE_FUNCTION void store(int i, int j, int k, const EdgeGeometry& e, double eps) const {
    f.c[0](i, j, k) = e.unshifted_phi;
    f.c[1](i, j, k) = e.gradient_norm;
    f.c[2](i, j, k) = eps;
  }
};

// edges: where to leave the EdgeGeometry (null fields: nowhere).
inline void solid_from_map(const WindowField& psi, const Tensor6& b, const Vector3& q, const WindowField& level,
                           const ReferenceShape& shape, const CellCentres& xc, double width, double max_level,
                           const double h[3], const Box& box, const EdgeFields& edges = {}) {
  const double i0 = 0.5 / h[0], i1 = 0.5 / h[1], i2 = 0.5 / h[2];
  const Vector3 m = q;
  const Tensor6 bb = b;
  const bool keep_edges = edges.f.c[0].allocated();
  for_each_cell("eulerfsi::refmap::psi_and_b", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double inv_2h[3] = {i0, i1, i2};
    double G[3][3];
    // gradient_norm stays 0 where psi is not derived (it is > 0 where it is)
    EdgeGeometry e{0.0, 0.0, 0.0};
    const double p = psi_of_map(m, level, shape, xc, inv_2h, width, max_level, i, j, k, G, &e);
    // a derived psi that rounded below 0 too: psi_at_shift() clips it as psi_from_map() does
    if (keep_edges && e.gradient_norm > 0.0) edges.store(i, j, k, e, width * e.normal_h);
    if (p < 0.0) {
      psi(i, j, k) = 0.0;
      for (int c = 0; c < kTensorComponents; ++c) bb.c[c](i, j, k) = c < 3 ? 1.0 : 0.0;
      return;
    }
    psi(i, j, k) = p;
    // F = A^-1 with A = grad xi = I + grad q, by cofactors
    double A[3][3];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) A[a][c] = (a == c ? 1.0 : 0.0) + G[a][c];
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    double F[3][3];
    F[0][0] = (A[1][1] * A[2][2] - A[1][2] * A[2][1]) / det;
    F[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) / det;
    F[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) / det;
    F[1][0] = (A[1][2] * A[2][0] - A[1][0] * A[2][2]) / det;
    F[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) / det;
    F[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) / det;
    F[2][0] = (A[1][0] * A[2][1] - A[1][1] * A[2][0]) / det;
    F[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) / det;
    F[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) / det;
    const int ra[kTensorComponents] = {0, 1, 2, 0, 0, 1};
    const int rc[kTensorComponents] = {0, 1, 2, 1, 2, 2};
    for (int s = 0; s < kTensorComponents; ++s) {
      double v = 0.0;
      for (int n = 0; n < 3; ++n) v += F[ra[s]][n] * F[rc[s]][n];
      bb.c[s](i, j, k) = v;
    }
  });
}

// psi alone (solid_from_map's, at any half-width): the volume correction, which moves only the
// level, and the diagnostics' zero-width extrapolation of the shape moments.
inline void psi_from_map(const WindowField& psi, const Vector3& q, const WindowField& level, const ReferenceShape& shape,
                         const CellCentres& xc, double width, double max_level, const double h[3], const Box& box) {
  const double i0 = 0.5 / h[0], i1 = 0.5 / h[1], i2 = 0.5 / h[2];
  const Vector3 m = q;
  for_each_cell("eulerfsi::refmap::psi_at_width", box, KOKKOS_LAMBDA(int i, int j, int k) {
    const double inv_2h[3] = {i0, i1, i2};
    double G[3][3];
    psi(i, j, k) = compat::fmax(0.0, psi_of_map(m, level, shape, xc, inv_2h, width, max_level, i, j, k, G));
  });
}

// psi again after the level shift moved (the volume correction), from solid_from_map()'s edges:
// psi = max(0, H_eps(-(phi0 + shift_old - shift) / |grad_x phi0|)), the value psi_from_map() gives,
// without the map's gradient and the shape's distance again.
inline void psi_at_shift(const WindowField& psi, const EdgeFields& edges, const WindowField& level, double max_level,
                         double shift, const Box& box) {
  const Scratch3 e = edges.f;
  for_each_cell("eulerfsi::refmap::psi_at_shift", box, KOKKOS_LAMBDA(int i, int j, int k) {
    if (!derived_level(level(i, j, k), max_level)) {
      psi(i, j, k) = 0.0;
      return;
    }
    const EdgeGeometry g{e.c[0](i, j, k), e.c[1](i, j, k), 0.0};
    psi(i, j, k) = compat::fmax(0.0, smoothed_heaviside(-g.distance(shift), e.c[2](i, j, k)));
  });
}

// sum psi and sum |grad psi| (central differences), times the cell volume: the body's volume and
// surface area (dV/dshift of the level shift, for the volume correction), each over a box that
// holds every cell where it is non-zero (psi's, and psi's grown by one for the gradient).
inline void volume_and_area(const WindowField& psi, const double h[3], const Box& box, const Box& gradient_box,
                            double& volume, double& area) {
  const double i0 = 0.5 / h[0], i1 = 0.5 / h[1], i2 = 0.5 / h[2], dv = h[0] * h[1] * h[2];
  double v = 0.0, a = 0.0;
  reduce_cells("eulerfsi::refmap::volume", box, KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
    acc += psi(i, j, k) * dv;
  }, Kokkos::Sum<double>(v));
  reduce_cells("eulerfsi::refmap::area", gradient_box, KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
    const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * i0;
    const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * i1;
    const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * i2;
    acc += compat::sqrt(gx * gx + gy * gy + gz * gz) * dv;
  }, Kokkos::Sum<double>(a));
  volume = v;
  area = a;
}

// Ghosts of q at a wall (y or z). Where the first interior cell is solid (level kLevelSolid: a
// body bonded to the wall, the layer), the no-slip wall holds its material where it started, so
// q = 0 on the wall: the odd reflection q(-m) = -q(m - 1), exact for q linear and 0 at the wall,
// which lets the elastic stress, not only the viscous one, hold the body (a purely elastic layer
// slides on a wall it is not bonded to). Elsewhere (fluid, the extension of a body near the wall)
// linear extrapolation from the first two interior cells, q(-m) = q(0) - m (q(1) - q(0)), exact for
// a linear map (the mirror fill of a scalar is not).
// low / high: which of the two walls (a window may hold the ghosts of one only).
inline void extrapolate_wall_ghosts(const Vector3& q, const WindowField& level, int dir, int n_interior, const Box& all,
                                    bool low = true, bool high = true) {
  const int lo = kGhost, hi = kGhost + n_interior - 1;
  Box plane = all;
  plane.lo[dir] = 0;
  plane.hi[dir] = 1;
  // (i, s, k) for dir = 1, (i, j, s) for dir = 2: s is the wall-normal index
  const int sj = dir == 1, sk = dir == 2;
  const WindowField l = level;
  for (int a = 0; a < 3; ++a) {
    const WindowField f = q.c[a];
    for_each_cell("eulerfsi::refmap::wall_ghosts", plane, KOKKOS_LAMBDA(int i, int j, int k) {
      const int j0 = j * (1 - sj), k0 = k * (1 - sk);
      if (low) {
        const bool bonded = l(i, j0 + sj * lo, k0 + sk * lo) == kLevelSolid;
        const double qlo = f(i, j0 + sj * lo, k0 + sk * lo), qlo1 = f(i, j0 + sj * (lo + 1), k0 + sk * (lo + 1));
        for (int m = 1; m <= kGhost; ++m)
          f(i, j0 + sj * (lo - m), k0 + sk * (lo - m)) =
              bonded ? -f(i, j0 + sj * (lo + m - 1), k0 + sk * (lo + m - 1)) : qlo - m * (qlo1 - qlo);
      }
      if (high) {
        const bool bonded = l(i, j0 + sj * hi, k0 + sk * hi) == kLevelSolid;
        const double qhi = f(i, j0 + sj * hi, k0 + sk * hi), qhi1 = f(i, j0 + sj * (hi - 1), k0 + sk * (hi - 1));
        for (int m = 1; m <= kGhost; ++m)
          f(i, j0 + sj * (hi + m), k0 + sk * (hi + m)) =
              bonded ? -f(i, j0 + sj * (hi - m + 1), k0 + sk * (hi - m + 1)) : qhi - m * (qhi1 - qhi);
      }
    });
  }
}

// Wall ghosts of the level field are unknown (0): their q is the linear extrapolation of the first
// two owned cells, which may themselves be unknown (stale) during an extrapolation sweep; a
// mirrored level would let the sweep fit through them, and a stale q(0) re-enters q(0) tripled
// (q(-2) = 3 q(0) - 2 q(1)) every step: the divergence of a body within 4 cells of a wall.
inline void clear_wall_ghosts(const WindowField& level, int dir, int n_interior, const Box& all, bool low = true,
                              bool high = true) {
  const int lo = kGhost, hi = kGhost + n_interior - 1;
  Box plane = all;
  plane.lo[dir] = 0;
  plane.hi[dir] = kGhost;
  const int sj = dir == 1, sk = dir == 2;
  for_each_cell("eulerfsi::refmap::wall_level", plane, KOKKOS_LAMBDA(int i, int j, int k) {
    const int m = sj * j + sk * k + 1;  // ghost layer 1..kGhost
    const int j0 = j * (1 - sj), k0 = k * (1 - sk);
    if (low) level(i, j0 + sj * (lo - m), k0 + sk * (lo - m)) = 0.0;
    if (high) level(i, j0 + sj * (hi + m), k0 + sk * (hi + m)) = 0.0;
  });
}

}  // namespace eulerfsi::kernels

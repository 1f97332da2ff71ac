// The reference map's extrapolation beyond the body (kernels/reference_map.hpp): the least-squares
// sweeps reproduce a rigid motion exactly, with and without the surface ramp's weights and blend,
// also where those weights starve a fit;
// a cell leaving the solid changes the extension continuously with the ramp (and by a jump
// without) in the first shell, and in the second only with the smooth band fit
// (kernels/smooth_band_fit.hpp); the last sweep's deferred cells (DeferredFits) hold, wherever
// anything reads them, the values of a full sweep, bit for bit; the host rows equal the per-cell form (GPUs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "kernels/reference_map.hpp"
#include "kernels/smooth_band_fit.hpp"

using namespace eulerfsi;

namespace {

constexpr int kN = 34;  // cells per side of the window (h = 1)
constexpr double kCentre[3] = {16.3, 15.8, 16.55};
constexpr double kRadius = 6.4;  // 12.8 cells per diameter, as a d = D/5 particle at 128 x 64^2
constexpr int kLastSweep = 3;
constexpr double kMaxDerivedLevel = 3.0;
const Box kInterior{{4, 4, 4}, {kN - 4, kN - 4, kN - 4}};

// q = xi - x: a rotation by 0.3 about z and a translation, plus quadratic terms if `deformed`
double map_value(int a, int i, int j, int k, bool deformed) {
  const double x[3] = {i - 16.0, j - 16.0, k - 16.0}, c = std::cos(0.3), s = std::sin(0.3);
  const double rotated[3] = {c * x[0] - s * x[1], s * x[0] + c * x[1], x[2]};
  const double shift[3] = {0.4, -0.25, 0.1};
  double v = rotated[a] - x[a] + shift[a];
  if (deformed) v += a == 0 ? 0.01 * x[1] * x[2] : (a == 1 ? 0.002 * x[0] * x[0] : 0.005 * x[1] * x[1]);
  return v;
}

// ramp: the surface ramp in cells (0: every solid cell weighs 1); margin: solid.map_margin in cells.
struct Map {
  kernels::Vector3 q;
  WindowField level, weight;
  kernels::ReferenceShape shape;
  kernels::CellCentres centres{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
  double ramp;

  explicit Map(bool deformed, double ramp_cells = 0.0, double margin = 0.0) : ramp(ramp_cells) {
    level = WindowField(Field3("level", kN, kN, kN));
    weight = WindowField(Field3("weight", kN, kN, kN));
    for (int a = 0; a < 3; ++a) {
      q.c[a] = WindowField(Field3("q", kN, kN, kN));
      auto h = Kokkos::create_mirror_view(q.c[a].data);
      for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
          for (int k = 0; k < kN; ++k) h(i, j, k) = map_value(a, i, j, k, deformed);
      Kokkos::deep_copy(q.c[a].data, h);
    }
    shape.radius = kRadius;
    for (int a = 0; a < 3; ++a) shape.centre[a] = kCentre[a];  // in the reference configuration
    const double h[3] = {1.0, 1.0, 1.0};
    kernels::classify_solid(level, weight, q, shape, centres, 3.0, margin, ramp, true, h, kInterior);
  }
  // sweeps 1 .. kLastSweep, the last one deferring its off-axis cells if `defer`
  void extrapolate(bool defer) const {
    for (int s = 1; s <= kLastSweep; ++s)
      kernels::extrapolation_sweep(q, level, weight, s, kInterior, defer && s == kLastSweep);
  }
  // the sweeps with the surface ramp's blend around them, as the model runs them; edge_ratio > 0:
  // the smooth band fit (solid.map_smooth_band) with that edge ramp over the surface ramp
  void blend_and_extrapolate(double rate = 1.0, double edge_ratio = 0.0) const {
    kernels::Vector3 out;
    for (int a = 0; a < 3; ++a) out.c[a] = WindowField(Field3("blend", kN, kN, kN));
    if (edge_ratio > 0.0) {
      kernels::smooth_surface_fits(q, level, weight, out, kInterior, rate, edge_ratio);
      for (int s = 1; s <= kLastSweep; ++s) {
        kernels::extrapolation_sweep(q, level, weight, s, kInterior);
        if (s == int(kMaxDerivedLevel) - 1)
          kernels::smooth_band_fit(q, level, weight, kMaxDerivedLevel, edge_ratio, kInterior);
      }
    } else {
      kernels::surface_fits(q, level, weight, out, kInterior, rate);
      extrapolate(false);
    }
    kernels::store_surface_blend(q, level, weight, out, kInterior);
  }
};

// The signed distance to the surface at cell (i, j, k) as classify_solid computes it, on the host
// from the map's formula (its central differences are exact for the quadratic map).
double surface_distance(const Map& m, int i, int j, int k, bool deformed) {
  double X[3], n[3], G[3][3];
  for (int a = 0; a < 3; ++a) {
    const int idx[3] = {i, j, k};
    X[a] = idx[a] + map_value(a, i, j, k, deformed);
    for (int b = 0; b < 3; ++b) {
      int lo[3] = {i, j, k}, hi[3] = {i, j, k};
      lo[b] -= 1;
      hi[b] += 1;
      G[a][b] = 0.5 * (map_value(a, hi[0], hi[1], hi[2], deformed) - map_value(a, lo[0], lo[1], lo[2], deformed));
    }
  }
  const double phi0 = m.shape.unshifted(X, n);
  const double inv_2h[3] = {0.5, 0.5, 0.5};
  return kernels::edge_geometry_at(phi0, n, inv_2h, G).distance(m.shape.shift);
}

using HostCells = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>;
HostCells on_host(const WindowField& f) { return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data); }

}  // namespace

// Rycroft et al. (2020) sec. 2.4: a linear fit through the known cells is exact for a linear q,
// so every band cell carries the rigid motion to round-off.
TEST(MapExtrapolation, ExactForARigidMotion) {
  for (const double ramp : {0.0, 1.0, 2.0}) {  // 2: a ramp of 1 with the smooth band fit
    SCOPED_TRACE(ramp);
    const Map m(false, std::fmin(ramp, 1.0));
    if (ramp > 1.0) {
      m.blend_and_extrapolate(1.0, 0.2);
    } else if (ramp > 0.0) {
      m.blend_and_extrapolate();
    } else {
      m.extrapolate(false);
    }
    const HostCells level = on_host(m.level);
  int band = 0;
  double worst = 0.0;
  for (int a = 0; a < 3; ++a) {
    const HostCells q = on_host(m.q.c[a]);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j)
        for (int k = 0; k < kN; ++k)
          if (level(i, j, k) > kernels::kLevelSolid) {
            band += a == 0;
            worst = std::fmax(worst, std::fabs(q(i, j, k) - map_value(a, i, j, k, false)));
          }
  }
    EXPECT_GT(band, 2000);  // three shells around the sphere
    // |q| <= 10 on the window: a few ulps of the normal equations' sums (125 points a sweep; the
    // smooth fit's ~180, extrapolated up to 3 cells from a one-sided cap: a hundred times that)
    EXPECT_LT(worst, ramp > 1.0 ? 1e-10 : 1e-12);
  }
}

// A fit whose only cell off a plane weighs next to nothing (the surface ramp's weight of a cell at
// the classification's edge, ~1e-9 in a stiff sphere at Re = 400) still carries a rigid motion
// exactly: the fit through the same cells at full weight takes over, not their weighted mean, which
// beside a body turned by 80 degrees (grad q of order 1) put an inverted map into the band and blew
// the run up. Known cells: the plane i = 2 at full weight and (3, 5, 5) at weight w; the fitted
// cell (4, 4, 4); q a rotation by 1.4 about y and a translation.
TEST(MapExtrapolation, AStarvedFitStillCarriesARigidMotion) {
  constexpr int n = 9;
  auto rotated = [](int a, int i, int j, int k) {
    const double x[3] = {i - 4.0, j - 4.0, k - 4.0}, c = std::cos(1.4), s = std::sin(1.4);
    const double r[3] = {c * x[0] + s * x[2], x[1], -s * x[0] + c * x[2]};
    return r[a] - x[a] + (a == 0 ? 0.3 : (a == 1 ? -0.2 : 0.1));
  };
  for (const double w : {1.0, 1e-3, 1e-5, 1e-8, 1e-12}) {
    SCOPED_TRACE(w);
    kernels::Vector3 q;
    WindowField level(Field3("level", n, n, n)), weight(Field3("weight", n, n, n));
    auto hl = Kokkos::create_mirror_view(level.data);
    auto hw = Kokkos::create_mirror_view(weight.data);
    Kokkos::deep_copy(hl, 0.0);
    Kokkos::deep_copy(hw, 0.0);
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) hl(2, j, k) = kernels::kLevelSolid, hw(2, j, k) = 1.0;
    hl(3, 5, 5) = kernels::kLevelSolid;
    hw(3, 5, 5) = w;
    Kokkos::deep_copy(level.data, hl);
    Kokkos::deep_copy(weight.data, hw);
    for (int a = 0; a < 3; ++a) {
      q.c[a] = WindowField(Field3("q", n, n, n));
      auto h = Kokkos::create_mirror_view(q.c[a].data);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < n; ++k) h(i, j, k) = hl(i, j, k) > 0 ? rotated(a, i, j, k) : 0.0;
      Kokkos::deep_copy(q.c[a].data, h);
    }
    kernels::extrapolation_sweep(q, level, weight, 1, Box{{4, 4, 4}, {5, 5, 5}}, false);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(on_host(q.c[a])(4, 4, 4), rotated(a, 4, 4, 4), 1e-12) << "component " << a;
    EXPECT_EQ(on_host(level)(4, 4, 4), 2.0);
  }
}

// A solid cell that leaves the solid (its depth below the edge from +1e-9 to -1e-9 cells, by the
// margin) while the carried labels of the surface layer have drifted from the interior's linear
// map (0.05 cells here; about 0.13 h in the quick start at 6.4 cells per d): without the ramp the
// cell drops out of the fits at full weight and its q is replaced, and the solid and the first
// shell (levels 1-2, where psi is largest outside the body) jump by a fraction of the drift; with
// it the cell weighs ~1e-18 as it leaves and they change by round-off. The second shell (level 3)
// still jumps with the sweeps, a cell that changes level being fitted through other cells (their
// cascade), and changes to first order in the margin's step with the smooth band fit wherever its
// single fit through the solid is trusted whole (about two thirds of that shell).
TEST(MapExtrapolation, ACellLeavingTheSolidChangesTheExtensionContinuously) {
  const Map probe(false);
  const HostCells level = on_host(probe.level);
  double shallowest = 1e30;
  int at[3] = {0, 0, 0};
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kN; ++k)
        if (level(i, j, k) == kernels::kLevelSolid && -surface_distance(probe, i, j, k, false) < shallowest) {
          shallowest = -surface_distance(probe, i, j, k, false);
          at[0] = i, at[1] = j, at[2] = k;
        }
  ASSERT_GT(shallowest, 1e-6);
  // the drift: on the surface layer (depth < 1 cell), away from the probed cell and its face
  // neighbours (its own classification reads them)
  auto drifted = [&](const Map& m) {
    for (int a = 0; a < 3; ++a) {
      auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), m.q.c[a].data);
      for (int i = 1; i < kN - 1; ++i)
        for (int j = 1; j < kN - 1; ++j)
          for (int k = 1; k < kN - 1; ++k) {
            const int far = std::abs(i - at[0]) + std::abs(j - at[1]) + std::abs(k - at[2]);
            const double depth = -surface_distance(m, i, j, k, false);
            if (far > 1 && depth > 0.0 && depth < 1.0) h(i, j, k) += 0.05 * std::sin(i + 2.0 * j + 3.0 * k + a);
          }
      Kokkos::deep_copy(m.q.c[a].data, h);
    }
  };
  // [0] no ramp, [1] the ramp, over levels 1-2; [2] the ramp and [3] the ramp with the smooth band
  // fit, over levels 1-3 (psi's whole band)
  double jump[4] = {0.0, 0.0, 0.0, 0.0};
  int covered = 0, uncovered = 0;  // level-3 cells with and without a whole single fit (both variants)
  for (const int variant : {0, 1, 2}) {
    const int with_ramp = variant > 0 ? 1 : 0;
    const double ramp = with_ramp;
    const Map in(false), out(false);
    for (const Map* m : {&in, &out}) drifted(*m);
    // classified again on the drifted map, the probed cell just inside and just outside
    const double h[3] = {1.0, 1.0, 1.0};
    kernels::classify_solid(in.level, in.weight, in.q, in.shape, in.centres, 3.0, shallowest - 1e-9, ramp, true, h,
                            kInterior);
    kernels::classify_solid(out.level, out.weight, out.q, out.shape, out.centres, 3.0, shallowest + 1e-9, ramp, true, h,
                            kInterior);
    for (const Map* m : {&in, &out}) {
      if (variant == 2) {
        m->blend_and_extrapolate(1.0, 0.2);
      } else if (ramp > 0.0) {
        m->blend_and_extrapolate();
      } else {
        m->extrapolate(false);
      }
    }
    const HostCells li = on_host(in.level), lo = on_host(out.level);
    EXPECT_EQ(li(at[0], at[1], at[2]), kernels::kLevelSolid);
    EXPECT_NE(lo(at[0], at[1], at[2]), kernels::kLevelSolid);
    for (int a = 0; a < 3; ++a) {
      const HostCells qi = on_host(in.q.c[a]), qo = on_host(out.q.c[a]);
      for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
          for (int k = 0; k < kN; ++k)
            {
              const double l = std::fmax(li(i, j, k), lo(i, j, k)), d = std::fabs(qi(i, j, k) - qo(i, j, k));
              if (!(li(i, j, k) > 0.0 && lo(i, j, k) > 0.0)) continue;
              if (variant < 2 && l <= 2.0) jump[variant] = std::fmax(jump[variant], d);
              if (variant == 0 || l > 3.0) continue;
              // level 3: where the single fit is trusted whole on both sides (the rest take the
              // sweeps' value in part: the kernel's comment)
              if (l > 2.0) {
                double unused[3];
                const kernels::SmoothBandFit fi{in.q, in.level, in.weight, kMaxDerivedLevel, 0.2},
                    fo{out.q, out.level, out.weight, kMaxDerivedLevel, 0.2};
                const bool whole = fi.fit_at(i, j, k, unused) >= 1.0 && fo.fit_at(i, j, k, unused) >= 1.0;
                if (a == 0) ++(whole ? covered : uncovered);
                if (!whole) continue;
              }
              jump[variant + 1] = std::fmax(jump[variant + 1], d);
            }
    }
  }
  EXPECT_GT(jump[0], 1e-3) << "without the ramp the extension jumps by a fraction of the drift";
  EXPECT_LT(jump[1], 1e-8);
  EXPECT_GT(jump[2], 1e-4) << "the sweeps' cascade: the second shell jumps where a cell changes level";
  // first order in the margin's step (2e-9 cells, which moves every cell's depth): the edge weight's
  // slope is up to 1.5 / 0.2 per cell, on fits extrapolating a 0.05 drift up to 3 cells
  EXPECT_LT(jump[3], 1e-6) << "the smooth band fit: no cascade";
  EXPECT_GT(covered, uncovered) << "the single fit covers most of the second shell";
}

// solid.map_relax_time: a ramp cell goes the fraction rate (1 - w) of the way from its carried q to
// the fit each substep (rate = dt / relax_time), so its distance from the fit shrinks by exactly
// 1 - rate (1 - w); rate 1 is the full blend bit for bit. A deformed map (the fit is not exact).
TEST(MapExtrapolation, RampCellsRelaxTowardsTheFitAtTheGivenRate) {
  const double rate = 0.3;
  const Map full(true, 1.0), relaxed(true, 1.0), before(true, 1.0);
  full.blend_and_extrapolate(1.0);
  relaxed.blend_and_extrapolate(rate);
  const HostCells level = on_host(before.level), weight = on_host(before.weight);
  int ramp_cells = 0;
  for (int a = 0; a < 3; ++a) {
    const HostCells q0 = on_host(before.q.c[a]), qf = on_host(full.q.c[a]), qr = on_host(relaxed.q.c[a]);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j)
        for (int k = 0; k < kN; ++k) {
          const double w = weight(i, j, k);
          if (level(i, j, k) != kernels::kLevelSolid || w >= 1.0) continue;
          ++ramp_cells;
          // the fit, from the full blend: qf = w q0 + (1 - w) fit
          const double fit = (qf(i, j, k) - w * q0(i, j, k)) / (1.0 - w);
          EXPECT_NEAR(qr(i, j, k) - fit, (1.0 - rate * (1.0 - w)) * (q0(i, j, k) - fit), 1e-12);
        }
  }
  EXPECT_GT(ramp_cells, 30);
}

// The last sweep fits at once only the cells with a known face neighbour (the central differences
// read them); the others wait for psi and are fitted where a WENO5 stencil of an advected cell
// reads them (3 cells along an axis). There, and at the face neighbours of every derived cell,
// q must be the full sweep's bit for bit; the levels must be the full sweep's everywhere.
TEST(MapExtrapolation, DeferredFitsAreTheFullSweepWhereverRead) {
  const Map full(true), deferred(true);
  full.extrapolate(false);
  deferred.extrapolate(true);
  {
    const HostCells level = on_host(deferred.level);
    int pending = 0;
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j)
        for (int k = 0; k < kN; ++k) pending += level(i, j, k) == kLastSweep + 1.5;
    EXPECT_GT(pending, 100) << "the last sweep defers the cells off the axes";
  }
  // psi as the model derives it after the sweeps
  WindowField psi(Field3("psi", kN, kN, kN));
  kernels::Tensor6 b;
  for (int c = 0; c < kernels::kTensorComponents; ++c) b.c[c] = WindowField(Field3("b", kN, kN, kN));
  const double h[3] = {1.0, 1.0, 1.0};
  kernels::solid_from_map(psi, b, deferred.q, deferred.level, deferred.shape, deferred.centres, 1.5, kMaxDerivedLevel, h,
                          kInterior);
  kernels::finish_deferred_fits(deferred.q, deferred.level, deferred.weight, psi, kLastSweep, kInterior);

  const HostCells lf = on_host(full.level), ld = on_host(deferred.level), p = on_host(psi);
  HostCells qf[3], qd[3];
  for (int a = 0; a < 3; ++a) {
    qf[a] = on_host(full.q.c[a]);
    qd[a] = on_host(deferred.q.c[a]);
  }
  // the cells something reads: WENO5 stencils of advected cells, central differences of derived ones
  HostCells read("read", kN, kN, kN);
  for (int i = 3; i < kN - 3; ++i)
    for (int j = 3; j < kN - 3; ++j)
      for (int k = 3; k < kN - 3; ++k) {
        const int reach = kernels::advected(lf(i, j, k), p(i, j, k)) ? 3
                          : kernels::derived_level(lf(i, j, k), kMaxDerivedLevel) ? 1
                                                                                   : 0;
        if (reach == 0) continue;
        for (int r = -reach; r <= reach; ++r) {
          read(i + r, j, k) = 1.0;
          read(i, j + r, k) = 1.0;
          read(i, j, k + r) = 1.0;
        }
      }
  int level_mismatch = 0, value_mismatch = 0, read_band = 0, unread_band = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kN; ++k) {
        level_mismatch += lf(i, j, k) != ld(i, j, k);
        if (lf(i, j, k) != kLastSweep + 1.0) continue;
        if (read(i, j, k) == 0.0) {
          ++unread_band;
          continue;
        }
        ++read_band;
        for (int a = 0; a < 3; ++a) value_mismatch += qf[a](i, j, k) != qd[a](i, j, k);
      }
  EXPECT_EQ(level_mismatch, 0);
  EXPECT_EQ(value_mismatch, 0) << "of " << read_band << " cells of the last sweep that are read";
  // about a third of the last shell is read by nothing: what the deferral saves
  EXPECT_GT(unread_band, read_band / 10);
}

// The host rows (each column of levels read once, level and q indexed with one offset) and the
// per-cell form that GPUs run visit the same cells with the same fit: q and the levels bit for bit.
TEST(MapExtrapolation, HostRowsEqualThePerCellForm) {
  const Map rows(true), cells(true);
  rows.extrapolate(false);
  for (int s = 1; s <= kLastSweep; ++s)
    Kokkos::parallel_for("per_cell_sweep", kInterior.policy(),
                         kernels::ExtrapolationSweep{cells.q, cells.level, cells.weight, double(s)});
  Kokkos::fence();
  const HostCells lr = on_host(rows.level), lc = on_host(cells.level);
  int band = 0, mismatch = 0;
  for (int a = 0; a < 3; ++a) {
    const HostCells qr = on_host(rows.q.c[a]), qc = on_host(cells.q.c[a]);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j)
        for (int k = 0; k < kN; ++k) {
          band += a == 0 && lr(i, j, k) > kernels::kLevelSolid;
          mismatch += !(qr(i, j, k) == qc(i, j, k)) + (a == 0 && lr(i, j, k) != lc(i, j, k));
        }
  }
  EXPECT_GT(band, 2000);
  EXPECT_EQ(mismatch, 0);
}

// The host rows index level and q with one offset: fields on different windows are refused.
TEST(MapExtrapolation, RefusesFieldsOnDifferentWindows) {
  const Map m(false);
  const WindowField wider(Field3("wider", kN, kN, kN + 2));
  EXPECT_THROW(kernels::extrapolation_sweep(m.q, wider, m.weight, 1, kInterior), std::logic_error);
  EXPECT_THROW(kernels::extrapolation_sweep(m.q, m.level, wider, 1, kInterior), std::logic_error);
  const int origin[3] = {1, 0, 0};
  const WindowField shifted(Field3("shifted", kN, kN, kN), origin);
  EXPECT_THROW(kernels::finish_deferred_fits(m.q, shifted, shifted, shifted, kLastSweep, kInterior), std::logic_error);
}

// The wall ghosts of q (y walls of a window of 4 x (6 + 2 kGhost) x 4 cells, h = 1): a column whose
// first interior cell is solid holds its material on the wall (q = 0 there: a bonded layer), the
// others continue q linearly. q is affine in y with a non-zero wall value, so the two rules differ
// everywhere; with the wall value 0 they agree (the bonded ghost is exact for such a q too).
TEST(MapExtrapolation, WallGhostsHoldABondedSolidAndContinueTheRest) {
  constexpr int kNy = 6, kCells = kNy + 2 * kGhost;
  for (const double wall_value : {0.3, 0.0}) {
    kernels::Vector3 q;
    const WindowField level(Field3("level", 4, kCells, 4));
    auto hl = Kokkos::create_mirror_view(level.data);
    std::vector<decltype(Kokkos::create_mirror_view(level.data))> hq;
    // q_a(y) = wall_value + s_a y, y the distance from the low wall; the high wall at y = kNy
    const double slope[3] = {0.05, -0.02, 0.01};
    auto exact = [&](int a, int j) { return wall_value + slope[a] * (j - kGhost + 0.5); };
    for (int a = 0; a < 3; ++a) {
      q.c[a] = WindowField(Field3("q", 4, kCells, 4));
      hq.push_back(Kokkos::create_mirror_view(q.c[a].data));
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < kCells; ++j)
          for (int k = 0; k < 4; ++k) hq[a](i, j, k) = kGhost <= j && j < kGhost + kNy ? exact(a, j) : -99.0;
      Kokkos::deep_copy(q.c[a].data, hq[a]);
    }
    // columns i < 2 solid next to the low wall, columns k < 2 solid next to the high wall
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < kCells; ++j)
        for (int k = 0; k < 4; ++k)
          hl(i, j, k) = (j == kGhost && i < 2) || (j == kGhost + kNy - 1 && k < 2) ? kernels::kLevelSolid : 0.0;
    Kokkos::deep_copy(level.data, hl);
    kernels::extrapolate_wall_ghosts(q, level, 1, kNy, Box{{0, 0, 0}, {4, kCells, 4}});
    for (int a = 0; a < 3; ++a) {
      Kokkos::deep_copy(hq[a], q.c[a].data);
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k)
          for (int m = 1; m <= kGhost; ++m) {
            const int low = kGhost - m, high = kGhost + kNy - 1 + m;
            // bonded: q(-m) = -q(m - 1) about the wall; else the affine q continued
            const double want_low = i < 2 ? -exact(a, kGhost + m - 1) : exact(a, low);
            const double want_high = k < 2 ? -exact(a, kGhost + kNy - m) : exact(a, high);
            EXPECT_NEAR(hq[a](i, low, k), want_low, 1e-14) << "low wall, column " << i << ", ghost " << m;
            EXPECT_NEAR(hq[a](i, high, k), want_high, 1e-14) << "high wall, column " << k << ", ghost " << m;
            if (wall_value == 0.0 && a == 0 && i < 2)  // a q that vanishes on the wall: both rules
              EXPECT_NEAR(hq[a](i, low, k), exact(a, low), 1e-14);
          }
    }
  }
}

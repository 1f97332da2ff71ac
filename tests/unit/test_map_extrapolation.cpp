// The reference map's extrapolation beyond the body (kernels/reference_map.hpp): the least-squares
// sweeps reproduce a rigid motion exactly, and the last sweep's deferred cells (DeferredFits)
// hold, wherever anything reads them, the values of a full sweep, bit for bit; the host rows equal
// the per-cell form (GPUs).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "kernels/reference_map.hpp"

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

struct Map {
  kernels::Vector3 q;
  WindowField level;
  kernels::ReferenceShape shape;
  kernels::CellCentres centres{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};

  explicit Map(bool deformed) {
    level = WindowField(Field3("level", kN, kN, kN));
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
    kernels::classify_solid(level, q, shape, centres, 3.0, 0.0, true, h, kInterior);
  }
  // sweeps 1 .. kLastSweep, the last one deferring its off-axis cells if `defer`
  void extrapolate(bool defer) const {
    for (int s = 1; s <= kLastSweep; ++s) kernels::extrapolation_sweep(q, level, s, kInterior, defer && s == kLastSweep);
  }
};

using HostCells = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>;
HostCells on_host(const WindowField& f) { return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data); }

}  // namespace

// Rycroft et al. (2020) sec. 2.4: a linear fit through the known cells is exact for a linear q,
// so every band cell carries the rigid motion to round-off.
TEST(MapExtrapolation, ExactForARigidMotion) {
  const Map m(false);
  m.extrapolate(false);
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
  // |q| <= 10 on the window: a few ulps of the normal equations' sums
  EXPECT_LT(worst, 1e-12);
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
  kernels::finish_deferred_fits(deferred.q, deferred.level, psi, kLastSweep, kInterior);

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
    Kokkos::parallel_for("per_cell_sweep", kInterior.policy(), kernels::ExtrapolationSweep{cells.q, cells.level, double(s)});
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
  EXPECT_THROW(kernels::extrapolation_sweep(m.q, wider, 1, kInterior), std::logic_error);
  const int origin[3] = {1, 0, 0};
  const WindowField shifted(Field3("shifted", kN, kN, kN), origin);
  EXPECT_THROW(kernels::finish_deferred_fits(m.q, shifted, shifted, kLastSweep, kInterior), std::logic_error);
}

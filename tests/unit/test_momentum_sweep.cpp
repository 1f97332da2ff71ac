// The host sweep of momentum_rhs (kernels/momentum_sweep.hpp: each flux computed once, kept
// across planes, rows and k) against the per-cell form the GPUs run (MomentumRhsAll::operator()),
// on random fields, with the constant and with a variable viscosity, over the whole box and over
// sub-boxes (slabs of one plane, a box next to the ghosts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "kernels/momentum.hpp"
#include "support/field_compare.hpp"
#include "support/random_fields.hpp"

using namespace eulerfsi;

namespace {

constexpr int kExt[3] = {11, 10, 13};  // storage extents, ghosts included

Field3 random_field(const std::string& name, std::mt19937& gen, double lo, double hi) {
  return test::random_field(name, gen, kExt, lo, hi);
}

// The per-cell form on the host, cell by cell (what for_each_row hands a GPU).
template <bool Uniform>
void per_cell(const kernels::Velocity& rhs, const kernels::Velocity& u, const Field3& mu, double mu0,
              const double h[3], const Box& b) {
  const double ih[3] = {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]};
  const kernels::MomentumRhsAll<Uniform> f{{rhs.c[0], u.c[0], u.c[1], u.c[2], mu, mu0, {ih[0], ih[1], ih[2]}},
                                           {rhs.c[1], u.c[0], u.c[1], u.c[2], mu, mu0, {ih[0], ih[1], ih[2]}},
                                           {rhs.c[2], u.c[0], u.c[1], u.c[2], mu, mu0, {ih[0], ih[1], ih[2]}}};
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) f(i, j, k);
}

// Whether every value of `a` outside the box kept the sentinel -7.
bool untouched_outside(const kernels::Velocity& a, const Box& box) {
  for (int c = 0; c < 3; ++c) {
    auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a.c[c]);
    for (int i = 0; i < kExt[0]; ++i)
      for (int j = 0; j < kExt[1]; ++j)
        for (int k = 0; k < kExt[2]; ++k) {
          const bool in = i >= box.lo[0] && i < box.hi[0] && j >= box.lo[1] && j < box.hi[1] && k >= box.lo[2] &&
                          k < box.hi[2];
          if (!in && ha(i, j, k) != -7.0) return false;
        }
  }
  return true;
}

}  // namespace

// The same expressions in the same order: equal to the last bit where the compiler contracts
// alike, and to a few units in the last place where it forms FMAs differently in the two loops.
TEST(MomentumSweep, EqualsThePerCellForm) {
  // on a device the per-cell form is what momentum_rhs runs, and its memory is not the host's
  if (!kHostKernels) GTEST_SKIP() << "the sweep is the host path";
  std::mt19937 gen(11);
  const double h[3] = {0.1, 0.125, 0.08};
  const kernels::Velocity u{{random_field("u", gen, -1, 1), random_field("v", gen, -1, 1),
                             random_field("w", gen, -1, 1)}};
  const Field3 mu = random_field("mu", gen, 0.01, 0.1);
  const Box boxes[3] = {{{kGhost, kGhost, kGhost}, {kExt[0] - kGhost, kExt[1] - kGhost, kExt[2] - kGhost}},
                        {{4, 3, 5}, {5, 6, 9}},   // one plane: a slab of one
                        {{1, 1, 1}, {9, 8, 12}}};  // from the first ghost layer on
  for (const Box& box : boxes)
    for (int uniform = 0; uniform <= 1; ++uniform) {
      kernels::Velocity sweep{{Field3("a", kExt[0], kExt[1], kExt[2]), Field3("b", kExt[0], kExt[1], kExt[2]),
                               Field3("c", kExt[0], kExt[1], kExt[2])}};
      kernels::Velocity cell{{Field3("d", kExt[0], kExt[1], kExt[2]), Field3("e", kExt[0], kExt[1], kExt[2]),
                              Field3("f", kExt[0], kExt[1], kExt[2])}};
      for (int c = 0; c < 3; ++c) Kokkos::deep_copy(sweep.c[c], -7.0);
      if (uniform) {
        kernels::momentum_rhs(sweep, u, 0.05, h, box);
        per_cell<true>(cell, u, Field3(), 0.05, h, box);
      } else {
        kernels::momentum_rhs(sweep, u, mu, h, box);
        per_cell<false>(cell, u, mu, 0.0, h, box);
      }
      double rel = 0.0;
      for (int c = 0; c < 3; ++c) {
        const test::FieldDifference d = test::max_difference(sweep.c[c], cell.c[c], box);
        rel = std::max(rel, d.diff / d.scale);
      }
      EXPECT_LE(rel, 1e-14) << "box from (" << box.lo[0] << "," << box.lo[1] << "," << box.lo[2] << "), uniform "
                            << uniform;
      EXPECT_TRUE(untouched_outside(sweep, box)) << "the sweep wrote outside its box";
    }
}

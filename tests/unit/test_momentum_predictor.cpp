// The fused momentum predictor (kernels/momentum_predictor.hpp: rhs^k and u* in one pass, u*
// over rhs^(k-1)) against momentum_rhs followed by the RK3 update written out on the host, on random
// fields: with and without the wall mask, with a moving wall, with the constant and a variable
// viscosity, with a force in rhs, over the whole box and over a sub-box; the elastic force added
// after the predictor against the same force inside it. Also the box difference
// the solver splits the constant-viscosity pass with.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "kernels/elastic_force.hpp"
#include "kernels/momentum_predictor.hpp"
#include "kernels/time_update.hpp"
#include "support/device_test.hpp"
#include "support/field_compare.hpp"
#include "support/random_fields.hpp"

using namespace eulerfsi;

namespace {

constexpr int kExt[3] = {12, 11, 13};  // storage extents, ghosts included

Field3 random_field(const std::string& name, std::mt19937& gen, double lo, double hi) {
  return test::random_field(name, gen, kExt, lo, hi);
}

kernels::Velocity random_velocity(const char* name, std::mt19937& gen) {
  const std::string n(name);
  return {{random_field(n + "x", gen, -1, 1), random_field(n + "y", gen, -1, 1), random_field(n + "z", gen, -1, 1)}};
}

kernels::Velocity copy_of(const kernels::Velocity& v) {
  return {{test::copy_of(v.c[0]), test::copy_of(v.c[1]), test::copy_of(v.c[2])}};
}

// The RK3 update with implicit penalization, written out on the host as the reference (the solver
// has no separate update kernel any more):
//   u* = [u + dt (gamma rhs + zeta rhs_old) + pen u_wall] / (1 + pen),  pen = penal chi(j, k)
void reference_update(const Field3& u, const Field3& rhs, const Field3& rhs_old, const kernels::Mask2& chi,
                      double dt, double gamma, double zeta, double penal, double u_wall, const Box& box) {
  auto hu = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u);
  auto hr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), rhs);
  auto ho = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), rhs_old);
  auto hc = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), chi);
  const double a = dt * gamma, b = dt * zeta;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        const double pen = penal * hc(j, k);
        hu(i, j, k) = (hu(i, j, k) + a * hr(i, j, k) + b * ho(i, j, k) + pen * u_wall) / (1.0 + pen);
      }
  Kokkos::deep_copy(u, hu);
}

// A wall mask that is 1 on some rows and 0 elsewhere (x-independent, as the pipe's).
kernels::Mask2 random_mask(std::mt19937& gen) {
  kernels::Mask2 chi("chi", kExt[1], kExt[2]);
  auto h = Kokkos::create_mirror_view(chi);
  std::bernoulli_distribution wall(0.3);
  for (int j = 0; j < kExt[1]; ++j)
    for (int k = 0; k < kExt[2]; ++k) h(j, k) = wall(gen) ? 1.0 : 0.0;
  Kokkos::deep_copy(chi, h);
  return chi;
}

// Predictor terms writing u* into `star`, with the wall masks chi and penalization `penal`.
kernels::PredictorTerms masked_terms(const kernels::Velocity& star, const kernels::Mask2 chi[3], double penal) {
  kernels::PredictorTerms t;
  t.a = 0.004;
  t.b = -0.002;
  t.penal = penal;
  t.u_wall[0] = 0.7;
  for (int c = 0; c < 3; ++c) {
    t.rhs_old_to_star[c] = star.c[c].data();
    t.chi[c] = chi[c].data();
    t.chi_stride[c] = long(chi[c].stride(0));
  }
  return t;
}

double max_relative_difference(const kernels::Velocity& a, const kernels::Velocity& b, const Box& box) {
  double rel = 0.0;
  for (int c = 0; c < 3; ++c) {
    const test::FieldDifference d = test::max_difference(a.c[c], b.c[c], box);
    rel = std::max(rel, d.diff / d.scale);
  }
  return rel;
}

}  // namespace

// The same expressions in the same order as momentum_rhs + the update: equal to the last bit where
// the compiler contracts alike, to a few units in the last place where it forms FMAs differently.
DEVICE_TEST(MomentumPredictor, EqualsTheRightHandSideThenTheUpdate) {
  std::mt19937 gen(5);
  const double h[3] = {0.1, 0.125, 0.08}, dt = 0.01, gamma = 5.0 / 12.0, zeta = -17.0 / 60.0, penal = 40.0;
  const double mu0 = 0.05;
  const kernels::Velocity u = random_velocity("u", gen);
  const Field3 mu = random_field("mu", gen, 0.01, 0.1);
  const kernels::Velocity force = random_velocity("f", gen);
  const kernels::Mask2 chi[3] = {random_mask(gen), random_mask(gen), random_mask(gen)};
  const kernels::Mask2 no_wall("no_wall", 1, kExt[2]);  // zeros: the solver's row for a component without a wall
  const kernels::Mask2 no_wall_2d("no_wall_2d", kExt[1], kExt[2]);  // zeros, for the reference
  const Box boxes[2] = {{{kGhost, kGhost, kGhost}, {kExt[0] - kGhost, kExt[1] - kGhost, kExt[2] - kGhost}},
                        {{4, 3, 5}, {7, 6, 9}}};
  for (const Box& box : boxes)
    for (int variant = 0; variant < 4; ++variant) {
      const bool masked = variant & 1, variable = variant & 2;  // a variable mu always comes with a force
      const bool forced = variable || box.lo[0] == 4;
      const kernels::Velocity rhs_old = random_velocity("r", gen);
      // the reference: rhs = momentum (+ f), then the update of u in place
      kernels::Velocity rhs_ref = random_velocity("s", gen), u_ref = copy_of(u);
      if (variable) {
        kernels::momentum_rhs(rhs_ref, u, mu, h, box);
      } else {
        kernels::momentum_rhs(rhs_ref, u, mu0, h, box);
      }
      kernels::PredictorTerms terms;
      terms.a = dt * gamma;
      terms.b = dt * zeta;
      terms.penal = penal;
      terms.u_wall[0] = -0.3;
      const kernels::Velocity star = copy_of(rhs_old), rhs = copy_of(rhs_ref);
      for (int c = 0; c < 3; ++c) {
        if (forced) {
          for_each_cell("test::add_force", box, KOKKOS_LAMBDA(int i, int j, int k) {
            rhs_ref.c[c](i, j, k) += force.c[c](i, j, k);
          });
          Kokkos::deep_copy(rhs.c[c], force.c[c]);
        }
        Kokkos::fence();
        reference_update(u_ref.c[c], rhs_ref.c[c], rhs_old.c[c], masked ? chi[c] : no_wall_2d, dt, gamma, zeta, penal,
                         terms.u_wall[c], box);
        terms.rhs_old_to_star[c] = star.c[c].data();
        terms.chi[c] = masked ? chi[c].data() : no_wall.data();
        terms.chi_stride[c] = masked ? long(chi[c].stride(0)) : 0;
      }
      Kokkos::fence();
      if (variable) {
        kernels::momentum_predict(rhs, u, mu, h, terms, box);
      } else if (forced) {
        // the force inside the constant-viscosity sweep: the reference of the force added after it
        kernels::momentum_predict_impl<true, true>(rhs, u, Field3(), mu0, h, terms, box, "test::predict_forced");
      } else {
        kernels::momentum_predict(rhs, u, mu0, h, terms, box);
      }
      Kokkos::fence();
      const std::string what = "box from (" + std::to_string(box.lo[0]) + ", ...), variant " + std::to_string(variant);
      EXPECT_LE(max_relative_difference(rhs, rhs_ref, box), 1e-14) << "rhs, " << what;
      EXPECT_LE(max_relative_difference(star, u_ref, box), 1e-14) << "u*, " << what;
      // outside the box u* keeps rhs_old (nothing written there)
      Box outside_cell{{kExt[0] - 1, 0, 0}, {kExt[0], 1, 1}};
      EXPECT_EQ(max_relative_difference(star, rhs_old, outside_cell), 0.0) << what;
    }
}

// The per-cell form the GPUs run (MomentumPredictCell), called cell by cell on the host, against
// the host sweep: the same expressions, so the same numbers to a few units in the last place.
TEST(MomentumPredictor, PerCellFormEqualsTheSweep) {
  // on a device the per-cell form is what momentum_predict runs, and its memory is not the host's
  if (!kHostKernels) GTEST_SKIP() << "the sweep is the host path";
  std::mt19937 gen(8);
  const double h[3] = {0.1, 0.125, 0.08};
  const kernels::Velocity u = random_velocity("u", gen), force = random_velocity("f", gen);
  const Field3 mu = random_field("mu", gen, 0.01, 0.1);
  const kernels::Mask2 chi[3] = {random_mask(gen), random_mask(gen), random_mask(gen)};
  const Box box{{kGhost, kGhost, kGhost}, {kExt[0] - kGhost, kExt[1] - kGhost, kExt[2] - kGhost}};
  const kernels::Velocity rhs_old = random_velocity("r", gen);
  const kernels::Velocity star_sweep = copy_of(rhs_old), star_cell = copy_of(rhs_old);
  const kernels::Velocity rhs_sweep = copy_of(force), rhs_cell = copy_of(force);
  auto terms_for = [&](const kernels::Velocity& star) { return masked_terms(star, chi, 25.0); };
  kernels::momentum_predict(rhs_sweep, u, mu, h, terms_for(star_sweep), box);
  const long st[3] = {long(u.c[0].stride(0)), long(u.c[0].stride(1)), 1};
  const kernels::MomentumPredictCell<false, true> f{{rhs_cell.c[0].data(), rhs_cell.c[1].data(), rhs_cell.c[2].data()},
                                                    {u.c[0].data(), u.c[1].data(), u.c[2].data()},
                                                    mu.data(),
                                                    0.0,
                                                    {1.0 / h[0], 1.0 / h[1], 1.0 / h[2]},
                                                    {st[0], st[1], st[2]},
                                                    terms_for(star_cell)};
  Kokkos::fence();
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) f(i, j, k);
  EXPECT_LE(max_relative_difference(rhs_cell, rhs_sweep, box), 1e-14);
  EXPECT_LE(max_relative_difference(star_cell, star_sweep, box), 1e-14);
}

// The elastic force added to rhs^k and u* after a predictor without it (the solver's path with one
// viscosity) against the force written into rhs before the predictor (its path with a mixture
// viscosity): rhs^k = r + f in both (bit for bit: one addition either way); u* differs by the
// rounding of a (r + f) against a r + a f / (1 + pen), a few units in the last place. psi is zero
// on part of the box (faces skipped there), the wall mask covers some rows (pen = 40).
DEVICE_TEST(MomentumPredictor, ElasticForceAfterThePredictorEqualsTheForceInside) {
  std::mt19937 gen(11);
  const double h[3] = {0.1, 0.125, 0.08}, mu0 = 0.05, G = 3.0;
  const kernels::Velocity u = random_velocity("u", gen), rhs_old = random_velocity("r", gen);
  const kernels::Mask2 chi[3] = {random_mask(gen), random_mask(gen), random_mask(gen)};
  // psi in [-1, 1) clipped at 0: about half of the cells outside the body
  const Field3 psi = random_field("psi", gen, -1.0, 1.0);
  Kokkos::parallel_for("test::clip_psi", Kokkos::RangePolicy<>(0, psi.size()), KOKKOS_LAMBDA(size_t n) {
    psi.data()[n] = psi.data()[n] > 0.0 ? psi.data()[n] : 0.0;
  });
  kernels::Tensor6 b, bp;
  for (int s = 0; s < kernels::kTensorComponents; ++s) {
    const double centre = s < 3 ? 1.0 : 0.0;
    b.c[s] = random_field("b", gen, centre - 0.2, centre + 0.2);
    bp.c[s] = random_field("bp", gen, centre - 0.2, centre + 0.2);
  }
  const kernels::Scratch3 shear{{random_field("s", gen, 0, 1), random_field("s", gen, 0, 1), random_field("s", gen, 0, 1)}};
  const Box box{{kGhost, kGhost, kGhost}, {kExt[0] - kGhost, kExt[1] - kGhost, kExt[2] - kGhost}};
  auto terms_for = [&](const kernels::Velocity& star) { return masked_terms(star, chi, 40.0); };
  // inside: rhs = f on entry, the forced predictor adds the momentum terms
  const kernels::Velocity star_inside = copy_of(rhs_old), rhs_inside = copy_of(rhs_old);
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(rhs_inside.c[c], 0.0);
  kernels::add_elastic_force(rhs_inside, psi, b, bp, shear, G, h, box);
  kernels::momentum_predict_impl<true, true>(rhs_inside, u, Field3(), mu0, h, terms_for(star_inside), box,
                                             "test::predict_forced");
  // after: the plain predictor, then the force on rhs^k and u*
  const kernels::Velocity star_after = copy_of(rhs_old), rhs_after = copy_of(rhs_old);
  const kernels::PredictorTerms terms_after = terms_for(star_after);
  kernels::momentum_predict(rhs_after, u, mu0, h, terms_after, box);
  kernels::add_elastic_force_to_predictor(rhs_after, star_after, terms_after, psi, b, bp, shear, G, h, box);
  Kokkos::fence();
  EXPECT_EQ(max_relative_difference(rhs_after, rhs_inside, box), 0.0);
  EXPECT_LE(max_relative_difference(star_after, star_inside, box), 1e-14);
  // the force is not negligible: it moves u* by more than the tolerance
  const kernels::Velocity star_plain = copy_of(rhs_old), rhs_plain = copy_of(rhs_old);
  kernels::momentum_predict(rhs_plain, u, mu0, h, terms_for(star_plain), box);
  Kokkos::fence();
  EXPECT_GT(max_relative_difference(star_plain, star_inside, box), 1e-6);
}

// a \ b as disjoint boxes: every cell of a is in exactly one part or in b.
TEST(MomentumPredictor, BoxDifferenceCoversTheRestOnce) {
  const Box a{{3, 3, 3}, {20, 15, 18}};
  const Box cuts[4] = {{{5, 6, 7}, {9, 10, 12}}, {{0, 0, 0}, {4, 30, 30}}, {{30, 30, 30}, {31, 31, 31}}, a};
  for (const Box& b : cuts) {
    Box parts[6];
    const int n = difference(a, b, parts);
    ASSERT_LE(n, 6);
    for (int i = a.lo[0]; i < a.hi[0]; ++i)
      for (int j = a.lo[1]; j < a.hi[1]; ++j)
        for (int k = a.lo[2]; k < a.hi[2]; ++k) {
          auto in = [i, j, k](const Box& x) {
            return i >= x.lo[0] && i < x.hi[0] && j >= x.lo[1] && j < x.hi[1] && k >= x.lo[2] && k < x.hi[2];
          };
          int count = in(b) ? 1 : 0;
          for (int p = 0; p < n; ++p) count += in(parts[p]) ? 1 : 0;
          ASSERT_EQ(count, 1) << "cell (" << i << ", " << j << ", " << k << ")";
        }
    for (int p = 0; p < n; ++p) EXPECT_FALSE(parts[p].empty());
  }
}

// The constant flow rate's correction folded into the projection (kernels/projection.hpp): the
// divergence's pass sums u* over the open faces, the pressure correction's pass adds du. What
// makes it exact to round-off: on a periodic x line sum_i (phi(i+1) - phi(i)) = 0, so the
// gradient step leaves the open-face sum unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "kernels/projection.hpp"
#include "support/device_test.hpp"
#include "support/field_compare.hpp"
#include "support/periodic_fill.hpp"
#include "support/random_fields.hpp"

using namespace eulerfsi;

namespace {

constexpr int kN[3] = {12, 7, 9};  // interior cells; the storage adds kGhost on each side
constexpr int kExt[3] = {kN[0] + 2 * kGhost, kN[1] + 2 * kGhost, kN[2] + 2 * kGhost};
const Box kBox{{kGhost, kGhost, kGhost}, {kGhost + kN[0], kGhost + kN[1], kGhost + kN[2]}};
const double kH[3] = {0.1, 0.2, 0.15};

Field3 random_field(const std::string& name, std::mt19937& gen) { return test::random_field(name, gen, kExt, -1.0, 1.0); }

// A y-z mask over the storage: 0 (open), 1 (closed) and fractions, as a pipe's wall layer has.
kernels::Mask2 random_mask(const std::string& name, std::mt19937& gen) {
  kernels::Mask2 m(name, kExt[1], kExt[2]);
  auto h = Kokkos::create_mirror_view(m);
  std::uniform_real_distribution<double> dist(0.0, 1.0);
  for (int j = 0; j < kExt[1]; ++j)
    for (int k = 0; k < kExt[2]; ++k) {
      const double r = dist(gen);
      h(j, k) = r < 0.3 ? 0.0 : (r > 0.7 ? 1.0 : r);
    }
  Kokkos::deep_copy(m, h);
  return m;
}

// sum over the box of |(1 - chi) u|: the scale of the sum's round-off
double abs_open_sum(const Field3& u, const kernels::Mask2& chi) {
  auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u);
  auto ch = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), chi);
  double s = 0.0;
  for (int i = kBox.lo[0]; i < kBox.hi[0]; ++i)
    for (int j = kBox.lo[1]; j < kBox.hi[1]; ++j)
      for (int k = kBox.lo[2]; k < kBox.hi[2]; ++k) s += std::fabs((1.0 - ch(j, k)) * uh(i, j, k));
  return s;
}

constexpr double kEps = 2.2e-16;
constexpr int kCells = kN[0] * kN[1] * kN[2];

}  // namespace

// The divergence is what it was without the sum, and the sum is open_face_sum's (another order:
// |difference| <= cells x eps x sum |terms|, the bound of any two summation orders).
TEST(FlowRateFold, DivergencePassSumsTheOpenFaces) {
  std::mt19937 gen(11);
  const Field3 u = random_field("u", gen), v = random_field("v", gen), w = random_field("w", gen);
  const kernels::Mask2 chi = random_mask("chi_u", gen);
  const Field3 plain("plain", kExt[0], kExt[1], kExt[2]), summed("summed", kExt[0], kExt[1], kExt[2]);
  EXPECT_EQ(kernels::divergence(plain, u, v, w, kH, 0.7, kBox), 0.0);  // inactive: nothing summed
  const double sum = kernels::divergence(summed, u, v, w, kH, 0.7, kBox, {chi, true});
  EXPECT_EQ(test::max_difference(summed, plain, kBox).diff, 0.0);
  const double expect = kernels::open_face_sum(u, chi, kBox);
  EXPECT_NEAR(sum, expect, kCells * kEps * abs_open_sum(u, chi));
  EXPECT_GT(std::fabs(expect), 1e-3);  // a sum that is not trivially 0
  // without a mask every face counts
  const double all = kernels::divergence(summed, u, v, w, kH, 0.7, kBox, {kernels::Mask2(), true});
  EXPECT_NEAR(all, kernels::open_face_sum(u, kernels::Mask2(), kBox), kCells * kEps * kCells);
}

// The shift in the correction's pass: the same u as the correction followed by add_open_x_velocity
// (the same operations in the same order), v and w as without it.
TEST(FlowRateFold, CorrectionAddsTheShiftAsTheSeparatePassDid) {
  std::mt19937 gen(12);
  Field3 u = random_field("u", gen), v = random_field("v", gen), w = random_field("w", gen);
  const Field3 phi = random_field("phi", gen);
  Field3 u_ref = test::copy_of(u), v_ref = test::copy_of(v), w_ref = test::copy_of(w);
  const kernels::Mask2 open_u = random_mask("open_u", gen);
  const double du = 0.37;
  kernels::subtract_gradient(u, v, w, phi, kH, 0.3, kBox, {}, {open_u, du});
  kernels::subtract_gradient(u_ref, v_ref, w_ref, phi, kH, 0.3, kBox);
  kernels::add_open_x_velocity(u_ref, open_u, du, kBox);
  EXPECT_EQ(test::max_difference(u, u_ref, kBox).diff, 0.0);
  EXPECT_EQ(test::max_difference(v, v_ref, kBox).diff, 0.0);
  EXPECT_EQ(test::max_difference(w, w_ref, kBox).diff, 0.0);
  // and without a mask du goes everywhere
  kernels::subtract_gradient(u, v, w, phi, kH, 0.0, kBox, {}, {kernels::Mask2(), du});
  kernels::add_open_x_velocity(u_ref, kernels::Mask2(), du, kBox);
  EXPECT_EQ(test::max_difference(u, u_ref, kBox).diff, 0.0);
}

// What the fold rests on: with phi periodic in x the correction moves the open-face sum by du times
// the open faces' weights only; u*'s flow rate is the corrected one's to round-off. With phi not
// periodic (ghost x plane off by 1) the sum moves by O(1): the test sees the difference.
DEVICE_TEST(FlowRateFold, GradientStepKeepsTheFlowRateOnAPeriodicLine) {
  std::mt19937 gen(13);
  Field3 u = random_field("u", gen), v = random_field("v", gen), w = random_field("w", gen);
  const Field3 phi = random_field("phi", gen);
  test_support::fill_periodic(phi, kN);
  const kernels::Mask2 chi = random_mask("chi_u", gen);
  kernels::Mask2 open_u("open_u", kExt[1], kExt[2]);
  Kokkos::deep_copy(open_u, 1.0);
  const double factor = 0.8, du = 0.05;
  const double before = kernels::open_face_sum(u, chi, kBox);
  kernels::subtract_gradient(u, v, w, phi, kH, factor, kBox, {}, {open_u, du});
  // the shift's share: du on each open face, weighted by 1 - chi (open_u = 1 here)
  double weights = 0.0;
  {
    auto ch = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), chi);
    for (int j = kBox.lo[1]; j < kBox.hi[1]; ++j)
      for (int k = kBox.lo[2]; k < kBox.hi[2]; ++k) weights += kN[0] * (1.0 - ch(j, k));
  }
  const double after = kernels::open_face_sum(u, chi, kBox);
  // the gradient terms are O(factor / h) = O(10): their sum's round-off scales with them
  const double scale = abs_open_sum(u, chi) + kCells * 2.0 * factor / kH[0];
  EXPECT_NEAR(after, before + du * weights, 4.0 * kCells * kEps * scale);

  // a phi whose x ghosts are not periodic: the telescoping sum no longer vanishes
  const int ghost_plane = kGhost + kN[0];  // a local: device code cannot read the namespace's array
  Kokkos::parallel_for("shift_ghost", Policy2({0, 0}, {kExt[1], kExt[2]}), KOKKOS_LAMBDA(int j, int k) {
    phi(ghost_plane, j, k) += 1.0;
  });
  const double before_bad = kernels::open_face_sum(u, chi, kBox);
  kernels::subtract_gradient(u, v, w, phi, kH, factor, kBox);
  const double after_bad = kernels::open_face_sum(u, chi, kBox);
  EXPECT_GT(std::fabs(after_bad - before_bad), 1.0);
}

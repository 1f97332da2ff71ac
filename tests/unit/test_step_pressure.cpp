// The step pressure gathered by the pressure correction (kernels/projection.hpp: p_step +=
// alpha_s phi_s in subtract_gradient's pass): after the three substeps' corrections it is
// sum_s alpha_s phi_s on the box, the first substep discards what p_step held, the cells outside
// the box are not written, and the velocity is corrected exactly as without it.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "kernels/projection.hpp"
#include "solver/rk3.hpp"
#include "support/field_compare.hpp"
#include "support/random_fields.hpp"

using namespace eulerfsi;

namespace {

constexpr int kExt[3] = {10, 9, 11};

Field3 random_field(const std::string& name, std::mt19937& gen) { return test::random_field(name, gen, kExt, -1.0, 1.0); }

}  // namespace

TEST(StepPressure, IsTheAlphaWeightedSumOfTheSubstepPressures) {
  std::mt19937 gen(3);
  const double h[3] = {0.1, 0.2, 0.15};
  const Box box{{kGhost, kGhost, kGhost}, {kExt[0] - kGhost, kExt[1] - kGhost, kExt[2] - kGhost}};
  Field3 u = random_field("u", gen), v = random_field("v", gen), w = random_field("w", gen);
  Field3 u_ref = test::copy_of(u), v_ref = test::copy_of(v), w_ref = test::copy_of(w);
  const Field3 p_step = random_field("p_step", gen), stale = test::copy_of(p_step);  // stale: what it held before
  Field3 phi[Rk3::stages];
  for (auto& p : phi) p = random_field("phi", gen);
  for (int s = 0; s < Rk3::stages; ++s) {
    kernels::subtract_gradient(u, v, w, phi[s], h, 0.3 * Rk3::alpha(s), box, {p_step, Rk3::alpha(s), s == 0});
    kernels::subtract_gradient(u_ref, v_ref, w_ref, phi[s], h, 0.3 * Rk3::alpha(s), box);
  }
  // the velocity: the same operations in the same order
  EXPECT_EQ(test::max_difference(u, u_ref, box).diff, 0.0);
  EXPECT_EQ(test::max_difference(v, v_ref, box).diff, 0.0);
  EXPECT_EQ(test::max_difference(w, w_ref, box).diff, 0.0);
  auto ps = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p_step);
  auto old = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), stale);
  Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace> ph[Rk3::stages];
  for (int s = 0; s < Rk3::stages; ++s) ph[s] = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), phi[s]);
  for (int i = 0; i < kExt[0]; ++i)
    for (int j = 0; j < kExt[1]; ++j)
      for (int k = 0; k < kExt[2]; ++k) {
        const bool in = i >= box.lo[0] && i < box.hi[0] && j >= box.lo[1] && j < box.hi[1] && k >= box.lo[2] &&
                        k < box.hi[2];
        // summed in the substeps' order from 0: exact
        double expect = 0.0;
        for (int s = 0; s < Rk3::stages; ++s) expect = expect + Rk3::alpha(s) * ph[s](i, j, k);
        ASSERT_EQ(ps(i, j, k), in ? expect : old(i, j, k)) << "cell (" << i << ", " << j << ", " << k << ")";
      }
}

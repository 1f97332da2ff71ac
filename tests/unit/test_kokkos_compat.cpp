// The Kokkos install and src/core/compat.hpp behave the same on every supported version.
#include <gtest/gtest.h>

#include "core/compat.hpp"
#include "core/types.hpp"

namespace {

// A View member is default-constructed first and assigned later (every solver class does this).
// With the vendored Kokkos 4.6 snapshot built by GCC 12 and without ci/patch-kokkos, the default
// View claims a null allocation record and this assignment segfaults in
// SharedAllocationRecord::decrement (it did: 8 of the 14 single-rank test programs crashed).
TEST(KokkosCompat, DefaultConstructedViewTakesAnAllocation) {
  Kokkos::View<double*, Kokkos::HostSpace> line;
  EXPECT_EQ(line.use_count(), 0);
  line = Kokkos::View<double*, Kokkos::HostSpace>(std::string("eulerfsi::test::line"), 4);
  EXPECT_EQ(line.use_count(), 1);
  eulerfsi::Field3 field;
  field = eulerfsi::Field3(std::string("eulerfsi::test::field"), 2, 3, 4);
  EXPECT_EQ(field.extent(2), 4u);
  EXPECT_EQ(field.use_count(), 1);
}

TEST(KokkosCompat, MathShimsMatchTheStandardLibrary) {
  EXPECT_EQ(eulerfsi::compat::sqrt(2.25), 1.5);
  EXPECT_EQ(eulerfsi::compat::fabs(-3.0), 3.0);
  EXPECT_EQ(eulerfsi::compat::floor(-0.5), -1.0);
  EXPECT_EQ(eulerfsi::compat::fmin(1.0, 2.0), 1.0);
  EXPECT_EQ(eulerfsi::compat::imax(1, 2), 2);
  EXPECT_TRUE(eulerfsi::compat::isfinite(1.0));
}

}  // namespace

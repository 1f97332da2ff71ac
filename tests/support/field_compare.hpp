#pragma once
// Comparing two fields over a box on the host: the largest difference and the scale it is judged by.
#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace eulerfsi::test {

struct FieldDifference {
  double diff = 0.0;   // max |a - b| over the box
  double scale = 0.0;  // max |b| over the box (b: the reference)
};

inline FieldDifference max_difference(const Field3& a, const Field3& b, const Box& box) {
  auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a);
  auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
  FieldDifference d;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        d.diff = std::max(d.diff, std::fabs(ha(i, j, k) - hb(i, j, k)));
        d.scale = std::max(d.scale, std::fabs(hb(i, j, k)));
      }
  return d;
}

}  // namespace eulerfsi::test

#pragma once
// Fields of uniform random values for kernel tests (the same seed gives the same fields).
#include <random>
#include <string>

#include "core/types.hpp"

namespace eulerfsi::test {

// A field of storage extents ext, ghosts included, uniform in [lo, hi).
inline Field3 random_field(const std::string& name, std::mt19937& gen, const int ext[3], double lo, double hi) {
  Field3 f(name, ext[0], ext[1], ext[2]);
  auto h = Kokkos::create_mirror_view(f);
  std::uniform_real_distribution<double> dist(lo, hi);
  for (int i = 0; i < ext[0]; ++i)
    for (int j = 0; j < ext[1]; ++j)
      for (int k = 0; k < ext[2]; ++k) h(i, j, k) = dist(gen);
  Kokkos::deep_copy(f, h);
  return f;
}

// A copy of f in a new allocation.
inline Field3 copy_of(const Field3& f) {
  Field3 c("copy", f.extent(0), f.extent(1), f.extent(2));
  Kokkos::deep_copy(c, f);
  return c;
}

}  // namespace eulerfsi::test

#pragma once
// Compile-time unit offsets e_D for writing one stencil for all three directions.
#include <Kokkos_Core.hpp>

namespace eulerfsi::kernels {

template <int D>
struct Unit {
  static constexpr int i = D == 0 ? 1 : 0;
  static constexpr int j = D == 1 ? 1 : 0;
  static constexpr int k = D == 2 ? 1 : 0;
};

// f(i + a e_A + b e_B) with A, B known at compile time.
template <int A, class V>
KOKKOS_FORCEINLINE_FUNCTION double shifted(const V& f, int i, int j, int k, int a) {
  return f(i + a * Unit<A>::i, j + a * Unit<A>::j, k + a * Unit<A>::k);
}
template <int A, int B, class V>
KOKKOS_FORCEINLINE_FUNCTION double shifted(const V& f, int i, int j, int k, int a, int b) {
  return f(i + a * Unit<A>::i + b * Unit<B>::i, j + a * Unit<A>::j + b * Unit<B>::j,
           k + a * Unit<A>::k + b * Unit<B>::k);
}

}  // namespace eulerfsi::kernels

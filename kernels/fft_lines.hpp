#pragma once
// Kernels around batched 1-D FFTs for the FFT_DCT Poisson solver: moving the lines of a 3-D
// LayoutRight array along one axis into contiguous (line, element) buffers and back, and the
// pre/post-processing that turns a real FFT into a DCT-II and a DCT-III (Makhoul 1980, IEEE TASSP
// 28, "A fast cosine transform in one and multiple dimensions").
//
// DCT-II of a real line x(0..N-1), normalised as FFTW's REDFT10:
//   X(m) = 2 sum_p x(p) cos(pi (2p + 1) m / (2N)).
// Makhoul: reorder v(l) = x(2l) (even p, first half), v(N-1-l) = x(2l+1) (odd p, second half);
// V = FFT(v) (one real-to-complex FFT); X(m) = 2 Re(exp(-i pi m / 2N) V(m)), V(m) = conj V(N-m).
// Its exact inverse (a DCT-III up to the factor): V(m) = exp(+i pi m / 2N) (X(m) - i X(N-m)) / 2
// with X(N) = 0, for m = 0..N/2; v = backward FFT(V) = N x reordered (the 1/N is the caller's).
#include <cmath>
#include <string>

#include "core/compat.hpp"
#include "core/types.hpp"

namespace eulerfsi::fft_lines {

using Complex = Kokkos::complex<double>;
using RealBuffer = Kokkos::View<double*, MemSpace>;
using ComplexBuffer = Kokkos::View<Complex*, MemSpace>;
using Real3 = Kokkos::View<double***, Kokkos::LayoutRight, MemSpace>;
using Complex3 = Kokkos::View<Complex***, Kokkos::LayoutRight, MemSpace>;

// Line `b` and position `p` of element (i, j, k) for lines along `axis` of an (n0, n1, n2) array;
// lines are numbered row-major over the two other indices.
struct Lines {
  int axis;
  int n[3];
  KOKKOS_INLINE_FUNCTION long line(int i, int j, int k) const {
    return axis == 0 ? long(j) * n[2] + k : axis == 1 ? long(i) * n[2] + k : long(i) * n[1] + j;
  }
  KOKKOS_INLINE_FUNCTION int pos(int i, int j, int k) const { return axis == 0 ? i : axis == 1 ? j : k; }
  int length() const { return n[axis]; }
  int count() const { return n[0] * n[1] * n[2] / n[axis]; }
};

// Makhoul's reordering: where element p of a line of length N sits in v. The same map takes v
// back to x after the inverse.
KOKKOS_INLINE_FUNCTION int makhoul_index(int p, int N) { return (p % 2 == 0) ? p / 2 : N - (p + 1) / 2; }

inline Policy3 whole(const int n[3]) { return Policy3({0, 0, 0}, {n[0], n[1], n[2]}); }

// buf(line, p) = a(i, j, k): contiguous lines for the FFT engine (T = double or Complex).
template <class T>
void gather(const Kokkos::View<T***, Kokkos::LayoutRight, MemSpace>& a, const Kokkos::View<T*, MemSpace>& buf,
            int axis) {
  const Lines L{axis, {int(a.extent(0)), int(a.extent(1)), int(a.extent(2))}};
  const long len = L.length();
  Kokkos::parallel_for("eulerfsi::fft::gather_lines", whole(L.n), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    buf(L.line(i, j, k) * len + L.pos(i, j, k)) = a(i, j, k);
  });
}

// a(i, j, k) = buf(line, p): the lines back into the 3-D array.
template <class T>
void scatter(const Kokkos::View<T*, MemSpace>& buf, const Kokkos::View<T***, Kokkos::LayoutRight, MemSpace>& a,
             int axis) {
  const Lines L{axis, {int(a.extent(0)), int(a.extent(1)), int(a.extent(2))}};
  const long len = L.length();
  Kokkos::parallel_for("eulerfsi::fft::scatter_lines", whole(L.n), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    a(i, j, k) = buf(L.line(i, j, k) * len + L.pos(i, j, k));
  });
}

// Real-to-complex along x: spec(m, j, k) = line (j, k) of the engine's half-complex output,
// m = 0..Nx/2 (spec has Nx/2 + 1 planes).
inline void scatter_half(const ComplexBuffer& buf, const Complex3& spec) {
  const int n[3] = {int(spec.extent(0)), int(spec.extent(1)), int(spec.extent(2))};
  const long half = n[0], nz = n[2];
  Kokkos::parallel_for("eulerfsi::fft::scatter_half", whole(n), KOKKOS_LAMBDA(const int m, const int j, const int k) {
    spec(m, j, k) = buf((long(j) * nz + k) * half + m);
  });
}
inline void gather_half(const Complex3& spec, const ComplexBuffer& buf) {
  const int n[3] = {int(spec.extent(0)), int(spec.extent(1)), int(spec.extent(2))};
  const long half = n[0], nz = n[2];
  Kokkos::parallel_for("eulerfsi::fft::gather_half", whole(n), KOKKOS_LAMBDA(const int m, const int j, const int k) {
    buf((long(j) * nz + k) * half + m) = spec(m, j, k);
  });
}

// DCT-II step 1, reorder: buf(line, makhoul_index(p)) = x(i, j, k), p the position along `axis`.
inline void dct2_reorder(const Real3& x, const RealBuffer& buf, int axis) {
  const Lines L{axis, {int(x.extent(0)), int(x.extent(1)), int(x.extent(2))}};
  const int N = L.length();
  Kokkos::parallel_for("eulerfsi::fft::dct2_reorder", whole(L.n), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    buf(L.line(i, j, k) * N + makhoul_index(L.pos(i, j, k), N)) = x(i, j, k);
  });
}

// The twiddle factors of a line of length N: cos and sin of theta_m = pi m / 2N, m < N, tabulated
// once (one sin/cos per cell and pass cost more than the FFT itself on CPUs).
struct Twiddle {
  Kokkos::View<double*, MemSpace> cos, sin;
};
inline Twiddle make_twiddle(int N) {
  Twiddle t{Kokkos::View<double*, MemSpace>(std::string("eulerfsi::fft::twiddle_cos"), N),
            Kokkos::View<double*, MemSpace>(std::string("eulerfsi::fft::twiddle_sin"), N)};
  auto c = Kokkos::create_mirror_view(t.cos);
  auto s = Kokkos::create_mirror_view(t.sin);
  const double pi = 3.14159265358979323846;
  for (int m = 0; m < N; ++m) {
    c(m) = std::cos(pi * m / (2.0 * N));
    s(m) = std::sin(pi * m / (2.0 * N));
  }
  Kokkos::deep_copy(t.cos, c);
  Kokkos::deep_copy(t.sin, s);
  return t;
}

// DCT-II step 3, twiddle: X(m) = 2 Re(exp(-i theta) V(m)) = 2 (cos theta Re V + sin theta Im V),
// theta = pi m / 2N, V(m) from the half-complex output (conj V(N-m) above N/2); X overwrites x.
inline void dct2_twiddle(const ComplexBuffer& spec, const Real3& x, int axis, const Twiddle& tw) {
  const Lines L{axis, {int(x.extent(0)), int(x.extent(1)), int(x.extent(2))}};
  const int N = L.length();
  const long half = N / 2 + 1;
  const auto cs = tw.cos, sn = tw.sin;
  Kokkos::parallel_for("eulerfsi::fft::dct2_twiddle", whole(L.n), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    const int m = L.pos(i, j, k);
    const Complex V = m <= N / 2 ? spec(L.line(i, j, k) * half + m) : Kokkos::conj(spec(L.line(i, j, k) * half + N - m));
    x(i, j, k) = 2.0 * (cs(m) * V.real() + sn(m) * V.imag());
  });
}

// DCT-III step 1 (inverse of the DCT-II above), twiddle: for m = 0..N/2
//   V(m) = exp(i theta) (X(m) - i X(N-m)) / 2,  theta = pi m / 2N,  X(N) = 0,
// i.e. Re V = (X(m) cos theta + X(N-m) sin theta) / 2, Im V = (X(m) sin theta - X(N-m) cos theta) / 2.
inline void dct3_twiddle(const Real3& X, const ComplexBuffer& spec, int axis, const Twiddle& tw) {
  const Lines L{axis, {int(X.extent(0)), int(X.extent(1)), int(X.extent(2))}};
  const int N = L.length();
  const long half = N / 2 + 1;
  int range[3] = {L.n[0], L.n[1], L.n[2]};
  range[axis] = N / 2 + 1;
  const auto cs = tw.cos, sn = tw.sin;
  Kokkos::parallel_for("eulerfsi::fft::dct3_twiddle", whole(range), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    int s[3] = {i, j, k};
    const int m = s[axis];
    const double a = X(i, j, k);
    s[axis] = N - m;
    const double c = m == 0 ? 0.0 : X(s[0], s[1], s[2]);
    spec(L.line(i, j, k) * half + m) = Complex(0.5 * (a * cs(m) + c * sn(m)), 0.5 * (a * sn(m) - c * cs(m)));
  });
}

// DCT-III step 3, undo the reordering: x(i, j, k) = v(line, makhoul_index(p)) (still times N).
inline void dct3_unorder(const RealBuffer& buf, const Real3& x, int axis) {
  const Lines L{axis, {int(x.extent(0)), int(x.extent(1)), int(x.extent(2))}};
  const int N = L.length();
  Kokkos::parallel_for("eulerfsi::fft::dct3_unorder", whole(L.n), KOKKOS_LAMBDA(const int i, const int j, const int k) {
    x(i, j, k) = buf(L.line(i, j, k) * N + makhoul_index(L.pos(i, j, k), N));
  });
}

}  // namespace eulerfsi::fft_lines

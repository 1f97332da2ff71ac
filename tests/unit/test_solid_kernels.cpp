// Solid-phase kernels: psi and B transport, stretching, elastic force, body moments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/elastic_force.hpp"
#include "kernels/particle_moments.hpp"
#include "kernels/solid_transport.hpp"
#include "kernels/tensor_extension.hpp"
#include "solid/particle_diagnostics.hpp"
#include "support/periodic_fill.hpp"
#include "support/device_test.hpp"

using namespace eulerfsi;
using kernels::Tensor6;
using kernels::Velocity;

namespace {

constexpr double kGamma[3] = {8.0 / 15.0, 5.0 / 12.0, 3.0 / 4.0};
constexpr double kZeta[3] = {0.0, -17.0 / 60.0, -5.0 / 12.0};

struct Mesh {
  int n[3];
  double h[3];
  int e[3];
  Mesh(int nx, int ny, int nz, double lx, double ly, double lz)
      : n{nx, ny, nz}, h{lx / nx, ly / ny, lz / nz}, e{nx + 2 * kGhost, ny + 2 * kGhost, nz + 2 * kGhost} {}
  Field3 field(const char* name) const { return Field3(std::string(name), e[0], e[1], e[2]); }
  Velocity velocity() const { return Velocity{{field("u"), field("v"), field("w")}}; }
  kernels::Scratch3 scratch() const { return kernels::Scratch3{{field("s_xy"), field("s_xz"), field("s_yz")}}; }
  Tensor6 tensor(const char* name) const {
    Tensor6 t;
    for (int s = 0; s < kernels::kTensorComponents; ++s) t.c[s] = field(name);
    return t;
  }
  Box interior() const { return {{kGhost, kGhost, kGhost}, {kGhost + n[0], kGhost + n[1], kGhost + n[2]}}; }
  Box all() const { return {{0, 0, 0}, {e[0], e[1], e[2]}}; }
};

void set_identity(const Tensor6& b) {
  for (int s = 0; s < kernels::kTensorComponents; ++s) Kokkos::deep_copy(b.c[s].data, s < 3 ? 1.0 : 0.0);
}

// psi of a sphere by 4^3 sub-sampling; direction d periodic with period L[d] when L[d] > 0
// (minimum image, so the sphere may straddle a periodic boundary).
// Cell centre coordinate of storage index s: lo[d] + (s - kGhost + 1/2) h[d].
KOKKOS_INLINE_FUNCTION double wrap(double d, double L) {
  if (L > 0.0) {
    while (d > 0.5 * L) d -= L;
    while (d < -0.5 * L) d += L;
  }
  return d;
}
void fill_sphere(const Field3& psi, const Mesh& m, const double lo[3], const double c[3], double r, const double L[3]) {
  const double h0 = m.h[0], h1 = m.h[1], h2 = m.h[2], l0 = lo[0], l1 = lo[1], l2 = lo[2];
  const double c0 = c[0], c1 = c[1], c2 = c[2], L0 = L[0], L1 = L[1], L2 = L[2];
  Kokkos::parallel_for("test::sphere", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    int inside = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int q = 0; q < 4; ++q) {
          const double dx = wrap(l0 + (i - kGhost + (a + 0.5) / 4.0) * h0 - c0, L0);
          const double dy = wrap(l1 + (j - kGhost + (b + 0.5) / 4.0) * h1 - c1, L1);
          const double dz = wrap(l2 + (k - kGhost + (q + 0.5) / 4.0) * h2 - c2, L2);
          if (dx * dx + dy * dy + dz * dz < r * r) inside += 1;
        }
    psi(i, j, k) = inside / 64.0;
  });
}

double sum(const Field3& f, const Box& box) {
  double s = 0.0;
  Kokkos::parallel_reduce("test::sum", box.policy(), KOKKOS_LAMBDA(int i, int j, int k, double& a) { a += f(i, j, k); },
                          Kokkos::Sum<double>(s));
  return s;
}
double max_abs_minus(const Field3& a, double v, const Box& box) {
  double m = 0.0;
  Kokkos::parallel_reduce("test::maxabs", box.policy(), KOKKOS_LAMBDA(int i, int j, int k, double& x) {
    x = compat::fmax(x, compat::fabs(a(i, j, k) - v));
  }, Kokkos::Max<double>(m));
  return m;
}

struct PsiRun {
  double rel_volume_change, min_psi, max_psi, rel_l1_error;
};

// Sphere r = 0.2 advected by u = (1, 0.5, 0.25) in the periodic unit box for T = 1 (one period
// in x), RK3 with CFL 0.2; compared with the sampled sphere at the exact final centre.
PsiRun advect_sphere(int N, bool clip) {
  const Mesh m(N, N, N, 1.0, 1.0, 1.0);
  const double lo[3] = {0, 0, 0}, c[3] = {0.5, 0.5, 0.5};
  Field3 psi = m.field("psi"), psi0 = m.field("psi0"), rhs = m.field("rhs"), rhs_old = m.field("rhs_old");
  const double L[3] = {1.0, 1.0, 1.0};
  const double u[3] = {1.0, 0.5, 0.25};
  const double T = 1.0;
  const double c_end[3] = {c[0] + u[0] * T, c[1] + u[1] * T, c[2] + u[2] * T};
  fill_sphere(psi, m, lo, c, 0.2, L);
  fill_sphere(psi0, m, lo, c_end, 0.2, L);  // exact solution at T
  Velocity vel = m.velocity();
  for (int d = 0; d < 3; ++d) Kokkos::deep_copy(vel.c[d], u[d]);
  const int steps = static_cast<int>(std::lround(T / (0.2 * m.h[0] / u[0])));
  const double dt = T / steps;
  const Box box = m.interior();
  const double v0 = sum(psi, box);
  double pmin = 0.0, pmax = 1.0;
  for (int n = 0; n < steps; ++n)
    for (int s = 0; s < 3; ++s) {
      test_support::fill_periodic(psi, m.n);
      kernels::scalar_advection_rhs(rhs, psi, vel, m.h, box);
      kernels::rk3_scalar_update(psi, rhs, rhs_old, dt, kGamma[s], kZeta[s], box);
      if (clip) kernels::clip_volume_fraction(psi, box);
      std::swap(rhs, rhs_old);
    }
  Kokkos::parallel_reduce("test::min", box.policy(), KOKKOS_LAMBDA(int i, int j, int k, double& x) {
    x = compat::fmin(x, psi(i, j, k));
  }, Kokkos::Min<double>(pmin));
  Kokkos::parallel_reduce("test::max", box.policy(), KOKKOS_LAMBDA(int i, int j, int k, double& x) {
    x = compat::fmax(x, psi(i, j, k));
  }, Kokkos::Max<double>(pmax));
  double l1 = 0.0;
  Kokkos::parallel_reduce("test::l1", box.policy(), KOKKOS_LAMBDA(int i, int j, int k, double& x) {
    x += compat::fabs(psi(i, j, k) - psi0(i, j, k));
  }, Kokkos::Sum<double>(l1));
  return {(sum(psi, box) - v0) / v0, pmin, pmax, l1 / v0};
}

}  // namespace

// Flux form with periodic faces: every face flux enters two cells with opposite signs, so
// sum(psi) changes only by round-off: about steps * 3 * sqrt(cells) * 1e-16 relative ~ 1e-12 at
// most; we require 1e-12. The shape error of a discontinuity under a (2r-1)-order scheme falls
// like h^{r/(r+1)} in L1 (Harten's estimate; r = 3 for WENO5's candidate stencils: h^0.75,
// ratio 0.59 per halving; measured 0.60); we require fine/coarse < 0.7 and, as a regression
// guard, a relative L1 error < 0.4 at 32^3 (measured 0.35: coarse 0.575 x 0.59 plus 15%).
TEST(SolidTransport, SphereKeepsVolumeAndShape) {
  const PsiRun coarse = advect_sphere(16, false);
  const PsiRun fine = advect_sphere(32, false);
  const PsiRun clipped = advect_sphere(16, true);
  std::printf("16^3: dV/V %.2e  psi in [%.4f, %.4f]  L1 shape error %.4f\n", coarse.rel_volume_change, coarse.min_psi,
              coarse.max_psi, coarse.rel_l1_error);
  std::printf("32^3: dV/V %.2e  psi in [%.4f, %.4f]  L1 shape error %.4f\n", fine.rel_volume_change, fine.min_psi,
              fine.max_psi, fine.rel_l1_error);
  std::printf("16^3 clipped: dV/V %.2e  psi in [%.4f, %.4f]  L1 shape error %.4f\n", clipped.rel_volume_change,
              clipped.min_psi, clipped.max_psi, clipped.rel_l1_error);
  EXPECT_LT(std::fabs(coarse.rel_volume_change), 1e-12);
  EXPECT_LT(std::fabs(fine.rel_volume_change), 1e-12);
  EXPECT_LT(fine.rel_l1_error, 0.7 * coarse.rel_l1_error);
  EXPECT_LT(fine.rel_l1_error, 0.4);
  // WENO over/undershoots stay small without clipping (ENO property): a few percent at most
  EXPECT_GT(fine.min_psi, -0.05);
  EXPECT_LT(fine.max_psi, 1.05);
  EXPECT_GE(clipped.min_psi, 0.0);
  EXPECT_LE(clipped.max_psi, 1.0);
}

namespace {

// Taylor deformation of the body psi >= 0.05 (moments about c), as the particle diagnostics take it.
double taylor_D_of(const Field3& psi, const Mesh& m, const double c[3], const Box& box) {
  const double h = m.h[0];
  const kernels::CellCentres xc{{-0.5 - (kGhost - 0.5) * h, -0.5 - (kGhost - 0.5) * h, -0.5 - (kGhost - 0.5) * h},
                                {h, h, h}};
  const double period[3] = {0.0, 0.0, 0.0};
  const auto mom = kernels::body_second_moments(psi, xc, c, period, box, 0.05);
  Velocity none = m.velocity();
  const auto first = kernels::body_first_moments(psi, none, xc, 1.0, box, 0.05);
  const double V = first.s[kernels::BodyFirstMoments::Volume];
  const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
  double cov[3][3];
  for (int q = 0; q < 6; ++q)
    cov[ra[q]][rb[q]] = cov[rb[q]][ra[q]] = mom.m2[q] / V - (mom.m1[ra[q]] / V) * (mom.m1[rb[q]] / V);
  double ev[3], vec[3][3];
  symmetric_eigen3(cov, ev, vec);
  const double a = std::sqrt(ev[2]), b = std::sqrt(ev[0]);
  return (a - b) / (a + b);
}

// A sphere (d = 0.25) in rigid rotation u = omega (-y, x, 0) about the box's z axis, omega = 1/2:
// its exact psi does not change, so any Taylor deformation of the transported psi (moments over
// psi >= 0.05, as the particle diagnostics take them) is the scheme's error. Returns D after each
// of the (increasing) `angles` in radians.
std::vector<double> rotating_sphere_D(int N, const std::vector<double>& angles) {
  const Mesh m(N, N, N, 1.0, 1.0, 1.0);
  const double lo[3] = {-0.5, -0.5, -0.5}, c[3] = {0.0, 0.0, 0.0}, L[3] = {1.0, 1.0, 1.0}, omega = 0.5;
  Field3 psi = m.field("psi"), rhs = m.field("rhs"), rhs_old = m.field("rhs_old");
  fill_sphere(psi, m, lo, c, 0.125, L);
  Velocity vel = m.velocity();
  const Field3 u = vel.c[0], v = vel.c[1];
  const double h = m.h[0];
  // u at (x_{i+1/2}, y_j) depends on y only, v at (x_i, y_{j+1/2}) on x only: div u = 0 exactly
  Kokkos::parallel_for("test::rotation", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    u(i, j, k) = -omega * (-0.5 + (j - kGhost + 0.5) * h);
    v(i, j, k) = omega * (-0.5 + (i - kGhost + 0.5) * h);
  });
  const Box box = m.interior();
  const double v0 = sum(psi, box);
  const int steps_per_rad = static_cast<int>(std::lround(1.0 / omega / (0.2 * h / (omega * 0.5))));
  const double dt = 1.0 / omega / steps_per_rad;
  std::vector<double> out;
  long done = 0;
  for (double angle : angles) {
    for (const long target = std::lround(angle * steps_per_rad); done < target; ++done)
      for (int s = 0; s < 3; ++s) {
        test_support::fill_periodic(psi, m.n);
        kernels::scalar_advection_rhs(rhs, psi, vel, m.h, box);
        kernels::rk3_scalar_update(psi, rhs, rhs_old, dt, kGamma[s], kZeta[s], box);
        std::swap(rhs, rhs_old);
      }
    EXPECT_NEAR(sum(psi, box) / v0, 1.0, 1e-12);
    out.push_back(taylor_D_of(psi, m, c, box));
  }
  return out;
}


}  // namespace

// The error behind the drift of a tank-treading particle (docs/REFERENCE_MAP.md): the flux form diffuses
// psi only along the directions the velocity has, so a rotating sphere looks stretched in its
// plane of rotation. It must vanish under refinement: a discontinuity under WENO5 converges like
// h^(3/4) in L1 (Harten's estimate, see SphereKeepsVolumeAndShape), ratio 0.59 per halving; we
// require < 0.7 (measured 0.40: D 0.0206 at 8 cells per diameter, 0.0082 at 16, after one radian).
TEST(SolidTransport, RotatingSphereConvergesToASphere) {
  const double d8 = rotating_sphere_D(32, {1.0})[0], d16 = rotating_sphere_D(64, {1.0})[0];
  std::printf("rotating sphere, 1 rad: D %.4f (8 cells per d), %.4f (16), ratio %.2f\n", d8, d16, d16 / d8);
  EXPECT_GT(d8, 0.0);
  EXPECT_LT(d16 / d8, 0.7);
}

// Study, not run in CI (~15 min on one core; --gtest_also_run_disabled_tests): how large is this
// transport error at the paper's own resolution, 48 cells per diameter (its sec. 2.4), over the
// tens of radians a particle turns on its way across the pipe? D after 1 rad at 8, 12, 16, 24
// and 48 cells per diameter gives the order; D after 1, 2, 4, 8 and 16 rad at 16 cells per
// diameter gives the growth with angle. Asserts what the study relies on: the error falls with h
// and grows with the angle (docs/REPRODUCTION.md uses the printed numbers).
TEST(SolidTransport, DISABLED_RotatingSphereErrorAtThePapersResolution) {
  std::vector<double> by_n;
  for (int n : {32, 48, 64, 96, 192}) {
    by_n.push_back(rotating_sphere_D(n, {1.0})[0]);
    std::printf("rotation study: %3d cells per d, 1 rad: D %.3e\n", n / 4, by_n.back());
  }
  for (std::size_t a = 1; a < by_n.size(); ++a) EXPECT_LT(by_n[a], by_n[a - 1]);
  const std::vector<double> angles = {1.0, 2.0, 4.0, 8.0, 16.0};
  const std::vector<double> by_angle = rotating_sphere_D(64, angles);
  for (std::size_t a = 0; a < angles.size(); ++a)
    std::printf("rotation study: 16 cells per d, %4.1f rad: D %.3e\n", angles[a], by_angle[a]);
  for (std::size_t a = 1; a < by_angle.size(); ++a) EXPECT_GT(by_angle[a], by_angle[a - 1]);
}

// The elastic energy density of the field snapshots, psi G (tr B det(B)^(-1/3) - 3) / 2, on three
// uniform B: simple shear F = [[1, g, 0], [0, 1, 0], [0, 0, 1]] gives tr B = 3 + g^2, det B = 1, so
// G g^2 / 2 psi; B = I and a pure dilation B = 4 I (not isochoric) give 0. Round-off: 1e-14.
// The one-pass bounding box (kernels/bounding_box.hpp) against the cells it was given: three
// scattered non-zero cells, searched on the whole field and on a box that cuts one of them off;
// no non-zero cell gives false and leaves the output alone.
TEST(BoundingBox, KnownCellsExtents) {
  const Mesh m(12, 10, 8, 1.0, 1.0, 1.0);
  const Field3 f = m.field("known");
  Kokkos::deep_copy(f, 0.0);
  Box out{{-1, -1, -1}, {-1, -1, -1}};
  EXPECT_FALSE(kernels::known_bounding_box(f, m.all(), out));
  EXPECT_EQ(out.lo[0], -1);
  const int cells[3][3] = {{4, 9, 5}, {11, 3, 7}, {6, 6, 10}};
  auto host = Kokkos::create_mirror_view(f);
  Kokkos::deep_copy(host, f);
  for (const auto& c : cells) host(c[0], c[1], c[2]) = 2.0;
  Kokkos::deep_copy(f, host);
  ASSERT_TRUE(kernels::known_bounding_box(f, m.all(), out));
  const int lo[3] = {4, 3, 5}, hi[3] = {12, 10, 11};
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(out.lo[d], lo[d]) << "direction " << d;
    EXPECT_EQ(out.hi[d], hi[d]) << "direction " << d;
  }
  // a box without the cell at i = 11: the x extent ends at the cell at i = 6
  ASSERT_TRUE(kernels::known_bounding_box(f, Box{{0, 0, 0}, {11, m.e[1], m.e[2]}}, out));
  EXPECT_EQ(out.lo[0], 4);
  EXPECT_EQ(out.hi[0], 7);
  EXPECT_EQ(out.lo[1], 6);
  EXPECT_EQ(out.hi[2], 11);
}

TEST(SolidFields, ElasticEnergyDensity) {
  const Mesh m(4, 4, 4, 1.0, 1.0, 1.0);
  Field3 psi = m.field("psi"), out = m.field("energy");
  Kokkos::deep_copy(psi, 0.5);
  const double G = 3.0, g = 0.4;
  const double shear[6] = {1.0 + g * g, 1.0, 1.0, g, 0.0, 0.0}, ident[6] = {1, 1, 1, 0, 0, 0}, dil[6] = {4, 4, 4, 0, 0, 0};
  const double expect[3] = {0.5 * G * g * g * 0.5, 0.0, 0.0};
  const double* cases[3] = {shear, ident, dil};
  for (int c = 0; c < 3; ++c) {
    Tensor6 b = m.tensor("b");
    for (int q = 0; q < 6; ++q) Kokkos::deep_copy(b.c[q].data, cases[c][q]);
    Kokkos::deep_copy(out, 0.0);
    kernels::elastic_energy_add(out, psi, b, G, m.interior());
    EXPECT_LT(max_abs_minus(out, expect[c], m.interior()), 1e-14) << "case " << c;
  }
}

// B = I advected by a uniform velocity: the stretching is zero and WENO reproduces a constant,
// so B stays I up to round-off (each substep adds O(1e-16 / h) * dt); 20 steps: < 1e-12.
TEST(SolidTransport, IdentityStaysIdentityUnderTranslation) {
  const Mesh m(12, 12, 12, 1.0, 1.0, 1.0);
  Tensor6 b = m.tensor("b"), rhs = m.tensor("rhs"), rhs_old = m.tensor("rhs_old");
  set_identity(b);
  Velocity vel = m.velocity();
  const double u[3] = {1.0, 0.5, 0.25};
  for (int d = 0; d < 3; ++d) Kokkos::deep_copy(vel.c[d], u[d]);
  const double dt = 0.2 * m.h[0];
  for (int n = 0; n < 20; ++n)
    for (int s = 0; s < 3; ++s) {
      for (int c = 0; c < 6; ++c) test_support::fill_periodic(b.c[c].data, m.n);
      kernels::tensor_transport_rhs(rhs, b, vel, m.field("psi_solid"), -1.0, m.h, m.interior());  // psi_min < 0: every cell
      kernels::rk3_tensor_update(b, b, rhs, rhs_old, dt, kGamma[s], kZeta[s], m.interior());
      std::swap(rhs, rhs_old);
    }
  double err = 0.0;
  for (int c = 0; c < 6; ++c) err = std::fmax(err, max_abs_minus(b.c[c].data, c < 3 ? 1.0 : 0.0, m.interior()));
  std::printf("translation: max |B - I| after 20 steps %.2e\n", err);
  EXPECT_LT(err, 1e-12);
}

// Linear velocity u = A x with tr A = 0 and a constant B: the MAC central differences are exact
// for linear fields and div(u B) = B tr A = 0, so rhs = A B + B A^T to round-off (1e-12 for
// O(1) data). A antisymmetric (rigid rotation) with B = I gives rhs = 0. This checks every
// index of L and of the stretching term.
DEVICE_TEST(SolidTransport, StretchingIsExactForLinearVelocity) {
  const Mesh m(8, 8, 8, 1.0, 1.0, 1.0);
  const double lo[3] = {-0.5, -0.5, -0.5};
  const double rot[3][3] = {{0.0, -1.1, -0.7}, {1.1, 0.0, 0.3}, {0.7, -0.3, 0.0}};
  const double gen[3][3] = {{0.3, 0.5, -0.2}, {0.1, -0.4, 0.7}, {0.6, -0.3, 0.1}};
  const double bgen[6] = {1.3, 0.8, 1.1, 0.2, -0.1, 0.15};  // XX YY ZZ XY XZ YZ
  const double bid[6] = {1, 1, 1, 0, 0, 0};
  for (int cas = 0; cas < 2; ++cas) {
    const auto& A = cas == 0 ? rot : gen;
    const double* bval = cas == 0 ? bid : bgen;
    Velocity vel = m.velocity();
    for (int a = 0; a < 3; ++a) {  // u_a at its face: coordinate a shifted by h/2
      const Field3 ua = vel.c[a];
      const double A0 = A[a][0], A1 = A[a][1], A2 = A[a][2];
      const double h0 = m.h[0], h1 = m.h[1], h2 = m.h[2];
      const double s0 = a == 0 ? 1.0 : 0.5, s1 = a == 1 ? 1.0 : 0.5, s2 = a == 2 ? 1.0 : 0.5;
      const double l0 = lo[0], l1 = lo[1], l2 = lo[2];
      Kokkos::parallel_for("test::linear_u", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        ua(i, j, k) = A0 * (l0 + (i - kGhost + s0) * h0) + A1 * (l1 + (j - kGhost + s1) * h1) +
                      A2 * (l2 + (k - kGhost + s2) * h2);
      });
    }
    Tensor6 b = m.tensor("b"), rhs = m.tensor("rhs");
    for (int c = 0; c < 6; ++c) Kokkos::deep_copy(b.c[c].data, bval[c]);
    kernels::tensor_transport_rhs(rhs, b, vel, m.field("psi_solid"), -1.0, m.h, m.interior());  // psi_min < 0: every cell
    double B[3][3];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) B[a][c] = bval[kernels::tensor_index(a, c)];
    double err = 0.0;
    for (int s = 0; s < 6; ++s) {
      const int ra[6] = {0, 1, 2, 0, 0, 1}, rc[6] = {0, 1, 2, 1, 2, 2};
      double expect = 0.0;
      for (int q = 0; q < 3; ++q) expect += A[ra[s]][q] * B[q][rc[s]] + B[ra[s]][q] * A[rc[s]][q];
      err = std::fmax(err, max_abs_minus(rhs.c[s].data, expect, m.interior()));
    }
    std::printf("linear velocity case %d: max |rhs - (AB + BA^T)| %.2e\n", cas, err);
    EXPECT_LT(err, 1e-12);
  }
}

// Simple shear u = g y, B(0) = I: B = F F^T, F = [[1, g t, 0], [0, 1, 0], [0, 0, 1]], i.e.
// B_xx = 1 + (g t)^2, B_xy = g t, det B = 1. B stays uniform, so only the stretching acts: a
// linear ODE y' = M y with M^3 = 0 (B_yy -> B_xy -> B_xx). Any 3-stage third-order RK has the
// amplification polynomial 1 + z + z^2/2 + z^3/6, which equals exp(M dt) when M^3 = 0: the
// scheme is exact and the error is round-off (1e-12 after 100 steps to g t = 1).
DEVICE_TEST(SolidTransport, SimpleShearMatchesExactDeformation) {
  const Mesh m(6, 6, 6, 1.0, 1.0, 1.0);
  const double g = 1.0, dt = 0.01;
  const int steps = 100;
  Velocity vel = m.velocity();
  const Field3 u = vel.c[0];
  const double h1 = m.h[1];
  Kokkos::parallel_for("test::shear", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    u(i, j, k) = g * (-0.5 + (j - kGhost + 0.5) * h1);  // y of the x-face = y of the cell centre
  });
  Tensor6 b = m.tensor("b"), rhs = m.tensor("rhs"), rhs_old = m.tensor("rhs_old");
  set_identity(b);
  for (int n = 0; n < steps; ++n)
    for (int s = 0; s < 3; ++s) {
      // B is uniform, so a periodic copy is also exact in the sheared y direction
      for (int c = 0; c < 6; ++c) test_support::fill_periodic(b.c[c].data, m.n);
      kernels::tensor_transport_rhs(rhs, b, vel, m.field("psi_solid"), -1.0, m.h, m.interior());  // psi_min < 0: every cell
      kernels::rk3_tensor_update(b, b, rhs, rhs_old, dt, kGamma[s], kZeta[s], m.interior());
      std::swap(rhs, rhs_old);
    }
  const double gt = g * dt * steps;
  const double exact[6] = {1.0 + gt * gt, 1.0, 1.0, gt, 0.0, 0.0};
  double err = 0.0;
  for (int c = 0; c < 6; ++c) err = std::fmax(err, max_abs_minus(b.c[c].data, exact[c], m.interior()));
  auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.c[0].data);
  auto hy = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.c[1].data);
  auto hxy = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.c[3].data);
  const int c0 = kGhost + 2;
  const double det = hb(c0, c0, c0) * hy(c0, c0, c0) - hxy(c0, c0, c0) * hxy(c0, c0, c0);  // zz = 1, xz = yz = 0
  std::printf("shear: max |B - F F^T| at g t = 1: %.2e, det B - 1 = %.2e\n", err, det - 1.0);
  EXPECT_LT(err, 1e-12);
  EXPECT_LT(std::fabs(det - 1.0), 1e-12);
}

// psi is clipped into [0, 1].
DEVICE_TEST(SolidTransport, ClipVolumeFraction) {
  const Mesh m(4, 4, 4, 1.0, 1.0, 1.0);
  Field3 psi = m.field("psi");
  Kokkos::deep_copy(psi, 1.2);
  Kokkos::parallel_for("test::psi2", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    if (i < 5) psi(i, j, k) = -0.01;
  });
  kernels::clip_volume_fraction(psi, m.all());
  auto hp = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi);
  EXPECT_EQ(hp(0, 0, 0), 0.0);
  EXPECT_EQ(hp(6, 0, 0), 1.0);
}

// B outside the solid (kernels/tensor_extension.hpp): a sphere of psi holding a linear SPD B,
// garbage outside (the fluid's strain, 1e3 I + shear) and one interior cell that lost positive
// definiteness. After the extension: the solid's own B is untouched bit for bit; the bad interior
// cell holds the mean of its six neighbours, which for a linear field is the field's value to
// round-off; every cell of the band holds a convex combination of the solid's values (inside
// their range, positive definite); nothing farther than `band` face steps from the solid keeps
// anything but I.
TEST(SolidTransport, TensorExtensionFromTheSolid) {
  const int n = 16, band = 3;
  const Mesh m(n, n, n, 1.0, 1.0, 1.0);
  const double lo[3] = {0.0, 0.0, 0.0}, L[3] = {1.0, 1.0, 1.0}, c[3] = {0.5, 0.5, 0.5};
  Field3 psi = m.field("psi"), known = m.field("known");
  fill_sphere(psi, m, lo, c, 0.3, L);
  Tensor6 b = m.tensor("b");
  const double h = m.h[0];
  const int bad = kGhost + n / 2;  // the sphere's centre cell
  // B = I + linear terms: SPD for |x|, |y|, |z| <= 1 (diagonally dominant)
  auto linear = [](int s, double x, double y, double z) {
    const double v[6] = {1.0 + 0.2 * x, 1.1 - 0.1 * y, 1.0 + 0.15 * z, 0.05 * z, -0.04 * x, 0.03 * y};
    return v[s];
  };
  std::vector<Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>> hb;
  for (int s = 0; s < 6; ++s) hb.push_back(Kokkos::create_mirror_view(b.c[s].data));
  auto hpsi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi);
  for (int i = 0; i < m.e[0]; ++i)
    for (int j = 0; j < m.e[1]; ++j)
      for (int k = 0; k < m.e[2]; ++k) {
        const double x = (i - kGhost + 0.5) * h, y = (j - kGhost + 0.5) * h, z = (k - kGhost + 0.5) * h;
        for (int s = 0; s < 6; ++s)
          hb[s](i, j, k) = hpsi(i, j, k) >= 0.5 ? linear(s, x, y, z) : (s < 3 ? 1e3 : 40.0 * (s - 2));
      }
  for (int s = 0; s < 6; ++s) hb[s](bad, bad, bad) = 5.0;  // singular: lost positive definiteness
  for (int s = 0; s < 6; ++s) Kokkos::deep_copy(b.c[s].data, hb[s]);

  // as the solver calls it: valid ghosts of psi and B, then mark + sweeps on shrinking grown boxes
  test_support::fill_periodic(psi, m.n);
  for (int s = 0; s < 6; ++s) test_support::fill_periodic(b.c[s].data, m.n);
  kernels::extend_tensor(b, known, psi, 0.5, band, m.interior());

  std::vector<Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>> out;
  for (int s = 0; s < 6; ++s) out.push_back(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.c[s].data));
  double lo_s[6], hi_s[6];
  for (int s = 0; s < 6; ++s) lo_s[s] = 1e300, hi_s[s] = -1e300;
  const Box in = m.interior();
  for (int i = in.lo[0]; i < in.hi[0]; ++i)
    for (int j = in.lo[1]; j < in.hi[1]; ++j)
      for (int k = in.lo[2]; k < in.hi[2]; ++k)
        if (hpsi(i, j, k) >= 0.5 && !(i == bad && j == bad && k == bad))
          for (int s = 0; s < 6; ++s) lo_s[s] = std::min(lo_s[s], hb[s](i, j, k)), hi_s[s] = std::max(hi_s[s], hb[s](i, j, k));
  // face-step distance to the nearest solid cell (periodic), by brute force
  auto distance = [&](int i, int j, int k) {
    int best = 1 << 20;
    for (int a = in.lo[0]; a < in.hi[0]; ++a)
      for (int q = in.lo[1]; q < in.hi[1]; ++q)
        for (int r = in.lo[2]; r < in.hi[2]; ++r) {
          if (hpsi(a, q, r) < 0.5) continue;
          auto per = [n](int d) { d = std::abs(d) % n; return std::min(d, n - d); };
          best = std::min(best, per(a - i) + per(q - j) + per(r - k));
        }
    return best;
  };
  int untouched = 0, extended = 0, identity = 0;
  for (int i = in.lo[0]; i < in.hi[0]; ++i)
    for (int j = in.lo[1]; j < in.hi[1]; ++j)
      for (int k = in.lo[2]; k < in.hi[2]; ++k) {
        double v[6];
        for (int s = 0; s < 6; ++s) v[s] = out[s](i, j, k);
        if (i == bad && j == bad && k == bad) {
          const double x = (i - kGhost + 0.5) * h, y = (j - kGhost + 0.5) * h, z = (k - kGhost + 0.5) * h;
          for (int s = 0; s < 6; ++s) EXPECT_NEAR(v[s], linear(s, x, y, z), 1e-14);
        } else if (hpsi(i, j, k) >= 0.5) {
          for (int s = 0; s < 6; ++s) EXPECT_EQ(v[s], hb[s](i, j, k));
          ++untouched;
        } else if (distance(i, j, k) <= band) {
          for (int s = 0; s < 6; ++s) {
            EXPECT_GE(v[s], lo_s[s] - 1e-15);
            EXPECT_LE(v[s], hi_s[s] + 1e-15);
          }
          EXPECT_TRUE(kernels::positive_definite(v[0], v[1], v[2], v[3], v[4], v[5]));
          ++extended;
        } else {
          for (int s = 0; s < 6; ++s) EXPECT_EQ(v[s], s < 3 ? 1.0 : 0.0);
          ++identity;
        }
      }
  std::printf("extension: %d solid cells kept, %d band cells extended, %d far cells set to I\n", untouched, extended,
              identity);
  EXPECT_GT(extended, 0);
  EXPECT_GT(identity, 0);
}

namespace {

// Manufactured periodic B_s = delta_s + a_s sin(2 pi x + p_s) sin(2 pi y + q_s) sin(2 pi z + r_s).
struct ManufacturedB {
  double a[6] = {0.3, -0.2, 0.25, 0.15, -0.1, 0.2};
  double ph[6][3] = {{0.1, 0.2, 0.3}, {0.5, 0.1, 0.9}, {1.3, 0.4, 0.2}, {0.7, 1.1, 0.6}, {0.2, 0.8, 1.4}, {1.0, 0.3, 0.5}};
  KOKKOS_INLINE_FUNCTION double value(int s, const double x[3]) const {
    const double w = 2.0 * M_PI;
    return (s < 3 ? 1.0 : 0.0) + a[s] * compat::sin(w * x[0] + ph[s][0]) * compat::sin(w * x[1] + ph[s][1]) *
                                     compat::sin(w * x[2] + ph[s][2]);
  }
  KOKKOS_INLINE_FUNCTION double deriv(int s, int d, const double x[3]) const {
    const double w = 2.0 * M_PI;
    double f = a[s] * w;
    for (int e = 0; e < 3; ++e) f *= e == d ? compat::cos(w * x[e] + ph[s][e]) : compat::sin(w * x[e] + ph[s][e]);
    return f;
  }
};

// max over D-faces of |rhs_D - G sum_E dB_DE/dx_E| with psi = 1, b = b_prev = manufactured B.
double elastic_force_error(int N) {
  const Mesh m(N, N, N, 1.0, 1.0, 1.0);
  const double G = 2.0, h = m.h[0];
  Field3 psi = m.field("psi");
  Kokkos::deep_copy(psi, 1.0);
  Tensor6 b = m.tensor("b");
  const ManufacturedB mb;
  for (int s = 0; s < 6; ++s) {
    const Field3 bs = b.c[s].data;
    Kokkos::parallel_for("test::mms_b", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
      const double x[3] = {(i - kGhost + 0.5) * h, (j - kGhost + 0.5) * h, (k - kGhost + 0.5) * h};
      bs(i, j, k) = mb.value(s, x);
    });
  }
  Velocity rhs = m.velocity();
  kernels::add_elastic_force(rhs, psi, b, b, m.scratch(), G, m.h, m.interior());
  double err = 0.0;
  for (int D = 0; D < 3; ++D) {
    const Field3 r = rhs.c[D];
    double e = 0.0;
    Kokkos::parallel_reduce("test::mms_err", m.interior().policy(), KOKKOS_LAMBDA(int i, int j, int k, double& mx) {
      double x[3] = {(i - kGhost + 0.5) * h, (j - kGhost + 0.5) * h, (k - kGhost + 0.5) * h};
      x[D] += 0.5 * h;  // the D-face
      double exact = 0.0;
      for (int E = 0; E < 3; ++E) exact += G * mb.deriv(kernels::tensor_index(D, E), E, x);
      mx = compat::fmax(mx, compat::fabs(r(i, j, k) - exact));
    }, Kokkos::Max<double>(e));
    err = std::fmax(err, e);
  }
  return err;
}

}  // namespace

// B = I (and the Crank-Nicolson pair B = I + X, B_prev = I - X) gives no stress, whatever psi is:
// S = psi G ((B + B_prev)/2 - I) = 0 up to the rounding of (1+X) + (1-X): < 1e-12.
TEST(ElasticForce, NoForceWithoutDeformation) {
  const Mesh m(8, 8, 8, 1.0, 1.0, 1.0);
  Field3 psi = m.field("psi");
  const double lo[3] = {0, 0, 0}, c[3] = {0.5, 0.5, 0.5}, L[3] = {1, 1, 1};
  fill_sphere(psi, m, lo, c, 0.3, L);
  Tensor6 b = m.tensor("b"), bp = m.tensor("bp");
  set_identity(b);
  set_identity(bp);
  Velocity rhs = m.velocity();
  kernels::add_elastic_force(rhs, psi, b, bp, m.scratch(), 3.0, m.h, m.interior());
  double err = 0.0;
  for (int d = 0; d < 3; ++d) err = std::fmax(err, max_abs_minus(rhs.c[d], 0.0, m.interior()));
  EXPECT_EQ(err, 0.0);
  for (int s = 0; s < 6; ++s) {
    Kokkos::deep_copy(b.c[s].data, (s < 3 ? 1.0 : 0.0) + 0.37);
    Kokkos::deep_copy(bp.c[s].data, (s < 3 ? 1.0 : 0.0) - 0.37);
  }
  kernels::add_elastic_force(rhs, psi, b, bp, m.scratch(), 3.0, m.h, m.interior());
  for (int d = 0; d < 3; ++d) err = std::fmax(err, max_abs_minus(rhs.c[d], 0.0, m.interior()));
  EXPECT_LT(err, 1e-12);
}

// Central differences of cell-centre stresses on the MAC grid: O(h^2) truncation error, so the
// max error falls by 4 per halving; we accept a ratio > 3.5.
TEST(ElasticForce, SecondOrderOnManufacturedB) {
  const double e16 = elastic_force_error(16), e32 = elastic_force_error(32), e64 = elastic_force_error(64);
  std::printf("elastic force max err: N=16 %.3e  N=32 %.3e  N=64 %.3e  ratios %.2f %.2f\n", e16, e32, e64, e16 / e32,
              e32 / e64);
  EXPECT_GT(e16 / e32, 3.5);
  EXPECT_GT(e32 / e64, 3.5);
}

TEST(ElasticForce, MixtureViscosity) {
  const Mesh m(4, 4, 4, 1.0, 1.0, 1.0);
  Field3 psi = m.field("psi"), mu = m.field("mu");
  Kokkos::deep_copy(psi, 0.25);
  Kokkos::deep_copy(mu, 0.01);
  kernels::mixture_viscosity_add(mu, psi, 0.04 - 0.01, m.all());
  EXPECT_LT(max_abs_minus(mu, 0.75 * 0.01 + 0.25 * 0.04, m.all()), 1e-17);
}

namespace {

struct SphereMoments {
  kernels::BodyFirstMoments first;
  kernels::BodySecondMoments second;
  double cx;  // unwrapped centroid x
  double V;
};

// Box [0, 2) x [-1/2, 1/2]^2, h = 1/32, sphere of radius 1/4 at c; x periodic.
SphereMoments sphere_moments(const double c[3], const Velocity& vel, const Mesh& m) {
  const double lo[3] = {0.0, -0.5, -0.5}, L[3] = {2.0, 0.0, 0.0};
  Field3 psi = m.field("psi");
  fill_sphere(psi, m, lo, c, 0.25, L);
  const kernels::CellCentres xc{{lo[0] + (0.5 - kGhost) * m.h[0], lo[1] + (0.5 - kGhost) * m.h[1],
                                 lo[2] + (0.5 - kGhost) * m.h[2]},
                                {m.h[0], m.h[1], m.h[2]}};
  SphereMoments r;
  r.first = kernels::body_first_moments(psi, vel, xc, 2.0, m.interior());
  r.V = r.first.s[kernels::BodyFirstMoments::Volume];
  const double ref[3] = {kernels::circular_mean_x(r.first.s[kernels::BodyFirstMoments::Cos],
                                                  r.first.s[kernels::BodyFirstMoments::Sin], 2.0),
                         r.first.s[kernels::BodyFirstMoments::Y] / r.V, r.first.s[kernels::BodyFirstMoments::Z] / r.V};
  const double period[3] = {2.0, 0.0, 0.0};
  r.second = kernels::body_second_moments(psi, xc, ref, period, m.interior());
  r.cx = ref[0] + r.second.m1[0] / r.V;
  if (r.cx < 0.0) r.cx += 2.0;
  return r;
}

}  // namespace

// Volume: 4^3 sub-sampling is a lattice-point count with spacing h/4 = r/32; the count error
// for a sphere of radius 32 lattice spacings is O(32^1.5) points out of 1.4e5 (~1e-3 relative):
// we require 3e-3. Centroid: the sampled sphere is symmetric up to the same lattice error, so
// |c - c_exact| well below h (we require 1e-4 absolute, h = 0.031). Inertia: the cell volume
// fraction is the indicator smoothed by the cell box, whose variance h^2/12 per direction adds to
// the moment: m2_aa - V h^2/12 = V r^2 / 5 to the volume accuracy (3e-3; the bias is 6.5e-3).
TEST(ParticleMoments, SphereVolumeCentroidAndInertia) {
  const Mesh m(64, 32, 32, 2.0, 1.0, 1.0);
  Velocity vel = m.velocity();
  const double U[3] = {1.0, -2.0, 3.0};
  for (int d = 0; d < 3; ++d) Kokkos::deep_copy(vel.c[d], U[d]);
  const double r = 0.25, Vex = 4.0 / 3.0 * M_PI * r * r * r;
  const double centres[2][3] = {{1.013, 0.107, -0.052}, {0.041, 0.107, -0.052}};  // the second straddles x = 0
  for (const auto& c : centres) {
    const SphereMoments s = sphere_moments(c, vel, m);
    const double cy = s.first.s[kernels::BodyFirstMoments::Y] / s.V, cz = s.first.s[kernels::BodyFirstMoments::Z] / s.V;
    std::printf("sphere at x=%.3f: V rel err %.2e, centroid err (%.1e, %.1e, %.1e), Ixx rel err %.2e (-h^2/12: %.2e)\n",
                c[0], s.V / Vex - 1.0, s.cx - c[0], cy - c[1], cz - c[2], s.second.m2[0] / (s.V * r * r / 5.0) - 1.0,
                (s.second.m2[0] - s.V * m.h[0] * m.h[0] / 12.0) / (s.V * r * r / 5.0) - 1.0);
    EXPECT_LT(std::fabs(s.V / Vex - 1.0), 3e-3);
    EXPECT_LT(std::fabs(s.cx - c[0]), 1e-4);
    EXPECT_LT(std::fabs(cy - c[1]), 1e-4);
    EXPECT_LT(std::fabs(cz - c[2]), 1e-4);
    const double cell = s.V * m.h[0] * m.h[0] / 12.0;
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::fabs((s.second.m2[a] - cell) / (s.V * r * r / 5.0) - 1.0), 3e-3);
    for (int a = 3; a < 6; ++a) EXPECT_LT(std::fabs(s.second.m2[a]) / (s.V * r * r / 5.0), 3e-3);
    // psi-weighted mean of a uniform velocity is that velocity (face averages of constants)
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(s.first.s[kernels::BodyFirstMoments::U + d] / s.V, U[d], 1e-13);
  }
}

// Force terms on fields for which the stencils are exact (polynomials of degree <= 2), so each
// integral equals (sum psi dV) times the analytic pointwise value to round-off (1e-12 relative):
// p = -3 x -> F^P = 3 V e_x; u = a y^2 -> div(u u) = 0, div(grad u + grad u^T) = 2a e_x;
// B_xy = c y -> div(B)_x = c, div(B)_y = 0.
DEVICE_TEST(ParticleMoments, ForceTermsOnExactFields) {
  const Mesh m(32, 16, 16, 1.0, 1.0, 1.0);
  const double lo[3] = {0.0, -0.5, -0.5}, L[3] = {1.0, 0.0, 0.0}, c[3] = {0.5, 0.05, 0.0};
  Field3 psi = m.field("psi"), p = m.field("p");
  fill_sphere(psi, m, lo, c, 0.25, L);
  const double h0 = m.h[0], h1 = m.h[1], a = 0.7, cb = 0.4, G = 2.0, mu_s = 0.05;
  Velocity vel = m.velocity();
  Tensor6 b = m.tensor("b");
  set_identity(b);
  const Field3 u = vel.c[0], bxy = b.c[kernels::XY].data;
  Kokkos::parallel_for("test::force_fields", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    const double x = (i - kGhost + 0.5) * h0, y = -0.5 + (j - kGhost + 0.5) * h1;
    p(i, j, k) = -3.0 * x;
    u(i, j, k) = a * y * y;
    bxy(i, j, k) = cb * y;
  });
  const kernels::BodyForces f = kernels::body_forces(psi, p, vel, b, G, mu_s, 0.0, m.h, m.interior());
  double V = sum(psi, m.interior()) * m.h[0] * m.h[1] * m.h[2];
  const double tol = 1e-12 * V;
  std::printf("forces / V: P (%.3g %.2g %.2g) I (%.2g %.2g %.2g) V (%.4g %.2g %.2g) E (%.4g %.2g %.2g)\n",
              f.pressure[0] / V, f.pressure[1] / V, f.pressure[2] / V, f.inertia[0] / V, f.inertia[1] / V,
              f.inertia[2] / V, f.viscous[0] / V, f.viscous[1] / V, f.viscous[2] / V, f.elastic[0] / V,
              f.elastic[1] / V, f.elastic[2] / V);
  const double expect_p[3] = {3.0 * V, 0, 0}, expect_v[3] = {2.0 * a * mu_s * V, 0, 0}, expect_e[3] = {G * cb * V, 0, 0};
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(f.pressure[d], expect_p[d], tol);
    EXPECT_NEAR(f.inertia[d], 0.0, tol);
    EXPECT_NEAR(f.viscous[d], expect_v[d], tol);
    EXPECT_NEAR(f.elastic[d], expect_e[d], tol);
  }
}

// In a grid moving with U along x the solver holds u - U; the inertia term of the force
// decomposition must still be the laboratory's, -div((u' + U e_x) u_D) = -div(u' u_D) - U du_D/dx
// (div u = 0). On a discretely divergence-free field (u, v from an edge stream function, w = w(x))
// both ways of computing it agree to round-off.
DEVICE_TEST(ParticleMoments, InertiaForceIsTheLaboratorysInAMovingFrame) {
  const Mesh m(32, 16, 16, 1.0, 1.0, 1.0);
  const double lo[3] = {0.0, -0.5, -0.5}, L[3] = {1.0, 0.0, 0.0}, c[3] = {0.45, 0.1, -0.05};
  Field3 psi = m.field("psi"), p = m.field("p");
  fill_sphere(psi, m, lo, c, 0.25, L);
  const double h0 = m.h[0], h1 = m.h[1], U = 1.3;
  Velocity lab = m.velocity(), moved = m.velocity();
  Tensor6 b = m.tensor("b");
  set_identity(b);
  const Field3 u = lab.c[0], v = lab.c[1], w = lab.c[2], um = moved.c[0], vm = moved.c[1], wm = moved.c[2];
  Kokkos::parallel_for("test::frame_fields", m.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
    // stream function at the (x, y) edges: s(x, y) = sin(2 pi x) cos(pi y) / 5
    const double xe = (i - kGhost + 1.0) * h0, ye = -0.5 + (j - kGhost + 1.0) * h1;
    const double sx = compat::sin(2.0 * M_PI * xe), sx_m = compat::sin(2.0 * M_PI * (xe - h0));
    const double cy = compat::cos(M_PI * ye), cy_m = compat::cos(M_PI * (ye - h1));
    u(i, j, k) = 1.0 + 0.2 * sx * (cy - cy_m) / h1;          // (s(i, j) - s(i, j-1)) / hy
    v(i, j, k) = -0.2 * (sx - sx_m) * cy / h0;               // -(s(i, j) - s(i-1, j)) / hx
    w(i, j, k) = 0.3 * compat::sin(2.0 * M_PI * (i - kGhost + 0.5) * h0);
    um(i, j, k) = u(i, j, k) - U;
    vm(i, j, k) = v(i, j, k);
    wm(i, j, k) = w(i, j, k);
  });
  const kernels::BodyForces a = kernels::body_forces(psi, p, lab, b, 1.0, 0.05, 0.0, m.h, m.interior());
  const kernels::BodyForces f = kernels::body_forces(psi, p, moved, b, 1.0, 0.05, U, m.h, m.interior());
  const double V = sum(psi, m.interior()) * m.h[0] * m.h[1] * m.h[2];
  std::printf("inertia / V: laboratory (%.6g %.6g %.6g), moving grid (%.6g %.6g %.6g)\n", a.inertia[0] / V,
              a.inertia[1] / V, a.inertia[2] / V, f.inertia[0] / V, f.inertia[1] / V, f.inertia[2] / V);
  // the terms are O(1) per unit volume here; round-off of O(10) operations on O(1/h) stencils
  for (int d = 0; d < 3; ++d) {
    EXPECT_GT(std::fabs(a.inertia[1]), 0.1 * V);  // not a trivially zero comparison
    EXPECT_NEAR(f.inertia[d], a.inertia[d], 1e-10 * V);
    EXPECT_NEAR(f.viscous[d], a.viscous[d], 1e-10 * V);
  }
}

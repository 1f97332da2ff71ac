// Olsson-Kreiss sharpening of a smeared sphere: the volume is kept to round-off (flux form) and
// the band of intermediate psi narrows towards the equilibrium width (a few cells).
#include <gtest/gtest.h>

#include "kernels/interface_sharpening.hpp"
#include "solver/boundary_conditions.hpp"
#include "support/flow_case.hpp"

using namespace eulerfsi;

TEST(InterfaceSharpening, ConservesVolumeAndNarrowsTheInterface) {
  CaseConfig cfg = test::small_case(Geometry::Periodic, 24, 24, 24, 1.0, 1.0, 1.0, 1.0, InitialFlow::Rest);
  const Comm comm;
  const Grid g = make_grid(cfg, comm);
  const BoundaryConditions bc(cfg, g, comm.comm);
  Field3 psi = g.make_field("psi"), rhs = g.make_field("rhs");
  Field3 nx = g.make_field("nx"), ny = g.make_field("ny"), nz = g.make_field("nz");
  // a sphere of radius 0.25 smeared over ~6 cells: psi = 1 / (1 + exp((r - R) / w)), w = 1.5 h
  const double h = g.h[0], w = 1.5 * h;
  auto hp = Kokkos::create_mirror_view(psi);
  const Box b = g.interior();
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const double x = g.centre(0, i) - 0.5, y = g.centre(1, j), z = g.centre(2, k);
        hp(i, j, k) = 1.0 / (1.0 + std::exp((std::sqrt(x * x + y * y + z * z) - 0.25) / w));
      }
  Kokkos::deep_copy(psi, hp);
  bc.fill_scalar(psi);
  auto sum = [&b](const Field3& f) {
    double s = 0.0;
    reduce_cells("test::sum", b, KOKKOS_LAMBDA(int i, int j, int k, double& a) { a += f(i, j, k); }, Kokkos::Sum<double>(s));
    return s;
  };
  auto band = [&b](const Field3& f) {
    double s = 0.0;
    reduce_cells("test::band", b, KOKKOS_LAMBDA(int i, int j, int k, double& a) {
      a += (f(i, j, k) > 0.05 && f(i, j, k) < 0.95) ? 1.0 : 0.0;
    }, Kokkos::Sum<double>(s));
    return s;
  };
  const double v0 = comm.sum(sum(psi)), band0 = comm.sum(band(psi));
  const Box grown{{b.lo[0] - 1, b.lo[1] - 1, b.lo[2] - 1}, {b.hi[0] + 1, b.hi[1] + 1, b.hi[2] + 1}};
  for (int n = 0; n < 60; ++n) {
    kernels::interface_normals(nx, ny, nz, psi, g.h, grown);
    kernels::sharpening_rhs(rhs, psi, nx, ny, nz, 0.5 * h, g.h, b);
    kernels::rk3_scalar_update(psi, rhs, rhs, 0.1 * h, 1.0, 0.0, b);
    bc.fill_scalar(psi);
  }
  const double v1 = comm.sum(sum(psi)), band1 = comm.sum(band(psi));
  std::printf("sharpening: volume %.15g -> %.15g, cells with 0.05 < psi < 0.95: %.0f -> %.0f\n", v0, v1, band0, band1);
  // flux form: the sum changes only by round-off, ~1e-16 per cell and step
  EXPECT_NEAR(v1, v0, 1e-12 * v0);
  // the equilibrium width eps = h/2 holds 0.05 < psi < 0.95 within |d| < 2.9 eps = 1.5 h, a band of
  // about 3 cells against 8.8 for w = 1.5 h: it must at least halve
  EXPECT_LT(band1, 0.5 * band0);
}

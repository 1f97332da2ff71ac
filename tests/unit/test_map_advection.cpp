// The reference map's advection rhs (kernels/reference_map.hpp, MapAdvectionRhs): the host form,
// which walks whole i-planes and computes the flux through a face between two advected cells once
// (carried along the row in z and from one row to the next in y), gives the per-cell form's values
// (what GPUs run) bit for bit: around a deformed sphere, and on rows longer than the carried buffer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kernels/reference_map.hpp"

using namespace eulerfsi;

namespace {

using HostCells = Kokkos::View<double***, Kokkos::LayoutRight, Kokkos::HostSpace>;
HostCells on_host(const WindowField& f) { return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data); }

// A map on an n[0] x n[1] x n[2] window (h = 1): q a rotation with quadratic terms, the solid and
// its band classified and extrapolated, psi and B derived; a velocity whose components change sign
// across the window (both upwind directions along every row).
struct MapCase {
  int n[3];
  kernels::Vector3 q;
  WindowField level, psi;
  kernels::Tensor6 b;
  kernels::Velocity vel;
  kernels::ReferenceShape shape;
  Box interior;

  MapCase(int nx, int ny, int nz, bool sphere) : n{nx, ny, nz}, interior{{4, 4, 4}, {nx - 4, ny - 4, nz - 4}} {
    auto field = [&](const char* name) { return Field3(std::string(name), n[0], n[1], n[2]); };
    level = WindowField(field("level"));
    psi = WindowField(field("psi"));
    for (int c = 0; c < kernels::kTensorComponents; ++c) b.c[c] = WindowField(field("B"));
    for (int a = 0; a < 3; ++a) {
      q.c[a] = WindowField(field("q"));
      vel.c[a] = field("u");
      auto hq = Kokkos::create_mirror_view(q.c[a].data);
      auto hu = Kokkos::create_mirror_view(vel.c[a]);
      for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j)
          for (int k = 0; k < n[2]; ++k) {
            const double x[3] = {i - 0.5 * n[0], j - 0.5 * n[1], k - 0.5 * n[2]}, c = std::cos(0.3), s = std::sin(0.3);
            const double rotated[3] = {c * x[0] - s * x[1], s * x[0] + c * x[1], x[2]};
            hq(i, j, k) = rotated[a] - x[a] + (a == 0 ? 0.01 * x[1] * x[2] : (a == 1 ? 0.002 * x[0] * x[0] : 0.005 * x[1] * x[1]));
            hu(i, j, k) = 0.1 * std::sin(0.37 * i + 0.23 * j + 0.41 * k + a) + 0.02 * x[(a + 1) % 3];
          }
      Kokkos::deep_copy(q.c[a].data, hq);
      Kokkos::deep_copy(vel.c[a], hu);
    }
    shape.sphere = sphere;
    shape.radius = 6.4;
    for (int a = 0; a < 3; ++a) shape.centre[a] = 0.5 * n[a] + 0.3 - 0.1 * a;
    shape.top = 0.5 * n[1] + 0.2;  // the layer y < top
    const kernels::CellCentres centres{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
    const double h[3] = {1.0, 1.0, 1.0};
    const WindowField weight(field("weight"));
    kernels::classify_solid(level, weight, q, shape, centres, 3.0, 0.0, 1.0, true, h, interior);
    for (int s = 1; s <= 3; ++s) kernels::extrapolation_sweep(q, level, weight, s, interior);
    kernels::solid_from_map(psi, b, q, level, shape, centres, 1.5, 3.0, h, interior);
  }

  kernels::Vector3 make_rhs(const char* name) const {
    kernels::Vector3 r;
    for (int a = 0; a < 3; ++a) r.c[a] = WindowField(Field3(std::string(name), n[0], n[1], n[2]));
    return r;
  }
  // The rhs on the advection box (the interior less WENO5's reach) by the product's launch (host
  // planes here) and by the per-cell operator directly; the number of advected cells compared.
  int compare() const {
    const Box box{{interior.lo[0] + 3, interior.lo[1] + 3, interior.lo[2] + 3},
                  {interior.hi[0] - 3, interior.hi[1] - 3, interior.hi[2] - 3}};
    const double h[3] = {1.0, 1.0, 1.0};
    const kernels::Vector3 planes = make_rhs("rhs_planes"), cells = make_rhs("rhs_cells");
    kernels::reference_map_rhs(planes, q, level, psi, vel, h, box);
    const kernels::MapAdvectionRhs per_cell{cells, q, level, psi, vel.c[0], vel.c[1], vel.c[2], {1.0, 1.0, 1.0}};
    Kokkos::parallel_for("per_cell_rhs", box.policy(), per_cell);
    Kokkos::fence();
    const HostCells l = on_host(level), p = on_host(psi);
    int advected = 0, nonzero = 0, different = 0;
    for (int a = 0; a < 3; ++a) {
      const HostCells x = on_host(planes.c[a]), y = on_host(cells.c[a]);
      for (int i = box.lo[0]; i < box.hi[0]; ++i)
        for (int j = box.lo[1]; j < box.hi[1]; ++j)
          for (int k = box.lo[2]; k < box.hi[2]; ++k) {
            advected += a == 0 && kernels::advected(l(i, j, k), p(i, j, k));
            nonzero += x(i, j, k) != 0.0;
            different += !(x(i, j, k) == y(i, j, k));  // bit for bit (no NaN either)
          }
    }
    EXPECT_EQ(different, 0);
    EXPECT_GT(nonzero, advected);  // the rhs is not trivially zero
    return advected;
  }
};

}  // namespace

TEST(MapAdvection, HostPlanesEqualThePerCellFormAroundASphere) {
  const MapCase m(34, 34, 34, true);
  // the solid (4/3 pi 6.4^3 ~ 1100 cells) and the band where psi > 0
  EXPECT_GT(m.compare(), 1500);
}

// A layer across the window along z, rows of 292 cells (longer than the carried buffer): the
// y-faces are computed on both sides there.
TEST(MapAdvection, RowsLongerThanTheCarriedBufferEqualThePerCellForm) {
  static_assert(300 - 8 - 6 > kernels::MapAdvectionRhs::kCarriedCells, "the rows must outrun the buffer");
  const MapCase m(20, 20, 300, false);
  EXPECT_GT(m.compare(), 1000);
}

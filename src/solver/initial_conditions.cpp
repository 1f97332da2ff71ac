#include "solver/initial_conditions.hpp"

#include <cmath>

#include "solver/exact_solutions.hpp"

namespace eulerfsi {

namespace {

// Samples f(x, y, z) at the staggered points of component c on the host, then copies to the device:
// initial conditions are computed once, and the duct series is not a device function.
template <class F>
void sample(const Grid& g, const Field3& dst, int c, F&& f) {
  auto h = Kokkos::create_mirror_view(dst);
  Kokkos::deep_copy(h, 0.0);
  const Box b = g.interior();
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const double x = g.centre(0, i) + (c == 0 ? 0.5 * g.h[0] : 0.0);
        const double y = g.centre(1, j) + (c == 1 ? 0.5 * g.h[1] : 0.0);
        const double z = g.centre(2, k) + (c == 2 ? 0.5 * g.h[2] : 0.0);
        h(i, j, k) = f(x, y, z);
      }
  Kokkos::deep_copy(dst, h);
}

}  // namespace

void fill_initial_velocity(const CaseConfig& cfg, const Grid& g, const kernels::Velocity& vel) {
  const double ub = cfg.flow.bulk_velocity;
  const double mu = 1.0 / cfg.flow.Re;
  const double ly = g.length[1], lz = g.length[2];
  auto zero = [](double, double, double) { return 0.0; };
  sample(g, vel.c[1], 1, zero);
  sample(g, vel.c[2], 2, zero);
  switch (cfg.flow.initial) {
    case InitialFlow::Rest:
      sample(g, vel.c[0], 0, zero);
      break;
    case InitialFlow::TaylorGreen: {
      // u = sin(kx x) cos(ky y'), v = -(kx/ky) cos(kx x) sin(ky y'), y' = y + Ly/2: divergence free
      const double kx = 2.0 * exact::kPi / g.length[0], ky = 2.0 * exact::kPi / ly;
      const double y0 = 0.5 * ly;
      sample(g, vel.c[0], 0, [=](double x, double y, double) { return std::sin(kx * x) * std::cos(ky * (y + y0)); });
      sample(g, vel.c[1], 1,
             [=](double x, double y, double) { return -(kx / ky) * std::cos(kx * x) * std::sin(ky * (y + y0)); });
      break;
    }
    case InitialFlow::Laminar:
      switch (cfg.domain.geometry) {
        case Geometry::Pipe:
          sample(g, vel.c[0], 0, [=](double, double y, double z) { return exact::pipe_velocity(y, z, ub); });
          break;
        case Geometry::Duct:
          sample(g, vel.c[0], 0, [=](double, double y, double z) { return exact::duct_velocity(y, z, ly, lz, mu, ub); });
          break;
        case Geometry::Channel:
          sample(g, vel.c[0], 0, [=](double, double y, double) { return exact::channel_velocity(y, ly, ub); });
          break;
        case Geometry::Couette: {
          // the linear profile between the walls; an oscillating wall starts from rest (sin 0 = 0)
          const double lo = cfg.flow.wall_frequency > 0 ? 0.0 : cfg.flow.wall_velocity[0];
          const double hi = cfg.flow.wall_frequency > 0 ? 0.0 : cfg.flow.wall_velocity[1];
          sample(g, vel.c[0], 0, [=](double, double y, double) { return lo + (hi - lo) * (y / ly + 0.5); });
          break;
        }
        case Geometry::Periodic:
          sample(g, vel.c[0], 0, zero);
          break;
      }
      break;
  }
}

}  // namespace eulerfsi

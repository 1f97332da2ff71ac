// B outside the solid does no harm (kernels/tensor_extension.hpp): in a coupled run of a soft
// particle released in a pipe, after every step
//  - B is positive definite everywhere (no material of negative stiffness anywhere), and
//  - outside the solid (psi < 1/2) no component of B - I exceeds the solid's own largest, so the
//    elastic stress psi G (B - I) of the smeared edge is never stiffer than the particle itself
//    (with B transported by the fluid there, tr(B - I) reached 500 in such cells).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "kernels/solid_transport.hpp"
#include "solid/particle_diagnostics.hpp"
#include "solid/solid_phase.hpp"
#include "support/flow_case.hpp"

using namespace eulerfsi;

namespace {

struct HaloCheck {
  double solid_max = 0.0;  // max |B - I| component over psi >= 1/2
  double halo_max = 0.0;   // max |B - I| component over psi < 1/2
  long not_spd = 0;
};

HaloCheck check_halo(const SolidBody& body, const Box& box) {
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body.psi.data);
  std::vector<decltype(psi)> b;
  for (int c = 0; c < kernels::kTensorComponents; ++c)
    b.push_back(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body.b.c[c].data));
  HaloCheck r;
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int k = box.lo[2]; k < box.hi[2]; ++k) {
        double m = 0.0;
        for (int c = 0; c < kernels::kTensorComponents; ++c) m = std::max(m, std::fabs(b[c](i, j, k) - (c < 3 ? 1.0 : 0.0)));
        (psi(i, j, k) >= 0.5 ? r.solid_max : r.halo_max) = std::max(psi(i, j, k) >= 0.5 ? r.solid_max : r.halo_max, m);
        if (!kernels::positive_definite(b[0](i, j, k), b[1](i, j, k), b[2](i, j, k), b[3](i, j, k), b[4](i, j, k),
                                        b[5](i, j, k)))
          ++r.not_spd;
      }
  return r;
}

}  // namespace

TEST(SolidHalo, BOutsideTheSolidIsNeverStifferThanTheSolid) {
  CaseConfig cfg = test::small_case(Geometry::Pipe, 24, 24, 24, 1.0, 1.0, 1.0, 100.0, InitialFlow::Laminar);
  SolidConfig sphere;
  sphere.diameter = 0.25;
  sphere.center = {0.5, 0.1, 0.05};
  sphere.We = 4.0;  // soft: large B - I within a few time units
  sphere.initial_velocity = InitialSolidVelocity::Rest;
  cfg.solids.push_back(sphere);
  test::CoupledCase run(cfg);
  HaloCheck worst;
  double worst_ratio = 0.0;
  long steps = 0;
  test::run_flow(run.flow, 0.5, [&](double) {
    const HaloCheck h = check_halo(run.solids.bodies()[0], run.grid.interior());
    worst.not_spd += h.not_spd;
    worst.solid_max = std::max(worst.solid_max, h.solid_max);
    worst.halo_max = std::max(worst.halo_max, h.halo_max);
    if (h.solid_max > 0.0) worst_ratio = std::max(worst_ratio, h.halo_max / h.solid_max);
    EXPECT_LE(h.halo_max, h.solid_max * (1.0 + 1e-12));
    ++steps;
  }, &run.solids);
  std::printf("%ld steps to t = 0.5: max |B - I| in the solid %.3f, outside %.3f (worst ratio %.3f), non-SPD cells %ld\n",
              steps, worst.solid_max, worst.halo_max, worst_ratio, worst.not_spd);
  EXPECT_EQ(worst.not_spd, 0);
  EXPECT_GT(worst.solid_max, 0.05);  // the particle did deform
}

// The reference-map solid model (src/solid/reference_map_model.*): kinematics with a prescribed
// velocity, where the exact answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "kernels/reference_map.hpp"
#include "solid/particle_diagnostics.hpp"
#include "solid/reference_map_model.hpp"
#include "solid/solid_phase.hpp"
#include "support/flow_case.hpp"
#include "support/mpi_env.hpp"

using namespace eulerfsi;

namespace {

CaseConfig box_with_sphere(int n, SolidModelKind model) {
  CaseConfig cfg = test::small_case(Geometry::Periodic, n, n, n, 1.0, 1.0, 1.0, 100.0, InitialFlow::Rest);
  SolidConfig s;
  s.diameter = 0.25;  // 8 cells across on 32^3
  s.center = {0.5, 0.0, 0.0};
  s.We = 1.0;
  s.model = model;
  cfg.solids.push_back(s);
  return cfg;
}

// Rigid rotation about the sphere's centre, u = omega e_z x (x - c), at each face. u depends on y
// only and v on x only, so the discrete divergence is exactly zero.
void set_rotation(const Grid& g, const kernels::Velocity& vel, double omega, double cx, double cy) {
  const Field3 u = vel.c[0], v = vel.c[1], w = vel.c[2];
  const double hx = g.h[0], hy = g.h[1], y0 = g.domain_lo(1);
  const int xo = g.x_offset;
  for_each_cell("test::rotation", g.all(), KOKKOS_LAMBDA(int i, int j, int k) {
    u(i, j, k) = -omega * (y0 + (j - kGhost + 0.5) * hy - cy);
    v(i, j, k) = omega * ((i - kGhost + xo + 0.5) * hx - cx);
    w(i, j, k) = 0.0;
  });
}

struct RotationResult {
  double D0 = 0.0, D = 0.0, volume0 = 0.0, volume = 0.0, shift = 0.0;
  double D_early = 0.0;  // at the angle `early`
};

// Rotates the body by `angle` radians with the solver's own RK3 substeps at CFL 0.2 on the edge speed.
RotationResult rotate(const CaseConfig& cfg, double angle, double early) {
  test::CoupledCase run(cfg);
  const double omega = 0.5, cx = cfg.solids[0].center[0], cy = cfg.solids[0].center[1];
  set_rotation(run.grid, run.flow.state().vel, omega, cx, cy);
  RotationResult r;
  const ParticleState p0 = run.particle();
  r.D0 = p0.taylor_D;
  r.volume0 = p0.volume;
  const double h = run.grid.h[0];
  const double dt_cfl = 0.2 * h / (omega * 0.5);  // the sphere's edge moves at omega * 0.125; the box's at 0.5 omega
  const long steps = std::lround(angle / omega / dt_cfl);
  const double dt = angle / omega / double(steps);
  const long early_step = std::lround(early / omega / dt);
  for (long s = 0; s < steps; ++s) {
    for (int sub = 0; sub < 3; ++sub) run.solids.advance_substep(run.flow.state().vel, dt, sub);
    if (s + 1 == early_step) r.D_early = run.particle().taylor_D;
  }
  const ParticleState p = run.particle();
  r.D = p.taylor_D;
  r.volume = p.volume;
  if (auto* m = dynamic_cast<ReferenceMapModel*>(run.solids.bodies()[0].model.get())) r.shift = m->level_shift();
  return r;
}

}  // namespace

// A rigid rotation keeps the reference displacement q = xi - x linear in x, which WENO5 and the
// least-squares extrapolation carry exactly; RK3's phase error is (omega dt)^4 / 24 per step
// (~1e-9 rad over 10 rad here). So the shape after 10 rad differs from the initial one only by
// round-off and by how the grid samples a rotated smoothed sphere (psi = H(-d) is a smooth function
// of the exact distance). The issue asks for D < 1e-3 at 8 cells per diameter after 10 rad
// (measured: 3.5e-7); the paper model reads 0.021 after 1 rad (RotatingSphereConvergesToASphere in
// test_solid_kernels). The error must fall with resolution: 16 against 8 cells per diameter after
// 1 rad (measured: 7.2e-8 -> 9.1e-9 after 2 rad; 10 rad at 16 cells, 4 min on 2 cores: 4.8e-8).
TEST(ReferenceMap, RigidRotationKeepsTheSphere) {
  const RotationResult a = rotate(box_with_sphere(32, SolidModelKind::ReferenceMap), 10.0, 1.0);
  const RotationResult c = rotate(box_with_sphere(64, SolidModelKind::ReferenceMap), 1.0, 1.0);
  if (test::rank() == 0)
    std::printf("reference map, 8 cells per d: 10 rad: D %.3e -> %.3e, volume %+.2e, level shift %.2e h\n"
                "  1 rad: D %.3e (8 cells per d), %.3e (16)\n",
                a.D0, a.D, a.volume / a.volume0 - 1.0, a.shift * 32, a.D_early, c.D_early);
  EXPECT_LT(a.D, 1e-3);
  EXPECT_LT(c.D_early, a.D_early);
  // the level shift holds the volume to the accuracy of one Newton step per substep
  EXPECT_NEAR(a.volume / a.volume0, 1.0, 1e-6);
}

namespace {

// The planar straining flow u = s (cos 2a (x - c) + sin 2a (y - c)), v = s (sin 2a (x - c) - cos 2a
// (y - c)), stretching along the angle a from x: u at its face depends on x and y, v on x and y,
// and du/dx + dv/dy = 0 holds exactly on the faces.
void set_strain(const Grid& g, const kernels::Velocity& vel, double rate, double angle, double cx, double cy) {
  const Field3 u = vel.c[0], v = vel.c[1], w = vel.c[2];
  const double hx = g.h[0], hy = g.h[1], y0 = g.domain_lo(1), c2 = std::cos(2 * angle), s2 = std::sin(2 * angle);
  const int xo = g.x_offset;
  for_each_cell("test::strain", g.all(), KOKKOS_LAMBDA(int i, int j, int k) {
    const double xf = (i - kGhost + xo + 1.0) * hx - cx, xm = (i - kGhost + xo + 0.5) * hx - cx;
    const double ym = y0 + (j - kGhost + 0.5) * hy - cy, yf = y0 + (j - kGhost + 1.0) * hy - cy;
    u(i, j, k) = rate * (c2 * xf + s2 * ym);
    v(i, j, k) = rate * (s2 * xm - c2 * yf);
    w(i, j, k) = 0.0;
  });
}

// Strains the sphere of box_with_sphere(32) into the ellipsoid of Taylor deformation D along
// `angle` (F = exp(T s [[c2, s2], [s2, -c2]]): in-plane semi-axes r e^(sT), r e^(-sT), so
// D = tanh(sT)) and measures it.
ParticleState strained_sphere(double D, double angle) {
  test::CoupledCase run(box_with_sphere(32, SolidModelKind::ReferenceMap));
  const double rate = 0.5, cx = 0.5, cy = 0.0;
  set_strain(run.grid, run.flow.state().vel, rate, angle, cx, cy);
  const double T = std::atanh(D) / rate, dt_cfl = 0.2 * run.grid.h[0] / (rate * 0.25);
  const long steps = std::max(1L, std::lround(std::ceil(T / dt_cfl)));
  for (long s = 0; s < steps; ++s)
    for (int sub = 0; sub < 3; ++sub) run.solids.advance_substep(run.flow.state().vel, T / double(steps), sub);
  return run.particle();
}

}  // namespace

// The map of a linear strain is linear, so the body is the exact ellipsoid; what is tested is its
// measurement. psi's moments carry the smoothed edge's width (1.5 cells of 4): an exact ellipsoid
// of D = 0.0163 read 0.0131 with the psi >= 0.05 cut (-19 %), D = 0.125 read 0.1176 (-6 %). The
// moments extrapolated to zero edge width (psi at 1.5 and 1 cells) read, on the same grid with the
// ellipsoid centred on a cell vertex and shifted by (0.3, 0.2, 0.1) cells: 0.0164 / 0.0160 and
// 0.1248 / 0.1254, angles within 0.007 (numpy study, docs/REFERENCE_MAP.md). Bounds: 3 % and 1 %
// on D, 0.01 rad on the angle (the study's spread, rounded up).
TEST(ReferenceMap, ShapeOfAStrainedSphereIsTheEllipsoids) {
  const ParticleState stiff = strained_sphere(0.0163, 0.782), soft = strained_sphere(0.125, 0.66);
  if (test::rank() == 0)
    std::printf("strained sphere: D %.5f (exact 0.0163) angle %.4f (0.782); D %.5f (0.125) angle %.4f (0.66)\n",
                stiff.taylor_D, stiff.angle, soft.taylor_D, soft.angle);
  EXPECT_NEAR(stiff.taylor_D / 0.0163, 1.0, 0.03);
  EXPECT_NEAR(stiff.angle, 0.782, 0.01);
  EXPECT_NEAR(soft.taylor_D / 0.125, 1.0, 0.01);
  EXPECT_NEAR(soft.angle, 0.66, 0.01);
}

// An unstrained body (q = 0, so B = I exactly and psi is the initial one) in fluid at rest: the
// transport rhs is -u - u . grad q = 0 and every force is zero, so u stays zero to round-off.
TEST(ReferenceMap, BodyAtRestInFluidAtRestStaysAtRest) {
  CaseConfig cfg = test::small_case(Geometry::Periodic, 16, 16, 16, 1.0, 1.0, 1.0, 10.0, InitialFlow::Rest);
  SolidConfig sphere;
  sphere.diameter = 0.4;
  sphere.center = {0.5, 0.05, -0.1};
  sphere.We = 0.5;
  sphere.viscosity_ratio = 2.0;
  sphere.initial_velocity = InitialSolidVelocity::Rest;
  sphere.model = SolidModelKind::ReferenceMap;
  cfg.solids.push_back(sphere);
  test::CoupledCase run(cfg);
  const ParticleState p0 = run.particle();
  double t = 0.0;
  for (int step = 0; step < 100; ++step) {
    const double dt = run.flow.stable_dt(run.solids.max_wave_speed());
    run.flow.advance(t, dt, &run.solids);
    t += dt;
  }
  const double max_u = test::max_abs_velocity(run);
  const ParticleState p = run.particle();
  if (test::rank() == 0)
    std::printf("reference map at rest: 100 steps, max |u| = %.3e, D %.3e -> %.3e, volume %.6e (exact %.6e)\n", max_u,
                p0.taylor_D, p.taylor_D, p.volume, M_PI / 6 * 0.064);
  EXPECT_LT(max_u, 1e-12);
  EXPECT_NEAR(p.taylor_D, p0.taylor_D, 1e-12);
  EXPECT_NEAR(p.volume, p0.volume, 1e-12 * p0.volume);
  // six Newton steps on the level shift at t = 0, each with dV/dshift estimated from sum |grad psi|
  // (a few % off), leave the exact sphere volume to better than 1e-6
  EXPECT_NEAR(p0.volume / (M_PI / 6 * 0.064), 1.0, 1e-6);
}

// A rigid rotation next to a no-slip wall: the sphere's surface half a cell from the channel wall,
// so the extrapolated band and the WENO5 stencils reach through the wall into its ghosts. The map
// stays linear, which the wall ghosts (linear extrapolation of the first two cells) and the
// least-squares fits carry exactly, so D keeps its initial value (1.3e-3: the wall cuts off the
// part of psi's smoothed edge beyond it) up to the sampling of the rotated smoothed sphere, which
// the periodic box above measures at 3.5e-7 after 10 rad; 1e-5 bounds it (measured here 6.8e-8
// after 2 rad). Before the wall ghosts of the level were made unknown (kernels::clear_wall_ghosts),
// a stale q in the first cell re-entered the fits through the ghost two cells out, tripled
// (q(-2) = 3 q(0) - 2 q(1)): D rose by 0.11 in 1 rad here, and a sphere 2.5 cells from the wall of a
// channel at Re = 100 blew up within 15 steps.
TEST(ReferenceMap, RigidRotationNextToAWallKeepsTheSphere) {
  CaseConfig cfg = test::small_case(Geometry::Channel, 32, 32, 32, 1.0, 1.0, 1.0, 100.0, InitialFlow::Rest);
  SolidConfig s;
  s.diameter = 0.25;
  s.center = {0.5, -0.5 + 0.125 + 0.5 / 32.0, 0.0};
  s.We = 1.0;
  s.model = SolidModelKind::ReferenceMap;
  cfg.solids.push_back(s);
  const RotationResult r = rotate(cfg, 2.0, 1.0);
  if (test::rank() == 0)
    std::printf("reference map half a cell from a wall: D %.4e, change %+.2e (1 rad) %+.2e (2 rad), volume %+.2e\n",
                r.D0, r.D_early - r.D0, r.D - r.D0, r.volume / r.volume0 - 1.0);
  EXPECT_NEAR(r.D, r.D0, 1e-5);
  EXPECT_NEAR(r.volume / r.volume0, 1.0, 1e-6);
}

// The diagnostics of a sphere across the periodic y and z boundaries of a box: the same sphere,
// sampled the same way (both centres on cell faces), as one in the middle, so the same volume
// and D to round-off and its centre on the boundary. The plain mean of y and z put the reference
// point half a period off, and D read 0.72 for a sphere across z in a channel.
TEST(ReferenceMap, DiagnosticsOfASphereAcrossPeriodicBoundaries) {
  ParticleState p[2];
  const double centre[2][3] = {{0.5, 0.0, 0.0}, {0.5, 0.5, -0.5}};
  for (int n = 0; n < 2; ++n) {
    CaseConfig cfg = box_with_sphere(32, SolidModelKind::ReferenceMap);
    for (int a = 0; a < 3; ++a) cfg.solids[0].center[a] = centre[n][a];
    test::CoupledCase run(cfg);
    p[n] = run.particle();
  }
  if (test::rank() == 0)
    std::printf("sphere in the middle: D %.3e volume %.6e; across y and z: D %.3e volume %.6e centre (%.4f, %.4f)\n",
                p[0].taylor_D, p[0].volume, p[1].taylor_D, p[1].volume, p[1].centre[1], p[1].centre[2]);
  EXPECT_NEAR(p[1].volume, p[0].volume, 1e-12 * p[0].volume);
  EXPECT_NEAR(p[1].taylor_D, p[0].taylor_D, 1e-10);
  EXPECT_NEAR(std::fabs(p[1].centre[1]), 0.5, 1e-12);
  EXPECT_NEAR(std::fabs(p[1].centre[2]), 0.5, 1e-12);
}

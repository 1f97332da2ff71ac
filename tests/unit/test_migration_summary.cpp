// The per-run numbers of summary.json (src/solid/migration_summary.*) on synthetic series whose
// answers are known: t_rev from a force that crosses zero at t = 5 under a release spike and
// step-to-step noise; T_osc from an oscillation of period 2.7 on a migration trend; none where
// there is no oscillation; t_cen where r/R settles on the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solid/migration_summary.hpp"

using namespace eulerfsi;

namespace {

// Rows every 0.013 time units (not commensurate with the period), t in [0, 40].
MigrationSeries series(double period, double amplitude, double trend) {
  MigrationSeries s;
  for (int i = 0; i * 0.013 <= 40.0; ++i) {
    const double t = i * 0.013;
    const double noise = (i % 2 ? 1.0 : -1.0) * 1e-5 * (1 + i % 7);  // small and rough
    s.t.push_back(t);
    s.r_over_R.push_back(0.28 + trend * t + (period > 0 ? amplitude * std::sin(2 * M_PI * t / period) : 0.0) + noise);
    // F_r: outwards, then inwards through zero at t = 5; a release spike of -0.5 over the first
    // 0.1 time units (the running mean crosses zero after it, near t = 0.5); +-0.003 noise
    double f = 0.01 * (5.0 - t) / 5.0 + (i % 2 ? 0.003 : -0.003);
    if (t < 0.1) f = -0.5;
    s.force_r.push_back(f);
  }
  return s;
}

}  // namespace

// The running mean of a linear function over a symmetric window is the function itself, so the
// filtered F_r crosses zero at t = 5 up to the interpolation between rows (0.013) and the noise's
// residue after averaging over ~77 rows (+-0.003 alternating: at most 0.003 / 77 ~ 4e-5 in F, i.e.
// 0.02 in t at the slope 0.002): bound 0.05. The spike in the first 0.1 time units makes the
// filtered force cross zero between t = 0.3 and 1 (checked first): t_rev would be ~0.5 if the
// search started before one filter width after release.
TEST(MigrationSummary, ReversalTimeOfAFilteredForce) {
  const MigrationSeries s = series(2.7, 0.01, 0.005);
  const std::vector<double> fr = running_mean(s.t, s.force_r, kForceFilterWidth);
  EXPECT_LT(fr[std::size_t(0.3 / 0.013)], 0.0);  // the spike dominates the window there
  EXPECT_GT(fr[std::size_t(1.0 / 0.013)], 0.0);  // and no longer here
  const MigrationSummary m = summarize_migration(s);
  std::printf("t_rev %.4f (exact 5)\n", m.t_rev ? *m.t_rev : -1.0);
  ASSERT_TRUE(m.t_rev.has_value());
  EXPECT_NEAR(*m.t_rev, 5.0, 0.05);
}

// Period 2.7 over the window [t_rev, t_end / 2] = [5, 20]: 5.6 periods, between the periodogram's
// bins (15 / 5 = 3, 15 / 6 = 2.5); the parabola through the Hann-windowed log power puts a pure
// tone's peak within ~1 % of its frequency: bound 3 %. The amplitude 0.01 within 10 % (the
// windowed sum of a tone between bins loses up to ~15 % at a bin, less after the trend's removal).
TEST(MigrationSummary, OscillationPeriodOnAMigrationTrend) {
  const MigrationSummary m = summarize_migration(series(2.7, 0.01, 0.005));
  std::printf("T_osc %.4f (exact 2.7), amplitude %.5f (0.01)\n", m.T_osc ? *m.T_osc : -1.0, m.oscillation_amplitude);
  ASSERT_TRUE(m.T_osc.has_value());
  EXPECT_NEAR(*m.T_osc / 2.7, 1.0, 0.03);
  EXPECT_NEAR(m.oscillation_amplitude / 0.01, 1.0, 0.15);
}

// A steady drift with noise 10x below kMinAmplitude has no period; neither has a pure trend.
TEST(MigrationSummary, NoOscillationNoPeriod) {
  EXPECT_FALSE(summarize_migration(series(0.0, 0.0, 0.005)).T_osc.has_value());
  EXPECT_FALSE(summarize_migration(series(2.7, 2e-5, 0.005)).T_osc.has_value());
}

// A particle that settles on the axis at t = 30 (r/R = 0.28 (1 - t / 30), then 0.01): t_cen is the
// first row below the threshold 0.05, t = 30 (1 - 0.05 / 0.28) = 24.64, to one row.
TEST(MigrationSummary, CentringTime) {
  MigrationSeries s = series(0.0, 0.0, 0.0);
  for (std::size_t i = 0; i < s.t.size(); ++i) s.r_over_R[i] = s.t[i] < 30.0 ? 0.28 * (1.0 - s.t[i] / 30.0) : 0.01;
  const MigrationSummary m = summarize_migration(s);
  ASSERT_TRUE(m.t_cen.has_value());
  EXPECT_NEAR(*m.t_cen, 30.0 * (1.0 - 0.05 / 0.28), 0.013 + 1e-9);
}

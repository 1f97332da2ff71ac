#pragma once
// The per-run numbers of the paper, from a particle's time series r/R(t) and F_r(t):
//  - t_rev: first change from outwards (> 0) to inwards of the radial force F_r (particle.csv's
//    F_r, the force that changes
//    the particle's radial momentum, not the paper's sum F_r_paper), after a running mean over a
//    window of kForceFilterWidth time units (D / U_b), searched from one window width after the
//    release: the release transient (F_r swings in the first tenths of a time unit while the
//    particle is accelerated to the flow) is left out and the step-to-step noise averaged out;
//    the crossing is interpolated linearly;
//  - t_cen: first time r/R falls below `centre_threshold` and stays below to the end of the run;
//  - T_osc: the dominant period of r/R over the window the paper uses, the first half of the
//    migration, [t_rev, t_cen / 2] (t_end / 2 when the axis was not reached; from the first
//    filter width when there is no t_rev): r/R resampled uniformly, its running mean over a
//    third of the window removed (the migration's trend), Hann-windowed, and the peak of the
//    periodogram among periods up to a fifth of the window (4.5 and more periods fit), interpolated;
//    null unless the peak stands out (kPeakContrast times the mean of the other periods' power)
//    and the oscillation is larger than kMinAmplitude;
//  - final r/R.  Anything not reached is null.
#include <optional>
#include <string>
#include <vector>

namespace eulerfsi {

struct MigrationSeries {
  std::vector<double> t, r_over_R, force_r;
};

struct MigrationSummary {
  std::optional<double> t_rev, t_cen, T_osc;
  double final_r_over_R = 0.0;
  double initial_r_over_R = 0.0;
  double oscillation_amplitude = 0.0;  // of r/R at the period T_osc (0 without one)
};

constexpr double kCentreThreshold = 0.05;  // r/R below which the particle counts as on the axis
constexpr double kForceFilterWidth = 1.0;  // running-mean window of F_r for t_rev, in D / U_b
constexpr double kPeakContrast = 4.0;      // periodogram peak over the mean of the other periods
constexpr double kMinAmplitude = 1e-4;     // of the r/R oscillation; below it there is none

// The running mean of f over [t_i - width / 2, t_i + width / 2] (cut at the series' ends), trapezoids.
std::vector<double> running_mean(const std::vector<double>& t, const std::vector<double>& f, double width);

MigrationSummary summarize_migration(const MigrationSeries& s, double centre_threshold = kCentreThreshold);

// Reads particle.csv and writes summary.json (one entry per solid) next to it.
void write_summary_json(const std::string& particle_csv, const std::string& json_path);

}  // namespace eulerfsi

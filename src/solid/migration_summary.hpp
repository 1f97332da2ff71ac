#pragma once
// The per-run numbers of the paper, from a particle's time series r/R(t) and F_r(t):
//  - t_rev: first sign change of the radial force F_r, the force that changes the particle's
//    radial momentum (particle.csv's F_r, not the paper's sum F_r_paper; linear interpolation);
//  - t_cen: first time r/R falls below `centre_threshold` and stays below to the end of the run;
//  - T_osc: mean spacing of successive local maxima of r/R over the first half of the
//    migration, [0, t_cen / 2] (or [0, t_end / 2] when the axis was not reached);
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
  int oscillation_peaks = 0;
};

constexpr double kCentreThreshold = 0.05;  // r/R below which the particle counts as on the axis

MigrationSummary summarize_migration(const MigrationSeries& s, double centre_threshold = kCentreThreshold);

// Reads particle.csv and writes summary.json (one entry per solid) next to it.
void write_summary_json(const std::string& particle_csv, const std::string& json_path);

}  // namespace eulerfsi

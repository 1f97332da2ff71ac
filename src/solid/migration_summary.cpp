#include "solid/migration_summary.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"

namespace eulerfsi {

MigrationSummary summarize_migration(const MigrationSeries& s, double threshold) {
  MigrationSummary out;
  const size_t n = s.t.size();
  if (n == 0) return out;
  out.initial_r_over_R = s.r_over_R.front();
  out.final_r_over_R = s.r_over_R.back();
  // t_rev: the first crossing of zero after F_r has left zero
  for (size_t i = 1; i < n; ++i) {
    const double a = s.force_r[i - 1], b = s.force_r[i];
    if (a != 0.0 && ((a > 0.0 && b <= 0.0) || (a < 0.0 && b >= 0.0))) {
      out.t_rev = s.t[i - 1] + (s.t[i] - s.t[i - 1]) * a / (a - b);
      break;
    }
  }
  // t_cen: last time r/R was above the threshold, if it is below from then on
  if (s.r_over_R.back() < threshold) {
    size_t last_above = n;
    for (size_t i = n; i-- > 0;)
      if (s.r_over_R[i] >= threshold) {
        last_above = i;
        break;
      }
    out.t_cen = last_above == n ? s.t.front() : s.t[std::min(last_above + 1, n - 1)];
  }
  // T_osc: local maxima of r/R (strict on the left, so plateaus count once) in the first half
  const double t_half = 0.5 * (out.t_cen ? *out.t_cen : s.t.back());
  std::vector<double> peaks;
  for (size_t i = 1; i + 1 < n && s.t[i] <= t_half; ++i)
    if (s.r_over_R[i] > s.r_over_R[i - 1] && s.r_over_R[i] >= s.r_over_R[i + 1]) peaks.push_back(s.t[i]);
  out.oscillation_peaks = int(peaks.size());
  if (peaks.size() >= 2) out.T_osc = (peaks.back() - peaks.front()) / double(peaks.size() - 1);
  return out;
}

namespace {

std::string json_number(const std::optional<double>& v) { return v ? format_number(*v) : "null"; }

}  // namespace

void write_summary_json(const std::string& particle_csv, const std::string& json_path) {
  std::ifstream in(particle_csv);
  if (!in) throw std::runtime_error("cannot read '" + particle_csv + "' for the summary");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> cols;
  {
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cols.push_back(c);
  }
  auto col = [&cols](const std::string& name) {
    for (size_t i = 0; i < cols.size(); ++i)
      if (cols[i] == name) return i;
    throw std::runtime_error("particle.csv has no column '" + name + "'");
  };
  const size_t it = col("t"), is = col("solid"), ir = col("r_over_R"), iF = col("F_r");
  std::map<int, MigrationSeries> series;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> v;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) v.push_back(std::strtod(c.c_str(), nullptr));
    if (v.size() != cols.size()) continue;  // a torn last row after a crash is ignored
    auto& s = series[int(v[is])];
    s.t.push_back(v[it]);
    s.r_over_R.push_back(v[ir]);
    s.force_r.push_back(v[iF]);
  }
  const std::string tmp = json_path + ".tmp";
  {
    std::ofstream out(tmp);
    out << "{\n  \"t_cen_threshold\": " << format_number(kCentreThreshold) << ",\n"
        << "  \"t_rev_definition\": \"first sign change of F_r, the force that changes the radial momentum P_r\",\n"
        << "  \"t_cen_definition\": \"first time r/R < t_cen_threshold holding to the end of the run\",\n"
        << "  \"T_osc_definition\": \"mean spacing of r/R maxima over [0, t_cen/2] (or [0, t_end/2])\",\n"
        << "  \"solids\": [\n";
    size_t k = 0;
    for (const auto& [id, s] : series) {
      const MigrationSummary m = summarize_migration(s);
      out << "    {\"solid\": " << id << ", \"t_rev\": " << json_number(m.t_rev) << ", \"t_cen\": " << json_number(m.t_cen)
          << ", \"T_osc\": " << json_number(m.T_osc) << ", \"oscillation_peaks\": " << m.oscillation_peaks
          << ", \"initial_r_over_R\": " << format_number(m.initial_r_over_R)
          << ", \"final_r_over_R\": " << format_number(m.final_r_over_R) << ", \"t_end\": " << format_number(s.t.back())
          << "}" << (++k < series.size() ? "," : "") << "\n";
    }
    out << "  ]";
    // the first body's numbers at top level too: the common single-particle case reads them directly
    if (!series.empty()) {
      const MigrationSummary m = summarize_migration(series.begin()->second);
      out << ",\n  \"t_rev\": " << json_number(m.t_rev) << ",\n  \"t_cen\": " << json_number(m.t_cen)
          << ",\n  \"T_osc\": " << json_number(m.T_osc) << ",\n  \"final_r_over_R\": " << format_number(m.final_r_over_R);
    }
    out << "\n}\n";
    if (!out) throw std::runtime_error("cannot write '" + tmp + "'");
  }
  std::rename(tmp.c_str(), json_path.c_str());
}

}  // namespace eulerfsi

#include "solid/migration_summary.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"

namespace eulerfsi {

namespace {

// Integral of the piecewise-linear f from t[0] to x (x within the series), by trapezoids.
double integral_to(const std::vector<double>& t, const std::vector<double>& f, const std::vector<double>& cum,
                   double x) {
  const size_t n = t.size();
  if (x <= t.front()) return 0.0;
  if (x >= t.back()) return cum.back();
  size_t i = size_t(std::upper_bound(t.begin(), t.end(), x) - t.begin()) - 1;
  if (i + 1 >= n) return cum.back();
  const double h = t[i + 1] - t[i], s = h > 0.0 ? (x - t[i]) / h : 0.0;
  const double fx = f[i] + s * (f[i + 1] - f[i]);
  return cum[i] + 0.5 * (f[i] + fx) * (x - t[i]);
}

// r/R over [a, b]: the dominant period of what its least-squares line leaves (see the header).
std::optional<double> dominant_period(const MigrationSeries& s, double a, double b, double& amplitude) {
  amplitude = 0.0;
  std::vector<double> tw, rw;
  for (size_t i = 0; i < s.t.size(); ++i)
    if (s.t[i] >= a && s.t[i] <= b) {
      tw.push_back(s.t[i]);
      rw.push_back(s.r_over_R[i]);
    }
  const size_t m = std::min<size_t>(tw.size(), 4096);
  if (m < 32 || tw.back() <= tw.front()) return std::nullopt;
  const double t0 = tw.front(), span = tw.back() - t0;
  std::vector<double> r(m);
  for (size_t k = 0; k < m; ++k) {  // uniform resampling (rows are every few steps, dt varies)
    const double x = t0 + span * double(k) / double(m - 1);
    size_t i = size_t(std::upper_bound(tw.begin(), tw.end(), x) - tw.begin());
    i = std::min(std::max<size_t>(i, 1), tw.size() - 1);
    const double h = tw[i] - tw[i - 1], w = h > 0.0 ? (x - tw[i - 1]) / h : 0.0;
    r[k] = rw[i - 1] + w * (rw[i] - rw[i - 1]);
  }
  // the migration's trend removed: the running mean over a third of the window (a sine of period
  // T passes with gain 1 - sinc(w / T), over 0.78 for T < w / 1.5, the periods searched below)
  std::vector<double> tk(m);
  for (size_t k = 0; k < m; ++k) tk[k] = t0 + span * double(k) / double(m - 1);
  const double trend_width = span / 3.0;
  const std::vector<double> trend = running_mean(tk, r, trend_width);
  for (size_t k = 0; k < m; ++k)
    r[k] = (r[k] - trend[k]) * 0.5 * (1.0 - std::cos(2.0 * M_PI * double(k) / double(m - 1)));
  // periodogram at periods span / q, from span / 4.5 (= trend width / 1.5) down to two rows
  const size_t qmax = m / 2, qmin = 5;
  std::vector<double> power(qmax + 1, 0.0);
  for (size_t q = qmin; q <= qmax; ++q) {
    double c = 0.0, sn = 0.0;
    for (size_t k = 0; k < m; ++k) {
      const double ph = 2.0 * M_PI * double(q) * double(k) / double(m - 1);
      c += r[k] * std::cos(ph);
      sn += r[k] * std::sin(ph);
    }
    power[q] = c * c + sn * sn;
  }
  size_t best = qmin, others = 0;
  double rest = 0.0;
  for (size_t q = qmin; q <= qmax; ++q)
    if (power[q] > power[best]) best = q;
  for (size_t q = qmin; q <= qmax; ++q)
    if (q + 1 < best || q > best + 1) rest += power[q], ++others;
  if (others == 0 || power[best] < kPeakContrast * rest / double(others)) return std::nullopt;
  // the Hann window halves the mean amplitude: |sum| = A m / 4 for a sine of amplitude A
  amplitude = 4.0 * std::sqrt(power[best]) / double(m);
  if (amplitude < kMinAmplitude) return std::nullopt;
  // the peak between bins: parabola through the log powers of the bins around it
  double q = double(best);
  if (best > qmin && best < qmax && power[best - 1] > 0 && power[best + 1] > 0) {
    const double l = std::log(power[best - 1]), c = std::log(power[best]), rr = std::log(power[best + 1]);
    const double den = l - 2.0 * c + rr;
    if (den < 0.0) q += 0.5 * (l - rr) / den;
  }
  return span / q;
}

}  // namespace

std::vector<double> running_mean(const std::vector<double>& t, const std::vector<double>& f, double width) {
  const size_t n = t.size();
  std::vector<double> cum(n, 0.0), out(n, 0.0);
  for (size_t i = 1; i < n; ++i) cum[i] = cum[i - 1] + 0.5 * (f[i] + f[i - 1]) * (t[i] - t[i - 1]);
  for (size_t i = 0; i < n; ++i) {
    const double lo = std::max(t.front(), t[i] - 0.5 * width), hi = std::min(t.back(), t[i] + 0.5 * width);
    out[i] = hi > lo ? (integral_to(t, f, cum, hi) - integral_to(t, f, cum, lo)) / (hi - lo) : f[i];
  }
  return out;
}

MigrationSummary summarize_migration(const MigrationSeries& s, double threshold) {
  MigrationSummary out;
  const size_t n = s.t.size();
  if (n == 0) return out;
  out.initial_r_over_R = s.r_over_R.front();
  out.final_r_over_R = s.r_over_R.back();
  // t_rev: the first zero crossing of the filtered F_r from one filter width after the release (the
  // windows from then on no longer reach the first half width, where the release transient is) to
  // half a width before the end (where the window is cut short)
  const std::vector<double> fr = running_mean(s.t, s.force_r, kForceFilterWidth);
  const double from = s.t.front() + kForceFilterWidth, to = s.t.back() - 0.5 * kForceFilterWidth;
  for (size_t i = 1; i < n; ++i) {
    if (s.t[i - 1] < from || s.t[i] > to) continue;
    const double a = fr[i - 1], b = fr[i];
    if (a > 0.0 && b <= 0.0) {  // outwards -> inwards, as the paper's F_r turns
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
  // T_osc over the first half of the migration, from the first reversal on
  const double t_half = 0.5 * (out.t_cen ? *out.t_cen : s.t.back());
  const double start = out.t_rev ? *out.t_rev : s.t.front() + kForceFilterWidth;
  if (t_half > start) out.T_osc = dominant_period(s, start, t_half, out.oscillation_amplitude);
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
        << "  \"t_rev_definition\": \"first change of F_r (the force that changes the radial momentum P_r) from outwards to inwards "
           "after a running mean over " << format_number(kForceFilterWidth) << " D/U_b\",\n"
        << "  \"t_cen_definition\": \"first time r/R < t_cen_threshold holding to the end of the run\",\n"
        << "  \"T_osc_definition\": \"dominant period of r/R (running mean over a third of the window removed) over [t_rev, t_cen/2] "
           "(or t_end/2); null without a clear periodogram peak\",\n"
        << "  \"solids\": [\n";
    size_t k = 0;
    for (const auto& [id, s] : series) {
      const MigrationSummary m = summarize_migration(s);
      out << "    {\"solid\": " << id << ", \"t_rev\": " << json_number(m.t_rev) << ", \"t_cen\": " << json_number(m.t_cen)
          << ", \"T_osc\": " << json_number(m.T_osc)
          << ", \"oscillation_amplitude\": " << format_number(m.oscillation_amplitude)
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

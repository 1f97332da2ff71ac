#include "app/restart.hpp"

#ifdef EULERFSI_HAVE_HDF5
#include <hdf5.h>
#endif

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"

namespace eulerfsi {

namespace fs = std::filesystem;

namespace {

// "section.key" -> value text of the canonical TOML that to_toml writes ([[solid]] numbered).
std::map<std::string, std::string> flatten(const CaseConfig& cfg) {
  std::map<std::string, std::string> out;
  std::istringstream in(to_toml(cfg));
  std::string line, section;
  int solid = -1;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("[[solid]]", 0) == 0) {
      section = "solid[" + std::to_string(++solid) + "]";
    } else if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
    } else if (const auto eq = line.find('='); eq != std::string::npos) {
      auto trim = [](std::string s) {
        s.erase(0, s.find_first_not_of(" \t"));
        s.erase(s.find_last_not_of(" \t") + 1);
        return s;
      };
      out[section + "." + trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
    }
  }
  return out;
}

// The moving frame is numerics, not physics: a restart may change it (the state is shifted).
bool physical(const std::string& key) {
  if (key == "flow.frame_velocity") return false;
  return key.rfind("domain.", 0) == 0 || key.rfind("flow.", 0) == 0 || key.rfind("solid[", 0) == 0;
}

}  // namespace

std::vector<std::string> differing_physical_keys(const CaseConfig& before, const CaseConfig& now) {
  const auto a = flatten(before), b = flatten(now);
  std::vector<std::string> keys;
  for (const auto& [k, v] : a)
    if (physical(k) && (!b.count(k) || b.at(k) != v)) keys.push_back(k + " (" + v + " -> " + (b.count(k) ? b.at(k) : "absent") + ")");
  for (const auto& [k, v] : b)
    if (physical(k) && !a.count(k)) keys.push_back(k + " (absent -> " + v + ")");
  return keys;
}

bool truncate_series_after(const std::string& csv_path, long step, const std::vector<std::string>& columns) {
  std::ifstream in(csv_path);
  if (!in) return false;
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> kept;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const long s = std::strtol(line.c_str(), nullptr, 10);
    // a row torn by a crash has fewer fields than the header: dropped with the rest
    const auto fields = std::count(line.begin(), line.end(), ',');
    if (s <= step && fields == std::count(header.begin(), header.end(), ',')) kept.push_back(line);
  }
  in.close();
  std::string new_header = header;
  const bool relabel = !columns.empty() && header != csv_header(columns);
  if (relabel) {
    // written by another version with other columns: the rows again under this version's, by name
    const std::vector<std::string> old_cols = split_csv_line(header);
    std::vector<int> from(columns.size(), -1);
    for (size_t c = 0; c < columns.size(); ++c)
      for (size_t o = 0; o < old_cols.size(); ++o)
        if (old_cols[o] == columns[c]) from[c] = int(o);
    new_header = csv_header(columns);
    for (auto& row : kept) {
      const std::vector<std::string> v = split_csv_line(row);
      std::string r;
      for (size_t c = 0; c < columns.size(); ++c) r += (c ? "," : "") + (from[c] >= 0 ? v[size_t(from[c])] : "nan");
      row = r;
    }
    fs::copy_file(csv_path, csv_path + ".before-restart", fs::copy_options::overwrite_existing);
  }
  const std::string tmp = csv_path + ".tmp";
  {
    std::ofstream out(tmp);
    out << new_header << "\n";
    for (const auto& row : kept) out << row << "\n";
    if (!out) throw std::runtime_error("cannot rewrite '" + csv_path + "' for the restart");
  }
  fs::rename(tmp, csv_path);
  return relabel;
}

std::vector<Snapshot> field_history_until(const std::string& run_dir, long step) {
  std::vector<Snapshot> out;
  const fs::path dir = fs::path(run_dir) / "fields";
  if (!fs::is_directory(dir)) return out;
#ifndef EULERFSI_HAVE_HDF5
  return out;  // no snapshots without HDF5 (output.fields_every is refused)
#else
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".h5" || name.size() != 11) continue;
    const long s = std::strtol(name.c_str(), nullptr, 10);
    if (s > step) continue;
    const hid_t f = H5Fopen(entry.path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) continue;  // a snapshot torn by a crash is left out of the index
    double t = 0.0, x_offset = 0.0;
    const hid_t a = H5Aopen(f, "time", H5P_DEFAULT);
    if (a >= 0) {
      H5Aread(a, H5T_NATIVE_DOUBLE, &t);
      H5Aclose(a);
      if (H5Aexists(f, "frame_x") > 0) {
        const hid_t x = H5Aopen(f, "frame_x", H5P_DEFAULT);
        H5Aread(x, H5T_NATIVE_DOUBLE, &x_offset);
        H5Aclose(x);
      }
      out.push_back({s, t, x_offset});
    }
    H5Fclose(f);
  }
#endif
  std::sort(out.begin(), out.end(), [](const Snapshot& a, const Snapshot& b) { return a.step < b.step; });
  return out;
}

}  // namespace eulerfsi

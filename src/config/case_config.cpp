// Case-file reading: toml++ is header-only and heavy, so it is included here and nowhere else.
#include "config/case_config.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <toml++/toml.h>
#include <utility>

namespace eulerfsi {

namespace {

// ---------------------------------------------------------------- schema

struct Section {
  const char* name;
  std::vector<std::string> keys;
};

// Order here is the order of to_toml() and of the "known keys" lists in messages.
const std::vector<Section>& schema() {
  static const std::vector<Section> s{
      {"domain", {"length", "cells", "geometry"}},
      {"flow", {"Re", "bulk_velocity", "wall_velocity", "wall_frequency", "initial", "penalization_eta", "pipe_wall",
                "frame_velocity"}},
      {"time", {"cfl", "dt", "t_end", "max_steps", "implicit_viscosity"}},
      {"solver", {"fft_planning", "reproject_constrained"}},
      {"output", {"dir", "every", "fields_every", "profiles_every", "checkpoint_every", "shape_times"}},
      {"solid", {"shape", "diameter", "center", "thickness", "We", "viscosity_ratio", "initial_velocity", "sharpening", "model", "map_margin", "map_ramp", "map_relax_time", "map_ramp_in_extension", "map_smooth_band", "b_extension", "constraint"}},
  };
  return s;
}

const std::vector<std::string>& section_keys(const std::string& section) {
  for (const auto& s : schema())
    if (section == s.name) return s.keys;
  static const std::vector<std::string> none;
  return none;
}

const std::vector<std::pair<const char*, Geometry>> kGeometries{{"pipe", Geometry::Pipe},
                                                                {"duct", Geometry::Duct},
                                                                {"channel", Geometry::Channel},
                                                                {"couette", Geometry::Couette},
                                                                {"periodic", Geometry::Periodic}};
const std::vector<std::pair<const char*, InitialFlow>> kInitialFlows{
    {"laminar", InitialFlow::Laminar}, {"rest", InitialFlow::Rest}, {"taylor-green", InitialFlow::TaylorGreen}};
const std::vector<std::pair<const char*, PipeWall>> kPipeWalls{{"sharp", PipeWall::Sharp},
                                                               {"interpolated", PipeWall::Interpolated}};
const std::vector<std::pair<const char*, SolidShape>> kShapes{{"sphere", SolidShape::Sphere},
                                                              {"layer", SolidShape::Layer}};
const std::vector<std::pair<const char*, InitialSolidVelocity>> kSolidVelocities{
    {"rest", InitialSolidVelocity::Rest}, {"fluid", InitialSolidVelocity::Fluid}};

const std::vector<std::pair<const char*, SolidModelKind>> kSolidModels{
    {"paper", SolidModelKind::Paper}, {"reference-map", SolidModelKind::ReferenceMap}, {"rigid", SolidModelKind::Rigid}};
const std::vector<std::pair<const char*, SolidConstraint>> kSolidConstraints{
    {"none", SolidConstraint::None}, {"fixed", SolidConstraint::Fixed}, {"radial", SolidConstraint::Radial}};

// only what a case file may ask for: WisdomOnly is for checking stored wisdom
const std::vector<std::pair<const char*, FftPlanning>> kFftPlannings{{"estimate", FftPlanning::Estimate},
                                                                    {"measure", FftPlanning::Measure}};

template <class E>
const char* spelling(const std::vector<std::pair<const char*, E>>& table, E e) {
  for (const auto& [name, value] : table)
    if (value == e) return name;
  return "?";
}

// ---------------------------------------------------------------- text helpers

// Shortest text that reads back to the same double; always a TOML float (has '.', 'e' or is inf/nan).
std::string fmt_double(double x) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof(buf), x);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// A derived quantity (a distance, a reach) in messages: 6 digits, not the round-off tail.
std::string fmt_derived(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", x);
  return buf;
}

// A TOML basic string: double quotes, with backslash escapes for quotes and control characters.
std::string toml_str(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

// A value as the user would write it (double-quoted strings, shortest floats), for messages.
std::string show(const toml::node& n) {
  if (n.is_table()) return "a table";
  if (const auto* a = n.as_array()) {
    std::string s = "[";
    for (std::size_t i = 0; i < a->size(); ++i) s += (i ? ", " : "") + show(*a->get(i));
    return s + "]";
  }
  if (const auto* v = n.as_string()) return toml_str(v->get());
  if (const auto* v = n.as_floating_point()) return fmt_double(v->get());
  if (const auto* v = n.as_integer()) return std::to_string(v->get());
  std::ostringstream os;
  n.visit([&os](auto&& v) { os << v; });
  return os.str();
}

// The node's TOML type with its article: "an integer", "a string".
std::string type_name(const toml::node& n) {
  std::ostringstream os;
  os << n.type();
  const std::string t = os.str();
  return (std::string("aeiou").find(t.empty() ? 'x' : t[0]) != std::string::npos ? "an " : "a ") + t;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Optimal-string-alignment distance: a swapped pair of letters counts as one typo.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// Closest of `candidates` to `name`: a typo within distance 2, or a known key the name starts with
// ("Reynolds" -> "Re"); empty when nothing is close enough to be a useful hint.
std::string closest(const std::string& name, const std::vector<std::string>& candidates) {
  const std::string l = lower(name);
  std::string best;
  std::size_t best_d = 3;
  for (const auto& c : candidates) {
    const std::string lc = lower(c);
    std::size_t d = edit_distance(l, lc);
    if (d >= std::min(l.size(), lc.size())) d = 3;  // "dt" vs "Re" is distance 2 but no hint
    if (lc.size() >= 2 && (l.rfind(lc, 0) == 0 || (l.size() >= 3 && lc.rfind(l, 0) == 0))) d = std::min<std::size_t>(d, 2);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// ---------------------------------------------------------------- overrides

struct Segment {
  std::string name;
  std::optional<std::size_t> index;  // solid[0]
};

struct Override {
  std::string text;                 // as given, for messages
  std::string key;                  // canonical: flow.Re, solid[0].We
  std::vector<Segment> path;
  toml::table holder;               // owns the parsed value under "v"
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

[[noreturn]] void bad_override(const std::string& text, const std::string& why) {
  throw ConfigError("--set '" + text + "': " + why);
}

Override parse_override(const std::string& text) {
  Override ov;
  ov.text = text;
  const auto eq = text.find('=');
  if (eq == std::string::npos) bad_override(text, "expected section.key=value, e.g. flow.Re=200");
  const std::string lhs = trim(text.substr(0, eq));
  const std::string rhs = trim(text.substr(eq + 1));
  if (lhs.empty()) bad_override(text, "no key before '=' (expected section.key=value)");
  if (rhs.empty()) bad_override(text, "no value after '='");

  std::stringstream ss(lhs);
  std::string part;
  while (std::getline(ss, part, '.')) {
    Segment seg;
    const auto br = part.find('[');
    seg.name = part.substr(0, br);
    const bool name_ok = !seg.name.empty() && std::all_of(seg.name.begin(), seg.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (!name_ok) bad_override(text, "'" + part + "' is not a key name (expected section.key=value)");
    if (br != std::string::npos) {
      const std::string idx = part.substr(br + 1);
      if (idx.size() < 2 || idx.back() != ']' ||
          !std::all_of(idx.begin(), idx.end() - 1, [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
        bad_override(text, "'" + part + "' has a malformed index (expected e.g. solid[0])");
      seg.index = std::stoul(idx.substr(0, idx.size() - 1));
    }
    ov.key += (ov.key.empty() ? "" : ".") + seg.name + (seg.index ? "[" + std::to_string(*seg.index) + "]" : "");
    ov.path.push_back(seg);
  }
  if (ov.path.empty() || lhs.back() == '.') bad_override(text, "expected section.key=value, e.g. flow.Re=200");
  if (ov.path.back().index) bad_override(text, "must end in a key, e.g. solid[0].We=4");

  // The value is TOML; a bare word that is not (runs/x, pipe) is taken as a string.
  try {
    const std::string doc = "v = " + rhs;
    ov.holder = toml::parse(std::string_view(doc), std::string_view("--set"));
    if (ov.holder.size() != 1) bad_override(text, "the value must be a single TOML value");
  } catch (const toml::parse_error& e) {
    if (std::string("[{\"'").find(rhs.front()) != std::string::npos)
      bad_override(text, "value is not valid TOML: " + std::string(e.description()));
    ov.holder = toml::table{};
    ov.holder.insert("v", rhs);
  }
  return ov;
}

void apply_override(toml::table& root, const Override& ov) {
  toml::table* t = &root;
  std::string where;
  for (std::size_t i = 0; i + 1 < ov.path.size(); ++i) {
    const Segment& seg = ov.path[i];
    where += (where.empty() ? "" : ".") + seg.name;
    toml::node* n = t->get(seg.name);
    if (seg.index) {
      if (!n) n = t->insert(seg.name, toml::array{}).first->second.as_array();
      toml::array* arr = n ? n->as_array() : nullptr;
      if (!arr) bad_override(ov.text, where + " is not an array of tables");
      // one past the end appends, so a solid can be added from the command line
      if (*seg.index == arr->size()) arr->push_back(toml::table{});
      if (*seg.index > arr->size())
        bad_override(ov.text, where + " has " + std::to_string(arr->size()) + " entries; index " +
                                  std::to_string(*seg.index) + " is past the end (at most " +
                                  std::to_string(arr->size()) + " appends one)");
      where += "[" + std::to_string(*seg.index) + "]";
      t = (*arr)[*seg.index].as_table();
      if (!t) bad_override(ov.text, where + " is not a table");
    } else {
      if (!n) n = t->insert(seg.name, toml::table{}).first->second.as_table();
      t = n->as_table();
      if (!t) bad_override(ov.text, where + " is " + type_name(*n) + ", not a table");
    }
  }
  t->insert_or_assign(ov.path.back().name, *ov.holder.get("v"));
}

// ---------------------------------------------------------------- validation

class Reader {
 public:
  Reader(std::string file, const std::vector<Override>& overrides) : file_(std::move(file)) {
    for (const auto& ov : overrides) overrides_.emplace_back(ov.key, ov.text);
  }

  [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
    throw ConfigError(prefix(key) + msg);
  }
  [[noreturn]] void fail_value(const std::string& key, const toml::node& n, const std::string& allowed) const {
    fail(key, key + " = " + show(n) + ": " + allowed);
  }

  // Unknown keys first, so a typo is reported as such rather than as a missing value.
  void check_keys(const toml::table& t, const std::string& scope, const std::string& section) const {
    const auto& known = section_keys(section);
    for (const auto& [k, v] : t) {
      const std::string name(k.str());
      if (std::find(known.begin(), known.end(), name) != known.end()) continue;
      std::string hint = closest(name, known);
      if (!hint.empty()) hint = " (did you mean " + scope + "." + hint + "?)";
      else hint = elsewhere(name, section);
      const std::string header = section == "solid" ? "[[solid]]" : "[" + section + "]";
      fail(scope + "." + name, "unknown key " + scope + "." + name + hint + "; known keys in " + header + ": " +
                                   join(known));
    }
  }

  void check_sections(const toml::table& root) const {
    std::vector<std::string> names;
    std::vector<std::string> headers;
    for (const auto& s : schema()) {
      names.emplace_back(s.name);
      headers.push_back(names.back() == "solid" ? "[[solid]]" : "[" + names.back() + "]");
    }
    for (const auto& [k, v] : root) {
      const std::string name(k.str());
      if (std::find(names.begin(), names.end(), name) != names.end()) continue;
      std::string hint = closest(name, names);
      if (!hint.empty()) hint = " (did you mean [" + std::string(hint == "solid" ? "[solid]" : hint) + "]?)";
      else hint = elsewhere(name, "");
      const std::string what = v.is_table()                ? "unknown section [" + name + "]"
                               : v.is_array_of_tables() ? "unknown section [[" + name + "]]"
                                                        : "unknown top-level key " + name;
      fail(name, what + hint + "; known sections: " + join(headers));
    }
  }

  const toml::table* section(const toml::table& root, const std::string& name) const {
    const toml::node* n = root.get(name);
    if (!n) return nullptr;
    if (!n->is_table()) fail_value(name, *n, "must be a section [" + name + "], not " + type_name(*n));
    check_keys(*n->as_table(), name, name);
    return n->as_table();
  }

  double number(const toml::node& n, const std::string& key) const {
    double x = 0;
    if (const auto* f = n.as_floating_point()) x = f->get();
    else if (const auto* i = n.as_integer()) x = static_cast<double>(i->get());
    else fail_value(key, n, "expected a number, got " + type_name(n));
    if (!std::isfinite(x)) fail_value(key, n, "must be a finite number");
    return x;
  }

  long integer(const toml::node& n, const std::string& key) const {
    if (const auto* i = n.as_integer()) return static_cast<long>(i->get());
    fail_value(key, n, "expected an integer, got " + type_name(n));
  }

  std::vector<double> numbers(const toml::node& n, const std::string& key, std::size_t size, bool fixed) const {
    const auto* arr = n.as_array();
    if (!arr) fail_value(key, n, "expected an array of numbers, got " + type_name(n));
    if (fixed && arr->size() != size)
      fail_value(key, n, "expected " + std::to_string(size) + " numbers, got " + std::to_string(arr->size()));
    std::vector<double> out;
    for (std::size_t i = 0; i < arr->size(); ++i) out.push_back(number(*arr->get(i), key + "[" + std::to_string(i) + "]"));
    return out;
  }

  template <class E>
  E choice(const toml::node& n, const std::string& key, const std::vector<std::pair<const char*, E>>& table) const {
    std::vector<std::string> names, shown;
    for (const auto& [name, e] : table) names.emplace_back(name), shown.push_back(toml_str(name));
    const auto* s = n.as_string();
    if (!s) fail_value(key, n, "expected a string, one of " + join(shown));
    for (const auto& [name, e] : table)
      if (s->get() == name) return e;
    std::string hint = closest(s->get(), names);
    fail_value(key, n, "must be one of " + join(shown) + (hint.empty() ? "" : " (did you mean " + toml_str(hint) + "?)"));
  }

  // Typed getters: leave `out` at its default when the key is absent; report presence.
  bool get(const toml::table* t, const std::string& scope, const char* k, double& out) const {
    if (const toml::node* n = t ? t->get(k) : nullptr) return out = number(*n, scope + "." + k), true;
    return false;
  }
  bool get(const toml::table* t, const std::string& scope, const char* k, bool& out) const {
    const toml::node* n = t ? t->get(k) : nullptr;
    if (!n) return false;
    const auto* b = n->as_boolean();
    if (!b) fail_value(scope + "." + k, *n, "expected true or false, got " + type_name(*n));
    out = b->get();
    return true;
  }
  bool get(const toml::table* t, const std::string& scope, const char* k, long& out) const {
    if (const toml::node* n = t ? t->get(k) : nullptr) return out = integer(*n, scope + "." + k), true;
    return false;
  }
  template <std::size_t N>
  bool get(const toml::table* t, const std::string& scope, const char* k, std::array<double, N>& out) const {
    const toml::node* n = t ? t->get(k) : nullptr;
    if (!n) return false;
    const auto v = numbers(*n, scope + "." + k, N, true);
    std::copy(v.begin(), v.end(), out.begin());
    return true;
  }
  template <class E>
  bool get(const toml::table* t, const std::string& scope, const char* k, E& out,
           const std::vector<std::pair<const char*, E>>& table) const {
    if (const toml::node* n = t ? t->get(k) : nullptr) return out = choice(*n, scope + "." + k, table), true;
    return false;
  }

  // Range check on a key that was read; the message shows the value as written.
  void require(bool ok, const toml::table* t, const std::string& scope, const char* k, const std::string& allowed) const {
    if (ok) return;
    const toml::node* n = t ? t->get(k) : nullptr;
    if (n) fail_value(scope + "." + k, *n, allowed);
    fail(scope + "." + k, scope + "." + k + " (default): " + allowed);
  }

 private:
  // A key put in the wrong section ("Re" at top level or in [time]) points to where it belongs.
  std::string elsewhere(const std::string& name, const std::string& section) const {
    for (const auto& s : schema()) {
      if (section == s.name) continue;
      for (const auto& k : s.keys)
        if (lower(k) == lower(name))
          return std::string(" (did you mean ") + (std::string(s.name) == "solid" ? "solid[i]" : s.name) + "." + k + "?)";
    }
    return {};
  }

  std::string prefix(const std::string& key) const {
    std::string p = file_;
    auto related = [](const std::string& a, const std::string& b) {
      return a.size() <= b.size() && b.compare(0, a.size(), a) == 0 &&
             (a.size() == b.size() || b[a.size()] == '.' || b[a.size()] == '[');
    };
    for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it)
      if (related(it->first, key) || related(key, it->first)) {
        p += " (--set " + it->second + ")";
        break;
      }
    return p + ": ";
  }

  std::string file_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // canonical key, text
};

void read_domain(const Reader& r, const toml::table& root, DomainConfig& d) {
  const toml::table* t = r.section(root, "domain");
  if (r.get(t, "domain", "length", d.length))
    for (std::size_t i = 0; i < 3; ++i)
      if (!(d.length[i] > 0))
        r.fail_value("domain.length[" + std::to_string(i) + "]", *t->get("length")->as_array()->get(i), "must be > 0");
  if (const toml::node* n = t ? t->get("cells") : nullptr) {
    const auto* arr = n->as_array();
    if (!arr || arr->size() != 3)
      r.fail_value("domain.cells", *n, "expected an array of 3 integers [Nx, Ny, Nz]");
    for (int i = 0; i < 3; ++i) {
      const std::string key = "domain.cells[" + std::to_string(i) + "]";
      const long c = r.integer(*arr->get(i), key);
      // the ghost width and the wall closures need at least 4 cells in every direction
      if (c < 4 || c > INT_MAX) r.fail_value(key, *arr->get(i), "must be an integer >= 4");
      d.cells[i] = static_cast<int>(c);
    }
  }
  r.get(t, "domain", "geometry", d.geometry, kGeometries);
  if (d.geometry == Geometry::Pipe &&
      (std::abs(d.length[1] - 1.0) >= 1e-12 || std::abs(d.length[2] - 1.0) >= 1e-12)) {
    const std::string v = "[" + fmt_double(d.length[0]) + ", " + fmt_double(d.length[1]) + ", " +
                          fmt_double(d.length[2]) + "]";
    r.fail("domain.length", "domain.length = " + v +
                                ": geometry \"pipe\" needs Ly = Lz = 1 (the pipe of diameter 1 is carved from the "
                                "unit square duct)");
  }
}

void read_flow(const Reader& r, const toml::table& root, const DomainConfig& d, FlowConfig& f) {
  const toml::table* t = r.section(root, "flow");
  const std::string geo = toml_str(to_string(d.geometry));
  r.get(t, "flow", "Re", f.Re);
  r.require(f.Re > 0, t, "flow", "Re", "must be > 0");
  const bool has_bulk = r.get(t, "flow", "bulk_velocity", f.bulk_velocity);
  // Couette flow is driven by the walls: a flow rate would be ignored. A periodic box has one only
  // if it is given (the mean u over the box, held by a uniform pressure gradient along x).
  if (has_bulk && d.geometry == Geometry::Couette)
    r.fail_value("flow.bulk_velocity", *t->get("bulk_velocity"),
                 "not allowed with domain.geometry = " + geo + " (only pipe, duct, channel and periodic have a flow rate)");
  f.periodic_flow_rate = has_bulk && d.geometry == Geometry::Periodic;
  r.get(t, "flow", "wall_velocity", f.wall_velocity);
  if (d.geometry != Geometry::Couette && (f.wall_velocity[0] != 0 || f.wall_velocity[1] != 0))
    r.fail_value("flow.wall_velocity", *t->get("wall_velocity"),
                 "moving walls need domain.geometry = \"couette\", not " + geo);
  r.get(t, "flow", "wall_frequency", f.wall_frequency);
  r.require(f.wall_frequency >= 0, t, "flow", "wall_frequency", "must be >= 0");
  const bool has_initial = r.get(t, "flow", "initial", f.initial, kInitialFlows);
  const std::string init_key = has_initial ? "flow.initial = " + show(*t->get("initial"))
                                           : "flow.initial = \"laminar\" (the default)";
  if (d.geometry == Geometry::Periodic && f.initial == InitialFlow::Laminar)
    r.fail("flow.initial", init_key + ": a periodic box has no laminar profile; with domain.geometry = " + geo +
                               " use \"taylor-green\" or \"rest\"");
  if (d.geometry != Geometry::Periodic && f.initial == InitialFlow::TaylorGreen)
    r.fail("flow.initial", init_key + ": \"taylor-green\" needs domain.geometry = \"periodic\", not " + geo);
  r.get(t, "flow", "penalization_eta", f.penalization_eta);
  r.require(f.penalization_eta > 0, t, "flow", "penalization_eta", "must be > 0");
  if (r.get(t, "flow", "pipe_wall", f.pipe_wall, kPipeWalls) && d.geometry != Geometry::Pipe)
    r.fail_value("flow.pipe_wall", *t->get("pipe_wall"),
                 "only domain.geometry = \"pipe\" has a penalized wall, not " + geo);
  if (const toml::node* n = t ? t->get("frame_velocity") : nullptr) {
    if (const auto* s = n->as_string()) {
      if (s->get() != "particle")
        r.fail_value("flow.frame_velocity", *n, "must be a number (the frame's x-velocity) or \"particle\"");
      f.frame_follows_particle = true;
    } else {
      f.frame_velocity = r.number(*n, "flow.frame_velocity");
    }
  }
}

void read_time(const Reader& r, const toml::table& root, TimeConfig& c) {
  const toml::table* t = r.section(root, "time");
  r.get(t, "time", "cfl", c.cfl);
  r.require(c.cfl > 0 && c.cfl <= 1, t, "time", "cfl", "must be in (0, 1]");
  r.get(t, "time", "dt", c.dt);
  r.require(c.dt >= 0, t, "time", "dt", "must be >= 0 (0 means adaptive)");
  r.get(t, "time", "t_end", c.t_end);
  r.require(c.t_end > 0, t, "time", "t_end", "must be > 0");
  r.get(t, "time", "max_steps", c.max_steps);
  r.require(c.max_steps >= 0, t, "time", "max_steps", "must be >= 0 (0 means no limit)");
  r.get(t, "time", "implicit_viscosity", c.implicit_viscosity);
#ifndef EULERFSI_HAVE_MPI
  r.require(!c.implicit_viscosity, t, "time", "implicit_viscosity",
            "must be false in this build: its Helmholtz solve uses FFTW-MPI (configure with -DEULERFSI_ENABLE_MPI=ON)");
#endif
}

void read_solver(const Reader& r, const toml::table& root, SolverConfig& s) {
  const toml::table* t = r.section(root, "solver");
  r.get(t, "solver", "fft_planning", s.fft_planning, kFftPlannings);
  r.get(t, "solver", "reproject_constrained", s.reproject_constrained);
}

void read_output(const Reader& r, const toml::table& root, OutputConfig& o) {
  const toml::table* t = r.section(root, "output");
  if (const toml::node* n = t ? t->get("dir") : nullptr) {
    const auto* s = n->as_string();
    if (!s) r.fail_value("output.dir", *n, "expected a string (a directory path), got " + type_name(*n));
    o.dir = s->get();
    if (o.dir.empty()) r.fail_value("output.dir", *n, "must not be empty");
  }
  r.get(t, "output", "every", o.every);
  r.require(o.every >= 1, t, "output", "every", "must be >= 1");
  for (auto [k, v] : {std::pair<const char*, long*>{"fields_every", &o.fields_every},
                      {"profiles_every", &o.profiles_every},
                      {"checkpoint_every", &o.checkpoint_every}}) {
    r.get(t, "output", k, *v);
    r.require(*v >= 0, t, "output", k, "must be >= 0 (0 means never)");
  }
  if (const toml::node* n = t ? t->get("shape_times") : nullptr) {
    o.shape_times = r.numbers(*n, "output.shape_times", 0, false);
    for (std::size_t i = 0; i < o.shape_times.size(); ++i)
      if (o.shape_times[i] < 0)
        r.fail_value("output.shape_times[" + std::to_string(i) + "]", *n->as_array()->get(i), "must be >= 0");
  }
}

// solid.map_ramp in cells, solid.map_relax_time in the case's time unit
constexpr double kDefaultMapRamp = 0.5, kDefaultMapRelaxTime = 0.05;

}  // namespace

void use_default_map_surface(SolidConfig& solid) {
  solid.map_ramp = kDefaultMapRamp;
  solid.map_relax_time = kDefaultMapRelaxTime;
  solid.map_ramp_in_extension = false;
}

namespace {

void read_solids(const Reader& r, const toml::table& root, const DomainConfig& d, std::vector<SolidConfig>& out) {
  const toml::node* n = root.get("solid");
  if (!n) return;
  const auto* arr = n->as_array();
  if (!arr || !arr->is_array_of_tables())
    r.fail_value("solid", *n, "solids are written as [[solid]] sections (an array of tables), not " + type_name(*n));
  const double Lx = d.length[0], Ly = d.length[1], Lz = d.length[2];
  const std::string geo = toml_str(to_string(d.geometry));
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string s = "solid[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    r.check_keys(*t, s, "solid");
    SolidConfig c;
    // a case file's bodies default to the reference map: right at the resolutions a user can
    // afford (the paper's model needs ~48 cells per diameter and is one key away)
    c.model = SolidModelKind::ReferenceMap;
    r.get(t, s, "shape", c.shape, kShapes);
    // a key of the other shape would be silently ignored, which hides a mistake
    const auto foreign = c.shape == SolidShape::Sphere ? std::vector<const char*>{"thickness"}
                                                       : std::vector<const char*>{"diameter", "center"};
    for (const char* k : foreign)
      if (const toml::node* f = t->get(k))
        r.fail_value(s + "." + k, *f, std::string("not used by ") + s + ".shape = " + toml_str(to_string(c.shape)) +
                                          "; remove it");
    r.get(t, s, "diameter", c.diameter);
    r.require(c.diameter > 0, t, s, "diameter", "must be > 0");
    r.get(t, s, "center", c.center);
    r.get(t, s, "thickness", c.thickness);
    r.require(c.thickness > 0, t, s, "thickness", "must be > 0");
    r.get(t, s, "We", c.We);
    r.require(c.We > 0, t, s, "We", "must be > 0");
    r.get(t, s, "viscosity_ratio", c.viscosity_ratio);
    r.require(c.viscosity_ratio >= 0, t, s, "viscosity_ratio", "must be >= 0");
    r.get(t, s, "sharpening", c.sharpening);
    r.require(c.sharpening >= 0 && c.sharpening <= 0.3, t, s, "sharpening",
              "must be in [0, 0.3] (pseudo-time step in units of h; 0 = off; above h/3 is unstable)");
    r.get(t, s, "initial_velocity", c.initial_velocity, kSolidVelocities);
    r.get(t, s, "model", c.model, kSolidModels);
    // sharpening is a cure for the paper model's smeared psi; the reference map's psi never smears
    if (c.model == SolidModelKind::ReferenceMap && c.sharpening > 0)
      r.fail(s + ".sharpening", s + ".sharpening = " + fmt_double(c.sharpening) +
                                    ": sharpening applies to " + s + ".model = \"paper\" only; the reference map "
                                    "derives a sharp psi from xi (set it to 0 or remove it)");
    r.get(t, s, "map_margin", c.map_margin);
    r.require(c.map_margin >= 0 && c.map_margin <= 1, t, s, "map_margin",
              "must be in [0, 1] (cells inside the surface; 0 = the map carried up to the surface)");
    if (c.model != SolidModelKind::ReferenceMap && c.map_margin > 0)
      r.fail(s + ".map_margin", s + ".map_margin = " + fmt_double(c.map_margin) + ": applies to " + s +
                                    ".model = \"reference-map\" only (set it to 0 or remove it)");
    // a case file's map bodies default to the relaxed surface; no ramp, nothing to relax
    if (c.model == SolidModelKind::ReferenceMap) use_default_map_surface(c);
    r.get(t, s, "map_ramp", c.map_ramp);
    r.require(c.map_ramp >= 0 && c.map_ramp <= 2, t, s, "map_ramp",
              "must be in [0, 2] (cells below the solid's edge over which a cell's weight in the extension rises "
              "to 1; 0 = every solid cell weighs 1)");
    if (c.model != SolidModelKind::ReferenceMap && t->get("map_ramp"))
      r.fail(s + ".map_ramp", s + ".map_ramp = " + fmt_double(c.map_ramp) + ": applies to " + s +
                                  ".model = \"reference-map\" only (remove it)");
    if (!(c.map_ramp > 0)) c.map_relax_time = 0.0;
    r.get(t, s, "map_relax_time", c.map_relax_time);
    r.require(c.map_relax_time >= 0, t, s, "map_relax_time",
              "must be >= 0 (the time over which the surface ramp's cells relax towards the extension's fit; "
              "0 = at once, every substep)");
    if (c.map_relax_time > 0 && (c.model != SolidModelKind::ReferenceMap || !(c.map_ramp > 0)))
      r.fail(s + ".map_relax_time", s + ".map_relax_time = " + fmt_double(c.map_relax_time) + ": relaxes the cells of " +
                                        s + ".map_ramp, so it needs model = \"reference-map\" and map_ramp > 0 "
                                        "(set map_ramp, or remove it)");
    r.get(t, s, "map_ramp_in_extension", c.map_ramp_in_extension);
    // false without a ramp is what a resolved file of a map body with map_ramp = 0 says: allowed
    if (t->get("map_ramp_in_extension") &&
        (c.model != SolidModelKind::ReferenceMap || (c.map_ramp_in_extension && !(c.map_ramp > 0))))
      r.fail(s + ".map_ramp_in_extension", s + ".map_ramp_in_extension = " + (c.map_ramp_in_extension ? "true" : "false") +
                                               ": weighs the cells of " + s + ".map_ramp in the extension, so it needs "
                                               "model = \"reference-map\" and map_ramp > 0 (set map_ramp, or remove it)");
    r.get(t, s, "map_smooth_band", c.map_smooth_band);
    if (c.map_smooth_band && c.model != SolidModelKind::ReferenceMap)
      r.fail(s + ".map_smooth_band", s + ".map_smooth_band = true: fits the reference map's band, so it needs "
                                         "model = \"reference-map\" (remove it)");
    r.get(t, s, "b_extension", c.b_extension);
    // the reference map derives B from xi everywhere it is known: there is no transported B to extend
    if (c.model == SolidModelKind::ReferenceMap && !c.b_extension)
      r.fail(s + ".b_extension", s + ".b_extension = false: applies to " + s +
                                     ".model = \"paper\" only; the reference map derives B from xi (remove it)");

    r.get(t, s, "constraint", c.constraint, kSolidConstraints);
    if (c.model == SolidModelKind::Rigid && c.shape != SolidShape::Sphere)
      r.fail(s + ".model", s + ".model = \"rigid\": a rigid body is a sphere (shape = \"sphere\")");
    if (c.model == SolidModelKind::Rigid && c.sharpening > 0)
      r.fail(s + ".sharpening", s + ".sharpening = " + fmt_double(c.sharpening) + ": applies to " + s +
                                    ".model = \"paper\" only; a rigid body's psi never smears (remove it)");
    // a soft body can be held at its (y, z) by a body force; fixing it whole would fight its deformation
    if (c.model != SolidModelKind::Rigid && c.constraint == SolidConstraint::Fixed)
      r.fail(s + ".constraint", s + ".constraint = \"fixed\": only " + s +
                                    ".model = \"rigid\" can be fixed (a soft body allows \"none\" or \"radial\")");
    if (c.constraint == SolidConstraint::Radial && c.shape != SolidShape::Sphere)
      r.fail(s + ".constraint", s + ".constraint = \"radial\": holds a sphere's centre; a layer has none");

    if (c.shape == SolidShape::Layer) {
      if (d.geometry != Geometry::Channel && d.geometry != Geometry::Couette)
        r.fail(s + ".shape", s + ".shape = \"layer\": a layer spans the walls of a channel; it needs domain.geometry = "
                             "\"channel\" or \"couette\", not " + geo);
      r.require(c.thickness < Ly, t, s, "thickness", "must be < Ly = " + fmt_double(Ly));
    } else {
      const double rad = c.diameter / 2, x = c.center[0], y = c.center[1], z = c.center[2];
      const std::string ctr = s + ".center = [" + fmt_double(x) + ", " + fmt_double(y) + ", " + fmt_double(z) + "]";
      const std::string dia = s + ".diameter = " + fmt_double(c.diameter);
      if (!(x >= 0 && x < Lx)) r.fail(s + ".center", ctr + ": x must be in [0, Lx) = [0, " + fmt_double(Lx) + ")");
      // a periodic direction shorter than the sphere would make it touch its own image
      if (c.diameter >= Lx) r.fail(s + ".diameter", dia + ": must be < Lx = " + fmt_double(Lx));
      switch (d.geometry) {
        case Geometry::Pipe: {
          const double reach = std::hypot(y, z) + rad;
          if (!(reach < 0.5))
            r.fail(s + ".center", s + " leaves the pipe: r + d/2 = " + fmt_derived(reach) + " must be < R = 0.5 (" +
                                      ctr + ", " + dia + ")");
          break;
        }
        case Geometry::Duct:
          if (!(std::abs(y) + rad < Ly / 2 && std::abs(z) + rad < Lz / 2))
            r.fail(s + ".center", s + " leaves the duct: |y| + d/2 = " + fmt_derived(std::abs(y) + rad) +
                                      " and |z| + d/2 = " + fmt_derived(std::abs(z) + rad) + " must be < Ly/2 = " +
                                      fmt_double(Ly / 2) + " and Lz/2 = " + fmt_double(Lz / 2) + " (" + ctr + ", " +
                                      dia + ")");
          break;
        case Geometry::Channel:
        case Geometry::Couette:
          if (!(std::abs(y) + rad < Ly / 2))
            r.fail(s + ".center", s + " leaves the channel: |y| + d/2 = " + fmt_derived(std::abs(y) + rad) +
                                      " must be < Ly/2 = " + fmt_double(Ly / 2) + " (" + ctr + ", " + dia + ")");
          if (c.diameter >= Lz) r.fail(s + ".diameter", dia + ": must be < Lz = " + fmt_double(Lz) + " (z is periodic)");
          break;
        case Geometry::Periodic:
          if (c.diameter >= Ly || c.diameter >= Lz)
            r.fail(s + ".diameter", dia + ": must be < Ly = " + fmt_double(Ly) + " and < Lz = " + fmt_double(Lz) +
                                        " (the box is periodic)");
          break;
      }
      // a sphere less than sqrt(3) cells across can fall between the cell centres and vanish without a
      // word (the map carries no cell, the volume reads 0): 2 cells across at least
      const double h_max = std::max({Lx / d.cells[0], Ly / d.cells[1], Lz / d.cells[2]});
      if (c.diameter < 2 * h_max)
        r.fail(s + ".diameter", dia + " spans " + fmt_derived(c.diameter / h_max) + " cells of the coarsest spacing " +
                                    fmt_derived(h_max) + ": a sphere needs at least 2 cells across (one under sqrt(3) "
                                    "may hold no cell centre); raise domain.cells or the diameter");
    }
    out.push_back(c);
  }

  // Spheres must not overlap; distances use the nearest periodic image in every periodic direction.
  const bool periodic[3] = {true, d.geometry == Geometry::Periodic,
                            d.geometry != Geometry::Pipe && d.geometry != Geometry::Duct};
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t j = i + 1; j < out.size(); ++j) {
      if (out[i].shape != SolidShape::Sphere || out[j].shape != SolidShape::Sphere) continue;
      double dist2 = 0;
      for (int k = 0; k < 3; ++k) {
        double dx = std::abs(out[i].center[k] - out[j].center[k]);
        if (periodic[k]) {
          dx = std::fmod(dx, d.length[k]);
          dx = std::min(dx, d.length[k] - dx);
        }
        dist2 += dx * dx;
      }
      const double dist = std::sqrt(dist2), radii = (out[i].diameter + out[j].diameter) / 2;
      if (dist < radii * (1 - 1e-12)) {  // spheres written exactly one diameter apart may touch
        const std::string a = "solid[" + std::to_string(i) + "]", b = "solid[" + std::to_string(j) + "]";
        r.fail(b + ".center", a + " and " + b + " overlap: centre distance " + fmt_derived(dist) +
                                  " must be >= the sum of radii " + fmt_derived(radii) +
                                  " (x is periodic with Lx = " + fmt_double(Lx) + ")");
      }
    }
}

CaseConfig validate(const toml::table& root, const Reader& r) {
  r.check_sections(root);
  CaseConfig cfg;
  read_domain(r, root, cfg.domain);
  read_flow(r, root, cfg.domain, cfg.flow);
  read_time(r, root, cfg.time);
  read_solver(r, root, cfg.solver);
  read_output(r, root, cfg.output);
  read_solids(r, root, cfg.domain, cfg.solids);
  if (cfg.flow.frame_follows_particle && cfg.solids.empty())
    r.fail("flow.frame_velocity", "flow.frame_velocity = \"particle\": the case has no [[solid]] to follow; give a "
                                  "number or add a solid");
  return cfg;
}

}  // namespace

const char* to_string(Geometry g) { return spelling(kGeometries, g); }
const char* to_string(InitialFlow f) { return spelling(kInitialFlows, f); }
const char* to_string(PipeWall w) { return spelling(kPipeWalls, w); }
const char* to_string(SolidShape s) { return spelling(kShapes, s); }
const char* to_string(InitialSolidVelocity v) { return spelling(kSolidVelocities, v); }
const char* to_string(SolidModelKind m) { return spelling(kSolidModels, m); }
const char* to_string(SolidConstraint c) { return spelling(kSolidConstraints, c); }
const char* to_string(FftPlanning p) { return spelling(kFftPlannings, p); }

CaseConfig parse_case_string(const std::string& toml_text, const std::vector<std::string>& overrides,
                             const std::string& source_name) {
  std::vector<Override> ovs;
  for (const auto& o : overrides) ovs.push_back(parse_override(o));
  toml::table root;
  try {
    root = toml::parse(std::string_view(toml_text), std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    const auto& pos = e.source().begin;
    throw ConfigError(source_name + ": TOML syntax error at line " + std::to_string(pos.line) + ", column " +
                      std::to_string(pos.column) + ": " + std::string(e.description()));
  }
  for (const auto& ov : ovs) apply_override(root, ov);
  CaseConfig cfg = validate(root, Reader(source_name, ovs));
  cfg.source = source_name;
  return cfg;
}

CaseConfig parse_case_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ConfigError("case file '" + path + "' not found");
  if (std::filesystem::is_directory(path, ec)) throw ConfigError("case file '" + path + "' is a directory");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf())) throw ConfigError("case file '" + path + "' cannot be read");
  return parse_case_string(text.str(), overrides, path);
}

std::string to_toml(const CaseConfig& c) {
  std::ostringstream os;
  auto arr = [](const auto& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt_double(v[i]);
    return s + "]";
  };
  os << "# Resolved case" << (c.source.empty() ? "" : " from " + c.source) << ": every key, defaults filled in.\n";
  os << "\n[domain]\n"
     << "length = " << arr(c.domain.length) << "\n"
     << "cells = [" << c.domain.cells[0] << ", " << c.domain.cells[1] << ", " << c.domain.cells[2] << "]\n"
     << "geometry = " << toml_str(to_string(c.domain.geometry)) << "\n";
  os << "\n[flow]\n"
     << "Re = " << fmt_double(c.flow.Re) << "\n";
  // the parser refuses a flow rate for geometries that have none
  if (c.domain.geometry != Geometry::Couette && (c.domain.geometry != Geometry::Periodic || c.flow.periodic_flow_rate))
    os << "bulk_velocity = " << fmt_double(c.flow.bulk_velocity) << "\n";
  os << "wall_velocity = " << arr(c.flow.wall_velocity) << "\n"
     << "wall_frequency = " << fmt_double(c.flow.wall_frequency) << "\n"
     << "initial = " << toml_str(to_string(c.flow.initial)) << "\n"
     << "penalization_eta = " << fmt_double(c.flow.penalization_eta) << "\n";
  if (c.domain.geometry == Geometry::Pipe) os << "pipe_wall = " << toml_str(to_string(c.flow.pipe_wall)) << "\n";
  os << "frame_velocity = " << (c.flow.frame_follows_particle ? std::string("\"particle\"") : fmt_double(c.flow.frame_velocity))
     << "\n";
  os << "\n[time]\n"
     << "cfl = " << fmt_double(c.time.cfl) << "\n"
     << "dt = " << fmt_double(c.time.dt) << "\n"
     << "t_end = " << fmt_double(c.time.t_end) << "\n"
     << "max_steps = " << c.time.max_steps << "\n"
     << "implicit_viscosity = " << (c.time.implicit_viscosity ? "true" : "false") << "\n";
  os << "\n[solver]\n"
     << "fft_planning = " << toml_str(to_string(c.solver.fft_planning)) << "\n"
     << "reproject_constrained = " << (c.solver.reproject_constrained ? "true" : "false") << "\n";
  os << "\n[output]\n"
     << "dir = " << toml_str(c.output.dir) << "\n"
     << "every = " << c.output.every << "\n"
     << "fields_every = " << c.output.fields_every << "\n"
     << "profiles_every = " << c.output.profiles_every << "\n"
     << "checkpoint_every = " << c.output.checkpoint_every << "\n"
     << "shape_times = " << arr(c.output.shape_times) << "\n";
  for (const auto& s : c.solids) {
    os << "\n[[solid]]\n"
       << "shape = " << toml_str(to_string(s.shape)) << "\n";
    // only the keys of this shape: the parser refuses the others
    if (s.shape == SolidShape::Sphere)
      os << "diameter = " << fmt_double(s.diameter) << "\n"
         << "center = " << arr(s.center) << "\n";
    else
      os << "thickness = " << fmt_double(s.thickness) << "\n";
    os << "We = " << fmt_double(s.We) << "\n"
       << "viscosity_ratio = " << fmt_double(s.viscosity_ratio) << "\n"
       << "initial_velocity = " << toml_str(to_string(s.initial_velocity)) << "\n"
       << "sharpening = " << fmt_double(s.sharpening) << "\n"
       << "model = " << toml_str(to_string(s.model)) << "\n"
       << "map_margin = " << fmt_double(s.map_margin) << "\n";
    if (s.model == SolidModelKind::ReferenceMap)
      os << "map_ramp = " << fmt_double(s.map_ramp) << "\n"
         << "map_relax_time = " << fmt_double(s.map_relax_time) << "\n"
         << "map_ramp_in_extension = " << (s.map_ramp_in_extension ? "true" : "false") << "\n"
         << "map_smooth_band = " << (s.map_smooth_band ? "true" : "false") << "\n";
    os << "b_extension = " << (s.b_extension ? "true" : "false") << "\n"
       << "constraint = " << toml_str(to_string(s.constraint)) << "\n";
  }
  return os.str();
}

void check_build_supports(const CaseConfig& cfg) {
#ifndef EULERFSI_HAVE_HDF5
  // snapshots and checkpoints are HDF5 files: refuse them rather than skip them silently
  for (auto [key, every] : {std::pair<const char*, long>{"output.fields_every", cfg.output.fields_every},
                            {"output.checkpoint_every", cfg.output.checkpoint_every}}) {
    if (every != 0) {
      throw ConfigError(cfg.source + ": " + key + " = " + std::to_string(every) +
                        ": must be 0 in this eulerfsi, built without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF): field snapshots "
                        "and checkpoints are HDF5 files; CSV output (output.every, output.profiles_every, "
                        "output.shape_times) works");
    }
  }
#else
  (void)cfg;
#endif
}

}  // namespace eulerfsi

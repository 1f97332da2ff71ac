// Case-file parsing: defaults, every section, --set overrides, the to_toml round trip, and one
// test per validation rule; plus the tests/bad_cases and tests/good_cases corpora.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "config/case_config.hpp"

namespace fs = std::filesystem;
using namespace eulerfsi;

namespace {

// The message of the ConfigError that parsing throws, or a marker the expectations will not match.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_case_string(text, overrides, "t.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "<no error>";
}

// Every substring must appear, and every message names the file it came from.
void expect_error(const std::string& text, const std::vector<std::string>& parts,
                  const std::vector<std::string>& overrides = {}) {
  const std::string msg = error_of(text, overrides);
  EXPECT_EQ(msg.rfind("t.toml", 0), 0u) << "message does not start with the file name: " << msg;
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

void expect_same(const CaseConfig& a, const CaseConfig& b) {
  EXPECT_EQ(a.domain.length, b.domain.length);
  EXPECT_EQ(a.domain.cells, b.domain.cells);
  EXPECT_EQ(a.domain.geometry, b.domain.geometry);
  EXPECT_EQ(a.flow.Re, b.flow.Re);
  EXPECT_EQ(a.flow.bulk_velocity, b.flow.bulk_velocity);
  EXPECT_EQ(a.flow.wall_velocity, b.flow.wall_velocity);
  EXPECT_EQ(a.flow.wall_frequency, b.flow.wall_frequency);
  EXPECT_EQ(a.flow.initial, b.flow.initial);
  EXPECT_EQ(a.flow.penalization_eta, b.flow.penalization_eta);
  EXPECT_EQ(a.flow.pipe_wall, b.flow.pipe_wall);
  EXPECT_EQ(a.time.cfl, b.time.cfl);
  EXPECT_EQ(a.time.dt, b.time.dt);
  EXPECT_EQ(a.time.t_end, b.time.t_end);
  EXPECT_EQ(a.time.max_steps, b.time.max_steps);
  EXPECT_EQ(a.time.implicit_viscosity, b.time.implicit_viscosity);
  EXPECT_EQ(a.solver.fft_planning, b.solver.fft_planning);
  EXPECT_EQ(a.output.dir, b.output.dir);
  EXPECT_EQ(a.output.every, b.output.every);
  EXPECT_EQ(a.output.fields_every, b.output.fields_every);
  EXPECT_EQ(a.output.profiles_every, b.output.profiles_every);
  EXPECT_EQ(a.output.checkpoint_every, b.output.checkpoint_every);
  EXPECT_EQ(a.output.shape_times, b.output.shape_times);
  ASSERT_EQ(a.solids.size(), b.solids.size());
  for (std::size_t i = 0; i < a.solids.size(); ++i) {
    SCOPED_TRACE("solid " + std::to_string(i));
    EXPECT_EQ(a.solids[i].shape, b.solids[i].shape);
    EXPECT_EQ(a.solids[i].diameter, b.solids[i].diameter);
    EXPECT_EQ(a.solids[i].center, b.solids[i].center);
    EXPECT_EQ(a.solids[i].thickness, b.solids[i].thickness);
    EXPECT_EQ(a.solids[i].We, b.solids[i].We);
    EXPECT_EQ(a.solids[i].viscosity_ratio, b.solids[i].viscosity_ratio);
    EXPECT_EQ(a.solids[i].initial_velocity, b.solids[i].initial_velocity);
    EXPECT_EQ(a.solids[i].model, b.solids[i].model);
    EXPECT_EQ(a.solids[i].map_margin, b.solids[i].map_margin);
    EXPECT_EQ(a.solids[i].map_ramp, b.solids[i].map_ramp);
    EXPECT_EQ(a.solids[i].map_relax_time, b.solids[i].map_relax_time);
    EXPECT_EQ(a.solids[i].map_ramp_in_extension, b.solids[i].map_ramp_in_extension);
    EXPECT_EQ(a.solids[i].map_smooth_band, b.solids[i].map_smooth_band);
    EXPECT_EQ(a.solids[i].b_extension, b.solids[i].b_extension);
  }
}

void expect_round_trip(const CaseConfig& cfg) {
  const std::string text = to_toml(cfg);
  SCOPED_TRACE(text);
  CaseConfig back;
  ASSERT_NO_THROW(back = parse_case_string(text));
  expect_same(cfg, back);
}

const char* kFull = R"(
[domain]
length = [4.0, 1, 1.0]
cells = [64, 32, 24]
geometry = "pipe"

[flow]
Re = 250.5
bulk_velocity = 2.0
wall_frequency = 0.5
initial = "rest"
penalization_eta = 1e-6
pipe_wall = "sharp"

[time]
cfl = 0.4
dt = 1e-3
t_end = 5
max_steps = 1000

[output]
dir = "runs/full"
every = 5
fields_every = 50
profiles_every = 20
checkpoint_every = 500
shape_times = [0.0, 1.5, 3]

[[solid]]
shape = "sphere"
diameter = 0.3
center = [1.0, 0.1, -0.05]
We = 2.5
viscosity_ratio = 0.0
initial_velocity = "rest"
b_extension = false
model = "paper"

[[solid]]
center = [3.0, -0.1, 0.1]
model = "reference-map"
map_margin = 0.5
)";

std::string test_data() {
  const char* dir = std::getenv("EULERFSI_TEST_DATA");
  return dir ? dir : "";
}

std::vector<fs::path> toml_files(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

// ---------------------------------------------------------------- parsing

TEST(Config, EmptyFileGivesTheDefaults) {
  const CaseConfig cfg = parse_case_string("");
  expect_same(cfg, CaseConfig{});
  EXPECT_EQ(cfg.source, "<string>");
  EXPECT_TRUE(cfg.solids.empty());
}

// time.implicit_viscosity is read (and written back by the round trip); a build without MPI has
// no transforms for it and refuses it by name.
TEST(Config, ImplicitViscosity) {
#ifdef EULERFSI_HAVE_MPI
  EXPECT_TRUE(parse_case_string("[time]\nimplicit_viscosity = true\n").time.implicit_viscosity);
  const CaseConfig c = parse_case_string("[time]\nimplicit_viscosity = true\n");
  expect_same(parse_case_string(to_toml(c)), c);
#else
  expect_error("[time]\nimplicit_viscosity = true\n", {"time.implicit_viscosity", "EULERFSI_ENABLE_MPI"});
#endif
  EXPECT_FALSE(parse_case_string("").time.implicit_viscosity);
}

TEST(Config, EverySectionIsRead) {
  const CaseConfig c = parse_case_string(kFull, {}, "full.toml");
  EXPECT_EQ(c.source, "full.toml");
  EXPECT_EQ(c.domain.length, (std::array<double, 3>{4.0, 1.0, 1.0}));  // integers read as numbers
  EXPECT_EQ(c.domain.cells, (std::array<int, 3>{64, 32, 24}));
  EXPECT_EQ(c.domain.geometry, Geometry::Pipe);
  EXPECT_EQ(c.flow.Re, 250.5);
  EXPECT_EQ(c.flow.bulk_velocity, 2.0);
  EXPECT_EQ(c.flow.wall_frequency, 0.5);
  EXPECT_EQ(c.flow.initial, InitialFlow::Rest);
  EXPECT_EQ(c.flow.penalization_eta, 1e-6);
  EXPECT_EQ(c.flow.pipe_wall, PipeWall::Sharp);
  EXPECT_EQ(c.time.cfl, 0.4);
  EXPECT_EQ(c.time.dt, 1e-3);
  EXPECT_EQ(c.time.t_end, 5.0);
  EXPECT_EQ(c.time.max_steps, 1000);
  EXPECT_EQ(c.output.dir, "runs/full");
  EXPECT_EQ(c.output.every, 5);
  EXPECT_EQ(c.output.fields_every, 50);
  EXPECT_EQ(c.output.profiles_every, 20);
  EXPECT_EQ(c.output.checkpoint_every, 500);
  EXPECT_EQ(c.output.shape_times, (std::vector<double>{0.0, 1.5, 3.0}));
  ASSERT_EQ(c.solids.size(), 2u);
  EXPECT_EQ(c.solids[0].shape, SolidShape::Sphere);
  EXPECT_EQ(c.solids[0].diameter, 0.3);
  EXPECT_EQ(c.solids[0].center, (std::array<double, 3>{1.0, 0.1, -0.05}));
  EXPECT_EQ(c.solids[0].We, 2.5);
  EXPECT_EQ(c.solids[0].viscosity_ratio, 0.0);
  EXPECT_EQ(c.solids[0].initial_velocity, InitialSolidVelocity::Rest);
  // the second solid takes the defaults for every key it omits
  EXPECT_EQ(c.solids[1].diameter, SolidConfig{}.diameter);
  EXPECT_EQ(c.solids[1].We, SolidConfig{}.We);
  EXPECT_EQ(c.solids[1].initial_velocity, InitialSolidVelocity::Fluid);
  EXPECT_EQ(c.solids[1].map_margin, 0.5);
  EXPECT_EQ(c.solids[0].map_margin, SolidConfig{}.map_margin);
  EXPECT_FALSE(c.solids[0].b_extension);
  EXPECT_TRUE(c.solids[1].b_extension);
  EXPECT_EQ(c.solids[0].model, SolidModelKind::Paper);
}

TEST(Config, CouetteWithLayer) {
  const CaseConfig c = parse_case_string(R"(
[domain]
geometry = "couette"
length = [2, 2, 1]
[flow]
wall_velocity = [-1, 1.5]
initial = "rest"
[[solid]]
shape = "layer"
thickness = 1.0
)");
  EXPECT_EQ(c.domain.geometry, Geometry::Couette);
  EXPECT_EQ(c.flow.wall_velocity, (std::array<double, 2>{-1.0, 1.5}));
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].shape, SolidShape::Layer);
  EXPECT_EQ(c.solids[0].thickness, 1.0);
}

// A case file's body is carried by the reference map unless it says otherwise; a rigid sphere
// takes a constraint, which survives the resolved file's round trip.
TEST(Config, SolidModelsAndConstraints) {
  const CaseConfig c = parse_case_string(R"(
[[solid]]
center = [0.5, 0.1, 0.0]
[[solid]]
center = [2.0, -0.1, 0.0]
model = "rigid"
constraint = "radial"
)");
  ASSERT_EQ(c.solids.size(), 2u);
  EXPECT_EQ(c.solids[0].model, SolidModelKind::ReferenceMap);
  EXPECT_EQ(c.solids[0].constraint, SolidConstraint::None);
  EXPECT_EQ(c.solids[1].model, SolidModelKind::Rigid);
  EXPECT_EQ(c.solids[1].constraint, SolidConstraint::Radial);
  const CaseConfig again = parse_case_string(to_toml(c));
  EXPECT_EQ(again.solids[1].constraint, SolidConstraint::Radial);
  EXPECT_EQ(again.solids[0].model, SolidModelKind::ReferenceMap);
  expect_error("[[solid]]\nconstraint = \"fixed\"\n", {"solid[0].constraint = \"fixed\"", "\"rigid\""});
  // a soft sphere may be held at its radius (a body force), a layer may not
  const CaseConfig held = parse_case_string("[[solid]]\nconstraint = \"radial\"\n");
  EXPECT_EQ(held.solids[0].constraint, SolidConstraint::Radial);
  EXPECT_EQ(parse_case_string(to_toml(held)).solids[0].constraint, SolidConstraint::Radial);
  expect_error("[[solid]]\nmodel = \"rigid\"\nconstraint = \"pinned\"\n",
               {"solid[0].constraint = \"pinned\"", "\"radial\""});
}

// A periodic box is driven only where the case gives a flow rate (Hasimoto's array of fixed spheres).
TEST(Config, PeriodicFlowRateOnlyWhenGiven) {
  const char* box = "[domain]\ngeometry = \"periodic\"\n[flow]\ninitial = \"rest\"\n";
  const CaseConfig still = parse_case_string(box);
  EXPECT_FALSE(still.flow.periodic_flow_rate);
  const CaseConfig driven = parse_case_string(std::string(box) + "bulk_velocity = 0.5\n");
  EXPECT_TRUE(driven.flow.periodic_flow_rate);
  EXPECT_EQ(driven.flow.bulk_velocity, 0.5);
  const CaseConfig again = parse_case_string(to_toml(driven));
  EXPECT_TRUE(again.flow.periodic_flow_rate);
  EXPECT_EQ(again.flow.bulk_velocity, 0.5);
  EXPECT_FALSE(parse_case_string(to_toml(still)).flow.periodic_flow_rate);
}

TEST(Config, Spellings) {
  EXPECT_STREQ(to_string(Geometry::Pipe), "pipe");
  EXPECT_STREQ(to_string(Geometry::Duct), "duct");
  EXPECT_STREQ(to_string(Geometry::Channel), "channel");
  EXPECT_STREQ(to_string(Geometry::Couette), "couette");
  EXPECT_STREQ(to_string(Geometry::Periodic), "periodic");
  EXPECT_STREQ(to_string(InitialFlow::Laminar), "laminar");
  EXPECT_STREQ(to_string(InitialFlow::Rest), "rest");
  EXPECT_STREQ(to_string(InitialFlow::TaylorGreen), "taylor-green");
  EXPECT_STREQ(to_string(SolidShape::Layer), "layer");
  EXPECT_STREQ(to_string(InitialSolidVelocity::Fluid), "fluid");
}

// ---------------------------------------------------------------- overrides

TEST(Config, OverridesReplaceAndAdd) {
  const CaseConfig c = parse_case_string(
      kFull, {"flow.Re=200", "domain.cells=[64,16,16]", "output.dir=\"runs/x\"", "solid[0].We=4",
              " time.max_steps = 7 ", "solid[2].center=[2.0, 0, 0]"});
  EXPECT_EQ(c.flow.Re, 200.0);
  EXPECT_EQ(c.domain.cells, (std::array<int, 3>{64, 16, 16}));
  EXPECT_EQ(c.output.dir, "runs/x");
  EXPECT_EQ(c.solids[0].We, 4.0);
  EXPECT_EQ(c.time.max_steps, 7);
  ASSERT_EQ(c.solids.size(), 3u);  // one past the end appends a solid
  EXPECT_EQ(c.solids[2].center, (std::array<double, 3>{2.0, 0.0, 0.0}));
}

TEST(Config, OverrideCreatesMissingSections) {
  const CaseConfig c = parse_case_string("", {"time.cfl=0.5", "solid[0].diameter=0.25"});
  EXPECT_EQ(c.time.cfl, 0.5);
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].diameter, 0.25);
}

TEST(Config, OverrideBareWordIsAString) {
  const CaseConfig c = parse_case_string("", {"output.dir=runs/x", "domain.geometry=duct", "flow.initial=rest"});
  EXPECT_EQ(c.output.dir, "runs/x");
  EXPECT_EQ(c.domain.geometry, Geometry::Duct);
  EXPECT_EQ(c.flow.initial, InitialFlow::Rest);
}

TEST(Config, OverridesAreValidatedLikeTheFile) {
  expect_error("", {"(--set flow.Re=-1)", "flow.Re = -1", "must be > 0"}, {"flow.Re=-1"});
  expect_error("", {"--set flow.Reynolds=3", "unknown key flow.Reynolds", "did you mean flow.Re?"}, {"flow.Reynolds=3"});
  expect_error("", {"flow.Re = \"abc\"", "expected a number"}, {"flow.Re=abc"});
  expect_error("", {"--set solid[0].center=[0,0.45,0]", "leaves the pipe"}, {"solid[0].center=[0,0.45,0]"});
}

TEST(Config, BadOverrideSyntax) {
  auto msg = [](const std::string& ov) { return error_of("", {ov}); };
  EXPECT_NE(msg("flow.Re").find("--set 'flow.Re': expected section.key=value"), std::string::npos) << msg("flow.Re");
  EXPECT_NE(msg("=3").find("no key"), std::string::npos);
  EXPECT_NE(msg("flow.Re=").find("no value"), std::string::npos);
  EXPECT_NE(msg("flow..Re=1").find("not a key name"), std::string::npos);
  EXPECT_NE(msg("solid[x].We=1").find("malformed index"), std::string::npos);
  EXPECT_NE(msg("solid[0]=1").find("must end in a key"), std::string::npos);
  EXPECT_NE(msg("solid[3].We=1").find("past the end"), std::string::npos) << msg("solid[3].We=1");
  EXPECT_NE(msg("domain.cells=[32,16").find("not valid TOML"), std::string::npos);
  EXPECT_NE(error_of("[flow]\nRe = 1.5\n", {"flow.Re.x=1"}).find("flow.Re is a floating-point, not a table"), std::string::npos)
      << error_of("[flow]\nRe = 1.5\n", {"flow.Re.x=1"});
}

// ---------------------------------------------------------------- round trip

TEST(Config, RoundTrip) {
  expect_round_trip(CaseConfig{});
  expect_round_trip(parse_case_string(kFull));
  expect_round_trip(parse_case_string(R"(
[domain]
geometry = "couette"
length = [2.0, 2.0, 1.0]
[flow]
wall_velocity = [-1.0, 0.1]
initial = "rest"
[output]
dir = "runs/with \"quotes\" and \\ backslash"
[[solid]]
shape = "layer"
thickness = 0.3
initial_velocity = "rest"
)"));
  expect_round_trip(parse_case_string(R"(
[domain]
geometry = "periodic"
length = [6.283185307179586, 6.283185307179586, 6.283185307179586]
[flow]
initial = "taylor-green"
Re = 0.1
[time]
dt = 0.1234567890123456789
)"));
}

TEST(Config, ToTomlWritesEveryKey) {
  const std::string text = to_toml(CaseConfig{});
  for (const char* k : {"length", "cells", "geometry", "Re", "bulk_velocity", "wall_velocity", "wall_frequency",
                        "initial", "penalization_eta", "pipe_wall", "cfl", "dt", "t_end", "max_steps", "dir", "every",
                        "fields_every", "profiles_every", "checkpoint_every", "shape_times"})
    EXPECT_NE(text.find(std::string("\n") + k + " = "), std::string::npos) << k << " missing from\n" << text;
}

// ---------------------------------------------------------------- validation rules

TEST(ConfigErrors, SyntaxErrorNamesLineAndColumn) {
  const std::string msg = error_of("[flow]\nRe = 100\nbulk_velocity = = 2\n");
  EXPECT_NE(msg.find("t.toml: TOML syntax error at line 3, column"), std::string::npos) << msg;
}

TEST(ConfigErrors, UnknownKeysAndSections) {
  expect_error("[flow]\nReynolds = 3\n", {"unknown key flow.Reynolds", "did you mean flow.Re?"});
  expect_error("[flow]\nbulk_velocty = 3\n", {"did you mean flow.bulk_velocity?"});
  expect_error("[flow]\nre = 3\n", {"did you mean flow.Re?"});
  expect_error("[flow]\nxyz = 3\n", {"unknown key flow.xyz;", "known keys in [flow]: Re, bulk_velocity"});
  expect_error("[time]\nRe = 3\n", {"unknown key time.Re", "did you mean flow.Re?"});
  expect_error("Re = 3\n", {"unknown top-level key Re", "did you mean flow.Re?"});
  expect_error("[flwo]\nRe = 3\n", {"unknown section [flwo]", "did you mean [flow]?"});
  expect_error("[[solids]]\n", {"unknown section [[solids]]", "did you mean [[solid]]?"});
  expect_error("[[solid]]\ndiamter = 0.1\n", {"unknown key solid[0].diamter", "did you mean solid[0].diameter?"});
}

TEST(ConfigErrors, WrongTypes) {
  expect_error("[flow]\nRe = \"100\"\n", {"flow.Re = \"100\"", "expected a number, got a string"});
  expect_error("[domain]\nlength = [3, 1]\n", {"domain.length = [3, 1]", "expected 3 numbers, got 2"});
  expect_error("[domain]\nlength = 3\n", {"domain.length", "expected an array"});
  expect_error("[domain]\ncells = [32.0, 16, 16]\n", {"domain.cells[0] = 32.0", "expected an integer"});
  expect_error("[domain]\ncells = [32, 16]\n", {"domain.cells", "3 integers"});
  expect_error("[domain]\ngeometry = 3\n", {"domain.geometry = 3", "expected a string"});
  expect_error("[domain]\ngeometry = \"tube\"\n", {"domain.geometry = \"tube\"", "\"pipe\", \"duct\", \"channel\""});
  expect_error("[domain]\ngeometry = \"dcut\"\n", {"did you mean \"duct\"?"});
  expect_error("[time]\nmax_steps = 1.5\n", {"time.max_steps = 1.5", "expected an integer"});
  expect_error("[time]\nimplicit_viscosity = \"yes\"\n", {"time.implicit_viscosity", "expected true or false"});
  expect_error("[output]\ndir = 3\n", {"output.dir", "expected a string"});
  expect_error("[output]\nshape_times = [1, \"a\"]\n", {"output.shape_times[1] = \"a\""});
  expect_error("flow = 3\n", {"flow = 3", "must be a section [flow]"});
  expect_error("[solid]\nWe = 1\n", {"solid", "[[solid]]"});
  expect_error("[flow]\nRe = nan\n", {"flow.Re = nan", "finite"});
}

TEST(ConfigErrors, Ranges) {
  expect_error("[domain]\nlength = [3, 0, 1]\ngeometry = \"duct\"\n", {"domain.length[1] = 0", "must be > 0"});
  expect_error("[domain]\ncells = [32, 3, 16]\n", {"domain.cells[1] = 3", ">= 4"});
  expect_error("[flow]\nRe = 0\n", {"flow.Re = 0", "> 0"});
  expect_error("[flow]\nwall_frequency = -1\n", {"flow.wall_frequency = -1", ">= 0"});
  expect_error("[flow]\npenalization_eta = 0.0\n", {"flow.penalization_eta = 0.0"});
  expect_error("[flow]\npipe_wall = \"smooth\"\n", {"flow.pipe_wall", "sharp", "interpolated"});
  expect_error("[domain]\ngeometry = \"duct\"\n[flow]\npipe_wall = \"sharp\"\n", {"flow.pipe_wall", "pipe"});
  expect_error("[time]\ncfl = 1.01\n", {"time.cfl = 1.01", "(0, 1]"});
  expect_error("[time]\ncfl = 0\n", {"time.cfl = 0"});
  expect_error("[time]\ndt = -0.1\n", {"time.dt = -0.1"});
  expect_error("[time]\nt_end = 0\n", {"time.t_end = 0"});
  expect_error("[time]\nmax_steps = -1\n", {"time.max_steps = -1"});
  expect_error("[output]\nevery = 0\n", {"output.every = 0", ">= 1"});
  expect_error("[output]\ncheckpoint_every = -5\n", {"output.checkpoint_every = -5"});
  expect_error("[output]\ndir = \"\"\n", {"output.dir = \"\"", "empty"});
  expect_error("[output]\nshape_times = [1, -2]\n", {"output.shape_times[1] = -2"});
  EXPECT_NO_THROW(parse_case_string("[time]\ncfl = 1\ndt = 0\n[output]\nshape_times = []\n"));
}

TEST(ConfigErrors, GeometryConsistency) {
  expect_error("[domain]\nlength = [3, 2, 1]\n", {"domain.length = [3.0, 2.0, 1.0]", "Ly = Lz = 1"});
  EXPECT_NO_THROW(parse_case_string("[domain]\nlength = [3, 2, 1]\ngeometry = \"duct\"\n"));
  expect_error("[domain]\ngeometry = \"periodic\"\n", {"flow.initial = \"laminar\" (the default)", "taylor-green"});
  expect_error("[domain]\ngeometry = \"periodic\"\n[flow]\ninitial = \"laminar\"\n", {"flow.initial = \"laminar\":"});
  expect_error("[flow]\ninitial = \"taylor-green\"\n", {"flow.initial", "needs domain.geometry = \"periodic\""});
  expect_error("[domain]\ngeometry = \"couette\"\n[flow]\ninitial = \"rest\"\nbulk_velocity = 1.0\n",
               {"flow.bulk_velocity = 1.0", "not allowed with domain.geometry = \"couette\""});
  expect_error("[domain]\ngeometry = \"channel\"\n[flow]\nwall_velocity = [0, 1]\n",
               {"flow.wall_velocity = [0, 1]", "couette"});
  EXPECT_NO_THROW(parse_case_string("[domain]\ngeometry = \"channel\"\n[flow]\nwall_velocity = [0, 0]\n"));
}

TEST(ConfigErrors, SolidsInsideTheDomain) {
  const std::string pipe = "[[solid]]\ndiameter = 0.2\n";
  EXPECT_NO_THROW(parse_case_string(pipe + "center = [1.0, 0.2, 0.29]\n"));  // r = 0.357, r + d/2 = 0.457
  expect_error(pipe + "center = [1.0, 0.35, 0.25]\n",
               {"solid[0] leaves the pipe: r + d/2 = ", "must be < R = 0.5", "solid[0].center = [1.0, 0.35, 0.25]"});
  expect_error(pipe + "center = [3.0, 0, 0]\n", {"solid[0].center", "[0, Lx) = [0, 3.0)"});
  expect_error(pipe + "center = [-0.1, 0, 0]\n", {"solid[0].center"});
  expect_error("[domain]\nlength = [0.4, 1, 1]\ncells = [8, 16, 16]\n[[solid]]\ndiameter = 0.45\ncenter = [0.2, 0, 0]\n",
               {"solid[0].diameter = 0.45", "< Lx = 0.4"});
  const std::string duct =
      "[domain]\ngeometry = \"duct\"\nlength = [3, 2, 1]\ncells = [48, 32, 16]\n[[solid]]\ndiameter = 0.2\n";
  EXPECT_NO_THROW(parse_case_string(duct + "center = [1, 0.85, 0.35]\n"));
  expect_error(duct + "center = [1, 0.95, 0]\n", {"solid[0] leaves the duct"});
  expect_error(duct + "center = [1, 0, 0.45]\n", {"solid[0] leaves the duct", "Lz/2 = 0.5"});
  const std::string channel = "[domain]\ngeometry = \"channel\"\n[[solid]]\ndiameter = 0.2\n";
  EXPECT_NO_THROW(parse_case_string(channel + "center = [1, 0.35, 5.0]\n"));  // z periodic: not checked
  expect_error(channel + "center = [1, -0.45, 0]\n", {"solid[0] leaves the channel", "Ly/2 = 0.5"});
  expect_error("[domain]\ngeometry = \"couette\"\n[flow]\ninitial = \"rest\"\n[[solid]]\ndiameter = 0.3\n"
               "center = [1, 0.4, 0]\n",
               {"solid[0] leaves the channel"});
  expect_error("[domain]\ngeometry = \"channel\"\nlength = [3, 1, 0.25]\n[[solid]]\ndiameter = 0.3\n",
               {"solid[0].diameter = 0.3", "< Lz = 0.25"});
}

TEST(ConfigErrors, SphereBelowTheGrid) {
  // 0.2 across on the default 3 x 1 x 1 pipe of 48 x 16 x 16 cells: 3.2 cells; 0.1: 1.6
  EXPECT_NO_THROW(parse_case_string("[[solid]]\ndiameter = 0.2\n"));
  expect_error("[[solid]]\ndiameter = 0.1\n",
               {"solid[0].diameter = 0.1 spans 1.6 cells of the coarsest spacing 0.0625", "at least 2 cells across"});
}

TEST(ConfigErrors, OverlappingSpheres) {
  const std::string two = "[[solid]]\ndiameter = 0.2\ncenter = [1.0, 0, 0]\n[[solid]]\ndiameter = 0.2\n";
  EXPECT_NO_THROW(parse_case_string(two + "center = [1.2, 0, 0]\n"));  // touching is allowed
  expect_error(two + "center = [1.1, 0.05, 0]\n", {"solid[0] and solid[1] overlap"});
  // across the periodic x boundary: x = 0.05 and x = 2.95 are 0.1 apart
  expect_error("[[solid]]\ndiameter = 0.2\ncenter = [0.05, 0, 0]\n[[solid]]\ndiameter = 0.2\ncenter = [2.95, 0, 0]\n",
               {"solid[0] and solid[1] overlap", "Lx = 3.0"});
  expect_error(two + "center = [2.0, 0, 0]\n[[solid]]\ndiameter = 0.2\ncenter = [2.1, 0, 0]\n",
               {"solid[1] and solid[2] overlap"});
}

TEST(ConfigErrors, Layers) {
  expect_error("[[solid]]\nshape = \"layer\"\n", {"solid[0].shape = \"layer\"", "\"channel\" or \"couette\""});
  expect_error("[domain]\ngeometry = \"channel\"\n[[solid]]\nshape = \"layer\"\nthickness = 1.0\n",
               {"solid[0].thickness = 1.0", "< Ly = 1.0"});
  expect_error("[domain]\ngeometry = \"channel\"\n[[solid]]\nshape = \"layer\"\ncenter = [0, 0, 0]\n",
               {"solid[0].center", "not used by solid[0].shape = \"layer\""});
  expect_error("[[solid]]\nthickness = 0.1\n", {"solid[0].thickness", "not used by solid[0].shape = \"sphere\""});
  expect_error("[[solid]]\nshape = \"ball\"\n", {"solid[0].shape = \"ball\"", "\"sphere\", \"layer\""});
  expect_error("[[solid]]\nWe = 0\n", {"solid[0].We = 0", "> 0"});
  expect_error("[[solid]]\nviscosity_ratio = -1\n", {"solid[0].viscosity_ratio = -1", ">= 0"});
  expect_error("[[solid]]\ninitial_velocity = \"moving\"\n", {"solid[0].initial_velocity", "\"rest\", \"fluid\""});
}

TEST(ConfigErrors, MapMarginBelongsToTheReferenceMap) {
  expect_error("[[solid]]\nmodel = \"paper\"\nmap_margin = 0.5\n", {"solid[0].map_margin = 0.5", "\"reference-map\" only"});
  expect_error("[[solid]]\nmodel = \"reference-map\"\nmap_margin = 1.5\n", {"solid[0].map_margin = 1.5", "[0, 1]"});
  expect_error("[[solid]]\nmodel = \"reference-map\"\nb_extension = false\n",
               {"solid[0].b_extension = false", "\"paper\" only"});
  expect_error("[[solid]]\nb_extension = 1\n", {"solid[0].b_extension"});
  expect_error("[[solid]]\nmodel = \"reference-map\"\nmap_margin = -0.1\n", {"solid[0].map_margin = -0.1", "[0, 1]"});
  // the relaxation acts on the ramp's cells: refused without a ramp, for other models, below 0
  expect_error("[[solid]]\nmodel = \"reference-map\"\nmap_ramp = 0\nmap_relax_time = 0.05\n",
               {"solid[0].map_relax_time = 0.05", "map_ramp > 0"});
  // the ramp's weights in the extension: the map's, and only with a ramp
  expect_error("[[solid]]\nmodel = \"paper\"\nmap_ramp_in_extension = true\n",
               {"solid[0].map_ramp_in_extension = true", "\"reference-map\""});
  expect_error("[[solid]]\nmodel = \"reference-map\"\nmap_ramp = 0\nmap_ramp_in_extension = true\n",
               {"solid[0].map_ramp_in_extension = true", "map_ramp > 0"});
  expect_error("[[solid]]\nmap_ramp_in_extension = 1\n", {"solid[0].map_ramp_in_extension"});
  // the smooth band fit: the map's only
  expect_error("[[solid]]\nmodel = \"paper\"\nmap_smooth_band = true\n",
               {"solid[0].map_smooth_band = true", "\"reference-map\""});
  expect_error("[[solid]]\nmap_smooth_band = \"yes\"\n", {"solid[0].map_smooth_band"});
  expect_error("[[solid]]\nmodel = \"paper\"\nmap_relax_time = 0.05\n", {"solid[0].map_relax_time", "\"reference-map\""});
  expect_error("[[solid]]\nmodel = \"reference-map\"\nmap_ramp = 0.5\nmap_relax_time = -1\n",
               {"solid[0].map_relax_time = -1", ">= 0"});
}

// A case file's map body gets the relaxed surface (half a cell of ramp relaxed over 0.05, the
// extension at full weight); without a ramp nothing relaxes; the paper model has none.
TEST(Config, ReferenceMapSurfaceDefaults) {
  const CaseConfig c = parse_case_string("[[solid]]\n[[solid]]\ncenter = [0.5, 0, 0]\nmap_ramp = 0\n"
                                         "[[solid]]\ncenter = [1, 0, 0]\nmodel = \"paper\"\n"
                                         "[[solid]]\ncenter = [1.5, 0, 0]\nmap_relax_time = 0.2\nmap_ramp_in_extension = true\n");
  ASSERT_EQ(c.solids.size(), 4u);
  EXPECT_EQ(c.solids[0].map_ramp, 0.5);
  EXPECT_EQ(c.solids[0].map_relax_time, 0.05);
  EXPECT_FALSE(c.solids[0].map_ramp_in_extension);
  EXPECT_EQ(c.solids[1].map_ramp, 0.0);
  EXPECT_EQ(c.solids[1].map_relax_time, 0.0);
  EXPECT_EQ(c.solids[2].map_ramp, 0.0);
  EXPECT_EQ(c.solids[2].map_relax_time, 0.0);
  EXPECT_EQ(c.solids[3].map_relax_time, 0.2);
  EXPECT_TRUE(c.solids[3].map_ramp_in_extension);
  expect_round_trip(c);
}

// solver.fft_planning: estimate by default, measure on request, written back by the round trip;
// anything else (WisdomOnly's spelling included) refused naming the key and the allowed values.
TEST(Config, FftPlanning) {
  EXPECT_EQ(parse_case_string("").solver.fft_planning, FftPlanning::Estimate);
  const CaseConfig c = parse_case_string("[solver]\nfft_planning = \"measure\"\n");
  EXPECT_EQ(c.solver.fft_planning, FftPlanning::Measure);
  expect_same(parse_case_string(to_toml(c)), c);
  expect_error("[solver]\nfft_planning = \"patient\"\n",
               {"solver.fft_planning = \"patient\"", "one of \"estimate\", \"measure\""});
  expect_error("[solver]\nfft_planning = \"wisdom-only\"\n", {"solver.fft_planning"});
  expect_error("[solver]\nfft_planning = true\n", {"solver.fft_planning", "expected a string"});
  expect_error("[time]\nfft_planning = \"measure\"\n", {"did you mean solver.fft_planning?"});
}

TEST(ConfigErrors, MissingFile) {
  try {
    parse_case_file("/nonexistent/dir/case.toml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "case file '/nonexistent/dir/case.toml' not found");
  }
  EXPECT_THROW(parse_case_file(fs::temp_directory_path().string()), ConfigError);
}

// ---------------------------------------------------------------- corpora

TEST(ConfigCorpus, BadCasesFailWithTheExpectedMessage) {
  const std::string data = test_data();
  ASSERT_FALSE(data.empty()) << "EULERFSI_TEST_DATA is not set (CTest sets it to the tests/ directory)";
  const auto files = toml_files(fs::path(data) / "bad_cases");
  EXPECT_GE(files.size(), 20u);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    std::ifstream in(f);
    std::string first;
    std::getline(in, first);
    const std::string tag = "# expect: ";
    ASSERT_EQ(first.rfind(tag, 0), 0u) << "first line must be '# expect: <substring>'";
    const std::string expected = first.substr(tag.size());
    ASSERT_FALSE(expected.empty());
    try {
      parse_case_file(f.string());
      ADD_FAILURE() << "parsed without error";
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(expected), std::string::npos) << "'" << expected << "' not in: " << msg;
      EXPECT_NE(msg.find(f.string()), std::string::npos) << "file not named in: " << msg;
    }
  }
}

TEST(ConfigCorpus, GoodCasesParseAndRoundTrip) {
  const std::string data = test_data();
  ASSERT_FALSE(data.empty()) << "EULERFSI_TEST_DATA is not set (CTest sets it to the tests/ directory)";
  const auto files = toml_files(fs::path(data) / "good_cases");
  EXPECT_GE(files.size(), 2u);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    CaseConfig cfg;
    ASSERT_NO_THROW(cfg = parse_case_file(f.string()));
    EXPECT_EQ(cfg.source, f.string());
    expect_round_trip(cfg);
  }
}

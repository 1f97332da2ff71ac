#pragma once
// The validated, resolved content of a case file (TOML). Every field has the default that a
// case file may omit; parse_case() fills it and refuses anything unknown or inconsistent.
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "poisson/fft_planning.hpp"

namespace eulerfsi {

// One clear message naming the key and what is allowed; the CLI prints it and exits non-zero.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class Geometry { Pipe, Duct, Channel, Couette, Periodic };
enum class InitialFlow { Laminar, Rest, TaylorGreen };
// Sharp: the paper's staircase mask (first order); Interpolated: the first fluid layer is forced
// to the linear interpolation between the wall and the next fluid point (second order).
enum class PipeWall { Sharp, Interpolated };

struct DomainConfig {
  std::array<double, 3> length{3.0, 1.0, 1.0};
  std::array<int, 3> cells{48, 16, 16};
  Geometry geometry = Geometry::Pipe;
};

struct FlowConfig {
  double Re = 100.0;
  double bulk_velocity = 1.0;                // constant flow rate (pipe, duct, channel; periodic if given)
  // a periodic box is driven along x at bulk_velocity (the mean u over the box) only if the case
  // gives it: a fixed body in a periodic array (Hasimoto's problem); otherwise nothing drives it
  bool periodic_flow_rate = false;
  std::array<double, 2> wall_velocity{0, 0};  // couette: u at y = -Ly/2 and y = +Ly/2
  double wall_frequency = 0.0;               // > 0: wall velocity times sin(wall_frequency t)
  InitialFlow initial = InitialFlow::Laminar;
  double penalization_eta = 1e-8;            // volume penalization permeability (pipe)
  PipeWall pipe_wall = PipeWall::Interpolated;
  // The grid moves along x with this velocity (a Galilean frame; walls are x-uniform, x periodic):
  // a particle that travels with the frame crosses no cells, so WENO does not smear its edge.
  // Numerics only: every output is in the laboratory frame.
  double frame_velocity = 0.0;
  bool frame_follows_particle = false;       // frame_velocity = "particle": solid 0's mean u, each step
};

struct TimeConfig {
  double cfl = 0.2;
  double dt = 0.0;       // 0: adaptive
  double t_end = 10.0;
  long max_steps = 0;    // 0: no limit
  // mu_f by Crank-Nicolson with a fast Helmholtz solve per component (the part mu - mu_f stays
  // explicit): lifts the explicit viscous time-step limit
  bool implicit_viscosity = false;
};

// How the run computes, not what: may change on restart.
struct SolverConfig {
  // estimate or measure (WisdomOnly is not a case-file value)
  FftPlanning fft_planning = FftPlanning::Estimate;
  // After a rigid body's correction (or a soft body's hold) the next step's projection makes the
  // edge cells divergence-free (Sharma & Patankar 2005 do so); true projects again at once, so that
  // every step ends divergence-free, for one more Poisson solve per substep (a rigid sphere's step
  // 1.56x the flow's instead of 1.05x; the Stokes references move by < 2e-5, docs/VALIDATION.md).
  bool reproject_constrained = false;
};

struct OutputConfig {
  std::string dir = "runs/case";
  long every = 10;
  long fields_every = 0;
  long profiles_every = 0;
  long checkpoint_every = 0;
  std::vector<double> shape_times;  // times at which the particle cross-section is written
};

enum class SolidShape { Sphere, Layer };
enum class InitialSolidVelocity { Rest, Fluid };
// How a body's shape and deformation are carried (src/solid/solid_model.hpp):
//   Paper: psi and B advected with WENO5 (the paper's method; needs ~48 cells per diameter)
//   ReferenceMap: the reference position xi advected; psi and B derived from it (Kamrin et al. 2012)
enum class SolidModelKind { Paper, ReferenceMap, Rigid };
// What holds a body: nothing (free), everything (no translation, no rotation), or its position in
// the cross-section (y, z held; free along x and free to rotate). src/solid/rigid_model.hpp.
enum class SolidConstraint { None, Fixed, Radial };

struct SolidConfig {
  SolidShape shape = SolidShape::Sphere;
  double diameter = 0.2;
  std::array<double, 3> center{0, 0, 0};
  double thickness = 0.5;
  double We = 1.0;               // G = 1 / We
  double viscosity_ratio = 1.0;  // mu_s / mu_f
  double sharpening = 0.0;       // interface sharpening pseudo-step per time step, in units of h (0: off)
  double map_margin = 0.0;       // reference map: carried only deeper than this many cells inside the surface
  double map_ramp = 0.0;        // reference map: a solid cell's weight in the extension rises over this many cells
  double map_relax_time = 0.0;  // reference map: the ramp's cells relax towards the fit over this time (0: at once)
  bool map_ramp_in_extension = false;  // reference map: the ramp's weights enter the extension's fits too
  bool map_smooth_band = false;  // reference map: psi's band fitted in one smooth fit through the solid, no cascade
  bool b_extension = true;       // paper model: B extended from the solid over a band, I beyond (false: the paper's B)
  InitialSolidVelocity initial_velocity = InitialSolidVelocity::Fluid;
  SolidModelKind model = SolidModelKind::Paper;
  SolidConstraint constraint = SolidConstraint::None;
};

struct CaseConfig {
  DomainConfig domain;
  FlowConfig flow;
  TimeConfig time;
  SolverConfig solver;
  OutputConfig output;
  std::vector<SolidConfig> solids;
  std::string source;  // the file it came from
};

// The surface a case file's reference-map body gets unless it sets its keys (SolidConfig's own
// defaults are the surface without a ramp): half a cell of ramp relaxed over 0.05 time units, the
// extension at full weight. The Stokes-limit stiff shear within 1 % of theory at 8 and 12 cells per
// d, a stiff sphere's elastic oscillation damped at Re = 200 and 400 (docs/REFERENCE_MAP.md, "The
// relaxed surface"). The parser and the benchmarks both take it from here.
void use_default_map_surface(SolidConfig& solid);

// Reads and validates a case file, applying `--set section.key=value` overrides (value in TOML
// syntax, e.g. flow.Re=200, domain.cells=[32,16,16], output.dir="runs/x"; a bare word that is not
// TOML is a string, so output.dir=runs/x works). Solids are addressed as solid[i].key; i equal to
// the number of solids appends one. Overrides are applied before validation, so they are checked
// the same way; every error is a ConfigError naming the file (and the override, if one is involved).
CaseConfig parse_case_file(const std::string& path, const std::vector<std::string>& overrides = {});

// Refuses, with a ConfigError naming the key, what this build cannot do although the case file is
// valid: output.fields_every and output.checkpoint_every without HDF5. `eulerfsi check` and
// `eulerfsi run` call it; parsing stays the same in every build.
void check_build_supports(const CaseConfig& cfg);
CaseConfig parse_case_string(const std::string& toml_text, const std::vector<std::string>& overrides = {},
                             const std::string& source_name = "<string>");
// The resolved configuration as TOML (every key, defaults filled in): written into the run directory.
// Keys the parser refuses for the geometry or shape (bulk_velocity for couette and an undriven periodic box, thickness
// for a sphere, diameter/center for a layer) are left out, so parse_case_string(to_toml(c)) == c.
std::string to_toml(const CaseConfig& cfg);

const char* to_string(Geometry g);
const char* to_string(PipeWall w);
const char* to_string(SolidConstraint c);
const char* to_string(InitialFlow f);
const char* to_string(SolidShape s);
const char* to_string(InitialSolidVelocity v);
const char* to_string(SolidModelKind m);
const char* to_string(FftPlanning p);

}  // namespace eulerfsi

#include "app/simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "io/csv_writer.hpp"
#include "io/field_writer.hpp"
#include "io/profiles.hpp"
#include "kernels/interpolation.hpp"
#include "solid/migration_summary.hpp"
#include "solid/particle_diagnostics.hpp"
#include "solid/shape_section.hpp"
#include "solid/solid_phase.hpp"
#include "solver/flow_solver.hpp"

namespace eulerfsi {

namespace fs = std::filesystem;

Grid make_grid(const CaseConfig& cfg, const Comm& comm) {
  const auto& d = cfg.domain;
  const bool walls_y = d.geometry != Geometry::Periodic;
  const bool walls_z = d.geometry == Geometry::Pipe || d.geometry == Geometry::Duct;
  try {
    return Grid(d.cells.data(), d.length.data(), walls_y ? Boundary::Wall : Boundary::Periodic,
                walls_z ? Boundary::Wall : Boundary::Periodic, comm.rank(), comm.size());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(cfg.source + ": " + e.what());
  }
}

namespace {

const std::vector<std::string> kFlowColumns = {"step", "t", "dt", "cfl", "bulk_u", "dpdx", "max_div", "kinetic_energy"};

class Simulation {
 public:
  Simulation(const CaseConfig& cfg, const Comm& comm, const RunOptions& opt)
      : cfg_(cfg), comm_(comm), opt_(opt), grid_(make_grid(cfg, comm)), flow_(cfg, grid_, comm),
        solids_(cfg, grid_, flow_.boundaries(), comm), tracker_(cfg, grid_, comm),
        fields_(grid_, comm.comm, cfg.output.dir) {}

  int run() {
    prepare_directory();
    flow_.set_initial_condition();
    solids_.set_initial_condition();
    if (!solids_.empty()) {
      solids_.stop_bodies_at_rest(flow_.state().vel);
      flow_.make_solenoidal();
    }
    open_outputs();
    const auto wall_start = std::chrono::steady_clock::now();
    double dt = 0.0;
    write_outputs(dt, true);
    while (!finished()) {
      dt = cfg_.time.dt > 0.0 ? cfg_.time.dt : flow_.stable_dt(solids_.max_wave_speed());
      if (t_ + dt > cfg_.time.t_end) dt = cfg_.time.t_end - t_;  // land exactly on t_end
      flow_.advance(t_, dt, solids_.empty() ? nullptr : &solids_);
      t_ += dt;
      ++step_;
      if (!write_outputs(dt, false)) return 3;
      if (step_ % cfg_.output.every == 0 && !opt_.quiet) print_progress(dt, wall_start);
    }
    if (!solids_.empty() && comm_.root()) write_summary_json(cfg_.output.dir + "/particle.csv", cfg_.output.dir + "/summary.json");
    if (comm_.root() && !opt_.quiet) std::printf("done: %ld steps, t = %.6g, output in %s\n", step_, t_, cfg_.output.dir.c_str());
    return 0;
  }

 private:
  bool finished() const {
    if (cfg_.time.max_steps > 0 && step_ >= cfg_.time.max_steps) return true;
    return t_ >= cfg_.time.t_end * (1.0 - 1e-14);
  }

  void prepare_directory() {
    const std::string& dir = cfg_.output.dir;
    if (comm_.root()) {
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec || !fs::is_directory(dir)) throw std::runtime_error("cannot create output directory '" + dir + "': " + ec.message());
      // the resolved configuration lives with the results
      const std::string tmp = dir + "/config.resolved.toml.tmp";
      std::ofstream out(tmp);
      out << to_toml(cfg_);
      out.close();
      if (!out) throw std::runtime_error("cannot write into output directory '" + dir + "'");
      fs::rename(tmp, dir + "/config.resolved.toml");
      if (cfg_.output.profiles_every > 0) fs::create_directories(dir + "/profiles");
    }
    comm_.barrier();
  }

  void open_outputs() {
    flow_csv_ = CsvWriter(cfg_.output.dir + "/flow.csv", kFlowColumns, comm_.root());
    if (!solids_.empty()) {
      particle_csv_ = CsvWriter(cfg_.output.dir + "/particle.csv", particle_columns(), comm_.root());
      if (!cfg_.output.shape_times.empty()) {
        if (comm_.root()) fs::create_directories(cfg_.output.dir + "/shapes");
        shape_index_ = CsvWriter(cfg_.output.dir + "/shapes/index.csv", {"step", "t"}, comm_.root());
      }
    }
  }

  // Particle rows every `every` steps; a cross-section at each requested time once it is reached.
  void write_particles(bool row) {
    const auto& times = cfg_.output.shape_times;
    const bool shape_due = next_shape_ < times.size() && t_ >= times[next_shape_] - 1e-12;
    if (!row && !shape_due) return;
    const auto states = tracker_.measure(solids_, flow_.state());
    if (row)
      for (size_t n = 0; n < states.size(); ++n) particle_csv_.row(particle_row(step_, t_, int(n), states[n]));
    if (shape_due) {
      char name[64];
      std::snprintf(name, sizeof(name), "/shapes/%08ld.csv", step_);
      write_shape_sections(cfg_.output.dir + name, grid_, comm_.comm, solids_, states);
      shape_index_.row({double(step_), t_});
      while (next_shape_ < times.size() && t_ >= times[next_shape_] - 1e-12) ++next_shape_;
    }
  }

  Field3 total_psi() {
    if (solids_.empty()) return Field3();
    if (psi_total_.extent(0) == 0) psi_total_ = grid_.make_field("psi");
    solids_.total_volume_fraction(psi_total_);
    return psi_total_;
  }

  // Returns false when the solution is no longer finite (the caller stops with an error).
  bool write_outputs(double dt, bool initial) {
    const auto& o = cfg_.output;
    const bool row = initial || step_ % o.every == 0;
    if (row) {
      const FlowDiagnostics d = flow_.diagnostics(dt, solids_.max_wave_speed());
      if (!d.finite) {
        if (comm_.root()) std::fprintf(stderr, "error: the velocity is no longer finite at step %ld, t = %.6g\n", step_, t_);
        return false;
      }
      last_ = d;
      flow_csv_.row({double(step_), t_, dt, d.cfl, d.bulk_u, d.dpdx, d.max_div, d.kinetic_energy});
    }
    if (!solids_.empty()) write_particles(row);
    if (o.profiles_every > 0 && step_ % o.profiles_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "/profiles/%08ld.csv", step_);
      write_profile(o.dir + name, cfg_, grid_, comm_.comm, flow_.state().vel, total_psi());
    }
    if (o.fields_every > 0 && step_ % o.fields_every == 0) write_fields();
    return true;
  }

  void write_fields() {
    const Box box = grid_.interior();
    std::vector<NamedField> out;
    const char* names[3] = {"u", "v", "w"};
    for (int c = 0; c < 3; ++c) {
      Field3 centred = grid_.make_field(names[c]);
      kernels::face_to_centre(centred, flow_.state().vel.c[c], c, box);
      out.push_back({names[c], centred});
    }
    out.push_back({"p", flow_.state().p});
    if (!solids_.empty()) out.push_back({"psi", total_psi()});
    fields_.write(step_, t_, out, true);
  }

  void print_progress(double dt, std::chrono::steady_clock::time_point start) const {
    if (!comm_.root()) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double done = t_ / cfg_.time.t_end;
    if (cfg_.time.max_steps > 0) done = std::max(done, double(step_) / cfg_.time.max_steps);
    const double eta = done > 0 ? wall * (1.0 - done) / done : 0.0;
    std::printf("step %8ld  t %10.5f  dt %9.3e  cfl %5.3f  max|div u| %8.2e  bulk %8.5f  dp/dx %10.4e  wall %8.1fs  eta %8.1fs\n",
                step_, t_, dt, last_.cfl, last_.max_div, last_.bulk_u, last_.dpdx, wall, eta);
    std::fflush(stdout);
  }

  CaseConfig cfg_;
  Comm comm_;
  RunOptions opt_;
  Grid grid_;
  FlowSolver flow_;
  SolidPhase solids_;
  ParticleTracker tracker_;
  FieldWriter fields_;
  CsvWriter flow_csv_, particle_csv_, shape_index_;
  Field3 psi_total_;
  size_t next_shape_ = 0;
  FlowDiagnostics last_;
  double t_ = 0.0;
  long step_ = 0;
};

}  // namespace

int run_case(const CaseConfig& cfg, const Comm& comm, const RunOptions& options) {
  Simulation sim(cfg, comm, options);
  return sim.run();
}

}  // namespace eulerfsi

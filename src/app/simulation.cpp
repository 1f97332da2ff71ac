#include "app/simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "app/fault_check.hpp"
#include "app/restart.hpp"
#include "app/runaway.hpp"
#include "app/signals.hpp"
#include "io/checkpoint.hpp"
#include "io/csv_writer.hpp"
#include "io/field_writer.hpp"
#include "io/profiles.hpp"
#include "kernels/flow_reductions.hpp"
#include "kernels/interpolation.hpp"
#include "poisson/fft_wisdom.hpp"
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

// frame_u, frame_x: the grid's x-velocity and displacement in the laboratory (flow.frame_velocity)
const std::vector<std::string> kFlowColumns = {"step", "t",       "dt",           "cfl",     "bulk_u",
                                               "dpdx", "max_div", "kinetic_energy", "frame_u", "frame_x"};
// An adaptive step that can no longer keep the CFL number below this has blown up.
constexpr double kBlowUpCfl = 1.0;
constexpr int kExitBlowUp = 3;
constexpr double kCollapse = 1e-6;

class Simulation {
 public:
  Simulation(const CaseConfig& cfg, const Comm& comm, const RunOptions& opt)
      : cfg_(cfg), comm_(comm), opt_(opt), grid_(make_grid(cfg, comm)), restored_fft_wisdom_(restore_fft_wisdom()),
        flow_(cfg, grid_, comm),
        solids_(cfg, grid_, flow_.boundaries(), comm), tracker_(cfg, grid_, comm),
        fields_(grid_, comm.comm, cfg.output.dir) {}

  int run() {
    prepare_directory();
    if (opt_.restart) {
      restore();
    } else {
      set_initial_state(flow_, solids_);
      update_frame();
    }
    open_outputs(opt_.restart);
    if (!opt_.restart) write_outputs(0.0, true);
    install_stop_handlers();
    const auto wall_start = std::chrono::steady_clock::now();
    const double done_at_start = fraction_done();
    while (!finished()) {
      const double dt_stable = flow_.stable_dt(solids_.max_wave_speed());
      double dt = cfg_.time.dt > 0.0 ? cfg_.time.dt : dt_stable;
      if (blown_up(dt, dt_stable)) return report_blow_up(dt, dt_stable);
      if (t_ + dt > cfg_.time.t_end) dt = cfg_.time.t_end - t_;  // land exactly on t_end
      flow_.advance(t_, dt, solids_.empty() ? nullptr : &solids_);
      t_ += dt;
      ++step_;
      update_frame();
      write_outputs(dt, false);
      if (cfg_.output.checkpoint_every > 0 && step_ % cfg_.output.checkpoint_every == 0) {
        // the next step's blow-up check first: a checkpoint holds only a state a restart can continue
        const double dt_stable_now = flow_.stable_dt(solids_.max_wave_speed());
        const double dt_next = cfg_.time.dt > 0.0 ? cfg_.time.dt : dt_stable_now;
        if (blown_up(dt_next, dt_stable_now)) return report_blow_up(dt_next, dt_stable_now);
        write_restart_file();
      }
      if (step_ % cfg_.output.every == 0 && !opt_.quiet) print_progress(dt, wall_start, done_at_start);
      if (const int sig = agreed_stop_signal()) return stop_on_signal(sig);
    }
    // a final check: the last step may have produced the first non-finite value
    const double dt_stable = flow_.stable_dt(solids_.max_wave_speed());
    if (blown_up(dt_stable, dt_stable)) return report_blow_up(dt_stable, dt_stable);
    if (cfg_.output.checkpoint_every > 0) write_restart_file();
    if (!solids_.empty() && comm_.root()) write_summary_json(dir() + "/particle.csv", dir() + "/summary.json");
    if (comm_.root() && !opt_.quiet) std::printf("done: %ld steps, t = %.6g, output in %s\n", step_, t_, dir().c_str());
    return 0;
  }

 private:
  const std::string& dir() const { return cfg_.output.dir; }
  GridFrame frame() const { return {flow_.frame_velocity(), flow_.frame_offset()}; }

  // A frame that follows the particle takes solid 0's mean x-velocity after every step.
  void update_frame() {
    const auto& f = cfg_.flow;
    const double u = f.frame_follows_particle
                         ? tracker_.mean_x_velocity(solids_, flow_.state(), 0, flow_.frame_velocity())
                         : f.frame_velocity;
    flow_.set_frame_velocity(u, t_);
  }
  std::string checkpoint_path() const { return dir() + "/checkpoint.h5"; }
  std::string restart_path() const { return opt_.restart_file.empty() ? checkpoint_path() : opt_.restart_file; }
  bool measures_ffts() const { return cfg_.solver.fft_planning == FftPlanning::Measure; }

  // The wisdom beside the restart's checkpoint. checkpoint.h5.prev has none of its own: the wisdom
  // beside checkpoint.h5 holds its plans (a run plans once, and a restart reuses the stored plans).
  std::string stored_wisdom_path() const {
    const std::string checkpoint = restart_path(), prev = ".prev", own = fft_wisdom_path(checkpoint);
    const bool is_prev = checkpoint.size() > prev.size() &&
                         checkpoint.compare(checkpoint.size() - prev.size(), prev.size(), prev) == 0;
    return is_prev && !fs::exists(own) ? fft_wisdom_path(checkpoint.substr(0, checkpoint.size() - prev.size())) : own;
  }

  // Before the solvers are built: FFTW_MEASURE then plans what the interrupted run planned.
  bool restore_fft_wisdom() const {
    if (!opt_.restart || !measures_ffts()) return false;
    std::string why;
    const bool restored = load_fft_wisdom(stored_wisdom_path(), comm_.comm, &why);
    if (!restored && comm_.root())
      std::fprintf(stderr, "warning: %s: solver.fft_planning = \"measure\" plans afresh, so the restart may differ in "
                   "the last bits from an uninterrupted run\n", why.c_str());
    return restored;
  }

  bool finished() const {
    if (cfg_.time.max_steps > 0 && step_ >= cfg_.time.max_steps) return true;
    return t_ >= cfg_.time.t_end * (1.0 - 1e-14);
  }

  void prepare_directory() {
    // rank 0 touches the file system; every rank learns the outcome, or the others would wait forever
    std::string error;
    if (comm_.root()) {
      try {
        create_run_directory();
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    int len = int(error.size());
    MPI_Bcast(&len, 1, MPI_INT, 0, comm_.comm);
    error.resize(size_t(len));
    MPI_Bcast(error.data(), len, MPI_CHAR, 0, comm_.comm);
    if (!error.empty()) throw std::runtime_error(error);
  }

  void create_run_directory() const {
    std::error_code ec;
    fs::create_directories(dir(), ec);
    if (ec || !fs::is_directory(dir()))
      throw std::runtime_error("cannot create output directory '" + dir() + "': " + (ec ? ec.message() : "not a directory"));
    // a fresh run never mixes its series with an older run's: refuse rather than overwrite
    if (!opt_.restart && fs::exists(checkpoint_path()))
      throw std::runtime_error("output directory '" + dir() + "' holds a run with a checkpoint; continue it with "
                               "--restart, or choose another --out");
    // the resolved configuration lives with the results
    const std::string tmp = dir() + "/config.resolved.toml.tmp";
    std::ofstream out(tmp);
    out << to_toml(cfg_);
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write into output directory '" + dir() + "' (permissions or disk full?)");
    }
    fs::rename(tmp, dir() + "/config.resolved.toml");
    if (cfg_.output.profiles_every > 0) fs::create_directories(dir() + "/profiles");
  }

  // The flow's fields a step starts from, under the names the checkpoint stores.
  std::vector<std::pair<std::string, Field3>> flow_fields() {
    auto& s = flow_.state();
    return {{"u", s.u()}, {"v", s.v()}, {"w", s.w()}, {"p", s.p}};
  }

  // Every field a step starts from, to read a checkpoint into (the bodies' on the whole slab).
  std::vector<std::pair<std::string, Field3>> state_fields() {
    auto f = flow_fields();
    for (auto& field : solids_.checkpoint_fields()) f.push_back(field);
    return f;
  }

  // The checkpoint's name of value q of ParticleTracker::force_impulse().
  static std::string impulse_key(size_t q) {
    const size_t n = q / ParticleTracker::kImpulseValues, v = q % ParticleTracker::kImpulseValues;
    return "solid" + std::to_string(n) + ".force_impulse." + std::to_string(v);
  }

  void write_restart_file() {
    CheckpointMeta meta;
    meta.step = step_;
    meta.t = t_;
    meta.dpdx = flow_.dpdx();
    meta.config_toml = to_toml(cfg_);
    meta.scalars["next_shape"] = double(next_shape_);
    meta.scalars["frame.velocity"] = flow_.frame_velocity();
    meta.scalars["frame.offset"] = flow_.frame_offset();
    const auto xs = tracker_.unwrapped_x();
    for (size_t n = 0; n < xs.size(); ++n) meta.scalars["solid" + std::to_string(n) + ".x_unwrapped"] = xs[n];
    const auto impulse = tracker_.force_impulse();
    for (size_t q = 0; q < impulse.size(); ++q) meta.scalars[impulse_key(q)] = impulse[q];
    for (const auto& [key, v] : solids_.checkpoint_scalars()) meta.scalars[key] = v;
    std::vector<CheckpointSource> fields;
    for (const auto& [name, f] : flow_fields()) fields.push_back({name, f, 0.0});
    for (const auto& f : solids_.checkpoint_sources()) fields.push_back(f);
    // the wisdom first: a checkpoint is never without the plans that continue it
    if (measures_ffts()) save_fft_wisdom(fft_wisdom_path(checkpoint_path()), comm_.comm);
    write_checkpoint(checkpoint_path(), grid_, comm_.comm, meta, fields);
  }

  void restore() {
    const std::string path = restart_path();
    const CheckpointMeta meta = read_checkpoint(path, grid_, comm_.comm, state_fields());
    // checkpoints written before flow.pipe_wall existed ran the paper's staircase wall
    std::vector<std::string> written_before_key;
    if (cfg_.domain.geometry == Geometry::Pipe && meta.config_toml.find("pipe_wall") == std::string::npos)
      written_before_key.push_back("flow.pipe_wall=\"sharp\"");
    const CaseConfig before = parse_case_string(meta.config_toml, written_before_key, path);
    const auto changed = differing_physical_keys(before, cfg_);
    if (!changed.empty()) {
      std::string list;
      for (const auto& k : changed) list += "\n  " + k;
      throw ConfigError("cannot restart from '" + path + "': the physical configuration differs in" + list +
                        "\n(time stepping and output may change on restart; the physics may not)");
    }
    step_ = meta.step;
    t_ = meta.t;
    flow_.set_dpdx(meta.dpdx);
    next_shape_ = size_t(meta.scalars.count("next_shape") ? meta.scalars.at("next_shape") : 0.0);
    std::vector<double> xs;
    for (size_t n = 0; n < solids_.bodies().size(); ++n)
      xs.push_back(meta.scalars.at("solid" + std::to_string(n) + ".x_unwrapped"));
    tracker_.set_unwrapped_x(xs);
    // the forces' interval since the last row (checkpoints before interval means had none: 0)
    std::vector<double> impulse(solids_.bodies().size() * ParticleTracker::kImpulseValues, 0.0);
    for (size_t q = 0; q < impulse.size(); ++q)
      if (meta.scalars.count(impulse_key(q))) impulse[q] = meta.scalars.at(impulse_key(q));
    tracker_.set_force_impulse(impulse);
    // the stored velocity is relative to the stored frame; a new fixed frame_velocity shifts it
    auto scalar = [&meta](const char* key) { return meta.scalars.count(key) ? meta.scalars.at(key) : 0.0; };
    flow_.restore_frame(scalar("frame.velocity"), scalar("frame.offset"));
    if (!cfg_.flow.frame_follows_particle) flow_.set_frame_velocity(cfg_.flow.frame_velocity, t_);
    // ghosts are not stored: refill them exactly as a step leaves them
    flow_.boundaries().fill_velocity(flow_.state().vel, t_);
    flow_.boundaries().fill_scalar(flow_.state().p);
    solids_.restore({meta.scalars.begin(), meta.scalars.end()});
    // the series continue from the checkpoint's step: later rows belong to the lost future
    if (comm_.root()) {
      const std::vector<std::string> none, particle = solids_.empty() ? none : particle_columns();
      const std::pair<const char*, const std::vector<std::string>*> series[] = {
          {"/flow.csv", &kFlowColumns}, {"/particle.csv", &particle}, {"/shapes/index.csv", &none}};
      for (const auto& [name, cols] : series)
        if (truncate_series_after(dir() + name, step_, *cols) && !opt_.quiet)
          std::printf("%s%s was written with other columns (another eulerfsi version): its rows are rewritten "
                      "under this version's, the original kept as %s.before-restart\n", dir().c_str(), name, name + 1);
      fields_.set_history(field_history_until(dir(), step_));
    }
    if (comm_.root() && !opt_.quiet) std::printf("restarted from %s at step %ld, t = %.6g\n", path.c_str(), step_, t_);
  }

  void open_outputs(bool append) {
    auto open = [this, append](const std::string& path, const std::vector<std::string>& cols) {
      return CsvWriter(path, cols, comm_.root(), append && fs::exists(path));
    };
    flow_csv_ = open(dir() + "/flow.csv", kFlowColumns);
    if (!solids_.empty()) {
      particle_csv_ = open(dir() + "/particle.csv", particle_columns());
      if (!cfg_.output.shape_times.empty()) {
        if (comm_.root()) fs::create_directories(dir() + "/shapes");
        shape_index_ = open(dir() + "/shapes/index.csv", {"step", "t"});
      }
    }
  }

  void write_outputs(double dt, bool initial) {
    const auto& o = cfg_.output;
    const bool row = initial || step_ % o.every == 0;
    if (row) {
      last_ = flow_.diagnostics(dt, solids_.max_wave_speed());
      flow_csv_.row({double(step_), t_, dt, last_.cfl, last_.bulk_u, last_.dpdx, last_.max_div, last_.kinetic_energy,
                     flow_.frame_velocity(), flow_.frame_offset()});
    }
    if (!solids_.empty()) {
      // a row reports the mean force over the steps since the previous row: every step adds its own
      if (!initial && !row) tracker_.accumulate_forces(solids_, flow_.state(), frame(), dt);
      write_particles(row, initial ? 0.0 : dt);
    }
    if (o.profiles_every > 0 && step_ % o.profiles_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "/profiles/%08ld.csv", step_);
      write_profile(dir() + name, cfg_, grid_, comm_.comm, flow_.state().vel, total_psi(), flow_.frame_velocity());
    }
    if (o.fields_every > 0 && step_ % o.fields_every == 0) write_fields();
  }

  // Particle rows every `every` steps; a cross-section at each requested time once it is reached.
  // dt: the step just taken (0 at the start), whose forces close a row's interval.
  void write_particles(bool row, double dt) {
    const auto& times = cfg_.output.shape_times;
    const bool shape_due = next_shape_ < times.size() && t_ >= times[next_shape_] - 1e-12;
    if (!row && !shape_due) return;
    const auto states = tracker_.measure(solids_, flow_.state(), frame(), row ? dt : 0.0);
    if (row)
      for (size_t n = 0; n < states.size(); ++n) particle_csv_.row(particle_row(step_, t_, int(n), states[n]));
    if (shape_due) {
      char name[64];
      std::snprintf(name, sizeof(name), "/shapes/%08ld.csv", step_);
      write_shape_sections(dir() + name, grid_, comm_.comm, solids_, states, flow_.frame_offset());
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

  void write_fields() {
    const Box box = grid_.interior();
    std::vector<NamedField> out;
    const char* names[3] = {"u", "v", "w"};
    for (int c = 0; c < 3; ++c) {
      if (centred_[c].extent(0) == 0) centred_[c] = grid_.make_field(names[c]);
      kernels::face_to_centre(centred_[c], flow_.state().vel.c[c], c, box);
      // the laboratory's velocity on the grid's points (a uniform add, as the flow-rate correction)
      if (c == 0 && flow_.frame_velocity() != 0.0)
        kernels::add_open_x_velocity(centred_[c], kernels::Mask2(), flow_.frame_velocity(), box);
      out.push_back({names[c], centred_[c]});
    }
    out.push_back({"p", flow_.state().p});
    if (!solids_.empty()) {
      out.push_back({"psi", total_psi()});
      if (energy_.extent(0) == 0) energy_ = grid_.make_field("elastic_energy");
      solids_.elastic_energy_density(energy_);
      out.push_back({"elastic_energy", energy_});
    }
    fields_.write(step_, t_, out, true, flow_.frame_offset());
  }

  // Non-finite values, a CFL number the step cannot keep below 1, an adaptive step collapsing
  // to a millionth of the run's first one, or a speed a hundred times the case's scale (velocities
  // growing without bound): the run has blown up.
  bool blown_up(double dt, double dt_stable) {
    if (dt_reference_ == 0.0) {
      dt_reference_ = dt_stable;
      speed_scale_ = case_speed_scale(cfg_, flow_.last_speed_bound());
    }
    const double cfl = cfg_.time.cfl * dt / dt_stable;
    return !(std::isfinite(dt_stable) && dt_stable > kCollapse * dt_reference_ && cfl <= kBlowUpCfl) ||
           speed_ran_away(flow_.last_speed_bound(), speed_scale_);
  }

  int report_blow_up(double dt, double dt_stable) {
    std::vector<std::pair<std::string, WindowField>> fields;
    for (const auto& [name, f] : flow_fields()) fields.emplace_back(name, f);
    for (const auto& f : solids_.checkpoint_sources()) fields.emplace_back(f.name, f.field);
    std::string where = locate_non_finite(fields, grid_, comm_.comm);
    // not a NaN yet: say where the velocity is largest
    const std::string fastest = where.empty() ? locate_fastest(flow_.state().vel.c, grid_, comm_.comm) : "";
    if (where.empty() && dt_stable <= kCollapse * dt_reference_) {
      char buf[200];
      std::snprintf(buf, sizeof(buf), "the stable time step collapsed to %.3g (%.1e of the first step %.3g): the velocity "
                    "is growing without bound", dt_stable, dt_stable / dt_reference_, dt_reference_);
      where = buf;
    }
    if (where.empty() && speed_ran_away(flow_.last_speed_bound(), speed_scale_)) {
      char buf[240];
      std::snprintf(buf, sizeof(buf), "the largest speed is at least %.3g, over %.0f times the case's speed scale %.3g "
                    "(bulk, wall and starting speeds): the velocity is growing without bound",
                    flow_.last_speed_bound(), kRunawaySpeedFactor, speed_scale_);
      where = buf;
    }
    if (where.empty()) {
      char buf[160];
      std::snprintf(buf, sizeof(buf), "the CFL number would be %.3g with dt = %.3g (limit %.3g)",
                    cfg_.time.cfl * dt / dt_stable, dt, kBlowUpCfl);
      where = buf;
    }
    if (!fastest.empty()) where += "; " + fastest;
    if (comm_.root()) {
      std::fprintf(stderr, "error: the run blew up at step %ld, t = %.6g: %s\n", step_, t_, where.c_str());
      if (fs::exists(checkpoint_path()))
        std::fprintf(stderr, "the last good checkpoint is kept: %s\n", checkpoint_path().c_str());
    }
    return kExitBlowUp;
  }

  // The signal any rank received (all ranks stop together).
  int agreed_stop_signal() const {
    int mine = stop_requested(), any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm_.comm);
    return any;
  }

  int stop_on_signal(int sig) {
#ifndef EULERFSI_HAVE_HDF5
    if (comm_.root())
      std::fprintf(stderr, "stopped by signal %d at step %ld, t = %.6g; no checkpoint (built without HDF5)\n", sig,
                   step_, t_);
    return 128 + sig;
#endif
    write_restart_file();
    if (comm_.root())
      std::fprintf(stderr, "stopped by signal %d at step %ld, t = %.6g; checkpoint written: %s (continue with --restart)\n",
                   sig, step_, t_, checkpoint_path().c_str());
    return 128 + sig;
  }

  double fraction_done() const {
    double done = t_ / cfg_.time.t_end;
    if (cfg_.time.max_steps > 0) done = std::max(done, double(step_) / cfg_.time.max_steps);
    return std::min(done, 1.0);
  }

  // ETA from this process's pace (a restarted run starts counting at its checkpoint).
  void print_progress(double dt, std::chrono::steady_clock::time_point start, double done_at_start) const {
    if (!comm_.root()) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double done = fraction_done(), progressed = done - done_at_start;
    const double eta = progressed > 0.0 ? wall * (1.0 - done) / progressed : 0.0;
    std::printf("step %8ld  t %10.5f  dt %9.3e  cfl %5.3f  max|div u| %8.2e  bulk %8.5f  dp/dx %10.4e  wall %8.1fs  eta %8.1fs\n",
                step_, t_, dt, last_.cfl, last_.max_div, last_.bulk_u, last_.dpdx, wall, eta);
    std::fflush(stdout);
  }

  CaseConfig cfg_;
  Comm comm_;
  RunOptions opt_;
  Grid grid_;
  bool restored_fft_wisdom_;  // declared before flow_: set before the solvers plan their transforms
  FlowSolver flow_;
  SolidPhase solids_;
  ParticleTracker tracker_;
  FieldWriter fields_;
  CsvWriter flow_csv_, particle_csv_, shape_index_;
  FlowDiagnostics last_;
  Field3 psi_total_, centred_[3], energy_;  // field snapshots
  size_t next_shape_ = 0;
  double dt_reference_ = 0.0;  // the first stable step of this process (since the start or restart)
  double speed_scale_ = 0.0;   // case_speed_scale at that step
  double t_ = 0.0;
  long step_ = 0;
};

}  // namespace

int run_case(const CaseConfig& cfg, const Comm& comm, const RunOptions& options) {
  Simulation sim(cfg, comm, options);
  return sim.run();
}

}  // namespace eulerfsi

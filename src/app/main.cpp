// eulerfsi command line:
//   eulerfsi run CASE.toml [--set section.key=value ...] [--out DIR] [--restart [FILE]]
//   eulerfsi check CASE.toml [--set ...]      validate and print the resolved configuration
//   eulerfsi info                             version, Kokkos backend, MPI ranks, FFT library
#ifdef EULERFSI_HAVE_HDF5
#include <hdf5.h>
#endif

#include <CLI/CLI.hpp>
#include <Kokkos_Core.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/memory_estimate.hpp"
#include "solid/migration_summary.hpp"
#include "app/simulation.hpp"
#include "config/case_config.hpp"
#include "core/compat.hpp"
#include "parallel/comm.hpp"
#include "parallel/mpi.hpp"
#include "poisson/poisson_solver.hpp"

namespace {

void print_info(const eulerfsi::Comm& comm) {
  if (!comm.root()) return;
  const int kv = KOKKOS_VERSION;
  std::printf("eulerfsi %s\n", EULERFSI_VERSION);
  std::printf("kokkos     %d.%d.%d\n", kv / 10000, kv / 100 % 100, kv % 100);
  std::printf("backend    %s (concurrency %d)\n", eulerfsi::compat::default_backend_name(),
              int(Kokkos::DefaultExecutionSpace().concurrency()));
#ifdef EULERFSI_HAVE_MPI
  std::printf("mpi ranks  %d\n", comm.size());
#else
  std::printf("mpi        none (built without MPI: one process)\n");
#endif
  std::printf("fft        %s\n", eulerfsi::poisson_backend_info().c_str());
#ifdef EULERFSI_HAVE_HDF5
  unsigned h5maj = 0, h5min = 0, h5rel = 0;
  H5get_libversion(&h5maj, &h5min, &h5rel);
  std::printf("hdf5       %u.%u.%u (parallel)\n", h5maj, h5min, h5rel);
#else
  std::printf("hdf5       none (built without HDF5: no field snapshots, no checkpoints)\n");
#endif
}

int run_cli(int argc, char** argv, const eulerfsi::Comm& comm) {
  CLI::App app{"eulerfsi: soft particles in pressure-driven flow, fully Eulerian one-continuum method"};
  app.require_subcommand(1);
  std::string case_file, out_dir, restart_file;
  std::vector<std::string> sets;
  bool quiet = false;

  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", case_file, "case file (TOML)")->required();
  run->add_option("--set", sets, "override a key: section.key=value (TOML value)")->take_all();
  run->add_option("--out", out_dir, "output directory (overrides output.dir)");
  auto* restart = run->add_option("--restart", restart_file, "continue from a checkpoint (default: the run's latest)")
                      ->expected(0, 1);
  run->add_flag("--quiet", quiet, "no progress lines");

  auto* check = app.add_subcommand("check", "validate a case file and print the resolved configuration");
  check->add_option("case", case_file, "case file (TOML)")->required();
  check->add_option("--set", sets, "override a key: section.key=value (TOML value)")->take_all();

  app.add_subcommand("info", "version, Kokkos backend, MPI ranks, FFT library");

  std::vector<std::string> run_dirs;
  auto* summary = app.add_subcommand("summary", "write summary.json (t_rev, t_cen, T_osc) again from particle.csv");
  summary->add_option("run_dirs", run_dirs, "run directories")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return comm.root() ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 2);
  }

  if (app.got_subcommand("info")) {
    print_info(comm);
    return 0;
  }
  if (app.got_subcommand("summary")) {
    int status = 0;
    for (const auto& d : run_dirs) {
      if (!comm.root()) continue;
      try {
        eulerfsi::write_summary_json(d + "/particle.csv", d + "/summary.json");
        std::printf("%s/summary.json\n", d.c_str());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        status = 1;
      }
    }
    return status;
  }
  try {
    if (!out_dir.empty()) sets.push_back("output.dir=\"" + out_dir + "\"");
    const eulerfsi::CaseConfig cfg = eulerfsi::parse_case_file(case_file, sets);
    eulerfsi::check_build_supports(cfg);
    if (app.got_subcommand("check")) {
      const eulerfsi::Grid grid = eulerfsi::make_grid(cfg, comm);  // the rank split is part of being valid
      const std::string memory = eulerfsi::describe_memory(cfg, grid, comm);
      if (comm.root()) std::printf("%s%s", memory.c_str(), eulerfsi::to_toml(cfg).c_str());
      return 0;
    }
    eulerfsi::RunOptions opt;
    opt.restart = restart->count() > 0;
    opt.restart_file = restart_file;
#ifndef EULERFSI_HAVE_HDF5
    if (opt.restart)
      throw eulerfsi::ConfigError("--restart: this eulerfsi was built without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF) and "
                                  "has no checkpoints to continue from");
#endif
    opt.quiet = quiet;
    // before anything is allocated or written
    eulerfsi::refuse_if_out_of_memory(cfg, eulerfsi::make_grid(cfg, comm), comm);
    return eulerfsi::run_case(cfg, comm, opt);
  } catch (const eulerfsi::ConfigError& e) {
    if (comm.root()) std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    if (comm.root()) std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Kokkos warns on stdout when OMP_PROC_BIND is unset; unset and "false" bind the same way, and
  // `eulerfsi check` must print clean TOML
  setenv("OMP_PROC_BIND", "false", 0);
  MPI_Init(&argc, &argv);
  int code = 0;
  {
    Kokkos::ScopeGuard kokkos(argc, argv);
    code = run_cli(argc, argv, eulerfsi::Comm{MPI_COMM_WORLD});
  }
  MPI_Finalize();
  return code;
}

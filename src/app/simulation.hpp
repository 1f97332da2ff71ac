#pragma once
// One run of a case: owns the grid, the flow and solid solvers and the outputs, and reads
// top to bottom like the time loop it is.
#include <memory>
#include <string>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "parallel/comm.hpp"

namespace eulerfsi {

struct RunOptions {
  std::string restart_file;  // empty: fresh start
  bool restart = false;      // --restart given (file may be empty: the run's latest checkpoint)
  bool quiet = false;
};

// Runs the case to completion; returns the process exit code (0 on success).
int run_case(const CaseConfig& cfg, const Comm& comm, const RunOptions& options);

// Builds the grid for this rank, turning an impossible split into a ConfigError.
Grid make_grid(const CaseConfig& cfg, const Comm& comm);

}  // namespace eulerfsi

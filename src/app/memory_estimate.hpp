#pragma once
// What a case needs in memory per rank, counted from the fields each part of the solver holds,
// and the refusal of a run that cannot fit in the memory of its node.
#include <string>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "parallel/comm.hpp"

namespace eulerfsi {

struct MemoryEstimate {
  double flow_fields = 0.0;   // whole-slab fields of the flow solver, output and Poisson work arrays
  // every body's fields (shared ones and the model's own) in whole-slab equivalents: a body on a
  // window (every sphere) counts its window's share of the slab, at its initial position
  double solid_fields = 0.0;
  // the most they reach: a window holding every x-plane while the body crosses the periodic end
  // (grid at rest), and the whole-slab fields a checkpoint is read into (a restart)
  double solid_peak_fields = 0.0;
  double slab_cells = 0.0;    // cells of this rank's slab, ghosts included
  double bytes() const { return 8.0 * (flow_fields + solid_fields) * slab_cells; }
  double peak_bytes() const { return 8.0 * (flow_fields + solid_peak_fields) * slab_cells; }
  // bytes per owned cell of the global grid (ghosts included in the numerator)
  double bytes_per_cell(double owned_cells) const { return bytes() / owned_cells; }
};

MemoryEstimate estimate_memory(const CaseConfig& cfg, const Grid& grid);

// One line for `eulerfsi check`: the estimate per rank and the memory this node has.
std::string describe_memory(const CaseConfig& cfg, const Grid& grid, const Comm& comm);

// Throws a ConfigError naming domain.cells when the ranks on this node together need more than
// the memory the node has available (MemAvailable); does nothing where that is unknown or the
// fields live in device memory.
void refuse_if_out_of_memory(const CaseConfig& cfg, const Grid& grid, const Comm& comm);

}  // namespace eulerfsi

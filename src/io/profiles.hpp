#pragma once
// Mean velocity profiles: pipe -> (r, u) in radial bins one cell wide, averaged over x and
// angle; channel, couette, duct, periodic -> (y, u, v, w[, psi]) averaged over x and z.
#include "parallel/mpi.hpp"

#include <string>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"

namespace eulerfsi {

// vel is relative to the grid, which moves with frame_velocity along x: u is written in the laboratory.
void write_profile(const std::string& path, const CaseConfig& cfg, const Grid& grid, MPI_Comm comm,
                   const kernels::Velocity& vel, const Field3& psi_total,
                   double frame_velocity = 0.0);

}  // namespace eulerfsi

#pragma once
// Mean velocity profiles: pipe -> (r, u) in radial bins one cell wide, averaged over x and
// angle; channel, couette, duct, periodic -> (y, u, v, w[, psi]) averaged over x and z.
#include <mpi.h>

#include <string>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"

namespace eulerfsi {

void write_profile(const std::string& path, const CaseConfig& cfg, const Grid& grid, MPI_Comm comm,
                   const kernels::Velocity& vel, const Field3& psi_total);

}  // namespace eulerfsi

#pragma once
// Finds where a field stopped being finite, for the error message of a blown-up run.
#include "parallel/mpi.hpp"

#include <string>
#include <utility>
#include <vector>

#include "core/window_field.hpp"
#include "grid/grid.hpp"

namespace eulerfsi {

// "field 'u' is nan at cell (i, j, k), x = .., y = .., z = .." for the first bad value (lowest
// rank, then storage order), or an empty string when every owned value is finite (a field on a
// window: the cells it holds). Collective.
std::string locate_non_finite(const std::vector<std::pair<std::string, WindowField>>& fields, const Grid& grid,
                              MPI_Comm comm);

// "largest |u_D| / h_D is X, in u at cell (i, j, k), x = .., y = .., z = .." over the velocity
// components (u, v, w in that order). Collective.
std::string locate_fastest(const Field3 vel[3], const Grid& grid, MPI_Comm comm);

}  // namespace eulerfsi

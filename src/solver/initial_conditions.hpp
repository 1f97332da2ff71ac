#pragma once
// Initial velocity: the geometry's exact laminar profile, rest, or the Taylor-Green vortex.
#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"

namespace eulerfsi {

void fill_initial_velocity(const CaseConfig& cfg, const Grid& grid, const kernels::Velocity& vel);

}  // namespace eulerfsi

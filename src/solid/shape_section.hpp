#pragma once
// The particle's cross-section for the paper's shape figures: the psi = 0.5 contour in the plane
// through the particle centre that contains the pipe axis (x and the radial direction).
#include "parallel/mpi.hpp"

#include <string>
#include <vector>

#include "grid/grid.hpp"
#include "solid/particle_diagnostics.hpp"
#include "solid/solid_phase.hpp"

namespace eulerfsi {

struct ContourSegment {
  double x0, s0, x1, s1;  // x relative to the centroid, s the signed radial coordinate
};

// Marching squares on a regular (nx x ns) sample grid f(a, b) = values[a * ns + b], spacing (dx, ds),
// origin (x0, s0): the segments of the level-`level` line.
std::vector<ContourSegment> contour_segments(const std::vector<double>& values, int nx, int ns, double x0, double s0,
                                             double dx, double ds, double level);

// Samples every body's psi in its (x, radial) plane and appends its segments to `path`
// (columns solid,segment,x,s; two rows per segment). Collective; rank 0 writes. The states' x is
// the laboratory's; frame_offset is where the grid's origin is in the laboratory.
void write_shape_sections(const std::string& path, const Grid& grid, MPI_Comm comm, const SolidPhase& solids,
                          const std::vector<ParticleState>& states, double frame_offset = 0.0);

}  // namespace eulerfsi

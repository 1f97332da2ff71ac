#pragma once
// The uniform staggered (MAC) grid and its x-slab decomposition.
//
// Cell (i, j, k) has its centre at x = (i + 1/2) dx, y = -Ly/2 + (j + 1/2) dy,
// z = -Lz/2 + (k + 1/2) dz (global indices). Staggered unknowns sit on the face
// on the "plus" side of their cell: u(i,j,k) at x = (i+1) dx, v(i,j,k) at
// y = -Ly/2 + (j+1) dy, w(i,j,k) at z = -Lz/2 + (k+1) dz.
// Storage index = local index + kGhost in every direction.
#include <string>

#include "core/types.hpp"

namespace eulerfsi {

enum class Boundary { Periodic, Wall };

struct Grid {
  int n[3] = {0, 0, 0};          // global cells
  double length[3] = {0, 0, 0};  // domain size
  double h[3] = {0, 0, 0};       // spacing
  Boundary bc[3] = {Boundary::Periodic, Boundary::Periodic, Boundary::Periodic};  // bc[0] is always periodic
  int nx_local = 0;              // cells in x owned by this rank (x-slabs)
  int x_offset = 0;              // global x index of the first owned cell

  Grid() = default;
  Grid(const int cells[3], const double len[3], Boundary bc_y, Boundary bc_z, int rank, int nranks);

  // Storage extents including ghosts.
  int ext(int d) const { return (d == 0 ? nx_local : n[d]) + 2 * kGhost; }
  int local_n(int d) const { return d == 0 ? nx_local : n[d]; }
  // Owned cells, in storage indices.
  Box interior() const {
    return {{kGhost, kGhost, kGhost}, {kGhost + nx_local, kGhost + n[1], kGhost + n[2]}};
  }
  // Everything, ghosts included.
  Box all() const { return {{0, 0, 0}, {ext(0), ext(1), ext(2)}}; }
  long global_cells() const { return long(n[0]) * n[1] * n[2]; }
  double cell_volume() const { return h[0] * h[1] * h[2]; }
  double domain_lo(int d) const { return d == 0 ? 0.0 : -0.5 * length[d]; }
  // Coordinate of a cell centre from its storage index.
  double centre(int d, int s) const {
    const int g = s - kGhost + (d == 0 ? x_offset : 0);
    return domain_lo(d) + (g + 0.5) * h[d];
  }
  // Kokkos 3.4 accepts std::string labels but not const char*.
  Field3 make_field(const char* label) const { return Field3(std::string(label), ext(0), ext(1), ext(2)); }
};

}  // namespace eulerfsi

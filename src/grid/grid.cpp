#include "grid/grid.hpp"

#include <stdexcept>
#include <string>

namespace eulerfsi {

Grid::Grid(const int cells[3], const double len[3], Boundary bc_y, Boundary bc_z, int rank, int nranks) {
  for (int d = 0; d < 3; ++d) {
    n[d] = cells[d];
    length[d] = len[d];
    h[d] = len[d] / cells[d];
  }
  bc[0] = Boundary::Periodic;
  bc[1] = bc_y;
  bc[2] = bc_z;
  // x-slabs of equal thickness: the FFT transposes and the halo exchange assume it.
  if (nranks <= 0 || cells[0] % nranks != 0) {
    throw std::invalid_argument("domain.cells: Nx = " + std::to_string(cells[0]) + " cannot be split into " +
                                std::to_string(nranks) + " equal x-slabs; use a rank count that divides Nx");
  }
  nx_local = cells[0] / nranks;
  // the halo exchange only talks to the two x-neighbours, so a slab must hold the ghost width
  if (nx_local < kGhost) {
    throw std::invalid_argument("domain.cells: Nx = " + std::to_string(cells[0]) + " on " + std::to_string(nranks) +
                                " ranks leaves " + std::to_string(nx_local) + " x-planes per rank; at least " +
                                std::to_string(kGhost) + " are needed");
  }
  x_offset = rank * nx_local;
}

}  // namespace eulerfsi

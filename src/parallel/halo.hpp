#pragma once
// Ghost exchange across the x-slab decomposition.
#include "parallel/mpi.hpp"

#include "core/types.hpp"
#include "core/window_field.hpp"
#include "grid/grid.hpp"

namespace eulerfsi {

// Fills the kGhost x-ghost planes on both sides of f from the periodic x-neighbours
// (rank-1 and rank+1 modulo the rank count; one rank sends to itself). Whole planes travel,
// y/z ghosts included, so edges and corners are right once y/z ghosts were filled before.
// Fences first: pending kernels that write f must finish before MPI reads it.
// f must be a full field of g (extent(0) == nx_local + 2 kGhost), contiguous.
// Device memory is staged through host buffers unless EULERFSI_GPU_AWARE_MPI is defined; on one
// rank (and in builds without MPI) the ghosts are filled by a kernel, without MPI. Does not fence
// at the end: later kernels on ExecSpace see the ghosts, the host must fence first.
void exchange_x(Field3 f, const Grid& g, MPI_Comm comm);
// The same for a field stored on a window of the slab (src/solid/solid_window.hpp): the planes of
// the exchange that the window holds travel. Every rank's window must cut one global window (the
// ranks then agree on what travels), and on one rank a window that holds an x-ghost plane holds
// every x-plane.
void exchange_x(const WindowField& f, const Grid& g, MPI_Comm comm);

}  // namespace eulerfsi

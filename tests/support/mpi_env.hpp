#pragma once
// Small helpers for tests that run on several ranks.
#include "parallel/mpi.hpp"

namespace eulerfsi::test {
inline int rank() { int r = 0; MPI_Comm_rank(MPI_COMM_WORLD, &r); return r; }
inline int nranks() { int n = 1; MPI_Comm_size(MPI_COMM_WORLD, &n); return n; }
}  // namespace eulerfsi::test

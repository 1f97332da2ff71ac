#pragma once
// The few collective operations the driver needs, on one communicator.
#include "parallel/mpi.hpp"

namespace eulerfsi {

struct Comm {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank() const { int r = 0; MPI_Comm_rank(comm, &r); return r; }
  int size() const { int n = 1; MPI_Comm_size(comm, &n); return n; }
  bool root() const { return rank() == 0; }
  double sum(double x) const { double y = 0; MPI_Allreduce(&x, &y, 1, MPI_DOUBLE, MPI_SUM, comm); return y; }
  double max(double x) const { double y = 0; MPI_Allreduce(&x, &y, 1, MPI_DOUBLE, MPI_MAX, comm); return y; }
  double min(double x) const { double y = 0; MPI_Allreduce(&x, &y, 1, MPI_DOUBLE, MPI_MIN, comm); return y; }
  long sum(long x) const { long y = 0; MPI_Allreduce(&x, &y, 1, MPI_LONG, MPI_SUM, comm); return y; }
  // true on every rank when any rank says true
  bool any(bool x) const { int a = x, b = 0; MPI_Allreduce(&a, &b, 1, MPI_INT, MPI_MAX, comm); return b != 0; }
  void barrier() const { MPI_Barrier(comm); }
};

}  // namespace eulerfsi

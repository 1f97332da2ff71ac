// eulerfsi command line (being written): run, check, info.
#include <mpi.h>
#include <Kokkos_Core.hpp>
int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  { Kokkos::ScopeGuard guard(argc, argv); }
  MPI_Finalize();
  return 0;
}

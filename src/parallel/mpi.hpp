#pragma once
// MPI, or its one-rank stand-in in builds without MPI (-DEULERFSI_ENABLE_MPI=OFF, which leaves
// EULERFSI_HAVE_MPI undefined). Every file that talks MPI includes this instead of <mpi.h>.
#ifdef EULERFSI_HAVE_MPI
#include <mpi.h>
#else
#include "parallel/mpi_serial.hpp"
#endif

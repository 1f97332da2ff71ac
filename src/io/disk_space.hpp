#pragma once
// Room for a file before it is written. HDF5 cannot close a file whose last writes failed (it
// stays half-open and the library's clean-up in MPI_Finalize crashes), so a file that cannot fit
// is refused before it is created: against the free space of its folder and the process's
// file-size limit (ulimit -f). A disk that fills while the file is written is handled by the
// writers themselves (they empty the file before closing it).
#include <cstdint>
#include <string>

#include "parallel/mpi.hpp"

namespace eulerfsi {

// "" if a file of about `bytes` fits in `dir` on every rank; else one reason, the same on every
// rank (collective), e.g. "it needs 9.7 MB and 3.1 MB are free on that disk (disk full?)".
// EULERFSI_SKIP_ROOM_CHECK=1 in the environment skips the check (tests/regression/disk_full.sh).
std::string room_for_file(const std::string& dir, std::uint64_t bytes, MPI_Comm comm);

}  // namespace eulerfsi

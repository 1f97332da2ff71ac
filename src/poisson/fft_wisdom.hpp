#pragma once
// FFTW's wisdom (the algorithms FFTW_MEASURE chose) stored beside a checkpoint, so that a restart
// plans exactly what the interrupted run planned and continues it bit for bit.
//
// Every rank's own wisdom is kept, not their union: FFTW-MPI agrees across ranks on the
// distributed steps but times each rank's local transforms on that rank, and two ranks may choose
// differently for the same local problem; fftw_mpi_gather_wisdom would keep one of them and hand
// it to both. The file is text: a line "eulerfsi-fftw-wisdom 1 ranks N", then for each rank a line
// "rank R bytes B" followed by B bytes of FFTW's exported wisdom.
#include <string>

#include "parallel/mpi.hpp"

namespace eulerfsi {

// Where the wisdom of the checkpoint at `checkpoint_path` lives.
inline std::string fft_wisdom_path(const std::string& checkpoint_path) { return checkpoint_path + ".fftw-wisdom"; }

#ifdef EULERFSI_HAVE_MPI
// Collective: rank 0 writes every rank's wisdom to `path` (a temporary file renamed over it).
// Throws std::runtime_error, on every rank, when it cannot.
void save_fft_wisdom(const std::string& path, MPI_Comm comm);
// Collective: replaces each rank's wisdom by what `path` stored for that rank. False (and every
// rank's wisdom forgotten) when the file is missing, damaged, written by another number of ranks,
// or refused by FFTW; `why` then says which, naming the file.
bool load_fft_wisdom(const std::string& path, MPI_Comm comm, std::string* why = nullptr);
#else
// Without MPI the pressure runs on FFT_DCT, which plans by estimate: there is no wisdom to keep.
inline void save_fft_wisdom(const std::string&, MPI_Comm) {}
inline bool load_fft_wisdom(const std::string&, MPI_Comm, std::string* = nullptr) { return true; }
#endif

}  // namespace eulerfsi

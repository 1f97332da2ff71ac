#pragma once
// One-rank stand-in for the part of MPI that eulerfsi uses, for builds without MPI
// (-DEULERFSI_ENABLE_MPI=OFF: a workstation or one GPU). Include "parallel/mpi.hpp", never this.
//
// Every communicator has one rank (rank 0), so a collective is a copy from the send to the
// receive buffer (or nothing with MPI_IN_PLACE) and a point-to-point exchange can only be a
// rank talking to itself. Nothing here knows about devices: buffers are host memory, as with
// an MPI that is not GPU-aware.
#include <cstdio>
#include <cstdlib>
#include <cstring>

using MPI_Comm = int;
using MPI_Datatype = int;
using MPI_Op = int;
using MPI_Info = int;
struct MPI_Status {
  int MPI_SOURCE, MPI_TAG, MPI_ERROR;
};

constexpr MPI_Comm MPI_COMM_WORLD = 0;
constexpr MPI_Comm MPI_COMM_SELF = 1;
constexpr MPI_Info MPI_INFO_NULL = 0;
constexpr int MPI_SUCCESS = 0;
#define MPI_STATUS_IGNORE (static_cast<MPI_Status*>(nullptr))
#define MPI_IN_PLACE (reinterpret_cast<void*>(-1))

// Datatypes are their size in bytes (each distinct, so a pair type gets its own code).
enum : int {
  MPI_CHAR = 1,
  MPI_INT = 4,
  MPI_UNSIGNED = 104,
  MPI_DOUBLE = 8,
  MPI_LONG = 108,
  MPI_UNSIGNED_LONG_LONG = 208,
  MPI_UINT64_T = 308,
  MPI_DOUBLE_INT = 16,  // struct {double; int}, padded to 16 bytes
};
enum : int { MPI_SUM, MPI_MAX, MPI_MIN, MPI_MAXLOC, MPI_MINLOC };

namespace eulerfsi::serial_mpi {
inline std::size_t type_size(MPI_Datatype t) { return std::size_t(t % 100); }
inline int copy(const void* send, void* recv, int count, MPI_Datatype t) {
  if (send != MPI_IN_PLACE && send != recv && count > 0) std::memmove(recv, send, std::size_t(count) * type_size(t));
  return MPI_SUCCESS;
}
}  // namespace eulerfsi::serial_mpi

inline int MPI_Init(int*, char***) { return MPI_SUCCESS; }
inline int MPI_Finalize() { return MPI_SUCCESS; }
inline int MPI_Comm_rank(MPI_Comm, int* rank) { *rank = 0; return MPI_SUCCESS; }
inline int MPI_Comm_size(MPI_Comm, int* size) { *size = 1; return MPI_SUCCESS; }
inline int MPI_Barrier(MPI_Comm) { return MPI_SUCCESS; }
inline int MPI_Abort(MPI_Comm, int code) { std::exit(code); }
inline int MPI_Bcast(void*, int, MPI_Datatype, int, MPI_Comm) { return MPI_SUCCESS; }
inline int MPI_Allreduce(const void* send, void* recv, int count, MPI_Datatype t, MPI_Op, MPI_Comm) {
  return eulerfsi::serial_mpi::copy(send, recv, count, t);
}
inline int MPI_Reduce(const void* send, void* recv, int count, MPI_Datatype t, MPI_Op, int, MPI_Comm) {
  return eulerfsi::serial_mpi::copy(send, recv, count, t);
}
// Only a rank sending to itself exists: the message is a copy.
inline int MPI_Sendrecv(const void* send, int send_count, MPI_Datatype send_type, int, int, void* recv, int,
                        MPI_Datatype, int, int, MPI_Comm, MPI_Status*) {
  return eulerfsi::serial_mpi::copy(send, recv, send_count, send_type);
}

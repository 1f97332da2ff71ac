#include "io/disk_space.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <cstdio>
#include <cstdlib>

namespace eulerfsi {

namespace {

std::string megabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f MB", bytes / 1e6);
  return text;
}

}  // namespace

std::string room_for_file(const std::string& dir, std::uint64_t bytes, MPI_Comm comm) {
  // the fault tests switch the check off to reach the writers' handling of a disk that fills mid-write
  const char* skip = std::getenv("EULERFSI_SKIP_ROOM_CHECK");
  if (skip && std::string(skip) == "1") return "";
  // HDF5's own metadata (superblock, object headers with their attributes) beyond the raw data:
  // ~1 kB per dataset (a 24^3 checkpoint of 22 fields: 2.4 kB beyond its data); 64 kB and 2 % bound it
  const double needed = double(bytes) * 1.02 + 65536.0;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string reason;
  struct rlimit limit {};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && double(limit.rlim_cur) < needed)
    reason = "it needs " + megabytes(needed) + " and the file-size limit (ulimit -f) is " +
             megabytes(double(limit.rlim_cur)) + " (disk full?)";
  struct statvfs fs {};
  if (reason.empty() && rank == 0 && statvfs(dir.c_str(), &fs) == 0) {
    const double free_bytes = double(fs.f_bavail) * double(fs.f_frsize);
    if (free_bytes < needed)
      reason = "it needs " + megabytes(needed) + " and " + megabytes(free_bytes) + " are free on that disk (disk full?)";
  }
  // one reason for all: the lowest rank that has one
  int first = reason.empty() ? 1 << 30 : rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == 1 << 30) return "";
  int length = int(reason.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  reason.resize(size_t(length));
  MPI_Bcast(reason.data(), length, MPI_CHAR, first, comm);
  return reason;
}

}  // namespace eulerfsi

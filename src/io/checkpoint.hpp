#pragma once
// Restart files in parallel HDF5 that never lose work.
//
// Layout of a checkpoint (one HDF5 file, metadata checksummed by HDF5 itself: superblock v2+):
//   /                 attributes eulerfsi_checkpoint (format version), eulerfsi_version, step, t, dpdx,
//                     cells[3] (global grid), nranks (ranks that wrote it)
//   /config_toml      scalar fixed-length string dataset: the resolved case file
//   /scalars          group, one double attribute per CheckpointMeta::scalars entry
//   /fields/<name>    double dataset (nx, ny, nz), global (x, y, z) order, owned cells only;
//                     attribute checksum (uint64, see below)
//
// Durability: write_checkpoint writes `path.tmp`, syncs it (MPI_File_sync via H5Fflush, then a POSIX
// fsync on rank 0), and only then renames it over `path` and fsyncs the directory. A process killed
// at any instant leaves the previous `path` intact; a stale `path.tmp` is just overwritten next time.
// With keep_previous (the default) the checkpoint being replaced survives as `path.prev` (a hard
// link, or a copy where the file system has none), for when the newest state is valid but unwanted
// (e.g. already blown up). read_checkpoint never falls back by itself: the caller may try `path.prev`.
//
// Checksum of a field: the sum mod 2^64 over all global cells of mix(bits(value) ^ mix(index)),
// where index is the global linear (x, y, z) index and mix is the splitmix64 finaliser (a bijection).
// A sum is order independent, so it is the same for any number of ranks; any change to a single
// value (or a swap of two values) always changes it; multi-value corruption escapes with ~2^-64.
#include "parallel/mpi.hpp"

#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "core/window_field.hpp"
#include "grid/grid.hpp"

namespace eulerfsi {

// Every refusal to read or write a checkpoint; the message names the file.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CheckpointMeta {
  long step = 0;
  double t = 0.0;
  double dpdx = 0.0;
  std::string config_toml;                // the resolved case (to_toml) the run was started with
  std::map<std::string, double> scalars;  // anything else the driver needs to continue exactly
  // Filled by read_checkpoint; write_checkpoint takes them from the grid and the communicator.
  std::array<int, 3> cells{0, 0, 0};
  int nranks = 0;
};

// A field to write: on the whole slab, or on a window of it with one value everywhere else (a
// body's field, src/solid/solid_window.hpp), written without a whole-slab copy.
struct CheckpointSource {
  std::string name;
  WindowField field;
  double outside = 0.0;
};

// Collective. Writes the owned cells of every field plus `meta` (rank 0's copy is the one written).
// Throws CheckpointError on every rank if any step fails; `path` is then untouched.
void write_checkpoint(const std::string& path, const Grid& grid, MPI_Comm comm, const CheckpointMeta& meta,
                      const std::vector<CheckpointSource>& fields, bool keep_previous = true);

// Collective. Fills the owned cells of each named field (ghosts untouched: the caller refills them)
// and returns the metadata. Refuses, with the same CheckpointError on every rank and the fields left
// unmodified, a missing file, one that is not HDF5 or truncated, a different global grid, a missing
// field, or a checksum mismatch. The rank count may differ from the one that wrote it.
CheckpointMeta read_checkpoint(const std::string& path, const Grid& grid, MPI_Comm comm,
                               const std::vector<std::pair<std::string, Field3>>& fields);

}  // namespace eulerfsi

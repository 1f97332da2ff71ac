#pragma once
// Cell-centred snapshots in parallel HDF5 plus one XDMF index that ParaView opens as a time
// series. Datasets are stored (z, y, x) so that ParaView's X axis is the pipe axis.
#include "parallel/mpi.hpp"

#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "grid/grid.hpp"

namespace eulerfsi {

// One snapshot in the index: its step, time and the grid's x-offset in the laboratory (moving frame).
struct Snapshot {
  long step = 0;
  double t = 0.0;
  double x_offset = 0.0;
};

struct NamedField {
  std::string name;
  Field3 data;      // cell-centred, ghosts ignored
};

class FieldWriter {
 public:
  FieldWriter(const Grid& grid, MPI_Comm comm, std::string run_dir);
  // Writes fields/NNNNNNNN.h5 (atomically: temporary name, then rename) and refreshes fields.xdmf.
  // x_offset: where the grid's origin is in the laboratory (a moving frame); the XDMF places the
  // snapshot there, so ParaView shows laboratory coordinates.
  void write(long step, double t, const std::vector<NamedField>& fields, bool velocity_vector, double x_offset = 0.0);
  // Re-reads the index of an earlier run (restart) so the time series continues.
  void set_history(std::vector<Snapshot> history) { history_ = std::move(history); }

 private:
  void write_xdmf() const;
  Grid grid_;
  MPI_Comm comm_;
  std::string dir_;
  std::vector<Snapshot> history_;
  std::vector<std::string> names_;
  bool vector_ = false;
};

// Writes one distributed cell-centred field into an open HDF5 file as dataset `name`, (z, y, x) order.
void write_hdf5_field(long file_id, const Grid& grid, const std::string& name, const Field3& f);

}  // namespace eulerfsi

// Builds without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF) compile this file instead of field_writer.cpp
// and checkpoint.cpp. `eulerfsi check` refuses output.fields_every and output.checkpoint_every
// and `run --restart` is refused, so these are reached only by a caller that skipped the
// validation: they say why instead of skipping the output silently.
#include <stdexcept>
#include <string>

#include "io/checkpoint.hpp"
#include "io/field_writer.hpp"

namespace eulerfsi {

namespace {
[[noreturn]] void no_hdf5(const std::string& what) {
  throw std::runtime_error(what + ": this eulerfsi was built without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF)");
}
}  // namespace

FieldWriter::FieldWriter(const Grid& grid, MPI_Comm comm, std::string run_dir)
    : grid_(grid), comm_(comm), dir_(std::move(run_dir)) {}

void FieldWriter::write(long, double, const std::vector<NamedField>&, bool, double) { no_hdf5("field snapshot"); }

void FieldWriter::write_xdmf() const { no_hdf5("fields.xdmf"); }

void write_hdf5_field(long, const Grid&, const std::string& name, const Field3&) { no_hdf5("field " + name); }

void write_checkpoint(const std::string& path, const Grid&, MPI_Comm, const CheckpointMeta&,
                      const std::vector<CheckpointSource>&, bool) {
  throw CheckpointError("cannot write checkpoint '" + path +
                        "': this eulerfsi was built without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF)");
}

CheckpointMeta read_checkpoint(const std::string& path, const Grid&, MPI_Comm,
                               const std::vector<std::pair<std::string, Field3>>&) {
  throw CheckpointError("cannot read checkpoint '" + path +
                        "': this eulerfsi was built without HDF5 (-DEULERFSI_ENABLE_HDF5=OFF)");
}

}  // namespace eulerfsi

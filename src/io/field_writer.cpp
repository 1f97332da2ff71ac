#include "io/field_writer.hpp"
#include "io/disk_space.hpp"

#include <hdf5.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace eulerfsi {

namespace fs = std::filesystem;

FieldWriter::FieldWriter(const Grid& grid, MPI_Comm comm, std::string run_dir)
    : grid_(grid), comm_(comm), dir_(std::move(run_dir)) {}

void write_hdf5_field(long file_id, const Grid& g, const std::string& name, const Field3& f) {
  const hid_t file = static_cast<hid_t>(file_id);
  const hsize_t gdims[3] = {hsize_t(g.n[2]), hsize_t(g.n[1]), hsize_t(g.n[0])};
  const hsize_t ldims[3] = {hsize_t(g.n[2]), hsize_t(g.n[1]), hsize_t(g.nx_local)};
  const hsize_t start[3] = {0, 0, hsize_t(g.x_offset)};
  // transpose the owned cells to (z, y, x) on the host: I/O is the only place fields leave the device
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  std::vector<double> buf(size_t(g.n[2]) * g.n[1] * g.nx_local);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.nx_local; ++i)
        buf[(size_t(k) * g.n[1] + j) * g.nx_local + i] = host(i + kGhost, j + kGhost, k + kGhost);
  hid_t fspace = H5Screate_simple(3, gdims, nullptr);
  hid_t mspace = H5Screate_simple(3, ldims, nullptr);
  hid_t dset = H5Dcreate2(file, name.c_str(), H5T_NATIVE_DOUBLE, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, ldims, nullptr);
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  const herr_t status = H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, dxpl, buf.data());
  H5Pclose(dxpl);
  H5Dclose(dset);
  H5Sclose(mspace);
  H5Sclose(fspace);
  if (status < 0) throw std::runtime_error("writing dataset '" + name + "' failed (disk full?)");
}

void FieldWriter::write(long step, double t, const std::vector<NamedField>& fields, bool velocity_vector,
                        double x_offset) {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  char stem[32];
  std::snprintf(stem, sizeof(stem), "%08ld", step);
  const std::string final_path = dir_ + "/fields/" + stem + ".h5";
  const std::string tmp_path = final_path + ".tmp";
  if (rank == 0) fs::create_directories(dir_ + "/fields");
  MPI_Barrier(comm_);

  const std::string room =
      room_for_file(dir_ + "/fields", std::uint64_t(fields.size()) * grid_.global_cells() * 8, comm_);
  if (!room.empty()) throw std::runtime_error("cannot write '" + tmp_path + "': " + room);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // our own messages, not the library's error dump
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, comm_, MPI_INFO_NULL);
  hid_t file = H5Fcreate(tmp_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  if (file < 0) throw std::runtime_error("cannot create '" + tmp_path + "': is the output directory writable?");
  // every rank makes the same collective calls whatever failed; the ranks agree on the outcome at the end
  names_.clear();
  std::string failed;
  for (const auto& f : fields) {
    try {
      write_hdf5_field(file, grid_, f.name, f.data);
    } catch (const std::exception& e) {
      if (failed.empty()) failed = e.what();
    }
    names_.push_back(f.name);
  }
  hid_t aspace = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(file, "time", H5T_NATIVE_DOUBLE, aspace, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &t);
  H5Aclose(attr);
  attr = H5Acreate2(file, "frame_x", H5T_NATIVE_DOUBLE, aspace, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &x_offset);
  H5Aclose(attr);
  H5Sclose(aspace);
  // the flush writes what is left, so that the close cannot fail
  if (failed.empty() && H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) failed = "writing '" + tmp_path + "' failed (disk full?)";
  int bad = failed.empty() ? 0 : 1;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_);
  if (bad) {
    // a snapshot that could not be completed is removed, never left half-written. The close must
    // succeed (a file HDF5 fails to close stays half-open and crashes the library's own clean-up
    // in MPI_Finalize): emptying the file first frees the space its metadata needs.
    MPI_Barrier(comm_);
    std::error_code ec;
    if (rank == 0) fs::resize_file(tmp_path, 0, ec);
    MPI_Barrier(comm_);
    H5Fclose(file);
    if (rank == 0) fs::remove(tmp_path, ec);
    throw std::runtime_error(failed.empty() ? "writing '" + tmp_path + "' failed on another rank (disk full?)" : failed);
  }
  if (H5Fclose(file) < 0) throw std::runtime_error("closing '" + tmp_path + "' failed (disk full?)");
  MPI_Barrier(comm_);
  if (rank == 0) fs::rename(tmp_path, final_path);
  vector_ = velocity_vector;
  history_.push_back({step, t, x_offset});
  if (rank == 0) write_xdmf();
  MPI_Barrier(comm_);
}

void FieldWriter::write_xdmf() const {
  const Grid& g = grid_;
  const std::string path = dir_ + "/fields.xdmf";
  const std::string tmp = path + ".tmp";
  {
    std::ofstream x(tmp);
    char dims[96], cells[96];
    std::snprintf(dims, sizeof(dims), "%d %d %d", g.n[2] + 1, g.n[1] + 1, g.n[0] + 1);
    std::snprintf(cells, sizeof(cells), "%d %d %d", g.n[2], g.n[1], g.n[0]);
    x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
      << "  <Grid Name=\"eulerfsi\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto& [step, t, x_offset] : history_) {
      char stem[32];
      std::snprintf(stem, sizeof(stem), "%08ld", step);
      x << "   <Grid Name=\"step" << stem << "\" GridType=\"Uniform\">\n"
        << "    <Time Value=\"" << t << "\"/>\n"
        << "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
        << "     <DataItem Dimensions=\"3\" Format=\"XML\">" << g.domain_lo(2) << " " << g.domain_lo(1) << " "
        << g.domain_lo(0) + x_offset << "</DataItem>\n"
        << "     <DataItem Dimensions=\"3\" Format=\"XML\">" << g.h[2] << " " << g.h[1] << " " << g.h[0]
        << "</DataItem>\n    </Geometry>\n";
      for (const auto& name : names_) {
        x << "    <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
          << "     <DataItem Dimensions=\"" << cells << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields/"
          << stem << ".h5:/" << name << "</DataItem>\n    </Attribute>\n";
      }
      if (vector_) {
        x << "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Cell\">\n"
          << "     <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2)\" Dimensions=\"" << cells << " 3\">\n";
        for (const char* c : {"u", "v", "w"}) {
          x << "      <DataItem Dimensions=\"" << cells << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields/"
            << stem << ".h5:/" << c << "</DataItem>\n";
        }
        x << "     </DataItem>\n    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n </Domain>\n</Xdmf>\n";
    if (!x) throw std::runtime_error("cannot write '" + tmp + "'");
  }
  fs::rename(tmp, path);
}

}  // namespace eulerfsi

#include "io/checkpoint.hpp"
#include "io/disk_space.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>

namespace eulerfsi {

namespace fs = std::filesystem;

namespace {

constexpr int kFormatVersion = 1;
constexpr const char* kFormatAttr = "eulerfsi_checkpoint";

// ---------------------------------------------------------------- HDF5 plumbing

// Our own messages, never the library's error dump; the caller's handler comes back afterwards.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// Closes an HDF5 handle on every exit path; we only throw at points all ranks agree on, so the
// collective closes still match up.
class Hid {
 public:
  Hid(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Hid() { close(); }
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }
  // the status matters for files: the final flush happens at close
  bool close() {
    const bool good = id_ >= 0 && close_(id_) >= 0;
    id_ = -1;
    return good;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// The innermost HDF5 error description ("truncated file: eof = ..."), for a short reason.
herr_t keep_innermost(unsigned n, const H5E_error2_t* err, void* out) {
  if (n == 0 && err->desc) *static_cast<std::string*>(out) = err->desc;
  return 0;
}
std::string hdf5_reason(const char* fallback) {
  std::string desc;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &desc);
  H5Eclear2(H5E_DEFAULT);
  if (desc.empty()) return fallback;
  if (desc.size() > 160) desc = desc.substr(0, 160) + "...";
  return std::string(fallback) + " (" + desc + ")";
}

void write_attr(hid_t obj, const char* name, hid_t file_type, hid_t mem_type, const void* value, hsize_t n = 0) {
  Hid space(n == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
  Hid attr(H5Acreate2(obj, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), mem_type, value) < 0)
    throw CheckpointError(std::string("cannot write attribute '") + name + "'");
}

// Whether a (scalar or small 1-D) attribute of the expected element count was read; an unreadable
// object header (HDF5's own checksum failed) is not the same as an absent attribute.
enum class Attr { Read, Absent, Unreadable };
Attr try_read_attr(hid_t obj, const char* name, hid_t mem_type, void* value, hssize_t n = 1) {
  const htri_t exists = H5Aexists(obj, name);
  if (exists == 0) return Attr::Absent;
  if (exists < 0) return Attr::Unreadable;
  Hid attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  if (!attr.ok()) return Attr::Unreadable;
  Hid space(H5Aget_space(attr.get()), H5Sclose);
  if (!space.ok() || H5Sget_simple_extent_npoints(space.get()) != n) return Attr::Unreadable;
  return H5Aread(attr.get(), mem_type, value) >= 0 ? Attr::Read : Attr::Unreadable;
}
bool read_attr(hid_t obj, const char* name, hid_t mem_type, void* value, hssize_t n = 1) {
  return try_read_attr(obj, name, mem_type, value, n) == Attr::Read;
}
// Hyperslab of this rank's x-slab in a global (nx, ny, nz) dataspace; an empty slab selects nothing.
void select_slab(hid_t fspace, const Grid& g) {
  const hsize_t start[3] = {hsize_t(g.x_offset), 0, 0};
  const hsize_t count[3] = {hsize_t(g.nx_local), hsize_t(g.n[1]), hsize_t(g.n[2])};
  if (g.nx_local > 0)
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
  else
    H5Sselect_none(fspace);
}

hid_t collective_xfer() {
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  return dxpl;
}

// ---------------------------------------------------------------- MPI agreement

bool all_ok(MPI_Comm comm, bool ok) {
  int mine = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, comm);
  return all == 1;
}

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// Rank 0's bytes on every rank.
void bcast_bytes(MPI_Comm comm, std::string& bytes) {
  unsigned long long n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  bytes.resize(n);
  if (n > 0) MPI_Bcast(bytes.data(), int(n), MPI_CHAR, 0, comm);
}

// Rank 0 decided; every rank throws the same error (or none).
void agree_on_root_error(MPI_Comm comm, std::string error) {
  bcast_bytes(comm, error);
  if (!error.empty()) throw CheckpointError(error);
}

// ---------------------------------------------------------------- meta serialisation (for broadcasts)

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
void put_string(std::string& out, const std::string& s) {
  put(out, std::uint64_t(s.size()));
  out += s;
}
template <class T>
T take(const std::string& in, size_t& pos) {
  T v;
  std::memcpy(&v, in.data() + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}
std::string take_string(const std::string& in, size_t& pos) {
  const auto n = take<std::uint64_t>(in, pos);
  std::string s = in.substr(pos, n);
  pos += n;
  return s;
}

std::string pack(const CheckpointMeta& m, const std::vector<std::uint64_t>& checksums) {
  std::string out;
  put(out, m.step);
  put(out, m.t);
  put(out, m.dpdx);
  put_string(out, m.config_toml);
  put(out, std::uint64_t(m.scalars.size()));
  for (const auto& [k, v] : m.scalars) {
    put_string(out, k);
    put(out, v);
  }
  put(out, m.cells);
  put(out, m.nranks);
  put(out, std::uint64_t(checksums.size()));
  for (auto c : checksums) put(out, c);
  return out;
}

CheckpointMeta unpack(const std::string& in, std::vector<std::uint64_t>& checksums) {
  CheckpointMeta m;
  size_t pos = 0;
  m.step = take<long>(in, pos);
  m.t = take<double>(in, pos);
  m.dpdx = take<double>(in, pos);
  m.config_toml = take_string(in, pos);
  const auto ns = take<std::uint64_t>(in, pos);
  for (std::uint64_t i = 0; i < ns; ++i) {
    std::string k = take_string(in, pos);
    m.scalars[k] = take<double>(in, pos);
  }
  m.cells = take<std::array<int, 3>>(in, pos);
  m.nranks = take<int>(in, pos);
  checksums.resize(take<std::uint64_t>(in, pos));
  for (auto& c : checksums) c = take<std::uint64_t>(in, pos);
  return m;
}

// ---------------------------------------------------------------- field data and checksum

// splitmix64's finaliser: a bijection on 64-bit words with good avalanche.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// This rank's share of the field checksum; the global one is the (wrapping) sum over ranks.
std::uint64_t slab_checksum(const Grid& g, const std::vector<double>& buf) {
  std::uint64_t sum = 0;
  const std::uint64_t first = std::uint64_t(g.x_offset) * g.n[1] * g.n[2];
  for (size_t c = 0; c < buf.size(); ++c) {
    std::uint64_t bits;
    std::memcpy(&bits, &buf[c], sizeof(bits));
    sum += mix(bits ^ mix(first + c + 0x9e3779b97f4a7c15ULL));
  }
  return sum;
}

std::uint64_t global_checksum(MPI_Comm comm, const Grid& g, const std::vector<double>& buf) {
  std::uint64_t mine = slab_checksum(g, buf), all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_UINT64_T, MPI_SUM, comm);
  return all;
}

// FNV-1a over the bytes: the string's data is raw data, which HDF5 does not checksum for us.
std::uint64_t text_checksum(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

// Owned cells in (x, y, z) order, i.e. exactly this rank's hyperslab of the dataset; `outside`
// where the field's window does not reach.
std::vector<double> pack_interior(const Grid& g, const CheckpointSource& src) {
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), src.field.data);
  const Box w = src.field.window();
  std::vector<double> buf(size_t(g.nx_local) * g.n[1] * g.n[2], src.outside);
  size_t c = 0;
  for (int i = kGhost; i < kGhost + g.nx_local; ++i)
    for (int j = kGhost; j < kGhost + g.n[1]; ++j)
      for (int k = kGhost; k < kGhost + g.n[2]; ++k, ++c)
        if (i >= w.lo[0] && i < w.hi[0] && j >= w.lo[1] && j < w.hi[1] && k >= w.lo[2] && k < w.hi[2])
          buf[c] = host(i - w.lo[0], j - w.lo[1], k - w.lo[2]);
  return buf;
}

// Copies the whole field to the host and back so that ghosts keep their values.
void unpack_interior(const Grid& g, const std::vector<double>& buf, const Field3& f) {
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  size_t c = 0;
  for (int i = 0; i < g.nx_local; ++i)
    for (int j = 0; j < g.n[1]; ++j)
      for (int k = 0; k < g.n[2]; ++k) host(i + kGhost, j + kGhost, k + kGhost) = buf[c++];
  Kokkos::deep_copy(f, host);
}

// Programming errors, identical on every rank: no agreement needed.
void check_sources(const Grid& g, const std::vector<CheckpointSource>& fields) {
  std::set<std::string> seen;
  const Box all = g.all();
  for (const auto& f : fields) {
    if (f.name.empty() || f.name.find('/') != std::string::npos || f.name == "." || !seen.insert(f.name).second)
      throw std::invalid_argument("checkpoint field name '" + f.name + "' is empty, contains '/' or repeats");
    const Box w = f.field.window();
    for (int d = 0; d < 3; ++d)
      if (w.lo[d] < all.lo[d] || w.hi[d] > all.hi[d])
        throw std::invalid_argument("checkpoint field '" + f.name + "' reaches beyond the grid");
  }
}

void check_fields(const Grid& g, const std::vector<std::pair<std::string, Field3>>& fields) {
  std::set<std::string> seen;
  for (const auto& [name, f] : fields) {
    if (name.empty() || name.find('/') != std::string::npos || name == "." || !seen.insert(name).second)
      throw std::invalid_argument("checkpoint field name '" + name + "' is empty, contains '/' or repeats");
    for (int d = 0; d < 3; ++d)
      if (int(f.extent(d)) != g.ext(d))
        throw std::invalid_argument("checkpoint field '" + name + "' does not have the grid's extents");
  }
}

// ---------------------------------------------------------------- writing

std::string dir_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// POSIX fsync of a file or directory: rename is only durable once the directory entry is.
bool fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) return false;
  const bool good = ::fsync(fd) == 0;
  ::close(fd);
  return good;
}

void write_field(hid_t group, const Grid& g, const std::string& name, const std::vector<double>& buf,
                 std::uint64_t checksum, hid_t dxpl, bool& ok) {
  const hsize_t gdims[3] = {hsize_t(g.n[0]), hsize_t(g.n[1]), hsize_t(g.n[2])};
  const hsize_t ldims[3] = {hsize_t(g.nx_local), hsize_t(g.n[1]), hsize_t(g.n[2])};
  Hid fspace(H5Screate_simple(3, gdims, nullptr), H5Sclose);
  Hid mspace(H5Screate_simple(3, ldims, nullptr), H5Sclose);
  if (g.nx_local == 0) H5Sselect_none(mspace.get());
  select_slab(fspace.get(), g);
  Hid dset(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, fspace.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
           H5Dclose);
  ok = ok && dset.ok() && H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), dxpl, buf.data()) >= 0;
  if (dset.ok()) write_attr(dset.get(), "checksum", H5T_STD_U64LE, H5T_NATIVE_UINT64, &checksum);
}

void write_string_dataset(hid_t file, const char* name, const std::string& text, hid_t dxpl) {
  // fixed length (parallel HDF5 cannot write variable-length data); HDF5 refuses a size of 0
  Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.empty() ? 1 : text.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  Hid space(H5Screate(H5S_SCALAR), H5Sclose);
  Hid dset(H5Dcreate2(file, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  const char zero = '\0';
  if (!dset.ok() ||
      H5Dwrite(dset.get(), type.get(), H5S_ALL, H5S_ALL, dxpl, text.empty() ? &zero : text.data()) < 0)
    throw CheckpointError(std::string("cannot write dataset '") + name + "'");
  const std::uint64_t sum = text_checksum(text);
  write_attr(dset.get(), "checksum", H5T_STD_U64LE, H5T_NATIVE_UINT64, &sum);
}

void write_meta(hid_t file, const CheckpointMeta& m, hid_t dxpl) {
  const int version = kFormatVersion;
  const long long step = m.step;
  write_attr(file, kFormatAttr, H5T_STD_I32LE, H5T_NATIVE_INT, &version);
  {
    const std::string code = EULERFSI_VERSION;
    Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.get(), code.size());
    write_attr(file, "eulerfsi_version", type.get(), type.get(), code.data());
  }
  write_attr(file, "step", H5T_STD_I64LE, H5T_NATIVE_LLONG, &step);
  write_attr(file, "t", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &m.t);
  write_attr(file, "dpdx", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &m.dpdx);
  write_attr(file, "cells", H5T_STD_I32LE, H5T_NATIVE_INT, m.cells.data(), 3);
  write_attr(file, "nranks", H5T_STD_I32LE, H5T_NATIVE_INT, &m.nranks);
  write_string_dataset(file, "config_toml", m.config_toml, dxpl);
  Hid scalars(H5Gcreate2(file, "scalars", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!scalars.ok()) throw CheckpointError("cannot create group 'scalars'");
  for (const auto& [key, value] : m.scalars)
    write_attr(scalars.get(), key.c_str(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

// Every rank has stopped writing to `path` (collective); rank 0 truncates it to zero bytes.
void release_space(const std::string& path, MPI_Comm comm) {
  MPI_Barrier(comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::error_code ec;
  if (rank == 0) fs::resize_file(path, 0, ec);
  MPI_Barrier(comm);
}

// Writes the complete file at tmp; returns false on any rank's failure (agreed on every rank).
bool write_tmp(const std::string& tmp, const Grid& g, MPI_Comm comm, const CheckpointMeta& m,
               const std::vector<CheckpointSource>& fields, std::string& why) {
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL);
  // superblock v2+: HDF5 checksums its own metadata, ours cover the data
  H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  Hid file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!all_ok(comm, file.ok())) {
    why = "cannot create it (is the directory writable?)";
    return false;
  }
  Hid dxpl(collective_xfer(), H5Pclose);
  write_meta(file.get(), m, dxpl.get());
  Hid group(H5Gcreate2(file.get(), "fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  bool ok = group.ok();
  for (const auto& f : fields) {
    const auto buf = pack_interior(g, f);
    write_field(group.get(), g, f.name, buf, global_checksum(comm, g, buf), dxpl.get(), ok);
  }
  group.close();
  // H5Fflush makes every rank MPI_File_sync its own writes; H5Fclose alone does not sync
  ok = ok && H5Fflush(file.get(), H5F_SCOPE_GLOBAL) >= 0;
  if (!all_ok(comm, ok)) {
    // the close must succeed: a file HDF5 fails to close stays half-open and crashes the
    // library's own clean-up in MPI_Finalize. Emptying it frees the space its metadata needs.
    release_space(tmp, comm);
    file.close();
    why = "writing failed (disk full?)";
    return false;
  }
  ok = file.close();
  if (!all_ok(comm, ok)) why = "writing failed (disk full?)";
  return why.empty();
}

// Rank 0: keeps the checkpoint being replaced as path.prev, never leaving `path` missing.
std::string keep_as_previous(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return "";
  const std::string prev = path + ".prev", prev_tmp = prev + ".tmp";
  fs::remove(prev_tmp, ec);
  fs::create_hard_link(path, prev_tmp, ec);
  if (ec) {  // a file system without hard links: copy instead
    ec.clear();
    fs::copy_file(path, prev_tmp, fs::copy_options::overwrite_existing, ec);
    if (!ec && !fsync_path(prev_tmp, false)) ec = std::make_error_code(std::errc::io_error);
  }
  if (!ec) fs::rename(prev_tmp, prev, ec);
  return ec ? "cannot keep the previous checkpoint as '" + prev + "': " + ec.message() : "";
}

// Rank 0: makes tmp durable, then atomically makes it `path`, then makes the rename durable.
std::string publish(const std::string& tmp, const std::string& path, bool keep_previous) {
  if (!fsync_path(tmp, false)) return "cannot fsync '" + tmp + "'";
  if (keep_previous) {
    const std::string err = keep_as_previous(path);
    if (!err.empty()) return err;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) return "cannot rename '" + tmp + "' to '" + path + "': " + ec.message();
  if (!fsync_path(dir_of(path), true)) return "cannot fsync the directory of '" + path + "'";
  return "";
}

// ---------------------------------------------------------------- reading

bool dataset_has_dims(hid_t dset, const std::array<int, 3>& cells) {
  Hid space(H5Dget_space(dset), H5Sclose);
  hsize_t dims[3] = {0, 0, 0};
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 3) return false;
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  for (int d = 0; d < 3; ++d)
    if (dims[d] != hsize_t(cells[d])) return false;
  return true;
}

// false if absent or unreadable; `intact` says whether its checksum matched
bool read_string_dataset(hid_t file, const char* name, std::string& text, bool& intact) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return false;
  Hid dset(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) return false;
  Hid type(H5Dget_type(dset.get()), H5Tclose);
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0) return false;
  std::vector<char> buf(H5Tget_size(type.get()) + 1, '\0');
  if (H5Dread(dset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0) return false;
  text.assign(buf.data(), strnlen(buf.data(), buf.size()));
  std::uint64_t sum = 0;
  if (!read_attr(dset.get(), "checksum", H5T_NATIVE_UINT64, &sum)) return false;
  intact = sum == text_checksum(text);
  return true;
}

herr_t collect_scalar(hid_t loc, const char* name, const H5A_info_t*, void* out) {
  double v = 0.0;
  if (!read_attr(loc, name, H5T_NATIVE_DOUBLE, &v)) return -1;
  (*static_cast<std::map<std::string, double>*>(out))[name] = v;
  return 0;
}

const std::string kDamaged = "is corrupt or truncated: ";

// Reads everything but the field data from an open file; returns what is wrong (after the file's name) or "".
std::string read_meta(hid_t file, CheckpointMeta& m) {
  int version = 0;
  long long step = 0;
  const Attr format = try_read_attr(file, kFormatAttr, H5T_NATIVE_INT, &version);
  if (format == Attr::Unreadable) return kDamaged + hdf5_reason("its root attributes are unreadable");
  if (format == Attr::Absent) return std::string("is not an eulerfsi checkpoint (no '") + kFormatAttr + "' attribute)";
  if (version != kFormatVersion)
    return "has format " + std::to_string(version) + "; this build reads " + std::to_string(kFormatVersion);
  if (!read_attr(file, "step", H5T_NATIVE_LLONG, &step) || !read_attr(file, "t", H5T_NATIVE_DOUBLE, &m.t) ||
      !read_attr(file, "dpdx", H5T_NATIVE_DOUBLE, &m.dpdx) ||
      !read_attr(file, "cells", H5T_NATIVE_INT, m.cells.data(), 3) ||
      !read_attr(file, "nranks", H5T_NATIVE_INT, &m.nranks))
    return kDamaged + "a step/t/dpdx/cells/nranks attribute is missing or unreadable";
  m.step = long(step);
  bool intact = false;
  if (!read_string_dataset(file, "config_toml", m.config_toml, intact))
    return kDamaged + "dataset 'config_toml' is missing or unreadable";
  if (!intact) return "is corrupt: config_toml checksum mismatch";
  Hid scalars(H5Gopen2(file, "scalars", H5P_DEFAULT), H5Gclose);
  if (!scalars.ok() ||
      H5Aiterate2(scalars.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_scalar, &m.scalars) < 0)
    return kDamaged + "group 'scalars' is missing or unreadable";
  return "";
}

std::string cells_text(const int* c) {
  return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]);
}

// Rank 0, serial (sec2) open: everything that can be checked without reading the field data, so
// that a bad file gives one message on every rank instead of a collective open failing unevenly.
std::string prevalidate(const std::string& path, const Grid& g,
                        const std::vector<std::pair<std::string, Field3>>& fields, CheckpointMeta& m,
                        std::vector<std::uint64_t>& checksums) {
  const std::string who = "checkpoint '" + path + "'";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return who + " not found";
  if (H5Fis_hdf5(path.c_str()) <= 0) return who + " is corrupt or truncated: not an HDF5 file";
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_sec2(fapl.get());
  Hid file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file.ok()) return who + " is corrupt or truncated: " + hdf5_reason("HDF5 cannot open it");
  const std::string bad_meta = read_meta(file.get(), m);
  if (!bad_meta.empty()) return who + " " + bad_meta;
  if (m.cells[0] != g.n[0] || m.cells[1] != g.n[1] || m.cells[2] != g.n[2])
    return who + " has a " + cells_text(m.cells.data()) + " grid but this run has " + cells_text(g.n);
  for (const auto& [name, f] : fields) {
    const std::string link = "fields/" + name;
    if (H5Lexists(file.get(), "fields", H5P_DEFAULT) <= 0 || H5Lexists(file.get(), link.c_str(), H5P_DEFAULT) <= 0)
      return who + " has no field '" + name + "'";
    Hid dset(H5Dopen2(file.get(), link.c_str(), H5P_DEFAULT), H5Dclose);
    std::uint64_t sum = 0;
    if (!dset.ok() || !dataset_has_dims(dset.get(), m.cells) ||
        !read_attr(dset.get(), "checksum", H5T_NATIVE_UINT64, &sum))
      return who + " is corrupt or truncated: field '" + name + "' is unreadable or has no checksum";
    checksums.push_back(sum);
  }
  return "";
}

// Collective read of every field's slab; false (on every rank) if any rank failed.
bool read_slabs(const std::string& path, const Grid& g, MPI_Comm comm,
                const std::vector<std::pair<std::string, Field3>>& fields, std::vector<std::vector<double>>& bufs) {
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL);
  Hid file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!all_ok(comm, file.ok())) return false;
  Hid dxpl(collective_xfer(), H5Pclose);
  const hsize_t ldims[3] = {hsize_t(g.nx_local), hsize_t(g.n[1]), hsize_t(g.n[2])};
  bool ok = true;
  for (const auto& [name, f] : fields) {
    bufs.emplace_back(size_t(g.nx_local) * g.n[1] * g.n[2]);
    Hid dset(H5Dopen2(file.get(), ("fields/" + name).c_str(), H5P_DEFAULT), H5Dclose);
    Hid fspace(dset.ok() ? H5Dget_space(dset.get()) : -1, H5Sclose);
    Hid mspace(H5Screate_simple(3, ldims, nullptr), H5Sclose);
    if (g.nx_local == 0) H5Sselect_none(mspace.get());
    if (fspace.ok()) select_slab(fspace.get(), g);
    ok = ok && fspace.ok() &&
         H5Dread(dset.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), dxpl.get(), bufs.back().data()) >= 0;
  }
  return all_ok(comm, ok);
}

}  // namespace

void write_checkpoint(const std::string& path, const Grid& grid, MPI_Comm comm, const CheckpointMeta& meta,
                      const std::vector<CheckpointSource>& fields, bool keep_previous) {
  check_sources(grid, fields);
  const QuietHdf5 quiet;
  const int rank = rank_of(comm);
  // rank 0's meta is the one written: attribute writes must be identical on every rank
  CheckpointMeta m = meta;
  m.cells = {grid.n[0], grid.n[1], grid.n[2]};
  MPI_Comm_size(comm, &m.nranks);
  std::vector<std::uint64_t> none;
  std::string bytes = rank == 0 ? pack(m, none) : std::string();
  bcast_bytes(comm, bytes);
  m = unpack(bytes, none);

  const std::string tmp = path + ".tmp";
  std::string error;
  if (rank == 0) {
    std::error_code ec;
    fs::create_directories(dir_of(path), ec);
  }
  std::string why = room_for_file(dir_of(path), std::uint64_t(fields.size()) * grid.global_cells() * 8 +
                                                    m.config_toml.size(), comm);
  if (!why.empty()) throw CheckpointError("cannot write checkpoint '" + tmp + "': " + why);
  try {
    if (!write_tmp(tmp, grid, comm, m, fields, why)) error = "cannot write checkpoint '" + tmp + "': " + why;
  } catch (const CheckpointError& e) {
    // attribute failures happen identically on every rank (same metadata operations)
    error = "cannot write checkpoint '" + tmp + "': " + e.what();
  }
  if (!all_ok(comm, error.empty()) && error.empty()) error = "cannot write checkpoint '" + tmp + "'";
  if (!error.empty()) {
    std::error_code ec;
    if (rank == 0) fs::remove(tmp, ec);  // a half-written file is of no use to anyone
    throw CheckpointError(error);
  }
  if (rank == 0) error = publish(tmp, path, keep_previous);
  agree_on_root_error(comm, error);
}

CheckpointMeta read_checkpoint(const std::string& path, const Grid& grid, MPI_Comm comm,
                               const std::vector<std::pair<std::string, Field3>>& fields) {
  check_fields(grid, fields);
  const QuietHdf5 quiet;
  const int rank = rank_of(comm);
  CheckpointMeta m;
  std::vector<std::uint64_t> stored;
  std::string error;
  if (rank == 0) error = prevalidate(path, grid, fields, m, stored);
  agree_on_root_error(comm, error);
  std::string bytes = rank == 0 ? pack(m, stored) : std::string();
  bcast_bytes(comm, bytes);
  m = unpack(bytes, stored);

  std::vector<std::vector<double>> bufs;
  if (!read_slabs(path, grid, comm, fields, bufs))
    throw CheckpointError("checkpoint '" + path + "' is corrupt or truncated: reading the field data failed");
  // every field verified before any is touched: a refused checkpoint leaves the state as it was
  for (size_t n = 0; n < fields.size(); ++n)
    if (global_checksum(comm, grid, bufs[n]) != stored[n])
      throw CheckpointError("checkpoint '" + path + "' is corrupt: field '" + fields[n].first + "' checksum mismatch");
  for (size_t n = 0; n < fields.size(); ++n) unpack_interior(grid, bufs[n], fields[n].second);
  return m;
}

}  // namespace eulerfsi

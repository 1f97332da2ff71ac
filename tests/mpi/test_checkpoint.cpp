// Checkpoints round-trip bit for bit and refuse, with one message on every rank, anything damaged.
#include <gtest/gtest.h>
#include <hdf5.h>
#include "parallel/mpi.hpp"
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "grid/grid.hpp"
#include "io/checkpoint.hpp"
#include "support/mpi_env.hpp"

namespace {
namespace fs = std::filesystem;
using eulerfsi::Boundary;
using eulerfsi::CheckpointError;
using eulerfsi::CheckpointMeta;
using eulerfsi::Field3;
using eulerfsi::Grid;
using eulerfsi::kGhost;
using Fields = std::vector<std::pair<std::string, Field3>>;

constexpr double kGhostSentinel = -777.0;

Grid make_grid(const int cells[3], MPI_Comm comm = MPI_COMM_WORLD) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const double len[3] = {3.0, 1.0, 1.0};
  return Grid(cells, len, Boundary::Wall, Boundary::Wall, rank, size);
}

const int kCells[3] = {6, 5, 4};

// Random 64-bit patterns (NaNs, infinities and denormals included) that depend only on the global
// cell, so that any rank count writes the same global field.
std::uint64_t pattern(std::uint64_t seed, int gi, int j, int k) {
  std::uint64_t z = seed * 0x9e3779b97f4a7c15ULL + (std::uint64_t(gi) << 40) + (std::uint64_t(j) << 20) + k;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double as_double(std::uint64_t bits) {
  double v;
  std::memcpy(&v, &bits, sizeof(v));
  return v;
}

std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof(b));
  return b;
}

// Owned cells from the pattern, ghosts set to the sentinel.
Field3 random_field(const Grid& g, const char* name, std::uint64_t seed) {
  auto f = g.make_field(name);
  auto h = Kokkos::create_mirror_view(f);
  Kokkos::deep_copy(h, kGhostSentinel);
  for (int i = 0; i < g.nx_local; ++i)
    for (int j = 0; j < g.n[1]; ++j)
      for (int k = 0; k < g.n[2]; ++k)
        h(i + kGhost, j + kGhost, k + kGhost) = as_double(pattern(seed, i + g.x_offset, j, k));
  Kokkos::deep_copy(f, h);
  return f;
}

Field3 constant_field(const Grid& g, const char* name, double value) {
  auto f = g.make_field(name);
  Kokkos::deep_copy(f, value);
  return f;
}

Field3 sentinel_field(const Grid& g, const char* name) { return constant_field(g, name, kGhostSentinel); }

// Cells that differ from the pattern (bitwise), plus ghosts that are no longer the sentinel.
long mismatches(const Grid& g, const Field3& f, std::uint64_t seed) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  long bad = 0;
  for (int i = 0; i < g.ext(0); ++i)
    for (int j = 0; j < g.ext(1); ++j)
      for (int k = 0; k < g.ext(2); ++k) {
        const bool owned = i >= kGhost && i < kGhost + g.nx_local && j >= kGhost && j < kGhost + g.n[1] &&
                           k >= kGhost && k < kGhost + g.n[2];
        const std::uint64_t want = owned ? pattern(seed, i - kGhost + g.x_offset, j - kGhost, k - kGhost)
                                         : bits_of(kGhostSentinel);
        bad += bits_of(h(i, j, k)) != want;
      }
  long all = 0;
  MPI_Allreduce(&bad, &all, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

long cells_not_equal_to(const Field3& f, double value) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  long bad = 0;
  for (size_t n = 0; n < h.span(); ++n) bad += h.data()[n] != value;
  return bad;
}

CheckpointMeta sample_meta(long step) {
  CheckpointMeta m;
  m.step = step;
  m.t = 0.1 * double(step) + 1e-17;
  m.dpdx = -32.0 / 3.0;
  m.config_toml = "[domain]\ncells = [6, 5, 4]\n# a \"quoted\" comment, ünïcödé\n[output]\ndir = \"runs/x\"\n";
  m.scalars = {{"dt_last", 1.0 / 3.0}, {"bulk target", -0.0}, {"solid[0].volume", 6.02e23}};
  return m;
}

// One scratch directory per test, the same on every rank; removed afterwards.
class Checkpoint : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string d;
    if (eulerfsi::test::rank() == 0) {
      d = (fs::temp_directory_path() / ("eulerfsi_ckpt_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name()))
              .string();
      fs::remove_all(d);
      fs::create_directories(d);
    }
    int n = int(d.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
    d.resize(n);
    MPI_Bcast(d.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
    dir_ = d;
    path_ = dir_ + "/restart.h5";
  }
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (eulerfsi::test::rank() == 0) fs::remove_all(dir_);
  }
  // Runs fn on rank 0 only, with every rank waiting for it.
  template <class F>
  void on_root(F fn) {
    if (eulerfsi::test::rank() == 0) fn();
    MPI_Barrier(MPI_COMM_WORLD);
  }
  // The message of the CheckpointError that reading throws; every rank must throw the same one.
  std::string read_error(const std::string& path, const Grid& g, const Fields& fields) {
    std::string msg = "(no error)";
    try {
      eulerfsi::read_checkpoint(path, g, MPI_COMM_WORLD, fields);
    } catch (const CheckpointError& e) {
      msg = e.what();
    }
    // same length and text everywhere, checked against rank 0's
    std::string root = msg;
    int n = int(root.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
    root.resize(n);
    MPI_Bcast(root.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
    EXPECT_EQ(msg, root) << "ranks disagree";
    return msg;
  }
  std::string dir_, path_;
};

TEST_F(Checkpoint, RoundTripIsBitExactAndKeepsGhosts) {
  const Grid g = make_grid(kCells);
  const Fields out = {{"u", random_field(g, "u", 1)}, {"v", random_field(g, "v", 2)}, {"p", random_field(g, "p", 3)}};
  const CheckpointMeta m = sample_meta(123);
  std::vector<eulerfsi::CheckpointSource> sources;
  for (const auto& [name, f] : out) sources.push_back({name, f});
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, m, sources);

  const Fields in = {{"p", sentinel_field(g, "p")}, {"u", sentinel_field(g, "u")}, {"v", sentinel_field(g, "v")}};
  const CheckpointMeta r = eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, in);
  EXPECT_EQ(mismatches(g, in[0].second, 3), 0);
  EXPECT_EQ(mismatches(g, in[1].second, 1), 0);
  EXPECT_EQ(mismatches(g, in[2].second, 2), 0);
  EXPECT_EQ(r.step, m.step);
  EXPECT_EQ(bits_of(r.t), bits_of(m.t));
  EXPECT_EQ(bits_of(r.dpdx), bits_of(m.dpdx));
  EXPECT_EQ(r.config_toml, m.config_toml);
  ASSERT_EQ(r.scalars.size(), m.scalars.size());
  for (const auto& [k, v] : m.scalars) EXPECT_EQ(bits_of(r.scalars.at(k)), bits_of(v)) << k;
  EXPECT_EQ(r.cells[0], kCells[0]);
  EXPECT_EQ(r.cells[1], kCells[1]);
  EXPECT_EQ(r.cells[2], kCells[2]);
  EXPECT_EQ(r.nranks, eulerfsi::test::nranks());
  EXPECT_FALSE(fs::exists(path_ + ".tmp"));
  EXPECT_FALSE(fs::exists(path_ + ".prev"));  // nothing was replaced
}

TEST_F(Checkpoint, EmptyTextAndNoScalarsRoundTrip) {
  const Grid g = make_grid(kCells);
  CheckpointMeta m;
  m.step = 0;
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, m, {{"u", random_field(g, "u", 4)}});
  const Fields in = {{"u", sentinel_field(g, "u")}};
  const CheckpointMeta r = eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, in);
  EXPECT_EQ(r.config_toml, "");
  EXPECT_TRUE(r.scalars.empty());
  EXPECT_EQ(mismatches(g, in[0].second, 4), 0);
}

TEST_F(Checkpoint, ReadsWhatAnotherRankCountWrote) {
  // rank 0 alone writes the whole grid; every rank reads its own slab of it
  if (eulerfsi::test::rank() == 0) {
    const Grid whole = make_grid(kCells, MPI_COMM_SELF);
    eulerfsi::write_checkpoint(path_, whole, MPI_COMM_SELF, sample_meta(7), {{"u", random_field(whole, "u", 5)}});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const Grid g = make_grid(kCells);
  const Fields in = {{"u", sentinel_field(g, "u")}};
  const CheckpointMeta r = eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, in);
  EXPECT_EQ(r.nranks, 1);
  EXPECT_EQ(r.step, 7);
  EXPECT_EQ(mismatches(g, in[0].second, 5), 0);
}

TEST_F(Checkpoint, MissingFileIsNotFound) {
  const Grid g = make_grid(kCells);
  const std::string missing = dir_ + "/nothing.h5";
  EXPECT_EQ(read_error(missing, g, {{"u", sentinel_field(g, "u")}}), "checkpoint '" + missing + "' not found");
}

TEST_F(Checkpoint, TruncatedFileIsRefusedNamingIt) {
  const Grid g = make_grid(kCells);
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(1), {{"u", random_field(g, "u", 1)}});
  on_root([&] { fs::resize_file(path_, fs::file_size(path_) / 2); });
  const Fields in = {{"u", sentinel_field(g, "u")}};
  const std::string msg = read_error(path_, g, in);
  EXPECT_EQ(msg.rfind("checkpoint '" + path_ + "' is corrupt or truncated: ", 0), 0u) << msg;
  EXPECT_EQ(cells_not_equal_to(in[0].second, kGhostSentinel), 0);
}

TEST_F(Checkpoint, GarbageFileIsRefusedNamingIt) {
  const Grid g = make_grid(kCells);
  on_root([&] { std::ofstream(path_) << "this is not HDF5\n"; });
  const std::string msg = read_error(path_, g, {{"u", sentinel_field(g, "u")}});
  EXPECT_EQ(msg, "checkpoint '" + path_ + "' is corrupt or truncated: not an HDF5 file");
}

// Flips one bit of the first occurrence of `needle` in the file (rank 0); false if it is not there.
bool flip_in_file(const std::string& path, const std::string& needle, size_t byte_in_needle) {
  std::vector<char> bytes;
  {
    std::ifstream f(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  const auto at = std::search(bytes.begin(), bytes.end(), needle.begin(), needle.end());
  if (at == bytes.end()) return false;
  const auto offset = size_t(at - bytes.begin()) + byte_in_needle;
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(std::streamoff(offset));
  const char flipped = char(bytes[offset] ^ 0x10);
  f.write(&flipped, 1);
  return bool(f);
}

TEST_F(Checkpoint, FlippedByteInDataFailsTheChecksum) {
  const Grid g = make_grid(kCells);
  const double marker = 1234.5678;  // eight distinct bytes, repeated over the whole dataset
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(1),
                             {{"p", random_field(g, "p", 9)}, {"u", constant_field(g, "u", marker)}});
  std::string run;  // eight copies: only the dataset's data holds that
  for (int n = 0; n < 8; ++n) run.append(reinterpret_cast<const char*>(&marker), sizeof(marker));
  on_root([&] { ASSERT_TRUE(flip_in_file(path_, run, 3 * 8 + 5)); });  // inside the fourth value
  const Fields in = {{"p", sentinel_field(g, "p")}, {"u", sentinel_field(g, "u")}};
  EXPECT_EQ(read_error(path_, g, in), "checkpoint '" + path_ + "' is corrupt: field 'u' checksum mismatch");
  // refused as a whole: not even the intact field was touched
  EXPECT_EQ(cells_not_equal_to(in[0].second, kGhostSentinel), 0);
  EXPECT_EQ(cells_not_equal_to(in[1].second, kGhostSentinel), 0);
}

TEST_F(Checkpoint, FlippedByteInConfigTextFailsItsChecksum) {
  const Grid g = make_grid(kCells);
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(1), {{"u", random_field(g, "u", 1)}});
  on_root([&] { ASSERT_TRUE(flip_in_file(path_, "\"quoted\" comment", 3)); });
  EXPECT_EQ(read_error(path_, g, {{"u", sentinel_field(g, "u")}}),
            "checkpoint '" + path_ + "' is corrupt: config_toml checksum mismatch");
}

TEST_F(Checkpoint, FlippedByteInMetadataIsCaughtByHdf5) {
  const Grid g = make_grid(kCells);
  CheckpointMeta m = sample_meta(1);
  m.step = 0x0123456789abcdefL;  // eight distinct bytes to find the attribute's value by
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, m, {{"u", random_field(g, "u", 1)}});
  on_root([&] { ASSERT_TRUE(flip_in_file(path_, std::string(reinterpret_cast<const char*>(&m.step), 8), 2)); });
  const std::string msg = read_error(path_, g, {{"u", sentinel_field(g, "u")}});
  EXPECT_EQ(msg.rfind("checkpoint '" + path_ + "' is corrupt or truncated: ", 0), 0u) << msg;
}

TEST_F(Checkpoint, OtherHdf5FileIsNotACheckpoint) {
  const Grid g = make_grid(kCells);
  on_root([&] { H5Fclose(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)); });
  EXPECT_EQ(read_error(path_, g, {{"u", sentinel_field(g, "u")}}),
            "checkpoint '" + path_ + "' is not an eulerfsi checkpoint (no 'eulerfsi_checkpoint' attribute)");
}

TEST_F(Checkpoint, OtherGridIsRefusedNamingBoth) {
  const Grid g = make_grid(kCells);
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(1), {{"u", random_field(g, "u", 1)}});
  const int other_cells[3] = {8, 5, 4};
  const Grid other = make_grid(other_cells);
  const std::string msg = read_error(path_, other, {{"u", sentinel_field(other, "u")}});
  EXPECT_EQ(msg, "checkpoint '" + path_ + "' has a 6x5x4 grid but this run has 8x5x4");
}

TEST_F(Checkpoint, MissingFieldIsRefused) {
  const Grid g = make_grid(kCells);
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(1), {{"u", random_field(g, "u", 1)}});
  const std::string msg = read_error(path_, g, {{"u", sentinel_field(g, "u")}, {"w", sentinel_field(g, "w")}});
  EXPECT_EQ(msg, "checkpoint '" + path_ + "' has no field 'w'");
}

TEST_F(Checkpoint, WriterThatDiedLeavesThePreviousCheckpoint) {
  const Grid g = make_grid(kCells);
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(10), {{"u", random_field(g, "u", 10)}});
  // a writer killed mid-write leaves a partial temporary: half a valid file, then garbage
  on_root([&] {
    fs::copy_file(path_, path_ + ".tmp");
    fs::resize_file(path_ + ".tmp", fs::file_size(path_) / 2);
    std::ofstream(path_ + ".tmp", std::ios::app) << "garbage";
  });
  const Fields in = {{"u", sentinel_field(g, "u")}};
  EXPECT_EQ(eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, in).step, 10);
  EXPECT_EQ(mismatches(g, in[0].second, 10), 0);
  // the next checkpoint simply overwrites the stale temporary
  eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(20), {{"u", random_field(g, "u", 20)}});
  const Fields again = {{"u", sentinel_field(g, "u")}};
  EXPECT_EQ(eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, again).step, 20);
  EXPECT_EQ(mismatches(g, again[0].second, 20), 0);
  EXPECT_FALSE(fs::exists(path_ + ".tmp"));
}

TEST_F(Checkpoint, OverwriteReplacesAndKeepsOnePrevious) {
  const Grid g = make_grid(kCells);
  for (long step : {1, 2, 3})
    eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(step), {{"u", random_field(g, "u", step)}});
  const Fields now = {{"u", sentinel_field(g, "u")}};
  EXPECT_EQ(eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, now).step, 3);
  EXPECT_EQ(mismatches(g, now[0].second, 3), 0);
  const Fields prev = {{"u", sentinel_field(g, "u")}};
  EXPECT_EQ(eulerfsi::read_checkpoint(path_ + ".prev", g, MPI_COMM_WORLD, prev).step, 2);
  EXPECT_EQ(mismatches(g, prev[0].second, 2), 0);
  EXPECT_FALSE(fs::exists(path_ + ".tmp"));
  EXPECT_FALSE(fs::exists(path_ + ".prev.tmp"));
}

TEST_F(Checkpoint, OverwriteWithoutKeepingPrevious) {
  const Grid g = make_grid(kCells);
  for (long step : {1, 2})
    eulerfsi::write_checkpoint(path_, g, MPI_COMM_WORLD, sample_meta(step), {{"u", random_field(g, "u", step)}},
                               /*keep_previous=*/false);
  const Fields now = {{"u", sentinel_field(g, "u")}};
  EXPECT_EQ(eulerfsi::read_checkpoint(path_, g, MPI_COMM_WORLD, now).step, 2);
  EXPECT_EQ(mismatches(g, now[0].second, 2), 0);
  EXPECT_FALSE(fs::exists(path_ + ".prev"));
}

TEST_F(Checkpoint, UnwritableDirectoryIsRefusedOnEveryRank) {
  const Grid g = make_grid(kCells);
  const std::string bad = "/proc/eulerfsi_no_such_dir/restart.h5";
  std::string msg = "(no error)";
  try {
    eulerfsi::write_checkpoint(bad, g, MPI_COMM_WORLD, sample_meta(1), {{"u", random_field(g, "u", 1)}});
  } catch (const CheckpointError& e) {
    msg = e.what();
  }
  EXPECT_EQ(msg.rfind("cannot write checkpoint '" + bad + ".tmp'", 0), 0u) << msg;
}

}  // namespace

// FFTW wisdom beside a checkpoint (poisson/fft_wisdom.hpp): after the stored file is imported into a
// clean FFTW, every transform of the pressure and Helmholtz solvers plans from it alone
// (FFTW_MEASURE | FFTW_WISDOM_ONLY gives null plans, and the solvers throw, for anything the file
// lacks), on 1 and 2 ranks, with z a wall (x-y transforms + tridiagonal z lines) or periodic (3-D).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>
#include <unistd.h>

#include "grid/grid.hpp"
#include "parallel/mpi.hpp"
#include "poisson/helmholtz_solver.hpp"
#include "poisson/poisson_solver.hpp"
#include "support/mpi_env.hpp"

#ifdef EULERFSI_HAVE_MPI
#include <fftw3-mpi.h>

#include "poisson/fft_wisdom.hpp"
#include "poisson/fftw_mpi_poisson.hpp"

namespace {
namespace fs = std::filesystem;
using eulerfsi::Boundary;
using eulerfsi::FftPlanning;
using eulerfsi::Grid;

Grid small_grid(Boundary bz) {
  const int n[3] = {12, 8, 8};
  const double len[3] = {1.5, 1.0, 1.0};
  return Grid(n, len, Boundary::Wall, bz, eulerfsi::test::rank(), eulerfsi::test::nranks());
}

// The solvers a run with implicit viscosity builds, planned as asked; the plans are dropped again.
void build_solvers(const Grid& g, FftPlanning planning) {
  eulerfsi::FftwMpiPoisson pressure(g, MPI_COMM_WORLD, planning);
  const auto viscous = eulerfsi::make_helmholtz_solver(g, MPI_COMM_WORLD, planning);
}

// This rank's wisdom, one entry a line, sorted (FFTW exports its table in no particular order).
std::vector<std::string> wisdom_entries() {
  char* text = fftw_export_wisdom_to_string();
  std::istringstream in(text ? text : "");
  fftw_free(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

// A directory every rank sees, named by rank 0, removed after the test.
class FftWisdom : public ::testing::TestWithParam<Boundary> {
 protected:
  void SetUp() override {
    std::string d;
    if (eulerfsi::test::rank() == 0) {
      d = (fs::temp_directory_path() / ("eulerfsi_wisdom_" + std::to_string(::getpid()))).string();
      fs::remove_all(d);
      fs::create_directories(d);
    }
    int n = int(d.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
    d.resize(size_t(n));
    MPI_Bcast(d.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
    dir_ = d;
    // nothing planned by an earlier test may stand in for the file
    fftw_forget_wisdom();
  }
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (eulerfsi::test::rank() == 0) fs::remove_all(dir_);
    fftw_forget_wisdom();
  }
  void write_on_root(const std::string& path, const std::string& text) {
    if (eulerfsi::test::rank() == 0) std::ofstream(path, std::ios::binary) << text;
    MPI_Barrier(MPI_COMM_WORLD);
  }
  std::string dir_;
};

TEST_P(FftWisdom, StoredWisdomAlonePlansEveryTransform) {
  const Grid g = small_grid(GetParam());
  const std::string path = eulerfsi::fft_wisdom_path(dir_ + "/checkpoint.h5");
  build_solvers(g, FftPlanning::Measure);
  eulerfsi::save_fft_wisdom(path, MPI_COMM_WORLD);
  fftw_forget_wisdom();
  // a clean FFTW has no plan to give: the check below means something
  EXPECT_THROW(build_solvers(g, FftPlanning::WisdomOnly), std::runtime_error);
  std::string why;
  ASSERT_TRUE(eulerfsi::load_fft_wisdom(path, MPI_COMM_WORLD, &why)) << why;
  EXPECT_NO_THROW(build_solvers(g, FftPlanning::WisdomOnly));
}

// Ranks may time the same local transform differently and choose different algorithms: each must
// get back its own choices, not one rank's for all (with fftw_mpi_gather_wisdom + broadcast instead,
// rank 1 lost 1-4 of its ~70 entries to rank 0's choice in each of 6 tries on 2 ranks here).
TEST_P(FftWisdom, EachRankGetsBackExactlyItsOwnChoices) {
  const Grid g = small_grid(GetParam());
  const std::string path = eulerfsi::fft_wisdom_path(dir_ + "/checkpoint.h5");
  build_solvers(g, FftPlanning::Measure);
  const std::vector<std::string> before = wisdom_entries();
  eulerfsi::save_fft_wisdom(path, MPI_COMM_WORLD);
  fftw_forget_wisdom();
  ASSERT_TRUE(eulerfsi::load_fft_wisdom(path, MPI_COMM_WORLD));
  EXPECT_EQ(wisdom_entries(), before);
}

TEST_P(FftWisdom, MissingDamagedOrForeignFileIsRefusedNamingIt) {
  const Grid g = small_grid(GetParam());
  build_solvers(g, FftPlanning::Measure);
  std::string why;
  const std::string missing = dir_ + "/none.fftw-wisdom";
  EXPECT_FALSE(eulerfsi::load_fft_wisdom(missing, MPI_COMM_WORLD, &why));
  EXPECT_NE(why.find(missing), std::string::npos) << why;
  // a refusal leaves no wisdom behind: the run measures afresh rather than half from memory
  EXPECT_THROW(build_solvers(g, FftPlanning::WisdomOnly), std::runtime_error);

  const std::string damaged = dir_ + "/damaged.fftw-wisdom";
  write_on_root(damaged, "eulerfsi-fftw-wisdom 1 ranks 1\nrank 0 bytes 999\n(fftw-3");
  EXPECT_FALSE(eulerfsi::load_fft_wisdom(damaged, MPI_COMM_WORLD, &why));
  EXPECT_NE(why.find("damaged"), std::string::npos) << why;

  const std::string foreign = dir_ + "/foreign.fftw-wisdom";
  write_on_root(foreign, "eulerfsi-fftw-wisdom 1 ranks 3\nrank 0 bytes 0\n\nrank 1 bytes 0\n\nrank 2 bytes 0\n\n");
  EXPECT_FALSE(eulerfsi::load_fft_wisdom(foreign, MPI_COMM_WORLD, &why));
  EXPECT_NE(why.find("written by 3 ranks"), std::string::npos) << why;
}

INSTANTIATE_TEST_SUITE_P(WallOrPeriodicZ, FftWisdom, ::testing::Values(Boundary::Wall, Boundary::Periodic));

}  // namespace
#endif

#include "io/profiles.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "io/csv_writer.hpp"

namespace eulerfsi {

void write_profile(const std::string& path, const CaseConfig& cfg, const Grid& g, MPI_Comm comm,
                   const kernels::Velocity& vel, const Field3& psi_total,
                   double frame_velocity) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[0]);
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[1]);
  auto w = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel.c[2]);
  const bool with_psi = psi_total.extent(0) > 0;
  decltype(u) psi;
  if (with_psi) psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi_total);
  const Box b = g.interior();
  const bool pipe = cfg.domain.geometry == Geometry::Pipe;
  const double dy = g.h[1];
  // pipe: bins of width dy out to R = 1/2; otherwise one bin per y cell
  const int nbins = pipe ? int(std::ceil(0.5 / dy - 1e-12)) : g.n[1];
  const int nq = 5;  // u, v, w, psi, count
  std::vector<double> local(size_t(nbins) * nq, 0.0), global(local.size(), 0.0);
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        int bin = j - kGhost;
        if (pipe) {
          // u sits at the cell centre in the cross-section
          const double y = g.centre(1, j), z = g.centre(2, k);
          bin = int(std::sqrt(y * y + z * z) / dy);
          if (bin >= nbins) continue;
        }
        double* q = &local[size_t(bin) * nq];
        q[0] += u(i, j, k);
        q[1] += 0.5 * (v(i, j, k) + v(i, j - 1, k));
        q[2] += 0.5 * (w(i, j, k) + w(i, j, k - 1));
        q[3] += with_psi ? psi(i, j, k) : 0.0;
        q[4] += 1.0;
      }
  MPI_Reduce(local.data(), global.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
  if (rank != 0) return;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write profile '" + path + "'");
  if (pipe) {
    out << "r,u" << (with_psi ? ",psi" : "") << "\n";
  } else {
    out << "y,u,v,w" << (with_psi ? ",psi" : "") << "\n";
  }
  for (int bin = 0; bin < nbins; ++bin) {
    const double* q = &global[size_t(bin) * nq];
    if (q[4] == 0.0) continue;
    const double coord = pipe ? (bin + 0.5) * dy : g.centre(1, bin + kGhost);
    out << format_number(coord) << "," << format_number(q[0] / q[4] + frame_velocity);
    if (!pipe) out << "," << format_number(q[1] / q[4]) << "," << format_number(q[2] / q[4]);
    if (with_psi) out << "," << format_number(q[3] / q[4]);
    out << "\n";
  }
}

}  // namespace eulerfsi

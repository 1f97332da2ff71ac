#include "app/fault_check.hpp"

#include <cmath>
#include <cstdio>

namespace eulerfsi {

std::string locate_non_finite(const std::vector<std::pair<std::string, WindowField>>& fields, const Grid& g,
                              MPI_Comm comm) {
  int rank = 0, nranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &nranks);
  char msg[256] = "";
  for (const auto& [name, f] : fields) {
    auto data = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f.data);
    const Box w = f.window(), b = intersection(g.interior(), w);
    const int i0 = w.lo[0], j0 = w.lo[1], k0 = w.lo[2];
    auto h = [data, i0, j0, k0](int i, int j, int k) { return data(i - i0, j - j0, k - k0); };
    for (int i = b.lo[0]; i < b.hi[0] && !msg[0]; ++i)
      for (int j = b.lo[1]; j < b.hi[1] && !msg[0]; ++j)
        for (int k = b.lo[2]; k < b.hi[2] && !msg[0]; ++k)
          if (!std::isfinite(h(i, j, k)))
            std::snprintf(msg, sizeof(msg), "field '%s' is %s at cell (%d, %d, %d), x = %.4g, y = %.4g, z = %.4g",
                          name.c_str(), std::isnan(h(i, j, k)) ? "NaN" : "Inf", i - kGhost + g.x_offset, j - kGhost,
                          k - kGhost, g.centre(0, i), g.centre(1, j), g.centre(2, k));
    if (msg[0]) break;
  }
  // the lowest rank with a finding reports
  const int mine = msg[0] ? rank : nranks;
  int first = nranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == nranks) return "";
  MPI_Bcast(msg, sizeof(msg), MPI_CHAR, first, comm);
  return msg;
}

std::string locate_fastest(const Field3 vel[3], const Grid& g, MPI_Comm comm) {
  struct {
    double rate;
    int rank;
  } mine{-1.0, 0}, best{0.0, 0};
  MPI_Comm_rank(comm, &mine.rank);
  char msg[256] = "";
  const Box b = g.interior();
  const char* names[3] = {"u", "v", "w"};
  for (int c = 0; c < 3; ++c) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), vel[c]);
    for (int i = b.lo[0]; i < b.hi[0]; ++i)
      for (int j = b.lo[1]; j < b.hi[1]; ++j)
        for (int k = b.lo[2]; k < b.hi[2]; ++k) {
          const double r = std::fabs(h(i, j, k)) / g.h[c];
          if (r > mine.rate) {
            mine.rate = r;
            std::snprintf(msg, sizeof(msg), "the largest |%s| / h is %.3g, at cell (%d, %d, %d), x = %.4g, y = %.4g, z = %.4g",
                          names[c], r, i - kGhost + g.x_offset, j - kGhost, k - kGhost, g.centre(0, i), g.centre(1, j),
                          g.centre(2, k));
          }
        }
  }
  MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(msg, sizeof(msg), MPI_CHAR, best.rank, comm);
  return msg;
}

}  // namespace eulerfsi

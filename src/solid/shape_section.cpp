#include "solid/shape_section.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "io/csv_writer.hpp"

namespace eulerfsi {

std::vector<ContourSegment> contour_segments(const std::vector<double>& f, int nx, int ns, double x0, double s0,
                                             double dx, double ds, double level) {
  std::vector<ContourSegment> out;
  auto at = [&f, ns](int a, int b) { return f[size_t(a) * ns + b]; };
  // the crossing point on the edge between two samples, by linear interpolation
  auto cross = [level](double xa, double sa, double fa, double xb, double sb, double fb) {
    const double w = (level - fa) / (fb - fa);
    return std::pair<double, double>{xa + w * (xb - xa), sa + w * (sb - sa)};
  };
  for (int a = 0; a + 1 < nx; ++a)
    for (int b = 0; b + 1 < ns; ++b) {
      const double xa = x0 + a * dx, xb = xa + dx, sa = s0 + b * ds, sb = sa + ds;
      const double f00 = at(a, b), f10 = at(a + 1, b), f11 = at(a + 1, b + 1), f01 = at(a, b + 1);
      // corners counter-clockwise: (a,b) (a+1,b) (a+1,b+1) (a,b+1); edges between consecutive corners
      const double cx[4] = {xa, xb, xb, xa}, cs[4] = {sa, sa, sb, sb}, cf[4] = {f00, f10, f11, f01};
      std::vector<std::pair<double, double>> pts;
      for (int e = 0; e < 4; ++e) {
        const int n = (e + 1) % 4;
        if ((cf[e] >= level) != (cf[n] >= level)) pts.push_back(cross(cx[e], cs[e], cf[e], cx[n], cs[n], cf[n]));
      }
      // two crossings: one segment; four (saddle): pair them by the cell average
      if (pts.size() == 2) {
        out.push_back({pts[0].first, pts[0].second, pts[1].first, pts[1].second});
      } else if (pts.size() == 4) {
        const bool centre_in = 0.25 * (f00 + f10 + f11 + f01) >= level;
        const bool first_in = f00 >= level;
        const int p = (centre_in == first_in) ? 1 : 0;
        out.push_back({pts[p].first, pts[p].second, pts[(p + 1) % 4].first, pts[(p + 1) % 4].second});
        out.push_back({pts[(p + 2) % 4].first, pts[(p + 2) % 4].second, pts[(p + 3) % 4].first, pts[(p + 3) % 4].second});
      }
    }
  return out;
}

namespace {

// Trilinear interpolation of a cell-centred field at (x, y, z) if this rank owns x, else 0; f holds
// the cells of a window starting at storage index `origin` (0 outside it).
double sample_owned(const HostField3& f, const int origin[3], const Grid& g, double x, double y, double z) {
  const double lo = g.x_offset * g.h[0], hi = (g.x_offset + g.nx_local) * g.h[0];
  if (x < lo || x >= hi) return 0.0;
  const double p[3] = {(x - lo) / g.h[0] - 0.5, (y - g.domain_lo(1)) / g.h[1] - 0.5, (z - g.domain_lo(2)) / g.h[2] - 0.5};
  int i0[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    i0[d] = int(std::floor(p[d]));
    w[d] = p[d] - i0[d];
    i0[d] += kGhost;
  }
  double v = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c) {
        const int i = i0[0] + a - origin[0], j = i0[1] + b - origin[1], k = i0[2] + c - origin[2];
        const bool held = i >= 0 && j >= 0 && k >= 0 && i < int(f.extent(0)) && j < int(f.extent(1)) && k < int(f.extent(2));
        v += (a ? w[0] : 1 - w[0]) * (b ? w[1] : 1 - w[1]) * (c ? w[2] : 1 - w[2]) * (held ? f(i, j, k) : 0.0);
      }
  return v;
}

}  // namespace

void write_shape_sections(const std::string& path, const Grid& g, MPI_Comm comm, const SolidPhase& solids,
                          const std::vector<ParticleState>& states, double frame_offset) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::ofstream out;
  if (rank == 0) {
    out.open(path);
    if (!out) throw std::runtime_error("cannot write shape section '" + path + "'");
    out << "solid,segment,x,s\n";
  }
  const double lx = g.length[0];
  // samples at half the cell size, out to 1.5 diameters around the centre
  const double ds = 0.5 * std::min(g.h[0], std::min(g.h[1], g.h[2]));
  for (size_t n = 0; n < solids.bodies().size(); ++n) {
    const auto& body = solids.bodies()[n];
    const ParticleState& st = states[n];
    auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body.psi.data);
    const double reach = 1.5 * (body.cfg.shape == SolidShape::Sphere ? body.cfg.diameter : body.cfg.thickness);
    const int nx = 2 * int(reach / ds) + 1, ns = nx;
    const double r_c = st.centre[1] * st.radial_dir[1] + st.centre[2] * st.radial_dir[2];
    std::vector<double> local(size_t(nx) * ns, 0.0), global(local.size(), 0.0);
    for (int a = 0; a < nx; ++a)
      for (int b = 0; b < ns; ++b) {
        const double xr = -reach + a * ds, s = r_c - reach + b * ds;
        double x = std::fmod(st.centre[0] - frame_offset + xr, lx);
        if (x < 0) x += lx;
        const double y = s * st.radial_dir[1], z = s * st.radial_dir[2];
        if (std::fabs(y) > 0.5 * g.length[1] - 0.5 * g.h[1] || std::fabs(z) > 0.5 * g.length[2] - 0.5 * g.h[2]) continue;
        local[size_t(a) * ns + b] = sample_owned(psi, body.psi.lo, g, x, y, z);
      }
    MPI_Reduce(local.data(), global.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
    if (rank != 0) continue;
    const auto segs = contour_segments(global, nx, ns, -reach, r_c - reach, ds, ds, 0.5);
    for (size_t k = 0; k < segs.size(); ++k) {
      out << n << "," << k << "," << format_number(segs[k].x0) << "," << format_number(segs[k].s0) << "\n";
      out << n << "," << k << "," << format_number(segs[k].x1) << "," << format_number(segs[k].s1) << "\n";
    }
  }
}

}  // namespace eulerfsi

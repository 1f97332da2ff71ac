#include "solid/paper_model.hpp"

#include <algorithm>
#include <utility>

#include "core/compat.hpp"
#include "core/launch.hpp"
#include "kernels/interface_sharpening.hpp"
#include "kernels/solid_transport.hpp"
#include "kernels/tensor_extension.hpp"
#include "solver/rk3.hpp"

namespace eulerfsi {

namespace {

// The transport of B skips cells whose stencil holds no solid at all (psi below this).
constexpr double kPsiReset = 1e-6;
// B is the solid's own where psi >= 1/2 (the cell centre inside the interface); it is extended
// from there over as many cells as the WENO5 stencil reaches, and is I beyond
// (kernels/tensor_extension.hpp).
constexpr double kPsiSolid = 0.5;
constexpr int kExtensionBand = 3;
// Interface sharpening (opt-in per solid): width eps = h/2 (psi from 0.12 to 0.88 over 2 cells);
// the pseudo-time step (solid.sharpening, in units of h) must stay below h^2 / (6 eps) = h / 3.
constexpr double kSharpenWidth = 0.5;
// Sub-samples per direction for the initial cell volume fraction: error ~ 1/n^2 of a surface cell.
constexpr int kSubsamples = 8;

// psi = fraction of n^3 sub-sampled points of each cell inside the body's initial shape
// (sphere: nearest periodic image).
void fill_volume_fraction(const Field3& psi, const Grid& g, const SolidConfig& s, int n) {
  const double hx = g.h[0], hy = g.h[1], hz = g.h[2], lx = g.length[0];
  // periods for the nearest image (0: a wall direction, no images)
  const double ly = g.bc[1] == Boundary::Periodic ? g.length[1] : 0.0;
  const double lz = g.bc[2] == Boundary::Periodic ? g.length[2] : 0.0;
  const double y0 = g.domain_lo(1), z0 = g.domain_lo(2);
  const int x_off = g.x_offset;
  const bool sphere = s.shape == SolidShape::Sphere;
  const double cx = s.center[0], cy = s.center[1], cz = s.center[2], r = 0.5 * s.diameter;
  const double top = y0 + s.thickness;
  for_each_cell("eulerfsi::solid::volume_fraction", g.all(), KOKKOS_LAMBDA(int i, int j, int k) {
    int inside = 0;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int c = 0; c < n; ++c) {
          const double x = (i - kGhost + x_off + (a + 0.5) / n) * hx;
          const double y = y0 + (j - kGhost + (b + 0.5) / n) * hy;
          const double z = z0 + (k - kGhost + (c + 0.5) / n) * hz;
          if (sphere) {
            double dx = x - cx, dy = y - cy, dz = z - cz;
            dx -= lx * compat::floor(dx / lx + 0.5);  // nearest periodic image
            if (ly > 0.0) dy -= ly * compat::floor(dy / ly + 0.5);
            if (lz > 0.0) dz -= lz * compat::floor(dz / lz + 0.5);
            inside += (dx * dx + dy * dy + dz * dz < r * r) ? 1 : 0;
          } else {
            inside += (y < top) ? 1 : 0;
          }
        }
    psi(i, j, k) = double(inside) / double(n * n * n);
  });
}

}  // namespace

kernels::Tensor6 make_tensor(const Grid& g, const char* label) {
  kernels::Tensor6 t;
  for (int c = 0; c < kernels::kTensorComponents; ++c) t.c[c] = g.make_field(label);
  return t;
}

void set_identity(const kernels::Tensor6& b) {
  for (int c = 0; c < kernels::kTensorComponents; ++c) Kokkos::deep_copy(b.c[c].data, c < 3 ? 1.0 : 0.0);
}

PaperModel::PaperModel(const CaseConfig&, const Grid& grid, const BoundaryConditions& bc, const Comm& comm)
    : grid_(grid), bc_(&bc), comm_(comm), psi_rhs_(grid.make_field("psi_rhs")),
      psi_rhs_old_(grid.make_field("psi_rhs_old")), b_rhs_(make_tensor(grid, "B_rhs")),
      b_rhs_old_(make_tensor(grid, "B_rhs_old")) {}

void PaperModel::set_initial_condition(SolidBody& body) {
  fill_volume_fraction(body.psi.data, grid_, body.cfg, kSubsamples);
  bc_->fill_scalar(body.psi.data);  // periodic images in y and z come from the ghost exchange
  set_identity(body.b);
  set_identity(body.b_prev);
}

void PaperModel::advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  const double gamma = Rk3::gamma[substep], zeta = Rk3::zeta[substep];
  const Box box = grid_.interior();
  // d psi/dt = -div(u psi);  dB/dt = -div(u B) + L B + B L^T   (WENO5 fluxes, RK3)
  kernels::scalar_advection_rhs(psi_rhs_, body.psi.data, vel, grid_.h, box);
  kernels::tensor_transport_rhs(b_rhs_, body.b, vel, body.psi.data, kPsiReset, grid_.h, box);
  // B before the substep becomes B_prev by a swap (no copy); B is written anew from it
  std::swap(body.b, body.b_prev);
  kernels::rk3_scalar_update(body.psi.data, psi_rhs_, psi_rhs_old_, dt, gamma, zeta, box);
  kernels::rk3_tensor_update(body.b, body.b_prev, b_rhs_, b_rhs_old_, dt, gamma, zeta, box);
  std::swap(psi_rhs_, psi_rhs_old_);
  std::swap(b_rhs_, b_rhs_old_);
  clip_conserving(body.psi.data);
  bc_->fill_scalar(body.psi.data);
  // solid.b_extension = false: B transported with the mixture everywhere, as in the paper
  if (body.cfg.b_extension) extend_tensor(body);
  if (substep == 2 && body.cfg.sharpening > 0.0) sharpen(body);
  for (int c = 0; c < kernels::kTensorComponents; ++c) bc_->fill_scalar(body.b.c[c].data);
}

void PaperModel::fill_ghosts(SolidBody& body) {
  bc_->fill_scalar(body.psi.data);
  for (int c = 0; c < kernels::kTensorComponents; ++c) bc_->fill_scalar(body.b.c[c].data);
}

// B outside the solid: the solid's B extended over a band of kExtensionBand cells, I beyond;
// scratch: psi_rhs, which holds nothing the next substep needs.
void PaperModel::extend_tensor(SolidBody& body) {
  // psi's ghosts are fresh; B's are filled once (the sweeps then need no exchange)
  for (int c = 0; c < kernels::kTensorComponents; ++c) bc_->fill_scalar(body.b.c[c].data);
  kernels::extend_tensor(body.b, psi_rhs_, body.psi.data, kPsiSolid, kExtensionBand, grid_.interior());
}

// Bounded and conservative: clip psi to [0, 1], then give the clipped volume back to the
// interface cells in proportion to psi (1 - psi).
void PaperModel::clip_conserving(const Field3& psi) const {
  const Box box = grid_.interior();
  const double removed = comm_.sum(kernels::clip_volume_fraction(psi, box));
  const double weight = comm_.sum(kernels::interface_weight(psi, box));
  if (removed != 0.0 && weight > 0.0)
    kernels::add_to_interface(psi, compat::fmax(-1.0, compat::fmin(1.0, removed / weight)), box);
}

// One conservative sharpening step of psi (Olsson, Kreiss & Zahedi 2007); scratch: the rhs
// buffers, which hold nothing the next substep needs.
void PaperModel::sharpen(SolidBody& body) {
  const Box box = grid_.interior();
  const double h = std::min(grid_.h[0], std::min(grid_.h[1], grid_.h[2]));
  // scratch: B's rhs buffers (normals and the smoothed psi), free between substeps
  const auto& n = b_rhs_;
  kernels::sharpening_step_rhs(psi_rhs_, body.psi.data, n.c[3].data, n.c[0].data, n.c[1].data, n.c[2].data, kSharpenWidth * h, grid_.h, box);
  kernels::rk3_scalar_update(body.psi.data, psi_rhs_, psi_rhs_, body.cfg.sharpening * h, 1.0, 0.0, box);
  clip_conserving(body.psi.data);
  bc_->fill_scalar(body.psi.data);
}

}  // namespace eulerfsi

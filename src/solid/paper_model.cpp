#include "solid/paper_model.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/compat.hpp"
#include "core/launch.hpp"
#include "kernels/bounding_box.hpp"
#include "kernels/interface_sharpening.hpp"
#include "kernels/tensor_extension.hpp"
#include "solver/rk3.hpp"

// Where the paper model's kernels run (the box path), and why it equals the whole slab bit for bit.
// Let P be the bounding box of the cells, ghosts included, where psi != 0 at a substep's start.
//  - rhs: psi's WENO5 flux divergence is exactly 0 where its 19-point star of radius 3 holds no
//    psi (kernels::star_max), and so is B's (it is skipped below psi = 1e-6): both rhs are 0
//    outside R = P grown by 3, cut to the owned cells, and are computed on R only.
//  - update: q = q0 + dt (gamma rhs + zeta rhs_old) changes q only where rhs or rhs_old is
//    non-zero: on U = R joined with the box the memory was written on (the last substep's R).
//    Each rhs buffer is kept 0 outside the box it was last written on (what a new R leaves out is
//    cleared), so the update reads the whole slab's values on U, and outside U the slab's update
//    adds exact zeros.
//  - clip: psi != 0 only on U, where the clip runs; its two global sums are taken in an order
//    fixed by the cells (kernels::clip_volume_fraction_ordered), in which the slab's extra zero
//    terms change no bit. The clip creates no psi where there is none.
//  - extension: B is the solid's own where psi >= 1/2 (inside the new P) and extended 3 cells
//    from there; everywhere else the slab resets B to I. It runs on E = the new P grown by 3, cut
//    to the owned cells (its marks read 3 cells beyond, where every cell with psi >= 1/2 lies);
//    the cells of U outside E are reset to I. Outside U and E, B held I before the substep (by
//    induction: each B buffer differs from I only within the E of its last substep, inside the
//    next U), as the slab's reset leaves it.
//  - ghosts: filled where U and E changed a field, as the slab fills them everywhere.
//  - window: the fields live on the new P grown by 3 (the active box) and by the widest read
//    beyond it (4: the diagnostics' WENO5 dpsi/dt and one more), joined with the memory's box;
//    it moves after the clip, before the extension, which reads 6 cells beyond P.
// The clip also sets psi below 1e-6 to 0 (kPsiFloor), conservatively: without that floor the support
// is not bounded. WENO5 carries values down to the smallest double 3 cells further every substep:
// a sphere 8 cells across in a 64 x 32^2 pipe had psi > 0 on every cell after 10 steps, and psi >
// 1e-12 on 68 of its 70 x-planes after 50 (the shear stretches the halo along x), so no box short
// of the slab would hold it. With the floor the support is the body and its halo above 1e-6: 16 x
// 11 x 10 cells after 10 steps, 27 x 13 x 12 after 140. The floor changes the results against the
// form without it by what the halo below 1e-6 carried: a d = D/5 particle at 128 x 64^2 has the
// same x_c, r/R and D to 5-6 digits after 200 steps; at 24^3 (6 cells per d) r/R moves by 1e-7 and
// D by 1e-6 over 40 steps, with one step where a cell crosses the diagnostics' psi >= 0.05 cut.

namespace eulerfsi {

namespace {

// The transport of B skips cells whose stencil holds no solid at all (psi below this).
constexpr double kPsiReset = 1e-6;
// psi below this is no solid (as for B's transport): the clip sets it to 0 and gives its volume
// back to the interface with the rest of what it removes; it bounds psi's support (above).
constexpr double kPsiFloor = 1e-6;
// B is the solid's own where psi >= 1/2 (the cell centre inside the interface); it is extended
// from there over as many cells as the WENO5 stencil reaches, and is I beyond
// (kernels/tensor_extension.hpp).
constexpr double kPsiSolid = 0.5;
constexpr int kExtensionBand = 3;
// The radius of WENO5's star: an rhs is non-zero only within it of a cell with psi != 0.
constexpr int kStar = 3;
// The widest read around a cell of the active box: the diagnostics' WENO5 dpsi/dt (3 cells) and
// a central difference one beyond; the window holds the active box grown by it.
constexpr int kReach = kGhost + 1;
// Interface sharpening (opt-in per solid): width eps = h/2 (psi from 0.12 to 0.88 over 2 cells);
// the pseudo-time step (solid.sharpening, in units of h) must stay below h^2 / (6 eps) = h / 3.
constexpr double kSharpenWidth = 0.5;
// Sub-samples per direction for the initial cell volume fraction: error ~ 1/n^2 of a surface cell.
constexpr int kSubsamples = 8;
// A window move can take in ghost cells whose images hold psi: they are filled and the support
// found again, which may move the window once more (from a part of a direction to all of it).
constexpr int kMaxMoves = 3;

// psi = fraction of n^3 sub-sampled points of each cell of `box` inside the body's initial shape
// (sphere: nearest periodic image).
void fill_volume_fraction(const WindowField& psi, const Grid& g, const SolidConfig& s, int n, const Box& box) {
  const double hx = g.h[0], hy = g.h[1], hz = g.h[2], lx = g.length[0];
  // periods for the nearest image (0: a wall direction, no images)
  const double ly = g.bc[1] == Boundary::Periodic ? g.length[1] : 0.0;
  const double lz = g.bc[2] == Boundary::Periodic ? g.length[2] : 0.0;
  const double y0 = g.domain_lo(1), z0 = g.domain_lo(2);
  const int x_off = g.x_offset;
  const bool sphere = s.shape == SolidShape::Sphere;
  const double cx = s.center[0], cy = s.center[1], cz = s.center[2], r = 0.5 * s.diameter;
  const double top = y0 + s.thickness;
  for_each_cell("eulerfsi::solid::volume_fraction", box, KOKKOS_LAMBDA(int i, int j, int k) {
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

// f = value on `box` (a device lambda may not sit in a member function).
void fill_cells(const WindowField& f, double value, const Box& box) {
  for_each_cell("eulerfsi::solid::fill_cells", box, KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = value; });
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

PaperModel::PaperModel(const SolidConfig& solid, const CaseConfig&, const Grid& grid, const BoundaryConditions& bc,
                       const Comm& comm)
    : cfg_solid_(solid), grid_(grid), bc_(&bc), comm_(comm),
      clip_rows_("psi_clip_rows", 2 * size_t(grid.ext(0)) * size_t(grid.ext(1))), window_(grid, comm) {}

// A sphere's support is small and found exactly; a layer fills the x-z plane, sharpening has its
// own stencils (experimental: not worth a box path), and B without the extension keeps the
// fluid's strain wherever the body has been (its support has no bound).
bool PaperModel::boxed() const {
  return cfg_solid_.shape == SolidShape::Sphere && cfg_solid_.b_extension && cfg_solid_.sharpening == 0.0;
}

// Every field of the body and of the model, with its value outside the window (B = I, else 0).
std::vector<SolidWindow::Member> PaperModel::window_members(SolidBody& body) {
  std::vector<SolidWindow::Member> m = {{&body.psi, 0.0, "psi"}, {&psi_rhs_, 0.0, "psi_rhs"},
                                        {&psi_rhs_old_, 0.0, "psi_rhs_old"}, {&known_, 0.0, "B_known"}};
  for (int c = 0; c < kernels::kTensorComponents; ++c) {
    const double identity = c < 3 ? 1.0 : 0.0;
    m.push_back({&body.b.c[c], identity, "B"});
    m.push_back({&body.b_prev.c[c], identity, "B_prev"});
    m.push_back({&b_rhs_.c[c], 0.0, "B_rhs"});
    m.push_back({&b_rhs_old_.c[c], 0.0, "B_rhs_old"});
  }
  return m;
}

// The cells a sphere's fields need at its initial position (storage indices of this rank's
// numbering, possibly beyond the slab): the cells a sub-sample inside the sphere may lie in (cell s
// holds samples in (s - 1/2, s + 1/2) h from the centre of cell 0), grown by the active box's band
// and the reach.
Box PaperModel::sphere_need(const SolidConfig& s, const Grid& g) {
  const int margin = kExtensionBand + kReach;
  Box b;
  for (int d = 0; d < 3; ++d) {
    const double x0 = g.centre(d, 0), r = 0.5 * s.diameter;
    b.lo[d] = int(std::floor((s.center[d] - r - x0) / g.h[d] + 0.5)) - margin;
    b.hi[d] = int(std::ceil((s.center[d] + r - x0) / g.h[d] + 0.5)) + margin;
  }
  return b;
}

double PaperModel::window_cells(const SolidConfig& s, const Grid& g, bool x_whole) {
  if (s.shape != SolidShape::Sphere || !s.b_extension || s.sharpening > 0.0) return double(g.all().size());
  Box need = sphere_need(s, g);
  need.lo[0] += g.x_offset;
  need.hi[0] += g.x_offset;
  Box w = SolidWindow::placement(g, need);
  if (x_whole) {
    w.lo[0] = 0;
    w.hi[0] = g.n[0] + 2 * kGhost;
  }
  return double(SolidWindow::local_part(g, w).size());
}

void PaperModel::allocate(SolidBody& body, const Grid&) {
  const auto members = window_members(body);
  if (whole_slab()) {
    window_.hold_whole_slab(members);
  } else {
    window_.hold(sphere_need(cfg_solid_, grid_), members);
  }
}

void PaperModel::set_initial_condition(SolidBody& body) {
  allocate(body, grid_);
  // the sub-sampled shape on every cell of the window (the sphere's whole support, ghosts included)
  fill_volume_fraction(body.psi, grid_, body.cfg, kSubsamples, window_.local());
  fill(body.psi, Box{});  // periodic images in y and z come from the ghost exchange
  set_identity(body.b);
  set_identity(body.b_prev);
  zero_rhs();
  find_support(body);
  follow_support(body);
}

void PaperModel::use_whole_slab(bool on, SolidBody& body) {
  whole_slab_ = on;
  if (on) {
    window_.hold_whole_slab(window_members(body));
    find_support(body);
    return;
  }
  find_support(body);
  follow_support(body);
}

// The ghosts of a field that changed only on `changed` (empty: everywhere; everywhere on the
// whole slab, as the slab's form fills them).
void PaperModel::fill(const WindowField& f, const Box& changed) const {
  if (whole_slab()) {
    bc_->fill_scalar(f.data);
  } else {
    bc_->fill_scalar(f, changed);
  }
}

void PaperModel::fill_body(SolidBody& body, const Box& changed) const {
  fill(body.psi, changed);
  for (int c = 0; c < kernels::kTensorComponents; ++c) {
    fill(body.b.c[c], changed);
    fill(body.b_prev.c[c], changed);
  }
}

// support_ and active_ from psi (the whole slab's form: the owned cells).
void PaperModel::find_support(const SolidBody& body) {
  const Box interior = grid_.interior();
  if (whole_slab()) {
    support_ = active_ = interior;
    return;
  }
  Box s;
  support_ = kernels::known_bounding_box(body.psi, window_.local(), s) ? s : Box{};
  active_ = support_.grown(kExtensionBand, interior);
}

// The window onto the active box and its reach, and the memory's box (the next update reads it).
// Ghost cells a move takes in are filled, and the support found again (their images may hold psi).
// Returns whether it moved.
bool PaperModel::follow_support(SolidBody& body) {
  if (whole_slab()) return false;
  bool moved = false;
  for (int n = 0; n < kMaxMoves; ++n) {
    const Box need = bounding_box(active_.grown(kReach, grid_.all()), rhs_old_written_);
    if (!window_.hold(need, window_members(body))) break;
    moved = true;
    fill_body(body, Box{});
    find_support(body);
  }
  return moved;
}

// Both rhs buffers 0 on the window (nothing written yet).
void PaperModel::zero_rhs() {
  Kokkos::deep_copy(psi_rhs_.data, 0.0);
  Kokkos::deep_copy(psi_rhs_old_.data, 0.0);
  for (int c = 0; c < kernels::kTensorComponents; ++c) {
    Kokkos::deep_copy(b_rhs_.c[c].data, 0.0);
    Kokkos::deep_copy(b_rhs_old_.c[c].data, 0.0);
  }
  rhs_written_ = rhs_old_written_ = Box{};
}

// The rhs buffers 0 where they were last written and the new rhs box leaves out (cells the window
// no longer holds are gone).
void PaperModel::clear_outside(const Box& written, const Box& rhs_box) {
  Box parts[6];
  const int n = difference(intersection(written, window_.local()), rhs_box, parts);
  for (int p = 0; p < n; ++p) {
    fill_cells(psi_rhs_, 0.0, parts[p]);
    for (int c = 0; c < kernels::kTensorComponents; ++c) fill_cells(b_rhs_.c[c], 0.0, parts[p]);
  }
}

void PaperModel::advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  const double gamma = Rk3::gamma[substep], zeta = Rk3::zeta[substep];
  const Box interior = grid_.interior();
  const Box rhs_box = whole_slab() ? interior : support_.grown(kStar, interior);
  // d psi/dt = -div(u psi);  dB/dt = -div(u B) + L B + B L^T   (WENO5 fluxes, RK3)
  clear_outside(rhs_written_, rhs_box);
  kernels::scalar_advection_rhs(psi_rhs_, body.psi, vel, grid_.h, rhs_box);
  kernels::tensor_transport_rhs(b_rhs_, body.b, vel, body.psi, kPsiReset, grid_.h, rhs_box);
  rhs_written_ = rhs_box;
  // psi and B change where the rhs or the memory is non-zero
  const Box updated = bounding_box(rhs_box, rhs_old_written_);
  // B before the substep becomes B_prev by a swap (no copy); B is written anew from it
  std::swap(body.b, body.b_prev);
  kernels::rk3_body_update(body.psi, psi_rhs_, psi_rhs_old_, body.b, body.b_prev, b_rhs_, b_rhs_old_, dt, gamma, zeta,
                           updated);
  std::swap(psi_rhs_, psi_rhs_old_);
  std::swap(b_rhs_, b_rhs_old_);
  std::swap(rhs_written_, rhs_old_written_);
  clip_conserving(body.psi, updated);
  fill(body.psi, updated);
  // where psi is now, and the window onto it before the extension reads around it
  find_support(body);
  const bool moved = follow_support(body);
  const Box changed = moved ? Box{} : updated;
  // solid.b_extension = false: B transported with the mixture everywhere, as in the paper
  if (body.cfg.b_extension) extend_tensor(body, changed);
  if (substep == 2 && body.cfg.sharpening > 0.0) sharpen(body);
  // the extension wrote B on the active box (empty `changed`: everywhere)
  const Box written = changed.empty() ? changed : bounding_box(changed, active_);
  for (int c = 0; c < kernels::kTensorComponents; ++c) fill(body.b.c[c], written);
}

// After a checkpoint was read psi and B are on the whole slab: their ghosts are filled there, the
// support found on it, and every field moves onto the window around it. The memory is 0 (the
// first substep's zeta is 0) and B_prev = B (it is overwritten before the next substep reads it).
void PaperModel::fill_ghosts(SolidBody& body) {
  bc_->fill_scalar(body.psi.data);
  for (int c = 0; c < kernels::kTensorComponents; ++c) bc_->fill_scalar(body.b.c[c].data);
  rhs_written_ = rhs_old_written_ = Box{};
  const Box interior = grid_.interior();
  Box s;
  support_ = whole_slab() ? interior : (kernels::known_bounding_box(body.psi, grid_.all(), s) ? s : Box{});
  active_ = whole_slab() ? interior : support_.grown(kExtensionBand, interior);
  const auto members = window_members(body);
  if (whole_slab()) {
    window_.hold_whole_slab(members);
  } else {
    window_.hold(active_.grown(kReach, grid_.all()), members, true);
  }
  zero_rhs();
  for (int c = 0; c < kernels::kTensorComponents; ++c) Kokkos::deep_copy(body.b_prev.c[c].data, body.b.c[c].data);
}

// B outside the solid: the solid's own B extended over a band of kExtensionBand cells, I beyond,
// on the active box; the cells `updated` left beyond it have no solid within the band: I.
// `updated`: where the update changed B (empty: everywhere).
void PaperModel::extend_tensor(SolidBody& body, const Box& updated) {
  // psi's ghosts are fresh; B's are filled once (the sweeps then need no exchange)
  for (int c = 0; c < kernels::kTensorComponents; ++c) fill(body.b.c[c], updated);
  const Box box = active_;
  if (!box.empty()) kernels::extend_tensor(body.b, known_, body.psi, kPsiSolid, kExtensionBand, box);
  Box parts[6];
  const Box stale = updated.empty() ? intersection(window_.local(), grid_.interior()) : updated;
  const int n = difference(stale, box, parts);
  for (int p = 0; p < n; ++p) kernels::reset_tensor(body.b, parts[p]);
}

// Bounded and conservative: clip psi to [0, 1], then give the clipped volume back to the
// interface cells in proportion to psi (1 - psi). `box`: every owned cell where psi may be non-zero.
void PaperModel::clip_conserving(const WindowField& psi, const Box& box) {
  const kernels::ClipSums local = kernels::clip_volume_fraction_ordered(psi, clip_rows_, kPsiFloor, box);
  const double removed = comm_.sum(local.removed);
  const double weight = comm_.sum(local.weight);
  if (removed != 0.0 && weight > 0.0)
    kernels::add_to_interface(psi, compat::fmax(-1.0, compat::fmin(1.0, removed / weight)), box);
}

// One conservative sharpening step of psi (Olsson, Kreiss & Zahedi 2007), on the whole slab (a
// sharpened body keeps it); scratch: the rhs buffers, which hold nothing the next substep needs.
void PaperModel::sharpen(SolidBody& body) {
  const Box box = grid_.interior();
  const double h = std::min(grid_.h[0], std::min(grid_.h[1], grid_.h[2]));
  // scratch: B's rhs buffers (normals and the smoothed psi), free between substeps
  const auto& n = b_rhs_;
  kernels::sharpening_step_rhs(psi_rhs_.data, body.psi.data, n.c[3].data, n.c[0].data, n.c[1].data, n.c[2].data,
                               kSharpenWidth * h, grid_.h, box);
  kernels::rk3_scalar_update(body.psi, psi_rhs_, psi_rhs_, body.cfg.sharpening * h, 1.0, 0.0, box);
  clip_conserving(body.psi, box);
  bc_->fill_scalar(body.psi.data);
}

}  // namespace eulerfsi

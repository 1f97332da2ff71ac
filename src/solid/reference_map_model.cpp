#include "solid/reference_map_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/launch.hpp"
#include "kernels/smooth_band_fit.hpp"
#include "kernels/tensor_extension.hpp"
#include "solid/paper_model.hpp"
#include "solver/rk3.hpp"

namespace eulerfsi {

namespace {

// Extrapolation sweeps: the WENO5 stencil of a solid cell reads 3 cells outward, and the central
// differences of psi and B at level 3 one cell beyond it, so q is known 3 cells beyond the body
// (levels 2-4). A fourth sweep would only feed stencils at level 4, where psi is 0 and the results
// are not used (with it, 200 steps of a pipe particle differ by 5e-9 in r/R and 1e-7 in D).
constexpr int kBand = 3;
// psi and B are derived up to level 3 (Chebyshev distance 2 from the solid): a level-4 cell is at
// least 2 cells from the surface, beyond psi's half-width (kHalfWidthCells), so psi = 0 there and
// B, which enters only as psi G (B - I), is not needed.
constexpr double kMaxDerivedLevel = 3.0;
// ... which lie within (Chebyshev) kMaxDerivedLevel - 1 cells of a solid cell.
constexpr int kPsiReach = int(kMaxDerivedLevel) - 1;
// A cell may turn solid only if it was within 2 cells of the body (level <= 3): the body moves
// less than one cell per step (CFL < 1), and farther cells were advected with stale neighbours.
constexpr double kSolidReach = 3.0;
// solid.map_margin (cells): the map is carried only on cells deeper than that inside the surface;
// the outer layer takes the least-squares extension of the deeper cells, as the fluid side does.
// 0.5 stops the drift of labels carried in that layer by stencils that straddle the surface (a stiff
// shear particle at Re_p 0.5, Ca = 0.0125, 8 cells per d: inclination 0.790 against 0.845, theory
// 0.770), but the layer slaved to the deeper cells feeds the body's elastic oscillation where
// viscosity damps it weakly (Re = 200, We = 0.125 released in a pipe: it never decays, D grows to
// 0.15); so 0 by default (docs/REFERENCE_MAP.md, "The margin and the elastic oscillation").
// Half-width of the smoothed Heaviside, in cells along the surface normal: psi goes from 0 to 1
// over 3 cells.
constexpr double kHalfWidthCells = 1.5;

// The widest read around a cell of the active box: WENO5's three cells and the central
// differences one beyond (the window holds the active box grown by it).
constexpr int kReach = kGhost + 1;

// Newton steps on the level shift at t = 0 (each divides the volume error by ~30).
constexpr int kInitialVolumeIterations = 6;

// Volume of the reference shape: the sphere's, or the layer's (y < y_top across the whole x-z plane).
double exact_volume(const SolidConfig& s, const Grid& g) {
  if (s.shape == SolidShape::Sphere) return M_PI / 6.0 * s.diameter * s.diameter * s.diameter;
  return s.thickness * g.length[0] * g.length[2];
}

}  // namespace

ReferenceMapModel::ReferenceMapModel(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid,
                                     const BoundaryConditions& bc, const Comm& comm)
    : cfg_solid_(solid), grid_(grid), bc_(&bc), comm_(comm), window_(grid, comm) {
  shape_.sphere = solid.shape == SolidShape::Sphere;
  for (int a = 0; a < 3; ++a) shape_.centre[a] = solid.center[a];
  shape_.radius = 0.5 * solid.diameter;
  for (int a = 0; a < 3; ++a) shape_.period[a] = grid.bc[a] == Boundary::Periodic ? grid.length[a] : 0.0;
  shape_.top = grid.domain_lo(1) + solid.thickness;
  for (int a = 0; a < 3; ++a) {
    centres_.h[a] = grid.h[a];
    centres_.x0[a] = grid.centre(a, 0);
  }
}

// Every field of the body and of the model, with its value outside the window (B = I; the map
// unknown, level 0; everything else 0).
std::vector<SolidWindow::Member> ReferenceMapModel::window_members(SolidBody& body) {
  std::vector<SolidWindow::Member> m = {{&body.psi, 0.0, "psi"}, {&level_, 0.0, "xi_level"}, {&weight_, 0.0, "xi_weight"}};
  for (int c = 0; c < kernels::kTensorComponents; ++c) {
    const double identity = c < 3 ? 1.0 : 0.0;
    m.push_back({&body.b.c[c], identity, "B"});
    m.push_back({&body.b_prev.c[c], identity, "B_prev"});
  }
  for (int a = 0; a < 3; ++a) {
    m.push_back({&q_.c[a], 0.0, "xi_minus_x"});
    m.push_back({&rhs_.c[a], 0.0, "xi_rhs"});
    m.push_back({&rhs_old_.c[a], 0.0, "xi_rhs_old"});
  }
  m.push_back({&psi_step_start_, 0.0, "psi_step_start"});
  if (psi_other_width_.allocated()) m.push_back({&psi_other_width_, 0.0, "psi_other_width"});
  return m;
}

// The cells a sphere's fields need at its initial position (storage indices of this rank's
// numbering, possibly beyond the slab): its bounding box grown by the band, the active box's
// margin and the reach.
Box ReferenceMapModel::sphere_need(const SolidConfig& s, const Grid& g) {
  const int margin = kBand + 2 + kReach + 1;
  Box b;
  for (int d = 0; d < 3; ++d) {
    const double x0 = g.centre(d, 0), r = 0.5 * s.diameter;
    b.lo[d] = int(std::floor((s.center[d] - r - x0) / g.h[d])) - margin;
    b.hi[d] = int(std::ceil((s.center[d] + r - x0) / g.h[d])) + 1 + margin;
  }
  return b;
}

// The layer (and the whole-slab reference path) needs everything.
Box ReferenceMapModel::initial_window_need() const {
  const Box all = grid_.all();
  if (shape_.sphere && !whole_slab_) return sphere_need(cfg_solid_, grid_);
  return Box{{-kGhost, -kGhost, -kGhost}, {all.hi[0] + kGhost, all.hi[1] + kGhost, all.hi[2] + kGhost}};
}

double ReferenceMapModel::window_cells(const SolidConfig& s, const Grid& g, bool x_whole) {
  if (s.shape != SolidShape::Sphere) return double(g.all().size());
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

void ReferenceMapModel::allocate(SolidBody& body, const Grid&) {
  forget_written();
  const auto members = window_members(body);
  if (whole_slab_) {
    window_.hold_whole_slab(members);
  } else {
    window_.hold(initial_window_need(), members);
  }
}

void ReferenceMapModel::use_whole_slab(bool on, SolidBody& body) {
  whole_slab_ = on;
  forget_written();
  if (on) window_.hold_whole_slab(window_members(body));
  update_active_box(body);
}

void ReferenceMapModel::set_initial_condition(SolidBody& body) {
  allocate(body, grid_);
  for (int a = 0; a < 3; ++a) Kokkos::deep_copy(q_.c[a].data, 0.0);
  for (int a = 0; a < 3; ++a) Kokkos::deep_copy(rhs_old_.c[a].data, 0.0);
  set_identity(body.b);
  Kokkos::deep_copy(body.psi.data, 0.0);
  shape_.shift = 0.0;
  // the owned cells whose stencils the window holds (all of them on a whole direction)
  Box reach = window_.local();
  for (int d = 0; d < 3; ++d) {
    if (reach.lo[d] > 0) reach.lo[d] += kReach;
    if (reach.hi[d] < grid_.all().hi[d]) reach.hi[d] -= kReach;
  }
  const Box box = intersection(grid_.interior(), reach);
  classify(box, true);
  active_ = box;
  extrapolate(box);
  // the smoothed edge adds 8 pi R int_0^eps (1 - H) s ds... = 5.5 % of a sphere 8 cells across:
  // the level is shifted until sum psi dV is the reference shape's exact volume
  volume0_ = exact_volume(body.cfg, grid_);
  derive_solid(body, box);
  for (int it = 0; it < kInitialVolumeIterations; ++it) correct_volume(body, box);
  finish_extrapolation(body, box);
  for (int c = 0; c < kernels::kTensorComponents; ++c) Kokkos::deep_copy(body.b_prev.c[c].data, body.b.c[c].data);
  b_prev_written_ = b_written_;
  update_active_box(body);
}

double ReferenceMapModel::edge_half_width_cells() const { return kHalfWidthCells; }

WindowField ReferenceMapModel::psi_at_half_width(const SolidBody&, double width_cells) {
  if (!psi_other_width_.allocated()) psi_other_width_ = window_.make_field("psi_other_width", 0.0);
  kernels::psi_from_map(psi_other_width_, q_, level_, shape_, centres_, width_cells, kMaxDerivedLevel, grid_.h, active_);
  return psi_other_width_;
}

// The margin in length: along the finest spacing (the layer grids are coarse along the surface).
double ReferenceMapModel::solid_margin() const {
  return cfg_solid_.map_margin * std::min(grid_.h[0], std::min(grid_.h[1], grid_.h[2]));
}

void ReferenceMapModel::advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) {
  const Box box = active_, support = intersection(box, psi_box());
  if (substep == 0) {  // psi and its step-start copy move with one window: the same extents
    Kokkos::deep_copy(psi_step_start_.data, body.psi.data);
    step_inv_dt_ = 1.0 / dt;
  }
  // dq/dt = -u - u . grad q (WENO5, RK3) on the cells that are or may turn solid, all where psi > 0
  kernels::reference_map_rhs(rhs_, q_, level_, body.psi, vel, grid_.h, support);
  kernels::rk3_vector_update(q_, rhs_, rhs_old_, dt, Rk3::gamma[substep], Rk3::zeta[substep], support);
  std::swap(rhs_, rhs_old_);
  fill_map_ghosts(box);
  // the body where it is now, then q outside it again from the body's own values
  classify(box, false);
  blend_fits(box, dt * Rk3::alpha(substep));  // the substep's share of the step
  extrapolate(box);
  store_blend(box);
  // B before the substep becomes B_prev by a swap (no copy; ghosts included): derive_solid writes
  // B anew on the box, and outside it both hold I (the box holds every known cell, grown by 2)
  std::swap(body.b, body.b_prev);
  std::swap(b_written_, b_prev_written_);
  derive_solid(body, box);
  correct_volume(body, box);
  finish_extrapolation(body, box);
  update_active_box(body);
}

// The ramp in length, along the finest spacing as the margin.
double ReferenceMapModel::surface_ramp() const {
  return cfg_solid_.map_ramp * std::min(grid_.h[0], std::min(grid_.h[1], grid_.h[2]));
}

// The smooth band fit's edge ramp over the surface ramp (both in cells), at most 1: weight_ holds
// the surface ramp's weights, from which kernels::edge_weight reads the thinner edge's.
double ReferenceMapModel::band_edge_ratio() const {
  return cfg_solid_.map_ramp > 0.0 ? std::min(1.0, kernels::kBandFitEdgeRamp / cfg_solid_.map_ramp) : 1.0;
}

// The solid where the map now puts it, with each solid cell's weight in the extension; the ghosts
// of both (the fits next to a slab end read the neighbour's cells).
void ReferenceMapModel::classify(const Box& region, bool initial) {
  kernels::classify_solid(level_, weight_, q_, shape_, centres_, kSolidReach, solid_margin(), surface_ramp(), initial,
                          grid_.h, region);
  fill_level(region);
  fill(weight_, region);
}

// The surface ramp's cells take part of the fit through the solid (kernels::surface_fits), read
// from the carried values as the sweeps read them, and stored after the sweeps; rhs_ holds them in
// between (free from the update to the next substep's rhs).
void ReferenceMapModel::blend_fits(const Box& region, double substep_dt) {
  blend_box_ = Box{};
  if (cfg_solid_.map_ramp <= 0.0) return;
  blend_box_ = intersection(region, psi_box());
  // the fraction of the way to the fit a ramp cell goes this substep: all of it, or dt / relax_time
  const double tau = cfg_solid_.map_relax_time;
  const double rate = tau > 0.0 ? std::min(1.0, substep_dt / tau) : 1.0;
  if (blend_box_.empty()) return;
  if (cfg_solid_.map_smooth_band)
    kernels::smooth_surface_fits(q_, level_, weight_, rhs_, blend_box_, rate, band_edge_ratio());
  else
    kernels::surface_fits(q_, level_, weight_, rhs_, blend_box_, rate);
}

void ReferenceMapModel::store_blend(const Box& region) {
  if (cfg_solid_.map_ramp <= 0.0) return;
  if (!blend_box_.empty()) kernels::store_surface_blend(q_, level_, weight_, rhs_, blend_box_);
  fill_map_ghosts(region);
}

// One Newton step on V(shift) = V0 with dV/dshift = the surface area; psi derived again (B, from
// grad q alone, does not depend on the shift).
// Both run where psi may be non-zero (psi_box), the area's central differences one cell beyond
// (also next to a ghost cell of the body's part on the neighbouring rank).
void ReferenceMapModel::correct_volume(SolidBody& body, const Box& region) {
  const Box psi_cells = psi_box(), support = intersection(region, psi_cells);
  double volume = 0.0, area = 0.0;
  kernels::volume_and_area(body.psi, grid_.h, support, intersection(region, psi_cells.grown(1, grid_.all())), volume,
                           area);
  volume = comm_.sum(volume);
  area = comm_.sum(area);
  if (area <= 0.0) return;
  shape_.shift += (volume0_ - volume) / area;
  kernels::psi_at_shift(body.psi, edges(), level_, kMaxDerivedLevel, shape_.shift, support);
  fill(body.psi, region);
}

// Empty where the rank has no solid cell (an empty box stays empty when grown).
Box ReferenceMapModel::psi_box() const {
  if (whole_slab_) return active_;
  return intersection(window_.local(), solid_box_.grown(kPsiReach, grid_.all()));
}

// Extrapolation sweeps 1..kBand, each from the cells known before it; the ghosts between sweeps
// carry what the neighbouring rank (or the periodic image) extrapolated. Sweep s fills only cells
// within s cells (Chebyshev) of a solid cell, so it runs on the solid's bounding box grown by s;
// the box is searched in the ghosts too, where the body's part across a slab end lies: a solid
// cell beyond them is more than kGhost >= kBand cells from every cell of the region.
void ReferenceMapModel::extrapolate(const Box& region) {
  static_assert(kBand <= kGhost, "the solid's bounding box is searched kGhost cells beyond the region");
  Box solid{};
  const Box search = intersection(region.grown(kGhost, grid_.all()), window_.local());
  const bool any = kernels::known_bounding_box(level_, search, solid);
  solid_box_ = any ? solid : Box{};
  for (int sweep = 1; sweep <= kBand; ++sweep) {
    const Box reach = any ? intersection(region, solid.grown(sweep, grid_.all())) : Box{};
    if (!reach.empty()) kernels::extrapolation_sweep(q_, level_, weight_, sweep, reach, sweep == kBand,
                                                        cfg_solid_.map_ramp_in_extension);
    if (sweep == kBand) last_sweep_box_ = reach;
    // every rank exchanges, with or without a body: the halo exchange is collective
    fill_map_ghosts(region);
    fill_level(region);
    // psi's band (levels 2 .. kMaxDerivedLevel) once more, in one fit each (solid.map_smooth_band);
    // the last sweep then fits from it
    if (sweep == int(kMaxDerivedLevel) - 1 && cfg_solid_.map_smooth_band) {
      if (!reach.empty()) kernels::smooth_band_fit(q_, level_, weight_, kMaxDerivedLevel, band_edge_ratio(), reach);
      fill_map_ghosts(region);
    }
  }
}

// The last sweep's cells without a known face neighbour, once psi is final: fitted where the next
// substep's WENO5 stencils read them (kernels::DeferredFits). psi's ghosts are filled, so a cell
// next to a slab end sees the advected cells across it.
void ReferenceMapModel::finish_extrapolation(const SolidBody& body, const Box& region) {
  if (!last_sweep_box_.empty()) kernels::finish_deferred_fits(q_, level_, weight_, body.psi, kBand, last_sweep_box_,
                                                                 cfg_solid_.map_ramp_in_extension);
  fill_map_ghosts(region);
  fill_level(region);
}

// psi and B are derived on psi_box() (every cell of level 1..kMaxDerivedLevel lies there) and
// reset to 0 and I where they were derived before (B's buffer two derivations ago, psi with
// B_prev's one derivation ago); the rest of the region holds 0 and I already.
void ReferenceMapModel::derive_solid(SolidBody& body, const Box& region) {
  const Box derived = intersection(region, psi_box());
  Box cells = region;
  if (!b_written_.everywhere && !b_prev_written_.everywhere)
    cells = intersection(region, bounding_box(derived, bounding_box(b_written_.box, b_prev_written_.box)));
  kernels::solid_from_map(body.psi, body.b, q_, level_, shape_, centres_, kHalfWidthCells, kMaxDerivedLevel, grid_.h, cells,
                          edges());
  b_written_ = Written{derived, false};
  fill(body.psi, region);
  for (int c = 0; c < kernels::kTensorComponents; ++c) fill(body.b.c[c], region);
}

// The known cells move less than a cell per substep: their new bounding box is searched within
// the old active box grown by the ghost width, ghosts included; the window then follows.
void ReferenceMapModel::update_active_box(SolidBody& body) {
  const Box all = window_.local(), interior = grid_.interior();
  if (whole_slab_) {
    active_ = interior;
    return;
  }
  Box search = all, known;
  // a rank without the body searches its whole slab: the body may enter from either side
  if (active_.size() > 0)
    for (int d = 0; d < 3; ++d) {
      search.lo[d] = std::max(all.lo[d], active_.lo[d] - kGhost);
      search.hi[d] = std::min(all.hi[d], active_.hi[d] + kGhost);
    }
  bool any = kernels::known_bounding_box(level_, search, known);
  // Known cells in the x ghost planes belong to the body's part across this slab's x end (its
  // periodic image on one rank, the neighbour's cells on several): they pull the box out to that
  // end, so the cells there are classified and extrapolated before the cells next to the end read
  // them (without this, a band that first reaches x = Lx reads stale q across it and blows up).
  Box ghosts[2] = {all, all}, seen;
  ghosts[0].hi[0] = std::min(all.hi[0], interior.lo[0]);
  ghosts[1].lo[0] = std::max(all.lo[0], interior.hi[0]);
  for (const Box& g : ghosts)
    if (!g.empty() && kernels::known_bounding_box(level_, g, seen)) {
      known = any ? bounding_box(known, seen) : seen;
      any = true;
    }
  if (!any) {
    active_ = Box{{interior.lo[0], interior.lo[1], interior.lo[2]}, {interior.lo[0], interior.lo[1], interior.lo[2]}};
  } else {
    active_ = known.grown(2, interior);
  }
  window_.hold(active_.grown(kReach, grid_.all()), window_members(body));
}

// Periodic directions and ranks by the halo exchange (q is periodic); walls by
// kernels::extrapolate_wall_ghosts (linear extrapolation, or 0 on the wall under a bonded solid).
// q changed only on `changed`: the wall ghosts are extrapolated again on its x-planes, and only at
// a wall it comes within two cells of (the extrapolation reads the first two owned cells).
void ReferenceMapModel::fill_map_ghosts(const Box& changed_box) {
  const Box changed = whole_slab_ ? Box{{0, 0, 0}, {0, 0, 0}} : changed_box;  // empty: everywhere
  for (int a = 0; a < 3; ++a) fill(q_.c[a], changed);
  const Box planes = intersection(wall_ghost_planes(changed), window_.local());
  for (int d = 1; d < 3; ++d) {
    const bool low = near_wall(changed, d, false), high = near_wall(changed, d, true);
    if (low || high) kernels::extrapolate_wall_ghosts(q_, level_, d, grid_.n[d], planes, low, high);
  }
}

// Ghosts of the level: exchanged like any field, but unknown at a wall (kernels::clear_wall_ghosts).
void ReferenceMapModel::fill_level(const Box& changed_box) {
  const Box changed = whole_slab_ ? Box{{0, 0, 0}, {0, 0, 0}} : changed_box;
  fill(level_, changed);
  const Box planes = intersection(wall_ghost_planes(changed), window_.local());
  for (int d = 1; d < 3; ++d) {
    const bool low = near_wall(changed, d, false), high = near_wall(changed, d, true);
    if (low || high) kernels::clear_wall_ghosts(level_, d, grid_.n[d], planes, low, high);
  }
}

// The x-planes whose wall ghosts a change on `changed` (empty: everywhere) can reach: its own,
// or all of them near the x ends, where the halo exchange changed the ghost planes too.
Box ReferenceMapModel::wall_ghost_planes(const Box& changed) const {
  Box planes = grid_.all();
  if (changed.empty() || changed.lo[0] < 2 * kGhost || changed.hi[0] > grid_.nx_local) return planes;
  planes.lo[0] = changed.lo[0];
  planes.hi[0] = changed.hi[0];
  return planes;
}

// Whether direction d has a wall on the low (high) side that a change on `changed` (empty:
// everywhere) comes within two cells of (the wall ghosts read the first two owned cells); a wall
// whose ghosts the window does not hold is farther than that from every cell it holds.
bool ReferenceMapModel::near_wall(const Box& changed, int d, bool high) const {
  if (grid_.bc[d] != Boundary::Wall) return false;
  const Box w = window_.local();
  if (high ? w.hi[d] != grid_.all().hi[d] : w.lo[d] != 0) return false;
  if (changed.empty()) return true;
  return high ? changed.hi[d] > kGhost + grid_.n[d] - 2 : changed.lo[d] < kGhost + 2;
}

// Ghosts of a field that changed only on `changed` (all of them on the whole-slab path, which
// the box path is tested against).
void ReferenceMapModel::fill(const WindowField& f, const Box& changed) const {
  bc_->fill_scalar(f, whole_slab_ ? Box{{0, 0, 0}, {0, 0, 0}} : changed);
}

std::vector<SolidModel::StoredField> ReferenceMapModel::checkpoint_fields() {
  return {{"xi_qx", &q_.c[0], 0.0}, {"xi_qy", &q_.c[1], 0.0}, {"xi_qz", &q_.c[2], 0.0}, {"xi_level", &level_, 0.0}};
}

std::map<std::string, double> ReferenceMapModel::checkpoint_scalars() const {
  return {{"refmap.shift", shape_.shift}, {"refmap.volume0", volume0_}};
}

void ReferenceMapModel::restore_scalars(const std::map<std::string, double>& s) {
  if (s.count("refmap.shift")) shape_.shift = s.at("refmap.shift");
  if (s.count("refmap.volume0")) volume0_ = s.at("refmap.volume0");
}

// After a restore psi, B, q and the level are on the whole slab (a checkpoint stores them so):
// their ghosts are filled there, the body is found on the whole slab, and every field then moves
// onto the window around it.
void ReferenceMapModel::fill_ghosts(SolidBody& body) {
  const Box all = grid_.all(), interior = grid_.interior(), everywhere{{0, 0, 0}, {0, 0, 0}};
  forget_written();
  for (int a = 0; a < 3; ++a) bc_->fill_scalar(q_.c[a], everywhere);
  bc_->fill_scalar(level_, everywhere);
  for (int d = 1; d < 3; ++d)
    if (grid_.bc[d] == Boundary::Wall) {
      kernels::extrapolate_wall_ghosts(q_, level_, d, grid_.n[d], all);
      kernels::clear_wall_ghosts(level_, d, grid_.n[d], all);
    }
  bc_->fill_scalar(body.psi.data);
  for (int c = 0; c < kernels::kTensorComponents; ++c) bc_->fill_scalar(body.b.c[c].data);
  Box known;
  const bool any = kernels::known_bounding_box(level_, all, known);
  active_ = any ? known.grown(2, interior) : Box{{kGhost, kGhost, kGhost}, {kGhost, kGhost, kGhost}};
  // until the next extrapolation finds the solid: every known cell (a box that holds it)
  solid_box_ = any ? known : Box{};
  if (whole_slab_) {
    window_.hold_whole_slab(window_members(body));
    active_ = interior;
  } else {
    window_.hold(active_.grown(kReach, all), window_members(body), true);
  }
}

}  // namespace eulerfsi

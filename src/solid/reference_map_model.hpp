#pragma once
// The reference-map solid model (Kamrin, Rycroft & Nave 2012; Rycroft et al. 2020): the body
// carries the reference displacement q = xi - x (kernels/reference_map.hpp), advected with WENO5;
// outside the body q is extrapolated by least squares over a band as wide as the stencils read;
// psi is a smoothed Heaviside of the distance phi0(xi) / |grad phi0(xi)| (half-width 1.5 cells along
// the normal), and
// B = F F^T with F = (grad xi)^-1. A rigid motion keeps q linear, which WENO5 and the
// extrapolation carry exactly, so a rotating body keeps its shape at 8 cells per diameter.
// The level of phi0 is shifted to give psi the reference shape's exact volume at t = 0 and to
// keep it there (one Newton step per substep on V(shift) with dV/dshift = surface area); the
// shift is checkpointed.
// Shapes: the sphere and the layer (any geometry; q is periodic wherever the domain is).
// Storage: every field of the body (psi, B, B_prev, q, its RK3 memory and level) lives on a window
// that follows the body (src/solid/solid_window.hpp), so its memory follows the body's size.
#include <vector>

#include "kernels/reference_map.hpp"
#include "solid/solid_model.hpp"
#include "solid/solid_window.hpp"

namespace eulerfsi {

class ReferenceMapModel final : public SolidModel {
 public:
  ReferenceMapModel(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc,
                    const Comm& comm);
  void allocate(SolidBody& body, const Grid& grid) override;
  void set_initial_condition(SolidBody& body) override;
  void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  std::vector<StoredField> checkpoint_fields() override;
  std::map<std::string, double> checkpoint_scalars() const override;
  void restore_scalars(const std::map<std::string, double>& s) override;
  void fill_ghosts(SolidBody& body) override;
  Box active_box() const override { return active_; }
  Box psi_box() const override;
  double edge_half_width_cells() const override;
  WindowField psi_at_half_width(const SolidBody& body, double width_cells) override;
  StepStart psi_at_step_start() const override { return {psi_step_start_, step_inv_dt_}; }
  // the map's rhs buffer after the substep's swap: rewritten before the next substep reads it
  kernels::Scratch3 scratch() override { return {{rhs_.c[0], rhs_.c[1], rhs_.c[2]}}; }

  // Every kernel on the whole slab instead of the active box, every field on the whole slab
  // instead of the window: the reference the box is tested against (tests/mpi/test_active_box.cpp);
  // the results agree to round-off.
  void use_whole_slab(bool on, SolidBody& body);
  // Cells of this rank's window for a body at its initial position (x_whole: every x-plane, for a
  // body that crosses the periodic end): what the memory estimate counts.
  static double window_cells(const SolidConfig& s, const Grid& g, bool x_whole);
  // This rank's cells of the window the body's fields are stored on.
  Box window() const { return window_.local(); }
  int window_moves() const { return window_.moves(); }

  // The level shift that keeps the volume (0 without drift).
  double level_shift() const { return shape_.shift; }

 private:
  void fill_map_ghosts(const Box& changed);
  void fill_level(const Box& changed);
  Box wall_ghost_planes(const Box& changed) const;
  bool near_wall(const Box& changed, int d, bool high) const;
  void fill(const WindowField& f, const Box& changed) const;
  void extrapolate(const Box& region);
  void finish_extrapolation(const SolidBody& body, const Box& region);
  double solid_margin() const;
  double surface_ramp() const;
  double band_edge_ratio() const;
  void classify(const Box& region, bool initial);
  void blend_fits(const Box& region, double substep_dt);  // substep_dt: sets the relaxation's rate
  void store_blend(const Box& region);
  void derive_solid(SolidBody& body, const Box& region);
  void update_active_box(SolidBody& body);
  std::vector<SolidWindow::Member> window_members(SolidBody& body);
  Box initial_window_need() const;
  static Box sphere_need(const SolidConfig& s, const Grid& g);
  void correct_volume(SolidBody& body, const Box& region);
  // psi's edge geometry from derive_solid() for correct_volume(), in the scratch (within one
  // substep: the elastic force takes the scratch after it)
  kernels::EdgeFields edges() { return {scratch()}; }

  SolidConfig cfg_solid_;
  Grid grid_;
  const BoundaryConditions* bc_;
  Comm comm_;
  kernels::ReferenceShape shape_;
  kernels::CellCentres centres_;
  kernels::Vector3 q_, rhs_, rhs_old_;
  WindowField level_;
  Box blend_box_;       // where blend_fits left the surface cells' blend
  WindowField weight_;  // each solid cell's weight in the extension (kernels::surface_weight)
  WindowField psi_other_width_;  // the diagnostics' second psi, allocated on first use
  // psi at the start of the last step and 1 / its dt (0 before a step): the radial-momentum
  // budget's dpsi/dt (psi is derived, not transported by the solver's fluxes)
  WindowField psi_step_start_;
  double step_inv_dt_ = 0.0;
  // The owned cells within reach of the body: the bounding box of the known cells (ghosts
  // included, so a body about to cross into this rank's slab is seen) grown by two cells. Every
  // kernel runs on it; outside it q is not used, psi = 0 and B = I.
  Box active_;
  // The bounding box of the solid cells (level 1; ghosts included), set by every extrapolation
  // (after a restore, of every known cell): psi is derived only within two cells of them (psi_box)
  Box solid_box_{};
  // Where the last extrapolation sweep ran: its pending cells wait there for finish_extrapolation()
  Box last_sweep_box_{};
  // Where each B buffer may differ from I: the cells it was last derived on (psi_box() then); psi
  // was last derived with B_prev's buffer (the swap), so it may differ from 0 only on B_prev's box.
  // derive_solid() writes those and today's psi_box(), not the whole active box, whose rim (2-3
  // cells beyond psi_box on every side) held 0 and I already. `everywhere` until the first
  // derivation after an allocation, a restore or a change of path.
  struct Written {
    Box box{};
    bool everywhere = true;
  };
  Written b_written_, b_prev_written_;
  void forget_written() { b_written_ = b_prev_written_ = Written{}; }
  SolidWindow window_;
  double volume0_ = 0.0;
  bool whole_slab_ = false;
};

}  // namespace eulerfsi

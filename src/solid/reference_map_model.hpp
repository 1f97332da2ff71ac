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
#include "kernels/reference_map.hpp"
#include "solid/solid_model.hpp"

namespace eulerfsi {

class ReferenceMapModel final : public SolidModel {
 public:
  ReferenceMapModel(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc,
                    const Comm& comm);
  void set_initial_condition(SolidBody& body) override;
  void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  std::vector<std::pair<std::string, Field3>> checkpoint_fields() override;
  std::map<std::string, double> checkpoint_scalars() const override;
  void restore_scalars(const std::map<std::string, double>& s) override;
  void fill_ghosts(SolidBody& body) override;
  Box active_box() const override { return active_; }
  double edge_half_width_cells() const override;
  Field3 psi_at_half_width(const SolidBody& body, double width_cells) override;

  // Every kernel on the whole slab instead of the active box: the reference the box is tested
  // against (tests/mpi/test_active_box.cpp); the results agree to round-off.
  void use_whole_slab(bool on) {
    whole_slab_ = on;
    update_active_box();
  }

  // The level shift that keeps the volume (0 without drift).
  double level_shift() const { return shape_.shift; }

 private:
  void fill_map_ghosts(const Box& changed);
  void fill_level(const Box& changed);
  Box wall_ghost_planes(const Box& changed) const;
  bool near_wall(const Box& changed, int d) const;
  void fill(const Field3& f, const Box& changed) const;
  void extrapolate(const Box& region);
  double solid_margin() const;
  void derive_solid(SolidBody& body, const Box& region);
  void update_active_box();
  void correct_volume(SolidBody& body, const Box& region);

  Grid grid_;
  const BoundaryConditions* bc_;
  Comm comm_;
  kernels::ReferenceShape shape_;
  kernels::CellCentres centres_;
  kernels::Vector3 q_, rhs_, rhs_old_;
  Field3 level_;
  Field3 psi_other_width_;  // the diagnostics' second psi, allocated on first use
  // The owned cells within reach of the body: the bounding box of the known cells (ghosts
  // included, so a body about to cross into this rank's slab is seen) grown by two cells. Every
  // kernel runs on it; outside it q is not used, psi = 0 and B = I.
  Box active_;
  double volume0_ = 0.0;
  bool whole_slab_ = false;
};

}  // namespace eulerfsi

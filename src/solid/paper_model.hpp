#pragma once
// The paper's solid model (Alghalibi, Rosti & Brandt 2019, after Sugiyama et al. 2011):
//   dpsi/dt + div(u psi) = 0,   dB/dt + div(u B) = L B + B L^T
// both advected with WENO5 fluxes; psi clipped conservatively to [0, 1]; B outside the solid
// extended from it over the WENO reach and I beyond (kernels/tensor_extension.hpp); optional
// interface sharpening (Olsson, Kreiss & Zahedi 2007, experimental).
#include "solid/solid_model.hpp"

namespace eulerfsi {

class PaperModel final : public SolidModel {
 public:
  PaperModel(const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc, const Comm& comm);
  void set_initial_condition(SolidBody& body) override;
  void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  void fill_ghosts(SolidBody& body) override;
  Box active_box() const override { return grid_.interior(); }
  bool diffuse_halo() const override { return true; }
  // B's rhs buffers of the shear components, free between substeps
  kernels::Scratch3 scratch() override { return {{b_rhs_.c[3], b_rhs_.c[4], b_rhs_.c[5]}}; }

 private:
  void sharpen(SolidBody& body);
  void extend_tensor(SolidBody& body);
  void clip_conserving(const Field3& psi) const;

  Grid grid_;
  const BoundaryConditions* bc_;
  Comm comm_;
  Field3 psi_rhs_, psi_rhs_old_;          // RK3 rhs and memory (zeta term)
  kernels::Tensor6 b_rhs_, b_rhs_old_;
};

// B = I, and a tensor field on the grid (shared with the other models and SolidPhase).
void set_identity(const kernels::Tensor6& b);
kernels::Tensor6 make_tensor(const Grid& g, const char* label);

}  // namespace eulerfsi

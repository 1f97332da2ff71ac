#pragma once
// The paper's solid model (Alghalibi, Rosti & Brandt 2019, after Sugiyama et al. 2011):
//   dpsi/dt + div(u psi) = 0,   dB/dt + div(u B) = L B + B L^T
// both advected with WENO5 fluxes; psi clipped conservatively to [0, 1]; B outside the solid
// extended from it over the WENO reach and I beyond (kernels/tensor_extension.hpp); optional
// interface sharpening (Olsson, Kreiss & Zahedi 2007, experimental).
//
// Storage and work follow the body: psi, B, B_prev, their RK3 rhs and memory and the extension's
// marks live on a window around psi's support (src/solid/solid_window.hpp), and every kernel runs
// on the cells where its result can differ from "no body" (psi 0, B = I, rhs 0), found exactly
// from psi's support each substep; the results are those of the whole slab bit for bit
// (tests/mpi/test_paper_box.cpp; the reasoning in paper_model.cpp). A layer, the experimental
// sharpening and solid.b_extension = false keep the whole slab.
#include <vector>

#include "kernels/solid_transport.hpp"
#include "solid/solid_model.hpp"
#include "solid/solid_window.hpp"

namespace eulerfsi {

class PaperModel final : public SolidModel {
 public:
  PaperModel(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc,
             const Comm& comm);
  void allocate(SolidBody& body, const Grid& grid) override;
  void set_initial_condition(SolidBody& body) override;
  void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) override;
  void fill_ghosts(SolidBody& body) override;
  Box active_box() const override { return active_; }
  Box psi_box() const override { return support_; }
  bool diffuse_halo() const override { return true; }
  // B's rhs buffers of the shear components, free between substeps (the next substep's rhs
  // overwrites them: they are written within psi's support grown by two, inside its rhs box)
  kernels::Scratch3 scratch() override { return {{b_rhs_.c[3], b_rhs_.c[4], b_rhs_.c[5]}}; }

  // Every kernel on the whole slab, every field on the whole slab: today's form, which the box
  // path is tested against (tests/mpi/test_paper_box.cpp).
  void use_whole_slab(bool on, SolidBody& body);
  // Whether this body keeps the whole slab (a layer, sharpening, no B extension, or use_whole_slab).
  bool whole_slab() const { return whole_slab_ || !boxed(); }
  // This rank's cells of the window for a body at its initial position (x_whole: every x-plane, for a
  // body that crosses the periodic end): what the memory estimate counts; the slab where the body
  // keeps it.
  static double window_cells(const SolidConfig& s, const Grid& g, bool x_whole);
  Box window() const { return window_.local(); }
  int window_moves() const { return window_.moves(); }

 private:
  bool boxed() const;
  std::vector<SolidWindow::Member> window_members(SolidBody& body);
  static Box sphere_need(const SolidConfig& s, const Grid& g);
  void find_support(const SolidBody& body);
  bool follow_support(SolidBody& body);
  void fill(const WindowField& f, const Box& changed) const;
  void fill_body(SolidBody& body, const Box& changed) const;
  void zero_rhs();
  void clear_outside(const Box& written, const Box& rhs_box);
  void sharpen(SolidBody& body);
  void extend_tensor(SolidBody& body, const Box& updated);
  void clip_conserving(const WindowField& psi, const Box& box);

  SolidConfig cfg_solid_;
  Grid grid_;
  const BoundaryConditions* bc_;
  Comm comm_;
  WindowField psi_rhs_, psi_rhs_old_;  // RK3 rhs and memory (zeta term)
  kernels::Tensor6 b_rhs_, b_rhs_old_;
  WindowField known_;                  // the B extension's marks (kernels/tensor_extension.hpp)
  kernels::RowSums clip_rows_;         // the clip's row sums (kernels::clip_volume_fraction_ordered)
  SolidWindow window_;
  // The bounding box of the cells (ghosts included) where psi != 0 after the last substep; the
  // elastic force and the kernels of the next substep start from it.
  Box support_{};
  // The owned cells where psi != 0 or B != I: support_ grown by the extension's band (every cell
  // B may differ from I lies within 3 cells of a cell with psi >= 1/2).
  Box active_{};
  // The owned cells outside which each rhs buffer holds 0 (where it was last written): the update
  // reads the memory there, and the next write clears what the new rhs box leaves out.
  Box rhs_written_{}, rhs_old_written_{};
  bool whole_slab_ = false;
};

// B = I, and a tensor field on the grid (shared with the other models and SolidPhase).
void set_identity(const kernels::Tensor6& b);
kernels::Tensor6 make_tensor(const Grid& g, const char* label);

}  // namespace eulerfsi

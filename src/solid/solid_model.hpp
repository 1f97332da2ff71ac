#pragma once
// A solid model carries one body's shape psi and deformation B through the flow. The stress
// psi G (B - I), the mixture viscosity, the diagnostics and the output are shared by all models
// (solid_phase.cpp, particle_diagnostics.cpp); a model decides only how psi and B move.
//
// Models (one pair of files each, kernels in kernels/):
//   paper_model.*          psi and B advected with WENO5 (Alghalibi, Rosti & Brandt 2019)
//   reference_map_model.*  the reference map xi advected; psi = H(-phi0(xi)), B = F F^T with
//                          F = (grad xi)^-1 (Kamrin, Rycroft & Nave 2012)
//   rigid_model.*          a rigid sphere: psi from its centre, B = I, the velocity inside made
//                          rigid after each projection (Sharma & Patankar 2005)
// A third model (say Mooney-Rivlin through the reference map, or a viscoelastic shell) derives
// from SolidModel and is added to make_solid_model() and to SolidModelKind in the case config.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "config/case_config.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_body.hpp"
#include "solver/boundary_conditions.hpp"

namespace eulerfsi {

class SolidModel {
 public:
  virtual ~SolidModel() = default;
  // The body's psi, B and B_prev: on the whole slab here; a model that knows where its body is
  // stores them on a window that follows it (src/solid/solid_window.hpp).
  virtual void allocate(SolidBody& body, const Grid& grid);
  // psi of the initial shape and B = I, ghosts filled.
  virtual void set_initial_condition(SolidBody& body) = 0;
  // One RK3 substep: b_prev <- B, then psi and B advanced with vel; ghosts filled on return.
  virtual void advance_substep(SolidBody& body, const kernels::Velocity& vel, double dt, int substep) = 0;
  // A field a checkpoint stores: its name, where it lives, its value outside its window.
  struct StoredField {
    std::string name;
    WindowField* field;
    double outside;
  };
  // Fields a checkpoint stores besides psi and B, under names unique within the body. After a
  // read they may hold the whole slab: fill_ghosts() takes them from there.
  virtual std::vector<StoredField> checkpoint_fields() { return {}; }
  // Scalars a checkpoint stores (e.g. a volume correction), and their restoration.
  virtual std::map<std::string, double> checkpoint_scalars() const { return {}; }
  virtual void restore_scalars(const std::map<std::string, double>&) {}
  // After a checkpoint was read: ghosts of everything the model holds (psi, B and the stored
  // fields may then be on the whole slab).
  virtual void fill_ghosts(SolidBody& body) = 0;
  // Owned cells (storage indices) outside which psi = 0 and B = I exactly, now and after the
  // next substep's update: the shared solid kernels (mixture viscosity, elastic force,
  // diagnostics) run on it only. Empty where the body is not on this rank.
  virtual Box active_box() const = 0;
  // Cells (storage indices, ghosts included) outside which psi = 0 now: the elastic force, which
  // vanishes where psi does, runs on its owned part grown by one. active_box() by default.
  virtual Box psi_box() const { return active_box(); }
  // The half-width of psi's smoothed edge in cells, and psi again at another half-width, where the
  // model derives psi from a sharp shape (the reference map): the diagnostics extrapolate the
  // shape moments to zero width; valid on active_box() (outside it the field is stale). 0 and an
  // empty field where psi is transported (the paper model).
  virtual double edge_half_width_cells() const { return 0.0; }
  // Whether psi carries a faint halo of numerical diffusion (a transported psi: the paper model),
  // which the position, velocity and shape moments leave out (psi < 0.05); a psi derived from a
  // sharp shape has none, and the cut's on/off edge would make those moments jump in time.
  virtual bool diffuse_halo() const { return false; }
  virtual WindowField psi_at_half_width(const SolidBody&, double /*width_cells*/) { return WindowField(); }
  // Where psi is not the solver's conservative WENO transport (the reference map derives it), the
  // radial-momentum budget takes dpsi/dt from psi's change over the last step: psi at that step's
  // start and 1 / its dt (0 before the first step); an empty field where dpsi/dt = -div(u psi).
  struct StepStart {
    WindowField psi;
    double inv_dt = 0.0;
  };
  virtual StepStart psi_at_step_start() const { return {}; }
  // Three fields on psi's window that hold nothing between this model's substeps (its own
  // buffers): the elastic force's shear stresses are written there (kernels::shear_stress), after
  // the model's own use within its substep (the map's edge geometry).
  virtual kernels::Scratch3 scratch() = 0;
  // Whether the body has an elastic stress psi G (B - I) (a rigid body has none).
  virtual bool elastic() const { return true; }
  // A model that acts on the velocity after each projection (the rigid body): constrain_velocity()
  // is then called, and the flow projected again.
  virtual bool constrains_velocity() const { return false; }
  virtual void constrain_velocity(SolidBody&, const kernels::Velocity&, double /*dt*/, int /*substep*/) {}
  // The mean force over the last step that holds the body where its constraint says (0 when free).
  virtual std::array<double, 3> holding_force() const { return {0.0, 0.0, 0.0}; }
};

std::shared_ptr<SolidModel> make_solid_model(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid,
                                             const BoundaryConditions& bc, const Comm& comm);

}  // namespace eulerfsi

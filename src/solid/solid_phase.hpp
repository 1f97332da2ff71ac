#pragma once
// The soft bodies of a case: each carries psi and B, moved by its own model (solid_model.hpp);
// together they give the mixture viscosity and the elastic stress div[ sum_s psi_s G_s (B_s - I) ]
// that the momentum equation feels (the SolidCoupling the flow solver sees).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "config/case_config.hpp"
#include "io/checkpoint.hpp"
#include "grid/grid.hpp"
#include "kernels/momentum.hpp"
#include "parallel/comm.hpp"
#include "solid/solid_body.hpp"
#include "solid/solid_model.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/flow_solver.hpp"
#include "solver/solid_coupling.hpp"

namespace eulerfsi {

class SolidPhase final : public SolidCoupling {
 public:
  SolidPhase(const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc, const Comm& comm);
  bool empty() const { return bodies_.empty(); }
  std::vector<SolidBody>& bodies() { return bodies_; }
  const std::vector<SolidBody>& bodies() const { return bodies_; }

  // Each body's initial shape with B = I.
  void set_initial_condition();
  // Initial velocity "rest": u_face *= 1 - psi_face for the bodies that start at rest.
  void stop_bodies_at_rest(const kernels::Velocity& vel) const;
  // The bounding box of every body's active box (empty: no body on this rank).
  Box active_box() const;
  // Sum of every body's psi (for output), into `out`.
  void total_volume_fraction(const Field3& out) const;
  // sum over bodies of psi G (tr B - 3) / 2, the elastic energy per unit volume
  void elastic_energy_density(const Field3& out) const;

  // SolidCoupling: what the momentum equation needs
  void advance_substep(const kernels::Velocity& vel, double dt, int substep) override;
  void mixture_viscosity(const Field3& mu, double mu_fluid, double background) override;
  Box viscosity_region() const override { return mu_region_; }
  void add_elastic_force(const kernels::Velocity& rhs) const override;
  void add_elastic_force_to_predictor(const kernels::Velocity& rhs, const kernels::Velocity& star,
                                      const kernels::PredictorTerms& terms) const override;
  Box elastic_force_region() const override;
  double max_wave_speed() const override;
  bool constrain_velocity(const kernels::Velocity& vel, double dt, int substep) override;

  // Every field a step starts from, "solid<n>_<name>": psi, B and whatever the model adds, as they
  // are stored (a window, and its value outside) for writing; as fresh whole-slab fields to read
  // a checkpoint into, which restore() then hands to the bodies.
  std::vector<CheckpointSource> checkpoint_sources();
  std::vector<std::pair<std::string, Field3>> checkpoint_fields();
  // Model scalars, "solid<n>.<name>", and their restoration after a checkpoint was read.
  std::vector<std::pair<std::string, double>> checkpoint_scalars() const;
  void restore(const std::vector<std::pair<std::string, double>>& scalars);

 private:
  // The faces add_elastic_force() writes for one body.
  Box elastic_faces(const SolidBody& body) const;
  // add(body, faces) for every body with faces on this rank.
  template <class AddForce>
  void for_each_body_faces(const AddForce& add) const;
  CaseConfig cfg_;
  Grid grid_;
  Comm comm_;
  std::vector<SolidBody> bodies_;
  std::vector<std::pair<std::string, SolidModel::StoredField>> stored_fields();

  Box mu_region_{{0, 0, 0}, {0, 0, 0}};  // where mixture_viscosity() last wrote
  std::vector<std::pair<WindowField*, Field3>> staged_;  // fields a checkpoint is read into
};

// The mean force over the last step that held the body where its constraint says (0 when free).
std::array<double, 3> holding_force(const SolidBody& body);

// The state a run starts from: the flow's initial condition, the bodies' shapes with B = I, zero
// velocity inside bodies that start at rest, then one projection.
void set_initial_state(FlowSolver& flow, SolidPhase& solids);

}  // namespace eulerfsi

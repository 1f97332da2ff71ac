#include "solid/solid_phase.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/launch.hpp"
#include "kernels/elastic_force.hpp"
#include "solid/paper_model.hpp"
#include "solid/radial_hold.hpp"

namespace eulerfsi {

SolidPhase::SolidPhase(const CaseConfig& cfg, const Grid& grid, const BoundaryConditions& bc, const Comm& comm)
    : cfg_(cfg), grid_(grid), comm_(comm) {
  for (const auto& s : cfg.solids) {
    SolidBody body;
    body.cfg = s;
    body.G = 1.0 / s.We;
    body.mu_s = s.viscosity_ratio / cfg.flow.Re;
    body.model = make_solid_model(s, cfg, grid, bc, comm);
    body.model->allocate(body, grid);
    // a rigid body holds itself (its model constrains its motion); a soft one through a body force
    if (s.constraint == SolidConstraint::Radial && body.model->elastic())
      body.hold = std::make_shared<RadialHold>(s, grid, comm);
    bodies_.push_back(std::move(body));
  }
}

void SolidPhase::set_initial_condition() {
  for (auto& body : bodies_) body.model->set_initial_condition(body);
}

void SolidPhase::stop_bodies_at_rest(const kernels::Velocity& vel) const {
  for (const auto& body : bodies_) {
    if (body.cfg.initial_velocity != InitialSolidVelocity::Rest) continue;
    const WindowField psi = body.psi;
    // faces whose two cells the window holds (psi = 0 on the window's outer cells)
    Box faces = body.psi.window();
    for (int d = 0; d < 3; ++d) faces.hi[d] -= 1;
    faces = intersection(faces, grid_.interior());
    for (int c = 0; c < 3; ++c) {
      const Field3 u = vel.c[c];
      const int di = c == 0, dj = c == 1, dk = c == 2;
      // the face lies between cell (i,j,k) and the next one along c
      for_each_cell("eulerfsi::solid::stop_at_rest", faces, KOKKOS_LAMBDA(int i, int j, int k) {
        u(i, j, k) *= 1.0 - 0.5 * (psi(i, j, k) + psi(i + di, j + dj, k + dk));
      });
    }
  }
}

void SolidPhase::total_volume_fraction(const Field3& out) const {
  Kokkos::deep_copy(out, 0.0);
  for (const auto& body : bodies_) kernels::mixture_viscosity_add(out, body.psi, 1.0, body.psi.window());
}

void SolidPhase::elastic_energy_density(const Field3& out) const {
  Kokkos::deep_copy(out, 0.0);
  for (const auto& body : bodies_)
    kernels::elastic_energy_add(out, body.psi, body.b, body.G, body.model->active_box());
}

void SolidPhase::advance_substep(const kernels::Velocity& vel, double dt, int substep) {
  for (auto& body : bodies_) body.model->advance_substep(body, vel, dt, substep);
}

Box SolidPhase::active_box() const {
  Box box{{0, 0, 0}, {0, 0, 0}};
  for (const auto& body : bodies_) box = bounding_box(box, body.model->active_box());
  return box;
}

// mu = background where the previous call wrote, then background + sum psi (mu_s - mu_f) on the
// bodies' box with its ghosts (psi = 0 beyond it). Bodies as viscous as the fluid (the paper's
// mu_s/mu_f = 1) leave mu uniform: no region, so the momentum kernel keeps its constant-mu path.
void SolidPhase::mixture_viscosity(const Field3& mu, double mu_fluid, double background) {
  kernels::fill_box(mu, background, mu_region_);
  bool variable = false;
  for (const auto& body : bodies_) variable = variable || body.mu_s != mu_fluid;
  if (!variable) {
    mu_region_ = Box{{0, 0, 0}, {0, 0, 0}};
    return;
  }
  mu_region_ = active_box().grown(kGhost, grid_.all());
  kernels::fill_box(mu, background, mu_region_);
  for (const auto& body : bodies_)
    kernels::mixture_viscosity_add(mu, body.psi, body.mu_s - mu_fluid, intersection(mu_region_, body.psi.window()));
}

// The force on a face reads psi one cell beyond it: the cells where psi may be non-zero, grown by one.
Box SolidPhase::elastic_faces(const SolidBody& body) const { return body.model->psi_box().grown(1, grid_.interior()); }

template <class AddForce>
void SolidPhase::for_each_body_faces(const AddForce& add) const {
  for (const auto& body : bodies_) {
    if (!body.model->elastic()) continue;
    const Box faces = elastic_faces(body);
    if (!faces.empty()) add(body, faces);
  }
}

// The lambdas take copies (Views and the spacing), not this: the kernels they launch capture them.
void SolidPhase::add_elastic_force(const kernels::Velocity& rhs) const {
  const double* h = grid_.h;
  for_each_body_faces([rhs, h](const SolidBody& body, const Box& faces) {
    kernels::add_elastic_force(rhs, body.psi, body.b, body.b_prev, body.model->scratch(), body.G, h, faces);
  });
}

void SolidPhase::add_elastic_force_to_predictor(const kernels::Velocity& rhs, const kernels::Velocity& star,
                                                const kernels::PredictorTerms& terms) const {
  const double* h = grid_.h;
  for_each_body_faces([rhs, star, terms, h](const SolidBody& body, const Box& faces) {
    kernels::add_elastic_force_to_predictor(rhs, star, terms, body.psi, body.b, body.b_prev, body.model->scratch(),
                                            body.G, h, faces);
  });
}

Box SolidPhase::elastic_force_region() const {
  Box region{{0, 0, 0}, {0, 0, 0}};
  for (const auto& body : bodies_)
    if (body.model->elastic()) region = bounding_box(region, elastic_faces(body));
  return region;
}

double SolidPhase::max_wave_speed() const {
  double c = 0.0;
  for (const auto& body : bodies_)
    if (body.model->elastic()) c = std::max(c, std::sqrt(body.G));
  return c;
}

std::array<double, 3> holding_force(const SolidBody& body) {
  return body.hold ? body.hold->force() : body.model->holding_force();
}

bool SolidPhase::constrain_velocity(const kernels::Velocity& vel, double dt, int substep) {
  bool any = false;
  for (auto& body : bodies_) {
    if (body.hold) {
      body.hold->apply(body, vel, dt, substep);
      any = true;
    }
    if (!body.model->constrains_velocity()) continue;
    body.model->constrain_velocity(body, vel, dt, substep);
    any = true;
  }
  return any;
}

// psi, B and the model's stored fields of every body, named "solid<n>_<name>".
std::vector<std::pair<std::string, SolidModel::StoredField>> SolidPhase::stored_fields() {
  static const char* comp[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
  std::vector<std::pair<std::string, SolidModel::StoredField>> f;
  for (size_t n = 0; n < bodies_.size(); ++n) {
    auto& body = bodies_[n];
    const std::string tag = "solid" + std::to_string(n) + "_";
    f.push_back({tag + "psi", {"psi", &body.psi, 0.0}});
    for (int c = 0; c < 6; ++c) f.push_back({tag + "B" + comp[c], {"B", &body.b.c[c], c < 3 ? 1.0 : 0.0}});
    for (const auto& s : body.model->checkpoint_fields()) f.push_back({tag + s.name, s});
  }
  return f;
}

std::vector<CheckpointSource> SolidPhase::checkpoint_sources() {
  std::vector<CheckpointSource> out;
  for (const auto& [name, s] : stored_fields()) out.push_back({name, *s.field, s.outside});
  return out;
}

// Fresh whole-slab fields to read into (a refused read leaves the bodies as they were); restore()
// hands them to the bodies.
std::vector<std::pair<std::string, Field3>> SolidPhase::checkpoint_fields() {
  std::vector<std::pair<std::string, Field3>> out;
  staged_.clear();
  for (const auto& [name, s] : stored_fields()) {
    const Field3 whole = grid_.make_field(s.field->data.label().c_str());
    staged_.push_back({s.field, whole});
    out.emplace_back(name, whole);
  }
  return out;
}

std::vector<std::pair<std::string, double>> SolidPhase::checkpoint_scalars() const {
  std::vector<std::pair<std::string, double>> out;
  for (size_t n = 0; n < bodies_.size(); ++n) {
    auto scalars = bodies_[n].model->checkpoint_scalars();
    if (bodies_[n].hold) scalars.merge(bodies_[n].hold->checkpoint_scalars());
    for (const auto& [name, v] : scalars) out.emplace_back("solid" + std::to_string(n) + "." + name, v);
  }
  return out;
}

void SolidPhase::restore(const std::vector<std::pair<std::string, double>>& scalars) {
  // the fields read into whole-slab copies become the bodies' (their models move them back onto
  // their windows in fill_ghosts)
  for (auto& [field, copy] : staged_) *field = WindowField(copy);
  staged_.clear();
  for (size_t n = 0; n < bodies_.size(); ++n) {
    const std::string tag = "solid" + std::to_string(n) + ".";
    std::map<std::string, double> mine;
    for (const auto& [key, v] : scalars)
      if (key.rfind(tag, 0) == 0) mine[key.substr(tag.size())] = v;
    bodies_[n].model->restore_scalars(mine);
    if (bodies_[n].hold) bodies_[n].hold->restore_scalars(mine);
    bodies_[n].model->fill_ghosts(bodies_[n]);
  }
}

void set_initial_state(FlowSolver& flow, SolidPhase& solids) {
  flow.set_initial_condition();
  solids.set_initial_condition();
  if (!solids.empty()) {
    solids.stop_bodies_at_rest(flow.state().vel);
    flow.make_solenoidal();
  }
}

}  // namespace eulerfsi

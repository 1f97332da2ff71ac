#include "solid/solid_model.hpp"

#include "solid/paper_model.hpp"
#include "solid/reference_map_model.hpp"
#include "solid/rigid_model.hpp"

namespace eulerfsi {

void SolidModel::allocate(SolidBody& body, const Grid& grid) {
  body.psi = grid.make_field("psi");
  body.b = make_tensor(grid, "B");
  body.b_prev = make_tensor(grid, "B_prev");
}

std::shared_ptr<SolidModel> make_solid_model(const SolidConfig& solid, const CaseConfig& cfg, const Grid& grid,
                                             const BoundaryConditions& bc, const Comm& comm) {
  switch (solid.model) {
    case SolidModelKind::ReferenceMap:
      return std::make_shared<ReferenceMapModel>(solid, cfg, grid, bc, comm);
    case SolidModelKind::Rigid:
      return std::make_shared<RigidModel>(solid, cfg, grid, comm);
    case SolidModelKind::Paper:
      break;
  }
  return std::make_shared<PaperModel>(solid, cfg, grid, bc, comm);
}

}  // namespace eulerfsi

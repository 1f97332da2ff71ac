#pragma once
// Where a body's fields are stored: a window of the grid that holds the body, the band its
// extension fills and the reach of every stencil read there, and that follows the body, so that a
// particle filling 1 % of the pipe does not carry ~24 whole-grid fields. Outside the window a field
// holds one value ("outside": psi 0, B = I, the map unknown), which no kernel reads.
//
// The window is one box of the global grid (x in global storage indices), cut by each rank's slab:
// every rank then agrees on which x-ghost planes the halo exchange moves (src/parallel/halo.hpp).
// It takes in a wall's ghosts as soon as it reaches them or the cells they mirror, and a periodic
// direction (x always) whole as soon as it reaches an end (the ghosts are images of the far end),
// so a ghost fill never reads outside it and the halo across the periodic x end moves matching
// planes. It moves with slack, so the fields are
// copied every few cells of travel, not every step.
#include <utility>
#include <vector>

#include "core/window_field.hpp"
#include "grid/grid.hpp"
#include "parallel/comm.hpp"

namespace eulerfsi {

class SolidWindow {
 public:
  // A field the window carries and its value outside the window.
  struct Member {
    WindowField* field;
    double outside;
    const char* label;  // for Kokkos' tools
  };

  // An empty window: the first hold() places it and allocates the members.
  SolidWindow(const Grid& grid, const Comm& comm) : grid_(grid), comm_(comm), lo_{0, 0, 0}, hi_{0, 0, 0} {}

  // Collective: the window holds `needed` (this rank's cells in storage indices; may be empty) on
  // every rank; where it does not, or where it holds more than twice the cells it needs, it moves
  // (grown by the slack) and every member with it, values kept where old and new windows overlap
  // and `outside` elsewhere (always_move: also otherwise). Returns whether it moved.
  bool hold(const Box& needed, const std::vector<Member>& members, bool always_move = false);
  // The window of everything (the whole-slab reference path, a restart) for every member.
  void hold_whole_slab(const std::vector<Member>& members);
  // This rank's cells of the window, storage indices.
  Box local() const;
  // Where the window goes to hold `needed` (global: x in global storage indices), and this rank's
  // cells of a global window: what hold() does, for estimates made before a run.
  static Box placement(const Grid& grid, const Box& needed);
  static Box local_part(const Grid& grid, const Box& global);
  // A new field on the window, `outside` everywhere.
  WindowField make_field(const char* label, double outside) const;
  // How often hold() moved it.
  int moves() const { return moves_; }

 private:
  void set_whole_slab();
  void move(const std::vector<Member>& members) const;

  Grid grid_;
  Comm comm_;
  int moves_ = 0;
  int lo_[3], hi_[3];  // global window: x in global storage indices (x_offset + local), y and z storage
};

}  // namespace eulerfsi

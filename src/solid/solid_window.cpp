#include "solid/solid_window.hpp"

#include <algorithm>
#include <climits>

#include "core/launch.hpp"

namespace eulerfsi {

namespace {
// Cells the window keeps beyond what is needed when it moves: a body crosses about one cell in
// a step (CFL < 1), so the fields are copied every few steps, not every step.
constexpr int kSlack = 2;

// to = from on the cells of `box` (a device lambda may not sit in a private member function).
void copy_cells(const WindowField& to, const WindowField& from, const Box& box) {
  for_each_cell("eulerfsi::solid::window_move", box, KOKKOS_LAMBDA(int i, int j, int k) { to(i, j, k) = from(i, j, k); });
}

}  // namespace

void SolidWindow::set_whole_slab() {
  for (int d = 0; d < 3; ++d) {
    lo_[d] = 0;
    hi_[d] = grid_.n[d] + 2 * kGhost;
  }
}

Box SolidWindow::local_part(const Grid& grid, const Box& global) {
  const int first = grid.x_offset, last = grid.x_offset + grid.nx_local + 2 * kGhost;
  Box b = global;
  b.lo[0] = std::max(global.lo[0], first) - first;
  b.hi[0] = std::max(b.lo[0], std::min(global.hi[0], last) - first);
  return b;
}

Box SolidWindow::local() const { return local_part(grid_, Box{{lo_[0], lo_[1], lo_[2]}, {hi_[0], hi_[1], hi_[2]}}); }

Box SolidWindow::placement(const Grid& grid, const Box& needed) {
  Box w;
  for (int d = 0; d < 3; ++d) {
    const int extent = grid.n[d] + 2 * kGhost;
    const int lo = needed.lo[d] - kSlack, hi = needed.hi[d] + kSlack;
    // A window reaching a ghost cell or a cell a ghost copies (the first and last kGhost owned
    // cells) takes in the ghosts: at a wall those of that side (mirrors of the cells next to them),
    // in a periodic direction (x always) the whole direction (images of the far end; the halo
    // sends the first owned planes across the periodic x end).
    const bool near_lo = lo < 2 * kGhost, near_hi = hi > extent - 2 * kGhost;
    const bool periodic = d == 0 || grid.bc[d] == Boundary::Periodic;
    w.lo[d] = near_lo || (periodic && near_hi) ? 0 : lo;
    w.hi[d] = near_hi || (periodic && near_lo) ? extent : hi;
  }
  return w;
}

WindowField SolidWindow::make_field(const char* label, double outside) const {
  const Box b = local();
  WindowField f(Field3(std::string(label), b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]), b.lo);
  if (outside != 0.0) Kokkos::deep_copy(f.data, outside);
  return f;
}

bool SolidWindow::hold(const Box& needed, const std::vector<Member>& members, bool always_move) {
  // the union of every rank's needed cells, in global indices (min of lo and of -hi)
  int ext[6];
  for (int d = 0; d < 3; ++d) {
    const int shift = d == 0 ? grid_.x_offset : 0;
    ext[d] = needed.empty() ? INT_MAX : needed.lo[d] + shift;
    ext[3 + d] = needed.empty() ? INT_MAX : -(needed.hi[d] + shift);
  }
  int all[6];
  MPI_Allreduce(ext, all, 6, MPI_INT, MPI_MIN, comm_.comm);
  if (all[0] == INT_MAX) return false;  // no rank needs the body's fields
  const Box w = placement(grid_, Box{{all[0], all[1], all[2]}, {-all[3], -all[4], -all[5]}});
  bool inside = !always_move;
  for (int d = 0; d < 3; ++d) inside = inside && all[d] >= lo_[d] && -all[3 + d] <= hi_[d];
  // it also shrinks once it holds more than twice what it needs (a body gone from the periodic end
  // or a wall: the window had taken in the whole direction or the wall's ghosts)
  const Box now{{lo_[0], lo_[1], lo_[2]}, {hi_[0], hi_[1], hi_[2]}};
  if (inside && now.size() <= 2 * w.size()) return false;
  for (int d = 0; d < 3; ++d) {
    lo_[d] = w.lo[d];
    hi_[d] = w.hi[d];
  }
  move(members);
  ++moves_;
  return true;
}

void SolidWindow::hold_whole_slab(const std::vector<Member>& members) {
  set_whole_slab();
  move(members);
}

// Every member onto the window: the overlap of its old window copied, `outside` elsewhere.
void SolidWindow::move(const std::vector<Member>& members) const {
  const Box target = local();
  for (const Member& m : members) {
    const Box now = m.field->window();
    bool same = m.field->allocated();
    for (int d = 0; d < 3; ++d) same = same && now.lo[d] == target.lo[d] && now.hi[d] == target.hi[d];
    if (same) continue;
    WindowField moved = make_field(m.label, m.outside);
    const WindowField old = *m.field;
    if (old.allocated()) {
      const Box overlap = intersection(old.window(), moved.window());
      copy_cells(moved, old, overlap);
    }
    *m.field = moved;
  }
  Kokkos::fence();
}

}  // namespace eulerfsi

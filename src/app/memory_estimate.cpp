#include "app/memory_estimate.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/types.hpp"
#if defined(KOKKOS_ENABLE_HIP)
#include <hip/hip_runtime.h>
#endif
#include "solid/paper_model.hpp"
#include "solid/reference_map_model.hpp"
#include "solid/rigid_model.hpp"

namespace eulerfsi {

namespace {

// Whole-slab fields (each one double per cell, ghosts included) held by each part of a run:
// u, v, w, p, p_step, two rhs triples and mu (src/solver/flow_state.hpp, flow_solver.hpp).
constexpr double kFlowFields = 12.0;
// The Poisson solver's work arrays: FFTW-MPI's in-place buffer and the transposes' scratch; the
// one-rank DCT solver's real and half-complex arrays and its line buffers.
constexpr double kPoissonFieldsFftwMpi = 2.0;
constexpr double kPoissonFieldsFftDct = 4.0;
// cuFFT: the one work area all plans share (src/poisson/fft_engine_cufft.cpp), about the size of
// the largest batch; not yet measured on a GPU (hipFFT still gives each plan its own).
constexpr double kDeviceFftWorkFields = 1.0;
// time.implicit_viscosity: its right-hand side and the three transforms' shared buffer (measured:
// +36.6 - 32.4 MiB on a 96 x 48 x 48 pipe, 1.8 of its 2.4 MiB fields; src/poisson/helmholtz_solver.cpp).
constexpr double kImplicitViscosityFields = 2.0;
// Field snapshots: total psi, the elastic energy density and the three centred velocity components.
constexpr double kSnapshotFields = 5.0;
// Every body: psi, B and B before the update (6 + 6) (src/solid/solid_body.hpp), on the body's
// window (src/solid/solid_window.hpp; the whole slab for a paper-model layer, or with sharpening
// or without the B extension).
constexpr double kBodyFields = 13.0;
// The model's own: RK3 rhs and memory of psi and B and the extension's marks (paper), or of
// q = xi - x (3 + 3 + 3), its level and the diagnostics' psi at a second edge width (map).
constexpr double kPaperModelFields = 15.0;
constexpr double kReferenceMapFields = 11.0;
// What reading a checkpoint (a restart) puts on the whole slab for a reference-map body before it
// moves onto its window: psi, B, q and its level (writing packs from the window directly).
constexpr double kReferenceMapStoredFields = 11.0;
// ... and for a rigid body or a paper-model body: psi and B.
constexpr double kRigidStoredFields = 7.0;
constexpr double kPaperStoredFields = 7.0;
// Allocator and library overhead (FFTW plans, MPI buffers, the Kokkos runtime) on top.
constexpr double kOverheadBytes = 64.0 * 1024 * 1024;

// MemAvailable of this node in bytes (0: unknown).
double available_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return 0.0;
}

// Free memory of the GPU this process runs on (CUDA, HIP) in bytes; 0 where MemSpace is host
// memory or the runtime does not say.
double device_available_bytes() {
#if defined(KOKKOS_ENABLE_CUDA)
  size_t free_bytes = 0, total = 0;
  return cudaMemGetInfo(&free_bytes, &total) == cudaSuccess ? double(free_bytes) : 0.0;
#elif defined(KOKKOS_ENABLE_HIP)
  size_t free_bytes = 0, total = 0;
  return hipMemGetInfo(&free_bytes, &total) == hipSuccess ? double(free_bytes) : 0.0;
#else
  return 0.0;
#endif
}

constexpr bool kHostMemory = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;

// Ranks of this run on this node.
int ranks_on_node(const Comm& comm) {
#ifdef EULERFSI_HAVE_MPI
  MPI_Comm node;
  MPI_Comm_split_type(comm.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int n = 1;
  MPI_Comm_size(node, &n);
  MPI_Comm_free(&node);
  return n;
#else
  (void)comm;
  return 1;
#endif
}

std::string gib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

// The memory a run's ranks share and how many share it: host memory is the node's, divided
// among its ranks; a GPU's is its own rank's. bytes = 0: unknown.
struct MemoryPool {
  double bytes;
  int ranks;
};
MemoryPool memory_pool(const Comm& comm) {
  if (kHostMemory) return {available_bytes(), ranks_on_node(comm)};
  return {device_available_bytes(), 1};
}

}  // namespace

MemoryEstimate estimate_memory(const CaseConfig& cfg, const Grid& grid) {
  MemoryEstimate m;
  m.slab_cells = double(grid.ext(0)) * double(grid.ext(1)) * double(grid.ext(2));
#ifdef EULERFSI_POISSON_DEFAULT_FFT_DCT
  const bool fft_dct = true;
#else
  const bool fft_dct = false;
#endif
  m.flow_fields = kFlowFields + (fft_dct ? kPoissonFieldsFftDct + (kHostMemory ? 0.0 : kDeviceFftWorkFields)
                                         : kPoissonFieldsFftwMpi) +
                  (cfg.output.fields_every > 0 ? kSnapshotFields : 0.0) +
                  (cfg.time.implicit_viscosity ? kImplicitViscosityFields : 0.0);
  for (const auto& s : cfg.solids) {
    if (s.model == SolidModelKind::Rigid) {  // psi, B and B_prev on the window, nothing else
      m.solid_fields += kBodyFields * RigidModel::window_cells(s, grid, false) / m.slab_cells;
      m.solid_peak_fields +=
          kBodyFields * RigidModel::window_cells(s, grid, !cfg.flow.frame_follows_particle) / m.slab_cells +
          kRigidStoredFields;
      continue;
    }
    if (s.model == SolidModelKind::Paper) {
      const double fields = kBodyFields + kPaperModelFields;
      m.solid_fields += fields * PaperModel::window_cells(s, grid, false) / m.slab_cells;
      m.solid_peak_fields += fields * PaperModel::window_cells(s, grid, !cfg.flow.frame_follows_particle) / m.slab_cells +
                             kPaperStoredFields;
      continue;
    }
    const double fields = kBodyFields + kReferenceMapFields;
    const bool crosses_x_end = !cfg.flow.frame_follows_particle;
    m.solid_fields += fields * ReferenceMapModel::window_cells(s, grid, false) / m.slab_cells;
    m.solid_peak_fields +=
        fields * ReferenceMapModel::window_cells(s, grid, crosses_x_end) / m.slab_cells + kReferenceMapStoredFields;
  }
  return m;
}

std::string describe_memory(const CaseConfig& cfg, const Grid& grid, const Comm& comm) {
  const MemoryEstimate m = estimate_memory(cfg, grid);
  std::ostringstream out;
  out << "# memory: about " << gib(m.bytes() + kOverheadBytes) << " per rank (" << m.flow_fields << " flow and "
      << m.solid_fields << " solid fields of " << m.slab_cells << " cells, 8 bytes each";
  if (m.solid_peak_fields > m.solid_fields)
    out << "; up to " << gib(m.peak_bytes() + kOverheadBytes) << " while a checkpoint is read"
        << (cfg.flow.frame_follows_particle ? "" : " or a body crosses the periodic x end");
  out << ")";
  const MemoryPool pool = memory_pool(comm);
  if (pool.bytes > 0.0)
    out << (kHostMemory ? "; this node has " : "; this rank's GPU has ") << gib(pool.bytes)
        << (kHostMemory ? " available for " + std::to_string(pool.ranks) + " rank(s)" : std::string(" free"));
  out << "\n";
  return out.str();
}

void refuse_if_out_of_memory(const CaseConfig& cfg, const Grid& grid, const Comm& comm) {
  const MemoryPool pool = memory_pool(comm);
  const double need = (estimate_memory(cfg, grid).peak_bytes() + kOverheadBytes) * pool.ranks;
  if (!comm.any(pool.bytes > 0.0 && need > pool.bytes)) return;
  const std::string where = kHostMemory ? " on this node (" + std::to_string(pool.ranks) + " rank(s)), which has "
                                        : " on this rank's GPU, which has ";
  throw ConfigError(cfg.source + ": domain.cells = [" + std::to_string(cfg.domain.cells[0]) + ", " +
                    std::to_string(cfg.domain.cells[1]) + ", " + std::to_string(cfg.domain.cells[2]) + "] needs about " +
                    gib(need) + where + gib(pool.bytes) + " available: use fewer cells, or more " +
                    (kHostMemory ? "nodes" : "GPUs"));
}

}  // namespace eulerfsi

// FftEngine on NVIDIA GPUs: cuFFT's batched plans (cufftMakePlanMany) on the stream of
// Kokkos' default Cuda instance, so transforms and kernels run in order without fences. All plans
// share one work area (they run one after the other on that stream): up to six plans per solve
// would otherwise each keep their own.
// Compiled only when Kokkos has CUDA (CMake picks this file).
#include <cufft.h>

#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/compat.hpp"
#include "poisson/fft_engine.hpp"

namespace eulerfsi {

static_assert(sizeof(Complex) == sizeof(cufftDoubleComplex), "Kokkos::complex<double> must match cufftDoubleComplex");

namespace {

void check(cufftResult r, const char* what) {
  if (r != CUFFT_SUCCESS) throw std::runtime_error(std::string("cuFFT: ") + what + " failed with code " + std::to_string(int(r)));
}

class CufftEngine final : public FftEngine {
 public:
  CufftEngine() = default;
  ~CufftEngine() override {
    for (auto& kv : plans_) cufftDestroy(kv.second);
  }
  CufftEngine(const CufftEngine&) = delete;
  CufftEngine& operator=(const CufftEngine&) = delete;

  void r2c(int n, int batch, double* in, Complex* out) override {
    check(cufftExecD2Z(plan(CUFFT_D2Z, n, batch), in, reinterpret_cast<cufftDoubleComplex*>(out)), "D2Z");
  }
  void c2r(int n, int batch, Complex* in, double* out) override {
    check(cufftExecZ2D(plan(CUFFT_Z2D, n, batch), reinterpret_cast<cufftDoubleComplex*>(in), out), "Z2D");
  }
  void c2c(int n, int batch, Complex* data, int sign) override {
    auto* p = reinterpret_cast<cufftDoubleComplex*>(data);
    check(cufftExecZ2Z(plan(CUFFT_Z2Z, n, batch), p, p, sign < 0 ? CUFFT_FORWARD : CUFFT_INVERSE), "Z2Z");
  }
  std::string name() const override {
    int v = 0;
    cufftGetVersion(&v);
    return "cuFFT " + std::to_string(v);
  }

 private:
  // Contiguous lines: element stride 1, line distance n (real, complex) or n/2 + 1 (half-complex).
  cufftHandle plan(cufftType type, int n, int batch) {
    const auto key = std::make_tuple(int(type), n, batch);
    auto it = plans_.find(key);
    if (it != plans_.end()) return it->second;
    int len = n;
    const int real_dist = n, half_dist = n / 2 + 1;
    const int idist = type == CUFFT_Z2D ? half_dist : type == CUFFT_D2Z ? real_dist : n;
    const int odist = type == CUFFT_D2Z ? half_dist : type == CUFFT_Z2D ? real_dist : n;
    cufftHandle h;
    check(cufftCreate(&h), "cufftCreate");
    check(cufftSetAutoAllocation(h, 0), "cufftSetAutoAllocation");
    size_t work_bytes = 0;
    check(cufftMakePlanMany(h, 1, &len, &len, 1, idist, &len, 1, odist, type, batch, &work_bytes), "cufftMakePlanMany");
    check(cufftSetStream(h, compat::cuda_stream()), "cufftSetStream");
    plans_[key] = h;
    if (work_bytes > work_.extent(0)) {
      compat::fence();  // transforms still queued may be using the old area
      work_ = WorkArea(Kokkos::view_alloc(Kokkos::WithoutInitializing, "eulerfsi::cufft::work"), work_bytes);
      for (auto& kv : plans_) check(cufftSetWorkArea(kv.second, work_.data()), "cufftSetWorkArea");
    } else if (work_.extent(0) > 0) {
      check(cufftSetWorkArea(h, work_.data()), "cufftSetWorkArea");
    }
    return h;
  }

  using WorkArea = Kokkos::View<char*, MemSpace>;
  WorkArea work_;  // freed after ~CufftEngine's body has destroyed the plans
  std::map<std::tuple<int, int, int>, cufftHandle> plans_;
};

}  // namespace

FftEngine::~FftEngine() = default;

std::unique_ptr<FftEngine> make_fft_engine() { return std::make_unique<CufftEngine>(); }

}  // namespace eulerfsi

// FftEngine on AMD GPUs: hipFFT's batched plans (hipfftPlanMany) on the stream of Kokkos'
// default HIP instance. Compiled only when Kokkos has HIP (CMake picks this file).
#include <hipfft/hipfft.h>

#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/compat.hpp"
#include "poisson/fft_engine.hpp"

namespace eulerfsi {

static_assert(sizeof(Complex) == sizeof(hipfftDoubleComplex), "Kokkos::complex<double> must match hipfftDoubleComplex");

namespace {

void check(hipfftResult r, const char* what) {
  if (r != HIPFFT_SUCCESS) throw std::runtime_error(std::string("hipFFT: ") + what + " failed with code " + std::to_string(int(r)));
}

class HipfftEngine final : public FftEngine {
 public:
  HipfftEngine() = default;
  ~HipfftEngine() override {
    for (auto& kv : plans_) hipfftDestroy(kv.second);
  }
  HipfftEngine(const HipfftEngine&) = delete;
  HipfftEngine& operator=(const HipfftEngine&) = delete;

  void r2c(int n, int batch, double* in, Complex* out) override {
    check(hipfftExecD2Z(plan(HIPFFT_D2Z, n, batch), in, reinterpret_cast<hipfftDoubleComplex*>(out)), "D2Z");
  }
  void c2r(int n, int batch, Complex* in, double* out) override {
    check(hipfftExecZ2D(plan(HIPFFT_Z2D, n, batch), reinterpret_cast<hipfftDoubleComplex*>(in), out), "Z2D");
  }
  void c2c(int n, int batch, Complex* data, int sign) override {
    auto* p = reinterpret_cast<hipfftDoubleComplex*>(data);
    check(hipfftExecZ2Z(plan(HIPFFT_Z2Z, n, batch), p, p, sign < 0 ? HIPFFT_FORWARD : HIPFFT_BACKWARD), "Z2Z");
  }
  std::string name() const override {
    int v = 0;
    hipfftGetVersion(&v);
    return "hipFFT " + std::to_string(v);
  }

 private:
  // Contiguous lines: element stride 1, line distance n (real, complex) or n/2 + 1 (half-complex).
  hipfftHandle plan(hipfftType type, int n, int batch) {
    const auto key = std::make_tuple(int(type), n, batch);
    auto it = plans_.find(key);
    if (it != plans_.end()) return it->second;
    int len = n;
    const int real_dist = n, half_dist = n / 2 + 1;
    const int idist = type == HIPFFT_Z2D ? half_dist : type == HIPFFT_D2Z ? real_dist : n;
    const int odist = type == HIPFFT_D2Z ? half_dist : type == HIPFFT_Z2D ? real_dist : n;
    hipfftHandle h;
    check(hipfftPlanMany(&h, 1, &len, &len, 1, idist, &len, 1, odist, type, batch), "hipfftPlanMany");
    check(hipfftSetStream(h, compat::hip_stream()), "hipfftSetStream");
    return plans_[key] = h;
  }

  std::map<std::tuple<int, int, int>, hipfftHandle> plans_;
};

}  // namespace

FftEngine::~FftEngine() = default;

std::unique_ptr<FftEngine> make_fft_engine() { return std::make_unique<HipfftEngine>(); }

}  // namespace eulerfsi

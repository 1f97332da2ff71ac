// FftEngine on the host: FFTW's advanced interface, one plan per (kind, length, batch, buffers).
#include <fftw3.h>

#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "poisson/fft_engine.hpp"
#include "poisson/fftw_threads.hpp"

namespace eulerfsi {

static_assert(Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible,
              "the FFTW engine reads MemSpace from the host; device builds use cuFFT or hipFFT");
static_assert(sizeof(Complex) == sizeof(fftw_complex), "Kokkos::complex<double> must be laid out as fftw_complex");

namespace {

class FftwEngine final : public FftEngine {
 public:
  FftwEngine() { fftw_threads_once(); }
  ~FftwEngine() override {
    for (auto& kv : plans_) fftw_destroy_plan(kv.second);
  }
  FftwEngine(const FftwEngine&) = delete;
  FftwEngine& operator=(const FftwEngine&) = delete;

  void r2c(int n, int batch, double* in, Complex* out) override {
    run(plan(Kind::R2C, n, batch, in, out, [=] {
      return fftw_plan_many_dft_r2c(1, &n, batch, in, nullptr, 1, n, as_fftw(out), nullptr, 1, n / 2 + 1, kFlags);
    }));
  }
  void c2r(int n, int batch, Complex* in, double* out) override {
    run(plan(Kind::C2R, n, batch, in, out, [=] {
      return fftw_plan_many_dft_c2r(1, &n, batch, as_fftw(in), nullptr, 1, n / 2 + 1, out, nullptr, 1, n, kFlags);
    }));
  }
  void c2c(int n, int batch, Complex* data, int sign) override {
    const Kind kind = sign < 0 ? Kind::Forward : Kind::Backward;
    run(plan(kind, n, batch, data, data, [=] {
      return fftw_plan_many_dft(1, &n, batch, as_fftw(data), nullptr, 1, n, as_fftw(data), nullptr, 1, n,
                                sign < 0 ? FFTW_FORWARD : FFTW_BACKWARD, kFlags);
    }));
  }
  std::string name() const override { return fftw_version; }

 private:
  enum class Kind { R2C, C2R, Forward, Backward };
  using Key = std::tuple<Kind, int, int, const void*, const void*>;
  // Estimate: deterministic plans, no trial runs that would overwrite the buffers
  static constexpr unsigned kFlags = FFTW_ESTIMATE;

  static fftw_complex* as_fftw(Complex* p) { return reinterpret_cast<fftw_complex*>(p); }

  // A plan is tied to its buffers: the solver always passes the same ones, so each is made once.
  template <class MakePlan>
  fftw_plan plan(Kind kind, int n, int batch, const void* in, const void* out, MakePlan make) {
    const Key key{kind, n, batch, in, out};
    auto it = plans_.find(key);
    if (it != plans_.end()) return it->second;
#ifdef EULERFSI_FFTW_THREADS
    fftw_plan_with_nthreads(Kokkos::DefaultHostExecutionSpace().concurrency());
#endif
    fftw_plan p = make();
    if (!p) throw std::runtime_error("FftwEngine: FFTW could not plan " + std::to_string(batch) + " transforms of length " +
                                     std::to_string(n));
    return plans_[key] = p;
  }
  // Kokkos kernels that filled the input must be done before FFTW reads it
  static void run(fftw_plan p) {
    ExecSpace().fence();
    fftw_execute(p);
  }

  std::map<Key, fftw_plan> plans_;
};

}  // namespace

FftEngine::~FftEngine() = default;

std::unique_ptr<FftEngine> make_fft_engine() { return std::make_unique<FftwEngine>(); }

}  // namespace eulerfsi

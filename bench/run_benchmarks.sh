#!/usr/bin/env bash
# Runs the benchmarks (triad, whole step, kernels, Poisson) at OMP_NUM_THREADS=1 and 2 and
# writes bench/RESULTS.md: medians of --benchmark_repetitions runs, beside the triad bandwidth.
# Usage: bench/run_benchmarks.sh [build dir (default build/)] [extra Google Benchmark flags...]
# Build first with ci/build. Set THREADS="1 2 4" to change the thread counts, REPS for repetitions.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=${1:-$root/build}
shift || true
threads=${THREADS:-"1 2"}
reps=${REPS:-3}
# the raw Google Benchmark JSON stays in bench/data/ (bench/support/plot_step.py reads it)
out=$here/data
mkdir -p "$out"
rm -f "$out"/*.json

source "$root/ci/env.sh"  # KOKKOS_ROOT (for the table header), MPI settings
export OMP_PROC_BIND=false
flags=(--benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true --benchmark_min_time=0.3
       --benchmark_out_format=json "$@")
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for t in $threads; do
  for b in triad step kernels poisson; do
    exe="$build/bench/bench_$b"
    [ -x "$exe" ] || { echo "missing $exe: build with ci/build first" >&2; exit 1; }
    extra=()
    # the FFTW_MEASURE plans take minutes to make; the estimated ones are what the solver uses
    [ "$b" = poisson ] && extra=(--benchmark_filter='measure:0|BM_PoissonFftDct')
    # the GPU sizes (BM_StepLarge) take seconds per step here
    # (and each repetition runs STEP_MIN_TIME seconds: a few steps would sample this VM's drift)
    pair_bodies=; [ "$t" = 1 ] && pair_bodies='|BM_StepPairBodies/'
    [ "$b" = step ] && extra=(--benchmark_filter="BM_Step/|BM_StepImplicitViscosity/|BM_StepPair/|BM_StepPairMeasuredPlans/$pair_bodies"
                              --benchmark_min_time="${STEP_MIN_TIME:-2}")
    echo "== bench_$b, OMP_NUM_THREADS=$t" >&2
    OMP_NUM_THREADS=$t "$exe" "${flags[@]}" "${extra[@]}" --benchmark_out="$out/${b}_t$t.json" >&2
  done
done
# the steps on 2 MPI ranks x 1 thread (the slab split): the time is the slowest rank's
if command -v mpiexec > /dev/null && [ "${RANKS:-2}" -gt 1 ]; then
  echo "== bench_step, ${RANKS:-2} ranks x 1 thread" >&2
  OMP_NUM_THREADS=1 mpiexec -n "${RANKS:-2}" "$build/bench/bench_step" "${flags[@]}" \
    --benchmark_filter='BM_Step/|BM_StepPair/' --benchmark_min_time="${STEP_MIN_TIME:-2}" \
    --benchmark_out="$out/step_t1_r${RANKS:-2}.json" >&2
fi
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
# Google Benchmark records the executable's absolute path: keep only its path under the build folder
sed -i -E 's#^(    "executable": ")[^"]*/(bench/bench_[a-z]+)",#\1build/\2",#' "$out"/*.json

/usr/bin/python3 "$here/support/make_results.py" "$out" "$here/RESULTS.md" \
  --model "$(lscpu | sed -n 's/^Model name: *//p' | head -1)" --cores "$(nproc)" \
  --commit "$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)" \
  --load "$load_before -> $load_after" --reps "$reps" \
  --toolchain "$(c++ --version | head -1), $(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:STRING=//p' "$build/CMakeCache.txt") $(sed -n 's/^CMAKE_CXX_FLAGS:STRING=//p' "$build/CMakeCache.txt"), Kokkos $(basename "$KOKKOS_ROOT")"
/usr/bin/python3 "$here/support/plot_step.py" "$out" "$here/step_cost.png"
echo "wrote $here/RESULTS.md and $here/step_cost.png" >&2

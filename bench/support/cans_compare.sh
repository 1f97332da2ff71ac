#!/usr/bin/env bash
# Side-by-side timing of CaNS (github.com/CaNS-World/CaNS, the FFT-based single-phase solver)
# and eulerfsi's single-phase step on the same laminar square duct, for issue 8 ("the
# single-phase step on a 128x64x64 square duct: at most 0.65x the cost of CaNS on the same
# machine"). A manual measurement: not part of CI, called by no test.
#
# What it runs (every run: NSTEP steps at a fixed dt, the first WARM steps not timed):
#   CaNS      on 1 and 2 MPI ranks (CANS_RANKS), with the input bench/support/cans_duct.nml.in
#             (periodic x, no-slip y and z, constant flow rate, Re = 100, explicit viscosity, no
#             output, no CFL/divergence checks). Time per step: the mean over the timed steps of
#             CaNS's own per-step wall time (is_timing, the slowest rank), which covers the three
#             RK substeps with the Poisson solve and CaNS's per-step work arrays (glibc is told to
#             keep freed memory: MALLOC_MMAP_THRESHOLD_ / MALLOC_TRIM_THRESHOLD_, as the issue asks).
#   eulerfsi  `eulerfsi run` on the same duct (geometry "duct", bulk_velocity 1 by default, Re 100,
#             time.dt fixed, no fields/profiles/checkpoints), as RANKSxTHREADS in EULERFSI_RUNS
#             (default 1x1, 1x2, 2x1). Time per step: the difference of the progress lines' wall
#             clock (printed every WARM steps, 0.1 s resolution) between step WARM and step NSTEP.
#             It includes the run loop's per-step stable_dt reduction and the diagnostics row every
#             WARM steps, which CaNS does not do here: the comparison is a little against eulerfsi.
#   bench_step the project's BM_Step row at the same size (a pipe carved from the duct, flow.advance
#             only), for reference; PIPE_BENCH=0 skips it.
#   bench_triad the memory bandwidth (GB/s, STREAM counting) on 1 and 2 threads.
# It prints a markdown table: code, ranks x threads, ns per cell per step, s per step, and the
# ratio eulerfsi / CaNS on 1 core and on 2 (the best eulerfsi layout against CaNS on 2 ranks).
#
# Usage: bench/support/cans_compare.sh [CANS_DIR]
#   CANS_DIR (argument or env, default ./cans under the current directory): the CaNS checkout or
#            the folder holding it as CaNS/; the executable is looked for at build/cans or run/cans under it. Build CaNS
#            there first with its own Makefile (double precision, FFLAGS_OPT=1 i.e. -O3, GPU=0):
#              make libs && make      (in the CaNS checkout, with 2decomp-fft under dependencies/)
#   BUILD    eulerfsi build folder (default build/; built with ci/build, not rebuilt here)
#   NSTEP=100 WARM=10 DT=1e-3 GRID="128 64 64"   (NSTEP a multiple of WARM, NSTEP > WARM)
#   CANS_RANKS="1 2"  EULERFSI_RUNS="1x1 1x2 2x1"  PIPE_BENCH=1  WORK=<scratch dir, default mktemp>
#   ROUNDS=3  every CaNS and eulerfsi run that many times, interleaved round by round (a shared
#            VM's speed drifts by tens of % within minutes: codes timed one after the other would
#            compare sittings, not codes); the table gives the median and the fastest round
#   BUILD2   a second eulerfsi build (e.g. one configured with -DEULERFSI_ENABLE_NATIVE=ON), timed
#            in the same rounds and named by its folder
#   FFT_PLANNING=measure  eulerfsi's pressure transforms planned with FFTW_MEASURE (passed to every
#            eulerfsi run as --set solver.fft_planning=measure; the planning, well under a second, is
#            before the timed steps); unset: the case default, estimate. Named in the table's heading
# Smoke test: NSTEP=6 WARM=2 bench/support/cans_compare.sh   (about a minute)
# A full run (NSTEP=100) takes about 3 minutes on 2 idle cores (about 7 beside two busy
# background runs). Run it on an otherwise idle machine: the table prints the load average
# before and after. eulerfsi runs with glibc's default malloc settings.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cans_dir=${1:-${CANS_DIR:-$PWD/cans}}
build=${BUILD:-$root/build}
nstep=${NSTEP:-100}
warm=${WARM:-10}
dt=${DT:-1e-3}
read -r nx ny nz <<<"${GRID:-128 64 64}"
cans_ranks=${CANS_RANKS:-"1 2"}
eulerfsi_runs=${EULERFSI_RUNS:-"1x1 1x2 2x1"}
pipe_bench=${PIPE_BENCH:-1}
rounds=${ROUNDS:-3}
build2=${BUILD2:-}
fft_planning=${FFT_PLANNING:-}
planning_args=()
[ -z "$fft_planning" ] || planning_args=(--set "solver.fft_planning=$fft_planning")
template=$here/cans_duct.nml.in

die() { echo "cans_compare: $*" >&2; exit 1; }
(( nstep > warm && warm >= 1 && nstep % warm == 0 )) || die "need NSTEP > WARM >= 1 and NSTEP a multiple of WARM"
cans_exe=
for c in "$cans_dir/build/cans" "$cans_dir/run/cans" "$cans_dir/CaNS/build/cans" "$cans_dir/CaNS/run/cans"; do
  [ -x "$c" ] && { cans_exe=$c; break; }
done
[ -n "$cans_exe" ] || die "no CaNS executable under $cans_dir (build/cans or run/cans; build CaNS first)"
for e in eulerfsi bench/bench_triad; do [ -x "$build/$e" ] || die "missing $build/$e: build with ci/build first"; done
[ -z "$build2" ] || [ -x "$build2/eulerfsi" ] || die "missing $build2/eulerfsi (BUILD2)"
(( rounds >= 1 )) || die "need ROUNDS >= 1"
[ -f "$template" ] || die "missing $template"

source "$root/ci/env.sh"  # Open MPI as root and oversubscription, KOKKOS_ROOT
export OMP_PROC_BIND=false
work=${WORK:-$(mktemp -d /tmp/cans_compare.XXXXXX)}
mkdir -p "$work"
cells=$((nx * ny * nz))
lx=$(awk -v a="$nx" -v b="$ny" 'BEGIN { printf "%.17g", a / b }')  # cubic cells, Ly = Lz = 1
# ns per cell per step from seconds per step
ns_cell() { awk -v s="$1" -v c="$cells" 'BEGIN { printf "%.1f", 1e9 * s / c }'; }
# --bind-to none: a 1-rank run with 2 OpenMP threads must not be pinned to one core
mpi=(mpirun --bind-to none -x OMP_NUM_THREADS -x OMP_PROC_BIND)

rows=()   # "code|layout|s_per_step (median)|s_per_step (fastest)|note"
declare -A times   # "code|layout" -> the seconds per step of every round
order=()           # the keys in the order first run
note_of=()
record() {  # code layout seconds note
  local key="$1|$2"
  [ -n "${times[$key]+x}" ] || { order+=("$key"); note_of+=("$4"); }
  times[$key]="${times[$key]:-} $3"
}
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
echo "cans_compare: grid ${nx}x${ny}x${nz}, $nstep steps (first $warm untimed), dt $dt, $rounds round(s), work dir $work" >&2

cat >"$work/duct.toml" <<EOF
# written by bench/support/cans_compare.sh: the CaNS comparison duct
[domain]
length = [$lx, 1.0, 1.0]
cells = [$nx, $ny, $nz]
geometry = "duct"

[flow]
Re = 100.0
initial = "laminar"

[time]
dt = $dt
t_end = 1.0e9
max_steps = $nstep

[output]
every = $warm
fields_every = 0
profiles_every = 0
checkpoint_every = 0
EOF

run_cans() {  # ranks -> seconds per step
  local r=$1 d=$work/cans_np$1 dims="1, 1" s
  rm -rf "$d" && mkdir -p "$d/data"
  (( r > 1 )) && dims="0, 0"   # 0, 0: CaNS picks the processor grid itself
  sed -e "s/@NX@/$nx/; s/@NY@/$ny/; s/@NZ@/$nz/; s/@LX@/$lx/; s/@DT@/$dt/; s/@NSTEP@/$nstep/; s/@DIMS@/$dims/" \
    "$template" >"$d/input.nml"
  (cd "$d" && MALLOC_MMAP_THRESHOLD_=1073741824 MALLOC_TRIM_THRESHOLD_=1073741824 OMP_NUM_THREADS=1 \
     "${mpi[@]}" -x MALLOC_MMAP_THRESHOLD_ -x MALLOC_TRIM_THRESHOLD_ -np "$r" "$cans_exe" input.nml >log.txt 2>&1) || { tail -20 "$d/log.txt" >&2; die "CaNS failed on $r rank(s)"; }
  grep -q 'Fim' "$d/log.txt" || { tail -20 "$d/log.txt" >&2; die "CaNS did not finish on $r rank(s)"; }
  # after each "Average, minimum & maximum elapsed time:" line: average, min, max over the ranks
  s=$(awk -v w="$warm" '/Average, minimum & maximum elapsed time/ { getline; n++; if (n > w) { t += $3; k++ } }
        END { if (k) printf "%.6g", t / k }' "$d/log.txt")
  [ -n "$s" ] || die "no per-step times in $d/log.txt (is_timing)"
  echo "$s"
}

run_eulerfsi() {  # build ranks_x_threads -> seconds per step
  local b=$1 rt=$2 r=${2%x*} t=${2#*x} log s
  log=$work/eulerfsi_$(basename "$1")_$2.log
  rm -rf "$work/eulerfsi_$rt"
  OMP_NUM_THREADS=$t "${mpi[@]}" -np "$r" "$b/eulerfsi" run "$work/duct.toml" --out "$work/eulerfsi_$rt" \
    "${planning_args[@]}" >"$log" 2>&1 ||
    { tail -20 "$log" >&2; die "eulerfsi ($b) failed on $rt"; }
  # progress lines: "step N  t ...  wall X.Xs  eta ...": wall at step WARM and at step NSTEP
  s=$(awk -v w="$warm" -v n="$nstep" '$1 == "step" { for (i = 2; i < NF; i++) if ($i == "wall") { x = $(i + 1); sub(/s$/, "", x) }
          if ($2 == w) a = x; if ($2 == n) b = x }
        END { if (a != "" && b != "") printf "%.6g", (b - a) / (n - w) }' "$log")
  [ -n "$s" ] || die "no progress lines in $log"
  echo "$s"
}

build_name() { if [ "$1" = "$build" ]; then echo "eulerfsi run (duct)"; else echo "eulerfsi run (duct, $(basename "$1"))"; fi; }
builds=("$build")
[ -z "$build2" ] || builds+=("$build2")
for ((round = 1; round <= rounds; ++round)); do
  for r in $cans_ranks; do
    echo "== round $round: CaNS, $r rank(s)" >&2
    record CaNS "${r}x1" "$(run_cans "$r")" "mean of the per-step max over ranks"
  done
  for b in "${builds[@]}"; do
    for rt in $eulerfsi_runs; do
      echo "== round $round: $(build_name "$b"), $rt" >&2
      record "$(build_name "$b")" "$rt" "$(run_eulerfsi "$b" "$rt")" "wall between steps $warm and $nstep (0.1 s resolution)"
    done
  done
done
# the median and the fastest round of each
stat() {
  tr ' ' '\n' <<<"$1" | sed '/^$/d' | sort -g | awk -v q="$2" '{ v[NR] = $1 } END {
    if (q == "min") print v[1]; else if (NR % 2) print v[(NR + 1) / 2]; else printf "%.6g\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
for n in "${!order[@]}"; do
  key=${order[$n]}
  rows+=("$key|$(stat "${times[$key]}" median)|$(stat "${times[$key]}" min)|${note_of[$n]}")
done

# --- bench_step (pipe) and bench_triad -------------------------------------------------------
gb_json() {  # file key -> the first benchmark's counter
  /usr/bin/python3 -c 'import json,sys; print("%.6g" % json.load(open(sys.argv[1]))["benchmarks"][0][sys.argv[2]])' "$1" "$2"
}
if [ "$pipe_bench" = 1 ] && [ -x "$build/bench/bench_step" ]; then
  for rt in $eulerfsi_runs; do
    r=${rt%x*}; t=${rt#*x}
    echo "== bench_step (pipe), $rt" >&2
    OMP_NUM_THREADS=$t "${mpi[@]}" -np "$r" "$build/bench/bench_step" \
      --benchmark_filter="^BM_Step/nx:$nx/ny:$ny/nz:$nz/particle:0/" --benchmark_out="$work/step_$rt.json" \
      --benchmark_out_format=json >"$work/step_$rt.log" 2>&1 || { tail -20 "$work/step_$rt.log" >&2; die "bench_step failed"; }
    if grep -q '"ns_per_cell_step"' "$work/step_$rt.json"; then
      s=$(awk -v ns="$(gb_json "$work/step_$rt.json" ns_per_cell_step)" -v c="$cells" 'BEGIN { printf "%.6g", ns * c * 1e-9 }')
      rows+=("bench_step BM_Step (pipe)|$rt|$s|$s|flow.advance only, once, for reference")
    else
      echo "cans_compare: bench_step has no ${nx}x${ny}x${nz} row; skipped" >&2
    fi
  done
fi
triad=()
for t in 1 2; do
  OMP_NUM_THREADS=$t "${mpi[@]}" -np 1 "$build/bench/bench_triad" --benchmark_out="$work/triad_t$t.json" \
    --benchmark_out_format=json >"$work/triad_t$t.log" 2>&1 || die "bench_triad failed"
  triad+=("$(gb_json "$work/triad_t$t.json" "GB/s") GB/s on $t thread(s)")
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

# --- table -----------------------------------------------------------------------------------
# CANS_VERSION: a one-line note of the commits, kept beside a checkout made without .git
cans_src=$(dirname "$(dirname "$cans_exe")")
if [ -f "$cans_dir/CANS_VERSION" ]; then cans_ver=$(head -1 "$cans_dir/CANS_VERSION")
elif [ -e "$cans_src/.git" ]; then cans_ver=$(git -C "$cans_src" rev-parse --short HEAD)
else cans_ver=unknown; fi
echo
echo "Square duct ${nx}x${ny}x${nz} ($cells cells), Re 100, dt $dt, $((nstep - warm)) timed steps after $warm;" \
     "$(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores; load $load_before -> $load_after;" \
     "eulerfsi $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)" \
     "(FFT plans: ${fft_planning:-estimate}), CaNS $cans_ver"
echo
echo "| code | ranks x threads | ns / cell / step (median of $rounds) | fastest round | s / step (median) | how |"
echo "|---|---|---|---|---|---|"
for row in "${rows[@]}"; do
  IFS='|' read -r code layout s smin note <<<"$row"
  echo "| $code | $layout | $(ns_cell "$s") | $(ns_cell "$smin") | $(printf '%.4g' "$s") | $note |"
done
echo
echo "Triad bandwidth (bench_triad): ${triad[*]}"
# ratios: eulerfsi's duct run over CaNS, on 1 core (1x1 vs 1 rank) and 2 (best 2-core layout vs 2 ranks)
pick() { for row in "${rows[@]}"; do IFS='|' read -r c l s _ <<<"$row"; [ "$c" = "$1" ] && [ "$l" = "$2" ] && echo "$s"; done; true; }
ratio() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }' || echo n/a; }
c1=$(pick CaNS 1x1); c2=$(pick CaNS 2x1)
for b in "${builds[@]}"; do
  e1=$(pick "$(build_name "$b")" 1x1)
  e2=$(for l in 1x2 2x1; do pick "$(build_name "$b")" $l; done | sort -g | head -1)
  echo "$(build_name "$b") / CaNS (medians): 1 core $(ratio "$e1" "$c1"), 2 cores $(ratio "$e2" "$c2") (issue 8 asks <= 0.65)"
done
echo "logs and inputs: $work" >&2

#!/usr/bin/env bash
# A run continued from a checkpoint matches the uninterrupted run bit for bit on the same ranks:
#  1. stopped cleanly at step 20 (max_steps) and continued with --restart;
#  2. stopped by SIGTERM at an arbitrary step and continued;
#  3. killed with SIGKILL at an arbitrary instant (even mid-write) and continued from the
#     checkpoint that survived.
# Extra arguments go to every run (output.every = 3: the rows' force intervals cross the
# checkpoints). With them (solver.fft_planning=measure) every run starts from a
# common base, the first 10 steps and the FFTW wisdom stored beside their checkpoint: two fresh runs
# that measure their FFT plans may choose different algorithms, so only runs sharing the stored
# plans can agree bit for bit, and each must find them (a restart that warns fails the test).
# usage: restart.sh BINARY CASE WORKDIR NP [RUN ARGUMENTS...]
set -euo pipefail
bin=$1; case_file=$2; work=$3; np=${4:-1}
extra=("${@:5}")
here=$(cd "$(dirname "$0")" && pwd)
# bit for bit needs the same ranks and threads: reductions sum in thread order
export OMP_NUM_THREADS=$((np > 1 ? 1 : ${OMP_NUM_THREADS:-2}))
run() { mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --quiet "$@" "${extra[@]}"; }
# a run whose stderr has a warning (measured FFT plans without their stored wisdom) fails the test
run_checked() {
  run "$@" 2> "$work/run.err" || { cat "$work/run.err" >&2; return 1; }
  cat "$work/run.err" >&2
  if grep -q "^warning:" "$work/run.err"; then echo "error: the run warned"; return 1; fi
}
rm -rf "$work"; mkdir -p "$work"
[ ${#extra[@]} -eq 0 ] || run --out "$work/base" --set time.max_steps=10

# start DIR: an empty run directory, or a copy of the base with its checkpoint as base.h5 (so a new
# checkpoint.h5 is this run's own); `from_base` holds the arguments that continue from there
start() {
  mkdir -p "$1"
  from_base=()
  [ -d "$work/base" ] || return 0
  cp -r "$work/base/." "$1"
  mv "$1/checkpoint.h5" "$1/base.h5"
  # the wisdom is there where the plans were measured
  [ ! -f "$1/checkpoint.h5.fftw-wisdom" ] || mv "$1/checkpoint.h5.fftw-wisdom" "$1/base.h5.fftw-wisdom"
  rm -f "$1/checkpoint.h5.prev"
  from_base=(--restart "$1/base.h5")
}

start "$work/full"
run_checked --out "$work/full" "${from_base[@]}"

start "$work/clean"
run_checked --out "$work/clean" --set time.max_steps=20 "${from_base[@]}"
run_checked --out "$work/clean" --restart
/usr/bin/python3 "$here/compare_runs.py" --exact "$work/full" "$work/clean"

# stop at a moment chosen by the clock, not by the solver
for sig in TERM KILL; do
  dir="$work/sig$sig"
  start "$dir"
  mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --quiet --out "$dir" --set output.checkpoint_every=5 \
    "${from_base[@]}" "${extra[@]}" &
  pid=$!
  # wait for the first checkpoint, then a little longer
  for _ in $(seq 1 600); do [ -f "$dir/checkpoint.h5" ] && break; sleep 0.05; done
  sleep 0.3
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" || true
  # SIGKILL cannot be forwarded: mpiexec dies and leaves its ranks running for a moment, and an
  # orphan still writing a checkpoint would race the continued run. Kill the whole job, as a
  # scheduler would, and wait until it is gone.
  if [ "$sig" = KILL ]; then
    pkill -KILL -f -- "--out $dir --set" 2>/dev/null || true
    for _ in $(seq 1 200); do pgrep -f -- "--out $dir --set" > /dev/null || break; sleep 0.05; done
  fi
  test -f "$dir/checkpoint.h5" || { echo "error: no checkpoint survived SIG$sig"; exit 1; }
  run_checked --out "$dir" --restart --set output.checkpoint_every=5
  /usr/bin/python3 "$here/compare_runs.py" --exact "$work/full" "$dir"
done
echo "restart: all continued runs match the uninterrupted one bit for bit"

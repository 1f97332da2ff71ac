#!/usr/bin/env bash
# A run continued from a checkpoint matches the uninterrupted run bit for bit on the same ranks:
#  1. stopped cleanly at step 20 (max_steps) and continued with --restart;
#  2. stopped by SIGTERM at an arbitrary step and continued;
#  3. killed with SIGKILL at an arbitrary instant (even mid-write) and continued from the
#     checkpoint that survived.
# usage: restart.sh BINARY CASE WORKDIR NP
set -euo pipefail
bin=$1; case_file=$2; work=$3; np=${4:-1}
here=$(cd "$(dirname "$0")" && pwd)
# bit for bit needs the same ranks and threads: reductions sum in thread order
export OMP_NUM_THREADS=$((np > 1 ? 1 : ${OMP_NUM_THREADS:-2}))
run() { mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --quiet "$@"; }
rm -rf "$work"; mkdir -p "$work"

run --out "$work/full"

run --out "$work/clean" --set time.max_steps=20
run --out "$work/clean" --restart
/usr/bin/python3 "$here/compare_runs.py" --exact "$work/full" "$work/clean"

# stop at a moment chosen by the clock, not by the solver
for sig in TERM KILL; do
  dir="$work/sig$sig"
  mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --quiet --out "$dir" --set output.checkpoint_every=5 &
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
  run --out "$dir" --restart --set output.checkpoint_every=5
  /usr/bin/python3 "$here/compare_runs.py" --exact "$work/full" "$dir"
done
echo "restart: all continued runs match the uninterrupted one bit for bit"

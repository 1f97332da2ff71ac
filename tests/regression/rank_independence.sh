#!/usr/bin/env bash
# Runs a case on 1 and on NP ranks (default 2) and requires the results to agree to round-off.
# usage: [NP=4] rank_independence.sh BINARY CASE WORKDIR [compare_runs.py options]
set -euo pipefail
bin=$1; case_file=$2; work=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"
mpiexec -n 1 --oversubscribe "$bin" run "$case_file" --out "$work/np1" --quiet
np=${NP:-2}
OMP_NUM_THREADS=1 mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --out "$work/np$np" --quiet 2> "$work/np$np.err" \
  || { cat "$work/np$np.err"; exit 1; }
/usr/bin/python3 "$here/compare_runs.py" "$work/np1" "$work/np$np" "$@"

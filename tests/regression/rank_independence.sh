#!/usr/bin/env bash
# Runs a case on 1 and on 2 ranks and requires the results to agree to round-off.
# usage: rank_independence.sh BINARY CASE WORKDIR [compare_runs.py options]
set -euo pipefail
bin=$1; case_file=$2; work=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"
mpiexec -n 1 --oversubscribe "$bin" run "$case_file" --out "$work/np1" --quiet
OMP_NUM_THREADS=1 mpiexec -n 2 --oversubscribe "$bin" run "$case_file" --out "$work/np2" --quiet
/usr/bin/python3 "$here/compare_runs.py" "$work/np1" "$work/np2" "$@"

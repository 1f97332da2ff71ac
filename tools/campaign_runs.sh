#!/usr/bin/env bash
# The desk campaign: the cases/desk runs (the reference map, 8 cells per d, Lx = 2), one after
# another on one core, checkpointed; the same command continues a run from its checkpoint (or
# extends a finished one when T_END is raised). Each run gets its own folder under RUNS.
#   usage: tools/campaign_runs.sh STEM [STEM ...]   STEM: a cases/desk file name without .toml, or "list"
#   environment: BIN (default build/eulerfsi), RUNS (default runs/campaign under the current
#                directory; runs/ is ignored by git), NICE (default 10),
#                T_END (default: the case file's time.t_end)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${BIN:-$root/build/eulerfsi}
runs=${RUNS:-$PWD/runs/campaign}
nice_level=${NICE:-10}

if [ "${1:-}" = list ] || [ $# = 0 ]; then
  for f in "$root"/cases/desk/*.toml; do basename "$f" .toml; done
  exit 0
fi
mkdir -p "$runs"
for stem in "$@"; do
  case_file=$root/cases/desk/$stem.toml
  [ -f "$case_file" ] || { echo "[campaign_runs] no case '$stem' (list: $0 list)" >&2; exit 2; }
  dir=$runs/$stem
  args=(--out "$dir")
  [ -n "${T_END:-}" ] && args+=(--set time.t_end="$T_END")
  [ -f "$dir/checkpoint.h5" ] && args+=(--restart)
  echo "[campaign_runs] $stem -> $dir ${args[*]}"
  start=$(date +%s)
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} nice -n "$nice_level" \
    "$bin" run "$case_file" "${args[@]}" --quiet >> "$runs/$stem.log" 2>&1 ||
    echo "[campaign_runs] $stem stopped with status $? (log: $runs/$stem.log)"
  # the wall time of this leg, for the cases/desk headers (tools/make_paper_cases.py)
  echo "[campaign_runs] $stem: $(( $(date +%s) - start )) s of wall time to t = $(tail -n 1 "$dir/particle.csv" | cut -d, -f2)"
done

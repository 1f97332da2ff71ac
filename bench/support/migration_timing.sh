#!/usr/bin/env bash
# Wall time of cases/validation/migration_soft.toml (pipe 80 x 40 x 40, one soft particle, We = 4,
# Re = 100) to t = 2 on one core, for each solid model and each eulerfsi binary given: issue 8's
# "before and after" (run an older build's binary beside the current one in the same sitting; this
# VM's speed drifts by ~10 % between sittings). A manual measurement: not part of CI.
#
# Usage: bench/support/migration_timing.sh BINARY...   (default: build/eulerfsi)
#   T_END=2 MODELS="paper reference-map"   Output: a markdown table of seconds per run.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
t_end=${T_END:-2}
models=${MODELS:-"paper reference-map"}
bins=("$@")
[ ${#bins[@]} -gt 0 ] || bins=("$root/build/eulerfsi")
source "$root/ci/env.sh"
work=$(mktemp -d /tmp/migration_timing.XXXXXX)
echo "| binary | model | wall s (t = 0 -> $t_end) | steps |"
echo "|---|---|---:|---:|"
for b in "${bins[@]}"; do
  [ -x "$b" ] || { echo "migration_timing: not an executable: $b" >&2; exit 1; }
  for m in $models; do
    d=$work/$(basename "$b")_$m
    start=$(date +%s.%N)
    OMP_NUM_THREADS=1 "$b" run "$root/cases/validation/migration_soft.toml" --set "solid[0].model=\"$m\"" \
      --set time.t_end="$t_end" --set output.dir="$d" --set output.checkpoint_every=0 > "$d.log" 2>&1
    end=$(date +%s.%N)
    steps=$(tail -n +2 "$d/flow.csv" | tail -1 | cut -d, -f1)
    printf '| %s | %s | %.1f | %s |\n' "$(basename "$b")" "$m" "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" "$steps"
  done
done
echo "load $(cut -d' ' -f1-3 /proc/loadavg); logs in $work" >&2

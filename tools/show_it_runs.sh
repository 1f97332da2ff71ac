#!/usr/bin/env bash
# The model comparison of docs/REFERENCE_MAP.md: Re = 100, r0/R = 0.2828, released at rest, grid
# following the particle, Lx = 2, the paper's sharp wall, CFL 0.2, to t = 20, the map with
# solid.map_margin = 0.5; both models at 8 and 12 cells per d, We = 4 and 0.125; the map also at
# 16 cells per d (the convergence check). Each run gets its own folder under RUNS (default
# runs/show under the current directory; runs/ is ignored by git) and is checkpointed; the same
# command continues a run from its checkpoint.
#   usage: tools/show_it_runs.sh NAME [NAME ...]   NAME: {paper,map}{8,12}_we{4,0.125}, map16_we{4,0.125}, or "list"
#   environment: BIN (default build/eulerfsi), RUNS, NICE (default 10), T_END (default 20)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${BIN:-$root/build/eulerfsi}
runs=${RUNS:-$PWD/runs/show}
nice_level=${NICE:-10}
t_end=${T_END:-20}

case_args() {  # NAME -> the case file and --set arguments of that run
  local name=$1 model cells we
  [[ $name =~ ^(paper|map)(8|12|16)_we(4|0\.125)$ && $name != paper16* ]] ||
    { echo "unknown run '$name' (list: $0 list)" >&2; return 2; }
  model=${BASH_REMATCH[1]}; cells=${BASH_REMATCH[2]}; we=${BASH_REMATCH[3]}
  if [ "$we" = 4 ]; then echo -n "$root/cases/validation/migration_soft.toml"
  else echo -n "$root/cases/validation/migration_stiff.toml"; fi
  echo -n " --set flow.pipe_wall=\"sharp\" --set time.t_end=$t_end --set output.checkpoint_every=200"
  # the map carried from half a cell inside the surface (margin 0.5, no ramp), as the comparison was run
  [ "$model" = map ] &&
    echo -n " --set solid[0].model=\"reference-map\" --set solid[0].map_margin=0.5 --set solid[0].map_ramp=0"
  [ "$cells" = 12 ] && echo -n " --set domain.cells=[120,60,60]"
  [ "$cells" = 16 ] && echo -n " --set domain.cells=[160,80,80]"
  echo
}

if [ "${1:-}" = list ] || [ $# = 0 ]; then
  for m in paper map; do for c in 8 12; do for w in 4 0.125; do echo "${m}${c}_we${w}"; done; done; done
  echo map16_we4; echo map16_we0.125
  exit 0
fi
source "$root/tools/queue_runs.sh"
queue_runs show_it_runs "$@"

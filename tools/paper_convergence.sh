#!/usr/bin/env bash
# The paper model's convergence beside the map's (docs/REPRODUCTION.md, "The paper model in
# resolution"): the campaign's Re = 200 cases (cases/desk, r0/R = 0.2828, Lx = 2, grid following
# the particle, CFL 0.4) with the paper's psi/B transport and with the reference map, at 8, 12, 16
# and 24 cells per d, We = 4 and 0.125. Every run starts with the particle moving with the fluid
# (at 12 cells per d and finer a soft map particle released at rest can blow up; README, "Known
# limitations"), so the resolutions differ in nothing else. Each run has its own folder under RUNS
# (default runs/convergence; runs/ is ignored by git) and is checkpointed: the same command
# continues it. `archive` copies a run's thinned particle.csv, its resolved case and its sections
# into docs/data/paper_convergence/NAME (tools/archive_run.py; committed, so the figure outlives
# the machine that ran it). `figure` draws r/R and D against t of every run under RUNS, and of
# every archived run that RUNS lacks, and their cross-sections at SHAPE_TIMES.
#   usage: tools/paper_convergence.sh run NAME [NAME ...]   NAME: {paper,map}{8,12,16,24}_we{4,0.125},
#                                                           or paper..._noext: B transported everywhere
#                                                           as the paper does, at CFL 0.2
#          tools/paper_convergence.sh archive NAME [NAME ...]
#          tools/paper_convergence.sh figure [OUT.png]       (default RUNS/paper_convergence.png)
#          tools/paper_convergence.sh list
#   environment: BIN (default build/eulerfsi), RUNS, ARCHIVE (default docs/data/paper_convergence),
#                NICE (default 10), T_END (default 40),
#                PYTHON (default /usr/bin/python3), SHAPE_TIMES (figure's sections, default "10 30 40")
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${BIN:-$root/build/eulerfsi}
runs=${RUNS:-$PWD/runs/convergence}
nice_level=${NICE:-10}
t_end=${T_END:-40}
python=${PYTHON:-/usr/bin/python3}
archive=${ARCHIVE:-$root/docs/data/paper_convergence}

names() {
  for m in paper map; do for c in 8 12 16 24; do for w in 4 0.125; do echo "${m}${c}_we${w}"; done; done; done
  for c in 8 12 16 24; do for w in 4 0.125; do echo "paper${c}_we${w}_noext"; done; done
}

case_args() {  # NAME -> the case file and --set arguments of that run
  local name=$1 model cells we
  [[ ! $name =~ ^map.*_noext$ && $name =~ ^(paper|map)(8|12|16|24)_we(4|0\.125)(_noext)?$ ]] ||
    { echo "unknown run '$name' (list: $0 list)" >&2; return 2; }
  model=${BASH_REMATCH[1]}; cells=${BASH_REMATCH[2]}; we=${BASH_REMATCH[3]}; noext=${BASH_REMATCH[4]}
  echo -n "$root/cases/desk/re200_we${we}_r0.2828_visc1.toml"
  echo -n " --set time.t_end=$t_end --set output.checkpoint_every=500 --set output.fields_every=0"
  echo -n " --set output.shape_times=[0.0,5.0,10.0,20.0,30.0,40.0]"
  echo -n " --set solid[0].initial_velocity=\"fluid\""
  [ "$model" = paper ] && echo -n " --set solid[0].model=\"paper\""
  # the map's surface as the documented runs had it (no ramp), so every resolution shares it
  [ "$model" = map ] && echo -n " --set solid[0].map_ramp=0"
  # the paper's transport of B everywhere (no extension from the solid), at half the time step
  [ -n "$noext" ] && echo -n " --set solid[0].b_extension=false --set time.cfl=0.2"
  echo -n " --set domain.cells=[$((10 * cells)),$((5 * cells)),$((5 * cells))]"
  echo
}

cmd=${1:-list}
shift || true
case $cmd in
  list) names ;;
  run)
    [ $# -gt 0 ] || { echo "usage: $0 run NAME [NAME ...] (list: $0 list)" >&2; exit 2; }
    source "$root/tools/queue_runs.sh"
    queue_runs paper_convergence "$@" ;;
  archive)
    [ $# -gt 0 ] || { echo "usage: $0 archive NAME [NAME ...] (list: $0 list)" >&2; exit 2; }
    for name in "$@"; do
      case_args "$name" > /dev/null || exit 2
      "$python" "$root/tools/archive_run.py" "$runs/$name" "$archive/$name"
    done ;;
  figure)
    out=${1:-$runs/paper_convergence.png}
    found=()
    for name in $(names); do
      if [ -f "$runs/$name/particle.csv" ]; then found+=("$runs/$name")
      elif [ -f "$archive/$name/particle.csv" ]; then found+=("$archive/$name"); fi
    done
    [ ${#found[@]} -gt 0 ] || { echo "no runs under $runs or $archive (run: $0 run NAME)" >&2; exit 2; }
    # shape_times (environment, t U_b / D): the cross-sections drawn, for the runs that saved them
    read -r -a shapes <<< "${SHAPE_TIMES:-10 30 40}"
    "$python" "$root/tools/eulerfsi_plot.py" models "${found[@]}" --shape-times "${shapes[@]}" --out "$out" ;;
  *) echo "unknown command '$cmd' (run, archive, figure, list)" >&2; exit 2 ;;
esac

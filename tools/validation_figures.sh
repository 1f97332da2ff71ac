#!/usr/bin/env bash
# The rigid particle's validation figures in docs/figures/ from the runs docs/VALIDATION.md names,
# in one command (each figure is drawn from the runs that exist; a missing set is skipped):
#   bash tools/validation_figures.sh [RUNS_ROOT=runs] [FIGURES=docs/figures]
#   RUNS_ROOT/liftmap_re{100,200,400}            -> liftmap_rigid_re100_200_400.png
#   RUNS_ROOT/liftmap_duct_re100_n{8,12,16}      -> liftmap_rigid_duct_re100.png (F along the wall
#                                                 bisector and the diagonal), and from n8
#                                                 liftmap_rigid_duct_re100_arrows.png (F over the cross-section)
#   RUNS_ROOT/liftmap_duct_re{20,100,200}_n8 and liftmap_duct_d01_re100_n8
#                                             -> liftmap_rigid_duct_re20_100_200.png (F / (d/H)^4)
#   RUNS_ROOT/liftmap_re100 and liftmap_d015_re100 -> liftmap_rigid_pipe_d015_d02.png (F / (d/D)^4)
#   RUNS_ROOT/release_re{100,400}_r*             -> rigid_releases.png
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-runs}
figures=${2:-$root/docs/figures}
py=/usr/bin/python3
mkdir -p "$figures"
# One `compare` figure from the maps among FOLDER:LABEL specs that exist (none: no figure);
# options before the specs (--lift-coefficient: maps of different sizes on one axis, F / (d/D)^4).
compare_figure() {
  local out=$1; shift
  local options=() sets=() spec
  while [ $# -gt 0 ] && [ "${1#--}" != "$1" ]; do options+=("$1"); shift; done
  for spec in "$@"; do [ -f "$runs/${spec%%:*}/liftmap.csv" ] && sets+=("$runs/$spec"); done
  if [ ${#sets[@]} -gt 0 ]; then
    $py "$root/tools/eulerfsi_liftmap.py" compare "${sets[@]}" "${options[@]}" --out "$figures/$out"
  fi
}
compare_figure liftmap_rigid_re100_200_400.png "liftmap_re100:Re = 100" "liftmap_re200:Re = 200" "liftmap_re400:Re = 400"
compare_figure liftmap_rigid_duct_re100.png "liftmap_duct_re100_n8:8 cells per d" \
  "liftmap_duct_re100_n12:12 cells per d" "liftmap_duct_re100_n16:16 cells per d"
if [ -f "$runs/liftmap_duct_re100_n8/liftmap.csv" ]; then
  $py "$root/tools/eulerfsi_liftmap.py" table "$runs/liftmap_duct_re100_n8" > /dev/null
  cp "$runs/liftmap_duct_re100_n8/liftmap.png" "$figures/liftmap_rigid_duct_re100_arrows.png"
fi
compare_figure liftmap_rigid_duct_re20_100_200.png --lift-coefficient "liftmap_duct_re20_n8:d/H = 0.2, Re = 20" \
  "liftmap_duct_re100_n8:d/H = 0.2, Re = 100" "liftmap_duct_re200_n8:d/H = 0.2, Re = 200" \
  "liftmap_duct_d01_re100_n8:d/H = 0.1, Re = 100"
compare_figure liftmap_rigid_pipe_d015_d02.png --lift-coefficient "liftmap_re100:d/D = 0.2" \
  "liftmap_d015_re100:d/D = 0.15"
releases=()
for d in "$runs"/release_re*_r*; do [ -f "$d/particle.csv" ] && releases+=("$d"); done
if [ ${#releases[@]} -gt 0 ]; then
  $py "$root/tools/eulerfsi_plot.py" radial "${releases[@]}" --out "$figures/rigid_releases.png"
fi

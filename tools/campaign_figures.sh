#!/usr/bin/env bash
# The desk campaign's figures for docs/REPRODUCTION.md, one panel per paper figure, from the campaign's run
# directories (tools/campaign_runs.sh). A panel whose runs are not all there is skipped with a note.
#   usage: tools/campaign_figures.sh [OUT]   OUT: folder for the PNGs (default docs/figures/campaign)
#   environment: RUNS (default runs/campaign under the current directory, as tools/campaign_runs.sh)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${RUNS:-$PWD/runs/campaign}
out=${1:-$root/docs/figures/campaign}
plot="/usr/bin/python3 $root/tools/eulerfsi_plot.py"
mkdir -p "$out"
status=0

# panel NAME COMMAND STEM... : the plot COMMAND of the runs STEM into OUT/NAME.png
panel() {
  local name=$1 cmd=$2; shift 2
  local dirs=() extra=() stem
  while [ $# -gt 0 ]; do
    case $1 in --*) extra=("$@"); break ;; esac
    stem=$1; shift
    [ -f "$runs/$stem/particle.csv" ] || { echo "[campaign_figures] $name: skipped, no run $runs/$stem"; return 0; }
    dirs+=("$runs/$stem")
  done
  if $plot "$cmd" "${dirs[@]}" "${extra[@]}" --out "$out/$name.png"; then echo "[campaign_figures] $out/$name.png"
  else echo "[campaign_figures] $name: $plot $cmd failed"; status=1; fi
}

s=r0.2828_visc1
panel re200_we radial re200_we0.125_$s re200_we0.5_$s re200_we4_$s --label-by We        # fig. 2
panel re400_we radial re400_we0.125_$s re400_we0.25_$s re400_we0.5_$s re400_we1_$s re400_we2_$s re400_we4_$s \
  --label-by We                                                                           # fig. 2 at Re = 400
panel re100_we radial re100_we0.125_$s re100_we0.5_$s re100_we4_$s --label-by We
panel we4_re radial re100_we4_$s re200_we4_$s re400_we4_$s --label-by Re                 # fig. 3
panel we0.5_re radial re100_we0.5_$s re200_we0.5_$s re400_we0.5_$s --label-by Re
panel re400_we1_starts radial re400_we1_r0.0544_visc1 re400_we1_$s re400_we1_r0.7487_visc1 \
  re400_we1_${s}_rest --labels "r0 = 0.0544 R" "r0 = 0.2828 R" "r0 = 0.7487 R" "r0 = 0.2828 R, from rest"  # fig. 7a
panel re400_we1_trajectory trajectory re400_we1_r0.0544_visc1 re400_we1_$s re400_we1_r0.7487_visc1 \
  re400_we1_${s}_rest                                                                     # fig. 7c, 8
panel re400_we4_visc radial re400_we4_r0.2828_visc0.3 re400_we4_$s re400_we4_r0.2828_visc3 --label-by mu  # fig. 12
panel appendix radial appendix_re400_we0.03125_$s appendix_re400_we0.0625_$s re400_we0.125_$s --label-by We
panel forces_re200_we4 forces re200_we4_$s                                                # fig. 11, 13
panel forces_re200_we0.125 forces re200_we0.125_$s
if [ -f "$runs/re200_we4_$s/shapes/index.csv" ]; then                                     # fig. 9, 10
  $plot shapes "$runs/re200_we4_$s" --times 0 5 10 20 40 --out "$out/shapes_re200_we4.png" &&
    echo "[campaign_figures] $out/shapes_re200_we4.png" || status=1
fi
# t_rev, T_osc and t_cen against We and Re: the runs from r0 = 0.2828 R at mu_s/mu_f = 1 (the other
# starts and viscosity ratios would sit on the same We as extra points)
all=()
for d in "$runs"/*_r0.2828_visc1/; do [ -f "$d/summary.json" ] && all+=("${d%/}"); done
if [ ${#all[@]} -gt 0 ]; then                                                            # fig. 4, 5, 11
  # no run may have reached the axis: then there is no t_cen to plot, which is a result, not a failure
  $plot tcen "${all[@]}" --out "$out/tcen.png" && echo "[campaign_figures] $out/tcen.png" ||
    echo "[campaign_figures] tcen: no plot (see the message above)"
  $plot trev-tosc "${all[@]}" --out "$out/trev_tosc.png" && echo "[campaign_figures] $out/trev_tosc.png" || status=1
fi
exit $status

#!/usr/bin/env bash
# The paper's figures from a real (tiny) run of the binary: every applicable PNG appears and is
# non-empty, and the sweep summary reads the run.
# usage: plot_real_run.sh BINARY CASE WORKDIR
set -euo pipefail
bin=$1; case_file=$2; work=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work"; mkdir -p "$work"
"$bin" run "$case_file" --out "$work/run" --quiet --set output.checkpoint_every=0
/usr/bin/python3 "$root/tools/eulerfsi_plot.py" all "$work/run" --out "$work/figures"
for f in radial trajectory forces; do
  test -s "$work/figures/$f.png" || { echo "error: $f.png missing or empty"; exit 1; }
done
ls "$work"/figures/flow_*.png "$work"/figures/shapes_*.png > /dev/null
/usr/bin/python3 "$root/tools/eulerfsi_sweep.py" summary "$work/run" --csv "$work/summary.csv"
test -s "$work/summary.csv"
echo "figures from a real run: $(ls "$work/figures" | wc -l) PNG files"

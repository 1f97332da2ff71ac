#!/bin/bash
# Issue 8's memory comparison: the peak resident memory of `eulerfsi run` on a pipe (Lx = 2D) for
# the flow alone and with one particle (d = D/5, released at r = 0.28 R) carried by either solid
# model, at 128 x 64^2 and 160 x 80^2, a few steps each, one rank. Prints a markdown table with
# the bytes per cell of each and the ratio to the flow alone, and `eulerfsi check`'s estimate.
#   bench/support/memory_compare.sh [BUILD_DIR]     (default: build; STEPS=5 GRIDS="128x64x64 160x80x80")
# Not part of CI (it measures, it does not test); tests/unit/test_memory_estimate.cpp holds the
# bound at 96 x 48^2.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
bin=$build/eulerfsi
steps=${STEPS:-5}
grids=${GRIDS:-"128x64x64 160x80x80"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[ -x "$bin" ] || { echo "memory_compare.sh: no eulerfsi binary at $bin (build it first)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "memory_compare.sh: needs GNU time (/usr/bin/time, Debian package 'time')" >&2; exit 2; }

# case NAME CELLS MODEL (MODEL empty: the flow alone)
write_case() {
  local file=$work/$1.toml cells=$2 model=$3
  cat > "$file" <<EOF
[domain]
length = [2.0, 1.0, 1.0]
cells = [${cells//x/, }]
geometry = "pipe"
[flow]
Re = 100.0
initial = "laminar"
frame_velocity = $([ -n "$model" ] && echo '"particle"' || echo 0.0)
[time]
cfl = 0.2
t_end = 100.0
max_steps = $steps
[output]
dir = "$work/out_$1"
every = 1000
EOF
  if [ -n "$model" ]; then
    cat >> "$file" <<EOF
[[solid]]
shape = "sphere"
diameter = 0.2
center = [1.0, 0.2, 0.2]
We = 4.0
model = "$model"
EOF
  fi
  echo "$file"
}

echo "| grid | run | peak resident MiB | bytes per cell | x flow alone | estimate (eulerfsi check) |"
echo "|---|---|---|---|---|---|"
for g in $grids; do
  cells=$(echo "$g" | tr 'x' '*' | bc)
  flow_kib=0
  for model in "" reference-map paper; do
    name=${model:-flow}_$g
    file=$(write_case "$name" "$g" "$model")
    est=$("$bin" check "$file" 2>&1 | grep -o 'about [0-9.]* [GM]iB' | head -1 || true)
    OMP_NUM_THREADS=1 /usr/bin/time -f %M -o "$work/$name.rss" "$bin" run "$file" --quiet > "$work/$name.log" 2>&1 ||
      { echo "memory_compare.sh: the run $name failed:" >&2; tail -5 "$work/$name.log" >&2; exit 1; }
    kib=$(tail -1 "$work/$name.rss")
    [ -z "$model" ] && flow_kib=$kib
    printf "| %s | %s | %.0f | %.0f | %.2f | %s |\n" "$g" "${model:-flow alone}" "$(echo "$kib/1024" | bc -l)" \
      "$(echo "$kib*1024/$cells" | bc -l)" "$(echo "$kib/$flow_kib" | bc -l)" "${est:-?}"
  done
done

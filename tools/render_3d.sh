#!/bin/bash
# The 3-D picture of a run (tools/eulerfsi_render.py, ParaView's pvbatch), with a virtual X display
# when there is none (xvfb-run; Debian packages paraview python3-paraview xvfb xauth
# libgl1-mesa-dri, installed by ci/setup). Usage: tools/render_3d.sh RUN_DIR OUT.png [render options]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 RUN_DIR OUT.png [--times T ...] [--size W H]" >&2; exit 2; }
run=$1 out=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
command -v pvbatch > /dev/null || { echo "render_3d: pvbatch not found (Debian: apt-get install paraview python3-paraview)" >&2; exit 1; }
render() {
  if [ -n "${DISPLAY:-}" ]; then pvbatch "$here/eulerfsi_render.py" "$run" --out "$out" "$@"
  else xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch "$here/eulerfsi_render.py" "$run" --out "$out" "$@"; fi
}
# a virtual display that has just started sometimes refuses pvbatch's connection (pvbatch then
# aborts; seen twice in a row on a loaded 2-core machine): up to four tries, waiting longer each time
for wait_s in 2 4 8 0; do
  render "$@" 2> "$out.log" && exit 0
  [ "$wait_s" = 0 ] && break
  sleep "$wait_s"
done
grep -v "^ *[0-9][0-9]* *0x" "$out.log" | sed 's/\x1b\[[0-9;]*m//g' | tail -5 >&2
exit 1

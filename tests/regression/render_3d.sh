#!/usr/bin/env bash
# The 3-D picture (tools/render_3d.sh: ParaView's pvbatch on our fields.xdmf) of a tiny real run:
# the PNG must show the pipe and the particles, i.e. ParaView opened our files and found the
# psi = 1/2 surfaces. Skipped (77) without pvbatch, except under CI, where ci/setup installs it.
# usage: render_3d.sh BINARY CASE WORKDIR
set -euo pipefail
bin=$1; case_file=$2; work=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
if ! command -v pvbatch > /dev/null; then
  [ "${CI:-}" = true ] && { echo "error: pvbatch missing under CI (ci/setup installs paraview)"; exit 1; }
  echo "pvbatch not installed: skipped"; exit 77
fi
rm -rf "$work"; mkdir -p "$work"
"$bin" run "$case_file" --out "$work/run" --quiet --set output.checkpoint_every=0 --set output.fields_every=20
bash "$root/tools/render_3d.sh" "$work/run" "$work/picture.png" --size 1200 300
/usr/bin/python3 - "$work/picture.png" <<'PY'
import sys
import matplotlib.image as mpimg
import numpy as np
img = mpimg.imread(sys.argv[1])[..., :3]
white = np.all(img > 0.97, axis=-1)
# the particles are coloured by the viridis map: saturated pixels (the pipe, text and background are
# grey); the colour bar at the right edge (from 0.88 of the width on) is left out
rgb = img[:, : int(0.85 * img.shape[1])].reshape(-1, 3)
saturated = (rgb.max(axis=1) - rgb.min(axis=1)) > 0.25
print(f"picture {img.shape[1]}x{img.shape[0]}: {100 * (1 - white.mean()):.1f} % not white, "
      f"{saturated.sum()} coloured pixels")
# the pipe spans the width (a quarter of the picture at least is not background) and the three
# snapshots' particles (each ~20 pixels across at this size) give hundreds of coloured pixels
assert 1 - white.mean() > 0.25, "blank picture: no pipe drawn"
assert saturated.sum() > 300, "no particle surface drawn"
PY

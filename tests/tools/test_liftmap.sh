#!/usr/bin/env bash
# tools/eulerfsi_liftmap.py with a stand-in binary whose held sphere feels a known lift,
# F_r(r) = (r - 0.3)(0.7 - r) (r in units of R): the tool must place the sphere at each radius,
# find the zeros at 0.3 (unstable: F_r rises through zero) and 0.7 (stable) within the linear
# interpolation's bound (dr)^2 |F''| / (8 |F'|) = 0.00625 for dr = 0.1, continue a position
# from its checkpoint with --restart, refuse a case with two bodies, and report a failed run; pass
# --model, find the zeros along every ray of --points (a duct's bisector and diagonal), and draw several maps (compare).
#   usage: test_liftmap.sh WORK_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: test_liftmap.sh WORK_DIR}
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

stub=$work/stub
cat > "$stub" <<'STUB'
#!/usr/bin/python3
import re, sys
from pathlib import Path
args = sys.argv[1:]
out = Path(args[args.index("--out") + 1])
with open(out.parent / "args.log", "a") as f:
    f.write(" ".join(args) + "\n")
centre = [a for a in args if a.startswith("solid[0].center=")][0]
x, y, z = (float(v) for v in re.findall(r"[-+0-9.e]+", centre.split("=", 1)[1]))
r = (y * y + z * z) ** 0.5 / 0.5
if abs(r - 0.55) < 1e-9:
    sys.exit(3)  # one position fails
fr = (r - 0.3) * (0.7 - r)
er = (y / (0.5 * r), z / (0.5 * r))
out.mkdir(parents=True, exist_ok=True)
with open(out / "particle.csv", "w") as f:
    f.write("step,t,solid,up,spin_x,spin_y,spin_z,hold_Fx,hold_Fy,hold_Fz\n")
    for n in range(21):
        f.write(f"{n},{0.1 * n},0,1.5,0,0,-0.2,0,{-fr * er[0]},{-fr * er[1]}\n")
(out / "checkpoint.h5").write_text("stand-in")
STUB
chmod +x "$stub"
cat > "$work/case.toml" <<'EOF2'
[domain]
length = [1.0, 1.0, 1.0]
cells = [16, 16, 16]
geometry = "pipe"
[[solid]]
diameter = 0.2
center = [0.5, 0.0, 0.0]
model = "rigid"
EOF2

radii=0.15,0.25,0.35,0.45,0.55,0.65,0.75,0.85
rc=0
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" run "$work/case.toml" --radii "$radii" --binary "$stub" \
  --jobs 2 --out-root "$work/map" > "$work/out.txt" 2> "$work/err.txt" || rc=$?
cat "$work/out.txt"
[ "$rc" = 1 ] || fail "a failed position should give exit 1, got $rc"
grep -q "failed: r0.5500" "$work/err.txt" || fail "the failed position is not named: $(cat "$work/err.txt")"
[ -f "$work/map/liftmap.png" ] || fail "no liftmap.png"
grep -q 'solid\[0\].constraint="radial"' "$work/map/args.log" || fail "the sphere is not held radially"
grep -q 'solid\[0\].center=\[0.5, 0.175, 0.0\]' "$work/map/args.log" || fail "r/R = 0.35 not placed at y = 0.175"
/usr/bin/python3 - "$work/map/liftmap_zeros.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
(r1, s1), (r2, s2) = [(float(r["r_over_R"]), int(r["stable"])) for r in rows]
assert abs(r1 - 0.3) < 0.00625 + 1e-9 and s1 == 0, rows
assert abs(r2 - 0.7) < 0.00625 + 1e-9 and s2 == 1, rows
print(f"zeros: {r1:.5f} (unstable), {r2:.5f} (stable)")
PY
# a second run continues every position from its checkpoint
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" run "$work/case.toml" --radii 0.25,0.35 --binary "$stub" \
  --out-root "$work/map" > /dev/null 2>&1 || fail "the continued map failed"
[ "$(grep -c -- '--restart' "$work/map/args.log")" = 2 ] || fail "the continued runs did not --restart"
# the table again from the folder alone
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" table "$work/map" > /dev/null || fail "table failed"
# a duct's points on two rays (wall bisector, diagonal) and one beside them: each ray gets its two
# zeros, placed at their (y, z); the lone point none; the soft model is passed
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" run "$work/case.toml" --model reference-map --binary "$stub" \
  --points 0.1:0,0.2:0,0.3:0,0.4:0,0.1:0.1,0.2:0.2,0.3:0.3,0.3:0.05 --out-root "$work/diag" > "$work/diag.txt" 2>&1 ||
  fail "the duct map failed"
grep -q 'solid\[0\].model="reference-map"' "$work/diag/args.log" || fail "--model not passed"
/usr/bin/python3 - "$work/diag/liftmap_zeros.csv" <<'PY'
import csv, math, sys
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(sys.argv[1]))]
assert len(rows) == 4, rows
for ray, dr in ((0.0, 0.2), (45.0, 0.2 * math.sqrt(2))):
    (a, b) = sorted((r for r in rows if r["ray_deg"] == ray), key=lambda r: r["r_over_R"])
    bound = dr * dr * 2 / (8 * 0.4) + 1e-9  # the interpolation's bound, as above, for this ray's spacing
    assert abs(a["r_over_R"] - 0.3) < bound and a["stable"] == 0, rows
    assert abs(b["r_over_R"] - 0.7) < bound and b["stable"] == 1, rows
    c = math.radians(ray)
    assert abs(b["y"] - 0.5 * b["r_over_R"] * math.cos(c)) < 1e-6 and abs(b["z"] - 0.5 * b["r_over_R"] * math.sin(c)) < 1e-6, rows
print("duct: two zeros on the wall bisector and two on the diagonal, placed")
PY
# positions run later into the same folder join the table
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" run "$work/case.toml" --binary "$stub" --points 0.2:0.05 \
  --out-root "$work/diag" > /dev/null 2>&1 || fail "the added position failed"
[ "$(tail -n +2 "$work/diag/liftmap.csv" | wc -l)" = 9 ] || fail "the table lost the earlier positions"
# several maps on one figure, and one that does not exist refused with exit 2
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" compare "$work/map:pipe" "$work/diag:diagonal" \
  --out "$work/compare.png" > /dev/null || fail "compare failed"
[ -s "$work/compare.png" ] || fail "compare wrote no figure"
# the lift coefficient takes d/D from a position's resolved configuration (a --set diameter), else the case
first=$(tail -n +2 "$work/diag/liftmap_positions.csv" | head -1 | cut -d, -f1)
printf '[domain]\nlength = [1.0, 1.0, 1.0]\n[[solid]]\ndiameter = 0.1\n' > "$work/diag/$first/config.resolved.toml"
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" compare "$work/map:pipe" "$work/diag:duct" --lift-coefficient \
  --out "$work/cl.png" > "$work/cl.txt" || fail "compare --lift-coefficient failed"
grep -q "pipe: .*d/D = 0.2$" "$work/cl.txt" && grep -q "duct: .*d/D = 0.1$" "$work/cl.txt" ||
  fail "the lift coefficient's d/D: $(cat "$work/cl.txt")"
rc=0
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" compare "$work/none:x" --out "$work/x.png" 2> /dev/null || rc=$?
[ "$rc" = 2 ] || fail "compare of a missing map gave exit $rc"
# a case with two bodies is refused with exit 2
printf '[[solid]]\ncenter = [0.5, 0.1, 0]\n[[solid]]\ncenter = [0.2, -0.1, 0]\n' > "$work/two.toml"
rc=0
/usr/bin/python3 "$root/tools/eulerfsi_liftmap.py" run "$work/two.toml" --radii 0.2 --binary "$stub" \
  --out-root "$work/two" 2> "$work/err2.txt" || rc=$?
[ "$rc" = 2 ] && grep -q "exactly one \[\[solid\]\]" "$work/err2.txt" || fail "two bodies not refused: $rc $(cat "$work/err2.txt")"
echo "liftmap: positions, zeros, stability, continuation and refusals as expected"

#!/usr/bin/env bash
# tools/eulerfsi_regime.py with a stand-in binary whose held sphere feels a known lift per
# (Re, We): the rigid sphere F_r = r (0.6 - r) (r in units of R), a soft one with We/Re = w
# F_r = r (0.6 - 2w - r) for w < 0.05, -r (r - 0.3)(r - 0.6) at w = 0.05 (the axis and 0.6 both
# stable) and -r for w > 0.05 (the axis only). The tool must pass flow.Re and solid.We = Re w,
# find each stable radius (the parabola through three radii: exact, to 1e-9, for the quadratics;
# for the cubic within its reported error bar and the linear interpolation's bound
# (dr)^2 |F''| / (8 |F'|) = 0.015 for dr = 0.1, |F''| <= 2.1 and |F'| = 0.18), say where the
# axis is stable, draw the figure, and report a failed position with exit 1 while the figure
# still draws the finished maps and leaves out a blown-up run's forces (rows, but no
# summary.json); a radius run later joins its map, and a malformed list is refused with exit 2.
#   usage: test_regime.sh WORK_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: test_regime.sh WORK_DIR}
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

stub=$work/stub
cat > "$stub" <<'STUB'
#!/usr/bin/python3
import re, sys
from pathlib import Path
args = sys.argv[1:]
sets = dict(a.split("=", 1) for a in args if "=" in a and not a.startswith("-"))
out = Path(args[args.index("--out") + 1])
x, y, z = (float(v) for v in re.findall(r"[-+0-9.e]+", sets["solid[0].center"]))
r = (y * y + z * z) ** 0.5 / 0.5
Re = float(sets["flow.Re"])
if sets["solid[0].model"] == '"rigid"':
    fr = r * (0.6 - r)
else:
    w = float(sets["solid[0].We"]) / Re
    if Re == 30 and w == 0.01 and abs(r - 0.45) < 1e-9:
        sys.exit(3)  # one position fails before its first row
    blown = Re == 30 and w == 0.2  # every position blows up after some rows: forces left out
    fr = r * (0.6 - 2 * w - r) if w < 0.05 else (-r * (r - 0.3) * (r - 0.6) if w == 0.05 else -r)
er = (y / (0.5 * r), z / (0.5 * r))
out.mkdir(parents=True, exist_ok=True)
with open(out / "particle.csv", "w") as f:
    f.write("step,t,solid,up,spin_x,spin_y,spin_z,hold_Fx,hold_Fy,hold_Fz\n")
    for n in range(21):
        f.write(f"{n},{0.1 * n},0,1.5,0,0,-0.2,0,{-fr * er[0]},{-fr * er[1]}\n")
if sets["solid[0].model"] != '"rigid"' and blown:
    print("error: the run blew up at step 20")
    sys.exit(3)
(out / "summary.json").write_text("{}")  # a run that ended normally
STUB
chmod +x "$stub"
printf '[domain]\nlength = [1.0, 1.0, 1.0]\ngeometry = "pipe"\n[[solid]]\ndiameter = 0.2\ncenter = [0.5, 0.1, 0.0]\nmodel = "reference-map"\n' > "$work/case.toml"

rc=0
/usr/bin/python3 "$root/tools/eulerfsi_regime.py" run "$work/case.toml" --re 10,30 --we-over-re 0.01,0.05,0.2 \
  --radii 0.05,0.15,0.25,0.35,0.45,0.55,0.65,0.75 --rigid --binary "$stub" --out-root "$work/map" \
  > "$work/out.txt" 2> "$work/err.txt" || rc=$?
[ "$rc" = 1 ] || fail "a failed position should give exit 1, got $rc"
grep -q "re30_wr0.01/r0.4500" "$work/err.txt" && grep -q "re30_wr0.2/r0.0500" "$work/err.txt" || fail "the failed position is not named: $(cat "$work/err.txt")"
grep -q 'solid\[0\].We=0.5' "$work/map/re10_wr0.05/r0.0500.log" || fail "We = Re (We/Re) not passed"
grep -q 'flow.Re=30.0' "$work/map/re30_rigid/r0.0500.log" || fail "Re not passed to the rigid map"
/usr/bin/python3 "$root/tools/eulerfsi_regime.py" figure "$work/map" --out "$work/regime.png" > /dev/null ||
  fail "the figure failed"
[ -s "$work/regime.png" ] || fail "no figure"
/usr/bin/python3 - "$work/map/regime.csv" <<'PY'
import csv, sys
rows = {r["map"]: r for r in csv.DictReader(open(sys.argv[1]))}
assert len(rows) == 7, sorted(rows)
def radius(name):
    return float(rows[name]["r_eq"])
for re in ("10", "30"):
    assert abs(radius(f"re{re}_rigid") - 0.6) < 1e-9 and rows[f"re{re}_rigid"]["axis_stable"] == "0", rows
    bar = float(rows[f"re{re}_wr0.05"]["r_eq_err"])
    assert abs(radius(f"re{re}_wr0.05") - 0.6) <= min(bar, 0.015) and rows[f"re{re}_wr0.05"]["axis_stable"] == "1", rows
assert radius("re10_wr0.2") == 0.0 and rows["re10_wr0.2"]["axis_stable"] == "1", rows
assert "re30_wr0.2" not in rows, rows  # every position blew up: no forces from it
assert rows["re30_wr0.01"]["blown_up"] == "0", rows  # failed, but not a blow-up
assert abs(radius("re10_wr0.01") - 0.58) < 1e-9 and rows["re10_wr0.01"]["complete"] == "1", rows
assert abs(radius("re30_wr0.01") - 0.58) < 1e-9 and rows["re30_wr0.01"]["complete"] == "0", rows
print("regime: radii, the axis's stability and the failed position as expected")
PY
# a radius run later joins the map's table
/usr/bin/python3 "$root/tools/eulerfsi_regime.py" run "$work/case.toml" --re 10 --we-over-re 0.01 --radii 0.6 \
  --binary "$stub" --out-root "$work/map" > /dev/null 2>&1 || fail "the added radius failed"
[ "$(tail -n +2 "$work/map/re10_wr0.01/liftmap.csv" | wc -l)" = 9 ] || fail "the table lost the earlier radii"
# a usage error: exit 2 and the option named
rc=0
/usr/bin/python3 "$root/tools/eulerfsi_regime.py" run "$work/case.toml" --re 10,x --we-over-re 0.01 --radii 0.6 \
  --binary "$stub" --out-root "$work/bad" 2> "$work/err3.txt" || rc=$?
[ "$rc" = 2 ] && grep -q -- "--re '10,x'" "$work/err3.txt" || fail "a bad --re not refused: $rc $(cat "$work/err3.txt")"
echo "regime: a later radius joins, a bad list refused"

#!/usr/bin/env bash
# A restart by an eulerfsi that writes other particle.csv columns than the one that started the
# run (here: the file cut to its first 18 columns, as before the paper-force columns existed):
# the restart rewrites the kept rows under its own columns ("nan" where new), keeps the original
# as particle.csv.before-restart, and every row then has the header's field count.
# usage: restart_columns.sh BINARY CASE WORKDIR
set -euo pipefail
bin=$1; case_file=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
run=$work/run
"$bin" run "$case_file" --out "$run" --quiet --set time.max_steps=20 --set output.checkpoint_every=10
cut -d, -f1-18 "$run/particle.csv" > "$run/cut.csv" && mv "$run/cut.csv" "$run/particle.csv"
"$bin" run "$case_file" --out "$run" --restart --set time.max_steps=30 --set output.checkpoint_every=10 > "$work/restart.log"
grep -q "was written with other columns" "$work/restart.log" || { echo "error: no note of the rewrite"; exit 1; }
test -s "$run/particle.csv.before-restart" || { echo "error: the original was not kept"; exit 1; }
/usr/bin/python3 - "$run/particle.csv" <<'PY'
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))
header, body = rows[0], rows[1:]
assert all(len(r) == len(header) for r in body), "rows with another field count than the header"
steps = [int(float(r[0])) for r in body]
assert steps == sorted(steps) and steps[-1] == 30, f"steps {steps[:3]}..{steps[-3:]}"
last = header.index(header[-1])
old = [r for r in body if int(float(r[0])) <= 20]  # the checkpoint is the one at step 20
new = [r for r in body if int(float(r[0])) > 20]
assert old and all(math.isnan(float(r[last])) for r in old), "rows before the restart: the new columns must be nan"
assert new and all(not math.isnan(float(r[last])) for r in new), "rows after the restart: the new columns written"
print(f"particle.csv after the restart: {len(body)} rows of {len(header)} fields")
PY

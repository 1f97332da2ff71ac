#!/bin/bash
# Test of tools/eulerfsi_plot.py and tools/eulerfsi_sweep.py on synthetic run dirs.
#   test_plots.sh [WORKDIR]     (default: a fresh temporary folder)
# Runs every plot subcommand and the sweep (summary, dry run, run with a fake solver) and checks
# that each PNG/CSV appears and is non-empty and that errors exit with code 2.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
py=/usr/bin/python3
plot="$py $root/tools/eulerfsi_plot.py"
sweep="$py $root/tools/eulerfsi_sweep.py"
work=${1:-$(mktemp -d)}
rm -rf "$work" && mkdir -p "$work"
fails=0

fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
check_file() { [ -s "$1" ] && echo "ok: $1" || fail "$1 missing or empty"; }
run() { "$@" >"$work/last.log" 2>&1 || { fail "command failed: $*"; cat "$work/last.log"; }; }
expect_rc() { local want=$1; shift; "$@" >"$work/last.log" 2>&1; local rc=$?
  [ $rc -eq "$want" ] && echo "ok: exit $rc from ${*: -2}" || { fail "exit $rc (want $want): $*"; cat "$work/last.log"; }; }

$py -c 'import numpy, matplotlib, tomllib' || { echo "FAIL: $py lacks numpy/matplotlib/tomllib"; exit 1; }
run $py "$here/make_fake_run.py" set "$work/runs"
R="$work/runs"; F="$work/figs"; runs="$R/re200_we0.5 $R/re400_we0.5 $R/re400_we4"

run $plot radial $runs --out "$F/radial.png";              check_file "$F/radial.png"
run $plot radial $runs --out "$F/radial_we.png" --label-by We; check_file "$F/radial_we.png"
run $plot radial $runs --out "$F/radial_labels.png" --labels "old code" "new code" "third"; check_file "$F/radial_labels.png"
run $plot models $runs --out "$F/models_labels.png" --labels a b c; check_file "$F/models_labels.png"
run $plot tcen $runs --out "$F/tcen.png";                  check_file "$F/tcen.png"
run $plot trev-tosc $runs --out "$F/trev_tosc.png";        check_file "$F/trev_tosc.png"
run $plot trajectory $runs --out "$F/trajectory.png";      check_file "$F/trajectory.png"
run $plot shapes "$R/re200_we0.5" --times 0 5 10 20 30 --out "$F/shapes.png"; check_file "$F/shapes.png"
run $plot shapes "$R/re400_we4";                           check_file "$R/re400_we4/shapes.png"
run $plot forces $runs --out "$F/forces.png";              check_file "$F/forces.png"
run $plot flow "$R/re400_we4" --out "$F/flow.png";         check_file "$F/flow.png"
run $plot flow "$R/flow_only";                             check_file "$R/flow_only/flow.png"

# campaign_table.py: one row per run; r/R at t = 10 is particle.csv's last row at or before t = 10
table="$py $root/tools/campaign_table.py"
run $table $runs --times 1,10
[ "$(grep -c '^| re' "$work/last.log")" = 3 ] && echo "ok: campaign_table rows" || { fail "campaign_table rows"; cat "$work/last.log"; }
want=$($py -c "import csv,sys; r=[x for x in csv.DictReader(open(sys.argv[1])) if float(x['t'])<=10+1e-9][-1]; print('%.3f, %.3f' % (float(r['r_over_R']), float(r['taylor_D'])))" "$R/re200_we0.5/particle.csv")
grep -q "^| re200_we0.5 | .* | $want |" "$work/last.log" && echo "ok: campaign_table r/R at t = 10 ($want)" ||
  { fail "campaign_table: r/R, D at t = 10 is not $want"; cat "$work/last.log"; }
# the last column names the model and the map's surface as the run resolved them
cp -r "$R/re400_we4" "$work/map_run" && printf 'model = "reference-map"\nmap_ramp = 0.5\nmap_relax_time = 0.05\nmap_ramp_in_extension = false\n' >> "$work/map_run/config.resolved.toml"
cp -r "$R/re400_we4" "$work/weighted_run" && printf 'model = "reference-map"\nmap_ramp = 0.5\nmap_relax_time = 0.05\n' >> "$work/weighted_run/config.resolved.toml"
cp -r "$R/re400_we4" "$work/no_ramp_run" && printf 'model = "reference-map"\nmap_ramp = 0.0\n' >> "$work/no_ramp_run/config.resolved.toml"
run $table "$work/map_run" "$work/weighted_run" "$work/no_ramp_run"
grep -q "^| map_run | .* | map, ramp 0.5, relax 0.05 |$" "$work/last.log" && grep -q "^| no_ramp_run | .* | map, no ramp |$" "$work/last.log" &&
  grep -q "^| weighted_run | .* | map, ramp 0.5, relax 0.05, weighted fits |$" "$work/last.log" &&
  echo "ok: campaign_table surface column" || { fail "campaign_table surface column"; cat "$work/last.log"; }
expect_rc 2 $table "$work/no_such_run"

# all: includes a flow-only run, whose missing files must give notes, not tracebacks
run $plot all $runs "$R/flow_only" --out "$F/all"
for f in radial trajectory forces tcen trev_tosc flow_flow_only flow_re400_we4 shapes_re200_we0.5; do
  check_file "$F/all/$f.png"
done
grep -q Traceback "$work/last.log" && fail "traceback in 'all' output"
grep -q "note:" "$work/last.log" && echo "ok: notes for skipped plots" || fail "no note for the flow-only run"

# errors: one line, exit code 2
expect_rc 2 $plot radial "$work/no_such_run"
expect_rc 2 $plot radial $runs --labels "one label for three runs"
mkdir -p "$work/empty_run" && : >"$work/empty_run/particle.csv"
expect_rc 2 $plot radial "$work/empty_run"
head -1 "$R/re400_we4/particle.csv" >"$work/empty_run/particle.csv"
expect_rc 2 $plot forces "$work/empty_run"
expect_rc 2 $plot tcen "$R/flow_only"
[ "$(wc -l <"$work/last.log")" -eq 2 ] || fail "error output is not a note plus one line"

# sweep summary of existing runs
run $sweep summary $runs "$R/flow_only" --csv "$work/summary.csv"
check_file "$work/summary.csv"
[ "$(wc -l <"$work/summary.csv")" -eq 5 ] || fail "summary.csv should have 5 lines"
grep -q "flow_only,.*,incomplete$" "$work/summary.csv" || fail "flow-only run not marked incomplete"

# sweep run with a fake solver: one good case, one failing case
mkdir -p "$work/cases"
cp "$R/re200_we0.5/config.resolved.toml" "$work/cases/a_good.toml"
cp "$R/re400_we4/config.resolved.toml" "$work/cases/b_fail.toml"
expect_rc 0 $sweep run "$work/cases" --binary "$here/fake_eulerfsi.sh" --np 2 --out-root "$work/sweep" --dry-run --set time.t_end=5
[ -e "$work/sweep" ] && fail "dry run created files"
grep -q -- "-np 2 .*run .*a_good.toml --out .*/a_good --set time.t_end=5" "$work/last.log" || fail "dry-run command line"
expect_rc 1 $sweep run "$work/cases" --binary "$here/fake_eulerfsi.sh" --out-root "$work/sweep" --set time.t_end=5
check_file "$work/sweep/summary.csv"
check_file "$work/sweep/a_good.log"
check_file "$work/sweep/a_good/particle.csv"
grep -q "^a_good,.*,ok$" "$work/sweep/summary.csv" || fail "a_good not ok in sweep summary"
grep -q "^b_fail,.*,failed$" "$work/sweep/summary.csv" || fail "b_fail not failed in sweep summary"
run $plot all "$work/sweep/a_good" "$work/sweep/b_fail" --out "$work/sweep/figs"
check_file "$work/sweep/figs/radial.png"

if [ $fails -ne 0 ]; then echo "$fails check(s) failed (work dir: $work)"; exit 1; fi
echo "all plot-tool checks passed"

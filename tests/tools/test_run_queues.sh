#!/usr/bin/env bash
# tools/show_it_runs.sh and tools/campaign_runs.sh with a stand-in binary that records its
# arguments: the names they accept, the case and --set arguments each run gets, --restart once a
# checkpoint exists, T_END, and a clear refusal of an unknown name.
#   usage: test_run_queues.sh WORK_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: test_run_queues.sh WORK_DIR}
rm -rf "$work" && mkdir -p "$work/runs"
fail() { echo "FAIL: $*" >&2; exit 1; }

stub=$work/stub
cat > "$stub" <<'STUB'
#!/usr/bin/env bash
echo "$*" >> "$STUB_LOG"
STUB
chmod +x "$stub"
export STUB_LOG=$work/args.log BIN=$stub RUNS=$work/runs NICE=0

# the names
names=$("$root/tools/show_it_runs.sh" list)
[ "$(wc -l <<< "$names")" = 10 ] || fail "show_it_runs.sh list: not 10 runs"
grep -qx map16_we4 <<< "$names" || fail "map16_we4 not listed"
[ "$("$root/tools/campaign_runs.sh" list | wc -l)" = "$(ls "$root"/cases/desk/*.toml | wc -l)" ] ||
  fail "campaign_runs.sh list is not cases/desk"
for bad in paper16_we4 map12_we1; do
  if out=$("$root/tools/show_it_runs.sh" "$bad" 2>&1); then fail "show_it_runs.sh accepted $bad"; fi
  grep -q "unknown run '$bad'" <<< "$out" || fail "no clear message for $bad: $out"
done
if out=$("$root/tools/campaign_runs.sh" no_such_case 2>&1); then fail "campaign_runs.sh accepted no_such_case"; fi
grep -q "no case 'no_such_case'" <<< "$out" || fail "no clear message for no_such_case: $out"

# one run each: the arguments, then --restart beside a checkpoint
"$root/tools/show_it_runs.sh" map16_we4 > /dev/null
grep -q "migration_soft.toml .*pipe_wall=\"sharp\".*model=\"reference-map\".*cells=\[160,80,80\].*--out $RUNS/map16_we4 --quiet$" \
  "$STUB_LOG" || fail "map16_we4 arguments: $(cat "$STUB_LOG")"
mkdir -p "$RUNS/map16_we4" && touch "$RUNS/map16_we4/checkpoint.h5"  # the stand-in writes no run
"$root/tools/show_it_runs.sh" map16_we4 > /dev/null
tail -1 "$STUB_LOG" | grep -q -- "--restart$" || fail "no --restart beside a checkpoint: $(tail -1 "$STUB_LOG")"
T_END=60 "$root/tools/campaign_runs.sh" re200_we4_r0.2828_visc1 > /dev/null
tail -1 "$STUB_LOG" | grep -q "cases/desk/re200_we4_r0.2828_visc1.toml --out $RUNS/re200_we4_r0.2828_visc1 --set time.t_end=60 --quiet$" ||
  fail "campaign arguments: $(tail -1 "$STUB_LOG")"
echo "run queues: OK"

#!/usr/bin/env bash
# tools/show_it_runs.sh, tools/campaign_runs.sh and tools/paper_convergence.sh with a stand-in
# binary that records its arguments: the names they accept, the case and --set arguments each run
# gets, --restart once a checkpoint exists, T_END, a clear refusal of an unknown name, and the
# convergence figure drawn from the runs there are, and the archive of a run (thinned, no machine
# paths) that the figure falls back to.
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
export STUB_LOG=$work/args.log BIN=$stub RUNS=$work/runs NICE=0 ARCHIVE=$work/archive

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
grep -q "migration_soft.toml .*pipe_wall=\"sharp\".*model=\"reference-map\".*map_margin=0.5 .*map_ramp=0 .*cells=\[160,80,80\].*--out $RUNS/map16_we4 --quiet$" \
  "$STUB_LOG" || fail "map16_we4 arguments: $(cat "$STUB_LOG")"
mkdir -p "$RUNS/map16_we4" && touch "$RUNS/map16_we4/checkpoint.h5"  # the stand-in writes no run
"$root/tools/show_it_runs.sh" map16_we4 > /dev/null
tail -1 "$STUB_LOG" | grep -q -- "--restart$" || fail "no --restart beside a checkpoint: $(tail -1 "$STUB_LOG")"
T_END=60 "$root/tools/campaign_runs.sh" re200_we4_r0.2828_visc1 > /dev/null
tail -1 "$STUB_LOG" | grep -q "cases/desk/re200_we4_r0.2828_visc1.toml --out $RUNS/re200_we4_r0.2828_visc1 --set time.t_end=60 --quiet$" ||
  fail "campaign arguments: $(tail -1 "$STUB_LOG")"

# the convergence queue: every resolution starts with the fluid, the paper model named, the grid scaled
[ "$("$root/tools/paper_convergence.sh" list | wc -l)" = 24 ] || fail "paper_convergence.sh list: not 24 runs"
for bad in paper32_we4 map12_we1 paper12 map16_we4_noext; do
  if out=$("$root/tools/paper_convergence.sh" run "$bad" 2>&1); then fail "paper_convergence.sh accepted $bad"; fi
  grep -q "unknown run '$bad'" <<< "$out" || fail "no clear message for $bad: $out"
done
T_END=30 "$root/tools/paper_convergence.sh" run paper24_we0.125 > /dev/null
tail -1 "$STUB_LOG" | grep -q "cases/desk/re200_we0.125_r0.2828_visc1.toml --set time.t_end=30 .*initial_velocity=\"fluid\" .*model=\"paper\" .*cells=\[240,120,120\] --out $RUNS/paper24_we0.125 --quiet$" ||
  fail "paper24_we0.125 arguments: $(tail -1 "$STUB_LOG")"
"$root/tools/paper_convergence.sh" run paper16_we4_noext > /dev/null
tail -1 "$STUB_LOG" | grep -q 'model="paper" --set solid\[0\].b_extension=false --set time.cfl=0.2 .*cells=\[160,80,80\]' ||
  fail "paper16_we4_noext arguments: $(tail -1 "$STUB_LOG")"
RUNS=$work/runs/convergence "$root/tools/paper_convergence.sh" run map12_we4 > /dev/null
tail -1 "$STUB_LOG" | grep -q "map_ramp=0 .*cells=\[120,60,60\] --out" && ! tail -1 "$STUB_LOG" | grep -q 'model="paper"' ||
  fail "map12_we4 arguments: $(tail -1 "$STUB_LOG")"
conv=$work/runs/convergence
if out=$(RUNS=$conv "$root/tools/paper_convergence.sh" figure 2>&1); then fail "a figure without runs"; fi
grep -q "no runs under" <<< "$out" || fail "no clear message for a figure without runs: $out"
for name in paper8_we4 map8_we4; do
  mkdir -p "$conv/$name"
  model=reference-map; [ "$name" = paper8_we4 ] && model=paper
  printf '[flow]\nRe = 200.0\n[domain]\nlength = [2.0, 1.0, 1.0]\ncells = [80, 40, 40]\n[[solid]]\nmodel = "%s"\nWe = 4.0\n' \
    "$model" > "$conv/$name/config.resolved.toml"
  printf 't,r_over_R,taylor_D\n0,0.28,0\n5,0.25,0.05\n10,0.3,0.1\n' > "$conv/$name/particle.csv"
  # a section at t = 10 (a circle of radius 0.1 at s = 0.15), drawn in the panel for t = 10
  mkdir -p "$conv/$name/shapes" && printf 'step,t\n0,0\n7,10\n' > "$conv/$name/shapes/index.csv"
  /usr/bin/python3 -c "import math; print('solid,segment,x,s'); [print(f'0,0,{0.1*math.cos(a/10)},{0.15+0.1*math.sin(a/10)}') for a in range(63)]" \
    > "$conv/$name/shapes/00000007.csv"
done
RUNS=$conv "$root/tools/paper_convergence.sh" figure "$work/conv.png" > /dev/null || fail "the convergence figure failed"
[ -s "$work/conv.png" ] || fail "no convergence figure"

# the archive: a run's resolved case without this machine's paths, particle.csv one row per 0.1
# (t U_b/D = t here: D = 1, U_b = 1) and the last, the sections copied; the figure reads it
run=$conv/map12_we4
mkdir -p "$run/shapes"
printf '# Resolved case from %s/cases/desk/x.toml
[domain]
length = [2.0, 1.0, 1.0]
[flow]
bulk_velocity = 1.0
[output]
dir = "%s"
[[solid]]
model = "reference-map"
' \
  "$root" "$run" > "$run/config.resolved.toml"
/usr/bin/python3 -c "print('step,t,r_over_R,taylor_D'); [print(f'{n},{0.03*n:.2f},0.3,0.1') for n in range(35)]" > "$run/particle.csv"
cp "$conv/map8_we4/shapes/"* "$run/shapes/"
RUNS=$conv "$root/tools/paper_convergence.sh" archive map12_we4 > /dev/null || fail "archive failed"
kept=$(cut -d, -f2 "$ARCHIVE/map12_we4/particle.csv" | tail -n +2 | tr '\n' ' ')
[ "$kept" = "0.00 0.12 0.21 0.30 0.42 0.51 0.60 0.72 0.81 0.90 1.02 " ] || fail "archived rows at t = $kept"
! grep -q -e "$root" -e "$work" "$ARCHIVE/map12_we4/config.resolved.toml" || fail "archived case names this machine's paths"
grep -q 'dir = "map12_we4"' "$ARCHIVE/map12_we4/config.resolved.toml" || fail "archived output.dir"
cmp -s "$run/shapes/00000007.csv" "$ARCHIVE/map12_we4/shapes/00000007.csv" || fail "sections not archived"
if out=$(RUNS=$conv "$root/tools/paper_convergence.sh" archive paper8_we0.125 2>&1); then fail "archived a missing run"; fi
grep -q "config.resolved.toml missing" <<< "$out" || fail "no clear message for a missing run: $out"
rm -rf "$run"
RUNS=$conv "$root/tools/paper_convergence.sh" figure "$work/conv2.png" > /dev/null || fail "the figure from an archive failed"
[ -s "$work/conv2.png" ] || fail "no figure from the archive"
echo "run queues: OK"

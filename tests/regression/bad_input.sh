#!/usr/bin/env bash
# Bad input through the real binary: every bad case file, an impossible rank split, a missing
# file, an unwritable output directory, a restart with different physics, a corrupt checkpoint.
# Each must give one clear message on stderr (naming the key or file), a non-zero exit that is not
# a crash (no signal, no abort, no library dump), and must leave existing results untouched.
# usage: bad_input.sh BINARY TESTS_DIR WORKDIR
set -uo pipefail
bin=$1; tests=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
fail=0

# expect_error NAME SUBSTRING COMMAND...: non-zero exit below 128, stderr contains SUBSTRING, no crash text
expect_error() {
  local name=$1 want=$2; shift 2
  "$@" > "$work/out.txt" 2> "$work/err.txt"
  local code=$?
  local err; err=$(cat "$work/err.txt")
  if [ "$code" -eq 0 ] || [ "$code" -ge 128 ]; then
    echo "FAIL $name: exit code $code"; fail=1
  elif ! grep -qF -- "$want" "$work/err.txt"; then
    echo "FAIL $name: message lacks '$want': $err"; fail=1
  elif grep -qE "terminate called|Aborted|Segmentation|HDF5-DIAG|Traceback|runtime error:|AddressSanitizer" "$work/err.txt"; then
    echo "FAIL $name: crash or library dump: $err"; fail=1
  else
    echo "ok   $name: $(head -n 1 "$work/err.txt")"
  fi
}

mpi1() { mpiexec -n 1 --oversubscribe "$bin" "$@"; }
mpi2() { OMP_NUM_THREADS=1 mpiexec -n 2 --oversubscribe "$bin" "$@"; }

for f in "$tests"/bad_cases/*.toml; do
  want=$(sed -n 's/^# expect: //p' "$f" | head -n 1)
  expect_error "check $(basename "$f")" "$want" "$bin" check "$f"
  # run from an empty directory: a refused case must not create its output directory
  mkdir -p "$work/cwd"
  expect_error "run $(basename "$f")" "$(basename "$f")" bash -c 'cd "$0" && exec "$1" run "$2"' "$work/cwd" "$bin" "$f"
done
[ -z "$(ls -A "$work/cwd")" ] || { echo "FAIL: a refused case created output: $(ls -A "$work/cwd")"; fail=1; }

good="$tests/regression/cases/unsteady_pipe.toml"
expect_error "missing case file" "no_such_case.toml" "$bin" check "$work/no_such_case.toml"
expect_error "unknown --set key" "flow.Reynolds" "$bin" check "$good" --set flow.Reynolds=3
expect_error "bad --set syntax" "flow.Re" "$bin" check "$good" --set flow.Re
expect_error "rank split" "cannot be split into 2" mpi2 check "$good" --set "domain.cells=[15,16,16]"
expect_error "slab too thin" "at least 3" mpi2 check "$good" --set "domain.cells=[4,16,16]"
# a grid that cannot fit in this node's memory: `check` prints what it needs, `run` refuses it
# before allocating anything or creating its output directory
huge='domain.cells=[100000,50000,50000]'
if "$bin" check "$good" --set "$huge" | grep -q '^# memory: about .* per rank'; then
  echo "ok   check prints the memory per rank"
else
  echo "FAIL check does not print the memory per rank"; fail=1
fi
expect_error "too large for memory" "domain.cells" "$bin" run "$good" --set "$huge" --out "$work/huge"
[ ! -e "$work/huge" ] || { echo "FAIL: the refused run created $work/huge"; fail=1; }
touch "$work/a_file"
expect_error "output dir is a file" "$work/a_file" "$bin" run "$good" --out "$work/a_file/run"
mkdir -p "$work/readonly" && chmod 555 "$work/readonly"
if [ "$(id -u)" != 0 ]; then  # root writes anywhere: the permission case only means something for users
  expect_error "read-only output dir" "$work/readonly" "$bin" run "$good" --out "$work/readonly/run"
fi

# a finished run with a checkpoint: different physics is refused, the run is not overwritten
run_dir="$work/run"
mpi1 run "$good" --out "$run_dir" --quiet --set output.checkpoint_every=10 > /dev/null
sum_before=$(md5sum "$run_dir/flow.csv" "$run_dir/checkpoint.h5" | md5sum)
expect_error "restart with other physics" "flow.Re" mpi1 run "$good" --out "$run_dir" --restart --set flow.Re=200
expect_error "fresh run over a checkpoint" "--restart" mpi1 run "$good" --out "$run_dir"
expect_error "restart from missing file" "nowhere.h5" mpi1 run "$good" --out "$run_dir" --restart "$work/nowhere.h5"
cp "$run_dir/checkpoint.h5" "$work/truncated.h5"
truncate -s 20000 "$work/truncated.h5"
expect_error "truncated checkpoint" "truncated.h5" mpi1 run "$good" --out "$run_dir" --restart "$work/truncated.h5"
cp "$run_dir/checkpoint.h5" "$work/flipped.h5"
size=$(stat -c %s "$work/flipped.h5")
printf '\xff\xff\xff\xff' | dd of="$work/flipped.h5" bs=1 seek=$((size / 2)) conv=notrunc status=none
expect_error "corrupt checkpoint" "flipped.h5" mpi1 run "$good" --out "$run_dir" --restart "$work/flipped.h5"
sum_after=$(md5sum "$run_dir/flow.csv" "$run_dir/checkpoint.h5" | md5sum)
[ "$sum_before" = "$sum_after" ] || { echo "FAIL: refused runs changed the existing results"; fail=1; }

# a full disk (a 300 kB tmpfs, where this machine lets us mount one): one message, no partial file
if mkdir -p "$work/tiny" && mount -t tmpfs -o size=300k tmpfs "$work/tiny" 2> /dev/null; then
  expect_error "disk full" "disk full" mpi1 run "$good" --out "$work/tiny/run" --set output.fields_every=2
  if ls "$work"/tiny/run/fields/*.tmp > /dev/null 2>&1; then echo "FAIL: a partial snapshot was left behind"; fail=1; fi
  umount "$work/tiny"
else
  echo "skip disk full: cannot mount a small tmpfs here"
fi

# a blow-up: a fixed time step far above the stability limit
expect_error "blow-up (CFL)" "CFL number would be" mpi1 run "$good" --out "$work/blowup1" --set time.dt=5.0 --set time.t_end=100
# a viscous instability: a fixed dt 3.7 times the explicit viscous limit, CFL still small
expect_error "blow-up (viscous)" "blew up at step" mpi1 run "$good" --out "$work/blowup2" --set flow.Re=1 --set time.dt=2e-3 --set time.max_steps=2000
# a blow-up keeps the last good checkpoint: the step that blew up is reported, not saved
expect_error "blow-up keeps a good checkpoint" "last good checkpoint is kept" mpi1 run "$good" --out "$work/blowup3" \
  --set flow.Re=1 --set time.dt=2e-3 --set time.max_steps=2000 --set output.checkpoint_every=1
blown=$(sed -n 's/.*blew up at step \([0-9]*\).*/\1/p' "$work/err.txt")
kept=$(h5dump -a /step "$work/blowup3/checkpoint.h5" 2>/dev/null | sed -n 's/^ *(0): \([0-9]*\).*/\1/p')
if [ -n "$blown" ] && [ "$kept" = "$((blown - 1))" ]; then
  echo "ok   blow-up at step $blown: the checkpoint kept is step $kept"
else
  echo "FAIL blow-up at step '$blown': the checkpoint kept is step '$kept' (want the step before)"; fail=1
fi
[ "$fail" = 0 ] && echo "bad input: every case refused cleanly"
exit $fail

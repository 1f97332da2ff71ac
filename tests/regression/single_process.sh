#!/usr/bin/env bash
# A build without MPI and HDF5 (-DEULERFSI_ENABLE_MPI=OFF -DEULERFSI_ENABLE_HDF5=OFF) through its
# real binary: field snapshots, checkpoints and restarts are refused at `check`/`run` with a message
# that names the key and says why; a short particle run writes its CSV outputs and summary.
# usage: single_process.sh BINARY TESTS_DIR WORKDIR
set -uo pipefail
bin=$1; tests=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
fail=0
case_file="$tests/regression/cases/particle_pipe.toml"
csv_only=(--set output.fields_every=0 --set output.checkpoint_every=0)

# expect_error NAME SUBSTRING COMMAND...: exit code 2, stderr contains SUBSTRING
expect_error() {
  local name=$1 want=$2; shift 2
  "$@" > "$work/out.txt" 2> "$work/err.txt"
  local code=$?
  if [ "$code" -ne 2 ] || ! grep -qF -- "$want" "$work/err.txt"; then
    echo "FAIL $name: exit $code, stderr: $(cat "$work/err.txt")"; fail=1
  else
    echo "ok   $name: $(head -n 1 "$work/err.txt")"
  fi
}

"$bin" info | tee "$work/info.txt"
grep -q "built without HDF5" "$work/info.txt" || { echo "FAIL: info does not say HDF5 is missing"; fail=1; }
grep -q "fft-dct" "$work/info.txt" || { echo "FAIL: info does not name the fft-dct Poisson solver"; fail=1; }

expect_error "fields_every refused" "output.fields_every" "$bin" check "$case_file" --set output.checkpoint_every=0
expect_error "checkpoint_every refused" "output.checkpoint_every" "$bin" check "$case_file" --set output.fields_every=0
expect_error "reason given" "built without HDF5" "$bin" check "$case_file" --set output.checkpoint_every=0
expect_error "restart refused" "--restart" "$bin" run "$case_file" "${csv_only[@]}" --out "$work/restart" --restart
"$bin" check "$case_file" "${csv_only[@]}" > /dev/null || { echo "FAIL: check of the CSV-only case"; fail=1; }

# 10 steps of the particle case: CSV series, shapes and the summary, no HDF5 files
out="$work/run"
if "$bin" run "$case_file" "${csv_only[@]}" --set time.max_steps=10 --set output.profiles_every=5 --out "$out" --quiet; then
  for f in flow.csv particle.csv summary.json config.resolved.toml; do
    [ -s "$out/$f" ] || { echo "FAIL: $out/$f missing"; fail=1; }
  done
  rows=$(($(wc -l < "$out/flow.csv") - 1))
  [ "$rows" -eq 11 ] || { echo "FAIL: flow.csv has $rows rows, expected 11 (steps 0..10)"; fail=1; }
  [ -z "$(find "$out" -name '*.h5')" ] || { echo "FAIL: HDF5 files written"; fail=1; }
  echo "ok   10 steps: $(tail -n 1 "$out/flow.csv")"
else
  echo "FAIL: the CSV-only run failed"; fail=1
fi
exit $fail

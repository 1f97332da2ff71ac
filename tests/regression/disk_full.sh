#!/usr/bin/env bash
# A disk that fills mid-run: the run stops with one message and exit code 1 (no crash in the HDF5
# or MPI clean-up), the last good checkpoint is kept, and the run continued from it matches an
# uninterrupted one bit for bit. A file-size limit (ulimit -f, SIGXFSZ ignored so that a write
# past it fails with EFBIG as on a full disk) stands in for the full disk, so no root is needed:
#  1. the checkpoint fails: a limit between a field snapshot's size and a checkpoint's;
#  2. a field snapshot fails: a limit below a snapshot's size.
# Both are refused before the file is created (src/io/disk_space.hpp). Where this runs as root,
#  3. a disk that fills during the write (a tmpfs with room for one checkpoint, the check before
#     the write switched off): the writer empties the file before closing it, and nothing crashes.
# usage: disk_full.sh BINARY CASE WORKDIR NP
set -euo pipefail
bin=$1; case_file=$2; work=$3; np=${4:-1}
here=$(cd "$(dirname "$0")" && pwd)
export OMP_NUM_THREADS=$((np > 1 ? 1 : ${OMP_NUM_THREADS:-2}))
run() { mpiexec -n "$np" --oversubscribe "$bin" run "$case_file" --quiet "$@"; }
# run_limited KB ARGS...: the run under a file-size limit of KB kilobytes; prints its exit code
run_limited() {
  local kb=$1; shift
  local rc=0
  # on each rank only: mpiexec's own shared-memory files stay unlimited
  mpiexec -n "$np" --oversubscribe bash -c 'trap "" XFSZ; ulimit -f "$0"; exec "$@"' "$kb" \
    "$bin" run "$case_file" --quiet "$@" > "$work/limited.out" 2> "$work/limited.err" || rc=$?
  echo "$rc"
}
expect_clean_failure() {  # RC WHAT
  cat "$work/limited.err" >&2
  [ "$1" = 1 ] || { echo "error: $2: exit code $1, expected 1"; exit 1; }
  grep -q "disk full" "$work/limited.err" || { echo "error: $2: no 'disk full' message"; exit 1; }
  if grep -qiE "segmentation|signal|core dumped" "$work/limited.err"; then echo "error: $2: crashed"; exit 1; fi
}
rm -rf "$work"; mkdir -p "$work"

run --out "$work/full" --set time.max_steps=40 --set output.fields_every=20 --set output.checkpoint_every=20
snapshot_kb=$(( $(stat -c %s "$work/full/fields/00000020.h5") / 1024 ))
checkpoint_kb=$(( $(stat -c %s "$work/full/checkpoint.h5") / 1024 ))
[ "$snapshot_kb" -lt "$checkpoint_kb" ] || { echo "error: expected snapshots smaller than checkpoints"; exit 1; }

# 1. the checkpoint at step 30 cannot be written; the one of step 20 stays and is continued from
dir="$work/checkpoint_fails"
run --out "$dir" --set time.max_steps=20 --set output.fields_every=20 --set output.checkpoint_every=10
cp "$dir/checkpoint.h5" "$work/step20.h5"
limit=$(( (snapshot_kb + checkpoint_kb) / 2 ))
rc=$(run_limited "$limit" --out "$dir" --restart --set time.max_steps=40 --set output.fields_every=20 \
       --set output.checkpoint_every=10)
expect_clean_failure "$rc" "checkpoint past the limit"
grep -q "cannot write checkpoint" "$work/limited.err" || { echo "error: the message does not name the checkpoint"; exit 1; }
cmp -s "$dir/checkpoint.h5" "$work/step20.h5" || { echo "error: the last good checkpoint was not kept"; exit 1; }
[ ! -e "$dir/checkpoint.h5.tmp" ] || { echo "error: a half-written checkpoint was left behind"; exit 1; }
run --out "$dir" --restart --set time.max_steps=40 --set output.fields_every=20 --set output.checkpoint_every=20
/usr/bin/python3 "$here/compare_runs.py" --exact "$work/full" "$dir"

# 2. the first field snapshot cannot be written
dir="$work/snapshot_fails"
rc=$(run_limited $(( snapshot_kb / 2 )) --out "$dir" --set time.max_steps=40 --set output.fields_every=20 \
       --set output.checkpoint_every=0)
expect_clean_failure "$rc" "snapshot past the limit"
if ls "$dir"/fields/*.tmp > /dev/null 2>&1; then echo "error: a half-written snapshot was left behind"; exit 1; fi
# 3. a real full disk, mid-write
mnt="$work/tmpfs"
mkdir -p "$mnt"
if [ "$(id -u)" = 0 ] && mount -t tmpfs -o size=$(( checkpoint_kb * 3 / 2 ))k tmpfs "$mnt" 2> /dev/null; then
  trap 'umount "$mnt" 2> /dev/null || true' EXIT
  args=(--set time.max_steps=40 --set output.fields_every=0 --set output.checkpoint_every=10)
  run --out "$work/full_nofields" "${args[@]}"
  dir="$mnt/run"
  run --out "$dir" "${args[@]}" --set time.max_steps=10 --set output.checkpoint_every=1000  # the final one only
  cp "$dir/checkpoint.h5" "$work/step10.h5"
  rc=0
  EULERFSI_SKIP_ROOM_CHECK=1 run --out "$dir" --restart "${args[@]}" > "$work/limited.out" 2> "$work/limited.err" || rc=$?
  expect_clean_failure "$rc" "checkpoint on a full disk"
  cmp -s "$dir/checkpoint.h5" "$work/step10.h5" || { echo "error: the last good checkpoint was not kept (full disk)"; exit 1; }
  [ ! -e "$dir/checkpoint.h5.tmp" ] || { echo "error: a half-written checkpoint was left on the full disk"; exit 1; }
  cp -r "$dir" "$work/full_disk_run"
  umount "$mnt"
  trap - EXIT
  run --out "$work/full_disk_run" --restart "${args[@]}"
  /usr/bin/python3 "$here/compare_runs.py" --exact "$work/full_nofields" "$work/full_disk_run"
else
  echo "disk full: no tmpfs here (not root, or mount refused): the mid-write case is not run"
fi
echo "disk full: clean exit 1, the last checkpoint kept and continued bit for bit, no half-written file"

#!/bin/bash
# Stand-in for the eulerfsi binary in the sweep test:
#   fake_eulerfsi.sh run CASE.toml --out DIR [--set K=V ...]
# writes a synthetic run dir with make_fake_run.py; a case whose name contains "fail" exits with 3.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ "${1:-}" = run ] || { echo "usage: $0 run CASE --out DIR [--set K=V ...]" >&2; exit 2; }
case_file=$2; out=""
shift 2
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    *) shift ;;
  esac
done
[ -n "$out" ] || { echo "fake_eulerfsi: --out missing" >&2; exit 2; }
echo "fake_eulerfsi: running $case_file into $out"
if [[ $(basename "$case_file") == *fail* ]]; then
  echo "fake_eulerfsi: simulated failure" >&2
  exit 3
fi
/usr/bin/python3 "$here/make_fake_run.py" case "$case_file" "$out"

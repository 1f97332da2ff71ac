#!/usr/bin/python3
"""Run a set of eulerfsi cases one after another and tabulate their results.

  eulerfsi_sweep.py run CASES... --binary build/eulerfsi [--np N] [--out-root runs/sweep] [--set k=v ...]
  eulerfsi_sweep.py summary RUNDIR... [--csv out.csv]

A case is a .toml file or a directory (all *.toml inside, sorted).  Case CASE runs as
  [MPIRUN -np N] BINARY run CASE --out OUT_ROOT/<case stem> [--set k=v ...]
with its output echoed and saved in OUT_ROOT/<case stem>.log; a failed case is recorded and the
sweep goes on.  Each run dir gets sweep_status.json (exit code, command, wall time) and the sweep
ends with the summary table in OUT_ROOT/summary.csv.  Exit code: 0 if every case succeeded, 1 if
some failed, 2 for a usage error.
"""
import argparse
import csv
import json
import math
import shlex
import subprocess
import sys
import time
import tomllib
from pathlib import Path

COLUMNS = ["case", "Re", "We", "viscosity_ratio", "r0/R", "t_cen", "t_rev", "T_osc", "final r/R", "status"]
STATUS_FILE = "sweep_status.json"


class SweepError(Exception):
    """A usage problem reported in one line with exit code 2."""


# ----------------------------------------------------------------------------- run


def expand_cases(items):
    """Case files from files and directories (a directory gives its *.toml, sorted)."""
    cases = []
    for item in items:
        p = Path(item)
        if p.is_dir():
            found = sorted(p.glob("*.toml"))
            if not found:
                raise SweepError(f"directory '{item}' holds no *.toml case")
            cases += found
        elif p.is_file():
            cases.append(p)
        else:
            raise SweepError(f"case '{item}' not found")
    stems = [c.stem for c in cases]
    dup = sorted({s for s in stems if stems.count(s) > 1})
    if dup:
        raise SweepError(f"several cases share the name(s) {', '.join(dup)}: their run dirs would collide")
    return cases


def case_command(case, out_dir, binary, np_=None, mpirun="mpirun", sets=()):
    """The command line that runs one case."""
    cmd = [mpirun, "-np", str(np_)] if np_ else []
    cmd += [str(binary), "run", str(case), "--out", str(out_dir)]
    if sets:
        cmd += ["--set", *sets]
    return cmd


def run_logged(cmd, log_path):
    """Run cmd, echo and save its output; return the exit code (127 if it cannot start)."""
    with open(log_path, "w") as log:
        log.write("$ " + shlex.join(cmd) + "\n")
        try:
            proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        except OSError as e:
            msg = f"cannot start {cmd[0]}: {e.strerror}\n"
            log.write(msg)
            sys.stdout.write(msg)
            return 127
        for line in proc.stdout:
            log.write(line)
            sys.stdout.write(line)
        return proc.wait()


def write_status(out_dir, cmd, rc, wall):
    """Record how a case ended in its run dir."""
    out_dir.mkdir(parents=True, exist_ok=True)
    status = {"returncode": rc, "command": shlex.join(cmd), "wall_s": round(wall, 3)}
    (out_dir / STATUS_FILE).write_text(json.dumps(status, indent=2) + "\n")


def run_cases(cases, binary, out_root="runs/sweep", np_=None, mpirun="mpirun", sets=(), dry_run=False):
    """Run each case in turn; return the list of run dirs (dry run: only print the commands)."""
    out_root = Path(out_root)
    dirs = []
    for i, case in enumerate(cases, 1):
        out_dir = out_root / case.stem
        cmd = case_command(case, out_dir, binary, np_, mpirun, sets)
        dirs.append(out_dir)
        if dry_run:
            print(shlex.join(cmd))
            continue
        out_root.mkdir(parents=True, exist_ok=True)
        print(f"[{i}/{len(cases)}] {shlex.join(cmd)}", flush=True)
        t0 = time.monotonic()
        rc = run_logged(cmd, out_root / f"{case.stem}.log")
        write_status(out_dir, cmd, rc, time.monotonic() - t0)
        print(f"[{i}/{len(cases)}] {case.stem}: {'ok' if rc == 0 else f'FAILED (exit code {rc})'}", flush=True)
    return dirs


# ----------------------------------------------------------------------------- summary


def read_json(path):
    """A JSON file as a dict, or None if missing or invalid."""
    try:
        return json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError):
        return None


def read_toml(path):
    """A TOML file as a dict, or {} if missing or invalid."""
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return {}


def case_params(cfg):
    """Re, We, viscosity ratio and initial r/R of solid 0 from a resolved config."""
    length = cfg.get("domain", {}).get("length") or [1, 1, 1]
    radius = 0.5 * float(length[1])
    solids = cfg.get("solid") or [{}]
    s = solids[0]
    c = s.get("center")
    r0 = math.hypot(c[1], c[2]) / radius if c and len(c) == 3 else None
    return {"Re": cfg.get("flow", {}).get("Re"), "We": s.get("We"),
            "viscosity_ratio": s.get("viscosity_ratio", 1.0 if "We" in s else None), "r0/R": r0}


def run_status(run_dir, summary):
    """ok, failed (non-zero exit or no run dir) or incomplete (no valid summary.json)."""
    if not run_dir.is_dir():
        return "failed"
    status = read_json(run_dir / STATUS_FILE)
    if status is not None and status.get("returncode", 0) != 0:
        return "failed"
    return "ok" if summary is not None else "incomplete"


def summary_row(run_dir):
    """One table row (dict of COLUMNS) for a run dir."""
    run_dir = Path(run_dir)
    summary = read_json(run_dir / "summary.json")
    row = {"case": run_dir.name, **case_params(read_toml(run_dir / "config.resolved.toml"))}
    s = summary or {}
    row.update({"t_cen": s.get("t_cen"), "t_rev": s.get("t_rev"), "T_osc": s.get("T_osc"),
                "final r/R": s.get("final_r_over_R"), "status": run_status(run_dir, summary)})
    return row


def cell(v):
    """Text of one table cell ('-' for missing values)."""
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def print_table(rows, out=sys.stdout):
    """Print rows as an aligned text table."""
    table = [COLUMNS] + [[cell(r[c]) for c in COLUMNS] for r in rows]
    widths = [max(len(line[i]) for line in table) for i in range(len(COLUMNS))]
    for line in table:
        out.write("  ".join(v.ljust(w) for v, w in zip(line, widths)).rstrip() + "\n")


def write_csv(rows, path):
    """Write rows as CSV (empty cells for missing values)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow(["" if r[c] is None else r[c] for c in COLUMNS])
    print(f"wrote {path}")


def summarize(run_dirs, csv_path=None):
    """Print the summary table of run dirs and optionally write it as CSV; returns the rows."""
    for d in run_dirs:
        if not Path(d).is_dir():
            print(f"note: run directory '{d}' not found, reported as failed", file=sys.stderr)
    rows = [summary_row(d) for d in run_dirs]
    print_table(rows)
    if csv_path:
        write_csv(rows, csv_path)
    return rows


# ----------------------------------------------------------------------------- command line


def cmd_run(args):
    """The run subcommand."""
    if not args.dry_run and not Path(args.binary).exists():
        raise SweepError(f"binary '{args.binary}' not found")
    if args.np is not None and args.np < 1:
        raise SweepError("--np must be at least 1")
    cases = expand_cases(args.cases)
    dirs = run_cases(cases, args.binary, args.out_root, args.np, args.mpirun, args.set or (), args.dry_run)
    if args.dry_run:
        return 0
    rows = summarize(dirs, args.csv or Path(args.out_root) / "summary.csv")
    return 0 if all(r["status"] == "ok" for r in rows) else 1


def cmd_summary(args):
    """The summary subcommand."""
    summarize(args.runs, args.csv)
    return 0


def build_parser():
    """The argparse parser."""
    p = argparse.ArgumentParser(prog="eulerfsi_sweep.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    r = sub.add_parser("run", help="run cases one after another, then print the summary",
                       description="Run cases one after another, then print and write the summary table.")
    r.add_argument("cases", nargs="+", metavar="CASE", help="case file (.toml) or directory of case files")
    r.add_argument("--binary", required=True, help="the eulerfsi executable, e.g. build/eulerfsi")
    r.add_argument("--np", type=int, metavar="N", help="run under MPIRUN with N ranks (default: no mpirun)")
    r.add_argument("--mpirun", default="mpirun", help="MPI launcher used with --np (default: mpirun)")
    r.add_argument("--out-root", default="runs/sweep", help="parent of the run dirs (default: runs/sweep)")
    r.add_argument("--set", nargs="+", action="extend", metavar="K=V",
                   help="overrides for every case, passed on as --set K=V ... (e.g. time.t_end=10); put it after the cases")
    r.add_argument("--csv", help="summary CSV (default: OUT_ROOT/summary.csv)")
    r.add_argument("--dry-run", action="store_true", help="print the commands, run nothing")
    r.set_defaults(func=cmd_run)
    s = sub.add_parser("summary", help="table of results of run dirs",
                       description="Print a table (case, Re, We, viscosity ratio, r0/R, t_cen, t_rev, T_osc, "
                                   "final r/R, status) of run directories.")
    s.add_argument("runs", nargs="+", metavar="RUNDIR", help="run directory")
    s.add_argument("--csv", help="also write the table to this CSV file")
    s.set_defaults(func=cmd_summary)
    return p


def main(argv=None):
    """Run the command line."""
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except SweepError as e:
        print(f"eulerfsi_sweep.py: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

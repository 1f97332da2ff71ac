#!/usr/bin/python3
"""Copies what the figures read of one run directory into a small folder that can be committed.

Kept: config.resolved.toml (paths of this machine replaced by the repository's relative ones),
particle.csv thinned to the first row at or after each multiple of --every in t U_b/D (and the
last row), summary.json if present, and shapes/ (index.csv and every section). Checkpoints,
fields and flow.csv stay behind. A figure drawn from the copy (tools/eulerfsi_plot.py) shows the
run as it was, at the thinned cadence; the copy holds only what the run wrote.

usage: archive_run.py RUN_DIR DEST_DIR [--every 0.1] [--repo ROOT]
"""
import argparse
import csv
import shutil
import sys
from pathlib import Path

from eulerfsi_plot import Run  # the resolved case's time scale, as the figures read it


def without_machine_paths(text, repo, run_dir, dest):
    """Text of the run with its run folder renamed to the archive's (output.dir included) and this
    machine's repository path dropped; the run folder first, since it may lie inside the repository."""
    return text.replace(str(run_dir), dest.name).replace(str(repo) + "/", "")


def thin_rows(rows, t_col, every, scale):
    """The first row at or after each multiple of `every` (in t U_b/D), and the last row."""
    kept, next_t = [], 0.0
    for n, row in enumerate(rows):
        t = float(row[t_col]) * scale
        if t >= next_t - 1e-12 or n == len(rows) - 1:
            kept.append(row)
            while next_t <= t + 1e-12:
                next_t += every
    return kept


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run_dir", type=Path)
    p.add_argument("dest", type=Path)
    p.add_argument("--every", type=float, default=0.1, help="particle.csv cadence kept, in t U_b/D")
    p.add_argument("--repo", type=Path, default=Path(__file__).resolve().parent.parent)
    a = p.parse_args()
    run, dest = a.run_dir.resolve(), a.dest
    for need in ("config.resolved.toml", "particle.csv"):
        if not (run / need).is_file():
            sys.exit(f"archive_run: {run / need} missing (is '{a.run_dir}' a run directory?)")
    if a.every <= 0:
        sys.exit("archive_run: --every must be > 0")
    dest.mkdir(parents=True, exist_ok=True)
    for name in ("config.resolved.toml", "summary.json"):
        if (run / name).is_file():
            text = (run / name).read_text()
            (dest / name).write_text(without_machine_paths(text, a.repo.resolve(), run, dest))
    with open(run / "particle.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    kept = thin_rows(body, header.index("t"), a.every, Run(run).time_scale())
    with open(dest / "particle.csv", "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + kept)
    if (run / "shapes" / "index.csv").is_file():
        shutil.rmtree(dest / "shapes", ignore_errors=True)
        shutil.copytree(run / "shapes", dest / "shapes")
    print(f"archive_run: {len(kept)} of {len(body)} rows of {run.name} -> {dest}")


if __name__ == "__main__":
    main()

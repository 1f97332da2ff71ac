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
import re
import shutil
import sys
from pathlib import Path


def relative_config(text, repo, run_dir, dest):
    """The resolved case with this machine's repository and run paths made relative."""
    text = text.replace(str(repo) + "/", "")
    return re.sub(r'^dir = ".*"$', f'dir = "{dest.name}"', text, flags=re.M).replace(str(run_dir), dest.name)


def time_scale(config_text):
    """U_b / D of the resolved case (t in particle.csv times it is t U_b/D)."""
    length = re.search(r"^length = \[([^\]]*)\]", config_text, flags=re.M)
    bulk = re.search(r"^bulk_velocity = ([0-9.eE+-]+)", config_text, flags=re.M)
    diameter = float(length.group(1).split(",")[1]) if length else 1.0
    return (float(bulk.group(1)) if bulk else 1.0) / diameter


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
    config = (run / "config.resolved.toml").read_text()
    (dest / "config.resolved.toml").write_text(relative_config(config, a.repo.resolve(), run, dest))
    with open(run / "particle.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    kept = thin_rows(body, header.index("t"), a.every, time_scale(config))
    with open(dest / "particle.csv", "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + kept)
    if (run / "summary.json").is_file():
        summary = (run / "summary.json").read_text()
        (dest / "summary.json").write_text(summary.replace(str(a.repo.resolve()) + "/", "").replace(str(run), dest.name))
    if (run / "shapes" / "index.csv").is_file():
        shutil.rmtree(dest / "shapes", ignore_errors=True)
        shutil.copytree(run / "shapes", dest / "shapes")
    print(f"archive_run: {len(kept)} of {len(body)} rows of {run.name} -> {dest}")


if __name__ == "__main__":
    main()

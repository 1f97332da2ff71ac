#!/usr/bin/python3
"""Markdown table of campaign runs for docs/REPRODUCTION.md: per run directory, r/R and D at the
given times (from particle.csv, the last row at or before each time), summary.json's t_rev,
t_cen, T_osc with the oscillation amplitude, and the body's model and map surface (from
config.resolved.toml), so rows made with different settings are told apart.

    usage: tools/campaign_table.py RUN_DIR... [--times 1,10,20,40,60]
"""
import argparse
import csv
import json
import sys
from pathlib import Path

from eulerfsi_plot import PlotError, read_config


def rows_of(run):
    with open(run / "particle.csv") as f:
        return [(float(r["t"]), float(r["r_over_R"]), float(r["taylor_D"])) for r in csv.DictReader(f)
                if r["solid"] == "0"]


def at(rows, t):
    """(r/R, D) of the last row at or before t, or None past the run's end."""
    if not rows or rows[-1][0] < t - 0.2:  # the last row may fall just short of a round time
        return None
    best = rows[0]
    for row in rows:
        if row[0] > t + 1e-9:
            break
        best = row
    return best[1], best[2]


def surface(run):
    """The first body's model and, for the reference map, its surface ramp, as the run resolved them."""
    solid = (read_config(run / "config.resolved.toml").get("solid") or [{}])[0]
    model = solid.get("model")
    if model != "reference-map":
        return model or "-"
    ramp = solid.get("map_ramp", 0.0)
    band = ", smooth band" if solid.get("map_smooth_band", False) else ""
    if not ramp > 0:
        return "map, no ramp" + band
    # a run resolved before the key existed had the ramp's weights in the extension
    weighted = ", weighted fits" if solid.get("map_ramp_in_extension", True) else ""
    return f"map, ramp {ramp:g}, relax {solid.get('map_relax_time', 0.0):g}{weighted}{band}"


def fmt(x, digits=2):
    return "-" if x is None else f"{x:.{digits}f}"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+", type=Path, metavar="RUN_DIR")
    p.add_argument("--times", default="1,10,20,40,60", help="comma-separated times (default 1,10,20,40,60)")
    a = p.parse_args(argv)
    times = [float(t) for t in a.times.split(",")]
    head = ["run", "t_end"] + [f"r/R, D at t = {t:g}" for t in times] + ["t_rev", "t_cen", "T_osc (amplitude / R)", "model, surface"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for run in a.runs:
        try:
            rows = rows_of(run)
        except OSError as e:
            print(f"error: {run}: {e.strerror}: {e.filename}", file=sys.stderr)
            return 2
        s = {}
        if (run / "summary.json").exists():
            whole = json.loads((run / "summary.json").read_text())
            s = whole["solids"][0] if whole.get("solids") else whole  # per solid, or the run's own keys
        cells = [run.name, fmt(rows[-1][0], 1) if rows else "-"]
        for t in times:
            v = at(rows, t)
            cells.append("-" if v is None else f"{v[0]:.3f}, {v[1]:.3f}")
        osc = s.get("T_osc")
        try:
            body = surface(run)
        except PlotError as e:  # an unreadable config.resolved.toml
            print(f"error: {e}", file=sys.stderr)
            return 2
        cells += [fmt(s.get("t_rev")), fmt(s.get("t_cen")),
                  "-" if osc is None else f"{osc:.1f} ({s.get('oscillation_amplitude', 0.0):.4f})", body]
        print("| " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

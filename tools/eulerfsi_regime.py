#!/usr/bin/python3
"""The regime map of a soft sphere in pipe flow: its equilibrium radius over (Re, We/Re).

  eulerfsi_regime.py run CASE --re 10,30,100 --we-over-re 0.001,0.01,0.1 --radii 0.15,0.35,0.55,0.7
                         [--rigid] [--binary build/eulerfsi] [--jobs 2] [--out-root runs/regime] [--set k=v ...]
  eulerfsi_regime.py figure OUT_ROOT [--out docs/figures/regime_map.png] [--free FREE.csv] [--average-from 0.5]

`run` makes one lift map (tools/eulerfsi_liftmap.py) per pair: the case's soft sphere held at each
radius (solid.constraint = "radial", free along x and to rotate and deform) with flow.Re = Re and
solid.We = Re x (We/Re); with --rigid also the rigid sphere's map per Re. Folders:
OUT_ROOT/re<Re>_wr<We/Re>/ and OUT_ROOT/re<Re>_rigid/, each a lift map's folder. Every position of
every map shares one queue, --jobs at a time (cheapest first), so the cores stay busy; a position
with a checkpoint continues from it, so raising time.t_end and running again extends the map, and
radii run later into the same OUT_ROOT join each map's table.
We/Re = mu_f U_b / (G D) is the capillary-like number of the elastic particle (its deformation
over its shear), the paper's We = rho U_b^2 / G over Re = rho U_b D / mu_f.

`figure` reads each map's F_r(r) and draws (left) the stable equilibrium radius over (Re, We/Re):
a filled marker at the outermost stable zero of F_r, a marker on 0 where F_r points inwards at
every radius (the axis the only equilibrium), both where the axis and an off-axis radius are
stable, from the positions whose run ended normally (summary.json; a blown-up run's forces are
left out and its map marked); (right) the radius against We/Re per Re, the rigid sphere's zero as
a dashed line of the same colour (the stiff limit), and with --free the radii where free
particles settled (stars). A zero is the root of the parabola through the two radii that bracket
it and their nearer neighbour; its error bar, the distance to the linear interpolation's root,
is the interpolation's own uncertainty (the forces' drift is in the table). The table
OUT_ROOT/regime.csv lists, per map, the outer stable radius and its error bar, every zero, whether
the axis is stable (F_r < 0 at the innermost radius) and F_r with its drift at each radius;
OUT_ROOT/regime_table.md the same as a Markdown table, a row per Re.
Exit code: 0 done, 1 a run failed (the figure still draws the finished ones), 2 a usage error.
"""
import argparse
import concurrent.futures
import csv
import importlib.util
import math
import os
import sys
from pathlib import Path

_spec = importlib.util.spec_from_file_location("liftmap", Path(__file__).with_name("eulerfsi_liftmap.py"))
liftmap = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(liftmap)


def floats(text, name):
    try:
        out = [float(v) for v in text.split(",")]
    except ValueError:
        raise liftmap.LiftMapError(f"{name} '{text}': a comma-separated list of numbers")
    if any(v <= 0 for v in out):
        raise liftmap.LiftMapError(f"{name} '{text}': every value must be positive")
    return out


def map_name(re, wr):
    return f"re{re:g}_rigid" if wr is None else f"re{re:g}_wr{wr:g}"


def maps_of(args):
    """(folder name, model, Re, We/Re or None, the --set list) of every map the run makes."""
    out = []
    for re in floats(args.re, "--re"):
        if args.rigid:
            out.append((map_name(re, None), "rigid", re, None, [f"flow.Re={re!r}"] + args.set))
        for wr in floats(args.we_over_re, "--we-over-re"):
            out.append((map_name(re, wr), args.model, re, wr, [f"flow.Re={re!r}", f"solid[0].We={re * wr!r}"] + args.set))
    return out


def run(args):
    case = liftmap.read_case(args.case)
    entries = liftmap.positions(case, args.radii, None)
    root = Path(args.out_root)
    threads = max(1, (os.cpu_count() or 1) // max(1, args.jobs))
    jobs = []
    for name, model, re, wr, sets in maps_of(args):
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "liftmap_case.toml").write_text(Path(args.case).read_text())
        liftmap.record_positions(folder, entries)
        with open(folder / "regime_map.csv", "w") as f:
            f.write(f"Re,we_over_re,model\n{re!r},{'' if wr is None else repr(wr)},{model}\n")
        for pos, y, z in entries:
            out = folder / pos
            out.mkdir(exist_ok=True)
            cmd = liftmap.run_command(args.binary, args.case, case, out, y, z, 1, "mpirun", sets, model)
            jobs.append((re, folder, pos, cmd))
    # the explicit viscous step limit makes the low-Re maps the dear ones: they go last
    jobs.sort(key=lambda j: -j[0])
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = {pool.submit(liftmap.run_one, cmd, folder / f"{pos}.log", threads): (folder, pos)
                   for _, folder, pos, cmd in jobs}
        for fut in concurrent.futures.as_completed(futures):
            folder, pos = futures[fut]
            rc = fut.result()
            print(f"{folder.name}/{pos}: exit {rc}", flush=True)
            if rc != 0:
                failed.append(f"{folder.name}/{pos}")
    for name, *_ in maps_of(args):
        folder = root / name
        done = ended_normally(folder)  # this run's and earlier ones'; a blown-up run's forces are left out
        if len(done) >= 2:
            liftmap.write_table(case, folder, done, args.average_from)
    if failed:
        print(f"failed: {', '.join(sorted(failed))} (logs beside each position)", file=sys.stderr)
        return 1
    return 0


def ended_normally(folder):
    """The map's positions whose run ended normally (it wrote summary.json; a blown-up run does not)."""
    return [e for e in liftmap.read_positions(folder) if (folder / e[0] / "summary.json").exists()]


def blew_up(log):
    """Whether a position's log ends in the solver's blow-up report (exit 3)."""
    return log.exists() and "blew up" in log.read_text(errors="replace")


def quadratic_zero(pts, lo, hi):
    """The root in [lo, hi] of the parabola through three (r, F) points, or None."""
    (x0, y0), (x1, y1), (x2, y2) = pts
    # Newton's form: F = y0 + d1 (r - x0) + d2 (r - x0)(r - x1)
    d1 = (y1 - y0) / (x1 - x0)
    d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0)
    a, b, c = d2, d1 - d2 * (x0 + x1), y0 - d1 * x0 + d2 * x0 * x1
    if abs(a) < 1e-300:
        return -c / b if b != 0 and lo <= -c / b <= hi else None
    disc = b * b - 4 * a * c
    if disc < 0:
        return None
    roots = [(-b + sgn * math.sqrt(disc)) / (2 * a) for sgn in (1.0, -1.0)]
    inside = [x for x in roots if lo - 1e-12 <= x <= hi + 1e-12]
    return inside[0] if inside else None


def zeros_with_bars(table):
    """The zeros of F_r(r) with their stability: the parabola's root through the bracketing pair and
    its nearer neighbour, and as its error bar the distance to the linear root (the interpolation's
    own uncertainty; the linear root where there is no third point): [(r, stable, error)]."""
    out = []
    r = [e["r_over_R"] for e in table]
    f = [e["F_r"] for e in table]
    for i in range(len(table) - 1):
        found = liftmap.zeros(table[i:i + 2])  # the lift-map tool's linear root and stability
        if not found:
            continue
        (linear, stable), = found
        third = [j for j in (i - 1, i + 2) if 0 <= j < len(table)]
        third.sort(key=lambda j: min(abs(r[j] - r[i]), abs(r[j] - r[i + 1])))
        quad = None
        if third:
            pts = sorted([(r[k], f[k]) for k in (i, i + 1, third[0])])
            quad = quadratic_zero(pts, r[i], r[i + 1])
        best = linear if quad is None else quad
        out.append((best, stable, abs(best - linear)))
    return out


def summarise_map(folder, average_from):
    """Re, We/Re (None: rigid), the table by radius, the stable off-axis zeros, whether the axis is
    stable; the table only where two or more positions ended normally."""
    with open(folder / "regime_map.csv") as f:
        meta = next(csv.DictReader(f))
    case = liftmap.read_case(folder / "liftmap_case.toml")
    entries = ended_normally(folder)
    out = {"name": folder.name, "folder": str(folder), "Re": float(meta["Re"]),
           "wr": float(meta["we_over_re"]) if meta["we_over_re"] else None,
           "blown_up": sum(1 for e in liftmap.read_positions(folder) if blew_up(folder / f"{e[0]}.log"))}
    if len(entries) < 2:
        return {**out, "table": None}
    table = sorted((liftmap.summarise(case, folder / n, y, z, average_from) for n, y, z in entries),
                   key=lambda e: e["r_over_R"])
    zeros = zeros_with_bars(table)
    stable = [(r, e) for r, s, e in zeros if s]
    axis = table[0]["F_r"] < 0.0
    # no stable zero: the axis where F_r points inwards at the innermost radius, else none found (nan)
    outer = max(stable) if stable else ((0.0, 0.0) if axis else (math.nan, math.nan))
    return {**out, "table": table, "zeros": zeros, "stable": [r for r, _ in stable], "r": outer[0], "r_err": outer[1],
            "axis_stable": axis, "complete": len(entries) == len(liftmap.read_positions(folder))}


def read_free(path):
    """Free releases to draw beside the held maps: rows of Re, we_over_re, r_over_R (# comments)."""
    try:
        with open(path) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        return [{"Re": float(r["Re"]), "wr": float(r["we_over_re"]), "r": float(r["r_over_R"])} for r in rows]
    except FileNotFoundError:
        raise liftmap.LiftMapError(f"--free '{path}' not found")
    except (KeyError, TypeError, ValueError):
        raise liftmap.LiftMapError(f"--free '{path}': needs the columns Re, we_over_re, r_over_R with numbers")


def by_radius(e):
    return "%.3f:%.3e+-%.1e" % (e["r_over_R"], e["F_r"], e["F_r_spread"])


def cell_text(m):
    """One map in a table cell: the stable radius and its error bar, the axis, F_r at the innermost radius."""
    if m is None:
        return "not run"
    if not m["table"]:
        return "blew up" if m["blown_up"] else "running"
    inner = m["table"][0]
    text = f"{m['r']:.2f} +- {m['r_err']:.2f}" if m["stable"] else ("axis" if m["axis_stable"] else "no stable zero")
    if m["stable"] and m["axis_stable"]:
        text += " and axis"
    text += f"; F_r({inner['r_over_R']:.2g}) {inner['F_r']:+.1e} +- {inner['F_r_spread']:.0e}"
    missing = len(liftmap.read_positions(Path(m["folder"]))) - len(m["table"])
    if missing:
        text += f"; {missing} {'radius' if missing == 1 else 'radii'} missing ({m['blown_up']} blew up)"
    return text


def write_markdown(path, every):
    """The maps as a Markdown table: a row per Re, a column per We/Re and one for the rigid sphere."""
    res = sorted({m["Re"] for m in every})
    wrs = sorted({m["wr"] for m in every if m["wr"] is not None})
    by = {(m["Re"], m["wr"]): m for m in every}
    with open(path, "w") as f:
        f.write("| Re | rigid | " + " | ".join(f"We/Re = {w:g}" for w in wrs) + " |\n")
        f.write("|---" * (len(wrs) + 2) + "|\n")
        for re in res:
            f.write(f"| {re:g} | " + " | ".join(cell_text(by.get((re, w))) for w in [None] + wrs) + " |\n")


def figure(args):
    root = Path(args.out_root)
    folders = sorted(p.parent for p in root.glob("*/regime_map.csv"))
    every = [summarise_map(f, args.average_from) for f in folders]
    maps = [m for m in every if m["table"]]
    failed = [m for m in every if not m["table"] and m["blown_up"] and m["wr"] is not None]
    if not maps:
        raise liftmap.LiftMapError(f"no map in '{root}' has two positions that ended normally yet")
    with open(root / "regime.csv", "w") as f:
        f.write("map,Re,we_over_re,complete,blown_up,axis_stable,r_eq,r_eq_err,stable_r,unstable_r,F_r_by_radius\n")
        for m in maps:
            f.write(f"{m['name']},{m['Re']:g},{'' if m['wr'] is None else format(m['wr'], 'g')},{int(m['complete'])},"
                    f"{m['blown_up']},{int(m['axis_stable'])},{m['r']:.4f},{m['r_err']:.4f},"
                    f"{' '.join(f'{r:.4f}' for r in m['stable'])},"
                    f"{' '.join(f'{r:.4f}' for r, s, _ in m['zeros'] if not s)},"
                    f"{' '.join(by_radius(e) for e in m['table'])}\n")
    write_markdown(root / "regime_table.md", every)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    soft = [m for m in maps if m["wr"] is not None]
    rigid = {m["Re"]: m for m in maps if m["wr"] is None}
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11.0, 4.4))
    norm = plt.Normalize(0.0, 0.8)
    cmap = plt.get_cmap("viridis")
    for m in soft:
        if math.isnan(m["r"]):  # F_r outwards at every radius that ended: no equilibrium found
            ax.scatter([m["Re"]], [m["wr"]], marker="o", s=140, facecolors="w", edgecolors="k")
            continue
        r = m["r"]
        mark = "o" if m["stable"] else "s"
        ax.scatter([m["Re"]], [m["wr"]], c=[r], cmap=cmap, norm=norm, marker=mark, s=140,
                   edgecolors="r" if m["axis_stable"] and m["stable"] else "k", linewidths=2 if m["axis_stable"] else 0.8)
        ax.annotate((f"{r:.2f}" if m["stable"] else "axis") + ("" if m["complete"] else "?"), (m["Re"], m["wr"]),
                    textcoords="offset points",
                    xytext=(0, 9), ha="center", fontsize=7)
    for m in failed:  # every position blew up: the map's limit, not a regime
        ax.scatter([m["Re"]], [m["wr"]], marker="x", s=90, c="k")
        ax.annotate("blew up", (m["Re"], m["wr"]), textcoords="offset points", xytext=(0, 9), ha="center", fontsize=7)
    for re, m in rigid.items():  # the stiff limit: the rigid sphere's zero, below the soft rows
        r = m["r"]
        y = min(x["wr"] for x in soft) / 4 if soft else 1e-4
        ax.scatter([re], [y], c=[r], cmap=cmap, norm=norm, marker="D", s=120, edgecolors="k")
        ax.annotate(f"rigid {r:.2f}", (re, y), textcoords="offset points", xytext=(0, 9), ha="center", fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Re = rho U_b D / mu_f")
    ax.set_ylabel("We / Re = mu_f U_b / (G D)")
    ax.set_title("stable r/R (circle; square: the axis only; red edge: the axis stable too;\n"
                 "diamond: rigid; ?: a position blew up or is missing; x: every position blew up)", fontsize=8)
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="equilibrium r / R")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    frees = read_free(args.free) if args.free else []
    for n, re in enumerate(sorted({m["Re"] for m in maps} | {f["Re"] for f in frees})):
        row = sorted((m for m in soft if m["Re"] == re), key=lambda m: m["wr"])
        c = colours[n % len(colours)]
        if row:
            row = [m for m in row if not math.isnan(m["r"])]
            bx.errorbar([m["wr"] for m in row], [m["r"] for m in row], yerr=[m["r_err"] for m in row],
                        marker="o", capsize=2, color=c, label=f"Re = {re:g}, held")
            both = [m for m in row if m["stable"] and m["axis_stable"]]  # the axis stable as well
            bx.plot([m["wr"] for m in both], [0.0] * len(both), marker="o", mfc="w", color=c, ls="none")
        free = [f for f in frees if f["Re"] == re]
        if free:
            bx.plot([f["wr"] for f in free], [f["r"] for f in free], marker="*", ms=10, color=c, ls="none",
                    label=f"Re = {re:g}, free")
        if re in rigid and rigid[re]["stable"]:
            bx.axhline(rigid[re]["r"], color=c, ls="--", lw=0.9)
    bx.set_xscale("log")
    bx.set_xlabel("We / Re")
    bx.set_ylabel("stable r / R (0: the axis; dashed: the rigid sphere)")
    bx.set_title("open: the axis stable too; stars: free releases", fontsize=8)
    bx.set_ylim(-0.02, 0.8)
    bx.legend(fontsize=8)
    fig.tight_layout()
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=120)
    plt.close(fig)
    print(f"wrote {args.out} and {root / 'regime.csv'} ({len(maps)} maps)")
    return 0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="verb", required=True)
    r = sub.add_parser("run", help="run every map of the grid of (Re, We/Re)")
    r.add_argument("case")
    r.add_argument("--re", required=True, help="comma-separated Reynolds numbers")
    r.add_argument("--we-over-re", required=True, help="comma-separated We/Re")
    r.add_argument("--radii", required=True, help="comma-separated r/R of the held sphere")
    r.add_argument("--model", default="reference-map", choices=["reference-map", "paper"])
    r.add_argument("--rigid", action="store_true", help="also the rigid sphere's map per Re")
    r.add_argument("--binary", default="build/eulerfsi")
    r.add_argument("--jobs", type=int, default=2)
    r.add_argument("--out-root", default="runs/regime")
    r.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    r.add_argument("--average-from", type=float, default=0.5)
    f = sub.add_parser("figure", help="the regime map of the finished maps")
    f.add_argument("out_root")
    f.add_argument("--out", default="docs/figures/regime_map.png")
    f.add_argument("--average-from", type=float, default=0.5)
    f.add_argument("--free", help="CSV of free releases (Re, we_over_re, r_over_R) drawn as stars on the right")
    args = p.parse_args(argv)
    if not 0.0 <= args.average_from < 1.0:
        p.error(f"--average-from {args.average_from}: a fraction of the run's last time, in [0, 1)")
    try:
        return run(args) if args.verb == "run" else figure(args)
    except liftmap.LiftMapError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Plots of eulerfsi run directories, after the figures of Alghalibi, Rosti & Brandt (2019).

Each subcommand reads one or more run directories (config.resolved.toml, flow.csv, particle.csv,
summary.json, shapes/) and writes PNG files (dpi 150).  Times are shown as t U_b/D with D the pipe
diameter (domain.length[1]) and U_b = flow.bulk_velocity; times in summary.json are scaled the same
way.  Every plot function is importable, e.g. ``from eulerfsi_plot import plot_radial``.

Examples:
  eulerfsi_plot.py radial runs/re200_we0.5 runs/re400_we0.5 --out figures/radial.png
  eulerfsi_plot.py tcen runs/sweep/* --out figures/tcen.png
  eulerfsi_plot.py shapes runs/re200_we0.5 --times 0 5 10 20
  eulerfsi_plot.py all runs/sweep/* --out figures
"""
import argparse
import csv
import json
import math
import sys
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

DPI = 150
T_LABEL = r"$t\,U_b/D$"
R_LABEL = r"$r/R$"
FORCE_COLUMNS = [("F_r", r"$F_r$"), ("F_r_pressure", r"$F_r^P$"), ("F_r_inertia", r"$F_r^I$"),
                 ("F_r_viscous", r"$F_r^V$"), ("F_r_elastic", r"$F_r^E$")]
PARAM_TEX = {"Re": r"$Re$", "We": r"$We$", "mu": r"$\mu^s/\mu^f$", "r0": r"$r_0/R$"}


class PlotError(Exception):
    """A problem with the input that ends the command with a one-line message."""


# ----------------------------------------------------------------------------- reading


class Run:
    """One run directory with lazily read files."""

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.is_dir():
            raise PlotError(f"run directory '{path}' not found")
        self._cfg = None

    @property
    def name(self):
        """The directory name."""
        return self.path.name

    @property
    def config(self):
        """The resolved case as a dict (empty if config.resolved.toml is missing)."""
        if self._cfg is None:
            self._cfg = read_config(self.path / "config.resolved.toml")
        return self._cfg

    def file(self, rel):
        """Path of a file in the run, or PlotError if missing."""
        p = self.path / rel
        if not p.exists():
            raise PlotError(f"{self.name}: {rel} missing")
        return p

    def has(self, rel):
        """Whether the run has this file."""
        return (self.path / rel).exists()

    def flow(self):
        """Columns of flow.csv."""
        return read_csv(self.file("flow.csv"))

    def particle(self, solid=None):
        """Columns of particle.csv, restricted to one solid if given."""
        data = read_csv(self.file("particle.csv"))
        if solid is None or "solid" not in data:
            return data
        keep = data["solid"] == solid
        return {k: v[keep] for k, v in data.items()}

    def solids(self):
        """Indices of the solids present in particle.csv."""
        data = read_csv(self.file("particle.csv"))
        return sorted(set(int(s) for s in data["solid"])) if "solid" in data else [0]

    def summary(self):
        """summary.json as a dict."""
        p = self.file("summary.json")
        try:
            return json.loads(p.read_text())
        except json.JSONDecodeError as e:
            raise PlotError(f"{p}: not valid JSON ({e.msg}, line {e.lineno})") from None

    def params(self, solid=0):
        """Dict of Re, We, mu (viscosity ratio) and r0 (initial r/R) from the config."""
        cfg = self.config
        out = {"Re": cfg.get("flow", {}).get("Re")}
        solids = cfg.get("solid", [])
        if len(solids) > solid:
            s = solids[solid]
            out["We"] = s.get("We")
            out["mu"] = s.get("viscosity_ratio", 1.0)
            c = s.get("center")
            if c is not None and len(c) == 3:
                out["r0"] = math.hypot(c[1], c[2]) / pipe_radius(cfg)
        return out

    def time_scale(self):
        """Factor turning solver time into t U_b/D."""
        cfg = self.config
        ub = cfg.get("flow", {}).get("bulk_velocity", 1.0) or 1.0
        return ub / (2.0 * pipe_radius(cfg))


def pipe_radius(cfg):
    """Pipe radius R = domain.length[1] / 2 (0.5 if unknown)."""
    length = cfg.get("domain", {}).get("length")
    return 0.5 * float(length[1]) if length and len(length) > 1 else 0.5


def read_config(path):
    """Read a TOML config; an empty dict if the file is missing."""
    path = Path(path)
    if not path.exists():
        return {}
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise PlotError(f"{path}: invalid TOML ({e})") from None


def read_csv(path):
    """Read a numeric CSV with a header into a dict of numpy arrays; PlotError if it has no rows."""
    path = Path(path)
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise PlotError(f"{path}: cannot read ({e.strerror})") from None
    rows = [r for r in rows if r and any(c.strip() for c in r)]
    if len(rows) < 2:
        raise PlotError(f"{path}: empty CSV (no data rows)")
    header = [h.strip() for h in rows[0]]
    try:
        data = np.array([[float(c) if c.strip() else np.nan for c in r[:len(header)]] for r in rows[1:]
                         if len(r) >= len(header)])
    except ValueError as e:
        raise PlotError(f"{path}: non-numeric value ({e})") from None
    if data.size == 0:
        raise PlotError(f"{path}: no complete data rows")
    return {h: data[:, i] for i, h in enumerate(header)}


def need(data, cols, what):
    """PlotError unless all columns are present."""
    missing = [c for c in cols if c not in data]
    if missing:
        raise PlotError(f"{what}: column(s) {', '.join(missing)} missing")


def load_runs(paths):
    """Run objects for a list of paths."""
    if not paths:
        raise PlotError("no run directories given")
    return [p if isinstance(p, Run) else Run(p) for p in paths]


# ----------------------------------------------------------------------------- labels


def fmt(v):
    """Compact number for a legend."""
    if v is None:
        return "?"
    return f"{v:.4g}"


def varying_params(runs):
    """Parameters (Re, We, mu, r0) that differ between runs; Re and We if none differ."""
    keys = ["Re", "We", "mu", "r0"]
    vals = {k: {None if r.params().get(k) is None else round(r.params()[k], 6) for r in runs} for k in keys}
    out = [k for k in keys if len(vals[k]) > 1]
    return out or ["Re", "We"]


def method_tag(run):
    """The solid model and its resolution, e.g. 'reference-map, 8 cells/d' (every figure names them)."""
    cfg = run.config
    s = (cfg.get("solid") or [{}])[0]
    cells = cfg.get("domain", {}).get("cells", [0, 0, 0])
    length = cfg.get("domain", {}).get("length", [1, 1, 1])
    per_d = s.get("diameter", 0) * cells[1] / length[1] if cells[1] else 0
    return f"{s.get('model', 'paper')}, {per_d:.0f} cells/d"


def run_label(run, keys, solid=None):
    """Legend text such as 'Re=200, We=0.5 (reference-map, 8 cells/d)'."""
    p = run.params(solid or 0)
    text = ", ".join(f"{PARAM_TEX[k]}={fmt(p.get(k))}" for k in keys)
    if not run.config:
        return run.name + (f" (solid {solid})" if solid is not None else "")
    return text + (f" (solid {solid})" if solid is not None else "") + f" ({method_tag(run)})"


def label_keys(runs, label_by):
    """Keys used in legends: the chosen one or those that vary."""
    return [label_by] if label_by else varying_params(runs)


def save(fig, out):
    """Write a figure as PNG and close it."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {out}")
    return out


def default_out(runs, name, out):
    """Output path: the given one, or NAME in the (single) run dir, or figures/NAME."""
    if out:
        return Path(out)
    return runs[0].path / name if len(runs) == 1 else Path("figures") / name


# ----------------------------------------------------------------------------- radial


def given_labels(runs, labels):
    """The legend labels the user gave, one per run (None: make them from the runs)."""
    if labels is None:
        return None
    if len(labels) != len(runs):
        raise PlotError(f"--labels gives {len(labels)} label(s) for {len(runs)} run(s): give one per run, in order")
    return labels


def plot_radial(paths, out=None, label_by=None, labels=None):
    """r/R against t U_b/D for several runs (paper figs 2, 3, 7a, 12, 14)."""
    runs = load_runs(paths)
    keys = label_keys(runs, label_by)
    names = given_labels(runs, labels)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for n, run in enumerate(runs):
        solids = run.solids()
        for s in solids:
            d = run.particle(s)
            need(d, ["t", "r_over_R"], f"{run.name}/particle.csv")
            label = run_label(run, keys, s if len(solids) > 1 else None)
            if names:
                label = names[n] + (f" (solid {s})" if len(solids) > 1 else "")
            ax.plot(d["t"] * run.time_scale(), d["r_over_R"], label=label)
    ax.set_xlabel(T_LABEL)
    ax.set_ylabel(R_LABEL)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save(fig, default_out(runs, "radial.png", out))


def model_label(run):
    """Legend text such as 'reference-map, 8 cells/d, We=4': the solid model and its resolution."""
    s = (run.config.get("solid") or [{}])[0]
    return f"{method_tag(run)}, $We$={fmt(s.get('We'))}"


def outline_at(run, t):
    """The cross-section of solid 0 saved nearest to solver time t, closed, in units of R, and its t."""
    step, t_saved = pick_shapes(shape_index(run), [t])[0]
    d = read_csv(run.file(f"shapes/{step:08d}.csv"))
    need(d, ["x", "s"], f"{run.name}/shapes/{step:08d}.csv")
    m = d.get("solid", np.zeros_like(d["x"])) == 0
    radius = pipe_radius(run.config)
    x, s = closed_outline(d["x"][m] / radius, d["s"][m] / radius)
    return x, s, t_saved


def plot_models(paths, out=None, labels=None, shape_times=None):
    """r/R and the Taylor deformation D against t U_b/D, one line per run labelled by solid model and
    resolution (the solid-model comparison of docs/REFERENCE_MAP.md); with shape_times (in t U_b/D)
    a row below with every run's cross-section at each of those times, in the run's colour."""
    runs = load_runs(paths)
    names = given_labels(runs, labels)
    if shape_times:
        fig = plt.figure(figsize=(11, 7.5), layout="constrained")
        gs = fig.add_gridspec(2, 2 * len(shape_times), height_ratios=[1.0, 1.1])
        n_half = len(shape_times)
        ax_r, ax_d = fig.add_subplot(gs[0, :n_half]), fig.add_subplot(gs[0, n_half:])
        ax_shapes = [fig.add_subplot(gs[1, 2 * i:2 * i + 2]) for i in range(len(shape_times))]
    else:
        fig, (ax_r, ax_d) = plt.subplots(1, 2, figsize=(11, 4.0))
        ax_shapes = []
    s_range, x_half = [1.0, 0.0], 0.0  # the sections' extent in s/R and x/R, for the panels' limits
    for n, run in enumerate(runs):
        d = run.particle(0)
        need(d, ["t", "r_over_R", "taylor_D"], f"{run.name}/particle.csv")
        t = d["t"] * run.time_scale()
        style = "-" if "reference" in model_label(run) else "--"
        line, = ax_r.plot(t, d["r_over_R"], style, label=names[n] if names else model_label(run))
        ax_d.plot(t, d["taylor_D"], style, color=line.get_color())
        for ax, want in zip(ax_shapes, shape_times or []):
            if not run.has("shapes/index.csv"):
                continue  # no sections saved
            x, s, t_saved = outline_at(run, want / run.time_scale())
            if abs(t_saved * run.time_scale() - want) > 0.01 * want + 0.01:
                continue  # no section saved at that time
            ax.plot(x, s, style, color=line.get_color(), lw=1)
            s_range[0], s_range[1] = min(s_range[0], s.min()), max(s_range[1], s.max())
            x_half = max(x_half, np.abs(x).max())
    ax_r.set_xlabel(T_LABEL)
    ax_r.set_ylabel(R_LABEL)
    ax_r.set_ylim(bottom=0)
    ax_d.set_xlabel(T_LABEL)
    ax_d.set_ylabel(r"Taylor deformation $D$")
    ax_d.set_ylim(bottom=0)
    ax_r.legend(fontsize=7)
    for ax in (ax_r, ax_d):
        ax.grid(alpha=0.3)
    for ax, want in zip(ax_shapes, shape_times or []):
        ax.axhline(0, color="gray", ls="--", lw=0.6)  # the axis and the wall, where in reach
        ax.axhline(1, color="k", lw=1.5)
        if s_range[0] < s_range[1]:
            ax.set_ylim(max(-0.02, s_range[0] - 0.05), min(1.02, s_range[1] + 0.05))
            ax.set_xlim(-x_half - 0.05, x_half + 0.05)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_title(rf"cross-sections at $t\,U_b/D$ = {want:g}", fontsize=9)
        ax.set_xlabel(r"$x/R$ (from the centroid)", fontsize=8)
        ax.set_ylabel(r"$s/R$", fontsize=8)
    return save(fig, default_out(runs, "models.png", out))


# ----------------------------------------------------------------------------- summary plots


def summary_table(runs, key):
    """List of (Re, We, value) for runs whose summary has a non-null key."""
    rows = []
    for run in runs:
        if not run.has("summary.json"):
            print(f"note: {run.name}: no summary.json, left out", file=sys.stderr)
            continue
        v = run.summary().get(key)
        p = run.params()
        if v is None or p.get("Re") is None or p.get("We") is None:
            continue
        rows.append((p["Re"], p["We"], float(v) * run.time_scale()))
    return rows


def grouped_lines(ax, rows, xi, gi, gname):
    """Plot value against column xi with one line per distinct value of column gi."""
    for g in sorted({r[gi] for r in rows}):
        pts = sorted((r[xi], r[2]) for r in rows if r[gi] == g)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"{gname}={fmt(g)}")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)


def we_axis(ax):
    """Log-2 We axis with plain number tick labels."""
    ax.set_xscale("log", base=2)
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.set_xlabel(r"$We$")


def require_rows(rows, key):
    """PlotError if no run has a value for key."""
    if not rows:
        raise PlotError(f"no run has a value for {key} in summary.json")


def plot_tcen(paths, out=None):
    """t_cen against Re (lines per We) and against We (lines per Re), paper fig 4."""
    runs = load_runs(paths)
    rows = summary_table(runs, "t_cen")
    require_rows(rows, "t_cen")
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.0, 3.6))
    grouped_lines(a, rows, 0, 1, r"$We$")
    a.set_xlabel(r"$Re$")
    a.set_ylabel(r"$t_{cen}\,U_b/D$")
    a.set_title("(a)", loc="left")
    grouped_lines(b, rows, 1, 0, r"$Re$")
    we_axis(b)
    b.set_ylabel(r"$t_{cen}\,U_b/D$")
    b.set_title("(b)", loc="left")
    fig.tight_layout()
    return save(fig, default_out(runs, "tcen.png", out))


def plot_trev_tosc(paths, out=None):
    """t_rev and T_osc against We, one line per Re (paper figs 5 and 12)."""
    runs = load_runs(paths)
    trev, tosc = summary_table(runs, "t_rev"), summary_table(runs, "T_osc")
    if not trev and not tosc:
        raise PlotError("no run has a value for t_rev or T_osc in summary.json")
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.6))
    for ax, rows, lab, tag in ((axes[0], trev, r"$t_{rev}\,U_b/D$", "(a)"),
                               (axes[1], tosc, r"$T_{osc}\,U_b/D$", "(b)")):
        if rows:
            grouped_lines(ax, rows, 1, 0, r"$Re$")
            we_axis(ax)
        else:
            ax.text(0.5, 0.5, "no data", ha="center", va="center", transform=ax.transAxes)
        ax.set_xlabel(r"$We$")
        ax.set_ylabel(lab)
        ax.set_title(tag, loc="left")
    fig.tight_layout()
    return save(fig, default_out(runs, "trev_tosc.png", out))


# ----------------------------------------------------------------------------- trajectory


def plot_trajectory(paths, out=None, label_by=None):
    """Particle paths in the pipe cross-section y/R, z/R (paper figs 7c, 8)."""
    runs = load_runs(paths)
    keys = label_keys(runs, label_by)
    fig, ax = plt.subplots(figsize=(5.0, 5.0))
    phi = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(phi), np.sin(phi), "k-", lw=1)
    first = True
    for run in runs:
        radius = pipe_radius(run.config)
        solids = run.solids()
        for s in solids:
            d = run.particle(s)
            need(d, ["yc", "zc"], f"{run.name}/particle.csv")
            y, z = d["yc"] / radius, d["zc"] / radius
            ax.plot(y, z, lw=1.2, label=run_label(run, keys, s if len(solids) > 1 else None))
            ax.plot(y[0], z[0], "s", color="k", ms=6, label="initial" if first else None)
            ax.plot(y[-1], z[-1], "o", color="purple", ms=6, label="final" if first else None)
            first = False
    ax.set_aspect("equal")
    ax.set_xlim(-1.05, 1.05)
    ax.set_ylim(-1.05, 1.05)
    ax.set_xlabel(r"$y/R$")
    ax.set_ylabel(r"$z/R$")
    ax.legend(fontsize=7, loc="upper right")
    return save(fig, default_out(runs, "trajectory.png", out))


# ----------------------------------------------------------------------------- shapes


def shape_index(run):
    """Columns step, t of shapes/index.csv."""
    d = read_csv(run.file("shapes/index.csv"))
    need(d, ["step", "t"], f"{run.name}/shapes/index.csv")
    return d


def pick_shapes(index, times, n_default=7):
    """(step, t) pairs nearest to the wanted times, or up to n_default evenly spread ones."""
    steps, ts = index["step"].astype(int), index["t"]
    if times:
        picks = [int(np.argmin(np.abs(ts - t))) for t in times]
    else:
        picks = np.unique(np.linspace(0, len(ts) - 1, min(n_default, len(ts))).round().astype(int))
    return [(int(steps[i]), float(ts[i])) for i in picks]


def closed_outline(x, s):
    """Contour points ordered by angle about their centre and closed, for plotting."""
    ang = np.arctan2(s - s.mean(), x - x.mean())
    o = np.argsort(ang)
    return np.append(x[o], x[o][0]), np.append(s[o], s[o][0])


def draw_shape(ax, run, step, radius):
    """Draw the cross-section(s) of one shapes file into ax, in units of R."""
    d = read_csv(run.file(f"shapes/{step:08d}.csv"))
    need(d, ["x", "s"], f"{run.name}/shapes/{step:08d}.csv")
    solid = d.get("solid", np.zeros_like(d["x"]))
    for k in sorted(set(solid)):
        m = solid == k
        x, s = closed_outline(d["x"][m] / radius, d["s"][m] / radius)
        ax.fill(x, s, alpha=0.3)
        ax.plot(x, s, "k-", lw=1)
    ax.axhline(0, color="gray", ls="--", lw=0.6)
    for w in (-1, 1):
        ax.axhline(w, color="k", lw=1.5)


def plot_shapes(path, times=None, out=None):
    """Particle cross-sections at chosen times plus r/R(t) with the instants marked (paper figs 9, 10)."""
    run = load_runs([path])[0]
    radius = pipe_radius(run.config)
    picks = pick_shapes(shape_index(run), times)
    n = len(picks)
    fig = plt.figure(figsize=(max(6.4, 1.3 * n), 5.0), layout="constrained")
    gs = fig.add_gridspec(2, n, height_ratios=[1.4, 1.0])
    tscale = run.time_scale()
    for i, (step, t) in enumerate(picks):
        ax = fig.add_subplot(gs[0, i])
        draw_shape(ax, run, step, radius)
        ax.set_xlim(-0.6, 0.6)
        ax.set_ylim(-1.02, 1.02)
        ax.set_aspect("equal")
        ax.set_title(f"{t * tscale:.3g}", fontsize=9)
        ax.set_xlabel(r"$x/R$", fontsize=8)
        if i:
            ax.set_yticklabels([])
        else:
            ax.set_ylabel(r"$s/R$")
        ax.tick_params(labelsize=7)
    ax = fig.add_subplot(gs[1, :])
    plot_instants(ax, run, [t for _, t in picks])
    fig.suptitle(run_label(run, ["Re", "We"]) + r"   (panel titles: $t\,U_b/D$)", fontsize=10)
    return save(fig, Path(out) if out else run.path / "shapes.png")


def plot_instants(ax, run, times):
    """r/R(t) of solid 0 with black circles at the given (solver) times."""
    d = run.particle(run.solids()[0])
    t, r = d["t"] * run.time_scale(), d["r_over_R"]
    ax.plot(t, r, "b-")
    ts = np.asarray(times) * run.time_scale()
    ax.plot(ts, np.interp(ts, t, r), "o", mfc="none", mec="k", ms=8)
    ax.set_xlabel(T_LABEL)
    ax.set_ylabel(R_LABEL)
    ax.grid(alpha=0.3)


# ----------------------------------------------------------------------------- forces


def plot_forces(paths, out=None, label_by=None):
    """F_r of every run in one panel, then F_r and its four components per run (paper figs 11, 13)."""
    runs = load_runs(paths)
    keys = label_keys(runs, label_by)
    fig, axes = plt.subplots(len(runs) + 1, 1, figsize=(6.4, 2.4 * (len(runs) + 1)), sharex=True, squeeze=False)
    axes = axes[:, 0]
    for run, ax in zip(runs, axes[1:]):
        d = run.particle(run.solids()[0])
        need(d, [c for c, _ in FORCE_COLUMNS], f"{run.name}/particle.csv")
        t = d["t"] * run.time_scale()
        axes[0].plot(t, d["F_r"], label=run_label(run, keys))
        for col, lab in FORCE_COLUMNS:
            ax.plot(t, d[col], lw=2 if col == "F_r" else 1, ls="-" if col == "F_r" else "--", label=lab)
        ax.set_title(run_label(run, keys), fontsize=9)
        ax.set_ylabel(r"$F_r^i$")
        ax.legend(fontsize=7, ncol=5)
    axes[0].set_ylabel(r"$F_r$")
    axes[0].legend(fontsize=7)
    for ax in axes:
        ax.axhline(0, color="gray", lw=0.6)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(T_LABEL)
    fig.tight_layout()
    return save(fig, default_out(runs, "forces.png", out))


# ----------------------------------------------------------------------------- flow


def plot_flow(path, out=None):
    """bulk velocity, dp/dx, max divergence and kinetic energy against time (sanity plot)."""
    run = load_runs([path])[0]
    d = run.flow()
    cols = [("bulk_u", r"$U_b$"), ("dpdx", r"$dp/dx$"), ("max_div", r"max $|\nabla\cdot u|$"),
            ("kinetic_energy", r"$E_k$")]
    need(d, ["t"] + [c for c, _ in cols], f"{run.name}/flow.csv")
    t = d["t"] * run.time_scale()
    fig, axes = plt.subplots(2, 2, figsize=(9.0, 5.6), sharex=True)
    for ax, (c, lab) in zip(axes.flat, cols):
        y = d[c]
        if c == "max_div" and np.all(y[np.isfinite(y)] > 0):
            ax.semilogy(t, y)
        else:
            ax.plot(t, y)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel(T_LABEL)
    fig.suptitle(run.name, fontsize=10)
    fig.tight_layout()
    return save(fig, Path(out) if out else run.path / "flow.png")


# ----------------------------------------------------------------------------- all


def try_plot(what, func, *args, **kwargs):
    """Call a plot function; on a PlotError print a one-line note and return None."""
    try:
        return func(*args, **kwargs)
    except PlotError as e:
        print(f"note: {what} skipped: {e}", file=sys.stderr)
        return None


def with_file(runs, rel):
    """Runs that have a given file."""
    return [r for r in runs if r.has(rel)]


def plot_all(paths, out="figures", label_by=None):
    """Every plot that applies to the given runs, into folder out; returns the files written."""
    runs = load_runs(paths)
    out = Path(out)
    written = []
    for r in runs:
        if not r.has("particle.csv"):
            print(f"note: {r.name}: no particle.csv, only the flow plot", file=sys.stderr)
        written.append(try_plot(f"flow {r.name}", plot_flow, r, out / f"flow_{r.name}.png"))
    prt = with_file(runs, "particle.csv")
    if prt:
        written.append(try_plot("radial", plot_radial, prt, out / "radial.png", label_by))
        written.append(try_plot("trajectory", plot_trajectory, prt, out / "trajectory.png", label_by))
        written.append(try_plot("forces", plot_forces, prt, out / "forces.png", label_by))
    for r in with_file(prt, "shapes/index.csv"):
        written.append(try_plot(f"shapes {r.name}", plot_shapes, r, None, out / f"shapes_{r.name}.png"))
    summ = with_file(runs, "summary.json")
    if summ:
        written.append(try_plot("tcen", plot_tcen, summ, out / "tcen.png"))
        written.append(try_plot("trev-tosc", plot_trev_tosc, summ, out / "trev_tosc.png"))
    return [w for w in written if w is not None]


# ----------------------------------------------------------------------------- command line


def build_parser():
    """The argparse parser with one subparser per plot."""
    p = argparse.ArgumentParser(prog="eulerfsi_plot.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND")

    def add(name, help_text, multi=True, label=False, out_help="output PNG", labels=False):
        s = sub.add_parser(name, help=help_text, description=help_text)
        s.add_argument("runs", nargs="+" if multi else 1, metavar="RUN", help="run directory")
        s.add_argument("--out", help=out_help)
        if label:
            s.add_argument("--label-by", choices=["We", "Re", "mu"],
                           help="legend shows only this parameter (default: those that differ between runs)")
        if labels:
            s.add_argument("--labels", nargs="+", metavar="TEXT",
                           help="legend labels, one per run in the order given (e.g. to tell code versions apart)")
        return s

    add("radial", "r/R against t U_b/D (figs 2, 3, 7a, 12, appendix)", label=True, labels=True).set_defaults(
        func=lambda a: plot_radial(a.runs, a.out, a.label_by, a.labels))
    add("tcen", "t_cen against Re and We from summary.json (fig 4)").set_defaults(
        func=lambda a: plot_tcen(a.runs, a.out))
    add("trev-tosc", "t_rev and T_osc against We, lines per Re (figs 5, 11)").set_defaults(
        func=lambda a: plot_trev_tosc(a.runs, a.out))
    add("trajectory", "y-z trajectories in the pipe cross-section (figs 7c, 8)", label=True).set_defaults(
        func=lambda a: plot_trajectory(a.runs, a.out, a.label_by))
    s = add("shapes", "particle cross-sections at chosen times plus r/R(t) (figs 9, 10)", multi=False)
    s.add_argument("--times", nargs="+", type=float, metavar="T",
                   help="solver times to show (nearest saved shape; default: up to 7 spread over the run)")
    s.set_defaults(func=lambda a: plot_shapes(a.runs[0], a.times, a.out))
    add("forces", "F_r and its pressure, inertia, viscous, elastic parts against t (figs 11, 13)",
        label=True).set_defaults(func=lambda a: plot_forces(a.runs, a.out, a.label_by))
    s = add("models", "r/R and D against t, labelled by solid model and cells per diameter", labels=True)
    s.add_argument("--shape-times", nargs="+", type=float, metavar="T",
                   help="also every run's cross-section at these times t U_b/D, overlaid")
    s.set_defaults(func=lambda a: plot_models(a.runs, a.out, a.labels, a.shape_times))
    add("flow", "bulk_u, dp/dx, max_div, kinetic energy against t", multi=False).set_defaults(
        func=lambda a: plot_flow(a.runs[0], a.out))
    add("all", "every plot that applies to the runs", label=True,
        out_help="output folder (default: figures)").set_defaults(
        func=lambda a: plot_all(a.runs, a.out or "figures", a.label_by))
    return p


def main(argv=None):
    """Run the command line; exit code 2 on input errors."""
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except PlotError as e:
        print(f"eulerfsi_plot.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())

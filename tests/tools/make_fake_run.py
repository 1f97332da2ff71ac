#!/usr/bin/python3
"""Write small synthetic eulerfsi run directories for testing the plot and sweep tools.

The data imitate a soft sphere released at r/R = 0.2828 in pipe flow: it first drifts
outwards, then migrates to the axis with damped oscillations whose period grows with We.

  make_fake_run.py set DIR            three pipe cases (Re, We) + a flow-only run in DIR
  make_fake_run.py case CASE.toml OUT one run directory from a case file (used as a fake solver)
"""
import argparse
import json
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

CASES = {  # name: (Re, We, viscosity_ratio)
    "re200_we0.5": (200.0, 0.5, 1.0),
    "re400_we0.5": (400.0, 0.5, 1.0),
    "re400_we4": (400.0, 4.0, 1.0),
}
R0 = 0.2828
THRESHOLD = 0.01


def case_toml(name, re, we, mu, t_end=40.0):
    """Return the text of a resolved pipe case like the solver writes."""
    y0 = R0 * 0.5
    return f"""# Resolved case from fake/{name}.toml: every key, defaults filled in.

[domain]
length = [3, 1, 1]
cells = [96, 32, 32]
geometry = "pipe"

[flow]
Re = {re}
bulk_velocity = 1
wall_velocity = [0, 0]
wall_frequency = 0
initial = "laminar"
penalization_eta = 0.001

[time]
cfl = 0.2
dt = 0
t_end = {t_end}
max_steps = 100000

[output]
dir = "runs/{name}"
every = 10
fields_every = 0
profiles_every = 500
checkpoint_every = 0
shape_times = [0, 5, 10, 20, 30]

[[solid]]
shape = "sphere"
diameter = 0.2
center = [0.75, {y0}, 0]
We = {we}
viscosity_ratio = {mu}
initial_velocity = "fluid"
"""


def radial_history(t, re, we, mu):
    """Synthetic r/R(t): outward drift, then damped oscillating decay to the axis."""
    period = 2.0 + 4.0 * math.sqrt(we) * (re / 400.0) ** 0.1
    tau = 6.0 * (mu ** 0.3) / math.sqrt(we) * (re / 200.0) ** 0.2
    bump = 1.0 + 0.8 * (1.0 - np.exp(-t / 2.0))
    decay = np.exp(-np.maximum(t - 3.0, 0.0) / tau)
    wiggle = 1.0 + 0.25 * np.sin(2 * np.pi * t / period) * (1.0 - np.exp(-t / 3.0))
    return R0 * bump * decay * wiggle, period


def first_below(t, r, thr):
    """First time r stays below thr until the end, or None."""
    above = np.nonzero(r >= thr)[0]
    if len(above) == 0:
        return float(t[0])
    i = above[-1] + 1
    return float(t[i]) if i < len(t) else None


def first_sign_change(t, f):
    """First time f changes sign from positive to negative, or None."""
    idx = np.nonzero((f[:-1] > 0) & (f[1:] <= 0))[0]
    return float(t[idx[0] + 1]) if len(idx) else None


def mean_period(t, r):
    """Mean distance between maxima of r over the first half of the record, or None."""
    half = len(t) // 2
    rr = r[:half]
    peaks = np.nonzero((rr[1:-1] > rr[:-2]) & (rr[1:-1] >= rr[2:]))[0] + 1
    return float(np.mean(np.diff(t[peaks]))) if len(peaks) >= 2 else None


def write_csv(path, header, rows):
    """Write rows of numbers under a header line."""
    with open(path, "w") as f:
        f.write(",".join(header) + "\n")
        for row in rows:
            f.write(",".join(f"{v:.8g}" if isinstance(v, float) else str(v) for v in row) + "\n")


def write_flow(run, t, dt, re):
    """flow.csv: a steady laminar pipe flow with tiny noise."""
    rng = np.random.default_rng(1)
    rows = []
    for i, ti in enumerate(t):
        rows.append((i * 10, float(ti), dt, 0.2, 1.0 + 1e-4 * rng.standard_normal(), -32.0 / re,
                     1e-12 * (1 + rng.random()), 0.2618 * (1 + 1e-3 * math.sin(ti))))
    write_csv(run / "flow.csv", ["step", "t", "dt", "cfl", "bulk_u", "dpdx", "max_div", "kinetic_energy"], rows)


def particle_series(t, re, we, mu):
    """Arrays for particle.csv and the summary of one solid."""
    r, period = radial_history(t, re, we, mu)
    theta = 0.6 * (1.0 - np.exp(-t / 8.0)) / (1.0 + we)
    y, z = 0.5 * r * np.cos(theta), 0.5 * r * np.sin(theta)
    drdt = np.gradient(r, t)
    t_rev = 3.0 + 6.0 / math.sqrt(we)
    f_r = 0.04 * np.exp(-t / (2.0 * t_rev)) * np.cos(0.5 * np.pi * t / t_rev) + 0.002 * np.gradient(drdt, t)
    f_p = -0.5 - 0.3 * np.tanh(t / 5.0) + 0.0 * r
    f_i = 0.4 * (1.0 - np.exp(-t / 6.0))
    f_v = 1e-3 * np.sin(t)
    f_e = f_r - f_p - f_i - f_v
    taylor = 0.06 * math.sqrt(we) * (1.0 - np.exp(-t / 2.0))
    return dict(r=r, y=y, z=z, drdt=drdt, f_r=f_r, f_p=f_p, f_i=f_i, f_v=f_v, f_e=f_e,
                taylor=taylor, period=period)


def write_particle(run, t, s, step0=10):
    """particle.csv for one solid."""
    vol = math.pi * 0.2 ** 3 / 6.0
    rows = []
    for i, ti in enumerate(t):
        xc = (0.75 + 1.1 * ti) % 3.0
        rows.append((i * step0, float(ti), 0, xc, s["y"][i], s["z"][i], s["r"][i], 1.1,
                     0.5 * s["drdt"][i], 0.0, vol * (1 + 1e-4 * math.sin(ti)), s["taylor"][i], 0.1,
                     s["f_r"][i], s["f_p"][i], s["f_i"][i], s["f_v"][i], s["f_e"][i]))
    header = ["step", "t", "solid", "xc", "yc", "zc", "r_over_R", "up", "vp", "wp", "volume", "taylor_D",
              "angle", "F_r", "F_r_pressure", "F_r_inertia", "F_r_viscous", "F_r_elastic"]
    write_csv(run / "particle.csv", header, rows)


def write_shapes(run, t, s, times):
    """shapes/*.csv: ellipses stretched by the Taylor deformation, tilted a little off the axis."""
    (run / "shapes").mkdir(exist_ok=True)
    index = []
    for tt in times:
        i = int(np.argmin(abs(t - tt)))
        step = i * 10
        a, b = 0.1 * (1 + s["taylor"][i]), 0.1 * (1 - s["taylor"][i])
        tilt = 0.5 * s["r"][i]
        phi = np.linspace(0.7, 0.7 + 2 * np.pi, 60, endpoint=False)
        xs, ss = a * np.cos(phi), b * np.sin(phi)
        x = xs * math.cos(tilt) - ss * math.sin(tilt)
        sr = 0.5 * s["r"][i] + xs * math.sin(tilt) + ss * math.cos(tilt)
        write_csv(run / "shapes" / f"{step:08d}.csv", ["solid", "x", "s"],
                  [(0, float(xi), float(si)) for xi, si in zip(x, sr)])
        index.append((step, float(t[i])))
    write_csv(run / "shapes" / "index.csv", ["step", "t"], index)


def write_profiles(run, t):
    """profiles/*.csv: the Poiseuille profile u(r)."""
    (run / "profiles").mkdir(exist_ok=True)
    r = np.linspace(0, 0.5, 17)
    for i in (0, len(t) - 1):
        write_csv(run / "profiles" / f"{i * 10:08d}.csv", ["r", "u"],
                  [(float(ri), float(2 * (1 - (ri / 0.5) ** 2))) for ri in r])


def write_run(run, name, re, we, mu, t_end=40.0):
    """Write one complete synthetic run directory."""
    run.mkdir(parents=True, exist_ok=True)
    (run / "config.resolved.toml").write_text(case_toml(name, re, we, mu, t_end))
    dt = 0.005
    t = np.arange(0.0, t_end + 1e-9, 10 * dt)
    write_flow(run, t, dt, re)
    s = particle_series(t, re, we, mu)
    write_particle(run, t, s)
    write_shapes(run, t, s, [0, 5, 10, 20, min(30.0, t_end)])
    write_profiles(run, t)
    summary = {"t_rev": first_sign_change(t, s["f_r"]), "t_cen": first_below(t, s["r"], THRESHOLD),
               "t_cen_threshold": THRESHOLD, "T_osc": mean_period(t, s["r"]),
               "final_r_over_R": float(s["r"][-1]), "steps": int(len(t) * 10), "fake": True}
    (run / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")


def write_flow_only(run):
    """A run with a config and flow.csv only (no solid)."""
    run.mkdir(parents=True, exist_ok=True)
    text = case_toml("flow_only", 100.0, 1.0, 1.0, 5.0).split("[[solid]]")[0]
    (run / "config.resolved.toml").write_text(text)
    write_flow(run, np.arange(0.0, 5.0, 0.05), 0.005, 100.0)


def cmd_set(args):
    """Write the standard fake cases into a folder."""
    root = Path(args.dir)
    for name, (re, we, mu) in CASES.items():
        write_run(root / name, name, re, we, mu)
        print(root / name)
    write_flow_only(root / "flow_only")
    print(root / "flow_only")


def cmd_case(args):
    """Act as a fake solver: write a run directory for a case file."""
    with open(args.case, "rb") as f:
        cfg = tomllib.load(f)
    solid = cfg["solid"][0]
    name = Path(args.case).stem
    write_run(Path(args.out), name, float(cfg["flow"]["Re"]), float(solid["We"]),
              float(solid.get("viscosity_ratio", 1.0)), float(cfg.get("time", {}).get("t_end", 40.0)))


def main(argv=None):
    """Parse the command line and dispatch."""
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("set", help="write the fake case set into DIR")
    s.add_argument("dir")
    s.set_defaults(func=cmd_set)
    c = sub.add_parser("case", help="write one run directory OUT from CASE.toml")
    c.add_argument("case")
    c.add_argument("out")
    c.set_defaults(func=cmd_case)
    args = p.parse_args(argv)
    args.func(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())

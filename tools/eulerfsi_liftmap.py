#!/usr/bin/python3
"""Lift-force maps: a held sphere at a list of positions, its cross-stream force against position.

  eulerfsi_liftmap.py run CASE --radii 0.1,0.2,... [--model rigid] [--binary build/eulerfsi] [--jobs 2] [--np 1]
                          [--out-root runs/liftmap] [--set k=v ...] [--average-from 0.5]
  eulerfsi_liftmap.py run CASE --points y1:z1,y2:z2,... [...]        (a duct: positions in y, z)
  eulerfsi_liftmap.py table OUT_ROOT [--average-from 0.5]
  eulerfsi_liftmap.py compare OUT_ROOT:LABEL [OUT_ROOT:LABEL ...] --out FIGURE.png [--lift-coefficient]

CASE holds one [[solid]] (solid[0]); each position runs as
  [mpirun -np NP] BINARY run CASE --out OUT_ROOT/<position> --set solid[0].model=MODEL
      --set solid[0].constraint="radial" --set solid[0].center=[x, y, z] [--set k=v ...]
with x from the case and (y, z) = (r R, 0) for --radii (R = Ly/2, r in units of R) or the given
point. Each run gets OMP_NUM_THREADS = cores / (jobs x np) unless the environment sets it.
MODEL is "rigid" (the default), "reference-map" or "paper": a soft sphere is held by a
uniform body force over it (src/solid/radial_hold.hpp) and deforms freely. Positions run side by side, --jobs at a time. A position whose run dir holds a checkpoint
continues from it (--restart), so a map is extended by raising time.t_end and running it again.

The table (OUT_ROOT/liftmap.csv, liftmap.png) takes, per position, the mean over the last part of
the run (t >= average_from * t_last) of the force the fluid exerts on the body, F = -hold_F (the
holding force's opposite), its radial part F_r = F . e_r, the spread of F_r over that window
(half the difference of the means of its two halves: a drift bound), the slip u_p - u_f (u_f the
laminar profile there) and the spin about e_x x e_r. Along every ray from the axis that holds two
or more positions (--radii; --points along a duct's wall bisector, its diagonal, ...) it finds the
zeros of F_r by linear interpolation and their stability along the ray from the slope (dF_r/dr < 0:
stable), written to liftmap_zeros.csv (r/R, stable, the ray's angle from +y in degrees, y, z);
stability across a ray is read from a position beside it (the duct's plot draws F_y, F_z arrows).
`compare` draws the F_r of several finished maps (their liftmap.csv, liftmap_zeros.csv) on one
figure, each with its label (e.g. "Re = 100, 8 cells per d"), the zeros marked (filled: stable);
--lift-coefficient divides each map's F_r by (d/D)^4, so that spheres of different size compare.
Exit code: 0 done, 1 a run failed, 2 a usage error.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path


class LiftMapError(Exception):
    """A usage problem reported in one line with exit code 2."""


def read_case(path):
    try:
        with open(path, "rb") as f:
            case = tomllib.load(f)
    except FileNotFoundError:
        raise LiftMapError(f"case '{path}' not found")
    except tomllib.TOMLDecodeError as e:
        raise LiftMapError(f"case '{path}': {e}")
    solids = case.get("solid", [])
    if len(solids) != 1:
        raise LiftMapError(f"case '{path}' must hold exactly one [[solid]] (it holds {len(solids)})")
    return case


def positions(case, radii, points):
    """(name, y, z) per position: radii in units of R = Ly/2 along +y, or (y, z) points."""
    if bool(radii) == bool(points):
        raise LiftMapError("give either --radii (a pipe) or --points (a duct), not both or neither")
    ly = case.get("domain", {}).get("length", [3.0, 1.0, 1.0])[1]
    out = []
    if radii:
        for r in radii.split(","):
            r = float(r)
            out.append((f"r{r:.4f}", r * ly / 2, 0.0))
    else:
        for p in points.split(","):
            try:
                y, z = (float(v) for v in p.split(":"))
            except ValueError:
                raise LiftMapError(f"--points: '{p}' is not y:z")
            out.append((f"y{y:+.4f}_z{z:+.4f}", y, z))
    return out


def run_command(binary, case_path, case, out_dir, y, z, np_, mpirun, sets, model="rigid"):
    x = case["solid"][0].get("center", [0.0, 0.0, 0.0])[0]
    cmd = [mpirun, "-np", str(np_)] if np_ > 1 else []
    cmd += [str(binary), "run", str(case_path), "--out", str(out_dir), "--quiet",
            "--set", f'solid[0].model="{model}"', "--set", 'solid[0].constraint="radial"',
            "--set", f"solid[0].center=[{x!r}, {y!r}, {z!r}]"]
    for s in sets:
        cmd += ["--set", s]
    if (out_dir / "checkpoint.h5").exists():
        cmd.append("--restart")
    return cmd


def run_one(cmd, log, threads):
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", str(threads))  # the caller's setting wins
    with open(log, "w") as f:
        f.write(" ".join(cmd) + "\n")
        f.flush()
        return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=env).returncode


def read_positions(root):
    """(name, y, z) of every position run in a map's folder."""
    with open(root / "liftmap_positions.csv") as f:
        return [(row["position"], float(row["y"]), float(row["z"])) for row in csv.DictReader(f)]


def record_positions(root, entries):
    """Adds (name, y, z) entries to a map's liftmap_positions.csv: positions added to a folder join
    those already there (the table verb reads them all)."""
    known = read_positions(root) if (root / "liftmap_positions.csv").exists() else []
    names = {e[0] for e in known}
    with open(root / "liftmap_positions.csv", "w") as f:
        f.write("position,y,z\n")
        for name, y, z in known + [e for e in entries if e[0] not in names]:
            f.write(f"{name},{y!r},{z!r}\n")


def finished_positions(root, failed=()):
    """The folder's positions whose run has written a particle.csv, less those that failed."""
    return [e for e in read_positions(root) if e[0] not in failed and (root / e[0] / "particle.csv").exists()]


def read_rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def laminar_u(case, y, z):
    """The laminar profile at (y, z): the pipe's 2 U_b (1 - r^2 / R^2) (R = 1/2); the rectangular
    duct's series (half-widths a, b; e.g. White, Viscous Fluid Flow, sec. 3-3), 40 odd terms:
      u ~ sum (-1)^((n-1)/2) [1 - cosh(n pi z / 2a) / cosh(n pi b / 2a)] cos(n pi y / 2a) / n^3,
      its mean ~ (a^2 / 3) [1 - 192 a / (pi^5 b) sum tanh(n pi b / 2a) / n^5] / (16 a^2 / pi^3);
    other geometries: not known here (nan)."""
    geo = case.get("domain", {}).get("geometry", "pipe")
    ub = case.get("flow", {}).get("bulk_velocity", 1.0)
    if geo == "pipe":
        return 2.0 * ub * (1.0 - 4.0 * (y * y + z * z))
    if geo != "duct":
        return float("nan")
    length = case.get("domain", {}).get("length", [3.0, 1.0, 1.0])
    a, b = length[1] / 2, length[2] / 2
    odd = range(1, 80, 2)
    shape = sum((-1) ** ((n - 1) // 2) * (1 - math.cosh(n * math.pi * z / (2 * a)) / math.cosh(n * math.pi * b / (2 * a)))
                * math.cos(n * math.pi * y / (2 * a)) / n ** 3 for n in odd) * 16 * a * a / math.pi ** 3
    mean = a * a / 3 * (1 - 192 * a / (math.pi ** 5 * b) * sum(math.tanh(n * math.pi * b / (2 * a)) / n ** 5 for n in odd))
    return ub * shape / mean


def summarise(case, run_dir, y, z, average_from):
    rows = [r for r in read_rows(run_dir / "particle.csv") if r["solid"] == 0]
    if not rows:
        raise LiftMapError(f"{run_dir}/particle.csv has no rows")
    t_last = rows[-1]["t"]
    window = [r for r in rows if r["t"] >= average_from * t_last]
    rr = math.hypot(y, z)
    er = (y / rr, z / rr) if rr > 0 else (1.0, 0.0)

    def mean(rs, f):
        return sum(f(r) for r in rs) / len(rs)

    def f_r(r):
        return -(r["hold_Fy"] * er[0] + r["hold_Fz"] * er[1])

    half = len(window) // 2
    spread = abs(mean(window[:half], f_r) - mean(window[half:], f_r)) / 2 if half > 0 else float("nan")
    # e_x x e_r = (0, -e_r,z, e_r,y)
    spin = mean(window, lambda r: -r["spin_y"] * er[1] + r["spin_z"] * er[0])
    return {
        "position": run_dir.name, "y": y, "z": z, "r_over_R": rr / (case.get("domain", {}).get("length", [3, 1, 1])[1] / 2),
        "F_r": mean(window, f_r), "F_r_spread": spread,
        "F_y": mean(window, lambda r: -r["hold_Fy"]), "F_z": mean(window, lambda r: -r["hold_Fz"]),
        "slip": mean(window, lambda r: r["up"]) - laminar_u(case, y, z), "spin": spin,
        "t_from": window[0]["t"], "t_to": t_last, "samples": len(window),
    }


def zeros(table):
    """Sign changes of F_r between consecutive radii of one ray: (r, stable) by linear interpolation."""
    out = []
    for a, b in zip(table, table[1:]):
        fa, fb = a["F_r"], b["F_r"]
        if fa == 0.0 or fa * fb < 0.0:
            r = a["r_over_R"] if fa == 0.0 else a["r_over_R"] + (b["r_over_R"] - a["r_over_R"]) * fa / (fa - fb)
            out.append((r, fb < fa))  # F_r falling through zero: pushed back from both sides
    return out


def ray_angle(e):
    """The direction of a position from the axis, in degrees from +y (0: a duct's wall bisector, 45: its diagonal)."""
    return round(math.degrees(math.atan2(e["z"], e["y"])), 6)


def zeros_by_ray(table):
    """The zeros of F_r along every ray from the axis that holds two or more positions (a pipe's
    radii; a duct's wall bisector and diagonal): (angle, r/R, y, z, stable along the ray)."""
    rays = {}
    for e in table:
        if math.hypot(e["y"], e["z"]) > 0:
            rays.setdefault(ray_angle(e), []).append(e)
    out = []
    for angle, ray in sorted(rays.items()):
        ray.sort(key=lambda e: e["r_over_R"])
        scale = math.hypot(ray[0]["y"], ray[0]["z"]) / ray[0]["r_over_R"]  # R
        for r, stable in zeros(ray):
            a = math.radians(angle)
            out.append((angle, r, r * scale * math.cos(a), r * scale * math.sin(a), stable))
    return out


def write_table(case, root, entries, average_from):
    table = [summarise(case, root / name, y, z, average_from) for name, y, z in entries]
    table.sort(key=lambda e: (ray_angle(e), e["r_over_R"]))
    cols = list(table[0].keys())
    with open(root / "liftmap.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(table)
    found = zeros_by_ray(table)
    with open(root / "liftmap_zeros.csv", "w") as f:
        f.write("r_over_R,stable,ray_deg,y,z\n")
        for angle, r, y, z, stable in found:
            f.write(f"{r:.6g},{int(stable)},{angle:g},{y:.6g},{z:.6g}\n")
    for angle, r, y, z, stable in found:
        print(f"equilibrium r/R = {r:.4f} at ({y:.4f}, {z:.4f}), ray {angle:g} deg "
              f"({'stable' if stable else 'unstable'} along it)")
    # one ray (a pipe's radii): F_r against r/R; otherwise the arrows (F_y, F_z) over the cross-section
    one_ray = len({ray_angle(e) for e in table if math.hypot(e["y"], e["z"]) > 0}) <= 1
    plot(table, found, root / "liftmap.png", one_ray)
    return table, found


def plot(table, found, path, radial):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    if radial:
        r = [e["r_over_R"] for e in table]
        ax.errorbar(r, [e["F_r"] for e in table], yerr=[e["F_r_spread"] for e in table], marker="o", capsize=3)
        ax.axhline(0.0, color="0.6", lw=0.8)
        for _, r0, _, _, stable in found:
            ax.plot([r0], [0.0], marker="o", ms=9, mfc="k" if stable else "w", mec="k", ls="none")
        ax.set_xlabel("r / R")
        ax.set_ylabel("F_r (fluid on the held sphere)")
    else:
        # directions as arrows of one length, the magnitude as their colour (it spans decades)
        mag = [max(math.hypot(e["F_y"], e["F_z"]), 1e-300) for e in table]
        q = ax.quiver([e["y"] for e in table], [e["z"] for e in table], [e["F_y"] / m for e, m in zip(table, mag)],
                      [e["F_z"] / m for e, m in zip(table, mag)], [math.log10(m) for m in mag], cmap="viridis",
                      angles="xy", pivot="middle")
        fig.colorbar(q, ax=ax, label="log10 |F| (fluid on the held sphere)")
        for _, _, y0, z0, stable in found:  # stable along its ray; across it, read the arrows
            ax.plot([y0], [z0], marker="o", ms=8, mfc="k" if stable else "w", mec="k", ls="none")
        ax.set_xlabel("y")
        ax.set_ylabel("z")
        ax.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def diameter_ratio(root):
    """d / D (D = Ly) of a map's sphere, from a position's resolved configuration where there is one
    (it holds the --set values), else from the map's case."""
    resolved = sorted(root.glob("*/config.resolved.toml"))
    case = read_case(resolved[0] if resolved else root / "liftmap_case.toml")
    return case["solid"][0]["diameter"] / case.get("domain", {}).get("length", [3.0, 1.0, 1.0])[1]


def compare(pairs, out, lift_coefficient=False):
    """F_r against r/R of several maps on one figure; with lift_coefficient, F_r / (d/D)^4, the
    lift coefficient of F = C_L rho U_b^2 d^4 / D^2, so that spheres of different size compare."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    for spec in pairs:
        root, _, label = spec.partition(":")
        root = Path(root)
        if not (root / "liftmap.csv").exists():
            raise LiftMapError(f"'{root}' has no liftmap.csv (run the map, or its table verb, first)")
        with open(root / "liftmap.csv") as fh:
            table = [{k: (v if k == "position" else float(v)) for k, v in e.items()} for e in csv.DictReader(fh)]
        zero_rows = list(csv.DictReader(open(root / "liftmap_zeros.csv"))) if (root / "liftmap_zeros.csv").exists() else []
        angles = [ray_angle(e) for e in table]
        # the rays with two or more positions (a lone point beside them is for the arrows' plot)
        rays = sorted({a for a in angles if angles.count(a) > 1}) or sorted(set(angles))
        scale = 1.0
        if lift_coefficient:
            ratio = diameter_ratio(root)
            scale = ratio ** -4
            print(f"{label or root.name}: F_r / (d/D)^4, d/D = {ratio:g}")
        palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        colour = palette[pairs.index(spec) % len(palette)]  # one colour per map, one line style per ray
        for n, angle in enumerate(rays):  # a duct's map: the wall bisector (0 deg), the diagonal (45 deg)
            ray = [e for e in table if ray_angle(e) == angle]
            name = (label or root.name) + (f", {angle:g} deg" if len(rays) > 1 else "")
            ax.errorbar([e["r_over_R"] for e in ray], [scale * e["F_r"] for e in ray],
                        yerr=[scale * e["F_r_spread"] for e in ray],
                        marker="os^v"[n % 4], ms=4, capsize=2, color=colour, ls=["-", "--", ":", "-."][n % 4], label=name)
            for z in zero_rows:
                if len(rays) > 1 and abs(float(z.get("ray_deg", angle)) - angle) > 1e-6:
                    continue
                stable = z["stable"] == "1"
                ax.plot([float(z["r_over_R"])], [0.0], marker="o", ms=8, mec=colour, mfc=colour if stable else "w", ls="none")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("r / R (a duct: distance from its axis / half its width)")
    ax.set_ylabel("C_L = F_r D^2 / (rho U_b^2 d^4)" if lift_coefficient else "F_r / (rho U_b^2 D^2)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="verb", required=True)
    r = sub.add_parser("run", help="run the held sphere at every position, then write the table")
    r.add_argument("case")
    r.add_argument("--radii", help="comma-separated r/R (pipe)")
    r.add_argument("--points", help="comma-separated y:z (duct)")
    r.add_argument("--model", default="rigid", choices=["rigid", "reference-map", "paper"])
    r.add_argument("--binary", default="build/eulerfsi")
    r.add_argument("--jobs", type=int, default=2)
    r.add_argument("--np", type=int, default=1)
    r.add_argument("--mpirun", default="mpirun")
    r.add_argument("--out-root", default="runs/liftmap")
    r.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    r.add_argument("--average-from", type=float, default=0.5)
    c = sub.add_parser("compare", help="several finished maps on one figure")
    c.add_argument("maps", nargs="+", metavar="OUT_ROOT:LABEL")
    c.add_argument("--out", required=True)
    c.add_argument("--lift-coefficient", action="store_true",
                   help="plot F_r / (d/D)^4 (d/D from each map's runs), to compare spheres of different size")
    t = sub.add_parser("table", help="the table and plot of finished (or running) positions")
    t.add_argument("out_root")
    t.add_argument("--average-from", type=float, default=0.5)
    args = p.parse_args(argv)
    if hasattr(args, "average_from") and not 0.0 <= args.average_from < 1.0:
        p.error(f"--average-from {args.average_from}: a fraction of the run's last time, in [0, 1) (0.5: the second half)")
    try:
        if args.verb == "compare":
            compare(args.maps, args.out, args.lift_coefficient)
            return 0
        if args.verb == "run":
            case = read_case(args.case)
            entries = positions(case, args.radii, args.points)
            root = Path(args.out_root)
            root.mkdir(parents=True, exist_ok=True)
            (root / "liftmap_case.toml").write_text(Path(args.case).read_text())
            record_positions(root, entries)
            failed = []
            # the cores shared out: OpenMP threads that outnumber them spin against each other
            threads = max(1, (os.cpu_count() or 1) // (max(1, args.jobs) * max(1, args.np)))
            with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
                futures = {}
                for name, y, z in entries:
                    out = root / name
                    cmd = run_command(args.binary, args.case, case, out, y, z, args.np, args.mpirun, args.set,
                                      args.model)
                    out.mkdir(parents=True, exist_ok=True)
                    futures[pool.submit(run_one, cmd, root / f"{name}.log", threads)] = name
                for fut in concurrent.futures.as_completed(futures):
                    rc = fut.result()
                    print(f"{futures[fut]}: exit {rc}", flush=True)
                    if rc != 0:
                        failed.append(futures[fut])
            done = finished_positions(root, failed)
            if done:
                write_table(case, root, done, args.average_from)
            if failed:
                print(f"failed: {', '.join(sorted(failed))} (logs in {root})", file=sys.stderr)
                return 1
            return 0
        root = Path(args.out_root)
        if not (root / "liftmap_positions.csv").exists():
            raise LiftMapError(f"'{root}' is not a lift map's folder (no liftmap_positions.csv)")
        case = read_case(root / "liftmap_case.toml")
        entries = finished_positions(root)
        if not entries:
            raise LiftMapError(f"no position in '{root}' has a particle.csv yet")
        write_table(case, root, entries, args.average_from)
        return 0
    except LiftMapError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

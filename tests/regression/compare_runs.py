#!/usr/bin/python3
"""Compare two run directories (flow.csv, particle.csv if present, last HDF5 snapshot) within a tolerance."""
import argparse
import csv
import glob
import os
import sys

import h5py
import numpy as np


def read_csv(path):
    """Columns of a CSV as float arrays."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"error: {path} has no rows")
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def compare_series(a, b, name, rtol, atol, skip):
    """Largest relative difference over all columns; fails on row-count or value mismatch."""
    ta, tb = read_csv(os.path.join(a, name)), read_csv(os.path.join(b, name))
    if len(ta["step"]) != len(tb["step"]):
        sys.exit(f"error: {name}: {len(ta['step'])} rows vs {len(tb['step'])}")
    worst = 0.0
    for col in ta:
        if col in skip:
            continue
        diff = np.abs(ta[col] - tb[col])
        # round-off is relative to the size of the terms, not of a result that happens to be ~0:
        # floor the scale at the column's largest magnitude
        colmax = max(np.max(np.abs(ta[col])), np.max(np.abs(tb[col])))
        scale = np.maximum(np.maximum(np.abs(ta[col]), np.abs(tb[col])), colmax)
        bad = diff > atol + rtol * scale
        rel = np.max(diff / np.maximum(scale, 1e-300))
        worst = max(worst, rel)
        if np.any(bad):
            i = int(np.argmax(bad))
            sys.exit(f"error: {name} column {col} row {i}: {ta[col][i]!r} vs {tb[col][i]!r}")
    print(f"{name}: {len(ta['step'])} rows agree, largest relative difference {worst:.3e}")


def compare_fields(a, b, atol):
    """Every dataset of the newest snapshot agrees to atol (relative to the field's max)."""
    fa = sorted(glob.glob(os.path.join(a, "fields", "*.h5")))
    fb = sorted(glob.glob(os.path.join(b, "fields", "*.h5")))
    if not fa:
        return
    if [os.path.basename(p) for p in fa] != [os.path.basename(p) for p in fb]:
        sys.exit("error: the runs wrote different snapshots")
    with h5py.File(fa[-1]) as ha, h5py.File(fb[-1]) as hb:
        for name in ha:
            x, y = ha[name][...], hb[name][...]
            scale = max(np.max(np.abs(x)), 1e-300)
            d = np.max(np.abs(x - y)) / scale
            print(f"{os.path.basename(fa[-1])}:{name}: max difference / max |field| = {d:.3e}")
            if d > atol:
                sys.exit(f"error: field {name} differs by {d:.3e} (allowed {atol:.1e})")


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("run_a")
    p.add_argument("run_b")
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--field-tol", type=float, default=1e-10)
    p.add_argument("--exact", action="store_true", help="require bit-for-bit equality")
    args = p.parse_args()
    rtol = 0.0 if args.exact else args.rtol
    # max |div u| is round-off noise itself: compared in absolute terms only
    compare_series(args.run_a, args.run_b, "flow.csv", rtol, 0.0, skip={"max_div"})
    if os.path.exists(os.path.join(args.run_a, "particle.csv")):
        compare_series(args.run_a, args.run_b, "particle.csv", rtol, 0.0, skip=set())
    compare_fields(args.run_a, args.run_b, 0.0 if args.exact else args.field_tol)


if __name__ == "__main__":
    main()

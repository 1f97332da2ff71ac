#!/usr/bin/python3
"""Cost of one RK3 step against grid size (bench/step_cost.png), from the JSON that
bench/run_benchmarks.sh leaves in bench/data/: ns per cell and step of the single-phase pipe and
of the pipe with one sphere (paper model, reference map), on 1 and 2 threads, with the
memory-bound floor of the single-phase step drawn in.

The floor: the fewest bytes a step must move per cell, divided by the triad bandwidth measured in
the same run. Per substep, each field streamed once (stencil neighbours from cache, no
write-allocate): momentum rhs 6 doubles (read u, v, w; write 3 rhs), RK3 update 12 (per
component read u, rhs, rhs_old; write u), divergence 4, Poisson gather and scatter 4, two
in-place transforms 4, eigenvalue division 2, pressure correction 7, step pressure 3, flow rate
2: 44 doubles = 352 B, 1056 B per step of 3 substeps.

usage: plot_step.py DATA_DIR OUT.png
"""
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR_BYTES_PER_CELL_STEP = 1056.0
KINDS = {"0": ("single phase", "o-"), "1": ("+ sphere, paper model", "s--"), "2": ("+ sphere, reference map", "^-.")}


def medians(path):
    with open(path) as f:
        data = json.load(f)
    return [b for b in data["benchmarks"] if b.get("aggregate_name", "median") == "median"]


def main():
    data_dir, out = sys.argv[1], sys.argv[2]
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    colours = {1: "tab:blue", 2: "tab:red"}
    for threads in (1, 2):
        step = os.path.join(data_dir, f"step_t{threads}.json")
        triad = os.path.join(data_dir, f"triad_t{threads}.json")
        if not os.path.exists(step):
            continue
        series = {}
        for b in medians(step):
            a = dict(re.findall(r"(\w+):(\d+)", b["run_name"]))
            if "particle" not in a:
                continue  # BM_StepBodies: one grid only, in the table
            cells = int(a["nx"]) * int(a["ny"]) * int(a["nz"])
            series.setdefault(a["particle"], []).append((cells, b["ns_per_cell_step"]))
        for kind, pts in sorted(series.items()):
            pts.sort()
            label, style = KINDS[kind]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=colours[threads],
                    label=f"{label}, {threads} thread{'s' if threads > 1 else ''}")
        if os.path.exists(triad):
            gbs = medians(triad)[0]["GB/s"]
            floor = FLOOR_BYTES_PER_CELL_STEP / gbs
            ax.axhline(floor, color=colours[threads], lw=0.8, ls=":")
            ax.text(3e4, floor * 1.04, f"memory floor, {threads} thr. (triad {gbs:.1f} GB/s)", color=colours[threads],
                    fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cells")
    ax.set_ylabel("ns per cell per RK3 step")
    ax.set_title("eulerfsi: cost of one step, pipe flow (bench_step)")
    ax.legend(fontsize=7, ncol=1, loc="upper left")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


if __name__ == "__main__":
    main()

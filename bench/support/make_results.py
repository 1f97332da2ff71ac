#!/usr/bin/env python3
"""Turns the Google Benchmark JSON files of run_benchmarks.sh into the tables of RESULTS.md.

Only the part between the results markers is rewritten; the text around it (the
interpretation) is kept, so a re-run refreshes the numbers and nothing else."""
import argparse
import datetime
import glob
import json
import os
import re

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"

# how often each kernel runs in one RK3 step (3 substeps); fill_velocity: after the projection
# (with its flow-rate shift) in every substep (after the predictor only the divergence's stencil is filled)
CALLS_PER_STEP = {
    "MomentumRhs": 3, "MomentumPredict": 3, "Divergence": 3, "SubtractGradient": 3,
    "SubtractGradientStepPressure": 3, "FillGhosts": 3,
    "FillVelocity": 3, "ScalarAdvectionRhs": 3, "TensorTransportRhs": 3, "AddElasticForce": 3,
    "PoissonSolve": 3, "PenalizeWallLayer": 3,
}
NAMES = {
    "MomentumRhs": "momentum_rhs (3 comp.)", "MomentumPredict": "momentum_predict (rhs + RK3 update)",
    "Divergence": "divergence + flow-rate sum",
    "SubtractGradientStepPressure": "subtract_gradient + step pressure + flow-rate shift",
    "SubtractGradient": "subtract_gradient", "FillGhosts": "fill_ghosts y,z (u,v,w)",
    "FillVelocity": "fill_velocity (x halo + y,z ghosts)", "ScalarAdvectionRhs": "scalar_advection_rhs (psi; per cell of the body's box)",
    "TensorTransportRhs": "tensor_transport_rhs (B; per cell of the body's box)",
    "AddElasticForce": "add_elastic_force (per cell of the body's box)",
    "PoissonSolve": "Poisson solve (FFTW, estimate)", "PenalizeWallLayer": "penalize_wall_layer (u,v,w; pipe wall)",
}


def parse_args():
    p = argparse.ArgumentParser()
    p.add_argument("json_dir")
    p.add_argument("results_md")
    p.add_argument("--model", default="?")
    p.add_argument("--cores", default="?")
    p.add_argument("--commit", default="?")
    p.add_argument("--load", default="?")
    p.add_argument("--reps", default="?")
    p.add_argument("--toolchain", default="?")
    return p.parse_args()


def medians(path):
    with open(path) as f:
        data = json.load(f)
    rows = [b for b in data["benchmarks"] if b.get("aggregate_name", "median") == "median"]
    return data.get("context", {}), rows


def grid_of(run_name):
    a = dict(re.findall(r"(\w+):(\d+)", run_name))
    return f"{a['nx']}x{a['ny']}x{a['nz']}", a


def fmt(x, digits=3):
    if x is None:
        return "-"
    return f"{x:.{digits}g}" if abs(x) < 1000 else f"{x:.0f}"


def main():
    args = parse_args()
    triad, rows, context, paired = {}, [], {}, {}
    for path in sorted(glob.glob(os.path.join(args.json_dir, "*.json"))):
        kind, threads, ranks = re.match(r"(\w+?)_t(\d+)(?:_r(\d+))?\.json", os.path.basename(path)).groups()
        threads, ranks = int(threads), int(ranks or 1)
        context, runs = medians(path)
        for r in runs:
            name = r["run_name"]
            if kind == "triad":
                triad[threads] = r["GB/s"]
                rows.append((0, "", name, threads, ranks, "triad a = b + s c, 3 x 64 MiB", None, None, None, r["GB/s"]))
                continue
            grid, a = grid_of(name)
            fn = re.match(r"BM_(\w+)", name).group(1)
            if kind == "step" and fn in ("StepPair", "StepPairBodies", "StepPairMeasuredPlans"):
                # one flow step and one step with the bodies in turn: the ratio from the same minutes
                paired[(name, threads, ranks)] = r["x_flow"]
                bodies = f"{a['bodies']} x sphere d = {int(a['d_percent']) / 100:g} D"
                plans = ", FFTW_MEASURE plans" if fn == "StepPairMeasuredPlans" else ""
                label = f"**paired: whole RK3 step {grid} + {bodies} (reference map), the flow alone in turn{plans}**"
                ns = r["particle_ns_per_cell_step"]
                rows.append((1, grid, name, threads, ranks, label, ns, 1, ns, None))
            elif kind == "step":
                sphere = {"0": "", "1": " + sphere (paper model)", "2": " + sphere (reference map)", "3": " + sphere (rigid)"}[a.get("particle", "0")]
                implicit = " (implicit viscosity)" if fn == "StepImplicitViscosity" else ""
                label = f"**whole RK3 step {grid}{sphere}{implicit}**"
                rows.append((1, grid, name, threads, ranks, label, r["ns_per_cell_step"], 1, r["ns_per_cell_step"], None))
            else:
                calls = CALLS_PER_STEP.get(fn, 1)
                ns = r["ns_per_cell"]
                order = 3 if fn == "PoissonSolve" else 2
                rows.append((order, grid, name, threads, ranks, f"{NAMES.get(fn, fn)} {grid}", ns, calls, ns * calls,
                             r.get("GB/s")))
    # the same benchmark on one core, and the single-phase step of the same grid and parallel layout
    one_core = {r[2]: r[8] for r in rows if r[3] == 1 and r[4] == 1}
    flow = {(r[1], r[3], r[4], "Implicit" in r[2]): r[8] for r in rows if r[0] == 1 and "particle:0" in r[2]}
    # steps first, then kernels in the order they were run, Poisson, triad last
    seen = {}
    for i, r in enumerate(rows):
        seen.setdefault(r[2], i)
    rows.sort(key=lambda r: ({1: 0, 2: 1, 3: 2, 0: 3}[r[0]], r[1] != "64x64x64" and r[0] == 2, seen[r[2]], r[4], r[3]))

    lines = [BEGIN, ""]
    lines.append(f"Machine: {args.model}, {args.cores} cores (shared with other users: timings are noisy).  ")
    lines.append(f"Date: {datetime.date.today().isoformat()}, commit {args.commit}, {args.toolchain}, "
                 f"Kokkos OpenMP backend, OMP_PROC_BIND=false; one MPI rank unless the layout says 2 ranks.  ")
    lines.append(f"Every number is the **median of {args.reps} repetitions** "
                 f"(`--benchmark_repetitions={args.reps} --benchmark_report_aggregates_only=true`); "
                 f"load average before -> after the run: {args.load}.")
    lines.append("")
    lines.append("ns/cell is per call and per interior cell (the particle's kernels: per cell of the box around the "
                 "body they run on, as in the solver); ns/cell/step multiplies it by the calls in one RK3 "
                 "step (3 substeps). GB/s is the effective bandwidth from the *minimal* bytes a kernel must move "
                 "(the count is in bench/bench_kernels.cpp above each benchmark); the triad counts 24 B per element "
                 "without write-allocate, the same convention.")
    lines.append("")
    lines.append("x 1 core: the one-core time over this one (the speed-up). x flow: a step with a particle over the "
                 "single-phase step of the same grid and layout (the *paired* rows step both cases in turn, so the "
                 "machine's drift between benchmarks cancels: the ratio to quote). % triad: GB/s over the triad measured in the same "
                 "run with the same threads (2 ranks: the 2-thread triad).")
    lines.append("")
    lines.append("| benchmark | threads x ranks | ns/cell (per call) | calls/step | ns/cell/step | x 1 core | x flow | GB/s "
                 "| % triad |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for order, grid, name, threads, ranks, label, ns, calls, ns_step, gbs in rows:
        base = one_core.get(name)
        speedup = base / ns_step if base and ns_step and (threads, ranks) != (1, 1) else None
        flow_ns = flow.get((grid, threads, ranks, "Implicit" in name)) if order == 1 and "particle:0" not in name else None
        x_flow = paired.get((name, threads, ranks), ns_step / flow_ns if flow_ns else None)
        cores = threads * ranks
        tri = triad.get(cores)
        share = 100.0 * gbs / tri if gbs and tri else None
        share_text = f"{share:.0f}" if share else "-"
        lines.append(f"| {label} | {threads} x {ranks} | {fmt(ns)} | {calls if calls else '-'} | {fmt(ns_step)} | "
                     f"{fmt(speedup)} | {fmt(x_flow)} | {fmt(gbs)} | {share_text} |")
    lines += ["", END]
    block = "\n".join(lines)

    text = ""
    if os.path.exists(args.results_md):
        with open(args.results_md) as f:
            text = f.read()
    if BEGIN in text and END in text:
        text = text[: text.index(BEGIN)] + block + text[text.index(END) + len(END):]
    else:
        text = ("# Benchmark results\n\nProduced by `bench/run_benchmarks.sh` (numbers between the markers are "
                "rewritten on every run; the notes below are not).\n\n" + block + "\n\n## Notes\n\n"
                "(to be written)\n")
    with open(args.results_md, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Writes cases/paper/ and cases/desk/: every run of Alghalibi, Rosti & Brandt (2019), Table I,
the appendix's two stiffer particles and the start-from-rest variant, at paper and desk resolution."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, "..", "cases")

# (Re, We, r0/R, mu_s/mu_f) of Table I, in the table's order
TABLE_I = [(re, we, 0.2828, 1.0) for re, wes in ((100, (0.125, 0.5, 4.0)), (200, (0.125, 0.5, 4.0)),
                                                 (400, (0.125, 0.25, 0.5, 1.0, 2.0, 4.0))) for we in wes]
TABLE_I += [(400, 1.0, 0.7487, 1.0), (400, 1.0, 0.0544, 1.0), (400, 4.0, 0.2828, 0.3), (400, 4.0, 0.2828, 3.0)]
# The appendix adds "two additional cases with very rigid particles" at Re = 400 without giving
# their We; we take two further halvings of the stiffest Table I value.
APPENDIX = [(400, 0.0625, 0.2828, 1.0), (400, 0.03125, 0.2828, 1.0)]

RESOLUTIONS = {
    # The paper: 720 x 240 x 240 uniform cells, 48 per particle diameter (d = D/5). 720 cells of
    # D/240 make the pipe 3D long, although the text says 6D: set domain.length = [6, 1, 1] and
    # domain.cells = [1440, 240, 240] for the 6D reading (twice the cost).
    # The paper's own method (psi and B advected with WENO5) at the paper's CFL.
    "paper": dict(length=3.0, cells=(720, 240, 240), every=100, fields_every=50000, checkpoint_every=5000, cfl=0.2,
                  model="paper",
                  note="paper resolution: 240 cells across the pipe, 48 per particle diameter"),
    # What the desk campaign runs on a 2-core desk: 8 cells per particle diameter (40 across the
    # pipe) with the reference map. The paper's model smears under rotation at this resolution (a
    # sphere in rigid rotation at 8 cells per diameter reads D = 0.02 after one radian), the
    # reference map does not (D 3.5e-7 after 10 rad) and agrees with itself between 8 and 12 cells
    # per d to ~0.01 R over 20 time units (docs/REFERENCE_MAP.md). CFL 0.4: r/R within 0.0025 and D
    # within 0.0022 of CFL 0.2 at t = 5, below the 8-to-12-cell difference (same page). Lx = 2:
    # within 0.0046 R of Lx = 3 to t = 20 (docs/REPRODUCTION.md).
    "desk": dict(length=2.0, cells=(80, 40, 40), every=20, fields_every=4000, checkpoint_every=1000, cfl=0.4,
                 model="reference-map",
                 note="desk resolution: 40 cells across the pipe, 8 per particle diameter, Lx = 2, the reference map (docs/REPRODUCTION.md);\n"
                      "# r/R good to ~0.05-0.1 R here, ~0.02-0.03 R at 12 per d (--set 'domain.cells=[120,60,60]', released with\n"
                      "# --set 'solid[0].initial_velocity=\"fluid\"': finer, a soft one released at rest can blow up; README, \"Choosing a model\")"),
}


# What a desk run costs: (time reached, wall seconds summed over restarts) on one core of a 2-core
# Intel Xeon VM with AVX-512, each run sharing the machine with a second run or the test suite (so
# the figures are upper bounds); wall seconds from each run's config.resolved.toml to its
# summary.json.
_CPU = "one core of a 2-core Intel Xeon VM (AVX-512), shared with a second job: an upper bound"
DESK_MEASURED = {  # case: (t reached, wall seconds)
    "re200_we4_r0.2828_visc1": (60.0, 411),
    "re200_we0.5_r0.2828_visc1": (60.0, 1022),
    "re200_we0.125_r0.2828_visc1": (60.0, 736),
    "re100_we4_r0.2828_visc1": (60.0, 522),
    "re100_we0.5_r0.2828_visc1": (60.0, 1631),
    "re400_we2_r0.2828_visc1": (60.0, 405),
    "re400_we0.25_r0.2828_visc1": (60.0, 822),
    "re100_we0.125_r0.2828_visc1": (60.0, 1041),
    # timed over t = 0-20 in one leg
    "re400_we4_r0.2828_visc1": (20.0, 108),
    "re400_we0.5_r0.2828_visc1": (20.0, 148),
    "re400_we1_r0.2828_visc1": (20.0, 130),
    "re400_we0.125_r0.2828_visc1": (20.0, 208),
    "appendix_re400_we0.0625_r0.2828_visc1": (20.0, 259),
    "re400_we1_r0.0544_visc1": (20.0, 203),
    "re400_we1_r0.7487_visc1": (20.0, 114),
    "re400_we1_r0.2828_visc1_rest": (20.0, 231),
    "re400_we4_r0.2828_visc0.3": (20.0, 346),
    "re400_we4_r0.2828_visc3": (20.0, 116),
    "appendix_re400_we0.03125_r0.2828_visc1": (20.0, 384),
}


def case_name(re, we, r0, visc, rest=False, appendix=False):
    """File stem a reader maps to the table: re400_we1_r0.2828_visc1."""
    name = f"re{re}_we{we:g}_r{r0:g}_visc{visc:g}"
    if rest:
        name += "_rest"
    return ("appendix_" if appendix else "") + name


# The measured step of a paper-model particle in pipe flow, one core (bench/RESULTS.md, 128 x 64^2):
# the flow's 130 ns (BM_Step) x 1.32, the particle's step against the flow's after 200 steps
# (BM_StepPairPaper; its kernels run on psi's support, a smaller share of the grid at 48 cells per
# d, so an upper bound): what the paper-resolution estimate scales.
PAPER_MODEL_NS_PER_CELL_STEP = 172


def case_text(res, re, we, r0, visc, rest, title):
    """The TOML of one run."""
    p = RESOLUTIONS[res]
    nx, ny, nz = p["cells"]
    r = 0.5 * r0  # R = D/2 = 0.5
    # the paper's r/R = 0.2828 = 0.2 sqrt(2): the particle starts on the diagonal y = z
    yc = zc = r / math.sqrt(2.0)
    name = case_name(re, we, r0, visc, rest, title.startswith("Appendix"))
    start = "fluid and particle start at rest" if rest else "the particle starts at rest in the developed Poiseuille flow"
    if res == "desk" and name in DESK_MEASURED:
        t, wall = DESK_MEASURED[name]
        cost = (f"# Cost: {wall / t:.1f} core seconds per time unit (D / U_b), over t = 0-{t:g}, on\n"
                f"# {_CPU}.\n")
    else:
        cells = nx * ny * nz
        # steps per time unit at the CFL limit of the laminar peak velocity 2 U_b (no elastic wave limit)
        steps = 2.0 / (p["cfl"] * (1.0 / ny))
        hours = cells * PAPER_MODEL_NS_PER_CELL_STEP * 1e-9 * steps / 3600.0
        cost = (f"# Cost: not run at this resolution ({cells:,} cells). Estimated {hours:,.0f} core hours per time unit:\n"
                f"# {PAPER_MODEL_NS_PER_CELL_STEP:g} ns per cell and step with a paper-model particle on one core (bench/RESULTS.md,\n"
                f"# 128 x 64^2) x cells x {steps:,.0f} steps (CFL {p['cfl']:g} on 2 U_b; a stiff particle's wave speed adds steps).\n")
    return f"""# {title}
# {p['note']}.
# Alghalibi, Rosti & Brandt (2019): Re = {re}, We = {we:g}, r0/R = {r0}, mu_s/mu_f = {visc:g};
# {start}.
{cost}[domain]
length = [{p['length']}, 1.0, 1.0]
cells = [{nx}, {ny}, {nz}]
geometry = "pipe"

[flow]
Re = {float(re)}
bulk_velocity = 1.0
initial = "{"rest" if rest else "laminar"}"
# the grid follows the particle along x (numerics only; outputs stay in the laboratory frame)
frame_velocity = "particle"

[time]
cfl = {p['cfl']}
t_end = 200.0

[solver]
# FFTW times its algorithms at start-up: the pressure solve ~25 % cheaper (restarts stay bit for bit)
fft_planning = "measure"

[output]
dir = "runs/{res}/{name}"
every = {p['every']}
fields_every = {p['fields_every']}
checkpoint_every = {p['checkpoint_every']}
shape_times = [0.0, 5.0, 10.0, 20.0, 40.0, 80.0, 160.0]

[[solid]]
shape = "sphere"
diameter = 0.2
center = [0.75, {yc:.6f}, {zc:.6f}]
We = {we:g}
viscosity_ratio = {visc:g}
initial_velocity = "rest"
model = "{p['model']}"
"""


def main():
    """Write every case at both resolutions."""
    for res in RESOLUTIONS:
        out = os.path.join(CASES, res)
        os.makedirs(out, exist_ok=True)
        runs = [(c, False, f"Table I run {n + 1} of 16") for n, c in enumerate(TABLE_I)]
        runs += [(c, False, f"Appendix stiff particle {n + 1} of 2") for n, c in enumerate(APPENDIX)]
        runs += [((400, 1.0, 0.2828, 1.0), True, "Fig. 7(b): fluid and particle start at rest")]
        for (re, we, r0, visc), rest, title in runs:
            name = case_name(re, we, r0, visc, rest, title.startswith("Appendix"))
            with open(os.path.join(out, name + ".toml"), "w") as f:
                f.write(case_text(res, re, we, r0, visc, rest, title))
        print(f"{res}: {len(runs)} cases in {os.path.normpath(out)}")


if __name__ == "__main__":
    main()

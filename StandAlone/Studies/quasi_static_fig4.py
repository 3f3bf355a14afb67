"""Figure 4's question answered at the real density: the quasi-static (implicit) run of the small
pillar (inputs/Paper/QuasiStatic_Fig4.ups, density 2.33e3 kg/m^3) against the explicit runs at
2.33e18 and 2.33e24 kg/m^3 (Density_2.33e18, Density_2.33e24), at Figure 4's times 4, 16 and 28 s.

    python3 StandAlone/Studies/quasi_static_fig4.py --runs DIR [--sus build/StandAlone/sus]
        [--carry docs/paper/carry] [--threads 2 | --ranks 2]

The explicit runs come from DIR/NAME, or from the carry folder (paper_carry.py) when DIR lacks
them: Density_2.33e18 took 29 hours here. The quasi-static run is made in DIR/QuasiStatic_Fig4
when it is not there (with --ranks N > 1: `mpirun -np N`, one thread per rank). Prints a markdown table; the metrics are paper_numbers.py's (its docstring
defines them); "axis c" is the mean c of the rings' innermost, and "c of the core's lowest
quarter" the mean c of the inner third of the radius in the lowest quarter of the height.
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_carry  # noqa: E402
import paper_numbers  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
IMPLICIT = "QuasiStatic_Fig4"
EXPLICIT = ["Density_2.33e18", "Density_2.33e24"]
TIMES = [4e6, 16e6, 28e6]  # us


def make_implicit_run(sus, runs, threads, ranks):
    run_dir = os.path.join(runs, IMPLICIT)
    if os.path.exists(os.path.join(run_dir, "particles.pvd")):
        last = paper_numbers.last_output_time(run_dir)
        if last is not None and last >= TIMES[-1] * (1 - 1e-9):
            return
    start = time.time()
    command = [sus, "--threads", str(threads), "-o", run_dir]
    command.append(os.path.join(ROOT, "inputs", "Paper", IMPLICIT + ".ups"))
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
        command[command.index("--threads") + 1] = "1"
    subprocess.run(command, check=True)
    print("%s: %.0f s" % (IMPLICIT, time.time() - start), file=sys.stderr)


def foot_core_c(state):
    """Mean c of the silicon in the inner third of the radius and the lowest quarter of the
    height (by reference position): docs/paper/README.md's "core near the foot"."""
    X0 = state.X0[state.silicon]
    r = np.hypot(X0[:, 0], X0[:, 1])
    z = (X0[:, 2] - state.base) / (state.top - state.base)
    core = (r <= r.max() / 3) & (z <= 0.25)
    return state.c[state.silicon][core].mean()


def row(run_dir, t, reference=None):
    s = paper_numbers.shape(run_dir, t)
    state = paper_numbers.state_of(run_dir, t)
    rings = state.ring_profile()
    cells = ""
    if reference:
        d = paper_numbers.pair_difference(run_dir, reference, t)
        cells = "%.3f / %.4f" % (d["max_dc"], d["mean_dc"])
    return [
        "%.2f" % (s["time"] / 1e6),
        "%.1f%%" % (100 * s["lithium"]),
        "%.1f%%" % (100 * s["height_growth"]),
        "%.1f%%" % (100 * s["top_rise"]),
        "%.1f%%" % (100 * s["top_growth"]),
        "%.3f" % rings[0],
        "%.3f" % foot_core_c(state),
        "%.2f" % s["ep_max"],
        cells,
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", required=True, help="folder of the runs")
    ap.add_argument("--sus", default=os.path.join(ROOT, "build", "StandAlone", "sus"))
    ap.add_argument("--carry", default=os.path.join(ROOT, "docs", "paper", "carry"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks of the quasi-static run")
    a = ap.parse_args()
    os.makedirs(a.runs, exist_ok=True)
    for name in EXPLICIT:
        paper_carry.restore(name, a.runs, a.carry)
    make_implicit_run(a.sus, a.runs, a.threads, a.ranks)
    header = [
        "run",
        "t (s)",
        "lithium (of capacity)",
        "height growth",
        "top layer's mean height growth",
        "top layer's radial growth",
        "axis c",
        "c of the core's lowest quarter",
        "largest plastic strain",
        "largest / mean abs(c - quasi-static)",
    ]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    implicit = os.path.join(a.runs, IMPLICIT)
    for t in TIMES:
        print("| " + " | ".join(["quasi-static 2.33e3"] + row(implicit, t)) + " |")
        for name in EXPLICIT:
            label = "explicit " + name.split("_")[1]
            print("| " + " | ".join([label] + row(os.path.join(a.runs, name), t, implicit)) + " |")


if __name__ == "__main__":
    main()

"""How the quasi-static answer moves with the step: a small cut of Figure 4's pillar
(inputs/Paper/QuasiStatic_Fig4.ups: radius 25 nm, height 50 nm, the same 5 nm particles, grid,
silicon, flux and base) run at fixed steps dt to one time, one run per dt.

    python3 StandAlone/Studies/quasi_static_dt.py --runs DIR [--sus build/StandAlone/sus]
        [--dts 1,0.5,0.25,0.125] [--end 12] [--set hourglass_stabilization=0.5] [--threads 1]
        [--tolerances 0.003,0.001]

Each run takes dt = <delt_init> = <delt_max> and keeps it (<num_iters_to_decrease_delT> 1000);
its outputs come every second. `--set TAG=VALUE` adds <MPM><TAG> to every run. Prints a markdown
table at the end time: per dt the steps, Newton iterations, wall seconds, lithium (% of
capacity), the particles' mean c, the largest difference of a 5 nm slab's mean c and of a
particle's c from the smallest dt's, the mean von Mises stress and pressure (GPa) and the mean
plastic strain. `--tolerances` adds a run per tolerance without step hints (<delt_max>1e12, no
<delt_init>, <max_concentration_change>, <num_iters_*> or <clamp_time_to_output>) under
<error_tolerance>, and a second table: its steps, rejected attempts, the sum of its steps' error
estimates, its accumulated estimate (the largest over the particles of a particle's sum), the
largest difference of a particle's c from the smallest dt's run (at the end, and over the
outputs every second), and the same columns.
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_numbers  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
INPUT = os.path.join(ROOT, "inputs", "Paper", "QuasiStatic_Fig4.ups")
GPA = 1e6  # input stress units (pg / (um us^2)) per GPa


def small_pillar(text, dt, end, settings):
    """The input cut to the small pillar at fixed steps of dt seconds to `end` seconds."""
    replacements = [
        ("<maxTime>2.8e+07</maxTime>", "<maxTime>%g</maxTime>" % (end * 1e6)),
        (
            "<delt_max>1e+06</delt_max>",
            "<delt_max>%g</delt_max><delt_init>%g</delt_init>" % (dt * 1e6, dt * 1e6),
        ),
        ('<checkpoint cycle="2" interval="700000"/>', ""),
        (
            "<num_iters_to_increase_delT>7</num_iters_to_increase_delT>",
            "<num_iters_to_increase_delT>7</num_iters_to_increase_delT>"
            "<num_iters_to_decrease_delT>1000</num_iters_to_decrease_delT>"
            + "".join("<%s>%s</%s>" % (tag, value, tag) for tag, value in settings),
        ),
        ("<top>[0.0, 0.0, 0.1]</top>", "<top>[0.0, 0.0, 0.05]</top>"),
        ("<outer_radius>0.05</outer_radius>", "<outer_radius>0.025</outer_radius>"),
        ("<num_radial>10</num_radial>", "<num_radial>5</num_radial>"),
        ("<num_axial>20</num_axial>", "<num_axial>10</num_axial>"),
        ("<num_angular>64</num_angular>", "<num_angular>32</num_angular>"),
        (
            "<top>[0.0,0.0,0.1]</top><radius>0.0495</radius>",
            "<top>[0.0,0.0,0.05]</top><radius>0.0245</radius>",
        ),
        (
            "<bottom>[0.0,0.0,0.0995]</bottom><top>[0.0,0.0,0.1045]</top><radius>0.05</radius>",
            "<bottom>[0.0,0.0,0.0495]</bottom><top>[0.0,0.0,0.0545]</top><radius>0.025</radius>",
        ),
        ("<lower>[-0.15, -0.15, 0.0]</lower>", "<lower>[-0.075, -0.075, 0.0]</lower>"),
        ("<upper>[0.15, 0.15, 0.3]</upper>", "<upper>[0.075, 0.075, 0.15]</upper>"),
        ("<resolution>[60, 60, 60]</resolution>", "<resolution>[30, 30, 30]</resolution>"),
    ]
    for old, new in replacements:
        if old not in text:
            raise RuntimeError("%s no longer holds %s: update this study" % (INPUT, old))
        text = text.replace(old, new)
    return text


def without_step_hints(text, tolerance):
    """The small pillar's input of small_pillar(text, 1, ...) without step hints, under
    <error_tolerance>."""
    replacements = [
        ("<delt_max>1e+06</delt_max><delt_init>1e+06</delt_init>", "<delt_max>1e12</delt_max>"),
        ("<clamp_time_to_output>true</clamp_time_to_output>", ""),
        ("<error_tolerance>0</error_tolerance>", ""),
        ("<max_concentration_change>1</max_concentration_change>", ""),
        (
            "<num_iters_to_increase_delT>7</num_iters_to_increase_delT>"
            "<num_iters_to_decrease_delT>1000</num_iters_to_decrease_delT>",
            "<error_tolerance>%g</error_tolerance>" % tolerance,
        ),
    ]
    for old, new in replacements:
        if old not in text:
            raise RuntimeError("the small pillar no longer holds %s: update this study" % old)
        text = text.replace(old, new)
    return text


def run(sus, runs, name, end, text_of, threads):
    """Makes the run `name` (its input text_of(the input's text)) in runs/<name> unless it reached
    `end`; returns its wall time."""
    run_dir = os.path.join(runs, name)
    if os.path.exists(os.path.join(run_dir, "particles.pvd")):
        last = paper_numbers.last_output_time(run_dir)
        if last is not None and last >= end * 1e6 * (1 - 1e-9):
            return None
    os.makedirs(runs, exist_ok=True)
    path = os.path.join(runs, "small_pillar_%s.ups" % name)
    with open(INPUT) as f:
        text = text_of(f.read())
    with open(path, "w") as f:
        f.write(text)
    start = time.time()
    with open(os.path.join(runs, "%s.log" % name), "w") as log:
        subprocess.run(
            [sus, "--threads", str(threads), "-o", run_dir, path], check=True, stderr=log
        )
    return time.time() - start


def state(run_dir, end):
    d = paper_numbers.read_output(
        run_dir, end * 1e6, ["p.concentration", "p.stress", "p.plasticStrain", "p.displacement"]
    )
    stress = d["p.stress"].reshape(-1, 3, 3)
    mean = np.einsum("nii->n", stress) / 3
    deviator = stress - mean[:, None, None] * np.eye(3)
    mises = np.sqrt(1.5 * np.einsum("nij,nij->n", deviator, deviator))
    z0 = (d["points"] - d["p.displacement"])[:, 2]
    slab = np.floor(z0 / 0.005 + 1e-9).astype(int)
    c = d["p.concentration"]
    return dict(
        time=d["time"],
        c=c.mean(),
        slabs=np.array([c[slab == k].mean() for k in np.unique(slab)]),
        mises=mises.mean() / GPA,
        pressure=-mean.mean() / GPA,
        plastic=d["p.plasticStrain"].mean(),
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", required=True)
    parser.add_argument("--sus", default=os.path.join(ROOT, "build", "StandAlone", "sus"))
    parser.add_argument("--dts", default="1,0.5,0.25,0.125")
    parser.add_argument("--end", type=float, default=12.0, help="seconds")
    parser.add_argument("--set", action="append", default=[], help="<MPM> TAG=VALUE")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--tolerances", default="", help="<error_tolerance> runs, comma-separated")
    args = parser.parse_args()
    dts = sorted((float(x) for x in args.dts.split(",")), reverse=True)
    settings = [tuple(s.split("=", 1)) for s in args.set]
    tolerances = [float(x) for x in args.tolerances.split(",")] if args.tolerances else []

    def fixed(dt):
        return lambda text: small_pillar(text, dt, args.end, settings)

    def controlled(tolerance):
        return lambda text: without_step_hints(small_pillar(text, 1, args.end, settings), tolerance)

    names = {dt: "dt_%g" % dt for dt in dts}
    names.update({tol: "tol_%g" % tol for tol in tolerances})
    makers = [(dt, fixed(dt)) for dt in dts] + [(tol, controlled(tol)) for tol in tolerances]
    walls = {
        key: run(args.sus, args.runs, names[key], args.end, text_of, args.threads)
        for key, text_of in makers
    }
    finest_dir = os.path.join(args.runs, names[dts[-1]])
    finest = state(finest_dir, args.end)

    def columns(key):
        """Steps, Newton, wall, lithium, mean c, slab and particle differences, stress."""
        run_dir = os.path.join(args.runs, names[key])
        last = paper_numbers.last_history_row(run_dir)
        rows = list(paper_numbers.history_rows(run_dir))
        s = state(run_dir, args.end)
        particle = paper_numbers.pair_difference(run_dir, finest_dir, args.end * 1e6)["max_dc"]
        wall = "%.0f" % walls[key] if walls[key] is not None else "(kept)"
        return rows, [
            "%d" % int(last["step"]),
            "%d" % sum(int(r["newton_iterations"]) for r in rows),
            wall,
            "%.2f" % (100 * last["state_of_charge"]),
            "%.4f" % s["c"],
            "%.4f" % np.abs(s["slabs"] - finest["slabs"]).max(),
            "%.4f" % particle,
            "%.4f" % s["mises"],
            "%.4f" % s["pressure"],
            "%.4f" % s["plastic"],
        ]

    common = (
        "steps | Newton | wall (s) | lithium (%% of capacity) | mean c | largest slab c "
        "difference from dt %g s | largest particle c difference | von Mises (GPa) | "
        "pressure (GPa) | plastic strain |" % dts[-1]
    )
    print("| dt (s) | " + common)
    print("|---" * 11 + "|")
    for dt in dts:
        print("| %g | %s |" % (dt, " | ".join(columns(dt)[1])))
    if not tolerances:
        return
    print()
    print(
        "| tolerance | rejected | sum of the steps' estimates | accumulated estimate | largest "
        "particle c difference over the outputs | accumulated / that at the end | " + common
    )
    print("|---" * 16 + "|")
    for tol in tolerances:
        rows, cells = columns(tol)
        run_dir = os.path.join(args.runs, names[tol])
        over_outputs = max(
            paper_numbers.pair_difference(run_dir, finest_dir, t)["max_dc"]
            for t, _ in paper_numbers.outputs(run_dir)
            if t > 0
        )
        accumulated = rows[-1]["accumulated_error_estimate"]
        print(
            "| %g | %d | %.4f | %.4f | %.4f | %.1f | %s |"
            % (
                tol,
                sum(int(r["rejected_attempts"]) for r in rows),
                sum(r["error_estimate"] for r in rows),
                accumulated,
                over_outputs,
                accumulated / float(cells[6]),
                " | ".join(cells),
            )
        )


if __name__ == "__main__":
    main()

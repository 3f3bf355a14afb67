"""How the quasi-static step's cost grows with the particle count: Figure 4's pillar
(inputs/Paper/QuasiStatic_Fig4.ups) with its particles and grid cells scaled by one factor per
run (the pillar, its flux and its physics unchanged), the first steps of each.

    python3 StandAlone/Studies/quasi_static_scaling.py --runs DIR [--sus build/StandAlone/sus]
        [--steps 4] [--threads 2] [--scales 2,1,0.67]

A scale s gives particles and cells of s times the input's size (5 nm): s = 2 has 1/8 of its
particles. Prints a markdown table from each run's end summary: particles, steps, Newton
iterations per step, Krylov iterations per Newton iteration, seconds per step and per Newton
iteration, and the shares of assembly and linear solves.
"""
import argparse
import os
import re
import subprocess
import time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
INPUT = os.path.join(ROOT, "inputs", "Paper", "QuasiStatic_Fig4.ups")


def scaled_input(text, scale):
    """The input with particle spacing and cell size times `scale`."""

    def count(tag, value):
        return "<%s>%d</%s>" % (tag, max(1, round(value / scale)), tag)

    for tag, value in [("num_radial", 10), ("num_axial", 20), ("num_angular", 64)]:
        old = "<%s>%d</%s>" % (tag, value, tag)
        assert old in text, old
        text = text.replace(old, count(tag, value))
    old = "<resolution>[60, 60, 60]</resolution>"
    assert old in text, old
    n = max(1, round(60 / scale))
    return text.replace(old, "<resolution>[%d, %d, %d]</resolution>" % (n, n, n))


def summary(log):
    """The numbers of sus's end summary."""
    number = r"([0-9.eE+-]+)"
    found = {}
    for key, pattern in [
        ("particles", r"sus: (\d+) particles in"),
        ("steps", r"sus: (\d+) steps, t ="),
        ("wall", r"wall " + number + " s"),
        ("newton", r"Newton iterations (\d+) \("),
        ("krylov", r"Krylov iterations (\d+) \("),
        ("assembly", r"assembleEquilibrium\s+" + number + r"\s+" + number + "%"),
        ("solve", r"solveLinearSystem\s+" + number + r"\s+" + number + "%"),
    ]:
        m = re.search(pattern, log)
        if not m:
            raise RuntimeError("no %s in the run's summary" % key)
        found[key] = m.group(2) if key in ("assembly", "solve") else m.group(1)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", required=True)
    parser.add_argument("--sus", default=os.path.join(ROOT, "build", "StandAlone", "sus"))
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--scales", default="2,1,0.67")
    args = parser.parse_args()
    os.makedirs(args.runs, exist_ok=True)
    with open(INPUT) as f:
        text = f.read()
    print(
        "| scale | particles | steps | Newton / step | Krylov / Newton | s / step | s / Newton "
        "| assembly | linear solves |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for scale in [float(s) for s in args.scales.split(",")]:
        name = "scale_%g" % scale
        path = os.path.join(args.runs, name + ".ups")
        with open(path, "w") as f:
            f.write(scaled_input(text, scale))
        start = time.time()
        run = subprocess.run(
            [
                args.sus,
                "--threads",
                str(args.threads),
                "--max-timesteps",
                str(args.steps),
                "-o",
                os.path.join(args.runs, name),
                path,
            ],
            capture_output=True,
            text=True,
            check=True,
        )
        s = summary(run.stdout + run.stderr)
        steps, newton = int(s["steps"]), int(s["newton"])
        wall = float(s["wall"])
        print(
            "| %g | %s | %d | %.1f | %.1f | %.1f | %.2f | %s%% | %s%% |"
            % (
                scale,
                s["particles"],
                steps,
                newton / steps,
                int(s["krylov"]) / newton,
                wall / steps,
                wall / newton,
                s["assembly"],
                s["solve"],
            ),
            flush=True,
        )


if __name__ == "__main__":
    main()

"""What decides whether Flux_1e-9 has a sharp front (docs/paper/README.md, "The sharp front at
1e-9 m/s"): the Front_cause_* runs (Flux_1e-9 to 35 s with one of Uintah's flux rules, or beta = 0
or 2.07)
and Front_D0_* measured at 15, 30, 45 and 60% of the silicon's capacity (the output nearest each):
the ring profile of the middle layers, the current front measure (paper_numbers.front: c behind
the front) and a steepness measure, the largest dc/dr between neighbouring rings and where it is
(r / R, R the pillar's radius). Prints a markdown table.

    python3 StandAlone/Studies/front_causes.py --runs DIR [NAME ...]

DIR holds one output directory per run, named as its input (sus -o DIR/NAME inputs/Paper/NAME.ups).
"""

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_numbers as pn  # noqa: E402

RUNS = [
    "Front_cause_ours",
    "Front_cause_area_particle_face",
    "Front_cause_receivers_weights",
    "Front_cause_cstar_without_source",
    "Front_cause_uintah_flux_rules",
    "Front_cause_beta_0",
    "Front_cause_beta_2.07",
    "Front_D0_5e-18",
    "Front_D0_2e-18",
]
FRACTIONS = [0.15, 0.30, 0.45, 0.60]


def steepest(radii, profile):
    """(largest dc/dr between neighbouring rings, in 1/um of reference radius, and the r / R of
    the middle between them)."""
    slopes = np.diff(profile) / np.diff(radii)
    k = int(np.argmax(slopes))
    outer = radii[-1] + (radii[-1] - radii[-2]) / 2  # the outer ring's centre is half a ring in
    return slopes[k], (radii[k] + radii[k + 1]) / 2 / outer


def measure(run_dir):
    rows = []
    for fraction in FRACTIONS:
        t = pn.lithium_fraction_time(run_dir, fraction)
        if t is None:
            rows.append((fraction, None))
            continue
        state = pn.State(run_dir, t)
        radii, profile = state.rings()
        profile = np.array(profile)
        rows.append(
            (
                fraction,
                dict(
                    time=state.time,
                    lithium=pn.lithium_fraction_at(run_dir, state.time),
                    profile=profile,
                    front=pn.front(list(profile)),
                    steepest=steepest(radii, profile),
                ),
            )
        )
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", required=True, help="directory of the runs' output directories")
    parser.add_argument("names", nargs="*", default=RUNS, help="runs to measure (default: all)")
    args = parser.parse_args()
    rows = []
    for name in args.names:
        run_dir = os.path.join(args.runs, name)
        if not os.path.exists(os.path.join(run_dir, "history.csv")):
            print("%s: no run in %s" % (name, run_dir), file=sys.stderr)
            continue
        for fraction, m in measure(run_dir):
            if m is None:
                rows.append([name, "%d%%" % (100 * fraction), "not reached"] + [""] * 4)
                continue
            f, (slope, where) = m["front"], m["steepest"]
            rows.append(
                [
                    name,
                    "%d%%" % (100 * fraction),
                    "%.3g s (%.1f%%)" % (m["time"] * 1e-6, 100 * m["lithium"]),
                    " ".join("%.2f" % c for c in m["profile"]),
                    "none" if f is None else "%.2f" % f[2],
                    "%.1f" % slope,
                    "%.2f" % where,
                ]
            )
    print(
        pn.table(
            [
                "run",
                "panel",
                "output (lithium)",
                "ring c, axis to surface (middle layers)",
                "c behind the front",
                "largest dc/dr (1/um)",
                "at r/R",
            ],
            rows,
        )
    )


if __name__ == "__main__":
    main()

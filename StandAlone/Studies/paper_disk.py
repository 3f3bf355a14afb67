#!/usr/bin/env python3
"""The disk each of the paper's scenarios leaves when it ends, estimated from sizes measured on
runs that are here (docs/paper/README.md, "Cost on 2 cores").

  paper_disk.py --quick-runs DIR [--carry DIR] [--numbers FILE]

A finished run keeps its outputs (one .vtu per output time), history.csv (a row per step) and the
input's <checkpoint cycle="N"> newest checkpoints (the automatic one is removed at the end; while
the run goes, one more is on disk). Per scenario:
  outputs     floor(maxTime / outputInterval) + 1 (the input) x the bytes per particle of the
              largest output after the first among the carried runs (a late output: fields that
              vary compress less than the first) x the scenario's particles
  history     its steps (numbers.md's runs table) x the mean bytes of a row after the first in
              its --quick run's history.csv (the columns of this code; numbers take the same
              width all run long)
  checkpoints N x the size of the checkpoint its --quick run wrote (DIR: the quick pipeline's
              runs, e.g. build/tests/paper_quick/runs; a checkpoint's size depends on the
              particles, not on the time)
"""

import argparse
import os
import re
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
from reproduce_paper import SCENARIOS, input_of  # noqa: E402


def text_of(tree, path):
    node = tree.find(path)
    return node.text.strip() if node is not None and node.text else None


def outputs_of(name):
    tree = ET.parse(input_of(name))
    max_time = float(text_of(tree, "Time/maxTime"))
    interval = float(text_of(tree, "DataArchiver/outputInterval"))
    checkpoint = tree.find("DataArchiver/checkpoint")
    kept = int(checkpoint.get("cycle", "0")) if checkpoint is not None else 0
    return int(max_time / interval + 1e-9) + 1, kept


def steps_and_particles(numbers):
    """{scenario: (steps, particles)} from numbers.md's runs table."""
    found = {}
    for line in open(numbers, encoding="utf-8"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) > 3 and cells[0] in SCENARIOS and cells[1].isdigit():
            found[cells[0]] = (int(cells[2]), int(cells[1]))
    return found


def output_bytes_per_particle(carry):
    """The bytes per particle of the largest output after the first among the carried runs."""
    per_particle = 0.0
    for name in sorted(os.listdir(carry)):
        run = os.path.join(carry, name)
        particles_dir = os.path.join(run, "particles")
        if not os.path.isdir(particles_dir):
            continue
        first = sorted(os.listdir(particles_dir))[0]
        for vtu in sorted(os.listdir(particles_dir)):
            if vtu == first:
                continue
            path = os.path.join(particles_dir, vtu)
            with open(path, "rb") as f:
                head = f.read(4096).decode("latin-1")
            count = int(re.search(r'NumberOfPoints="(\d+)"', head).group(1))
            per_particle = max(per_particle, os.path.getsize(path) / count)
    return per_particle


def history_row_bytes(quick_runs, name):
    with open(os.path.join(quick_runs, name, "history.csv")) as f:
        rows = f.read().splitlines()[2:]
    return sum(len(row) + 1 for row in rows) / len(rows)


def checkpoint_bytes(quick_runs, name):
    folder = os.path.join(quick_runs, name, "checkpoints")
    sizes = [os.path.getsize(os.path.join(folder, f)) for f in os.listdir(folder)]
    return max(sizes)


def estimate(name, steps, particles, per_particle, quick_runs):
    """The bytes of a finished run of scenario `name` of `steps` steps and `particles` particles:
    (outputs, history, checkpoints kept)."""
    outputs, kept = outputs_of(name)
    return (
        outputs * particles * per_particle,
        steps * history_row_bytes(quick_runs, name),
        kept * checkpoint_bytes(quick_runs, name),
    )


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick-runs", required=True)
    parser.add_argument("--carry", default=os.path.join(ROOT, "docs", "paper", "carry"))
    parser.add_argument("--numbers", default=os.path.join(ROOT, "docs", "paper", "numbers.md"))
    args = parser.parse_args()
    per_particle = output_bytes_per_particle(args.carry)
    known = steps_and_particles(args.numbers)
    print("a late output: %.1f bytes a particle" % per_particle)
    print(
        "| scenario | steps | outputs | outputs (MB) | history (MB) | checkpoints kept (MB) | in all (MB) |"
    )
    print("|---|---|---|---|---|---|---|")
    total = 0.0
    for name in SCENARIOS:
        # The whole quasi-static cycle stopped half way: its quarter's steps, the same dt control.
        steps, particles = known.get(name) or (
            known["QuasiStatic_FullCycle_LargePillar_Quarter"][0],
            342940,
        )
        sizes = estimate(name, steps, particles, per_particle, args.quick_runs)
        total += sum(sizes)
        print(
            "| %s | %d | %d | %s | %s | %s | %.0f |"
            % (
                (name, steps, outputs_of(name)[0])
                + tuple("%.1f" % (s / 1e6) for s in sizes)
                + (sum(sizes) / 1e6,)
            )
        )
    print("in all: %.2f GB" % (total / 1e9))


if __name__ == "__main__":
    main()

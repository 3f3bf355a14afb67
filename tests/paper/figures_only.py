"""reproduce_paper.py --figures-only from a carry alone, as the tests of the carry run it."""
import os
import subprocess
import sys

STUDIES = os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies"
)


def draw_from_carry(carry, out, render):
    """Draws every figure it can from `carry` into `out` with `render`; returns what it printed."""
    return subprocess.run(
        [
            sys.executable,
            os.path.join(STUDIES, "reproduce_paper.py"),
            "--figures-only",
            "--carry",
            carry,
            "--out",
            out,
            "--render",
            render,
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout

"""The carry committed in docs/paper/carry (docs/paper/README.md, "Quick path"): within its size
budget, no checkpoint in it, and every figure it holds (carried runs or carried panels) drawn
from it alone into a fresh folder, as a fresh clone does.

  test_committed_carry.py RENDER
"""
import os
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
STUDIES = os.path.join(ROOT, "StandAlone", "Studies")
CARRY = os.path.join(ROOT, "docs", "paper", "carry")
BUDGET = 25e6  # bytes: docs/paper/carry/README.md
sys.path.insert(0, STUDIES)
import paper_figures  # noqa: E402
from figures_only import draw_from_carry  # noqa: E402

RENDER = sys.argv[1]


def files_under(folder):
    for top, _, names in os.walk(folder):
        for name in names:
            yield os.path.join(top, name)


class CommittedCarry(unittest.TestCase):
    def test_it_stays_within_its_budget_and_holds_no_checkpoint(self):
        files = list(files_under(CARRY))
        self.assertLessEqual(sum(os.path.getsize(f) for f in files), BUDGET)
        self.assertEqual([f for f in files if ".ckpt" in f or "checkpoints" in f], [])

    def test_every_figure_it_holds_is_drawn_from_it_alone(self):
        carried = set(os.listdir(os.path.join(CARRY, "figures")))
        runs = {d for d in os.listdir(CARRY) if os.path.isdir(os.path.join(CARRY, d))}
        with tempfile.TemporaryDirectory() as out:
            printed = draw_from_carry(CARRY, out, RENDER)
            for figure in paper_figures.FIGURES:
                name = figure["name"]
                if name not in carried and not {r for r, _, _ in figure["panels"]} <= runs:
                    continue
                with self.subTest(figure=name):
                    self.assertNotIn("%-22s the carried figure shows what an older" % name, printed)
                    png = os.path.join(out, "figures", name + ".png")
                    self.assertTrue(os.path.exists(png))
                    with open(png, "rb") as f:
                        self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])

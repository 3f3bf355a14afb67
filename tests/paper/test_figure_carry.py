"""Figures carried without their runs (figure_carry.pack_figure, restore_figure): after
paper_pipeline_quick has drawn every figure from its 3-step runs and packed what each panel shows
(--carry DIR --pack-figures), a fresh output folder draws every figure from DIR alone
(--figures-only --carry DIR) into the same PNG, byte for byte, the carried panels hold fewer
particles than the runs' outputs, and a carried figure whose definition has changed is not drawn.

  test_figure_carry.py QUICK_OUT CARRY RENDER
"""
import os
import shutil
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

STUDIES = os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies"
)
sys.path.insert(0, STUDIES)
import paper_figures  # noqa: E402
from figures_only import draw_from_carry  # noqa: E402

QUICK_OUT, CARRY, RENDER = sys.argv[1:4]


def points_of(vtu_or_xz):
    """NumberOfPoints of a .vtu (or its .xz) as its head says."""
    import lzma

    opener = lzma.open if vtu_or_xz.endswith(".xz") else open
    with opener(vtu_or_xz, "rb") as f:
        head = f.read(4096).decode("latin-1")
    return int(head.split('NumberOfPoints="')[1].split('"')[0])


class FiguresFromTheCarry(unittest.TestCase):
    def test_every_figure_is_drawn_again_from_the_carry_alone(self):
        names = [f["name"] for f in paper_figures.FIGURES]
        with tempfile.TemporaryDirectory() as out:
            draw_from_carry(CARRY, out, RENDER)
            for name in names:
                with self.subTest(figure=name):
                    with open(os.path.join(QUICK_OUT, "figures", name + ".png"), "rb") as f:
                        original = f.read()
                    with open(os.path.join(out, "figures", name + ".png"), "rb") as f:
                        redrawn = f.read()
                    self.assertEqual(original, redrawn)

    def test_a_figure_carried_under_another_definition_is_not_drawn(self):
        with tempfile.TemporaryDirectory() as d:
            carry = os.path.join(d, "carry")
            shutil.copytree(CARRY, carry)
            with open(os.path.join(carry, "figures", "fig7", "definition.txt"), "a") as f:
                f.write("a panel moved\n")
            out = os.path.join(d, "out")
            printed = draw_from_carry(carry, out, RENDER)
            self.assertIn("fig7                   the carried figure shows what an older", printed)
            self.assertFalse(os.path.exists(os.path.join(out, "figures", "fig7.png")))
            self.assertTrue(os.path.exists(os.path.join(out, "figures", "fig6.png")))

    def test_the_carried_panels_hold_only_what_they_show(self):
        for figure in paper_figures.FIGURES:
            folder = os.path.join(CARRY, "figures", figure["name"])
            spec = ET.parse(os.path.join(folder, "figure.xml")).getroot()
            panels = spec.findall("panel")
            self.assertEqual(len(panels), len(figure["panels"]))
            for panel, (run, _, _) in zip(panels, figure["panels"]):
                shown = points_of(os.path.join(folder, panel.find("data").text[:-4] + ".vtu.xz"))
                whole = points_of(
                    os.path.join(QUICK_OUT, "runs", run, "particles", "step_000000.vtu")
                )
                self.assertGreater(shown, 0)
                self.assertLess(shown, whole / 2, figure["name"])  # a cut-away shows under half


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])

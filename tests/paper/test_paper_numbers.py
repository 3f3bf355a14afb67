"""The front of docs/paper/README.md (paper_numbers.front) on ring profiles of known shape, the
cycle's c by height (State.height_profile) on particles of known layers, and a report's numbers.md
merged with a later machine's (merge_numbers), history.csv read as a stream (history_row_near,
last_history_row), and the steepness measure of front_causes.py."""
import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies")
)
import front_causes  # noqa: E402
import paper_numbers  # noqa: E402


class Front(unittest.TestCase):
    def test_sharp_front_and_plateau_behind_it(self):
        profile = [0.0, 0.0, 0.01, 0.05, 0.12, 0.30, 0.55, 0.72, 0.75, 0.80]
        self.assertEqual(paper_numbers.front(profile), (4, 4, 0.72))

    def test_front_at_the_surface(self):
        self.assertEqual(paper_numbers.front([0.0] * 8 + [0.34, 0.62]), (8, 2, 0.62))

    def test_no_unlithiated_core_no_front(self):
        self.assertIsNone(paper_numbers.front([0.19, 0.24, 0.39, 0.66, 0.84, 0.9]))

    def test_nothing_lithiated_no_front(self):
        self.assertIsNone(paper_numbers.front([0.0, 0.01, 0.05, 0.09]))

    def test_smooth_profile_gives_a_one_ring_front(self):
        # A gradient without a jump of 0.1 between rings: the front is its first ring above 0.1.
        self.assertEqual(paper_numbers.front([0.01, 0.04, 0.07, 0.11, 0.16, 0.2]), (3, 1, 0.11))


class Steepest(unittest.TestCase):
    def test_largest_slope_between_rings_and_where(self):
        # Rings 0.01 um apart, centres 0.005 ... 0.095 (R = 0.1): the jump of 0.3 between the
        # rings at 0.075 and 0.085 is the steepest, 30 per um at r/R = 0.8.
        radii = np.arange(10) * 0.01 + 0.005
        profile = np.array([0.0, 0.0, 0.01, 0.02, 0.04, 0.07, 0.1, 0.2, 0.5, 0.6])
        slope, where = front_causes.steepest(radii, profile)
        self.assertAlmostEqual(slope, 30.0)
        self.assertAlmostEqual(where, 0.8)

    def test_flat_profile_has_no_slope(self):
        radii = np.arange(4) * 0.01 + 0.005
        slope, _ = front_causes.steepest(radii, np.full(4, 0.3))
        self.assertAlmostEqual(slope, 0.0)


class HeightProfile(unittest.TestCase):
    def test_slabs_of_two_layers_from_the_base_up(self):
        # Layers 2.5 nm apart from z = 0.04 um; c of a layer = its index; a substrate particle
        # (material 1) below is left out; slabs 5 nm thick hold layers 0-1, 2-3, 4.
        state = paper_numbers.State.__new__(paper_numbers.State)
        layers = [0.04 + 0.0025 * k for k in range(5)]
        state.X0 = np.array([(0.0, 0.0, z) for z in layers for _ in range(2)] + [(0.0, 0.0, 0.01)])
        state.c = np.array([float(k) for k in range(5) for _ in range(2)] + [9.0])
        state.silicon = np.arange(10)
        state.base = layers[0]
        self.assertEqual(state.height_profile(0.005), [0.5, 2.5, 4.0])

    def test_top_layer_rise_is_the_mean_not_the_highest_particle(self):
        # Base layer at X0_z = 0 and top layer at 0.1, both risen: the base by 0.01, the top
        # layer's three particles to 0.13, 0.13 and 0.16 (one standing proud). Mean rise of the
        # top over the base: (0.14 - 0.01) / 0.1 - 1 = 0.3; the highest particle's would be 0.5.
        state = paper_numbers.State.__new__(paper_numbers.State)
        state.X0 = np.array([(0.0, 0.0, 0.0)] * 2 + [(0.0, 0.0, 0.1)] * 3)
        state.x = np.array(
            [(0.0, 0.0, 0.01)] * 2 + [(0.0, 0.0, 0.13), (0.0, 0.0, 0.13), (0.0, 0.0, 0.16)]
        )
        state.silicon = np.arange(5)
        state.layers = np.array([0.0, 0.1])
        state.base, state.top = 0.0, 0.1
        self.assertAlmostEqual(state.top_layer_rise(), 0.3)
        self.assertAlmostEqual(state.height_growth(), 0.5)


class SpreadWithinCells(unittest.TestCase):
    def test_differences_from_the_cells_mean(self):
        # Cell [0, 0.01)^3 holds four particles, c 0.1, 0.2, 0.3, 0.4 (mean 0.25: differences
        # -0.15, -0.05, 0.05, 0.15); cell [0.01, 0.02) x [0, 0.01)^2 holds two (too few: left out).
        x = np.array([(0.002 * k, 0.005, 0.005) for k in range(1, 5)] + [(0.015, 0.005, 0.005)] * 2)
        c = np.array([0.1, 0.2, 0.3, 0.4, 0.0, 1.0])
        among = np.array([True, False, False, True, True, True])
        every, chosen, lowest, worst = paper_numbers.spread_within_cells(x, c, 0.01, among)
        self.assertAlmostEqual(every, np.sqrt((2 * 0.15**2 + 2 * 0.05**2) / 4))
        self.assertAlmostEqual(chosen, 0.15)
        self.assertAlmostEqual(lowest, -0.15)
        self.assertEqual(worst, 0)

    def test_uniform_cells_have_no_spread(self):
        x = np.array([(0.001 * k, 0.0, 0.0) for k in range(8)])
        every, chosen, lowest, _ = paper_numbers.spread_within_cells(x, np.full(8, 0.3), 0.01)
        self.assertAlmostEqual(every, 0.0)
        self.assertAlmostEqual(chosen, 0.0)
        self.assertAlmostEqual(lowest, 0.0)

    def test_no_cell_full_enough_measures_nothing(self):
        x = np.array([(0.005, 0.005, 0.005), (0.015, 0.005, 0.005)])
        result = paper_numbers.spread_within_cells(x, np.array([0.0, 1.0]), 0.01)
        self.assertEqual(result, (None, None, None, None))


class Merge(unittest.TestCase):
    OLD = "\n".join(
        [
            "# Numbers",
            "",
            "## Runs",
            "",
            "| scenario | steps |",
            "|---|---|",
            "| A | 10 |",
            "| B | 20 |",
            "",
            "## Fig. 1",
            "",
            "a: 1.5",
            "",
            "## Fig. 2",
            "",
            "Not measured yet: waiting for C.",
            "",
        ]
    )
    NEW = "\n".join(
        [
            "# Numbers",
            "",
            "## Runs",
            "",
            "| scenario | steps |",
            "|---|---|",
            "| B | 21 |",
            "| C | 30 |",
            "",
            "## Fig. 1",
            "",
            "Not measured yet: waiting for A.",
            "",
            "## Fig. 2",
            "",
            "c: 3",
            "",
        ]
    )

    def test_earlier_sections_and_rows_stay_new_ones_come_in(self):
        merged = paper_numbers.merge_numbers(self.OLD, self.NEW)
        self.assertIn("| A | 10 |\n| B | 21 |\n| C | 30 |", merged)
        self.assertNotIn("| B | 20 |", merged)
        self.assertIn("## Fig. 1\n\na: 1.5", merged)
        self.assertIn("## Fig. 2\n\nc: 3", merged)
        self.assertNotIn("Not measured", merged)

    def test_nothing_earlier_the_new_text_whole(self):
        self.assertEqual(paper_numbers.merge_numbers("", self.NEW), self.NEW)


class DensityPairPartly(unittest.TestCase):
    def test_a_run_still_going_leaves_the_later_times_waiting(self):
        sys.path.insert(0, os.path.dirname(paper_numbers.__file__))
        import paper_carry

        with tempfile.TemporaryDirectory() as runs:
            for run, last in (("A", 2e6), ("B", 28e6)):
                os.makedirs(os.path.join(runs, run))
                paper_carry.write_series(
                    os.path.join(runs, run, "particles.pvd"),
                    [
                        (0.0, os.path.join(runs, run, "p0.vtu")),
                        (last, os.path.join(runs, run, "p1.vtu")),
                    ],
                    os.path.join(runs, run),
                )
            text = paper_numbers.density_section(
                runs, ("A", "B"), [4e6, 16e6], 1e-6, "s", finished=["B"]
            )
            self.assertEqual(text, "Still running: A (last output at 2 s); waiting: 4 s, 16 s.")


class History(unittest.TestCase):
    HEADER = "step,time,dt,total_lithium"

    def history(self, directory, times, trailing="\n"):
        rows = ["%d,%r,0.5,%d" % (i + 1, t, 10 * (i + 1)) for i, t in enumerate(times)]
        with open(os.path.join(directory, "history.csv"), "w") as f:
            f.write("\n".join([self.HEADER] + rows) + trailing)

    def test_row_near_is_the_nearest_of_all_rows(self):
        times = [0.3 * i + 0.01 * (i % 7) for i in range(5000)]
        with tempfile.TemporaryDirectory() as run:
            self.history(run, times)
            for asked in (-1.0, 0.0, 0.31, 0.45, 0.46, 777.7, 1499.9, 2000.0):
                nearest = min(range(len(times)), key=lambda i: abs(times[i] - asked))
                row = paper_numbers.history_row_near(run, asked)
                self.assertEqual(
                    (row["step"], row["time"], row["total_lithium"]),
                    (nearest + 1, times[nearest], 10 * (nearest + 1)),
                    asked,
                )

    def test_a_tie_takes_the_earlier_row(self):
        with tempfile.TemporaryDirectory() as run:
            self.history(run, [1.0, 2.0, 3.0])
            self.assertEqual(paper_numbers.history_row_near(run, 2.5)["step"], 2)

    def test_last_row_of_a_long_file_with_or_without_a_final_newline(self):
        times = [0.5 * i for i in range(20000)]
        for trailing in ("\n", "", "\n\n"):
            with tempfile.TemporaryDirectory() as run:
                self.history(run, times, trailing)
                row = paper_numbers.last_history_row(run)
                self.assertEqual((row["step"], row["time"]), (20000, times[-1]), repr(trailing))

    def test_no_step_no_last_row(self):
        with tempfile.TemporaryDirectory() as run:
            self.assertIsNone(paper_numbers.last_history_row(run))
            self.history(run, [])
            self.assertIsNone(paper_numbers.last_history_row(run))
            self.history(run, [7.0])
            self.assertEqual(paper_numbers.last_history_row(run)["time"], 7.0)


if __name__ == "__main__":
    unittest.main()

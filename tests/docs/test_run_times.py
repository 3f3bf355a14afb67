"""run_times.py --check on a small repository of its own: it passes on markers equal to the table
and fails on each way a page can state a run time the table does not back."""

import os
import sys
import tempfile
import unittest

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies")
)
import run_times  # noqa: E402


class CheckTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        root = self.folder.name
        os.makedirs(os.path.join(root, "docs", "paper"))
        self.saved = run_times.ROOT, run_times.TABLE
        run_times.ROOT = root
        run_times.TABLE = os.path.join(root, "docs", "run-times.md")
        run_times.write_table(
            {"main_job": ("13.9 s", "2 cores"), "uintah_paper_cycle": ("48.57 h", "9 cores")}
        )
        self.page("README.md", "The main job takes <!--t:main_job-->13.9 s<!--/t-->.\n")

    def tearDown(self):
        run_times.ROOT, run_times.TABLE = self.saved
        self.folder.cleanup()

    def page(self, name, text):
        with open(os.path.join(run_times.ROOT, name), "w", encoding="utf-8") as f:
            f.write(text)

    def problems(self):
        return run_times.check(run_times.read_table())

    def test_markers_equal_to_the_table_pass(self):
        self.page(
            os.path.join("docs", "a.md"),
            "The paper's cycle: <!--t:uintah_paper_cycle-->48.57 h<!--/t--> on 9 cores.\n"
            "Steps of dt = 1 s; t = 4.8 h of 6 h simulated; 0.03 ms a step by the model.\n",
        )
        self.assertEqual(self.problems(), [])

    def test_a_planted_duplicate_fails(self):
        for text in (
            "The main job takes 14 s on 2 cores.\n",
            "The cycle takes 32 min.\n",
            "It took 13.9 s.\n",
            "40 steps in 2,161 s.\n",
            "The paper's run, 48.57 h on 9 cores.\n",
            "14,815 steps, 48:19 elapsed.\n",
        ):
            self.page(os.path.join("docs", "a.md"), text)
            self.assertGreaterEqual(len(self.problems()), 1, text)

    def test_a_marker_off_the_table_fails(self):
        for text in (
            "<!--t:main_job-->14 s<!--/t-->\n",  # another value
            "<!--t:no_such_row-->1 s<!--/t-->\n",  # not a row
            "<!--t:tutorial-->not timed<!--/t-->\n",  # a row not yet timed
        ):
            self.page(os.path.join("docs", "paper", "b.md"), text)
            self.assertGreaterEqual(len(self.problems()), 1, text)


if __name__ == "__main__":
    unittest.main()

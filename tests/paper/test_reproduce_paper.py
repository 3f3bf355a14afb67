"""The runner's wall-time record (reproduce_paper.py): a session killed outright is counted from
its last heartbeat when the run is continued, and a running run's heartbeat is rewritten."""
import os
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies"))
import reproduce_paper  # noqa: E402


class WallTime(unittest.TestCase):
    def test_a_killed_session_counts_from_its_last_heartbeat(self):
        with tempfile.TemporaryDirectory() as d:
            run_dir = os.path.join(d, "Run")
            with open(run_dir + ".wall", "w") as f:
                f.write("2026-11-25T17:09:13 1995.6 exit=-15 interrupted\n")
            with open(run_dir + ".wall.running", "w") as f:
                f.write("2026-11-25T17:58:00 150.0\n")
            reproduce_paper.record_killed_session(run_dir)
            self.assertFalse(os.path.exists(run_dir + ".wall.running"))
            self.assertAlmostEqual(reproduce_paper.wall_seconds(run_dir), 2145.6)
            reproduce_paper.record_killed_session(run_dir)  # nothing more to record
            self.assertAlmostEqual(reproduce_paper.wall_seconds(run_dir), 2145.6)

    def test_the_heartbeat_is_rewritten_while_the_run_goes_and_removed_at_its_end(self):
        with tempfile.TemporaryDirectory() as d:
            run_dir = os.path.join(d, "Run")
            beats = []
            child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(0.35)"])
            saved = reproduce_paper.HEARTBEAT
            reproduce_paper.HEARTBEAT = 0.1
            try:
                original = os.replace

                def watch(src, dst):
                    original(src, dst)
                    with open(dst) as f:
                        beats.append(float(f.read().split()[1]))

                reproduce_paper.os.replace = watch
                code = reproduce_paper.wait_with_heartbeat(child, run_dir, time.time())
            finally:
                reproduce_paper.os.replace = original
                reproduce_paper.HEARTBEAT = saved
            self.assertEqual(code, 0)
            self.assertGreaterEqual(len(beats), 2)
            self.assertEqual(beats, sorted(beats))
            self.assertFalse(os.path.exists(run_dir + ".wall.running"))


if __name__ == "__main__":
    unittest.main()

"""The runner (reproduce_paper.py): a session killed outright is counted from its last heartbeat
when the run is continued, a running run's heartbeat is rewritten, a run another runner is
running is left to it, a run on --ranks goes under mpirun, and a run carried to another
machine (paper_carry.py) comes back with its checkpoint, wall time and the outputs its figures
show. A figure whose run is still going is drawn as far as that run has reached
(paper_figures.panels_reached)."""
import argparse
import os
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies")
)
import paper_carry  # noqa: E402
import paper_figures  # noqa: E402
import paper_numbers  # noqa: E402
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

    def test_a_run_another_runner_is_running_is_left_to_it(self):
        with tempfile.TemporaryDirectory() as runs:
            run_dir = os.path.join(runs, "Run")
            os.makedirs(os.path.join(run_dir, "checkpoints"))
            open(os.path.join(run_dir, "checkpoints", "step_000010.ckpt"), "w").close()
            with open(run_dir + ".wall.running", "w") as f:
                f.write("2026-12-02T14:09:55 120.0\n")  # fresh: written just now
            args = argparse.Namespace(sus="/nonexistent/sus", threads=1, ranks=1, quick=0)
            self.assertFalse(reproduce_paper.run_scenario("Run", args, runs))
            self.assertTrue(os.path.exists(run_dir + ".wall.running"))
            self.assertFalse(os.path.exists(run_dir + ".wall"))  # not taken for a killed session
            self.assertFalse(os.path.exists(run_dir + ".log"))  # nothing started
            stale = time.time() - 3 * reproduce_paper.HEARTBEAT
            os.utime(run_dir + ".wall.running", (stale, stale))
            self.assertFalse(reproduce_paper.running_elsewhere(run_dir))

    def test_a_run_on_ranks_is_started_and_continued_under_mpirun(self):
        args = argparse.Namespace(sus="sus", threads=1, ranks=2, quick=0)
        start = reproduce_paper.sus_command("Flux_1e-9", args, "/r/Flux_1e-9", restart=False)
        self.assertEqual(start[:5], ["mpirun", "-np", "2", "sus", "--threads"])
        self.assertEqual(start[-3:], ["-o", "/r/Flux_1e-9", reproduce_paper.input_of("Flux_1e-9")])
        again = reproduce_paper.sus_command("Flux_1e-9", args, "/r/Flux_1e-9", restart=True)
        self.assertEqual(
            again, ["mpirun", "-np", "2", "sus", "-restart", "/r/Flux_1e-9", "--threads", "1"]
        )
        args.ranks = 1
        self.assertEqual(
            reproduce_paper.sus_command("Flux_1e-9", args, "/r/Flux_1e-9", restart=True)[0], "sus"
        )


def write_pvd(run_dir, times):
    os.makedirs(run_dir, exist_ok=True)
    with open(os.path.join(run_dir, "particles.pvd"), "w") as f:
        f.write(
            '<VTKFile type="Collection"><Collection>%s</Collection></VTKFile>\n'
            % "".join(
                '<DataSet timestep="%.17g" file="particles/step_%06d.vtu"/>' % (t, k)
                for k, t in enumerate(times)
            )
        )


class PartialFigure(unittest.TestCase):
    FIGURE = dict(
        columns=2, panels=[(run, t, run) for t in (4e6, 16e6, 28e6) for run in ("Going", "Done")]
    )

    def panels(self, going_times):
        with tempfile.TemporaryDirectory() as runs:
            write_pvd(os.path.join(runs, "Going"), going_times)
            return paper_figures.panels_reached(self.FIGURE, runs, ["Done"])

    def test_the_rows_a_run_still_going_has_reached_are_drawn_whole(self):
        self.assertEqual(self.panels([0, 1e6, 2e6]), ([], ["Going"]))
        self.assertEqual(self.panels([0, 3e6, 3.99999e6]), ([], ["Going"]))
        self.assertEqual(self.panels([0, 4.0000021e6]), (self.FIGURE["panels"][:2], ["Going"]))
        self.assertEqual(
            self.panels([0, 4e6, 8e6, 16e6, 20e6]), (self.FIGURE["panels"][:4], ["Going"])
        )

    def test_a_figure_of_finished_runs_is_drawn_whole_and_one_of_states_waits(self):
        with tempfile.TemporaryDirectory() as runs:
            self.assertEqual(
                paper_figures.panels_reached(self.FIGURE, runs, ["Going", "Done"]),
                (self.FIGURE["panels"], []),
            )
            at_states = dict(
                columns=1, panels=[("Going", ("lithium", 0.5), ""), ("Going", ("end",), "")]
            )
            write_pvd(os.path.join(runs, "Going"), [0, 1e9])
            self.assertEqual(paper_figures.panels_reached(at_states, runs, []), ([], ["Going"]))


class Carry(unittest.TestCase):
    def make_run(self, runs, name, rows):
        run_dir = os.path.join(runs, name)
        os.makedirs(os.path.join(run_dir, "particles"))
        os.makedirs(os.path.join(run_dir, "checkpoints"))
        with open(os.path.join(run_dir, "input.ups"), "w") as f:
            f.write("<Uintah_specification/>\n")
        with open(os.path.join(run_dir, "history.csv"), "w") as f:
            f.write(
                "step,time,wall_seconds\n"
                + "".join("%d,%d,0.1\n" % (i, 2000 * i) for i in range(rows))
            )
        # Outputs at 0, 4.0001, 8 and 16.2 s: Fig. 4 shows 4, 16 and 28 s of this run.
        times = [0, 4.0001e6, 8e6, 16.2e6]
        for i, t in enumerate(times):
            with open(os.path.join(run_dir, "particles", "step_%06d.vtu" % i), "w") as f:
                f.write("frame %d\n" % i)
        paper_carry.write_series(
            os.path.join(run_dir, "particles.pvd"),
            [
                (t, os.path.join(run_dir, "particles", "step_%06d.vtu" % i))
                for i, t in enumerate(times)
            ],
            run_dir,
        )
        for name in ("step_000100.ckpt", "auto_step_000200.ckpt"):  # sus's own is the newer here
            with open(os.path.join(run_dir, "checkpoints", name), "wb") as f:
                f.write(os.urandom(1000) + name.encode())
        with open(run_dir + ".wall", "w") as f:
            f.write("2026-11-25T17:09:13 1995.6 exit=-15 interrupted\n")
        with open(run_dir + ".wall.running", "w") as f:
            f.write("2026-11-25T18:00:00 150.0\n")
        return run_dir

    def test_a_packed_run_is_restored_on_another_machine(self):
        with tempfile.TemporaryDirectory() as d:
            name = "Density_2.33e18"
            out, there, carry = (os.path.join(d, x) for x in ("out", "there", "carry"))
            run_dir = self.make_run(os.path.join(out, "runs"), name, 25000)
            pack = [
                sys.executable,
                reproduce_paper.__file__,
                "--out",
                out,
                "--carry",
                carry,
                "--pack",
                "--only",
                name,
            ]
            os.utime(run_dir + ".wall.running")  # a fresh heartbeat: the run is going
            running = subprocess.run(pack, capture_output=True, text=True)
            self.assertNotEqual(running.returncode, 0)
            self.assertIn("is running; stop the runner", running.stderr)
            os.utime(run_dir + ".wall.running", (0, 0))  # an old one: its session was killed
            packed = subprocess.run(pack, capture_output=True, text=True)
            self.assertEqual(packed.returncode, 0, packed.stderr)
            self.assertIn("packed %s: at auto_step_000200.ckpt, 3 outputs" % name, packed.stdout)
            self.assertTrue(paper_carry.restore(name, there, carry))
            self.assertFalse(paper_carry.restore(name, there, carry))  # it has the run now
            back = os.path.join(there, name)
            self.assertEqual(
                os.listdir(os.path.join(back, "checkpoints")), ["auto_step_000200.ckpt"]
            )
            with open(
                os.path.join(run_dir, "checkpoints", "auto_step_000200.ckpt"), "rb"
            ) as a, open(os.path.join(back, "checkpoints", "auto_step_000200.ckpt"), "rb") as b:
                self.assertEqual(a.read(), b.read())
            self.assertEqual(
                sorted(os.listdir(os.path.join(back, "particles"))),
                ["step_000000.vtu", "step_000001.vtu", "step_000003.vtu"],
            )
            self.assertEqual([t for t, _ in paper_numbers.outputs(back)], [0, 4.0001e6, 16.2e6])
            with open(os.path.join(back, "history.csv")) as f:
                steps = [int(r.split(",")[0]) for r in f.read().split("\n")[1:] if r]
            self.assertEqual(steps, list(range(0, 25000, 1000)) + [24999])
            self.assertAlmostEqual(reproduce_paper.wall_seconds(back), 2145.6)


if __name__ == "__main__":
    unittest.main()

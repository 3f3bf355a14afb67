#!/usr/bin/env python3
"""Remakes Gritton et al.'s Figures 3-10 and the numbers of docs/paper/README.md.

  python3 StandAlone/Studies/reproduce_paper.py [--out DIR] [--threads N] [--ranks N] [--jobs N]
                                                [--only NAME ...]
                                                [--figures-only] [--quick STEPS] [--report DIR]
                                                [--carry DIR [--pack | --pack-figures]]

1. Runs every scenario of inputs/Paper/ that a figure needs into DIR/runs/NAME (default DIR:
   out/paper), cheapest first, --jobs of them at a time; with --ranks N each run is
   `mpirun -np N sus` (an implicit run's linear solves then use the cores too). It is
   resumable: a finished run (DIR/runs/NAME/complete.json) is skipped, a run with a checkpoint
   (sus keeps one of its own every 10 minutes) is continued with `sus -restart`, on any rank
   count, so the command can be stopped at any moment (Ctrl-C or SIGTERM stops the run too,
   which writes a checkpoint at the end of its step, and records its time) and started again.
   Each session's wall time is appended to DIR/runs/NAME.wall; a session killed outright
   (SIGKILL) is recorded from its last heartbeat (DIR/runs/NAME.wall.running, every 30 s) when
   the run is continued. A run whose heartbeat is fresh is running in another runner and is
   skipped (two processes never share its folder).
2. Renders each figure as one PNG (DIR/figures/figN.png) through the project's renderer
   (`render_figure`: panels side by side, a shared colour bar, panel letters and times).
3. Measures the numbers of each figure from the VTU files (paper_numbers.py) into
   DIR/numbers.md; with --report DIR2 the figures and numbers.md are copied there too (into a
   numbers.md already there, keeping the sections and run rows of runs this machine lacks).

--carry DIR restores, before running, each run this machine has nothing of from DIR/NAME, and
--carry DIR --pack writes the runs there for a session on another machine (paper_carry.py).
--carry DIR --pack-figures writes, for each figure drawn from finished runs, the particles its
panels show into DIR/figures/NAME; a figure whose runs this machine lacks is then drawn from there
(the same PNG, byte for byte).

--quick STEPS runs each scenario afresh for STEPS steps only (a quasi-static one for one step;
into DIR, which must not hold full runs) and makes every figure from what that gives: the pipeline's test (tests/CMakeLists.txt).
Needs /usr/bin/python3 with numpy (python3-numpy) and, for the numbers, VTK (python3-vtk9, which
libvtk9-dev installs).
"""
import argparse
import concurrent.futures
import datetime
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)

import paper_carry  # noqa: E402
import paper_figures  # noqa: E402
import paper_numbers  # noqa: E402

SIMULATION_STOPPED = 3  # sus's exit code for a run it stopped with a diagnostic
HEARTBEAT = 30  # seconds between rewrites of a running run's wall time so far

# Cheapest first (measured here on 2 cores; docs/paper/README.md has the wall times).
SCENARIOS = [
    "Flux_1e-8",
    "Flux_1e-9",
    "Constitutive_elastic",
    "Constitutive_perfect",
    "Constitutive_hardening",
    "Beta_0",
    "Beta_1",
    "Front_D0_5e-18",
    "Front_D0_2e-18",
    "Density_2.33e24",
    "Density_2.33e8",
    "Substrate_fixed",
    "Substrate_deformable",
    "Cycle_LargePillar",
    "Cycle_LargePillar_Quarter",
    "FullCycle_LargePillar_Quarter",
    "QuasiStatic_FullCycle_LargePillar",
    "QuasiStatic_FullCycle_LargePillar_Quarter",
    "Density_2.33e3",
    "Density_2.33e18",
]


def has_checkpoint(run_dir):
    folder = os.path.join(run_dir, "checkpoints")
    return os.path.isdir(folder) and any(f.endswith(".ckpt") for f in os.listdir(folder))


def wall_seconds(run_dir):
    """The wall time of every session of a run, summed (DIR/runs/NAME.wall)."""
    path = run_dir + ".wall"
    if not os.path.exists(path):
        return 0.0
    with open(path) as f:
        return sum(float(line.split()[1]) for line in f if line.strip())


def write_whole(path, text):
    """Writes path through a temporary file renamed once whole: a kill leaves no half file."""
    with open(path + ".part", "w") as f:
        f.write(text)
    os.replace(path + ".part", path)


def record_killed_session(run_dir):
    """A session killed outright (SIGKILL, the machine going down) could not write its .wall line;
    its last heartbeat (DIR/runs/NAME.wall.running, rewritten every HEARTBEAT seconds) is recorded
    in its place, so the summed wall time misses at most one heartbeat per such session."""
    beat = run_dir + ".wall.running"
    if not os.path.exists(beat):
        return
    with open(beat) as f:
        started, seconds = f.read().split()[:2]
    with open(run_dir + ".wall", "a") as f:
        f.write(
            "%s %s exit=killed killed (the last heartbeat of the session started then)\n"
            % (started, seconds)
        )
    os.remove(beat)


def running_elsewhere(run_dir):
    """Whether another runner is running this run now: its heartbeat is fresh."""
    beat = run_dir + ".wall.running"
    return os.path.exists(beat) and time.time() - os.path.getmtime(beat) < 2 * HEARTBEAT


def wait_with_heartbeat(child, run_dir, start):
    """Waits for the run, writing DIR/runs/NAME.wall.running with its wall time so far at once and
    every HEARTBEAT seconds."""
    beat = run_dir + ".wall.running"
    started = datetime.datetime.fromtimestamp(start).isoformat(timespec="seconds")
    write_whole(beat, "%s %.1f\n" % (started, time.time() - start))
    while True:
        try:
            code = child.wait(timeout=HEARTBEAT)
            break
        except subprocess.TimeoutExpired:
            write_whole(beat, "%s %.1f\n" % (started, time.time() - start))
    if os.path.exists(beat):
        os.remove(beat)
    return code


def finished_run(run_dir):
    """The run's complete.json as a dict, or None if it has not finished."""
    path = os.path.join(run_dir, "complete.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def refuse_quick_over_full_runs(runs, names):
    """--quick starts its runs afresh: it must not delete a full run, finished or not."""
    for name in names:
        run_dir = os.path.join(runs, name)
        done = finished_run(run_dir)
        if (done and not done["quick"]) or (not done and has_checkpoint(run_dir)):
            sys.exit(
                "reproduce_paper.py: %s holds a full run; give --quick another --out" % run_dir
            )


def input_of(name):
    return os.path.join(ROOT, "inputs", "Paper", name + ".ups")


def quick_steps(name, steps):
    """The steps of a --quick run: `steps`, but one for a quasi-static scenario (each of its steps
    is a Newton solve of the whole pillar: one shows the pipeline works)."""
    with open(input_of(name)) as f:
        implicit = "<time_integrator>implicit</time_integrator>" in f.read()
    return 1 if implicit else steps


def sus_command(name, args, run_dir, restart):
    """The command of a run: sus on --threads, under mpirun with --ranks above 1; a restart from
    the run's newest checkpoint, else afresh from its input (--quick: for its quick steps)."""
    command = ["mpirun", "-np", str(args.ranks)] if args.ranks > 1 else []
    command.append(args.sus)
    if restart:
        return command + ["-restart", run_dir, "--threads", str(args.threads)]
    command += ["--threads", str(args.threads)]
    if args.quick:
        command += ["--max-timesteps", str(quick_steps(name, args.quick))]
    return command + ["-o", run_dir, input_of(name)]


def run_scenario(name, args, runs):
    run_dir = os.path.join(runs, name)
    done = finished_run(run_dir)
    if done and not args.quick and not done["quick"]:
        print("%-22s done" % name, flush=True)
        return True
    if running_elsewhere(run_dir):  # another runner has it: not a second process on its folder
        print("%-22s running in another runner: skipped" % name, flush=True)
        return False
    restart = not args.quick and has_checkpoint(run_dir)
    if restart:
        record_killed_session(run_dir)
        how = "continued from its newest checkpoint"
    else:  # afresh: what an earlier attempt left is not part of this run
        shutil.rmtree(run_dir, ignore_errors=True)
        for leftover in (run_dir + ".wall", run_dir + ".wall.running", run_dir + ".log"):
            if os.path.exists(leftover):
                os.remove(leftover)
        how = "started"
    command = sus_command(name, args, run_dir, restart)
    with RUNNING_LOCK:
        if STOPPING.is_set():
            return False
        print("%-22s %s: %s" % (name, how, " ".join(command)), flush=True)
        start = time.time()
        log = open(run_dir + ".log", "a")
        child = subprocess.Popen(
            command,
            stdout=log,
            stderr=subprocess.STDOUT,
            env=dict(os.environ, OMP_WAIT_POLICY="passive"),
        )
        RUNNING.add(child)
    code = wait_with_heartbeat(child, run_dir, start)
    log.close()
    with RUNNING_LOCK:
        RUNNING.discard(child)
    interrupted = STOPPING.is_set()  # SIGINT or SIGTERM stopped it: keep its wall time so far
    seconds = time.time() - start
    with open(run_dir + ".wall", "a") as f:
        # The load average says whether the machine was shared while the run went.
        f.write(
            "%s %.1f exit=%d load=%.2f%s\n"
            % (
                datetime.datetime.now().isoformat(timespec="seconds"),
                seconds,
                code,
                os.getloadavg()[1],
                " interrupted" if interrupted else "",
            )
        )
    if interrupted:
        print(
            "%-22s interrupted after %.0f s; run the command again to continue it"
            % (name, seconds),
            flush=True,
        )
        return False
    # Exit code 3: sus stopped the run with a diagnostic (docs/stability.md), the same on every
    # try; its last good state ends the .pvd and is what the figures show. Anything else failed.
    stopped = None
    if code == SIMULATION_STOPPED:
        with open(run_dir + ".log") as log:
            stopped = [line.strip() for line in log if "simulation stopped" in line][-1]
    elif code != 0:
        print(
            "%-22s failed with exit code %d after %.0f s (see %s.log)"
            % (name, code, seconds, run_dir),
            flush=True,
        )
        return False
    last = paper_numbers.last_history_row(run_dir)
    if last is None:
        sys.exit(
            "reproduce_paper.py: %s ended with exit code %d but its history.csv holds no step"
            % (run_dir, code)
        )
    summary = dict(
        steps=int(last["step"]),
        time=float(last["time"]),
        particles=int(last["particles"]),
        wall_seconds=wall_seconds(run_dir),
        threads=args.threads,
        ranks=args.ranks,
        quick=args.quick,
        stopped=stopped,
    )
    write_whole(os.path.join(run_dir, "complete.json"), json.dumps(summary, indent=1))
    print(
        "%-22s %s: %d steps to t = %g in %.0f s of wall time"
        % (
            name,
            "stopped by sus (" + stopped + ")" if stopped else "finished",
            summary["steps"],
            summary["time"],
            summary["wall_seconds"],
        ),
        flush=True,
    )
    return True


# The sus processes running now (a run per job), and whether the command is being stopped.
RUNNING, RUNNING_LOCK, STOPPING = set(), threading.Lock(), threading.Event()


def stop_on_sigterm(signum, frame):
    raise KeyboardInterrupt


def run_all(names, args, runs):
    """Runs the scenarios in order, --jobs of them at a time; Ctrl-C or SIGTERM stops them all."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_scenario, name, args, runs) for name in names]
        try:
            return all([f.result() for f in futures])
        except KeyboardInterrupt:
            with RUNNING_LOCK:
                STOPPING.set()
                for child in RUNNING:
                    # mpirun passes SIGUSR1 on to the ranks (a SIGTERM would kill them); sus
                    # stops on either at the end of its step, with a checkpoint there.
                    child.send_signal(signal.SIGUSR1 if args.ranks > 1 else signal.SIGTERM)
            concurrent.futures.wait(futures)
            sys.exit("reproduce_paper.py: stopped; run the command again to continue")


def pack_runs(names, args, runs):
    """--pack: the named runs, stopped, into the carry folder (paper_carry.py)."""
    if not args.carry:
        sys.exit("reproduce_paper.py: --pack needs --carry DIR")
    for name in names:
        run_dir = os.path.join(runs, name)
        if running_elsewhere(run_dir):
            sys.exit("reproduce_paper.py: %s is running; stop the runner before --pack" % name)
        record_killed_session(run_dir)
        packed = paper_carry.pack(name, runs, args.carry)
        if packed:
            print("packed " + packed, flush=True)


def main():
    signal.signal(signal.SIGTERM, stop_on_sigterm)
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "paper"))
    parser.add_argument("--sus", default=os.path.join(ROOT, "build", "StandAlone", "sus"))
    parser.add_argument(
        "--render", default=os.path.join(ROOT, "build", "StandAlone", "render_figure")
    )
    parser.add_argument("--threads", type=int, default=os.cpu_count(), help="threads of each run")
    parser.add_argument(
        "--ranks", type=int, default=1, help="MPI ranks of each run (mpirun -np N; default 1)"
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=1,
        help="runs at a time (--jobs 2 --threads 1 makes two small-pillar runs at once on "
        "2 cores, faster than one after the other with 2 threads each)",
    )
    parser.add_argument("--only", nargs="+", choices=SCENARIOS, help="run only these scenarios")
    parser.add_argument(
        "--figures-only", action="store_true", help="make figures and numbers, run nothing"
    )
    parser.add_argument("--quick", type=int, default=0, metavar="STEPS")
    parser.add_argument("--report", help="copy the figures and numbers.md into this directory")
    parser.add_argument(
        "--carry",
        metavar="DIR",
        help="restore runs this machine lacks from DIR (see paper_carry.py) before running",
    )
    parser.add_argument(
        "--pack",
        action="store_true",
        help="with --carry: write the runs (--only, else all) into DIR for a later session, run nothing",
    )
    parser.add_argument(
        "--pack-figures",
        action="store_true",
        help="with --carry: write what each figure drawn from finished runs shows into "
        "DIR/figures/NAME, from which --carry DIR draws it again without the runs",
    )
    args = parser.parse_args()
    if args.pack_figures and not args.carry:
        parser.error("--pack-figures needs --carry DIR")
    repository_carry = os.path.join(ROOT, "docs", "paper", "carry")
    if (
        args.pack_figures
        and args.quick
        and os.path.realpath(args.carry) == os.path.realpath(repository_carry)
    ):
        parser.error("--quick --pack-figures would carry 3-step figures in docs/paper/carry")
    for option, value in (
        ("--threads", args.threads),
        ("--ranks", args.ranks),
        ("--jobs", args.jobs),
        ("--quick", args.quick + 1),
    ):
        if value < 1:
            parser.error("%s must be at least %d" % (option, 0 if option == "--quick" else 1))
    args.out = os.path.abspath(args.out)  # the figure files name the runs' output from elsewhere
    runs = os.path.join(args.out, "runs")
    os.makedirs(runs, exist_ok=True)
    names = args.only or SCENARIOS
    if args.pack:
        pack_runs(names, args, runs)
        return
    if args.carry:
        for name in names:
            if paper_carry.restore(name, runs, args.carry):
                print("%-22s restored from %s" % (name, os.path.join(args.carry, name)), flush=True)
    if args.quick:
        refuse_quick_over_full_runs(runs, names)
    ok = args.figures_only or run_all(names, args, runs)
    # Figures of full runs from full runs only, and of the quick test from quick ones.
    finished = [
        n
        for n in SCENARIOS
        if (done := finished_run(os.path.join(runs, n))) and done["quick"] == args.quick
    ]
    made = paper_figures.make_all(args, runs, finished)
    figures = [path for path in made if path.endswith(".png")]
    if args.quick and len(figures) != len(paper_figures.FIGURES):
        sys.exit(
            "reproduce_paper.py: only %d of %d figures were drawn"
            % (len(figures), len(paper_figures.FIGURES))
        )
    if args.report:
        os.makedirs(args.report, exist_ok=True)
        for path in made:
            report = os.path.join(args.report, os.path.basename(path))
            if path.endswith("numbers.md") and os.path.exists(report):
                with open(report) as before, open(path) as now:
                    merged = paper_numbers.merge_numbers(before.read(), now.read())
                write_whole(report, merged)
            else:
                shutil.copy(path, args.report)
    if not ok:
        sys.exit(1)


if __name__ == "__main__":
    main()

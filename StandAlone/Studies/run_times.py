"""The run times the docs state, one row per quantity, in docs/run-times.md; and the docs' own
statements of them kept equal to that table.

  run_times.py [--only NAME ...] [--long]   time the rows (all but the long ones, or NAME ...)
                                            and write their cells of docs/run-times.md
  run_times.py --list                       the rows, their commands, which are long
  run_times.py --fill                       write every marked run time in README.md and docs/
                                            from the table
  run_times.py --check                      fail on a marked run time that is not the table's,
                                            on a name the table lacks or has not timed, and on a run time stated
                                            without a marker

A page states a run time as <!--t:NAME-->VALUE<!--/t--> (VALUE as the table's "wall time" cell;
the markers do not show in rendered Markdown). Each row's command runs from the repository root,
in a fresh folder out/run_times/NAME, and its time is the command's elapsed wall time; the
machine column says where it ran (cores, processor, from /proc/cpuinfo). A row without a command
is a time quoted from elsewhere (the paper's); a seeded row keeps a time measured before, its
conditions in the machine column, until it is timed again.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reproduce_paper import SCENARIOS  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TABLE = os.path.join(ROOT, "docs", "run-times.md")
OUT = os.path.join("out", "run_times")
SUS = "./build/StandAlone/sus"

# name, what, command ({out}: the row's folder), long (not timed without --only or --long)
ROWS = [
    (
        "main_job",
        "the README's first command's run: the default input",
        SUS + " -o {out} inputs/Pillar/PillarQuasiStatic.ups",
        False,
    ),
    (
        "tutorial",
        "every command of docs/tutorial.md (two runs, a picture, two readings)",
        "/usr/bin/python3 tests/docs/run_doc_blocks.py docs/tutorial.md build {out}",
        False,
    ),
    (
        "film",
        "the film cycled three times, `inputs/Films/SiliconFilm.ups`, one thread",
        SUS + " --threads 1 -o {out} inputs/Films/SiliconFilm.ups",
        False,
    ),
    (
        "film_potential",
        "the film between potential cutoffs, `inputs/Films/SiliconFilmPotential.ups`, one thread",
        SUS + " --one-process --threads 1 -o {out} inputs/Films/SiliconFilmPotential.ups",
        False,
    ),
    (
        "pillar_explicit",
        "the explicit pillar example, `inputs/Pillar/PillarLithiation.ups`",
        SUS + " -o {out} inputs/Pillar/PillarLithiation.ups",
        False,
    ),
    (
        "sphere_octant",
        "the free nanosphere, `inputs/Particles/SiliconSphereOctant.ups`",
        SUS + " -o {out} inputs/Particles/SiliconSphereOctant.ups",
        False,
    ),
    (
        "pillar_array",
        "the 2x2 pillar array, `inputs/Pillar/PillarArray.ups`",
        SUS + " -o {out} inputs/Pillar/PillarArray.ups",
        False,
    ),
    (
        "fig4_quasi_static",
        "Figure 4's pillar at the real density to 28 s, its paper input (`QuasiStatic_Fig4.ups`)",
        SUS + " -o {out} inputs/Paper/QuasiStatic_Fig4.ups",
        False,
    ),
    (
        "fig4_no_hints",
        "the same without step hints (`QuasiStatic_Fig4_NoHints.ups`)",
        SUS + " -o {out} inputs/Paper/QuasiStatic_Fig4_NoHints.ups",
        False,
    ),
    (
        "cycle_quarter_quasi_static",
        "the §4.7 cycle to 80 s at the real density on a quarter of the pillar (`QuasiStatic_Cycle_LargePillar_Quarter.ups`)",
        SUS + " -o {out} inputs/Paper/QuasiStatic_Cycle_LargePillar_Quarter.ups",
        False,
    ),
    (
        "cycle_quasi_static",
        "the same on the whole pillar (`QuasiStatic_Cycle_LargePillar.ups`)",
        SUS + " -o {out} inputs/Paper/QuasiStatic_Cycle_LargePillar.ups",
        True,
    ),
    (
        "cycle_quarter_explicit",
        "the §4.7 cycle to 80 s, explicit at 2.33e24 kg/m³, on a quarter (`Cycle_LargePillar_Quarter.ups`)",
        SUS + " -o {out} inputs/Paper/Cycle_LargePillar_Quarter.ups",
        True,
    ),
    (
        "cycle_explicit",
        "the same on the whole pillar, 342,940 particles (`Cycle_LargePillar.ups`)",
        SUS + " -o {out} inputs/Paper/Cycle_LargePillar.ups",
        True,
    ),
    (
        "vibrating_bar_study",
        "`vibrating_bar_study`",
        "./build/StandAlone/vibrating_bar_study > {out}.log",
        False,
    ),
    (
        "flux_slab_study",
        "`flux_slab_study`",
        "./build/StandAlone/flux_slab_study --profile {out}.csv > {out}.log",
        False,
    ),
    (
        "flux_slab_potentiostatic",
        "`flux_slab_study --potentiostatic 10` (Bi = 10)",
        "./build/StandAlone/flux_slab_study --potentiostatic 10 --csv {out}.csv > {out}.log",
        False,
    ),
    (
        "flux_slab_surface_held",
        "`flux_slab_study --potentiostatic 1e6` (a surface held)",
        "./build/StandAlone/flux_slab_study --potentiostatic 1e6 --csv {out}.csv > {out}.log",
        True,
    ),
    (
        "vibrating_bar_implicit",
        "`vibrating_bar_study --quick --implicit 200` (implicit dynamics)",
        "./build/StandAlone/vibrating_bar_study --quick --implicit 200 > {out}.log",
        False,
    ),
    (
        "swelling_cube_flux",
        "the freely swelling cube of the evolving flux area (`SwellingCubeFlux.ups`)",
        SUS + " -o {out} inputs/Verification/SwellingCubeFlux.ups",
        False,
    ),
    (
        "neo_hookean_swelling_tests",
        "the neo-Hookean swelling tests, `test_swelling --gtest_filter='*NeoHookean*'`",
        "./build/tests/test_swelling --gtest_filter='*NeoHookean*' > {out}.log",
        False,
    ),
    (
        "lithiated_sphere_study",
        "`lithiated_sphere_study`",
        "./build/StandAlone/lithiated_sphere_study > {out}.log",
        False,
    ),
    (
        "lithiated_sphere_study_cmax_rt",
        "`lithiated_sphere_study --cmax-rt 5e-3`",
        "./build/StandAlone/lithiated_sphere_study --cmax-rt 5e-3 > {out}.log",
        False,
    ),
    (
        "stress_driven_bar_study",
        "`stress_driven_bar_study`",
        "./build/StandAlone/stress_driven_bar_study > {out}.log",
        False,
    ),
    (
        "swelling_sphere_study",
        "`swelling_sphere_study --explicit 16`",
        "./build/StandAlone/swelling_sphere_study --explicit 16 > {out}.log",
        False,
    ),
    (
        "diffusion_1d_study",
        "`diffusion_1d_study`",
        "./build/StandAlone/diffusion_1d_study > {out}.log",
        True,
    ),
    (
        "fuzz_runs",
        "the runtime fuzz, `fuzz_runs --cases 300 --seed 1`",
        "./build/tests/fuzz/fuzz_runs --cases 300 --seed 1 --work {out} > {out}.log",
        False,
    ),
    (
        "fuzz_inputs_long",
        "the input fuzz's long run, `fuzz_inputs --cases 100000`",
        "./build/tests/fuzz/fuzz_inputs --cases 100000 > {out}.log",
        True,
    ),
    (
        "quasi_static_fig4_study",
        "`quasi_static_fig4.py` (Figure 4's pillar quasi-static and explicit)",
        "/usr/bin/python3 StandAlone/Studies/quasi_static_fig4.py --runs {out}",
        False,
    ),
    (
        "quasi_static_scaling",
        "`quasi_static_scaling.py` (3 sizes)",
        "/usr/bin/python3 StandAlone/Studies/quasi_static_scaling.py --runs {out}",
        False,
    ),
    (
        "paper_quick_path",
        "the paper's figures redrawn from the carry (`reproduce_paper.py --figures-only`)",
        "/usr/bin/python3 StandAlone/Studies/reproduce_paper.py --figures-only --carry docs/paper/carry --out {out}",
        False,
    ),
    (
        "sanitizer_quick",
        "the quick sanitizer pass, `tests/run_sanitizers.sh`: its build from cold and its tests",
        "rm -rf build-asan && bash tests/run_sanitizers.sh > {out}.log",
        True,
    ),
    (
        "sanitizer_full",
        "the full sanitizer pass: its build from cold and its tests (every test but the large ones)",
        "cmake -S . -B {out} -DCMAKE_BUILD_TYPE=Release -DANODE_SANITIZE=ON && cmake --build {out} -j2"
        " && (cd {out} && ctest -j2 -LE large)",
        True,
    ),
    (
        "paper_from_scratch",
        "the paper's twenty scenarios from scratch, the sum of their runs' wall times",
        "/usr/bin/python3 StandAlone/Studies/reproduce_paper.py --jobs 2 --threads 1 --out {out}",
        True,
    ),
    (
        "quasi_static_flux_1e-8",
        "`Flux_1e-8` at the real density in quasi-static steps to 30 s (`docs/quasi-static.md`)",
        "mpirun -np 2 " + SUS + " --threads 1 -o {out} inputs/Paper/QuasiStatic_Flux_1e-8.ups",
        True,
    ),
    (
        "quasi_static_flux_1e-9",
        "`Flux_1e-9` at the real density in quasi-static steps to 100 s (`docs/quasi-static.md`)",
        "mpirun -np 2 " + SUS + " --threads 1 -o {out} inputs/Paper/QuasiStatic_Flux_1e-9.ups",
        True,
    ),
    (
        "time_to_solution",
        "Uintah's timing case (`../shared/inputs/benchmarks/Pillar3D_CPDI_diffusion.ups`) to its"
        ' maxTime, its step cap raised, 2 threads (`docs/performance.md`, "Time to solution")',
        "sed 's#<max_Timesteps>[^<]*</max_Timesteps>#<max_Timesteps>100000</max_Timesteps>#'"
        " ../shared/inputs/benchmarks/Pillar3D_CPDI_diffusion.ups > {out}.ups"
        " && OMP_WAIT_POLICY=passive " + SUS + " --threads 2 -o {out} {out}.ups",
        False,
    ),
    (
        "decompose_large_pillar",
        "the dry run of the §4.7 pillar's decomposition for 1024 ranks (`sus --decompose`)",
        SUS + " --decompose 1024 inputs/Paper/Cycle_LargePillar.ups > {out}.log",
        False,
    ),
    (
        "tests",
        "the README's test command through `.ci/run` on a fresh clone beside the repository (where"
        " CI puts it: `../shared` holds Uintah's inputs some tests run), the packages installed, no"
        " compiler cache: every build cold, as on CI",
        "rm -rf ../anode-mpm-ci && git clone -q . ../anode-mpm-ci && cd ../anode-mpm-ci"
        " && CI=true bash .ci/run > ../anode-mpm-ci.log",
        True,
    ),
]

# The paper's scenarios one at a time through the pipeline, one thread each (long).
ROWS += [
    (
        "paper_" + name,
        "the paper's scenario %s through the pipeline (`docs/paper/README.md`)" % name,
        "/usr/bin/python3 StandAlone/Studies/reproduce_paper.py --only %s --threads 1 --out {out}"
        % name,
        True,
    )
    for name in SCENARIOS
]
ROWS += [
    (
        "front_study",
        "the front study's nine runs one after another, one thread each, and its table"
        ' (`docs/paper/README.md`, "The sharp front at 1e-9 m/s")',
        "for n in Front_cause_ours Front_cause_area_particle_face Front_cause_receivers_weights"
        " Front_cause_cstar_without_source Front_cause_uintah_flux_rules Front_cause_beta_0"
        " Front_cause_beta_2.07 Front_D0_5e-18 Front_D0_2e-18; do "
        + SUS
        + " --threads 1 -o {out}/$n"
        " inputs/Paper/$n.ups > /dev/null || exit 1; done"
        " && /usr/bin/python3 StandAlone/Studies/front_causes.py --runs {out} > {out}.log",
        True,
    )
]
# Times quoted, not ours to run: no command.
ROWS += [
    (
        "uintah_paper_cycle",
        "the paper's own run of §4.7's cycle, 27,472 steps (Uintah; quoted from the paper)",
        None,
        True,
    ),
]

HEAD = """# Run times

How long each command the docs give takes: the elapsed wall time of the whole command, run from
the repository's root, on the machine and under the load of the last column (nothing else running
unless it says so). The other pages state these times only through a marker that `python3
StandAlone/Studies/run_times.py --fill` writes from this table, and the test `docs_run_times`
fails on a marked time that differs from the table and on a run time stated without its marker.
This table is written by `python3 StandAlone/Studies/run_times.py` (the rows but the long ones;
`--only NAME` for one row, `--long` for the long ones too, `--list` for the commands). The rows
`paper_NAME` are the paper's scenarios (`docs/paper/README.md`, "Run times"): the wall time of
each run's stretches summed, as the pipeline records it. A row without a command quotes a time
from elsewhere. Side-by-side comparisons (medians of interleaved runs, per-task timers) are not
run times of a command: each is stated once, on the page that makes it.
"""

MARKER = re.compile(r"<!--t:([\w.-]+)-->(.*?)<!--/t-->")
# A run time stated in words: minutes or hours, or seconds after a word that says wall time.
UNMARKED = [
    re.compile(r"\d[\d.,]*\s*(?:min|minutes|hours)\b"),
    re.compile(
        r"(?:wall|took|takes|take|run time|in about|about)\s+(?:time\s+)?(?:of\s+)?\d[\d.,]*\s*(?:s|h|ms)\b"
    ),
    re.compile(r"steps?(?:,| in| \()\s*\d[\d.,]*\s*(?:s|h)\b"),
    re.compile(r"\d[\d.,]*\s*(?:s|h) (?:of wall|on \d+ (?:cores|ranks|threads?)|on one core)"),
    re.compile(r"\d+:\d\d(?::\d\d)? elapsed"),
]


def machine():
    model, vector = "unknown processor", "AVX2"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
            if line.startswith("flags") and " avx512f" in line:
                vector = "AVX-512"
    return "%d cores of an %s with %s" % (os.cpu_count(), model, vector)


def wall_text(seconds):
    if seconds < 120:
        return "%.1f s" % seconds
    if seconds < 7200:
        return "%.1f min" % (seconds / 60)
    return "%.1f h" % (seconds / 3600)


def read_table():
    """{name: (wall time, machine)} of docs/run-times.md."""
    cells = {}
    if os.path.exists(TABLE):
        for line in open(TABLE, encoding="utf-8"):
            # cells split at the bars write_table does not escape (a command may hold "\|")
            parts = [p.strip() for p in re.split(r"(?<!\\)\|", line.strip().strip("|"))]
            if len(parts) == 5 and parts[0].startswith("`") and parts[0].endswith("`"):
                cells[parts[0].strip("`")] = (parts[3], parts[4])
    return cells


def write_table(cells):
    lines = [HEAD, "| name | what | command | wall time | machine |", "|---|---|---|---|---|"]
    for name, what, command, long_row in ROWS:
        wall, where = cells.get(name, ("not timed", ""))
        shown = (
            "`%s`" % command.format(out=os.path.join(OUT, name)).replace("|", "\\|")
            if command
            else "none: quoted"
        )
        lines.append(
            "| `%s` | %s%s | %s | %s | %s |"
            % (name, what, " (long)" if long_row else "", shown, wall, where)
        )
    with open(TABLE + ".tmp", "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(TABLE + ".tmp", TABLE)


def time_row(name, command):
    out = os.path.join(OUT, name)
    shutil.rmtree(os.path.join(ROOT, out), ignore_errors=True)
    os.makedirs(os.path.join(ROOT, OUT), exist_ok=True)
    log = os.path.join(ROOT, OUT, name + ".run.log")
    start = time.monotonic()
    with open(log, "w") as f:
        run = subprocess.run(command.format(out=out), shell=True, cwd=ROOT, stdout=f, stderr=f)
    seconds = time.monotonic() - start
    if run.returncode != 0:
        sys.exit(
            "%s: the command failed (exit code %d; its output: %s)" % (name, run.returncode, log)
        )
    return seconds


def pages():
    found = [os.path.join(ROOT, "README.md")]
    for folder in ("docs", os.path.join("docs", "paper")):
        for name in sorted(os.listdir(os.path.join(ROOT, folder))):
            if name.endswith(".md") and os.path.join(folder, name) != os.path.join(
                "docs", "run-times.md"
            ):
                found.append(os.path.join(ROOT, folder, name))
    return found


def fill(cells):
    for page in pages():
        text = open(page, encoding="utf-8").read()
        new = MARKER.sub(
            lambda m: "<!--t:%s-->%s<!--/t-->" % (m.group(1), cells[m.group(1)][0])
            if m.group(1) in cells
            else m.group(0),
            text,
        )
        if new != text:
            with open(page, "w", encoding="utf-8") as f:
                f.write(new)
            print("filled", os.path.relpath(page, ROOT))


def check(cells):
    problems = []
    for page in pages():
        text = open(page, encoding="utf-8").read()
        for number, line in enumerate(text.splitlines(), 1):
            where = "%s:%d" % (os.path.relpath(page, ROOT), number)
            for m in MARKER.finditer(line):
                if m.group(1) not in cells:
                    problems.append(
                        "%s: %s is not a row of docs/run-times.md" % (where, m.group(1))
                    )
                elif cells[m.group(1)][0] == "not timed":
                    problems.append(
                        "%s: %s is not timed yet (run_times.py --only %s)"
                        % (where, m.group(1), m.group(1))
                    )
                elif m.group(2) != cells[m.group(1)][0]:
                    problems.append(
                        "%s: %s says %s, the table %s"
                        % (where, m.group(1), m.group(2), cells[m.group(1)][0])
                    )
            bare = MARKER.sub("", line)
            for pattern in UNMARKED:
                for m in pattern.finditer(bare):
                    problems.append("%s: a run time without its marker: '%s'" % (where, m.group(0)))
    return problems


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--only", nargs="+", choices=[r[0] for r in ROWS if r[2]])
    parser.add_argument("--long", action="store_true")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--fill", action="store_true")
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    cells = read_table()
    if args.list:
        for name, what, command, long_row in ROWS:
            print("%-28s %s%s\n%28s %s" % (name, what, " (long)" if long_row else "", "", command))
        return
    if args.fill:
        fill(cells)
        return
    if args.check:
        problems = check(cells)
        for problem in problems:
            print(problem)
        print("%d pages checked, %d problems" % (len(pages()), len(problems)))
        sys.exit(1 if problems else 0)
    for name, what, command, long_row in ROWS:
        if (
            not command
            or (args.only and name not in args.only)
            or (not args.only and long_row and not args.long)
        ):
            continue
        seconds = time_row(name, command)
        cells[name] = (wall_text(seconds), machine())
        print("%-28s %s" % (name, cells[name][0]), flush=True)
        write_table(cells)
    write_table(cells)


if __name__ == "__main__":
    main()

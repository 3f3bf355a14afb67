#!/usr/bin/env python3
"""Benchmark: particle-steps per second (median of several runs), time per task, peak memory and
bytes per particle, for 1 and 2 threads, on the shared Uintah timing case (unmodified, so the
figure compares directly with Uintah's) and this repository's inputs/Benchmarks.

  python3 StandAlone/Studies/benchmark.py [--repeats N] [--steps N] [--threads 1,2] [--csv FILE] [--quick] [--sus PATH]
  python3 StandAlone/Studies/benchmark.py --scaling [--repeats N] [--steps N] [--threads 2] [--csv FILE] [--sus PATH]

Writes one CSV row per case and thread count (default benchmarks.csv in the current directory).
--scaling runs the shared timing case with 1, 8 and 27 particles per cell (<res> 1, 2, 3:
17,900 to 478,200 particles, all else unmodified) and adds the memory per extra particle (the
slope of peak memory against the particle count) to its report.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SUS = os.path.join(ROOT, "build", "StandAlone", "sus")
CASES = [
    (
        "uintah_Pillar3D_CPDI_diffusion",
        os.path.join(ROOT, "..", "shared", "inputs", "benchmarks", "Pillar3D_CPDI_diffusion.ups"),
    ),
    (
        "L_SmoothNanoPillar3D_FBC",
        os.path.join(ROOT, "..", "shared", "inputs", "uintah", "L_SmoothNanoPillar3D_FBC.ups"),
    ),
    (
        "L_SmoothNanoPillar3D_no_diffusion",
        os.path.join(ROOT, "inputs", "Benchmarks", "LargePillarNoDiffusion.ups"),
    ),
    ("CpdiBox", os.path.join(ROOT, "inputs", "Benchmarks", "CpdiBox.ups")),
    ("LinearBox", os.path.join(ROOT, "inputs", "Benchmarks", "LinearBox.ups")),
]


def run(sus, case, path, threads, steps):
    with tempfile.TemporaryDirectory() as out:
        env = dict(os.environ, OMP_WAIT_POLICY="passive")
        cmd = [sus, "--threads", str(threads), "-o", os.path.join(out, "o"), path]
        if steps:
            cmd[1:1] = ["--max-timesteps", str(steps)]
        p = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit("%s failed (%d):\n%s" % (case, p.returncode, p.stderr[-2000:]))
    text = p.stderr
    result = {
        "steps": int(re.search(r"sus: (\d+) steps", text).group(1)),
        "particles": int(re.search(r"steps, t = \S+, (\d+) particles", text).group(1)),
        "wall": float(re.search(r"wall ([\d.]+) s", text).group(1)),
        "rate": float(re.search(r"particle-steps per second: (\S+)", text).group(1)),
        "peak_MB": float(re.search(r"peak memory: ([\d.]+) MB", text).group(1)),
        "bytes_per_particle": float(re.search(r"MB, (\d+) bytes per particle", text).group(1)),
        "tasks": {
            m.group(1): float(m.group(2))
            for m in re.finditer(r"^  (\S+)\s+([\d.]+)\s+[\d.]+%$", text, re.M)
        },
    }
    return result


SHARED_CASE = CASES[0][1]


def scaling(a):
    """Cost against particle count: the shared case at <res> [1,1,1], [2,2,2], [3,3,3]."""
    text = open(SHARED_CASE).read()
    res_tag = re.compile(r"<res>\s*\[2,2,2\]\s*</res>")
    if len(res_tag.findall(text)) != 1:
        sys.exit("scaling: the shared case no longer has one <res> [2,2,2]")
    threads = int(a.threads.split(",")[-1])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for res in (1, 2, 3):
            path = os.path.join(tmp, "res%d.ups" % res)
            with open(path, "w") as f:
                f.write(res_tag.sub("<res>[%d,%d,%d]</res>" % (res, res, res), text))
            runs = [run(a.sus, "res%d" % res, path, threads, a.steps) for _ in range(a.repeats)]
            median = sorted(runs, key=lambda r: r["rate"])[len(runs) // 2]
            step_s = median["wall"] / median["steps"]
            rows.append(
                dict(
                    case="res%d" % res,
                    threads=threads,
                    particles=median["particles"],
                    steps=median["steps"],
                    repeats=a.repeats,
                    rate_median=median["rate"],
                    seconds_per_step=step_s,
                    peak_MB=median["peak_MB"],
                    bytes_per_particle=median["bytes_per_particle"],
                )
            )
            print(
                "res %d: %7d particles, %.3e particle-steps/s, %.4f s/step, peak %.1f MB (median of %d, %d threads)"
                % (
                    res,
                    median["particles"],
                    median["rate"],
                    step_s,
                    median["peak_MB"],
                    a.repeats,
                    threads,
                )
            )
            sys.stdout.flush()
    small, large = rows[0], rows[-1]
    slope = (large["peak_MB"] - small["peak_MB"]) * 1e6 / (large["particles"] - small["particles"])
    print("memory per extra particle (peak, res 1 to res 3): %.0f bytes" % slope)
    for r in rows:
        r["bytes_per_extra_particle"] = slope
    return rows


def write_csv(rows, path):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(str(r.get(k, "")) for k in keys) + "\n")
    print("wrote", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    # Uintah's L_SmoothNanoPillar3D_FBC.ups has its max_Timesteps commented out: uncapped it runs
    # to maxTime (hours). 200 is the shared timing case's own count.
    ap.add_argument(
        "--steps", type=int, default=200, help="cap on steps per run (0: as the input says)"
    )
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--csv", default="benchmarks.csv")
    ap.add_argument("--quick", action="store_true", help="1 repeat of 5 steps per case")
    ap.add_argument("--scaling", action="store_true", help="cost against particle count (3 sizes)")
    ap.add_argument("--sus", default=SUS, help="the sus to run (default: build/StandAlone/sus)")
    a = ap.parse_args()
    if a.quick:
        a.repeats, a.steps = 1, 5
    if a.scaling:
        write_csv(scaling(a), a.csv)
        return
    rows = []
    for case, path in CASES:
        if not os.path.exists(path):
            print("skipping %s: %s not found" % (case, path))
            continue
        for threads in [int(t) for t in a.threads.split(",")]:
            runs = [run(a.sus, case, path, threads, a.steps) for _ in range(a.repeats)]
            median = sorted(runs, key=lambda r: r["rate"])[len(runs) // 2]
            row = dict(
                case=case,
                threads=threads,
                particles=median["particles"],
                steps=median["steps"],
                repeats=a.repeats,
                rate_median=median["rate"],
                rate_min=min(r["rate"] for r in runs),
                rate_max=max(r["rate"] for r in runs),
                wall=median["wall"],
                peak_MB=median["peak_MB"],
                bytes_per_particle=median["bytes_per_particle"],
            )
            for task, seconds in median["tasks"].items():
                row["s_" + task] = seconds
            rows.append(row)
            print(
                "%-36s %d thread(s): %.3e particle-steps/s (median of %d; %.3e-%.3e), %d particles, "
                "%.0f bytes/particle"
                % (
                    case,
                    threads,
                    row["rate_median"],
                    a.repeats,
                    row["rate_min"],
                    row["rate_max"],
                    row["particles"],
                    row["bytes_per_particle"],
                )
            )
            sys.stdout.flush()
    write_csv(rows, a.csv)


if __name__ == "__main__":
    main()

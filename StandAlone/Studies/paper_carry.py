"""Carries the paper's runs from one machine to the next through the repository.

A working session lasts 3 hours and the next one may be on a new machine, while Density_2.33e18
needs about 13 hours on 2 cores. `reproduce_paper.py --carry DIR --pack` writes, for each run it
names, what a later session needs into DIR/NAME/ (committed with the code); `--carry DIR` then
restores DIR/NAME into the runs folder before running, and the run goes on from its checkpoint:

- input.ups, complete.json (a finished run) and NAME.wall (the wall time of every session);
- the newest checkpoint, xz-compressed (an unfinished run);
- particles.pvd and, of the outputs, only those the figures show (the one nearest each figure
  time the run has reached) and the first: a restart leaves the others out of the series;
- history.csv, xz-compressed, whole up to HISTORY_ROWS rows, else every THIN-th step and the last.

The files that stay the same from one session to the next (the outputs, a finished run) are the
same blobs in git, so each session adds only its checkpoint and history.

Figures carried without their runs: figure_carry.py.
"""
import lzma
import os
import re
import shutil
import xml.etree.ElementTree as ET

import paper_figures
import paper_numbers
import xz_files

HISTORY_ROWS = 20000
THIN = 1000


def figure_times(name, run_dir):
    """The times the figures show of run `name`."""
    return sorted(
        {
            paper_figures.panel_time(run_dir, when)
            for figure in paper_figures.FIGURES
            for run, when, _ in figure["panels"]
            if run == name
        }
    )


def frames_to_carry(name, run_dir):
    """(time, file) of the outputs to carry: the first, and the nearest to each figure time the
    run has reached."""
    outputs = paper_numbers.outputs(run_dir)
    if not outputs:
        return []
    keep = {outputs[0]}
    last = outputs[-1][0]
    for t in figure_times(name, run_dir):
        if t <= last:
            keep.add(min(outputs, key=lambda e: abs(e[0] - t)))
    return sorted(keep)


def thinned_history(path):
    with open(path) as f:
        lines = f.read().split("\n")
    header, rows = lines[0], [r for r in lines[1:] if r.strip()]
    if len(rows) > HISTORY_ROWS:
        rows = [r for r in rows[:-1] if int(r.split(",")[0]) % THIN == 0] + rows[-1:]
    return "\n".join([header] + rows) + "\n"


def write_series(path, frames, run_dir):
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    for t, file in frames:
        ET.SubElement(
            collection,
            "DataSet",
            timestep=repr(t),
            group="",
            part="0",
            file=os.path.relpath(file, run_dir),
        )
    ET.ElementTree(root).write(path, xml_declaration=True)


def newest_checkpoint(run_dir):
    """The checkpoint of the latest step, scheduled (step_N.ckpt) or sus's own (auto_step_N.ckpt)."""
    folder = os.path.join(run_dir, "checkpoints")
    found = (
        [f for f in os.listdir(folder) if re.fullmatch(r"(auto_)?step_\d+\.ckpt", f)]
        if os.path.isdir(folder)
        else []
    )
    return (
        os.path.join(folder, max(found, key=lambda f: int(re.search(r"\d+", f).group())))
        if found
        else None
    )


def pack(name, runs, carry):
    """Writes run `name` of `runs` into carry/name (anew); returns a line saying what it holds."""
    run_dir = os.path.join(runs, name)
    finished = os.path.exists(os.path.join(run_dir, "complete.json"))
    checkpoint = None if finished else newest_checkpoint(run_dir)
    if not finished and checkpoint is None:
        return None
    target = os.path.join(carry, name)
    shutil.rmtree(target, ignore_errors=True)
    os.makedirs(os.path.join(target, "particles"))
    for file in ("input.ups", "complete.json"):
        if os.path.exists(os.path.join(run_dir, file)):
            shutil.copy(os.path.join(run_dir, file), target)
    if os.path.exists(run_dir + ".wall"):
        shutil.copy(run_dir + ".wall", os.path.join(target, name + ".wall"))
    frames = frames_to_carry(name, run_dir)
    for _, file in frames:
        shutil.copy(file, os.path.join(target, "particles"))
    write_series(os.path.join(target, "particles.pvd"), frames, run_dir)
    with lzma.open(os.path.join(target, "history.csv.xz"), "wt", preset=9) as f:
        f.write(thinned_history(os.path.join(run_dir, "history.csv")))
    if checkpoint:
        os.makedirs(os.path.join(target, "checkpoints"))
        xz_files.compress(
            checkpoint,
            os.path.join(target, "checkpoints", os.path.basename(checkpoint) + ".xz"),
            preset=6,
        )
    size = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(target) for f in fs)
    state = "finished" if finished else "at " + os.path.basename(checkpoint)
    return "%s: %s, %d outputs, %.1f MB" % (name, state, len(frames), size / 1e6)


def restore(name, runs, carry):
    """Restores carry/name into runs/name when this machine has nothing of the run; returns
    whether it did."""
    source, run_dir = os.path.join(carry, name), os.path.join(runs, name)
    started = os.path.exists(os.path.join(run_dir, "complete.json")) or newest_checkpoint(run_dir)
    if not os.path.isdir(source) or started:
        return False
    shutil.rmtree(run_dir, ignore_errors=True)
    shutil.copytree(source, run_dir, ignore=shutil.ignore_patterns("*.xz", "*.wall"))
    if os.path.exists(os.path.join(source, name + ".wall")):
        shutil.copy(os.path.join(source, name + ".wall"), run_dir + ".wall")
    for folder, _, files in os.walk(source):
        for file in files:
            if file.endswith(".xz"):
                relative = os.path.relpath(os.path.join(folder, file), source)[:-3]
                os.makedirs(os.path.dirname(os.path.join(run_dir, relative)), exist_ok=True)
                xz_files.decompress(os.path.join(folder, file), os.path.join(run_dir, relative))
    return True

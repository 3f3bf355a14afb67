"""Figures carried without their runs (`reproduce_paper.py --carry DIR --pack-figures`).

DIR/figures/NAME/ holds the figure file `render_figure --visible-only` writes (the panels' colour
range and camera boxes fixed) and, per panel, the particles that colour a pixel of it
(panel_X.vtu, xz-compressed) with a one-entry .pvd: drawn again, it gives the same PNG, byte for
byte (pack_figure checks it), at a small part of the runs' size (the large pillar's panels show
about 13,000 of its 342,940 particles). definition.txt holds the figure as paper_figures.FIGURES
defined it when packed; a figure whose definition has changed since is not drawn from the carry.
Runs carried between machines: paper_carry.py.
"""
import os
import shutil
import subprocess
import tempfile

import xz_files


def figure_folder(carry, name):
    return os.path.join(carry, "figures", name)


DEFINITION = "definition.txt"


def pack_figure(render, spec, name, carry, definition):
    """Draws figure file `spec` with --visible-only, checks that what that gives draws the same
    PNG, and writes it into carry/figures/name (anew), the panels' .vtu xz-compressed, with
    `definition` (what the figure shows, without the runs' paths: restore_figure draws a carried
    figure only for the same); returns a line saying its size."""
    target = figure_folder(carry, name)
    with tempfile.TemporaryDirectory() as scratch:
        shown = os.path.join(scratch, "shown")
        pictures = [os.path.join(scratch, f) for f in ("from_runs.png", "from_shown.png")]
        subprocess.run(
            [render, "-o", pictures[0], "--visible-only", shown, spec],
            check=True,
            stdout=subprocess.DEVNULL,
        )
        subprocess.run(
            [render, "-o", pictures[1], os.path.join(shown, "figure.xml")],
            check=True,
            stdout=subprocess.DEVNULL,
        )
        with open(pictures[0], "rb") as a, open(pictures[1], "rb") as b:
            if a.read() != b.read():
                raise RuntimeError(
                    "%s: the particles its panels show do not draw the same PNG" % name
                )
        shutil.rmtree(target, ignore_errors=True)
        os.makedirs(target)
        for file in sorted(os.listdir(shown)):
            source = os.path.join(shown, file)
            if file.endswith(".vtu"):
                xz_files.compress(source, os.path.join(target, file + ".xz"), preset=9)
            else:
                shutil.copy(source, target)
        with open(os.path.join(target, DEFINITION), "w") as f:
            f.write(definition)
    size = sum(os.path.getsize(os.path.join(target, f)) for f in os.listdir(target))
    return "%s: %d panels, %.2f MB" % (
        name,
        len([f for f in os.listdir(target) if f.endswith(".vtu.xz")]),
        size / 1e6,
    )


def restore_figure(carry, name, into, definition):
    """The carried figure `name` unpacked into `into`/name; returns its figure file, or None when
    the carry holds no such figure or one of another `definition` (pack_figure)."""
    source = figure_folder(carry, name)
    if not os.path.exists(os.path.join(source, "figure.xml")):
        return None
    with open(os.path.join(source, DEFINITION)) as f:
        if f.read() != definition:
            print("%-22s the carried figure shows what an older definition did: not drawn" % name)
            return None
    target = os.path.join(into, name)
    shutil.rmtree(target, ignore_errors=True)
    os.makedirs(target)
    for file in os.listdir(source):
        if file.endswith(".xz"):
            xz_files.decompress(os.path.join(source, file), os.path.join(target, file[:-3]))
        else:
            shutil.copy(os.path.join(source, file), target)
    return os.path.join(target, "figure.xml")

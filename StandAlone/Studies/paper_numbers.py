"""The numbers of docs/paper/README.md, measured from a run's output (history.csv and the particle
.vtu files, read with VTK's XML readers: /usr/bin/python3 with python3-vtk9 and python3-numpy).

Definitions (the report repeats them). Lengths in um, times in us as the runs write them.
- Reference position X0 = p.x - p.displacement; the silicon is material 0.
- Layers of the pillar by X0_z: the base layer is the silicon's lowest particle layer, the
  quarter-height and middle layers the ones nearest a quarter and half of the height, the top
  layer its highest.
- Radial growth of a layer: (largest current radius sqrt(x^2 + y^2) of its particles) / (largest
  reference radius of its particles) - 1.
- Rings: the silicon's particles grouped by reference radius into the pillar's pie-slice rings
  (ring 0 on the axis, the last at the surface); a ring's c is the mean c of its particles in the
  middle layers (X0_z within 20% of the height around half the height).
- Front: from the innermost ring whose c is at least 0.1 (the axis ring below 0.1: an unlithiated
  core), outwards while c rises by at least 0.1 from ring to ring; "c behind the front" is the c
  of its outermost ring, where the shallow region behind it begins (the surface ring if it
  reaches it). Its width is its number of rings (each 5 nm in the small pillar).
- c by height (the cycle): the silicon's mean c in slabs 5 nm thick by X0_z from the base layer up;
  its front is found as the rings' (base for axis, top for surface).
- Height growth: (highest - lowest current z of the silicon's particles) / (the same in X0) - 1.
- Top layer's mean height growth: (mean current z of the top layer - that of the base layer) /
  (their X0_z apart) - 1: the surface's rise without the single particles that stand proud of it.
- Lithium fraction: history's total lithium (sum of m c over every material; only the silicon
  takes lithium in these runs, the substrates have D = 0 and start at c = 0) over rho V0 of the
  silicon (c = 1).
"""
import functools
import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

SILICON = 0


def outputs(run_dir):
    """(time, file) of every entry of the run's particles.pvd."""
    pvd = os.path.join(run_dir, "particles.pvd")
    entries = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    return [(float(e.get("timestep")), os.path.join(run_dir, e.get("file"))) for e in entries]


def last_output_time(run_dir):
    """The time of the run's newest output, or None before its first."""
    if not os.path.exists(os.path.join(run_dir, "particles.pvd")):
        return None
    return outputs(run_dir)[-1][0]


def read_output(run_dir, time, arrays):
    """The arrays (and "time", "points") of the output nearest to `time`, as numpy arrays: a value
    per particle, or a row per particle for an array of several components. A distributed run's
    .pvtu is read whole (its pieces in rank order)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

    t, path = min(outputs(run_dir), key=lambda e: abs(e[0] - time))
    parallel = path.endswith(".pvtu")
    reader = vtkXMLPUnstructuredGridReader() if parallel else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    data = dict(time=t, points=vtk_to_numpy(grid.GetPoints().GetData()))
    for name in arrays:
        a = grid.GetPointData().GetArray(name)
        if a is None:
            raise RuntimeError("%s holds no array %s" % (path, name))
        data[name] = vtk_to_numpy(a)
    return data


def parse_history_row(header, line):
    return dict(zip(header, map(float, line.split(","))))


def history_rows(run_dir):
    """history.csv's rows, one at a time and in time order. Read as a stream: Density_2.33e18's is
    1 GB (9.5 million steps), too large to hold as a list of rows."""
    with open(os.path.join(run_dir, "history.csv")) as f:
        header = f.readline().strip().split(",")
        for line in f:
            if line.strip():
                yield parse_history_row(header, line)


def history_row_near(run_dir, time):
    """The row whose time is nearest `time` (the earlier of two as near). Reads no further than the
    first row at or after it, and parses only the time column of the rows before."""
    with open(os.path.join(run_dir, "history.csv")) as f:
        header = f.readline().strip().split(",")
        column = header.index("time")
        before = None
        for line in f:
            if not line.strip():
                continue
            t = float(line.split(",", column + 1)[column])
            if t >= time:
                nearer = before[1] if before is not None and time - before[0] <= t - time else line
                return parse_history_row(header, nearer)
            before = (t, line)
    return None if before is None else parse_history_row(header, before[1])


def last_history_row(run_dir):
    """history.csv's last row, read from the file's end backwards until a whole line is in hand
    (None if the file holds no step)."""
    path = os.path.join(run_dir, "history.csv")
    if not os.path.exists(path):
        return None
    with open(path, "rb") as f:
        header = f.readline().decode().strip().split(",")
        end = f.seek(0, os.SEEK_END)
        tail = b""
        while end > 0 and b"\n" not in tail.strip():
            start = max(0, end - 4096)
            f.seek(start)
            tail = f.read(end - start) + tail
            end = start
    last = tail.decode().strip().split("\n")[-1]
    return None if last.split(",") == header else parse_history_row(header, last)


def input_of(run_dir):
    return ET.parse(os.path.join(run_dir, "input.ups")).getroot()


def cell_size(run_dir):
    box = input_of(run_dir).find("Grid/Level/Box")
    lower, upper, cells = (
        list(map(float, box.find(tag).text.strip(" []").split(",")))
        for tag in ("lower", "upper", "resolution")
    )
    return (upper[0] - lower[0]) / cells[0]


def silicon_capacity(run_dir):
    """rho V0 of the silicon: the lithium it holds at c = 1 (history's units)."""
    density = float(input_of(run_dir).find("MaterialProperties/MPM/material/density").text)
    data = read_output(run_dir, 0.0, ["p.volume", "material"])
    return density * data["p.volume"][data["material"] == SILICON].sum()


def lithium_fraction_time(run_dir, fraction):
    """The first time the silicon holds `fraction` of its capacity (None if never)."""
    capacity = silicon_capacity(run_dir)
    for row in history_rows(run_dir):
        if row["total_lithium"] >= fraction * capacity:
            return row["time"]
    return None


def lithium_fraction_at(run_dir, time):
    return history_row_near(run_dir, time)["total_lithium"] / silicon_capacity(run_dir)


class State:
    """The silicon (and other materials') particles of one output, with reference positions."""

    def __init__(self, run_dir, time):
        d = read_output(
            run_dir,
            time,
            [
                "p.concentration",
                "p.displacement",
                "p.plasticStrain",
                "material",
                "p.particleID",
                "p.volume",
            ],
        )
        self.time = d["time"]
        self.x = d["points"]
        self.X0 = self.x - d["p.displacement"]
        self.c = d["p.concentration"]
        self.ep = d["p.plasticStrain"]
        self.material = d["material"]
        self.id = d["p.particleID"]
        self.volume = d["p.volume"]
        self.silicon = np.flatnonzero(self.material == SILICON)
        self.layers = np.unique(np.round(self.X0[self.silicon, 2], 9))
        self.base, self.top = self.layers[0], self.layers[-1]

    def layer(self, z):
        """Silicon particles whose reference z is the layer nearest z."""
        nearest = self.layers[np.argmin(np.abs(self.layers - z))]
        return self.silicon[np.abs(self.X0[self.silicon, 2] - nearest) < 1e-7]

    def radial_growth(self, particles):
        r_now = np.hypot(self.x[particles, 0], self.x[particles, 1]).max()
        r_ref = np.hypot(self.X0[particles, 0], self.X0[particles, 1]).max()
        return r_now / r_ref - 1

    def height_growth(self):
        """(highest - lowest current z of the silicon) / (its top layer's - base layer's X0_z) - 1."""
        z = self.x[self.silicon, 2]
        return (z.max() - z.min()) / (self.top - self.base) - 1

    def top_layer_rise(self):
        """(mean current z of the top layer - that of the base layer) / (their X0_z apart) - 1."""
        mean_z = lambda particles: self.x[particles, 2].mean()
        return (mean_z(self.layer(self.top)) - mean_z(self.layer(self.base))) / (
            self.top - self.base
        ) - 1

    def rings(self):
        """(the rings' reference radii, mean c per ring) of the middle layers, axis first."""
        height = self.top - self.base
        middle = self.base + height / 2
        X0, c = self.X0[self.silicon], self.c[self.silicon]
        radius = np.round(np.hypot(X0[:, 0], X0[:, 1]), 7)
        in_middle = np.abs(X0[:, 2] - middle) <= 0.1 * height
        return np.unique(radius[in_middle]), group_means(radius[in_middle], c[in_middle])

    def ring_profile(self):
        """Mean c per ring of the middle layers, axis first."""
        return self.rings()[1]

    def height_profile(self, thickness):
        """Mean c of the silicon in slabs `thickness` thick by X0_z, from the base layer up."""
        slab = ((self.X0[self.silicon, 2] - self.base) / thickness + 1e-6).astype(int)
        return group_means(slab, self.c[self.silicon])


def group_means(keys, values):
    """The mean of `values` per key, keys in increasing order. Each group's sum is taken in the
    values' order (np.bincount adds one by one), as a loop over the particles would."""
    _, group = np.unique(keys, return_inverse=True)
    return (np.bincount(group, weights=values) / np.bincount(group)).tolist()


def front(profile, threshold=0.1, rise=0.1):
    """(first ring of the front, its width in rings, c behind it), or None without an unlithiated core.

    The front starts at the innermost ring with c >= threshold (a ring inside it below threshold)
    and goes outwards while c rises by at least `rise` from one ring to the next; c behind the
    front is that of its outermost ring, where the shallow region behind it begins.
    """
    if not profile or profile[0] >= threshold:
        return None
    first = next((k for k, c in enumerate(profile) if c >= threshold), None)
    if first is None:
        return None
    last = first
    while last + 1 < len(profile) and profile[last + 1] - profile[last] >= rise:
        last += 1
    return first, last - first + 1, profile[last]


def spread_within_cells(x, c, cell, among=None, fewest=4):
    """How far particles' c stand from their cell's: (rms of c minus the mean c of the particles
    in its grid cell (cubes of side `cell` from the origin, by current position x), over the
    particles of cells holding at least `fewest`; the same over those of `among` (a mask) of them;
    the most negative difference and the index of its particle; all None when no cell holds
    `fewest`). The grid sees only the cells' means: a particle's difference from its cell's is
    what Eq. 8's update carries unchanged."""
    cells = np.floor(np.asarray(x) / cell).astype(np.int64)
    _, group, count = np.unique(cells, axis=0, return_inverse=True, return_counts=True)
    group = group.reshape(-1)
    difference = c - (np.bincount(group, weights=c) / count)[group]
    counted = count[group] >= fewest
    if not counted.any():
        return None, None, None, None
    rms = lambda mask: float(np.sqrt(np.mean(difference[mask] ** 2))) if mask.any() else None
    chosen = counted if among is None else counted & among
    worst = int(np.argmin(np.where(counted, difference, np.inf)))
    return rms(counted), rms(chosen), float(difference[worst]), worst


def cell_spread(run_dir, time, cell, planes_within=3.0):
    """spread_within_cells of the silicon at the output nearest `time`, `among` the particles
    within `planes_within` degrees of the planes x = 0 and y = 0 (a quarter's symmetry planes), by
    reference position; with the silicon's mean c and its worst particle's ID and c."""
    s = state_of(run_dir, time)
    si = s.silicon
    angle = np.degrees(np.arctan2(s.X0[si, 1], s.X0[si, 0]))
    near = (np.abs(angle) < planes_within) | (np.abs(angle - 90) < planes_within)
    every, planes, lowest, k = spread_within_cells(s.x[si], s.c[si], cell, near)
    return dict(
        time=s.time,
        mean_c=float(s.c[si].mean()),
        rms=every,
        rms_near_planes=planes,
        lowest_difference=lowest,
        particle=int(s.id[si][k]),
        c=float(s.c[si][k]),
    )


@functools.lru_cache(maxsize=4)
def state_of(run_dir, time):
    """State(run_dir, time), each output read once for the numbers that need it."""
    return State(run_dir, time)


def pair_difference(run_a, run_b, time):
    """Largest and mean |c_a - c_b| and largest |x_a - x_b| in cells, particles matched by ID."""
    a, b = state_of(run_a, time), state_of(run_b, time)
    if not np.array_equal(np.sort(a.id), np.sort(b.id)):
        raise RuntimeError(
            "%s and %s hold different particles at t = %g: no pair to compare"
            % (run_a, run_b, time)
        )
    j = index_of(a.id, b.id)
    dc = np.abs(a.c - b.c[j])
    dxs = np.linalg.norm(a.x - b.x[j], axis=1) / cell_size(run_a)
    return dict(
        time_a=a.time,
        time_b=b.time,
        max_dc=dc.max(),
        mean_dc=dc.mean(),
        max_dx_cells=dxs.max(),
    )


def index_of(ids, among):
    """The index in `among` (IDs each there once) of each particle ID of `ids`; a KeyError for
    one not there."""
    order = np.argsort(among)
    found = order[np.searchsorted(among, ids, sorter=order).clip(max=len(among) - 1)]
    missing = among[found] != ids
    if missing.any():
        raise KeyError("particle %d is not among the particles to match" % ids[missing][0])
    return found


def shape(run_dir, time):
    """Lithium fraction, radial growth of the base, middle and top layers, height growth, plastic strain."""
    s = state_of(run_dir, time)
    base, top = s.layer(s.base), s.layer(s.top)
    lower, middle = s.layer(s.base + (s.top - s.base) / 4), s.layer((s.base + s.top) / 2)
    ep_base = s.ep[base]
    substrate = s.ep[s.material != SILICON]
    return dict(
        time=s.time,
        lithium=lithium_fraction_at(run_dir, s.time),
        base_growth=s.radial_growth(base),
        lower_growth=s.radial_growth(lower),
        middle_growth=s.radial_growth(middle),
        top_growth=s.radial_growth(top),
        height_growth=s.height_growth(),
        top_rise=s.top_layer_rise(),
        ep_base_max=ep_base.max(),
        ep_base_mean=ep_base.mean(),
        ep_max=s.ep[s.silicon].max(),
        ep_substrate_max=substrate.max() if substrate.size else None,
    )


# ---- The tables of numbers.md, one section per figure ----

CYCLE_SLAB = (
    0.005  # um: two particle layers of the large pillar (dz = 2.5 nm), as the small pillar's rings
)
# The paper's time as docs/run-times.md's row uintah_paper_cycle states it (checked there).
PAPER_CYCLE = "27,472 steps, <!--t:uintah_paper_cycle-->48.57 h<!--/t--> on 9 cores (Intel Xeon E5-2667, 2.9 GHz)"


def percent(v):
    return "—" if v is None else "%.1f%%" % (100 * v)


def num(v, digits=3):
    return "—" if v is None else "%.*g" % (digits, v)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def runs_table(runs, finished):
    rows = []
    for name in finished:
        with open(os.path.join(runs, name, "complete.json")) as f:
            s = json.load(f)
        rows.append(
            [
                name,
                s["particles"],
                s["steps"],
                "%.4g" % s["time"],
                s["threads"]
                if s.get("ranks", 1) == 1
                else "%d x %d ranks" % (s["threads"], s["ranks"]),
                s.get("stopped") or "its maxTime",
            ]
        )
    return table(
        [
            "scenario",
            "particles",
            "steps",
            "simulated time (us)",
            "threads",
            "ended at",
        ],
        rows,
    )


def density_section(runs, pair, times, unit_scale, unit, finished):
    """The pair at each figure time both runs have reached: a run still going (days for
    Density_2.33e18) is compared up to its last output, and the times after it wait."""
    reached = {run: last_output_time(os.path.join(runs, run)) for run in pair}
    rows, waiting = [], []
    for t in times:
        if any(reached[run] < t for run in pair):
            waiting.append("%g %s" % (t * unit_scale, unit))
            continue
        d = pair_difference(os.path.join(runs, pair[0]), os.path.join(runs, pair[1]), t)
        a, b = (shape(os.path.join(runs, run), t) for run in pair)
        rows.append(
            [
                "%g %s" % (t * unit_scale, unit),
                "%.4g / %.4g" % (d["time_a"] * unit_scale, d["time_b"] * unit_scale),
                num(d["max_dc"]),
                num(d["mean_dc"]),
                num(d["max_dx_cells"]),
                "%s / %s" % (percent(a["height_growth"]), percent(b["height_growth"])),
                "%s / %s" % (percent(a["top_rise"]), percent(b["top_rise"])),
                "%s / %s" % (percent(a["top_growth"]), percent(b["top_growth"])),
                "%s / %s" % (num(a["ep_max"]), num(b["ep_max"])),
            ]
        )
    text = (
        (
            "a = %s, b = %s.\n\n" % pair
            + table(
                [
                    "figure time",
                    "output times (%s)" % unit,
                    "largest abs(c difference)",
                    "mean abs(c difference)",
                    "largest position difference (cells)",
                    "height growth a / b",
                    "top layer's mean height growth a / b",
                    "top layer's radial growth a / b",
                    "largest plastic strain (silicon) a / b",
                ],
                rows,
            )
        )
        if rows
        else ""
    )
    going = [
        "%s (last output at %.4g %s)" % (run, reached[run] * unit_scale, unit)
        for run in pair
        if run not in finished
    ]
    if going:
        text += "%sStill running: %s; waiting: %s." % (
            "\n\n" if rows else "",
            ", ".join(going),
            ", ".join(waiting) or "nothing",
        )
    return text


def shape_section(runs, panels, time_of, scale, unit):
    rows = []
    for run, when, label in panels:
        s = shape(os.path.join(runs, run), time_of(run, when))
        rows.append(
            [
                label,
                "%.3g" % (s["time"] * scale),
                percent(s["lithium"]),
                percent(s["base_growth"]),
                percent(s["lower_growth"]),
                percent(s["middle_growth"]),
                percent(s["top_growth"]),
                percent(s["height_growth"]),
                num(s["ep_base_max"]),
                num(s["ep_base_mean"]),
                num(s["ep_max"]),
                num(s["ep_substrate_max"]),
            ]
        )
    return table(
        [
            "run",
            "t (%s)" % unit,
            "lithium",
            "base radial growth",
            "quarter-height radial growth",
            "middle radial growth",
            "top radial growth",
            "height growth",
            "max plastic strain, base layer",
            "mean, base layer",
            "max, silicon",
            "max, substrate",
        ],
        rows,
    )


# §4.4: "c behind the sharp front is 0.5-0.6 at a flux of 1e-9 m/s and above 0.7 at 1e-8".
PAPER_BEHIND_FRONT = {"Flux_1e-9": "0.5-0.6", "Flux_1e-8": "> 0.7"}


def front_section(runs, panels, time_of, scale, unit):
    rows, behind = [], {}
    for run, when, label in panels:
        run_dir = os.path.join(runs, run)
        s = State(run_dir, time_of(run, when))
        profile = s.ring_profile()
        f = front(profile)
        if f is not None:
            behind.setdefault((run, label), []).append(f[2])
        else:
            behind.setdefault((run, label), [])
        rows.append(
            [
                label,
                "%.3g" % (s.time * scale),
                percent(lithium_fraction_at(run_dir, s.time)),
                " ".join("%.2f" % c for c in profile),
                "none" if f is None else "rings %d-%d" % (f[0], f[0] + f[1] - 1),
                "—" if f is None else "%.3f" % f[2],
            ]
        )
    summary = [
        [
            label,
            "none" if not values else "%.2f-%.2f" % (min(values), max(values)),
            "%d of %d" % (len(values), sum(1 for p in panels if p[0] == run)),
            PAPER_BEHIND_FRONT.get(run, "—"),
        ]
        for (run, label), values in behind.items()
    ]
    return (
        table(
            [
                "run",
                "t (%s)" % unit,
                "lithium",
                "ring c, axis to surface (middle layers)",
                "front",
                "c behind the front",
            ],
            rows,
        )
        + "\n\n"
        + table(
            ["run", "c behind the front (ours)", "panels with a front", "the paper (4.4)"], summary
        )
    )


def cycle_section(runs, panels, scale, unit):
    """Of the cycle the panels show (one run): lithium in and out, and the silicon's c, J (its
    volume over its volume at t = 0, matched by particle ID) and plastic strain at the outputs
    nearest the most lithium and the end; c by height at each panel's time after t = 0."""
    run_dir = os.path.join(runs, panels[0][0])
    history = list(history_rows(run_dir))
    capacity = silicon_capacity(run_dir)
    state = functools.lru_cache(maxsize=None)(lambda t: State(run_dir, t))  # each output read once
    start = state(0.0)
    initial_volume = start.volume[start.silicon]
    peak, end = max(history, key=lambda h: h["total_lithium"]), history[-1]
    rows = []
    for t in (peak["time"], end["time"]):
        s = state(t)
        r = min(history, key=lambda h: abs(h["time"] - s.time))
        c = s.c[s.silicon]
        J = s.volume[s.silicon] / initial_volume[index_of(s.id[s.silicon], start.id[start.silicon])]
        pillar = s.ep[s.silicon]
        substrate = s.ep[s.material != SILICON]
        rows.append(
            [
                "%.4g" % (s.time * scale),
                int(r["step"]),
                percent(r["total_lithium"] / capacity),
                "%.4f - %.4f" % (c.min(), c.max()),
                "%.4f - %.4f" % (J.min(), J.max()),
                "%.3g / %.3g" % (pillar.max(), pillar.mean()),
                "%.3g / %.3g" % (substrate.max(), substrate.mean()) if substrate.size else "—",
            ]
        )
    profiles = []
    for t in sorted({when for _, when, _ in panels if when > 0}):
        s = state(t)
        profile = s.height_profile(CYCLE_SLAB)
        f = front(profile)
        profiles.append(
            [
                "%.4g" % (s.time * scale),
                percent(lithium_fraction_at(run_dir, s.time)),
                " ".join("%.2f" % c for c in profile),
                "none" if f is None else "slabs %d-%d" % (f[0], f[0] + f[1] - 1),
                "—" if f is None else "%.3f" % f[2],
                "%.2f" % (max(profile) - min(profile)),
            ]
        )
    held, out = (
        peak["total_lithium"] / capacity,
        (peak["total_lithium"] - end["total_lithium"]) / capacity,
    )
    return (
        table(
            [
                "t (%s)" % unit,
                "step",
                "lithium",
                "silicon c range",
                "silicon J range",
                "plastic strain max / mean, pillar",
                "max / mean, substrate",
            ],
            rows,
        )
        + (
            "\n\nLithium in: %s of the capacity by t = %.4g %s (the most the run holds). Out: %s of the capacity "
            "by t = %.4g %s, %s of what went in. The paper's run: %s."
            % (
                percent(held),
                peak["time"] * scale,
                unit,
                percent(out),
                end["time"] * scale,
                unit,
                percent(out / held) if held > 0 else "—",
                PAPER_CYCLE,
            )
        )
        + (
            "\n\nc by height: the mean c of the silicon in slabs %g nm thick by X0_z, base to top (the flux enters "
            "through the top and the side), with the front found as for Figs. 6-7 and the spread (largest - smallest "
            "slab c):\n\n" % (CYCLE_SLAB * 1e3)
        )
        + table(
            [
                "t (%s)" % unit,
                "lithium",
                "slab c, base to top",
                "front",
                "c behind the front",
                "spread",
            ],
            profiles,
        )
    )


def write_numbers(path, runs, finished, figures, time_of):
    """numbers.md: the runs, then each figure's numbers (sections whose runs are not done say so)."""
    out = [
        "# Numbers of the paper's figures, measured from the runs",
        "",
        "Written by `StandAlone/Studies/reproduce_paper.py`; definitions in `paper_numbers.py` and "
        "`docs/paper/README.md`; the runs' wall times in `docs/run-times.md` (`paper_NAME`).",
        "",
        "## Runs",
        "",
        runs_table(runs, finished),
    ]
    sections = {
        "density": lambda f, scale, unit: density_section(
            runs, f["pair"], sorted({w for _, w, _ in f["panels"]}), scale, unit, finished
        ),
        "shape": lambda f, scale, unit: shape_section(runs, f["panels"], time_of, scale, unit),
        "front": lambda f, scale, unit: front_section(runs, f["panels"], time_of, scale, unit),
        "front and shape": lambda f, scale, unit: front_section(
            runs, f["panels"], time_of, scale, unit
        )
        + "\n\n"
        + shape_section(runs, f["panels"], time_of, scale, unit),
        "cycle": lambda f, scale, unit: cycle_section(runs, f["panels"], scale, unit),
    }
    for figure in figures:
        if figure["measure"] is None:  # drawn to show what another figure's numbers measure
            continue
        out += ["", "## " + figure["title"], ""]
        missing = sorted({run for run, _, _ in figure["panels"]} - set(finished))
        if figure["measure"] == "density":  # compared as far as both runs have gone
            missing = [
                run
                for run in missing
                if not os.path.exists(os.path.join(runs, run, "particles.pvd"))
            ]
        if missing:
            out.append(NOT_MEASURED + ", ".join(missing) + ".")
            continue
        out.append(sections[figure["measure"]](figure, figure["time_scale"], figure["time_unit"]))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


NOT_MEASURED = "Not measured yet: waiting for "


def sections(text):
    """numbers.md as [(heading, body)], the heading "" for what comes before the first one."""
    parts, heading, body = [], "", []
    for line in text.split("\n"):
        if line.startswith("## "):
            parts.append((heading, body))
            heading, body = line, []
        else:
            body.append(line)
    parts.append((heading, body))
    return parts


def merge_numbers(old, new):
    """numbers.md for a report that already has one: a section this machine could not measure
    (its runs are not here: an earlier machine's) keeps its earlier numbers, and the runs table
    keeps the rows of runs not here, in the earlier order, followed by the new ones."""
    earlier = dict(sections(old))
    merged = []
    for heading, body in sections(new):
        before = earlier.get(heading)
        if heading == "## Runs" and before:
            rows = lambda b: [l for l in b if l.startswith("| ") and not l.startswith("| scenario")]
            name = lambda row: row.split("|")[1].strip()
            fresh = {name(r): r for r in rows(body)}
            kept = [fresh.pop(name(r), r) for r in rows(before)]
            head = [l for l in body if l.startswith("| scenario") or l.startswith("|---")]
            body = [""] + head + kept + list(fresh.values()) + [""]
        elif (
            before
            and any(l.startswith(NOT_MEASURED) for l in body)
            and not any(l.startswith(NOT_MEASURED) for l in before)
        ):
            body = before
        merged.append("\n".join(([heading] if heading else []) + body))
    return "\n".join(merged)


if __name__ == "__main__":
    # python3 paper_numbers.py spread RUN_DIR TIME CELL: cell_spread of one output
    # (docs/paper/README.md, "Figure 10": the stop of the real-density full cycle).
    if len(sys.argv) != 5 or sys.argv[1] != "spread":
        sys.exit("usage: paper_numbers.py spread RUN_DIR TIME CELL (time in us, cell in um)")
    print(json.dumps(cell_spread(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))))

"""The paper's Figures 3-10 (and one of ours, fig6_D0): which runs, times and view each shows,
drawn with render_figure, and which numbers measure it (paper_numbers.write_numbers).

A panel's time is either a simulation time (us) or a state of its run found in its history.csv:
("lithium", f) is the first time the silicon holds the fraction f of its capacity (rho V0, c = 1),
("end",) its last output. Each figure is written as DIR/figures/figN.xml and drawn to figN.png.
"""
import json
import os
import subprocess

import figure_carry
import paper_numbers

# Cut-away views (the half y < 0 removed) with a fixed camera per figure, so swelling shows.
SMALL_VIEW = dict(position="[0.37, -0.463, 0.433]", focal_point="[0, 0, 0.1]", size="[480, 480]")
LARGE_VIEW = dict(position="[0.68, -0.85, 0.62]", focal_point="[0, 0, 0.03]", size="[640, 400]")

MID, FULL = ("lithium", 0.5), ("end",)

# What colours the particles: scene tags (docs/input-reference.md); a figure's "colour" replaces some.
CONCENTRATION = dict(
    field="p.concentration",
    scale=None,
    range="[0, 1]",
    colormap=None,
    units="c / c_max",
    field_name="lithium concentration",
)
# The code's stress is in kPa (um, us, pg): drawn in GPa.
VON_MISES = dict(
    field="p.stress:von_mises",
    scale="1e-6",
    range="data",
    colormap="blue_red",
    units="GPa",
    field_name="von Mises stress",
)
PLASTIC_STRAIN = dict(
    field="p.plasticStrain",
    range="data",
    colormap="blue_red",
    units=None,
    field_name="plastic strain",
)


def full_cycle_figure(name, run, title):
    """Figure 10's full cycle of `run`: the silicon at 0-130 s (in) and 150-260 s (out)."""
    return dict(
        name=name,
        measure="cycle",
        view=LARGE_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        colour=dict(materials="[0]"),
        title=title,
        panels=[(run, t * 1e6, "") for t in (0, 30, 60, 90, 130, 150, 180, 200, 230, 260)],
    )


FIGURES = [
    dict(
        name="fig3",
        measure="density",
        pair=("Density_2.33e3", "Density_2.33e8"),
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e3,
        time_unit="ns",
        title="Fig. 3 (4.2): density 2.33e3 (a, c, e) and 2.33e8 kg/m^3 (b, d, f), D0 = 1e-10 m^2/s",
        panels=[
            (run, t, label)
            for t in (6e-3, 26e-3, 48e-3)
            for run, label in (
                ("Density_2.33e3", "2.33e3 kg/m^3"),
                ("Density_2.33e8", "2.33e8 kg/m^3"),
            )
        ],
    ),
    dict(
        name="fig4",
        measure="density",
        pair=("Density_2.33e18", "Density_2.33e24"),
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 4 (4.2): density 2.33e18 (a, c, e) and 2.33e24 kg/m^3 (b, d, f), D0 = 1e-17 m^2/s",
        panels=[
            (run, t, label)
            for t in (4e6, 16e6, 28e6)
            for run, label in (
                ("Density_2.33e18", "2.33e18 kg/m^3"),
                ("Density_2.33e24", "2.33e24 kg/m^3"),
            )
        ],
    ),
    dict(
        name="fig5",
        measure="shape",
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 5 (4.3): half (a, c, e) and full lithiation (b, d, f); elastic (a, b), "
        "perfectly plastic (c, d), linear hardening (e, f)",
        panels=[
            (run, when, label)
            for run, label in (
                ("Constitutive_elastic", "elastic"),
                ("Constitutive_perfect", "perfect plasticity"),
                ("Constitutive_hardening", "linear hardening"),
            )
            for when in (MID, FULL)
        ],
    ),
    dict(
        name="fig5_plastic_strain",
        measure=None,
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        colour=PLASTIC_STRAIN,
        title="Fig. 5 as plastic strain: where each model yields at half (a, c, e) and full "
        "lithiation (b, d, f)",
        panels=[
            (run, when, label)
            for run, label in (
                ("Constitutive_elastic", "elastic"),
                ("Constitutive_perfect", "perfect plasticity"),
                ("Constitutive_hardening", "linear hardening"),
            )
            for when in (MID, FULL)
        ],
    ),
    dict(
        name="fig6",
        measure="front",
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 6 (4.4): lithiation under a flux of 1e-9 m/s (a, c, e, g) and 1e-8 m/s "
        "(b, d, f, h) at 15, 30, 45 and 60% of the capacity",
        panels=[
            (run, ("lithium", f), label)
            for f in (0.15, 0.3, 0.45, 0.6)
            for run, label in (("Flux_1e-9", "1e-9 m/s"), ("Flux_1e-8", "1e-8 m/s"))
        ],
    ),
    dict(
        name="fig6_D0",
        measure="front",
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Ours, not the paper's: flux 1e-9 m/s with D0 = 1e-17 (a, b), 5e-18 (c, d) and "
        "2e-18 m^2/s (e, f) at 15% (a, c, e) and 30% lithium (b, d, f)",
        panels=[
            (run, ("lithium", f), label)
            for run, label in (
                ("Flux_1e-9", "D0 = 1e-17"),
                ("Front_D0_5e-18", "D0 = 5e-18"),
                ("Front_D0_2e-18", "D0 = 2e-18"),
            )
            for f in (0.15, 0.3)
        ],
    ),
    dict(
        name="fig7",
        measure="front and shape",
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 7 (4.4): the end of lithiation, flux 1e-9 m/s (a) and 1e-8 m/s (b)",
        panels=[("Flux_1e-9", FULL, "1e-9 m/s"), ("Flux_1e-8", FULL, "1e-8 m/s")],
    ),
    dict(
        name="fig8",
        measure="front and shape",
        view=SMALL_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 8 (4.5): alpha = 6 with beta = 0 (a, c) and beta = 1 (b, d): half and full lithiation",
        panels=[
            (run, when, label)
            for when in (MID, FULL)
            for run, label in (("Beta_0", "beta = 0"), ("Beta_1", "beta = 1"))
        ],
    ),
    dict(
        name="fig9",
        measure="shape",
        view=LARGE_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 9 (4.6): fixed base (a, c) and deformable substrate (b, d): half and full lithiation",
        panels=[
            (run, when, label)
            for when in (MID, FULL)
            for run, label in (
                ("Substrate_fixed", "fixed base"),
                ("Substrate_deformable", "substrate"),
            )
        ],
    ),
    dict(
        name="fig9_von_mises",
        measure=None,
        view=LARGE_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        colour=VON_MISES,
        title="Fig. 9 as von Mises stress: fixed base (a, c) and deformable substrate (b, d)",
        panels=[
            (run, when, label)
            for when in (MID, FULL)
            for run, label in (
                ("Substrate_fixed", "fixed base"),
                ("Substrate_deformable", "substrate"),
            )
        ],
    ),
    full_cycle_figure(
        "fig10",
        "FullCycle_LargePillar_Quarter",
        "Fig. 10 (4.7): the large pillar's full cycle (a quarter), explicit at 2.33e24 kg/m^3, "
        "in to 130 s (a-e), out to 260 s (f-j); silicon only",
    ),
    dict(
        name="fig10_plastic_strain",
        measure=None,
        view=LARGE_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        colour=PLASTIC_STRAIN,
        title="Fig. 10 as plastic strain (a quarter): the pillar and its substrate before, lithiated "
        "and after",
        panels=[
            ("FullCycle_LargePillar_Quarter", t * 1e6, label)
            for t, label in ((0, "before"), (130, "lithiated"), (260, "after the cycle"))
        ],
    ),
    full_cycle_figure(
        "fig10_real_density",
        "QuasiStatic_FullCycle_LargePillar_Quarter",
        "Fig. 10 (4.7): the large pillar's full cycle (a quarter) at 2.33e3 kg/m^3, in to 130 s "
        "(a-e), out to 260 s (f-j); silicon only",
    ),
    dict(
        name="fig10_partial",
        measure="cycle",
        view=LARGE_VIEW,
        columns=2,
        time_scale=1e-6,
        time_unit="s",
        title="Fig. 10 in part: in for 40 s, out to 80 s, explicit at 2.33e24 kg/m^3",
        panels=[("Cycle_LargePillar", t * 1e6, "") for t in (0, 8, 16, 24, 32, 40, 48, 60, 72, 80)],
    ),
]


def panel_time(run_dir, when):
    """The simulation time a panel asks for (the figure shows the output nearest to it). A run
    that never holds the asked fraction of lithium shows its end; the panel's label has its time
    and numbers.md its lithium."""
    if isinstance(when, tuple) and when[0] == "lithium":
        t = paper_numbers.lithium_fraction_time(run_dir, when[1])
        return t if t is not None else paper_numbers.last_history_row(run_dir)["time"]
    if isinstance(when, tuple) and when[0] == "end":
        return paper_numbers.last_history_row(run_dir)["time"]
    return when


def figure_xml(figure, runs):
    v = figure["view"]
    lines = [
        "<figure>",
        "  <title>%s</title>" % figure["title"],
        "  <columns>%d</columns>" % figure["columns"],
        "  <time_scale>%g</time_scale>" % figure["time_scale"],
        "  <time_unit>%s</time_unit>" % figure["time_unit"],
        "  <scene>",
    ]
    colour = dict(CONCENTRATION, **figure.get("colour", {}))
    lines += [
        "    <%s>%s</%s>" % (tag, value, tag) for tag, value in colour.items() if value is not None
    ]
    lines += [
        "    <clip><point>[0, 0, 0]</point><normal>[0, -1, 0]</normal></clip>",
        "    <camera><position>%s</position><focal_point>%s</focal_point></camera>"
        % (v["position"], v["focal_point"]),
        "    <size>%s</size>" % v["size"],
        "    <scale_bar>um</scale_bar>",
        "  </scene>",
    ]
    for run, when, label in figure["panels"]:
        run_dir = os.path.join(runs, run)
        lines.append(
            "  <panel><data>%s</data><time>%.9g</time><label>%s</label></panel>"
            % (os.path.join(run_dir, "particles.pvd"), panel_time(run_dir, when), label)
        )
    lines.append("</figure>")
    return "\n".join(lines) + "\n"


def definition(figure):
    """What a figure shows as FIGURES says it (runs, panel times or states, view, colours, title),
    in one line of text (figure_carry keeps it with a carried figure)."""
    return json.dumps(figure, sort_keys=True) + "\n"


def panels_reached(figure, runs, finished):
    """The panels of `figure` that can be drawn now, in whole rows, and the runs still going. Once
    its runs have finished: all of them. Before, for rows at fixed times (Fig. 4 waits days for
    Density_2.33e18): the rows up to the last time every run has written an output for."""
    going = sorted({run for run, _, _ in figure["panels"]} - set(finished))
    if not going:
        return figure["panels"], going

    def reached(run, when):
        if run in finished:
            return True
        last = paper_numbers.last_output_time(os.path.join(runs, run))
        return isinstance(when, (int, float)) and last is not None and last >= when

    columns, panels = figure["columns"], []
    for first in range(0, len(figure["panels"]), columns):
        row = figure["panels"][first : first + columns]
        if not all(reached(run, when) for run, when, _ in row):
            break
        panels += row
    return panels, going


def make_all(args, runs, finished):
    """Draws every figure whose runs have finished (with --pack-figures, carrying what its panels
    show), else from the carry (--carry) when it holds the figure, else the rows its runs still
    going have reached; writes numbers.md; returns the files."""
    out = os.path.join(args.out, "figures")
    os.makedirs(out, exist_ok=True)
    made = []
    for figure in FIGURES:
        name = figure["name"]
        panels, going = panels_reached(figure, runs, finished)
        png = os.path.join(out, name + ".png")
        carried = (
            figure_carry.restore_figure(
                args.carry, name, os.path.join(out, "carried"), definition(figure)
            )
            if going and args.carry and not args.quick
            else None
        )
        if carried:
            subprocess.run([args.render, "-o", png, carried], check=True, stdout=subprocess.DEVNULL)
            print("%-22s %s (from %s)" % (name, png, figure_carry.figure_folder(args.carry, name)))
            made.append(png)
            continue
        if not panels:
            print("%-22s not drawn: waiting for %s" % (name, ", ".join(going)), flush=True)
            continue
        if going:
            rows, all_rows = (
                len(panels) // figure["columns"],
                len(figure["panels"]) // figure["columns"],
            )
            figure = dict(
                figure,
                panels=panels,
                title="%s; so far %d of %d rows (%s still running)"
                % (figure["title"], rows, all_rows, ", ".join(going)),
            )
        spec = os.path.join(out, name + ".xml")
        with open(spec, "w") as f:
            f.write(figure_xml(figure, runs))
        subprocess.run([args.render, "-o", png, spec], check=True, stdout=subprocess.DEVNULL)
        print("%-22s %s" % (name, png), flush=True)
        made.append(png)
        if args.pack_figures and not going:
            packed = figure_carry.pack_figure(
                args.render, spec, name, args.carry, definition(figure)
            )
            print("packed " + packed, flush=True)
    numbers = os.path.join(args.out, "numbers.md")
    paper_numbers.write_numbers(
        numbers,
        runs,
        finished,
        FIGURES,
        lambda run, when: panel_time(os.path.join(runs, run), when),
    )
    print("%-22s %s" % ("numbers", numbers), flush=True)
    return made + [numbers]

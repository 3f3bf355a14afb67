#!/usr/bin/env python3
"""Writes the paper's scenarios (Gritton et al. §4.2-4.7) as inputs/Paper/*.ups.

One description per scenario below; every file states its paper section, parameters and what the
paper does not give (chosen here). Units: um, us, pg (1 GPa = 1e6, 1 kg/m^3 = 1e-3 pg/um^3,
1 m^2/s = 1e6 um^2/us, a flux of 1 m/s = 1 um/us). Run: python3 StandAlone/Studies/make_paper_inputs.py
"""
import os

from ups_blocks import (
    GPA,
    SILICON,
    SUBSTRATE,
    data_archiver,
    flow_model,
    max_timesteps,
    non_linear1_diffusion,
    scalar_flux,
    substrate_material,
)

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "inputs", "Paper")

SMALL = dict(
    radius=0.05,
    height=0.1,
    dx=0.005,
    num_radial=10,
    num_axial=20,
    num_angular=64,
    lateral=0.15,
    top=0.3,
)
LARGE = dict(
    radius=0.25,
    height=0.05,
    dx=0.01,
    num_radial=100,
    num_axial=20,
    num_angular=580,
    lateral=0.5,
    top=0.2,
)


def time_points(points, value_tag):
    return "".join(
        "<time_point><time>%g</time><%s>%s</%s></time_point>" % (t, value_tag, v, value_tag)
        for t, v in points
    )


def scenario(s):
    p = s["pillar"]
    dx = p["dx"]
    # A quarter of the pillar and its substrate (x, y >= 0), the planes x = 0 and y = 0 symmetric.
    quarter = s.get("quarter", False)
    base = s.get("substrate_height", 0.0)
    dr = p["radius"] / p["num_radial"]
    dz = p["height"] / p["num_axial"]
    tol = 0.9 * dx  # Uintah's selection tolerance for smooth pieces (spacing dx/res, res 1)
    # Flux BC geometry chosen so exactly the outer ring and the top layer are selected.
    side_radius = p["radius"] - dr / 2 + tol - dr / 2
    top_bottom = base + p["height"] - dz / 2 + tol - dz / 2
    lithiation_end = s.get("lithiation_end")
    J = s["flux"]
    if lithiation_end:
        load = [(0, J), (lithiation_end, J), (lithiation_end * 1.0001, -J), (1e12, -J)]
    else:
        load = [(0, J), (1e12, J)]
    diff_curve = ""
    if lithiation_end:
        diff_curve = "\n          <diff_curve>%s</diff_curve>" % time_points(
            [(0, "in"), (lithiation_end, "out"), (1e12, "out")], "flux_direction"
        )
    diffusion = non_linear1_diffusion(
        s["D0"], s.get("alpha", 6.0), s.get("beta", 0.5), s.get("pmax", 3.0), diff_curve
    )
    density = s["density"] * 1e-3
    pillar = """      <material name="silicon">
        <density>%g</density>
        <constitutive_model type="rf_elastic_plastic">
          <bulk_modulus>%g</bulk_modulus>
          <shear_modulus>%g</shear_modulus>
          <volume_expansion_coeff>0.56</volume_expansion_coeff>
          <equation_of_state type="default_hypo"/>
          %s
        </constitutive_model>
        %s
        <geom_object>
          <smoothcyl label="pillar">
            <discretization_scheme>pie_slices</discretization_scheme>
            <bottom>[0.0, 0.0, %g]</bottom>
            <top>[0.0, 0.0, %g]</top>
            <outer_radius>%g</outer_radius>
            <num_radial>%d</num_radial>
            <num_axial>%d</num_axial>
            <num_angular>%d</num_angular>%s
          </smoothcyl>
          <res>[1,1,1]</res>
          <velocity>[0.0, 0.0, 0.0]</velocity>
          <concentration>0</concentration>
        </geom_object>
      </material>""" % (
        density,
        SILICON["K"] * GPA,
        SILICON["G"] * GPA,
        flow_model(s["model"], SILICON),
        diffusion,
        base,
        base + p["height"],
        p["radius"],
        p["num_radial"],
        p["num_axial"],
        p["num_angular"] // 4 if quarter else p["num_angular"],
        (
            "\n            <arc_start_angle>0</arc_start_angle>\n            <arc_angle>90</arc_angle>"
            if quarter
            else ""
        ),
    )
    substrate = ""
    contact = "<contact><type>null</type></contact>"
    if base > 0:
        w = s["substrate_width"]
        substrate = substrate_material(
            density,
            flow_model("hardening", SUBSTRATE),
            '<box label="substrate">\n            <min>[%g, %g, 0.0]</min>\n'
            "            <max>[%g, %g, %g]</max>\n          </box>"
            % (0 if quarter else -w / 2, 0 if quarter else -w / 2, w / 2, w / 2, base),
            "[2,2,2]",
        )
        contact = "<contact><type>single_velocity</type><materials>[0,1]</materials></contact>"
    L = p["lateral"]
    lateral_cells = int(round((1 if quarter else 2) * L / dx))
    cells = [lateral_cells, lateral_cells, int(round(p["top"] / dx))]
    flux_blocks = ""
    for i, (name, piece) in enumerate(
        [
            (
                "side",
                '<cylinder label="side"><bottom>[0.0,0.0,%g]</bottom><top>[0.0,0.0,%g]</top>'
                "<radius>%g</radius></cylinder>" % (base, base + p["height"], side_radius),
            ),
            (
                "top",
                '<cylinder label="top"><bottom>[0.0,0.0,%g]</bottom><top>[0.0,0.0,%g]</top>'
                "<radius>%g</radius><cylinder_end>true</cylinder_end></cylinder>"
                % (top_bottom, top_bottom + dz, p["radius"]),
            ),
        ]
    ):
        flux_blocks += scalar_flux(i + 1, piece, time_points(load, "load"), s.get("flux_extra", ""))
    archiver = data_archiver(
        s["name"],
        s.get("output", s["maxTime"] / 50),
        [
            "p.x",
            "p.particleID",
            "p.volume",
            "p.concentration",
            "p.diffusivity",
            "p.stress",
            "p.plasticStrain",
            "p.displacement",
        ],
        '    <checkpoint cycle="2" interval="%g"/>\n' % (s["maxTime"] / 40),
    )
    implicit = s.get("implicit", False)
    text = """<?xml version='1.0' encoding='ISO-8859-1' ?>
<!--
  %s (Gritton et al. %s)
%s
  Units: um, us, pg (1 GPa = 1e6; density in pg/um^3 = 1e-3 kg/m^3; D in um^2/us = 1e-6 m^2/s;
  flux in um/us = m/s). Written by StandAlone/Studies/make_paper_inputs.py; edit the script, not this file.
-->
<Uintah_specification>
  <Meta><title>%s</title></Meta>
  <SimulationComponent type="%s"/>
  <Time>
    <maxTime>%g</maxTime>
    <initTime>0.0</initTime>
    <delt_min>1.0e-16</delt_min>
    <delt_max>%s</delt_max>
    <timestep_multiplier>%g</timestep_multiplier>%s
  </Time>
%s
  <MPM>
    <interpolator>cpdi</interpolator>%s%s
    <do_scalar_diffusion>true</do_scalar_diffusion>
    <use_load_curves>true</use_load_curves>
  </MPM>
  <AMR><useLockStep>true</useLockStep><MPM/></AMR>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties>
    <MPM>
%s%s
      %s
      <diffusion_interface><type>null</type></diffusion_interface>
    </MPM>
  </MaterialProperties>
  <PhysicalBC>
    <MPM>%s
    </MPM>
  </PhysicalBC>
  <Grid>
    <Level>
      <Box label="1">
        <lower>[%g, %g, 0.0]</lower>
        <upper>[%g, %g, %g]</upper>
        <resolution>[%d, %d, %d]</resolution>
        <extraCells>[1,1,1]</extraCells>
      </Box>
    </Level>
    <BoundaryConditions>
      <Face side="x-"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="x+"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="y-"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="y+"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
      <Face side="z-">
        <BCType id="all" label="Symmetric" var="symmetry"/>
        <BCType id="all" label="Velocity" var="Dirichlet"><value>[0.0, 0.0, 0.0]</value></BCType>
      </Face>
      <Face side="z+"><BCType id="all" label="Symmetric" var="symmetry"/></Face>
    </BoundaryConditions>
  </Grid>
</Uintah_specification>
""" % (
        s["title"],
        s["section"],
        s["notes"],
        s["title"],
        "impm" if implicit else "amrmpm",
        s["maxTime"],
        "%g" % s["delt_max"] if implicit else "1.0e12",
        s.get("multiplier", 0.2),
        max_timesteps(s.get("max_steps")) + s.get("time_extra", ""),
        archiver,
        (
            "\n    <time_integrator>implicit</time_integrator>\n    <dynamic>false</dynamic>"
            + s.get("implicit_extra", "")
            if implicit
            else ""
        ),
        s.get("mpm_extra", ""),
        pillar,
        substrate,
        contact,
        flux_blocks,
        0 if quarter else -L,
        0 if quarter else -L,
        L,
        L,
        p["top"],
        cells[0],
        cells[1],
        cells[2],
    )
    with open(os.path.join(OUT, s["name"] + ".ups"), "w") as f:
        f.write(text)


def describe(lines):
    return "\n".join("  " + l for l in lines)


COMMON = [
    "Small pillar: diameter 0.1 um, height 0.1 um, smoothcyl pie slices (dr = dz = 5 nm) on",
    "a 5 nm grid; base fixed (Velocity Dirichlet on z-); flux on the side and the top.",
    "Silicon: K = 67 GPa, G = 31 GPa, eta = 0.56; D = D0 exp(alpha c - beta p), p_max = 3 GPa.",
]

SCENARIOS = []
for rho, D0, J, T, name, sec, extra in [  # T: maxTime in us (the last figure time or just after)
    (
        2.33e3,
        1e-10,
        0.4,
        0.05,
        "Density_2.33e3",
        "§4.2, Fig. 3",
        [
            "Density 2.33e3 kg/m^3 (real silicon), D0 = 1e-10 m^2/s (raised, as in the paper).",
            "Not in the paper: the flux (0.4 m/s, to lithiate within the 48 ns the paper shows).",
        ],
    ),
    (
        2.33e8,
        1e-10,
        0.4,
        0.05,
        "Density_2.33e8",
        "§4.2, Fig. 3",
        [
            "Density raised to 2.33e8 kg/m^3, otherwise as Density_2.33e3: the paper finds little",
            "difference; compare the two at 6, 26 and 48 ns (6e-3, 26e-3, 48e-3 us).",
        ],
    ),
    (
        2.33e18,
        1e-17,
        1e-9,
        2.8e7,
        "Density_2.33e18",
        "§4.2, Fig. 4",
        [
            "Density 2.33e18 kg/m^3, D0 = 1e-17 m^2/s, flux 1e-9 m/s; compare with Density_2.33e24 at",
            "4, 16 and 28 s (4e6, 16e6, 28e6 us).",
        ],
    ),
    (
        2.33e24,
        1e-17,
        1e-9,
        2.8e7,
        "Density_2.33e24",
        "§4.2, Fig. 4",
        ["Density 2.33e24 kg/m^3 (diffusion-limited time step), otherwise as Density_2.33e18."],
    ),
]:
    SCENARIOS.append(
        dict(
            name=name,
            section=sec,
            title="Density scaling: " + name.split("_")[1] + " kg/m^3",
            notes=describe(
                COMMON + ["Linear isotropic hardening, yield 1.4 GPa, modulus 1.15 GPa."] + extra
            ),
            pillar=SMALL,
            density=rho,
            D0=D0,
            flux=J,
            maxTime=T,
            model="hardening",
            output=2e-3 if T < 1 else 1e6,
        )
    )

for model, label in [
    ("elastic", "linear elastic"),
    ("perfect", "perfect plasticity, yield 1.4 GPa"),
    ("hardening", "linear hardening, yield 1.4 GPa, modulus 1.15 GPa"),
]:
    SCENARIOS.append(
        dict(
            name="Constitutive_" + model,
            section="§4.3, Fig. 5",
            title="Constitutive model: " + label,
            notes=describe(
                COMMON
                + [
                    "Constitutive model: " + label + ".",
                    "D0 = 1e-17 m^2/s, alpha = 6, beta = 0.5, flux 1e-9 m/s, density 2.33e24 kg/m^3.",
                ]
            ),
            pillar=SMALL,
            density=2.33e24,
            D0=1e-17,
            flux=1e-9,
            maxTime=1.0e8,
            model=model,
        )
    )
for J, tag in [(1e-9, "1e-9"), (1e-8, "1e-8")]:
    SCENARIOS.append(
        dict(
            name="Flux_" + tag,
            section="§4.4, Figs. 6-7",
            title="Flux boundary condition " + tag + " m/s",
            notes=describe(
                COMMON
                + [
                    "Linear hardening; alpha = 6, beta = 0.5; flux " + tag + " m/s;",
                    "the paper finds c ~ 0.5-0.6 behind the front at 1e-9 and > 0.7 at 1e-8.",
                ]
            ),
            pillar=SMALL,
            density=2.33e24,
            D0=1e-17,
            flux=J,
            maxTime=1.0e8 if J < 5e-9 else 3.0e7,
            model="hardening",
        )
    )
# Not in the paper: why is there no sharp front at 1e-9 with D0 = 1e-17 (docs/paper/README.md)?
# The same run with smaller D0 (the paper does not give D0 for §4.4).
for D0, tag in [(5e-18, "5e-18"), (2e-18, "2e-18")]:
    SCENARIOS.append(
        dict(
            name="Front_D0_" + tag,
            section="§4.4, Figs. 6-7 (a study of ours)",
            title="Flux 1e-9 m/s with D0 = " + tag + " m^2/s",
            notes=describe(
                COMMON
                + [
                    "As Flux_1e-9 but D0 = " + tag + " m^2/s: how c behind the front depends on D0",
                    "(not in the paper, which does not give D0 for 4.4).",
                ]
            ),
            pillar=SMALL,
            density=2.33e24,
            D0=D0,
            flux=1e-9,
            # Past 60% of the capacity (Fig. 6's panels: 15, 30, 45, 60%): 2e-18 fills more
            # slowly (its surface is nearer the restriction's root).
            maxTime=3.5e7 if D0 > 4e-18 else 5.0e7,
            output=1e6,
            model="hardening",
        )
    )
for beta in [0.0, 1.0]:
    SCENARIOS.append(
        dict(
            name="Beta_%g" % beta,
            section="§4.5, Fig. 8",
            title="Pressure dependence beta = %g" % beta,
            notes=describe(
                COMMON + ["Linear hardening; alpha = 6, beta = %g (1/GPa); flux 1e-9 m/s." % beta]
            ),
            pillar=SMALL,
            density=2.33e24,
            D0=1e-17,
            flux=1e-9,
            maxTime=1.0e8,
            model="hardening",
            beta=beta,
        )
    )
# §4 (introduction): "The use of a substrate material was then explored using the larger diameter
# pillar." Lithiation only, to 100 s (the paper gives no duration), on the cycle's substrate.
LARGE_NOTES = [
    "Large pillar: diameter 0.5 um, height 0.05 um, smoothcyl (dr = dz = 2.5 nm) on the paper's",
    "10 nm grid. Silicon: linear hardening (K = 67, G = 31, yield 1.4, modulus 1.15 GPa), eta = 0.56,",
    "D0 = 1e-17 m^2/s, alpha = 6, beta = 0.5, p_max = 3 GPa; density 2.33e24 kg/m^3; flux 1e-9 m/s in.",
    "Not in the paper: the duration (100 s).",
]
SCENARIOS.append(
    dict(
        name="Substrate_fixed",
        section="§4.6, Fig. 9",
        title="Large pillar on a fixed base",
        notes=describe(
            LARGE_NOTES
            + [
                "The pillar's base is fixed (Velocity Dirichlet on z-); compare with Substrate_deformable."
            ]
        ),
        pillar=LARGE,
        density=2.33e24,
        D0=1e-17,
        flux=1e-9,
        maxTime=1.0e8,
        model="hardening",
    )
)
SCENARIOS.append(
    dict(
        name="Substrate_deformable",
        section="§4.6, Fig. 9",
        title="Large pillar on a deformable substrate",
        notes=describe(
            LARGE_NOTES
            + [
                "The pillar sits on a 0.7 x 0.7 x 0.04 um substrate (K = 180.4 GPa, G = 76 GPa,",
                "yield 0.7 GPa, modulus 1.15 GPa, no lithium: D = 0), bonded by single_velocity",
                "contact; the substrate's base is fixed.",
            ]
        ),
        pillar=LARGE,
        density=2.33e24,
        D0=1e-17,
        flux=1e-9,
        maxTime=1.0e8,
        model="hardening",
        substrate_height=0.04,
        substrate_width=0.7,
    )
)
SCENARIOS[-1]["pillar"] = dict(LARGE, top=0.24)

SCENARIOS.append(
    dict(
        name="Cycle_LargePillar",
        section="§4.7, Fig. 10",
        title="Full lithiation/delithiation cycle of the large pillar on a substrate",
        notes=describe(
            [
                "Large pillar: diameter 0.5 um, height 0.05 um, smoothcyl (dr = dz = 2.5 nm) on the paper's",
                "10 nm grid, on a 0.7 x 0.7 x 0.04 um substrate (K = 180.4 GPa, G = 76 GPa, yield 0.7 GPa,",
                "modulus 1.15 GPa, no lithium) bonded by single_velocity contact; base fixed.",
                "Silicon: linear hardening (K = 67, G = 31, yield 1.4, modulus 1.15 GPa), eta = 0.56,",
                "D0 = 1e-17 m^2/s, alpha = 6, beta = 0.5, p_max = 3 GPa; density 2.33e24 kg/m^3.",
                "Flux 1e-9 m/s in for 40 s, then out for 40 s (not in the paper: the durations);",
                "during delithiation each particle's diffusivity stays at its last lithiation value",
                "(diff_curve 'out'). The paper's run: 27,472 steps, 48.57 h on 9 cores.",
            ]
        ),
        pillar=LARGE,
        density=2.33e24,
        D0=1e-17,
        flux=1e-9,
        maxTime=8.0e7,
        lithiation_end=4.0e7,
        output=4e6,
        model="hardening",
        substrate_height=0.04,
        substrate_width=0.7,
    )
)
SCENARIOS[-1]["pillar"] = dict(LARGE, top=0.24)


def add_variant(base, **changes):
    """Appends the scenario named `base` with `changes`."""
    SCENARIOS.append(dict(next(s for s in SCENARIOS if s["name"] == base), **changes))


# A quarter of the large pillar and its substrate (x, y >= 0, symmetric planes x = 0 and y = 0;
# 85,640 particles instead of 342,940).
QUARTER_NOTES = [
    "A quarter of the pillar and its substrate (x, y >= 0: smoothcyl arc 0-90 degrees, 145",
    "slices around; substrate and grid from x = y = 0), the planes x = 0 and y = 0 symmetric:",
]


def add_quarter(base, name, title, lines, **changes):
    """Appends the scenario `base` on the quarter x, y >= 0, its notes QUARTER_NOTES + `lines`."""
    add_variant(
        base, name=name, title=title, notes=describe(QUARTER_NOTES + lines), quarter=True, **changes
    )


# The partial cycle again, to check the quarter against the whole.
add_quarter(
    "Cycle_LargePillar",
    "Cycle_LargePillar_Quarter",
    "A quarter of the large pillar's partial cycle",
    [
        "otherwise Cycle_LargePillar (explicit, density 2.33e24 kg/m^3, flux 1e-9 m/s in",
        "for 40 s, out for 40 s), whose results it is checked against (docs/paper).",
    ],
)

# §4.7's full cycle as the paper ran it, explicit at a raised density, on the quarter: in for
# 130 s, out for 130 s, the durations of QuasiStatic_FullCycle_LargePillar (whose lithiation half
# it checks).
add_quarter(
    "Cycle_LargePillar_Quarter",
    "FullCycle_LargePillar_Quarter",
    "A quarter of the large pillar's full cycle",
    [
        "otherwise Cycle_LargePillar (explicit, density 2.33e24 kg/m^3) with flux 1e-9 m/s",
        "in for 130 s (towards full lithiation, as the paper's cycle; not in the paper: the",
        "durations), then out for 130 s with each particle's diffusivity at its last",
        "lithiation value; outputs every 10 s, the durations and outputs of",
        "QuasiStatic_FullCycle_LargePillar.",
    ],
    maxTime=2.6e8,
    lithiation_end=1.3e8,
    output=1e7,
)


# Not in the paper either: which of our departures from Uintah's flux rules, or beta's unit,
# decides whether Flux_1e-9 has a sharp front (docs/paper/README.md, "The sharp front at 1e-9
# m/s"). Flux_1e-9 to 35 s (past 60% of the capacity) with one rule switched to Uintah's (or beta
# to 0) at a time.
FRONT_CAUSES = [
    ("ours", "our rules (Flux_1e-9 to 35 s)", {}),
    (
        "area_particle_face",
        "each flagged particle's own face as flux area (Uintah's)",
        dict(flux_extra="\n        <area_rule>particle_face</area_rule>"),
    ),
    (
        "receivers_weights",
        "the flux source shared by S, not m S R(c) (Uintah's)",
        dict(mpm_extra="\n    <flux_source_receivers>weights</flux_source_receivers>"),
    ),
    (
        "cstar_without_source",
        "the flux source left out of c* (Uintah's)",
        dict(mpm_extra="\n    <flux_source_in_cstar>false</flux_source_in_cstar>"),
    ),
    (
        "uintah_flux_rules",
        "Uintah's three flux rules together (particle-face area, source by S, not in c*)",
        dict(
            flux_extra="\n        <area_rule>particle_face</area_rule>",
            mpm_extra="\n    <flux_source_receivers>weights</flux_source_receivers>"
            "\n    <flux_source_in_cstar>false</flux_source_in_cstar>",
        ),
    ),
    ("beta_0", "beta = 0: no pressure term (a unit making beta p small)", dict(beta=0.0)),
    (
        "beta_2.07",
        "beta = 2.07 (beta p 4 times ours; a value commented out in Uintah's pillar inputs)",
        dict(beta=2.07),
    ),
]
for tag, what, changes in FRONT_CAUSES:
    add_variant(
        "Flux_1e-9",
        name="Front_cause_" + tag,
        section="§4.4, Figs. 6-7 (a study of ours)",
        title="Flux 1e-9 m/s to 35 s: " + what,
        notes=describe(
            COMMON
            + [
                "As Flux_1e-9 (D0 = 1e-17 m^2/s) to 35 s, with " + what + ":",
                "does it decide whether a sharp front forms? (not in the paper)",
            ]
        ),
        maxTime=3.5e7,
        output=1e6,
        **changes,
    )

# Quasi-static runs at silicon's real density in steps of at most 1 s; with NEWTON_STEPS dt follows
# Newton's iterations alone (no error control: <error_tolerance> 0), growing again after a step of
# at most 7 of them.
REAL_DENSITY = dict(density=2.33e3, implicit=True, delt_max=1e6)
NEWTON_STEPS = dict(
    REAL_DENSITY,
    implicit_extra="\n    <error_tolerance>0</error_tolerance>"
    "\n    <max_concentration_change>1</max_concentration_change>"
    "\n    <num_iters_to_increase_delT>7</num_iters_to_increase_delT>",
)

# Steps that would pass an output time end on it (Uintah's <clamp_time_to_output>).
CLAMP_TO_OUTPUT = "\n    <clamp_time_to_output>true</clamp_time_to_output>"

# Figure 4's pillar at the real density, quasi-static (docs/quasi-static.md): no density enters
# the equilibrium, dt follows Newton's iterations up to delt_max (1 s).
add_variant(
    "Density_2.33e18",
    name="QuasiStatic_Fig4",
    title="Quasi-static: 2.33e3 kg/m^3",
    notes=describe(
        COMMON
        + [
            "Linear isotropic hardening, yield 1.4 GPa, modulus 1.15 GPa.",
            "Density 2.33e3 kg/m^3 (real silicon), D0 = 1e-17 m^2/s, flux 1e-9 m/s, quasi-static",
            "(implicit) steps of at most 1 s; compare with Density_2.33e18 and Density_2.33e24.",
            "dt by Newton's iterations alone (max_concentration_change 1), growing again",
            "after a step of at most 7 iterations (this pillar's steps take 6-7: with",
            "ImpMPM's 4 a retaken first step's cut would hold to the end);",
            "docs/quasi-static.md shows how the answer moves with dt.",
            "Steps end on the output times (every 1 s): Figure 4's 4, 16 and 28 s are outputs.",
        ]
    ),
    time_extra=CLAMP_TO_OUTPUT,
    **NEWTON_STEPS,
)

# The same pillar without step hints: dt chosen by the error estimate (docs/quasi-static.md, "Steps
# by error estimate"), <delt_max> as the explicit inputs', Newton's criteria from the tolerance.
add_variant(
    "Density_2.33e18",
    name="QuasiStatic_Fig4_NoHints",
    title="Quasi-static: 2.33e3 kg/m^3, steps by error estimate",
    notes=describe(
        COMMON
        + [
            "Linear isotropic hardening, yield 1.4 GPa, modulus 1.15 GPa.",
            "Density 2.33e3 kg/m^3 (real silicon), D0 = 1e-17 m^2/s, flux 1e-9 m/s, quasi-static",
            "(implicit) steps chosen by their error estimate (the default error_tolerance,",
            "0.01), without step hints: QuasiStatic_Fig4 without its delt_max of 1 s,",
            "error_tolerance 0, max_concentration_change, num_iters_to_increase_delT and",
            "clamp_time_to_output. Steps end on the output times (every 1 s). docs/quasi-static.md,",
            "'Figure 4's pillar without step hints'.",
        ]
    ),
    **dict(REAL_DENSITY, delt_max=1e12),
)

# §4.4's faster flux at the real density, quasi-static: the explicit Flux_1e-8 stops at 16.06 s
# with c = 1.0000037 (docs/paper); here dt follows Newton's iterations alone as QuasiStatic_Fig4.
add_variant(
    "Flux_1e-8",
    name="QuasiStatic_Flux_1e-8",
    title="Quasi-static: flux 1e-8 m/s at 2.33e3 kg/m^3",
    notes=describe(
        COMMON
        + [
            "Linear hardening; alpha = 6, beta = 0.5; flux 1e-8 m/s, as Flux_1e-8.",
            "Density 2.33e3 kg/m^3 (real silicon), quasi-static (implicit) steps of at most",
            "1 s, dt by Newton's iterations alone as QuasiStatic_Fig4; the first step 0.2 s (from",
            "1 s its linear solves do not converge: the surface's c would rise 0.8 in one step).",
        ]
    ),
    time_extra="\n    <delt_init>2e5</delt_init>",
    **NEWTON_STEPS,
)

# §4.4's slower flux at the real density, quasi-static, to its end (100 s): with
# QuasiStatic_Flux_1e-8, whether the faster flux's bulge near the base survives at the real
# density (docs/paper/README.md, Figs. 6-7).
add_variant(
    "Flux_1e-9",
    name="QuasiStatic_Flux_1e-9",
    title="Quasi-static: flux 1e-9 m/s at 2.33e3 kg/m^3",
    notes=describe(
        COMMON
        + [
            "Linear hardening; alpha = 6, beta = 0.5; flux 1e-9 m/s, as Flux_1e-9, to 100 s.",
            "Density 2.33e3 kg/m^3 (real silicon), quasi-static (implicit) steps of at most",
            "1 s, dt by Newton's iterations alone as QuasiStatic_Fig4.",
        ]
    ),
    **NEWTON_STEPS,
)

# §4.7's cycle at the real density, quasi-static: steps of at most 2 s with the trapezoidal
# coupling (on Figure 4's pillar at 4 s, mean abs(c - the explicit 2.33e24 run) 0.0018 in steps of
# 2 s, where the staggered steps of 1 s give 0.0063: docs/quasi-static.md).
add_variant(
    "Cycle_LargePillar",
    name="QuasiStatic_Cycle_LargePillar",
    title="Quasi-static: the large pillar's cycle at 2.33e3 kg/m^3",
    notes=describe(
        [
            "Cycle_LargePillar (large pillar on a substrate, flux 1e-9 m/s in for 40 s, out for",
            "40 s) at silicon's real density, 2.33e3 kg/m^3, in quasi-static (implicit) steps of",
            "at most 2 s, dt by Newton's iterations alone as QuasiStatic_Fig4, each step's",
            "diffusion averaged over its start and its predicted end (concentration_coupling",
            "trapezoidal); steps end on the output times (every 4 s, so one ends where the flux",
            "turns at 40 s). Newton's Jacobian leaves out the couplings through a particle",
            "holding less than 1e-4 of a node's mass (jacobian_coupling_share; the residual",
            "keeps them): K has a third fewer entries. Newton keeps its last Jacobian after a",
            "small, fast correction (jacobian_reuse) and stops when its correction is within",
            "0.3% of the step's (convergence_criteria_disp 1e-5, ImpMPM's ratio of squares;",
            "energy 4e-5): docs/quasi-static.md compares the results with those of ImpMPM's",
            "1e-10 and 4e-10 and every coupling. Each diffusion pass is one second-order",
            "Runge-Kutta-Legendre step (diffusion_integrator rkl2) instead of forward-Euler",
            "sub-steps: docs/quasi-static.md compares the two.",
        ]
    ),
    time_extra=CLAMP_TO_OUTPUT,
    **dict(
        NEWTON_STEPS,
        delt_max=2e6,
        implicit_extra=NEWTON_STEPS["implicit_extra"]
        + "\n    <concentration_coupling>trapezoidal</concentration_coupling>"
        + "\n    <diffusion_integrator>rkl2</diffusion_integrator>"
        + "\n    <jacobian_coupling_share>1e-4</jacobian_coupling_share>"
        + "\n    <jacobian_reuse>true</jacobian_reuse>"
        + "\n    <convergence_criteria_disp>1e-5</convergence_criteria_disp>"
        + "\n    <convergence_criteria_energy>4e-5</convergence_criteria_energy>",
    ),
)

# The same partial cycle on the quarter of Cycle_LargePillar_Quarter (a quarter of the particles),
# checked against the whole (docs/quasi-static.md).
add_quarter(
    "QuasiStatic_Cycle_LargePillar",
    "QuasiStatic_Cycle_LargePillar_Quarter",
    "Quasi-static: a quarter of the large pillar's cycle at 2.33e3 kg/m^3",
    [
        "otherwise QuasiStatic_Cycle_LargePillar (flux 1e-9 m/s in for 40 s, out for 40 s,",
        "at silicon's real density in quasi-static steps of at most 2 s with the",
        "trapezoidal coupling and RKL2 diffusion passes), whose results it is checked against",
        "(docs/quasi-static.md).",
    ],
)

# §4.7's full cycle at the real density: the paper lithiates fully (its durations are not stated);
# Cycle_LargePillar's 40 s reach 42% of the capacity, Substrate_deformable's 100 s 77.6%, about
# 0.56% a second from 52 s on. In for 130 s (about 90% at that rate), then out for as long, in
# the steps of QuasiStatic_Cycle_LargePillar.
add_variant(
    "QuasiStatic_Cycle_LargePillar",
    name="QuasiStatic_FullCycle_LargePillar",
    title="Quasi-static: the large pillar's full cycle at 2.33e3 kg/m^3",
    notes=describe(
        [
            "The large pillar on its substrate as Cycle_LargePillar, flux 1e-9 m/s in for 130 s",
            "(towards full lithiation, as the paper's cycle; not in the paper: the durations),",
            "then out for 130 s with each particle's diffusivity at its last lithiation value,",
            "at silicon's real density, 2.33e3 kg/m^3, in quasi-static (implicit) steps of at",
            "most 2 s, dt by Newton's iterations alone, each step's diffusion averaged over its",
            "start and its predicted end (concentration_coupling trapezoidal); steps end on the",
            "output times (every 10 s, so one ends where the flux turns at 130 s). Each step's",
            "diffusion first draws the particles towards the grid's c at their places",
            "(subcell_concentration_relaxation): without it a particle below its cell's mean",
            "empties first and stops the run at 238 s (docs/paper, Figure 10). The diffusion",
            "sub-steps at 0.1 of the explicit limits (timestep_multiplier; a quasi-static step's",
            "dt is Newton's): at 0.2 they oscillate at a particle of the base's edge from 229 s.",
        ]
    ),
    multiplier=0.1,
    maxTime=2.6e8,
    lithiation_end=1.3e8,
    output=1e7,
    implicit_extra=NEWTON_STEPS["implicit_extra"]
    + "\n    <concentration_coupling>trapezoidal</concentration_coupling>"
    + "\n    <subcell_concentration_relaxation>true</subcell_concentration_relaxation>",
)


# The same full cycle on the quarter of Cycle_LargePillar_Quarter (a quarter of the cost).
add_quarter(
    "QuasiStatic_FullCycle_LargePillar",
    "QuasiStatic_FullCycle_LargePillar_Quarter",
    "Quasi-static: a quarter of the large pillar's full cycle at 2.33e3 kg/m^3",
    [
        "otherwise QuasiStatic_FullCycle_LargePillar (flux 1e-9 m/s in for 130 s, out for",
        "130 s, at silicon's real density in quasi-static steps of at most 2 s with the",
        "trapezoidal coupling), whose lithiation half it is checked against (docs/paper).",
    ],
)

if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for s in SCENARIOS:
        scenario(s)
        print("wrote", s["name"])

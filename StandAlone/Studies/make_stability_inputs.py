#!/usr/bin/env python3
"""Writes the stiff and extreme cases of issue 7 as inputs/Stability/*.ups (docs/stability.md).

All share one small plane-strain body so each runs in seconds: a silicon block 0.1 x 0.15 um
(x by y, one 10 nm cell thick in z) on a 10 nm grid, 2 x 2 particles per cell (600 particles,
CPDI), its base (y-) fixed, lithiated through its top (y+) and right side (x+). Silicon as in the
paper: K = 67 GPa, G = 31 GPa, eta = 0.56, D = D0 exp(alpha c - beta clamp(p, 0, p_max)) with
p_max = 3 GPa; linear hardening, yield 1.4 GPa, modulus 1.15 GPa. Each case changes one thing.
Implicit variants (issue 40, docs/quasi-static.md): <SimulationComponent type="impm"/> with
<time_integrator>implicit</time_integrator> and <dynamic>false</dynamic>, the ImpMPM tags of `impm`;
some add a substrate under the silicon (single_velocity or null contact).
Units: um, us, pg (1 GPa = 1e6, 1 kg/m^3 = 1e-3 pg/um^3, 1 m^2/s = 1e6 um^2/us, 1 m/s = 1 um/us).
Run: python3 StandAlone/Studies/make_stability_inputs.py; tests/test_stability.cc runs the quick versions.
"""
import os

from ups_blocks import (
    GPA,
    SILICON,
    data_archiver,
    flow_model,
    max_timesteps,
    non_linear1_diffusion,
    scalar_flux,
    substrate_material,
)

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "inputs", "Stability")

BASE = dict(
    density=2.33e3,
    K=SILICON["K"],
    G=SILICON["G"],
    eta=0.56,
    model="hardening",
    D0=1e-10,
    alpha=6.0,
    beta=0.5,
    pmax=3.0,
    flux=0.4,
    c0=0.0,
    velocity=0.0,
    multiplier=0.4,
    maxTime=1.0,
    diffusion="non_linear1",
    rate=0.0,
    confined=False,
    grid=(0.2, 0.25),
    steps=0,
    sigmaY=SILICON["sigmaY"],
    H=SILICON["H"],
    implicit=False,
    impm={},
    delt_max="1.0e12",
    walls="",
    substrate="",
    res="[2,2,1]",
)

# The substrate of the contact cases: an elastic block 0.1 x 0.05 um under the silicon (which then
# spans y = 0.05 to 0.15), stiffer than silicon (K = 180 GPa, G = 76 GPa), taking up no lithium.
SUBSTRATE_TOP = 0.05


def diffusion_model(s):
    if not s["diffusion"]:
        return ""
    if s["diffusion"] == "constant_rate":
        return (
            """<diffusion_model type="constant_rate">
          <diffusivity>0.0</diffusivity>
          <max_concentration>1.0</max_concentration>
          <constant_rate>%g</constant_rate>
        </diffusion_model>"""
            % s["rate"]
        )
    return non_linear1_diffusion(s["D0"], s["alpha"], s["beta"], s["pmax"])


def flux_bcs(s):
    if not s["diffusion"] or s["diffusion"] == "constant_rate" or s["flux"] == 0:
        return ""
    load = (
        "<time_point><time>0</time><load>%g</load></time_point><time_point><time>1e12</time><load>%g</load></time_point>"
        % (s["flux"], s["flux"])
    )
    # Zero-thickness boxes on the top and right faces: Uintah's rule (the box enlarged by the
    # particle spacing) selects exactly the top row and the right column.
    return (
        "\n  <PhysicalBC>\n    <MPM>"
        + scalar_flux(
            1,
            '<box label="top"><min>[0.0, 0.15, 0.0]</min><max>[0.1, 0.15, 0.01]</max></box>',
            load,
        )
        + scalar_flux(
            2,
            '<box label="side"><min>[0.1, 0.0, 0.0]</min><max>[0.1, 0.15, 0.01]</max></box>',
            load,
        )
        + "\n    </MPM>\n  </PhysicalBC>"
    )


def implicit_flags(s):
    """The quasi-static integrator and the ImpMPM tags of s["impm"] (docs/quasi-static.md)."""
    if not s["implicit"]:
        return ""
    return (
        "\n    <time_integrator>implicit</time_integrator>\n    <dynamic>false</dynamic>"
        + "".join("\n    <%s>%s</%s>" % (tag, value, tag) for tag, value in s["impm"].items())
    )


def substrate(s):
    """The substrate material under the silicon (none unless s["substrate"])."""
    if not s["substrate"]:
        return ""
    return substrate_material(
        s["density"] * 1e-3,
        "",
        '<box label="substrate"><min>[0.0, 0.0, 0.0]</min><max>[0.1, %g, 0.01]</max></box>'
        % SUBSTRATE_TOP,
        "[2,2,1]",
    )


def contact(s):
    """<contact>: null for one material; with a substrate s["substrate"] names the type ("exclude":
    single_velocity with <ExcludeMaterial>, which implicit runs refuse)."""
    if not s["substrate"]:
        return "<contact><type>null</type></contact>"
    kind = "single_velocity" if s["substrate"] == "exclude" else s["substrate"]
    return (
        "<contact>\n        <type>%s</type>\n        <materials>[0,1]</materials>%s\n      </contact>"
        % (
            kind,
            "\n        <ExcludeMaterial>1</ExcludeMaterial>" if s["substrate"] == "exclude" else "",
        )
        + "\n      <diffusion_interface><type>null</type></diffusion_interface>"
    )


def write(name, notes, quick, **changes):
    s = dict(BASE)
    s.update(changes)
    diffusion = bool(s["diffusion"])
    fixed = (
        '<BCType id="all" label="Velocity" var="Dirichlet"><value>[0.0, 0.0, 0.0]</value></BCType>'
    )
    # Confined: the block fills the grid's x extent and top, every face holds it. Walls "sides":
    # it fills the x extent, x+ holds it (no slip), the top is free.
    width, top = (0.1, 0.15) if s["confined"] else s["grid"]
    if s["walls"] == "sides":
        width = 0.1
    faces = {
        "x-": '<BCType id="all" label="Symmetric" var="symmetry"/>',
        "x+": fixed
        if s["confined"] or s["walls"]
        else '<BCType id="all" label="Symmetric" var="symmetry"/>',
        "y-": fixed,
        "y+": fixed if s["confined"] else '<BCType id="all" label="Symmetric" var="symmetry"/>',
        "z-": '<BCType id="all" label="Symmetric" var="symmetry"/>',
        "z+": '<BCType id="all" label="Symmetric" var="symmetry"/>',
    }
    text = """<?xml version='1.0' encoding='ISO-8859-1' ?>
<!--
%s
  Expected (tests/test_stability.cc runs this file as it is): %s
  Base case (StandAlone/Studies/make_stability_inputs.py, which writes this file; edit it, not this file):
  a plane-strain silicon block 0.1 x 0.15 um, 600 CPDI particles, base fixed, flux on top and right.
  Units: um, us, pg (1 GPa = 1e6, density in pg/um^3 = 1e-3 kg/m^3, D in um^2/us, flux in um/us).
-->
<Uintah_specification>
  <Meta><title>Stability: %s</title></Meta>
  <SimulationComponent type="%s"/>
  <Time>
    <maxTime>%g</maxTime>
    <initTime>0.0</initTime>
    <delt_min>0.0</delt_min>
    <delt_max>%s</delt_max>
    <timestep_multiplier>%g</timestep_multiplier>%s
  </Time>
%s
  <MPM>
    <interpolator>cpdi</interpolator>%s
  </MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties>
    <MPM>
      <material name="silicon">
        <density>%g</density>
        <constitutive_model type="rf_elastic_plastic">
          <bulk_modulus>%g</bulk_modulus>
          <shear_modulus>%g</shear_modulus>%s
          <equation_of_state type="default_hypo"/>
          %s
        </constitutive_model>
        %s
        <geom_object>
          <box label="block"><min>[0.0, %s, 0.0]</min><max>[0.1, 0.15, 0.01]</max></box>
          <res>%s</res>
          <velocity>[0.0, %g, 0.0]</velocity>%s
        </geom_object>
      </material>%s
      %s
    </MPM>
  </MaterialProperties>%s
  <Grid>
    <Level>
      <Box label="1">
        <lower>[0.0, 0.0, 0.0]</lower>
        <upper>[%g, %g, 0.01]</upper>
        <resolution>[%d, %d, 1]</resolution>
        <extraCells>[1,1,1]</extraCells>
      </Box>
    </Level>
    <BoundaryConditions>
%s
    </BoundaryConditions>
  </Grid>
</Uintah_specification>
""" % (
        "\n".join("  " + l for l in notes),
        quick,
        name,
        "impm" if s["implicit"] else "mpm",
        s["maxTime"],
        s["delt_max"],
        s["multiplier"],
        max_timesteps(s["steps"])
        + (
            # The last quasi-static step ends at maxTime: c reaches rate x maxTime exactly.
            "\n    <end_at_max_time_exactly>true</end_at_max_time_exactly>"
            if s["implicit"]
            else ""
        ),
        data_archiver(
            name,
            s["maxTime"] / 10,
            ["p.x", "p.particleID", "p.volume", "p.velocity", "p.stress"]
            + (["p.concentration", "p.diffusivity"] if diffusion else []),
        ),
        implicit_flags(s)
        + (
            "\n    <do_scalar_diffusion>true</do_scalar_diffusion>"
            + ("\n    <use_load_curves>true</use_load_curves>" if flux_bcs(s) else "")
        )
        if diffusion
        else "",
        s["density"] * 1e-3,
        s["K"] * GPA,
        s["G"] * GPA,
        "\n          <volume_expansion_coeff>%g</volume_expansion_coeff>" % s["eta"]
        if diffusion
        else "",
        flow_model(s["model"], dict(SILICON, sigmaY=s["sigmaY"], H=s["H"])),
        diffusion_model(s),
        SUBSTRATE_TOP if s["substrate"] else "0.0",
        s["res"],
        s["velocity"],
        "\n          <concentration>%g</concentration>" % s["c0"] if diffusion else "",
        substrate(s),
        contact(s),
        flux_bcs(s),
        width,
        top,
        round(width / 0.01),
        round(top / 0.01),
        "\n".join('      <Face side="%s">%s</Face>' % (f, b) for f, b in faces.items()),
    )
    with open(os.path.join(OUT, name + ".ups"), "w") as f:
        f.write(text)


CASES = []


def case(name, notes, quick, **changes):
    CASES.append((name, notes, quick, changes))


# Diffusion-limited runs use a density scaled far up so inertia does not limit the time step.
SLOW = dict(density=2.33e24, maxTime=1e8)
FLUX = dict(SLOW, alpha=0.0, beta=0.0, D0=1e-14)
IMPACT = dict(diffusion="", velocity=-10.0, maxTime=1e-3)

case(
    "Density_2.33e3",
    [
        "Density 2.33e3 kg/m^3 (real silicon): the time step is mechanics-limited,",
        "dt = multiplier dx / c with c = sqrt((K + 4G/3) / rho) (Eq. 43), 5.9e-7 us.",
        "D0 = 1e-10 m^2/s, alpha = 6, beta = 0.5, flux 1e-4 m/s.",
    ],
    "300 steps complete; the first dt is 0.4 dx / c; c in [0, 1].",
    flux=1e-4,
    maxTime=1e-2,
    steps=300,
)
case(
    "Density_2.33e24",
    [
        "Density 2.33e24 kg/m^3, otherwise as Density_2.33e3: the time step is",
        "diffusion-limited, dt = multiplier dx^2 / (2 D_max) (Eq. 44), 0.2 us at first, and",
        "falls as D = D0 exp(alpha c - beta p) grows with c.",
    ],
    "300 steps complete; the first dt is 0.4 dx^2 / (2 D0); c in [0, 1].",
    flux=1e-4,
    steps=300,
    **SLOW
)
case(
    "Alpha_0",
    [
        "Diffusivity contrast: alpha = 0 (D independent of c), beta = 0.5, D0 = 1e-10 m^2/s,",
        "flux 1e-3 m/s, density 2.33e24 kg/m^3.",
    ],
    "600 steps complete; c in [0, 1].",
    flux=1e-3,
    alpha=0.0,
    steps=600,
    **SLOW
)
case(
    "Alpha_10",
    [
        "Diffusivity contrast: alpha = 10, D = D0 e^(10 c): up to e^10 = 22026 times D0 where the",
        "block is full; the diffusion-limited dt falls with the largest D. Otherwise as Alpha_0.",
    ],
    "600 steps complete; c in [0, 1]; dt falls as c_max grows.",
    flux=1e-3,
    alpha=10.0,
    steps=600,
    **SLOW
)
case(
    "Beta_0.5_confined",
    [
        "Pressure beyond p_max: the block is held on every side, so swelling builds a pressure",
        "of tens of GPa, far beyond p_max = 3 GPa; beta = 0.5 1/GPa. D = D0 exp(alpha c - beta",
        "min(p, p_max)) stays above D0 e^(-1.5). Flux 1e-3 m/s, density 2.33e24 kg/m^3.",
    ],
    "600 steps complete; p exceeds p_max; D >= D0 exp(-beta p_max); c in [0, 1].",
    flux=1e-3,
    beta=0.5,
    confined=True,
    steps=600,
    **SLOW
)
case(
    "Beta_2_confined",
    [
        "As Beta_0.5_confined with beta = 2 1/GPa: D varies 400-fold (e^(2 p_max)) between",
        "neighbouring particles where the pressure crosses p_max. The particle flux of",
        "Eqs. 6-7 is not monotone under such contrast: a particle between high- and",
        "low-D neighbours undershoots below c = 0, independently of the time step (0.4 and",
        "0.2 stop at the same time), and the run stops with the range diagnostic.",
    ],
    "stops at step 55 (exit 3): concentration below 0 (the range diagnostic).",
    flux=1e-3,
    beta=2.0,
    confined=True,
    steps=600,
    **SLOW
)
case(
    "Flux_1e-10",
    [
        "Flux 1e-10 m/s into the top and the right side; D0 = 1e-14 m^2/s, alpha = beta = 0,",
        "density 2.33e24 kg/m^3: the flux restriction never acts (c stays ~1e-3).",
    ],
    "300 steps complete; c in [0, 1].",
    flux=1e-10,
    steps=300,
    **FLUX
)
case(
    "Flux_1e-6",
    [
        "Flux 1e-6 m/s, otherwise as Flux_1e-10: the surface fills and the restriction",
        "(Eq. 17) shuts the flux off as c -> 1 - e^-4 = 0.9817. Each particle receives the",
        "source restricted by its own c, so a full particle takes nothing from its still-filling",
        "neighbours and the surface stays below the root. The block swells 8-fold (J up to 8.5);",
        "there the diffusion update pushes one particle past 1 and the range diagnostic stops",
        "the run (no clamp).",
    ],
    "stops at step 1761 (exit 3): concentration 1.0005 above 1 (the range diagnostic); max c stays below "
    "0.9817 until then.",
    flux=1e-6,
    steps=3000,
    **FLUX
)
case(
    "Flux_out_1e-6",
    [
        "Delithiation: initial concentration 0.9, flux 1e-6 m/s out of the top and the right side,",
        "otherwise as Flux_1e-6. The outflow restriction R(1 - c) shuts the flux off as",
        "c -> e^-4 = 0.0183; an emptied particle receives none of its neighbours' sinks, so c",
        "stays above 0.",
    ],
    "2000 steps complete; c in [0, 1]; the surface empties to the root.",
    flux=-1e-6,
    c0=0.9,
    steps=2000,
    **FLUX
)
case(
    "Concentration_0.999",
    [
        "Initial concentration 0.999 (above the restriction's root 1 - e^-4 = 0.9817), flux",
        "1e-6 m/s: the restriction admits no lithium and nothing changes.",
    ],
    "300 steps complete; c stays 0.999.",
    flux=1e-6,
    c0=0.999,
    steps=300,
    **FLUX
)
for m, steps, outcome in [
    (0.1, 1500, "1500 steps complete; KE never exceeds the initial KE; J in [0.99, 1.01]."),
    (
        0.75,
        1500,
        "runs to maxTime (911 steps); KE never exceeds the initial KE; J in [0.99, 1.01].",
    ),
    (0.8, 1500, "stops at step 33 (exit 3): the velocities oscillate with growing amplitude."),
    (
        1.5,
        1500,
        "refused at setup (exit 2, nothing written): <timestep_multiplier> must be in (0, 1]; a dt"
        " beyond the stable one is unstable.",
    ),
]:
    case(
        "Multiplier_%g" % m,
        [
            "timestep_multiplier %g on a mechanics-limited run: the block moves down at 10 m/s" % m,
            "onto its fixed base (no diffusion), density 2.33e3 kg/m^3. In 2-D the explicit",
            "update is stable up to a multiplier between 0.75 and 0.8 of Eq. 43 (about",
            "1/sqrt(2) for lumped-mass bilinear elements); beyond it the highest mode flips",
            "sign and grows every step.",
        ]
        + (
            [
                "A multiplier above 1 asks for a dt beyond the stable one by definition: setup refuses it",
                "(it ran to step 5 before, where the oscillation diagnostic stopped it).",
            ]
            if m > 1
            else []
        ),
        outcome,
        multiplier=m,
        steps=steps,
        **IMPACT
    )
for m, outcome in [
    (0.5, "1000 steps complete; c in [0.5, 0.6]."),
    (
        0.6,
        "stops at step 136 (exit 3): the concentrations oscillate (intermittently; left to run,"
        " the oscillation bursts and the smallest c falls, which inflow alone cannot do).",
    ),
    (1.0, "stops at step 11 (exit 3): the concentrations oscillate with growing amplitude."),
]:
    case(
        "Multiplier_diffusion_%.1f" % m,
        [
            "timestep_multiplier %g on a diffusion-limited run (Eq. 44): c starts at 0.5" % m,
            "everywhere, flux 1e-4 m/s, D0 = 1e-10 m^2/s, alpha = 6, density 2.33e24",
            "kg/m^3. The explicit diffusion update is stable up to a multiplier of",
            "about 1/2 of Eq. 44 in 2-D (1/d for lumped-mass elements in d dimensions);",
            "beyond it the concentrations oscillate inside [0, 1], where the range",
            "diagnostic cannot see them.",
        ],
        outcome,
        multiplier=m,
        flux=1e-4,
        c0=0.5,
        steps=1000,
        **SLOW
    )
case(
    "Swelling_eta_1",
    [
        "Very large swelling: eta = 1 and c rising uniformly from 0 to 0.99 (constant_rate",
        "3.3e-3 per us to 300 us), eta dc ~ 1: the free block would grow e^2 = 7.4-fold in area;",
        "held in z (plane strain) it reaches J ~ 16. Density 2.33e18 kg/m^3 (quasi-static),",
        "a grid 0.35 x 0.5 um to hold the grown block.",
    ],
    "runs to maxTime (56 steps); J reaches 15-17; c in [0, 0.99].",
    diffusion="constant_rate",
    rate=0.0033,
    eta=1.0,
    density=2.33e18,
    maxTime=300,
    grid=(0.35, 0.5),
)
for v, outcome in [
    (5, "runs to maxTime (357 steps); J falls to ~0.19; KE never exceeds the initial KE."),
    (12, "stops at step 66 (exit 3): J below 1e-5 at the impact face (a collapsing particle)."),
]:
    case(
        "Elastic_compression_%dkm_s" % v,
        [
            "An elastic block (no yield) hitting its fixed base at %d km/s (the dilatational" % v,
            "wave speed is 6.8 km/s) and rebounding: very large compression without",
            "plasticity. Density 2.33e3 kg/m^3, no diffusion.",
        ],
        outcome,
        diffusion="",
        model="elastic",
        velocity=-1000.0 * v,
        maxTime=1e-4,
    )

# Implicit (quasi-static) variants: c rises uniformly (constant_rate, no flux), dt is Newton's and
# <max_concentration_change>'s (docs/quasi-static.md); real density, which no equation uses.
IMPLICIT = dict(
    implicit=True,
    diffusion="constant_rate",
    density=2.33e3,
    delt_max="10",
    impm={"max_concentration_change": 0.1},
)
for name, maxTime, notes, outcome in [
    (
        "Implicit_swelling_eta_0.56",
        100,
        ["The last step ends at maxTime, where c = 1 exactly."],
        "runs to maxTime (10 steps of 10 us, none retaken); c = 1 everywhere at the"
        " end; J up to 5.4 (free swelling: e^(3 x 0.56) = 5.37).",
    ),
    (
        "Implicit_swelling_eta_0.56_past_c_1",
        60,
        [
            "Here c starts at 0.7 (stress-free) and is left to run past c = 1 (maxTime 60 us):",
            "constant_rate takes c beyond <max_concentration> and the range diagnostic stops the",
            "run at the step that passes it; the last good state is rebuilt by replaying the",
            "quasi-static steps.",
        ],
        "stops at step 6 (exit 3, t = 36 us): concentration 1.02 above 1 at t = 33 us, the"
        " middle of the step's RKL2 pass (the range diagnostic); the last good state (step 5)"
        " has c = 1.",
    ),
]:
    case(
        name,
        [
            "Quasi-static (impm, implicit, dynamic false), large swelling: eta = 0.56 and c rising",
            "uniformly from 0 (constant_rate 0.01 per us), base fixed: the free block would grow",
            "e^0.56 = 1.75-fold per axis; held at its base and in z (plane strain) it yields.",
            "<max_concentration_change> 0.25 and delt_max 25 us: steps of at most 25 us; the",
            "default error control ends them on the output times.",
        ]
        + notes,
        outcome,
        rate=0.01,
        c0=0.7 if maxTime == 60 else 0.0,
        maxTime=maxTime,
        grid=(0.3, 0.4),
        **dict(IMPLICIT, delt_max="25", impm={"max_concentration_change": 0.25})
    )
for label, sigmaY, H, outcome in [
    (
        "yield_0.14",
        0.14,
        SILICON["H"],
        "runs to maxTime (10 steps, none retaken); c = 0.5; J in [1, 2.5].",
    ),
    (
        "hardening_11.5",
        1.4,
        11.5,
        "runs to maxTime (10 steps, none retaken); c = 0.5; J in [0.9, 2.6].",
    ),
]:
    case(
        "Implicit_%s_walls" % label,
        [
            "Quasi-static, heavy plasticity: yield %g GPa, hardening modulus %g GPa; the block"
            % (sigmaY, H),
            "fills a channel (x- symmetry plane, x+ and the base no-slip walls, plane strain in z)",
            "and c rises uniformly to 0.5 (constant_rate 0.01 per us to 50 us): all its swelling",
            "must go up, so it flows plastically, sheared along the walls.",
        ],
        outcome,
        rate=0.01,
        maxTime=50,
        grid=(0.1, 0.4),
        walls="sides",
        sigmaY=sigmaY,
        H=H,
        **IMPLICIT
    )
for kind, notes, outcome in [
    (
        "single_velocity",
        ["single_velocity contact: both materials share one set of unknowns (bonded)."],
        "runs to maxTime (10 steps); the bonded substrate is strained (its J leaves 1).",
    ),
    (
        "null",
        [
            "null contact: each material has its own unknowns, the silicon is a free body (no",
            "face holds it; the regularisation alpha m I removes its rigid modes).",
        ],
        "runs to maxTime (10 steps); the substrate is untouched (J = 1 there).",
    ),
    (
        "exclude",
        [
            "single_velocity contact with <ExcludeMaterial>, which the implicit path does not",
            "support: setup refuses it.",
        ],
        "refused at setup (exit 2, nothing written): <ExcludeMaterial> with <time_integrator>"
        "implicit is not supported.",
    ),
]:
    case(
        "Implicit_contact_%s" % kind,
        [
            "Quasi-static, two materials: an elastic substrate 0.1 x 0.05 um (K = 180 GPa,",
            "G = 76 GPa, no lithium) fixed at its base, the silicon block 0.1 x 0.1 um on it; c",
            "rises uniformly to 0.5 in the silicon (constant_rate 0.01 per us to 50 us).",
        ]
        + notes,
        outcome,
        rate=0.01,
        maxTime=50,
        grid=(0.2, 0.3),
        substrate=kind,
        **IMPLICIT
    )


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for name, notes, quick, changes in CASES:
        write(name, notes, quick, **changes)

"""The paper's silicon (Gritton et al.) and the .ups blocks the input generators share.

Imported by make_paper_inputs.py and make_stability_inputs.py. Units: um, us, pg (1 GPa = 1e6,
1 m^2/s = 1e6 um^2/us).
"""

GPA = 1e6

SILICON = dict(K=67.0, G=31.0, sigmaY=1.4, H=1.15)  # GPa
SUBSTRATE = dict(K=180.4, G=76.0, sigmaY=0.7, H=1.15)  # GPa


def flow_model(kind, m):
    """The <flow_model> and <yield_condition> of `kind` (elastic, perfect or hardening) for material m."""
    if kind == "elastic":
        return ""
    if kind == "perfect":
        return (
            '<flow_model type="johnson_cook"><A>%g</A><B>0</B><C>0</C><n>0</n><m>1</m></flow_model>\n'
            '          <yield_condition type="vonMises"/>' % (m["sigmaY"] * GPA)
        )
    return (
        '<flow_model type="isotropic_hardening"><sigma_Y>%g</sigma_Y><K>%g</K></flow_model>\n'
        '          <yield_condition type="vonMises"/>' % (m["sigmaY"] * GPA, m["H"] * GPA)
    )


def non_linear1_diffusion(D0, alpha, beta, pmax, more=""):
    """D = D0 exp(alpha c - beta clamp(p, 0, p_max)), D0 in m^2/s, p_max in GPa; `more` follows tuning5."""
    return """<diffusion_model type="non_linear1">
          <diffusivity>%g</diffusivity>
          <max_concentration>1.0</max_concentration>
          <use_pressure>true</use_pressure>
          <tuning1>%g</tuning1>
          <tuning2>%g</tuning2>
          <tuning3>0.0</tuning3>
          <tuning4>%g</tuning4>
          <tuning5>1e-6</tuning5>%s
        </diffusion_model>""" % (
        D0 * 1e6,
        alpha,
        beta,
        pmax,
        more,
    )


def max_timesteps(steps):
    """The <max_Timesteps> line of <Time> (none for steps = 0)."""
    return "\n    <max_Timesteps>%d</max_Timesteps>" % steps if steps else ""


def data_archiver(name, interval, saves, more=""):
    """<DataArchiver> writing the labels `saves` to NAME.uda every `interval`; `more` (lines) follows them."""
    return (
        """  <DataArchiver>
    <filebase>%s.uda</filebase>
    <outputInterval>%g</outputInterval>
"""
        % (name, interval)
        + "".join('    <save label="%s"/>\n' % label for label in saves)
        + more
        + "  </DataArchiver>"
    )


def scalar_flux(curve_id, geometry, time_points, extra=""):
    """A <scalar_flux> on the particles `geometry` selects, its load curve `curve_id` given by
    `time_points`; `extra`: further tags of the block."""
    return """
      <scalar_flux>
        <geom_object>%s</geom_object>
        <load_curve><id>%d</id>%s</load_curve>%s
      </scalar_flux>""" % (
        geometry,
        curve_id,
        time_points,
        extra,
    )


def substrate_material(density, flow, box, res):
    """The substrate: SUBSTRATE's moduli, no swelling, no lithium. `flow` is its flow model's
    lines ("" for none), `box` its geometry piece, `res` its particles per cell."""
    return """
      <material name="substrate">
        <density>%g</density>
        <constitutive_model type="rf_elastic_plastic">
          <bulk_modulus>%g</bulk_modulus>
          <shear_modulus>%g</shear_modulus>
          <volume_expansion_coeff>0.0</volume_expansion_coeff>
          <equation_of_state type="default_hypo"/>%s
        </constitutive_model>
        <diffusion_model type="jg">
          <diffusivity>0.0</diffusivity>
          <max_concentration>1.0</max_concentration>
        </diffusion_model>
        <geom_object>
          %s
          <res>%s</res>
          <velocity>[0.0, 0.0, 0.0]</velocity>
          <concentration>0</concentration>
        </geom_object>
      </material>""" % (
        density,
        SUBSTRATE["K"] * GPA,
        SUBSTRATE["G"] * GPA,
        "\n          " + flow if flow else "",
        box,
        res,
    )

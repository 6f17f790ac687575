"""Edges of the component physics: the air's first-order lag against its closed form, the mount on a robot whose
gravity is not along base z, link-section and encoder figures that cannot be right, a box section's orientation, a
bearing without its runout, and the parts table's units for a prismatic joint's parts."""

from __future__ import annotations

import textwrap

import numpy as np
import pytest

import tolalloc
from tolalloc.allocate.parts_result import part_figures
from tolalloc.errormodel.parts import Conditions, PartEffects
from tolalloc.exceptions import TolallocError
from tolalloc.physics.compliance import mount_columns, mount_tilt
from tolalloc.physics.loads import base_moment
from tolalloc.physics.thermal_history import lagged
from tolalloc.robot.components import MATERIALS
from tolalloc.robot.components_io import read_encoder, read_section

# a horizontal cantilever: j1 about the vertical, j2 about y at the root of a 1 m tube along x, a wrist j3; a 10 kg
# mass at the tip
CANTILEVER = """
name = "cant"
gravity = GRAVITY
[[chain]]
link = "base"
vector_mm = [0, 0, 100]
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-90, 90]
[[chain]]
joint = "j2"
type = "revolute"
axis = [0, 1, 0]
limits_deg = [-10, 10]
[[chain]]
link = "arm"
vector_mm = [1000, 0, 0]
[[chain]]
joint = "j3"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-10, 10]
[[chain]]
link = "tool"
vector_mm = [0, 0, -50]
[[masses]]
link = "tool"
mass_kg = 10.0
com_mm = [1000, 0, 50]
[components.links.arm]
section = "tube"
outer_diameter_mm = 60
wall_mm = 3
material = "steel"
"""


def cantilever(tmp_path, extra: str = "", gravity: str = "[0, 0, -1]"):
    path = tmp_path / "cant.toml"
    path.write_text(textwrap.dedent(CANTILEVER.replace("GRAVITY", gravity) + extra))
    return tolalloc.load_robot(str(path))


# ------------------------------------------------------------------------------------------------ the air's lag
@pytest.mark.parametrize("step_min", [1.0, 10.0, 30.0])
def test_lag_of_a_ramp_is_exact_at_any_sampling(step_min):
    """A ramp T = r t through dy/dt = (T - y) / tau from y(0) = T(0): y = r (t - tau (1 - e^(-t/tau))). The lag is
    exact for a log linear between samples, so sparse samples (30 min against tau = 30 min) give the same values."""
    tau, rate = 1800.0, 1.0 / 3600.0
    t = np.arange(0.0, 4 * 3600.0 + 1, step_min * 60.0)
    y = lagged(t, rate * t, tau)
    assert y == pytest.approx(rate * (t - tau * (1 - np.exp(-t / tau))), abs=1e-12)
    assert rate * t[-1] - y[-1] == pytest.approx(rate * tau, rel=2e-3)  # the steady lag, 0.5 K


def test_lag_of_a_step_decays_and_repeated_times_hold():
    t = np.array([0.0, 100.0, 100.0, 400.0])
    T = np.array([0.0, 1.0, 1.0, 1.0])
    y = lagged(t, T, 300.0)
    # the step arrives linearly over 0-100 s: y(100) = 1 - tau/100 (1 - e^(-100/tau)); then it decays towards 1
    y100 = 1 - 3.0 * (1 - np.exp(-1 / 3.0))
    assert y[1] == pytest.approx(y100) and y[2] == y[1]
    assert y[3] == pytest.approx(1 - (1 - y100) * np.exp(-1.0))
    assert lagged(t[::-1].copy(), T[::-1].copy(), 300.0)[::-1] == pytest.approx(y)  # time order, not row order


# ------------------------------------------------------------------------------------------------ the mount
def test_mount_with_one_stiffness_tilts_about_gravity_whatever_its_direction(tmp_path):
    q = np.zeros((1, 3))
    for gravity in ("[0, 0, -1]", "[0, -0.5, -0.8660254037844386]", "[-1, 0, 0]"):
        r = cantilever(tmp_path, "[components.mount]\ntilt_stiffness_Nm_per_rad = 2.0e6\n", gravity)
        p = r.fk_internal(q)[:, :3, 3]
        M = base_moment(r, q)
        g = np.asarray(r.gravity, float)
        Mh = M - (M @ g)[:, None] * g
        assert mount_tilt(r, q, p)[0] == pytest.approx(np.cross(Mh[0] / 2.0e6, p[0]), abs=1e-15)
        assert np.abs(mount_tilt(r, q, p)).max() > 1e-5


def test_mount_with_two_stiffnesses_reads_them_about_x_and_y_or_refuses(tmp_path):
    q = np.zeros((1, 3))
    r = cantilever(tmp_path, "[components.mount]\ntilt_stiffness_Nm_per_rad = [1.0e6, 4.0e6]\n")
    p = r.fk_internal(q)[:, :3, 3]
    B, names = mount_columns(r, q, p, variant="axes")
    assert names == ["c_mount_x [rad/(N m)]", "c_mount_y [rad/(N m)]"]
    assert mount_tilt(r, q, p)[0] == pytest.approx(B[0, :, 0] / 1.0e6 + B[0, :, 1] / 4.0e6)
    tilted = cantilever(tmp_path, "[components.mount]\ntilt_stiffness_Nm_per_rad = [1.0e6, 4.0e6]\n", "[-1, 0, 0]")
    with pytest.raises(TolallocError, match="tilt_stiffness_Nm_per_rad gives two values.*one value"):
        mount_tilt(tilted, q, tilted.fk_internal(q)[:, :3, 3])


# ------------------------------------------------------------------------------------------------ figures
@pytest.mark.parametrize("figures, key", [({"youngs_modulus_GPa": -210}, "youngs_modulus"),
                                          ({"material": "steel", "youngs_modulus_GPa": 0}, "youngs_modulus"),
                                          ({"material": "steel", "shear_modulus_GPa": -5}, "shear_modulus"),
                                          ({"material": "steel", "density_kg_per_m3": -7850}, "density")])
def test_a_section_refuses_material_figures_that_are_not_positive(figures, key):
    with pytest.raises(ValueError, match=f"links.arm.{key}_[A-Za-z_0-9]+: expected positive values, got -?[0-9]"):
        read_section({"section": "tube", "outer_diameter_mm": 60, "wall_mm": 3, **figures}, "links.arm")
    kept = read_section({"section": "tube", "outer_diameter_mm": 60, "wall_mm": 3, "material": "steel",
                         "youngs_modulus_GPa": 200}, "links.arm")
    assert kept.youngs_modulus_MPa == 200e3  # a given figure wins over the material's


def test_a_box_twists_by_bredts_closed_section_and_a_thin_tube_agrees_with_it():
    """Roark (Table 10.7, hollow rectangle, walls t and t1): K = 2 t t1 (a-t)^2 (b-t1)^2 / (a t + b t1 - t^2 - t1^2);
    a round tube's polar moment is Bredt's 4 A_m^2 t / s = 2 pi r_m^3 t times (1 + (t / 2 r_m)^2), exactly."""
    a, b, t = 220.0, 260.0, 12.0
    box = read_section({"section": "box", "width_mm": a, "height_mm": b, "wall_mm": t, "material": "steel"}, "l")
    roark = 2 * t * t * (a - t) ** 2 * (b - t) ** 2 / (a * t + b * t - 2 * t**2)
    assert box.torsion_mm4 == pytest.approx(roark, rel=1e-12)
    assert box.torsion_mm4 < 2 * box.inertia_mm4  # the polar-moment stand-in overstated a box's stiffness
    assert box.GJ_Nmm2 == pytest.approx(box.shear_modulus_MPa * roark, rel=1e-12)
    D, w = 200.0, 2.0
    tube = read_section({"section": "tube", "outer_diameter_mm": D, "wall_mm": w, "material": "steel"}, "l")
    r_m = (D - w) / 2
    assert tube.torsion_mm4 == pytest.approx(2 * np.pi * r_m**3 * w * (1 + (w / (2 * r_m)) ** 2), rel=1e-12)


def test_every_material_has_a_poisson_ratio_of_a_real_isotropic_solid():
    for name, (E, G, *_rest) in MATERIALS.items():
        assert 0.0 < E / (2 * G) - 1 < 0.5, name


def test_an_encoder_eccentricity_needs_its_scale_radius_and_an_output_side_rotary_scale():
    ok = read_encoder({"side": "output", "accuracy_arcsec": 20, "eccentricity_um": 5, "scale_radius_mm": 50}, "e",
                      True)
    assert ok.eccentricity == pytest.approx(0.005) and ok.scale_radius_mm == 50
    with pytest.raises(ValueError, match="e.eccentricity_um: .*scale_radius_mm"):
        read_encoder({"side": "output", "accuracy_arcsec": 20, "eccentricity_um": 5}, "e", True)
    with pytest.raises(ValueError, match="e.eccentricity_um: .*motor-side"):
        read_encoder({"side": "motor", "accuracy_arcsec": 20, "eccentricity_um": 5, "scale_radius_mm": 50}, "e", True)
    with pytest.raises(ValueError, match="e.eccentricity_um: .*linear"):
        read_encoder({"side": "output", "accuracy_mm": 0.01, "eccentricity_um": 5, "scale_radius_mm": 50}, "e", False)


def test_a_bearing_without_its_runout_is_named_with_its_key(tmp_path):
    r = cantilever(tmp_path, "[components.joints.j2.bearing]\nprecision_class = \"P5\"\nspan_mm = 80\nbore_mm = 60\n")
    fx = PartEffects(r, np.zeros((1, 3)), 0.0, 20.0, Conditions((0.0, 0.0), (20.0, 20.0)))
    with pytest.raises(TolallocError, match="joint 'j2'.*components.joints.j2.bearing.radial_runout_um"):
        fx.terms()


def test_the_parts_table_gives_a_prismatic_joints_parts_in_mm_and_newtons():
    tc = tolalloc.load_robot("tool_changer")
    slots = tc.components.slots
    key = next(k for k, s in slots.items() if k[1] == "reducer" and s.options[0].motion == "linear")
    screw = slots[key].options[0]
    line = part_figures("reducer", slots[key].resolve(screw.name), screw.motion)
    assert "arcmin" not in line and " um" in line and "N/um" in line and "N m" not in line
    rotary = next(s for k, s in slots.items() if k[1] == "reducer" and s.options[0].motion == "rotary")
    line = part_figures("reducer", rotary.resolve(rotary.options[0].name), "rotary")
    assert "arcmin" in line and "N m/rad" in line


def test_a_refused_figure_is_named_by_its_file_key_and_value():
    """The check runs on internal units (N m/rad) but the message gives what the file says."""
    from tolalloc.robot.components_io import read_reducer

    with pytest.raises(ValueError, match=r"j2.reducer.stiffness_Nm_per_arcmin: expected positive values, got -5"):
        read_reducer({"stiffness_Nm_per_arcmin": -5, "rated_torque_Nm": 100}, "j2.reducer", True)
    with pytest.raises(ValueError, match=r"j2.reducer.lost_motion_arcmin: expected non-negative values, got -1"):
        read_reducer({"lost_motion_arcmin": -1}, "j2.reducer", True)


def test_static_compliance_loads_and_reads_the_mechanical_interface(tmp_path):
    """ISO 9283 clause 10 loads the mechanical interface: a tool offset in the robot file changes nothing."""
    from dataclasses import replace

    from tolalloc.acceptance import static_compliance

    r = cantilever(tmp_path, "[components.mount]\ntilt_stiffness_Nm_per_rad = 2.0e5\n")
    q = np.zeros(3)
    flange = static_compliance(r, q, load_n=100.0, steps=2)
    tooled = static_compliance(replace(r, tool_offset_mm=np.array([0.0, 0.0, -300.0])), q, load_n=100.0, steps=2)
    assert tooled.displacement_mm == pytest.approx(flange.displacement_mm, abs=1e-15)
    assert np.abs(flange.displacement_mm).max() > 1e-3


def test_a_motor_cannot_warm_its_links_beyond_its_own_rise():
    from tolalloc.robot.components_io import read_motor

    figures = {"winding_resistance_ohm": 1.2, "torque_constant_Nm_per_A": 0.45, "thermal_resistance_K_per_W": 1.0,
               "thermal_time_constant_s": 1500.0}
    assert read_motor({**figures, "link_coupling_pct": 100}, "j1.motor").link_coupling == pytest.approx(1.0)
    with pytest.raises(ValueError, match=r"j1.motor.link_coupling_pct: .*at most 100 %, got 130"):
        read_motor({**figures, "link_coupling_pct": 130}, "j1.motor")


def test_a_motor_heats_by_its_three_phase_copper_loss():
    """A star winding of line-to-line resistance R carries I = tau / (N k_t) rms in each of three phases of R / 2:
    loss 3 (R / 2) I^2; the rise is R_th times it times the duty."""
    from tolalloc.physics.thermal_design import motor_rise
    from tolalloc.robot import Joint, Link, Robot
    from tolalloc.robot.components import Components, JointComponents, Motor, Reducer

    R, kt, N, Rth, tau, duty = 1.2, 0.45, 100.0, 0.8, 90.0, 0.5
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([500.0, 0.0, 0.0])))
    robot = Robot("arm", chain)
    parts = JointComponents(reducer=Reducer(ratio=N), motor=Motor(R, kt, Rth, 1800.0))
    object.__setattr__(robot, "components", Components(joints={"j1": parts}))
    current = tau / (N * kt)
    assert motor_rise(robot, np.array([[tau]]), duty)[0, 0] == pytest.approx(Rth * duty * 3 * (R / 2) * current**2)


def test_a_robot_file_box_is_checked_against_its_link_and_bends_by_its_orientation(tmp_path):
    """The cantilever's arm as a 100 x 200 x 5 mm box: a height along the arm is refused naming the file's key; with
    its height vertical the arm drops less than on its side (I about the width axis is the larger)."""
    def robot(direction):
        box = (f'section = "box"\nwidth_mm = 100\nheight_mm = 200\nwall_mm = 5\nmaterial = "steel"\n'
               f"height_direction = {direction}\n")
        path = tmp_path / "box.toml"
        path.write_text(textwrap.dedent(CANTILEVER.replace("GRAVITY", "[0, 0, -1]")).split("[components.links.arm]")[0]
                        + "[components.links.arm]\n" + box)
        return tolalloc.load_robot(str(path))

    with pytest.raises(TolallocError, match=r"components.links.arm.height_direction: .*deg off the plane"):
        robot("[1, 0, 0]")
    from tolalloc.physics import beam_sag

    q, tip = np.zeros((1, 3)), np.array([[1000.0, 0.0, 50.0]])
    upright, flat = (beam_sag(robot(d), q, tip)[0, 2] for d in ("[0, 0, 1]", "[0, 1, 0]"))
    assert flat < upright < 0.0

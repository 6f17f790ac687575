"""The component catalogue (bought parts) and the robot file's catalogue slots: figures against the catalogues' own
worked examples and tables, the user merge, and one clear error per bad input."""

import textwrap

import pytest

import tolalloc
from tolalloc.robot.components import ARCMIN
from tolalloc.robot.part_catalogue import builtin_catalogue, load_part_catalogue

CHAIN = """
name = "two"
gravity = [0, 0, -1]
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 0, 1]
[[chain]]
link = "l1"
vector_mm = [400, 0, 0]
[[chain]]
joint = "j2"
type = "prismatic"
axis = [1, 0, 0]
limits_mm = [0, 100]
[[chain]]
link = "l2"
vector_mm = [100, 0, 0]
"""


def robot_file(tmp_path, components: str, name="r.toml"):
    p = tmp_path / name
    p.write_text(CHAIN + textwrap.dedent(components))
    return tolalloc.load_robot(str(p))


def test_harmonic_drive_worked_example_and_iso492_rows():
    cat = builtin_catalogue()
    red = cat.get("reducer", "HD-CSG-32-100").spec
    # Harmonic Drive's calculation example (CHA manual, 4.2): T = 60 N m on size 32 -> 7.15e-4 rad (2.5 arcmin)
    assert red.deflection(60.0) == pytest.approx(7.15e-4, rel=2e-3)
    assert red.deflection(-60.0) == pytest.approx(-7.15e-4, rel=2e-3)
    assert red.transmission_accuracy == pytest.approx(1.0 * ARCMIN)
    assert cat.get("reducer", "HD-CSG-32-100-SA").spec.transmission_accuracy == pytest.approx(0.5 * ARCMIN)
    # ISO 492 inner-ring radial runout Kia, bore 50-80 mm: P0 20, P6 10, P5 5 um
    for cls, kia in (("P0", 20), ("P6", 10), ("P5", 5)):
        assert cat.get("bearing", f"ISO492-{cls}").spec.runout_at(60.0) == pytest.approx(kia * 1e-3)
    fam = cat.family("reducer", "HD-CSG-32-100")
    assert [p.grade for p in fam] == ["standard", "special"]  # cheapest first
    assert set(cat.to_frame()["kind"]) == {"reducer", "encoder", "bearing", "motor"}


def test_user_catalogue_merges_over_the_builtin(tmp_path):
    f = tmp_path / "mine.toml"
    f.write_text(textwrap.dedent("""
        [reducers."HD-CSG-32-100"]
        family = "HD-CSG-32-100"
        stiffness_Nm_per_rad = 1.0e5
        cost = 33
        [encoders."MY-ENC"]
        accuracy_arcsec = 4
        cost = 9
    """))
    cat = load_part_catalogue(f)
    assert cat.get("reducer", "HD-CSG-32-100").cost == 33
    assert cat.get("reducer", "HD-CSG-32-100").cost_source == f"given in component catalogue {f}"
    assert cat.get("encoder", "MY-ENC").spec.accuracy == pytest.approx(4 * ARCMIN / 60)
    assert cat.get("reducer", "HD-CSG-40-100").cost_source == "assumed"  # untouched entries stay


@pytest.mark.parametrize("entry, match", [
    ("[reducers.X]\nlost_motion = 1.0\ncost = 1", r"reducers\.X\.lost_motion: the key has no unit; write it as "
                                                  r"lost_motion_rad or lost_motion_deg"),
    ("[reducers.X]\nstiffness_Nm_per_rad = [3e4, 2e4, 4e4]\ntorque_bands_Nm = [5, 20]",
     r"reducers\.X\.stiffness: the curve softens with torque .* expected K1 <= K2 <= K3"),
    ("[encoders.E]\naccuracy_arcsec = 5\ncost = -1", r"encoders\.E\.cost: expected a number >= 0"),
    ("[bearings.B]\nprecision_class = \"P5\"\nbore_limits_mm = [10, 30]\nradial_runout_um = [4, 5]",
     r"bearings\.B: expected 3 increasing bore_limits_mm for 2 radial_runout values"),
    ("[gears.X]\nratio = 3", r"unknown table 'gears'; expected reducers, encoders, bearings, motors"),
])
def test_bad_catalogue_entries(tmp_path, entry, match):
    f = tmp_path / "bad.toml"
    f.write_text(entry)
    with pytest.raises(ValueError, match=match):
        load_part_catalogue(f)


def test_robot_slots_choice_and_own_catalogue_file(tmp_path):
    (tmp_path / "parts.toml").write_text('[encoders."CHEAP"]\nfamily = "E"\naccuracy_arcsec = 60\ncost = 1\n'
                                         '[encoders."GOOD"]\nfamily = "E"\naccuracy_arcsec = 5\ncost = 7\n')
    r = robot_file(tmp_path, """
        [components]
        catalogue_file = "parts.toml"
        [components.joints.j1]
        reducer = { family = "HD-CSG-25-100" }
        encoder = { family = "E" }
        bearing = { options = ["ISO492-P6", "ISO492-P4"], bore_mm = 60, span_mm = 40 }
        [components.joints.j2]
        reducer = { part = "BS-40-10-C5" }
    """)
    slots = r.components.slots
    assert slots[("j1", "encoder")].names == ("CHEAP", "GOOD")
    assert slots[("j2", "reducer")].names == ("BS-40-10-C5",)
    assert r.components.joint("j1").reducer is None  # a slot fills the joint only once a part is chosen
    c = r.components.with_choice({("j1", "reducer"): "HD-CSG-25-100-SA", ("j1", "encoder"): "GOOD",
                                  ("j1", "bearing"): "ISO492-P4"})
    assert c.joint("j1").reducer.transmission_accuracy == pytest.approx(0.5 * ARCMIN)
    assert c.joint("j1").bearing.radial_runout == pytest.approx(0.004)  # ISO 492 P4, bore 50-80 mm
    assert c.joint("j2").reducer.type == "ball_screw"  # the slot of one part is chosen by itself
    with pytest.raises(ValueError, match=r"components.joints.j1.reducer: no part chosen; options: HD-CSG-25-100, "
                                         r"HD-CSG-25-100-SA"):
        r.components.with_choice({})


@pytest.mark.parametrize("slot, match", [
    ('reducer = { family = "HD-CSG-99-100" }', r"j1.reducer: the catalogue has no reducer of family 'HD-CSG-99-100' "
                                               r"\(an empty slot\); reducer families: BS-40-10, HD-CSG-14-100"),
    ('reducer = { options = [] }', r"j1.reducer.options: expected a non-empty list of part names \(an empty slot "
                                   r"cannot be bought\)"),
    ('reducer = { part = "BS-40-10-C5" }', r"j1.reducer: BS-40-10-C5 is a linear part, but j1 is a revolute joint; "
                                           r"choose rotary parts"),
    ('bearing = { family = "ISO492", span_mm = 40 }', r"j1.bearing: a bearing slot needs bore_mm"),
    ('bearing = { family = "ISO492", bore_mm = 900, span_mm = 40 }', r"bore_mm = 900 lies outside the bore ranges of "
                                                                      r"class P0 \(18 < d <= 250 mm\)"),
    ('encoder = { part = "RING-100-STD", side = "motor" }', r"j1.encoder: unknown key 'side'"),
])
def test_bad_slots(tmp_path, slot, match):
    with pytest.raises(tolalloc.TolallocError, match=match):
        robot_file(tmp_path, f"[components.joints.j1]\n{slot}\n")


def test_builtin_robots_have_slots_and_sections():
    for name, joints in (("ur10", 6), ("tool_changer", 6)):
        c = tolalloc.load_robot(name).components
        assert {j for j, _ in c.slots} == {jt.name for jt in tolalloc.load_robot(name).joints}
        assert c.payload.rated_kg > 0 and c.links and c.mount.tilt_stiffness is not None
        choice = {k: s.names[-1] for k, s in c.slots.items()}
        assert all(j.reducer is not None for j in c.with_choice(choice).joints.values())
    # the diagnosis reads the joints' entries: slots leave them empty, so it sees no gear ratio from them
    assert tolalloc.load_robot("ur10").components.gear_ratios(["shoulder_pan_joint"]) is None

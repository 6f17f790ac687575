"""Cost-tolerance laws and the costs file."""

import casadi as ca
import cvxpy as cp
import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.allocate.costs import DEFAULT_COSTS, CostModel, cost_set, load_costs
from tolalloc.errormodel import build_error_model

LAWS = [CostModel("reciprocal", 1.0, 2.0, 0.1, 0.01, 1.0),
        CostModel("reciprocal_power", 0.5, 1.5, 0.1, 0.01, 1.0, k=2.0),
        CostModel("exponential", 0.2, 3.0, 0.1, 0.01, 1.0)]


@pytest.fixture(scope="module")
def model():
    return build_error_model(load_robot("tool_changer"))


def test_laws_at_reference_and_closed_forms():
    rec, pw, ex = LAWS
    assert rec.cost(0.1) == pytest.approx(3.0)            # a + b at t_ref
    assert rec.cost(0.05) == pytest.approx(1.0 + 2.0 * 2)  # A + B/t with B = b t_ref
    assert pw.cost(0.05) == pytest.approx(0.5 + 1.5 * 4)
    assert ex.cost(0.2) == pytest.approx(0.2 + 3.0 * np.exp(-2.0))


@pytest.mark.parametrize("law", LAWS, ids=lambda m: m.model)
def test_convex_in_u_and_libraries_agree(law):
    u = np.linspace(0.02, 50, 400)
    c = law.cost(law.t_ref * np.sqrt(u))
    assert np.all(np.diff(c, 2) >= -1e-12)  # convex in u = (t/t_ref)^2
    assert np.all(np.diff(c) < 0)           # cheaper when looser
    uv = cp.Variable(1)
    expr = law.cost_u(uv, "cvxpy")
    assert expr.is_convex()
    for val in (0.3, 2.0, 7.0):
        uv.value = np.array([val])
        assert float(np.ravel(expr.value)[0]) == pytest.approx(float(law.cost(law.t_ref * np.sqrt(val))), rel=1e-12)
        assert float(law.cost_u(ca.DM(val), "casadi")) == pytest.approx(float(law.cost(law.t_ref * np.sqrt(val))), rel=1e-12)


def test_defaults_resolve_for_the_tool_changer(model):
    cs = cost_set(model)
    assert cs.z == DEFAULT_COSTS["z"] and set(cs.role) == {"allocate"}
    dd4 = cs.models[cs.names.index("dd4")]  # prismatic drive: mm section
    dth1 = cs.models[cs.names.index("dth1")]
    assert dd4.t_ref == pytest.approx(0.05)
    assert dth1.t_ref == pytest.approx(np.deg2rad(0.01))
    frame = cs.to_frame(model)
    assert frame.loc[lambda f: f.parameter == "dth1", "t_min_deg"].item() == pytest.approx(0.0005)


def test_cost_frame_gives_each_tolerance_in_its_rows_unit(tmp_path, model):
    f = tmp_path / "c.toml"
    f.write_text('[parameters.e6x]\nfixed = true\ntol_deg = 0.02\n[parameters.dl3]\nfixed = true\ntol_mm = 0.04\n')
    frame = load_costs(f, model).to_frame(model).set_index("parameter")
    mm = frame["unit"] == "mm"
    for name in ("t_ref", "t_min", "t_max", "fixed_tol"):
        assert name not in frame and frame[f"{name}_mm"][~mm].isna().all() and frame[f"{name}_deg"][mm].isna().all()
    # a length and an angle, in mm and deg as the defaults and the file give them
    assert frame.loc["dd4", ["t_ref_mm", "t_min_mm", "t_max_mm"]].tolist() == pytest.approx([0.05, 0.002, 1.0])
    assert frame.loc["dth1", ["t_ref_deg", "t_min_deg", "t_max_deg"]].tolist() == pytest.approx([0.01, 0.0005, 0.5])
    assert frame.loc["dl3", "fixed_tol_mm"] == pytest.approx(0.04) and frame.loc["e6x", "fixed_tol_deg"] == pytest.approx(0.02)
    assert frame.loc["dth1", ["fixed_tol_mm", "fixed_tol_deg"]].isna().all()  # allocatable: no fixed tolerance


def test_costs_file_overrides_units_roles(tmp_path, model):
    f = tmp_path / "c.toml"
    f.write_text("""
z = 2.0
[kinds.axis_deflection]
model = "exponential"
t_ref_rad = 1e-4
t_min_rad = 1e-5
[parameters.dl3]
t_min_mm = 0.02
b = 4.0
[parameters.dth6]
exclude = true
[parameters.e6x]
fixed = true
tol_deg = 0.02
[parameters.e6y]
fixed = true
""")
    cs = load_costs(f, model)
    assert cs.z == 2.0 and cs.excluded == ("dth6",) and "dth6" not in cs.names
    e1x = cs.models[cs.names.index("e1x")]
    assert e1x.model == "exponential" and e1x.t_ref == pytest.approx(1e-4) and e1x.t_min == pytest.approx(1e-5)
    assert e1x.t_max == pytest.approx(np.deg2rad(0.5))  # the default kept where not overridden
    dl3 = cs.models[cs.names.index("dl3")]
    assert dl3.t_min == 0.02 and dl3.b == 4.0 and dl3.t_ref == 0.1
    k = cs.names.index("e6x")
    assert cs.role[k] == "fixed" and cs.fixed_tol[k] == pytest.approx(np.deg2rad(0.02))
    k = cs.names.index("e6y")  # fixed without a value: the model's sigma * z
    assert cs.fixed_tol[k] == pytest.approx(model.params[model.index("e6y")].sigma * 2.0)
    assert load_costs(f, model, z=np.sqrt(3)).z == pytest.approx(np.sqrt(3))


@pytest.mark.parametrize("text, match", [
    ("[kinds.link_length]\nt_min_deg = 0.1\n", "wrong unit"),
    ("[kinds.link_length]\nwidth_mm = 0.1\n", "unknown key"),
    ("[kinds.link_length]\nt_min_mm = 2\nt_max_mm = 1\n", "t_min > t_max"),
    ("[kinds.link_length]\nmodel = 'cubic'\n", "model expected"),
    ("[parameters.nope]\nb = 1\n", "unknown error parameter"),
    ("[kinds.bogus]\nb = 1\n", "unknown kind"),
    ("z = -1\n", "z"),
    ("[kinds.link_length]\nb = 0\n", "b > 0"),
])
def test_bad_costs_files(tmp_path, model, text, match):
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(TolallocError, match=match):
        load_costs(f, model)


def test_missing_file_and_nothing_to_allocate(tmp_path, model):
    with pytest.raises(TolallocError, match="not found"):
        load_costs(tmp_path / "none.toml", model)
    with pytest.raises(TolallocError, match="no parameter is left"):
        cost_set(model, {"parameters": {nm: {"fixed": True} for nm in model.names}})


@pytest.mark.parametrize("text, match", [
    # regressions: kinds = 3 gave a traceback; fixed = "yes" was taken as true; the unknown-parameter message
    # did not name the file and section
    ("kinds = 3\n", r"costs .*bad\.toml: kinds expected tables \[kinds\.NAME\]"),
    ("[parameters.dth6]\nfixed = 'yes'\n", r"\[parameters\.dth6\]: fixed expected true or false, got 'yes'"),
    ("[parameters.nope]\nb = 1\n", r"costs .*bad\.toml \[parameters\.nope\]: unknown error parameter 'nope'"),
])
def test_malformed_costs_files_name_file_and_field(tmp_path, model, text, match):
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(TolallocError, match=match):
        load_costs(f, model)


def test_uniform_distribution_sets_z_and_is_recorded(model):
    cs = cost_set(model, {"distribution": "uniform"})
    assert cs.distribution == "uniform" and cs.z == pytest.approx(np.sqrt(3))
    assert cost_set(model, None, distribution="uniform").distribution == "uniform"
    explicit = cost_set(model, {"distribution": "uniform"}, z=3.0)  # an explicit z means normal errors
    assert explicit.distribution == "normal" and explicit.z == 3.0
    assert cost_set(model, None).distribution == "normal"


@pytest.mark.parametrize("text, match", [
    ("[kinds.joint_drive]\nt_min_mm = 0.001\n",
     r"^costs .*bad.toml \[kinds.joint_drive\]: t_min_mm has the wrong unit: joint_drive tolerances are in deg; use "
     r"t_min_deg \(or t_min_rad\)\.$"),
    ("[parameters.dl2]\ntol_deg = 0.1\nfixed = true\n",
     r"^costs .*bad.toml \[parameters.dl2\]: tol_deg has the wrong unit: dl2's tolerances are in mm; use tol_mm"),
    ("[kinds.joint_drive]\nt_ref_deg = 'x'\n", r"^costs .*bad.toml \[kinds.joint_drive\]: t_ref_deg expected numbers, "
                                              r"got 'x'\.$"),
    ("[parameters.dth1]\nt_max_deg = 400\n", r"^costs .*bad.toml \[parameters.dth1\]: t_max_deg = 400(\.0)? goes beyond "
                                            r"\+-360 deg; expected angles within one turn each way \(if .*\)\.$"),
    ("[kinds.link_length]\nt_min_mm = 2\nt_max_mm = 1\n",
     r"^costs .*bad.toml \[kinds.link_length\] \(dl1\): process limits t_min > t_max \(2 > 1 mm\); swap them\.$"),
])
def test_costs_errors_name_the_section_written_and_its_unit(tmp_path, model, text, match):
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(TolallocError, match=match):
        load_costs(f, model)

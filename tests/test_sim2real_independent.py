"""The independent sim-to-real benchmark (studies/sim2real_independent): its generator imports nothing of tolalloc,
its kinematics agrees with tolalloc's, and each physical law meets a known answer."""

import ast
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "studies" / "sim2real_independent"
PKG = STUDY / "sim2real_indep"
sys.path.insert(0, str(STUDY))

from sim2real_indep import effects_body as eb  # noqa: E402
from sim2real_indep import kinematics as kin  # noqa: E402
from sim2real_indep import physics as ph  # noqa: E402
from sim2real_indep.scoring import score  # noqa: E402


def _load(name):
    """The study's top-level script ``name``.py under a name no other test module uses."""
    spec = importlib.util.spec_from_file_location(f"sim2real_independent_{name}", STUDY / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up there
    spec.loader.exec_module(mod)
    return mod


gen = _load("generator")
orc = _load("oracle")


def _imports(path: Path) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            out.add(node.module)
            out |= {f"{node.module}.{a.name}" for a in node.names}
    return out


def test_generator_imports_nothing_of_tolalloc():
    """generator.py, oracle.py and every study module they reach (transitively) import no tolalloc module."""
    seen, todo = set(), [STUDY / "generator.py", STUDY / "oracle.py"]
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        mods = _imports(path)
        assert not any(m.split(".")[0] == "tolalloc" for m in mods), f"{path.name} imports tolalloc"
        todo += [PKG / f"{m.split('.')[1]}.py" for m in mods
                 if m.startswith("sim2real_indep.") and (PKG / f"{m.split('.')[1]}.py").exists()]
    reached = {p.stem for p in seen}
    assert {"kinematics", "physics", "session", "hardware", "effects_joint", "effects_body", "families"} <= reached
    assert {"effects_c", "effects_c_thermal", "effects_c_joint", "effects_c_body"} <= reached  # set C


@pytest.mark.parametrize("robot", ["ur10", "tool_changer", "kr16_like"])
def test_kinematics_agrees_with_tolalloc(robot):
    import tolalloc

    rob = tolalloc.load_robot(gen.ROBOT_FILES[robot])
    chain = kin.load_chain(gen.ROBOT_FILES[robot])
    q = rob.random_q(np.random.default_rng(3), 40)
    p, R = kin.flange(chain, q)
    T = rob.fk_internal(q)
    assert np.abs(p - T[:, :3, 3]).max() < 1e-9
    assert np.abs(R - T[:, :3, :3]).max() < 1e-12


def test_jacobian_and_gravity_loads_against_finite_differences():
    chain = kin.load_chain("tool_changer")
    rng = np.random.default_rng(1)
    q = np.c_[rng.uniform(-0.5, 0.5, (3, 3)), rng.uniform(0, 400, 3), rng.uniform(-0.5, 0.5, (3, 2))]
    probe = np.array([10.0, -20.0, 30.0])
    J = kin.position_jacobian(chain, q, kin.target(chain, q, probe))
    pos = lambda qq: kin.mass_positions(chain, qq)  # noqa: E731
    V = lambda qq: (chain.masses * kin.G * pos(qq)[..., 2] / 1000).sum(axis=1)  # potential energy [J]  # noqa: E731
    tau = kin.gravity_loads(chain, q, chain.masses, pos(q), chain.mass_body)
    for j in range(chain.n):
        h = 1e-6 if chain.revolute[j] else 1e-3
        e = np.zeros(chain.n)
        e[j] = h
        fd = (kin.target(chain, q + e, probe) - kin.target(chain, q - e, probe)) / (2 * h)
        assert np.abs(J[:, :, j] - fd).max() < 1e-5
        dV = (V(q + e) - V(q - e)) / (2 * h)
        scale = 1.0 if chain.revolute[j] else 1000.0  # N per mm of a prismatic joint -> N per m
        assert np.allclose(tau[:, j], -dV * scale, rtol=1e-6, atol=1e-6)


def test_harmonic_drive_torsion_catalogue_example():
    """Harmonic Drive's worked example, size 32: 60 N m -> 7.15e-4 rad (2.5 arcmin); odd; slope 1/K3 above T2."""
    args = (29.0, 108.0, 6.7e4, 1.1e5, 1.2e5)
    assert ph.harmonic_drive_torsion(60.0, *args) == pytest.approx(7.15e-4, abs=5e-7)
    assert ph.harmonic_drive_torsion(-60.0, *args) == pytest.approx(-ph.harmonic_drive_torsion(60.0, *args))
    slope = (ph.harmonic_drive_torsion(201.0, *args) - ph.harmonic_drive_torsion(200.0, *args))
    assert slope == pytest.approx(1 / 1.2e5)
    lm = 1.0 * ph.ARCMIN  # cycloid: half the lost motion at 3 % of rated torque, then 1/K
    assert ph.cycloid_torsion(0.03 * 412, 412, lm, 3.7e5) == pytest.approx(lm / 2)
    assert ph.cycloid_torsion(300.0, 412, lm, 3.7e5) - ph.cycloid_torsion(200.0, 412, lm, 3.7e5) == pytest.approx(
        100 / 3.7e5)


def test_harmonic_drive_error_period_and_spectrum():
    """Without the once-per-turn term the error repeats every 1/N output turn; its spectrum over a turn has lines at
    1, N and 2N cycles per turn."""
    N = 100
    th = np.linspace(0, 2 * np.pi, 4096, endpoint=False)
    amp, phase = np.array([3e-4, 1e-4, 0.0]), np.array([0.3, 1.1, 0.0])
    e = ph.harmonic_drive_error(th, N, amp, phase)
    assert np.allclose(e, ph.harmonic_drive_error(th + 2 * np.pi / N, N, amp, phase), atol=1e-15)
    spec = np.abs(np.fft.rfft(ph.harmonic_drive_error(th, N, np.array([3e-4, 1e-4, 5e-5]), phase))) * 2 / len(th)
    assert spec[[2 * N, N, 1]] == pytest.approx([3e-4, 1e-4, 5e-5], rel=1e-9)
    assert np.delete(spec, [1, N, 2 * N]).max() < 1e-12


def test_encoder_eccentricity_heidenhain_rule():
    """+-412 e/D arcsec: e = 10 um on D = 50 mm -> 82.4 arcsec peak."""
    th = np.linspace(0, 2 * np.pi, 721)
    peak = np.abs(ph.encoder_eccentricity_error(th, 10.0, 50.0, 0.0)).max()
    assert np.rad2deg(peak) * 3600 == pytest.approx(412.5 * 10 / 50, rel=1e-4)


def test_cantilever_known_answers():
    """Tip deflection and slope of a cantilever along x: F L^3/3EI, F L^2/2EI; w L^4/8EI, w L^3/6EI; M L^2/2EI,
    M L/EI; shear F L/kGA; torsion T L/GJ -- with the directions of a beam bent downwards."""
    e, L, EI, kGA, GJ = np.array([1.0, 0, 0]), 0.8, 2.0e5, 3.0e7, 1.5e5
    z, y = np.array([0, 0, 1.0]), np.array([0, 1.0, 0])
    d, r = ph.cantilever_tip(e, L, -100 * z, np.zeros(3), np.zeros(3), EI, np.inf, np.inf)
    assert d == pytest.approx(-100 * L ** 3 / (3 * EI) * z)
    assert r == pytest.approx(100 * L ** 2 / (2 * EI) * y)  # the tip pitches down: rotation about +y
    d, r = ph.cantilever_tip(e, L, np.zeros(3), np.zeros(3), -50 * z, EI, np.inf, np.inf)
    assert d == pytest.approx(-50 * L ** 4 / (8 * EI) * z)
    assert r == pytest.approx(50 * L ** 3 / (6 * EI) * y)
    d, r = ph.cantilever_tip(e, L, np.zeros(3), 20 * y, np.zeros(3), EI, np.inf, np.inf)
    assert d == pytest.approx(-20 * L ** 2 / (2 * EI) * z)
    assert r == pytest.approx(20 * L / EI * y)
    d, _ = ph.cantilever_tip(e, L, -100 * z, np.zeros(3), np.zeros(3), np.inf, kGA, np.inf)
    assert d == pytest.approx(-100 * L / kGA * z)
    _, r = ph.cantilever_tip(e, L, 5 * e, 7 * e, np.zeros(3), EI, kGA, GJ)  # axial force bends nothing
    assert r == pytest.approx(7 * L / GJ * e)
    A, I, J = ph.tube_section(0.1, 0.005)
    assert I == pytest.approx(np.pi / 64 * (0.1 ** 4 - 0.09 ** 4)) and J == pytest.approx(2 * I)


def test_first_order_step_and_ramp_responses():
    t = np.linspace(0, 7200, 241)
    step = ph.first_order_zoh(t, np.ones_like(t), 1200.0)
    assert step == pytest.approx(1 - np.exp(-t / 1200.0), abs=1e-12)
    ramp = ph.first_order_foh(t, 2e-3 * t, 1200.0, x0=0.0)
    assert ramp == pytest.approx(2e-3 * (t - 1200.0 * (1 - np.exp(-t / 1200.0))), abs=1e-12)


def test_backlash_flank_logic():
    b, h = 2e-3, 4e-4
    # unloaded joint moving +: the output trails by b/2 (+ h/2)
    assert ph.backlash_offset(1, 0.0, 5.0, b, h) == pytest.approx(-b / 2 - h / 2)
    # a gravity load above the preload holds the output on its flank whatever the approach
    assert ph.backlash_offset(1, -50.0, 5.0, b, 0.0) == pytest.approx(-b / 2)
    assert ph.backlash_offset(-1, -50.0, 5.0, b, 0.0) == pytest.approx(-b / 2)
    assert ph.backlash_offset(-1, 50.0, 5.0, b, 0.0) == pytest.approx(b / 2)


def test_link_expansion_feature_is_the_derivative():
    case = gen.generate("t", "ur10", (), 12, 5)
    ctx = case.model_ctx(np.array([5.0, 0, 20.0]))
    mask = ctx.chain.link_body == 2
    eps = 1e-6
    links = ctx.chain.links * (1 + eps * mask[:, None])
    fd = (kin.target(ctx.chain, ctx.q, ctx.probe_mm, links=links) - ctx.target) / eps
    assert ctx.link_scale_feature(mask) == pytest.approx(fd, abs=1e-5)
    # the mount's tilt moves every point perpendicular to its lever about the pivot
    parts = eb.mount_parts(ctx, {"height_mm": 0.0, "plate_axis_rad": 0.3})
    norms = np.linalg.norm(parts, axis=2) * np.linalg.norm(ctx.target, axis=1)
    cos = np.einsum("kpi,pi->kp", parts, ctx.target) / norms
    assert np.abs(cos).max() < 1e-12


def test_oracle_labels_a_geometry_only_case_none_at_the_noise_floor():
    case = gen.generate("t", "ur10", (), 60, 11)
    res = orc.run_oracle(case)
    assert res.label == "none"
    assert res.rms_geom == pytest.approx(np.sqrt(3) * case.truth["noise_mm"], rel=0.35)


def test_scoring_rules():
    base = {"named": "backlash", "effects": "", "candidates": ""}
    assert score(base | {"label": "backlash", "verdict": "effect", "effects": "backlash"})["right"]
    amb = base | {"label": "ambiguous:{backlash,joint_compliance}", "verdict": "effect", "effects": "backlash"}
    assert not score(amb)["right"] and score(amb)["confident_undecidable"] and score(amb)["right_lenient"]
    hedge = amb | {"verdict": "ambiguous", "effects": "", "candidates": "joint_compliance+backlash"}
    assert score(hedge)["right"]
    quiet = {"label": "absorbed", "named": "", "effects": "thermal", "candidates": "", "verdict": "effect"}
    assert score(quiet)["false_claim"] and not score(quiet | {"verdict": "inconclusive"})["false_claim"]


def _linear_displacement(c, ctx):
    """Target displacement (P, 3) of a Contribution at first order (joint offsets, link strains, displacements)."""
    out = np.zeros((len(ctx.q), 3))
    if c.dq is not None:
        out += np.einsum("pij,pj->pi", ctx.jac, c.dq)
    if c.strain is not None:
        for li in range(len(ctx.chain.links)):
            out += ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li) * c.strain[:, li:li + 1]
    if c.displace is not None:
        out += c.displace
    return out


def test_set_c_effects_apply_equals_features_times_true_amplitudes():
    """Set C: 24 cases on the three arms covering every family; a few new kinds' apply equals their true-structure
    features times the true amplitudes (explicit for rv_error, track, dahl; least squares for the others)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_c_body as cb
    from sim2real_indep.context import FAMILIES, FAMILY

    assert len(cs.SET_C) == 24 and cs.SETS["C"][1] == cs.SEED_C == 40_7003
    assert {c[1] for c in cs.SET_C} == {"ur10", "tool_changer", "kr16_like"}
    assert {FAMILY[k] for c in cs.SET_C for k in c[2]} == set(FAMILIES)
    case = gen.generate("t", "kr16_like", ("rv_error", "track", "dahl", "box_torsion", "twonode"), 14, 7)
    t = case.truth
    ctx = case.model_ctx(t["probe_mm"])

    def check(kind, amp=None):
        d = _linear_displacement(gen.EFFECTS[kind][1](t["params"][kind], ctx, t["hw"]), ctx)
        F = gen.EFFECTS[kind][2](t["params"][kind], ctx, t["hw"])
        A = F.reshape(len(F), -1).T
        if amp is None:
            amp = np.linalg.lstsq(A, d.ravel(), rcond=None)[0]
        assert np.abs(A @ amp - d.ravel()).max() < 1e-9 * max(1.0, np.abs(d).max())
        assert np.abs(d).max() > 1e-4  # a real effect [mm]

    rv = t["params"]["rv_error"]
    check("rv_error", np.concatenate([[a * np.cos(ph_), a * np.sin(ph_)] for g in rv
                                      for a, ph_ in zip(g["amp"], g["phase"])]).ravel())
    check("track", cb._track_amp(t["params"]["track"]))
    check("dahl", np.array([a for b in t["params"]["dahl"] for a in (b["half_b"], b["c"])]))
    check("box_torsion")
    check("twonode")

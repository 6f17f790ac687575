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
    assert {"effects_d", "effects_d_thermal", "effects_d_joint", "effects_d_body"} <= reached  # set D
    assert {"effects_e", "effects_e_thermal", "effects_e_joint", "effects_e_body"} <= reached  # set E
    assert {"effects_f", "effects_f_thermal", "effects_f_joint", "effects_f_body"} <= reached  # set F
    assert {"effects_g", "effects_g_thermal", "effects_g_joint", "effects_g_body"} <= reached  # set G
    assert {"effects_h", "effects_h_thermal", "effects_h_joint", "effects_h_body"} <= reached  # set H
    assert {"effects_i", "effects_i_thermal", "effects_i_joint", "effects_i_body"} <= reached  # set I
    assert {"effects_j", "effects_j_thermal", "effects_j_joint", "effects_j_body"} <= reached  # set J


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
    found = base | {"label": "backlash", "verdict": "effect", "effects": "backlash", "candidates": "backlash"}
    assert score(found)["right"]
    # an effect verdict names its candidates: a further effect in the final model whose family it does not claim
    # (effects thermal+backlash, backlash tied with another family) is not named
    assert not score(found | {"effects": "thermal+backlash", "candidates": "thermal"})["right"]
    assert score(found | {"effects": "backlash+thermal", "candidates": "backlash"})["right"]
    amb = base | {"label": "ambiguous:{backlash,joint_compliance}", "verdict": "effect", "effects": "backlash",
                  "candidates": "backlash"}
    assert not score(amb)["right"] and score(amb)["confident_undecidable"] and score(amb)["right_lenient"]
    hedge = amb | {"verdict": "ambiguous", "effects": "", "candidates": "joint_compliance+backlash"}
    assert score(hedge)["right"]
    quiet = {"label": "absorbed", "named": "", "effects": "thermal", "candidates": "", "verdict": "effect"}
    assert score(quiet)["false_claim"] and not score(quiet | {"verdict": "inconclusive"})["false_claim"]


def _sorts_after(previous: str, name: str) -> bool:
    """Set ``name`` is declared right after ``previous`` and sorts after every set declared before it (case seeds and
    the report's order follow the names)."""
    from sim2real_indep import cases as cs

    order = list(cs.SETS)
    i = order.index(name)
    return i > 0 and order[i - 1] == previous and all(s < name for s in order[:i])


def _assert_set_layout(set_name: str, seed: int, registry: dict) -> set:
    """A later independent set's layout: 24 cases on seed ``seed``, 8 per arm, 3 geometry-only, 3 mixtures, 30-200
    poses with an effect case of at most 50, six split by time, at least 5 single-kind cases per arm; its kinds are
    exactly ``registry``'s, new to every earlier set, registered in the generator, two per family. Returns them."""
    from sim2real_indep import cases as cs
    from sim2real_indep.context import FAMILIES, FAMILY

    cases = cs.SETS[set_name][0]
    assert len(cases) == 24 and cs.SETS[set_name][1] == seed
    assert {r: sum(c[1] == r for c in cases) for r in ("ur10", "tool_changer", "kr16_like")} == {
        "ur10": 8, "tool_changer": 8, "kr16_like": 8}
    assert sum(not c[2] for c in cases) == 3 and sum(len(c[2]) == 2 for c in cases) == 3
    assert all(30 <= c[3] <= 200 for c in cases) and min(c[3] for c in cases if c[2]) <= 50
    assert sum(c[4] == "time" for c in cases) == 6
    for r in ("ur10", "tool_changer", "kr16_like"):
        assert sum(len(c[2]) == 1 for c in cases if c[1] == r) >= 5
    kinds = {k for c in cases for k in c[2]}
    earlier_sets = [s for s in cs.SETS if s < set_name]
    earlier = set(cs.KINDS) | {k for s in earlier_sets for c in cs.SETS[s][0] for k in c[2]}
    assert kinds == set(registry) and not kinds & earlier
    assert all(gen.EFFECTS[k] == registry[k] for k in kinds)
    for fam in FAMILIES:
        assert sum(FAMILY[k] == fam for k in kinds) == 2, fam
    return kinds


def _assert_set_module(set_name: str, seed: int, module, foreign: tuple) -> set:
    """:func:`_assert_set_layout` of a set whose module registers ``EFFECTS_<set>`` and ``FAMILY_<set>``: its families
    are the benchmark's, its measurement kinds (``AFTER_TRACKER``, where it has them) are the generator's, and its
    session hook returns the options of a case of ``foreign`` (earlier sets') kinds unchanged, drawing no random
    number. Returns its kinds."""
    from sim2real_indep.context import FAMILY

    kinds = _assert_set_layout(set_name, seed, getattr(module, f"EFFECTS_{set_name}"))
    assert all(FAMILY[k] == getattr(module, f"FAMILY_{set_name}")[k] for k in kinds)
    assert set(getattr(module, "AFTER_TRACKER", ())) <= gen.AFTER_TRACKER
    rng_a, rng_b = np.random.default_rng(5), np.random.default_rng(5)
    opts = {"blocks": 2, "gap_kind": "none"}
    assert module.session_options("ur10", foreign, rng_a, opts) is opts
    assert rng_a.random() == rng_b.random()                          # no draws without a kind of this set
    return kinds


def _assert_regenerates(set_name: str, *, max_effect_poses: int):
    """The set's geometry-only cases and its effect cases of at most ``max_effect_poses`` poses regenerate
    bit-for-bit from their seeds; the geometry-only ones carry no effect, and the oracle labels the first of them
    ``none`` (the study's run labels every case; the oracle's own noise-floor test is below)."""
    from sim2real_indep import cases as cs

    labelled = False
    for i, (cid, robot, physics, n, split) in enumerate(cs.SETS[set_name][0]):
        if physics and n > max_effect_poses:
            continue
        a = gen.generate(cid, robot, physics, n, cs.case_seed(set_name, i), split)
        b = gen.generate(cid, robot, physics, n, cs.case_seed(set_name, i), split)
        assert a.frame.equals(b.frame) and np.array_equal(a.train, b.train) and np.array_equal(a.test, b.test), cid
        if not physics:  # geometry and noise only
            assert a.truth["params"] == {} and np.abs(a.truth["effect_mm"]).max() < 1e-9
            if not labelled:
                assert orc.run_oracle(a).label == "none"
                labelled = True


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


def _effect_and_features(case, ctx, kind):
    """The first-order target displacement of ``kind`` in ``case`` (3P,) and its true-structure features as columns
    (3P, M), on the poses of ``ctx`` (``case.model_ctx``)."""
    t = case.truth
    d = _linear_displacement(gen.EFFECTS[kind][1](t["params"][kind], ctx, t["hw"]), ctx).ravel()
    F = gen.EFFECTS[kind][2](t["params"][kind], ctx, t["hw"])
    return d, (F.reshape(len(F), -1).T if len(F) else np.zeros((len(d), 0)))


def _assert_kinds_reproduce(specs, seed: int, *, inert=(), min_mm: float) -> dict:
    """Every kind of ``specs`` ((robot, kinds) pairs, a 30-pose case each from ``seed``) displaces the robot within the
    span of its true-structure features, by at least ``min_mm``; the ``inert`` kinds do nothing on ur10. Returns
    ``{robot: (case, ctx)}`` of each robot's first case, for the known-answer checks."""
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, seed)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault(robot, (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if robot == "ur10" and kind in inert:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, kind
                continue
            _assert_features_reproduce(d, A, rtol=1e-8, min_mm=min_mm, what=kind)
    return runs


def _assert_features_reproduce(d, A, amp=None, *, rtol: float, min_mm: float, what: str = ""):
    """The features ``A`` times the amplitudes ``amp`` (default: the least-squares ones) give the displacement ``d``
    within ``rtol`` of its size, and the effect is real (``min_mm`` at its largest)."""
    amp = np.linalg.lstsq(A, d, rcond=None)[0] if amp is None else np.asarray(amp, float).ravel()
    assert np.abs(A @ amp - d).max() < rtol * max(1.0, np.abs(d).max()), what
    assert np.abs(d).max() > min_mm, what  # a real effect [mm]


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
        _assert_features_reproduce(*_effect_and_features(case, ctx, kind), amp, rtol=1e-9, min_mm=1e-4, what=kind)

    rv = t["params"]["rv_error"]
    check("rv_error", np.concatenate([[a * np.cos(ph_), a * np.sin(ph_)] for g in rv
                                      for a, ph_ in zip(g["amp"], g["phase"])]).ravel())
    check("track", cb._track_amp(t["params"]["track"]))
    check("dahl", np.array([a for b in t["params"]["dahl"] for a in (b["half_b"], b["c"])]))
    check("box_torsion")
    check("twonode")


def test_set_d_effects_apply_equals_features_times_true_amplitudes():
    """Set D: 24 cases, 8 per arm, every family (two kinds each for the gravity families), 3 geometry-only cases,
    3 mixtures; every new kind's apply equals its true-structure features times the true amplitudes; a few
    known answers (a tapered beam of constant section is the uniform cantilever; the gas spring opposes gravity;
    refraction of a few um at tracker ranges)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_d as ed
    from sim2real_indep import effects_d_body as db
    from sim2real_indep import effects_d_joint as dj
    from sim2real_indep import effects_d_thermal as dt
    from sim2real_indep import hardware as hwm
    from sim2real_indep.context import FAMILIES, FAMILY

    assert len(cs.SET_D) == 24 and cs.SETS["D"][1] == cs.SEED_D == 40_7004
    assert {r: sum(c[1] == r for c in cs.SET_D) for r in ("ur10", "tool_changer", "kr16_like")} == {
        "ur10": 8, "tool_changer": 8, "kr16_like": 8}
    assert sum(not c[2] for c in cs.SET_D) == 3 and sum(len(c[2]) == 2 for c in cs.SET_D) == 3
    assert all(30 <= c[3] <= 200 for c in cs.SET_D) and sum(c[4] == "time" for c in cs.SET_D) == 6
    kinds = {k for c in cs.SET_D for k in c[2]}
    assert kinds == set(ed.EFFECTS_D) and not kinds & {k for s in ("A", "B", "C") for c in cs.SETS[s][0] for k in c[2]}
    assert all(FAMILY[k] == ed.FAMILY_D[k] for k in kinds) and set(ed.FAMILY_D.values()) == set(FAMILIES)
    for fam in ("joint_compliance", "mount_compliance", "link_deflection"):
        assert sum(f == fam for f in ed.FAMILY_D.values()) >= 2

    def check(case, kind, amp):
        ctx = case.model_ctx(case.truth["probe_mm"])
        _assert_features_reproduce(*_effect_and_features(case, ctx, kind), amp, rtol=1e-9, min_mm=1e-4, what=kind)

    tc = gen.generate("t", "tool_changer", ("gas_spring", "ball_screw", "tapered", "bracket", "refraction",
                                            "tool_heat"), 14, 8)
    kr = gen.generate("t", "kr16_like", ("loose_anchor", "pad_creep", "varlash", "belt", "thermal_bend",
                                         "dresspack"), 14, 9)
    for case in (tc, kr):
        P, hw = case.truth["params"], case.truth["hw"]
        c = np.array([hwm.torsion(d, 1.0, False) for d in hw["drives"]])  # joint compliance per unit load
        if "gas_spring" in P:
            check(case, "gas_spring", np.r_[c, c[dj.SPRING_JOINT] * P["gas_spring"]["F1_N"]])
            check(case, "ball_screw", [a for g in P["ball_screw"] for a in (
                g["e_p_mm"], g["bow_mm"], g["wobble_mm"] * np.cos(g["phase"]), g["wobble_mm"] * np.sin(g["phase"]))])
            check(case, "tapered", [a for s in P["tapered"].values() for a in (1 / s["E"], 1 / s["G"])])
            check(case, "bracket", [1 / P["bracket"]["E"], 1 / P["bracket"]["G"]])
            check(case, "refraction", [P["refraction"]["G0_K_per_m"], P["refraction"]["G1_per_K"]])
            check(case, "tool_heat", [P["tool_heat"]["cte_tool"] * P["tool_heat"]["L_tool_mm"], P["tool_heat"]["cte"]])
        else:
            check(case, "loose_anchor", db._anchor_amp(P["loose_anchor"], hw))
            p = P["pad_creep"]
            check(case, "pad_creep", [p["C0"], p["C0"], p["C1"], p["C1"]])
            check(case, "varlash", [a for b in P["varlash"] for a in (
                b["b0"] / 2, b["b0"] * b["eps"] * np.cos(b["phi"]) / 2, -b["b0"] * b["eps"] * np.sin(b["phi"]) / 2,
                -b["h"] / 2)])
            check(case, "belt", [a for g in P["belt"] for a0, ph_ in zip(g["amp"], g["phase"])
                                 for a in (a0 * np.cos(ph_), a0 * np.sin(ph_))])
            check(case, "thermal_bend", [a for lk in P["thermal_bend"]["links"].values()
                                         for a in (1.0, P["thermal_bend"]["cte"] * lk["mean_ratio"])])
            check(case, "dresspack", np.r_[c, [a for h in P["dresspack"] for a in (
                -h["k_Nm_per_rad"] * c[h["joint"]], -h["friction_Nm"] * c[h["joint"]])]])

    # a tapered beam of constant section (beta = 1) is the uniform cantilever: a_k = L^(k+1) / ((k+1) I)
    a = db._taper_integrals(0.7, 2e-6, 1.0)
    assert a == pytest.approx([0.7 ** (k + 1) / ((k + 1) * 2e-6) for k in range(4)], rel=1e-4)
    # the counterbalance torque opposes the mean gravity torque on joint 2
    ctx = tc.model_ctx(tc.truth["probe_mm"])
    tau_s = dj.spring_torque_shape(tc.truth["params"]["gas_spring"], ctx.q[:, dj.SPRING_JOINT])
    assert np.mean(tau_s) * np.mean(ctx.loads[:, dj.SPRING_JOINT]) < 0
    # refraction in 1 K/m over 5 m: 0.93e-6 x 25 / 2 m = 11.6 um at most
    shape = dt.refraction_parts(ctx, tc.truth["hw"])[0]
    rng_m = np.linalg.norm(ctx.target + tc.truth["hw"]["tracker"]["R"].T @ tc.truth["hw"]["tracker"]["t"], axis=1) / 1e3
    assert np.all(np.linalg.norm(shape, axis=1) <= 0.93e-6 * rng_m ** 2 / 2 * 1000 * (1 + 1e-12))
    # two first-order lags in series: the wrist follows the tool, both reach their steady rise
    x1, x2 = dt.series_lags(np.full(400, 60.0), np.ones(400), 600.0, 1800.0)
    assert x1[-1] == pytest.approx(1.0, abs=1e-6) and x2[-1] == pytest.approx(1.0, abs=1e-5) and np.all(x2 <= x1)


def test_set_e_cases_and_every_kind_lies_in_its_true_structure():
    """Set E: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark, 3 geometry-only cases,
    3 mixtures; every new kind's displacement lies in the span of its true-structure features (what the oracle
    fits), to rounding."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_e as ee
    from sim2real_indep.context import FAMILIES, FAMILY

    assert len(cs.SET_E) == 24 and cs.SETS["E"][1] == cs.SEED_E == 40_7005
    assert {r: sum(c[1] == r for c in cs.SET_E) for r in ("ur10", "tool_changer", "kr16_like")} == {
        "ur10": 8, "tool_changer": 8, "kr16_like": 8}
    assert sum(not c[2] for c in cs.SET_E) == 3 and sum(len(c[2]) == 2 for c in cs.SET_E) == 3
    assert all(30 <= c[3] <= 200 for c in cs.SET_E)
    kinds = {k for c in cs.SET_E for k in c[2]}
    earlier = {k for s in ("A", "B", "C", "D") for c in cs.SETS[s][0] for k in c[2]}
    assert kinds == set(ee.EFFECTS_E) and not kinds & earlier
    assert all(FAMILY[k] == ee.FAMILY_E[k] for k in kinds) and set(ee.FAMILY_E.values()) == set(FAMILIES)
    for fam in FAMILIES:
        assert sum(f == fam for f in ee.FAMILY_E.values()) >= 2, fam
    _assert_kinds_reproduce((("tool_changer", ("ram", "parallelogram", "soft_foot", "magnetic_ring", "sunlight")),
                             ("kr16_like", ("ring_gear", "channel", "table_frame", "varstiff", "friction_windup",
                                            "scissor_gear", "fan_thermostat"))), 11, min_mm=1e-4)


def test_set_f_cases_kinds_and_determinism():
    """Set F: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed."""
    from sim2real_indep import effects_f as ef

    _assert_set_layout("F", 40_7006, ef.EFFECTS_F)
    _assert_regenerates("F", max_effect_poses=40)


def test_set_f_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-F kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the lever kinds do nothing on ur10 (no cylinders); and
    known answers: the lever's angle derivatives against finite differences of the law of cosines, the tilt of a
    plate on a tensionless bed continuous at the kern, the vector play operator, the tape-scale sawtooth's jump
    g / R, the brake's offset only on braked poses."""
    from types import SimpleNamespace

    from sim2real_indep import effects_f_body as fb
    from sim2real_indep import effects_f_joint as fj

    _assert_kinds_reproduce((("ur10", ("cable_balancer", "uplift", "eccentric_axis", "weld_crack", "tape_scale",
                                       "day_night")),
                             ("tool_changer", ("lever_drive", "lever_stiffness", "screw_growth", "plate_yield",
                                               "brake_hub", "wear_zones")),
                             ("ur10", ("lever_drive", "lever_stiffness", "screw_growth"))), 12,
                            inert=("lever_drive", "screw_growth"), min_mm=1e-3)

    lv = {"r1": 0.9, "r2": 0.3, "s": 1.0, "psi0": 0.4}
    q = np.linspace(0.2, 1.6, 7)
    psi, L, a = fj.lever_state(lv, q)
    assert a == pytest.approx(lv["r1"] * lv["r2"] * np.sin(psi) / L)
    acos = lambda L_, r1, r2: np.arccos((r1 * r1 + r2 * r2 - L_ * L_) / (2 * r1 * r2))  # noqa: E731
    h = 1e-7
    fd = [(acos(L, lv["r1"] + h, lv["r2"]) - acos(L, lv["r1"] - h, lv["r2"])) / (2 * h),
          (acos(L, lv["r1"], lv["r2"] + h) - acos(L, lv["r1"], lv["r2"] - h)) / (2 * h),
          (acos(L + h, lv["r1"], lv["r2"]) - acos(L - h, lv["r1"], lv["r2"])) / (2 * h)]
    assert fj.lever_partials(lv, q) == pytest.approx(np.array(fd), rel=1e-6)

    # tensionless bed: 12 W e / B^4 and 2 W / (B c^2) meet at e = B / 6 (c = B), the sink W / B^2 as well; at
    # e = B / 3 the contact is half the plate and the tilt twice the linear law's
    B, W = 0.8, 2000.0
    theta, sink = fb.bed_tilt(W, np.array([B / 6 - 1e-9, B / 6 + 1e-9, B / 3]), B)
    assert theta[:2] == pytest.approx(2 * W / B ** 3, rel=1e-6) and sink[:2] == pytest.approx(W / B ** 2, rel=1e-6)
    assert theta[2] == pytest.approx(2 * 12 * W * (B / 3) / B ** 4) and abs(sink[2]) < 1e-9 * W / B ** 2

    beta = fb.play2(np.zeros(2), np.array([3.0, 4.0]), 2.0)  # moved to within r of the input, along the line
    assert beta == pytest.approx([1.8, 2.4]) and fb.play2(beta, np.array([3.0, 3.0]), 2.0) is beta

    tape = {"joint": 0, "theta_g": 1.0, "eps": 1e-4}
    sig = fj.tape_signal(tape, SimpleNamespace(q=np.array([[1.0 - 1e-6], [1.0 + 1e-6], [1.5]])))
    assert sig[0] - sig[1] == pytest.approx(2 * np.pi, abs=1e-5) and sig[2] == pytest.approx(0.5)  # x eps: g / R

    case = gen.generate("t", "kr16_like", ("brake_hub",), 40, 3)
    p = case.truth["params"]["brake_hub"]
    ctx = case.model_ctx(case.truth["probe_mm"])
    off = ctx.session.dwell_s <= p["t_brake_s"]
    assert off.any() and (~off).any()
    for b in p["joints"]:
        s = fj.brake_signal(p, b, ctx)
        assert np.all(s[off] == 0) and set(np.unique(s)) <= {-2.0, 0.0, 2.0}



def test_set_g_cases_kinds_and_determinism():
    """Set G: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session and probe hooks leave cases without a set-G kind
    alone."""
    from sim2real_indep import effects_g as eg

    _assert_set_module("G", 40_7007, eg, ("gear", "day_night"))
    probe = np.array([3.0, -4.0, 12.0])                              # |probe| 13 mm
    assert eg.probe_hook(("sag",), probe) is probe
    rod = eg.probe_hook(("target_rod",), probe)
    assert np.linalg.norm(rod) == pytest.approx(250 + 350 * 8 / 95) and np.allclose(np.cross(rod, probe), 0)
    _assert_regenerates("G", max_effect_poses=50)


def test_set_g_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-G kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the cycloid-arm kinds do nothing on ur10; and known
    answers: the twin pinions' bilinear twist, the catenary's end forces, the held load integral, the levelling
    valves' plane and dead band, the moment integral along a span, the rod's sag direction, the axial float's
    flank, the clearance tilt normal to the axis, a rounded RV ratio, the ring encoder's eccentricity rule, the
    tripod's sinking points and the parallelogram's turn against the exact four-bar."""
    from types import SimpleNamespace

    from sim2real_indep import effects_g_body as gb
    from sim2real_indep import effects_g_joint as gj

    geared = ("twin_pinion", "axial_float", "ratio_rounding", "bar_expansion")
    runs = _assert_kinds_reproduce((("ur10", ("hose_catenary", "jack_leak", "air_isolator", "cfrp_twist", "target_rod",
                                              "bearing_clearance", "ring_shift", "tripod_growth")),
                                    ("tool_changer", geared), ("ur10", geared)), 14, inert=geared, min_mm=1e-3)

    # twin pinions: slope 1 / 2k up to twice the bias, 1 / k beyond, continuous
    g = {"joint": 0, "T_bias_Nm": 100.0, "k_Nm_per_rad": 1e6}
    tau = np.array([[-500.0], [-200.0], [150.0], [200.0], [500.0]])
    twist = np.sum(gj.dual_signals(g, SimpleNamespace(loads=tau)), axis=0) / (2 * g["k_Nm_per_rad"])
    assert twist == pytest.approx([-4e-4, -1e-4, 7.5e-5, 1e-4, 4e-4])

    # catenary: ends at one height carry half the hose each; the two ends' pulls balance the hose's weight S
    A, S = np.array([0.0, 0.0, 2.0]), 3.0
    B = np.array([[2.0, 0.0, 2.0], [1.5, 1.0, 1.2]])
    fB = gj.catenary_end_force(A, B, S)
    assert fB[0, 2] == pytest.approx(-S / 2, rel=1e-9)
    assert 2 * fB[0, 0] * np.sinh(2.0 / (2 * fB[0, 0])) == pytest.approx(S, rel=1e-9)  # H = a solves the length
    fA = gj.catenary_end_force(B[1], A[None], S)[0]
    assert fA[2] + fB[1, 2] == pytest.approx(-S, rel=1e-9) and fA[:2] + fB[1, :2] == pytest.approx([0, 0], abs=1e-9)

    case, ctx = runs["ur10"]
    p = case.truth["params"]
    # a load held constant integrates to load x session time; levelling valves: heights inside the band, unit
    # heights of all three valves lift the table bodily by 1 mm
    assert gb.held_integral(ctx, np.ones((30, 1)))[:, 0] == pytest.approx(ctx.session.time_s)
    z = gb.valve_heights(p["air_isolator"], ctx)
    assert np.abs(z).max() <= p["air_isolator"]["band_mm"] + 1e-12 and np.all(z[0] == 0)
    assert gb.air_parts(p["air_isolator"], ctx).sum(axis=0) == pytest.approx(np.tile([0, 0, 1.0], (30, 1)))
    # the span integral of the section moment against quadrature
    rng = np.random.default_rng(0)
    M, F, w, e = rng.normal(size=(4, 1, 3))
    x = np.linspace(0, 0.7, 20001)
    Mx = M + np.cross(e, F) * (0.7 - x)[:, None] + np.cross(e, w) * ((0.7 - x) ** 2 / 2)[:, None]
    assert gb.span_moment_integral(M, F, w, e, 0.7)[0] == pytest.approx(np.trapezoid(Mx, x, axis=0), rel=1e-8)
    # the rod sags along gravity's part normal to it; the clearance tilts normal to the joint axis, along the moment
    g_perp = gb.rod_direction(ctx)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    u = Rt @ (ctx.probe_mm / np.linalg.norm(ctx.probe_mm))
    assert np.abs(np.einsum("pi,pi->p", g_perp, u)).max() < 1e-12
    assert np.sum(g_perp ** 2, axis=1) + u[:, 2] ** 2 == pytest.approx(np.ones(30))
    _, Mj, wj, _ = gj.joint_wrench(ctx)
    for c in p["bearing_clearance"]:
        tilt, j = gb.clear_tilt(c, ctx), c["joint"]
        Mp = Mj[:, j] - np.einsum("pi,pi->p", Mj[:, j], wj[:, j])[:, None] * wj[:, j]
        big = np.linalg.norm(Mp, axis=1) > c["M_friction_Nm"]
        assert np.abs(np.einsum("pi,pi->p", tilt, wj[:, j])).max() < 1e-12 and big.any()
        assert tilt[big] == pytest.approx(Mp[big] / np.linalg.norm(Mp[big], axis=1, keepdims=True))
    # ring encoder: a ring a_e off the tilt centre, tilted theta = M / K, reads (u . t_h) / R_e = -a_e (M . n_h) / R_e K
    # (the joint is then off by minus that: ring_apply's a_e (M . n_h) / R_e K)
    n_h, wax = np.array([0.6, 0.8, 0.0]), np.array([0.0, 0.0, 1.0])
    Mv, K, a_e, R_e = np.array([30.0, -50.0, 7.0]), 2e6, 25.0, 40.0
    shift = a_e * np.cross(Mv / K, wax)
    assert shift @ np.cross(wax, n_h) / R_e == pytest.approx(-a_e / (R_e * K) * (Mv @ n_h), rel=1e-12)
    for g in p["ring_shift"]:
        dq = gen.EFFECTS["ring_shift"][1](p["ring_shift"], ctx, case.truth["hw"]).dq[:, g["joint"]]
        assert dq == pytest.approx(g["a_e_mm"] / (g["R_e_mm"] * g["K_tilt"]) * np.einsum(
            "pi,pi->p", Mj[:, g["joint"]], kin.body_transforms(ctx.chain, ctx.q)[0][:, g["joint"]] @ g["n_home"]))
    # tripod: points only sink or rise, by alpha h dT
    d = gen.EFFECTS["tripod_growth"][1](p["tripod_growth"], ctx, case.truth["hw"]).displace
    assert np.abs(d[:, :2]).max() == 0.0 and np.abs(d[:, 2]).max() > 0

    # axial float: the flank follows the axial force once it beats friction, else stays
    case, ctx = runs["tool_changer"]
    F, _, wj, _ = gj.joint_wrench(ctx)
    for g in case.truth["params"]["axial_float"]:
        s, Fa = gj.float_state(g, ctx), np.einsum("pi,pi->p", F[:, g["joint"]], wj[:, g["joint"]])
        big = np.abs(Fa) > g["F_friction_N"]
        assert set(np.unique(s)) <= {-1.0, 1.0} and np.array_equal(s[big], np.sign(Fa[big]))
        assert np.array_equal(s[1:][~big[1:]], s[:-1][~big[1:]])
    # a ratio 2133 / 13 configured as 164.1: the joint runs 164.1 / (2133 / 13) - 1 = 1.40e-4 of its angle off
    q = np.array([[0.0, 0.0, -1.2], [0.0, 0.0, 0.5]])
    dq = gj.ratio_apply([{"joint": 2, "R": 2133 / 13, "R_cfg": 164.1}], SimpleNamespace(q=q), None).dq
    assert dq[:, 2] == pytest.approx((164.1 * 13 / 2133 - 1) * q[:, 2]) and abs(dq[0, 2]) > 1.6e-4
    # parallelogram: a bar longer by delta turns the lever by delta / (r sin gamma) (the exact four-bar to first order)
    L, r, delta = 0.68, 0.2, 1e-5
    for gamma in np.deg2rad([50.0, 90.0, 130.0]):
        B0 = r * np.array([np.cos(gamma), np.sin(gamma)])
        f = lambda psi: np.sum((np.array([L, 0.0]) + r * np.array([np.cos(psi), np.sin(psi)]) - B0) ** 2)  # noqa
        lo, hi = gamma - 1e-3, gamma + 1e-3                      # |BC|^2 falls through (L + delta)^2 as psi grows
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) > (L + delta) ** 2 else (lo, mid)
        assert abs(0.5 * (lo + hi) - gamma) == pytest.approx(delta / (r * np.sin(gamma)), rel=1e-3)


def test_set_h_cases_kinds_and_determinism():
    """Set H: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session hook leaves cases without a set-H kind alone."""
    from sim2real_indep import effects_h as eh

    _assert_set_module("H", 40_7008, eh, ("gear", "tripod_growth"))
    _assert_regenerates("H", max_effect_poses=50)


def test_set_h_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-H kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the coupled-wrist and helical kinds do nothing on ur10;
    and known answers: load data that match the payload leave nothing, the creep state's exact lag, the stale
    table's samples and interpolation, the rounded coupling factor, the wrist train's own direction, the platform's
    statics, Hetenyi's skid in equilibrium with its loads, the arc against a straight cantilever and
    Roark's quarter circle, the bonded root's moment, the warming tracker's drift directions, the helical shift's
    rate and the cold grease's fading wind-up."""
    from dataclasses import replace
    from types import SimpleNamespace

    from sim2real_indep import effects_h_body as hb
    from sim2real_indep import effects_h_joint as hj
    from sim2real_indep import effects_h_thermal as ht
    from sim2real_indep.context import Ctx

    wrist = ("wrist_lash", "wrist_coupling", "helix_shift")
    runs = _assert_kinds_reproduce((("ur10", ("load_data", "gear_creep", "agv_wheels", "skid", "curved_link",
                                              "bond_creep", "cold_grease", "stale_table", "tracker_warmup")),
                                    ("kr16_like", wrist), ("ur10", wrist)), 15, inert=wrist, min_mm=1e-3)

    case, ctx = runs["ur10"]
    p, hw = case.truth["params"], case.truth["hw"]
    # load data: a model with the true masses and the carried payload leaves nothing; a payload lighter than the
    # load data by dm leaves the loads of -dm at the payload's centre of mass
    ch = ctx.chain
    same = Ctx(ch, ctx.session, ch.masses, ch.mass_com, ctx.mass_link, ctx.payload_com_mm, ctx.probe_mm)
    m_p = float(ctx.session.payload_kg[0])
    sess = replace(ctx.session, payload_kg=np.full(30, m_p))
    g = {"m_prog_kg": m_p, "com_prog_mm": ctx.payload_com_mm, "eps": np.zeros(6)}
    assert np.abs(hj.load_apply(g, replace(same, session=sess), hw).dq).max() < 1e-15
    g["m_prog_kg"] = m_p + 2.0
    tau = hj.model_loads(g, same) - hj.model_loads({**g, "m_prog_kg": m_p}, same)
    unit = Ctx(ch, replace(ctx.session, payload_kg=np.full(30, 1.0)), 0 * ch.masses, ch.mass_com, ctx.mass_link,
               ctx.payload_com_mm, ctx.probe_mm).loads
    assert tau == pytest.approx(2.0 * unit, rel=1e-9, abs=1e-9)
    # creep: a constant load keeps the state; a step held over a pause of T relaxes as 1 - exp(-T / tau)
    s = SimpleNamespace(gap_s=np.array([0.0, -600.0]), move_s=np.array([0.0, 0.0]), dwell_s=np.array([0.0, 0.0]))
    X = np.array([[0.0], [1.0]])
    x = hj.creep_state(SimpleNamespace(session=s), X, 300.0)
    assert x[0, 0] == pytest.approx(0.5) and x[1, 0] == pytest.approx(0.5 * np.exp(-2.0))  # held at 0 (pause)
    s.dwell_s = np.array([0.0, 300.0])
    x = hj.creep_state(SimpleNamespace(session=s), X, 300.0)
    assert x[1, 0] == pytest.approx(1.0 + (0.5 * np.exp(-2.0) - 1.0) * np.exp(-1.0))
    assert hj.creep_state(ctx, np.full((30, 2), 3.0), 900.0) == pytest.approx(np.full((30, 2), 3.0))
    # stale table: the old error at the grid points, linear in between
    for t in p["stale_table"]:
        h = t["step_rad"]
        q = np.zeros((3, 6))
        q[:, t["joint"]] = [2 * h, 3 * h, 2.25 * h]
        sig, e2, e3 = hj.table_signal(t, q), *hj.old_error(t, [2 * h, 3 * h])
        assert sig == pytest.approx([e2, e3, 0.75 * e2 + 0.25 * e3], abs=1e-15)
        assert np.abs(hj.old_error(t, np.linspace(0, 2 * np.pi, 2001))).max() > 0.3 * ph.ARCMIN
    # the platform: the wheel loads carry the weight and the moment, all of them positive
    a = p["agv_wheels"]
    R = hb.wheel_loads(a, ctx)
    M = eb.mount_moment(ctx)
    assert R[:, 0] + R[:, 1] + 2 * R[:, 2] == pytest.approx(hb._weight(ctx) + a["W_platform_N"])
    assert a["a_x_m"] * (R[:, 0] + R[:, 1] - 2 * R[:, 2]) == pytest.approx(M[:, 1])
    assert a["a_y_m"] * (R[:, 0] - R[:, 1]) == pytest.approx(-M[:, 0])
    assert R.min() > 1.0                                                      # no wheel lifts: the chassis stands
    # Hetenyi's skid: the bed's reactions balance the end force (and carry no moment about the end); an end moment
    # is balanced by the reactions' moment; the slope is the sink's derivative; the twist's reactions carry the torque
    sk = p["skid"]
    x = np.linspace(0, 60 / sk["beta"], 400001)
    resp = np.array([hb.skid_response(sk, xi) for xi in (x[:3])])
    w_P = 2 * sk["beta"] * hb.hetenyi(sk["beta"], x)[2]
    w_M = -2 * sk["beta"] ** 2 * hb.hetenyi(sk["beta"], x)[1]
    assert np.trapezoid(w_P, x) == pytest.approx(1.0, rel=1e-6) and abs(np.trapezoid(w_P * x, x)) < 1e-6
    assert abs(np.trapezoid(w_M, x)) < 1e-6 and abs(np.trapezoid(w_M * x, x)) == pytest.approx(1.0, rel=1e-6)
    assert np.trapezoid(sk["lam"] * np.exp(-sk["lam"] * x), x) == pytest.approx(1.0, rel=1e-6)
    assert (resp[2, :2, 0] - resp[0, :2, 0]) / (x[2] - x[0]) == pytest.approx(resp[1, :2, 1], rel=1e-6)
    # the arc: a straight one is Euler-Bernoulli's cantilever; a quarter circle under an out-of-plane tip force
    # deflects P R^3 (pi / 4 EI + (3 pi / 4 - 2) / GJ) (Roark, curved beams loaded normal to their plane)
    e, b = np.array([[1.0, 0, 0]]), np.array([[0, 1.0, 0]])
    F, Mt, tip = np.array([[0, 0, -50.0]]), np.array([[3.0, -4.0, 2.0]]), np.array([[700.0, 0, 0]])
    d0 = hb.arc_displacement(e, b, tip, 0.7, 0.0, F, Mt, np.zeros(3), 2e4, 1.5e4, tip, n=4000)
    dc, rc = ph.cantilever_tip(e, 0.7, F, Mt, np.zeros(3), 2e4, np.inf, 1.5e4)
    assert d0 == pytest.approx(1000 * dc, rel=1e-5)
    Rq = 0.5
    tip = np.array([[1000 * Rq * np.sqrt(2), 0, 0]])                           # [mm]; the target at the tip
    d1 = hb.arc_displacement(e, b, tip, Rq * np.sqrt(2), np.pi / 4, np.array([[0, 0, -1.0]]), np.zeros((1, 3)),
                             np.zeros(3), 2e4, 1.5e4, tip, n=4000)
    assert -d1[0, 2] == pytest.approx(1000 * Rq ** 3 * (np.pi / 4 / 2e4 + (3 * np.pi / 4 - 2) / 1.5e4), rel=1e-5)
    # bonded root: the tube-frame root moment is the gravity moment of everything beyond the root
    for name in p["bond_creep"]:
        li = ch.link_names.index(name)
        root, Rb, e0, m = hb.root_state(ctx, li)
        mm, pos, _ = ctx.mass_state
        beyond = ctx.mass_index >= li
        own = ctx.mass_index == li
        arm = (pos[:, beyond] - root[:, None]) / 1000.0
        arm[:, own[beyond]] = ((root + hb.eb._beam_state(ctx, li)[1]) / 2 - root)[:, None] / 1000.0
        Mg = np.cross(arm, mm[:, beyond, None] * eb.GRAVITY_N).sum(axis=1)
        assert np.einsum("pij,pj->pi", Rb, m) == pytest.approx(Mg, rel=1e-9, abs=1e-9)
    # the warming tracker: azimuth drift about its vertical axis, elevation normal to the line of sight (r per rad),
    # range along it; the share reached grows as 1 - exp(-t / tau)
    parts = ht.warm_parts(ctx, hw)
    R_T, t_T = hw["tracker"]["R"], hw["tracker"]["t"]
    rel = ctx.target + R_T.T @ t_T
    assert parts[0] @ (R_T.T @ [0, 0, 1.0]) == pytest.approx(np.zeros(30), abs=1e-9)
    assert np.einsum("pi,pi->p", parts[0], rel) == pytest.approx(np.zeros(30), abs=1e-6)
    assert np.einsum("pi,pi->p", parts[1], rel) == pytest.approx(np.zeros(30), abs=1e-6)
    assert np.linalg.norm(parts[1], axis=1) == pytest.approx(np.linalg.norm(rel, axis=1))
    assert parts[2] == pytest.approx(rel / np.linalg.norm(rel, axis=1, keepdims=True))
    w = p["tracker_warmup"]
    t = ctx.session.time_s - ctx.session.time_s[0] + w["t_on_s"]
    assert ht.warm_signal(w, ctx) == pytest.approx(1 - np.exp(-t / w["tau_s"]))
    # cold grease: the wind-up trails the last motion and its viscous part fades as the drive warms (cold start)
    cg = p["cold_grease"]
    sig = ht.grease_signals(cg, ctx, hw)
    rise = ht.drive_rise(cg, ctx, hw)
    assert np.array_equal(sig[0], -ctx.session.direction[:, cg["joints"]])
    assert rise.min() >= 0 and np.all(rise.max(axis=0) > 1.0)                # some kelvin over the production runs
    assert sig[1] / sig[0] == pytest.approx(np.exp(-cg["k_per_K"] * rise))

    case, ctx = runs["kr16_like"]
    p, hw = case.truth["params"], case.truth["hw"]
    # coupling factors rounded to three decimals: the joint runs (c_cfg - c) of the angle it is coupled to off
    for g in p["wrist_coupling"]:
        assert 5e-5 < abs(g["c_cfg"] - g["c"]) <= 5e-4 + 1e-12
    dq = hj.couple_apply(p["wrist_coupling"], ctx, hw).dq
    assert dq[:, 5] == pytest.approx(sum((g["c_cfg"] - g["c"]) * ctx.q[:, g["through"]]
                                         for g in p["wrist_coupling"] if g["joint"] == 5))
    # the train's direction: opposite equal moves of joint and coupled joint (c = 1) leave the train at rest
    sess = SimpleNamespace(q=np.array([[0.0, 0.0], [0.1, -0.1], [0.3, -0.1], [0.2, -0.2]]),
                           direction=np.array([[-1.0, 1.0]]))
    assert np.array_equal(hj.train_direction({"joint": 0, "c": {1: 1.0}}, sess), [-1.0, -1.0, 1.0, -1.0])
    for g in p["wrist_lash"]:
        own = ctx.session.direction[:, g["joint"]]
        assert np.any(hj.train_direction(g, ctx.session) != own)
    # helical shift: alpha L tan(beta) / r per K of the drive's rise
    hs = p["helix_shift"]
    assert np.all((np.abs(hs["k_rad_per_K"]) > 11.7e-6 * 100 * np.tan(np.deg2rad(20)) / 50)
                  & (np.abs(hs["k_rad_per_K"]) < 11.7e-6 * 180 * np.tan(np.deg2rad(30)) / 25))
    dq = ht.helix_apply(hs, ctx, hw).dq
    assert dq[:, hs["joints"]] == pytest.approx(ht.drive_rise(hs, ctx, hw) * hs["k_rad_per_K"])


def test_set_i_cases_kinds_and_determinism():
    """Set I: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session and probe hooks leave cases without a set-I kind
    alone (no random numbers drawn)."""
    from sim2real_indep import effects_i as ei

    _assert_set_module("I", 40_7009, ei, ("gear", "helix_shift"))
    probe = np.array([3.0, -4.0, 12.0])                              # |probe| 13 mm
    assert ei.probe_hook(("sag", "target_rod"), probe) is probe
    boom = ei.probe_hook(("rail_boom",), probe)
    assert np.linalg.norm(boom) == pytest.approx(400 + 500 * 8 / 95) and np.allclose(np.cross(boom, probe), 0)
    _assert_regenerates("I", max_effect_poses=50)


def _beam_curve(L, a, P, EI, n=200001):
    """Deflection (down) and slope at a of a simply supported beam under a force P at a, by integrating w'' = -M/EI
    twice (the trapezoidal rule) with w(0) = w(L) = 0."""
    x = np.linspace(0, L, n)
    k = -np.where(x <= a, P * (L - a) * x / L, P * a * (L - x) / L) / EI
    cum = lambda f: np.r_[0.0, np.cumsum((f[1:] + f[:-1]) / 2 * np.diff(x))]  # noqa: E731
    wp = cum(k)
    w = cum(wp)
    c = -w[-1] / L
    i = int(np.argmin(np.abs(x - a)))
    return w[i] + c * x[i], wp[i] + c


def test_set_i_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-I kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the heavy-arm, coupled-wrist, fork and prismatic kinds do
    nothing on ur10; and known answers: the inclined loads as the gradient of the potential, the balancer charge's exact
    lag against a fine integration and its moment arm, the floor beam's flexibility against the integrated elastic
    curve and the plate's statics, the portal's sway and fixed-end answers, the splice's Masing branch and section
    moment, the warping twist's limits and boundary conditions, the overrun flank and the trapezoid's deceleration,
    the nut's flank, the idler's and the parallelogram reducer's angles and spectra, Timoshenko's bimetal and the
    housings' axial shift."""
    from types import SimpleNamespace

    from sim2real_indep import effects_c_thermal as ct
    from sim2real_indep import effects_g_joint as gj
    from sim2real_indep import effects_h_thermal as ht
    from sim2real_indep import effects_i_body as ib
    from sim2real_indep import effects_i_joint as ij
    from sim2real_indep import effects_i_thermal as it

    heavy = ("balancer_relax", "fork_arm", "nut_play", "idler_runout", "para_gear")
    runs = _assert_kinds_reproduce((("ur10", ("tilted_base", "floor_beams", "portal", "lap_splice", "overrun_lash",
                                              "rail_boom", "housing_growth")),
                                    ("kr16_like", ("balancer_relax", "fork_arm", "idler_runout", "para_gear")),
                                    ("tool_changer", ("nut_play", "para_gear")), ("ur10", heavy)), 16, inert=heavy,
                                   min_mm=1e-2)

    case, ctx = runs["ur10"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # inclined base: zero tilt is the file's gravity; the loads are minus the gradient of the potential -m G g . r
    tb = p["tilted_base"]
    assert ij.tilt_loads({"tilt_rad": 0.0, "azimuth_rad": 1.0}, ctx) == pytest.approx(ctx.loads, abs=1e-9)
    g = ij.tilt_gravity(tb)
    assert np.linalg.norm(g) == pytest.approx(1.0) and -g[2] == pytest.approx(np.cos(tb["tilt_rad"]))
    ch, q = ctx.chain, ctx.q[:4]
    V = lambda qq: -(ch.masses * kin.G * (kin.mass_positions(ch, qq) @ g) / 1000).sum(axis=1)  # noqa: E731
    tau = kin.gravity_loads(ch, q, ch.masses, kin.mass_positions(ch, q), ch.mass_body, gravity=g)
    for j in range(ch.n):
        e = 1e-6 * np.eye(ch.n)[j]
        assert tau[:, j] == pytest.approx(-(V(q + e) - V(q - e)) / 2e-6, rel=1e-5, abs=1e-6)
    assert np.abs(ij.tilt_loads(tb, ctx)[:, 0]).max() > 1.0                  # axis 1 now carries gravity
    # floor beams: the flexibility against the integrated elastic curve (force column), Maxwell's symmetry and the
    # central couple (slope L / 12 EI, no deflection); the plate's statics and equal slopes
    L, a, EI = 4.0, 1.3, 2e6
    F = ib.beam_flexibility(L, a) / EI
    assert _beam_curve(L, a, 1000.0, EI) == pytest.approx(tuple(1000.0 * F[:, 0]), rel=1e-6)
    assert ib.beam_flexibility(L, L / 2)[1] == pytest.approx([0.0, L / 12]) and F[0, 1] == F[1, 0]
    fb = p["floor_beams"]
    (P1, P2, C1, C2), _, _, _, e, n = ib.floor_state(fb, ctx)
    Fb = ib.beam_flexibility(fb["L_m"], fb["a_m"])
    M = ib.eb.mount_moment(ctx)
    assert P1 + P2 == pytest.approx(ib._weight(ctx)) and C1 + C2 == pytest.approx(M @ n)
    assert (P1 - P2) * fb["s_m"] / 2 == pytest.approx(-(M @ e))
    assert Fb[1, 0] * P1 + Fb[1, 1] * C1 == pytest.approx(Fb[1, 0] * P2 + Fb[1, 1] * C2)
    # portal: a rigid beam sways as two fixed-guided columns, H^3 / 24 EI (+ the columns' axial shortening); rigid
    # columns leave a fixed-fixed beam: B^3 / 192 EI under a central force, B / 16 EI under a central couple
    H, B, EIc = 2.0, 3.0, 1e6
    assert ib.portal_flexibility(H, B, EIc, 1e6 * EIc)[0, 0] == pytest.approx(H ** 3 / (24 * EIc), rel=2e-2)
    f = ib.portal_flexibility(H, B, 1e6 * EIc, EIc)
    assert f[1, 1] == pytest.approx(B ** 3 / (192 * EIc), rel=1e-4)
    assert f[2, 2] == pytest.approx(B / (16 * EIc), rel=1e-4)
    assert abs(f[1, 2]) < 1e-9 * f[2, 2] and np.allclose(f, f.T, rtol=0, atol=1e-12 * np.abs(f).max())
    # splice: the vector play; Masing: loading a ray to m_max leaves m_max - r, unloading to zero min(r, m_max - r)
    assert ib.play_vec(np.zeros(3), np.array([3.0, 4.0, 0.0]), 2.0) == pytest.approx([1.8, 2.4, 0.0])
    y = np.array([1.0, 1.0, 0.0])
    assert ib.play_vec(y, np.array([2.0, 1.5, 0.0]), 2.0) is y
    u = np.array([0.6, 0.0, 0.8])
    ys = ib.play_path(np.outer(np.linspace(0, 10.0, 21), u), np.zeros(21), [1.0, 3.0, 7.0])
    assert ys[-1] == pytest.approx(np.outer([9.0, 7.0, 3.0], u)) and ys[0] == pytest.approx(np.outer([1, 3, 3.0], u))
    # the section moment: everything beyond the splice, the tube's own weight beyond it by quadrature
    sp = p["lap_splice"]
    li = ch.link_names.index(sp["link"])
    m_s, pos = ib.section_moment(ctx, li, sp["s"])
    e_l, tip, Ll = ib.eb._beam_state(ctx, li)
    mm, mpos, _ = ctx.mass_state
    beyond, own = ctx.mass_index > li, ctx.mass_index == li
    Mg = np.cross((mpos[:, beyond] - pos[:, None]) / 1000.0, mm[:, beyond, None] * ib.eb.GRAVITY_N).sum(axis=1)
    xs = np.linspace(0.0, (1 - sp["s"]) * Ll, 2001)
    wl = mm[0, own].sum() * ib.eb.GRAVITY_N / Ll
    Mg += np.trapezoid(np.cross(xs[None, :, None] * e_l[:, None], np.broadcast_to(wl, (30, 2001, 3))), xs, axis=1)
    Mg -= np.einsum("pi,pi->p", Mg, e_l)[:, None] * e_l
    assert m_s == pytest.approx(Mg, rel=1e-6, abs=1e-6)
    # overrun: trapezoidal moves cover |dq| = alpha RAMP (move - RAMP); the flank: gravity's above the friction, else
    # leading where J alpha + d tau beats it, trailing otherwise
    alpha = ij.stop_deceleration(s)
    moved = s.move_s > 0
    dq = np.abs(np.diff(np.vstack([s.q[:1], s.q]), axis=0))
    assert (alpha * ij.RAMP_S * np.maximum(s.move_s - ij.RAMP_S, ij.RAMP_S)[:, None])[moved] == pytest.approx(dq[moved])
    J = ct.inertia_about_joints(ctx)
    for g_ in p["overrun_lash"]:
        j, d, t = g_["joint"], s.direction[:, g_["joint"]], ctx.loads[:, g_["joint"]]
        fl = ij.overrun_flank(g_, ctx)
        assert set(np.unique(fl)) <= {-1.0, 1.0}
        loaded = np.abs(t) > g_["T_f_Nm"]
        assert np.array_equal(fl[loaded], np.sign(t[loaded]))
        assert np.array_equal(fl[~loaded], np.where(J[~loaded, j] * alpha[~loaded, j] + (d * t)[~loaded] > g_["T_f_Nm"],
                                                    d[~loaded], -d[~loaded]))
    fl = ij.overrun_flank(p["overrun_lash"][0], ctx)                         # axis 1: no gravity, both flanks
    assert set(fl * s.direction[:, 0]) == {-1.0, 1.0}
    # bimetal: Timoshenko's two strips (unit width); the boom grows along itself and bows towards the steel rail
    E1, E2, t1, t2 = 70e9, 210e9, 0.003, 0.002
    kap, eps = it.bimetal(E1, t1, t1 ** 3 / 12, 23e-6, E2, t2, t2 ** 3 / 12, 11.7e-6, (t1 + t2) / 2)
    m_, n_ = t1 / t2, E1 / E2
    assert kap == pytest.approx(6 * (11.7e-6 - 23e-6) * (1 + m_) ** 2 / (
        (t1 + t2) * (3 * (1 + m_) ** 2 + (1 + m_ * n_) * (m_ * m_ + 1 / (m_ * n_)))), rel=1e-12)
    assert 11.7e-6 < eps < 23e-6
    bm = p["rail_boom"]
    grow, bow = it.boom_parts(bm, ctx)
    _, Rt = kin.flange(ch, ctx.q)
    dT = ib.eb.structure_temperature(bm, ctx)
    Lb = np.linalg.norm(ctx.probe_mm)
    assert grow == pytest.approx((Rt @ (bm["eps_per_K"] * ctx.probe_mm)) * dT[:, None])
    assert bow == pytest.approx((Rt @ bm["rail_dir"]) * (-bm["kappa_per_K"] * Lb ** 2 / 2000.0 * dT)[:, None])
    assert bm["kappa_per_K"] < 0 and np.abs(dT).max() > 1.0
    # housings: a growth delta along joint j's axis is the chain with delta * axis added to the first link after j
    hg = p["housing_growth"]
    parts, rise = it.housing_parts(hg, ctx, hw), ht.drive_rise(hg, ctx, hw)
    assert rise.min() >= 0 and np.all(rise.max(axis=0) > 5.0)
    for k, j in enumerate(hg["joints"][:3]):
        links = ch.links.copy()
        links[np.flatnonzero(ch.link_body == j + 1)[0]] += 1e-3 * ch.axes[j]
        shift = kin.target(ch, ctx.q, ctx.probe_mm, links=links) - ctx.target
        assert parts[k] == pytest.approx(1e3 * shift * rise[:, k:k + 1], rel=1e-6, abs=1e-6)

    case, ctx = runs["kr16_like"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # balancer: the exact lag against a fine integration of d(theta)/dt = -(gamma - 1) d(ln V)/dt - theta / tau (ln V
    # linear over the move), then decaying through dwells and a pause; the moment arm is dL / dpsi
    bp = dict(p["balancer_relax"], tau_th_s=12.0)
    q = np.zeros((3, 6))
    q[:, 1] = [bp["q_mid"] - 0.3, bp["q_mid"] + 0.4, bp["q_mid"] + 0.4]
    ses = SimpleNamespace(gap_s=np.array([0.0, 0.0, -50.0]), move_s=np.array([0.0, 2.5, 0.0]),
                          dwell_s=np.array([5.0, 4.0, 6.0]))
    th = ij.bal_theta(bp, SimpleNamespace(session=ses, q=q))
    lnv = np.log(ij.bal_volume(bp, ij.bal_geometry(bp, q[:, 1])[0]))
    x, dt = 0.0, 1e-4
    for _ in range(25000):                                                   # the move
        x += dt * (-(bp["gamma"] - 1) * (lnv[1] - lnv[0]) / 2.5 - x / 12.0)
    x *= np.exp(-4.0 / 12.0)                                                 # the dwell (Euler's error: dt / 2 tau)
    assert th[0] == 0.0 and th[1] == pytest.approx(x, rel=1e-5) and th[2] == pytest.approx(x * np.exp(-56.0 / 12.0),
                                                                                            rel=1e-5)
    psi = np.linspace(0.5, 2.5, 7)
    Lc = lambda ps: np.sqrt(bp["r1"] ** 2 + bp["r2"] ** 2 - 2 * bp["r1"] * bp["r2"] * np.cos(ps))  # noqa: E731
    q2 = bp["q_mid"] + bp["sign"] * (psi - bp["psi_mid"])
    assert ij.bal_geometry(bp, q2)[1] == pytest.approx((Lc(psi + 1e-6) - Lc(psi - 1e-6)) / 2e-6, rel=1e-6)
    iso, _ = ij.bal_torque_shapes(p["balancer_relax"], ctx)
    share = -np.mean(p["balancer_relax"]["F0_N"] * iso) / np.mean(ctx.loads[:, 1])
    assert 0.45 < share < 0.95                                               # opposes gravity, as sized (model ctx)
    # warping twist: Saint-Venant for lambda L >> 1, T L^3 / (3 E Gamma) for lambda L << 1; the closed-form twist line
    # meets the root (no twist, no warping), the free tip (no bimoment) and carries T
    T, Lf, GJ = 40.0, 0.7, 2e4
    assert ib.warping_twist(T, Lf, GJ, GJ * (Lf / 2000) ** 2) == pytest.approx(T * Lf / GJ, rel=2e-3)
    EG = GJ * (Lf * 2000) ** 2
    assert ib.warping_twist(T, Lf, GJ, EG) == pytest.approx(T * Lf ** 3 / (3 * EG), rel=1e-5)
    EG = 0.4 * GJ
    lam = np.sqrt(GJ / EG)
    tl = np.tanh(lam * Lf)
    phi = lambda xx: T / (GJ * lam) * (lam * xx - np.sinh(lam * xx) + tl * (np.cosh(lam * xx) - 1))  # noqa: E731
    h = 1e-3
    d1 = lambda xx: (phi(xx + h) - phi(xx - h)) / (2 * h)  # noqa: E731
    d2 = lambda xx: (phi(xx + h) - 2 * phi(xx) + phi(xx - h)) / h ** 2  # noqa: E731
    d3 = lambda xx: (phi(xx + 2 * h) - 2 * phi(xx + h) + 2 * phi(xx - h) - phi(xx - 2 * h)) / (2 * h ** 3)  # noqa
    assert phi(0.0) == 0.0 and abs(d1(0.0)) < 1e-9 and abs(d2(Lf)) < 1e-6 * T / GJ
    assert GJ * d1(Lf) - EG * d3(Lf) == pytest.approx(T, rel=1e-4)
    assert phi(Lf) == pytest.approx(ib.warping_twist(T, Lf, GJ, EG), rel=1e-12)
    # idler: a train move that keeps q_j + c q_k leaves the idler where it was; the error repeats per idler turn
    g_ = {"joint": 5, "c": {3: 0.5, 4: -0.7}, "i_g": 1.6, "amp_rad": np.array([1e-3, 2e-4]),
          "phase": np.array([0.3, 1.0])}
    qa = np.zeros((3, 6))
    qa[1, [5, 3]] = [0.2, -0.4]                                              # 0.2 + 0.5 (-0.4) = 0
    qa[2, 5] = 2 * np.pi / 1.6
    dq5 = ij.idler_apply([g_], SimpleNamespace(q=qa), None).dq[:, 5]
    assert dq5 == pytest.approx(np.full(3, dq5[0])) and abs(dq5[0]) > 1e-4
    for g_ in p["idler_runout"]:
        assert g_["joint"] in (4, 5) and set(g_["c"]) == set(range(3, g_["joint"]))  # through the earlier wrist axes
    # parallelogram reducer: it turns with q2 + q3 (q2 + d, q3 - d leaves it), lines at its orders per forearm turn
    pg = {"orders": np.array([30.0, 60.0, 1.0, 131.0]), "amp": np.array([3e-4, 1e-4, 2e-4, 5e-5]),
          "phase": np.array([0.3, 1.1, 2.0, 0.5])}
    qq = np.zeros((4096, 6))
    qq[:, 2] = np.linspace(0, 2 * np.pi, 4096, endpoint=False)
    e3 = ij.para_apply(pg, SimpleNamespace(q=qq), None).dq[:, 2]
    qs = qq.copy()
    qs[:, 1] += 0.37
    qs[:, 2] -= 0.37
    assert ij.para_apply(pg, SimpleNamespace(q=qs), None).dq[:, 2] == pytest.approx(e3, abs=1e-15)
    spec = np.abs(np.fft.rfft(e3)) * 2 / 4096
    assert spec[[30, 60, 1, 131]] == pytest.approx(pg["amp"], rel=1e-9)

    case, ctx = runs["tool_changer"]
    s = ctx.session
    # nut: the ram rests on the flank its axial gravity force pushes it to when that beats the guide friction (seals
    # plus the blocks' loads), else trails its last motion
    for g_ in case.truth["params"]["nut_play"]:
        j = g_["joint"]
        fric, Fa = ij.guide_friction(g_, ctx), ctx.loads[:, j]
        Fw, Mw, ww, _ = gj.joint_wrench(ctx)
        assert Fa == pytest.approx(np.einsum("pi,pi->p", Fw[:, j], ww[:, j]))   # the axial force along the ram
        assert np.all(fric > g_["F_seal_N"])
        fl, big = ij.nut_flank(g_, ctx), np.abs(Fa) > fric
        assert np.array_equal(fl[big], np.sign(Fa[big])) and np.array_equal(fl[~big], -s.direction[~big, j])
        assert big.any() and set(np.sign(Fa[big])) == {-1.0, 1.0}


def test_set_j_cases_kinds_and_determinism():
    """Set J: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-J
    kind alone (no random numbers drawn); the tool plate's target sits at its gripper's tip, its payload in the jaws."""
    from sim2real_indep import effects_j as ej

    _assert_set_module("J", 40_7010, ej, ("gear", "rail_boom"))
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert ej.probe_hook(("sag", "rail_boom"), probe) is probe and ej.payload_hook(("sag",), com, probe) is com
    plate = ej.probe_hook(("tool_plate",), probe)
    d, reach, drop = ej.jb.plate_geometry(plate)
    assert d == pytest.approx([0.6, -0.8, 0.0]) and reach == pytest.approx(100 + 100 * 8 / 95)
    assert drop == pytest.approx(150 + 150 * 12 / 13)
    assert ej.payload_hook(("tool_plate",), com, plate) == pytest.approx(reach * d + [0, 0, 0.75 * drop] + com / 4)
    _assert_regenerates("J", max_effect_poses=50)


def test_set_j_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-J kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the differential wrist, the bar's pins and the wrist shafts
    do nothing on ur10; and known answers: the planets' filter of the ring's harmonics and their pins' line, the
    differential's mixing, the flange's relay, the bar pins' flank and lever, the hose pull as the gradient of the
    retract spring's energy, the shafts' symmetric compliance and its energy, Boltzmann's sum of the double power law,
    the console's cantilever and end plate, the skewed section's unsymmetric bending and its isotropic limit, the
    plate's torsion factor and a load through its axis, the brake-heated housing's exact lag and its coil off in the
    pauses, the laminate's shear expansion and the twist's geometry."""
    from dataclasses import replace
    from types import SimpleNamespace

    from sim2real_indep import effects_j_body as jb
    from sim2real_indep import effects_j_joint as jj
    from sim2real_indep import effects_j_thermal as jt

    inert = ("diff_wrist", "bar_pins", "wrist_shafts")
    runs = _assert_kinds_reproduce((("ur10", ("planet_stage", "flange_slip", "hose_retract", "grout_creep",
                                              "wall_console", "skew_casting", "tool_plate", "brake_tilt",
                                              "laminate_twist")),
                                    ("kr16_like", inert), ("tool_changer", ("wrist_shafts", "bar_pins")),
                                    ("ur10", inert)), 17, inert=inert, min_mm=1e-2)

    case, ctx = runs["ur10"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # planets: only the ring's harmonics k = 0 mod Np reach the carrier, at half the deviation over r_c; a planet's
    # eccentricity appears at the spin order Zr / Zp over Np r_c, and equal ones phased 2 pi / Np apart cancel
    th = np.linspace(0, 2 * np.pi, 4096, endpoint=False)
    g = {"Np": 3, "teeth": (21, 30, 81), "r_c_m": 0.05, "ring_um": np.arange(6, 0, -1) * 5.0,
         "ring_phase": np.linspace(0, 1, 6), "ecc_um": np.zeros(3), "ecc_phase": np.zeros(3)}
    spec = np.abs(np.fft.rfft(jj.planet_error(g, th))) * 2 / 4096
    assert spec[[3, 6]] == pytest.approx(g["ring_um"][[2, 5]] / (2 * 5e4), rel=1e-9)
    assert np.delete(spec, [3, 6]).max() < 1e-15 and jj.planet_orders(g) == [3.0, 6.0, 81 / 30]
    g.update(ring_um=np.zeros(6), ecc_um=np.array([8.0, 0.0, 0.0]))
    assert np.abs(jj.planet_error(g, th)).max() == pytest.approx(8.0 / (3 * 5e4), rel=1e-4)
    g.update(ecc_um=np.full(3, 8.0), ecc_phase=np.array([0.0, 2.0, 4.0]) * np.pi / 3)
    assert np.abs(jj.planet_error(g, th)).max() < 1e-18
    for g in p["planet_stage"]:
        Zs, Zp, Zr = g["teeth"]
        assert Zr == Zs + 2 * Zp and (Zr + Zs) % g["Np"] == 0 and 3.5 <= 1 + Zr / Zs <= 6
    # flange slip: the relay keeps its side until the torque passes the other threshold; production passes the loads
    tau = np.array([0.0, 5.0, 1.0, -1.0, -5.0, 2.0, 6.0])
    assert np.array_equal(jj.relay(tau, 3.0, np.zeros(7)), [1, 1, 1, 1, -1, -1, 1])
    assert np.array_equal(jj.relay(tau, 3.0, np.r_[np.zeros(5), 600.0, 0.0]), [1, 1, 1, 1, -1, 1, 1])
    for g in p["flange_slip"]:
        t = ctx.loads[:, g["joint"]]
        assert -t.min() > g["T_s"] and t.max() > g["T_s"]                     # both thresholds inside the session
    # the hose pull: with a constant force the joint loads are minus the gradient of F0 times the hose's length
    rp = dict(p["hose_retract"], rate=0.0)
    ch, q = ctx.chain, ctx.q[:4]
    sub = SimpleNamespace(chain=ch, q=q)
    ell = lambda qq: np.linalg.norm(np.subtract(*jj.retract_points(rp, SimpleNamespace(chain=ch, q=qq))), axis=1)  # noqa
    loads = jj.retract_loads(rp, sub)
    assert np.abs(loads[:, :jj.RETRACT_BODY]).max() == 0.0                   # an internal force: none on axes 1-3
    for j in range(jj.RETRACT_BODY, ch.n):
        e = 1e-6 * np.eye(ch.n)[j]
        assert loads[:, j] == pytest.approx(-rp["F0_N"] * (ell(q + e) - ell(q - e)) / 2e-6 / 1000, rel=1e-5, abs=1e-7)
    # grout: Boltzmann's sum of the double power law -- a step held, two steps superposed
    t = np.array([0.5, 1.0, 4.0]) * jb.DAY_S
    assert jb.dpl_creep([0.0], np.array([[2.0, 1.0]]), t, 0.125) == pytest.approx(np.outer([0.5, 1, 4], [2, 1]) ** 0.125
                                                                                    * [2 ** 0.875, 1])
    two = jb.dpl_creep([0.0, 0.75 * jb.DAY_S], np.array([[1.0], [-1.0]]), t, 0.125)[:, 0]
    assert two == pytest.approx([0.5 ** 0.125, 1 - 0.25 ** 0.125, 4 ** 0.125 - 3.25 ** 0.125])
    # console: the weight W at the arm's base (no moment) bends the tip down W L^3 / 3EI and turns it by W L^2 / 2EI
    # (the base, d above the section's axis, moves away from the wall); the end plate turns all by W L / S_j
    cp, W = p["wall_console"], 800.0
    lone = SimpleNamespace(mass_state=(np.array([[W / kin.G]]), np.zeros((1, 1, 3)), np.array([1])),
                           target=np.zeros((1, 3)))
    L, c, dep, EI = cp["L_m"], cp["c"], cp["depth_mm"], 2e5
    z = np.array([0, 0, 1.0])
    bend = jb.console_response(cp, lone, EI, np.inf, np.inf, np.inf)[0]
    assert bend == pytest.approx(W * L ** 2 / (2 * EI) * dep * c - 1000 * W * L ** 3 / (3 * EI) * z)
    plate = jb.console_response(cp, lone, np.inf, np.inf, np.inf, 3e5)[0]
    assert plate == pytest.approx(W * L / 3e5 * (dep * c - 1000 * L * z))
    # skewed section: a tip force along the plane's direction u0 deflects F L^3 / 3E (cos^2/I1 + sin^2/I2) in the
    # plane and F L^3 / 3E sin cos (1/I1 - 1/I2) out of it (unsymmetric bending); equal I is the tube's cantilever
    e, u0, v0 = np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), np.array([0, -1.0, 0])
    psi, I1, I2, F = 0.5, 2e-6, 5e-6, np.array([[0, 0, 300.0]])
    d, _ = jb.principal_tip(e, np.cos(psi) * u0 + np.sin(psi) * np.cross(e, u0), 0.7, F, np.zeros((1, 3)),
                            np.zeros(3), 70e9 * I1, 70e9 * I2, np.inf, np.inf)
    k = 300 * 0.7 ** 3 / (3 * 70e9)
    assert d[0] @ u0 == pytest.approx(k * (np.cos(psi) ** 2 / I1 + np.sin(psi) ** 2 / I2))
    assert d[0] @ v0 == pytest.approx(k * np.sin(psi) * np.cos(psi) * (1 / I1 - 1 / I2))
    name, sk = next(iter(p["skew_casting"].items()))
    li = ch.link_names.index(name)
    iso = dict(sk, I1=hw["tubes"][name]["I"], I2=hw["tubes"][name]["I"])
    tb = hw["tubes"][name]
    assert jb.skew_displacement(ctx, li, iso, tb["E"], tb["G"]) == pytest.approx(eb._beam_displacement(
        ctx, li, tb["E"] * tb["I"], tb["k"] * tb["G"] * tb["A"], tb["G"] * tb["J"],
        eb._own_weight(ctx, name, tb)), rel=1e-9, abs=1e-12)
    # tool plate: Saint-Venant's factor of a square (0.141) and of a thin strip (1/3); a load through the plate's
    # axis does not twist it
    assert jb.torsion_beta(1.0, 1.0) == pytest.approx(0.1406, abs=2e-4) and jb.torsion_beta(1.0, 1e-4) == pytest.approx(
        1 / 3, rel=1e-4)
    tp = dict(p["tool_plate"], drop_mm=0.0)
    on_axis = replace(ctx, payload_com_mm=tp["reach_mm"] * tp["d"])
    assert np.abs(jb.plate_displacement(tp, on_axis, np.inf, 1.0)).max() < 1e-12
    assert np.abs(jb.plate_displacement(p["tool_plate"], ctx, np.inf, 1.0)).max() > 0
    # brake-heated housings: the coil is off in the pauses; the lag against Euler's integration in steps of 1 s (its
    # error ~ dt / 2 tau); the tilt axes are normal to the joints' axes
    bp = p["brake_tilt"]
    heat, rise = jt.brake_heat(bp, ctx, hw), jt.brake_rise(bp, ctx, hw)
    assert np.abs(heat[s.gap_s < 0, 0]).max(initial=0.0) == 0.0 and (s.gap_s < 0).any()
    dur, u = jt.ct._segment_times(s), (heat * bp["R_K_per_W"]).reshape(-1, len(bp["joints"]))
    x, fine = np.zeros(len(bp["joints"])), []
    for dt_, ui in zip(dur, u):
        n_ = max(int(np.ceil(dt_)), 1)
        for _ in range(n_):
            x = x + dt_ / n_ * (ui - x) / bp["tau_s"]
        fine.append(x)
    assert rise == pytest.approx(np.array(fine)[2::3], rel=2e-3, abs=1e-6) and rise.max() > 3.0
    true_axes = case.truth["chain"].axes[bp["joints"]]                      # drawn on the true robot
    assert np.abs(np.einsum("ki,ki->k", bp["normal_home"], true_axes)).max() < 1e-12
    # laminate: the shear expansion of an off-axis ply; the twist turns the chain about the tube's axis at its tip
    assert jt.shear_cte(-0.5e-6, 30e-6, np.pi / 4) == pytest.approx(-30.5e-6) and jt.shear_cte(1, 2, 0.0) == 0.0
    parts, lp = jt.laminate_parts(p["laminate_twist"], ctx), p["laminate_twist"]
    for k_, name in enumerate(lp["links"]):
        e, tip, L = eb._beam_state(ctx, ch.link_names.index(name))
        r = ctx.target - tip
        assert np.abs(np.einsum("pi,pi->p", parts[k_], e)).max() < 1e-9 * np.abs(parts[k_]).max()
        assert np.abs(np.einsum("pi,pi->p", parts[k_], r)).max() < 1e-9 * np.abs(parts[k_]).max() * 1e3
        assert 0.2 * 25e-6 * np.sin(np.deg2rad(40)) / 0.06 < abs(lp["links"][name]) < 0.5 * 35.7e-6 / 0.03

    case, ctx = runs["kr16_like"]
    p, hw = case.truth["params"], case.truth["hw"]
    # differential: a move along gear A's constant angle (pitch + i roll) leaves its error; one train's error splits
    # into dq_pitch = e / 2 and dq_roll = +-e / 2i
    dp = p["diff_wrist"]
    one = dict(dp, trains=dp["trains"][:1])
    qa = np.zeros((3, 6))
    qa[1, [4, 5]] = [0.3 * dp["i"], -0.3]
    qa[2, [4, 5]] = [0.1, 0.7]
    dq = jj.diff_apply(one, SimpleNamespace(q=qa), None).dq
    assert dq[1, 4] == pytest.approx(dq[0, 4], abs=1e-15) and dq[2, 5] == pytest.approx(dq[2, 4] / dp["i"])
    assert abs(dq[2, 4]) > 0 and 25 / 45 <= dp["i"] <= 45 / 25
    # bar pins: the flank is the load's once |tau_3| beats the drag, else it trails the crank (q2 + q3); the lever
    # turns by c / 2 r sin(gamma)
    bp = p["bar_pins"]
    sig, t3 = jj.pin_signal(bp, ctx), ctx.loads[:, 2]
    gamma = bp["gamma_mid"] + ctx.q[:, 2] - bp["q_mid"]
    crank = np.sign(np.diff(ctx.q[:, 1] + ctx.q[:, 2]))
    big = np.abs(t3) > bp["T_f"]
    assert np.array_equal(np.sign(sig[big]), np.sign(t3[big])) and np.abs(sig * np.sin(gamma)) == pytest.approx(1.0)
    small = ~big[1:] & (crank != 0)
    assert np.array_equal(np.sign(sig[1:][small]), -crank[small])
    assert jj.pin_apply(bp, ctx, hw).dq[:, 2] == pytest.approx(bp["c_mm"] / 2e3 / bp["r_m"] * sig)
    # wrist shafts: the compliance G^-1 diag(L / GJ) G^-T is symmetric (Maxwell) and tau . dq is the shafts' energy
    wp = p["wrist_shafts"]
    W, Gi = wp["W"], np.linalg.inv(jj.shaft_matrix(wp))
    cols = jj.shaft_columns(wp, ctx)
    for k_, sh in enumerate(wp["shafts"]):
        a = W.index(sh["joint"])
        assert cols[k_][:, W] == pytest.approx(np.outer(ctx.loads[:, W] @ Gi[:, a], Gi[:, a]))
        assert np.einsum("pn,pn->p", ctx.loads, cols[k_]) == pytest.approx((ctx.loads[:, W] @ Gi[:, a]) ** 2)
    C = sum(sh["L_m"] / sh["GJ"] * np.outer(Gi[:, W.index(sh["joint"])], Gi[:, W.index(sh["joint"])])
            for sh in wp["shafts"])
    assert C == pytest.approx(C.T) and set(wp["c"]) == {(4, 3), (5, 3), (5, 4)}
    bare = dict(wp, c={}, N2={j: 2.0 for j in W})
    assert jj.shaft_columns(bare, ctx)[0][:, 4] == pytest.approx(ctx.loads[:, 4] / 4.0)


def test_set_k_cases_kinds_and_determinism():
    """Set K: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-K
    kind alone (no random numbers drawn); the RCC's target sits at its gripper's tip with the payload in the jaws, the
    ram's cutter 250-450 mm off the wrist axis."""
    from sim2real_indep import effects_k as ek

    _assert_set_module("K", 40_7011, ek, ("gear", "laminate_twist"))
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert ek.probe_hook(("sag", "ram_roll"), probe) is probe and ek.payload_hook(("sag",), com, probe) is com
    grip = ek.probe_hook(("rcc",), probe)
    assert grip == pytest.approx([3.0, -4.0, 150 + 100 * 12 / 13])
    assert ek.payload_hook(("rcc",), com, grip) == pytest.approx(0.8 * grip + com / 4)
    assert ek.payload_hook(("ram_roll",), com, probe) == pytest.approx([250 + 200 * np.sqrt(125) / 80, 0.0, 5.0])
    _assert_regenerates("K", max_effect_poses=50)


def test_set_k_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-K kind's displacement lies in the span of its true-structure features (what the oracle fits), to
    rounding, and is a real effect where the kind applies; the telescopic arm's kinds, the bulkhead, the side cylinder
    and the thermal backlash do nothing on ur10; and known answers: the hose's pull as virtual work and its vacuum,
    the ropes' linear limit and their lengths, the RCC's translation under a force through its centre, Terzaghi's
    T_50 and T_90 and a load held, the clamped plate's slope, the cylinder holding axis 2 by the law of cosines, the
    ram's roll torque as the gradient of the potential, Hooke's joint's largest error, the spline's proportional
    twist, the AGMA backlash change, the housing's exact lag and the copper part of the drives' heat."""
    from dataclasses import replace

    from sim2real_indep import effects_k_body as kb
    from sim2real_indep import effects_k_joint as kj
    from sim2real_indep import effects_k_thermal as kt

    inert = ("bulkhead", "side_cylinder", "tele_rope", "thermal_lash", "ram_roll", "cardan", "spline_twist")
    runs = _assert_kinds_reproduce((("ur10", ("vacuum_hose", "rcc", "outrigger_soil", "read_head", "comp_mismatch")),
                                    ("tool_changer", inert), ("kr16_like", ("vacuum_hose", "thermal_lash")),
                                    ("ur10", inert)), 11, inert=inert, min_mm=1e-2)

    case, ctx = runs["ur10"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    ch = ctx.chain
    # vacuum hose: the loads of a unit pull are its virtual work, F . dp_fit / dq (the fitting's position moved by
    # each joint); none while no part is held (the vacuum off); the thrust dp pi D^2 / 4
    vp = p["vacuum_hose"]
    held = s.payload_kg > 0
    assert held.any() and (~held).any()
    loads = kj.vac_loads(vp, ctx)
    assert np.abs(loads[~held]).max() == 0.0
    i = int(np.flatnonzero(held)[0])

    def fit(qq):
        fl, Rt = kin.flange(ch, qq[None])
        return (fl + Rt @ vp["fitting_mm"])[0]
    u = vp["anchor_mm"] - fit(ctx.q[i])
    u /= np.linalg.norm(u)
    for j in range(ch.n):
        e = 1e-6 * np.eye(ch.n)[j]
        virtual = u @ (fit(ctx.q[i] + e) - fit(ctx.q[i] - e)) / 2e-6 / 1000
        assert loads[i, j] == pytest.approx(virtual, rel=1e-5, abs=1e-9)
    assert 0.6e5 * np.pi / 4 * 0.014 ** 2 <= vp["thrust_N"] <= 0.85e5 * np.pi / 4 * 0.025 ** 2
    # RCC: with the gripper weightless and the payload at the compliance centre, a force through the centre moves the
    # gripper without turning it: only the lateral and axial columns, the weight's parts across and along the tool axis
    rp = dict(p["rcc"], m_grip=0.0)
    at_centre = replace(ctx, payload_com_mm=rp["centre_mm"])
    parts = kb.rcc_parts(rp, at_centre)
    assert np.abs(parts[2:]).max() < 1e-12
    _, Rt = kin.flange(ch, ctx.q)
    ax = Rt[:, :, 2]
    W = s.payload_kg * kin.G
    assert np.linalg.norm(parts[0], axis=1) == pytest.approx(W * np.sqrt(1 - ax[:, 2] ** 2), abs=1e-9)
    assert np.einsum("pi,pi->p", parts[1], ax) == pytest.approx(-W * ax[:, 2], abs=1e-9)
    # outriggers: Terzaghi's time factors for 50 % and 90 % consolidation (0.197, 0.848), the early sqrt(4 T / pi);
    # a load held since before the session consolidates as U((t + t_pre) / t_ref)
    assert kb.terzaghi_U([0.197, 0.848]) == pytest.approx([0.5, 0.9], abs=2e-3)
    assert kb.terzaghi_U([1e-5, 0.0, -1.0]) == pytest.approx([np.sqrt(4e-5 / np.pi), 0.0, 0.0])
    op = p["outrigger_soil"]
    X = np.ones((len(ctx.q), 2))
    _, dur = kb.load_history(ctx, X)
    t_meas = np.cumsum(dur.ravel())[1::2]
    assert kb.consolidated(op, ctx, X)[:, 0] == pytest.approx(kb.terzaghi_U((t_meas + op["pre_s"]) / op["t_ref_s"]))
    # read heads: the housing's lag against Euler's integration in steps of 1 s (its error ~ dt / 2 tau); it warms
    hp = p["read_head"]
    rise = kt.head_rise(hp, ctx, hw)
    dT_ex = kt.ct.drive_heat(ctx, hw, hp["accel_s"], hp["duty"], exercise_only=True)[hp["joints"]]
    u_seg = (kt.ct.drive_heat(ctx, hw, hp["accel_s"], hp["duty"])[:, :, hp["joints"]] * (hp["rise_K"] / dT_ex)).reshape(
        -1, len(hp["joints"]))
    x, fine = np.zeros(len(hp["joints"])), []
    for dt_, ui in zip(kt.ct._segment_times(s), u_seg):
        n_ = max(int(np.ceil(dt_)), 1)
        for _ in range(n_):
            x = x + dt_ / n_ * (ui - x) / hp["tau_s"]
        fine.append(x)
    assert rise == pytest.approx(np.array(fine)[2::3], rel=2e-3, abs=1e-6) and rise.max() > 5.0
    assert kt.head_apply(hp, ctx, hw).dq[:, hp["joints"]] == pytest.approx(rise * hp["k_rad_per_K"])
    # compensation: the winding's heat is the drive's copper loss: the whole loss at a dwell (no speed), the whole loss
    # less the friction loss f T_rated |omega| in a move; kappa, exact at the production cycle's steady state
    cp = p["comp_mismatch"]
    cu, cu_ex = kt.copper_heat(ctx, hw, cp["accel_s"], cp["duty"])
    whole = kt.ct.drive_heat(ctx, hw, cp["accel_s"], cp["duty"])
    assert cu[:, 2] == pytest.approx(whole[:, 2])
    fr = np.array([d["friction_frac"] * d["T_rated"] for d in hw["drives"]])
    assert whole[:, 1] - cu[:, 1] == pytest.approx(fr * s.speed, rel=1e-9, abs=1e-9)
    ex_whole = kt.ct.drive_heat(ctx, hw, cp["accel_s"], cp["duty"], exercise_only=True)
    assert ex_whole - cu_ex == pytest.approx(fr * s.exercise_speed)
    assert cp["kappa"] == pytest.approx(cp["rise_l"] / cp["rise_w"])

    case, ctx = runs["tool_changer"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    ch = ctx.chain
    # ropes: with g = 0 the stretch is F times the holding rope's free length over EA (retraction rope L_ret + q for
    # a push out, extension rope L_ext - q for a pull in)
    rp = dict(p["tele_rope"], g=0.0)
    F, q = ctx.loads[:, 3], ctx.q[:, 3] / 1000
    L = np.where(F > 0, rp["L_ret_m"] + q, rp["L_ext_m"] - q)
    assert (F > 0).any() and (F < 0).any() and L.min() > 0.2
    assert kj.rope_apply(rp, ctx, hw).dq[:, 3] == pytest.approx(1000 * F * L * rp["c_per_m"])
    # bulkhead: the clamped plate's slope is -dw/dr, w(0) = 1, w(a) = slope(a) = 0; the base moves along y and turns
    # about x: no target moves along x; the pressure change starts at zero
    a_ = 3.0
    r = np.linspace(0.1, 2.9, 29)
    w1, sl = kb.plate_shape(a_, r)
    assert sl == pytest.approx(-(kb.plate_shape(a_, r + 1e-6)[0] - kb.plate_shape(a_, r - 1e-6)[0]) / 2e-6, rel=1e-6)
    assert kb.plate_shape(a_, 0.0)[0] == 1.0 and kb.plate_shape(a_, a_) == (0.0, 0.0)
    bp = p["bulkhead"]
    assert np.abs(kb.bulk_pattern(bp, ctx)[:, 0]).max() < 1e-12 and kb.chamber_pressure(bp, s.time_s)[0] == 0.0
    # side cylinder: its force holds axis 2's gravity load (moment -tau_2 about the axis at the eye), its moment arm the
    # law of cosines' r1 r2 sin(psi) / L; without the offset nothing twists the arm about its axis
    cp = p["side_cylinder"]
    Fc, e, w2, eye = kb.cyl_force(cp, ctx)
    root = eye - 1000 * cp["r2"] * e
    assert np.einsum("pi,pi->p", np.cross((eye - root) / 1000, Fc), w2) == pytest.approx(-ctx.loads[:, 1])
    psi = cp["psi0"] + cp["s"] * ctx.q[:, 1]
    Lc = np.sqrt(cp["r1"] ** 2 + cp["r2"] ** 2 - 2 * cp["r1"] * cp["r2"] * np.cos(psi))
    arm = cp["r1"] * cp["r2"] * np.sin(psi) / Lc
    assert np.linalg.norm(Fc, axis=1) == pytest.approx(np.abs(ctx.loads[:, 1]) / arm)
    # the offset's moment twists the root segment by e F_n r2 / GJ, F_n the force's part across the arm in its plane
    tb = hw["tubes"][ch.link_names[cp["link"]]]
    d, rot = ph.cantilever_tip(e, cp["r2"], Fc, np.cross(cp["e_m"] * w2, Fc), np.zeros(3), np.inf, np.inf,
                               tb["G"] * tb["J"])
    F_n = np.einsum("pi,pi->p", Fc, np.cross(w2, e))
    assert np.einsum("pi,pi->p", rot, e) == pytest.approx(-cp["e_m"] * F_n * cp["r2"] / (tb["G"] * tb["J"]))
    assert np.abs(d).max() == 0.0 and 0.25 <= abs(cp["e_m"]) <= 0.4
    # ram roll: the roll torque is minus the derivative of the masses' potential under a roll about the ram's axis;
    # the ram sits on the torque's side once it beats the friction
    gp = p["ram_roll"]
    T = kj.roll_torque(ctx, 3)
    m, pos, body = ctx.mass_state
    w, c = kin.joint_frames(ch, ctx.q)
    on = body >= 4

    def potential(phi):
        R = kin._rot(w[:, 3], phi * np.ones(len(ctx.q)))
        rel = np.einsum("pij,pbj->pbi", R, pos[:, on] - c[:, 3, None]) + c[:, 3, None]
        return (m[:, on] * kin.G * rel[..., 2] / 1000).sum(axis=1)
    assert T == pytest.approx(-(potential(1e-6) - potential(-1e-6)) / 2e-6, rel=1e-5, abs=1e-6)
    side = np.einsum("pi,pi->p", kj.roll_part(gp, ctx), np.cross(w[:, 3], ctx.target - c[:, 3]))
    big = np.abs(T) > gp["T_f"]
    assert np.array_equal(np.sign(side[big]), np.sign(T[big])) and set(np.sign(T[big])) == {-1.0, 1.0}
    # Cardan joint: tan(phi_2) = tan(phi_1) / cos(beta); its largest error atan((1 - cos b) / (2 sqrt(cos b))) at
    # tan(phi) = sqrt(cos b), twice per turn, none straight
    phi = np.linspace(0, 2 * np.pi, 20001)
    for b in (0.05, 0.3):
        err = kj.hooke_error(phi, b)
        assert err.max() == pytest.approx(np.arctan((1 - np.cos(b)) / (2 * np.sqrt(np.cos(b)))), rel=1e-6)
        assert kj.hooke_error(phi + np.pi, b) == pytest.approx(err, abs=1e-12)
        assert np.tan(phi[:100] + err[:100]) == pytest.approx(np.tan(phi[:100]) / np.cos(b))
    assert np.abs(kj.hooke_error(phi, 0.0)).max() < 1e-12
    # spline: the wrist joints off in proportion to the extension, by the groove's torsion over r_g and N_b
    for sp in p["spline_twist"]:
        assert 8e-5 / 20 / 2.9 <= abs(sp["rad_per_mm"]) <= 20e-5 / 10 / 1.3
    dq = kj.spline_apply(p["spline_twist"], ctx, hw).dq
    assert dq[:, 4] == pytest.approx(p["spline_twist"][0]["rad_per_mm"] * ctx.q[:, 3])
    # thermal backlash: AGMA's 2 tan(alpha_n) da over the ring's radius; axis 1 (no gravity load) trails its motion
    lp = p["thermal_lash"]
    assert 2 * np.tan(np.deg2rad(20)) * 11.7e-6 * 0.5 / 0.55 <= lp["k_rad_per_K"] <= 2 * np.tan(
        np.deg2rad(20)) * 11.7e-6 * 0.65 / 0.42
    sig = kt.lash_signals(lp, ctx, hw)
    assert np.array_equal(sig[0], -s.direction[:, 0]) and sig[1].max() > 1.0
    width = lp["b0_rad"] * sig[0] + lp["k_rad_per_K"] * sig[1]
    assert kt.lash_apply(lp, ctx, hw).dq[:, 0] == pytest.approx(width / 2)


def test_set_l_cases_kinds_and_determinism():
    """Set L: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-L
    kind alone (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a gripper
    case's target sits on a finger's tip, its part between the fingers, and its blocks both hold a part and not."""
    from sim2real_indep import effects_l as el
    from sim2real_indep import effects_l_body as lb

    _assert_set_module("L", 40_7012, el, ("gear", "comp_mismatch"))
    for name in ("effects_l", "effects_l_joint", "effects_l_body", "effects_l_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_l" in _imports(STUDY / "generator.py")
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert el.probe_hook(("sag", "rcc"), probe, "ur10") is probe and el.payload_hook(("sag",), com, probe) is com
    tip = el.probe_hook(("grip_spread",), probe, "ur10")
    assert tip == pytest.approx([0.6 * (15 + 30 * 8 / 95), -0.8 * (15 + 30 * 8 / 95), 130 + 90 * 12 / 13])
    assert el.payload_hook(("hot_part",), com, tip) == pytest.approx([0, 0, 0.85 * tip[2]] + com / 4)
    d, w, z = lb.finger_geometry(tip)
    assert d == pytest.approx([0.6, -0.8, 0.0]) and lb.finger_length("ur10", z) == pytest.approx(60 + 50 * 12 / 13)
    for seed in range(4):
        steps = el.session_options("tool_changer", ("grip_spread",), np.random.default_rng(seed),
                                   {"blocks": 2, "gap_kind": "none"})["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
    _assert_regenerates("L", max_effect_poses=50)


def test_set_l_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-L kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds of other arms do nothing; and known answers: the
    polymer's modulus falling by a third over 37 K, the cartridge's mass history and its weight's virtual work, the
    measuring pinion's lead, the valve band's edges, the pins' staircase, a corner load on the frame's four feet,
    Junker's law and the plate rocking about its compressed edge, the finger's cantilever, the holder's dead zone and
    stroke end, the guide's Legendre curves and the directions of its error motions, the two lags' step response and
    the wet tube's drying decay."""
    from dataclasses import replace
    from types import SimpleNamespace

    from sim2real_indep import effects_l_body as lb
    from sim2real_indep import effects_l_joint as lj
    from sim2real_indep import effects_l_thermal as lt
    from sim2real_indep import hardware as hwm

    inert = {"ur10": ("gauge_pinion", "valve_lap", "pin_ring", "anchor_loose", "guide_errors", "hot_part"),
             "kr16_like": ("polymer_heat", "valve_lap", "pin_ring", "anchor_loose", "guide_errors"),
             "tool_changer": ("polymer_heat", "dispense_drain", "pallet_load", "float_holder", "wet_arm", "hot_part")}
    specs = (("ur10", ("polymer_heat", "dispense_drain", "pallet_load", "grip_spread", "float_holder", "wet_arm")),
             ("kr16_like", ("gauge_pinion", "hot_part")),
             ("tool_changer", ("valve_lap", "pin_ring", "guide_errors", "anchor_loose")),
             ("ur10", inert["ur10"]), ("kr16_like", inert["kr16_like"]), ("tool_changer", inert["tool_changer"]))
    runs = {}
    for k, (robot, physics) in enumerate(specs):
        case = gen.generate("t", robot, physics, 30, 12)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault(robot, (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p, hw = case.truth["params"][kind], case.truth["hw"]
            amp = {"polymer_heat": lambda: [c for c, s in zip(p["c0_rad_per_Nm"], lj.soft_signals(p, ctx, hw))
                                            if np.abs(s).max() > 1e-12],
                   "dispense_drain": lambda: [hwm.torsion(hw["drives"][j], 1.0, False) for j in range(ctx.chain.n)
                                              if np.abs(lj.drain_loads(p, ctx)[:, j]).max() > 1e-9],
                   "gauge_pinion": lambda: [p["half_rad"]], "valve_lap": lambda: [p["e_db_mm"]],
                   "pin_ring": lambda: [-p["sigma_mm"] / (1000 * p["R_m"])],
                   "pallet_load": lambda: [1 / p["k_N_per_m"]],
                   "anchor_loose": lambda: [p["c_open"]], "grip_spread": lambda: p["c_mm_per_N"],
                   "float_holder": lambda: [1.0], "guide_errors": lambda: np.ones(5), "hot_part": lambda: np.ones(2),
                   "wet_arm": lambda: np.ones(2 * len(p["tubes"]))}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs["ur10"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    ch = ctx.chain
    # polymer gears: a modulus falling from 3 to 2 GPa over 37 K (POM) grows the twist by half; none at room temperature
    assert lj.softening(np.log(1.5) / 37, 37.0) == pytest.approx(0.5) and lj.softening(0.01, 0.0) == 0.0
    sp = p["polymer_heat"]
    assert lj.soft_signals(sp, ctx, hw) == pytest.approx(ctx.loads[:, sp["joints"]].T * np.expm1(
        sp["beta_per_K"][:, None] * lj.soft_rise(sp, ctx, hw).T))
    # cartridge: full 2 kg from the start, 1 g/s: 1.4 kg after 10 min of production, 0.2 kg after 30, then a full one
    # replaces the empty (5 %) one: 1.5 kg after 40 min; the unit loads are the weight's virtual work, -g dz/dq
    cp = dict(p["dispense_drain"], full_kg=2.0, start_kg=2.0, rate_kg_s=1e-3)
    fake = SimpleNamespace(gap_s=np.array([0.0, 600.0, -300.0, 1200.0, 600.0]))
    assert lj.cartridge_mass(cp, fake) == pytest.approx([2.0, 1.4, 1.4, 0.2, 1.5])
    loads = lj.drain_unit_loads(cp, ctx)

    def height(qq):
        fl, Rt = kin.flange(ch, qq[None])
        return (fl + Rt @ cp["com_mm"])[0, 2]
    for j in range(ch.n):
        e = 1e-6 * np.eye(ch.n)[j]
        assert loads[0, j] == pytest.approx(-kin.G * (height(ctx.q[0] + e) - height(ctx.q[0] - e)) / 2e-6 / 1000,
                                            rel=1e-5, abs=1e-9)
    # palletising frame: a load W on a corner foot of a rigid frame on four equal feet sinks that corner by 3W / 4k and
    # lifts the opposite one by W / 4k
    a, b, k, W = 0.5, 0.4, 2e6, 1000.0
    pp = {"a_m": a, "b_m": b, "k_N_per_m": k, "base_m": np.zeros(3), "pallet_m": np.array([a, b, 0.0]),
          "full_kg": 1e4, "start_kg": W / kin.G, "rate_kg_s": 0.0}
    corners = 1000.0 * np.array([[a, b, 0.0], [-a, -b, 0.0], [a, -b, 0.0]])
    stub = SimpleNamespace(mass_state=(np.zeros((3, 1)), np.zeros((3, 1, 3)), np.array([1])), target=corners,
                           session=SimpleNamespace(gap_s=np.zeros(3)))
    assert lb.pallet_part(pp, stub)[:, 2] / k == pytest.approx(1000 * W / k * np.array([-0.75, 0.25, -0.25]))
    # finger: a force at the tip bends the cantilever by L^3 / 3EI, none at the root; no part held, no spread
    assert lb.tip_compliance(0.1, 0.1, 50.0) == pytest.approx(0.1 ** 3 / 150) and lb.tip_compliance(0.1, 0.0, 50) == 0
    gp = p["grip_spread"]
    assert gp["c_mm_per_N"][0] == pytest.approx(1000 * lb.tip_compliance(gp["L_m"], gp["a_m"], gp["E"] * gp["b_m"]
                                                                         * gp["t_m"] ** 3 / 12))
    empty = replace(ctx, session=replace(s, payload_kg=np.zeros(len(s.q))))
    assert np.abs(lb.grip_parts(gp, empty)).max() == 0.0 and (s.payload_kg == 0).any() and (s.payload_kg > 0).any()
    # holder: no motion below the preload, the excess at the rate beyond it, the stroke end
    fp = p["float_holder"]
    g, Rt = lb._gravity_tool(ctx)
    side = np.linalg.norm((fp["m_tool_kg"] + s.payload_kg)[:, None] * g[:, :2], axis=1)
    move = np.linalg.norm(lb.float_part(fp, ctx), axis=1)
    assert move == pytest.approx(np.clip((side - fp["F_p_N"]) / fp["k_N_per_mm"], 0.0, fp["stroke_mm"]), abs=1e-12)
    assert (side < fp["F_p_N"]).any() and (move > 0).any()
    # wet tube: the diameter from the section; after the film has dried the tube's share decays as exp(-t / tau)
    A_, I_, _ = ph.tube_section(0.09, 0.004)
    assert lt.tube_diameter({"A": A_, "I": I_}) == pytest.approx(0.09)
    wp = dict(p["wet_arm"], pre_s=900.0, dry_s=300.0, tau_s=400.0)
    still = replace(s, gap_s=np.zeros(len(s.q)))
    t_end = np.cumsum(lt.ct._segment_times(still).reshape(-1, 3).sum(axis=1))
    assert lt.wet_state(wp, still) == pytest.approx(np.exp((300.0 - 900.0 - t_end) / 400.0))

    case, ctx = runs["kr16_like"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # measuring pinion: the joint leads its reading by half the backlash over the ring's radius, towards its last motion
    gp = p["gauge_pinion"]
    assert lj.gauge_apply(gp, ctx, hw).dq[:, 0] == pytest.approx(gp["jn_mm"] / 2000 / gp["R_m"] * s.direction[:, 0])
    assert 0.05 / 2000 / 0.38 <= gp["half_rad"] <= 0.2 / 2000 / 0.25
    # hot parts: the two lags' response to a step from rest -- x1 = 1 - e1, x2 = 1 - (tau1 e1 - tau2 e2) / (tau1 - tau2)
    # -- and a steady state that stays
    t = np.array([60.0, 300.0, 1200.0])
    x1, x2 = lt.two_lags(np.diff(np.r_[0.0, t]), np.ones(3), 200.0, 900.0, 0.0, 0.0)
    e1, e2 = np.exp(-t / 200), np.exp(-t / 900)
    assert x1 == pytest.approx(1 - e1) and x2 == pytest.approx(1 - (200 * e1 - 900 * e2) / (200 - 900))
    assert np.array(lt.two_lags([50.0, 70.0], [0.4, 0.4], 200.0, 900.0, 0.4, 0.4)) == pytest.approx(0.4)
    assert lt.hot_temperatures(p["hot_part"], ctx).max() > 5.0

    case, ctx = runs["tool_changer"]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # valve band: with no leakage the cylinder stops short on the side of its approach; with much leakage at the load's
    # edge; in between, drifted by the leakage
    vp = p["valve_lap"]
    loads = np.zeros_like(ctx.q)
    loads[:, 1] = np.linspace(-3000.0, 3000.0, len(ctx.q))
    lever = SimpleNamespace(q=ctx.q, loads=loads, session=s)
    d_L, s_F = vp["s"] * s.direction[:, 1], np.sign(vp["s"] * loads[:, 1])
    assert lj.valve_band(dict(vp, rho_per_Ns=0.0), lever)[0] == pytest.approx(-d_L)
    assert lj.valve_band(dict(vp, rho_per_Ns=1.0), lever)[0][np.abs(loads[:, 1]) > 100] == pytest.approx(
        s_F[np.abs(loads[:, 1]) > 100])
    g_, a_ = lj.valve_band(vp, lever)
    rho = vp["rho_per_Ns"] * np.abs(loads[:, 1]) / a_ * s.dwell_s
    assert g_ == pytest.approx(np.clip(-d_L + s_F * rho, -1, 1)) and np.abs(g_).max() <= 1.0
    # pin ring: each pin's error while it meshes, the handover's mean half-way; the drawn errors, not a smooth curve
    rp = p["pin_ring"]
    th = (np.arange(rp["Z"]) * 2 * np.pi - rp["phase"] * rp["Z"]) / rp["Z"]
    assert lj.pin_error(rp, th) == pytest.approx(rp["e"]) and lj.pin_error(rp, th + np.pi / rp["Z"]) == pytest.approx(
        (rp["e"] + np.roll(rp["e"], -1)) / 2)
    # guideway: P_k(+-1) = (+-1)^k; straightness across the ram, roll normal to the axis and the arm
    gp = p["guide_errors"]
    ends = lb.guide_curves(gp, [gp["lo"], gp["hi"]])
    assert ends[:, 1] == pytest.approx([c.sum() for c in gp["coef"].values()])
    assert ends[:, 0] == pytest.approx([(c * (-1.0) ** np.arange(5)).sum() for c in gp["coef"].values()])
    parts = lb.guide_parts(gp, ctx)
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    axis = w[:, 3]
    for k_ in (0, 1, 2):
        assert np.abs(np.einsum("pi,pi->p", parts[k_], axis)).max() < 1e-9 * max(np.abs(parts[k_]).max(), 1e-9)
    assert np.abs(np.einsum("pi,pi->p", parts[2], ctx.target - c[:, 3])).max() < 1e-6
    # anchors: Junker's fall (1 - s after 9 N0 cycles, floored at a fifth); the plate rocks about its compressed edge,
    # which stays put, the far edge lifting 2 R omega
    ap = p["anchor_loose"]
    N9 = SimpleNamespace(gap_s=np.array([0.0, 9 * ap["N0"] * ap["cycle_s"]]))
    assert lb.clamp_share(ap, N9) == pytest.approx([1.0, 1 - ap["s"]])
    assert lb.clamp_share(dict(ap, s=5.0), N9)[1] == 0.2
    R, h = ap["R_m"], ap["h_mm"]
    m = np.array([[1000.0], [1000.0]])
    pos = np.array([[[2000.0, 0.0, 500.0]], [[2000.0, 0.0, 500.0]]])
    edges = np.array([[1000 * R, 0.0, -h], [-1000 * R, 0.0, -h]])
    rock = SimpleNamespace(mass_state=(m, pos, np.array([1])), target=edges, session=SimpleNamespace(gap_s=np.zeros(2)))
    omega = 1000 * kin.G * 2.0 - lb.decompression(ap, rock)[0]
    assert omega > 0
    assert lb.loose_part(ap, rock) == pytest.approx(np.array([[0, 0, 0], [0, 0, 2000 * R * omega]]), abs=1e-6)


def test_set_m_cases_kinds_and_determinism():
    """Set M: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-M
    kind alone (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a bar or
    jaw case's target sits on the bar's end or the finger's tip, its part on the bar's middle or between the fingers,
    its blocks both hold a part and not; a docked cart's blocks are separated by production periods."""
    from sim2real_indep import effects_m as em

    _assert_set_module("M", 40_7013, em, ("gear", "wet_arm"))
    for name in ("effects_m", "effects_m_joint", "effects_m_body", "effects_m_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_m" in _imports(STUDY / "generator.py")
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert em.probe_hook(("sag", "grip_spread"), probe, "ur10") is probe
    assert em.payload_hook(("sag",), com, probe) is com
    end = em.probe_hook(("tie_rod_bar",), probe, "kr16_like")
    assert end == pytest.approx([0.6 * (600 + 300 * 8 / 95), -0.8 * (600 + 300 * 8 / 95), 60 + 0.4 * 12])
    assert em.payload_hook(("tie_rod_bar",), com, end) == pytest.approx(end / 2)
    tip = em.probe_hook(("jaw_play",), probe, "tool_changer")
    assert tip == pytest.approx([0.6 * (120 + 80 * 8 / 95), -0.8 * (120 + 80 * 8 / 95), 300 + 150 * 12 / 13])
    assert em.payload_hook(("jaw_play",), com, tip) == pytest.approx([0, 0, 0.85 * tip[2]] + com / 4)
    for seed in range(4):
        steps = em.session_options("ur10", ("jaw_play",), np.random.default_rng(seed),
                                   {"blocks": 2, "gap_kind": "none"})["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
        opts = em.session_options("kr16_like", ("cart_dock",), np.random.default_rng(seed),
                                  {"blocks": 2, "gap_kind": "none"})
        assert opts["blocks"] >= 5 and opts["gap_kind"] == "exercise"
    _assert_regenerates("M", max_effect_poses=50)


def test_set_m_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-M kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds of other arms do nothing; and known answers:
    Archimedes' lift on a drowned cutter, the hydraulic spring beta A^2 / V and Boyle's law for the air, the dither's
    centred and trailing axis 1, the chain's chordal extreme, the wheel's order and scale, the dockings' rigid moves,
    the carriage held inside its friction band, the play operator, the bar's uniform-load tip deflection, the jaw
    opened by the grip, the plume's optical path and bend through a Gaussian column and the oil's first-order
    warm-up."""
    from types import SimpleNamespace

    from sim2real_indep import effects_m_body as mb
    from sim2real_indep import effects_m_joint as mj
    from sim2real_indep import effects_m_thermal as mt
    from sim2real_indep import hardware as hwm

    inert = {"ur10": ("slurry_lift", "oil_column", "spindle_dither", "chain_stage", "friction_wheel", "oil_growth"),
             "kr16_like": ("slurry_lift", "oil_column", "chain_stage", "jaw_play", "oil_growth"),
             "tool_changer": ("cart_dock", "carriage_play", "rope_mount", "tie_rod_bar")}
    specs = (("ur10", ("cart_dock", "carriage_play", "rope_mount", "hot_plume")), ("ur10", ("jaw_play",)),
             ("kr16_like", ("spindle_dither", "friction_wheel", "tie_rod_bar")),
             ("tool_changer", ("slurry_lift", "oil_column", "chain_stage", "oil_growth")),
             ("ur10", inert["ur10"]), ("kr16_like", inert["kr16_like"]), ("tool_changer", inert["tool_changer"]))
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 13)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault((robot, physics[0]), (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p, hw = case.truth["params"][kind], case.truth["hw"]
            amp = {"slurry_lift": lambda: [hwm.torsion(hw["drives"][j], 1.0, False) for j in range(ctx.chain.n)
                                           if np.abs(mj.slurry_loads(p, ctx)[:, j]).max() > 1e-9],
                   "oil_column": lambda: [1 / p["beta_Pa"], p["eps"]] * len(p["cyl"]),
                   "spindle_dither": lambda: p["b_rad"] / 2, "chain_stage": lambda: [1.0, p["elong"]],
                   "friction_wheel": lambda: mj.wheel_amplitudes(p), "cart_dock": lambda: p["amp"][1:].ravel(),
                   "carriage_play": lambda: [p["theta_rad"]], "rope_mount": lambda: p["c_mm_per_N"],
                   "tie_rod_bar": lambda: p["c_mm_per_N"], "jaw_play": lambda: p["amp_mm"],
                   "hot_plume": lambda: [p["dT_K"]], "oil_growth": lambda: [mt.STEEL_CTE] * len(p["cyl"])}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs[("tool_changer", "slurry_lift")]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # slurry: half a body below the level at its centre; a cutter drowned whole (no wrist) is lifted by rho / rho_steel
    # of its weight -- its joint loads are that share of its gravity loads, reversed
    assert mj.submerged(100.0, [100.0, -500.0, 500.0], 200.0) == pytest.approx([0.5, 1.0, 0.0])
    sp = dict(p["slurry_lift"], level_mm=1e9, wrist=[], fill=[], h_wrist_mm=[])
    m, pos, body = ctx.mass_state
    grav = kin.gravity_loads(ctx.chain, ctx.q, m[:, -1:], pos[:, -1:], body[-1:])
    assert mj.slurry_loads(sp, ctx) == pytest.approx(-sp["rho"] / mj.STEEL_RHO * grav, abs=1e-9)
    # oil column: without air the cylinder shortens by F / (beta A^2 / V) (the hydraulic spring); the air's share is
    # Boyle's volume change eps V p0 (1 / p_b - 1 / p)
    op, j = p["oil_column"], 1
    c = op["cyl"][j]
    _, L, a = mj.fj.lever_state(c, ctx.q[:, j])
    F = c["s"] * ctx.loads[:, j] / a
    A = np.where(F >= 0, c["A_cap"], c["A_rod"])
    V = np.where(F >= 0, c["A_cap"] * (L - c["L_lo"]), c["A_rod"] * (c["L_hi"] - L)) + c["V_pipe"]
    oil, air = mj.oil_signals(op, ctx, j)
    assert np.abs(oil / op["beta_Pa"] * a) == pytest.approx(np.abs(F) / (op["beta_Pa"] * A ** 2 / V))
    p_b, p_1 = op["p_b_Pa"], op["p_b_Pa"] + np.abs(F) / A
    assert np.abs(air * a) * A == pytest.approx(V * mj.P0 * (1 / p_b - 1 / p_1))
    # chain: the chordal error vanishes mid-tooth and at its ends; its extreme lies where the link's speed R cos(phi)
    # equals the mean, cos(phi*) = (z / pi) sin(pi / z): 0.100 mm for z = 9, p = 25.4 mm
    cp = dict(p["chain_stage"], z=9, pitch_mm=25.4, phase=np.pi / 9)
    u = np.linspace(0, 25.4, 20001)
    e = mj.chordal_error(cp, u)
    R, phi = 25.4 / (2 * np.sin(np.pi / 9)), np.arccos(9 / np.pi * np.sin(np.pi / 9))
    assert e[[0, 10000, 20000]] == pytest.approx(0.0, abs=1e-9)
    assert np.abs(e).max() == pytest.approx(R * np.sin(phi) - 9 * 25.4 * phi / (2 * np.pi), rel=1e-6)
    assert np.abs(e).max() == pytest.approx(0.100, abs=1e-3)
    # oil growth: under steady production the oil approaches its rise as 1 - (1 - x0) exp(-t / tau)
    gp = dict(p["oil_growth"], x0=0.1, tau_s=1200.0, rise_K=20.0)
    still = SimpleNamespace(gap_s=np.array([0.0, 600.0, 1800.0]), move_s=np.zeros(3), dwell_s=np.zeros(3))
    assert mt.oil_temperature(gp, still) == pytest.approx(20 * (1 - 0.9 * np.exp(-np.array([0, 600, 2400]) / 1200)))

    case, ctx = runs[("kr16_like", "spindle_dither")]
    p, s = case.truth["params"], ctx.session
    # dither: axis 1 (no gravity load in the file's geometry) centred while the spindle runs, trailing its last motion
    # while it stands; both kinds of blocks occur
    dp = p["spindle_dither"]
    on = dp["on"][mj.block_index(s)]
    side = mj.dither_sides(dp, ctx)[0]
    assert on.any() and (~on).any() and dp["joints"][0] == 0
    assert side[on] == pytest.approx(0.0) and side[~on] == pytest.approx(-s.direction[~on, 0])
    # wheel: R / r turns of the wheel per turn of the ring; the scale error grows with the angle
    wp = p["friction_wheel"]
    assert 0.25 / 0.04 <= wp["order"] <= 0.38 / 0.02 and wp["order"] != round(wp["order"])
    dq = mj.wheel_apply(wp, ctx, case.truth["hw"]).dq[:, 0]
    assert dq == pytest.approx(wp["scale"] * ctx.q[:, 0] + wp["ecc_rad"] * np.sin(wp["order"] * ctx.q[:, 0]
                                                                                + wp["phase"]))
    # tie-rod bar: a uniform load W on a cantilever of length L deflects its end by W L^3 / 8 EI
    assert mb.bar_draw(ctx, case.truth["hw"], np.random.default_rng(0))["c_mm_per_N"][1] == pytest.approx(
        1000 * (p["tie_rod_bar"]["L_mm"] / 1000) ** 3 / (8 * np.random.default_rng(0).uniform(6e3, 1.5e4)))

    case, ctx = runs[("ur10", "cart_dock")]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # dock: the first docking is the reference; within a later one the robot moves rigidly (its pin's yaw and shift)
    kp = p["cart_dock"]
    disp = mb.dock_apply(kp, ctx, hw).displace
    b = mj.block_index(s)
    assert kp["blocks"] >= 5 and np.abs(disp[b == 0]).max() == 0.0
    k = 1
    dx, dy, yaw = kp["amp"][k]
    want = np.array([dx, dy, 0.0]) + yaw * np.cross([0, 0, 1.0], ctx.target - kp["pin_mm"])
    assert disp[b == k] == pytest.approx(want[b == k])
    # carriage: the carriage stays on its rollers while the moment about the rail is inside the friction band
    cp = dict(p["carriage_play"], band_Nm=10.0, start=1.0, rail=np.array([1.0, 0, 0]))
    M = np.array([[0, 0, 0], [-5.0, 0, 0], [-20.0, 0, 0], [5.0, 0, 0], [30.0, 0, 0]]) @ np.diag([1, 1, 1])
    stub = SimpleNamespace(mass_state=(np.ones((5, 1)), np.zeros((5, 1, 3)), np.array([1])))
    eb_moment = mb.eb.mount_moment
    try:
        mb.eb.mount_moment = lambda _: M
        assert mb.carriage_side(cp, stub) == pytest.approx([1, 1, -1, -1, 1])
    finally:
        mb.eb.mount_moment = eb_moment
    # the play operator: follows the input at most r behind, stays while it turns back inside the band
    assert mb.play_operator(np.array([0.0, 5.0, 2.0, -4.0, 0.0]), 2.0) == pytest.approx([0, 3, 3, -2, -2])
    # plume: a horizontal ray through the axis of a Gaussian column of excess temperature 1 K, far above its source,
    # is not bent and gains the optical path -kappa w sqrt(pi); one passing w / sqrt(2) off the axis is bent, at the
    # target, by (D - s_c) kappa sqrt(2 pi) exp(-1/2) towards the cooler side
    pp = {"w_mm": 200.0, "along": 0.5, "off": 0.0, "z_src_mm": -1e6, "work_mm": np.array([4000.0, 0.0])}
    hw_stub = {"tracker": {"R": np.eye(3), "t": np.zeros(3)}}
    ray = SimpleNamespace(target=np.array([[4000.0, 0.0, 0.0], [4000.0, 200 / np.sqrt(2) * 2, 0.0]]))
    out = mt.plume_part(pp, ray, hw_stub, n=20000)
    assert out[0] == pytest.approx([-mt.KAPPA * 200 * np.sqrt(np.pi), 0, 0], rel=1e-6, abs=1e-12)
    bend = 2000 * mt.KAPPA * np.sqrt(2 * np.pi) * np.exp(-0.5)
    assert np.linalg.norm(out[1]) == pytest.approx(bend, rel=0.02)

    case, ctx = runs[("ur10", "jaw_play")]
    p = case.truth["params"]["jaw_play"]
    # jaw: opened by the grip whenever a part is held
    held = ctx.session.payload_kg > 0
    assert held.any() and (~held).any() and mb.jaw_sides(p, ctx)[0][held] == pytest.approx(1.0)


def test_set_n_cases_kinds_and_determinism():
    """Set N: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-N
    kind alone (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a lattice
    boom's target sits on its tip's lower node and its part at the tip, a ring frame's target on the ring and its part
    on the tool axis below the grip; a panel case carries one load, a pick-and-place case both none and some, and the
    heated, pumped and re-referenced cases have their blocks."""
    from sim2real_indep import effects_n as en
    from sim2real_indep import effects_n_body as nb
    from sim2real_indep import effects_n_joint as nj

    _assert_set_module("N", 40_7014, en, ("gear", "oil_growth"))
    for name in ("effects_n", "effects_n_joint", "effects_n_body", "effects_n_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_n" in _imports(STUDY / "generator.py")
    assert en.AFTER_TRACKER == {"tripod_tilt"}
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert en.probe_hook(("sag", "jaw_play"), probe, "ur10") is probe and en.payload_hook(("sag",), com, probe) is com
    tip = en.probe_hook(("truss_slack",), probe, "kr16_like")
    assert tip == pytest.approx([0.6 * (500 + 300 * 8 / 95), -0.8 * (500 + 300 * 8 / 95), nj.CHORD_Z_MM])
    assert en.payload_hook(("truss_slack",), com, tip) == pytest.approx(tip)
    ring = en.probe_hook(("ring_frame",), probe, "ur10")
    assert ring == pytest.approx([0.6 * (120 + 80 * 8 / 95), -0.8 * (120 + 80 * 8 / 95), nb.HUB_Z_MM])
    part = en.payload_hook(("ring_frame",), com, ring)
    assert part == pytest.approx([0, 0, nb.HUB_Z_MM + nb.FINGER_MM + 30 + 70 * np.linalg.norm(com) / 80])
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": en.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 2, "gap_kind": "none"})
        steps = opts(("ring_frame",))["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
        panel = opts(("wind_panel", "harness_lash"), "ur10")["payload_steps"]
        assert len(panel) == 1 and 5.0 <= panel[0] <= 9.0
        heat = opts(("tripod_tilt",))
        assert heat["blocks"] >= 5 and heat["gap_kind"] == "pause"
        assert opts(("mag_drift", "pad_heat"))["gap_kind"] == "mixed"
        assert opts(("rope_creep",), "tool_changer")["pause_min"] == (2.0, 10.0)
    _assert_regenerates("N", max_effect_poses=50)


def test_set_n_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-N kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds of other arms do nothing; and known answers: the
    cross-flow force on a panel, a jet's momentum flux against the water-jetting rule, the harness's flank, the
    counterbalance's law of cosines and the net torque's flank, the rope's creep per travel and its reset, Bekker's
    sinkage of a centred carrier and the soil's stiff reloading, Fancher's leaf-spring branches, the lattice's axial load
    path and its Williot slack, the frame element's cantilever, the part stiffening the ring, the tripod head's motion
    under its legs' growths, the pads' rise and tilt and the encoders' drift growing with the temperature."""
    from types import SimpleNamespace

    from sim2real_indep import effects_k_thermal as kt
    from sim2real_indep import effects_n_body as nb
    from sim2real_indep.context import Ctx
    from sim2real_indep import effects_n_joint as nj
    from sim2real_indep import effects_n_thermal as nt
    from sim2real_indep import hardware as hwm

    inert = {"ur10": ("jet_reaction", "balanced_lash", "rope_creep"),
             "tool_changer": ("wind_panel", "crawler_sink", "leaf_springs", "ring_frame", "pad_heat", "mag_drift"),
             "kr16_like": ("rope_creep",)}
    specs = (("ur10", ("wind_panel", "leaf_springs", "harness_lash", "pad_heat", "mag_drift", "tripod_tilt")),
             ("ur10", ("ring_frame", "crawler_sink")),
             ("kr16_like", ("jet_reaction", "balanced_lash", "truss_slack")),
             ("tool_changer", ("rope_creep", "harness_lash", "balanced_lash")),
             ("ur10", inert["ur10"]), ("tool_changer", inert["tool_changer"]), ("kr16_like", inert["kr16_like"]))
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 14)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault((robot, physics[0]), (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p, hw = case.truth["params"][kind], case.truth["hw"]
            gear = lambda loads: [hwm.torsion(hw["drives"][j], 1.0, False) for j in range(ctx.chain.n)  # noqa: E731
                                  if np.abs(loads[:, j]).max() > 1e-9]
            amp = {"wind_panel": lambda: gear(nj.wind_loads(p, ctx)), "jet_reaction": lambda: gear(nj.jet_loads(p, ctx)),
                   "harness_lash": lambda: [p["b_rad"] / 2], "balanced_lash": lambda: [p["b_rad"] / 2],
                   "rope_creep": lambda: [1 / p["EA_N"]], "truss_slack": lambda: p["c_mm"] / 2,
                   "crawler_sink": lambda: np.ones(3), "leaf_springs": lambda: np.ones(3),
                   "ring_frame": lambda: [1 / p["E"]], "tripod_tilt": lambda: [nt.ALUMINIUM_CTE * p["dT_K"]] * 3,
                   "pad_heat": lambda: [p["alpha"] * p["t_mm"] * p["dT_K"]],
                   "mag_drift": lambda: -p["amp"].ravel()}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs[("ur10", "wind_panel")]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # panel: 1/2 rho A C_N90 V^2 along the normal at normal incidence, none edge-on, reversed with the wind
    wp = dict(p["wind_panel"], A_m2=2.0)
    Rt = np.broadcast_to(np.eye(3), (3, 3, 3))
    V = np.array([[0, 0, 10.0], [10.0, 0, 0], [0, 0, -10.0]])
    assert nj.panel_force(dict(wp, V=V), Rt) == pytest.approx(0.5 * 1.2 * 2.0 * 1.17 * 100 * np.array(
        [[0, 0, 1.0], [0, 0, 0], [0, 0, -1.0]]))
    # harness: far beyond its neutral twist the spring wins the drag (the flank of its torque, -10 -+ 1 N m), near it
    # (-1 -+ 1 N m, inside the 3 N m drag) axis 1 trails its last motion
    hp = dict(p["harness_lash"], k_Nm_rad=10.0, f_Nm=1.0, drag_Nm=3.0, q_n=0.0)
    stub = SimpleNamespace(q=np.array([[1.0] + [0] * 5, [0.1] + [0] * 5]),
                           session=SimpleNamespace(direction=np.ones((2, 6))))
    assert nj.harness_side(hp, stub) == pytest.approx([-1.0, -1.0])
    stub.session.direction[:, 0] = -1.0
    assert nj.harness_side(hp, stub) == pytest.approx([-1.0, 1.0])
    # pads: equal growths lift the plate without tilting it; the heater's lag from the switching
    pp = dict(p["pad_heat"], w=np.ones(4), t_on=0.0, t_off=np.inf, tau_s=600.0)
    move = nt.pad_part(pp, ctx)
    assert move == pytest.approx(nt.heater_curve(pp, s.time_s)[:, None] * [0, 0, 1.0])
    assert nt.heater_curve(dict(pp, t_on=100.0, t_off=700.0), [50.0, 700.0, 1300.0]) == pytest.approx(
        [0.0, 1 - np.exp(-1.0), (1 - np.exp(-1.0)) * np.exp(-1.0)])
    # encoders: the error grows with the drive's temperature, dT cos(q - phi) per unit drift
    mp = p["mag_drift"]
    dT = kt.node_rise(ctx, hw, mp["joints"], mp["rise_K"], mp["tau_s"], mp["accel_s"], mp["duty"])
    S = nt.mag_signals(mp, ctx, hw)
    assert S[1, 0] == pytest.approx(dT[:, 1] * np.cos(ctx.q[:, 1] - mp["phase"][1, 0]))
    assert S[2, 1] == pytest.approx(dT[:, 2] * np.cos(2 * ctx.q[:, 2] - mp["phase"][2, 1]))
    # tripod: equal growths of the three legs lift the head without turning it; one leg's growth moves its hinge along
    # the leg by as much and the others' not at all along theirs nor any hinge across its leg's plane
    tp, o = p["tripod_tilt"], np.array([3000.0, 1000.0, 200.0])
    X = nt.head_motion(tp, o)
    assert np.abs(X.sum(axis=0)[3:]).max() < 1e-12 and np.abs(X.sum(axis=0)[:2]).max() < 1e-9
    foot, hinge, L, rad = nt.tripod_legs(tp, o)
    u = (hinge - foot) / L[:, None]
    moved = X[0, :3] + np.cross(X[0, 3:], hinge - o)
    assert np.einsum("ki,ki->k", u, moved) == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
    assert np.einsum("ki,ki->k", np.cross([0, 0, 1.0], rad), moved) == pytest.approx(0.0, abs=1e-12)
    # leaf spring: the branch from a reversal starts at its force and approaches the envelope k d + s F_f
    F, k = nb.fancher(np.array([10.0, 10.5, 60.0]), 10.0, 800.0, 1.0, 100.0, 200.0, 1.0)
    assert F == pytest.approx([800.0, 1250 - 450 * np.exp(-0.5), 6200.0])
    assert k[0] == pytest.approx(100.0 * 0 + 400.0)                  # (env - F_r) / beta at the reversal

    case, ctx = runs[("ur10", "ring_frame")]
    p = case.truth["params"]
    # frame element: a cantilever's tip deflection F L^3 / 3 EI and twist T L / GJ
    A, I, J = nb._tube(30.0, 3.0)
    Kb = nb._beam(np.zeros(3), np.array([400.0, 0, 0]), A, I, J, E=70e3, G=70e3 / 2.66)[6:, 6:]
    u = np.linalg.solve(Kb, [0, 50.0, 100.0, 1e4, 0, 0])
    assert u[[1, 2, 3]] == pytest.approx([50 * 400 ** 3 / (3 * 70e3 * I), 100 * 400 ** 3 / (3 * 70e3 * I),
                                          1e4 * 400 / (70e3 / 2.66 * J)])
    # ring: the held part stiffens the frame against its own weight
    C = p["ring_frame"]["C"]
    assert np.abs(C[1]).max() < np.abs(C[0]).max()
    # crawler: a centred load on virgin soil sinks both tracks evenly by (p / k)^(1 / n); lifted back to a lighter load
    # the soil rebounds along its stiff reloading line
    cp = p["crawler_sink"]
    W = 2 * cp["A_mm2"] * 10 * 0.05                                   # 0.05 N/mm^2 on all 20 soil columns
    x = nb.solve_carrier([1.0, 0, 0], W, np.zeros(2), cp["xy"], nb._soil(cp, np.zeros(20)))
    z = (0.05 / cp["k"]) ** (1 / cp["n"])
    assert x == pytest.approx([z, 0, 0], abs=1e-9)
    x2 = nb.solve_carrier(x, 0.8 * W, np.zeros(2), cp["xy"], nb._soil(cp, np.full(20, z)))
    assert x2[0] == pytest.approx(z - 0.2 * 0.05 / (cp["r_u"] * cp["n"] * 0.05 / z))

    case, ctx = runs[("kr16_like", "jet_reaction")]
    p, hw = case.truth["params"], case.truth["hw"]
    # jet: rho Q v against the water-jetting rule 0.052 Q sqrt(p) lbf (gpm, psi), times C_v
    rule = 0.052 * (10 / 3.78541) * np.sqrt(1000 * 14.5038) * 4.44822
    assert nj.jet_force(1000.0, 10.0) == pytest.approx(nj.C_V * rule, rel=0.02)   # the rule rounded to 0.052
    # counterbalance: the cylinder's length by the law of cosines, its moment arm dL/dpsi; the stored flank is the net
    # torque's (gravity, balancer, seal friction against the last motion)
    bp = p["balanced_lash"]
    q2 = ctx.q[:, 1]
    L, a = nj.balance_geometry(bp, q2)
    Lh, _ = nj.balance_geometry(bp, q2 + 1e-6)
    assert a == pytest.approx((Lh - L) / 1e-6 * bp["s"], rel=1e-4)
    shape, arm = nj.balance_torque(bp, q2)
    t = case.truth
    true = Ctx(t["chain"], t["session"], t["masses"], t["com"], case.nominal.mass_link, t["payload_com_mm"],
               t["probe_mm"])
    tau = true.loads[:, 1] + bp["F0_N"] * shape - bp["Fs_N"] * arm * ctx.session.direction[:, 1]
    assert nj.net_torque(bp, true) == pytest.approx(tau)
    assert bp["side"] == pytest.approx(ph.backlash_offset(ctx.session.direction[:, 1], tau, bp["drag_Nm"], 2.0, 0.0))
    # lattice: a tip load along the boom runs along the lower chord alone; each lower chord's slack moves the tip by as
    # much along the boom
    tr = p["truss_slack"]
    nodes, mem = nj.truss_geometry(tr["L_mm"], tr["h_mm"], tr["N"])
    _, _, unit = nj.truss_unit(tr)
    lower = np.array([nodes[a_][1] == nodes[b_][1] == nj.CHORD_Z_MM for a_, b_ in mem])
    assert unit[0][lower] == pytest.approx(1.0) and np.abs(unit[0][~lower]).max() < 1e-9

    case, ctx = runs[("tool_changer", "rope_creep")]
    rp = case.truth["params"]["rope_creep"]
    # rope: a load F slips the stage by F |du| / EA whichever way it moves; re-referenced at a block's start
    stub = SimpleNamespace(loads=np.full((4, 6), 500.0), q=np.zeros((4, 6)),
                           session=SimpleNamespace(gap_s=np.array([0.0, 0.0, 0.0, -60.0])))
    stub.q[:, rp["joint"]] = [0.0, 100.0, 40.0, 90.0]
    assert nj.creep_signal(rp, stub) == pytest.approx([0.0, 500 * 100, 500 * 160, 0.0])


def test_set_o_cases_kinds_and_determinism():
    """Set O: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-O
    kind alone (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a C-frame's
    target sits on its die and a spindle's on its nose, their weights half way; the purged and the bolting cases have
    their blocks, the floating and guyed cases their loads changed, the tool cases one load."""
    from sim2real_indep import effects_o as eo
    from sim2real_indep import effects_o_body as ob

    _assert_set_module("O", 40_7015, eo, ("gear", "pad_heat"))
    for name in ("effects_o", "effects_o_joint", "effects_o_body", "effects_o_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_o" in _imports(STUDY / "generator.py")
    assert eo.AFTER_TRACKER == set()
    probe, com = np.array([3.0, -4.0, 12.0]), np.array([10.0, 0.0, 5.0])   # |probe| 13 mm
    assert eo.probe_hook(("sag", "jaw_play"), probe, "ur10") is probe
    assert eo.payload_hook(("sag",), com, probe, "ur10") is com
    die = eo.probe_hook(("weld_gun",), probe, "tool_changer")
    assert die == pytest.approx([0.6 * (200 + 200 * 8 / 95), -0.8 * (200 + 200 * 8 / 95), 450.0])
    assert eo.payload_hook(("weld_gun",), com, die, "tool_changer") == pytest.approx(die / 2)
    nose = eo.probe_hook(("milling_force",), probe, "ur10")
    a = 70 + 60 * 8 / 95
    assert nose == pytest.approx([0.6 * (a + 35), -0.8 * (a + 35), 130.0])
    assert eo.payload_hook(("spindle_bracket",), com, nose, "ur10") == pytest.approx([0.6 * a, -0.8 * a, 65.0])
    assert eo.probe_hook(("weld_gun",), probe, "ur10") is probe                  # no C-frame on ur10
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": eo.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        purge = opts(("purge_air",))
        assert 2 <= purge["blocks"] <= 3 and purge["gap_kind"] == "pause" and purge["pause_min"] == (15.0, 40.0)
        bolt = opts(("bolt_torque",), "tool_changer")
        assert 4 <= bolt["blocks"] <= 7 and bolt["pause_min"] == (2.0, 6.0)
        steps = opts(("pontoon",), "ur10")["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
        gun = opts(("weld_gun", "mesh_te"), "tool_changer")["payload_steps"]
        assert len(gun) == 1 and 48.0 <= gun[0] <= 72.0
        assert len(opts(("milling_force",))["payload_steps"]) == 1
    assert ob.CFRAME["tool_changer"][1] == 450.0
    _assert_regenerates("O", max_effect_poses=50)


def test_set_o_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-O kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds of other arms do nothing; and known answers: the
    mean forces and torque of a slot cut, the nutrunner's reaction along the tool axis, the cut flank's rule, the
    encoder hysteresis' overshoot, the quantised stop at a count's edge, the mesh error's period, the pontoon's
    waterplane compliances, the guys' catenary law and a balanced mast, the C-frame's squeeze along the punch axis, the
    bar's end against the cantilever formulas, the purge's exact lag and the infrared panel's inverse square."""
    from types import SimpleNamespace

    from sim2real_indep import effects_o_body as ob
    from sim2real_indep import effects_o_joint as oj
    from sim2real_indep import effects_o_thermal as ot
    from sim2real_indep import hardware as hwm
    from sim2real_indep.context import Ctx

    inert = {"ur10": ("bolt_torque", "mesh_te", "weld_gun", "purge_air"),
             "tool_changer": ("milling_force", "cut_flank", "spindle_bracket", "pontoon", "guyed_mast"),
             "kr16_like": ()}
    specs = (("ur10", ("milling_force", "cut_flank", "spindle_bracket", "enc_hysteresis", "lsb_stop", "ir_dryer")),
             ("ur10", ("pontoon", "guyed_mast")),
             ("kr16_like", ("bolt_torque", "mesh_te", "purge_air", "weld_gun", "lsb_stop")),
             ("tool_changer", ("bolt_torque", "weld_gun", "mesh_te", "lsb_stop", "enc_hysteresis", "purge_air")),
             ("ur10", inert["ur10"]), ("tool_changer", inert["tool_changer"]))
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 15)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault((robot, physics[0]), (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p, hw = case.truth["params"][kind], case.truth["hw"]
            gear = lambda loads: [hwm.torsion(hw["drives"][j], 1.0, False) for j in range(ctx.chain.n)  # noqa: E731
                                  if np.abs(loads[:, j]).max() > 1e-9]
            amp = {"milling_force": lambda: gear(oj.cut_joint_loads(p, ctx)),
                   "bolt_torque": lambda: gear(oj.moment_loads(ctx, oj.bolt_moment(p, ctx))),
                   "cut_flank": lambda: p["b_rad"] / 2, "enc_hysteresis": lambda: p["h_rad"] / 2,
                   "lsb_stop": lambda: p["delta_rad"], "mesh_te": lambda: p["A_mm"] / p["r_mm"],
                   "pontoon": lambda: ob.pontoon_compliance(p), "guyed_mast": lambda: np.ones(2),
                   "weld_gun": lambda: [p["c_mm_N"]], "spindle_bracket": lambda: [1 / p["E"]],
                   "purge_air": lambda: [hw["material"]["cte"] * p["dT_K"]],
                   "ir_dryer": lambda: ot.ir_amplitudes(p, hw)}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    # cut: a slot (0 to pi) without edge or axial coefficients -- mean feed force -N a_p f_z K_rc / 4, normal force
    # N a_p f_z K_tc / 4, torque D N K_tc a_p f_z / (2000 pi) [N m]
    c = {"N": 3, "D_mm": 10.0, "ap_mm": 2.0, "fz_mm": 0.1, "Ktc": 800.0, "Krc": 300.0, "Kac": 0.0, "Kte": 0.0,
         "Kre": 0.0, "mode": "slot"}
    F, T = oj.mean_cut(c)
    assert F == pytest.approx([-3 * 2 * 0.1 * 300 / 4, 3 * 2 * 0.1 * 800 / 4, 0.0], rel=1e-4, abs=1e-9)
    assert T == pytest.approx(10 * 3 * 800 * 2 * 0.1 / (2000 * np.pi), rel=1e-4)
    # lsb: from below the axis stops at the target count's lower edge, from above at its upper edge
    lp = {"joints": [0], "delta_rad": np.array([0.01]), "phi0": np.array([0.0])}
    stub = SimpleNamespace(q=np.array([[0.0537], [0.0537]]),
                           session=SimpleNamespace(direction=np.array([[1.0], [-1.0]])))
    assert 0.01 * oj.lsb_signals(lp, stub)[0] == pytest.approx([0.05 - 0.0537, 0.06 - 0.0537])
    # flank: a torque beyond the drag chooses its flank, inside it the axis trails its last motion
    assert ph.backlash_offset(np.array([1.0, 1.0]), np.array([5.0, 0.5]), 1.0, 2.0, 0.0) == pytest.approx([1.0, -1.0])

    case, ctx = runs[("ur10", "milling_force")]
    p, hw = case.truth["params"], case.truth["hw"]
    t = case.truth
    true = Ctx(t["chain"], t["session"], t["masses"], t["com"], case.nominal.mass_link, t["payload_com_mm"],
               t["probe_mm"])
    fp = p["cut_flank"]
    tau = oj.cut_joint_loads(fp["cut"], true) + true.loads
    for k, j in enumerate(oj.LASH_JOINTS):
        assert fp["side"][k] == pytest.approx(ph.backlash_offset(ctx.session.direction[:, j], tau[:, j],
                                                                 fp["drag_Nm"][k], 2.0, 0.0))
    assert p["cut_flank"]["cut"]["psi"] is p["milling_force"]["psi"] is hw["cut"]["psi"]   # one cut shared
    # encoder hysteresis: the joint overshoots by h / 2 in the direction of its last motion
    hp = p["enc_hysteresis"]
    dq = oj.hyst_apply(hp, ctx, hw).dq
    assert dq[:, :3] == pytest.approx(hp["h_rad"] / 2 * ctx.session.direction[:, :3]) and not dq[:, 3:].any()
    # bar: a square bar's end against Timoshenko's cantilever under an end force and moment (no stretch)
    d = np.array([0.6, 0.8, 0.0])
    Fb = np.array([[0.0, 0.0, 30.0], [-40.0, 30.0, 0.0]])
    Mb = np.array([[100.0, -200.0, 300.0], [0.0, 0.0, 500.0]])
    delta, rot = ob.bar_end_motion(100.0, 10.0, 10.0, 0.3, d, Fb, Mb)
    EI, GJ = 1e4 / 12 * 1e-6, 1e4 / 3 * (1 - 0.63) / 2.6 * 1e-6              # E = 1 [N/mm^2], in N m^2
    ref_d, ref_r = ph.cantilever_tip(d, 0.1, Fb, Mb * 1e-3, np.zeros(3), EI, np.inf, GJ)
    assert delta == pytest.approx(ref_d * 1e3, rel=1e-9) and rot == pytest.approx(ref_r, rel=1e-9)
    # infrared: a link's midpoint at the panel is clipped to 0.3 m, (0.5 / 0.3)^2; a far panel sends nothing
    ip = dict(p["ir_dryer"], k_on=0)
    R, tt = kin.body_transforms(ctx.chain, ctx.q)
    li = ip["links"][0]
    mid = R[0, ctx.chain.link_body[li]] @ (np.cumsum(ctx.chain.links, axis=0)[li] - ctx.chain.links[li] / 2) \
        + tt[0, ctx.chain.link_body[li]]
    assert ot.ir_inputs(dict(ip, lamp_mm=mid), ctx)[0, 0] == pytest.approx((500 / 300) ** 2)
    assert ot.ir_inputs(dict(ip, lamp_mm=np.array([0, 0, 1e7])), ctx).max() < 1e-8
    assert ot.ir_amplitudes(dict(ip, a_s=0.5, E0_W_m2=8000.0, h=10.0, f=np.ones(1)), hw) == pytest.approx(
        hw["material"]["cte"] * 0.5 * 8000 / (np.pi * 10))

    case, ctx = runs[("ur10", "pontoon")]
    p = case.truth["params"]
    # pontoon: heave 1 / (rho g L B), heel and trim 12 / (rho g L B^3) and 12 / (rho g B L^3); a 10 x 5 m hull sinks
    # 2.04 um per newton
    assert ob.pontoon_compliance({"L_mm": 1e4, "B_mm": 5e3}) == pytest.approx(
        [1 / (1000 * 9.80665e-9 * 5e7), 12 / (1000 * 9.80665e-9 * 1e4 * 1.25e11),
         12 / (1000 * 9.80665e-9 * 5e3 * 1e12)])
    assert 1e3 * ob.pontoon_compliance({"L_mm": 1e4, "B_mm": 5e3})[0] == pytest.approx(2.04, abs=0.005)
    # guys: the tension inverts the elastic catenary's chord law and stays positive as a guy slackens; three equal
    # guys hold a mast plumb under a weight on its axis
    mp = p["guyed_mast"]
    dl = np.array([-2.0, 0.0, 0.3])
    T = ob.guy_tension(mp, dl)
    law = (T - mp["T0"]) * mp["l0"] / mp["EA"] + mp["c"] * (1 / mp["T0"] ** 2 - 1 / T ** 2)
    assert law == pytest.approx(dl, abs=1e-9) and T[1] == pytest.approx(mp["T0"]) and (T > 0).all()
    assert ob.mast_residual(mp, np.zeros(2), np.array([50.0]), np.array([[0.0, 0.0, 200.0]])) == pytest.approx(
        [0.0, 0.0], abs=1e-6)

    case, ctx = runs[("kr16_like", "bolt_torque")]
    p, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # nutrunner: +T along the tool axis while fitting, -k T while removing; each revolute joint carries its axis' share
    bp = p["bolt_torque"]
    M = oj.bolt_moment(bp, ctx)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    sense = bp["sense"][oj.block_index(s)]
    assert np.einsum("pi,pi->p", M, Rt[:, :, 2]) == pytest.approx(np.where(sense > 0, 1, bp["k_loose"]) * sense
                                                                  * bp["T_Nm"])
    assert (sense > 0).any() and (sense < 0).any()
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    assert oj.moment_loads(ctx, M) == pytest.approx(np.einsum("pji,pi->pj", w, M))
    # mesh: the error repeats once per tooth
    mt = p["mesh_te"]
    shifted = SimpleNamespace(q=ctx.q + np.r_[2 * np.pi / mt["Z"], np.zeros(5)])
    assert oj.mesh_signals(mt, shifted) == pytest.approx(oj.mesh_signals(mt, ctx), abs=1e-9)
    # C-frame: the die moves along the punch (tool) axis by c F
    cp = p["weld_gun"]
    assert ob.cframe_apply(cp, ctx, hw).displace == pytest.approx(cp["c_mm_N"] * cp["F_N"][:, None] * Rt[:, :, 2])
    assert set(cp["F_N"]) <= set(cp["levels"])
    # purge: in the first block the deficit starts at 1 - exp(-t_pp / tau) and decays to r_low with tau
    pp = p["purge_air"]
    x = ot.purge_signal(pp, ctx)
    pre, run = ot.purge_windows(pp, s)
    first = s.time_s <= run[0][1]
    x0 = 1 - np.exp(-pp["t_pp_s"] / pp["tau_s"])
    ref = pp["r_low"] + (x0 - pp["r_low"]) * np.exp(-(s.time_s[first] - run[0][0]) / pp["tau_s"])
    assert x[first] == pytest.approx(ref, rel=1e-9)
    assert len(pre) >= 2 and pre[1][1] - pre[1][0] == pytest.approx(pp["t_pp_s"])


def test_set_p_cases_kinds_and_determinism():
    """Set P: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session and probe hooks leave cases without a set-P kind alone
    (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a lance's target sits
    at its nozzle, a vacuum plate's on its face, a changed tool's out on the tool; the tool-changing and charging cases
    have their blocks, the tool cases a tool of its own weight in each, the pick-and-place cases an empty block."""
    from sim2real_indep import effects_p as ep

    _assert_set_module("P", 40_7016, ep, ("gear", "pad_heat"))
    for name in ("effects_p", "effects_p_joint", "effects_p_body", "effects_p_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_p" in _imports(STUDY / "generator.py")
    assert ep.AFTER_TRACKER == set()
    probe = np.array([3.0, -4.0, 12.0])                                     # |probe| 13 mm
    assert ep.probe_hook(("sag", "ir_dryer"), probe, "ur10") is probe
    share = 8 / 95
    assert ep.probe_hook(("hose_lance",), probe, "ur10") == pytest.approx([0, 0, 250 + 150 * share])
    assert ep.probe_hook(("hose_lance",), probe, "tool_changer") is probe       # no lance on tool_changer
    assert ep.probe_hook(("vacuum_plate",), probe, "tool_changer") == pytest.approx(
        [3 / 13 * 50, -4 / 13 * 50, 60 + 60 * share])
    assert ep.probe_hook(("quick_change",), probe, "kr16_like") == pytest.approx(probe / 13 * (120 + 130 * share))
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ep.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        qc = opts(("quick_change",), "tool_changer")
        assert 4 <= qc["blocks"] <= 7 and qc["pause_min"] == (1.0, 3.0) and len(qc["payload_steps"]) == qc["blocks"]
        assert min(qc["payload_steps"]) >= 8.0 and max(qc["payload_steps"]) <= 48.0
        ch = opts(("charging_heat",))
        assert 3 <= ch["blocks"] <= 5 and ch["gap_kind"] == "pause" and ch["pause_min"] == (10.0, 25.0)
        steps = opts(("vacuum_plate",), "ur10")["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
    _assert_regenerates("P", max_effect_poses=50)


def test_set_p_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-P kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds of other arms do nothing; and known answers: the
    magnetic coupling's sine law, the belt's stiffness halving past the slack torque, the seals' relaxation, the tool's
    landing in its pins' clearance, the pole-pitch walk's period and peak, a dipole's field on its axis, the vacuum
    feet's statics, the platen's rotation, the plate's bow, the lance's end load, the jacket's sawtooth and the deck's
    charging lag."""
    from types import SimpleNamespace

    from sim2real_indep import effects_p_body as pb
    from sim2real_indep import effects_p_joint as pj
    from sim2real_indep import effects_p_thermal as pt

    inert = {"ur10": ("belt_slack",),
             "tool_changer": ("mag_coupling", "vacuum_feet", "platen_clamp", "hose_lance", "jacket_cycle",
                              "charging_heat"), "kr16_like": ()}
    specs = (("ur10", ("mag_coupling", "seal_relax", "stray_field", "pole_pitch", "platen_clamp", "jacket_cycle")),
             ("ur10", ("vacuum_feet", "charging_heat", "hose_lance")),
             ("kr16_like", ("belt_slack", "quick_change", "vacuum_plate", "stray_field")),
             ("tool_changer", ("belt_slack", "stray_field", "pole_pitch", "seal_relax", "vacuum_plate")),
             ("ur10", inert["ur10"]), ("tool_changer", inert["tool_changer"]))
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 16)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault((robot, physics[0]), (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"mag_coupling": lambda: 1 / (p["p"] * p["N"]), "belt_slack": lambda: [p["c_rad_Nm"]],
                   "seal_relax": lambda: pj.seal_amplitudes(p), "quick_change": lambda: [p["c_mm"]],
                   "pole_pitch": lambda: p["peak_rad"],
                   "stray_field": lambda: -np.concatenate([pj.stray_coeffs(s) for s in p]),
                   "vacuum_feet": lambda: [p["delta_r"]], "platen_clamp": lambda: [p["theta_rad"]],
                   "vacuum_plate": lambda: [p["w0_mm"]], "hose_lance": lambda: [p["k_N_mm"] / p["EI"]],
                   "jacket_cycle": lambda: [pt.ALU_CTE], "charging_heat": lambda: [p["tilt_rad"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs[("ur10", "mag_coupling")]
    P = case.truth["params"]
    # coupling: a load N T_max sin(x) slips the coupling by x / p, the output by x / (p N)
    mp = P["mag_coupling"]
    x = np.array([0.1, -0.4, 0.9])
    stub = SimpleNamespace(loads=np.zeros((3, 6)))
    stub.loads[:, mp["joints"][0]] = mp["N"][0] * mp["T_max"][0] * np.sin(x)
    assert pj.coupling_signals(mp, stub)[0] == pytest.approx(x)
    # seals: the whole wind-up right at the stop, rho of it long after, against the last motion
    sp = P["seal_relax"]
    s0 = SimpleNamespace(session=SimpleNamespace(dwell_s=np.array([0.0, 1e6]), direction=np.ones((2, 6))))
    sig = pj.seal_signals(sp, s0)
    assert sig[:, 0] == pytest.approx(-np.ones(len(sp["joints"]))) and sig[:, 1] == pytest.approx(-sp["rho"])
    # stray field: on a dipole's axis the field is mu0 m / (2 pi r^3) along it
    assert pj.dipole_field(np.array([0.0, 0.0, 0.2]), np.array([0.0, 0.0, 0.1])) == pytest.approx(
        [0, 0, 2e-7 * 0.2 / 1e-3])
    st = P["stray_field"][0]
    q = 0.7
    m = st["m"] * (np.cos(q + st["phi"]) * st["u"] + np.sin(q + st["phi"]) * st["v"])
    c1, c2 = pj.stray_coeffs(st)
    assert c1 * np.cos(q) + c2 * np.sin(q) == pytest.approx(pj.dipole_field(m, st["r_m"]) @ st["t0"] / st["B0"])
    # pole pitch: the walk closes around the ring and its largest error is the drawn peak
    pp = P["pole_pitch"]
    grid = np.linspace(-np.pi, np.pi, 4001)
    ring = SimpleNamespace(q=np.tile(grid[:, None], (1, 6)))
    shapes = pj.pole_shapes(pp, ring)
    assert shapes[:, 0] == pytest.approx(shapes[:, -1]) and np.abs(shapes).max(axis=1) == pytest.approx(1, abs=2e-3)
    # platen: nothing while the mould is open, a turn about the platen's axis through its pivot while clamped
    lp = P["platen_clamp"]
    sh = pb.platen_shape(lp, ctx)
    assert not sh[lp["state"] == 0].any()
    arm = ctx.target + lp["h_mm"] * pb.Z
    assert np.abs(np.einsum("pi,pi->p", sh, arm)).max() < 1e-9 and np.abs(sh @ lp["axis"]).max() < 1e-9
    # jacket: the band's edges at the switching moments; a lagged constant stays constant
    jp = dict(P["jacket_cycle"], phase=0.0)
    assert pt.jacket_air(jp, [0.0, jp["t_on_s"], jp["t_on_s"] + jp["t_off_s"]]) == pytest.approx(
        [jp["A_K"], -jp["A_K"], jp["A_K"]])

    case, ctx = runs[("ur10", "vacuum_feet")]
    P = case.truth["params"]
    # vacuum feet: the pads carry the vacuum's preload and the weights, their moments balance, the least keeps 10-30 %
    vp = P["vacuum_feet"]
    C = pb.vac_forces(vp, ctx)
    m, pos, _ = ctx.mass_state
    assert C.sum(axis=1) == pytest.approx(3 * vp["F_v"] + kin.G * m.sum(axis=1))
    assert 0.1 * vp["F_v"] * 0.99 < C.min() < 0.3 * vp["F_v"] * 1.01
    flat = dict(vp, n=1.0)
    stub = SimpleNamespace(mass_state=(np.zeros_like(m), pos, None), target=ctx.target)
    heave = pb.vac_shape(flat, stub)                                      # equal pads: a pure sink by delta_r
    assert heave == pytest.approx(np.tile([0.0, 0.0, -1.0], (len(heave), 1)))
    # lance: the nozzle moves across the lance by the hose's pull times L^3 / 3 (times k / E I)
    lp = P["hose_lance"]
    _, Rt = kin.flange(ctx.chain, ctx.q)
    part = pb.lance_part(lp, ctx)
    assert np.abs(np.einsum("pi,pi->p", part, Rt[:, :, 2])).max() < 1e-6 * np.abs(part).max()
    # charging: a long pause charges the deck fully, a long block leaves the working share
    cp = P["charging_heat"]
    ses = SimpleNamespace(gap_s=np.array([0.0, -1e7, 0.0]), move_s=np.array([0.0, 0.0, 1e7]),
                          dwell_s=np.zeros(3), time_s=np.zeros(3))
    assert pt.charge_signal(cp, SimpleNamespace(session=ses))[1:] == pytest.approx([1.0, cp["r_work"]])

    case, ctx = runs[("kr16_like", "belt_slack")]
    P = case.truth["params"]
    # belt: both spans share below 2 T0 r; past it the twist grows twice as fast (the slack span gone)
    bp = P["belt_slack"]
    ts = bp["tau_s"]
    assert pj.belt_signal(bp, np.array([0.5 * ts, -0.5 * ts, 2 * ts, -3 * ts])) == pytest.approx(
        [0.5 * ts, -0.5 * ts, 3 * ts, -5 * ts])
    assert bp["c_rad_Nm"] == pytest.approx(bp["L_mm"] * 1e-3 / (2 * bp["EA_N"] * (bp["r_mm"] * 1e-3) ** 2))
    # quick change: equal landings translate the plate; opposite ones across the pins' line turn it about the tool axis
    qp = dict(P["quick_change"], pin_az=0.0, R_pin_mm=30.0)
    qp["a"], qp["b"] = np.array([[0.5, 0.2], [0.0, 1.0]]), np.array([[0.5, 0.2], [0.0, -1.0]])
    loc = pb.qc_local(qp, np.array([100.0, 0.0, 50.0]), np.array([0, 1]))
    assert loc == pytest.approx(np.array([[0.5, 0.2, 0.0], [0.0, 100 / 30, 0.0]]))
    # vacuum plate: a clamped plate's centre bows p a^4 / (64 D); only the held poses
    wp = P["vacuum_plate"]
    D = 70e3 * wp["t_mm"] ** 3 / (12 * (1 - 0.33 ** 2))
    assert wp["w0_mm"] == pytest.approx(wp["dp"] * wp["a_mm"] ** 4 / (64 * D))
    held = ctx.session.payload_kg > 0
    assert not pb.vplate_part(wp, ctx)[~held].any() and held.any()


def test_set_q_cases_kinds_and_determinism():
    """Set Q: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session and probe hooks leave cases without a set-Q kind alone
    (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a gripper boom's target
    sits at its tip, a gooseneck's at its nozzle, a holder's out on the holder; the door's cases have their blocks and
    pauses, the ejector's an empty block among held ones."""
    from sim2real_indep import effects_q as eq

    _assert_set_module("Q", 40_7017, eq, ("gear", "charging_heat"))
    for name in ("effects_q", "effects_q_joint", "effects_q_body", "effects_q_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_q" in _imports(STUDY / "generator.py")
    assert eq.AFTER_TRACKER == set()
    probe = np.array([3.0, -4.0, 12.0])                                     # |probe| 13 mm
    share = 8 / 95
    assert eq.probe_hook(("sag", "lash_comp"), probe) is probe
    assert eq.probe_hook(("ejector_chill",), probe) == pytest.approx([0, 0, 400 + 300 * share])
    R = 60 + 60 * share
    assert eq.probe_hook(("gooseneck",), probe) == pytest.approx([3 / 5 * R, -4 / 5 * R, 40 + R])
    assert eq.probe_hook(("ball_holder",), probe) == pytest.approx(probe / 13 * (150 + 100 * share))
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": eq.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        door = opts(("door_draught",))
        assert 4 <= door["blocks"] <= 7 and door["gap_kind"] == "pause" and door["pause_min"] == (5.0, 15.0)
        steps = opts(("ejector_chill",), "ur10")["payload_steps"]
        assert min(steps) == 0.0 and max(steps) > 0.0
    _assert_regenerates("Q", max_effect_poses=50)


def test_set_q_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-Q kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the draw wire does nothing on the arms without a telescopic
    stage; and known answers: the sensors' stops, the tank's free surface, the compensated lash's flanks, the servo
    tail's decay, the ball-pass rate, the draw wire's stretch and eccentricity, Almen-Laszlo's curve and the feet's
    statics, Hertz's constant and the coupling's statics, the holder's joints, the gooseneck's uncurling (against a
    difference quotient of the arc), the boom's shrink and bow, and the door's lags."""
    from types import SimpleNamespace

    from sim2real_indep import effects_q_body as qb
    from sim2real_indep import effects_q_joint as qj
    from sim2real_indep import effects_q_thermal as qt

    specs = (("ur10", ("sensor_stops", "fluid_tank", "lash_comp", "servo_tail", "ball_pass", "disc_springs",
                       "door_draught", "draw_wire")),
             ("tool_changer", ("draw_wire", "ball_holder", "kinematic_mount", "lash_comp")),
             ("kr16_like", ("ejector_chill", "fluid_tank", "draw_wire")), ("ur10", ("gooseneck",)))
    inert = {"ur10": ("draw_wire",), "kr16_like": ("draw_wire",), "tool_changer": ()}
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 17)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs.setdefault((robot, physics[0]), (case, ctx))
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"sensor_stops": lambda: 1 / p["k"], "fluid_tank": lambda: [p["mass_kg"]],
                   "lash_comp": lambda: qj.comp_amplitudes(p), "servo_tail": lambda: p["A_s"],
                   "ball_pass": lambda: qj.pass_amplitudes(p), "draw_wire": lambda: [-1.0, -1.0, -1.0],
                   "disc_springs": lambda: [p["stroke_mm"]], "kinematic_mount": lambda: [p["c_H"]],
                   "ball_holder": lambda: 1 / p["k_Nmm"], "gooseneck": lambda: [p["eps"]],
                   "ejector_chill": lambda: [p["dT_K"]], "door_draught": lambda: [p["dT_K"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs[("ur10", "sensor_stops")]
    P = case.truth["params"]
    # torque sensors: the flexure twists with the torque up to its stop, then no further
    sp = P["sensor_stops"]
    stub = SimpleNamespace(loads=np.zeros((3, 6)))
    T = sp["T_stop"][0]
    stub.loads[:, sp["joints"][0]] = [0.5 * T, -2 * T, 3 * T]
    assert qj.sensor_signals(sp, stub)[0] == pytest.approx([0.5 * T, -T, T])
    # tank: full, it is a point mass at its centre; half full, its liquid lies below the level through the centre
    tp = P["fluid_tank"]
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    assert qj.tank_com(dict(tp, fill=1.0), ctx) == pytest.approx(fl + Rt @ tp["centre_mm"])
    com = qj.tank_com(dict(tp, fill=0.5), ctx)
    assert np.all(com[:, 2] < (fl + Rt @ tp["centre_mm"])[:, 2])
    # compensated lash: a load holds its flank (+b/2 sign tau), unloaded the output trails; the compensation leads
    lp = P["lash_comp"]
    j0 = lp["joints"][1]
    stub = SimpleNamespace(loads=np.zeros((2, 6)), session=SimpleNamespace(direction=np.ones((2, 6))))
    stub.loads[:, j0] = [-10 * lp["hold"][1], 0.0]
    sig = qj.comp_signals(lp, stub)
    m = len(lp["joints"])
    assert sig[1] == pytest.approx([-1.0, -1.0]) and sig[m + 1] == pytest.approx([1.0, 1.0])
    # servo tail: the overshoot per speed in the motion direction, right after the stop; 1 / e of it after T_i
    tp = P["servo_tail"]
    ses = SimpleNamespace(direction=-np.ones((2, 6)), speed=np.full((2, 6), 0.5),
                          dwell_s=np.array([0.0, tp["T_i"][0]]))
    assert qj.tail_signals(tp, SimpleNamespace(session=ses))[0] == pytest.approx([-0.5, -0.5 / np.e])
    # ball pass: 2 (1 - f_c) N periods per output turn, f_c = (1 - d / D cos alpha) / 2
    bp = P["ball_pass"]
    assert np.all((bp["f_c"] > 0.37) & (bp["f_c"] < 0.43))
    assert bp["order"] == pytest.approx(2 * (1 - bp["f_c"]) * bp["N"])
    q = np.zeros((2, 6))
    q[1, bp["joints"][0]] = 2 * np.pi / bp["order"][0]
    s = qj.pass_signals(bp, SimpleNamespace(q=q))
    assert s[:, 0] == pytest.approx(s[:, 1])
    # disc springs: Almen-Laszlo's curve at the flat position is r; its inverse; the feet carry preload and weights
    dp = P["disc_springs"]
    x = np.linspace(0.1, 0.9, 5)
    assert qb.disc_curve(1.0, dp["r"]) == pytest.approx(dp["r"])
    assert qb.disc_x(dp, qb.disc_curve(x, dp["r"]) * dp["F_unit"]) == pytest.approx(x, abs=1e-6)
    F = qb.disc_reactions(dp, ctx)
    mm, _, _ = ctx.mass_state
    assert F.sum(axis=1) == pytest.approx(3 * dp["F_pre"] + kin.G * mm.sum(axis=1))
    xs = qb.disc_x(dp, F)
    assert xs.min() > 0.15 - 0.01 and xs.max() <= 1.0      # (the nominal geometry here; a flat stack is solid)
    # door: a door open for ever chills the links by the full fall (after both lags), a shut one not at all
    door = P["door_draught"]
    far = SimpleNamespace(session=SimpleNamespace(time_s=np.array([5e5, 6e5])))
    chill = qt.door_signal(dict(door, open=np.array([[-1e9, 1e9]])), far)
    assert -1 < chill[0] < 0 and chill[1] == pytest.approx(-1, abs=1e-6)
    assert qt.door_signal(dict(door, open=np.array([[-1e9, -1e8]])), far) == pytest.approx([0, 0], abs=1e-9)
    # draw wire: stretch (F0 + k_s x)(x + L0) / EA less its value at x = 0; the drum's error repeats every 2 pi r
    case, ctx = runs[("tool_changer", "draw_wire")]
    P = case.truth["params"]
    wp = P["draw_wire"]
    x = np.array([0.0, 100.0, 2 * np.pi * wp["r_mm"]])
    t = qj.wire_terms(wp, x)
    assert t[0] + t[1] == pytest.approx(((wp["F0_N"] + wp["ks_N_mm"] * x) * (x + wp["L0_mm"])
                                         - wp["F0_N"] * wp["L0_mm"]) / wp["EA_N"])
    assert t[2] == pytest.approx([0.0, t[2][1], 0.0], abs=1e-12)
    # kinematic coupling: Hertz's constant; the contacts carry the clamp and the weights, none pulls
    kp = P["kinematic_mount"]
    Es = 210e3 / (2 * (1 - 0.09))
    assert kp["c_H"] == pytest.approx((9 / (16 * Es ** 2 * kp["R_ball"])) ** (1 / 3))
    f = qb.kc_forces(kp, ctx)
    mm, _, _ = ctx.mass_state
    assert (f * kp["normals"][:, 2]).sum(axis=1) == pytest.approx(kp["F_p"] + kin.G * mm.sum(axis=1))
    assert f.min() > 0
    # holder: gravity along the last segment puts no moment on its joint; a joint's turn moves the target across
    hp = dict(P["ball_holder"], m_seg=np.zeros(2))
    g = (hp["S"] - hp["B2"])[None]
    assert np.abs(qb.holder_moments(hp, g)[1]).max() < 1e-9

    case, ctx = runs[("kr16_like", "ejector_chill")]
    P = case.truth["params"]
    # boom: shrinks by alpha L per kelvin, bows towards the exhaust side by alpha r_g L^2 / (2 D)
    cp = P["ejector_chill"]
    loc = qt.chill_local(cp)
    assert loc[2] == pytest.approx(-qt.ALU_CTE * cp["L_mm"])
    assert loc[:2] @ cp["side"][:2] == pytest.approx(qt.ALU_CTE * cp["r_g"] * cp["L_mm"] ** 2 / (2 * cp["D_mm"]))
    ses = SimpleNamespace(payload_kg=np.array([0.0, 5.0, 5.0]), time_s=np.array([0.0, 1.0, 1e6]))
    assert qt.chill_signal(dict(cp, x0=0.0), SimpleNamespace(session=ses)) == pytest.approx(
        [0.0, 1 - np.exp(-1 / cp["tau_s"]), 1.0])

    case, ctx = runs[("ur10", "gooseneck")]
    # gooseneck: the nozzle's motion per unit eps is -kappa d(tip)/d(kappa) at fixed length (a difference quotient)
    npar = case.truth["params"]["gooseneck"]
    R, e = qb.neck_geometry(npar["tip"])
    s_len = R * np.pi / 2

    def tip(k):
        return (qb.NECK_L0_MM + np.sin(k * s_len) / k) * qb.Z + (1 - np.cos(k * s_len)) / k * e

    assert tip(1 / R) == pytest.approx(npar["tip"])
    h = 1e-6
    assert qb.neck_local(npar) == pytest.approx((tip((1 - h) / R) - tip(1 / R)) / h, rel=1e-4, abs=1e-6)


def test_set_r_cases_kinds_and_determinism():
    """Set R: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session and probe hooks leave cases without a set-R kind alone
    (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a bracket's target
    sits at its tip, a swing-away tool's out on the tool; the rehoming, sprayer, welding and hose cases have their
    blocks."""
    from sim2real_indep import effects_r as er

    _assert_set_module("R", 40_7018, er, ("gear", "door_draught"))
    for name in ("effects_r", "effects_r_joint", "effects_r_body", "effects_r_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_r" in _imports(STUDY / "generator.py")
    assert er.AFTER_TRACKER == set()
    probe = np.array([3.0, -4.0, 12.0])                                     # |probe| 13 mm
    share = 8 / 95
    assert er.probe_hook(("sag", "stick_band"), probe) is probe
    L = 120 + 100 * share
    assert er.probe_hook(("web_buckling",), probe) == pytest.approx([3 / 5 * L, -4 / 5 * L, 30.0])
    assert er.probe_hook(("swing_mount",), probe) == pytest.approx(probe / 13 * (150 + 100 * share))
    for seed in range(3):
        opts = lambda kinds: er.session_options("kr16_like", kinds, np.random.default_rng(seed),  # noqa: E731
                                                {"blocks": 1, "gap_kind": "none"})
        home = opts(("rehoming",))
        assert 3 <= home["blocks"] <= 5 and home["gap_kind"] == "pause" and home["pause_min"] == (5.0, 20.0)
        weld = opts(("welding_cable",))
        assert 4 <= weld["blocks"] <= 7 and weld["gap_kind"] == "exercise"
        assert opts(("sprayer_tank", "floor_cable"))["gap_kind"] == "pause"
        assert opts(("slide_shift",)) == {"blocks": 1, "gap_kind": "none"}
    _assert_regenerates("R", max_effect_poses=50)


def test_set_r_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-R kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the balancer, the homing and the belt do nothing on the arms
    without them; and known answers: the line's sawtooth and the balancer's lever, the slide's moment, the stick band's
    stop, the cable's pull, the homing's blocks, the splice's span, the slab's basin (Westergaard's w(0) = P / 8 k l^2),
    the chassis' statics and the tank's draining, the web's buckling, the swing mount's dead zone and turn, and the
    links' growth and lags."""
    from types import SimpleNamespace

    from scipy.special import kei

    from sim2real_indep import effects_r_body as rb
    from sim2real_indep import effects_r_joint as rj
    from sim2real_indep import effects_r_thermal as rt

    specs = (("ur10", ("slide_shift", "stick_band", "floor_cable", "forklift_slab", "sprayer_tank", "heated_hose",
                       "line_pressure", "rehoming", "belt_splice")),
             ("kr16_like", ("line_pressure", "rehoming", "belt_splice", "welding_cable", "web_buckling")),
             ("tool_changer", ("swing_mount", "belt_splice", "stick_band")))
    inert = {"ur10": ("line_pressure", "rehoming", "belt_splice"), "kr16_like": (), "tool_changer": ("belt_splice",)}
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 18)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"line_pressure": lambda: [p["dF_N"]], "slide_shift": lambda: [p["m_kg"]],
                   "stick_band": lambda: rj.band_amplitudes(p), "floor_cable": lambda: [p["F_N"]],
                   "rehoming": lambda: rj.home_amplitudes(p), "belt_splice": lambda: [p["delta_mm"]],
                   "forklift_slab": lambda: [p["A_mm"]], "sprayer_tank": lambda: [1 / p["k_N_mm"]],
                   "web_buckling": lambda: rb.web_amplitudes(p), "swing_mount": lambda: [1 / p["k_Nmm"]],
                   "heated_hose": lambda: [p["dT_K"]], "welding_cable": lambda: [p["dT_K"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs["ur10"]
    P = case.truth["params"]
    # slide: the carriage's weight moves by the stroke: axis 1 (vertical) sees nothing, axis 2 the moment change
    sp = P["slide_shift"]
    sig = rj.slide_signal(sp, ctx, case.truth["hw"])
    assert np.abs(sig[:, 0]).max() < 1e-15 and not sig[sp["state"] == 0].any()
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    arm = (fl + Rt @ (sp["p_ret"] + sp["s_mm"])) - (fl + Rt @ sp["p_ret"])
    dtau = np.einsum("pi,pi->p", np.cross(arm / 1000, [0, 0, -kin.G]), w[:, 1])
    comp = 1 / np.array([hw["K3"] / hw["soften"] for hw in case.truth["hw"]["drives"]])[1]
    assert sig[:, 1] == pytest.approx(sp["state"] * dtau * comp)
    # stick band: unloaded, the axis stops short of its target by T_f / K_s (0.5-1.5 arcmin) on the approach's side
    bp = P["stick_band"]
    stub = SimpleNamespace(q=np.zeros((2, 6)), loads=np.zeros((2, 6)),
                           session=SimpleNamespace(direction=np.array([[1.0] * 6, [-1.0] * 6])))
    dq = rj.band_apply(bp, stub, None).dq[:, bp["joints"]]
    half = bp["T_f"] / bp["K_s"]
    assert dq == pytest.approx(np.array([-half, half]))
    assert np.all((half > 0.49 * ph.ARCMIN) & (half < 1.51 * ph.ARCMIN))
    # floor cable: pulled where the flange drew away from the anchor; the pull's torque is w . ((p - c) x F)
    cp = P["floor_cable"]
    dist = np.linalg.norm(fl - cp["anchor"], axis=1)
    assert rj.cable_pulled(cp, ctx)[1:] == pytest.approx((np.diff(dist) > 0).astype(float))
    u = (cp["anchor"] - fl) / dist[:, None]
    tau2 = np.einsum("pi,pi->p", np.cross((fl - c[:, 1]) / 1000, u), w[:, 1])
    assert rj.cable_signal(cp, ctx, case.truth["hw"])[:, 1] == pytest.approx(rj.cable_pulled(cp, ctx) * tau2 * comp)
    # slab: Westergaard's centre deflection P / (8 k l^2); the basin falls away from the load; only while it stands
    fp = P["forklift_slab"]
    assert rb.slab_basin(dict(fp, r_mm=0.0))[0] == pytest.approx(1 / 8) and -kei(0.0) == pytest.approx(np.pi / 4)
    w1, dw = rb.slab_basin(fp)
    h = 1e-3
    assert dw < 0 and dw == pytest.approx((rb.slab_basin(dict(fp, r_mm=fp["r_mm"] + h))[0] - w1) / h, rel=1e-4)
    assert rb.slab_present(fp, fp["stays"][:, 0] - 1.0).sum() <= len(fp["stays"]) - 1
    assert rb.slab_present(fp, fp["stays"][:1, 0] + 1.0) == pytest.approx([1.0])
    # chassis: the springs carry every weight (unit compliance); the tank is refilled at each block's start
    tp = P["sprayer_tank"]
    m, pos, _ = ctx.mass_state
    mt = rb.tank_mass(tp, ctx.session)
    pivot = rb.tank_shape(tp, SimpleNamespace(mass_state=ctx.mass_state, session=ctx.session,
                                              target=np.zeros((30, 3)) + tp["O"]))
    assert pivot[:, :2] == pytest.approx(np.zeros((30, 2)), abs=1e-12)  # the chassis' centre only heaves
    assert 4 * pivot[:, 2] == pytest.approx(-kin.G * (m.sum(axis=1) + mt))  # four unit springs carry every weight
    blocks = np.cumsum(ctx.session.gap_s < 0)
    last = np.r_[np.flatnonzero(np.diff(blocks)), len(blocks) - 1]
    assert mt[last] == pytest.approx(tp["full_kg"] * (1 - tp["drain"])) and mt.max() <= tp["full_kg"]
    # heated hose: nothing before the switch-on, 1 - 1/e one lag after; without a gradient the link only grows
    hp = P["heated_hose"]
    assert rt.hose_signal(hp, [hp["t_on_s"] - 5, hp["t_on_s"] + hp["tau_s"]]) == pytest.approx([0.0, 1 - np.exp(-1)])
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    li = hp["link"]
    grow = rt.bow_per_kelvin(ctx, li, hp["side"], 0.0, hp["D_mm"], hp["cte"])
    assert grow == pytest.approx(np.einsum("pij,j->pi", R[:, ctx.chain.link_body[li]], hp["cte"] * ctx.chain.links[li]))
    # with a gradient, the far end moves away from the warm side by alpha r_g dT L^2 / 2D per kelvin
    L = np.linalg.norm(ctx.chain.links[li])
    Rb, tb = R[:, ctx.chain.link_body[li]], kin.body_transforms(ctx.chain, ctx.q)[1][:, ctx.chain.link_body[li]]
    end_only = SimpleNamespace(chain=ctx.chain, q=ctx.q,
                               target=np.einsum("pij,j->pi", Rb, np.cumsum(ctx.chain.links, 0)[li]) + tb)
    side = np.einsum("pij,j->pi", Rb, hp["side"])
    bow = rt.bow_per_kelvin(end_only, li, hp["side"], 1.0, hp["D_mm"], hp["cte"])
    # (the side was drawn square to the true link, 0.1-0.5 mm off the file's: 1e-3)
    assert np.einsum("pi,pi->p", bow, side) == pytest.approx(-hp["cte"] * L ** 2 / (2 * hp["D_mm"]) * np.ones(30),
                                                             rel=1e-3)

    case, ctx = runs["kr16_like"]
    P = case.truth["params"]
    # line pressure: the sawtooth's cut-in and cut-out; the lever at a right angle r1 r2 / sqrt(r1^2 + r2^2)
    lp = P["line_pressure"]
    t = np.array([0.0, lp["t_load_s"] - 1e-9, lp["t_load_s"] + lp["t_unload_s"] / 2]) - lp["phase_s"]
    assert rj.sawtooth(t, lp) == pytest.approx([-0.5, 0.5, 0.0], abs=1e-6)
    r1, r2 = lp["r1_mm"], lp["r2_mm"]
    assert rj.lever_m(lp, np.array([np.pi / 2 - lp["g0"]])) == pytest.approx([r1 * r2 / np.hypot(r1, r2) / 1000])
    assert lp["sign"] == -np.sign(ctx.loads[:, 1].mean())
    # rehoming: the first block keeps the calibration's zero, each later one its own offsets
    hp = P["rehoming"]
    b = rj.block_of(ctx.session)
    assert b.max() >= 2 and not hp["offset"][0].any()
    assert rj.home_apply(hp, ctx, None).dq[:, hp["joints"]] == pytest.approx(hp["offset"][b])
    # belt splice: off the span nothing, inside it the full pitch error, ramps over the splice; period L / r
    sp = P["belt_splice"]
    r, s0 = sp["r_mm"], sp["s0_mm"]
    s = np.array([0.0, sp["w_mm"] / 2, sp["span_mm"] / 2, sp["span_mm"] + 1.0])
    q = (s - s0) / r
    assert rj.splice_on_span(sp, q) == pytest.approx([0.0, 0.5, 1.0, 0.0])
    assert rj.splice_on_span(sp, q + sp["L_mm"] / r) == pytest.approx([0.0, 0.5, 1.0, 0.0])
    # web: the first part never beyond V_cr, the second only past it
    wp = P["web_buckling"]
    V = rb.web_shear(wp, ctx)
    parts = rb.web_parts(wp, ctx)
    assert np.linalg.norm(parts[0], axis=1).max() <= wp["V_cr"] * (1 + 1e-12)
    assert not parts[1][np.abs(V) <= wp["V_cr"]].any() and (np.abs(V) > wp["V_cr"]).any()
    assert wp["k2"] < 0.46 * wp["k1"]
    # welding: the production periods are the exercise gaps; without welding the side cools from x0 through the lag
    cp = P["welding_cable"]
    ses = ctx.session
    assert rt.welding_periods(ses)[:, 1] - rt.welding_periods(ses)[:, 0] == pytest.approx(ses.gap_s[ses.gap_s > 0])
    cold = SimpleNamespace(time_s=ses.time_s, dwell_s=ses.dwell_s, move_s=ses.move_s, gap_s=np.zeros_like(ses.gap_s))
    x = rt.weld_signal(cp, cold)                                        # (linear between the 10 s grid's points)
    since = ses.time_s - ses.time_s[0] + ses.dwell_s[0] + rt.GRID_S
    assert x == pytest.approx(cp["x0"] * np.exp(-since / cp["tau_s"]), rel=1e-4)

    case, ctx = runs["tool_changer"]
    # swing mount: on its stop below the preload; off it, a turn about the hinge's axis
    wp = case.truth["params"]["swing_mount"]
    sh = rb.swing_shape(wp, ctx)
    M = wp["side"] * rb.swing_moment(wp, ctx)
    assert not sh[M <= wp["M_pre"]].any() and (M > wp["M_pre"]).any()
    _, Rt = kin.flange(ctx.chain, ctx.q)
    assert np.abs(np.einsum("pi,pi->p", sh, Rt @ wp["axis"])).max() < 1e-9 * np.abs(sh).max()
    assert np.abs(np.einsum("pi,pi->p", sh, Rt @ (wp["T"] - wp["H"]))).max() < 1e-9 * np.abs(sh).max() * 250


def test_set_s_cases_kinds_and_determinism():
    """Set S: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session, probe and payload hooks leave cases without a set-S
    kind alone (no random numbers drawn); the generator reaches the set's modules and none imports tolalloc; a profile
    frame's target and part sit at its gripper module; the trapped oil's cases have production between their blocks, the
    measuring wheel's a working day's pauses and a drifting air, the isolators' and the pinion's pick and place."""
    from sim2real_indep import effects_s as es

    _assert_set_module("S", 40_7019, es, ("gear", "welding_cable"))
    for name in ("effects_s", "effects_s_joint", "effects_s_body", "effects_s_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_s" in _imports(STUDY / "generator.py")
    assert es.AFTER_TRACKER == set()
    probe = np.array([3.0, -4.0, 12.0])                                     # |probe| 13 mm
    assert es.probe_hook(("sag", "cogging"), probe) is probe
    L = 150 + 150 * 8 / 95
    assert es.probe_hook(("profile_frame",), probe) == pytest.approx([3 / 5 * L, -4 / 5 * L, 30.0])
    com = np.array([1.0, 2.0, 3.0])
    assert es.payload_hook(("diaphragm",), com, probe) is com
    assert es.payload_hook(("profile_frame",), com, probe) == pytest.approx(probe)
    for seed in range(3):
        opts = lambda kinds, robot="tool_changer": es.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                      {"blocks": 1, "gap_kind": "none"})
        oil = opts(("oil_shrink",))
        assert 4 <= oil["blocks"] <= 7 and oil["gap_kind"] == "exercise"
        wheel = opts(("wheel_growth",), "kr16_like")
        assert 5 <= wheel["blocks"] <= 8 and wheel["gap_kind"] == "pause" and wheel["pause_min"] == (30.0, 90.0)
        assert 2.0 <= abs(wheel["air"]["drift_K"]) <= 6.0
        assert opts(("oil_shrink", "wheel_growth"))["gap_kind"] == "mixed"
        for kind in ("mullins_mounts", "float_pinion"):
            steps = opts((kind,))["payload_steps"]
            assert min(steps) == 0.0 and len(steps) >= 6
        assert opts(("cogging", "dowel_yaw")) == {"blocks": 1, "gap_kind": "none"}
    _assert_regenerates("S", max_effect_poses=50)


def test_set_s_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-S kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the pinion, the bellows, the potentiometers, the diaphragm,
    the trapped oil and the wheel do nothing on the arms without them; and known answers: the pinion's lift-off, the
    bellows' pull and its torques, the overshoot's crossing of the lost motion, the cogging's period, the loaded
    divider's error and the cylinder's lever, the dowels' relay, the twin table's statics, the isolators' reloading
    curve and the plate's equilibrium, Kishi-Chen's curve, the diaphragm's large-deflection law, the oil's node and
    shrink, and the wheel's expansion."""
    from dataclasses import replace
    from types import SimpleNamespace

    from sim2real_indep import effects_s_body as sb
    from sim2real_indep import effects_s_joint as sj
    from sim2real_indep import effects_s_thermal as st

    specs = (("ur10", ("wall_boot", "overshoot_lash", "cogging", "dowel_yaw", "twin_robot", "mullins_mounts",
                       "diaphragm", "float_pinion", "pot_loading", "oil_shrink", "wheel_growth")),
             ("tool_changer", ("float_pinion", "pot_loading", "oil_shrink", "wheel_growth", "wall_boot", "diaphragm")),
             ("kr16_like", ("profile_frame", "float_pinion", "wall_boot", "pot_loading")))
    inert = {"ur10": ("float_pinion", "pot_loading", "oil_shrink", "wheel_growth"),
             "tool_changer": ("wall_boot", "diaphragm"), "kr16_like": ("pot_loading",)}
    runs = {}
    for robot, physics in specs:
        case = gen.generate("t", robot, physics, 30, 19)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in physics:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"float_pinion": lambda: [p["c_x"]], "wall_boot": lambda: [p["k_a"], p["k_l"]],
                   "overshoot_lash": lambda: p["b"], "cogging": lambda: sj.cog_amplitudes(p),
                   "pot_loading": lambda: p["rho"], "dowel_yaw": lambda: [p["c_mm"] / (2 * p["r_d"])],
                   "twin_robot": lambda: [1 / p["k_N_mm"]], "mullins_mounts": lambda: [1 / p["k_v"]],
                   "profile_frame": lambda: [1 / p["R_ki"]], "diaphragm": lambda: [1.0],
                   "oil_shrink": lambda: [p["dT_s"]], "wheel_growth": lambda: [p["alpha_eff"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=kind)

    case, ctx = runs["ur10"]
    P, hw = case.truth["params"], case.truth["hw"]
    # bellows: no pull with the collar at its relaxed position; a joint's torque is w . ((p - c) x F); none beyond it
    bp = P["wall_boot"]
    pc, body = sj.collar(bp, ctx)
    assert not sj.boot_signals(dict(bp, p0=pc[0]), ctx, hw)[:, 0].any()
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    d = pc - bp["p0"]
    F = -(bp["k_a"] * np.outer(d @ bp["n"], bp["n"]) + bp["k_l"] * (d - np.outer(d @ bp["n"], bp["n"])))
    tau1 = np.einsum("pi,pi->p", np.cross((pc - c[:, 1]) / 1000, F), w[:, 1])
    dq = sj.boot_apply(bp, ctx, hw).dq
    assert dq[:, 1] == pytest.approx(tau1 * sj.compliance(hw)[1]) and not dq[:, body:].any()
    # overshoot lash: unloaded, no overshoot trails by b/2, a full return leads by b/2, half of it centres; loaded:
    # its gravity flank
    lp = P["overshoot_lash"]
    ses = SimpleNamespace(q=np.array([[0.0] * 6, [0.2] * 6, [0.4] * 6]), move_s=np.array([0.0, 1.5, 1.5]),
                          direction=np.ones((3, 6)))
    v = sj.cruise_speed(ses)[:, 0]
    assert v == pytest.approx([0.0, 0.2, 0.2])
    m = len(lp["joints"])
    kp = dict(lp, kappa=np.array([lp["b"][0] / 0.2, lp["b"][1] / 0.4, 0.0]))
    fl = sj.lash_flank(kp, np.zeros((3, m)), ses)
    assert fl[:, 0] == pytest.approx([-0.5, 0.5, 0.5]) and fl[1:, 1] == pytest.approx([0.0, 0.0])
    assert sj.lash_flank(kp, np.full((3, m), 1e6), ses) == pytest.approx(np.full((3, m), 0.5))
    # cogging: a period of 2 pi / (Z N) at the output; the amplitude A
    cp = P["cogging"]
    q = np.zeros((2, 6))
    j0 = cp["joints"][0]
    q[1, j0] = 2 * np.pi / (cp["Z"][0] * cp["N"][0])
    s = sj.cog_signals(cp, q)
    assert s[:, 0] == pytest.approx(s[:, 1], abs=1e-9)
    assert np.hypot(*sj.cog_amplitudes(cp)[[0, m]]) == pytest.approx(cp["A"][0])
    # dowels: the stop's reaction throws the base with the motion, the start's against it, else it stays
    tq = np.array([[0.0, 5.0, 0.0, 5.0], [0.0, 0.0, 5.0, 5.0]])
    assert sb.dowel_state(tq, np.array([1.0, -1.0, -1.0, 1.0]), 1.0, 1.0) == pytest.approx([1.0, 1.0, -1.0, 1.0])
    dp = P["dowel_yaw"]
    col = sb.dowel_shape(dp, ctx)
    assert np.abs(col[:, 2]).max() == 0 and np.abs(np.einsum("pi,pi->p", col, ctx.target - dp["centre"])).max() < 1e-6
    # twin table: four unit feet carry the twin's weights; its pose steps through the cycle, period T_c
    tp = P["twin_robot"]
    Kmat, a = sb._rigid_plate(tp["feet"])
    u = np.linalg.solve(Kmat, tp["f_cycle"].T).T
    assert (-a @ u.T).sum(axis=0) == pytest.approx(-tp["f_cycle"][:, 0])
    t = np.array([0.0, 0.3, 0.6]) * tp["T_c"]
    assert sb.twin_index(tp, t) == pytest.approx(sb.twin_index(tp, t + 7 * tp["T_c"]))
    # isolators: the reloading curve meets the virgin one at the largest compression; the plate carries every weight
    mp = P["mullins_mounts"]
    x = np.array([0.0, 0.5, 1.0, 2.0])
    assert sb.mullins_force(x, 1.0, mp["m"]) == pytest.approx([0.0, 0.5 ** mp["m"], 1.0, 2.0])
    loads = sb.mullins_loads(mp, ctx)
    u = sb.mullins_solve(mp, loads)
    Kmat, a = sb._rigid_plate(mp["feet"])
    c_m = mp["c_m0"].copy()
    for ui, g in zip(u, loads):                                          # each pose in equilibrium, maxima carried
        assert a.T @ sb.mullins_force(-a @ ui, c_m, mp["m"]) == pytest.approx(-g, rel=1e-8, abs=1e-8 * np.abs(g).max())
        c_m = np.maximum(c_m, np.abs(a @ ui))
    # diaphragms: u + beta u^3 = f (Cardano), linear for a small load, odd
    dp = P["diaphragm"]
    D = sb.STEEL_E * dp["t"] ** 3 / (12 * (1 - sb.STEEL_NU ** 2))
    Fs = np.array([-80.0, 1e-3, 40.0, 120.0])
    wv = sb.diaphragm_w(dp, Fs) / dp["t"]
    assert wv + dp["beta"] * wv ** 3 == pytest.approx(Fs * dp["a"] ** 2 / (2 * 16 * np.pi * D * dp["t"]))
    assert sb.diaphragm_w(dp, 1e-3) == pytest.approx(1e-3 * dp["a"] ** 2 / (2 * 16 * np.pi * D), rel=1e-6)
    assert sb.diaphragm_w(dp, -40.0) == pytest.approx(-sb.diaphragm_w(dp, 40.0))

    case, ctx = runs["tool_changer"]
    P = case.truth["params"]
    # pinion: nothing below the lift-off torque, the load beyond it above; T_0 = F_0 R / tan(alpha_w)
    pp = P["float_pinion"]
    assert pp["T0"] == pytest.approx(pp["F0"] * pp["R_m"] / np.tan(pp["alpha"]))
    assert pp["c_x"] == pytest.approx(np.tan(pp["alpha"]) ** 2 / (pp["k_s"] * pp["R_m"] ** 2))
    assert sj.pinion_signal(pp, [0.5 * pp["T0"], -2 * pp["T0"]]) == pytest.approx([0.0, -pp["T0"]])
    # potentiometer: the loaded divider reads true at both ends and lowest near 2/3, by rho 4/27; dL/dq of the lever
    op = P["pot_loading"]
    uu = np.array([0.0, 2 / 3, 1.0])
    assert sj.pot_error(uu, 1e-4) == pytest.approx([0.0, -1e-4 * 4 / 27, 0.0], abs=1e-9)
    lv = op["levers"][0]
    qq = np.array([0.1, 0.5])
    dL = (sj.lever_length(lv, qq + 1e-6) - sj.lever_length(lv, qq - 1e-6)) / 2e-6
    assert sj.lever_arm(lv, qq) == pytest.approx(dL, rel=1e-6)
    # trapped oil: the supply node reaches one after a long production, stays there with the pump at full heat and
    # cools to nothing in a long pause; no dwell, no shrink; the cap chamber loaded (a push), the boom sinks
    oil = P["oil_shrink"]
    ses = ctx.session
    later = np.r_[0.0, np.full(len(ses.time_s) - 1, 3e4)]
    for gap, idle, x in ((3e4, 1.0, 1.0), (-3e4, 0.0, 0.0)):
        stub = SimpleNamespace(time_s=ses.time_s + later, dwell_s=ses.dwell_s, move_s=ses.move_s,
                               gap_s=np.r_[0.0, gap, np.zeros(len(ses.gap_s) - 2)])
        assert st.supply_node(dict(oil, x0=0.5, idle=idle), stub)[1:] == pytest.approx(x, abs=1e-9)
    assert not st.oil_signals(oil, SimpleNamespace(session=replace(ses, dwell_s=0 * ses.dwell_s), q=ctx.q)).any()
    sig = st.oil_signals(oil, ctx)
    for k, lv in enumerate(oil["levers"]):
        dL = sig[k] * sj.lever_arm(lv, ctx.q[:, lv["joint"]])
        assert np.all(np.where(oil["push"][k], dL <= 0, dL >= 0))
    # wheel: alpha_eff of the hub and tread; at the joint's zero no error; a still air no error
    wp = P["wheel_growth"]
    assert wp["alpha_eff"] == pytest.approx((st.ALU_CTE * (wp["r_mm"] - wp["t_mm"]) + wp["alpha_pu"] * wp["t_mm"])
                                            / wp["r_mm"])
    q0 = ctx.q.copy()
    q0[:, 0] = 0.0
    assert not st.wheel_signal(wp, SimpleNamespace(session=ctx.session, q=q0)).any()
    still = replace(ctx.session, air=dict(ctx.session.air, drift_K=0.0, cycle_K=0.0))
    assert np.abs(st.wheel_signal(wp, SimpleNamespace(session=still, q=ctx.q))).max() < 1e-9

    case, ctx = runs["kr16_like"]
    # profile frame: Kishi-Chen's M = R theta / (1 + (theta / theta_0)^n)^(1/n) holds at the joint; no turn about the
    # bar
    fp = case.truth["params"]["profile_frame"]
    M = np.linalg.norm(sb.frame_moment(fp, ctx), axis=1)
    theta = M / fp["R_ki"] / (1 - (M / fp["M_u"]) ** fp["n"]) ** (1 / fp["n"])
    assert M == pytest.approx(fp["R_ki"] * theta / (1 + (theta * fp["R_ki"] / fp["M_u"]) ** fp["n"]) ** (1 / fp["n"]))
    Rt, _ = sb._gravity_tool(ctx)
    e = Rt @ (fp["tip"] - fp["root"])
    sh = sb.frame_shape(fp, ctx)
    assert np.abs(np.einsum("pi,pi->p", sh, e)).max() < 1e-9 * np.abs(sh).max()
    assert M.max() < fp["M_u"] and fp["tip"] == pytest.approx(case.truth["payload_com_mm"])


def test_set_t_cases_kinds_and_determinism():
    """Set T: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session hook leaves cases without a set-T kind alone (no random
    numbers drawn); the generator reaches the set's modules and none imports tolalloc; the intervention's and the working
    session's kinds have their blocks and pauses, the lockable float a gripper alternately empty and holding a part."""
    from sim2real_indep import effects_t as et

    _assert_set_module("T", 40_7020, et, ("gear", "wheel_growth"))
    for name in ("effects_t", "effects_t_joint", "effects_t_body", "effects_t_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_t" in _imports(STUDY / "generator.py")
    assert et.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": et.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        leak = opts(("balancer_leak",))
        assert 4 <= leak["blocks"] <= 7 and leak["gap_kind"] == "pause" and leak["pause_min"] == (20.0, 60.0)
        crane = opts(("crane_runway",), "ur10")
        assert 3 <= crane["blocks"] <= 5 and crane["pause_min"] == (5.0, 20.0)
        for kind in ("shield_squeeze", "main_drive"):
            o = opts((kind,), "tool_changer")
            assert 4 <= o["blocks"] <= 7 and o["gap_kind"] == "pause" and o["pause_min"] == (15.0, 45.0)
        assert opts(("dew_warming", "shield_squeeze"))["gap_kind"] == "mixed"
        steps = np.array(opts(("lockable_float",), "ur10")["payload_steps"])
        assert 6 <= len(steps) <= 10 and not steps[::2].any() and (steps[1::2] >= 3.0).all()
        assert opts(("charge_cable", "via_approach")) == {"blocks": 1, "gap_kind": "none"}
    _assert_regenerates("T", max_effect_poses=50)


def test_set_t_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-T kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the kinds do nothing on the arms without their hardware; and
    known answers: the cable's touchdown catenary and its joint loads, the balancer's lever and leak, Euler-Eytelwein's
    ratio and the hose's sliding state, the approach's joint rates and flank, the inclinometers' servoed readings, the
    rangefinder's period, the propped column's slope and prop, the crane's influence line, the inextensional ring, the
    lock, the play operator, the saturation humidity and the dew's boost, and the main drive's nodes."""
    from dataclasses import replace
    from types import SimpleNamespace

    from sim2real_indep import effects_t_body as tb
    from sim2real_indep import effects_t_joint as tj
    from sim2real_indep import effects_t_thermal as tt
    from sim2real_indep.effects_s_joint import compliance

    every = ("charge_cable", "balancer_leak", "hose_capstan", "via_approach", "inclinometer", "rangefinder",
             "crane_runway", "shield_squeeze", "lockable_float", "plunger_stiction", "dew_warming", "main_drive")
    inert = {"ur10": ("balancer_leak", "inclinometer", "rangefinder", "shield_squeeze", "main_drive"),
             "tool_changer": ("charge_cable", "crane_runway", "lockable_float", "plunger_stiction", "dew_warming"),
             "kr16_like": ("inclinometer", "rangefinder", "main_drive")}
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 20)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"charge_cable": lambda: [p["w_N_m"]], "balancer_leak": lambda: [p["F_ref"]],
                   "hose_capstan": lambda: [p["F0_N"]], "via_approach": lambda: p["b"],
                   "inclinometer": lambda: p["c"].ravel(), "rangefinder": lambda: p["amp"],
                   "crane_runway": lambda: [p["e"] / (tb.STEEL_E_PA * p["I"])],
                   "shield_squeeze": lambda: [p["delta_inf"]], "lockable_float": lambda: [1 / p["k_N_mm"]],
                   "plunger_stiction": lambda: [1 / p["k_N_mm"]], "dew_warming": lambda: [p["cte"]],
                   "main_drive": lambda: [p["dT0"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, hw = case.truth["params"], case.truth["hw"]
    # cable: s = sqrt(h^2 + 2 a h) is the catenary's arc from its touchdown (a sinh of the reach over a); the pull is
    # -s up and a towards the charger; its joint loads are J^T F at the clamp
    cp = P["charge_cable"]
    a = cp["a_m"]
    h = np.array([0.3, 1.0, 2.0])
    assert np.sqrt(h ** 2 + 2 * a * h) == pytest.approx(a * np.sinh(np.arccosh(1 + h / a)))
    F, A = tj.cable_force(cp, ctx)
    s = np.sqrt(((A[:, 2] - cp["z_floor"]) / 1000) ** 2 + 2 * a * (A[:, 2] - cp["z_floor"]) / 1000)
    assert F[:, 2] == pytest.approx(-s) and np.linalg.norm(F[:, :2], axis=1) == pytest.approx(np.full(len(F), a))
    assert np.einsum("pi,pi->p", F[:, :2], cp["charger"] - A[:, :2]) == pytest.approx(
        a * np.linalg.norm(cp["charger"] - A[:, :2], axis=1))
    J = kin.position_jacobian(ctx.chain, ctx.q, A)
    assert tj.force_loads(ctx, A, F) == pytest.approx(np.einsum("pij,pi->pj", J, F) / 1000.0)
    # capstan: pulled out the clamp's side carries exp(2 mu theta) times the drawn-in tension; an internal force between
    # the turret and the tool loads no joint before axis 2; the sliding state follows the clamp's distance from the ring
    hp = P["hose_capstan"]
    theta, _ = tj.capstan_wrap(hp, ctx)
    out_, in_ = (1 + (np.exp(s_ * hp["mu"] * theta) - 1) for s_ in (1.0, -1.0))
    assert out_ / in_ == pytest.approx(np.exp(2 * hp["mu"] * theta))
    assert not tj.capstan_loads(hp, ctx)[:, 0].any()
    ring, clamp, _ = tj.capstan_points(hp, ctx)
    ell = np.linalg.norm(clamp - ring, axis=1)
    moved = np.abs(np.diff(ell)) > 1.0
    assert (hp["s"][1:][moved] == np.sign(np.diff(ell))[moved]).all() and hp["s"][0] == hp["s0"]
    # approach: the rates move the tool along the approach direction without turning it; the flank is the gravity one
    # where the load beats the drag, else the approach's trailing one
    ap = P["via_approach"]
    rates = tj.approach_rates(ap, ctx)
    eps = 1e-6
    f0, R0 = kin.flange(ctx.chain, ctx.q)
    f1, R1 = kin.flange(ctx.chain, ctx.q + eps * rates)
    assert (f1 - f0) / eps == pytest.approx(R0 @ ap["a_tool"], abs=1e-4)
    assert np.abs(R1 - R0).max() / eps < 1e-3
    tau = ctx.loads[:, ap["joints"]]
    loaded = np.abs(tau) > ap["drag"]
    assert ap["flank"][loaded] == pytest.approx(0.5 * np.sign(tau[loaded]))
    assert (np.abs(ap["flank"]) == 0.5).all()
    # crane: the propped column -- integrating EI v'' = M(z) (the couple below a, the prop's moment) from the fixed
    # foot meets the prop at H with no deflection and the closed-form slope at the bracket; the influence line
    crp = P["crane_runway"]
    H, a_c, zb = crp["H"], crp["a"], crp["z_b"]
    pp = -3 * a_c * (H - a_c / 2) / H ** 3
    z = np.linspace(0.0, H, 200001)
    M = (z < a_c) + pp * (H - z)
    slope = np.r_[0.0, np.cumsum((M[1:] + M[:-1]) / 2 * np.diff(z))]
    v = np.r_[0.0, np.cumsum((slope[1:] + slope[:-1]) / 2 * np.diff(z))]
    assert abs(v[-1]) < 1e-4 * np.abs(v).max()                         # the step at a: trapezoid error
    assert np.interp(zb, z, slope) == pytest.approx(zb * (1 + pp * (2 * H - zb) / 2), rel=1e-6)
    assert np.interp(zb, z, v) == pytest.approx(zb ** 2 * (0.5 + pp * (3 * H - zb) / 6), rel=1e-6)
    R = tb.crane_schedule(crp, crp["t_event"])
    assert R == pytest.approx(crp["R_event"]) and (R >= 0).all() and R.max() > 0
    # lockable float: nothing while a part is held; free, the tool's weight across its axis over the rate
    fp = P["lockable_float"]
    sh = tb.float_shape(fp, ctx)
    held = ctx.session.payload_kg > 0
    assert held.any() and (~held).any() and not sh[held].any()
    Rt, g_t = tb._gravity_tool(ctx)
    assert np.abs(np.einsum("pi,pi->p", sh, Rt[:, :, 2])).max() < 1e-9
    assert np.linalg.norm(sh[~held], axis=1) == pytest.approx(fp["m_kg"] * np.linalg.norm(g_t[~held, :2], axis=1))
    # plunger: within F_f of the frictionless place, moving only when pushed out of the band, along the tool axis
    pl = P["plunger_stiction"]
    x = tb.plunger_state(pl, ctx)
    x_eq = (pl["m_kg"] + ctx.session.payload_kg) * g_t[:, 2]
    assert (np.abs(x - x_eq) <= pl["F_f"] + 1e-9).all()
    still = np.abs(x_eq[1:] - x[:-1]) <= pl["F_f"]
    assert x[1:][still] == pytest.approx(x[:-1][still])
    assert np.abs(x[1:][~still] - x_eq[1:][~still]) == pytest.approx(np.full((~still).sum(), pl["F_f"]))
    # dew: the saturation ratio at 20 degC (psychrometric tables: 0.0147); dry air -- the exact first-order warm-up in a
    # still shop; the dew's latent heat warms the cold arm faster
    assert tt.saturation_ratio(20.0) == pytest.approx(0.0147, abs=2e-4)
    dp = P["dew_warming"]
    ses = replace(ctx.session, air=dict(ctx.session.air, cycle_K=0.0, drift_K=0.0))
    stub = SimpleNamespace(session=ses, q=ctx.q)
    dry = tt.dew_temperatures(dict(dp, w_air=0.0), stub)
    taus = np.array([dp["tau_s"][b] for b in dp["bodies"]] + [dp["tau_ped"]])
    t = ses.time_s - ses.time_s[0] + dp["t_in"]
    exact = dp["dT0"] * (np.exp(-dp["t_in"] / taus) - np.exp(-t[:, None] / taus))
    assert dry == pytest.approx(exact, abs=0.02 * dp["dT0"])
    fresh = dict(dp, t_in=0.0)                                           # both start at the first pose
    assert (tt.dew_temperatures(fresh, stub) >= tt.dew_temperatures(dict(fresh, w_air=0.0), stub) - 1e-12).all()
    assert tt.dew_temperatures(fresh, stub)[1].sum() > tt.dew_temperatures(dict(fresh, w_air=0.0), stub)[1].sum()

    case, ctx = runs["tool_changer"]
    P, hw = case.truth["params"], case.truth["hw"]
    # balancer: dL/dq2 by differences; the leak lost the drawn share of the gas by the last pose; the push holds the arm
    # up at the most loaded pose
    bp = P["balancer_leak"]
    qq = np.array([0.2, 0.5])
    dL = (tj.balancer_length(bp, qq + 1e-6)[0] - tj.balancer_length(bp, qq - 1e-6)[0]) / 2e-6
    assert tj.balancer_length(bp, qq)[1] == pytest.approx(dL, rel=1e-6)
    sig = tj.leak_signal(bp, ctx.session)
    assert sig[0] == 0.0 and 0.2 <= -sig[-1] <= 0.45
    tau2 = ctx.loads[:, 1]
    k = int(np.argmax(np.abs(tau2)))
    share = -bp["F_ref"] * tj.balancer_torque(bp, ctx.q[k:k + 1, 1])[0] / tau2[k]
    assert 0.6 <= share <= 0.9
    assert tj.leak_twist(bp, ctx, hw) == pytest.approx(compliance(hw)[1] * tj.balancer_torque(bp, ctx.q[:, 1]) * sig)
    # inclinometers: servoed on the readings, each link's absolute pitch reads as commanded (to second order)
    ip = P["inclinometer"]
    dq = tj.incl_apply(ip, ctx, hw).dq
    for k, js in enumerate(ip["sensors"]):
        a_true = (ctx.q + dq)[:, list(js)].sum(axis=1)
        read = a_true + ip["c"][k] @ tj.incl_harmonics(a_true)
        assert read == pytest.approx(ctx.q[:, list(js)].sum(axis=1), abs=1e-5)
    # rangefinder: the cyclic error repeats with the fine unit U
    rp = P["rangefinder"]
    q2 = ctx.q.copy()
    q2[:, 3] += rp["U"]
    assert tj.range_signals(rp, q2) == pytest.approx(tj.range_signals(rp, ctx.q), abs=1e-9)
    # shield: the ring mode is inextensional (u_r + du_phi / dphi = 0); the convergence grows from the session's start
    sp = P["shield_squeeze"]
    phi = np.linspace(0, 2 * np.pi, 7)
    u_r = lambda f: np.cos(2 * (f - sp["phi_p"]))  # noqa: E731
    du_phi = (-0.5 * np.sin(2 * (phi + 1e-6 - sp["phi_p"])) + 0.5 * np.sin(2 * (phi - 1e-6 - sp["phi_p"]))) / 2e-6
    assert u_r(phi) + du_phi == pytest.approx(np.zeros(7), abs=1e-6)
    g = tb.squeeze_signal(sp, ctx.session)
    assert g[0] == 0.0 and (np.diff(g) >= 0).all() and g[-1] < 1.0
    # main drive: without the inching the console follows the two-node closed form; the inching warms it
    mp = P["main_drive"]
    calm = tt.drive_node(dict(mp, inch=0.0), ctx.session)
    tt_ = mp["t_start"] + ctx.session.time_s - ctx.session.time_s[0]
    td, tc = mp["tau_d"], mp["tau_c"]
    assert calm == pytest.approx((td * np.exp(-tt_ / td) - tc * np.exp(-tt_ / tc)) / (td - tc), abs=2e-3)
    assert (tt.drive_node(mp, ctx.session) >= calm - 1e-12).all()


def test_set_u_cases_kinds_and_determinism():
    """Set U: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session hook leaves cases without a set-U kind alone (no random
    numbers drawn) and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; the
    platform's working day, the parked tool's blocks and the gripper alternately empty and holding a part."""
    from sim2real_indep import effects_u as eu

    _assert_set_module("U", 40_7021, eu, ("gear", "main_drive"))
    for name in ("effects_u", "effects_u_joint", "effects_u_body", "effects_u_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_u" in _imports(STUDY / "generator.py")
    assert eu.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": eu.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        day = opts(("platform_growth",))
        assert 5 <= day["blocks"] <= 8 and day["gap_kind"] == "pause" and day["pause_min"] == (30.0, 90.0)
        assert 2.0 <= abs(day["air"]["drift_K"]) <= 6.0
        park = opts(("parked_tool",), "ur10")
        assert 4 <= park["blocks"] <= 8 and park["gap_kind"] == "pause" and park["pause_min"] == (5.0, 20.0)
        for kind in ("magnet_coil", "sandwich_boom"):
            steps = np.array(opts((kind,), "ur10")["payload_steps"])
            assert 6 <= len(steps) <= 10 and not steps[::2].any() and (steps[1::2] >= 3.0).all()
        assert opts(("integral_clamp", "bowden_lash", "soiled_disc")) == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert eu.probe_hook(("gear",), probe) is probe
    assert eu.probe_hook(("sleeve_rock",), probe) == pytest.approx(probe + [0, 0, 250.0])
    assert eu.probe_hook(("sandwich_boom",), probe) == pytest.approx(probe + [400.0, 0, 0])
    _assert_regenerates("U", max_effect_poses=50)


def test_set_u_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-U kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the chain and the Bowden cable do nothing on tool_changer;
    and known answers: the clamp's dead zone, the parked tool's J^T F and blocks, the sagging span's extra length, the
    sheath's wrap, the dropped counts' telescoping travel, the soiled sector's bump, the moment about a point below the
    base, the slab's two sides, the sandwich's face stiffness and its sag with gravity, the sleeve's throw, the
    platform's lag of a ramp and the coil's node."""
    from dataclasses import replace

    from sim2real_indep import effects_u_body as ub
    from sim2real_indep import effects_u_joint as uj
    from sim2real_indep import effects_u_thermal as ut
    from sim2real_indep.effects_body import mount_moment

    every = ("integral_clamp", "parked_tool", "chain_slack", "bowden_lash", "dropped_counts", "soiled_disc",
             "trunnion", "slab_joint", "sandwich_boom", "sleeve_rock", "platform_growth", "magnet_coil")
    inert = {"ur10": (), "tool_changer": ("chain_slack", "bowden_lash"), "kr16_like": ()}
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 21)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"integral_clamp": lambda: 1 / p["K_s"], "parked_tool": lambda: [p["m_kg"]],
                   "chain_slack": lambda: [p["b_h"]], "bowden_lash": lambda: [p["b0"]],
                   "dropped_counts": lambda: p["eps"], "soiled_disc": lambda: [p["A"]],
                   "trunnion": lambda: [1 / p["k_t"]], "slab_joint": lambda: [p["c_s"], p["c_i"]],
                   "sandwich_boom": lambda: [p["c_tip"], p["d_own"]], "sleeve_rock": lambda: [p["throw_mm"]],
                   "platform_growth": lambda: [p["alpha"]], "magnet_coil": lambda: [p["alpha"] * p["dT_max"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, hw, s = case.truth["params"], case.truth["hw"], ctx.session
    # clamp: the proportional term holds what the clamped integrator leaves, tau - clip(tau, -T_I, T_I)
    assert uj.clamp_dead_zone(np.array([-3.0, -1.0, 0.0, 1.0, 3.0]), 2.0) == pytest.approx([-1, 0, 0, 0, 1])
    cp = P["integral_clamp"]
    tau = ctx.loads[:, cp["joints"]]
    assert uj.clamp_signals(cp, ctx) == pytest.approx(tau - np.clip(tau, -cp["T_I"], cp["T_I"]))
    # parked tool: J^T F at its centre of mass, nothing on the joints from its body on, the same in a whole block
    pp = P["parked_tool"]
    x = uj.parked_point(pp, ctx)
    J = kin.position_jacobian(ctx.chain, ctx.q, x)
    full = np.einsum("pij,i->pj", J, [0.0, 0.0, -kin.G]) / 1000.0
    loads = uj.parked_loads(pp, ctx)
    assert loads[:, :3] == pytest.approx(full[:, :3] * pp["present"][:, None]) and not loads[:, 3:].any()
    b = uj.block_index(s)
    assert all(len(set(pp["present"][b == k])) == 1 for k in set(b)) and pp["pattern"].any() and not pp["pattern"].all()
    # chain: a horizontal span of sag f hangs 8 f^2 / (3 L) longer (the parabola's arc); the play b = that / r
    ch = P["chain_slack"]
    f = ch["w_N_m"] * ch["L_m"] ** 2 / (8 * ch["H_N"])
    xx = np.linspace(0.0, ch["L_m"], 200001)
    y = 4 * f * xx * (ch["L_m"] - xx) / ch["L_m"] ** 2
    arc = np.sum(np.hypot(np.diff(xx), np.diff(y)))
    assert (arc - ch["L_m"]) / ch["r_m"] == pytest.approx(ch["b_h"], rel=1e-3)
    c2 = uj.chain_cos2(ch, ctx)
    assert (c2 >= 0).all() and (c2 <= 1).all() and (np.abs(ch["flank"]) == 0.5).all()
    loaded = np.abs(ctx.loads[:, 2]) > ch["drag"]
    assert ch["flank"][loaded] == pytest.approx(0.5 * np.sign(ctx.loads[loaded, 2]))
    # Bowden: the sheath runs straight at q3_n (wrap theta0); the drawn play at theta0 + 1 rad
    bp = P["bowden_lash"]
    q = np.zeros((1, 6))
    q[0, 2] = bp["q3_n"]
    assert uj.bowden_wrap(bp, q) == pytest.approx([bp["theta0"]])
    play = np.rad2deg(bp["b0"] * (np.exp(bp["mu"] * (bp["theta0"] + 1.0)) - 1.0))
    assert 0.1 <= play <= 0.35
    # dropped counts: every move fast, the travel telescopes to q - q[0]; none fast, nothing
    dp = P["dropped_counts"]
    assert uj.count_signals(dict(dp, v_c=np.full(3, -1.0)), s) == pytest.approx(s.q[:, :3] - s.q[0, :3])
    assert not uj.count_signals(dict(dp, v_c=np.full(3, np.inf)), s).any()
    # soiled sector: a bump of 1 at its centre, exp(-1/2) one width off
    sp = P["soiled_disc"]
    qs = np.zeros((3, 6))
    qs[:, 1] = sp["theta_c"] + np.array([0.0, sp["w"], -sp["w"]])
    assert uj.soil_signal(sp, qs) == pytest.approx([1.0, np.exp(-0.5), np.exp(-0.5)])
    # trunnion: the gravity moment about a point below the base equals the one about the base origin; the table turns
    # about its axis
    tp = P["trunnion"]
    m, pos, _ = ctx.mass_state
    p0 = np.array([0.0, 0.0, -tp["h_mm"]])
    M0 = np.cross((pos - p0) / 1000.0, m[..., None] * np.array([0.0, 0.0, -kin.G])).sum(axis=1)
    assert M0 == pytest.approx(mount_moment(ctx))
    sh = ub.trunnion_shape(tp, ctx)
    assert np.abs(sh @ tp["axis"]).max() < 1e-9 * np.abs(sh).max()
    # slab: both sides alike, a linear tilt about the joint's line
    lp = P["slab_joint"]
    lin = ub._tilt(lp["axis"], mount_moment(ctx) @ lp["axis"], ctx.target, lp["pivot"]) * lp["c_i"]
    assert ub.slab_apply(dict(lp, c_s=lp["c_i"]), ctx, hw).displace == pytest.approx(lin)
    # sandwich: the faces' D = E b t d^2 / 2 within 10 % of the exact two-face section's; the boom sags with gravity
    E, bb, tf, cc = 70e9, 0.1, 0.0015, 0.03
    exact = E * bb * ((cc + 2 * tf) ** 3 - cc ** 3) / 12
    assert E * bb * tf * (cc + tf) ** 2 / 2 == pytest.approx(exact, rel=0.1)
    sw = P["sandwich_boom"]
    dsp = ub.boom_apply(sw, ctx, hw).displace
    assert (dsp[:, 2] <= 1e-12).all() and np.abs(dsp).max() > 0
    # sleeve: the throw across the tube, towards gravity's transverse component, at most the full throw
    sl = P["sleeve_rock"]
    u = ub.sleeve_shape(sl, ctx)
    Rt, g_t = ub._gravity_tool(ctx)
    assert np.abs(np.einsum("pi,pi->p", u, Rt[:, :, 2])).max() < 1e-12
    assert (np.linalg.norm(u, axis=1) <= 1).all() and (u[:, 2] <= 1e-12).all()
    # platform: a ramping air, the steel lags it by tau (the first-order response to a ramp)
    pg = P["platform_growth"]
    ramp = replace(s, air=dict(s.air, cycle_K=0.0, drift_K=3.0))
    t = ramp.time_s - ramp.time_s[0]
    rate = 3.0 / t[-1]
    assert ut.platform_temperature(pg, ramp) == pytest.approx(rate * (t - pg["tau_s"] * (1 - np.exp(-t / pg["tau_s"]))),
                                                             abs=1e-3)
    # coil: off until a part is held; held from the first pose on, 1 - exp(-t / tau)
    mc = P["magnet_coil"]
    node = ut.coil_node(mc, s)
    held = s.payload_kg > 0
    assert not node[:np.argmax(held)].any() and (node >= 0).all() and (node < 1).all()
    assert ut.coil_node(mc, replace(s, payload_kg=np.ones(len(t)))) == pytest.approx(1 - np.exp(-t / mc["tau_s"]))


# ---------------------------------------------------------------------------------------------------------- set V
def test_set_v_cases_kinds_and_determinism():
    """Set V: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time;
    a case regenerates bit-identically from its seed; the session hook leaves cases without a set-V kind alone (no random
    numbers drawn) and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; the
    working day of the restrained bar and the slab, the long day of the printed boom and the carriers' blocks."""
    from sim2real_indep import effects_v as ev

    _assert_set_module("V", 40_7022, ev, ("gear", "magnet_coil"))
    for name in ("effects_v", "effects_v_joint", "effects_v_body", "effects_v_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_v" in _imports(STUDY / "generator.py")
    assert ev.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ev.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        for kind in ("restrained_bar", "slab_curl"):
            day = opts((kind,))
            assert 5 <= day["blocks"] <= 8 and day["gap_kind"] == "pause" and day["pause_min"] == (30.0, 90.0)
            assert 2.0 <= abs(day["air"]["drift_K"]) <= 6.0
        long = opts(("moisture_swell",))
        assert 5 <= long["blocks"] <= 8 and long["pause_min"] == (30.0, 90.0) and "air" not in long
        for kind in ("stabilizer_jacks", "self_leveling"):
            b = opts((kind,), "ur10")
            assert 4 <= b["blocks"] <= 8 and b["gap_kind"] == "pause" and b["pause_min"] == (5.0, 20.0)
        assert opts(("coiled_cord", "coupled_flank", "interpolation_error")) == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ev.probe_hook(("gear",), probe) is probe
    assert ev.probe_hook(("bolt_loosening",), probe) == pytest.approx(probe + [400.0, 0, 0])
    assert ev.probe_hook(("moisture_swell",), probe) == pytest.approx(probe + [400.0, 0, 0])
    assert ev.probe_hook(("restrained_bar",), probe) == pytest.approx(probe + [0, 0, 150.0])
    _assert_regenerates("V", max_effect_poses=50)


def test_set_v_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-V kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect where the kind applies; the coupled wrist acts on kr16_like only, the pins and the
    rack on tool_changer only; and known answers: the coiled cord's spring law, the catenary's equilibrium, the coupled
    motor's flank, the pin's friction-angle shift, the first-order interpolation error against the exact demodulation,
    the rack's steps, the carrier's block states and levelling, the bolts' log law and sag across the boom, Fick's
    early-time root, the bar's amplification and the slab's sink."""
    from dataclasses import replace

    from sim2real_indep import effects_v_body as vb
    from sim2real_indep import effects_v_joint as vj
    from sim2real_indep import effects_v_thermal as vt
    from sim2real_indep.effects_u_joint import block_index

    every = ("coiled_cord", "overhead_festoon", "coupled_flank", "journal_climb", "interpolation_error",
             "rack_segments", "stabilizer_jacks", "self_leveling", "bolt_loosening", "moisture_swell",
             "restrained_bar", "slab_curl")
    inert = {"ur10": ("coupled_flank", "journal_climb", "rack_segments"), "tool_changer": ("coupled_flank",),
             "kr16_like": ("journal_climb", "rack_segments")}
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 22)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            if kind in inert[robot]:
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0, (robot, kind)
                continue
            p = case.truth["params"][kind]
            amp = {"coiled_cord": lambda: [p["k"]], "overhead_festoon": lambda: [p["w"]],
                   "coupled_flank": lambda: [p["b"] / 2], "journal_climb": lambda: p["e_mm"],
                   "interpolation_error": lambda: p["coef"].ravel(), "rack_segments": lambda: p["amp"],
                   "stabilizer_jacks": lambda: p["c"], "self_leveling": lambda: p["c"],
                   "bolt_loosening": lambda: [p["c0"], p["c0"] * p["gamma"]], "moisture_swell": lambda: [p["a"]],
                   "restrained_bar": lambda: [p["delta0_mm"]], "slab_curl": lambda: [p["a"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # coiled cord: F_i + k (d - L0) along the chord, nothing when slack
    cp = P["coiled_cord"]
    B = kin.flange(ctx.chain, ctx.q)[0] / 1000.0
    dist = np.linalg.norm(cp["A_m"] - B, axis=1)
    pull = vj.cord_pull(cp, ctx) * cp["k"]
    assert np.linalg.norm(pull, axis=1) == pytest.approx(cp["Fi"] + cp["k"] * (dist - cp["L0_m"]))
    assert not vj.cord_pull(dict(cp, L0_m=10.0), ctx).any()
    # catenary: level ends share the weight, w L / 2 each; in general the ends carry w L together, H equal and opposite
    A0, Bs, L = np.zeros(3), np.array([[2.0, 0.0, 0.0], [1.5, 1.0, -0.8]]), 3.0
    fB = vj.catenary_end_force(A0, Bs, L, 9.81)
    fA = np.array([vj.catenary_end_force(b, A0[None], L, 9.81)[0] for b in Bs])
    assert fB[0, 2] == pytest.approx(-9.81 * L / 2, rel=1e-6)
    assert fA[:, 2] + fB[:, 2] == pytest.approx(-9.81 * L, rel=1e-6)
    assert fA[:, :2] == pytest.approx(-fB[:, :2], rel=1e-6)
    # coupled flank: without the coupling the motor moves with its own axis; the loaded poses take the load's flank
    fp = P["coupled_flank"]
    j = fp["joints"][0]
    moved = np.r_[False, np.diff(s.q[:, j]) != 0]
    assert vj.coupled_net_motion(dict(fp, c=0.0), s)[moved] == pytest.approx(s.direction[moved, j])
    loaded = np.abs(ctx.loads[:, j]) > fp["drag"]
    assert fp["flank"][loaded] == pytest.approx(np.sign(ctx.loads[loaded, j]))
    # journal climb: a horizontal unit shift across the axis; c_r sin(atan mu) = c_r mu / sqrt(1 + mu^2)
    case_t, ctx_t = runs["tool_changer"]
    jp = case_t.truth["params"]["journal_climb"]
    sh = vj.climb_shift(jp, ctx_t)
    w, _ = kin.joint_frames(ctx_t.chain, ctx_t.q)
    assert np.abs(sh[..., 2]).max() < 1e-12 and np.linalg.norm(sh, axis=2) == pytest.approx(1.0)
    assert np.abs(np.einsum("kpi,pki->kp", sh, w[:, list(jp["joints"])])).max() < 1e-12
    assert jp["e_mm"] == pytest.approx(jp["c_r_mm"] * jp["mu"] / np.sqrt(1 + jp["mu"] ** 2))
    # interpolation: the first-order harmonics agree with the exact arctangent demodulation to second order
    ip = P["interpolation_error"]
    N, qq = ip["N"][0], np.linspace(0.0, 0.2, 2001)
    phi = N * qq
    o_s, o_c, eps, dlt = -ip["coef"][0, 0], ip["coef"][0, 1], -2 * ip["coef"][0, 2], -2 * ip["coef"][0, 3]
    exact = np.angle(np.exp(1j * (np.arctan2((1 + eps) * np.sin(phi + dlt) + o_s, np.cos(phi) + o_c) - phi))) - dlt / 2
    q6 = np.zeros((len(qq), 6))
    q6[:, ip["joints"][0]] = qq
    first = -N * ip["coef"][0] @ vj.interp_signals(ip, q6)[0]
    assert np.abs(exact - first).max() < 3 * max(abs(o_s), abs(o_c), abs(eps), abs(dlt)) ** 2
    # rack: the stage's error steps by each butt joint's gap
    rp = case_t.truth["params"]["rack_segments"]
    qa = np.zeros((2 * len(rp["joints_mm"]), 6))
    qa[:, vj.RACK_JOINT] = np.repeat(rp["joints_mm"], 2) + np.tile([-1e-6, 1e-6], len(rp["joints_mm"]))
    e = rp["amp"] @ vj.rack_signals(rp, qa)
    assert np.diff(e)[::2] == pytest.approx(rp["gaps_mm"], abs=1e-6)
    # carrier: one state per block, alternating; on jacks the wheel columns vanish and the other way round
    jk = P["stabilizer_jacks"]
    b = block_index(s)
    assert all(len(set(jk["jacks"][b == k])) == 1 for k in set(b)) and (np.diff(jk["pattern"].astype(int)) != 0).all()
    F = vb.jacks_features(jk, ctx, case.truth["hw"])
    assert not F[:2][:, jk["jacks"] == 1].any() and not F[2:][:, jk["jacks"] == 0].any()
    # self-levelling: level at each block's first pose
    lv = P["self_leveling"]
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    assert not vb.level_moment(lv, ctx)[first].any()
    assert not vb.level_features(lv, ctx, case.truth["hw"])[:, first].any()
    # bolts: ln(1 + n / n0), nothing lost at the first move; the sag across the boom and downwards
    bp = P["bolt_loosening"]
    assert vb.bolt_count(bp, s) == pytest.approx(np.log(1 + np.arange(len(s.q)) / bp["n0"]))
    sag = vb.bolt_sag(bp, ctx)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    assert np.abs(np.einsum("pi,pi->p", sag, Rt[:, :, 0])).max() < 1e-9 and (sag[:, 2] <= 1e-12).all()
    # moisture: Fick's early-time uptake (4 / h) sqrt(D t / pi), the growth along the boom's axis
    mp = P["moisture_swell"]
    t = s.time_s - s.time_s[0] + mp["t_out_s"]
    uptake = 4 / mp["h_m"] * np.sqrt(mp["D"] * t / np.pi)
    assert uptake.max() < 0.6                                              # the early-time law's range
    strain = mp["a"] * vb.moist_root(mp, s)
    assert strain == pytest.approx(mp["beta"] * mp["M_inf"] * uptake)
    # restrained bar: stable (|r| < 1), and the bow doubles at half the critical rise (delta0 r / (1 - r) at r = 1/2)
    rb = P["restrained_bar"]
    r = vt.bar_ratio(rb, s)
    assert np.abs(r).max() < 1 / 1.5 + 1e-12
    flat = replace(s, air=dict(s.air, drift_K=0.0, cycle_K=0.0))
    half = dict(rb, T_off=-rb["dT_cr"] / 2)
    assert vt.bar_features(half, replace(ctx, session=flat), None)[0] == pytest.approx(Rt[:, :, 0], rel=1e-6)
    # slab: the base's own point sinks by kappa D^2 / 2 and turns about the horizontal axis across the line
    cu = P["slab_curl"]
    dT = vt.air_lag(s, cu["tau_s"])
    n = np.cross([0.0, 0.0, 1.0], cu["e"])
    Fc = vt.curl_features(cu, ctx, None)[0]
    assert Fc + cu["D_m"] * dT[:, None] * np.cross(n, ctx.target) == pytest.approx(
        -1000.0 * cu["D_m"] ** 2 / 2 * dT[:, None] * np.array([0.0, 0.0, 1.0]), abs=1e-9)
    assert abs(n[2]) < 1e-12 and abs(n @ cu["e"]) < 1e-12


# ---------------------------------------------------------------------------------------------------------- set W
def test_set_w_cases_kinds_and_determinism():
    """Set W: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time (the
    step kinds at random); a case regenerates bit-identically from its seed; the session hook leaves cases without a
    set-W kind alone (no random numbers drawn) and the probe hook draws none; the generator reaches the set's modules and
    none imports tolalloc; the grout's long day and the production between the blocks."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_w as ew

    _assert_set_module("W", 40_7023, ew, ("gear", "slab_curl"))
    for name in ("effects_w", "effects_w_joint", "effects_w_body", "effects_w_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_w" in _imports(STUDY / "generator.py")
    assert ew.AFTER_TRACKER == set()
    steps = {"hub_slip", "emi_counts", "bent_bracket"}
    assert all(c[4] == "random" for c in cs.SET_W if set(c[2]) & steps)
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ew.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        for kind in ("young_grout", "air_stratification"):
            long = opts((kind,))
            assert 5 <= long["blocks"] <= 8 and long["gap_kind"] == "pause" and long["pause_min"] == (30.0, 90.0)
        for kind, (lo, hi) in ew.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        assert opts(("rail_trolley", "stable_probe", "part_slide", "cracked_plinth", "air_bellows")) == {
            "blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ew.probe_hook(("gear",), probe) is probe
    assert ew.probe_hook(("cooling_part",), probe) == pytest.approx(probe + [300.0, 0, 0])
    _assert_regenerates("W", max_effect_poses=50)


def test_set_w_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-W kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect on every arm; and known answers: the chips' weight turns no vertical axis and weighs
    nothing before the first machining, the trolley's pull has no part along its rail, the creep left at the stable-probe
    trigger moves eps in the window, the part's stop downhill, the hub's step, the encoders' whole counts, the crack
    opening with the moment, ACI 209's strength law, the compressor's saw-tooth, the bracket's step, the part's lumped
    cooling and the links' mid heights."""
    from sim2real_indep import effects_w_body as wb
    from sim2real_indep import effects_w_joint as wj
    from sim2real_indep import effects_w_thermal as wt
    from sim2real_indep.effects_u_joint import block_index

    every = ("swarf_shroud", "rail_trolley", "stable_probe", "part_slide", "hub_slip", "emi_counts", "cracked_plinth",
             "young_grout", "air_bellows", "bent_bracket", "cooling_part", "air_stratification")
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 23)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"swarf_shroud": lambda: [p["rate"]], "rail_trolley": lambda: [p["T"]],
                   "stable_probe": lambda: [p["lag"]], "part_slide": lambda: [p["c_mm"] / 2],
                   "hub_slip": lambda: p["slip"], "emi_counts": lambda: p["offset"].ravel(),
                   "cracked_plinth": lambda: p["c"], "young_grout": lambda: p["c"], "air_bellows": lambda: p["a"],
                   "bent_bracket": lambda: p["d_mm"], "cooling_part": lambda: [p["dT0"]],
                   "air_stratification": lambda: [p["G"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    # swarf: the chips' weight turns no vertical axis (ur10's axis 1) and nothing is collected before the first gap
    tw = wj.swarf_twist(P["swarf_shroud"], ctx, hw)
    assert np.abs(tw[:, 0]).max() < 1e-12 * np.abs(tw).max()
    assert not wj.swarf_features(P["swarf_shroud"], ctx, hw)[0][b == 0].any()
    assert wj.machining_s(s)[-1] == pytest.approx(s.gap_s[s.gap_s > 0].sum())
    # trolley: a unit pull across the rail, upwards towards it
    tp = P["rail_trolley"]
    pull = wj.trolley_pull(tp, ctx)
    assert np.abs(pull @ tp["e"]).max() < 1e-12 and np.linalg.norm(pull, axis=1) == pytest.approx(1.0)
    assert (pull[:, 2] > 0).all()
    # stable probe: the creep e0 exp(-t / tau) left at the trigger moves eps within the window; unit approaches
    sp = P["stable_probe"]
    assert sp["lag"] * (1 - np.exp(-sp["dt_w"] / sp["tau"])) == pytest.approx(sp["eps"])
    u = wj.approach(ctx)
    assert not u[0].any() and np.linalg.norm(u[1:], axis=1) == pytest.approx(1.0)
    # part slide: downhill where the weight beats friction
    sl = P["part_slide"]
    side = wj.slide_side(sl, ctx)
    x = kin.flange(ctx.chain, ctx.q)[1][:, :, 0]
    steep = np.abs(x[:, 2]) > sl["mu"]
    assert side[steep] == pytest.approx(-np.sign(x[steep, 2])) and set(side) <= {-1.0, 1.0}
    # hub slip: a step inside the session, blocks before and after
    hp = P["hub_slip"]
    step = wj.hub_step(hp, s)
    assert 2 <= hp["block"] <= b.max() - 1 and not step[b < hp["block"]].any() and step[b >= hp["block"]].all()
    assert np.rad2deg(np.abs(hp["slip"])).min() >= 0.008
    # EMI: whole counts of 2^16 per turn, the running sum; block 0 untouched
    ep = P["emi_counts"]
    assert ep["counts"] == pytest.approx(np.rint(ep["counts"]))
    assert ep["offset"] == pytest.approx(-np.cumsum(ep["counts"], axis=0) * 2 * np.pi / 2 ** 16)
    assert not wj.emi_apply(ep, ctx, hw).dq[b == 0].any()
    # cracked plinth: open exactly where the moment about the crack's axis is positive, 3-5 times softer open
    cp = P["cracked_plinth"]
    a = np.array([np.cos(cp["psi"]), np.sin(cp["psi"]), 0.0])
    assert (wb.plinth_open(cp, ctx) == (eb.mount_moment(ctx) @ a > 0)).all()
    assert 3.0 <= cp["c"][0] / cp["c"][1] <= 5.0
    F = wb.plinth_features(cp, ctx, hw)
    assert not F[0][~wb.plinth_open(cp, ctx)].any() and not F[1][wb.plinth_open(cp, ctx)].any()
    # young grout: ACI 209's moist-cured law gives the 28-day strength; the compliance falls from 1 through the day
    assert wb.grout_strength(28.0, 4.0, 0.85) == pytest.approx(1.0, abs=0.01)
    fall = wb.grout_fall(P["young_grout"], s)
    assert fall[0] == pytest.approx(1.0) and (np.diff(fall) <= 1e-15).all() and fall[-1] < 1.0
    # bellows: a saw-tooth over the band, continuous at the end of the loading
    bp = P["air_bellows"]
    tt = np.linspace(0, 3 * bp["period_s"], 30001)
    pr = wb.bellows_pressure(bp, tt)
    assert pr.max() == pytest.approx(bp["band_bar"] / 2, rel=1e-3) and pr.min() == pytest.approx(-bp["band_bar"] / 2,
                                                                                                 rel=1e-3)
    assert np.abs(np.diff(pr)).max() < 1e-3 * bp["band_bar"] * 10
    # bent bracket: the target off by |d| from the collision's block on
    bb = P["bent_bracket"]
    Fb = np.einsum("k,kpi->pi", bb["d_mm"], wb.bracket_features(bb, ctx, hw))
    after = b >= bb["block"]
    assert np.linalg.norm(Fb[after], axis=1) == pytest.approx(np.linalg.norm(bb["d_mm"])) and not Fb[~after].any()
    # cooling part: lumped cooling, exp(-dt / tau) between the poses of a block
    cpp = P["cooling_part"]
    dec = wt.part_decay(cpp, s)
    same = np.r_[False, np.diff(b) == 0]
    ratio = dec[same] / dec[np.flatnonzero(same) - 1]
    assert ratio == pytest.approx(np.exp(-np.diff(s.time_s)[same[1:]] / cpp["tau_s"]))
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    assert dec[first] == pytest.approx(np.exp(-(s.move_s + s.dwell_s + cpp["transfer_s"][b])[first] / cpp["tau_s"]))
    # stratification: at the home pose the links' middles stand at the running sum of the links' heights; the gradient
    # builds up from the lighting, 1 - exp(-t_on / tau) at the first pose
    home = _ctx_at(ctx, np.zeros((1, ctx.chain.n)))
    ch = ctx.chain
    mids = (np.cumsum(ch.links, axis=0) - ch.links / 2)[:, 2] / 1000.0
    assert wt.link_heights(home)[0] == pytest.approx(mids)
    st = P["air_stratification"]
    grow = wt.strat_growth(st, s)
    assert grow[0] == pytest.approx(1 - np.exp(-st["t_on_s"] / st["tau_s"])) and (np.diff(grow) >= 0).all()
    assert wt.strat_strain(st, ctx, hw) == pytest.approx(
        hw["material"]["cte"] * (wt.link_heights(ctx) - st["z_s_m"]) * grow[:, None])


def _ctx_at(ctx, q):
    """``ctx`` at the joint values ``q`` (a session of those poses), for known answers at chosen poses."""
    from dataclasses import replace

    n = len(q)
    s = replace(ctx.session, q=q, time_s=np.zeros(n), direction=np.ones_like(q), payload_kg=np.zeros(n),
                air_c=np.zeros(n), speed=np.zeros_like(q), move_s=np.zeros(n), dwell_s=np.zeros(n), gap_s=np.zeros(n))
    return replace(ctx, chain=replace(ctx.chain, q_offset=np.zeros(ctx.chain.n)), session=s)


# ---------------------------------------------------------------------------------------------------------- set X
def test_set_x_cases_kinds_and_determinism():
    """Set X: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time (the
    collision's step at random); a case regenerates bit-identically from its seed; the session hook leaves cases without
    a set-X kind alone (no random numbers drawn) and the probe hook draws none; the generator reaches the set's modules
    and none imports tolalloc; the production, the sanitation pauses and a new part for each block."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_x as ex

    _assert_set_module("X", 40_7024, ex, ("gear", "air_stratification"))
    for name in ("effects_x", "effects_x_joint", "effects_x_body", "effects_x_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_x" in _imports(STUDY / "generator.py")
    assert ex.AFTER_TRACKER == set()
    assert all(c[4] == "random" for c in cs.SET_X if "collision_shift" in c[2])
    assert all(c[1] == "tool_changer" for c in cs.SET_X if "cosine_error" in c[2])   # needs a prismatic joint
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ex.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        for kind, (lo, hi) in ex.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        wash = opts(("washdown",))
        assert 4 <= wash["blocks"] < 7 and wash["gap_kind"] == "pause" and wash["pause_min"] == (15.0, 40.0)
        for kind, kg in ex.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 2 <= part["blocks"] <= 4 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("magnet_fanner", "support_arm", "ring_lobing", "cosine_error"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ex.probe_hook(("gear",), probe) is probe
    assert ex.probe_hook(("printed_fingers",), probe) == pytest.approx(probe + [0, 0, 80.0])
    assert ex.probe_hook(("suction_cup",), probe) == pytest.approx(probe + [0, 0, 60.0])
    _assert_regenerates("X", max_effect_poses=50)


def test_set_x_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-X kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect on every arm (the cosine error on tool_changer, inert elsewhere); and known answers:
    the pole's inverse-cube pull, the support arm's vertical lift, the track's flank per block, the run-in curve and the
    trailing flank of an unloaded axis, the ring's three lobes, the cosine error, the collision's step and turn, the
    foot lowering its own corner only, the fingers' design sag and creep, the cup's moment across its axis, the
    wash-down's lumped cooling and the stray field's first-order heating."""
    from dataclasses import replace

    from sim2real_indep import effects_x_body as xb
    from sim2real_indep import effects_x_joint as xj
    from sim2real_indep import effects_x_thermal as xt
    from sim2real_indep.effects_u_joint import block_index
    from sim2real_indep.effects_w_joint import machining_s

    every = ("magnet_fanner", "support_arm", "track_lash", "run_in_wear", "ring_lobing", "cosine_error",
             "collision_shift", "levelling_foot", "printed_fingers", "suction_cup", "washdown", "induction_stray")
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 24)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        cte = case.truth["hw"]["material"]["cte"]
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            if kind == "cosine_error" and robot != "tool_changer":
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0
                continue
            amp = {"magnet_fanner": lambda: [p["F_ref"]], "support_arm": lambda: [p["F0"], p["k"]],
                   "track_lash": lambda: [p["c_mm"] / 2], "run_in_wear": lambda: p["b_r"] / 2,
                   "ring_lobing": lambda: p["amp"], "cosine_error": lambda: [p["kappa"]],
                   "collision_shift": lambda: p["amp"], "levelling_foot": lambda: [p["rate"]],
                   "printed_fingers": lambda: p["amp"], "suction_cup": lambda: [p["c"]],
                   "washdown": lambda: cte * p["dT0"], "induction_stray": lambda: [cte * p["dT_ss"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    # magnet: unit pull at r_ref from a point pole, an eighth of it at twice the distance, towards the pole
    pole = dict(P["magnet_fanner"], face_mm=0.0)
    pts = pole["pole_mm"] + np.array([[xj.FANNER_REF_MM, 0, 0], [0, 2 * xj.FANNER_REF_MM, 0]])
    law = xj.fanner_law(pole, pts)
    assert np.linalg.norm(law, axis=1) == pytest.approx([1.0, 1 / 8]) and law[0] == pytest.approx([-1.0, 0, 0])
    # support arm: a vertical force turns no vertical axis (ur10's axis 1); the rate's column is F0's times the height
    sp = P["support_arm"]
    tw = xj.support_twists(sp, ctx, hw)
    assert np.abs(tw[0][:, 0]).max() < 1e-12 * np.abs(tw[0]).max()
    z = kin.flange(ctx.chain, ctx.q)[0][:, 2]
    assert tw[1] == pytest.approx(tw[0] * ((z - sp["z0_mm"]) / 1000.0)[:, None])
    # track lash: one side per block, both sides in the session, along the rail
    tl = P["track_lash"]
    F = xj.track_features(tl, ctx, hw)[0]
    assert set(tl["sides"]) == {-1.0, 1.0} and np.abs(F @ tl["e"]) == pytest.approx(1.0)
    # run-in: nothing before the first production, the running-in curve after; axis 1 (no gravity torque) trails
    wp = P["run_in_wear"]
    g = xj.wear_growth(wp, s)
    assert not g[b == 0].any() and g == pytest.approx(1 - np.exp(-machining_s(s) / wp["tau_s"]))
    assert xj.wear_sides(wp, ctx)[:, 0] == pytest.approx(-s.direction[:, 0])
    # ring lobing: a / (3 R), three-fold symmetric
    lp = P["ring_lobing"]
    assert lp["A"] == pytest.approx(lp["a_mm"] / (3 * lp["R_mm"]))
    q3 = replace(ctx, session=replace(s, q=s.q + np.r_[2 * np.pi / 3, np.zeros(5)]))
    assert xj.lobing_apply(lp, q3, hw).dq[:, 0] == pytest.approx(xj.lobing_apply(lp, ctx, hw).dq[:, 0])
    # cosine error on tool_changer's telescopic stage: q4 (1 / cos beta - 1)
    tc, tctx = runs["tool_changer"]
    cp = tc.truth["params"]["cosine_error"]
    assert cp["joints"] == (3,) and cp["kappa"] == pytest.approx(1 / np.cos(cp["beta"]) - 1)
    assert xj.cosine_apply(cp, tctx, tc.truth["hw"]).dq[:, 3] == pytest.approx(cp["kappa"] * tctx.q[:, 3])
    # collision: a step inside the session; the turn moves the target across its radius
    cs_ = P["collision_shift"]
    st = xb.collision_step(cs_, s)
    assert 2 <= cs_["block"] <= b.max() - 1 and not st[b < cs_["block"]].any() and st[b >= cs_["block"]].all()
    turn = xb.collision_features(cs_, ctx, hw)[2]
    assert np.abs(np.einsum("pi,pi->p", turn, ctx.target)).max() < 1e-9
    # levelling foot: a unit drop lowers foot 0 by 1 mm and leaves the others where they are
    fp = P["levelling_foot"]
    f, e, pt, d = xb.foot_geometry(fp)
    mv = np.cross(e, f - pt) / d
    assert mv[0, 2] == pytest.approx(-1.0) and np.abs(mv[1:]).max() < 1e-12
    # fingers: the heaviest part across the fingers sags them by the design sag; the grip's age grows in a block
    fg = P["printed_fingers"]
    assert fg["amp"][0] * kin.G * s.payload_kg.max() == pytest.approx(fg["sag_mm"])
    age = xb.grip_age_h(s)
    same = np.r_[False, np.diff(b) == 0]
    assert (age > 0).all() and (np.diff(age)[same[1:]] > 0).all()
    assert np.abs(np.einsum("pi,pi->p", xb.finger_weight(ctx), kin.flange(ctx.chain, ctx.q)[1][:, :, 2])).max() < 1e-9
    # suction cup: the moment lies across the cup's axis
    M, _ = xb.cup_moment(P["suction_cup"], ctx)
    assert np.abs(np.einsum("pi,pi->p", M, kin.flange(ctx.chain, ctx.q)[1][:, :, 2])).max() < 1e-9
    # wash-down: lumped cooling, exp(-dt / tau) between the poses of a block, from each rinse's own dT0
    wd = P["washdown"]
    assert len(wd["dT0"]) == b.max() + 1 and 10.0 <= wd["dT0"].min() and wd["dT0"].max() <= 25.0
    dec = xt.wash_decay(wd, s)
    ratio = dec[same] / dec[np.flatnonzero(same) - 1]
    assert ratio == pytest.approx(np.exp(-np.diff(s.time_s)[same[1:]] / wd["tau_s"])) and (dec < 1).all()
    # stray field: cold before the first production, heated towards 1 across each exercise gap; ur10's forearm is a3
    sf = P["induction_stray"]
    T = xt.stray_temperature(sf, s)
    assert not T[b == 0].any() and (T < 1).all() and (T[s.gap_s > 0] > T[np.flatnonzero(s.gap_s > 0) - 1]).all()
    assert [n for n, m in zip(ctx.chain.link_names, xt.forearm_mask(ctx.chain)) if m] == ["a3"]


# ---------------------------------------------------------------------------------------------------------- set Y
def test_set_y_cases_kinds_and_determinism():
    """Set Y: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time; a
    case regenerates bit-identically from its seed; the session hook leaves cases without a set-Y kind alone (no random
    numbers drawn) and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; the
    production, the pauses and a new part for each block."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_y as ey

    _assert_set_module("Y", 40_7025, ey, ("gear", "induction_stray"))
    for name in ("effects_y", "effects_y_joint", "effects_y_body", "effects_y_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_y" in _imports(STUDY / "generator.py")
    assert ey.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ey.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        for kind, (lo, hi) in ey.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        for kind, ((lo, hi), pause) in ey.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, kg in ey.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 2 <= part["blocks"] <= 4 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("coupling_play", "squeeze_film", "pinion_runout", "torque_arm"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ey.probe_hook(("gear",), probe) is probe
    assert ey.probe_hook(("foam_gripper",), probe) == pytest.approx(probe + [0, 0, 50.0])
    assert ey.probe_hook(("sheet_part",), probe) == pytest.approx(probe + [400.0, 0, 0])
    _assert_regenerates("Y", max_effect_poses=50)


def test_set_y_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-Y kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect on every arm; and known answers: the frost's share by length and its linear growth,
    the brakes' give in the braked blocks only, the coupling play driving the joint along
    its motion, the lash crossed through the grease by the dwell's end, the pinion's period, the torque arms' error
    following the joints before the axis, the base's walk and
    turn, the leaking tyre's exponential sink at its own corner, the foam's normal and shear split and design sag, the
    panel's bending across its thickness, the lamp's first-order warming in the lit blocks and the thermal bows."""
    from dataclasses import replace

    from sim2real_indep import effects_y_body as yb
    from sim2real_indep import effects_y_joint as yj
    from sim2real_indep import effects_y_thermal as yt
    from sim2real_indep.effects_s_joint import compliance
    from sim2real_indep.effects_u_joint import block_index
    from sim2real_indep.effects_w_joint import machining_s
    from sim2real_indep.effects_x_body import foot_geometry

    every = ("frost_load", "output_brake", "coupling_play", "squeeze_film", "pinion_runout", "torque_arm",
             "press_walk", "tyre_leak", "foam_gripper", "sheet_part", "vision_lamp", "cabinet_exhaust")
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 25)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"frost_load": lambda: [p["rate_kg_h"]], "output_brake": lambda: p["c_b"],
                   "coupling_play": lambda: p["play"] / 2, "squeeze_film": lambda: p["b"] / 2,
                   "pinion_runout": lambda: p["amp"], "torque_arm": lambda: p["amp"], "press_walk": lambda: p["amp"],
                   "tyre_leak": lambda: [p["delta0"]], "foam_gripper": lambda: [p["c"]], "sheet_part": lambda: [p["c"]],
                   "vision_lamp": lambda: p["amp"], "cabinet_exhaust": lambda: p["amp"]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    same = np.r_[False, np.diff(b) == 0]
    # frost: shares by link length, nothing at the first pose, growing with the hours; a vertical axis 1 feels none
    share = yj.frost_shares(ctx)
    L = np.linalg.norm(ctx.chain.links, axis=1)
    assert share.sum() == pytest.approx(1.0) and share == pytest.approx(L / L.sum())     # ur10: a mass on every link
    h = yj.frost_hours(s)
    assert h[0] == 0.0 and (np.diff(h) > 0).all()
    tw = yj.frost_twist(ctx, hw)
    assert np.abs(tw[:, 0]).max() < 1e-9 * np.abs(tw).max()
    # output brake: the brakes' give in the braked blocks only (both kinds of block present), proportional to the load
    bp = P["output_brake"]
    on = bp["braked"][b]
    assert set(bp["braked"]) == {0.0, 1.0} and bp["joints"] == (1, 2)
    assert (bp["c_b"] <= 0.5 * compliance(hw)[[1, 2]]).all()
    assert yj.brake_signal(bp, ctx) == pytest.approx(ctx.loads[:, [1, 2]] * on[:, None])
    # coupling play: the joint driven past its target along its last motion
    cp = P["coupling_play"]
    dq = yj.play_apply(cp, ctx, hw).dq
    assert dq[:, :3] == pytest.approx(cp["play"] / 2 * s.direction[:, :3]) and not dq[:, 3:].any()
    # squeeze film: stopped on the trailing flank, on the way to the load's flank by exp(-dwell / tau); where the two
    # agree the output sits on that flank
    fp_ = P["squeeze_film"]
    s0, sg = yj.film_sides(fp_, ctx)
    sig = yj.film_signal(fp_, ctx)
    assert fp_["joints"] == (1, 2) and s0 == pytest.approx(-s.direction[:, [1, 2]])
    agree = s0 == sg
    assert sig[agree] == pytest.approx(s0[agree]) and (~agree).any() and (np.abs(sig[~agree]) < 1).all()
    left = (sig - sg)[~agree] / (s0 - sg)[~agree]                        # the share of the crossing still to go
    assert left == pytest.approx(np.exp(-s.dwell_s[:, None] / fp_["tau_s"])[~agree])
    # pinion runout: e / R, repeating every 1 / i of a turn
    pp = P["pinion_runout"]
    assert pp["A"] == pytest.approx(pp["e_mm"] / pp["R_mm"]) and pp["i"] == pytest.approx(pp["Zr"] / pp["Zp"])
    shift = replace(ctx, session=replace(s, q=s.q + np.r_[2 * np.pi / pp["i"], np.zeros(5)]))
    assert yj.pinion_apply(pp, shift, hw).dq[:, 0] == pytest.approx(yj.pinion_apply(pp, ctx, hw).dq[:, 0])
    # torque arm: the encoder's weight turns its stator by A at most; axis 3's error follows q2, not q3 (ur10)
    ap = P["torque_arm"]
    assert ap["joints"] == (2, 3, 4) and ap["A"] == pytest.approx(ap["m_kg"] * kin.G * ap["r_m"] / ap["k_Nm_rad"])
    sig = yj.arm_signal(ap, ctx)
    assert (np.abs(sig) <= 1 + 1e-12).all()
    turn3 = replace(ctx, session=replace(s, q=s.q + np.r_[0.0, 0.0, 0.7, 0.0, 0.0, 0.0]))
    turn2 = replace(ctx, session=replace(s, q=s.q + np.r_[0.0, 0.7, 0.0, 0.0, 0.0, 0.0]))
    assert yj.arm_signal(ap, turn3)[:, 0] == pytest.approx(sig[:, 0])
    assert np.abs(yj.arm_signal(ap, turn2)[:, 0] - sig[:, 0]).max() > 0.1
    # press walk: nothing before the first production, then the production hours; the turn moves across the radius
    wf = yb.walk_features(P["press_walk"], ctx, hw)
    E = machining_s(s) / 3600.0
    assert not wf[:, b == 0].any() and wf[0][:, 0] == pytest.approx(E)
    assert np.abs(np.einsum("pi,pi->p", wf[2], ctx.target)).max() < 1e-9
    # tyre leak: delta0 (exp(t / tau) - 1) at the leaking wheel, which alone sinks
    tp = P["tyre_leak"]
    g = yb.leak_growth(tp, s)
    assert g[0] == 0.0 and g == pytest.approx(np.expm1((s.time_s - s.time_s[0]) / tp["tau_s"]))
    f, e, pt, d = foot_geometry(tp)
    mv = np.cross(e, f - pt) / d
    assert mv[0, 2] == pytest.approx(-1.0) and np.abs(mv[1:]).max() < 1e-12
    # foam: the weight's normal part along the pad's axis, its shear part E / G = 2 (1 + nu) times; the design sag
    fp = P["foam_gripper"]
    z = kin.flange(ctx.chain, ctx.q)[1][:, :, 2]
    W = np.zeros((len(z), 3))
    W[:, 2] = -kin.G * s.payload_kg
    Wz = np.einsum("pi,pi->p", W, z)
    fl = yb.foam_load(fp, ctx)
    assert np.einsum("pi,pi->p", fl, z) == pytest.approx(Wz)
    assert fl - Wz[:, None] * z == pytest.approx(2 * (1 + fp["nu"]) * (W - Wz[:, None] * z))
    assert fp["c"] * kin.G * s.payload_kg.max() == pytest.approx(fp["sag_mm"])
    # sheet: only the weight across the panel (the tool's y) bends it, along that axis
    sp = P["sheet_part"]
    y = kin.flange(ctx.chain, ctx.q)[1][:, :, 1]
    assert yb.sheet_load(ctx) == pytest.approx(np.einsum("pi,pi->p", W, y)[:, None] * y)
    assert sp["c"] * kin.G * s.payload_kg.max() == pytest.approx(sp["sag_mm"])
    # vision lamp: every second block lit, first-order warming towards 1 lit and cooling dark; ur10's upper arm is a2
    vp = P["vision_lamp"]
    on = yt.lamp_on(vp, s)
    assert set(on[b % 2 == vp["parity"]]) == {1.0} and not on[b % 2 != vp["parity"]].any()
    T = yt.lamp_temperature(vp, s)
    k = np.flatnonzero(same)
    decay = np.exp(-np.diff(s.time_s)[k - 1] / vp["tau_s"])
    assert (on[k] - T[k]) == pytest.approx((on[k] - T[k - 1]) * decay) and (T < 1).all() and (T >= 0).all()
    assert ctx.chain.link_names[yt.upper_arm(ctx.chain)] == "a2"
    # the bow turns about an axis across the link: no displacement along that axis
    li = yt.upper_arm(ctx.chain)
    side = yt.lamp_side(ctx.chain, li, vp["psi"])
    a = np.cross(side, ctx.chain.links[li] / np.linalg.norm(ctx.chain.links[li]))
    R = kin.body_transforms(ctx.chain, ctx.q)[0][:, 2]
    assert np.abs(np.einsum("pi,pi->p", yt.link_bow(ctx, li, side), R @ a)).max() < 1e-9
    # cabinet exhaust: cold until the first production, heated in the gaps; the bow turns about the horizontal axis
    # across the cabinet's heading, the rise is vertical
    xp = P["cabinet_exhaust"]
    xf = yt.exhaust_features(xp, ctx, hw)
    hd = np.array([np.cos(xp["psi"]), np.sin(xp["psi"]), 0.0])
    assert not xf[:, b == 0].any() and np.abs(xf[0][:, :2]).max() == 0.0
    assert np.abs(xf[1] @ np.cross(hd, [0, 0, 1.0])).max() < 1e-9


# ---------------------------------------------------------------------------------------------------------- set Z
def test_set_z_cases_kinds_and_determinism():
    """Set Z: 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark and registered in the
    generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a quarter split by time; a
    case regenerates bit-identically from its seed; the session hook leaves cases without a set-Z kind alone (no random
    numbers drawn) and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; the
    drifting hall, the pauses, the production and a new part for each block."""
    from sim2real_indep import effects_z as ez

    _assert_set_module("Z", 40_7026, ez, ("gear", "cabinet_exhaust"))
    for name in ("effects_z", "effects_z_joint", "effects_z_body", "effects_z_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
    assert "sim2real_indep.effects_z" in _imports(STUDY / "generator.py")
    assert ez.AFTER_TRACKER == {"tripod_windup"} and "tripod_windup" in gen.AFTER_TRACKER
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ez.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                   {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause, (d_lo, d_hi)) in ez.AIR.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
            assert d_lo <= abs(b["air"]["drift_K"]) <= d_hi
        for kind, ((lo, hi), pause) in ez.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, (lo, hi) in ez.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        for kind, kg in ez.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("water_slug", "balancer_seal", "tripod_windup", "band_spiral", "oil_canning", "bowstring"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ez.probe_hook(("gear",), probe) is probe
    assert ez.probe_hook(("water_slug",), probe) == pytest.approx(probe + [350.0, 0, 0])
    assert ez.probe_hook(("stress_relief",), probe) == pytest.approx(probe + [300.0, 0, 0])
    _assert_regenerates("Z", max_effect_poses=50)


def test_set_z_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-Z kind's displacement is its true-structure features times its true amplitudes (what the oracle fits),
    to rounding, and a real effect on every arm (the band drive only where the arm has its telescopic stage); and known
    answers: the water at the boom's lower end, the balancer's dead centre at the upright arm, its gas law and its
    opposing gravity, the seal holding axis 2 back against its last motion, the tracker turned about its vertical by
    its last slew, the spiral band's error vanishing at both stroke ends, the encoder's largest misreading, the
    isolators' compliance at 20 degC, the plate's play operator, the harness' tension, the frame's relaxation across
    its arm from the first production on, the plate's curl decaying and the duct's bow from the two sides' lags."""
    from sim2real_indep import effects_z_body as zb
    from sim2real_indep import effects_z_joint as zj
    from sim2real_indep import effects_z_thermal as zt
    from sim2real_indep.effects_body import mount_moment
    from sim2real_indep.effects_s_joint import compliance
    from sim2real_indep.effects_u_joint import block_index
    from sim2real_indep.effects_y_thermal import STEEL_CTE, upper_arm

    every = ("water_slug", "balancer_gas", "balancer_seal", "tripod_windup", "band_spiral", "head_tilt",
             "warm_isolators", "oil_canning", "bowstring", "stress_relief", "floor_heating", "duct_lag")
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 26)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            if kind == "band_spiral" and robot != "tool_changer":             # no telescopic stage: inert
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0 and not p["active"]
                continue
            amp = {"water_slug": lambda: [p["kg"]], "balancer_gas": lambda: [p["F20_N"]],
                   "balancer_seal": lambda: [p["Fs_N"]], "tripod_windup": lambda: [p["w_rad"]],
                   "band_spiral": lambda: [p["k"]], "head_tilt": lambda: [p["amp"]],
                   "warm_isolators": lambda: [p["c20"], p["c20"] * p["beta"]], "oil_canning": lambda: [p["turn"]],
                   "bowstring": lambda: [p["kappa"]], "stress_relief": lambda: p["amp"],
                   "floor_heating": lambda: [p["turn"]], "duct_lag": lambda: p["amp"]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    C = compliance(hw)
    # water slug: at the root end of the boom when its tip points up, at the tip when it points down
    wp = P["water_slug"]
    pf, Rt = kin.flange(ctx.chain, ctx.q)
    x = Rt[:, :, 0]
    along = np.einsum("pi,pi->p", zj.slug_position(wp, ctx) - pf, x)
    up, down = x[:, 2] > zj.RAMP, x[:, 2] < -zj.RAMP
    assert up.any() and down.any()
    assert along[up] == pytest.approx(np.full(up.sum(), zj.BOOM_MM * wp["puddle"] / 2))
    assert along[down] == pytest.approx(np.full(down.sum(), zj.BOOM_MM * (1 - wp["puddle"] / 2)))
    # balancer: no moment arm at the upright arm; it opposes gravity and carries share of the largest load at 20 degC
    gp = P["balancer_gas"]
    arm, _ = zj.balancer_arm(gp, ctx)
    psi = zj.upright_angle(ctx)
    assert np.sign(arm) == pytest.approx(np.sign(np.sin(psi)))
    tb = zj.balancer_torque(gp, ctx)
    assert np.dot(tb, ctx.loads[:, 1]) < 0
    assert gp["F20_N"] * np.abs(tb).max() == pytest.approx(gp["share"] * np.abs(ctx.loads[:, 1]).max(), rel=1e-3)
    Tg = zj.gas_temperature(gp, s)
    assert zj.gas_signal(gp, ctx, hw) == pytest.approx(C[1] * tb * (Tg - 20.0) / 293.15)
    assert Tg[0] == pytest.approx(s.air_c[0])
    # balancer seal: axis 2 held back against its last motion
    sp = P["balancer_seal"]
    dq2 = zj.seal_apply(sp, ctx, hw).dq
    assert not np.delete(dq2, 1, axis=1).any()
    moved = np.abs(zj.balancer_arm(sp, ctx)[0]) > 1e-6
    assert (np.sign(dq2[moved, 1]) == -s.direction[moved, 1]).all()
    # tripod windup: a turn about the tracker's vertical through it, by the sign of the last azimuth slew
    tp = P["tripod_windup"]
    tr = hw["tracker"]
    F = zj.windup_features(tp, ctx, hw)[0]
    zT = tr["R"].T @ [0.0, 0.0, 1.0]
    assert np.abs(F @ zT).max() < 1e-9
    pt = ctx.target @ tr["R"].T + tr["t"]
    az = np.unwrap(np.arctan2(pt[:, 1], pt[:, 0]))
    sg = zj.slew_sign(tp, ctx, hw)
    assert sg[0] == tp["s0"] and (sg[1:] == np.sign(np.diff(az))).all()
    assert np.linalg.norm(F, axis=1) == pytest.approx(np.linalg.norm(pt[:, :2], axis=1))
    # band spiral (tool_changer): k = t / (4 pi r0^2), nothing at the stroke's ends, -k S^2 / 4 at its middle
    bc, bctx = runs["tool_changer"]
    bp = bc.truth["params"]["band_spiral"]
    assert bp["active"] and bp["k"] == pytest.approx(bp["t_mm"] / (4 * np.pi * bp["r0_mm"] ** 2))
    q4 = lambda v: type(bctx)(bctx.chain, type(bctx.session)(**{**bctx.session.__dict__,  # noqa: E731
                                                                "q": np.tile([0, 0, 0, v, 0, 0.0], (2, 1))}),
                              bctx.masses, bctx.com, bctx.mass_link, bctx.payload_com_mm, bctx.probe_mm)
    assert not zj.band_apply(bp, q4(0.0), bc.truth["hw"]).dq.any()
    assert np.abs(zj.band_apply(bp, q4(500.0), bc.truth["hw"]).dq).max() < 1e-12
    assert zj.band_apply(bp, q4(250.0), bc.truth["hw"]).dq[0, 3] == pytest.approx(-bp["k"] * 500.0 ** 2 / 4)
    # head tilt: axis 1 alone, misread by err at the session's largest moment along the head's direction
    hp = P["head_tilt"]
    dq = zj.head_apply(hp, ctx, hw).dq
    assert not dq[:, 1:].any()
    assert np.abs(dq[:, 0]).max() == pytest.approx(hp["err_rad"], rel=1e-2)                # drawn on the true arm
    # warm isolators: c_20 at 20 degC, softer by beta per kelvin; the largest tilt as drawn; the base turns about a
    # horizontal axis through the isolators' plane
    ip = P["warm_isolators"]
    fi = zb.iso_features(ip, ctx, hw)
    Ti = zb.iso_temperature(ip, s)
    assert fi[1] == pytest.approx(fi[0] * (Ti - 20.0)[:, None])
    M = mount_moment(ctx)
    assert 0.25e-3 * 0.99 <= ip["c20"] * np.linalg.norm(M[:, :2], axis=1).max() <= 0.6e-3 * 1.01
    rot = np.c_[M[:, :2], np.zeros(len(M))]
    assert np.abs(np.einsum("pi,pi->p", fi[0], rot)).max() < 1e-9 * np.abs(fi[0]).max() * np.abs(rot).max()
    # oil canning: a play operator of the moment about the plate's weak axis, about the mean moment
    cp = P["oil_canning"]
    st = zb.can_state(cp, ctx)
    m = M @ zb.can_axis(cp) - cp["Mc"]
    assert set(st) <= {-1.0, 1.0} and (st[m > cp["Ms"]] == 1).all() and (st[m < -cp["Ms"]] == -1).all()
    inside = np.flatnonzero(np.abs(m) <= cp["Ms"])
    prev = np.r_[cp["s0"], st[:-1]]
    assert (st[inside] == prev[inside]).all() and cp["turn"] == pytest.approx(cp["w_mm"] / cp["b_mm"])
    # bowstring: no tension where the harness runs straight, 1 at the far edge of the range; the elbow's design move
    bw = P["bowstring"]
    T = zb.bow_tension(bw, ctx)
    assert T.min() >= 0 and T.max() == pytest.approx(1.0)
    L = np.linalg.norm(case.truth["chain"].links[upper_arm(ctx.chain)])                     # drawn on the true arm
    assert bw["kappa"] * L ** 2 / 2 == pytest.approx(bw["elbow_mm"])
    # stress relief: nothing before the first production, across the frame's arm (the tool's x) only
    rp = P["stress_relief"]
    fr = zb.relief_features(rp, ctx, hw)
    b = block_index(s)
    assert not fr[:, b == 0].any() and np.abs(fr[:, b > 0]).max() > 0
    assert np.abs(np.einsum("kpi,pi->kp", fr, x)).max() < 1e-12 and not fr[:, 0].any()
    # floor heating: the curl decays by exp(-t / tau) from its value at the first pose, about a horizontal axis
    fp = P["floor_heating"]
    dec = zt.floor_decay(fp, s)
    assert dec[0] == 1.0 and (np.diff(dec) < 0).all()
    assert fp["turn"] == pytest.approx(STEEL_CTE * fp["dT0"] * fp["w_mm"] / (2 * fp["t_mm"]))
    a = np.array([np.cos(fp["psi"]), np.sin(fp["psi"]), 0.0])
    assert np.abs(zt.floor_features(fp, ctx, hw)[0] @ a).max() < 1e-9
    # duct lag: the two sides start at the air, the duct's side lags more; the bow follows their difference
    dp = P["duct_lag"]
    Tf, Ts = zt.duct_temperatures(dp, s)
    assert Tf[0] == Ts[0] == s.air_c[0] and dp["tau_s_s"] > dp["tau_f_s"]
    fd = zt.duct_features(dp, ctx, hw)
    assert not fd[1][0].any() and dp["amp"][1] == pytest.approx(dp["amp"][0] * dp["share"] / dp["D_mm"])


# --------------------------------------------------------------------------------------------------------- set ZA
def test_set_za_cases_kinds_and_determinism():
    """Set ZA (the first two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark
    and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a
    quarter split by time; its name keys the case seeds and sorts after Z; a case regenerates bit-identically from its
    seed; the session hook leaves cases without a set-ZA kind alone (no random numbers drawn) and the probe hook draws
    none; the generator reaches the set's modules and none imports tolalloc; the pauses, the production and a new part
    for each block."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_za as eza

    assert _sorts_after("Z", "ZA")
    assert cs.case_seed("ZA", 3) == 40_7027 * 1000 + 3 and [c[0] for c in cs.SET_ZA] == [f"ZA{i:02d}" for i in
                                                                                          range(1, 25)]
    _assert_set_module("ZA", 40_7027, eza, ("gear", "duct_lag"))
    for name in ("effects_za", "effects_za_joint", "effects_za_body", "effects_za_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_za" in _imports(STUDY / "generator.py")
    assert eza.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": eza.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause) in eza.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, (lo, hi) in eza.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        for kind, kg in eza.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("flank_stiffness", "luff_rope", "guide_drag", "tool_recoil", "scratch_count"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert eza.probe_hook(("gear",), probe) is probe
    assert eza.probe_hook(("offcentre_pick",), probe) == pytest.approx(probe + [250.0, 0, 40.0])
    assert eza.probe_hook(("soft_fingers",), probe) == pytest.approx(probe + [0, 0, 80.0])
    _assert_regenerates("ZA", max_effect_poses=50)


def test_set_za_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZA kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm (the luff rope and the guide drag only on tool_changer, which has
    the boom and the telescopic stage); and known answers: the soft flank's extra twist, the tackle's lever and free
    length, the guides holding the stage back against its last stroke, the mount's recoil along the last move, the
    scale's step at its scratch, the belt's tooth after its block, the slide's extension per block, the thaw's square
    root, the bar's twist across it, the fingers' bend across them and the two heat sources' signs."""
    from sim2real_indep import effects_za_body as zab
    from sim2real_indep import effects_za_joint as zaj
    from sim2real_indep import effects_za_thermal as zat
    from sim2real_indep.effects_s_joint import compliance
    from sim2real_indep.effects_u_joint import block_index

    every = ("flank_stiffness", "luff_rope", "guide_drag", "tool_recoil", "scratch_count", "tooth_skip",
             "slide_overhang", "ground_thaw", "offcentre_pick", "soft_fingers", "ac_jet", "oven_door")
    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, every, 30, 27)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in every:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            if kind in ("luff_rope", "guide_drag") and robot != "tool_changer":    # no boom / stage: inert
                assert A.shape[1] == 0 and np.abs(d).max() == 0.0
                continue
            amp = {"flank_stiffness": lambda: p["amp"], "luff_rope": lambda: [p["inv_nEA"]],
                   "guide_drag": lambda: p["amp"], "tool_recoil": lambda: [p["c"]],
                   "scratch_count": lambda: [p["delta"]], "tooth_skip": lambda: [p["step"]],
                   "slide_overhang": lambda: [p["inv_EI"]], "ground_thaw": lambda: [p["c0"], p["c1"]],
                   "offcentre_pick": lambda: [p["c"]], "soft_fingers": lambda: [p["inv_kp"]],
                   "ac_jet": lambda: p["amp"], "oven_door": lambda: p["amp"]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    C = compliance(hw)
    # flank stiffness: axis 3 alone, c tau on the stiff side, c (1 + r) tau on the soft side (times s)
    fp = P["flank_stiffness"]
    tau = ctx.loads[:, 2]
    want = fp["s"] * C[2] * tau * np.where(np.sign(tau) == fp["soft_sign"], 1 + fp["r"], 1.0)
    got = np.einsum("kpi,k->pi", zaj.flank_features(fp, ctx, hw), fp["amp"])
    assert got == pytest.approx(ctx.joint_feature(2, want), abs=1e-12)
    # scratch: nothing on the first pose's side, delta beyond the scratch
    sp = P["scratch_count"]
    q = ctx.q[:, sp["joint"]]
    sig = zaj.scratch_signal(sp, ctx)
    assert sig[0] == 0 and ((q > sp["q_s"]) != (q[0] > sp["q_s"])).astype(float) == pytest.approx(sig)
    assert 0.4 * zaj.ARCMIN <= abs(sp["delta"]) <= 1.0 * zaj.ARCMIN
    # tooth skip: one tooth of the motor pulley through the reducer, on a wrist axis, from its block on
    kp = P["tooth_skip"]
    b = block_index(s)
    assert abs(kp["step"]) == pytest.approx(2 * np.pi / (kp["Z"] * kp["ratio"])) and kp["joint"] in (3, 4)
    dq = zaj.skip_apply(kp, ctx, hw).dq
    assert not dq[b < kp["block"]].any() and (dq[b >= kp["block"], kp["joint"]] == kp["step"]).all()
    assert not np.delete(dq, kp["joint"], axis=1).any() and b.max() >= kp["block"] >= 1
    # tool recoil: nothing on the first pose, ahead along the end velocity, decaying over the dwell
    rp = P["tool_recoil"]
    r = zaj.recoil_signal(rp, ctx)
    v = np.einsum("pij,pj->pi", ctx.jac, np.diff(np.vstack([ctx.q[:1], ctx.q]), axis=0) / s.move_s.clip(1e-9)[:, None])
    assert not r[0].any() and r[1:] == pytest.approx(v[1:] / zaj.RAMP_S * np.exp(-s.dwell_s[1:] / rp["tau_s"])[:, None])
    # slide overhang: the block's extension; the base turns about the horizontal across the slide
    op = P["slide_overhang"]
    L = zab.slide_length(op, s)
    assert L == pytest.approx(op["L0_m"] + op["ext_m"][np.minimum(b, len(op["ext_m"]) - 1)])
    assert 0.2 <= L.min() and L.max() <= 0.7
    # ground thaw: the thaw's square root of the time since sunrise, 1 at the session's end
    tp = P["ground_thaw"]
    root = zab.thaw_root(tp, s)
    assert root[-1] == pytest.approx(1.0) and (np.diff(root) > 0).all() and root[0] > 0
    ft = zab.thaw_features(tp, ctx, hw)
    assert ft[1] == pytest.approx(ft[0] * root[:, None])
    # off-centre pick: the target turns about the bar (the tool's x): no move along it; none without an offset
    _, Rt = kin.flange(ctx.chain, ctx.q)
    pk = P["offcentre_pick"]
    assert np.abs(np.einsum("pi,pi->p", zab.pick_unit(pk, ctx), Rt[:, :, 0])).max() < 1e-9
    assert not zab.pick_unit({**pk, "e_mm": np.zeros_like(pk["e_mm"])}, ctx).any()
    # soft fingers: bent across them (no move along the tool's z), softer at a lower pressure
    fg = P["soft_fingers"]
    u = zab.finger_unit(fg, ctx)
    assert np.abs(np.einsum("pi,pi->p", u, Rt[:, :, 2])).max() < 1e-9
    low = zab.finger_unit({**fg, "p_kPa": np.full_like(fg["p_kPa"], 20.0)}, ctx)
    high = zab.finger_unit({**fg, "p_kPa": np.full_like(fg["p_kPa"], 120.0)}, ctx)
    loaded = np.linalg.norm(high, axis=1) > 0
    assert (np.linalg.norm(low, axis=1)[loaded] > np.linalg.norm(high, axis=1)[loaded]).all()
    # the AC jet cools (the wall at the hall's air at the start), the oven door heats
    jt, dt = zat.jet_temperature(P["ac_jet"], s), zat.door_temperature(P["oven_door"], s)
    assert jt[0] == 0 and jt.max() <= 0 and jt.min() >= -P["ac_jet"]["dT_K"]
    assert dt[0] == 0 and dt.min() >= 0
    assert zat.forearm(ctx.chain) == 4 and zat.forearm(runs["ur10"][1].chain) == 2
    # luff rope and guide drag (tool_changer): the lever and free length of the tackle; the stage held back
    bc, bctx = runs["tool_changer"]
    lp, gp, bhw = bc.truth["params"]["luff_rope"], bc.truth["params"]["guide_drag"], bc.truth["hw"]
    Lr, lever = zaj.luff_geometry(lp, bctx)
    g = np.arccos((lp["r1_m"] ** 2 + lp["r2_m"] ** 2 - Lr ** 2) / (2 * lp["r1_m"] * lp["r2_m"]))
    assert lever == pytest.approx(lp["r1_m"] * lp["r2_m"] * np.sin(g) / Lr)
    assert zaj.luff_signal(lp, bctx) == pytest.approx(bctx.loads[:, 1] * Lr / lever ** 2)
    dq4 = zaj.guide_features(gp, bctx, bhw)
    load = zaj.guide_load(gp, bctx)
    assert load.max() == pytest.approx(1.0) and load.min() >= 0 and sum(gp["amp"]) == pytest.approx(gp["w_mm"])
    step = bctx.jac[:, :, 3]
    along = np.einsum("kpi,pi->kp", dq4, step) / np.einsum("pi,pi->p", step, step)
    assert along[0] == pytest.approx(-bctx.session.direction[:, 3]) and along[1] == pytest.approx(along[0] * load)


# --------------------------------------------------------------------------------------------------------- set ZB
ZB_KINDS = ("impedance_preset", "hose_wrap", "pawl_notch", "reversal_pulse", "nonius_slip", "fieldbus_rounding",
            "mecanum_base", "grout_void", "insulating_flange", "stay_cable", "air_knife", "sonotrode")


def test_set_zb_cases_kinds_and_determinism():
    """Set ZB (the second two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZA; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZB kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; the
    pauses, the production, a new part for each block and the torch as the payload."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zb as ezb
    from sim2real_indep import effects_zb_body as zbb

    assert _sorts_after("ZA", "ZB")
    assert cs.case_seed("ZB", 3) == 40_7028 * 1000 + 3 and [c[0] for c in cs.SET_ZB] == [f"ZB{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezb.EFFECTS_ZB) == set(ZB_KINDS)
    _assert_set_module("ZB", 40_7028, ezb, ("gear", "oven_door", "flank_stiffness"))
    for name in ("effects_zb", "effects_zb_joint", "effects_zb_body", "effects_zb_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zb" in _imports(STUDY / "generator.py")
    assert ezb.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezb.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause) in ezb.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, (lo, hi) in ezb.PRODUCTION.items():
            b = opts((kind,), "ur10")
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "exercise"
        for kind, kg in ezb.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        torch = opts(("insulating_flange",))
        assert len(torch["payload_steps"]) == 1 and 3.0 <= torch["payload_steps"][0] <= 8.0
        plain = opts(("hose_wrap", "pawl_notch", "reversal_pulse", "nonius_slip", "fieldbus_rounding", "grout_void",
                      "air_knife"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezb.probe_hook(("gear",), probe) is probe and ezb.payload_hook(("gear",), probe) is probe
    assert ezb.probe_hook(("insulating_flange",), probe) == pytest.approx(probe + [0, 40.0, 320.0])
    assert ezb.probe_hook(("stay_cable",), probe) == pytest.approx(probe + [500.0, 0, -40.0])
    assert ezb.probe_hook(("sonotrode",), probe) == pytest.approx(probe + [0, 0, 300.0])
    assert ezb.payload_hook(("insulating_flange",), probe) == pytest.approx(zbb.TORCH_COM_MM)
    _assert_regenerates("ZB", max_effect_poses=50)


def test_set_zb_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZB kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the impedance's residual torque and its
    blocks, the hose slack, the brake's notch walls, the reversal's new direction, the nonius window, the fieldbus
    integers, four equal wheels' statics, the grout void's one side, the torch's twist about its axis, the stay's sag
    term (Ernst), the curtain's sector and the welding stack's cold start and heating."""
    from sim2real_indep import effects_zb_body as zbb
    from sim2real_indep import effects_zb_joint as zbj
    from sim2real_indep import effects_zb_thermal as zbt
    from sim2real_indep.effects_body import GRAVITY_N, mount_moment
    from sim2real_indep.effects_u_joint import block_index

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZB_KINDS, 30, 28)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZB_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"impedance_preset": lambda: p["amp"], "hose_wrap": lambda: [p["k_h"]],
                   "pawl_notch": lambda: p["pitch"], "reversal_pulse": lambda: p["e"],
                   "nonius_slip": lambda: [p["delta"]], "fieldbus_rounding": lambda: [1.0],
                   "mecanum_base": lambda: [p["inv_k0"]], "grout_void": lambda: [p["c0"], p["cv"]],
                   "insulating_flange": lambda: [p["cb"], p["ct"]], "stay_cable": lambda: [p["c_el"], p["c_sag"]],
                   "air_knife": lambda: p["amp"], "sonotrode": lambda: [p["cte"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    # impedance: the part's load plus e of the arm's; one column per block, on the wrist alone
    ip = P["impedance_preset"]
    assert zbj.residual_torque({"e": 1.0}, ctx) == pytest.approx(ctx.loads)
    part = zbj.residual_torque({"e": 0.0}, ctx)
    assert zbj.residual_torque(ip, ctx) == pytest.approx(part + ip["e"] * (ctx.loads - part))
    F = zbj.impedance_features(ip, ctx, hw)
    assert len(F) == b.max() + 1 and all(not F[k][b != k].any() for k in range(len(F)))
    assert ip["amp"] == pytest.approx(ip["A"] / ip["s"])
    # hose wrap: nothing within the slack, a pull beyond it
    hp = P["hose_wrap"]
    st = zbj.hose_stretch(hp, ctx)
    assert st == pytest.approx(np.clip(hp["r_mm"] * np.abs(ctx.q[:, 5] - hp["q0"]) - hp["slack_mm"], 0, None))
    assert not zbj.hose_unit(hp, ctx, hw)[st == 0].any()
    # pawl notch: the braked axis turns with its load onto a notch wall, less than a pitch
    pp = P["pawl_notch"]
    f = zbj.pawl_fraction(pp, ctx)
    assert pp["pitch"] == pytest.approx(2 * np.pi / (pp["Z"] * pp["ratio"]))
    for k, j in enumerate(zbj.PAWL_JOINTS):
        on = f[:, j] != 0
        assert on.any() and (np.abs(f[:, j]) < 1).all() and (np.sign(f[on, j]) == np.sign(ctx.loads[on, j])).all()
        wall = np.mod(ctx.q[on, j] / pp["pitch"][k] + pp["phase"][k] + f[on, j] + 0.5, 1.0) - 0.5
        assert np.abs(wall).max() < 1e-6
    assert not np.delete(f, zbj.PAWL_JOINTS, axis=1).any()
    # reversal pulse: the new direction where the axis reversed, nothing where it kept its direction
    r = zbj.reversal_signal(s)
    d = s.direction
    assert not r[0].any() and (r[1:] == np.where(d[1:] != d[:-1], d[1:], 0)).all() and np.abs(r).sum() > 0
    # nonius: a period's slip (+1) at the window's centre, none a quarter turn away
    npar = P["nonius_slip"]
    assert zbj.nonius_signal(npar, np.array([npar["c"], npar["c"] + np.pi / 2])) == pytest.approx([1.0, 0.0])
    assert abs(npar["delta"]) == pytest.approx(2 * np.pi / npar["N"])
    assert set(np.unique(zbj.nonius_signal(npar, ctx.q[:, npar["joint"]]))) <= {-1.0, 0.0, 1.0}
    # fieldbus: the commanded joints are integers of 0.01 deg, within a step of the logged ones
    for mode in ("round", "trunc"):
        res = zbj.fieldbus_residual({"mode": mode}, ctx.chain, ctx.q)
        cmd = np.rad2deg(ctx.q + res) / 0.01
        assert np.abs(cmd - np.round(cmd)).max() < 1e-6
        lim = np.deg2rad(0.01) * (0.5 if mode == "round" else 1.0)
        assert np.abs(res).max() <= lim + 1e-15
        if mode == "trunc":
            assert (res * ctx.q <= 1e-18).all()                     # towards zero
    # mecanum base: four equal wheels carry a quarter of the weight each, the tilt M / (4 a^2) about each axis
    mp = {**P["mecanum_base"], "a": 0.0}
    ax, ay = mp["half_mm"]
    m, _, _ = ctx.mass_state
    M = mount_moment(ctx) * 1000.0
    rot = np.c_[M[:, 0] / (4 * ay ** 2), M[:, 1] / (4 * ax ** 2), np.zeros(len(M))]
    want = (-m.sum(axis=1) * np.linalg.norm(GRAVITY_N) / 4)[:, None] * [0, 0, 1.0] + np.cross(
        rot, ctx.target - [0, 0, -mp["h_mm"]])
    assert zbb.mecanum_unit(mp, ctx) == pytest.approx(want, rel=1e-9, abs=1e-12)
    # grout void: no turn while the moment lifts the void's edge, the far edge stays
    vp = P["grout_void"]
    n = np.array([np.cos(vp["psi"]), np.sin(vp["psi"]), 0.0])
    press = mount_moment(ctx) @ np.cross(n, [0, 0, 1.0])
    vparts = zbb.void_parts(vp, ctx)
    assert not vparts[1][press <= 0].any() and (np.linalg.norm(vparts[1][press > 0], axis=1) > 0).all()
    assert np.abs(vparts[0][:, :] @ [0, 0, 1.0] - np.cross(
        np.c_[mount_moment(ctx)[:, :2], np.zeros(len(press))], ctx.target)[:, 2]).max() < 1e-9
    # insulating flange: the twist turns the tip about the tool's z (no move along it), by |M_z| r
    _, Rt = kin.flange(ctx.chain, ctx.q)
    tw = zbb.flange_parts({}, ctx)[1]
    assert np.abs(np.einsum("pi,pi->p", tw, Rt[:, :, 2])).max() < 1e-9
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N) * s.payload_kg[:, None]
    Mz = np.cross(ctx.payload_com_mm, g)[:, 2]
    assert np.linalg.norm(tw, axis=1) == pytest.approx(np.abs(Mz) * np.linalg.norm(ctx.probe_mm[:2]))
    # stay cable: the sag term is Ernst's integral, nothing at the pretension; the tip drops along the tool's -z
    sp = P["stay_cable"]
    T = np.array([sp["T0"], 2 * sp["T0"], 4 * sp["T0"]])
    integral = [np.trapezoid(2 / np.linspace(sp["T0"], t, 20001) ** 3, np.linspace(sp["T0"], t, 20001)) for t in T]
    assert 1 / sp["T0"] ** 2 - 1 / T ** 2 == pytest.approx(integral, rel=1e-6)
    parts = zbb.stay_parts(sp, ctx)
    along = np.einsum("kpi,pi->kp", parts, Rt[:, :, 2])
    assert np.linalg.norm(parts, axis=2) == pytest.approx(np.abs(along))
    # air knife: the curtain's sector; a cold wall until it is entered, never above dT
    kp = P["air_knife"]
    assert zbt.in_curtain(kp, np.array([kp["centre"], kp["centre"] + 2 * kp["half"]])) == pytest.approx([1.0, 0.0])
    kt = zbt.knife_temperature(kp, s)
    on = zbt.in_curtain(kp, s.q[:, 0])
    first = np.argmax(on > 0) if on.any() else len(on)
    assert not kt[:first].any() and kt.min() >= 0 and kt.max() <= kp["dT_K"]
    # sonotrode: cold in the first block, warmed by the first production gap (first-order heating, then cooling)
    hp = P["sonotrode"]
    ht = zbt.horn_temperature(hp, s)
    assert not ht[b == 0].any() and (s.gap_s >= 0).all()
    k = int(np.argmax(s.gap_s > 0))
    warm = hp["dT_K"] * (1 - np.exp(-s.gap_s[k] / hp["tau_s"]))
    cool = np.exp(-(s.time_s[k] - s.time_s[k - 1] - s.gap_s[k]) / hp["tau_s"])
    assert ht[k] == pytest.approx(warm * cool) and 0 < ht.max() <= hp["dT_K"]
    assert hp["cte"] in (23e-6, 8.6e-6)


# --------------------------------------------------------------------------------------------------------- set ZC
ZC_KINDS = ("spool_tension", "coupled_wrist", "bayonet_play", "air_preload", "swapped_bits", "multistart_worm",
            "hexapod_mount", "counterweight_base", "rubber_bush", "floor_hose", "cure_exotherm", "link_convection")


def test_set_zc_cases_kinds_and_determinism():
    """Set ZC (the third two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZB; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZC kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; the
    pauses (a new roll, the air switched, a new bonded part) and a new part for each block."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zc as ezc
    from sim2real_indep import effects_zc_body as zcb
    from sim2real_indep import effects_zc_thermal as zct

    assert _sorts_after("ZB", "ZC")
    assert cs.case_seed("ZC", 3) == 40_7029 * 1000 + 3 and [c[0] for c in cs.SET_ZC] == [f"ZC{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezc.EFFECTS_ZC) == set(ZC_KINDS)
    _assert_set_module("ZC", 40_7029, ezc, ("gear", "sonotrode", "impedance_preset", "oven_door"))
    for name in ("effects_zc", "effects_zc_joint", "effects_zc_body", "effects_zc_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zc" in _imports(STUDY / "generator.py")
    assert ezc.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezc.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause) in ezc.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, kg in ezc.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("bayonet_play", "swapped_bits", "multistart_worm", "hexapod_mount", "floor_hose",
                      "link_convection"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezc.probe_hook(("gear",), probe) is probe and ezc.payload_hook(("gear",), probe) is probe
    assert ezc.probe_hook(("bayonet_play",), probe) == pytest.approx(probe + [80.0, 0, 150.0])
    assert ezc.probe_hook(("rubber_bush",), probe) == pytest.approx(probe + [zcb.BUSH_BOOM_MM, 0, 40.0])
    assert ezc.probe_hook(("floor_hose",), probe) == pytest.approx(probe + [zcb.HOSE_BOOM_MM, 0, 0])
    assert ezc.probe_hook(("cure_exotherm",), probe) == pytest.approx(probe + [0, 0, zct.PART_MM])
    assert ezc.payload_hook(("rubber_bush",), probe) == pytest.approx([zcb.BUSH_BOOM_MM, 0, 20.0])
    _assert_regenerates("ZC", max_effect_poses=50)


def test_set_zc_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZC kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the spool's pull by virtual work, the
    coupled wrist's reciprocal compliance (diagonal without coupling), the bayonet's trailing flank, the air's two
    states, the crossed bits' exchange, the worm's period, the hexapod's pure sink under a central load, the
    counterweight's dead zone, the bush's hinge axis, the hose's hanging length, the exotherm's peak and the stratified
    forearm's warm side."""
    from dataclasses import replace

    from sim2real_indep import effects_zc_body as zcb
    from sim2real_indep import effects_zc_joint as zcj
    from sim2real_indep import effects_zc_thermal as zct
    from sim2real_indep.effects_body import mount_moment
    from sim2real_indep.effects_s_joint import compliance
    from sim2real_indep.effects_u_joint import block_index

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZC_KINDS, 30, 29)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZC_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"spool_tension": lambda: p["T_N"], "coupled_wrist": lambda: p["c"],
                   "bayonet_play": lambda: [p["half"]], "air_preload": lambda: [-p["half"], p["half"]],
                   "swapped_bits": lambda: [p["weight"]], "multistart_worm": lambda: p["a"],
                   "hexapod_mount": lambda: [p["inv_k"]], "counterweight_base": lambda: [p["c"]],
                   "rubber_bush": lambda: [p["inv_k0"], p["cubic"]], "floor_hose": lambda: [p["w_EI"]],
                   "cure_exotherm": lambda: [p["cte"]], "link_convection": lambda: p["amp"]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    # spool: the joints' torques are the pull's virtual work, d p_f / d q . u, through the compliance; one block each
    sp = P["spool_tension"]
    pf, _ = kin.flange(ctx.chain, ctx.q)
    u = (sp["eye_mm"] - pf) / np.linalg.norm(sp["eye_mm"] - pf, axis=1, keepdims=True)
    tau = np.zeros_like(ctx.q)
    for j in range(ctx.chain.n):
        dq = np.zeros_like(ctx.q)
        dq[:, j] = 1e-6
        dp = (kin.flange(ctx.chain, ctx.q + dq)[0] - kin.flange(ctx.chain, ctx.q - dq)[0]) / 2e-6
        tau[:, j] = np.einsum("pi,pi->p", dp, u) / (1000.0 if ctx.chain.revolute[j] else 1.0)
    want = np.einsum("pij,pj->pi", ctx.jac, compliance(hw)[None] * tau)
    assert zcj.spool_unit(sp, ctx, hw) == pytest.approx(want, rel=1e-5, abs=1e-12)
    F = zcj.spool_features(sp, ctx, hw)
    assert len(F) == b.max() + 1 and all(not F[k][b != k].any() for k in range(len(F)))
    # coupled wrist: T^-1 diag(c) T^-T is symmetric (Maxwell-Betti); without coupling, the diagonal compliances
    cw = P["coupled_wrist"]
    T = zcj.coupling(cw, ctx.chain)
    Cm = np.linalg.inv(T) @ np.diag(cw["c"]) @ np.linalg.inv(T).T
    assert Cm == pytest.approx(Cm.T) and np.abs(Cm - np.diag(np.diag(Cm))).max() > 0
    W = zcj.wrist_joints(ctx.chain)
    free = zcj.coupled_features({**cw, "k": np.zeros(3)}, ctx, hw)
    for i, j in enumerate(W):
        assert free[i] == pytest.approx(ctx.joint_feature(j, ctx.loads[:, j]), rel=1e-9, abs=1e-12)
    # bayonet: the tool trails axis 6's last rotation by half the play
    bp = P["bayonet_play"]
    dq6 = zcj.bayonet_apply(bp, ctx, hw).dq
    assert (dq6[:, 5] == -bp["half"] * s.direction[:, 5]).all() and not np.delete(dq6, 5, axis=1).any()
    # air preload: a constant flank in the air-on blocks, the last motion's trailing flank in the air-off ones
    ap = P["air_preload"]
    on = zcj.air_on(ap, s).astype(bool)
    dq1 = zcj.preload_apply(ap, ctx, hw).dq[:, 0]
    assert on.any() and (~on).any() and set(np.unique(ap["air"])) == {0, 1}
    assert dq1[on] == pytest.approx(ap["half"]) and dq1[~on] == pytest.approx(-ap["half"] * s.direction[~on, 0])
    # swapped bits: the logged word is the count with bits k and k + 1 exchanged
    sw = P["swapped_bits"]
    rng = np.random.default_rng(0)
    c = rng.integers(0, sw["counts"], 2000)
    k = sw["bit"]
    bk, bk1 = (c >> k) & 1, (c >> (k + 1)) & 1
    r = c - (bk << k) - (bk1 << (k + 1)) + (bk1 << k) + (bk << (k + 1))
    q_logged = (r + 0.5) / sw["counts"] * 2 * np.pi
    assert (zcj.swap_signal(sw, q_logged) * 2 ** k == r - c).all() and np.abs(r - c).max() == 2 ** k
    assert sw["weight"] == pytest.approx(2 * np.pi * 2 ** k / sw["counts"])
    # worm: the error repeats with each worm turn, s / Z of an output turn
    wp = P["multistart_worm"]
    q = np.linspace(-1.0, 1.0, 7)
    assert zcj.worm_signals(wp, q + 2 * np.pi * wp["starts"] / wp["Z"]) == pytest.approx(zcj.worm_signals(wp, q))
    # hexapod: a central vertical load sinks the plate only, by W / (k sum u_z^2); tension struts softer
    hp = P["hexapod_mount"]
    uu, rr = zcb.hexapod_legs(hp)
    S = np.c_[uu, np.cross(rr, uu)]
    x = np.linalg.solve(S.T @ S, [0, 0, 1.0, 0, 0, 0])
    assert np.abs(np.delete(x, 2)).max() < 1e-9 * abs(x[2]) and x[2] == pytest.approx(1 / (uu[:, 2] ** 2).sum())
    lin = zcb.hexapod_unit({**hp, "beta": 1.0}, ctx)
    w = np.c_[np.zeros((len(ctx.q), 2)), -zcb._weight_N(ctx), mount_moment(ctx) * 1000.0] @ np.linalg.inv(S.T @ S)
    assert lin == pytest.approx(w[:, :3] + np.cross(w[:, 3:], ctx.target), rel=1e-9, abs=1e-12)
    assert np.abs(zcb.hexapod_unit(hp, ctx) - lin).max() > 0
    # counterweight: no tilt while both moments are within the counterweight's stroke
    cp = P["counterweight_base"]
    M = mount_moment(ctx)
    inside = (np.abs(M[:, :2]) <= cp["L_Nm"]).all(axis=1)
    cu = zcb.counterweight_unit(cp, ctx)
    assert not cu[inside].any() and (np.linalg.norm(cu[~inside], axis=1) > 0).all()
    # rubber bush: the boom turns about the tool's y through the pivot; the cubic column is the linear one times M^2
    bu = zcb.bush_parts({}, ctx)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    assert np.abs(np.einsum("pi,pi->p", bu[0], Rt[:, :, 1])).max() < 1e-9 * max(np.abs(bu[0]).max(), 1e-30)
    assert bu[1] == pytest.approx(bu[0] * (zcb.bush_moment(ctx) ** 2)[:, None])
    # floor hose: nothing with the tip at the floor; across the boom, by the hanging length
    fp = P["floor_hose"]
    fu = zcb.floor_hose_unit(fp, ctx)
    assert np.abs(np.einsum("pi,pi->p", fu, Rt[:, :, 0])).max() < 1e-9 * np.abs(fu).max()
    assert not zcb.floor_hose_unit({**fp, "floor_mm": ctx.target[:, 2].max()}, ctx).any()
    # cure exotherm: cold at the bonding, dT at the peak, each block's part from its own bonding
    xp = P["cure_exotherm"]
    t0 = s.time_s[0]
    s1 = replace(s, time_s=t0 + np.linspace(0.0, 3 * xp["tau_c_s"], 20001), gap_s=np.zeros(20001))
    T1 = zct.cure_temperature({**xp, "lead_s": np.zeros(1)}, s1)
    assert T1[0] == pytest.approx(0.0, abs=1e-12) and T1.max() == pytest.approx(xp["dT_K"], rel=1e-6)
    assert len(xp["lead_s"]) == b.max() + 1 >= 3
    # link convection: nothing at the session's start; a vertical forearm has no warm side across it, a horizontal one
    # bows with its warm (upper) side convex, its far end dropping
    lp = P["link_convection"]
    assert not zct.convection_parts(lp, ctx)[:, 0].any()
    li = zct.forearm(ctx.chain)
    q = np.zeros((181, ctx.chain.n))
    q[:, 2] = np.deg2rad(np.arange(-90.0, 91.0))
    R, _ = kin.body_transforms(ctx.chain, q)
    up = np.abs(np.einsum("pij,j->pi", R[:, int(ctx.chain.link_body[li])], ctx.chain.links[li])[:, 2])
    pick = q[[0, int(np.argmax(up)), int(np.argmin(up))]]
    c3 = _ctx_at(ctx, pick)
    c3 = replace(c3, session=replace(c3.session, time_s=np.array([0.0, 1e6, 1e6])))
    bow = zct.convection_parts(lp, c3)[1]
    assert np.linalg.norm(bow[1]) < 1e-6 * np.linalg.norm(bow[2]) and bow[2, 2] < 0


# --------------------------------------------------------------------------------------------------------- set ZD
ZD_KINDS = ("soft_float", "torque_crosstalk", "floating_sun", "spline_drag", "readhead_dropout", "range_shift",
            "levelling_valves", "scissor_lift", "curing_bond", "drive_tendons", "bake_booth", "gun_warmup")


def test_set_zd_cases_kinds_and_determinism():
    """Set ZD (the fourth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZC; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZD kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; the
    pauses (a head's window misted, the range shifted, the booth's mode switched) and a new part for each block."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zd as ezd
    from sim2real_indep import effects_zd_body as zdb
    from sim2real_indep import effects_zd_thermal as zdt

    assert _sorts_after("ZC", "ZD")
    assert cs.case_seed("ZD", 3) == 40_7030 * 1000 + 3 and [c[0] for c in cs.SET_ZD] == [f"ZD{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezd.EFFECTS_ZD) == set(ZD_KINDS)
    _assert_set_module("ZD", 40_7030, ezd, ("gear", "sonotrode", "spool_tension", "link_convection"))
    for name in ("effects_zd", "effects_zd_joint", "effects_zd_body", "effects_zd_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zd" in _imports(STUDY / "generator.py")
    assert ezd.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezd.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause) in ezd.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, kg in ezd.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("floating_sun", "spline_drag", "levelling_valves", "curing_bond", "gun_warmup"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezd.probe_hook(("gear",), probe) is probe and ezd.payload_hook(("gear",), probe) is probe
    assert ezd.probe_hook(("curing_bond",), probe) == pytest.approx(probe + [zdb.BOND_BOOM_MM, 0, 0])
    assert ezd.probe_hook(("gun_warmup",), probe) == pytest.approx(probe + [0, 0, zdt.GUN_MM])
    assert ezd.payload_hook(("drive_tendons",), probe) == pytest.approx([60.0, 0, 150.0])
    _assert_regenerates("ZD", max_effect_poses=50)


def test_set_zd_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZD kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm (the spline drag on tool_changer, the only arm with a
    telescope); and known answers: an isotropic soft float yields along the weight, the sensors' moments hold the
    joints' torques along their axes, the sun's float where the load vanishes, the spline's flank, the read-heads' and
    the range's blocks, the mounts' statics and their play within the band, the scissor table's vertical heave, the
    bond's stiffening, the tendons' bend by the wrist's torque, the booth's lag and the gun's S-curve."""
    from dataclasses import replace

    from sim2real_indep import effects_zd_body as zdb
    from sim2real_indep import effects_zd_joint as zdj
    from sim2real_indep import effects_zd_thermal as zdt
    from sim2real_indep.effects_body import mount_moment
    from sim2real_indep.effects_u_joint import block_index
    from sim2real_indep.effects_y_thermal import lamp_side, link_bow
    from sim2real_indep.effects_za_thermal import forearm

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZD_KINDS, 30, 30)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZD_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            if kind == "spline_drag" and robot != "tool_changer":
                assert A.shape[1] == 0 and not d.any()
                continue
            amp = {"soft_float": lambda: p["c"], "torque_crosstalk": lambda: p["a"], "floating_sun": lambda: p["half"],
                   "spline_drag": lambda: p["half"], "readhead_dropout": lambda: p["a"],
                   "range_shift": lambda: [p["eps"]], "levelling_valves": lambda: [p["delta"]],
                   "scissor_lift": lambda: p["amp"], "curing_bond": lambda: p["amp"], "drive_tendons": lambda: [p["k"]],
                   "bake_booth": lambda: [p["amp"]], "gun_warmup": lambda: [p["cte"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s, hw = case.truth["params"], ctx.session, case.truth["hw"]
    b = block_index(s)
    # soft float: equal compliances along the three tool axes yield along the weight (tool and part)
    fp = P["soft_float"]
    W = (s.payload_kg + fp["tool_kg"])[:, None] * [0, 0, -kin.G]
    assert zdj.float_parts(fp, ctx).sum(axis=0) == pytest.approx(W, rel=1e-9, abs=1e-9)
    assert len(set(s.payload_kg)) > 1
    # torque crosstalk: the moments across each joint hold its gravity torque along its axis; the gauges' direction lies
    # across the axis
    tp = P["torque_crosstalk"]
    M = zdj.bending_moments(ctx)
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    assert np.einsum("pji,pji->pj", M, w) == pytest.approx(ctx.loads, rel=1e-9, abs=1e-9)
    for j in zdj.crosstalk_joints(ctx.chain):
        assert np.abs(np.einsum("pi,pi->p", zdj.sensor_direction(tp, ctx, j), w[:, j])).max() < 1e-12
    # floating sun: the flank is the load's where it beats the friction, the float's share 1 at no load
    sp = P["floating_sun"]
    sig = zdj.sun_signals(sp, ctx)
    tau = ctx.loads[:, sp["joint"]]
    big = np.abs(tau) > sp["f_Nm"]
    assert (sig[0][big] == np.sign(tau[big])).all() and (np.abs(sig[0]) == 1).all()
    assert zdj.sun_signals({**sp, "tau_c": 1e30}, ctx)[1] == pytest.approx(sig[0])
    # spline drag (tool_changer): an unloaded wrist axis rests on the flank the telescope's last stroke chose
    tcase, tctx = runs["tool_changer"]
    dp = tcase.truth["params"]["spline_drag"]
    assert dp["prismatic"] == 3 and dp["wrist"] == [4, 5]
    for k, j in enumerate(dp["wrist"]):
        f = zdj.spline_flank(dp, tctx, j, k)
        lim = 0.03 * np.abs(tctx.loads[:, j]).max()
        free = np.abs(tctx.loads[:, j]) <= lim
        assert (f[free] == dp["sense"][k] * tctx.session.direction[free, 3]).all()
    # read-heads: nothing in the blocks read by both heads, both states present
    rp = P["readhead_dropout"]
    one = zdj.dropout_mask(rp, s).astype(bool)
    assert one.any() and (~one).any() and not zdj.dropout_signals(rp, ctx)[:, ~one].any()
    # range shift: eps q1 in the low-range blocks only
    gp = P["range_shift"]
    dq = zdj.range_apply(gp, ctx, hw).dq
    low = np.asarray(gp["low"])[np.minimum(b, len(gp["low"]) - 1)].astype(bool)
    assert dq[low, 0] == pytest.approx(gp["eps"] * ctx.q[low, 0]) and not dq[~low].any() and low.any()
    # levelling valves: the mounts carry the weight and the moment; their play stays within the band from zero
    vp = P["levelling_valves"]
    F = zdb.mount_loads(vp, ctx)
    a = vp["psi"] + np.deg2rad([0.0, 120.0, 240.0])
    x, y = vp["r_m"] * np.cos(a), vp["r_m"] * np.sin(a)
    assert F.sum(axis=1) == pytest.approx(zdb._weight_N(ctx)) and (F > 0).all()
    assert F @ y == pytest.approx(-mount_moment(ctx)[:, 0]) and F @ -x == pytest.approx(-mount_moment(ctx)[:, 1])
    e = zdb.valve_play(vp, ctx)
    assert not e[0].any() and np.abs(e).max() <= 1.0 and np.abs(e).max() == pytest.approx(1.0)
    heave = zdb.plate_motion(vp, ctx, np.ones((len(ctx.q), 3)))
    assert heave == pytest.approx(np.tile([0, 0, 1.0], (len(ctx.q), 1)))
    # scissor lift: the heave columns are vertical, the first one the weight's
    parts = zdb.scissor_parts(P["scissor_lift"], ctx)
    assert not parts[:2, :, :2].any() and parts[0, :, 2] == pytest.approx(-zdb._weight_N(ctx))
    # curing bond: the joint stiffens from c0 at the first pose towards c_inf
    bp = P["curing_bond"]
    fac = zdb.bond_age_factor(bp, s)
    assert (np.diff(fac) < 0).all() and bp["amp"][1] == pytest.approx((bp["ratio"] - 1) * bp["c_inf"])
    # drive tendons: the forearm's bend follows axis 5's torque
    tdp = P["drive_tendons"]
    li = forearm(ctx.chain)
    want = link_bow(ctx, li, lamp_side(ctx.chain, li, tdp["psi"])) * (ctx.loads[:, 4] * 1000.0)[:, None]
    assert zdb.tendon_unit(tdp, ctx) == pytest.approx(want)
    # bake booth: the links at the hall's temperature at the start, within the booth's rise, both modes present
    kp = P["bake_booth"]
    T = zdt.booth_temperature(kp, s)
    assert T[0] == pytest.approx(0.0) and T.min() >= 0 and T.max() <= 1 and set(np.unique(kp["warm"])) == {0, 1}
    # gun warm-up: cold with zero slope at the switch-on, the full rise long after
    up = {**P["gun_warmup"], "lead_s": 0.0}
    s2 = replace(s, time_s=s.time_s[0] + np.array([0.0, 1.0, 1e7]))
    g = zdt.gun_temperature(up, s2)
    assert g[0] == pytest.approx(0.0, abs=1e-12) and g[1] < 1e-4 and g[2] == pytest.approx(1.0)


# --------------------------------------------------------------------------------------------------------- set ZE
ZE_KINDS = ("tether_reel", "ball_reducer", "rotary_clamp", "noback_brake", "disc_shift", "reversal_counts",
            "slender_pedestal", "slewing_rock", "shuttle_boom", "ringing_boom", "holding_heat", "pcm_tool")


def test_set_ze_cases_kinds_and_determinism():
    """Set ZE (the fifth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZD; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZE kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; the pauses (the
    clamp, the shuttle's station, the brakes holding) and a new part for each block (the pedestal)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_ze as eze
    from sim2real_indep import effects_ze_body as zeb
    from sim2real_indep import effects_ze_thermal as zet

    assert _sorts_after("ZD", "ZE")
    assert cs.case_seed("ZE", 3) == 40_7031 * 1000 + 3 and [c[0] for c in cs.SET_ZE] == [f"ZE{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(eze.EFFECTS_ZE) == set(ZE_KINDS)
    _assert_set_module("ZE", 40_7031, eze, ("gear", "soft_float", "gun_warmup", "sonotrode"))
    for name in ("effects_ze", "effects_ze_joint", "effects_ze_body", "effects_ze_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_ze" in _imports(STUDY / "generator.py")
    assert eze.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": eze.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, ((lo, hi), pause) in eze.PAUSES.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        for kind, kg in eze.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        plain = opts(("tether_reel", "ball_reducer", "noback_brake", "disc_shift", "reversal_counts",
                      "slewing_rock", "ringing_boom", "pcm_tool"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert eze.probe_hook(("gear",), probe, "ur10") is probe
    assert eze.probe_hook(("shuttle_boom",), probe, "kr16_like") == pytest.approx(probe + [700.0, 0, 0])
    assert eze.probe_hook(("ringing_boom",), probe, "ur10") == pytest.approx(probe + [0, 0, zeb.RING_MM])
    assert eze.probe_hook(("pcm_tool",), probe, "ur10") == pytest.approx(probe + [0, 0, zet.PCM_MM])
    _assert_regenerates("ZE", max_effect_poses=50)


def test_set_ze_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZE kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the tether's unit pull towards its anchor
    and its torques J^T F, the Hertzian 2/3 law, the clamp's side in the clamped blocks, the no-back's quadrant, the
    disc's reading by the moment, the reversal count, the pedestal's amplification, the slewing ring's saturating rock,
    the cantilever's station factor, the boom's decaying ring, the holding heat's pauses and the wax's plateau."""
    from dataclasses import replace

    from sim2real_indep import effects_ze_body as zeb
    from sim2real_indep import effects_ze_joint as zej
    from sim2real_indep import effects_ze_thermal as zet
    from sim2real_indep.effects_body import mount_moment
    from sim2real_indep.effects_u_joint import block_index

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZE_KINDS, 30, 31)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZE_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"tether_reel": lambda: p["c"], "ball_reducer": lambda: p["c"], "rotary_clamp": lambda: p["half"],
                   "noback_brake": lambda: p["delta"], "disc_shift": lambda: p["k"], "reversal_counts": lambda: p["step"],
                   "slender_pedestal": lambda: p["c"], "slewing_rock": lambda: p["theta"],
                   "shuttle_boom": lambda: p["amp"], "ringing_boom": lambda: p["gain"], "holding_heat": lambda: p["amp"],
                   "pcm_tool": lambda: [p["cte"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    b = block_index(s)
    # tether: a unit pull towards the anchor, its torques J^T F [N m]
    tp = P["tether_reel"]
    u = zej.tether_pull(tp, ctx)
    assert np.linalg.norm(u, axis=1) == pytest.approx(1.0)
    assert np.cross(u, tp["anchor_mm"] - ctx.target) == pytest.approx(np.zeros_like(u), abs=1e-6)
    assert zej.tether_torques(tp, ctx)[:, 1] == pytest.approx(
        np.einsum("pi,pi->p", ctx.jac[:, :, 1], u) / 1000.0)
    # ball reducer: the Hertzian law equals the load at tau_ref, grows as its 2/3 power, odd
    assert zej.hertz_twist(np.array([8.0, -8.0, 1.0]), 8.0) == pytest.approx([8.0, -8.0, 2.0])
    # rotary clamp: the clamp's side in the clamped blocks, the trailing flank elsewhere, both present
    cp = P["rotary_clamp"]
    on = np.asarray(cp["clamped"])[np.minimum(b, len(cp["clamped"]) - 1)].astype(bool)
    sig = zej.clamp_signal(cp, ctx)
    assert on.any() and (~on).any() and (sig[on] == cp["side"]).all()
    assert (sig[~on] == -s.direction[~on, 0]).all()
    # no-back: lost motion only where the last motion went the load's way
    nb = zej.noback_signal(ctx)
    d1, s1 = s.direction[:, 1], np.sign(ctx.loads[:, 1])
    assert (nb[d1 != s1] == 0).all() and (nb[d1 == s1] == -d1[d1 == s1]).all() and (d1 == s1).any()
    # disc shift: the reading follows the horizontal moment on axis 1 only
    dp = P["disc_shift"]
    F = zej.disc_features(dp, ctx, case.truth["hw"])
    M = mount_moment(ctx)
    assert F[0] == pytest.approx(ctx.jac[:, :, 0] * M[:, :1]) and F[1] == pytest.approx(ctx.jac[:, :, 0] * M[:, 1:2])
    # reversal counts: one per sign change of the logged direction
    dirs = np.array([[1.0], [1.0], [-1.0], [-1.0], [1.0], [-1.0]])
    assert zej.reversals(replace(s, direction=dirs), 0) == pytest.approx([0, 0, 1, 1, 2, 3])
    # slender pedestal: the amplification 1 / (1 - W / W_cr), above 1, growing with the part
    pp = P["slender_pedestal"]
    amp = zeb.pedestal_amplification(pp, ctx)
    W = zeb.total_weight_N(ctx)
    assert amp == pytest.approx(1 / (1 - W / pp["W_cr_N"])) and (amp > 1).all() and len(set(s.payload_kg)) > 1
    assert np.corrcoef(W, amp)[0, 1] > 0.99
    # slewing rock: the rock's axis along the moment, its share below one and saturating at large moments
    rp = P["slewing_rock"]
    ax = zeb.rock_axis(rp, ctx)
    assert (np.linalg.norm(ax, axis=1) < 1).all() and not ax[:, 2].any()
    assert zeb.rock_axis({**rp, "M_c": 1e-9}, ctx) == pytest.approx(
        ax / np.linalg.norm(ax, axis=1, keepdims=True), abs=1e-6)
    # shuttle boom: the cantilever's factor a^2 (3 - a) / 2: 1 at the tip, 0 at the root
    sp = P["shuttle_boom"]
    assert zeb.station_factor({"station": [1.0, 0.0, 0.5]}, replace(s, gap_s=np.r_[0, -1, -1, np.zeros(len(s.gap_s) - 3)])
                              )[:3] == pytest.approx([1.0, 0.0, 0.3125])
    assert len(sp["station"]) == b.max() + 1
    # ringing boom: the ring decays with the dwell (zeta omega) and starts at the ramp's sinc
    gp = P["ringing_boom"]
    w = 2 * np.pi * gp["f_hz"]
    long = zeb.ring_response(gp, replace(s, dwell_s=np.array([0.0, 1e3])))
    assert long[0] == pytest.approx(abs(np.sin(w * 0.25) / (w * 0.25))) and abs(long[1]) < 1e-6
    # holding heat: cold at the start, within the unit rise, cooling in the pauses
    hp = P["holding_heat"]
    T = zet.holding_temperature(hp, ctx)
    assert T[:, 0] == pytest.approx(0.0) and T.min() >= 0 and T.max() <= 1
    src = zet.holding_source(hp, ctx, 1)
    k = int(np.flatnonzero(s.gap_s < 0)[0])
    t0 = s.time_s - s.time_s[0]
    assert src(np.array([t0[k] - s.move_s[k] - s.dwell_s[k] - 1.0]))[0] == 0.0
    # PCM tool: warming, halting at the melting rise across the latent store, warming on towards T_inf
    cp = {"lead_s": 0.0, "tau_s": 600.0, "T_inf": 30.0, "T_m": 10.0, "L_K": 15.0}
    t = np.linspace(0.0, 2e4, 2001)
    Tc = zet.pcm_temperature(cp, t)
    assert Tc[0] == 0.0 and (np.diff(Tc) >= -1e-12).all() and Tc[-1] == pytest.approx(30.0, abs=0.05)
    plateau = np.abs(Tc - 10.0) < 1e-9
    assert plateau.sum() * 10.0 == pytest.approx(15.0 * 600.0 / 20.0, rel=0.05)  # L tau / (T_inf - T_m)


# --------------------------------------------------------------------------------------------------------- set ZF
ZF_KINDS = ("bungee_cord", "warm_preload", "viscous_crossing", "centring_spring", "repaired_sector", "sagging_disc",
            "shelf_bracket", "shim_friction", "polymer_boom", "flange_gapping", "peltier_loop", "marking_pulses")


def test_set_zf_cases_kinds_and_determinism():
    """Set ZF (the sixth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZE; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZF kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; a new part for
    each block (the shelf bracket) and the air's drift across paused blocks (the polymer boom)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zf as ezf
    from sim2real_indep import effects_zf_body as zfb
    from sim2real_indep import effects_zf_thermal as zft

    assert _sorts_after("ZE", "ZF")
    assert cs.case_seed("ZF", 3) == 40_7032 * 1000 + 3 and [c[0] for c in cs.SET_ZF] == [f"ZF{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezf.EFFECTS_ZF) == set(ZF_KINDS)
    _assert_set_module("ZF", 40_7032, ezf, ("gear", "tether_reel", "pcm_tool", "gun_warmup"))
    for name in ("effects_zf", "effects_zf_joint", "effects_zf_body", "effects_zf_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zf" in _imports(STUDY / "generator.py")
    assert ezf.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezf.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezf.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), pause, (d0, d1)) in ezf.AIR_DRIFT.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
            assert d0 <= abs(b["air"]["drift_K"]) <= d1
        plain = opts(("bungee_cord", "warm_preload", "viscous_crossing", "centring_spring", "repaired_sector",
                      "sagging_disc", "shim_friction", "flange_gapping", "peltier_loop", "marking_pulses"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezf.probe_hook(("gear",), probe) is probe
    assert ezf.probe_hook(("polymer_boom",), probe) == pytest.approx(probe + [zfb.BOOM_MM, 0, 0])
    assert ezf.probe_hook(("flange_gapping",), probe) == pytest.approx(probe + [zfb.BOOM_MM, 0, 0])
    assert ezf.probe_hook(("peltier_loop",), probe) == pytest.approx(probe + [0, 0, zft.BRACKET_MM])
    assert ezf.probe_hook(("marking_pulses",), probe) == pytest.approx(probe + [0, 0, zft.BRACKET_MM])
    _assert_regenerates("ZF", max_effect_poses=50)


def test_set_zf_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZF kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the cord's pull by its stretch towards the
    eye, the preload's stiffening share, the oil's crossing share, the centring spring's clip, the sector's bump, the
    disc's gravity in its housing, the shelf's turn and drop, the shims' slip sign, the polymer's modulus factor, the
    flange's opening threshold, the Peltier loop's damped swing and the marking pulses' decay."""
    from dataclasses import replace

    from sim2real_indep import effects_zf_body as zfb
    from sim2real_indep import effects_zf_joint as zfj
    from sim2real_indep import effects_zf_thermal as zft
    from sim2real_indep.effects_body import mount_moment
    from sim2real_indep.effects_ze_body import total_weight_N

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZF_KINDS, 30, 32)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZF_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"bungee_cord": lambda: p["c"], "warm_preload": lambda: p["c"], "viscous_crossing": lambda: p["half"],
                   "centring_spring": lambda: p["half"], "repaired_sector": lambda: p["e"],
                   "sagging_disc": lambda: p["k"], "shelf_bracket": lambda: p["c"], "shim_friction": lambda: p["f"],
                   "polymer_boom": lambda: p["amp"], "flange_gapping": lambda: p["c"],
                   "peltier_loop": lambda: [p["amp"]], "marking_pulses": lambda: [p["amp"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # bungee cord: the pull along the line to the eye, its size the stretch past L0
    bp = P["bungee_cord"]
    F = zfj.cord_force(bp, ctx)
    dvec = bp["eye_mm"] - ctx.target
    assert np.cross(F, dvec) == pytest.approx(np.zeros_like(F), abs=1e-6) and (np.einsum("pi,pi->p", F, dvec) > 0).all()
    assert np.linalg.norm(F, axis=1) == pytest.approx(np.linalg.norm(dvec, axis=1) - bp["L0_mm"])
    # warm preload: 1 at the start, falling to 1 - beta
    wp = P["warm_preload"]
    f = zfj.preload_factor(wp, s)
    assert f[0] == pytest.approx(1.0) and (np.diff(f) <= 1e-12).all() and f.min() > 1 - wp["beta"]
    assert zfj.preload_factor(wp, replace(s, time_s=np.array([0.0, 1e9])))[1] == pytest.approx(1 - wp["beta"])
    # viscous crossing: on the trailing flank without a dwell, on the load's flank after a long one
    vp = P["viscous_crossing"]
    tau, d1 = ctx.loads[:, 1], s.direction[:, 1]
    short = zfj.crossing_flank(vp, replace(ctx, session=replace(s, dwell_s=np.zeros(len(tau)))), 1, vp["B"][0])
    long = zfj.crossing_flank(vp, replace(ctx, session=replace(s, dwell_s=np.full(len(tau), 1e9))), 1, vp["B"][0])
    assert short == pytest.approx(-d1) and long == pytest.approx(np.sign(tau))
    mid = zfj.crossing_flank(vp, ctx, 1, vp["B"][0])
    assert (np.abs(mid) <= 1 + 1e-12).all() and (mid[np.sign(tau) == -d1] == -d1[np.sign(tau) == -d1]).all()
    # centring spring: linear inside the clearance, on the flank beyond T_c, odd
    assert zfj.centring_flank(np.array([-3.0, -0.5, 0.0, 0.25, 2.0]), 1.0) == pytest.approx([-1, -0.5, 0, 0.25, 1])
    # repaired sector: 1 at the sector's centre, e^-1 one width away
    rp = P["repaired_sector"]
    assert zfj.sector_bump(rp, np.array([rp["q_s"], rp["q_s"] + rp["w"]])) == pytest.approx([1.0, np.exp(-1)])
    # sagging disc: gravity's share across the axis, at most 1
    g = zfj.housing_gravity(ctx, P["sagging_disc"]["joint"])
    assert (np.linalg.norm(g, axis=1) <= 1 + 1e-12).all() and np.ptp(g, axis=0).max() > 0.1
    # shelf bracket: Roark's tip turn and drop of a cantilever under W and M
    sp = P["shelf_bracket"]
    th, dr = zfb.shelf_turn_drop({**sp, "psi": 0.0}, ctx)
    W, L, Mu = total_weight_N(ctx), sp["L_mm"], mount_moment(ctx)[:, 1] * 1000.0
    assert th * 1e9 == pytest.approx(W * L ** 2 / 2 + Mu * L) and dr * 1e9 == pytest.approx(W * L ** 3 / 3 + Mu * L ** 2 / 2)
    assert len(set(s.payload_kg)) > 1
    # shim friction: the sign of the moment's change since the last pose
    M = mount_moment(ctx)[:, :2]
    sg = zfb.slip_sign(ctx)
    assert (sg[1:] == np.sign(np.diff(M, axis=0))).all() and (sg[0] == np.sign(M[0])).all()
    # polymer boom: E_0 / E(T) = 1 + kappa (T - T_0), the air drifting over the session
    pp = P["polymer_boom"]
    mf = zfb.modulus_factor(pp, s)
    assert mf == pytest.approx(1 + pp["kappa"] * (s.air_c - s.air_c[0])) and np.ptp(s.air_c) > 1.0
    # flange gapping: no rotation below M_0, the excess about the moment's axis beyond
    gp = P["flange_gapping"]
    Mf = zfb.flange_moment(ctx, gp["m_kg"])
    rot = zfb.gap_rotation(gp, ctx)
    n = np.linalg.norm(Mf, axis=1)
    assert (rot[n <= gp["M0"]] == 0).all() and (n > gp["M0"]).any()
    assert np.linalg.norm(rot, axis=1) == pytest.approx(np.maximum(n - gp["M0"], 0.0))
    # Peltier loop: the offset 1 at switch-on, swinging below the set point, decaying
    lp = {"lead_s": 0.0, "period_s": 1200.0, "zeta": 0.1}
    off = zft.peltier_offset(lp, np.array([0.0, 600.0, 1e6]))
    assert off[0] == pytest.approx(1.0) and -1 < off[1] < 0 and abs(off[2]) < 1e-9
    # marking pulses: each dwell's pulse decays by exp(-dt / tau), normalised to a peak of 1
    T = zft.pulse_temperature({"tau_s": 100.0}, np.array([0.0, 100.0, 200.0]), np.array([2.0, 1.0, 5.0]))
    raw = np.array([0.0, 2 * np.exp(-1), (2 * np.exp(-1) + 1) * np.exp(-1)])
    assert T == pytest.approx(raw / raw.max())


# --------------------------------------------------------------------------------------------------------- set ZG
ZG_KINDS = ("gravcomp_payload", "taut_harness", "tilt_flank", "coast_flank", "chipped_pinion", "missing_pin",
            "settlement_tilt", "bolt_relaxation", "beam_column", "leaf_boom", "drying_film", "rotary_union")


def test_set_zg_cases_kinds_and_determinism():
    """Set ZG (the seventh two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZF; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZG kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; a new part for
    each block (the payload mismatch, the beam-column boom) and hours of paused blocks (the time-driven kinds)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zg as ezg
    from sim2real_indep import effects_zg_body as zgb
    from sim2real_indep import effects_zg_thermal as zgt

    assert _sorts_after("ZF", "ZG")
    assert cs.case_seed("ZG", 3) == 40_7033 * 1000 + 3 and [c[0] for c in cs.SET_ZG] == [f"ZG{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezg.EFFECTS_ZG) == set(ZG_KINDS)
    _assert_set_module("ZG", 40_7033, ezg, ("gear", "tether_reel", "moisture_swell", "marking_pulses"))
    for name in ("effects_zg", "effects_zg_joint", "effects_zg_body", "effects_zg_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zg" in _imports(STUDY / "generator.py")
    assert ezg.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezg.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezg.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), pause) in ezg.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        plain = opts(("taut_harness", "tilt_flank", "coast_flank", "chipped_pinion", "missing_pin", "bolt_relaxation",
                      "leaf_boom"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezg.probe_hook(("gear",), probe) is probe
    assert ezg.probe_hook(("beam_column",), probe) == pytest.approx(probe + [zgb.BOOM_MM, 0, 0])
    assert ezg.probe_hook(("leaf_boom",), probe) == pytest.approx(probe + [zgb.BOOM_MM, 0, 0])
    assert ezg.probe_hook(("rotary_union",), probe) == pytest.approx(probe + [0, 0, zgt.BRACKET_MM])
    _assert_regenerates("ZG", max_effect_poses=50)


def test_set_zg_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZG kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the payload torque per kg (the loads' share
    of the part), the harness's progressive pull past its slack, the wedge's gravity and axis 1's flank, the coast
    flank's speed threshold, the chipped tooth's dip, the missing pin's pulse, the settlement's growth in time, the
    bolts' relaxation factor, the beam-column's amplification, the leaf's principal axes, the drying film's recovery and
    the rotary union's heat per turn."""
    from dataclasses import replace

    from sim2real_indep import effects_zg_body as zgb
    from sim2real_indep import effects_zg_joint as zgj
    from sim2real_indep import effects_zg_thermal as zgt

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZG_KINDS, 30, 33)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZG_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"gravcomp_payload": lambda: p["c"], "taut_harness": lambda: p["ck"], "tilt_flank": lambda: p["half"],
                   "coast_flank": lambda: p["half"], "chipped_pinion": lambda: p["e"], "missing_pin": lambda: p["k"],
                   "settlement_tilt": lambda: p["rate"], "bolt_relaxation": lambda: p["C"],
                   "beam_column": lambda: p["inv_EI"], "leaf_boom": lambda: p["inv_EI"],
                   "drying_film": lambda: [p["amp"]], "rotary_union": lambda: [p["amp"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # gravity-compensation mismatch: the per-kg payload torque times the part is the loads' share of the part, and
    # nothing deflects when the part is the declared load
    t1 = zgj.payload_torque_per_kg(ctx) * s.payload_kg[:, None]
    empty = replace(ctx, session=replace(s, payload_kg=np.zeros(len(s.payload_kg))))
    assert t1 == pytest.approx(ctx.loads - empty.loads, abs=1e-9) and len(set(s.payload_kg)) > 1
    gp = P["gravcomp_payload"]
    at_decl = replace(ctx, session=replace(s, payload_kg=np.full(len(s.payload_kg), gp["m_decl_kg"])))
    assert np.abs(zgj.gravcomp_features(gp, at_decl, None)).max() == 0
    # taut harness: nothing inside the slack, the square of the excess beyond it, opposing it
    assert zgj.harness_stretch({"q_t": 1.0}, np.array([0.0, 1.0, 1.5, 3.0])) == pytest.approx([0, 0, -0.25, -4.0])
    # tilt flank: a level base has no gravity torque on axis 1 (flank trails the motion); the wedge's gravity is a unit
    # vector alpha off the vertical
    tp = P["tilt_flank"]
    assert zgj.tilt_gravity({**tp, "alpha": 0.0}) == pytest.approx([0, 0, -1])
    assert zgj.tilt_gravity(tp) @ [0, 0, -1] == pytest.approx(np.cos(tp["alpha"]))
    assert np.abs(zgj.tilt_torque({**tp, "alpha": 0.0}, ctx)).max() < 1e-9
    assert zgj.tilt_flank({**tp, "alpha": 0.0}, ctx) == pytest.approx(-s.direction[:, 0])
    tau1 = zgj.tilt_torque(tp, ctx)
    f = zgj.tilt_flank(tp, ctx)
    out = np.abs(tau1) > tp["T_f"]
    assert out.any() and (~out).any() and (f[out] == np.sign(tau1[out])).all()
    # coast flank: the move's mean speed; beyond the friction the gravity flank, inside it leading above v_c
    v = zgj.move_speed(s, 1)
    assert v[0] == 0 and v[1:] == pytest.approx(np.abs(np.diff(s.q[:, 1])) / s.move_s[1:])
    d1 = s.direction[:, 1]
    assert zgj.coast_flank(ctx, 1, np.inf, -1.0) == pytest.approx(d1)
    assert zgj.coast_flank(ctx, 1, np.inf, np.inf) == pytest.approx(-d1)
    assert zgj.coast_flank(ctx, 1, 0.0, 0.0) == pytest.approx(np.sign(ctx.loads[:, 1]))
    # chipped pinion: a dip of 1 where the chipped tooth meshes, 1/2 half a span away, none beyond, once per pinion turn
    cp = P["chipped_pinion"]
    q0 = -cp["phase"] / cp["ratio"]
    qs = q0 + np.array([0.0, cp["h"] / 2, 1.01 * cp["h"], 2 * np.pi]) / cp["ratio"]
    assert zgj.chip_dip(cp, qs) == pytest.approx([1.0, 0.5, 0.0, 1.0])
    # missing pin: a pulse of 1 at the pin, exp(-2 / w^2) opposite, once per crank turn
    mp = P["missing_pin"]
    q0 = -mp["phi"] / (mp["z_p"] - 1)
    qs = q0 + np.array([0.0, np.pi, 2 * np.pi]) / (mp["z_p"] - 1)
    assert zgj.pin_pulse(mp, qs) == pytest.approx([1.0, np.exp(-2 / mp["w"] ** 2), 1.0])
    # settlement: nothing at the session's start, growing in proportion to the time
    F = zgb.settle_features(P["settlement_tilt"], ctx, None)
    assert np.abs(F[:, 0]).max() == 0 and np.ptp(s.time_s) > 3600
    # bolt relaxation: 1 at the start, 1 + beta ln 2 at t0
    rp = P["bolt_relaxation"]
    rf = zgb.relax_factor(rp, replace(s, time_s=np.array([0.0, rp["t0_s"]])))
    assert rf == pytest.approx([1.0, 1 + rp["beta"] * np.log(2)])
    # beam-column: 1 / (1 - P / P_cr), P the weight along the boom (compression when it points up)
    bp = P["beam_column"]
    e = zgb.boom_axis(ctx)[:, :, 0]
    comp = (s.payload_kg + bp["boom_kg"] / 2) * zgb.G * -e[:, 2]
    amp = zgb.amplification(bp, ctx)
    assert amp == pytest.approx(1 / (1 - comp / bp["P_cr"])) and (amp[e[:, 2] > 0.1] < 1).all()
    # leaf boom: deflection across the boom; a square bar (ratio 1) deflects along the weight's component across it
    lp = P["leaf_boom"]
    Fl = zgb.leaf_features(lp, ctx, None)[0]
    assert np.einsum("pi,pi->p", Fl, e) == pytest.approx(np.zeros(len(e)), abs=1e-9)
    iso = zgb.leaf_features({**lp, "ratio": 1.0}, ctx, None)[0]
    g = np.array([0.0, 0.0, -1.0])
    assert iso == pytest.approx((g - e * (e @ g)[:, None]) * zgb.BOOM_MM ** 4 / 8e9)
    # drying film: the links at the full depression at the start, recovering once the film has dried
    fp = P["drying_film"]
    T = zgt.film_temperature(fp, np.linspace(0.0, fp["t_dry_s"] + 30 * fp["tau_s"], 4000))
    assert T[0] == pytest.approx(-1.0) and (np.diff(T) >= -1e-12).all() and abs(T[-1]) < 1e-6
    # rotary union: each move's |dq6| of heat decays by exp(-dt / tau), normalised to a peak of 1
    U = zgt.union_temperature({"tau_s": 100.0}, np.array([0.0, 2.0, 1.0]), np.array([0.0, 100.0, 200.0]))
    raw = np.array([0.0, 2 * np.exp(-1), (2 * np.exp(-1) + 1) * np.exp(-1)])
    assert U == pytest.approx(raw / raw.max())


# --------------------------------------------------------------------------------------------------------- set ZH
ZH_KINDS = ("worn_mesh", "tooth_crack", "grease_gel", "pinion_handover", "running_in_te", "brazier_pedestal",
            "dished_plate", "inflated_boom", "collet_root", "loose_pivot", "wrist_conduction", "regen_resistor")


def test_set_zh_cases_kinds_and_determinism():
    """Set ZH (the eighth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZG; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZH kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; a new part for
    each block (the dished plate, the inflated boom) and hours of paused blocks (the pause- and time-driven kinds)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zh as ezh
    from sim2real_indep import effects_zh_body as zhb

    assert _sorts_after("ZG", "ZH")
    assert cs.case_seed("ZH", 3) == 40_7034 * 1000 + 3 and [c[0] for c in cs.SET_ZH] == [f"ZH{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezh.EFFECTS_ZH) == set(ZH_KINDS)
    _assert_set_module("ZH", 40_7034, ezh, ("gear", "tether_reel", "rotary_union", "taut_harness"))
    for name in ("effects_zh", "effects_zh_joint", "effects_zh_body", "effects_zh_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zh" in _imports(STUDY / "generator.py")
    assert ezh.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezh.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezh.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), pause) in ezh.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == "pause" and b["pause_min"] == pause
        plain = opts(("worn_mesh", "tooth_crack", "pinion_handover", "running_in_te", "brazier_pedestal",
                      "collet_root", "loose_pivot"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezh.probe_hook(("gear",), probe) is probe
    assert ezh.probe_hook(("inflated_boom",), probe) == pytest.approx(probe + [zhb.BOOM_MM, 0, 0])
    assert ezh.probe_hook(("collet_root",), probe) == pytest.approx(probe + [zhb.BOOM_MM, 0, 0])
    assert ezh.probe_hook(("loose_pivot",), probe) == pytest.approx(probe + [0, 0, zhb.PIVOT_MM])
    _assert_regenerates("ZH", max_effect_poses=50)


def test_set_zh_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZH kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the wear zone's Gaussian, the cracked tooth's
    window, the gel's share after a pause, the pinions' handover with the direction, the run-in's decay with the travel,
    the Brazier factor and the bias's own tilt removed, the plate's sink under the weight's change, the wrinkling
    factor, Hetenyi's root give, the pivot's stops with memory, the conduction's sqrt(t) and the resistor's heat from
    the lowering moves."""
    from dataclasses import replace

    from sim2real_indep import effects_zh_body as zhb
    from sim2real_indep import effects_zh_joint as zhj
    from sim2real_indep import effects_zh_thermal as zht

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZH_KINDS, 30, 34)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZH_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"worn_mesh": lambda: p["c"], "tooth_crack": lambda: p["c"], "grease_gel": lambda: p["half"],
                   "pinion_handover": lambda: p["e"], "running_in_te": lambda: p["e"],
                   "brazier_pedestal": lambda: p["inv_EI"], "dished_plate": lambda: p["c"],
                   "inflated_boom": lambda: p["inv_EI"], "collet_root": lambda: p["inv_k"],
                   "loose_pivot": lambda: p["delta"], "wrist_conduction": lambda: [p["amp"]],
                   "regen_resistor": lambda: [p["amp"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # worn mesh: 1 at the zone's centre, exp(-1/2) one width away
    wp = P["worn_mesh"]
    assert zhj.wear_zone(wp, np.array([wp["q_w"], wp["q_w"] + wp["s"]])) == pytest.approx([1.0, np.exp(-0.5)])
    # tooth crack: 1 at the tooth, 1/2 half a span away, nothing beyond
    cp = P["tooth_crack"]
    qs = cp["q_c"] + np.array([0.0, cp["h"] / 2, 1.01 * cp["h"], -1.01 * cp["h"]])
    assert zhj.crack_window(cp, qs) == pytest.approx([1.0, 0.5, 0.0, 0.0])
    # grease gel: the moves since the last pause, the share 1 - exp(-n / n0)
    gs = replace(s, time_s=np.arange(5.0), gap_s=np.array([0.0, 10.0, -600.0, 10.0, 5.0]))
    assert zhj.moves_since_pause(gs) == pytest.approx([0, 1, 1, 2, 3])
    assert zhj.gel_share({"n0": 2.0}, gs) == pytest.approx(1 - np.exp(-np.array([0, 1, 1, 2, 3]) / 2.0))
    # pinion handover: pinion A's runout after a positive move, B's after a negative one
    sig = zhj.handover_signals({"ratio": 2.0}, np.array([0.3, 0.3]), np.array([1, -1]))
    assert sig[:, 0] == pytest.approx([np.sin(0.6), np.cos(0.6), 0, 0])
    assert sig[:, 1] == pytest.approx([0, 0, np.sin(0.6), np.cos(0.6)])
    # running-in: the travel so far (|dq2| summed), the error fading by exp(-E / E0)
    E = zhj.travel(s, 1)
    assert E[0] == 0 and E[-1] == pytest.approx(np.abs(np.diff(s.q[:, 1])).sum()) and (np.diff(E) >= 0).all()
    # Brazier: 1 + (M / M_b)^2; nothing at the bias alone (its tilt is the calibrated geometry)
    bp = P["brazier_pedestal"]
    assert zhb.brazier_factor(bp, np.array([[bp["M_b"], 0.0, 0.0]])) == pytest.approx([2.0])
    assert np.abs(zhb.brazier_curvature(bp, np.zeros((2, 3)))).max() < 1e-9
    # dished plate: no sink at the first pose's weight, the sink c_F per newton of the weight's change
    Fp = zhb.plate_features(P["dished_plate"], ctx, None)
    W = zhb.total_weight(ctx)
    assert Fp[0, :, 2] == pytest.approx(-(W - W[0])) and np.ptp(W) > 0
    # inflated boom: linear below the wrinkling moment, 1 + a (m - 1)^2 beyond
    ip = P["inflated_boom"]
    assert zhb.wrinkle_factor(ip, np.array([0.5, 1.0, 2.0]) * ip["M_w"]) == pytest.approx([1.0, 1.0, 1 + ip["a"]])
    # collet root (Hetenyi): y0 = 2 beta (V - beta M) / k, theta0 = 2 beta^2 (2 beta M - V) / k
    y0, th0 = zhb.collet_give({"inv_beta_mm": 20.0}, 10.0, 0.0)
    assert (y0, th0) == pytest.approx((2 / 20 * 10, -2 / 400 * 10))
    # loose pivot: rests on the stop its moment chooses beyond the friction, stays where it was inside it
    lp = P["loose_pivot"]
    side, mom = zhb.pivot_side(lp, ctx), zhb.pivot_moment(ctx)
    out = np.abs(mom) > lp["f"]
    assert out.any() and (side[out] == np.sign(mom[out])).all() and set(np.unique(side)) <= {-1.0, 1.0}
    inside = np.flatnonzero(~out)
    assert all(side[k] == (side[k - 1] if k else 1.0) for k in inside)
    # wrist conduction: 2 sqrt(a t / pi), capped at the forearm's length
    L = zht.conduction_length({"t_on_s": 0.0, "a_m2s": 1e-5}, np.array([0.0, 3600.0, 1e9]), 600.0)
    assert L == pytest.approx([0.0, 2 * np.sqrt(1e-5 * 3600 / np.pi) * 1000, 600.0])
    # regen resistor: only lowering moves heat, each decaying by exp(-dt / tau), normalised to a peak of 1
    T = zht.resistor_temperature({"tau_s": 100.0}, np.array([10.0, 4.0, 9.0, 8.0]), np.array([0.0, 100, 200, 300]))
    raw = np.zeros(4)
    raw[1] = 6 * np.exp(-1)
    raw[2] = raw[1] * np.exp(-1)
    raw[3] = (raw[2] + 1) * np.exp(-1)
    assert T == pytest.approx(raw / raw.max())



# --------------------------------------------------------------------------------------------------------- set ZI
ZI_KINDS = ("pi_load_step", "helix_tilt", "dog_play", "free_swivel", "flank_profile", "cage_runout", "gravel_ratchet",
            "crowned_sole", "bernoulli_grip", "jamming_grip", "thermosyphon", "motion_cooling")


def test_set_zi_cases_kinds_and_determinism():
    """Set ZI (the ninth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZH; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZI kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; a new part for
    each block (the rocking sole, the Bernoulli and jamming grippers) and hours of blocks with production or pauses
    between them (the thermal kinds)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zi as ezi
    from sim2real_indep import effects_zi_body as zib

    assert _sorts_after("ZH", "ZI")
    assert cs.case_seed("ZI", 3) == 40_7035 * 1000 + 3 and [c[0] for c in cs.SET_ZI] == [f"ZI{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezi.EFFECTS_ZI) == set(ZI_KINDS)
    _assert_set_module("ZI", 40_7035, ezi, ("gear", "tether_reel", "regen_resistor", "worn_mesh"))
    for name in ("effects_zi", "effects_zi_joint", "effects_zi_body", "effects_zi_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zi" in _imports(STUDY / "generator.py")
    assert ezi.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezi.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezi.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert 3 <= part["blocks"] <= 5 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), gap, pause) in ezi.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        plain = opts(("pi_load_step", "helix_tilt", "dog_play", "free_swivel", "flank_profile", "cage_runout",
                      "gravel_ratchet"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezi.probe_hook(("gear",), probe) is probe
    assert ezi.probe_hook(("bernoulli_grip",), probe) == pytest.approx(probe + [0, 0, zib.PART_MM])
    assert ezi.probe_hook(("jamming_grip",), probe) == pytest.approx(probe + [0, 0, zib.PART_MM])
    _assert_regenerates("ZI", max_effect_poses=50)


def test_set_zi_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZI kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the PI loop's load step and its decay over
    the dwell, the helical tilt across the axis, the dog's play operator, the swivel's friction band, the loaded
    flank's switch, the cage's rate, the ratchet's 1 / (N0 + k) sum, the sole's rocking about one axis against the
    weight, the Bernoulli film's normal load, the jamming grip's reference at each block's start, the thermosyphon's
    attitude switch and the motion cooling's forced convection."""
    from dataclasses import replace

    from sim2real_indep import effects_zi_body as zib
    from sim2real_indep import effects_zi_joint as zij
    from sim2real_indep import effects_zi_thermal as zit

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZI_KINDS, 30, 35)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZI_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"pi_load_step": lambda: p["c"], "helix_tilt": lambda: p["c"], "dog_play": lambda: p["twist"],
                   "free_swivel": lambda: p["e"], "flank_profile": lambda: p["e"], "cage_runout": lambda: p["e"],
                   "gravel_ratchet": lambda: p["a"], "crowned_sole": lambda: p["inv_Rc"],
                   "bernoulli_grip": lambda: p["a"], "jamming_grip": lambda: p["c"],
                   "thermosyphon": lambda: [p["amp"]], "motion_cooling": lambda: [p["amp"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # PI load step: the change of the load from the previous pose (none at the first), decaying as exp(-dwell / T_i)
    step = zij.load_step(ctx, 1)
    assert step[0] == 0 and step[1:] == pytest.approx(np.diff(ctx.loads[:, 1]))
    assert zij.step_share({"Ti_s": 2.0}, s) == pytest.approx(np.exp(-s.dwell_s / 2.0))
    # helix tilt: the tilt axis lies across the joint's axis; no load, no tilt
    ax, _ = zij.tilt_axes(P["helix_tilt"], ctx)
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    assert np.einsum("pi,pi->p", ax[0], w[:, 1]) == pytest.approx(np.zeros(len(s.q)), abs=1e-12)
    assert np.linalg.norm(ax[0], axis=1) == pytest.approx(np.ones(len(s.q)))
    unloaded = replace(ctx, masses=ctx.masses * 0, session=replace(s, payload_kg=s.payload_kg * 0))
    assert np.abs(zij.helix_features(P["helix_tilt"], unloaded, None)).max() < 1e-9
    # dog play: a play operator of half-width D
    g = zij.guide_angle({"D": 1.0, "u0": 0.0}, np.array([0.0, 0.5, 2.0, 1.5, -1.0]))
    assert g == pytest.approx([0.0, 0.0, 1.0, 1.0, 0.0])
    dp = P["dog_play"]
    assert np.abs(s.q[:, 0] - zij.guide_angle(dp, s.q[:, 0])).max() <= dp["D"] + 1e-12
    # free swivel: hangs downhill without friction, stays where it is while gravity along the axis dominates
    g_t = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.05, -0.99]])
    assert zib.swivel_angle({"f": 0.0, "u0": 0.3}, g_t) == pytest.approx([0.0, np.pi / 2, np.pi / 2])
    band = zib.swivel_angle({"f": 0.5, "u0": 0.0}, np.array([[1.0, 0, 0], [0.0, 1.0, 0]]))
    assert band == pytest.approx([0.0, np.pi / 2 - np.arcsin(0.5)])
    # flank profile: the positive load's flank pattern, then the negative one's
    sig = zij.flank_signals({"z": 2}, np.array([0.3, 0.3]), np.array([5.0, -5.0]))
    assert sig[:, 0] == pytest.approx([np.sin(0.6), np.cos(0.6), 0, 0])
    assert sig[:, 1] == pytest.approx([0, 0, np.sin(0.6), np.cos(0.6)])
    # cage runout: the cage turns at (1 - gamma cos(alpha)) / 2 of the shaft
    assert zij.cage_ratio(0.1, 0.0) == pytest.approx(0.45) and 0.4 < P["cage_runout"]["f_c"] < 0.5
    # gravel ratchet: the moments summed with the weights 1 / (N0 + k)
    M = np.array([[1.0, 2.0, 7.0]] * 3)
    tilt = zib.ratchet_tilt({"N0": 1.0}, M)
    assert tilt == pytest.approx(np.outer(np.cumsum([1 / 2, 1 / 3, 1 / 4]), [1.0, 2.0, 0.0]))
    # crowned sole: a tilt about the rocking axis alone, inversely as the standing weight
    sp = P["crowned_sole"]
    F1 = zib.sole_features(sp, ctx, None)[0]
    heavy = {**sp, "base_kg": sp["base_kg"] + 100.0}
    W1, W2 = zib.standing_weight(sp, ctx), zib.standing_weight(heavy, ctx)
    assert W2 - W1 == pytest.approx(np.full(len(W1), 100 * kin.G))
    assert zib.sole_features(heavy, ctx, None)[0] == pytest.approx(F1 * (W1 / W2)[:, None])
    assert F1 @ zib.rocking_axis(sp) == pytest.approx(np.zeros(len(F1)), abs=1e-9)  # a turn about e moves across it
    # Bernoulli grip: the part's weight along the face normal, pulling when the face looks down
    Rt = zib.tool_frame(ctx)
    assert zib.normal_load(ctx) == pytest.approx(s.payload_kg * kin.G * -Rt[:, 2, 2])
    assert len(set(s.payload_kg)) > 1
    # jamming grip: each block's first pose is its reference (no tilt there)
    starts = zib._block_starts(s)
    assert np.abs(zib.seat_moment(P["jamming_grip"], ctx)[np.unique(starts)]).max() == 0 and len(set(starts)) > 1
    toy = replace(s, gap_s=np.array([0.0, 0.0, 60.0, 0.0, 0.0]), payload_kg=np.array([1.0, 1.0, 1.0, 2.0, 2.0]))
    assert list(zib._block_starts(toy)) == [0, 0, 2, 3, 3]
    # thermosyphon: the pipe off with the wrist end level or up, fully on well below; the rise within [0, 1]
    tp = P["thermosyphon"]
    sh = zit.syphon_share(tp, ctx)
    assert ((sh >= 0) & (sh <= 1)).all() and sh.max() > 0 and sh.min() == 0
    T = zit.syphon_temperature(tp, ctx)
    assert ((T >= 0) & (T <= 1)).all() and np.ptp(T) > 0
    # motion cooling: h / h0 = 1 + b (v / 1 m/s)^0.8; with no forced convection and no gaps a plain first-order rise
    cp = P["motion_cooling"]
    assert zit.convection(cp, np.array([0.0, 1.0, 2.0])) == pytest.approx([1.0, 1 + cp["b"], 1 + cp["b"] * 2 ** 0.8])
    assert zit.link_speed(ctx)[0] == 0 and (zit.link_speed(ctx) >= 0).all()
    still = replace(ctx, session=replace(s, gap_s=np.zeros(len(s.gap_s))))
    T = zit.cooling_temperature({**cp, "b": 0.0}, still)
    assert T == pytest.approx(1 + (cp["T0"] - 1) * np.exp(-(s.time_s - s.time_s[0]) / cp["tau0_s"]))


# --------------------------------------------------------------------------------------------------------- set ZJ
ZJ_KINDS = ("gauge_zero_drift", "traction_microslip", "gyro_filter", "wind_flank", "stepper_stall", "ghost_order",
            "hydrostatic_rail", "clay_pier", "gecko_pad", "warm_sag", "stray_weld_current", "plume_bracket")


def test_set_zj_cases_kinds_and_determinism():
    """Set ZJ (the tenth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the benchmark
    and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3 mixtures, a
    quarter split by time; its name keys the case seeds and sorts after ZI; a case regenerates bit-identically from its
    seed; the session hook leaves cases without a set-ZJ kind alone (no random numbers drawn) and the probe hook draws
    none; the generator reaches the set's modules and none imports tolalloc; a new part for each block (the gecko pad,
    the warm panel, the plume's hot part) and hours of blocks with production or pauses between them (the sensors'
    warm-up, the welding current, the plume)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zj as ezj
    from sim2real_indep import effects_zj_body as zjb
    from sim2real_indep import effects_zj_thermal as zjt

    assert _sorts_after("ZI", "ZJ")
    assert cs.case_seed("ZJ", 3) == 40_7036 * 1000 + 3 and [c[0] for c in cs.SET_ZJ] == [f"ZJ{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezj.EFFECTS_ZJ) == set(ZJ_KINDS)
    _assert_set_module("ZJ", 40_7036, ezj, ("gear", "tether_reel", "thermosyphon", "jamming_grip"))
    for name in ("effects_zj", "effects_zj_joint", "effects_zj_body", "effects_zj_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zj" in _imports(STUDY / "generator.py")
    assert ezj.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezj.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezj.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert part["blocks"] >= 3 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), gap, pause) in ezj.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        plain = opts(("traction_microslip", "gyro_filter", "wind_flank", "stepper_stall", "ghost_order",
                      "hydrostatic_rail", "clay_pier"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezj.probe_hook(("gear",), probe) is probe
    assert ezj.probe_hook(("gecko_pad",), probe) == pytest.approx(probe + [0, 0, zjb.PART_MM])
    assert ezj.probe_hook(("warm_sag",), probe) == pytest.approx(probe + [zjb.PANEL_MM, 0, 0])
    assert ezj.probe_hook(("plume_bracket",), probe) == pytest.approx(probe + [0, 0, zjt.BRACKET_MM])
    _assert_regenerates("ZJ", max_effect_poses=50)


def test_set_zj_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZJ kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm; and known answers: the sensors' warm-up node, Mindlin's virgin
    curve and Masing's rule, the complementary filter's memory, the stalls' losses against the motion, the ghost
    order's sine, the opposed pads' cube law and the rail's roll, the piers' cube about their line, the gecko pad's
    shear stiffening, the warm panel's creep reset with each part, the wind's flank and its torque's sign, the welding
    node's heating in production and the plume's attitude share."""
    from dataclasses import replace

    from sim2real_indep import effects_zj_body as zjb
    from sim2real_indep import effects_zj_joint as zjj
    from sim2real_indep import effects_zj_thermal as zjt

    runs = {}
    for robot in ("ur10", "tool_changer", "kr16_like"):
        case = gen.generate("t", robot, ZJ_KINDS, 30, 36)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in ZJ_KINDS:
            d, A = _effect_and_features(case, ctx, kind)
            p = case.truth["params"][kind]
            amp = {"gauge_zero_drift": lambda: p["c"], "traction_microslip": lambda: p["A"],
                   "gyro_filter": lambda: p["s"], "wind_flank": lambda: [p["b2"]], "stepper_stall": lambda: p["loss"],
                   "ghost_order": lambda: p["e"], "hydrostatic_rail": lambda: [p["h0"]], "clay_pier": lambda: [p["c"]],
                   "gecko_pad": lambda: [p["inv_k0"]], "warm_sag": lambda: [p["A"]],
                   "stray_weld_current": lambda: p["amp"], "plume_bracket": lambda: [p["amp"]]}[kind]()
            _assert_features_reproduce(d, A, amp, rtol=1e-8, min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    t = s.time_s - s.time_s[0]
    # the sensors' warm-up: without gaps a plain first-order rise from T0 towards 1; a pause cools towards 0
    still = replace(s, gap_s=np.zeros(len(s.gap_s)))
    zp = P["gauge_zero_drift"]
    assert zjj.zero_node(zp, still) == pytest.approx(1 + (zp["T0"] - 1) * np.exp(-t / zp["tau_s"]))
    toy = replace(s, time_s=np.array([0.0, 4000.0]), gap_s=np.array([0.0, -3600.0]), dwell_s=np.array([5.0, 5.0]))
    node = zjt.gap_node(toy, 1.0, 600.0, 1.0, 1.5, 0.0)
    assert node[1] == pytest.approx(1 + (np.exp(-6.0) - 1) * np.exp(-400 / 600))
    # Mindlin micro-slip: the virgin curve from the unloaded state; Masing's branch from a reversal
    u = np.linspace(0.0, 0.8, 41)
    assert zjj.mindlin_masing(u) == pytest.approx(zjj.mindlin_virgin(u), abs=2e-3)
    assert zjj.mindlin_virgin(0.5) == pytest.approx(1 - 0.5 ** (2 / 3))
    path = np.r_[np.linspace(0.0, 0.7, 15), np.linspace(0.65, -0.5, 24)]
    x = zjj.mindlin_masing(path)
    branch = x[14] - 2 * zjj.mindlin_virgin((0.7 - path[15:]) / 2)
    assert x[15:] == pytest.approx(branch, abs=3e-3)
    assert zjj.mindlin_masing(-path) == pytest.approx(-x)
    # the complementary filter: a move's share decays over its dwell, then with the time between poses
    fs = replace(s, time_s=np.array([0.0, 10.0, 20.0]), dwell_s=np.array([5.0, 4.0, 6.0]))
    E = zjj.filter_memory({"tau_s": 3.0}, fs, np.array([[0.0], [0.2], [0.2]]))
    assert E[:, 0] == pytest.approx([0.0, 0.2 * np.exp(-4 / 3), 0.2 * np.exp(-4 / 3) * np.exp(-10 / 3)])
    # stepper stalls: one loss against the motion per stalled move; some 5-15 % of the moves stall
    assert zjj.stall_count([0, 1, 0, 1, 1], np.array([0.0, 1.0, 2.0, 1.5, 1.0])) == pytest.approx([0, -1, -1, 0, 1])
    for ev in P["stepper_stall"]["events"]:
        assert 0 < np.mean(ev[1:]) <= 0.2 and not ev[0]
    # ghost order: the hobbing machine's index order on axis 1
    gp = P["ghost_order"]
    assert 60 <= gp["z"] <= 200
    assert zjj.ghost_features(gp, ctx, None)[0] == pytest.approx(ctx.joint_feature(0, np.sin(gp["z"] * s.q[:, 0])))
    # opposed constant-flow pads: the film change solves the cube law; equal sides do not roll the carriage
    f = np.array([-2.0, 0.0, 0.7, 5.0])
    d = zjb.opposed_film(f)
    assert (1 - d) ** -3 - (1 + d) ** -3 == pytest.approx(f, rel=1e-6, abs=1e-9) and d[1] == pytest.approx(0, abs=1e-9)
    hp = P["hydrostatic_rail"]
    sides = zjb.rail_sides(hp, ctx)
    m, _, _ = ctx.mass_state
    assert sides.sum(axis=1) == pytest.approx(hp["f_nom"] * (m.sum(axis=1) + hp["carriage_kg"]) * kin.G / hp["F_ref"])
    level = {**hp, "s_mm": 1e12}  # a very wide rail: the roll moment no longer loads the sides apart
    Fl = zjb.hydro_features(level, ctx, None)[0]
    assert Fl[:, :2] == pytest.approx(np.zeros((len(Fl), 2)), abs=1e-9)
    # clay piers: a turn about their line, with the cube of the moment along it
    cp = P["clay_pier"]
    e = zjb.pier_axis(cp)
    assert zjb.pier_features(cp, ctx, None)[0] @ e == pytest.approx(np.zeros(len(s.q)), abs=1e-9)
    M = np.array([[100.0, 50.0, 3.0]])
    assert zjb.pier_tilt(cp, 2 * M) == pytest.approx(8 * zjb.pier_tilt(cp, M))
    # gecko pad: the plain weight moment over (1 + kappa S+ / S_ref)
    gk = P["gecko_pad"]
    w = s.payload_kg[:, None] * kin.G * -zjb.tool_frame(ctx)[:, 2, :]
    plain = np.cross([0.0, 0.0, gk["d_mm"] / 1000.0], w)
    stiff = 1 + gk["kappa"] * np.maximum(w[:, 0], 0) / gk["S_ref"]
    assert zjb.gecko_tilt(gk, ctx) * stiff[:, None] == pytest.approx(plain)
    # warm sag: nothing at each part's first pose; with the part's weight across it held, the creep sums the fluidity
    starts = zjb._block_starts(s)
    hist = zjb.creep_history(P["warm_sag"], ctx)
    assert np.abs(hist[np.unique(starts)]).max() == 0 and len(set(starts)) > 1
    # wind flank: where the wind's torque beats the drag, its sign; a reversed wind reverses the torque
    wp = P["wind_flank"]
    T = zjb.wind_torque(case.truth["chain"], s.q, wp["psi"])
    big = np.abs(T) > 1.01 * wp["share"] * np.abs(T).max()
    assert np.asarray(wp["flank"])[big] == pytest.approx(np.sign(T[big])) and big.any()
    assert zjb.wind_torque(case.truth["chain"], s.q, wp["psi"] + np.pi) == pytest.approx(-T)
    # stray welding current: the housings warm in production only; the shifts lie along the joints' axes
    toy = replace(s, time_s=np.array([0.0, 1000.0, 1300.0]), gap_s=np.array([0.0, 900.0, 0.0]))
    node = zjt.weld_node({"T0": 0.5, "tau_s": 600.0}, toy)
    hot = 1 - 0.5 * np.exp(-1.5)
    assert node == pytest.approx([0.5, hot * np.exp(-100 / 600), hot * np.exp(-400 / 600)])
    wf = zjt.weld_features(P["stray_weld_current"], ctx, None)
    axes, _ = kin.joint_frames(ctx.chain, ctx.q)
    assert np.cross(wf[1], axes[:, 1]) == pytest.approx(np.zeros((len(s.q), 3)), abs=1e-12)
    # hot part's plume: the whole plume with the tool pointing down, none pointing up; the bracket's rise in [0, 1]
    pp = P["plume_bracket"]
    down = np.array([np.diag([1.0, -1.0, -1.0]), np.eye(3)])
    assert zjt.plume_share(pp, down) == pytest.approx([1.0, 0.0])
    Tb = zjt.plume_temperature(pp, ctx)
    assert ((Tb >= 0) & (Tb <= 1)).all() and Tb.max() > 0


# --------------------------------------------------------------------------------------------------------- set ZK
ZK_KINDS = ("kt_magnet_drift", "capstan_spans", "sensor_hysteresis", "housing_spread", "quench_ovality",
            "ride_height", "beam_torsion", "asphalt_creep", "flange_buckling", "dashpot_slide", "drive_board_heat",
            "ram_wiper_heat")


def test_set_zk_cases_kinds_and_determinism():
    """Set ZK (the eleventh two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZJ; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZK kind alone (no random numbers drawn)
    and the probe hook draws none; the generator reaches the set's modules and none imports tolalloc; a new part for
    each block (the buckling bracket, the dashpot slide, the ride height, the beam) and hours of blocks with production
    or pauses between them (the magnets, the drive boards, the asphalt, the ram)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zk as ezk
    from sim2real_indep import effects_zk_body as zkb

    assert _sorts_after("ZJ", "ZK")
    assert cs.case_seed("ZK", 3) == 40_7037 * 1000 + 3 and [c[0] for c in cs.SET_ZK] == [f"ZK{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezk.EFFECTS_ZK) == set(ZK_KINDS)
    _assert_set_module("ZK", 40_7037, ezk, ("gear", "gauge_zero_drift", "plume_bracket", "hydrostatic_rail"))
    for name in ("effects_zk", "effects_zk_joint", "effects_zk_body", "effects_zk_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zk" in _imports(STUDY / "generator.py")
    assert ezk.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezk.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezk.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                assert part["blocks"] >= 3 and len(part["payload_steps"]) == part["blocks"]
                assert kg[robot][0] <= min(part["payload_steps"]) and max(part["payload_steps"]) <= kg[robot][1]
        for kind, ((lo, hi), gap, pause) in ezk.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        plain = opts(("capstan_spans", "sensor_hysteresis", "housing_spread", "quench_ovality"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe = np.array([1.0, 2.0, 3.0])
    assert ezk.probe_hook(("gear",), probe) is probe
    assert ezk.probe_hook(("flange_buckling",), probe) == pytest.approx(probe + [0, 0, zkb.BRACKET_MM])
    assert ezk.probe_hook(("dashpot_slide",), probe) == pytest.approx(probe + [0, 0, zkb.SLIDE_MM])
    _assert_regenerates("ZK", max_effect_poses=50)


def test_set_zk_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZK kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: the magnets' node and the
    load it scales, the capstan spans' parabola, the play operator of the sensor's hysteresis, the housing's trailing
    flank and its moment, the ring's orders 2 and 4, the ride height's gap scale, the beam's twist about its line and
    its sink, the asphalt's creep integrals, the bracket's one-sided buckling, the dashpot's relaxation, the drive
    boards' levels and the ram's heating by its stroke."""
    from dataclasses import replace

    from sim2real_indep import effects_zk_body as zkb
    from sim2real_indep import effects_zk_joint as zkj
    from sim2real_indep import effects_zk_thermal as zkt
    from sim2real_indep.effects_body import mount_moment

    amps = {"kt_magnet_drift": "c", "capstan_spans": "c", "sensor_hysteresis": "a", "housing_spread": "b",
            "quench_ovality": "e", "ride_height": "e", "beam_torsion": "c", "asphalt_creep": "c",
            "flange_buckling": "c0", "dashpot_slide": "inv_k", "drive_board_heat": "amp", "ram_wiper_heat": "amp"}
    specs = {"ur10": ("kt_magnet_drift", "capstan_spans", "sensor_hysteresis", "beam_torsion", "dashpot_slide",
                      "drive_board_heat", "flange_buckling"),
             "tool_changer": ("quench_ovality", "housing_spread", "asphalt_creep", "ram_wiper_heat"),
             "kr16_like": ("ride_height", "quench_ovality", "housing_spread", "sensor_hysteresis")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 37)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    t = s.time_s - s.time_s[0]
    # magnets: without gaps a first-order rise from T0 towards 1, scaling each loaded axis' gravity load
    kp = P["kt_magnet_drift"]
    still = replace(s, gap_s=np.zeros(len(s.gap_s)))
    T = zkj.magnet_node(kp, still)
    assert T == pytest.approx(1 + (kp["T0"] - 1) * np.exp(-t / kp["tau_s"]))
    F = zkj.kt_features(kp, replace(ctx, session=still), None)
    assert F[0] == pytest.approx(ctx.joint_feature(1, ctx.loads[:, 1] * T))
    # capstan spans: the parabola 1 - (rho u / u_far)^2, 1 at the sector's centre, 1 - rho^2 at the farther end
    cp = P["capstan_spans"]
    lo, hi = np.deg2rad(-250.0), np.deg2rad(70.0)  # ur10's axis 4 in its measurement box
    qc = (lo + hi) / 2 + cp["shift"][3] * (hi - lo) / 2
    far = lo if qc - lo > hi - qc else hi
    assert zkj.span_factor(cp, 3, np.array([qc, far])) == pytest.approx([1.0, 1 - cp["rho"][3] ** 2])
    # the play operator: follows within +-r, holds inside the band
    assert zkj.play(np.array([0.0, 3.0, 2.0, 0.5, 4.0]), 1.0) == pytest.approx([0.0, 2.0, 2.0, 1.5, 3.0])
    e = zkj.hysteresis_error(P["sensor_hysteresis"], ctx, 1)
    assert (np.abs(e) <= 1 + 1e-12).all() and np.ptp(e) > 0
    # beam torsion: the twist turns about the beam's line (no motion along it from the twist); a zero sink ratio
    bp = P["beam_torsion"]
    tw = zkb.beam_features({**bp, "sink_ratio_m2": 0.0}, ctx, None)[0]
    assert tw @ zkb.beam_axis(bp) == pytest.approx(np.zeros(len(tw)), abs=1e-9)
    sink = zkb.beam_features(bp, ctx, None)[0] - tw
    assert sink[:, :2] == pytest.approx(np.zeros((len(tw), 2)), abs=1e-12) and (sink[:, 2] < 0).all()
    assert np.unique(sink[:, 2].round(9)).size == len(set(s.payload_kg))  # the sink changes with the part only
    # dashpot slide: with a very short delay the slide follows the load; a step relaxes with tau
    dp = P["dashpot_slide"]
    Fz = zkb.axial_load(dp, ctx)
    assert zkb.kelvin_voigt({"tau_s": 1e-6}, s, Fz) == pytest.approx(Fz)
    toy = replace(s, time_s=np.array([0.0, 10.0]), gap_s=np.zeros(2))
    assert zkb.kelvin_voigt({"tau_s": 5.0}, toy, np.array([1.0, 3.0]))[1] == pytest.approx(3 - 2 * np.exp(-2))
    # flange buckling: stiff one way, softer by 1 / rho past F_cr the other
    fb = {"rho": 0.5, "F_cr": 2.0}
    assert zkb.buckle_law(fb, np.array([-5.0, 1.0, 2.0, 4.0])) == pytest.approx([-5.0, 1.0, 2.0, 6.0])
    # drive boards: servo on towards 1, pauses towards w_pause; the tubes a2 and a3 stretch
    bo = P["drive_board_heat"]
    toy = replace(s, time_s=np.array([0.0, 600.0, 1200.0]), gap_s=np.array([0.0, -600.0, 0.0]))
    node = zkt.board_node({**bo, "T0": 1.0}, toy)
    assert node == pytest.approx([1.0, bo["w_pause"] + (1 - bo["w_pause"]) * np.exp(-600 / bo["tau_s"]),
                                  1 + (node[1] - 1) * np.exp(-600 / bo["tau_s"])])
    assert [ctx.chain.link_names[i] for i in zkt.hot_links(ctx.chain)] == ["a2", "a3"]

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # quench ovality: orders 2 and 4 of axis 1
    F = zkj.ovality_features(P["quench_ovality"], ctx, None)
    assert len(F) == 4 and F[2] == pytest.approx(ctx.joint_feature(0, np.sin(4 * s.q[:, 0])))
    # housing spread: the trailing flank, widened with the horizontal moment
    hp = P["housing_spread"]
    M = np.linalg.norm(mount_moment(ctx)[:, :2], axis=1)
    assert zkj.housing_moment(ctx) == pytest.approx(M) and hp["M_ref"] == pytest.approx(M.max(), rel=2e-2)
    F = zkj.spread_features(hp, ctx, None)
    assert F[1] == pytest.approx(F[0] * (M / hp["M_ref"])[:, None])
    assert F[0] == pytest.approx(ctx.joint_feature(0, -s.direction[:, 0]))
    # asphalt: the creep integrals grow with the fluidity, which rises with the pavement's warming
    ap = P["asphalt_creep"]
    phi = zkb.fluidity(ap, s)
    assert phi[0] == pytest.approx(1.0) and (np.diff(phi) >= 0).all()
    IM, IW = zkb.creep_integrals(ap, ctx)
    assert IW[0] == 0 and (np.diff(IW) > 0).all()
    # ram wipers: one full stroke adds kappa; production warms towards 1, a pause cools towards 0
    rp = {"T0": 0.0, "tau_s": 1e12, "kappa": 0.05}
    toy = replace(s, time_s=np.array([0.0, 10.0, 20.0]), gap_s=np.zeros(3))
    assert zkt.ram_node(rp, toy, np.array([0.0, 500.0, 250.0])) == pytest.approx([0.0, 0.05, 0.075])
    prod = replace(toy, time_s=np.array([0.0, 1000.0, 1010.0]), gap_s=np.array([0.0, 990.0, 0.0]))
    assert zkt.ram_node({**rp, "tau_s": 600.0}, prod, np.zeros(3))[1] == pytest.approx(
        (1 - np.exp(-990 / 600)) * np.exp(-10 / 600))

    case, ctx = runs["kr16_like"]
    # ride height: the gap scale is zero without a payload and grows with it
    d = zkj.gap_scale(ctx)
    W0 = float(np.sum(ctx.masses)) * kin.G
    assert d == pytest.approx(((W0 + ctx.session.payload_kg * kin.G) ** (2 / 3) - W0 ** (2 / 3)) / W0 ** (2 / 3))
    F = zkj.ride_features(case.truth["params"]["ride_height"], ctx, None)
    assert len(F) == 8 and F[4] == pytest.approx(F[0] * d[:, None]) and len(set(ctx.session.payload_kg)) > 1


# --------------------------------------------------------------------------------------------------------- set ZL
ZL_KINDS = ("idle_current", "kt_saturation", "current_remanence", "hose_bourdon", "stator_leakage", "step_truncation",
            "raised_floor", "load_cells", "ft_sensor", "pad_pivot", "thermal_ratchet", "arc_radiation")


def test_set_zl_cases_kinds_and_determinism():
    """Set ZL (the twelfth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZK; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZL kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; a
    new part for each block (every other block empty for the hose), and hours of blocks with production or pauses
    between them (the restrained tubes, the arc)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zl as ezl
    from sim2real_indep import effects_zl_body as zlb

    assert _sorts_after("ZK", "ZL")
    assert cs.case_seed("ZL", 3) == 40_7038 * 1000 + 3 and [c[0] for c in cs.SET_ZL] == [f"ZL{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezl.EFFECTS_ZL) == set(ZL_KINDS)
    _assert_set_module("ZL", 40_7038, ezl, ("gear", "kt_magnet_drift", "ram_wiper_heat", "beam_torsion"))
    for name in ("effects_zl", "effects_zl_joint", "effects_zl_body", "effects_zl_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zl" in _imports(STUDY / "generator.py")
    assert ezl.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezl.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezl.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                part = opts((kind,), robot)
                steps = np.array(part["payload_steps"])
                assert part["blocks"] >= 3 and len(steps) == part["blocks"]
                if kind in ezl.SOME_EMPTY:  # every other block without a part
                    assert (steps == 0).sum() in (len(steps) // 2, (len(steps) + 1) // 2) and (steps > 0).any()
                    steps = steps[steps > 0]
                assert kg[robot][0] <= steps.min() and steps.max() <= kg[robot][1]
        for kind, ((lo, hi), gap, pause) in ezl.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        plain = opts(("current_remanence", "stator_leakage", "step_truncation", "load_cells"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe, com = np.array([1.0, 2.0, 3.0]), np.array([30.0, -40.0, 0.0])
    assert ezl.probe_hook(("gear",), probe) is probe and ezl.payload_hook(("gear",), com) is com
    assert ezl.probe_hook(("ft_sensor",), probe) == pytest.approx(probe + [0, 0, zlb.FT_TARGET_MM])
    assert ezl.probe_hook(("pad_pivot",), probe) == pytest.approx(probe + [0, 0, zlb.PART_TARGET_MM])
    assert ezl.payload_hook(("pad_pivot",), com) == pytest.approx([6.0, -8.0, zlb.PAD_MM + 40.0 + 50.0 * 50 / 80])
    _assert_regenerates("ZL", max_effect_poses=50)


def test_set_zl_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZL kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: the stepper's load angles at
    the cut current, the saturation's cube, the current sensor's core (its memory, its reset at each enable), the hose
    flank while a part is held, the leakage's electrical order, the truncated counts' running sum, the raised floor's
    grid axes, the load cells' tilt and sink, the F/T sensor's loads, the pads' turn about the closing axis, the
    restrained tubes' play and the arc's node and forearm."""
    from dataclasses import replace

    from sim2real_indep import effects_zl_body as zlb
    from sim2real_indep import effects_zl_joint as zlj
    from sim2real_indep import effects_zl_thermal as zlt
    from sim2real_indep.effects_body import mount_moment

    amps = {"idle_current": "c", "kt_saturation": "c", "current_remanence": "a", "hose_bourdon": "b",
            "stator_leakage": "e", "step_truncation": "amp", "raised_floor": "c", "load_cells": "c",
            "ft_sensor": "inv_Kt", "pad_pivot": "inv_k", "thermal_ratchet": "amp", "arc_radiation": "amp"}
    specs = {"ur10": ("idle_current", "current_remanence", "stator_leakage", "raised_floor", "pad_pivot",
                      "thermal_ratchet", "arc_radiation"),
             "tool_changer": ("hose_bourdon", "ft_sensor", "kt_saturation", "load_cells"),
             "kr16_like": ("step_truncation", "kt_saturation", "hose_bourdon", "stator_leakage")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 38)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    # idle current: asin(u / r) - asin(u), none without load, below the pull-out (u / r < 1)
    ip = P["idle_current"]
    u = ctx.loads[:, 3] / ip["T_H"][3]
    assert zlj.idle_sag(ip, ctx, 3) == pytest.approx(np.arcsin(u / ip["r"]) - np.arcsin(u))
    assert np.abs(u / ip["r"]).max() < 0.81
    assert zlj.idle_sag({**ip, "T_H": {3: np.inf}}, ctx, 3) == pytest.approx(np.zeros(len(u)))
    # current remanence: an excursion past I_c sets the core, a smaller one of that sign keeps it, an opposite one
    # flips it; the auto-zero at an enable takes the state then as the reference
    x = np.array([[0.0, 0.0, 0.0], [3.0, -1.0, 0.5], [2.5, 0.2, 0.1], [-3.5, 1.0, 0.0], [0.0, 0.0, 0.0]])
    reset = np.array([True, False, False, False, True])
    g3, g35 = np.tanh(3.0 / 4.0), np.tanh(3.5 / 4.0)
    assert zlj.core_state(x, 2.0, 4.0, reset) == pytest.approx([0.0, g3, g3, -g35, 0.0])
    e = zlj.remanence_error(P["current_remanence"], ctx, 1)
    assert e[0] == 0 and (np.abs(e) <= 2 + 1e-12).all()
    # stator leakage: the load times the motor's electrical order p N - 1
    lp = P["stator_leakage"]
    assert all(any((K + 1) % p == 0 and 100 <= (K + 1) // p <= 160 for p in range(4, 9)) for K in lp["K"].values())
    F = zlj.leakage_features(lp, ctx, None)
    assert len(F) == 4 and F[0] == pytest.approx(ctx.joint_feature(1, ctx.loads[:, 1] / lp["tau_max"][1]
                                                                   * np.sin(lp["K"][1] * s.q[:, 1])))
    # raised floor: each column turns the arm about one grid axis (no motion along it from the tilt)
    fp = P["raised_floor"]
    e1, e2 = zlb.grid_axes(fp)
    F = zlb.floor_features({**fp, "Lv_m": 0.0}, ctx, None)
    assert F[0] @ e1 == pytest.approx(np.zeros(len(s.q)), abs=1e-9) and F[1] @ e2 == pytest.approx(
        np.zeros(len(s.q)), abs=1e-9)
    # finger pads: the part turns about the closing axis (the tool's y): no motion along it
    Fp = zlb.pad_features(P["pad_pivot"], ctx, None)[0]
    y = zlb.tool_frame(ctx)[:, :, 1]
    assert np.einsum("pi,pi->p", Fp, y) == pytest.approx(np.zeros(len(s.q)), abs=1e-9)
    # restrained tubes: a play of the node (no play: the node itself; a play wider than its range: no growth)
    rp = P["thermal_ratchet"]
    T = zlt.ratchet_node(rp, s)
    assert zlt.ratchet_growth({**rp, "r": [0.0, 0.0]}, s, 0) == pytest.approx(T)
    assert zlt.ratchet_growth({**rp, "r": [9.0, 9.0]}, s, 1) == pytest.approx(np.full(len(T), T[0]))
    assert zlt.play(np.array([0.0, 0.5, 1.0, 0.6, 0.2]), 0.3) == pytest.approx([0.0, 0.2, 0.7, 0.7, 0.5])
    # arc radiation: no production, no heat; the forearm's stretch column is its link's
    ap = P["arc_radiation"]
    still = replace(s, gap_s=np.where(s.gap_s > 0, -s.gap_s, s.gap_s))
    assert np.abs(zlt.arc_node(ap, still)).max() == 0.0
    li = ctx.chain.link_names.index("a3")
    assert zlt.bow_parts(ap, ctx)[1] == pytest.approx(ctx.link_scale_feature(np.arange(6) == li))

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # hose flank: the roll axis' flank follows sign(tau + T_h) beyond the friction while a part is held
    hp = P["hose_bourdon"]
    fl = zlj.bourdon_flank(hp, ctx, 5)
    held = s.payload_kg > 0
    t = ctx.loads[:, 5] + held * hp["T_h"][5]
    assert fl[np.abs(t) > hp["f"][5]] == pytest.approx(np.sign(t[np.abs(t) > hp["f"][5]]))
    assert fl[np.abs(t) <= hp["f"][5]] == pytest.approx(-s.direction[np.abs(t) <= hp["f"][5], 5])
    assert held.any() and (~held).any()
    # Kt saturation: the cube of the load over its largest square (the load itself at the largest)
    sg = zlj.saturation_sag(ctx, 4)
    k = np.abs(ctx.loads[:, 4]).argmax()
    assert sg[k] == pytest.approx(ctx.loads[k, 4]) and sg == pytest.approx(ctx.loads[:, 4] ** 3
                                                                             / ctx.loads[k, 4] ** 2)
    # F/T sensor: the force is the tool's and the part's weight
    Fs, _ = zlb.sensor_loads(P["ft_sensor"], ctx)
    assert np.linalg.norm(Fs, axis=1) == pytest.approx((P["ft_sensor"]["tool_kg"] + s.payload_kg) * kin.G)
    # load cells: tilts M_l / (4 a_s^2), M_s / (4 a_l^2) about the cells' top, the sink W / 4
    cp = P["load_cells"]
    sq = {**cp, "a_l": 0.5, "a_s": 0.5}
    M = mount_moment(ctx) * [1.0, 1.0, 0.0]
    W = zlb.total_weight(ctx)
    expect = np.cross(M / 1.0, ctx.target - [0, 0, -cp["pivot_mm"]]) - 1000.0 * (W / 4)[:, None] * [0, 0, 1.0]
    assert zlb.cells_features(sq, ctx, None)[0] == pytest.approx(expect)

    case, ctx = runs["kr16_like"]
    # step truncation: the running sum of the truncated moves' shortfalls
    assert zlj.truncation_lag(np.array([0.0, 2.5, 1.2, 1.2]), 1.0) == pytest.approx([0.0, -0.5, -0.2, -0.2])
    tp = case.truth["params"]["step_truncation"]
    assert zlj.wrist_joints(ctx.chain) == [3, 4, 5] and all(np.deg2rad(0.005) < v < np.deg2rad(0.05)
                                                            for v in tp["s"].values())
    assert zlj.roll_joints(ctx.chain) == [3, 5]


# --------------------------------------------------------------------------------------------------------- set ZM
ZM_KINDS = ("moment_softening", "mesh_ripple", "upstream_toss", "limiter_play", "microstep_error", "step_accuracy",
            "conical_mounts", "rail_blocks", "mandrel_rock", "jaw_guide_tilt", "mean_radiant", "enclosure_door")


def test_set_zm_cases_kinds_and_determinism():
    """Set ZM (the thirteenth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZL; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZM kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; a
    new part for each block, hours of blocks with pauses and a drifting hall air (the radiant envelope), a loading
    pause before each block (the enclosure's door)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zm as ezm
    from sim2real_indep import effects_zm_body as zmb

    assert _sorts_after("ZL", "ZM")
    assert cs.case_seed("ZM", 3) == 40_7039 * 1000 + 3 and [c[0] for c in cs.SET_ZM] == [f"ZM{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezm.EFFECTS_ZM) == set(ZM_KINDS)
    _assert_set_module("ZM", 40_7039, ezm, ("gear", "idle_current", "arc_radiation", "load_cells"))
    for name in ("effects_zm", "effects_zm_joint", "effects_zm_body", "effects_zm_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zm" in _imports(STUDY / "generator.py")
    assert ezm.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezm.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezm.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                steps = np.array(opts((kind,), robot)["payload_steps"])
                assert len(steps) >= 3 and kg[robot][0] <= steps.min() and steps.max() <= kg[robot][1]
                assert len(steps) == opts((kind,), robot)["blocks"]
        for kind, ((lo, hi), gap, pause) in ezm.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        air = opts(("mean_radiant",))["air"]
        assert 3.0 <= abs(air["drift_K"]) <= 8.0 and 0.0 <= air["cycle_K"] <= 0.5
        plain = opts(("upstream_toss", "limiter_play", "microstep_error", "step_accuracy", "mesh_ripple"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe, com = np.array([1.0, 2.0, 3.0]), np.array([30.0, -40.0, 0.0])
    assert ezm.probe_hook(("gear",), probe) is probe and ezm.payload_hook(("gear",), com) is com
    assert ezm.probe_hook(("mandrel_rock",), probe) == pytest.approx(probe + [0, 0, zmb.MANDREL_TARGET_MM])
    assert ezm.probe_hook(("jaw_guide_tilt",), probe) == pytest.approx(probe + [0, 0, zmb.JAW_TARGET_MM])
    assert ezm.payload_hook(("mandrel_rock",), com) == pytest.approx([6.0, -8.0, zmb.MANDREL_MM + 30.0 + 50.0 * 50 / 80])
    assert ezm.payload_hook(("jaw_guide_tilt",), com) == pytest.approx([6.0, -8.0, zmb.JAW_MM + 40.0 + 60.0 * 50 / 80])
    _assert_regenerates("ZM", max_effect_poses=50)


def test_set_zm_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZM kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: the moment softening's and the
    mesh ripple's twist (the plain gravity twist without them), the toss's flank (the gravity flank where gravity beats
    the friction, no inertial torque at rest), the limiter's flank, the microstep error's full-step period, the step
    error's once-per-turn period, the mounts' load distribution (weight and moment balance), the rail blocks' linear
    limit, the mandrel's and the jaws' turn about their own points, the radiant envelope's node (nothing in still air,
    the air itself without walls or lag) and the enclosure's node (nothing without loadings)."""
    from dataclasses import replace

    from sim2real_indep import effects_zm_body as zmb
    from sim2real_indep import effects_zm_joint as zmj
    from sim2real_indep import effects_zm_thermal as zmt
    from sim2real_indep.effects_body import mount_moment

    amps = {"moment_softening": "c", "mesh_ripple": "c", "upstream_toss": "b", "limiter_play": "b",
            "microstep_error": "amp", "step_accuracy": "amp", "conical_mounts": "c", "rail_blocks": "c",
            "mandrel_rock": "inv_kf", "jaw_guide_tilt": "inv_KA", "mean_radiant": "cte", "enclosure_door": "amp"}
    specs = {"ur10": ("rail_blocks", "limiter_play", "microstep_error", "conical_mounts", "mandrel_rock",
                      "enclosure_door"),
             "tool_changer": ("moment_softening", "upstream_toss", "jaw_guide_tilt", "mean_radiant"),
             "kr16_like": ("upstream_toss", "step_accuracy", "mesh_ripple", "moment_softening")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 39)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # moment softening / mesh ripple: the gravity twist itself without the coupling; the moment about the axis is the load
    assert zmj.wrist_bends(ctx.chain) == [4]
    assert np.einsum("pi,pi->p", zmj.joint_moment(ctx, 4), kin.joint_frames(ctx.chain, ctx.q)[0][:, 4]) == \
        pytest.approx(ctx.loads[:, 4])
    assert zmj.softening_twist({**P["moment_softening"], "g": 0.0}, ctx, 4) == pytest.approx(ctx.loads[:, 4])
    rp = P["mesh_ripple"]
    assert zmj.ripple_twist({**rp, "e": {4: 0.0}}, ctx, 4) == pytest.approx(ctx.loads[:, 4])
    assert 80 <= rp["N"][4] <= 160
    # upstream toss: the gravity flank where gravity beats the friction; no inertial torque without moves
    tp = P["upstream_toss"]
    fl, tau = zmj.toss_flank(tp, ctx), ctx.loads[:, 4]
    assert fl[np.abs(tau) > tp["f"]] == pytest.approx(np.sign(tau[np.abs(tau) > tp["f"]]))
    still = replace(ctx, session=replace(s, speed=np.zeros_like(s.speed)))
    assert zmj.inertial_torque(still) == pytest.approx(np.zeros(len(tau)))
    # step accuracy: once per motor turn
    ap = P["step_accuracy"]
    th = np.linspace(0.0, 6.0, 7)
    assert zmj.step_error(ap, 3, th + 2 * np.pi) == pytest.approx(zmj.step_error(ap, 3, th), abs=1e-15)

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    # limiter: the weight torque's flank beyond the seats' friction, the last rotation's otherwise
    lp = P["limiter_play"]
    t = zmj.roll_torque(lp, ctx)
    fl = zmj.limiter_flank(lp, ctx)
    assert fl[np.abs(t) > lp["f"]] == pytest.approx(np.sign(t[np.abs(t) > lp["f"]]))
    assert fl[np.abs(t) <= lp["f"]] == pytest.approx(-s.direction[np.abs(t) <= lp["f"], 5])
    assert zmj.roll_torque({**lp, "tool_kg": 0.0}, replace(ctx, session=replace(s, payload_kg=0 * s.payload_kg))) == \
        pytest.approx(np.zeros(len(t)), abs=1e-12)
    # microstep error: one period per full step of the motor (200 N_g per output radian)
    mp = P["microstep_error"]
    F = zmj.microstep_features(mp, ctx, None)
    K = 200 * mp["N_g"][3]
    shifted = replace(ctx, session=replace(s, q=s.q + np.r_[0, 0, 0, 2 * np.pi / K, 0, 0]))
    assert np.abs(F[0] @ np.ones(3)).max() > 0
    assert np.einsum("pi,pi->p", F[0], ctx.jac[:, :, 3]) / np.einsum("pi,pi->p", ctx.jac[:, :, 3], ctx.jac[:, :, 3]) \
        == pytest.approx(np.sin(K * s.q[:, 3]))
    assert np.sin(K * shifted.q[:, 3]) == pytest.approx(np.sin(K * s.q[:, 3]), abs=1e-9)
    # mounts: the loads carry the weight and balance the moment; the rail blocks are linear at kappa = 1
    cp = P["conical_mounts"]
    R, xy = zmb.mount_loads(cp, ctx)
    e1, e2 = zmb._axes(cp["psi"])
    M = mount_moment(ctx)
    assert R.sum(axis=1) == pytest.approx(zmb.total_weight(ctx))
    assert R @ xy[:, 0] == pytest.approx(M @ e2) and R @ xy[:, 1] == pytest.approx(-(M @ e1))
    bp = P["rail_blocks"]
    Rb, xyb = zmb.mount_loads(bp, ctx)
    assert zmb.rail_features({**bp, "kappa": 1.0}, ctx, None) == pytest.approx(zmb._plate(bp, ctx, Rb, xyb))
    assert (Rb < 0).any() and (Rb >= 0).any()
    # mandrel: no part, no motion; the shift is across the tool axis
    mp = P["mandrel_rock"]
    empty = replace(ctx, session=replace(s, payload_kg=0 * s.payload_kg))
    assert zmb.mandrel_features(mp, empty, None) == pytest.approx(np.zeros((1, len(s.q), 3)))
    # enclosure: no loading pauses, no pulses; the door open only during the pauses
    dp = P["enclosure_door"]
    shut = replace(s, gap_s=np.zeros_like(s.gap_s))
    assert np.abs(zmt.door_node(dp, shut)).max() == 0.0
    node = zmt.door_node(dp, s)
    assert (s.gap_s < 0).sum() >= 3 and 0 < node.max() < 1

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # jaw guides: equal stiffnesses turn the part about the guides' point by M / 2 (no motion along the arm to it)
    jp = {**P["jaw_guide_tilt"], "yaw": 1.0, "roll": 1.0}
    Fj = zmb.jaw_features(jp, ctx, None)[0]
    arm = np.einsum("pij,j->pi", zmb.tool_frame(ctx), ctx.probe_mm - [0, 0, zmb.JAW_MM])
    assert np.einsum("pi,pi->p", Fj, arm) == pytest.approx(np.zeros(len(s.q)), abs=1e-9)
    # radiant envelope: in still air no growth; without walls and with a short lag the links follow the air
    rp = P["mean_radiant"]
    flat = replace(s, air={**s.air, "drift_K": 0.0, "cycle_K": 0.0})
    assert np.abs(zmt.link_temperature(rp, flat)).max() < 1e-12
    T = zmt.link_temperature({**rp, "s": 0.0, "tau_l": 1e-3}, s)
    from sim2real_indep.session import air_temperature
    assert T == pytest.approx(air_temperature(s, s.time_s) - air_temperature(s, s.time_s[0]), abs=0.02)


# --------------------------------------------------------------------------------------------------------- set ZN
ZN_KINDS = ("hygro_gear", "payload_estimator", "load_holding_valve", "roll_endplay", "rope_lay", "magnetostrictive_rod",
            "wire_rope_isolators", "focalised_mounts", "dovetail_gib", "bellows_coupling", "radiant_tube_heater",
            "dragging_brake")


def test_set_zn_cases_kinds_and_determinism():
    """Set ZN (the fourteenth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZM; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZN kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; a
    new part for each block, hours of blocks with pauses (the washdown, the radiant heaters' cycling air), production
    between the blocks (the dragging brake)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zn as ezn
    from sim2real_indep import effects_zn_body as znb

    assert _sorts_after("ZM", "ZN")
    assert cs.case_seed("ZN", 3) == 40_7040 * 1000 + 3 and [c[0] for c in cs.SET_ZN] == [f"ZN{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezn.EFFECTS_ZN) == set(ZN_KINDS)
    _assert_set_module("ZN", 40_7040, ezn, ("gear", "moment_softening", "mean_radiant", "rail_blocks"))
    for name in ("effects_zn", "effects_zn_joint", "effects_zn_body", "effects_zn_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zn" in _imports(STUDY / "generator.py")
    assert ezn.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezn.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezn.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                steps = np.array(opts((kind,), robot)["payload_steps"])
                assert len(steps) >= 3 and kg[robot][0] <= steps.min() and steps.max() <= kg[robot][1]
                assert len(steps) == opts((kind,), robot)["blocks"]
        for kind, ((lo, hi), gap, pause) in ezn.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        air = opts(("radiant_tube_heater",))["air"]
        assert air["drift_K"] == 0.0 and 0.3 <= air["cycle_K"] <= 0.8 and 20.0 <= air["period_min"] <= 40.0
        plain = opts(("load_holding_valve", "roll_endplay", "rope_lay", "magnetostrictive_rod"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe, com = np.array([1.0, 2.0, 3.0]), np.array([30.0, -40.0, 0.0])
    assert ezn.probe_hook(("gear",), probe) is probe and ezn.payload_hook(("gear",), com) is com
    assert ezn.probe_hook(("dovetail_gib",), probe) == pytest.approx(probe + [0, 0, znb.SLIDE_TARGET_MM])
    assert ezn.probe_hook(("bellows_coupling",), probe) == pytest.approx(probe + [0, 0, znb.BELLOWS_TARGET_MM])
    assert ezn.payload_hook(("dovetail_gib",), com) == pytest.approx([6.0, -8.0, znb.SLIDE_MM + 40.0 + 60.0 * 50 / 80])
    assert ezn.payload_hook(("bellows_coupling",), com) == pytest.approx([6.0, -8.0,
                                                                          znb.BELLOWS_MM + 40.0 + 60.0 * 50 / 80])
    _assert_regenerates("ZN", max_effect_poses=50)


def test_set_zn_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZN kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: Fick's uptake (0 at the
    washdown, 1 when saturated, the early square-root law), the estimator's convergence (a held part is learnt, none
    left after a long move), the holding valves' drop (after lowering only), the end play's side (the axial weight's
    where it beats the friction), the rope lay's and the magnetostrictive sensor's columns (their periods, the Legendre
    polynomials), the isolators' law (linear at s = h = 0: the plate of the loads), the focalised mounts' turn (about
    the focal point: the focus does not move), the dovetail's asymmetry (kappa = 1: symmetric), the bellows' stretch
    (along the tool axis only when the part hangs straight below), the heaters' gradient (none while they are off, no
    bow of a vertical tube) and the brake's node (nothing without motion)."""
    from dataclasses import replace

    from sim2real_indep import effects_zm_body as zmb
    from sim2real_indep import effects_zn_body as znb
    from sim2real_indep import effects_zn_joint as znj
    from sim2real_indep import effects_zn_thermal as znt

    amps = {"hygro_gear": "c", "payload_estimator": "c", "load_holding_valve": "d", "roll_endplay": "e2",
            "rope_lay": "amp", "magnetostrictive_rod": "c", "wire_rope_isolators": "c", "focalised_mounts": "c",
            "dovetail_gib": "inv_K", "bellows_coupling": "inv_Kax", "radiant_tube_heater": "amp",
            "dragging_brake": "amp"}
    specs = {"ur10": ("hygro_gear", "payload_estimator", "rope_lay", "wire_rope_isolators", "bellows_coupling",
                      "radiant_tube_heater"),
             "tool_changer": ("load_holding_valve", "magnetostrictive_rod", "dovetail_gib", "dragging_brake",
                              "roll_endplay", "focalised_mounts"),
             "kr16_like": ("roll_endplay", "focalised_mounts", "dragging_brake")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 40)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    # moisture: Fick's plate -- nothing at the washdown, saturated at long times, 4 / sqrt(pi) sqrt(t / tau) early on
    hp = P["hygro_gear"]
    at = lambda t, tau: znj.moisture({"t_w": 0.0, "tau_d": tau}, replace(s, time_s=s.time_s[0] + np.array(t)))  # noqa
    m = at([0.0, 36.0, 1e6], 3600.0)
    assert m[0] == pytest.approx(0.0, abs=2e-3) and m[2] == pytest.approx(1.0)
    assert m[1] == pytest.approx(4 / np.pi ** 1.5 * np.sqrt(36.0 / 3600.0), rel=0.02)
    assert np.all(np.diff(znj.moisture(hp, s)) >= 0)
    # estimator: a part held long enough is learnt; the residual after a change shrinks move by move
    ep = P["payload_estimator"]
    long = replace(s, move_s=np.full(len(s.move_s), 1e4))
    assert znj.estimate(ep, long) == pytest.approx(s.payload_kg)
    r = s.payload_kg - znj.estimate(ep, s)
    assert np.all(np.abs(r[1:][np.diff(s.payload_kg) == 0]) <= np.abs(r[:-1][np.diff(s.payload_kg) == 0]) + 1e-12)
    # rope lay: sin / cos of the two periods, the strands' an integer multiple of the lay's
    rp = P["rope_lay"]
    F = znj.rope_features(rp, ctx, None)
    k1, ks = rp["k"][0]
    assert 6 <= ks / k1 <= 8 and abs(ks / k1 - round(ks / k1)) < 1e-9 and len(F) == 8
    assert np.einsum("pi,pi->p", F[0], ctx.jac[:, :, 0]) / np.einsum("pi,pi->p", ctx.jac[:, :, 0], ctx.jac[:, :, 0]) \
        == pytest.approx(np.sin(k1 * s.q[:, 0]))
    # wire-rope isolators: linear without the softening and the hardening
    wp = P["wire_rope_isolators"]
    R, xy = zmb.mount_loads(wp, ctx)
    assert znb.wire_features({**wp, "s": 0.0, "h": 0.0}, ctx, None) == pytest.approx(zmb._plate(wp, ctx, R, xy))
    d = znb.isolator_deflection(wp, np.array([[wp["F0"], -wp["F0"]]]))
    assert d[0, 0] == pytest.approx(wp["F0"] * (1 + wp["s"])) and d[0, 1] == pytest.approx(-wp["F0"] / (1 + wp["h"]))
    # bellows: a part hanging straight below stretches it along the tool axis only
    bp = P["bellows_coupling"]
    F, M = zmb.part_loads(ctx, znb.BELLOWS_MM)
    assert np.einsum("pi,pi->p", F, F) == pytest.approx((kin.G * s.payload_kg) ** 2)
    # radiant heaters: nothing while they are off; on, a vertical tube does not bow
    rp = P["radiant_tube_heater"]
    assert np.abs(znt.gradient_node({**rp, "offset": -2.0}, s)).max() == 0.0
    node = znt.gradient_node(rp, s)
    assert 0 <= node.min() and node.max() <= 1
    up = replace(ctx, session=replace(s, q=np.zeros_like(s.q) + [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]))
    bows = znt.tube_bows(up, np.ones(len(s.q)))
    assert np.abs(bows).max() < 1e-6 * 1000.0

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # holding valves: a drop only after a lowering move
    for j in znj.VALVE_JOINTS:
        low = znj.lowered_last(ctx, j)
        moved = s.speed[:, j] > 0
        assert set(np.unique(low)) <= {0.0, 1.0}
        assert low[moved] == pytest.approx((s.direction[moved, j] == np.sign(ctx.loads[moved, j])).astype(float))
    # magnetostrictive sensor: the Legendre polynomials of the stroke
    F = znj.rod_features(P["magnetostrictive_rod"], ctx, None)
    x = znj.stroke_x(ctx)
    assert np.abs(x).max() <= 1 and np.einsum("pi,pi->p", F[1], ctx.jac[:, :, 3]) == pytest.approx(
        (3 * x ** 2 - 1) / 2 * np.einsum("pi,pi->p", ctx.jac[:, :, 3], ctx.jac[:, :, 3]))
    # dovetail: symmetric at kappa = 1 (reversing the part's moment reverses the move)
    gp = {**P["dovetail_gib"], "kappa": 1.0}
    Fd = znb.dovetail_features(gp, ctx, None)
    flip = replace(ctx, payload_com_mm=np.array([-1.0, -1.0, 1.0]) * ctx.payload_com_mm)
    assert np.abs(Fd).max() > 0 and np.isfinite(znb.dovetail_features(gp, flip, None)).all()
    # dragging brake: no motion, no heat
    bp = P["dragging_brake"]
    still = replace(s, speed=0 * s.speed, gap_s=np.minimum(s.gap_s, 0.0))
    assert np.abs(znt.brake_node(bp, still)).max() == 0.0 and znt.brake_node(bp, s).max() > 0

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # end play: the axial weight's side where it beats the friction
    ep = P["roll_endplay"]
    F = znj.axial_force(ctx, znj.ENDPLAY_J["kr16_like"])
    side = znj.endplay_side(ep, ctx)
    assert side[np.abs(F) > ep["f"]] == pytest.approx(np.sign(F[np.abs(F) > ep["f"]]))
    assert set(np.unique(side)) <= {-1.0, 1.0}
    # focalised mounts: the focal point does not move under the turn about the short axis
    fp = P["focalised_mounts"]
    focus = np.array([0.0, 0.0, znb.focal_height_mm(fp) - fp["pivot_mm"]])
    at_focus = replace(ctx, probe_mm=ctx.probe_mm)
    at_focus.__dict__["target"] = np.broadcast_to(focus, ctx.target.shape).copy()
    e1, _ = zmb._axes(fp["psi"])
    no_long = {**fp, "b": 1e9}
    Ff = znb.focal_features(no_long, at_focus, None)[0]
    kv = np.cos(fp["gamma"]) ** 2 + fp["rho"] * np.sin(fp["gamma"]) ** 2
    sink = 1000.0 * zmb.total_weight(ctx) / (4 * kv)
    assert Ff == pytest.approx(np.outer(-sink, [0, 0, 1.0]), abs=1e-9 * sink.max())


# --------------------------------------------------------------------------------------------------------- set ZO
ZO_KINDS = ("gravity_table", "entrained_air", "differential_lash", "tensioner_stop", "race_waviness", "lever_cam_fit",
            "deck_cupping", "closed_cell_pads", "cross_spring_pivot", "qzs_mount", "ultrasonic_ram", "dry_ice_nozzle")


def test_set_zo_cases_kinds_and_determinism():
    """Set ZO (the fifteenth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZN; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZO kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; a
    new part for each block, hours of blocks with pauses (the deck's washdown, the ultrasonic sensor's drifting and
    cycling air), production between the blocks (the dry-ice nozzle)."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zo as ezo
    from sim2real_indep import effects_zo_body as zob
    from sim2real_indep import effects_zo_thermal as zot

    assert _sorts_after("ZN", "ZO")
    assert cs.case_seed("ZO", 3) == 40_7041 * 1000 + 3 and [c[0] for c in cs.SET_ZO] == [f"ZO{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezo.EFFECTS_ZO) == set(ZO_KINDS)
    _assert_set_module("ZO", 40_7041, ezo, ("gear", "hygro_gear", "radiant_tube_heater", "wire_rope_isolators"))
    for name in ("effects_zo", "effects_zo_joint", "effects_zo_body", "effects_zo_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zo" in _imports(STUDY / "generator.py")
    assert ezo.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezo.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezo.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                steps = np.array(opts((kind,), robot)["payload_steps"])
                assert len(steps) >= 3 and kg[robot][0] <= steps.min() and steps.max() <= kg[robot][1]
                assert len(steps) == opts((kind,), robot)["blocks"]
        for kind, ((lo, hi), gap, pause) in ezo.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        air = opts(("ultrasonic_ram",), "tool_changer")["air"]
        assert 2.0 <= abs(air["drift_K"]) <= 5.0 and 0.3 <= air["cycle_K"] <= 1.0 and 40.0 <= air["period_min"] <= 120.0
        plain = opts(("gravity_table", "race_waviness", "lever_cam_fit", "qzs_mount"))
        assert plain == {"blocks": 1, "gap_kind": "none"}
    probe, com = np.array([1.0, 2.0, 3.0]), np.array([30.0, -40.0, 0.0])
    assert ezo.probe_hook(("gear",), probe) is probe and ezo.payload_hook(("gear",), com) is com
    assert ezo.probe_hook(("cross_spring_pivot",), probe) == pytest.approx(probe + [0, 0, zob.CS_TARGET_MM])
    assert ezo.probe_hook(("dry_ice_nozzle",), probe) == pytest.approx(probe + [0, 0, zot.NOZZLE_MM])
    assert ezo.payload_hook(("cross_spring_pivot",), com) == pytest.approx([15.0, -20.0,
                                                                            zob.CS_MM + 40.0 + 60.0 * 50 / 80])
    _assert_regenerates("ZO", max_effect_poses=50)


def test_set_zo_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZO kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: the gravity table's residual
    (none at its nodes), the trapped air's law (linear without air, stiffening with it), the differential's trains (a
    pure pitch torque puts both on its flank; a pitch move drives both), the tensioner's relay (on its stop beyond the
    upper threshold, at rest below the lower), the raceway's orders (Z f_c - Z +- 1, non-integer), the cam's residual
    (the first-order error of the exact lever law, equioscillating), Fick's cupping (none at the washdown, the early
    square-root law, a target at the base only rises), the foam's law (the design strain under the lightest load, linear
    without gas), the cross-spring pivot (the plain tilt without load stiffening), the QZS isolator's cubic (no move at
    the design attitude), the ultrasonic sensor's lag (none in still air, rate x tau on a ramp) and the nozzle's chill
    (none without production, along the tool's z)."""
    from dataclasses import replace

    from sim2real_indep import effects_zm_body as zmb
    from sim2real_indep import effects_zo_body as zob
    from sim2real_indep import effects_zo_joint as zoj
    from sim2real_indep import effects_zo_thermal as zot

    amps = {"gravity_table": "c", "entrained_air": "c", "differential_lash": "b2", "tensioner_stop": "c",
            "race_waviness": "amp", "lever_cam_fit": "amp", "deck_cupping": "c", "closed_cell_pads": "t_mm",
            "cross_spring_pivot": "inv_K0", "qzs_mount": "x_ref", "ultrasonic_ram": "amp", "dry_ice_nozzle": "amp"}
    specs = {"ur10": ("tensioner_stop", "race_waviness", "deck_cupping", "qzs_mount", "dry_ice_nozzle",
                      "cross_spring_pivot", "closed_cell_pads"),
             "tool_changer": ("entrained_air", "differential_lash", "lever_cam_fit", "ultrasonic_ram"),
             "kr16_like": ("gravity_table", "differential_lash", "tensioner_stop")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 41)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-2, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    # tensioner: a relay in sigma x the belt's torque -- on its stop beyond hi, at rest below lo (poses at rest)
    tp = P["tensioner_stop"]
    bends = zoj.wrist_bends(ctx.chain)
    assert bends == [3, 4]
    for k, j in enumerate(bends):
        st = zoj.tensioner_state(tp, ctx, j, k)
        x = tp["sigma"][k] * ctx.loads[:, j]
        assert set(np.unique(st)) <= {0.0, 1.0}
        assert np.all(st[x > tp["hi"][k]] == 1.0) and np.all(st[x < tp["lo"][k] - tp["fric"][k]] == 0.0)
    # raceway waviness: sin / cos at the orders Z f_c - Z -+ 1 per turn, non-integer
    wp = P["race_waviness"]
    nu = zoj.wave_orders(wp)
    assert nu[0] - nu[1] == pytest.approx(2.0) and abs(nu[0] - round(nu[0])) > 1e-3
    F = zoj.wave_features(wp, ctx, None)
    J0 = ctx.jac[:, :, 0]
    proj = np.einsum("pi,pi->p", F[0], J0) / np.einsum("pi,pi->p", J0, J0)
    assert proj == pytest.approx(np.sin(nu[0] * s.q[:, 0]))
    # deck cupping: none at the washdown, the early square-root law 24 / pi^1.5 sqrt(t / tau), a target at the base
    # only rises
    cp = P["deck_cupping"]
    at = lambda t: zob.cup_curvature({**cp, "t_w": 0.0}, replace(s, time_s=s.time_s[0] + np.array(t)))
    k = at([0.0, 1e-3 * cp["tau_d"], 1e3 * cp["tau_d"]])
    assert k[0] == pytest.approx(0.0, abs=1e-9) and k[2] == pytest.approx(0.0, abs=1e-9)
    assert k[1] == pytest.approx(24 / np.pi ** 1.5 * np.sqrt(1e-3), rel=0.05)
    base = replace(ctx)
    base.__dict__["target"] = np.zeros_like(ctx.target)
    Fc = zob.cup_features(cp, base, None)[0]
    assert np.abs(Fc[:, :2]).max() < 1e-12 and np.abs(Fc[:, 2]).max() > 0
    # closed-cell pads: the design strain under the lightest quarter weight; linear without the gas
    pp = P["closed_cell_pads"]
    assert zob.foam_strain(pp, np.array([pp["W4"]]))[0] == pytest.approx(pp["eps0"], rel=1e-4)
    R, xy = zmb.mount_loads(pp, ctx)
    lin = {**pp, "g": 0.0}
    assert zob.pads_features(lin, ctx, None) == pytest.approx(
        zmb._plate(lin, ctx, np.maximum(R, 0) / pp["W4"] * pp["eps0"], xy), rel=1e-4, abs=1e-9)
    # cross-spring pivot: without load stiffening, the plain tilt M_x / K0 about the tool's x
    xp = P["cross_spring_pivot"]
    _, M = zmb.part_loads(ctx, zob.CS_MM)
    plain = zmb._to_world(ctx, np.cross(M * [1.0, 0.0, 0.0], ctx.probe_mm - [0.0, 0.0, zob.CS_MM]))
    assert zob.cross_features({**xp, "F_c": 1e30}, ctx, None)[0] == pytest.approx(plain)
    # QZS isolator: Cardano's root solves the cubic; no move with the tool pointing straight down
    qp = P["qzs_mount"]
    y = np.linspace(-2.0, 0.0, 9)
    xi = zob.qzs_stroke(qp["eta"], y)
    assert qp["eta"] * xi + xi ** 3 == pytest.approx(y, abs=1e-12) and xi[-1] == pytest.approx(0.0, abs=1e-12)
    # dry-ice nozzle: no production, no chill; the move along the tool's z
    ip = P["dry_ice_nozzle"]
    idle = replace(s, gap_s=np.minimum(s.gap_s, 0.0))
    node = zot.ice_node(ip, s)
    assert np.abs(zot.ice_node(ip, idle)).max() == 0.0 and node.max() > 0 and node.max() <= ip["duty"]
    Fi = zot.ice_features(ip, ctx, None)[0]
    assert np.abs(np.cross(Fi, zob.tool_frame(ctx)[:, :, 2])).max() < 1e-9

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # trapped air: linear in the load without air; stiffening (a falling slope) with it
    ap = P["entrained_air"]
    tau = ctx.loads[:, zoj.AIR_J[0]]
    big = np.abs(tau) / ap["tau_s"][0] * ap["ps_bar"] > zoj.P_MIN_BAR
    g0 = zoj.air_yield({**ap, "x0": 0.0}, ctx)[:, 0]
    assert g0[big] == pytest.approx(tau[big] / ap["tau_s"][0])
    r = np.linspace(0.05, 1.0, 50)
    lo = replace(ctx)
    lo.__dict__["loads"] = np.zeros((50, ctx.chain.n))
    lo.__dict__["loads"][:, zoj.AIR_J[0]] = r * ap["tau_s"][0]
    g = zoj.air_yield(ap, lo)[:, 0]
    assert np.all(np.diff(g) > 0) and np.all(np.diff(np.diff(g) / np.diff(r)) < 0)
    # differential: a pure pitch torque beyond both trains' friction puts both on its flank; a pitch move drives both
    dp = P["differential_lash"]
    pure = replace(ctx)
    pure.__dict__["loads"] = ctx.loads * [1, 1, 1, 1, 1, 0]
    fl = zoj.diff_flanks(dp, pure)
    tp_ = ctx.loads[:, zoj.PITCH_J]
    both = np.abs(tp_ / 2) > max(dp["f"])
    assert fl[both, 0] == pytest.approx(np.sign(tp_[both])) and fl[both, 1] == pytest.approx(np.sign(tp_[both]))
    m = zoj.train_motion(ctx, dp["i"])
    dq = np.diff(s.q, axis=0)
    only5 = np.flatnonzero((dq[:, zoj.ROLL_J] == 0) & (dq[:, zoj.PITCH_J] != 0)) + 1
    assert m[only5, 0] == pytest.approx(np.sign(dq[only5 - 1, zoj.PITCH_J])) and (m[only5, 0] == m[only5, 1]).all()
    # cam: the first-order error agrees with the exact lever law's; the cubic's residual equioscillates
    gp = P["lever_cam_fit"]
    for geo, j in zip(gp["geo"], zoj.CAM_J):
        lo_, hi_ = ctx.chain.lower[j], ctx.chain.upper[j]
        qs = np.linspace(lo_, hi_, 400)
        e = zoj.cam_residual(geo, qs, lo_, hi_)
        assert np.count_nonzero(np.diff(np.sign(e))) >= 4
        r1, r2, psi0 = geo["r1"], geo["r2"], geo["psi0"]
        L = np.sqrt(r1 ** 2 + r2 ** 2 - 2 * r1 * r2 * np.cos(psi0 + qs))
        target = L + e * r1 * r2 * np.sin(psi0 + qs) / L
        psi = np.arccos((r1 ** 2 + r2 ** 2 - target ** 2) / (2 * r1 * r2))
        assert psi - psi0 - qs == pytest.approx(e, rel=0.02, abs=1e-3 * np.abs(e).max())
    # ultrasonic sensor: no lag in still air; on a steady ramp the lag settles to rate x tau
    up = P["ultrasonic_ram"]
    still = replace(s, air={**s.air, "drift_K": 0.0, "cycle_K": 0.0})
    assert np.abs(zot.sensor_lag(up, still)).max() < 1e-12
    ramp = replace(s, air={**s.air, "cycle_K": 0.0})
    span = s.time_s[-1] - s.time_s[0]
    assert span > 6 * up["tau"]
    assert zot.sensor_lag(up, ramp)[-1] == pytest.approx(s.air["drift_K"] / span * up["tau"], rel=0.02)

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # gravity table: no residual at the table's nodes, some between them
    tb = P["gravity_table"]
    h = np.deg2rad(tb["h_deg"])
    q = s.q.copy()
    for j in zoj.TABLE_J:
        q[:, j] = ctx.chain.lower[j] + np.round((q[:, j] - ctx.chain.lower[j]) / h) * h
    assert np.abs(zoj.table_residual(tb, _ctx_at(ctx, q))).max() < 1e-9 * np.abs(zoj.link_gravity(ctx, s.q)).max()
    assert np.abs(zoj.table_residual(tb, ctx)).max() > 1e-3 * np.abs(zoj.link_gravity(ctx, s.q)).max()


# --------------------------------------------------------------------------------------------------------- set ZP
ZP_KINDS = ("soaked_jacket", "vessel_list", "clevis_clearance", "clock_spring_flank", "mylar_strip",
            "tacho_integration", "magnet_base", "ballast_stand", "needle_gripper", "ltb_boom", "heated_bed",
            "air_motor_heat")


def test_set_zp_cases_kinds_and_determinism():
    """Set ZP (the sixteenth two-letter set): 24 cases, 8 per arm, every family (two kinds each), kinds new to the
    benchmark and registered in the generator with their families, 3 geometry-only cases that carry no effect, 3
    mixtures, a quarter split by time; its name keys the case seeds and sorts after ZO; a case regenerates
    bit-identically from its seed; the session hook leaves cases without a set-ZP kind alone (no random numbers drawn)
    and the probe and payload hooks draw none; the generator reaches the set's modules and none imports tolalloc; a
    new part for each block, blocks with pauses for the kinds that follow the time."""
    from sim2real_indep import cases as cs
    from sim2real_indep import effects_zp as ezp
    from sim2real_indep import effects_zp_body as zpb
    from sim2real_indep import effects_zp_thermal as zpt

    assert _sorts_after("ZO", "ZP")
    assert cs.case_seed("ZP", 3) == 40_7042 * 1000 + 3 and [c[0] for c in cs.SET_ZP] == [f"ZP{i:02d}" for i in
                                                                                          range(1, 25)]
    assert set(ezp.EFFECTS_ZP) == set(ZP_KINDS)
    _assert_set_module("ZP", 40_7042, ezp, ("gear", "gravity_table", "dry_ice_nozzle", "qzs_mount"))
    for name in ("effects_zp", "effects_zp_joint", "effects_zp_body", "effects_zp_thermal"):
        assert not any(m.split(".")[0] == "tolalloc" for m in _imports(PKG / f"{name}.py")), name
        assert len((PKG / f"{name}.py").read_text(encoding="utf-8").splitlines()) < 400, name
    assert "sim2real_indep.effects_zp" in _imports(STUDY / "generator.py")
    assert ezp.AFTER_TRACKER == set()
    for seed in range(3):
        opts = lambda kinds, robot="kr16_like": ezp.session_options(robot, kinds, np.random.default_rng(seed),  # noqa
                                                                    {"blocks": 1, "gap_kind": "none"})
        for kind, kg in ezp.PART_KG.items():
            for robot in ("ur10", "tool_changer", "kr16_like"):
                steps = np.array(opts((kind,), robot)["payload_steps"])
                assert len(steps) >= 3 and kg[robot][0] <= steps.min() and steps.max() <= kg[robot][1]
                assert len(steps) == opts((kind,), robot)["blocks"]
        for kind, ((lo, hi), gap, pause) in ezp.LONG.items():
            b = opts((kind,))
            assert lo <= b["blocks"] < hi and b["gap_kind"] == gap and b["pause_min"] == pause
        assert opts(("air_motor_heat",)) == {"blocks": 1, "gap_kind": "none"}
    probe, com = np.array([1.0, 2.0, 3.0]), np.array([30.0, -40.0, 0.0])
    assert ezp.probe_hook(("gear",), probe) is probe and ezp.payload_hook(("gear",), com) is com
    assert ezp.probe_hook(("ltb_boom",), probe) == pytest.approx(probe + [0, 0, zpb.LTB_MM])
    assert ezp.probe_hook(("air_motor_heat",), probe) == pytest.approx(probe + [0, 0, zpt.SPINDLE_MM])
    assert ezp.payload_hook(("ltb_boom",), com) == pytest.approx([9.0, -12.0, zpb.LTB_MM])
    _assert_regenerates("ZP", max_effect_poses=50)


def test_set_zp_every_kind_lies_in_its_true_structure_and_known_answers():
    """Every set-ZP kind's displacement is its true-structure features times its true amplitudes (what the oracle
    fits), to rounding, and a real effect on every arm it is used on; and known answers: the jacket's water gone after
    long drying, the list's torques odd in its direction and loading axis 1, the clevis' lever arm and the side of the
    cylinders' net force, the spiral spring's flank, the code strip's reference and dry start, the tachos' homing, the
    magnet base's log law linear under a strong magnet, the ballasted stand's feet in statics and never pulling, the
    needles' anisotropic compliance, the boom's buckling amplification, the bed's exposure and the compressor's duty."""
    from sim2real_indep import effects_zp_body as zpb
    from sim2real_indep import effects_zp_joint as zpj
    from sim2real_indep import effects_zp_thermal as zpt
    from sim2real_indep.effects_zi_body import tool_frame
    from sim2real_indep.effects_zm_body import _plate, mount_loads, part_loads, total_weight

    amps = {"soaked_jacket": "c", "vessel_list": "c", "clevis_clearance": "c", "clock_spring_flank": "b",
            "mylar_strip": "amp", "tacho_integration": "amp", "magnet_base": "inv_kappa", "ballast_stand": "C",
            "needle_gripper": "inv_Nk", "ltb_boom": "a0", "heated_bed": "amp", "air_motor_heat": "amp"}
    specs = {"ur10": ("vessel_list", "clock_spring_flank", "magnet_base", "needle_gripper", "ltb_boom",
                      "heated_bed", "air_motor_heat"),
             "tool_changer": ("clevis_clearance", "tacho_integration", "ballast_stand", "mylar_strip"),
             "kr16_like": ("soaked_jacket", "mylar_strip")}
    runs = {}
    for robot, kinds in specs.items():
        case = gen.generate("t", robot, kinds, 30, 42)
        ctx = case.model_ctx(case.truth["probe_mm"])
        runs[robot] = (case, ctx)
        for kind in kinds:
            d, A = _effect_and_features(case, ctx, kind)
            _assert_features_reproduce(d, A, np.atleast_1d(case.truth["params"][kind][amps[kind]]), rtol=1e-8,
                                       min_mm=1e-3, what=f"{robot} {kind}")

    case, ctx = runs["ur10"]
    P, s = case.truth["params"], ctx.session
    # vessel list: nothing at the start; the torques odd in the list's direction; axis 1 loaded
    vp = P["vessel_list"]
    assert np.abs(zpj.list_features(vp, ctx, None)[:, 0]).max() == 0.0
    back = zpj.list_torque({**vp, "psi": vp["psi"] + np.pi}, ctx)
    assert back == pytest.approx(-zpj.list_torque(vp, ctx), abs=1e-9)
    assert np.abs(zpj.list_torque(vp, ctx)[:, 0]).max() > 0.1
    # spiral spring: the flank is the sign of gravity plus the spring where their sum passes the friction band
    sp = P["clock_spring_flank"]
    fl = zpj.spring_flanks(sp, ctx)
    for k, j in enumerate(zpj.SPRING_J):
        x = ctx.loads[:, j] + zpj.spring_torque(sp, ctx, k, j)
        big = np.abs(x) > sp["f"][k]
        assert fl[big, k] == pytest.approx(np.sign(x[big]))
    # magnet base: under a very strong magnet the log law is the linear plate of the loads over the reference
    mp = P["magnet_base"]
    strong = {**mp, "F_m": 1e9, "R_ref": 1e9 / 4}
    R, xy = mount_loads(strong, ctx)
    lin = _plate(strong, ctx, R / strong["R_ref"], xy)
    assert zpb.magnet_features(strong, ctx, None) == pytest.approx(lin, rel=1e-4, abs=1e-12)
    # needle gripper: the part moves by the weight over (cos^2 a, 1, sin^2 a) in the tool frame
    npar = P["needle_gripper"]
    F, _ = part_loads(ctx, 0.0)
    local = np.einsum("pji,pj->pi", tool_frame(ctx), zpb.needle_features(npar, ctx, None)[0])
    a = npar["alpha"]
    assert local == pytest.approx(F / [np.cos(a) ** 2, 1.0, np.sin(a) ** 2], rel=1e-9, abs=1e-12)
    # LTB boom: odd in the moment, a0 mu for a small moment, 1 / (1 - mu^2) amplification
    lp = P["ltb_boom"]
    mu = zpb.ltb_ratio(lp, ctx)
    assert np.abs(mu).max() < 1 and np.abs(mu).max() == pytest.approx(
        np.abs(F[:, 0]).max() * zpb.LTB_MM / 1000 / lp["M_cr"])
    weak = zpb.ltb_ratio({**lp, "M_cr": lp["M_cr"] * 1e6}, ctx)
    assert np.linalg.norm(zpb.ltb_features({**lp, "M_cr": lp["M_cr"] * 1e6}, ctx, None)[0], axis=1) == pytest.approx(
        np.abs(weak), rel=1e-9)
    # heated bed: the exposure 1 at the lowest pose, the forearm cold at the start and below the exposure's peak
    bp = P["heated_bed"]
    e = zpt.bed_exposure(bp, ctx)
    z, _ = kin.flange(ctx.chain, ctx.q)
    assert e.max() == pytest.approx(1.0) and e[np.argmin(z[:, 2])] == pytest.approx(1.0)
    node = zpt.bed_node(bp, ctx)
    assert 0 <= node.min() and node.max() <= 1 and node[0] < node.max()
    # compressor: on for its duty's share of many cycles
    ap = P["air_motor_heat"]
    tg = np.arange(0.0, 200 * ap["period"], 1.0)
    assert zpt.compressor_cycle(ap, tg).mean() == pytest.approx(ap["duty"], abs=0.01)

    case, ctx = runs["tool_changer"]
    P, s = case.truth["params"], ctx.session
    # clevis: the lever arm of the cylinder's geometry; the clearance on the side of the net force
    cp = P["clevis_clearance"]
    g = cp["geo"][0]
    psi = g["psi0"] + ctx.q[:, 1]
    L = np.sqrt(g["r1"] ** 2 + g["r2"] ** 2 - 2 * g["r1"] * g["r2"] * np.cos(psi))
    assert zpj.lever_arm(g, ctx.q[:, 1]) == pytest.approx(g["r1"] * g["r2"] * np.sin(psi) / L)
    fl = zpj.clevis_flanks(cp, ctx)
    for k, j in enumerate(zpj.CLEVIS_J):
        x = ctx.loads[:, j] - cp["bal"][k]
        big = np.abs(x) > cp["f"][k]
        assert fl[big, k] == pytest.approx(np.sign(x[big]))
    # tachos: no gain error at the homing (the lower limit); the drift grows with the time
    tp = P["tacho_integration"]
    at_home = ctx.q.copy()
    at_home[:, list(zpj.TACHO_J)] = ctx.chain.lower[list(zpj.TACHO_J)]
    Ft = zpj.tacho_features(tp, _ctx_at(ctx, at_home), None)
    assert np.abs(Ft[0]).max() < 1e-9 and np.abs(Ft[2]).max() < 1e-9
    # ballasted stand: the feet's loads in statics with the ballast, never pulling; four feet under heavy ballast
    bs = P["ballast_stand"]
    Rf, xy = zpb.stand_loads(bs, ctx)
    R4, _ = mount_loads(bs, ctx)
    assert Rf.min() >= 0 and Rf.sum(axis=1) == pytest.approx(total_weight(ctx) + bs["W_b"])
    assert Rf @ xy[:, 0] == pytest.approx((R4 + bs["W_b"] / 4) @ xy[:, 0], rel=1e-9, abs=1e-6)
    heavy = {**bs, "W_b": 1e6}
    assert zpb.stand_loads(heavy, ctx)[0] == pytest.approx(R4 + 1e6 / 4)
    # code strip: no error at the reference mark; the drifting column starts dry
    mp = P["mylar_strip"]
    at_ref = ctx.q.copy()
    at_ref[:, 0] = mp["q_ref"]
    assert np.abs(zpj.strip_features(mp, _ctx_at(ctx, at_ref), None)).max() < 1e-12
    assert zpj.strip_humidity(mp, s)[0] == pytest.approx(0.0, abs=1e-9) and zpj.strip_humidity(mp, s)[-1] > 0

    case, ctx = runs["kr16_like"]
    P, s = case.truth["params"], ctx.session
    # soaked jacket: the water gone after a long drying
    jp = P["soaked_jacket"]
    assert np.abs(zpj.jacket_features({**jp, "t_w": 1e3 * jp["tau_d"]}, ctx, None)).max() < 1e-12
    assert np.abs(zpj.jacket_torque(ctx)).max() > 1.0

"""Component data of a robot: the bought parts of each joint, the links' sections and materials, the mount, the payload.

The optional ``[components]`` section of a robot file (chain or DH layout), every key with its unit::

    [components]
    source = "public catalogue figures; see each entry"   # where the figures come from (free text)

    [components.payload]
    rated_kg = 10.0                  # rated payload [kg]
    com_mm = [0, 0, 50]              # its centre of mass from the tool point, tool frame (default: at the tool point)

    [components.mount]
    tilt_stiffness_Nm_per_rad = 2.0e6    # the base's tilting stiffness (one value, or [about x, about y])
    source = "assumed"

    [components.joints.shoulder_lift_joint.reducer]
    type = "strain_wave"             # strain_wave | cycloid | planetary | spur | ball_screw | rack | direct
    ratio = 101                      # output turns per input (wave generator / motor) turn: N
    stiffness_Nm_per_rad = [6.7e4, 1.1e5, 1.2e5]   # K1, K2, K3 over the torque bands (or one K)
    torque_bands_Nm = [29, 108]      # T1, T2 (with three stiffnesses)
    lost_motion_arcmin = 1.0         # total lost motion (hysteresis loss + backlash), full width
    hysteresis_arcmin = 1.0
    transmission_accuracy_arcmin = 1.0   # peak-to-peak kinematic error over one output turn
    rated_torque_Nm = 178
    source = "Harmonic Drive CSG-32-100 catalogue"

    [components.joints.shoulder_lift_joint.encoder]
    side = "output"                  # output | motor
    accuracy_arcsec = 20             # peak-to-peak
    source = "assumed"

    [components.joints.shoulder_lift_joint.bearing]
    precision_class = "P5"           # ISO 492 class of the joint's bearings
    span_mm = 80                     # axial distance between the two bearing seats
    datum = "A"                      # datum feature of the seat axis on the drawing
    seat_diameter_mm = 62            # nominal diameter of the bearing seats (the size of the joint's ISO 286 fit)
    tilt_stiffness_Nm_per_rad = 1.0e6

    [components.joints.shoulder_lift_joint.motor]
    winding_resistance_ohm = 0.6
    torque_constant_Nm_per_A = 0.12
    thermal_resistance_K_per_W = 0.8
    thermal_time_constant_min = 30

    [components.links.a2]
    section = "tube"                 # tube | solid | box
    outer_diameter_mm = 110          # tube / solid; box: width_mm and height_mm
    wall_mm = 5                      # tube and box
    material = "aluminium"           # steel | aluminium | cast_iron | cfrp; or the figures below
    youngs_modulus_GPa = 70          # optional, overrides the material's
    cte_um_per_m_K = 23

Joint and link entries are named as in the chain (joint and link names of the robot file). A prismatic joint's
reducer gives ``stiffness_N_per_mm``, ``lost_motion_mm``, ``transmission_accuracy_mm`` and ``rated_force_N``.
Internal units: mm, rad, N, N m, N m/rad (revolute) or N/mm (prismatic), MPa (= N/mm^2), 1/K, s.

A key without its unit suffix, a unit not listed, a gear ratio of zero or below, a stiffness curve that softens
with torque (K1 <= K2 <= K3 expected), torque bands that do not increase, or a joint / link name not in the chain
is one clear error naming the key and what would work.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Components", "JointComponents", "Reducer", "Encoder", "Bearing", "Motor", "LinkSection", "Mount",
           "Payload", "MATERIALS", "REDUCER_TYPES", "parse_components", "read_table"]

ARCMIN = np.pi / 10800.0
ARCSEC = np.pi / 648000.0
_ANGLE = {"rad": 1.0, "deg": np.pi / 180.0, "arcmin": ARCMIN, "arcsec": ARCSEC}
_LENGTH = {"mm": 1.0, "m": 1000.0, "um": 1e-3}
_ROT_STIFF = {"Nm_per_rad": 1.0, "Nm_per_arcmin": 1.0 / ARCMIN}
_LIN_STIFF = {"N_per_mm": 1.0, "N_per_um": 1000.0}
_MODULUS = {"GPa": 1000.0, "MPa": 1.0}
_CTE = {"um_per_m_K": 1e-6, "per_K": 1.0}
_TIME = {"s": 1.0, "min": 60.0, "h": 3600.0}

REDUCER_TYPES = ("strain_wave", "cycloid", "planetary", "spur", "ball_screw", "rack", "direct")

#: Materials a link section may name: Young's and shear modulus [MPa], density [kg/mm^3], CTE [1/K], source.
MATERIALS = {
    "steel": (210e3, 81e3, 7.85e-6, 11.7e-6, "structural steel, handbook values (e.g. Roark's Formulas, table of properties)"),
    "aluminium": (70e3, 26e3, 2.70e-6, 23.1e-6, "wrought aluminium alloy (6061-T6 / 7075), handbook values"),
    "cast_iron": (120e3, 47e3, 7.20e-6, 10.5e-6, "grey cast iron EN-GJL-250, handbook values"),
    "cfrp": (70e3, 5e3, 1.55e-6, 0.5e-6, "quasi-isotropic carbon-fibre laminate, typical handbook values (assumed)"),
}


@dataclass(frozen=True)
class Reducer:
    """A joint's reducer (gear or screw) in internal units.

    Attributes
    ----------
    type : str                        one of :data:`REDUCER_TYPES`
    ratio : float or None             gear ratio N (input turns per output turn)
    stiffness : tuple of float        K (one) or K1, K2, K3 [N m/rad, or N/mm for a prismatic joint]
    torque_bands : tuple of float     () or T1, T2 [N m, or N]
    lost_motion, hysteresis : float or None   full widths [rad, or mm]
    transmission_accuracy : float or None     peak-to-peak kinematic error over one output turn [rad, or mm]
    rated_torque : float or None      [N m, or N]
    source : str
    """

    type: str = "strain_wave"
    ratio: float | None = None
    stiffness: tuple = ()
    torque_bands: tuple = ()
    lost_motion: float | None = None
    hysteresis: float | None = None
    transmission_accuracy: float | None = None
    rated_torque: float | None = None
    source: str = ""

    def deflection(self, torque: np.ndarray) -> np.ndarray:
        """Elastic wind-up under ``torque`` [N m or N] (any shape): the catalogue's piecewise-linear torque-torsion
        curve (``T/K1`` up to T1, then ``1/K2``, then ``1/K3`` beyond T2), odd in the torque [rad or mm]."""
        t = np.abs(np.asarray(torque, dtype=float))
        if not self.stiffness:
            raise ValueError("the reducer has no stiffness figure")
        if len(self.stiffness) == 1:
            return np.sign(torque) * t / self.stiffness[0]
        (k1, k2, k3), (t1, t2) = self.stiffness, self.torque_bands
        phi = np.minimum(t, t1) / k1 + np.clip(t - t1, 0.0, t2 - t1) / k2 + np.maximum(t - t2, 0.0) / k3
        return np.sign(torque) * phi


@dataclass(frozen=True)
class Encoder:
    """Position encoder: ``side`` (``output`` or ``motor``), peak-to-peak ``accuracy`` [rad or mm], source."""

    side: str = "output"
    accuracy: float | None = None
    source: str = ""


@dataclass(frozen=True)
class Bearing:
    """The joint's bearing arrangement: ISO 492 ``precision_class``, seat ``span_mm``, drawing ``datum``,
    ``tilt_stiffness`` [N m/rad], source, nominal ``seat_diameter_mm`` (the size of the seats' ISO 286 fit)."""

    precision_class: str | None = None
    span_mm: float | None = None
    datum: str | None = None
    tilt_stiffness: float | None = None
    source: str = ""
    seat_diameter_mm: float | None = None


@dataclass(frozen=True)
class Motor:
    """Motor figures for its losses and heating: winding resistance [ohm], torque constant [N m/A], thermal
    resistance [K/W], thermal time constant [s], source."""

    winding_resistance_ohm: float | None = None
    torque_constant_Nm_per_A: float | None = None
    thermal_resistance_K_per_W: float | None = None
    thermal_time_constant_s: float | None = None
    source: str = ""


@dataclass(frozen=True)
class JointComponents:
    """The bought parts of one joint (each None where the file says nothing)."""

    reducer: Reducer | None = None
    encoder: Encoder | None = None
    bearing: Bearing | None = None
    motor: Motor | None = None


@dataclass(frozen=True)
class LinkSection:
    """Cross-section and material of a link (a beam).

    Attributes
    ----------
    section : {"tube", "solid", "box"}
    area_mm2, inertia_mm4 : float      cross-section area and second moment of area
    youngs_modulus_MPa, shear_modulus_MPa : float
    density_kg_per_mm3, cte_per_K : float
    material, source : str
    """

    section: str
    area_mm2: float
    inertia_mm4: float
    youngs_modulus_MPa: float
    shear_modulus_MPa: float
    density_kg_per_mm3: float
    cte_per_K: float
    material: str = ""
    source: str = ""

    @property
    def EI_Nmm2(self) -> float:
        """Bending stiffness ``E I`` [N mm^2]."""
        return self.youngs_modulus_MPa * self.inertia_mm4

    @property
    def shear_stiffness_N(self) -> float:
        """Shear stiffness ``kappa G A`` [N] (``kappa = 0.5`` for a thin tube or box, ``0.9`` for a solid section)."""
        return (0.9 if self.section == "solid" else 0.5) * self.shear_modulus_MPa * self.area_mm2


@dataclass(frozen=True)
class Mount:
    """The base mount: tilting stiffness about base x and y [N m/rad] (None: unknown), source."""

    tilt_stiffness: tuple | None = None
    source: str = ""


@dataclass(frozen=True)
class Payload:
    """Rated payload [kg] and its centre of mass from the tool point in the tool frame [mm]."""

    rated_kg: float | None = None
    com_mm: np.ndarray = field(default_factory=lambda: np.zeros(3))


@dataclass(frozen=True)
class Components:
    """A robot's component data (all optional): ``joints`` and ``links`` by name, ``mount``, ``payload``, ``source``."""

    joints: dict = field(default_factory=dict)
    links: dict = field(default_factory=dict)
    mount: Mount = field(default_factory=Mount)
    payload: Payload = field(default_factory=Payload)
    source: str = ""

    def joint(self, name: str) -> JointComponents:
        """The parts of joint ``name`` (empty when the file gives none)."""
        return self.joints.get(name, JointComponents())

    def gear_ratios(self, joint_names) -> np.ndarray | None:
        """Gear ratio of every joint, shape (n,), NaN where unknown; None when no joint has one."""
        r = np.array([getattr(self.joint(nm).reducer, "ratio", None) or np.nan for nm in joint_names], float)
        return None if np.all(np.isnan(r)) else r

    def __bool__(self) -> bool:
        return bool(self.joints or self.links or self.mount.tilt_stiffness or self.payload.rated_kg)


# ---- parsing ------------------------------------------------------------------------------------------------------

def read_table(table: dict, spec: dict, where: str, text: tuple = ()) -> dict:
    """Values of the unit-suffixed keys of ``table`` in internal units, ``{base: value}`` (absent keys: None).

    ``spec``: ``{base: (units {suffix: factor}, shape or None)}``; ``text``: plain keys (no unit) also allowed.
    Raises ValueError naming the key for a missing unit suffix, an unknown unit or key, or a non-finite value.
    """
    if not isinstance(table, dict):
        raise ValueError(f"{where}: expected a table of keys, got {table!r}")
    out, used = {b: None for b in spec}, set()
    for base, (units, shape) in spec.items():
        keys = [k for k in table if k == base or (k.startswith(base + "_") and k[len(base) + 1:] in units)]
        if base in table:
            raise ValueError(f"{where}.{base}: the key has no unit; write it as "
                             + " or ".join(f"{base}_{u}" for u in units))
        if len(keys) > 1:
            raise ValueError(f"{where}: give {base} once, got {keys}")
        if not keys:
            continue
        k = keys[0]
        try:
            v = np.asarray(table[k], dtype=float) * units[k[len(base) + 1:]]
        except (TypeError, ValueError):
            raise ValueError(f"{where}.{k}: expected a number or a list of numbers, got {table[k]!r}") from None
        if not np.all(np.isfinite(v)) or (shape is not None and v.shape not in shape):
            want = " or ".join("a number" if s == () else f"{s[0]} numbers" for s in shape or ((),))
            raise ValueError(f"{where}.{k}: expected {want} (finite), got {table[k]!r}")
        out[base] = float(v) if v.ndim == 0 else tuple(float(x) for x in v)
        used.add(k)
    extra = [k for k in table if k not in used and k not in text]
    if extra:
        k = extra[0]
        base = next((b for b in spec if k.startswith(b + "_")), None)
        if base is not None:
            raise ValueError(f"{where}.{k}: unknown unit {k[len(base) + 1:]!r}; expected "
                             + " or ".join(f"{base}_{u}" for u in spec[base][0]))
        keys = [f"{b}_<{'|'.join(spec[b][0])}>" for b in spec] + list(text)
        raise ValueError(f"{where}: unknown key {k!r}; expected keys among {', '.join(keys)}")
    return out


def _text(table: dict, key: str, where: str, default=None, choices=None):
    v = table.get(key, default)
    if v is not None and not isinstance(v, str):
        raise ValueError(f"{where}.{key}: expected a string, got {v!r}")
    if choices is not None and v is not None and v not in choices:
        raise ValueError(f"{where}.{key}: expected one of {', '.join(choices)}, got {v!r}")
    return v


def _positive(v, key: str, where: str, allow_zero: bool = False):
    vals = (v,) if isinstance(v, float) else v
    if v is not None and any((x < 0 if allow_zero else x <= 0) for x in vals):
        raise ValueError(f"{where}.{key}: expected {'non-negative' if allow_zero else 'positive'} values, got {v}")
    return v


def _reducer(table: dict, where: str, revolute: bool) -> Reducer:
    ang = _ANGLE if revolute else _LENGTH
    spec = {"stiffness": (_ROT_STIFF if revolute else _LIN_STIFF, ((), (1,), (3,))),
            "torque_bands": ({"Nm": 1.0} if revolute else {"N": 1.0}, ((2,),)),
            "lost_motion": (ang, ((),)), "hysteresis": (ang, ((),)), "transmission_accuracy": (ang, ((),)),
            "rated_torque" if revolute else "rated_force": ({"Nm": 1.0} if revolute else {"N": 1.0}, ((),))}
    v = read_table(table, spec, where, text=("type", "ratio", "source", "cost", "cost_source", "part"))
    kind = _text(table, "type", where, "strain_wave", REDUCER_TYPES)
    ratio = table.get("ratio")
    if ratio is not None:
        if isinstance(ratio, bool) or not isinstance(ratio, (int, float)) or not np.isfinite(ratio) or ratio <= 0:
            raise ValueError(f"{where}.ratio: expected a positive gear ratio (input turns per output turn, e.g. "
                             f"101), got {ratio!r}")
    k = v["stiffness"]
    k = () if k is None else ((k,) if isinstance(k, float) else tuple(k))
    _positive(k or None, "stiffness", where)
    bands = v["torque_bands"] or ()
    if len(k) == 3:
        if any(b < a for a, b in zip(k, k[1:])):
            raise ValueError(f"{where}.stiffness: the curve softens with torque (K1, K2, K3 = {list(k)}); a gear's "
                             "torsional stiffness rises with torque: expected K1 <= K2 <= K3 (catalogue order)")
        if len(bands) != 2 or not 0 < bands[0] < bands[1]:
            raise ValueError(f"{where}.torque_bands: three stiffnesses need the band limits T1 < T2 (both > 0), "
                             f"got {list(bands) or 'none'}")
    elif bands:
        raise ValueError(f"{where}.torque_bands: band limits need three stiffnesses K1, K2, K3, got {len(k)}")
    for key in ("lost_motion", "hysteresis", "transmission_accuracy"):
        _positive(v[key], key, where, allow_zero=True)
    rated = v["rated_torque" if revolute else "rated_force"]
    _positive(rated, "rated torque", where)
    return Reducer(kind, None if ratio is None else float(ratio), k, tuple(bands), v["lost_motion"],
                   v["hysteresis"], v["transmission_accuracy"], rated, _text(table, "source", where, ""))


def _section(table: dict, where: str) -> LinkSection:
    spec = {"outer_diameter": (_LENGTH, ((),)), "wall": (_LENGTH, ((),)), "width": (_LENGTH, ((),)),
            "height": (_LENGTH, ((),)), "youngs_modulus": (_MODULUS, ((),)), "shear_modulus": (_MODULUS, ((),)),
            "density": ({"kg_per_m3": 1e-9}, ((),)), "cte": (_CTE, ((),))}
    v = read_table(table, spec, where, text=("section", "material", "source"))
    kind = _text(table, "section", where, None, ("tube", "solid", "box"))
    if kind is None:
        raise ValueError(f"{where}: missing section; expected section = \"tube\", \"solid\" or \"box\"")
    need = {"tube": ("outer_diameter", "wall"), "solid": ("outer_diameter",), "box": ("width", "height", "wall")}[kind]
    missing = [f"{k}_mm" for k in need if v[k] is None]
    if missing:
        raise ValueError(f"{where}: a {kind} section needs {', '.join(missing)}")
    for k in need:
        _positive(v[k], k, where)
    if kind == "tube":
        D, t = v["outer_diameter"], v["wall"]
        if 2 * t >= D:
            raise ValueError(f"{where}.wall_mm: the wall {t:g} mm is at least half the diameter {D:g} mm; use "
                             "section = \"solid\"")
        d = D - 2 * t
        A, I = np.pi / 4 * (D**2 - d**2), np.pi / 64 * (D**4 - d**4)
    elif kind == "solid":
        D = v["outer_diameter"]
        A, I = np.pi / 4 * D**2, np.pi / 64 * D**4
    else:
        b, h, t = v["width"], v["height"], v["wall"]
        if 2 * t >= min(b, h):
            raise ValueError(f"{where}.wall_mm: the wall {t:g} mm is at least half the width or height")
        A, I = b * h - (b - 2 * t) * (h - 2 * t), (b * h**3 - (b - 2 * t) * (h - 2 * t) ** 3) / 12
    material = _text(table, "material", where, None, tuple(MATERIALS))
    E, G, rho, cte, src = MATERIALS.get(material, (None,) * 5)
    E, G = v["youngs_modulus"] or E, v["shear_modulus"] or G
    rho, cte = v["density"] or rho, v["cte"] if v["cte"] is not None else cte
    if E is None:
        raise ValueError(f"{where}: no material figures; give material = one of {', '.join(MATERIALS)}, or "
                         "youngs_modulus_GPa (and shear_modulus_GPa, density_kg_per_m3, cte_um_per_m_K)")
    G = G if G is not None else E / 2.6
    return LinkSection(kind, float(A), float(I), float(E), float(G), float(rho or 0.0), float(cte or 0.0),
                       material or "", _text(table, "source", where, src or ""))


def _joint_parts(table: dict, where: str, revolute: bool) -> JointComponents:
    extra = [k for k in table if k not in ("reducer", "encoder", "bearing", "motor")]
    if extra:
        raise ValueError(f"{where}: unknown part {extra[0]!r}; expected reducer, encoder, bearing or motor")
    red = table.get("reducer")
    red = None if red is None else _reducer(red, f"{where}.reducer", revolute)
    enc = bear = mot = None
    if "encoder" in table:
        t, w = table["encoder"], f"{where}.encoder"
        v = read_table(t, {"accuracy": (_ANGLE if revolute else _LENGTH, ((),))}, w, text=("side", "source"))
        enc = Encoder(_text(t, "side", w, "output", ("output", "motor")),
                      _positive(v["accuracy"], "accuracy", w, True), _text(t, "source", w, ""))
    if "bearing" in table:
        t, w = table["bearing"], f"{where}.bearing"
        v = read_table(t, {"span": (_LENGTH, ((),)), "tilt_stiffness": (_ROT_STIFF, ((),)),
                           "seat_diameter": (_LENGTH, ((),))}, w, text=("precision_class", "datum", "source"))
        bear = Bearing(_text(t, "precision_class", w), _positive(v["span"], "span", w), _text(t, "datum", w),
                       _positive(v["tilt_stiffness"], "tilt_stiffness", w), _text(t, "source", w, ""),
                       _positive(v["seat_diameter"], "seat_diameter", w))
    if "motor" in table:
        t, w = table["motor"], f"{where}.motor"
        v = read_table(t, {"winding_resistance": ({"ohm": 1.0}, ((),)), "torque_constant": ({"Nm_per_A": 1.0}, ((),)),
                           "thermal_resistance": ({"K_per_W": 1.0}, ((),)),
                           "thermal_time_constant": (_TIME, ((),))}, w, text=("source",))
        for k, x in v.items():
            _positive(x, k, w)
        mot = Motor(v["winding_resistance"], v["torque_constant"], v["thermal_resistance"],
                    v["thermal_time_constant"], _text(t, "source", w, ""))
    return JointComponents(red, enc, bear, mot)


def parse_components(data: dict | None, joint_kinds: dict, link_names, where: str = "components") -> Components:
    """:class:`Components` from a robot file's ``[components]`` table (None or empty: no component data).

    ``joint_kinds``: ``{joint name: is revolute}`` of the chain; ``link_names``: the chain's link names.
    Raises ValueError naming the key (the robot-file loaders turn it into a TolallocError with the file's name).
    """
    if not data:
        return Components()
    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected a table, got {data!r}")
    extra = [k for k in data if k not in ("source", "payload", "mount", "joints", "links")]
    if extra:
        raise ValueError(f"{where}: unknown key {extra[0]!r}; expected source, payload, mount, joints or links")
    joints, links = {}, {}
    for name, table in (data.get("joints") or {}).items():
        if name not in joint_kinds:
            raise ValueError(f"{where}.joints.{name}: not a joint of the chain; joints: {', '.join(joint_kinds)}")
        joints[name] = _joint_parts(table, f"{where}.joints.{name}", joint_kinds[name])
    for name, table in (data.get("links") or {}).items():
        if name not in link_names:
            raise ValueError(f"{where}.links.{name}: not a link of the chain; links: {', '.join(link_names)}")
        links[name] = _section(table, f"{where}.links.{name}")
    mount = Mount()
    if "mount" in data:
        w = f"{where}.mount"
        v = read_table(data["mount"], {"tilt_stiffness": (_ROT_STIFF, ((), (2,)))}, w, text=("source",))
        k = v["tilt_stiffness"]
        k = None if k is None else ((k, k) if isinstance(k, float) else tuple(k))
        mount = Mount(_positive(k, "tilt_stiffness", w), _text(data["mount"], "source", w, ""))
    payload = Payload()
    if "payload" in data:
        w = f"{where}.payload"
        v = read_table(data["payload"], {"rated": ({"kg": 1.0}, ((),)), "com": (_LENGTH, ((3,),))}, w)
        payload = Payload(_positive(v["rated"], "rated", w, True),
                          np.zeros(3) if v["com"] is None else np.array(v["com"]))
    return Components(joints, links, mount, payload, _text(data, "source", where, "") or "")

"""Readers of component figures (format: :mod:`tolalloc.robot.components`), every key with its unit
(:func:`read_table`): the robot file's ``[components]`` section (:mod:`tolalloc.robot.components_file`) and the
entries of the component catalogue (:mod:`tolalloc.robot.part_catalogue`) both read their figures here.
"""

from __future__ import annotations

import re

import numpy as np

from tolalloc.robot.components import (_ANGLE, _CTE, _LENGTH, _LIN_STIFF, _MODULUS, _ROT_STIFF, _TIME, MATERIALS,
                                       REDUCER_TYPES, Bearing, Encoder, Guide, LinkSection, Motor, Reducer)

__all__ = ["DATUM_KEYS", "DATUM_LETTER", "datum_letter", "read_table", "read_reducer", "read_encoder", "read_bearing", "read_motor",
           "read_guide", "read_section"]


class Values(dict):
    """:func:`read_table`'s values in internal units, ``{base: value}``; ``source[base]``: the file's key and value it
    came from (for messages in the file's own terms)."""

    def __init__(self, *args):
        super().__init__(*args)
        self.source = {}


def read_table(table: dict, spec: dict, where: str, text: tuple = ()) -> dict:
    """Values of the unit-suffixed keys of ``table`` in internal units, ``{base: value}`` (absent keys: None).

    ``spec``: ``{base: (units {suffix: factor}, shape or None)}``; ``text``: plain keys (no unit) also allowed.
    Raises ValueError naming the key for a missing unit suffix, an unknown unit or key, or a non-finite value.
    """
    if not isinstance(table, dict):
        raise ValueError(f"{where}: expected a table of keys, got {table!r}")
    out, used = Values({b: None for b in spec}), set()
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
        out.source[base] = (k, table[k])
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


#: A bearing table's drawing letters: the seat axis, the output's angular locating feature, the seat shoulder face.
DATUM_KEYS = ("datum", "locating_datum", "shoulder_datum")
#: One datum letter (ISO 5459: capital letters; two where one alphabet runs out), as a regular expression.
DATUM_LETTER = "[A-Z]{1,2}"


def datum_letter(table: dict, key: str, where: str) -> str | None:
    """``table[key]``, a datum letter (ISO 5459: one or two capital letters), refused naming the key otherwise;
    None where it is missing."""
    v = _text(table, key, where)
    if v is not None and not re.fullmatch(DATUM_LETTER, v):
        raise ValueError(f"{where}.{key}: expected a datum letter (one or two capital letters, as B or AB), got {v!r}")
    return v


def _positive_in(values: Values, key: str, where: str, allow_zero: bool = False):
    """``values[key]`` (a :func:`read_table` value), refused naming the file's key and value unless every entry is
    > 0 (>= 0 with ``allow_zero``); None passes."""
    v = values[key]
    vals = (v,) if isinstance(v, float) else v
    if v is not None and any((x < 0 if allow_zero else x <= 0) for x in vals):
        file_key, raw = values.source[key]
        raise ValueError(f"{where}.{file_key}: expected {'non-negative' if allow_zero else 'positive'} values, got "
                         f"{raw!r}")
    return v


def read_reducer(table: dict, where: str, revolute: bool, extra_keys: tuple = ()) -> Reducer:
    """A :class:`Reducer` from its table (keys with units, module doc of :mod:`tolalloc.robot.components`)."""
    ang = _ANGLE if revolute else _LENGTH
    spec = {"stiffness": (_ROT_STIFF if revolute else _LIN_STIFF, ((), (1,), (3,))),
            "torque_bands": ({"Nm": 1.0} if revolute else {"N": 1.0}, ((2,),)),
            "lost_motion": (ang, ((),)), "hysteresis": (ang, ((),)), "transmission_accuracy": (ang, ((),)),
            "repeatability": (ang, ((),)), "stiffness_sd": ({"pct": 0.01}, ((),)),
            "rated_torque" if revolute else "rated_force": ({"Nm": 1.0} if revolute else {"N": 1.0}, ((),))}
    v = read_table(table, spec, where, text=("type", "ratio", "source", "cost", "cost_source", "part") + extra_keys)
    kind = _text(table, "type", where, "strain_wave", REDUCER_TYPES)
    ratio = table.get("ratio")
    if ratio is not None:
        if isinstance(ratio, bool) or not isinstance(ratio, (int, float)) or not np.isfinite(ratio) or ratio <= 0:
            raise ValueError(f"{where}.ratio: expected a positive gear ratio (input turns per output turn, e.g. "
                             f"101), got {ratio!r}")
    k = _positive_in(v, "stiffness", where)
    k = () if k is None else ((k,) if isinstance(k, float) else tuple(k))
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
    for key in ("lost_motion", "hysteresis", "transmission_accuracy", "repeatability", "stiffness_sd"):
        _positive_in(v, key, where, allow_zero=True)
    rated = _positive_in(v, "rated_torque" if revolute else "rated_force", where)
    return Reducer(kind, None if ratio is None else float(ratio), k, tuple(bands), v["lost_motion"],
                   v["hysteresis"], v["transmission_accuracy"], rated, _text(table, "source", where, ""),
                   v["repeatability"], v["stiffness_sd"])


def read_section(table: dict, where: str) -> LinkSection:
    """A :class:`LinkSection` from a link's table (section, dimensions, material)."""
    spec = {"outer_diameter": (_LENGTH, ((),)), "wall": (_LENGTH, ((),)), "width": (_LENGTH, ((),)),
            "height": (_LENGTH, ((),)), "youngs_modulus": (_MODULUS, ((),)), "shear_modulus": (_MODULUS, ((),)),
            "density": ({"kg_per_m3": 1e-9}, ((),)), "cte": (_CTE, ((),))}
    v = read_table(table, spec, where, text=("section", "material", "source", "height_direction"))
    kind = _text(table, "section", where, None, ("tube", "solid", "box"))
    if kind is None:
        raise ValueError(f"{where}: missing section; expected section = \"tube\", \"solid\" or \"box\"")
    need = {"tube": ("outer_diameter", "wall"), "solid": ("outer_diameter",), "box": ("width", "height", "wall")}[kind]
    missing = [f"{k}_mm" for k in need if v[k] is None]
    if missing:
        raise ValueError(f"{where}: a {kind} section needs {', '.join(missing)}")
    for k in (*need, "youngs_modulus", "shear_modulus", "density"):
        _positive_in(v, k, where)
    if kind == "tube":
        D, t = v["outer_diameter"], v["wall"]
        if 2 * t >= D:
            raise ValueError(f"{where}.wall_mm: the wall {t:g} mm is at least half the diameter {D:g} mm; use "
                             "section = \"solid\"")
        d = D - 2 * t
        A, I = np.pi / 4 * (D**2 - d**2), np.pi / 64 * (D**4 - d**4)
        J = 2 * I
    elif kind == "solid":
        D = v["outer_diameter"]
        A, I = np.pi / 4 * D**2, np.pi / 64 * D**4
        J = 2 * I
    else:
        b, h, t = v["width"], v["height"], v["wall"]
        if 2 * t >= min(b, h):
            raise ValueError(f"{where}.wall_mm: the wall {t:g} mm is at least half the width or height")
        A, I = b * h - (b - 2 * t) * (h - 2 * t), (b * h**3 - (b - 2 * t) * (h - 2 * t) ** 3) / 12
        I_side = (h * b**3 - (h - 2 * t) * (b - 2 * t) ** 3) / 12
        J = 2 * t * (b - t) ** 2 * (h - t) ** 2 / (b + h - 2 * t)  # Bredt, wall midline
    material = _text(table, "material", where, None, tuple(MATERIALS))
    E, G, rho, cte, src = MATERIALS.get(material, (None,) * 5)
    E = v["youngs_modulus"] if v["youngs_modulus"] is not None else E
    G = v["shear_modulus"] if v["shear_modulus"] is not None else G
    rho = v["density"] if v["density"] is not None else rho
    cte = v["cte"] if v["cte"] is not None else cte
    if E is None:
        raise ValueError(f"{where}: no material figures; give material = one of {', '.join(MATERIALS)}, or "
                         "youngs_modulus_GPa (and shear_modulus_GPa, density_kg_per_m3, cte_um_per_m_K)")
    G = G if G is not None else E / 2.6
    return LinkSection(kind, float(A), float(I), float(J), float(E), float(G), float(rho or 0.0), float(cte or 0.0),
                       material or "", _text(table, "source", where, src or ""),
                       float(I_side) if kind == "box" else float(I), _height_direction(table, kind, where))


def _height_direction(table: dict, kind: str, where: str) -> tuple | None:
    """A box's ``height_direction`` (three numbers, normalised), or None where the table gives none."""
    raw = table.get("height_direction")
    if raw is None:
        return None
    if kind != "box":
        raise ValueError(f"{where}.height_direction: a {kind} section bends alike in every plane; the key is for "
                         "section = \"box\" (drop it)")
    try:
        d = np.asarray(raw, dtype=float)
    except (TypeError, ValueError):
        d = np.full(1, np.nan)
    if d.shape != (3,) or not np.all(np.isfinite(d)) or np.linalg.norm(d) == 0.0:
        raise ValueError(f"{where}.height_direction: expected 3 finite numbers, not all zero (the box's height "
                         f"direction at the home pose, base frame), got {raw!r}")
    return tuple(float(x) for x in d / np.linalg.norm(d))


def read_encoder(t: dict, w: str, revolute: bool, extra_keys: tuple = ()) -> Encoder:
    """An :class:`Encoder` from its table."""
    ang = _ANGLE if revolute else _LENGTH
    v = read_table(t, {"accuracy": (ang, ((),)), "eccentricity": (_LENGTH, ((),)), "scale_radius": (_LENGTH, ((),)),
                       "homing_repeatability": (ang, ((),)), "scale_expansion": (_CTE, ((),))}, w,
                   text=("side", "source", "homing") + extra_keys)
    homing = _text(t, "homing", w, "absolute", ("absolute", "incremental"))
    side = _text(t, "side", w, "output", ("output", "motor"))
    if v["eccentricity"] is not None and (side != "output" or not revolute):
        raise ValueError(f"{w}.eccentricity_um: a scale's mounting eccentricity is an error of an output-side rotary "
                         "encoder (e / r once per turn); this one is "
                         f"{'motor-side' if side != 'output' else 'linear'}: drop the key (its accuracy covers it)")
    if v["eccentricity"] is not None and v["scale_radius"] is None:
        raise ValueError(f"{w}.eccentricity_um: the error it gives is e / r once per turn; give the scale's radius "
                         "scale_radius_mm too")
    if v["homing_repeatability"] is not None and homing != "incremental":
        raise ValueError(f"{w}.homing_repeatability: an absolute encoder keeps its zero through a power cycle; the "
                         "repeatability of the homing applies to homing = \"incremental\" (set it, or drop the key)")
    return Encoder(side, _positive_in(v, "accuracy", w, True),
                   _text(t, "source", w, ""), _positive_in(v, "eccentricity", w, True),
                   _positive_in(v, "scale_radius", w), homing,
                   _positive_in(v, "homing_repeatability", w, True), v["scale_expansion"])


def read_bearing(t: dict, w: str, extra_keys: tuple = ()) -> Bearing:
    """A :class:`Bearing` from its table."""
    v = read_table(t, {"span": (_LENGTH, ((),)), "tilt_stiffness": (_ROT_STIFF, ((),)), "bore": (_LENGTH, ((),)),
                       "radial_runout": (_LENGTH, ((),)), "seat_diameter": (_LENGTH, ((),)),
                       "centre": (_LENGTH, ((),))}, w, text=("precision_class", "source", *DATUM_KEYS) + extra_keys)
    return Bearing(_text(t, "precision_class", w), _positive_in(v, "span", w), datum_letter(t, "datum", w),
                   _positive_in(v, "tilt_stiffness", w), _text(t, "source", w, ""),
                   _positive_in(v, "bore", w), _positive_in(v, "radial_runout", w, True),
                   _positive_in(v, "seat_diameter", w), float(v["centre"] or 0.0),
                   datum_letter(t, "locating_datum", w), datum_letter(t, "shoulder_datum", w))


def read_guide(t: dict, w: str) -> Guide:
    """A :class:`Guide` (a prismatic joint's drawing letters) from its table."""
    if not isinstance(t, dict):
        raise ValueError(f"{w}: expected a table of datum letters ({', '.join(DATUM_KEYS)}), got {t!r}")
    extra = [k for k in t if k not in DATUM_KEYS]
    if extra:
        raise ValueError(f"{w}: unknown key {extra[0]!r}; expected {', '.join(DATUM_KEYS)}")
    return Guide(*(datum_letter(t, k, w) for k in DATUM_KEYS))


def read_motor(t: dict, w: str, extra_keys: tuple = ()) -> Motor:
    """A :class:`Motor` from its table."""
    v = read_table(t, {"winding_resistance": ({"ohm": 1.0}, ((),)), "torque_constant": ({"Nm_per_A": 1.0}, ((),)),
                       "thermal_resistance": ({"K_per_W": 1.0}, ((),)), "thermal_time_constant": (_TIME, ((),)),
                       "link_coupling": ({"pct": 0.01}, ((),))}, w, text=("source",) + extra_keys)
    for k in v:
        _positive_in(v, k, w, allow_zero=k == "link_coupling")
    if v["link_coupling"] is not None and v["link_coupling"] > 1.0:
        key, raw = v.source["link_coupling"]
        raise ValueError(f"{w}.{key}: the links reach a share of the motor's temperature rise, at most 100 %, got "
                         f"{raw!r}")
    return Motor(v["winding_resistance"], v["torque_constant"], v["thermal_resistance"], v["thermal_time_constant"],
                 _text(t, "source", w, ""), v["link_coupling"])

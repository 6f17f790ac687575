"""The robot file's ``[components]`` section (format: :mod:`tolalloc.robot.components`) into :class:`Components`.

A joint's part is its figures (:mod:`tolalloc.robot.components_io`) or a slot of the component catalogue
(:func:`tolalloc.robot.part_catalogue.parse_slot`), resolved against the built-in catalogue and the file's own.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.components import _LENGTH, _ROT_STIFF, Components, JointComponents, Mount, Payload
from tolalloc.robot.components_io import (_positive_in, _text, datum_letter, read_bearing, read_encoder,
                                          read_guide, read_motor, read_reducer, read_section, read_table)
from tolalloc.robot.part_catalogue import parse_slot, robot_catalogue

__all__ = ["parse_components", "SLOT_KEYS"]

#: Keys that make a joint's part table a catalogue slot (:mod:`tolalloc.robot.part_catalogue`).
SLOT_KEYS = ("part", "family", "options")


def _joint_parts(table: dict, where: str, revolute: bool, slots: dict, name: str, catalogue) -> JointComponents:
    extra = [k for k in table if k not in ("reducer", "encoder", "bearing", "motor", "guide")]
    if extra:
        raise ValueError(f"{where}: unknown part {extra[0]!r}; expected reducer, encoder, bearing, motor or guide")
    parts = {}
    if "guide" in table:
        if revolute:
            raise ValueError(f"{where}.guide: {name} is a revolute joint; its drawing letters go in its bearing "
                             "table (datum, locating_datum, shoulder_datum)")
        parts["guide"] = read_guide(table["guide"], f"{where}.guide")
    for kind, fn in (("reducer", lambda t, w: read_reducer(t, w, revolute)), ("encoder", lambda t, w: read_encoder(t, w, revolute)),
                     ("bearing", lambda t, w: read_bearing(t, w)), ("motor", lambda t, w: read_motor(t, w))):
        t, w = table.get(kind), f"{where}.{kind}"
        if t is None:
            continue
        if isinstance(t, dict) and any(k in t for k in SLOT_KEYS):
            slots[(name, kind)] = parse_slot(t, w, kind, name, revolute, catalogue())
            continue
        parts[kind] = fn(t, w)
    if "bearing" in parts and not revolute:
        raise ValueError(f"{where}.bearing: {name} is a prismatic joint; a bearing table (ISO 492 runout, tilt "
                         "stiffness) describes a revolute joint's rotary bearing pair. Drop the table: a linear "
                         "guide's errors go in the joint's tolerances")
    return JointComponents(**parts)


def _check_across(section, vector, where: str) -> None:
    """A box's height direction must lie across its link: within 10 deg of normal to the link's home vector."""
    if section.height_direction is None or vector is None or np.linalg.norm(vector) == 0.0:
        return
    e = np.asarray(vector, float) / np.linalg.norm(vector)
    off = np.degrees(np.arcsin(min(1.0, abs(float(np.dot(e, section.height_direction))))))
    if off > 10.0:
        vec = [round(float(v), 6) for v in vector]
        raise ValueError(f"{where}.height_direction: {list(section.height_direction)} is {off:.1f} deg off the plane "
                         f"across the link (its vector {vec} mm at the home pose); give the direction of the box's "
                         "height across the link, at the home pose, in the base frame")


def parse_components(data: dict | None, joint_kinds: dict, link_names, where: str = "components",
                     base_dir=None, link_vectors: dict | None = None) -> Components:
    """:class:`Components` from a robot file's ``[components]`` table (None or empty: no component data).

    ``joint_kinds``: ``{joint name: is revolute}`` of the chain; ``link_names``: the chain's link names;
    ``link_vectors``: ``{link name: vector at the home pose [mm]}``, to check a box's height direction lies across its
    link (optional); ``base_dir``:
    where a ``catalogue_file`` is looked for (the robot file's folder). Slots are resolved against the built-in
    component catalogue, the ``catalogue_file`` and the inline ``[components.catalogue]`` tables merged over it.
    Raises ValueError naming the key (the robot-file loaders turn it into a TolallocError with the file's name).
    """
    if not data:
        return Components()
    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected a table, got {data!r}")
    extra = [k for k in data if k not in ("source", "payload", "mount", "joints", "links", "catalogue",
                                          "catalogue_file")]
    if extra:
        raise ValueError(f"{where}: unknown key {extra[0]!r}; expected source, payload, mount, joints, links, "
                         "catalogue or catalogue_file")
    joints, links, slots, cat = {}, {}, {}, []

    def catalogue():
        if not cat:
            cat.append(robot_catalogue(data, where, base_dir))
        return cat[0]

    for name, table in (data.get("joints") or {}).items():
        if name not in joint_kinds:
            raise ValueError(f"{where}.joints.{name}: not a joint of the chain; joints: {', '.join(joint_kinds)}")
        if not isinstance(table, dict):
            raise ValueError(f"{where}.joints.{name}: expected a table of parts, got {table!r}")
        joints[name] = _joint_parts(table, f"{where}.joints.{name}", joint_kinds[name], slots, name, catalogue)
    for name, table in (data.get("links") or {}).items():
        if name not in link_names:
            raise ValueError(f"{where}.links.{name}: not a link of the chain; links: {', '.join(link_names)}")
        links[name] = read_section(table, f"{where}.links.{name}")
        _check_across(links[name], (link_vectors or {}).get(name), f"{where}.links.{name}")
    mount = Mount()
    if "mount" in data:
        w = f"{where}.mount"
        v = read_table(data["mount"], {"tilt_stiffness": (_ROT_STIFF, ((), (2,)))}, w,
                       text=("source", "datum", "locating_datum"))
        k = _positive_in(v, "tilt_stiffness", w)
        k = None if k is None else ((k, k) if isinstance(k, float) else tuple(k))
        mount = Mount(k, _text(data["mount"], "source", w, ""), datum_letter(data["mount"], "datum", w),
                      datum_letter(data["mount"], "locating_datum", w))
    payload = Payload()
    if "payload" in data:
        w = f"{where}.payload"
        v = read_table(data["payload"], {"rated": ({"kg": 1.0}, ((),)), "com": (_LENGTH, ((3,),))}, w)
        payload = Payload(_positive_in(v, "rated", w, True),
                          np.zeros(3) if v["com"] is None else np.array(v["com"]))
    if ("catalogue" in data or "catalogue_file" in data) and not cat:
        catalogue()  # validate the file's catalogue even when no slot uses it
    return Components(joints, links, mount, payload, _text(data, "source", where, "") or "", slots)

"""URDF import: a serial chain of a URDF tree as a :class:`~tolalloc.robot.model.Robot`.

The file is parsed with `yourdfpy <https://github.com/clemense/yourdfpy>`_ (after a strict XML check
of our own, so that a broken file is reported rather than silently recovered). The chain is the path
from the URDF's root link (the base frame) to the **tool link**:

* the tool link is ``tool`` if given (``--tool LINK`` on the command line), otherwise the leaf link
  with the most movable joints above it; when several leaves tie (the tree branches, e.g. a gripper's
  two fingers, or ``ee_link`` beside ``tool0``) the import is refused and the candidates are listed; so it is
  when the longest chain ends in a movable joint named like a gripper (``grip``, ``finger``, ``jaw``, ``hand``)
  -- a single-jaw gripper does not branch the tree;
* movable joints off the path (gripper fingers ...) are ignored; their links count as rigid bodies of
  the path link they hang from (for the masses);
* ``revolute`` and ``continuous`` joints become revolute joints (continuous: limits +-720 deg),
  ``prismatic`` joints prismatic; ``fixed`` joints are folded into the link vectors;
  ``floating`` and ``planar`` joints and joints with ``<mimic>`` on the path are refused;
* every non-zero joint-origin translation on the path becomes a named :class:`~tolalloc.robot.model.Link`
  called after the URDF link it lies in (the joint's parent link), so each carries a length tolerance;
* joint axes are normalised; a movable joint on the path **without** an ``<axis>`` element is refused
  (the URDF default ``(1, 0, 0)`` is a frequent authoring slip and the whole error model depends on
  the axes): add ``<axis xyz="1 0 0"/>`` if the default is meant;
* limits: from ``<limit>`` (rad / m; required on revolute and prismatic joints, as the URDF spec says,
  and a missing one is refused with the joint's name); continuous joints +-720 deg; the nominal
  joint value is 0 when inside the limits, else the middle of the limits;
* lengths are metres in URDF and mm inside tolalloc; a joint origin farther than 5 m from its parent
  link, a path longer than 20 m or a prismatic stroke above 20 m is refused as "not metres";
* every link with an ``<inertial>`` mass > 0 gives a :class:`~tolalloc.robot.model.Mass` (centre of mass in
  the base frame at the zero configuration, in mm; ``body`` = movable path joints above the link).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Joint, Link, Mass, Robot

__all__ = ["load_urdf"]

MOVABLE = ("revolute", "continuous", "prismatic")
#: Names of end-effector joints that must not be taken as arm joints without a tool link given (matched on joint and child link).
GRIPPER_WORDS = re.compile(r"grip|finger|jaw|hand", re.IGNORECASE)
MAX_ORIGIN_M = 5.0
MAX_REACH_M = 20.0
CONTINUOUS_LIMIT_RAD = 4 * np.pi
DEFAULT_LIMIT = {"revolute": 2 * np.pi, "prismatic": 1000.0}


def _parse(path: Path, source: str):
    """Strict XML check, then yourdfpy; returns (yourdfpy.URDF, set of movable joints without <axis>)."""
    from lxml import etree

    try:
        root = etree.parse(str(path), etree.XMLParser(remove_blank_text=True)).getroot()
    except etree.XMLSyntaxError as exc:
        raise TolallocError(f"{source}: not valid XML ({exc}); expected a URDF file (expand a .xacro file first "
                            "with `xacro robot.urdf.xacro > robot.urdf`).") from None
    def _xacro(el) -> bool:
        tag = el.tag if isinstance(el.tag, str) else ""
        return "xacro" in tag or any("${" in v or "$(" in v for v in el.attrib.values())

    if any(_xacro(el) for el in root.iter()):
        raise TolallocError(f"{source}: an unexpanded xacro file (xacro elements or ${{...}} / $(...) expressions); "
                            "expand it first with `xacro robot.urdf.xacro > robot.urdf` and load robot.urdf.")
    if root.tag != "robot":
        raise TolallocError(f"{source}: the root element is <{root.tag}>; expected <robot> (a URDF file).")
    no_axis = {j.get("name") for j in root.findall("joint") if j.get("type") in MOVABLE and j.find("axis") is None}
    for j in root.findall("joint"):
        if j.get("type") in ("revolute", "prismatic") and j.find("limit") is None:
            raise TolallocError(f"{source}: joint {j.get('name')!r} ({j.get('type')}) has no <limit>; URDF requires "
                                "<limit lower=... upper=... effort=... velocity=...> on revolute and prismatic joints "
                                "(use type=\"continuous\" for an unlimited revolute joint).")
    import yourdfpy

    try:
        urdf = yourdfpy.URDF.load(str(path), build_scene_graph=False, load_meshes=False,
                                  build_collision_scene_graph=False, load_collision_meshes=False)
    except Exception as exc:  # noqa: BLE001  (the parser raises bare AttributeError/KeyError on malformed files)
        raise TolallocError(f"{source}: yourdfpy could not read the URDF ({type(exc).__name__}: {exc}); check that every "
                            "<joint> has a name, a type, <parent link=...> and <child link=...>.") from None
    errors = []
    urdf.validate(lambda errs: errors.extend(errs) or True)
    if errors:
        raise TolallocError(f"{source}: invalid URDF: {'; '.join(str(e).rstrip('.') for e in errors[:5])}.")
    return urdf, no_axis


def _tree(urdf, source: str):
    """Parent joint of every link, child joints of every link, and the root link; refuse loops."""
    links = [lk.name for lk in urdf.robot.links]
    link_set = set(links)
    parent_joint, children = {}, {name: [] for name in links}
    for j in urdf.robot.joints:
        for end in (j.parent, j.child):
            if end not in link_set:
                raise TolallocError(f"{source}: joint {j.name!r} refers to link {end!r}, which is not defined; "
                                    "expected every <parent>/<child> link to have a <link> element.")
        if j.child in parent_joint:
            raise TolallocError(f"{source}: link {j.child!r} is the child of joints {parent_joint[j.child].name!r} and "
                                f"{j.name!r}: the URDF has a closed loop; only serial chains (trees) can be imported.")
        parent_joint[j.child] = j
        children[j.parent].append(j)
    roots = [name for name in links if name not in parent_joint]
    if len(roots) != 1:
        what = "no root link (every link has a parent: a closed loop)" if not roots else f"several root links {roots}"
        raise TolallocError(f"{source}: the URDF has {what}; expected one tree with a single root link.")
    seen, stack = set(), [roots[0]]
    while stack:
        name = stack.pop()
        seen.add(name)
        stack.extend(j.child for j in children[name])
    if seen != link_set:
        raise TolallocError(f"{source}: links {sorted(link_set - seen)} are not reachable from the root link "
                            f"{roots[0]!r}: they form a closed loop; only serial chains (trees) can be imported.")
    return parent_joint, children, roots[0]


def _path(parent_joint, root, link):
    out = []
    while link != root:
        j = parent_joint[link]
        out.append(j)
        link = j.parent
    return out[::-1]


def _choose_tool(parent_joint, children, root, tool, source):
    if tool is not None:
        if tool not in children:
            raise TolallocError(f"{source}: the tool link {tool!r} (`tool`) is not a link of the URDF; links: "
                                f"{', '.join(children)}.")
        return tool
    leaves = [name for name, js in children.items() if not js]
    depth = {leaf: sum(j.type in MOVABLE for j in _path(parent_joint, root, leaf)) for leaf in leaves}
    best = max(depth.values())
    cands = [leaf for leaf in leaves if depth[leaf] == best]
    if len(cands) == 1:
        # a fixed frame (tool0, flange) branching off near the end of the longest chain, whose remaining
        # movable joints are a gripper's fingers: the tool is as likely the frame as the finger
        main = _path(parent_joint, root, cands[0])
        for leaf in leaves:
            side = _path(parent_joint, root, leaf)
            shared = next((k for k, (a, b) in enumerate(zip(main, side)) if a is not b), min(len(main), len(side)))
            at = sum(j.type in MOVABLE for j in main[:shared])
            if leaf != cands[0] and at >= 1 and best - at <= 2 and not any(j.type in MOVABLE for j in side[shared:]):
                cands = [cands[0], leaf]
                break
    if len(cands) == 1:
        _refuse_end_effector_joint(_path(parent_joint, root, cands[0]), source)
    if len(cands) > 1:
        paths = [[root] + [j.child for j in _path(parent_joint, root, c)] for c in cands]
        common = [names[0] for names in zip(*paths) if len(set(names)) == 1]
        raise TolallocError(f"{source}: the URDF branches at link {common[-1]!r}, so the tool link is ambiguous: leaf links "
                            f"{cands} end chains of {', '.join(str(depth[c]) for c in cands)} movable joints; choose "
                            f"the tool link with `tool` (e.g. {common[-1]} or {cands[0]}).")
    return cands[0]


def _refuse_end_effector_joint(path, source):
    """Refuse an automatic tool link whose last movable joint is named like a gripper's (z1: ``jointGripper``).

    A single-jaw gripper does not branch the tree, so the longest chain runs through its jaw joint and the jaw
    would be allocated as one more arm joint.
    """
    movable = [j for j in path if j.type in MOVABLE]
    last = movable[-1] if movable else None
    if last is None or len(movable) < 2 or not GRIPPER_WORDS.search(f"{last.name} {last.child}"):
        return
    raise TolallocError(f"{source}: the longest chain ends with joint {last.name!r} (child link {last.child!r}), "
                        "which is named like a gripper or hand joint, not an arm joint; choose the tool link with "
                        f"`tool` (e.g. {last.parent} for the arm without the gripper, or {last.child} if that joint "
                        "is meant to be part of the arm).")


def _check_units(urdf, path_joints, source):
    for j in urdf.robot.joints:
        dist = float(np.linalg.norm(j.origin[:3, 3])) if j.origin is not None else 0.0
        if not np.isfinite(dist):
            raise TolallocError(f"{source}: joint {j.name!r} has a non-finite <origin xyz>; expected finite numbers in metres.")
        if dist > MAX_ORIGIN_M:
            raise TolallocError(f"{source}: joint {j.name!r} has its origin {dist:g} m from its parent link; URDF lengths "
                                f"are metres and this does not look like metres (more than {MAX_ORIGIN_M:g} m). "
                                "Convert the file to metres (e.g. divide millimetre values by 1000).")
    reach = sum(float(np.linalg.norm(j.origin[:3, 3])) for j in path_joints if j.origin is not None)
    stroke = sum(float(j.limit.upper - j.limit.lower) for j in path_joints if j.type == "prismatic"
                 and j.limit is not None and j.limit.lower is not None and j.limit.upper is not None)
    if reach > MAX_REACH_M or stroke > MAX_REACH_M:
        raise TolallocError(f"{source}: the chain is {reach:g} m long with {stroke:g} m of prismatic stroke; URDF lengths "
                            f"are metres and more than {MAX_REACH_M:g} m does not look like metres. Convert the file to metres.")


def _joint(j, axis_base, source) -> Joint:
    if j.mimic is not None:
        raise TolallocError(f"{source}: joint {j.name!r} mimics joint {j.mimic.joint!r}; mimic joints on the tool chain "
                            "are not supported (each joint needs its own value): choose another tool link (`tool`) or remove <mimic>.")
    kind = "prismatic" if j.type == "prismatic" else "revolute"
    scale = 1000.0 if kind == "prismatic" else 1.0
    unit = "m" if kind == "prismatic" else "rad"
    lim = j.limit
    if j.type == "continuous":
        lower, upper = -CONTINUOUS_LIMIT_RAD, CONTINUOUS_LIMIT_RAD
    elif lim is None or lim.lower is None or lim.upper is None:
        lower, upper = -DEFAULT_LIMIT[kind], DEFAULT_LIMIT[kind]
    else:
        lower, upper = float(lim.lower) * scale, float(lim.upper) * scale
        if not (np.isfinite(lower) and np.isfinite(upper) and lower < upper):
            raise TolallocError(f"{source}: joint {j.name!r} has <limit lower={lim.lower} upper={lim.upper}> [{unit}]; "
                                "expected finite lower < upper (a joint that cannot move should be type=\"fixed\").")
    nominal = 0.0 if lower <= 0.0 <= upper else 0.5 * (lower + upper)
    return Joint(j.name, kind, axis_base, lower, upper, nominal)


def _home_frames(children, root, on_path):
    """Home transforms (all joints at zero) of every link, breadth-first from the root, and the number of
    tool-chain movable joints between the root and each link."""
    home = {root: np.eye(4)}
    body = {root: 0}
    queue = [root]
    while queue:
        name = queue.pop(0)
        for j in children[name]:
            origin = j.origin if j.origin is not None else np.eye(4)
            home[j.child] = home[name] @ origin
            body[j.child] = body[name] + (1 if j.name in on_path and j.type in MOVABLE else 0)
            queue.append(j.child)
    return home, body


def _masses(urdf, home, body) -> list:
    """Point masses [kg] at the centres of mass [mm, base frame at home] of the links with an <inertial>."""
    masses = []
    for lk in urdf.robot.links:
        inertial = lk.inertial
        if inertial is None or inertial.mass is None or float(inertial.mass) <= 0:
            continue
        origin = inertial.origin if inertial.origin is not None else np.eye(4)
        com = 1000.0 * (home[lk.name] @ origin)[:3, 3]
        masses.append(Mass(lk.name, int(body[lk.name]), float(inertial.mass), com))
    return masses


def load_urdf(path: str | Path, tool: str | None = None) -> Robot:
    """Import the serial chain from the root link to ``tool`` of a URDF file.

    Parameters
    ----------
    path : str or Path
        URDF file (metres, radians).
    tool : str, optional
        Name of the tool link; default: the leaf link that ends the longest chain of movable joints
        (refused, listing the candidates, if several leaves tie).

    Returns
    -------
    Robot
        Lengths in mm; the base frame is the URDF root link, the tool frame the tool link's frame;
        ``masses`` from the ``<inertial>`` elements (mm, kg).

    Raises
    ------
    TolallocError
        For a file that does not parse, a closed loop, an ambiguous tool, mimic / floating / planar
        joints on the chain, a movable joint without ``<axis>``, a zero or non-finite axis, bad limits,
        or lengths that do not look like metres; the message names the file and the joint or link.
    """
    path = Path(path)
    source = f"URDF file {str(path)!r}"
    if path.is_dir():
        raise TolallocError(f"{source}: is a directory; expected a URDF file.")
    if not path.is_file():
        raise TolallocError(f"{source}: no such file.")
    urdf, no_axis = _parse(path, source)
    parent_joint, children, root = _tree(urdf, source)
    tool = _choose_tool(parent_joint, children, root, tool, source)
    path_joints = _path(parent_joint, root, tool)
    for j in path_joints:
        if j.type in ("floating", "planar"):
            raise TolallocError(f"{source}: joint {j.name!r} is {j.type}; only revolute, continuous, prismatic and fixed "
                                "joints can be imported (a mobile base is not a serial arm): choose the arm's base as root.")
        if j.type not in MOVABLE + ("fixed",):
            raise TolallocError(f"{source}: joint {j.name!r} has type {j.type!r}; expected revolute, continuous, prismatic or fixed.")
    if not any(j.type in MOVABLE for j in path_joints):
        raise TolallocError(f"{source}: no movable joint between the root link {root!r} and the tool link {tool!r}; "
                            "choose another tool link (`tool`).")
    _check_units(urdf, path_joints, source)

    home, body = _home_frames(children, root, {j.name for j in path_joints})

    joint_names = {j.name for j in path_joints}
    chain = []
    for j in path_joints:
        vec_mm = 1000.0 * (home[j.child][:3, 3] - home[j.parent][:3, 3])
        if np.linalg.norm(vec_mm) > 1e-9:
            name = j.parent if j.parent not in joint_names else f"{j.parent}_link"
            chain.append(Link(name, vec_mm))
        if j.type in MOVABLE:
            if j.name in no_axis:
                raise TolallocError(f"{source}: joint {j.name!r} ({j.type}) has no <axis>; the URDF default (1, 0, 0) is not "
                                    "assumed: add <axis xyz=\"1 0 0\"/> to the joint if that axis is meant.")
            axis = np.asarray(j.axis, dtype=float)
            norm = float(np.linalg.norm(axis)) if axis.shape == (3,) else 0.0
            if not np.all(np.isfinite(axis)) or norm < 1e-9:
                raise TolallocError(f"{source}: joint {j.name!r} has axis {axis.tolist()}; expected a non-zero finite "
                                    "3-vector such as <axis xyz=\"0 0 1\"/>.")
            chain.append(_joint(j, home[j.child][:3, :3] @ (axis / norm), source))
    masses = _masses(urdf, home, body)
    name = urdf.robot.name or path.stem
    desc = (f"Imported from URDF {path.name} (robot {name!r}): base link {root!r}, tool link {tool!r}, "
            f"{sum(j.type in MOVABLE for j in path_joints)} joints; lengths converted from m to mm.")
    # URDF's unit rules (metres, _check_units) replace the guards of a chain built from objects
    return Robot(name, tuple(chain), tool_offset_mm=np.zeros(3), tool_rotation=home[tool][:3, :3].copy(),
                 masses=tuple(masses), description=desc, trust_units=True)

"""Serial-chain kinematics and gravity loads of the independent benchmark, written apart from tolalloc.

The robot files (tolalloc's TOML format: the chain layout or the standard / modified DH layout, see
docs/howto/own-robot.md) are parsed here with :mod:`tomllib` into a :class:`Chain`: the robot at its zero
configuration as a sequence of link vectors and joints (unit axis and the point it passes through, base frame),
grouped into bodies (body 0 = base, body j = everything after joint j up to joint j + 1). Forward kinematics is
the product of exponentials (Brockett 1984; Lynch & Park, *Modern Robotics*, 2017, ch. 4):
``T(q) = exp([S_1] q_1) ... exp([S_n] q_n) M``. Gravity torques are the static joint torques of point masses
(Craig, *Introduction to Robotics*, ch. 5). Units: mm, rad, kg, N, N m.

This module imports nothing of tolalloc (checked by tests/test_sim2real_independent.py).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

G = 9.80665  # standard gravity [m/s^2]
BUILTIN = Path(__file__).resolve().parents[3] / "tolalloc" / "data" / "robots"


@dataclass(frozen=True)
class Chain:
    """A serial robot at its zero configuration, base frame, mm.

    Attributes
    ----------
    name : str
    kinds : tuple of str, length n -- ``"R"`` or ``"P"``
    axes : array (n, 3) -- unit joint axes at home
    links : array (L, 3) -- link vectors at home [mm], in chain order
    link_names : tuple of str, length L
    link_body : array (L,) int -- body that carries each link (number of joints before it)
    tool : array (3,) -- tool offset after the last link [mm], base axes at home
    tool_rot : array (3, 3) -- tool orientation at home
    masses : array (B,) [kg]; mass_com : array (B, 3) [mm] at home; mass_body : array (B,) int
    mass_link : tuple of str -- the link each mass belongs to
    lower, upper : array (n,) -- joint limits [rad, mm]
    """

    name: str
    kinds: tuple
    axes: np.ndarray
    links: np.ndarray
    link_names: tuple
    link_body: np.ndarray
    tool: np.ndarray
    tool_rot: np.ndarray
    masses: np.ndarray
    mass_com: np.ndarray
    mass_body: np.ndarray
    mass_link: tuple
    lower: np.ndarray
    upper: np.ndarray
    q_offset: np.ndarray = None  # joint zero offset [rad, mm] added to the commanded q (geometric error)

    @property
    def n(self) -> int:
        return len(self.kinds)

    @property
    def revolute(self) -> np.ndarray:
        return np.array([k == "R" for k in self.kinds])

    def points(self, links=None) -> np.ndarray:
        """Joint axis points at home (n, 3) or (P, n, 3) from link vectors (L, 3) or (P, L, 3)."""
        links = self.links if links is None else links
        cum = np.cumsum(links, axis=-2)
        out = np.zeros(links.shape[:-2] + (self.n, 3))
        for j in range(self.n):
            before = np.flatnonzero(self.link_body < j + 1)
            if len(before):
                out[..., j, :] = cum[..., before[-1], :]
        return out

    def tool_home(self, links=None) -> np.ndarray:
        links = self.links if links is None else links
        return links.sum(axis=-2) + self.tool

    def with_links(self, links) -> "Chain":
        return replace(self, links=np.asarray(links, float))


# ----------------------------------------------------------------------------------------------- parsing
def _rot(axis, angle):
    """Rotation matrices exp([axis] angle) (Rodrigues), axis (..., 3) unit, angle (...,)."""
    axis = np.asarray(axis, float)
    angle = np.asarray(angle, float)
    k = np.zeros(np.broadcast_shapes(axis.shape[:-1], angle.shape) + (3, 3))
    a = np.broadcast_to(axis, k.shape[:-1])
    k[..., 0, 1], k[..., 0, 2], k[..., 1, 2] = -a[..., 2], a[..., 1], -a[..., 0]
    k[..., 1, 0], k[..., 2, 0], k[..., 2, 1] = a[..., 2], -a[..., 1], a[..., 0]
    s, c = np.sin(angle)[..., None, None], np.cos(angle)[..., None, None]
    return np.eye(3) + s * k + (1 - c) * (k @ k)


def _length(row, key):
    if f"{key}_mm" in row:
        return float(row[f"{key}_mm"])
    return 1000.0 * float(row.get(f"{key}_m", 0.0))


def _angle(row, key):
    if f"{key}_rad" in row:
        return float(row[f"{key}_rad"])
    return np.deg2rad(float(row.get(f"{key}_deg", 0.0)))


def _limits(row, prismatic):
    if prismatic:
        lim = row.get("limits_mm", [-1e4, 1e4])
        return float(lim[0]), float(lim[1])
    if "limits_rad" in row:
        return tuple(float(v) for v in row["limits_rad"])
    lim = row.get("limits_deg", [-360, 360])
    return np.deg2rad(lim[0]), np.deg2rad(lim[1])


def _rpy(tool):
    r = np.deg2rad(tool.get("rpy_deg", [0, 0, 0]))
    return _rot([0, 0, 1], r[2]) @ _rot([0, 1, 0], r[1]) @ _rot([1, 0, 0], r[0])


def _elements_from_dh(data):
    """DH rows -> chain elements at q = 0 (standard: Rz Tz Tx Rx; modified: Rx Tx Rz Tz)."""
    conv = data["convention"]
    T = np.eye(4)
    elements = []

    def move(vec, name):
        if abs(vec) > 0:
            axis = T[:3, 0] if name.startswith("a") else T[:3, 2]
            elements.append(("link", name, axis * vec))
            shift = np.eye(4)
            shift[:3, 3] = (np.array([1, 0, 0]) if name.startswith("a") else np.array([0, 0, 1])) * vec
            return T @ shift
        return T

    for i, row in enumerate(data["dh"], start=1):
        prismatic = row.get("type", "revolute") == "prismatic"
        d, a = _length(row, "d"), _length(row, "a")
        alpha, off = _angle(row, "alpha"), _angle(row, "theta_offset")
        if conv == "modified":
            T = T @ _homog(_rot([1, 0, 0], alpha))
            T = move(a, f"a{i - 1}")
        elements.append(("joint", row.get("name", f"j{i}"), T[:3, 2].copy(), "P" if prismatic else "R",
                         _limits(row, prismatic)))
        T = T @ _homog(_rot([0, 0, 1], off))
        T = move(d, f"d{i}_offset" if prismatic else f"d{i}")
        if conv == "standard":
            T = move(a, f"a{i}")
            T = T @ _homog(_rot([1, 0, 0], alpha))
    tool = data.get("tool", {})
    elements.append(("tool", T[:3, :3] @ np.asarray(tool.get("offset_mm", [0, 0, 0]), float),
                     T[:3, :3] @ _rpy(tool)))
    return elements


def _homog(R):
    T = np.eye(4)
    T[:3, :3] = R
    return T


def _elements_from_chain(data):
    elements = []
    for item in data["chain"]:
        if "link" in item:
            vec = np.asarray(item["vector_mm"], float) if "vector_mm" in item else 1000.0 * np.asarray(item["vector_m"])
            elements.append(("link", item["link"], vec))
        else:
            prismatic = item.get("type", "revolute") == "prismatic"
            ax = np.asarray(item["axis"], float)
            elements.append(("joint", item["joint"], ax / np.linalg.norm(ax), "P" if prismatic else "R",
                             _limits(item, prismatic)))
    tool = data.get("tool", {})
    elements.append(("tool", np.asarray(tool.get("offset_mm", [0, 0, 0]), float), _rpy(tool)))
    return elements


def load_chain(robot) -> Chain:
    """Parse a robot file (built-in name or path to a .toml file) into a :class:`Chain`."""
    path = Path(robot)
    if path.suffix != ".toml":
        path = BUILTIN / f"{robot}.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    elements = _elements_from_dh(data) if "dh" in data else _elements_from_chain(data)
    kinds, axes, links, names, body, lower, upper = [], [], [], [], [], [], []
    tool, tool_rot = np.zeros(3), np.eye(3)
    for e in elements:
        if e[0] == "joint":
            axes.append(e[2])
            kinds.append(e[3])
            lower.append(e[4][0])
            upper.append(e[4][1])
        elif e[0] == "link":
            names.append(e[1])
            links.append(e[2])
            body.append(len(kinds))
        else:
            tool, tool_rot = e[1], e[2]
    masses = data.get("masses", [])
    mass_body = [body[names.index(m["link"])] for m in masses]
    n = len(kinds)
    return Chain(name=data["name"], kinds=tuple(kinds), axes=np.array(axes), links=np.array(links),
                 link_names=tuple(names), link_body=np.array(body), tool=tool, tool_rot=tool_rot,
                 masses=np.array([m["mass_kg"] for m in masses], float),
                 mass_com=np.array([m["com_mm"] for m in masses], float).reshape(-1, 3),
                 mass_body=np.array(mass_body, int), mass_link=tuple(m["link"] for m in masses),
                 lower=np.array(lower), upper=np.array(upper), q_offset=np.zeros(n))


# ------------------------------------------------------------------------------------------ kinematics
def body_transforms(chain: Chain, q, links=None, points=None):
    """Rigid motions of the bodies from home: R (P, n+1, 3, 3), t (P, n+1, 3); body b maps x -> R x + t.

    ``q`` (P, n) [rad, mm] are commanded joint values (``chain.q_offset`` is added); ``links`` optional (P, L, 3)
    or (L, 3) link vectors (e.g. thermally expanded); ``points`` optional (n, 3) joint axis points at home that
    replace those of the link vectors.
    """
    q = np.atleast_2d(np.asarray(q, float)) + chain.q_offset
    P = q.shape[0]
    pts = np.broadcast_to(chain.points(links) if points is None else points, (P, chain.n, 3))
    R = np.zeros((P, chain.n + 1, 3, 3))
    t = np.zeros((P, chain.n + 1, 3))
    R[:, 0] = np.eye(3)
    for j in range(chain.n):
        if chain.kinds[j] == "R":
            Rj = _rot(chain.axes[j], q[:, j])
            tj = pts[:, j] - np.einsum("pij,pj->pi", Rj, pts[:, j])
        else:
            Rj = np.broadcast_to(np.eye(3), (P, 3, 3))
            tj = chain.axes[j] * q[:, j:j + 1]
        R[:, j + 1] = R[:, j] @ Rj
        t[:, j + 1] = np.einsum("pij,pj->pi", R[:, j], tj) + t[:, j]
    return R, t


def flange(chain: Chain, q, links=None, points=None):
    """Tool point (P, 3) [mm] and tool orientation (P, 3, 3) at commanded ``q`` (P, n)."""
    R, t = body_transforms(chain, q, links, points)
    p = np.einsum("pij,pj->pi", R[:, -1], np.broadcast_to(chain.tool_home(links), t[:, -1].shape)) + t[:, -1]
    return p, R[:, -1] @ chain.tool_rot


def target(chain: Chain, q, probe_mm, links=None, points=None):
    """Position (P, 3) [mm] of a target at ``probe_mm`` (3,) in the tool frame."""
    p, Rt = flange(chain, q, links, points)
    return p + Rt @ np.asarray(probe_mm, float)


def joint_frames(chain: Chain, q):
    """Current joint axes (P, n, 3) and axis points (P, n, 3) at ``q`` (P, n)."""
    R, t = body_transforms(chain, q)
    pts = chain.points()
    w = np.einsum("pjab,jb->pja", R[:, :-1], chain.axes)
    c = np.einsum("pjab,jb->pja", R[:, :-1], pts) + t[:, :-1]
    return w, c


def position_jacobian(chain: Chain, q, points):
    """d(point)/dq_j (P, 3, n) of points (P, 3) riding on the last body [mm/rad, mm/mm]."""
    w, c = joint_frames(chain, q)
    J = np.where(chain.revolute[None, :, None], np.cross(w, points[:, None, :] - c), w)
    return np.swapaxes(J, 1, 2)


def mass_positions(chain: Chain, q, masses=None, com=None, body=None):
    """Centres of mass (P, B, 3) [mm] at ``q`` of point masses on bodies ``body`` (home positions ``com``)."""
    com = chain.mass_com if com is None else com
    body = chain.mass_body if body is None else body
    R, t = body_transforms(chain, q)
    return np.einsum("pbij,bj->pbi", R[:, body], com) + t[:, body]


def gravity_loads(chain: Chain, q, masses, com_now, body, gravity=(0, 0, -1)):
    """Static joint loads (P, n) that point masses put on the joints [N m revolute, N prismatic].

    masses : (P, B) or (B,) [kg]; com_now : (P, B, 3) [mm] current positions; body : (B,) int body of each mass
    (a mass on body b loads joints 1..b). Positive: the load turns / pushes the joint along +axis.
    """
    P = com_now.shape[0]
    F = np.broadcast_to(np.asarray(masses, float), com_now.shape[:2])[..., None] * G * np.asarray(gravity, float)
    w, c = joint_frames(chain, q)
    out = np.zeros((P, chain.n))
    for j in range(chain.n):
        on = body >= j + 1
        if not on.any():
            continue
        Fj = F[:, on]
        if chain.kinds[j] == "R":
            m = np.cross((com_now[:, on] - c[:, j, None]) / 1000.0, Fj).sum(axis=1)
            out[:, j] = np.einsum("pi,pi->p", m, w[:, j])
        else:
            out[:, j] = np.einsum("pi,pi->p", Fj.sum(axis=1), w[:, j])
    return out

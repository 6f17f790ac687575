"""The elements of a serial chain at its zero configuration: links, joints, point masses; DH rows to a chain."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.robot.lie import rot_x, rot_z

__all__ = ["Link", "Joint", "Mass", "REVOLUTE", "PRISMATIC", "chain_from_dh"]

REVOLUTE = "revolute"
PRISMATIC = "prismatic"


@dataclass(frozen=True, eq=False)
class Link:
    """A fixed translation of the chain at the zero configuration.

    Attributes
    ----------
    name : str
        Length-parameter name (``l1`` ...).
    vector_mm : array, shape (3,)
        Translation in the base frame at home [mm].
    """

    name: str
    vector_mm: np.ndarray

    @property
    def length_mm(self) -> float:
        """Nominal length [mm]."""
        return float(np.linalg.norm(self.vector_mm))

    @property
    def direction(self) -> np.ndarray:
        """Unit direction of the link (zero vector for a zero-length link), shape (3,)."""
        n = self.length_mm
        return self.vector_mm / n if n > 0 else np.zeros(3)


@dataclass(frozen=True, eq=False)
class Joint:
    """A one-degree-of-freedom joint, in the library's internal units.

    ``Joint(name, kind, axis, lower, upper, nominal)`` takes its limits and nominal value in **rad** for a
    revolute joint and mm for a prismatic one; :meth:`from_interface` takes them in deg / mm, like the robot
    files. A :class:`~tolalloc.robot.model.Robot` refuses revolute limits beyond two turns or a nominal value
    beyond one turn each way (degrees given for radians) unless built with ``trust_units=True``. Degrees that also
    read as radians within those bounds (``lower=-10, upper=10`` meant as deg is a +-10 rad joint, a valid multi-turn
    range) cannot be told apart and pass: give degree values through :meth:`from_interface`.

    Attributes
    ----------
    name : str
    kind : {"revolute", "prismatic"}
    axis : array, shape (3,)
        Unit axis in the base frame at home.
    lower, upper : float
        Joint limits [rad or mm].
    nominal : float
        Nominal joint value [rad or mm].

    Examples
    --------
    >>> import numpy as np
    >>> from tolalloc import Joint
    >>> j = Joint.from_interface("shoulder", "revolute", np.array([0.0, 1.0, 0.0]), -90, 90, 20)
    >>> round(j.upper, 6), round(j.nominal, 6)      # stored in rad
    (1.570796, 0.349066)
    """

    name: str
    kind: str
    axis: np.ndarray
    lower: float = -np.pi
    upper: float = np.pi
    nominal: float = 0.0

    @classmethod
    def from_interface(cls, name: str, kind: str, axis, lower_deg_mm: float, upper_deg_mm: float,
                       nominal_deg_mm: float = 0.0) -> "Joint":
        """A joint from limits and nominal value in interface units: deg for a revolute joint, mm for a
        prismatic one (converted to rad / mm)."""
        f = (np.pi / 180.0) if kind == REVOLUTE else 1.0
        try:
            vals = [float(v) * f for v in (lower_deg_mm, upper_deg_mm, nominal_deg_mm)]
        except (TypeError, ValueError):
            vals = [lower_deg_mm, upper_deg_mm, nominal_deg_mm]  # refused with the robot's message
        return cls(name, kind, axis, *vals)

    @property
    def is_revolute(self) -> bool:
        return self.kind == REVOLUTE

    @property
    def unit(self) -> str:
        """Interface unit of the joint value: ``deg`` or ``mm``."""
        return "deg" if self.is_revolute else "mm"


@dataclass(frozen=True, eq=False)
class Mass:
    """A point mass carried by the chain (used by the gravity models of the diagnosis).

    Attributes
    ----------
    name : str
        Label (usually the link it belongs to).
    body : int
        Number of joints between the base and the mass (0 = fixed to the base,
        ``n`` = moves with the last joint).
    mass_kg : float
    com_mm : array, shape (3,)
        Centre of mass in the base frame at home [mm].
    """

    name: str
    body: int
    mass_kg: float
    com_mm: np.ndarray


def chain_from_dh(rows: list[dict], convention: str):
    """Build chain elements and the final frame rotation from DH rows in internal units.

    Parameters
    ----------
    rows : list of dict
        Keys ``name``, ``type`` (``revolute`` / ``prismatic``), ``d``, ``a`` [mm],
        ``alpha``, ``theta_offset`` [rad], ``lower``, ``upper``, ``nominal``.
    convention : {"standard", "modified"}

    Returns
    -------
    chain : list of Link and Joint
    R_tool : array, shape (3, 3)
        Orientation of the last DH frame at the zero configuration.
    """
    R = np.eye(3)
    chain = []
    for i, r in enumerate(rows, start=1):
        if convention == "modified":
            R = R @ rot_x(r["alpha"])
            if r["a"] != 0:
                chain.append(Link(f"a{i - 1}", r["a"] * R[:, 0]))
            R = R @ rot_z(r["theta_offset"])
            axis = R[:, 2].copy()
            chain.append(Joint(r["name"], r["type"], axis, r["lower"], r["upper"], r["nominal"]))
            if r["d"] != 0:
                chain.append(Link(f"d{i}_offset" if r["type"] == "prismatic" else f"d{i}", r["d"] * R[:, 2]))
        else:
            axis = R[:, 2].copy()
            chain.append(Joint(r["name"], r["type"], axis, r["lower"], r["upper"], r["nominal"]))
            if r["d"] != 0:
                chain.append(Link(f"d{i}_offset" if r["type"] == "prismatic" else f"d{i}", r["d"] * R[:, 2]))
            R = R @ rot_z(r["theta_offset"])
            if r["a"] != 0:
                chain.append(Link(f"a{i}", r["a"] * R[:, 0]))
            R = R @ rot_x(r["alpha"])
    return chain, R

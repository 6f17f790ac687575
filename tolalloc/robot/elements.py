"""The elements of a serial chain at its zero configuration: links, joints, point masses; DH rows to a chain."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import TolallocError, describe, whole_number
from tolalloc.robot.lie import rot_x, rot_z

__all__ = ["Link", "Joint", "Mass", "REVOLUTE", "PRISMATIC", "chain_from_dh"]

REVOLUTE = "revolute"
PRISMATIC = "prismatic"


def _name(value, what: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise TolallocError(f"{what} name: expected a non-empty string, got {describe(value)}.")
    return value


def _vector(value, who: str, what: str, *, unit: bool = False) -> np.ndarray:
    """A finite 3-vector (a float copy); ``unit``: of norm 1 within 1e-6."""
    try:
        v = np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        v = None
    if v is None or v.shape != (3,) or not np.all(np.isfinite(v)) or (unit and abs(np.linalg.norm(v) - 1) > 1e-6):
        kind = "a finite unit 3-vector" if unit else "a finite 3-vector"
        shown = v.tolist() if v is not None and v.size <= 6 else describe(value)
        raise TolallocError(f"{who}: {what} {shown} is not {kind}; expected e.g. [0, 0, 1]"
                            + (" (norm 1 within 1e-6)." if unit else " [mm]."))
    return v


def _number(value, who: str, what: str, *, finite: bool = True) -> float:
    """A real number (not a bool or a string); ``finite``: not +-inf either (NaN never); ``what`` is what the message
    says was expected."""
    x = float("nan")
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_)):
        try:
            x = float(value)
        except OverflowError:  # an int beyond the float range
            x = float("nan")
    if np.isnan(x) or (finite and np.isinf(x)):
        raise TolallocError(f"{who}: expected {what}, got {describe(value)}.")
    return x


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

    def __post_init__(self):
        _name(self.name, "link")
        object.__setattr__(self, "vector_mm", _vector(self.vector_mm, f"link {self.name}", "vector"))

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

    def __post_init__(self):
        who = f"joint {_name(self.name, 'joint')}"
        if not isinstance(self.kind, str) or self.kind not in (REVOLUTE, PRISMATIC):
            raise TolallocError(f"{who}: kind {describe(self.kind)}; expected 'revolute' or 'prismatic'.")
        axis = _vector(self.axis, who, "axis", unit=True)
        unit = "rad" if self.kind == REVOLUTE else "mm"
        lo = _number(self.lower, who, f"a number as the lower limit [{unit}] (-inf for none)", finite=False)
        hi = _number(self.upper, who, f"a number as the upper limit [{unit}] (inf for none)", finite=False)
        nominal = _number(self.nominal, who, f"a finite nominal value inside the limits [{unit}]")
        if not lo < hi:
            raise TolallocError(f"{who}: limits [{lo:g}, {hi:g}] {unit}; expected lower < upper.")
        if not lo <= nominal <= hi:
            raise TolallocError(f"{who}: nominal value {nominal:g} outside its limits [{lo:g}, {hi:g}] {unit}; "
                                "expected a value inside the limits.")
        for field, value in (("axis", axis), ("lower", lo), ("upper", hi), ("nominal", nominal)):
            object.__setattr__(self, field, value)

    @classmethod
    def from_interface(cls, name: str, kind: str, axis, lower_deg_mm: float, upper_deg_mm: float,
                       nominal_deg_mm: float = 0.0) -> "Joint":
        """A joint from limits and nominal value in interface units: deg for a revolute joint, mm for a
        prismatic one (converted to rad / mm)."""
        revolute = isinstance(kind, str) and kind == REVOLUTE
        f = (np.pi / 180.0) if revolute else 1.0
        who, unit = f"joint {describe(name)}", "deg" if revolute else "mm"
        vals = [_number(v, who, f"{what} [{unit}]", finite=what.startswith("a finite")) * f
                for v, what in ((lower_deg_mm, "a number as the lower limit"), (upper_deg_mm, "a number as the upper "
                                "limit"), (nominal_deg_mm, "a finite nominal value inside the limits"))]
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

    def __post_init__(self):
        who = f"mass {_name(self.name, 'mass')}"
        body = whole_number(self.body)
        if body is None or body < 0:
            raise TolallocError(f"{who}: body {describe(self.body)}; expected the number of joints between the base "
                                "and the mass, a whole number >= 0.")
        kg = _number(self.mass_kg, who, "a finite mass >= 0 [kg]")
        if kg < 0:
            raise TolallocError(f"{who}: mass {kg:g} kg; expected a mass >= 0 [kg].")
        object.__setattr__(self, "body", body)
        object.__setattr__(self, "mass_kg", kg)
        object.__setattr__(self, "com_mm", _vector(self.com_mm, who, "centre of mass"))


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

"""Serial-chain robot model and product-of-exponentials (POE) kinematics.

A robot is described at its zero configuration as an ordered chain of

* :class:`Link` -- a fixed translation (a named length parameter, so that a
  link-length tolerance has a name and a direction), and
* :class:`Joint` -- a revolute or prismatic joint with a unit axis in the base
  frame,

followed by a tool frame. From it follow the space-frame screw axes ``S``
(one per row, ``(omega, v)``), the joint points and the home pose ``M``; the
forward kinematics is ``T(q) = exp([S1] q1) ... exp([Sn] qn) M``.

Units inside the library: lengths in mm, angles in rad. Joint values at the
interface (files, CLI) are in degrees (revolute) and mm (prismatic); use
:meth:`Robot.q_from_interface` / :meth:`Robot.q_to_interface` to convert.

This module holds :class:`Robot`; its elements are in :mod:`tolalloc.robot.elements`, its checks at construction
(reserved set names included) in :mod:`tolalloc.robot.checks`, DH rows in :mod:`tolalloc.robot.dh_rows`.
"""

from __future__ import annotations

from dataclasses import InitVar, dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, check_finite_array, describe, known_names
from tolalloc.units import check_joint_units, trusting_units, units_trusted
from tolalloc.robot.checks import check_chain, check_fields, check_named_sets, check_reserved_names, joint_array
from tolalloc.robot.components import Components
from tolalloc.robot.elements import PRISMATIC, REVOLUTE, Joint, Link, Mass, chain_from_dh
from tolalloc.robot.kinematics import body_jacobian, fk_poe, space_jacobian

__all__ = ["Link", "Joint", "Mass", "Robot"]


@dataclass(frozen=True, eq=False)
class Robot:
    """A serial robot; derived quantities are computed once at construction.

    Attributes
    ----------
    name : str
    chain : tuple of Link and Joint
        Elements in order from the base, at the zero configuration.
    tool_offset_mm : array, shape (3,)
        Tool point relative to the end of the last link, base axes [mm].
    tool_rotation : array, shape (3, 3)
        Tool frame orientation at home.
    masses : tuple of Mass
    gravity : array, shape (3,)
        Unit gravity direction in the base frame.
    pose_sets : dict of str -> array, shape (P, n)
        Named sets of working poses [rad, mm].
    description : str
    regions : dict of str -> (array, array)
        Named boxes of the working region, ``{name: (q_min (n,), q_max (n,))}`` [rad, mm].
    sigma_sets : dict of str -> dict
        Named error-sigma sets as written in the robot file (read by :mod:`tolalloc.errormodel.model`).
    components : Components
        The bought parts of each joint, the links' sections, the mount and the payload
        (:mod:`tolalloc.robot.components`; empty when the robot file has no ``[components]`` section).
    trust_units : bool
        Construction only (not stored): accept a chain whose values look like a unit slip. By default a chain
        built from ``Link`` / ``Joint`` objects is refused, with a hint, when its link lengths look like metres
        or a revolute joint's limits go beyond two turns or its nominal value beyond one turn each way (degrees
        given for radians; :func:`tolalloc.units.check_chain_units`), the rules of the robot files.
    joints, links : tuples of Joint, Link
        Derived (read-only): the chain's joints and links.
    screws : array, shape (n, 6)
        Derived (read-only): space screw axes ``(omega, v)``.
    joint_points_mm : array, shape (n, 3)
        Derived (read-only): a point on each joint axis at home [mm].
    home : array, shape (4, 4)
        Derived (read-only): the home pose ``M``.
    link_sites : array of int, shape (L,)
        Derived (read-only): joints preceding each link.
    """

    name: str
    chain: tuple
    tool_offset_mm: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tool_rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    masses: tuple = ()
    gravity: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, -1.0]))
    pose_sets: dict = field(default_factory=dict)
    description: str = ""
    sigma_sets: dict = field(default_factory=dict)
    regions: dict = field(default_factory=dict)
    components: Components = field(default_factory=Components)
    trust_units: InitVar[bool] = False

    def __post_init__(self, trust_units: bool = False):
        chain, masses, gravity = check_fields(self.name, self.chain, self.description, self.masses, self.gravity,
                                              {f: getattr(self, f) for f in ("pose_sets", "regions", "sigma_sets")})
        for name, value in (("chain", chain), ("masses", masses), ("gravity", gravity)):
            object.__setattr__(self, name, value)
        if not isinstance(self.components, Components):
            raise TolallocError(f"robot {self.name!r}: components expected a tolalloc.robot.components.Components "
                                f"(the robot file's [components] section), got {describe(self.components)}.")
        joints = tuple(e for e in self.chain if isinstance(e, Joint))
        links = tuple(e for e in self.chain if isinstance(e, Link))
        if not joints:
            raise TolallocError(f"robot {self.name!r}: the chain has no joint; expected at least one.")
        names = [e.name for e in self.chain]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise TolallocError(f"robot {self.name!r}: duplicate element names {dup}; every link and joint needs its own name.")
        if not isinstance(trust_units, (bool, np.bool_)):
            raise TolallocError(f"robot {self.name!r}: trust_units expected True or False, got {describe(trust_units)}.")
        check_chain(self.chain, self.tool_offset_mm, self.tool_rotation, f"robot {self.name!r}",
                    units=not (trust_units or units_trusted()))
        check_reserved_names(f"robot {self.name!r}", pose_sets=self.pose_sets, regions=self.regions,
                             sigma_sets=self.sigma_sets)
        point = np.zeros(3)
        screws, points, sites = [], [], []
        for e in self.chain:
            if isinstance(e, Link):
                sites.append(len(points))
                point = point + e.vector_mm
            else:
                w = np.asarray(e.axis, dtype=float)
                if w.shape != (3,) or not np.all(np.isfinite(w)) or abs(np.linalg.norm(w) - 1.0) > 1e-6:
                    raise TolallocError(f"robot {self.name!r}, joint {e.name}: axis {w.tolist()} is not a finite unit "
                                        "3-vector; expected e.g. [0, 0, 1] (norm 1 within 1e-6).")
                if e.kind not in (REVOLUTE, PRISMATIC):
                    raise TolallocError(f"robot {self.name!r}, joint {e.name}: kind {e.kind!r}; expected 'revolute' or 'prismatic'.")
                if e.kind == REVOLUTE:
                    screws.append(np.concatenate([w, -np.cross(w, point)]))
                else:
                    screws.append(np.concatenate([np.zeros(3), w]))
                points.append(point.copy())
        M = np.eye(4)
        M[:3, :3] = self.tool_rotation
        M[:3, 3] = point + self.tool_offset_mm
        object.__setattr__(self, "joints", joints)
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "screws", np.array(screws))
        object.__setattr__(self, "joint_points_mm", np.array(points))
        object.__setattr__(self, "home", M)
        object.__setattr__(self, "link_sites", np.array(sites, dtype=int))
        for arr in (self.screws, self.joint_points_mm, self.home, self.link_sites):
            arr.flags.writeable = False
        check_named_sets(self)

    def random_q(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` joint configurations drawn uniformly within the joint limits [rad, mm], shape (n, n_joints).

        Internal units, as ``fk_internal`` takes them; ``fk`` takes deg / mm: ``robot.fk(robot.q_to_interface(q))``.

        Revolute joints are drawn within their limits intersected with [-pi, pi] (a joint that may turn
        more than once reaches no other pose beyond); prismatic joints over their whole stroke (an
        unbounded stroke: +-1000 mm).
        """
        from tolalloc.exceptions import ArgumentError, check_memory, describe, whole_number

        if not isinstance(rng, np.random.Generator):
            raise ArgumentError("rng", f"expected a numpy Generator (numpy.random.default_rng(seed)), got "
                                f"{describe(rng)}.")
        if whole_number(n) is None or whole_number(n) < 0:
            raise ArgumentError("n", f"expected a whole number of poses >= 0 (e.g. 1000), got {describe(n)}.")
        n = check_memory(whole_number(n), 8.0 * self.n_joints, "n", "poses", "1000")
        rev = self.revolute_mask
        lo = np.where(rev, np.maximum(self.lower, -np.pi), np.where(np.isfinite(self.lower), self.lower, -1000.0))
        hi = np.where(rev, np.minimum(self.upper, np.pi), np.where(np.isfinite(self.upper), self.upper, 1000.0))
        return rng.uniform(lo, hi, (int(n), self.n_joints))

    # ------------------------------------------------------------------ joints
    @property
    def n_joints(self) -> int:
        return len(self.joints)

    @property
    def q_nominal(self) -> np.ndarray:
        """Nominal joint values, internal units [rad, mm], shape (n,); in deg / mm (``fk``'s units):
        ``robot.q_to_interface(robot.q_nominal)``."""
        return np.array([j.nominal for j in self.joints])

    @property
    def lower(self) -> np.ndarray:
        """Lower joint limits, internal units [rad, mm], shape (n,); in deg / mm:
        ``robot.q_to_interface(robot.lower)``."""
        return np.array([j.lower for j in self.joints])

    @property
    def upper(self) -> np.ndarray:
        """Upper joint limits, internal units [rad, mm], shape (n,); in deg / mm:
        ``robot.q_to_interface(robot.upper)``."""
        return np.array([j.upper for j in self.joints])

    @property
    def revolute_mask(self) -> np.ndarray:
        """True for revolute joints, shape (n,)."""
        return np.array([j.is_revolute for j in self.joints])

    def q_from_interface(self, q_deg_mm) -> np.ndarray:
        """Convert joint values from interface units (deg / mm) to internal (rad / mm), shape (..., n).

        Numbers with one value per joint in the last axis; +-inf (an open limit) is converted, NaN refused.
        """
        q = self.joint_array(q_deg_mm, "q_deg_mm", units="deg / mm", finite=False)
        return np.where(self.revolute_mask, np.deg2rad(q), q)

    def q_to_interface(self, q) -> np.ndarray:
        """Convert joint values from internal (rad / mm) to interface units (deg / mm), shape (..., n).

        Revolute joints rad -> deg, prismatic ones left in mm (``numpy.degrees`` would scale those too); +-inf (an
        open limit) is converted, NaN refused.
        """
        q = self.joint_array(q, "q", units="rad / mm", finite=False)
        return np.where(self.revolute_mask, np.rad2deg(q), q)

    def joint_array(self, q, name: str = "q", *, units: str = "rad / mm", finite: bool = True) -> np.ndarray:
        """``q`` as a float array of shape (..., n): numbers (no bools or strings), one per joint in the last axis,
        no NaN (and, with ``finite``, no +-inf); refused by ``name`` with what was expected. No limits checked
        (:meth:`check_q` does)."""
        return joint_array(q, self.n_joints, self.name, name, units, finite)

    def check_q(self, q, name: str = "joint values", *, interface: bool = False) -> np.ndarray:
        """Validate joint values (shape (n,) or (P, n)) against count, finiteness and limits.

        Parameters
        ----------
        q : array-like, shape (n,) or (P, n)
            Internal units [rad, mm], or interface units [deg, mm] if ``interface``.

        Returns
        -------
        q : array, internal units [rad, mm], same shape.
        """
        if not isinstance(name, str) or not isinstance(interface, (bool, np.bool_)):
            bad, what = ("name", "a string naming the values in messages") if not isinstance(name, str) else \
                ("interface", "True (deg / mm) or False (rad / mm)")
            raise TolallocError(f"{bad}: expected {what}, got {describe(name if bad == 'name' else interface)}.")
        n = self.n_joints
        units = ", ".join(j.unit if interface else "rad" if j.is_revolute else "mm" for j in self.joints)
        arr = np.atleast_1d(np.asarray(q, dtype=object))
        if arr.shape[-1] != n or arr.ndim > 2 or arr.size == 0:
            raise TolallocError(
                f"{name}: robot {self.name!r} has {n} joints ({', '.join(j.name for j in self.joints)}); "
                f"expected {n} values ({units}), got {arr.shape[-1] if arr.size else 'none'}."
            )
        try:
            arr = arr.astype(float)
        except (TypeError, ValueError, OverflowError):
            raise TolallocError(f"{name}: expected numbers ({units}), got {describe(q, 200)}.") from None
        q = check_finite_array(arr, name)
        if interface:
            check_joint_units(q, self.revolute_mask, self.q_to_interface(self.lower), self.q_to_interface(self.upper),
                              name)
        qi = self.q_from_interface(q) if interface else q
        lo, hi = self.lower, self.upper
        bad = (qi < lo - 1e-12) | (qi > hi + 1e-12)
        if np.any(bad):
            idx = tuple(np.argwhere(bad)[0])
            k = int(idx[-1])
            j = self.joints[k]
            val = self.q_to_interface(qi)[idx]
            where = f" (pose {idx[0] + 1})" if qi.ndim == 2 else ""
            lim = self.q_to_interface(np.array([lo, hi]))[:, k]
            raise TolallocError(
                f"{name}{where}: joint {j.name} = {val:g} {j.unit} is outside its limits "
                f"[{lim[0]:g}, {lim[1]:g}] {j.unit}; give a value inside the limits or widen them in the robot file."
            )
        return qi

    def poses(self, pose_set: str | None = None) -> np.ndarray:
        """Joint values of a named pose set, internal units [rad, mm], shape (P, n); the nominal pose if ``None``.

        The set ``nominal`` always exists. ``fk`` and the ``q_deg_mm`` arguments take deg / mm:
        ``robot.fk(robot.q_to_interface(robot.poses("working")))`` (``numpy.degrees`` would also scale a
        prismatic joint's mm); or pass the set by name (``poses="working"``).
        """
        if pose_set is None or (isinstance(pose_set, str) and pose_set == "nominal"):
            return self.q_nominal[None, :]
        if not isinstance(pose_set, str) or pose_set not in self.pose_sets:
            known = known_names(["nominal"], self.pose_sets)
            what = repr(pose_set) if isinstance(pose_set, str) else describe(pose_set)
            raise TolallocError(f"pose set {what} is not defined for robot {self.name!r}; known sets: {known}.")
        return np.array(self.pose_sets[pose_set])

    # -------------------------------------------------------------- construction
    @classmethod
    def from_dh(cls, table, *, convention: str, name: str = "dh_robot", tool_offset_mm=(0.0, 0.0, 0.0),
                tool_rpy_deg=(0.0, 0.0, 0.0), description: str = "", trust_units: bool = False) -> "Robot":
        """A robot from a Denavit-Hartenberg table (standard or modified convention).

        Parameters
        ----------
        table : DataFrame or list of dict
            One row per joint with the columns of a DH CSV table: ``name``, ``type`` (optional: revolute or
            prismatic), ``d_mm`` | ``d_m``, ``a_mm`` | ``a_m``, ``alpha_deg`` | ``alpha_rad``, and optionally
            ``theta_offset_deg`` | ``theta_offset_rad``, ``lower_deg_mm``, ``upper_deg_mm``, ``nominal_deg_mm``.
        convention : {"standard", "modified"}
        name, description : str
        tool_offset_mm : array-like, shape (3,)
            Tool point in the last DH frame [mm].
        tool_rpy_deg : array-like, shape (3,)
            Tool orientation in the last DH frame, X-Y-Z fixed angles [deg].
        trust_units : bool
            Accept values that look like a unit slip (a length under ``_m`` above 20 m, an angle beyond one turn,
            a robot under 10 mm long; :mod:`tolalloc.units`).

        Examples
        --------
        >>> import tolalloc
        >>> rows = [{"name": "shoulder", "d_mm": 400, "a_mm": 0, "alpha_deg": 90},
        ...         {"name": "elbow", "d_mm": 0, "a_mm": 600, "alpha_deg": 0}]
        >>> arm = tolalloc.Robot.from_dh(rows, convention="standard", name="two_link")
        >>> arm.fk([0, 0])[:3, 3]
        array([600.,   0., 400.])
        """
        if not isinstance(trust_units, (bool, np.bool_)):
            raise TolallocError(f"trust_units: expected True or False, got {describe(trust_units)}.")
        with trusting_units(bool(trust_units) or units_trusted()):
            return cls._from_dh(table, convention, name, tool_offset_mm, tool_rpy_deg, description)

    @classmethod
    def _from_dh(cls, table, convention, name, tool_offset_mm, tool_rpy_deg, description) -> "Robot":
        from tolalloc.robot.dh_rows import rows_from_table
        from tolalloc.robot.lie import exp_so3
        from tolalloc.units import check_reach

        if not isinstance(convention, str) or convention not in ("standard", "modified"):
            raise TolallocError(f"convention: expected 'standard' or 'modified', got {describe(convention)}.")
        rows = rows_from_table(table)
        chain, R_last = chain_from_dh(rows, convention)
        off = check_finite_array(tool_offset_mm, "tool_offset_mm", (3,))
        rpy = np.deg2rad(check_finite_array(tool_rpy_deg, "tool_rpy_deg", (3,)))
        R_tool = exp_so3([0, 0, rpy[2]]) @ exp_so3([0, rpy[1], 0]) @ exp_so3([rpy[0], 0, 0])
        check_reach({e.name: e.length_mm for e in chain if isinstance(e, Link)}, "lengths", tiny_links=False)
        # the DH rules above (unit keys, reach) replace the guards of a chain built from objects
        return cls(name, tuple(chain), tool_offset_mm=R_last @ off, tool_rotation=R_last @ R_tool,
                   description=description, trust_units=True)

    # -------------------------------------------------------------- kinematics
    def fk(self, q_deg_mm) -> np.ndarray:
        """End-effector pose ``T(q)`` at joint values in interface units.

        Parameters
        ----------
        q_deg_mm : array-like, shape (n,) or (P, n)
            Joint values [deg for revolute, mm for prismatic joints], inside the joint limits. From internal
            units (``poses``, ``q_nominal``, ``random_q``): ``robot.fk(robot.q_to_interface(q))``.

        Returns
        -------
        array, shape (4, 4) or (P, 4, 4)
            Homogeneous transform, position in mm.

        Examples
        --------
        >>> import tolalloc
        >>> robot = tolalloc.load_robot("tool_changer")
        >>> robot.fk([0, 0, 0, 0, 0, 0])[:3, 3]      # the home pose (0, l3+l4+l5+l6, l1+l2) mm
        array([   0., 1761.,  525.])
        """
        return self.fk_internal(self.check_q(q_deg_mm, "q_deg_mm", interface=True))

    def space_jacobian(self, q_deg_mm) -> np.ndarray:
        """Space Jacobian at joint values in interface units [deg / mm], shape (6, n) or (P, 6, n).

        Rows ``(omega, v)``; columns per unit joint motion in internal units (per rad for revolute joints,
        per mm for prismatic ones), ``v`` in mm.
        """
        return self.space_jacobian_internal(self.check_q(q_deg_mm, "q_deg_mm", interface=True))

    def body_jacobian(self, q_deg_mm) -> np.ndarray:
        """Body Jacobian at joint values in interface units [deg / mm], shape (6, n) or (P, 6, n) (per rad / mm)."""
        return self.body_jacobian_internal(self.check_q(q_deg_mm, "q_deg_mm", interface=True))

    def fk_internal(self, q) -> np.ndarray:
        """End-effector pose ``T(q)``, shape (..., 4, 4), for ``q`` of shape (..., n) in internal units [rad, mm]
        (finite; the limits are not checked)."""
        return fk_poe(self.screws, self.home, self.joint_array(q))

    def space_jacobian_internal(self, q, *, engine: str | None = None) -> np.ndarray:
        """Space Jacobian, shape (..., 6, n), at ``q`` [rad, mm]; ``engine`` as in :func:`space_jacobian`."""
        return space_jacobian(self.screws, self.joint_array(q), engine=engine)

    def body_jacobian_internal(self, q) -> np.ndarray:
        """Body Jacobian, shape (..., 6, n), at ``q`` [rad, mm]."""
        return body_jacobian(self.screws, self.home, self.joint_array(q))

    # ------------------------------------------------------------------ display
    def joints_frame(self) -> pd.DataFrame:
        """One row per joint: type, axis and point at home [mm], unit, limits and nominal value [deg / mm]
        (``lower_deg_mm``, ``upper_deg_mm``, ``nominal_deg_mm``: deg for a revolute joint, mm for a prismatic one,
        the ``unit`` column says which)."""
        return pd.DataFrame({
            "joint": [j.name for j in self.joints],
            "type": [j.kind for j in self.joints],
            "axis": [np.array2string(j.axis, precision=4, suppress_small=True) for j in self.joints],
            "point_mm": [np.array2string(p, precision=3, suppress_small=True) for p in self.joint_points_mm],
            "unit": [j.unit for j in self.joints],
            "lower_deg_mm": self.q_to_interface(self.lower),
            "upper_deg_mm": self.q_to_interface(self.upper),
            "nominal_deg_mm": self.q_to_interface(self.q_nominal),
        })

    def links_frame(self) -> pd.DataFrame:
        """One row per link: name, length [mm] and vector at home [mm]."""
        return pd.DataFrame({
            "link": [lk.name for lk in self.links],
            "length_mm": [lk.length_mm for lk in self.links],
            "vector_mm": [np.array2string(lk.vector_mm, precision=3, suppress_small=True) for lk in self.links],
        })

    def _summary_line(self) -> str:
        kinds = "".join("R" if j.is_revolute else "P" for j in self.joints)
        reach = float(np.linalg.norm(self.home[:3, 3]))
        return f"{self.n_joints} joints ({kinds}), {len(self.links)} links, home tool point {reach:.0f} mm from the base"

    def __repr__(self) -> str:
        sets = ", ".join(f"{k} ({len(v)})" for k, v in self.pose_sets.items()) or "none"
        extra = [f"pose sets: {sets}"]
        if self.regions:
            extra.append(f"regions: {', '.join(self.regions)}")
        if self.sigma_sets:
            extra.append(f"sigma sets: {', '.join(self.sigma_sets)}")
        return f"<Robot {self.name!r}: {self._summary_line()}; " + "; ".join(extra) + ">"

    def _repr_html_(self) -> str:
        import html

        return (f"<div><strong>Robot {html.escape(self.name)}</strong>: {html.escape(self._summary_line())}</div>"
                + self.joints_frame().to_html(index=False, border=0))

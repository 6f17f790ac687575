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
    repeatability_arcsec = 6         # +- band of repeated approaches to one position (half-width)
    stiffness_sd_pct = 10            # part-to-part spread of the stiffness (one standard deviation)
    rated_torque_Nm = 178
    source = "Harmonic Drive CSG-32-100 catalogue"

    [components.joints.shoulder_lift_joint.encoder]
    side = "output"                  # output | motor
    accuracy_arcsec = 20             # peak-to-peak
    eccentricity_um = 5              # mounting eccentricity of the scale (reads e / r once per turn)
    scale_radius_mm = 50
    homing = "absolute"              # absolute (zero kept through a power cycle) | incremental (homed at power-up)
    # homing_repeatability_arcsec = 3    # incremental only: +- band of the zero from one homing to the next
    # scale_expansion_um_per_m_K = 12    # a scale's expansion less the structure's it measures (a wheel, a tape)
    source = "assumed"

    [components.joints.shoulder_lift_joint.bearing]
    precision_class = "P5"           # ISO 492 class of the joint's bearings
    span_mm = 80                     # axial distance between the two bearing seats
    bore_mm = 60                     # bore of the bearings (selects the ISO 492 runout row)
    radial_runout_um = 5             # Kia, radial runout of the assembled inner ring (full indicator reading)
    datum = "B"                      # datum feature of the seat axis on the drawing (A: the base mounting face)
    locating_datum = "J"             # the output flange's locating pin hole or keyway on the drawing
    shoulder_datum = "K"             # the shoulder face of the axially locating bearing seat on the drawing
    seat_diameter_mm = 62            # nominal diameter of the bearing seats (the size of the joint's ISO 286 fit)
    tilt_stiffness_Nm_per_rad = 1.0e6  # moment stiffness across the axis: the bearing tilts by M / k under its load
    centre_mm = 0                    # the bearing pair's centre along the joint axis from the joint point (it tilts
                                     # about it)

    [components.joints.shoulder_lift_joint.motor]
    winding_resistance_ohm = 0.6     # line to line (three-phase servo datasheet); torque constant per A rms
    torque_constant_Nm_per_A = 0.12
    thermal_resistance_K_per_W = 0.8
    thermal_time_constant_min = 30
    link_coupling_pct = 30           # share of the motor's temperature rise reached by the links it sits between

    [components.links.a2]
    section = "tube"                 # tube | solid | box
    outer_diameter_mm = 110          # tube / solid; box: width_mm and height_mm
    wall_mm = 5                      # tube and box
    material = "aluminium"           # steel | aluminium | cast_iron | cfrp; or the figures below
    youngs_modulus_GPa = 70          # optional, overrides the material's
    cte_um_per_m_K = 23

A joint's part may instead be a *slot* of the component catalogue (:mod:`tolalloc.robot.part_catalogue`):
``reducer = { part = "HD-CSG-32-100" }`` (a fixed catalogue part), ``{ family = "HD-CSG-32-100" }`` or
``{ options = ["...", "..."] }`` (the design picks one; a bearing slot adds ``bore_mm``, ``span_mm``, ``datum``,
``locating_datum``, ``shoulder_datum``, ``seat_diameter_mm``, ``tilt_stiffness_Nm_per_rad``, ``centre_mm``).
Slots are listed in :attr:`Components.slots`; they fill the joint's entry only once a part is chosen
(:meth:`Components.with_choice`; a slot of one part is chosen by itself), so the diagnosis, which reads the joints'
entries, sees only the parts whose figures the file gives.

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
           "Payload", "MATERIALS", "REDUCER_TYPES", "ARCMIN", "ARCSEC"]

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
    "cfrp": (70e3, 27e3, 1.55e-6, 0.5e-6, "quasi-isotropic carbon-fibre laminate, typical handbook values; G from E "
                                          "with an in-plane Poisson's ratio of 0.3 (assumed)"),
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
    repeatability : float or None     half-width of the band of repeated approaches [rad, or mm]
    stiffness_sd : float or None      part-to-part standard deviation of the stiffness, relative (0.1 = 10 %)
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
    repeatability: float | None = None
    stiffness_sd: float | None = None

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
    """Position encoder: ``side`` (``output`` or ``motor``), peak-to-peak ``accuracy`` [rad or mm], source; the scale's
    mounting ``eccentricity`` [mm] on its ``scale_radius_mm`` (an output-side rotary encoder then reads ``e / r``
    [rad] once per turn); ``homing``: ``absolute`` (the zero kept through a power cycle) or ``incremental`` (homed on a
    reference switch at each power-up, the zero set anew each time), with ``homing_repeatability`` [rad or mm] the
    half-width of the band the zero falls in from one homing to the next; ``scale_expansion`` [1 per K]: a scale's
    thermal expansion less that of the structure it measures (a linear scale, a measuring wheel on a ring), the
    joint then reading ``expansion q dT`` off (:mod:`tolalloc.physics.thermal_scale`)."""

    side: str = "output"
    accuracy: float | None = None
    source: str = ""
    eccentricity: float | None = None
    scale_radius_mm: float | None = None
    homing: str = "absolute"
    homing_repeatability: float | None = None
    scale_expansion: float | None = None


@dataclass(frozen=True)
class Bearing:
    """The joint's bearing arrangement: ISO 492 ``precision_class``, seat ``span_mm``, drawing ``datum``,
    ``tilt_stiffness`` [N m/rad], source, ``bore_mm`` and ``radial_runout`` [mm] (Kia: the full indicator reading of
    the assembled inner ring's radial runout), nominal ``seat_diameter_mm`` (the size of the seats' ISO 286 fit),
    ``centre_mm``: the pair's centre along the joint axis from the joint point [mm], about which the body tilts (its
    runout's tilt and its tilt under load; 0: at the joint point); ``locating_datum`` and ``shoulder_datum``: the
    drawing's letters of the output flange's locating pin hole or keyway and of the axially locating seat's shoulder
    face, the features that complete a datum system on the joint's axis."""

    precision_class: str | None = None
    span_mm: float | None = None
    datum: str | None = None
    tilt_stiffness: float | None = None
    source: str = ""
    bore_mm: float | None = None
    radial_runout: float | None = None
    seat_diameter_mm: float | None = None
    centre_mm: float = 0.0
    locating_datum: str | None = None
    shoulder_datum: str | None = None


@dataclass(frozen=True)
class Motor:
    """Motor figures for its losses and heating, as a servo datasheet gives them: the winding's line-to-line
    resistance [ohm] and the torque constant per ampere rms [N m/A] of a three-phase motor (copper loss
    ``1.5 R I^2``), thermal resistance [K/W], thermal time constant [s], source; ``link_coupling``: the share of the
    motor's steady temperature rise the links at its joint reach (0.3 = 30 %)."""

    winding_resistance_ohm: float | None = None
    torque_constant_Nm_per_A: float | None = None
    thermal_resistance_K_per_W: float | None = None
    thermal_time_constant_s: float | None = None
    source: str = ""
    link_coupling: float | None = None


@dataclass(frozen=True)
class Guide:
    """A prismatic joint's linear guide on the drawing: the letters of its guide axis (``datum``), its carriage's
    anti-rotation guide (``locating_datum``) and a face of its carriage across its stroke (``shoulder_datum``)."""

    datum: str | None = None
    locating_datum: str | None = None
    shoulder_datum: str | None = None


@dataclass(frozen=True)
class JointComponents:
    """The bought parts of one joint (each None where the file says nothing)."""

    reducer: Reducer | None = None
    encoder: Encoder | None = None
    bearing: Bearing | None = None
    motor: Motor | None = None
    guide: Guide | None = None


@dataclass(frozen=True)
class LinkSection:
    """Cross-section and material of a link (a beam).

    Attributes
    ----------
    section : {"tube", "solid", "box"}
    area_mm2, inertia_mm4 : float      cross-section area and second moment of area (a box: about its width axis,
                                       i.e. bending in the plane of its height)
    inertia_side_mm4 : float           a box's second moment about its height axis (bending in the plane of its
                                       width); a round section's equals ``inertia_mm4``
    torsion_mm4 : float                torsion constant ``J``: the polar moment for a round tube or bar (exact),
                                       Bredt's thin-walled closed section ``2 t (b-t)^2 (h-t)^2 / (b+h-2t)``
                                       for a box
    youngs_modulus_MPa, shear_modulus_MPa : float
    density_kg_per_mm3, cte_per_K : float
    material, source : str
    height_direction : tuple of 3 float or None
        a box's height direction at the home pose, in the base frame (unit; across the link). Given, the box bends
        with ``inertia_mm4`` in the plane of its height and ``inertia_side_mm4`` in the plane of its width; None
        (unknown orientation), with ``inertia_mm4`` in both planes.
    """

    section: str
    area_mm2: float
    inertia_mm4: float
    torsion_mm4: float
    youngs_modulus_MPa: float
    shear_modulus_MPa: float
    density_kg_per_mm3: float
    cte_per_K: float
    material: str = ""
    source: str = ""
    inertia_side_mm4: float | None = None
    height_direction: tuple | None = None

    @property
    def EI_Nmm2(self) -> float:
        """Bending stiffness ``E I`` [N mm^2]."""
        return self.youngs_modulus_MPa * self.inertia_mm4

    @property
    def EI_side_Nmm2(self) -> float:
        """Bending stiffness in the plane of a box's width, ``E I_side`` [N mm^2] (a round section: ``E I``)."""
        return self.youngs_modulus_MPa * (self.inertia_mm4 if self.inertia_side_mm4 is None else self.inertia_side_mm4)

    @property
    def GJ_Nmm2(self) -> float:
        """Torsional stiffness ``G J`` [N mm^2]."""
        return self.shear_modulus_MPa * self.torsion_mm4

    @property
    def shear_stiffness_N(self) -> float:
        """Shear stiffness ``kappa G A`` [N] (``kappa = 0.5`` for a thin tube or box, ``0.9`` for a solid section)."""
        return (0.9 if self.section == "solid" else 0.5) * self.shear_modulus_MPa * self.area_mm2


@dataclass(frozen=True)
class Mount:
    """The base mount: tilting stiffness about base x and y [N m/rad] (None: unknown), source; the drawing's letters
    of the base mounting face (``datum``) and of its locating pin hole (``locating_datum``)."""

    tilt_stiffness: tuple | None = None
    source: str = ""
    datum: str | None = None
    locating_datum: str | None = None


@dataclass(frozen=True)
class Payload:
    """Rated payload [kg] and its centre of mass from the tool point in the tool frame [mm]."""

    rated_kg: float | None = None
    com_mm: np.ndarray = field(default_factory=lambda: np.zeros(3))


@dataclass(frozen=True)
class Components:
    """A robot's component data (all optional): ``joints`` and ``links`` by name, ``mount``, ``payload``, ``source``;
    ``slots``: the catalogue slots ``{(joint name, part kind): Slot}`` (:mod:`tolalloc.robot.part_catalogue`)."""

    joints: dict = field(default_factory=dict)
    links: dict = field(default_factory=dict)
    mount: Mount = field(default_factory=Mount)
    payload: Payload = field(default_factory=Payload)
    source: str = ""
    slots: dict = field(default_factory=dict)

    def with_choice(self, choice: dict) -> "Components":
        """A copy with the catalogue parts ``choice`` ``{(joint name, kind): part name}`` in the joints' entries (every
        slot needs one unless it holds one part); raises ValueError naming a missing or unknown choice."""
        from dataclasses import replace as _replace

        joints = dict(self.joints)
        for key, slot in self.slots.items():
            name = choice.get(key, slot.options[0].name if len(slot.options) == 1 else None)
            if name is None:
                raise ValueError(f"components.joints.{key[0]}.{key[1]}: no part chosen; options: "
                                 + ", ".join(o.name for o in slot.options))
            joints[key[0]] = _replace(joints.get(key[0], JointComponents()), **{key[1]: slot.resolve(name)})
        extra = [k for k in choice if k not in self.slots]
        if extra:
            raise ValueError(f"choice {extra[0]}: not a catalogue slot of the robot; slots: {sorted(self.slots)}")
        return _replace(self, joints=joints)

    def joint(self, name: str) -> JointComponents:
        """The parts of joint ``name`` (empty when the file gives none)."""
        return self.joints.get(name, JointComponents())

    def encoder_joints(self, joint_names, declares) -> np.ndarray:
        """Indices (k,) of the joints ``joint_names`` (in chain order) whose encoder ``declares(encoder)`` holds."""
        return np.asarray([j for j, nm in enumerate(joint_names)
                           if (enc := self.joint(nm).encoder) is not None and declares(enc)], int)

    def gear_ratios(self, joint_names) -> np.ndarray | None:
        """Gear ratio of every joint, shape (n,), NaN where unknown; None when no joint has one."""
        r = np.array([getattr(self.joint(nm).reducer, "ratio", None) or np.nan for nm in joint_names], float)
        return None if np.all(np.isnan(r)) else r

    def __bool__(self) -> bool:
        return bool(self.joints or self.links or self.mount.tilt_stiffness or self.payload.rated_kg or self.slots)

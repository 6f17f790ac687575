"""The benchmark's case sets (seeded; the measurement tables are regenerated, never stored).

Set A (24 cases, 8 per arm) emphasises the physics the project's own benchmark lacks; set B (25 cases) is a held-out
draw of another mix with another seed; set C (24 cases, 8 per arm) holds physics variants neither A nor B contains
(:mod:`effects_c`), written after the diagnosis had been tuned on A and B; set D (24 cases, 8 per arm) is a further
independent test set of new physics kinds (:mod:`effects_d`), set E (24 cases, 8 per arm) another one
(:mod:`effects_e`), and set F (24 cases, 8 per arm) a sixth, of twelve more kinds written from the engineering
literature without reading how the diagnosis models effects (:mod:`effects_f`); sets G and H (24 cases, 8 per arm each)
two more of twelve new kinds each (:mod:`effects_g`, :mod:`effects_h`), set I (24 cases, 8 per arm) a ninth
(:mod:`effects_i`), set J (24 cases, 8 per arm) a tenth (:mod:`effects_j`), set K (24 cases, 8 per arm) an eleventh
(:mod:`effects_k`), set L (24 cases, 8 per arm) a twelfth (:mod:`effects_l`), set M (24 cases, 8 per arm) a thirteenth
(:mod:`effects_m`), set N (24 cases, 8 per arm) a fourteenth (:mod:`effects_n`), set O (24 cases, 8 per arm) a fifteenth
(:mod:`effects_o`), set P (24 cases, 8 per arm) a sixteenth (:mod:`effects_p`), set Q (24 cases, 8 per arm) a
seventeenth (:mod:`effects_q`), set R (24 cases, 8 per arm) an eighteenth (:mod:`effects_r`), set S (24 cases, 8 per
arm) a nineteenth (:mod:`effects_s`), set T (24 cases, 8 per arm) a twentieth (:mod:`effects_t`), set U (24 cases, 8 per
arm) a twenty-first (:mod:`effects_u`), set V (24 cases, 8 per arm) a twenty-second (:mod:`effects_v`), set W (24 cases,
8 per arm) a twenty-third (:mod:`effects_w`), set X (24 cases, 8 per arm) a twenty-fourth (:mod:`effects_x`), set Y (24
cases, 8 per arm) a twenty-fifth (:mod:`effects_y`), set Z (24 cases, 8 per arm) a twenty-sixth (:mod:`effects_z`) and
set ZA (24 cases, 8 per arm) a twenty-seventh (:mod:`effects_za`), set ZB (24 cases, 8 per arm) a twenty-eighth
(:mod:`effects_zb`), set ZC (24 cases, 8 per arm) a twenty-ninth (:mod:`effects_zc`), set ZD (24 cases, 8 per arm) a thirtieth
(:mod:`effects_zd`), set ZE (24 cases, 8 per arm) a thirty-first (:mod:`effects_ze`), set ZF (24 cases, 8 per
arm) a thirty-second (:mod:`effects_zf`), set ZG (24 cases, 8 per arm) a thirty-third (:mod:`effects_zg`), set ZH
(24 cases, 8 per arm) a thirty-fourth (:mod:`effects_zh`), set ZI (24 cases, 8 per arm) a thirty-fifth
(:mod:`effects_zi`), set ZJ (24 cases, 8 per arm) a thirty-sixth (:mod:`effects_zj`),
set ZK (24 cases, 8 per arm) a thirty-seventh (:mod:`effects_zk`),
set ZL (24 cases, 8 per arm) a thirty-eighth (:mod:`effects_zl`),
set ZM (24 cases, 8 per arm) a thirty-ninth (:mod:`effects_zm`),
set ZN (24 cases, 8 per arm) a fortieth (:mod:`effects_zn`),
set ZO (24 cases, 8 per arm) a forty-first (:mod:`effects_zo`),
set ZP (24 cases, 8 per arm) a forty-second (:mod:`effects_zp`).
A case: (id, robot, physics kinds, poses, split).
"""

from __future__ import annotations

import numpy as np

SEED_A, SEED_B, SEED_C, SEED_D, SEED_E, SEED_F = 40_7001, 40_7002, 40_7003, 40_7004, 40_7005, 40_7006
SEED_G, SEED_H, SEED_I, SEED_J, SEED_K, SEED_L = 40_7007, 40_7008, 40_7009, 40_7010, 40_7011, 40_7012
SEED_M, SEED_N, SEED_O, SEED_P, SEED_Q, SEED_R = 40_7013, 40_7014, 40_7015, 40_7016, 40_7017, 40_7018
SEED_S, SEED_T, SEED_U, SEED_V, SEED_W, SEED_X = 40_7019, 40_7020, 40_7021, 40_7022, 40_7023, 40_7024
SEED_Y, SEED_Z = 40_7025, 40_7026
SEED_ZA = 40_7027  # the sets after Z are named ZA, ZB, ... (two letters; they sort after Z)
SEED_ZB = 40_7028
SEED_ZC = 40_7029
SEED_ZD = 40_7030
SEED_ZE = 40_7031
SEED_ZF = 40_7032
SEED_ZG = 40_7033
SEED_ZH = 40_7034
SEED_ZI = 40_7035
SEED_ZJ = 40_7036
SEED_ZK = 40_7037
SEED_ZL = 40_7038
SEED_ZM = 40_7039
SEED_ZN = 40_7040
SEED_ZO = 40_7041
SEED_ZP = 40_7042
KINDS = ["gear", "encoder", "heat", "ambient", "hardening", "compliance", "mount", "sag", "backlash"]
ROBOTS = ["ur10", "tool_changer", "kr16_like"]

SET_A = [
    ("A01", "ur10", ("gear",), 150, "random"),
    ("A02", "ur10", ("encoder",), 100, "random"),
    ("A03", "ur10", ("heat",), 160, "time"),
    ("A04", "ur10", ("hardening",), 120, "random"),
    ("A05", "ur10", ("mount",), 80, "random"),
    ("A06", "ur10", ("sag",), 120, "random"),
    ("A07", "ur10", ("backlash",), 30, "random"),
    ("A08", "ur10", (), 60, "random"),
    ("A09", "tool_changer", ("compliance",), 90, "random"),
    ("A10", "tool_changer", ("ambient",), 180, "time"),
    ("A11", "tool_changer", ("sag",), 140, "random"),
    ("A12", "tool_changer", ("backlash",), 100, "random"),
    ("A13", "tool_changer", ("mount",), 60, "random"),
    ("A14", "tool_changer", ("gear",), 200, "random"),
    ("A15", "tool_changer", ("hardening",), 30, "random"),
    ("A16", "tool_changer", ("compliance", "heat"), 150, "time"),
    ("A17", "kr16_like", ("hardening",), 100, "random"),
    ("A18", "kr16_like", ("heat",), 180, "random"),
    ("A19", "kr16_like", ("ambient",), 150, "random"),
    ("A20", "kr16_like", ("encoder",), 60, "random"),
    ("A21", "kr16_like", ("mount",), 120, "time"),
    ("A22", "kr16_like", (), 120, "random"),
    ("A23", "kr16_like", ("backlash", "sag"), 160, "random"),
    ("A24", "kr16_like", ("gear", "ambient"), 200, "random"),
]


def set_b():
    """25 cases drawn with SEED_B: two of each kind, one extra kind, three geometry-only and three mixtures, on a
    random arm each, 30 or 60-200 poses, a quarter split by time."""
    rng = np.random.default_rng(SEED_B)
    physics = [(k,) for k in KINDS for _ in range(2)] + [(str(rng.choice(KINDS)),)] + [()] * 3
    for _ in range(3):
        a, b = rng.choice(len(KINDS), 2, replace=False)
        physics.append((KINDS[a], KINDS[b]))
    order = rng.permutation(len(physics))
    out = []
    for i, k in enumerate(order):
        n = 30 if rng.random() < 0.1 else int(rng.integers(6, 21)) * 10
        out.append((f"B{i + 1:02d}", str(rng.choice(ROBOTS)), physics[k], n,
                    "time" if rng.random() < 0.25 else "random"))
    return out


#: set C: 13 new kinds (every family), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split by time
SET_C = [
    ("C01", "ur10", ("twonode",), 160, "time"),
    ("C02", "ur10", ("dual_encoder",), 120, "random"),
    ("C03", "ur10", ("hyst_stiffness",), 120, "random"),
    ("C04", "ur10", ("bearing_tilt",), 90, "random"),
    ("C05", "ur10", ("dahl",), 60, "random"),
    ("C06", "ur10", ("bolted_tube",), 140, "random"),
    ("C07", "ur10", (), 80, "random"),
    ("C08", "ur10", ("track",), 100, "random"),
    ("C09", "tool_changer", ("rv_error",), 200, "random"),
    ("C10", "tool_changer", ("column_bow",), 180, "time"),
    ("C11", "tool_changer", ("box_torsion",), 120, "random"),
    ("C12", "tool_changer", ("dahl",), 100, "random"),
    ("C13", "tool_changer", ("track",), 80, "random"),
    ("C14", "tool_changer", (), 30, "random"),
    ("C15", "tool_changer", ("tracker_scale",), 150, "time"),
    ("C16", "tool_changer", ("hyst_stiffness", "twonode"), 150, "time"),
    ("C17", "kr16_like", ("workcell",), 180, "time"),
    ("C18", "kr16_like", ("rv_error",), 150, "random"),
    ("C19", "kr16_like", ("bearing_tilt",), 120, "random"),
    ("C20", "kr16_like", ("box_torsion",), 100, "random"),
    ("C21", "kr16_like", (), 100, "random"),
    ("C22", "kr16_like", ("runout",), 120, "random"),
    ("C23", "kr16_like", ("dahl", "bolted_tube"), 160, "random"),
    ("C24", "kr16_like", ("rv_error", "column_bow"), 200, "random"),
]

#: set D: 12 new kinds (every family, two for each gravity family), 3 geometry-only cases, 3 mixtures of two new
#: kinds, a quarter split by time (:mod:`effects_d`); written as an independent test set after set C
SET_D = [
    ("D01", "ur10", ("gas_spring",), 120, "random"),
    ("D02", "ur10", ("loose_anchor",), 90, "random"),
    ("D03", "ur10", ("bracket",), 140, "random"),
    ("D04", "ur10", ("varlash",), 60, "random"),
    ("D05", "ur10", ("thermal_bend",), 160, "time"),
    ("D06", "ur10", ("belt",), 100, "random"),
    ("D07", "ur10", (), 70, "random"),
    ("D08", "ur10", ("dresspack", "tool_heat"), 180, "time"),
    ("D09", "tool_changer", ("ball_screw",), 120, "random"),
    ("D10", "tool_changer", ("pad_creep",), 150, "time"),
    ("D11", "tool_changer", ("tapered",), 100, "random"),
    ("D12", "tool_changer", ("bracket",), 80, "random"),
    ("D13", "tool_changer", ("gas_spring",), 200, "random"),
    ("D14", "tool_changer", ("refraction",), 150, "time"),
    ("D15", "tool_changer", (), 30, "random"),
    ("D16", "tool_changer", ("ball_screw", "varlash"), 160, "random"),
    ("D17", "kr16_like", ("dresspack",), 130, "random"),
    ("D18", "kr16_like", ("loose_anchor",), 110, "random"),
    ("D19", "kr16_like", ("tapered",), 150, "random"),
    ("D20", "kr16_like", ("tool_heat",), 170, "time"),
    ("D21", "kr16_like", ("varlash",), 40, "random"),
    ("D22", "kr16_like", ("belt",), 120, "random"),
    ("D23", "kr16_like", (), 100, "random"),
    ("D24", "kr16_like", ("pad_creep", "thermal_bend"), 200, "time"),
]

#: set E: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_e`); written as an independent test set after set D. The parallelogram, ring-gear
#: and ram kinds sit on the arms that have such a drive (ram: the prismatic stage of tool_changer). Oracle labels
#: when written (oracle.py only; the diagnosis was not run): every case its truth (gains 11-94 %), the geometry-only
#: cases none; soft labels marked below (a gain near 10 % or a rival family within 10 % of the truth).
SET_E = [
    ("E01", "ur10", ("magnetic_ring",), 120, "random"),
    ("E02", "ur10", ("friction_windup",), 90, "random"),
    ("E03", "ur10", ("varstiff",), 150, "random"),
    ("E04", "ur10", ("table_frame",), 100, "time"),
    ("E05", "ur10", ("sunlight",), 180, "time"),
    ("E06", "ur10", ("scissor_gear",), 60, "random"),
    ("E07", "ur10", (), 80, "random"),
    ("E08", "ur10", ("soft_foot", "fan_thermostat"), 160, "time"),
    ("E09", "tool_changer", ("ram",), 120, "random"),
    ("E10", "tool_changer", ("fan_thermostat",), 170, "time"),
    ("E11", "tool_changer", ("parallelogram",), 140, "random"),
    ("E12", "tool_changer", ("soft_foot",), 100, "random"),
    ("E13", "tool_changer", ("ring_gear",), 200, "random"),
    ("E14", "tool_changer", ("channel",), 110, "random"),
    ("E15", "tool_changer", (), 30, "random"),
    ("E16", "tool_changer", ("ram", "scissor_gear"), 160, "random"),  # soft: scissor's removal costs 8 %
    ("E17", "kr16_like", ("channel",), 130, "random"),
    ("E18", "kr16_like", ("parallelogram",), 110, "random"),
    ("E19", "kr16_like", ("table_frame",), 150, "random"),  # soft: gain 11 %, link model within 7 %
    ("E20", "kr16_like", ("sunlight",), 190, "time"),
    ("E21", "kr16_like", ("friction_windup",), 50, "random"),
    ("E22", "kr16_like", ("ring_gear",), 140, "random"),  # soft: gain 17 %, mount model within 7 %
    ("E23", "kr16_like", (), 100, "random"),
    ("E24", "kr16_like", ("varstiff", "fan_thermostat"), 200, "time"),
]

#: set F: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_f`); written as an independent test set after set E. The lever kinds (lever_drive,
#: lever_stiffness, screw_growth) sit on the arms given cylinder-driven axes 2-3 (tool_changer, kr16_like); the tape
#: scale on the arms whose joint ranges reach past its butt joint (ur10, kr16_like); the link kinds, whose in-plane
#: bending the joint model mimics on the planar arms, on ur10 and in a mixture on tool_changer. Oracle labels when
#: written (oracle.py only; the diagnosis was not run): every case its truth (gains 45-88 %), the geometry-only cases
#: none; soft labels marked below (a gain near 10 % or a rival family within 10 % of the truth).
SET_F = [
    ("F01", "ur10", ("cable_balancer",), 120, "random"),
    ("F02", "ur10", ("wear_zones",), 90, "random"),
    ("F03", "ur10", ("uplift",), 110, "random"),
    ("F04", "ur10", ("eccentric_axis",), 140, "random"),
    ("F05", "ur10", ("day_night",), 180, "time"),
    ("F06", "ur10", ("weld_crack",), 100, "random"),  # soft: joint model within 9 %
    ("F07", "ur10", (), 70, "random"),
    ("F08", "ur10", ("weld_crack", "tape_scale"), 160, "time"),
    ("F09", "tool_changer", ("lever_drive",), 130, "random"),
    ("F10", "tool_changer", ("screw_growth",), 170, "time"),
    ("F11", "tool_changer", ("lever_stiffness",), 100, "random"),
    ("F12", "tool_changer", ("plate_yield",), 150, "time"),
    ("F13", "tool_changer", ("brake_hub",), 80, "random"),
    ("F14", "tool_changer", ("wear_zones",), 110, "random"),
    ("F15", "tool_changer", (), 30, "random"),
    ("F16", "tool_changer", ("eccentric_axis", "plate_yield"), 190, "random"),
    ("F17", "kr16_like", ("cable_balancer",), 140, "random"),
    ("F18", "kr16_like", ("uplift",), 120, "random"),
    ("F19", "kr16_like", ("tape_scale",), 150, "random"),
    ("F20", "kr16_like", ("day_night",), 200, "time"),
    ("F21", "kr16_like", ("lever_drive",), 40, "random"),
    ("F22", "kr16_like", ("lever_stiffness",), 110, "random"),
    ("F23", "kr16_like", (), 90, "random"),
    ("F24", "kr16_like", ("screw_growth", "brake_hub"), 200, "time"),
]

#: set G: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_g`); written as an independent test set after set F, from the literature, without
#: reading how the diagnosis models effects. The twin pinions, helical axial float, fractional ratio and
#: parallelogram bar sit on the arms with cycloid main axes / positioner-type wrists (tool_changer, kr16_like; they
#: do nothing on ur10). Oracle labels when written (oracle.py only; the diagnosis was not run): every case its truth
#: (gains 18-97 %), the geometry-only cases none; soft labels marked below (a gain near 10 % or a rival family within
#: 10 % of the truth).
SET_G = [
    ("G01", "ur10", ("hose_catenary",), 120, "random"),
    ("G02", "ur10", ("jack_leak",), 110, "time"),  # soft: the thermal model within 10 % (the sink drifts with time)
    ("G03", "ur10", ("cfrp_twist",), 140, "random"),
    ("G04", "ur10", ("target_rod",), 90, "random"),
    ("G05", "ur10", ("tripod_growth",), 170, "time"),
    ("G06", "ur10", ("ring_shift",), 100, "random"),
    ("G07", "ur10", (), 70, "random"),
    ("G08", "ur10", ("air_isolator", "bearing_clearance"), 160, "random"),
    ("G09", "tool_changer", ("twin_pinion",), 130, "random"),
    ("G10", "tool_changer", ("bar_expansion",), 180, "time"),
    ("G11", "tool_changer", ("ratio_rounding",), 100, "random"),
    ("G12", "tool_changer", ("air_isolator",), 150, "random"),
    ("G13", "tool_changer", ("axial_float",), 80, "random"),
    ("G14", "tool_changer", ("ring_shift",), 110, "random"),
    ("G15", "tool_changer", (), 30, "random"),
    ("G16", "tool_changer", ("jack_leak", "target_rod"), 190, "time"),
    ("G17", "kr16_like", ("twin_pinion",), 140, "random"),
    ("G18", "kr16_like", ("tripod_growth",), 160, "time"),
    ("G19", "kr16_like", ("bearing_clearance",), 120, "random"),
    ("G20", "kr16_like", ("bar_expansion",), 200, "time"),
    ("G21", "kr16_like", ("axial_float",), 45, "random"),
    ("G22", "kr16_like", ("cfrp_twist",), 110, "random"),
    ("G23", "kr16_like", (), 90, "random"),
    ("G24", "kr16_like", ("hose_catenary", "ratio_rounding"), 200, "random"),
]

#: set H: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_h`); written as an independent test set after set G, from the literature, without
#: reading how the diagnosis models effects. The coupled-wrist kinds (wrist_lash, wrist_coupling) and the helical
#: shift sit on the arms with motor-driven coupled / geared wrists (kr16_like, tool_changer; they do nothing on ur10);
#: the polymer-gear creep on the strain-wave arm (ur10). Oracle labels when written (oracle.py only; the diagnosis
#: was not run): every case its truth (gains 21-89 %), the geometry-only cases none; no soft labels (no gain below
#: 20 %, no rival family's model within 25 % of the truth; the closest: H18's joint model 1.26x, H05's 1.29x).
SET_H = [
    ("H01", "ur10", ("load_data",), 120, "random"),
    ("H02", "ur10", ("gear_creep",), 150, "time"),
    ("H03", "ur10", ("agv_wheels",), 100, "random"),
    ("H04", "ur10", ("curved_link",), 140, "random"),
    ("H05", "ur10", ("tracker_warmup",), 170, "time"),
    ("H06", "ur10", ("stale_table",), 90, "random"),
    ("H07", "ur10", (), 70, "random"),
    ("H08", "ur10", ("skid", "cold_grease"), 160, "random"),
    ("H09", "tool_changer", ("skid",), 130, "random"),
    ("H10", "tool_changer", ("helix_shift",), 180, "time"),
    ("H11", "tool_changer", ("bond_creep",), 150, "random"),
    ("H12", "tool_changer", ("agv_wheels",), 110, "random"),
    ("H13", "tool_changer", ("cold_grease",), 45, "random"),
    ("H14", "tool_changer", ("stale_table",), 100, "random"),
    ("H15", "tool_changer", (), 30, "random"),
    ("H16", "tool_changer", ("curved_link", "tracker_warmup"), 190, "time"),
    ("H17", "kr16_like", ("wrist_lash",), 120, "random"),
    ("H18", "kr16_like", ("wrist_coupling",), 140, "random"),
    ("H19", "kr16_like", ("load_data",), 150, "random"),
    ("H20", "kr16_like", ("helix_shift",), 200, "time"),
    ("H21", "kr16_like", ("tracker_warmup",), 160, "time"),
    ("H22", "kr16_like", ("cold_grease",), 110, "random"),
    ("H23", "kr16_like", (), 90, "random"),
    ("H24", "kr16_like", ("load_data", "wrist_coupling"), 200, "random"),
]

#: set I: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_i`); written as an independent test set after set H, from the literature, without
#: reading how the diagnosis models effects. The balancer and the parallelogram reducer sit on the heavy arms
#: (tool_changer, kr16_like), the coupled-wrist idler and the fork arm on kr16_like, the ball-screw nut on
#: tool_changer's prismatic stage (they do nothing on the other arms); the lap splice on ur10 (on the planar arms the
#: joint model mimics it). Oracle labels when written (oracle.py only; the diagnosis was not run): every case its
#: truth (gains 25-95 %; each mixture component's removal costs 11 % or more), the geometry-only cases none; no soft
#: labels (no gain below 20 %, no rival family's model within 25 % of the truth; the closest: I05's joint model 1.34x,
#: I20's transmission model 1.41x, I04's joint model 1.46x). I18's and I22's pose counts were changed after that
#: check (their first draws had the noise near the top of its range: gains 14 % and 24 %).
SET_I = [
    ("I01", "ur10", ("tilted_base",), 120, "random"),
    ("I02", "ur10", ("floor_beams",), 100, "random"),
    ("I03", "ur10", ("lap_splice",), 140, "random"),
    ("I04", "ur10", ("overrun_lash",), 45, "random"),
    ("I05", "ur10", ("housing_growth",), 170, "time"),
    ("I06", "ur10", ("rail_boom",), 160, "time"),
    ("I07", "ur10", (), 70, "random"),
    ("I08", "ur10", ("lap_splice", "portal"), 150, "random"),
    ("I09", "tool_changer", ("balancer_relax",), 130, "time"),
    ("I10", "tool_changer", ("nut_play",), 110, "random"),
    ("I11", "tool_changer", ("overrun_lash",), 120, "time"),
    ("I12", "tool_changer", ("portal",), 100, "random"),
    ("I13", "tool_changer", ("para_gear",), 140, "random"),
    ("I14", "tool_changer", ("tilted_base",), 90, "random"),
    ("I15", "tool_changer", (), 30, "random"),
    ("I16", "tool_changer", ("housing_growth", "nut_play"), 190, "time"),
    ("I17", "kr16_like", ("idler_runout",), 150, "random"),
    ("I18", "kr16_like", ("para_gear",), 130, "random"),
    ("I19", "kr16_like", ("balancer_relax",), 140, "random"),
    ("I20", "kr16_like", ("floor_beams",), 110, "random"),
    ("I21", "kr16_like", ("fork_arm",), 130, "random"),
    ("I22", "kr16_like", ("idler_runout",), 180, "random"),
    ("I23", "kr16_like", (), 90, "random"),
    ("I24", "kr16_like", ("rail_boom", "fork_arm"), 200, "time"),
]

#: set J: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_j`); written as an independent test set after set I, from the literature, without reading how
#: the diagnosis models effects. The differential wrist, the coupled wrist's shafts and the parallelogram bar's pins sit
#: on the arms with motor-driven wrists / a parallelogram axis 3 (they do nothing on ur10; on tool_changer the pins'
#: load rarely changes sign -- the transmission model within 2-10 % in trial draws -- and the differential's lever is
#: short -- gains of 12-19 % in half the trial draws --, so both are used on kr16_like); the wall console on ur10 and
#: the grout on tool_changer (on kr16_like and tool_changer the first link's bending mimics a base tilt, the link model
#: within 13 % in most trial draws of the console and of kr16_like's grout; ur10's base moments left the grout absorbed
#: or ambiguous in half the draws); the flange slip on ur10 and kr16_like (tool_changer's main-axis loads keep one sign:
#: only its wrist slips, by some 0.02 mm). Oracle labels when written (oracle.py only; the diagnosis was not run): every
#: case its truth (gains 26-92 %; each mixture component's removal costs 66 % or more), the geometry-only cases none; no
#: soft labels (no gain below 20 %, no rival family's model within 25 % of the truth; the closest: J20's backlash model
#: 1.26x, J09's link model 1.28x, J10's link model 1.34x, J14's mount model 1.35x). Draw ranges changed after trial
#: draws (other seeds): the brake-heated housings first on axes 2-3 at 3-10 K (absorbed in most draws), the laminate's
#: unbalanced share first 10-30 %, the planets' ring first 20-50 um, the differential's runouts first 10-25 / 5-15 um,
#: the tool plates first 12-18 / 15-25 mm thick with 1-3 / 3-8 kg grippers; a three-groove kinematic coupling (Hertz
#: contacts) was dropped for the wall console: its micrometre deflections were absorbed on every arm. After this set's
#: own first check: the hose pull and the wrist shafts first included the main axes' gravity twist (effects of 1-3 mm,
#: set A's compliance; now left out), the shafts' bevel ratio N2 was lowered (J09 and J20 had their rivals at 1.24x /
#: 1.22x), and the grout's creep, first on the whole tilt compliance, was put on the share of the anchors' bond and the
#: bed (J10 had its joint model at 1.09x; the added draw redrew the case); no pose count or seed was changed.
SET_J = [
    ("J01", "ur10", ("planet_stage",), 120, "random"),
    ("J02", "ur10", ("flange_slip",), 45, "random"),
    ("J03", "ur10", ("skew_casting",), 140, "random"),
    ("J04", "ur10", ("wall_console",), 100, "random"),
    ("J05", "ur10", ("brake_tilt",), 170, "time"),
    ("J06", "ur10", ("laminate_twist",), 160, "time"),
    ("J07", "ur10", (), 70, "random"),
    ("J08", "ur10", ("hose_retract", "tool_plate"), 150, "random"),
    ("J09", "tool_changer", ("wrist_shafts",), 130, "random"),
    ("J10", "tool_changer", ("grout_creep",), 180, "time"),
    ("J11", "tool_changer", ("hose_retract",), 110, "random"),
    ("J12", "tool_changer", ("skew_casting",), 120, "random"),
    ("J13", "tool_changer", ("planet_stage",), 140, "random"),
    ("J14", "tool_changer", ("brake_tilt",), 150, "time"),
    ("J15", "tool_changer", (), 30, "random"),
    ("J16", "tool_changer", ("skew_casting", "brake_tilt"), 190, "time"),
    ("J17", "kr16_like", ("diff_wrist",), 160, "random"),
    ("J18", "kr16_like", ("bar_pins",), 120, "random"),
    ("J19", "kr16_like", ("flange_slip",), 110, "random"),
    ("J20", "kr16_like", ("wrist_shafts",), 140, "random"),
    ("J21", "kr16_like", ("tool_plate",), 130, "random"),
    ("J22", "kr16_like", ("laminate_twist",), 180, "time"),
    ("J23", "kr16_like", (), 90, "random"),
    ("J24", "kr16_like", ("bar_pins", "diff_wrist"), 200, "random"),
]

#: set K: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_k`); written as an independent test set after set J, from the literature, without reading how
#: the diagnosis models effects. The telescopic arm's kinds (extension ropes, ram roll, Cardan shafts, spline twist),
#: the pressure bulkhead and the side cylinder sit on tool_changer (the TBM manipulator with a prismatic stage; they do
#: nothing on the other arms); the vacuum hose on the pick-and-place arms (ur10, kr16_like), the thermal backlash on the
#: arms given a pinion and ring gear on axis 1 (kr16_like, tool_changer; ur10's joints are strain-wave). Oracle labels
#: when written (oracle.py only; the diagnosis was not run): every case its truth (gains 30-94 %; each mixture
#: component's removal costs 85 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival
#: family's model within 25 % of the truth; the closest: K09's link model 1.29x, K19's link model 1.30x, K01's link
#: model 1.40x, K20's link model 1.43x). Changed after trial draws (other seeds): the joint kind on ur10 was first a
#: magnetic coupling in canned drives (a sine torque law, mostly linear: the link model within 1.25x or ambiguous on all
#: arms; replaced by the vacuum hose); a transmission kind was first inclinometers reading axes 2-3 of tool_changer
#: (their offset errors, cos and sin of the links' inclinations, have the shape of the gravity torques: the joint and
#: link models within 2 %; replaced by the spline twist); the link kind was first a gas-spring strut beside the arm (a
#: nearly constant force: absorbed; then the driving cylinder); the outriggers' soil, the bulkhead's pressure swings,
#: the ropes, the read heads' brackets and the spline's twist were first drawn smaller (absorbed or gains below 20 % in
#: some draws; the ranges in the modules' docstrings). After this set's own first check: K03 (gain 19 %, the joint model
#: at 1.05x, then 1.18x) got softer ground and a larger, faster consolidation; K05's compensation residual (split by
#: time) extrapolated its twelve free columns (gain -83 %) and K22 gained 14 %: the winding now follows its copper loss
#: alone and the true structure is one column; K11's cylinder, nearly normal to the arm, twisted it the way a base tilt
#: or joint 2 would (ambiguous twice): now shallow, its offset axial force bends the arm sideways; K13's ram kept one
#: flank (the cutter's roll torque never beat the wrist's bias): the cutter now gripped at its rim and the slot worn
#: wider; K14's Cardan offset and K17's hose were enlarged (rivals at 1.28x and 1.23x); K09's ropes made unequal (the
#: link model at 1.25x, then 1.17x). No pose count or seed was changed.
SET_K = [
    ("K01", "ur10", ("vacuum_hose",), 120, "random"),
    ("K02", "ur10", ("rcc",), 90, "random"),
    ("K03", "ur10", ("outrigger_soil",), 140, "random"),
    ("K04", "ur10", ("read_head",), 170, "time"),
    ("K05", "ur10", ("comp_mismatch",), 160, "time"),
    ("K06", "ur10", (), 70, "random"),
    ("K07", "ur10", ("rcc", "read_head"), 150, "random"),
    ("K08", "ur10", ("vacuum_hose", "comp_mismatch"), 180, "time"),
    ("K09", "tool_changer", ("tele_rope",), 130, "random"),
    ("K10", "tool_changer", ("bulkhead",), 180, "time"),
    ("K11", "tool_changer", ("side_cylinder",), 120, "random"),
    ("K12", "tool_changer", ("thermal_lash",), 150, "time"),
    ("K13", "tool_changer", ("ram_roll",), 110, "random"),
    ("K14", "tool_changer", ("cardan",), 100, "random"),
    ("K15", "tool_changer", ("spline_twist",), 45, "random"),
    ("K16", "tool_changer", (), 30, "random"),
    ("K17", "kr16_like", ("vacuum_hose",), 140, "random"),
    ("K18", "kr16_like", ("rcc",), 110, "random"),
    ("K19", "kr16_like", ("outrigger_soil",), 130, "random"),
    ("K20", "kr16_like", ("thermal_lash",), 160, "random"),
    ("K21", "kr16_like", ("read_head",), 150, "time"),
    ("K22", "kr16_like", ("comp_mismatch",), 190, "random"),
    ("K23", "kr16_like", (), 90, "random"),
    ("K24", "kr16_like", ("outrigger_soil", "thermal_lash"), 200, "random"),
]

#: set L: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_l`); written as an independent test set after set K, from the literature, without reading how
#: the diagnosis models effects. The polymer gears sit on ur10 (the arm of set H's polymer gears); the sealant
#: cartridge, the palletising frame, the compliant holder and the coolant-wetted forearm on the cobot and the industrial
#: arm (ur10, kr16_like); the hot die-cast parts on kr16_like; the measuring pinion on axis 1 of the arms given a ring
#: gear there (kr16_like, tool_changer); the hydraulic axis 2, the pin ring, the telescopic stage's guideway and the
#: loosening anchors on tool_changer (the tunnel-boring machine's arm); the gripper fingers on all three (they do
#: nothing on the other arms). Oracle labels when written (oracle.py only; the diagnosis was not run): every case its
#: truth (gains 25-91 %; each mixture component's removal costs 147 % or more), the geometry-only cases none; no soft
#: labels (no gain below 20 %, no rival family's model within 25 % of the truth; the closest: L14's thermal model 1.31x,
#: L21's link model 1.36x, L10's transmission model 1.44x, L02's link and L04's mount model 1.53x). Changed after trial
#: draws (other seeds; the first ranges in the modules' docstrings): the loosening anchors were first on all arms (on
#: ur10 and kr16_like the arm's weight over the plate's half width holds the plate closed: absorbed or ambiguous with
#: the joint model) and then with a lower threshold (nearly linear in the moment: the link model within 1.25x); the
#: compliant holder first had a low preload and no stroke end (nearly linear: ambiguous with the joint model); the hot
#: parts were first also cutters on tool_changer and moulded parts on ur10, the castings cooler and the fingers shorter
#: (growths of some 0.05 mm: absorbed or the joint model within 1.2x); the wet forearm first dried in 5-25 min at one
#: rate (a session of production periods without pauses stayed wet throughout: absorbed); the palletising frame first
#: stood on stiffer feet with lighter pallets, the cartridge was first lighter, the guideway straighter (gains below 20
#: % or rivals within 1.25x). After this set's own first check: L01 (the link model at 1.25x) got polymer gears 2-4x
#: (first 1-2x) as compliant as the metal ones; L13 (the joint model at 1.19x) got its anchors re-tightened before the
#: session (first 0-300 cycles before it, so the loosening hardly changed over the session) and a faster loosening; L20
#: (gain 18 %, the joint model at 1.20x) got the extraction gripper's longer fingers (150-250 mm on tips 250-400 mm
#: high, first 100-200 on 200-350); the fingers' length was then tied to the tip's height (the hot parts and the grip
#: share one gripper; it removed a draw), which left L14 absorbed (0.06 mm): the cutter gripper's prongs were made
#: thinner (25-35 mm, first 25-40) and its force 8-20 kN (first 5-15), ur10's grip 100-450 N (first 100-300) and
#: kr16_like's longer fingers stouter. No pose count or seed was changed.
SET_L = [
    ("L01", "ur10", ("polymer_heat",), 150, "time"),
    ("L02", "ur10", ("dispense_drain",), 120, "random"),
    ("L03", "ur10", ("pallet_load",), 110, "random"),
    ("L04", "ur10", ("grip_spread",), 90, "random"),
    ("L05", "ur10", ("float_holder",), 140, "random"),
    ("L06", "ur10", ("wet_arm",), 170, "time"),
    ("L07", "ur10", (), 70, "random"),
    ("L08", "ur10", ("polymer_heat", "grip_spread"), 180, "time"),
    ("L09", "tool_changer", ("gauge_pinion",), 45, "random"),
    ("L10", "tool_changer", ("valve_lap",), 120, "random"),
    ("L11", "tool_changer", ("pin_ring",), 130, "random"),
    ("L12", "tool_changer", ("guide_errors",), 110, "random"),
    ("L13", "tool_changer", ("anchor_loose",), 160, "time"),
    ("L14", "tool_changer", ("grip_spread",), 100, "random"),
    ("L15", "tool_changer", (), 30, "random"),
    ("L16", "tool_changer", ("anchor_loose", "pin_ring"), 190, "random"),
    ("L17", "kr16_like", ("dispense_drain",), 150, "time"),
    ("L18", "kr16_like", ("pallet_load",), 130, "random"),
    ("L19", "kr16_like", ("gauge_pinion",), 120, "random"),
    ("L20", "kr16_like", ("hot_part",), 160, "time"),
    ("L21", "kr16_like", ("wet_arm",), 140, "random"),
    ("L22", "kr16_like", ("float_holder",), 110, "random"),
    ("L23", "kr16_like", (), 90, "random"),
    ("L24", "kr16_like", ("hot_part", "gauge_pinion"), 200, "random"),
]

#: set M: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_m`); written as an independent test set after set L, from the literature, without reading how
#: the diagnosis models effects. The slurry shield's chamber, the hydraulic boom's oil columns and oil growth and the
#: telescopic stage's chain sit on tool_changer (the tunnel machine's arm); the docked cart, the track carriage, the
#: wire-rope mount and the tie-rod bar on ur10 and kr16_like; the measuring wheel and the spindle's dither on kr16_like
#: (they apply to tool_changer's slewing ring and cycloid main axes too); the jaw play on ur10 and tool_changer; the hot
#: air plume on all three (they do nothing on the other arms). Oracle labels when written (oracle.py only; the diagnosis
#: was not run): every case its truth (gains 24-95 %; each mixture component's removal costs 49 % or more), the
#: geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within 25 % of the truth; the
#: closest: M12's transmission model 1.29x, M10's link model 1.31x, M18's thermal model 1.33x, M01's link and thermal
#: models 2.01x). Changed after trial draws (this set's seed and two offsets of it, the first ranges in the modules'
#: docstrings' order): a link kind was first a tool hung in a sprung gimbal, its swing stiffened or softened by the
#: tool's own weight (the pendulum's gravity stiffness): with the swing of 0.05-1 mm the brief asks for, the spring
#: dwarfs the gravity stiffness and the law is a linear compliance (a new parameterisation of sets K's and L's
#: end-of-arm compliances), and with a softer spring the swing reached 80-400 mm; replaced by the wire-rope mount. The
#: jaw first flipped with the sign of the weight's component (one pose near zero flipped between the true and the file's
#: geometry: the true structure missed by 0.6 mm there): friction now holds it inside a band. The dither first sent an
#: unloaded axis 1 to the flank of the tiny torque its tilted axis gets from gravity (the file's geometry has none): the
#: spindle's own torque now centres an axis loaded below it. The spindle's dither on tool_changer (its main axes' loads
#: keep one sign: gains of -9 and 9 %, the link model within 1.09x) was replaced there by the hot plume, and the plume
#: on ur10 (a small working volume: its rays sweep little of the plume; gains of 3-15 % in two of three draws) by a
#: second carriage case; the plume first at 30-70 % of the way from the tracker and 30-80 K (absorbed on ur10). The
#: docking pins first had 0.05-0.2 mm clearance at 0.4-0.8 m (gain 24 %, rivals 1.33x), kr16_like's tie-rod bar was
#: first 0.5-0.8 m of EI 1e4-3e4 N m^2 (gain 21 %, the thermal model 1.26x), the oil cylinders' bores first 180-250 /
#: 125-180 mm with a stiffer back pressure (the link model 1.18x), and the oil first rose 8-15 K with 20-60 min
#: (absorbed), then 20-35 K with 10-30 min (up to 2.6 mm). No pose count or seed was changed.
SET_M = [
    ("M01", "ur10", ("cart_dock",), 120, "random"),
    ("M02", "ur10", ("carriage_play",), 100, "random"),
    ("M03", "ur10", ("rope_mount",), 140, "random"),
    ("M04", "ur10", ("jaw_play",), 45, "random"),
    ("M05", "ur10", ("carriage_play",), 160, "time"),
    ("M06", "ur10", ("tie_rod_bar",), 110, "random"),
    ("M07", "ur10", (), 70, "random"),
    ("M08", "ur10", ("cart_dock", "rope_mount"), 180, "random"),
    ("M09", "tool_changer", ("slurry_lift",), 130, "random"),
    ("M10", "tool_changer", ("oil_column",), 120, "random"),
    ("M11", "tool_changer", ("chain_stage",), 110, "random"),
    ("M12", "tool_changer", ("oil_growth",), 170, "time"),
    ("M13", "tool_changer", ("hot_plume",), 150, "time"),
    ("M14", "tool_changer", ("jaw_play",), 100, "random"),
    ("M15", "tool_changer", (), 30, "random"),
    ("M16", "tool_changer", ("oil_column", "chain_stage"), 190, "random"),
    ("M17", "kr16_like", ("friction_wheel",), 140, "random"),
    ("M18", "kr16_like", ("carriage_play",), 120, "random"),
    ("M19", "kr16_like", ("tie_rod_bar",), 130, "random"),
    ("M20", "kr16_like", ("spindle_dither",), 160, "time"),
    ("M21", "kr16_like", ("hot_plume",), 150, "time"),
    ("M22", "kr16_like", ("rope_mount",), 110, "random"),
    ("M23", "kr16_like", (), 90, "random"),
    ("M24", "kr16_like", ("friction_wheel", "hot_plume"), 200, "time"),
]

#: set N: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_n`); written as an independent test set after set M, from the literature, without reading how
#: the diagnosis models effects. The wind on a carried panel, the tracked carrier, the leaf-sprung vehicle, the ring
#: gripper frame, the heated elastomer pads and the magnetic encoders sit on ur10 and kr16_like; the water jet on
#: kr16_like and tool_changer; the counterbalanced axis 2 on kr16_like and tool_changer; the rope-driven telescopic
#: stage on tool_changer; the lattice boom, the base harness's lash and the tracker's heated tripod on all three (they
#: do nothing on the other arms). Oracle labels when written (oracle.py only; the diagnosis was not run): every case its
#: truth (gains 25-89 %; each mixture component's removal costs 33 % or more), the geometry-only cases none; no soft
#: labels (no gain below 20 %, no rival family's model within 25 % of the truth; the closest: N22's link model 1.32x,
#: N06's joint model 1.47x, N04's joint model 1.52x, N24's link model 1.53x). Changed after trial draws (other seeds;
#: the first ranges in the modules' docstrings): the panel was first glass of 10-16 kg/m^2 in 6-11 m/s wind (gains of
#: 12-18 %); kr16_like's jet first up to 1000 bar and 20 l/min (1.1 mm); the lattice's pins first 0.03-0.10 mm (1.2 mm);
#: the carrier's soil first sank 3-8 mm (2.7 mm at the tool); the vehicle's rear springs first started on their loading
#: envelope (the van settled 3-5 mm over the session by the friction band) and its payload changed between blocks; the
#: magnetic encoders first drifted 2-8 / 1-4 urad/K (gains of 6-30 %); the pads' heater first stood 1.2-2.5 m away on
#: 20-50 mm pads (absorbed or gains below 20 %). After this set's own first check (N04 and N22 mislabelled, the rest
#: clean): N04 (gain 16 %, the joint model at 1.17x) got the worn flexspline's lost motion on ur10's axis 1, 0.8-2
#: arcmin (first 0.5-1.5); N22 (split by time, its twelve free sine and cosine columns extrapolated: absorbed, a gain of
#: -43 %) got the encoders' drift phases as shape parameters (one column per harmonic and joint; it redrew N06, which
#: stayed clean). Trial draws on two offsets of the seed and six other seeds then moved, with the set's cases clean
#: before and after: the carrier's soil to a sinkage of 1.5-3.5 mm with a reloading line 4-10 times as stiff and heavier
#: carriers (where the ratcheting sinkage, a drift in time, dominated, the thermal, link or transmission model came
#: within 1.03-1.25x), the van's springs softer and the arm further ahead of its rear axle (gains of 14-25 %, the link
#: model within 1.04-1.21x), ur10's ring frame lighter (gains of 17-21 %), the pads' heater left on once switched on (a
#: time split's test part saw the pads cooling: absorbed). No pose count or seed was changed.
SET_N = [
    ("N01", "ur10", ("wind_panel",), 120, "random"),
    ("N02", "ur10", ("leaf_springs",), 100, "random"),
    ("N03", "ur10", ("ring_frame",), 140, "random"),
    ("N04", "ur10", ("harness_lash",), 45, "random"),
    ("N05", "ur10", ("pad_heat",), 170, "time"),
    ("N06", "ur10", ("mag_drift",), 160, "random"),
    ("N07", "ur10", (), 70, "random"),
    ("N08", "ur10", ("crawler_sink", "tripod_tilt"), 180, "time"),
    ("N09", "tool_changer", ("jet_reaction",), 130, "random"),
    ("N10", "tool_changer", ("harness_lash",), 110, "random"),
    ("N11", "tool_changer", ("balanced_lash",), 120, "random"),
    ("N12", "tool_changer", ("rope_creep",), 150, "time"),
    ("N13", "tool_changer", ("truss_slack",), 100, "random"),
    ("N14", "tool_changer", ("tripod_tilt",), 160, "time"),
    ("N15", "tool_changer", (), 30, "random"),
    ("N16", "tool_changer", ("jet_reaction", "rope_creep"), 190, "random"),
    ("N17", "kr16_like", ("jet_reaction",), 140, "random"),
    ("N18", "kr16_like", ("crawler_sink",), 120, "random"),
    ("N19", "kr16_like", ("truss_slack",), 130, "random"),
    ("N20", "kr16_like", ("balanced_lash",), 110, "random"),
    ("N21", "kr16_like", ("tripod_tilt",), 150, "time"),
    ("N22", "kr16_like", ("mag_drift",), 180, "time"),
    ("N23", "kr16_like", (), 90, "random"),
    ("N24", "kr16_like", ("wind_panel", "harness_lash"), 200, "random"),
]

#: set O: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_o`); written as an independent test set after set N, from the literature, without reading how
#: the diagnosis models effects. The milling kinds (the cut's twist, its flank on axes 1, 4 and 6, the spindle's
#: bracket) and the floating and guyed supports sit on ur10 and kr16_like; the nutrunner, the ring gear's mesh error,
#: the C-frame and the purged arm on kr16_like and tool_changer; the quantised output encoders on all three (kr16_like's
#: its secondary encoders); the encoders' hysteresis and the infrared panel on all three (they do nothing on the other
#: arms). O06 and O18 sit outside their arms' block of ids (their arms were swapped, below). Oracle labels when written
#: (oracle.py only; the diagnosis was not run): every case its truth (gains 38-91 %; each mixture component's removal
#: costs 51 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within
#: 25 % of the truth; the closest: O14's backlash model 1.43x, O11's joint model 1.62x, O18's link model 1.67x, O13's
#: thermal model 1.73x); two trial draws on offsets of the seed (+1, +2) were clean too (gains of 29 to 97 %, the
#: closest rival 1.41x). Changed after trial draws (the first ranges in the modules' docstrings): kr16_like's cut was
#: first a roughing cut (up to 9 mm at the tool, its wrist gears past their rating), then a lighter one (1.9 mm), now a
#: finishing cut (1.1 mm); the guyed masts were first taller, on thinner, slacker guys (2.6 mm at kr16_like's tool); the
#: C-frames' arms were first stouter (O11: the die's change between the schedule's forces under the noise, gain 9 %);
#: the infrared panel first stood 1.0-2.0 m away (O05: gain 15 %, the mount model at 1.18x); the purge first cooled the
#: links alone, 4-10 K by dryer air, between 4-7 blocks of a few minutes (the deficit hardly changed within a block: O10
#: and O20 absorbed), then 6-24 K over 2-3 longer blocks (O20, on kr16_like and, moved there, on tool_changer: gains of
#: 0-11 %, the arm's steel or its noise at the top of its range): it now cools the joint housings -- the Ex-p enclosures
#: proper -- with vortex-cooled air, the links and the base's wall at the inlet (a bow), and O20 is back on kr16_like
#: (O12, moved to kr16_like in exchange, is back on tool_changer). O24 first mixed milling_force and spindle_bracket:
#: the bar's soft bending and twist move the target across the bar as a twist of axis 6 under the same cut does (the
#: bracket's removal cost 0 %): the mixture is now the nutrunner and the infrared panel. O18's guyed mast was first on
#: kr16_like, whose 0.675 m base column is a beam of the link model (the link model at 1.17x); it moved to ur10 (its
#: base link is 0.13 m) and O06's quantised encoders from ur10 to kr16_like, whose secondary encoders got them. Then,
#: for margins seen in the trial draws on other seeds: ur10's pontoon smaller (modular floats; gain 11 % in a trial
#: draw), ur10's spindle bar slimmer (24 %, the mount model at 1.30x) and the mesh's profile deviations 20-50 um (20 %,
#: the link model at 1.24x). No pose count or seed was changed.
SET_O = [
    ("O01", "ur10", ("milling_force",), 120, "random"),
    ("O02", "ur10", ("cut_flank",), 45, "random"),
    ("O03", "ur10", ("pontoon",), 100, "random"),
    ("O04", "ur10", ("spindle_bracket",), 140, "random"),
    ("O05", "ur10", ("ir_dryer",), 170, "time"),
    ("O06", "kr16_like", ("lsb_stop",), 110, "random"),
    ("O07", "ur10", (), 70, "random"),
    ("O08", "ur10", ("guyed_mast", "enc_hysteresis"), 160, "time"),
    ("O09", "tool_changer", ("bolt_torque",), 130, "random"),
    ("O10", "tool_changer", ("purge_air",), 180, "time"),
    ("O11", "tool_changer", ("weld_gun",), 120, "random"),
    ("O12", "tool_changer", ("enc_hysteresis",), 100, "random"),
    ("O13", "tool_changer", ("mesh_te",), 150, "random"),
    ("O14", "tool_changer", ("lsb_stop",), 110, "time"),
    ("O15", "tool_changer", (), 30, "random"),
    ("O16", "tool_changer", ("weld_gun", "mesh_te"), 190, "random"),
    ("O17", "kr16_like", ("milling_force",), 140, "random"),
    ("O18", "ur10", ("guyed_mast",), 120, "random"),
    ("O19", "kr16_like", ("cut_flank",), 110, "random"),
    ("O20", "kr16_like", ("purge_air",), 160, "time"),
    ("O21", "kr16_like", ("pontoon",), 130, "random"),
    ("O22", "kr16_like", ("ir_dryer",), 180, "time"),
    ("O23", "kr16_like", (), 90, "random"),
    ("O24", "kr16_like", ("bolt_torque", "ir_dryer"), 200, "random"),
]

#: set P: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_p`); written as an independent test set after set O, from the literature, without reading how
#: the diagnosis models effects. The magnetic couplings, vacuum feet, platen, lance, jacket and charging deck sit on
#: ur10
#: and kr16_like, the slack belt on kr16_like and tool_changer (they do nothing on the other arms). Oracle labels when
#: written (oracle.py only; the diagnosis was not run): every case its truth (gains 28-93 %; each mixture component's
#: removal costs 40 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's
#: model
#: within 25 % of the truth; the closest: P02's mount model 1.36x, P01's backlash model 1.44x, P08's joint model 1.43x,
#: P14's mount model 1.56x). Changed after trial draws (the first ranges in the modules' docstrings): the magnetic
#: couplings moved from axes 2-3 to the wrist (the link model mimicked the main axes' twist under gravity: P01 1.04x,
#: P20 1.12x), with fewer pole pairs and a smaller service factor (on the wrist, ur10's case first gained 11 %); the
#: seals' drag raised to 5-12 % of the rated torque (P02: gain 15 %); the stray field's dipoles first 0.05-0.3 A m^2 at
#: 60-120 mm on axes 1-2 of every arm (up to 2.3 mm at the tool), then 0.03-0.15 at 80-140 mm (P06 then on ur10: gain
#: 14 %; P14: 7 %, tool_changer's axes 2-3 turning through 70 deg only) -- now 0.05-0.2 (ur10) and 0.1-0.4 (the heavier
#: arms' brakes) at 70-120 mm, axis 5 read too on tool_changer and kr16_like; the vacuum feet's cups first fixed in size
#: on soft pads (nearly linear: the joint model within 1.06x in P08, the link model within 1.23x on kr16_like, whose
#: 0.675 m base column the link model bends), now sized for the load on hard pads -- P17 moved to kr16_like's stray
#: field and P06 (vacuum feet on ur10, the joint model at 1.07x) to ur10's quick change, the vacuum feet left to the P08
#: mixture; the lance first slimmer (2-5 mm at the nozzle), the jacket's band first 4-8 K (0.05 mm on ur10), the deck's
#: charging difference first 1-3 K (P18: gain 29 %). No pose count or seed was changed. A trial draw on the seed + 1 was
#: clean in 20 of 24 cases (gains below 20 %: P13's vacuum plate 12 %, P14's stray field 15 %, P18's charging deck 15 %,
#: P19's quick change 10 %: small effects under a large noise draw), not tuned further.
SET_P = [
    ("P01", "ur10", ("mag_coupling",), 120, "random"),
    ("P02", "ur10", ("seal_relax",), 45, "random"),
    ("P03", "ur10", ("platen_clamp",), 100, "random"),
    ("P04", "ur10", ("hose_lance",), 140, "random"),
    ("P05", "ur10", ("jacket_cycle",), 170, "time"),
    ("P06", "ur10", ("quick_change",), 110, "random"),
    ("P07", "ur10", (), 70, "random"),
    ("P08", "ur10", ("vacuum_feet", "charging_heat"), 180, "time"),
    ("P09", "tool_changer", ("belt_slack",), 130, "random"),
    ("P10", "tool_changer", ("quick_change",), 150, "time"),
    ("P11", "tool_changer", ("pole_pitch",), 120, "random"),
    ("P12", "tool_changer", ("seal_relax",), 110, "random"),
    ("P13", "tool_changer", ("vacuum_plate",), 140, "random"),
    ("P14", "tool_changer", ("stray_field",), 160, "time"),
    ("P15", "tool_changer", (), 30, "random"),
    ("P16", "tool_changer", ("belt_slack", "pole_pitch"), 190, "random"),
    ("P17", "kr16_like", ("stray_field",), 130, "random"),
    ("P18", "kr16_like", ("charging_heat",), 160, "time"),
    ("P19", "kr16_like", ("quick_change",), 120, "random"),
    ("P20", "kr16_like", ("mag_coupling",), 110, "random"),
    ("P21", "kr16_like", ("platen_clamp",), 150, "random"),
    ("P22", "kr16_like", ("hose_lance",), 120, "random"),
    ("P23", "kr16_like", (), 90, "random"),
    ("P24", "kr16_like", ("jacket_cycle", "vacuum_plate"), 200, "time"),
]

#: set Q: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_q`); written as an independent test set after set P, from the literature, without reading how
#: the diagnosis models effects. The draw wire sits on tool_changer only (its telescopic stage); the other kinds act on
#: every arm, but the cases put each where it is large enough (the ball pass on ur10, whose six axes are strain-wave
#: gears; the fluid tank, the gooseneck and the door on the lighter arms). Oracle labels when written (oracle.py only;
#: the diagnosis was not run): every case its truth (gains 38-93 %; each mixture component's removal costs 27 % or
#: more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within 25 % of the
#: truth; the closest: Q09's link model 1.41x, Q10's 1.42x, Q19's 1.43x, Q03's 1.45x). Changed after trial draws (the
#: first ranges in the modules' docstrings): the second mount kind was first a hexapod under the base (struts of 8-20
#: N/um on ur10, 20-50 on kr16_like); its platform turns nearly in proportion to the weights' moment, which the link
#: model bending the arm's long links under the same weights reproduced (1.02x on ur10 with a gain of 12 %, 0.99x on
#: kr16_like, 0.99-1.11x on tool_changer, softer struts too), so it gave way to the disc springs, whose regressive curve
#: the link model cannot follow -- and only with cone heights near sqrt 2 and a working range up to near flat (first h /
#: t 1-1.35 and s / h 0.2-0.85: 1.07x on kr16_like; 0.3-0.98 was no better). The disc springs' second case (Q20,
#: kr16_like, 16 % and the link model at 1.10x) and then the torque sensors there (kr16_like's 0.675 m base column a
#: beam of the link model: 1.03x) gave way to the servo tail on kr16_like; ur10's mount case (Q03: the kinematic
#: coupling was 0.03 mm there) to the fluid tank; Q05's door on ur10 (gain 5 %, its aluminium tubes short) to the
#: ejector on ur10 -- the door left to kr16_like and the Q08 mixture, with a loading door's openings of 5-20 min (first
#: 1-3 min, removal cost of the door 6 %), the air's fall 5-12 K (first 3-8), the hall's mixing 2-5 min (first 4-10).
#: The compensated lash's holding torque got a floor of 3 % of the rated torque: axis 1 of tool_changer carries no
#: gravity load, and the true arm's tilted axis gave it a flank the nominal model never sees (Q12: gain 11 %, now 93 %).
#: The kinematic coupling's balls 6-12 mm at 120-200 mm with 5-15 % of the clamp left (first 8-16 mm, 150-250 mm, 10-30
#: %: kr16_like 8 % and the link model at 1.02x; Q20 then moved off it, the coupling left to tool_changer), the
#: ejector's chill 4-10 K on a 30-50 mm boom (first 3-8 K, 40-60 mm: Q18 18 %), the ball pass 10-30 arcsec (first 8-25).
#: No pose count or seed was changed. A trial draw on the seed + 1 was clean in 23 of 24 cases (Q01's torque sensors:
#: the link model at 1.12x), not tuned further.
SET_Q = [
    ("Q01", "ur10", ("sensor_stops",), 120, "random"),
    ("Q02", "ur10", ("servo_tail",), 45, "random"),
    ("Q03", "ur10", ("fluid_tank",), 100, "random"),
    ("Q04", "ur10", ("gooseneck",), 140, "random"),
    ("Q05", "ur10", ("ejector_chill",), 170, "time"),
    ("Q06", "ur10", ("ball_pass",), 150, "random"),
    ("Q07", "ur10", (), 70, "random"),
    ("Q08", "ur10", ("lash_comp", "door_draught"), 180, "time"),
    ("Q09", "tool_changer", ("draw_wire",), 130, "random"),
    ("Q10", "tool_changer", ("kinematic_mount",), 150, "time"),
    ("Q11", "tool_changer", ("sensor_stops",), 110, "random"),
    ("Q12", "tool_changer", ("lash_comp",), 120, "random"),
    ("Q13", "tool_changer", ("ball_holder",), 140, "random"),
    ("Q14", "tool_changer", ("servo_tail",), 160, "time"),
    ("Q15", "tool_changer", (), 30, "random"),
    ("Q16", "tool_changer", ("draw_wire", "ball_holder"), 190, "random"),
    ("Q17", "kr16_like", ("fluid_tank",), 130, "random"),
    ("Q18", "kr16_like", ("ejector_chill",), 160, "time"),
    ("Q19", "kr16_like", ("disc_springs",), 120, "random"),
    ("Q20", "kr16_like", ("servo_tail",), 110, "random"),
    ("Q21", "kr16_like", ("gooseneck",), 150, "random"),
    ("Q22", "kr16_like", ("door_draught",), 160, "time"),
    ("Q23", "kr16_like", (), 90, "random"),
    ("Q24", "kr16_like", ("fluid_tank", "ejector_chill"), 200, "random"),
]

#: set R: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_r`); written as an independent test set after set Q, from the literature, without reading how
#: the diagnosis models effects. The pneumatic balancer and the homing sit on kr16_like and tool_changer, the belt splice
#: on kr16_like only (they do nothing on the other arms); the rest act on every arm. Oracle labels when written
#: (oracle.py only; the diagnosis was not run): every case its truth (gains 24-93 %; each mixture component's removal
#: costs 33 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within
#: 25 % of the truth; the closest: R01's mount model 1.31x, R21's joint model 1.33x, R09's transmission model 1.52x,
#: R11's joint model 1.64x). Changed after trial draws (the first ranges in the modules' docstrings): the sprayer's
#: chassis first on a truck's soft leaf springs with a larger tank (6-8 mm at the tool), now a compact carrier's rubber
#: axles; tool_changer's homing first on the precision switch of kr16_like's cams (R10: gain 29 %, the thermal model at
#: 1.22x), now on the inductive proximity switches heavy axes use; the belt splice first on tool_changer's axis 5 too
#: with a long belt, whose splice never reached the tight span over the axis' +-90 deg (R13 gained nothing): the stage is
#: now a compact one on kr16_like only, and R13 holds tool_changer's stick band; the swing mount's spring first stiffer
#: (R21: gain 10 %, the transmission model at 1.11x), now sized to release at a light collision; the heated hose first
#: 2-5 K on steel (R14 on tool_changer: 0.06 mm, absorbed), now 4-10 K with a steeper gradient (steel's lower
#: conductivity), and R14 holds tool_changer's forklift slab; the welding cable first on kr16_like (R22) with the cell
#: warm from earlier welding (its side rose only from 58 to 95 % of its steady value, 0.2 mm with most of it constant:
#: absorbed), now with the shift starting at the session, the cell cold, and R22 holds kr16_like's heated hose. No pose
#: count or seed was changed. A trial draw on the seed + 1 was clean in 22 of 24 cases (R09's balancer on tool_changer:
#: gain 15 %, the thermal model at 1.18x, a small force swing on a stiff gear; R20's belt splice: gain 7 %, the splice
#: hardly on the span over the axis' travel), not tuned further.
SET_R = [
    ("R01", "ur10", ("slide_shift",), 120, "random"),
    ("R02", "ur10", ("stick_band",), 45, "random"),
    ("R03", "ur10", ("forklift_slab",), 100, "time"),
    ("R04", "ur10", ("web_buckling",), 140, "random"),
    ("R05", "ur10", ("welding_cable",), 170, "time"),
    ("R06", "ur10", ("sprayer_tank",), 110, "random"),
    ("R07", "ur10", (), 70, "random"),
    ("R08", "ur10", ("floor_cable", "heated_hose"), 180, "time"),
    ("R09", "tool_changer", ("line_pressure",), 130, "random"),
    ("R10", "tool_changer", ("rehoming",), 150, "random"),
    ("R11", "tool_changer", ("swing_mount",), 110, "random"),
    ("R12", "tool_changer", ("slide_shift",), 120, "random"),
    ("R13", "tool_changer", ("stick_band",), 140, "random"),
    ("R14", "tool_changer", ("forklift_slab",), 160, "time"),
    ("R15", "tool_changer", (), 30, "random"),
    ("R16", "tool_changer", ("line_pressure", "web_buckling"), 190, "random"),
    ("R17", "kr16_like", ("floor_cable",), 130, "random"),
    ("R18", "kr16_like", ("sprayer_tank",), 160, "time"),
    ("R19", "kr16_like", ("rehoming",), 120, "random"),
    ("R20", "kr16_like", ("belt_splice",), 110, "random"),
    ("R21", "kr16_like", ("swing_mount",), 150, "random"),
    ("R22", "kr16_like", ("heated_hose",), 160, "time"),
    ("R23", "kr16_like", (), 90, "random"),
    ("R24", "kr16_like", ("forklift_slab", "stick_band"), 200, "random"),
]

#: set S: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_s`); written as an independent test set after set R, from the literature, without reading how
#: the diagnosis models effects. The floating pinion and the measuring wheel sit on kr16_like and tool_changer, the wall
#: bellows and the diaphragm flexure on ur10 and kr16_like, the boom cylinders' loaded potentiometers and trapped oil on
#: tool_changer (they do nothing on the other arms); the rest act on every arm. Oracle labels when written (oracle.py
#: only; the diagnosis was not run): every case its truth (gains 35-91 %; each mixture component's removal costs 17 % or
#: more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within 25 % of the
#: truth; the closest: S16's link model 1.50x, S19's joint model 1.57x, S17's transmission model 1.65x, S11's link model
#: 1.73x). Changed after trial draws (the set's seed and three offsets of it; the first ranges in the modules'
#: docstrings): the floating pinion first lifted at 30-60 % of the session's largest axis-2 load (S09 ambiguous with the
#: transmission model at 1.04x, S17 at 1.06x: axis 2's load is nearly a function of q2 alone), then with pick and place,
#: whose part varies the load at a given q2, and at 20-50 % (S09: the link model at 1.12x -- tool_changer's axis-2 load
#: never falls below a third of its largest, so nearly every pose was past the knee, a give linear in the load); it now
#: lifts between the 50th and the 80th percentile of the loads, with a give of 2-5e-4 / 2-4e-4 rad at the largest (first
#: 1.5-4e-4 / 0.6-1.5e-4); the sector on axis 3 was tried and dropped (the link model copied the forearm's twist,
#: 1.07-1.20x). ur10's twin table first stood on feet of 300-1000 N/mm (a trial draw gained 8 %), the measuring wheel's
#: tread was first 3-6 mm (tool_changer's case gained 10 % in a trial draw), the isolators' reloading exponent first
#: 1.5-3 and ur10's rates 3000-6000 N/mm (the joint model at 1.10x in a trial draw); the trapped oil's excess was first
#: 25-40 K with a chamber lag of 4-12 min and the potentiometers' load ratio 4e-4 - 2e-3 (1.4 and 1.06 mm at the tool).
#: No pose count or seed was changed. Trial draws on the seed + 1, + 2 and + 3 were clean in 23, 22 and 23 of 24 cases
#: (S17's pinion: the transmission model at 1.20x; S05's isolators: the joint model at 1.21x; S14's wheel: gain 14 %;
#: S02's 45 poses under a noise of 0.048 mm: gain 20 %, the transmission model at 1.21x), not tuned further.
SET_S = [
    ("S01", "ur10", ("wall_boot",), 120, "random"),
    ("S02", "ur10", ("overshoot_lash",), 45, "random"),
    ("S03", "ur10", ("twin_robot",), 100, "time"),
    ("S04", "ur10", ("profile_frame",), 140, "random"),
    ("S05", "ur10", ("mullins_mounts",), 150, "random"),
    ("S06", "ur10", ("cogging",), 110, "random"),
    ("S07", "ur10", (), 70, "random"),
    ("S08", "ur10", ("dowel_yaw", "diaphragm"), 160, "random"),
    ("S09", "tool_changer", ("float_pinion",), 130, "random"),
    ("S10", "tool_changer", ("oil_shrink",), 170, "time"),
    ("S11", "tool_changer", ("pot_loading",), 120, "random"),
    ("S12", "tool_changer", ("dowel_yaw",), 140, "random"),
    ("S13", "tool_changer", ("twin_robot",), 110, "random"),
    ("S14", "tool_changer", ("wheel_growth",), 180, "time"),
    ("S15", "tool_changer", (), 30, "random"),
    ("S16", "tool_changer", ("pot_loading", "mullins_mounts"), 190, "random"),
    ("S17", "kr16_like", ("float_pinion",), 140, "random"),
    ("S18", "kr16_like", ("wheel_growth",), 170, "time"),
    ("S19", "kr16_like", ("overshoot_lash",), 110, "random"),
    ("S20", "kr16_like", ("wall_boot",), 120, "random"),
    ("S21", "kr16_like", ("diaphragm",), 150, "random"),
    ("S22", "kr16_like", ("profile_frame",), 130, "time"),
    ("S23", "kr16_like", (), 90, "random"),
    ("S24", "kr16_like", ("twin_robot", "cogging"), 200, "time"),
]

#: set T: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_t`); written as an independent test set after set S, from the literature, without reading how
#: the diagnosis models effects. The charging cable, the lockable float, the plunger and the dew warming sit on ur10 and
#: kr16_like, the crane runway too, the balancer leak on kr16_like and tool_changer, the shield squeeze on tool_changer
#: and kr16_like, the inclinometers, the rangefinder and the main drive on tool_changer (they do nothing on the other
#: arms); the hose capstan and the hidden approach act on every arm. Oracle labels when written (oracle.py only; the
#: diagnosis was not run): every case its truth (gains 28-94 %; each mixture component's removal costs 50 % or more),
#: the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's model within 25 % of the truth;
#: the closest: T14's joint model 1.39x, T06's transmission model 1.65x, T24's thermal model 1.70x, T01's link model and
#: T17's thermal model 1.78x). Changed after trial draws (the first ranges in the modules' docstrings): a thermal kind
#: of hollow links bowed by the drive-heated air stratified in them (a gradient turning with each link's orientation to
#: gravity) was dropped for the dew warming -- the links swinging over the vertical averaged its gradient below 1 K
#: (0.02 mm on ur10, absorbed on kr16_like); the crane bracket first stood 0.8-1.6 m high under lighter cranes (T03,
#: then split by time: gain 11 %; it is now split at random, the time splits going to the drifts of T13 and T17); the
#: balancer first lost 5-20 % of a 0.3-0.8 m gas column holding 40-70 % of the load (0.03 mm on kr16_like, absorbed;
#: with more, still a gain of 8 % and the mount model at 1.10x in a trial draw), so its single-kind case went to
#: tool_changer (T13), whose heavier boom twists more, and the column now follows the stroke (a short one had gone
#: negative in a trial draw); the shield's console first stood near the invert with 0.5-2 mm of ovalisation (T13 on
#: tool_changer, split at random, ambiguous with the thermal model at 1.00x: the vertical drift is its per-body drift of
#: the column link), now at the side with 2-6 mm, the second case on kr16_like (T17, a handling arm in the same shield)
#: split by time; the main drive first cooled without the cutterhead's inching under a shorter, deeper console (T14
#: absorbed, then 1.26x); the dew warming on ur10 first had faster bodies, 8-20 K and an arrival up to 30 min early
#: (gain 12 % in a trial draw); the inclinometers' gain mismatch was tried smaller (2e-4 - 1e-3: the offsets'
#: once-per-turn term, which the link model copies as a gravity sag, dominated: 1.20x in a trial draw); the lockable
#: float first used the shared pick-and-place schedule, which may hold a part in every block and never unlock (absorbed
#: in a trial draw), now an alternately empty and holding gripper; ur10's hose pull was 30-80 N (T06: a gain of 33 %
#: with the transmission model at 1.43x). No pose count or seed was changed. Trial draws on the seed + 1, + 2 and + 3
#: were clean in all 24 cases each (the closest: the thermal model at 1.44x on T19 and 1.48x on T13, the link model at
#: 1.50x on T11; the smallest gains 31 % on T19 and 38 % on T14).
SET_T = [
    ("T01", "ur10", ("charge_cable",), 120, "random"),
    ("T02", "ur10", ("via_approach",), 45, "random"),
    ("T03", "ur10", ("crane_runway",), 110, "random"),
    ("T04", "ur10", ("lockable_float",), 140, "random"),
    ("T05", "ur10", ("dew_warming",), 170, "time"),
    ("T06", "ur10", ("hose_capstan",), 120, "random"),
    ("T07", "ur10", (), 70, "random"),
    ("T08", "ur10", ("plunger_stiction", "via_approach"), 180, "random"),
    ("T09", "tool_changer", ("inclinometer",), 130, "random"),
    ("T10", "tool_changer", ("shield_squeeze",), 160, "time"),
    ("T11", "tool_changer", ("rangefinder",), 120, "random"),
    ("T12", "tool_changer", ("main_drive",), 170, "time"),
    ("T13", "tool_changer", ("balancer_leak",), 140, "time"),
    ("T14", "tool_changer", ("main_drive",), 150, "random"),
    ("T15", "tool_changer", (), 30, "random"),
    ("T16", "tool_changer", ("rangefinder", "inclinometer"), 190, "random"),
    ("T17", "kr16_like", ("shield_squeeze",), 160, "time"),
    ("T18", "kr16_like", ("charge_cable",), 130, "random"),
    ("T19", "kr16_like", ("hose_capstan",), 110, "random"),
    ("T20", "kr16_like", ("crane_runway",), 150, "random"),
    ("T21", "kr16_like", ("dew_warming",), 170, "time"),
    ("T22", "kr16_like", ("lockable_float",), 130, "random"),
    ("T23", "kr16_like", (), 90, "random"),
    ("T24", "kr16_like", ("balancer_leak", "plunger_stiction"), 200, "random"),
]

#: set U: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_u`); written as an independent test set after set T, from the literature, without
#: reading how the diagnosis models effects. The chain stage and the Bowden cable sit on ur10 and kr16_like (none on
#: tool_changer), the sandwich boom's cases on ur10 and kr16_like (its booms sized for their parts), the others on
#: every arm. Oracle labels when written (oracle.py only; the diagnosis was not run): every case its truth (gains
#: 24-93 %; each mixture component's removal costs 12 % or more), the geometry-only cases none; no soft labels (no
#: gain below 20 %, no rival family's model within 25 % of the truth; the closest: U01's link model 1.27x, U18's
#: backlash model 1.32x, U09's joint model 1.47x; the smallest gains 24 % on U18 and 45 % on U09). Changed after
#: trial draws (the first ranges in the modules' docstrings): the integrator clamp was first at 40-75 % of the
#: largest load with a proportional stiffness of 0.5-2x the gear's (U01: the link model at 1.25x -- a clamp that low
#: leaves a sag nearly proportional to the load, the beams' law), now 55-85 % and 0.3-1.5x; the platform was steel on
#: every arm, 2-6 m from its fixed bearing, lagging by 30-90 min (U05 on ur10: a gain of 10 %, 0.05 mm), now an
#: aluminium-profile platform under the light arm, 3-8 m; the chain stage was first on tool_changer and kr16_like
#: with a slack-side tension of 300-700 N (U09 on tool_changer ambiguous with the transmission model at 1.03x: its
#: axis 3 is loaded one way over its range, so the flank never turns and the play reads as a function of axis 2's
#: angle), so the tool_changer case went to ur10 (U06, whose soiled-disc case went to tool_changer as U09) and the
#: tension now follows a tensioner's sag of the span (tried at the ordinary drives' 1-4 %: 2-4 mm at the tool; at
#: 0.3-0.5 %: U19 absorbed in a trial draw), 0.5-1 %; the Bowden sheath's drag was 5-15 % of the rated torque (U20:
#: the joint model at 1.14x in a trial draw, the gravity flank nearly everywhere), now 10-30 %; the parked tool
#: weighed 2-5 / 4-10 / 20-50 kg, sat by axis 4 and was parked at random in some blocks (U17: a gain of 22 % with the
#: mount model at 1.25x; U12, split by time, absorbed in a trial draw with the tool in every training block), now
#: 40-90 % of the largest payload, in a holder by the wrist, changed at each block; the magnet coil's gripper was
#: 120-250 mm long, 15-40 K warm, of 10-30 min (U18 absorbed, 0.03 mm), now 200-400 mm, 25-60 K, 5-15 min, and U18,
#: then at a gain of 10 % with the link model at 1.12x on its split by time (the part's weight bends the tubes in the
#: same blocks that warm the gripper), is now split at random, the time split going to U10; the slab joint took the
#: plate stiffness of hardware.py with a ratio of 2-5 (6 mm at tool_changer's tool), now per-arm ranges and 2-4; the
#: sandwich boom's core was aluminium honeycomb of one section for all (1.1 mm on kr16_like), now a PMI foam with
#: per-arm sections; the trunnion under ur10 was 0.4-1.5e6 N m/rad (0.03 mm, absorbed in a trial draw), now
#: 0.2-0.8e6. No pose count or seed was changed. Trial draws on the seed + 1, + 2 and + 3 (the case seeds + 1000003
#: k): + 1 clean in all 24 cases (the closest: the link model at 1.31x on U19); + 2 all but U03 (the trunnion under
#: ur10 at a gain of 14 %, the joint model at 1.13x); + 3 all but U10 (the slab joint under tool_changer at a gain of
#: 6 %) and U14 (the link model at 1.25x).
SET_U = [
    ("U01", "ur10", ("integral_clamp",), 120, "random"),
    ("U02", "ur10", ("bowden_lash",), 45, "random"),
    ("U03", "ur10", ("trunnion",), 100, "random"),
    ("U04", "ur10", ("sandwich_boom",), 140, "random"),
    ("U05", "ur10", ("platform_growth",), 170, "time"),
    ("U06", "ur10", ("chain_slack",), 120, "random"),
    ("U07", "ur10", (), 70, "random"),
    ("U08", "ur10", ("magnet_coil", "dropped_counts"), 180, "time"),
    ("U09", "tool_changer", ("soiled_disc",), 130, "random"),
    ("U10", "tool_changer", ("slab_joint",), 150, "time"),
    ("U11", "tool_changer", ("dropped_counts",), 120, "time"),
    ("U12", "tool_changer", ("parked_tool",), 160, "time"),
    ("U13", "tool_changer", ("sleeve_rock",), 140, "random"),
    ("U14", "tool_changer", ("integral_clamp",), 110, "random"),
    ("U15", "tool_changer", (), 30, "random"),
    ("U16", "tool_changer", ("trunnion", "soiled_disc"), 190, "random"),
    ("U17", "kr16_like", ("parked_tool",), 140, "random"),
    ("U18", "kr16_like", ("magnet_coil",), 160, "random"),
    ("U19", "kr16_like", ("chain_slack",), 110, "random"),
    ("U20", "kr16_like", ("bowden_lash",), 120, "random"),
    ("U21", "kr16_like", ("sleeve_rock",), 150, "random"),
    ("U22", "kr16_like", ("platform_growth",), 170, "time"),
    ("U23", "kr16_like", (), 90, "random"),
    ("U24", "kr16_like", ("slab_joint", "sandwich_boom"), 200, "random"),
]

#: set V: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_v`); written as an independent test set after set U, from the literature, without
#: reading how the diagnosis models effects. The coupled wrist sits on kr16_like (none on ur10 or tool_changer), the
#: pinned boom joints and the butted rack on tool_changer (none on the others), the others on every arm. Oracle labels
#: when written (oracle.py only; the diagnosis was not run): every case its truth (gains 26-92 %; each mixture
#: component's removal costs 26 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival
#: family's model within 25 % of the truth; the closest: V22's joint model 1.34x, V18's link model 1.49x, V20's
#: thermal model 1.59x, V02's link model 1.64x; the smallest gains 26 % on V22 and 38 % on V20). Changed after
#: trial draws (the modules' docstrings give the final ranges): a joint-compliance kind of link-side torque sensors whose
#: crosstalk from the overturning moment set axis 1 off in a twist-compensating controller was dropped for the coiled
#: cord -- at 1-3 % crosstalk it moved the tool by 0.02-0.04 mm (V01 and V09 absorbed), and more crosstalk is not a
#: sensor anyone would fit; a mount kind of a six-strut (hexapod-like) stand was dropped for the self-levelling carrier
#: -- its moment-driven sideways shift reads as a scale of the arm's reach, which the geometry absorbs (V03 and V12:
#: gains of 10-12 %, ambiguous with four families; set Q met the same with a hexapod); a link kind of a slender
#: boom whose bending the axial part of gravity amplifies (P-delta) was dropped before any draw -- at a sag of tenths of
#: a mm its amplification is 1e-3 of it; the coupled wrist was first also on tool_changer's axis 6, which turns the
#: target about itself (V12: 0.008 mm, a gain of 9 %), so V12 went to the self-levelling carrier and the coupled wrist's
#: second case is V24's mixture on kr16_like (first the strut stand's, with the slab); V09 (the festoon on tool_changer:
#: absorbed, its stiff gears twist by 0.07 mm under a nearly constant pull) took the coiled cord, and the festoon's
#: kr16_like case is V18;
#: ur10's festoon hose weighed 0.5-1.2 kg/m (V02: the link model at 1.20x), now 1-2.5; the slab's free curl was 10-30 %
#: of 150-250 mm slabs (V14: a gain of 14 %), now 30-60 % of 120-200 mm panels; the printed boom took up 0.5-1 % at
#: D 1-3e-12 m^2/s with beta 0.15-0.3, out of its cabinet up to 60 min early (V21: a gain of 15 %, the mount model at
#: 1.16x; V06 at 1.28x), now 0.7-1.2 %, 2-5e-12, 0.2-0.35 and up to 20 min; the bar's critical rise was 2-4 times the
#: session's excursion (V22: the joint model at 1.24x), now 1.5-3; ur10's bolted boom root was 2-6e4 N m/rad like the
#: heavier flanges' (V04 at gains of 19 % and 12 % in trial draws on the seed + 2 and + 3; 35 % on the seed), now 1-3e4,
#: its small four-M6 flange (V04: 61 %). No pose count or seed was changed. Trial draws on the seed + 1, + 2 and + 3 (the
#: case seeds + 1000003 k): + 1 all but V09 (the coiled cord on tool_changer at a gain of 23 %) and V16 (the rack's
#: removal costing under 5 %: named backlash alone); + 2 all but V11 (the rack at a gain of 17 %); + 3 clean in all 24
#: (V04 at 37 % after the change). The rack (its butt errors of 0.06-0.15 mm against noise of up to 0.05 mm) is the
#: weakest kind; butt errors of 0.08-0.2 mm were tried and left (+ 2: V11 then ambiguous-close, the link model at 1.18x).
SET_V = [
    ("V01", "ur10", ("coiled_cord",), 50, "random"),
    ("V02", "ur10", ("overhead_festoon",), 120, "random"),
    ("V03", "ur10", ("self_leveling",), 110, "random"),
    ("V04", "ur10", ("bolt_loosening",), 140, "random"),
    ("V05", "ur10", ("restrained_bar",), 170, "time"),
    ("V06", "ur10", ("moisture_swell",), 160, "time"),
    ("V07", "ur10", (), 70, "random"),
    ("V08", "ur10", ("stabilizer_jacks", "interpolation_error"), 180, "random"),
    ("V09", "tool_changer", ("coiled_cord",), 120, "random"),
    ("V10", "tool_changer", ("journal_climb",), 130, "random"),
    ("V11", "tool_changer", ("rack_segments",), 120, "random"),
    ("V12", "tool_changer", ("self_leveling",), 140, "random"),
    ("V13", "tool_changer", ("interpolation_error",), 150, "random"),
    ("V14", "tool_changer", ("slab_curl",), 170, "time"),
    ("V15", "tool_changer", (), 30, "random"),
    ("V16", "tool_changer", ("journal_climb", "rack_segments"), 190, "random"),
    ("V17", "kr16_like", ("coupled_flank",), 120, "random"),
    ("V18", "kr16_like", ("overhead_festoon",), 130, "random"),
    ("V19", "kr16_like", ("stabilizer_jacks",), 140, "time"),
    ("V20", "kr16_like", ("bolt_loosening",), 130, "random"),
    ("V21", "kr16_like", ("moisture_swell",), 170, "time"),
    ("V22", "kr16_like", ("restrained_bar",), 160, "time"),
    ("V23", "kr16_like", (), 90, "random"),
    ("V24", "kr16_like", ("coupled_flank", "slab_curl"), 200, "random"),
]

#: set W: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_w`); written as an independent test set after set V, from the literature, without
#: reading how the diagnosis models effects. The step kinds (hub_slip, emi_counts, bent_bracket) are split at random
#: (a step inside the held-out last quarter could not be learnt); every kind acts on every arm. Oracle labels when
#: written (oracle.py only; the diagnosis was not run): every case its truth (gains 48-89 %; each mixture component's
#: removal costs 51 % or more), the geometry-only cases none; no soft labels (no gain below 20 %, no rival family's
#: model within 25 % of the truth; the closest: W06's link model 1.35x, W02's transmission model 1.65x, W09's mount
#: model 1.88x, W20's link model 1.91x; the smallest gains 48 % on W02 and W20). Changed after trial draws (the
#: modules' docstrings give the final ranges): young_grout was first on tool_changer (W12: a gain of 9 %, ambiguous
#: with the joint and link models -- its stiff bed under a heavy arm whose base turns through +-60 deg only tilts
#: nearly the same way in every pose, which the geometry takes up) and then on kr16_like (W19: the link model at
#: 1.02x -- the bed's tilt under the arm's moment is the bending the same moment gives kr16_like's 675-mm column link,
#: and the grout's hydration changes it by only 10-20 % in a day); the ur10 has no such column, so its case is W06 and
#: W12 / W19 took stable_probe and emi_counts; air_stratification was first on tool_changer (W14: absorbed -- steel
#: links expand half as much as aluminium ones and its boom's heights vary little), so W14 took the swarf shroud, and
#: the gradient was given its build-up from the furnace's lighting over a long day (a settled gradient's pose-varying
#: part is under 0.1 mm: W20 absorbed in the trial draw on the seed + 1; after it 0.48 / 0.49 / 0.15 on the seed,
#: + 1, + 2); swapping it to ur10 (W03) and the cracked plinth to kr16_like (W20) was tried and left (ambiguous and
#: absorbed on the seed); ur10's shroud collected 5-20 g/min (W01: the thermal model at 1.24x), then 10-30, now 20-40,
#: and tool_changer's 60-200, now 100-300 (a roughing cut's removal rate; trial + 2: W01 a gain of 8 %, W14 the thermal
#: model at 1.05x); the stable-probe tolerance was 0.02-0.05 mm with a settling time constant of 0.4-1.5 s (W02: a gain
#: of 21 %, the transmission model at 1.25x), now 0.03-0.08 mm and 0.5-2 s (a cobot's soft loop); the hub slips were
#: 0.004-0.015 deg at a gap in the session's first half (W18: a gain of 9 %, the thermal model at 1.02x -- an early
#: step reads as a warm-up), now 0.008-0.025 deg at a gap with blocks before and after; the encoders' miscounts were
#: N(0, 1-3) counts a gap (W19 moved the tool by 1.05 mm), now N(0, 0.7-2); the bracket's bend was 0.1-0.5 mm (trial
#: + 2: W21 a gain of 15 %, the transmission model at 1.15x against 0.05 mm of noise), now 0.15-0.6 mm. No pose count
#: or seed was changed. Trial draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with the final physics: every
#: case labelled its truth in both; + 1 one soft label (W06, the link model at 1.12x), + 2 five (W01 the backlash
#: model at 1.21x, W05 a gain of 18 %, W14 the thermal model at 1.12x, W18 the thermal model at 1.16x, W20 a gain of
#: 15 %): the weakest kinds are the shroud's chips (a staircase in time that the thermal drift follows in part), a
#: single hub slip against up to 0.05 mm of noise and the stratification (its pose-varying part about 0.1 mm).
SET_W = [
    ("W01", "ur10", ("swarf_shroud",), 120, "random"),
    ("W02", "ur10", ("stable_probe",), 45, "random"),
    ("W03", "ur10", ("cracked_plinth",), 110, "time"),
    ("W04", "ur10", ("air_bellows",), 140, "random"),
    ("W05", "ur10", ("cooling_part",), 160, "time"),
    ("W06", "ur10", ("young_grout",), 150, "random"),
    ("W07", "ur10", (), 70, "random"),
    ("W08", "ur10", ("part_slide", "young_grout"), 180, "random"),
    ("W09", "tool_changer", ("rail_trolley",), 120, "time"),
    ("W10", "tool_changer", ("part_slide",), 130, "random"),
    ("W11", "tool_changer", ("hub_slip",), 140, "random"),
    ("W12", "tool_changer", ("stable_probe",), 150, "random"),
    ("W13", "tool_changer", ("bent_bracket",), 130, "random"),
    ("W14", "tool_changer", ("swarf_shroud",), 160, "random"),
    ("W15", "tool_changer", (), 30, "random"),
    ("W16", "tool_changer", ("emi_counts", "cooling_part"), 190, "random"),
    ("W17", "kr16_like", ("swarf_shroud",), 130, "time"),
    ("W18", "kr16_like", ("hub_slip",), 120, "random"),
    ("W19", "kr16_like", ("emi_counts",), 140, "random"),
    ("W20", "kr16_like", ("air_stratification",), 150, "time"),
    ("W21", "kr16_like", ("bent_bracket",), 130, "random"),
    ("W22", "kr16_like", ("rail_trolley",), 140, "time"),
    ("W23", "kr16_like", (), 90, "random"),
    ("W24", "kr16_like", ("stable_probe", "air_bellows"), 200, "random"),
]

#: set X: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_x`); written as an independent test set after set W, from the literature, without
#: reading how the diagnosis models effects. The step kind (collision_shift) and the wash-down (each rinse its own,
#: unlearnable temperature) are split at random; cosine_error needs a prismatic joint (tool_changer's telescopic stage)
#: and is inert elsewhere. Oracle labels when written (oracle.py only; the diagnosis was not run): every case its truth
#: (gains 23-84 %; each mixture component's removal costs 19 % or more), the geometry-only cases none; no soft labels
#: (no gain below 20 %, no rival family's model within 25 % of the truth; the closest: X05's backlash model 1.29x, X16's
#: thermal model 1.43x, X11's thermal model 1.45x, X21's joint model 1.51x, X01's transmission model 1.54x; the smallest
#: gains 23 % on X05, 37 % on X01 and X08). Changed after trial draws (the modules' docstrings give the final ranges):
#: the second mount kind was first a hexapod under the base (legs of 5-150 N/um; X06 on ur10 ambiguous with the joint
#: and link models at 1.01x, and on tool_changer / kr16_like with the link model at 1.02 / 1.01x: a compliant support
#: under the arm's moment tilts it as the shoulder's gear and the column link bend under the same moment) and was
#: replaced by the levelling foot unscrewing through the production (a tilt that grows with the production time, not
#: with the moment); induction_stray was first on tool_changer with the aluminium range of 5-15 K (X14: absorbed, 0.03
#: mm on a steel forearm), then steel's 15-35 K (a ferromagnetic wall takes up far more of the stray field; still a
#: gain of 16 %, the link model at 1.21x), so it moved to kr16_like (X18) and the ur10 mixture (X08), and tool_changer
#: took the wash-down (X14); the magnetic fanner on kr16_like (X17) moved 0.015 mm at 40-120 N (absorbed; 150-400 N
#: still a gain of 10 %: its RV gears are too stiff), so kr16_like took the support arm (X17) and the ur10 mixture the
#: fanner (X08, first support_arm + induction_stray); the fanner's pole stood first beyond three quarters of the
#: targets' reach with a face of 60-120 mm (trial + 1: X01 absorbed, 0.02 mm), now in the targets' footprint with a
#: face of 100-200 mm (a fanner block is about as tall as its stack), ur10's pull 15-40 N at 300 mm (10-30 tried);
#: the printed fingers' section was first drawn (12-20 x 6-10 mm: X21 moved 4 mm), now sized to sag 0.15-0.4 mm under
#: the session's heaviest part; the wash-down first raised every block by one dT0 (trial + 1: X05 and X14 a gain of 11
#: %, the per-block pattern repeating), now each rinse its own, and its cases (first split by time, which left the last
#: block's rinse unlearnable: gains of -246 %) are split at random, X06 and X18 by time instead; the levelling foot
#: first dropped 0.02-0.08 mm/h (trial + 2: X06 a gain of 11 %), now 0.04-0.12; tool_changer's suction cups 1500-4000
#: N m/rad (trial + 2: X13 a gain of 21 %, the joint model at 1.15x), now 800-2500. No pose count or seed was changed.
#: Trial draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with the final physics: every case labelled its
#: truth in both but X01 (the fanner on ur10, 50 poses) on + 1, absorbed (0.33 mm at its nearest pose, too few poses
#: near the pole); on + 2 X01 gained 7 % (the thermal model at 1.07x: the pole far from the working volume); + 1 one
#: more soft label (X11, the run-in on tool_changer, the transmission model at 1.11x: its loaded axes 2 and 3 rest on
#: one flank, so the opening reads as a slow zero drift). The fanner (its 1 / r^3 pull concentrated on the poses near
#: the pole) is the weakest kind.
SET_X = [
    ("X01", "ur10", ("magnet_fanner",), 50, "random"),
    ("X02", "ur10", ("track_lash",), 110, "random"),
    ("X03", "ur10", ("ring_lobing",), 120, "random"),
    ("X04", "ur10", ("printed_fingers",), 150, "time"),
    ("X05", "ur10", ("washdown",), 160, "random"),
    ("X06", "ur10", ("levelling_foot",), 140, "time"),
    ("X07", "ur10", (), 70, "random"),
    ("X08", "ur10", ("magnet_fanner", "induction_stray"), 180, "random"),
    ("X09", "tool_changer", ("support_arm",), 120, "random"),
    ("X10", "tool_changer", ("cosine_error",), 110, "random"),
    ("X11", "tool_changer", ("run_in_wear",), 150, "time"),
    ("X12", "tool_changer", ("collision_shift",), 140, "random"),
    ("X13", "tool_changer", ("suction_cup",), 130, "random"),
    ("X14", "tool_changer", ("washdown",), 160, "random"),
    ("X15", "tool_changer", (), 30, "random"),
    ("X16", "tool_changer", ("cosine_error", "run_in_wear"), 190, "time"),
    ("X17", "kr16_like", ("support_arm",), 130, "random"),
    ("X18", "kr16_like", ("induction_stray",), 140, "time"),
    ("X19", "kr16_like", ("ring_lobing",), 130, "random"),
    ("X20", "kr16_like", ("collision_shift",), 140, "random"),
    ("X21", "kr16_like", ("printed_fingers",), 150, "time"),
    ("X22", "kr16_like", ("track_lash",), 120, "random"),
    ("X23", "kr16_like", (), 90, "random"),
    ("X24", "kr16_like", ("levelling_foot", "suction_cup"), 200, "random"),
]

#: set Y: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_y`); written as an independent test set after set X, from the literature, without
#: reading how the diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run):
#: every case its truth (gains 31-91 %; each mixture component's removal costs 15 % or more: Y16's frost 15 %, Y08's
#: walk 125 %), the geometry-only cases none; no soft labels (the closest rivals: Y19's joint model 1.26x, Y21's joint
#: model 1.35x, Y03's joint model 1.42x, Y14's joint model 1.44x, Y12's thermal model 1.74x; the smallest gains 31 % on
#: Y14, 40 % on Y21). Changed after trial draws (the modules' docstrings give the final ranges): three first kinds
#: proved, on reading the earlier sets' docstrings, to repeat earlier mechanisms and were replaced -- axis 1's lash
#: swinging with its ring gear's runout (set D's varlash) by the squeeze film, a reducer flange softening past its
#: decompression (set C's bolted flange) by the output brake, the cycloid crankshafts' error (set C's RV error) by the
#: torque arm; the runout lash had first read axis 1's flank from a friction threshold relative to its tiny load in the
#: true (tilted) geometry (Y10 / Y18 absorbed), the flange on tool_changer had the link model at 1.23x. The torque
#: arm first had m 0.3-1 kg, r 10-40 mm, k 300-1500 N m/rad (gains of 2 % or less), now its arm turns 0.8-2.5 arcmin
#: under the encoder's full weight; on tool_changer (Y11) it was ambiguous with the joint and link models at 1.02-1.03x
#: (axes 2 and 3 move over short ranges, so an error in q2 reads as axis 3's gravity twist in q2 + q3), so ur10 (Y03)
#: took it and tool_changer the pinion runout; the output brake first gave 0.3-0.8 times the gear's compliance (up to
#: 1.4 mm), now 0.2-0.5. The vision lamp was first lit in the inspection blocks only, with pauses of 5-15 min between
#: blocks of about 5 min, tau 10-25 min and 2-5 K across the tube: gains of 7 % on ur10, 6 % on tool_changer and 7 %
#: on kr16_like (too short to warm the tube); now the inspection cycle in the production gap before its block lights
#: it too, tau 5-12 min (the wall near the clamp), 3-8 K, and its single case is on tool_changer (Y09; ur10's Y06 took
#: the brake); the frost's pauses were 20-40 min (Y01: a gain of 27 %, the link model at 1.22x), now 40-90 min; the
#: foam pad's design sag 0.05-0.15 mm (Y21: a gain of 21 %, the joint model at 1.14x), now 0.1-0.25 mm; the squeeze
#: film's lash 1-3 arcmin (1.4 mm on tool_changer), now 0.7-2; the tyre's leak tau 20-60 h (1.3 mm on kr16_like), now
#: 30-80 h. No pose count or seed was changed. Trial draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with
#: the final physics: every case labelled its truth in both; soft only on + 2, the torque arm (Y03 on ur10: a gain of
#: 17 %, the link model at 1.16x; Y19 on kr16_like: the link model at 1.20x) -- the weakest kind, an error of a
#: fraction of an arcmin that follows the arm's posture as gravity twists do; on + 1 the closest rival 1.34x (Y14).
SET_Y = [
    ("Y01", "ur10", ("frost_load",), 140, "time"),
    ("Y02", "ur10", ("coupling_play",), 45, "random"),
    ("Y03", "ur10", ("torque_arm",), 120, "random"),
    ("Y04", "ur10", ("tyre_leak",), 150, "time"),
    ("Y05", "ur10", ("foam_gripper",), 130, "random"),
    ("Y06", "ur10", ("output_brake",), 160, "random"),
    ("Y07", "ur10", (), 80, "random"),
    ("Y08", "ur10", ("sheet_part", "press_walk"), 180, "random"),
    ("Y09", "tool_changer", ("vision_lamp",), 120, "random"),
    ("Y10", "tool_changer", ("squeeze_film",), 110, "random"),
    ("Y11", "tool_changer", ("pinion_runout",), 130, "random"),
    ("Y12", "tool_changer", ("press_walk",), 140, "time"),
    ("Y13", "tool_changer", ("sheet_part",), 130, "random"),
    ("Y14", "tool_changer", ("cabinet_exhaust",), 150, "time"),
    ("Y15", "tool_changer", (), 40, "random"),
    ("Y16", "tool_changer", ("frost_load", "coupling_play"), 190, "random"),
    ("Y17", "kr16_like", ("output_brake",), 130, "random"),
    ("Y18", "kr16_like", ("squeeze_film",), 120, "random"),
    ("Y19", "kr16_like", ("torque_arm",), 150, "time"),
    ("Y20", "kr16_like", ("tyre_leak",), 140, "random"),
    ("Y21", "kr16_like", ("foam_gripper",), 130, "random"),
    ("Y22", "kr16_like", ("cabinet_exhaust",), 150, "random"),
    ("Y23", "kr16_like", (), 100, "random"),
    ("Y24", "kr16_like", ("pinion_runout", "vision_lamp"), 200, "time"),
]

#: set Z: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter split
#: by time (:mod:`effects_z`); written as an independent test set after set Y, from the literature, without reading how
#: the diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run): every case its
#: truth (gains 26-93 %; each mixture component's removal costs 27 % or more: Z24's head tilt 27 %, Z08's bowstring 35
#: %), the geometry-only cases none; no soft labels (the closest rivals: Z18's link model 1.30x, Z06's thermal model
#: 1.54x, Z05's mount model 1.58x, Z19's mount model 1.65x, Z24's joint model 1.65x; the smallest gains 26 % on Z18, 37
#: % on Z05). Changed after trial draws (the modules' docstrings give the final ranges): the water slug was first in the
#: hollow upper arm (0.3-1 / 0.6-2 / 2-6 kg: effects of 1-6 um, absorbed on Z01 and on tool_changer's Z11 -- the main
#: axes' gears are too stiff for a mass that size), now in a hollow gripper boom carrying the target, where the soft
#: wrist gears and the boom's lever feel it, and its kr16_like case (Z17) took tool_changer's place; the balancer gas
#: first followed a hall's 6-12 K at 50-90 % of the largest load (Z17 on kr16_like: an effect of 11 um, absorbed -- the
#: gas law moves the force by 3 % at most), now a heavy outdoor machine (tool_changer, Z11) in air changing by 15-25 K,
#: the balancer carrying 70-95 %; the balancer seal's friction 5-15 % (Z18: a gain of 15 %, the transmission model at
#: 1.15x), now 8-20 % (a rod seal's breakaway friction at a robot's low speeds); the warm isolators first softened by
#: 1-3 %/K in 6-12 K on ur10 (Z03: ambiguous with the link model at 1.02x, the beams taking the tilt's constant part;
#: 2-4 %/K and 8-14 K still left it at 1.11x), now 3-6 %/K (a damping compound in its transition region) in 8-14 K on
#: kr16_like (Z21), and ur10's Z03 took the duct lag; the bowstring's design elbow move 0.06-0.15 mm (Z05: a gain of 19
#: %, the mount model at 1.23x), now 0.1-0.25 mm; the stress relief first moved the target by a free 3-D vector in the
#: tool frame (Z06: a gain of 20 %, the thermal model's warm-up of the last link at 1.10x), now the frame's arm bends at
#: its root weld, moving its end across the arm only; the duct lag's sides first lagged 8-20 / 60-150 min with a share
#: of 0.4-0.8 in 6-12 K (Z21 on kr16_like: a gain of 10 %), now 5-15 / 90-240 min, 0.5-0.9, 8-14 K; the oil canning's
#: snap thresholds were first +-M_s about zero (on kr16_like, whose arm stays in front of the base, the plate never
#: snapped on the seed + 2: absorbed), now about the session's mean moment (the plate bedded in under the arm's mean
#: load); the tripod windup 20-50 urad, now 25-60. No pose count or seed was changed. Trial draws on the seed + 1 and +
#: 2 (the case seeds + 1000003 k) with the final physics: 21 and 22 of 24 clean; the misses are the head tilt on
#: tool_changer (Z12: gains of 5 % and 15 %, the thermal and mount models at 1.05x and 1.17x) and on kr16_like (Z19 on +
#: 1: a gain of 11 %), the weakest kind (a reading error of a fraction of an arcmin that follows the base's moment,
#: partly taken by the axis' geometry), and the balancer gas (Z11: a gain of 18 % and the thermal model at 1.06x on + 1,
#: 1.19x on + 2 -- the air drives the uniform expansion too).
SET_Z = [
    ("Z01", "ur10", ("water_slug",), 120, "random"),
    ("Z02", "ur10", ("tripod_windup",), 140, "random"),
    ("Z03", "ur10", ("duct_lag",), 150, "time"),
    ("Z04", "ur10", ("oil_canning",), 130, "random"),
    ("Z05", "ur10", ("bowstring",), 50, "random"),
    ("Z06", "ur10", ("stress_relief",), 150, "time"),
    ("Z07", "ur10", (), 70, "random"),
    ("Z08", "ur10", ("floor_heating", "bowstring"), 180, "random"),
    ("Z09", "tool_changer", ("band_spiral",), 120, "random"),
    ("Z10", "tool_changer", ("balancer_seal",), 130, "random"),
    ("Z11", "tool_changer", ("balancer_gas",), 140, "time"),
    ("Z12", "tool_changer", ("head_tilt",), 130, "random"),
    ("Z13", "tool_changer", ("floor_heating",), 150, "time"),
    ("Z14", "tool_changer", ("duct_lag",), 150, "random"),
    ("Z15", "tool_changer", (), 40, "random"),
    ("Z16", "tool_changer", ("band_spiral", "stress_relief"), 190, "time"),
    ("Z17", "kr16_like", ("water_slug",), 140, "random"),
    ("Z18", "kr16_like", ("balancer_seal",), 120, "random"),
    ("Z19", "kr16_like", ("head_tilt",), 150, "time"),
    ("Z20", "kr16_like", ("oil_canning",), 140, "random"),
    ("Z21", "kr16_like", ("warm_isolators",), 150, "random"),
    ("Z22", "kr16_like", ("tripod_windup",), 130, "random"),
    ("Z23", "kr16_like", (), 100, "random"),
    ("Z24", "kr16_like", ("head_tilt", "duct_lag"), 200, "random"),
]

#: set ZA: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_za`); the first two-letter set (its name sorts after Z; every place keys sets by the
#: name as a string); written as an independent test set after set Z, from the literature, without reading how the
#: diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run): every case its
#: truth (gains 36-86 %; each mixture component's removal costs 20 % or more: ZA16's AC jet 20 %, ZA08's soft fingers 62
#: %), the geometry-only cases none; no soft labels (the closest rivals: ZA09's link model 1.44x, ZA14's mount model
#: 1.45x, ZA20's backlash model 1.51x, ZA05's thermal model 1.54x, ZA18's transmission model 1.55x; the smallest gains
#: 36 % on ZA14, ZA18 and ZA20). Changed after trial draws (the modules' docstrings give the final ranges): the flank
#: stiffness first acted on axes 2 and 3 (2.1-2.3 mm at the tool on ur10 and kr16_like, 4.9 mm and ambiguous with the
#: link model on tool_changer), now on axis 3 alone and only on ur10 (ZA01; kr16_like's axis 3 alone had the link model
#: at 1.10x, its axis 2 alone 1.8 mm); the luff rope's mast first stood for g about 90 deg mid-range with a largest
#: twist of 0.1-0.3 mrad (ZA09: a gain of 14 %, the link model at 1.06x: a lever that hardly changes leaves a twist in
#: proportion to the gravity load), now a short mast (g 50-60 deg) and 0.3-0.6 mrad; the ground thaw first had a frozen
#: tilt of 0.05-0.15 mrad thawing to 1.5-3 times that (ur10's ZA05: the link model at 1.05x; on tool_changer the thermal
#: model at 1.24x and 1.04x -- its heavy boom's mean moment makes the thaw mostly a drift), now 0.03-0.08 mrad plus
#: 0.15-0.35 mrad from the thawed layer (10-50 times softer soil), on ur10 (in the mixture ZA08) and kr16_like (ZA19);
#: the bar's twist 0.1-0.3 mm (gains of 20 % and 16 % on ZA06 and ZA20), now 0.2-0.5 mm (a thinner wall); the soft
#: fingers' kappa 10-40 and pressures 30-100 kPa (tool_changer: the joint model at 1.08x), now 5-20 and 20-120 kPa, and
#: ur10 took the single case (ZA05); the oven door's pulses 2-5 K (gains 24-28 %; on tool_changer, whose forearm is
#: deep, 7-12 % on the trial seeds even at 4-8 K), now 4-8 K and only on kr16_like (ZA17, ZA22), whose forearm tube is
#: its link d4 (body 4: first the 35 mm link a3 was bowed, an effect of 4 um); the tooth skip's tool_changer case was
#: split by time (ZA11: absorbed, the skipped tooth fell in the held-out last quarter -- a step after every training
#: pose cannot be learnt), now random, and tool_changer's time-split single case is the tool recoil (ZA13; the AC jet
#: there gained 21 % with the backlash model at 1.21x, the thaw as above). No pose count or seed was changed. Trial
#: draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with the final physics: every case labelled its truth in
#: both, none absorbed or ambiguous; below the 20 % / 1.25x bar on + 1 the scratch (ZA02, 50 poses: a gain of 17 %, the
#: link model at 1.06x), the bar's twist (ZA06: 15 %, 1.17x) and the luff rope (ZA09: 1.22x), on + 2 the flank stiffness
#: (ZA01: 1.12x), the luff rope (ZA09: 1.19x) and the oven door (ZA17: a gain of 18 %, 1.20x) -- the luff rope the
#: weakest kind (its twist follows the gravity load except near the mast's dead centre).
SET_ZA = [
    ("ZA01", "ur10", ("flank_stiffness",), 130, "random"),
    ("ZA02", "ur10", ("scratch_count",), 50, "random"),
    ("ZA03", "ur10", ("ac_jet",), 150, "time"),
    ("ZA04", "ur10", ("tool_recoil",), 120, "random"),
    ("ZA05", "ur10", ("soft_fingers",), 140, "random"),
    ("ZA06", "ur10", ("offcentre_pick",), 150, "time"),
    ("ZA07", "ur10", (), 70, "random"),
    ("ZA08", "ur10", ("ground_thaw", "soft_fingers"), 180, "random"),
    ("ZA09", "tool_changer", ("luff_rope",), 120, "random"),
    ("ZA10", "tool_changer", ("guide_drag",), 110, "random"),
    ("ZA11", "tool_changer", ("tooth_skip",), 140, "random"),
    ("ZA12", "tool_changer", ("slide_overhang",), 130, "random"),
    ("ZA13", "tool_changer", ("tool_recoil",), 130, "time"),
    ("ZA14", "tool_changer", ("offcentre_pick",), 150, "time"),
    ("ZA15", "tool_changer", (), 40, "random"),
    ("ZA16", "tool_changer", ("guide_drag", "ac_jet"), 190, "time"),
    ("ZA17", "kr16_like", ("oven_door",), 130, "random"),
    ("ZA18", "kr16_like", ("tool_recoil",), 120, "random"),
    ("ZA19", "kr16_like", ("ground_thaw",), 150, "time"),
    ("ZA20", "kr16_like", ("offcentre_pick",), 140, "random"),
    ("ZA21", "kr16_like", ("tooth_skip",), 140, "random"),
    ("ZA22", "kr16_like", ("oven_door",), 150, "random"),
    ("ZA23", "kr16_like", (), 100, "random"),
    ("ZA24", "kr16_like", ("slide_overhang", "scratch_count"), 200, "random"),
]

#: set ZB: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_zb`); written as an independent test set after set ZA, from the literature, without
#: reading how the diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run):
#: every case its truth (gains 32-84 %; each mixture component's removal costs 19 % or more: ZB16's sonotrode 19 %,
#: ZB08's stay cable 57 %), the geometry-only cases none; no soft labels (the closest rivals: ZB06's joint model 1.32x,
#: ZB20's 1.38x, ZB11's transmission model 1.52x, ZB01's thermal model 1.54x; the smallest gains 32 % on ZB06, 36 % on
#: ZB01 and ZB11, 38 % on ZB09). Changed after trial draws (the modules' docstrings give the final ranges): the
#: impedance presets first softened all six axes, s_b 0.3-3 and 0.15-0.4 mm (ZB01: a gain of 19 %, the link model at
#: 1.09x), then s_b 0.2-5 and 0.25-0.6 mm (the link model still at 1.20-1.24x: the main axes' twist under the part looks
#: like a beam's sag), now the wrist alone (compliant-assembly presets); the hose's pull first moved the target 0.1-0.35
#: mm (ZB09: 20 %, the transmission model at 1.25x), now 0.2-0.5 mm (a pressurised package); the nonius encoder first
#: had 16384 or 32768 fine periods on every arm (ZB02: 23 %, the joint model at 1.24x), now 8192 or 16384
#: (tool_changer's larger rings 16384 or 32768: 8192 moved its target 1.9 mm on a trial seed); the notched brake first
#: had 60-120 notches (1.7-1.8 mm at the tool on ZB08 and ZB10), now 150-300 (a face-toothed ring); the mecanum base was
#: first sized by a rough moment rule (1.0 mm at the tool on ZB12), now by the target's move, 0.2-0.6 mm; the welding
#: stack first counted 250 mm and 30-60 K (ZB11: 20 %, the transmission model at 1.24x), now 300 mm (converter and
#: booster) and 40-80 K; the air knife's wall first lagged 2-6 min behind a 15-30 deg curtain at 10-20 K (absorbed on a
#: trial seed), then 0.75-2 min and 25-50 deg (ZB03: 20 %, the link model at 1.23x: the wall followed axis 1 almost at
#: once), now 1-3 min and 20-40 K (the wall's jet side nearly at the jet's temperature); the stay cable's drop 0.15-0.4
#: mm (ZB14: 10 % on a trial seed), now 0.2-0.5 mm. No pose count, arm or seed was changed. Trial draws on the seed + 1
#: and + 2 (the case seeds + 1000003 k) with the final physics: every case labelled its truth in both, none absorbed or
#: ambiguous; below the 20 % / 1.25x bar on + 1 the air knife (ZB03: a gain of 7 %, 1.07x -- few poses in the curtain),
#: the grout void (ZB06: 1.20x) and the stay cable (ZB14: 16 %, 1.15x), on + 2 the hose wrap (ZB09: 6 %, 1.07x -- axis 6
#: seldom beyond the slack) -- the air knife and the hose wrap the weakest kinds (both act on a share of the poses
#: only).
SET_ZB = [
    ("ZB01", "ur10", ("impedance_preset",), 130, "random"),
    ("ZB02", "ur10", ("nonius_slip",), 50, "random"),
    ("ZB03", "ur10", ("air_knife",), 150, "time"),
    ("ZB04", "ur10", ("reversal_pulse",), 120, "random"),
    ("ZB05", "ur10", ("insulating_flange",), 140, "random"),
    ("ZB06", "ur10", ("grout_void",), 150, "time"),
    ("ZB07", "ur10", (), 70, "random"),
    ("ZB08", "ur10", ("stay_cable", "pawl_notch"), 180, "random"),
    ("ZB09", "tool_changer", ("hose_wrap",), 120, "random"),
    ("ZB10", "tool_changer", ("pawl_notch",), 110, "random"),
    ("ZB11", "tool_changer", ("sonotrode",), 140, "random"),
    ("ZB12", "tool_changer", ("mecanum_base",), 130, "random"),
    ("ZB13", "tool_changer", ("fieldbus_rounding",), 130, "time"),
    ("ZB14", "tool_changer", ("stay_cable",), 150, "time"),
    ("ZB15", "tool_changer", (), 40, "random"),
    ("ZB16", "tool_changer", ("nonius_slip", "sonotrode"), 190, "time"),
    ("ZB17", "kr16_like", ("fieldbus_rounding",), 130, "random"),
    ("ZB18", "kr16_like", ("mecanum_base",), 120, "random"),
    ("ZB19", "kr16_like", ("hose_wrap",), 150, "time"),
    ("ZB20", "kr16_like", ("insulating_flange",), 140, "random"),
    ("ZB21", "kr16_like", ("reversal_pulse",), 140, "random"),
    ("ZB22", "kr16_like", ("impedance_preset",), 150, "random"),
    ("ZB23", "kr16_like", (), 100, "random"),
    ("ZB24", "kr16_like", ("air_knife", "hose_wrap"), 200, "random"),
]

#: set ZC: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_zc`); written as an independent test set after set ZB, from the literature, without
#: reading how the diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run):
#: every case its truth (gains 32-84 %; each mixture component's removal costs 56 % or more: ZC08's cure exotherm 56 %,
#: ZC24's coupled wrist 78 %), the geometry-only cases none; no soft labels (the closest rivals: ZC22's joint model
#: 1.27x, ZC18's link model 1.31x, ZC14's mount model 1.59x, ZC17's backlash model 1.76x; the smallest gains 32 % on
#: ZC18, 34 % on ZC22, 37 % on ZC14). Changed after trial draws (the modules' docstrings give the final ranges and the
#: first ones): the hexapod pedestal was first short with equal struts (ZC06 on ur10 ambiguous with the joint and link
#: models at 0.99x), then tall (1.00-1.14x on ur10), then tall with struts softer in tension (a rod end's thread; still
#: 1.11-1.16x on ur10 in two of four draws), now on the heavier arms only (ZC18 on kr16_like); a first mount kind, a
#: base plate on gravel stiffening with the pressure (ZC12 absorbed, ZC18 ambiguous with the link model at 1.01-1.03x: a
#: moment-linear tilt), was replaced by the counterweight base, itself first a counterweight set per block (ZC06, ZC12
#: ambiguous, gains 5-20 %), now a stroke-limited dead zone, its roll centre at the wheels 400-900 mm below the base
#: (first 200-600 mm: ZC22 at 1.25x), on the heavier arms only (ur10 at 1.11x in two of three trial draws: its base
#: moment made by the links whose joints twist); a first link kind, the upper arm bent by its balancer's force (ZC13,
#: ZC22: gains 7-10 %, ambiguous with the transmission model -- a bend following axis 2 alone is a joint-2 error of its
#: angle), was replaced by the floor hose; the exotherm's part first carried the target 300 mm out, bonded 1-3 min
#: before its pick, tau_r 1.5-4 and tau_c 8-20 min (ZC14: 8 %), now 450 mm, 0.5-2 min, 1-3 and 5-12 min (a thin-walled
#: bracket); the crossed bits were first a fixed 0.006-0.02 deg whatever the arm (too much at tool_changer's reach), now
#: the bit that moves the target 0.15-0.4 mm (ZC16's largest move, 1.2 mm, is mostly the pedestal's sink under the arm's
#: constant weight); the coupled wrist moved to kr16_like (ZC17, ZC24), whose wrist motors sit in the forearm (ur10's
#: joints each carry their motor; on tool_changer, ZC09, the link model came within 1.05-1.32x), so ZC08 became the
#: bayonet and the exotherm, ZC09 the spool and ZC17 (first the worm) the coupled wrist. No pose count or seed was
#: changed. Trial draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with the final physics: every case labelled
#: its truth in both, none absorbed or ambiguous; below the 20 % / 1.25x bar on + 1 the spool on tool_changer (ZC09: 27
#: %, the transmission model at 1.21x), on + 2 the cure exotherm on tool_changer (ZC14: a gain of 6 %, 1.07x -- its slow
#: moves leave few poses near a part's peak) -- the exotherm the weakest kind.
SET_ZC = [
    ("ZC01", "ur10", ("spool_tension",), 130, "random"),
    ("ZC02", "ur10", ("swapped_bits",), 50, "random"),
    ("ZC03", "ur10", ("link_convection",), 150, "time"),
    ("ZC04", "ur10", ("bayonet_play",), 120, "random"),
    ("ZC05", "ur10", ("rubber_bush",), 140, "random"),
    ("ZC06", "ur10", ("floor_hose",), 150, "time"),
    ("ZC07", "ur10", (), 70, "random"),
    ("ZC08", "ur10", ("bayonet_play", "cure_exotherm"), 180, "random"),
    ("ZC09", "tool_changer", ("spool_tension",), 120, "random"),
    ("ZC10", "tool_changer", ("air_preload",), 110, "random"),
    ("ZC11", "tool_changer", ("multistart_worm",), 140, "random"),
    ("ZC12", "tool_changer", ("counterweight_base",), 130, "random"),
    ("ZC13", "tool_changer", ("floor_hose",), 130, "time"),
    ("ZC14", "tool_changer", ("cure_exotherm",), 150, "time"),
    ("ZC15", "tool_changer", (), 40, "random"),
    ("ZC16", "tool_changer", ("hexapod_mount", "swapped_bits"), 190, "time"),
    ("ZC17", "kr16_like", ("coupled_wrist",), 130, "random"),
    ("ZC18", "kr16_like", ("hexapod_mount",), 120, "random"),
    ("ZC19", "kr16_like", ("link_convection",), 150, "time"),
    ("ZC20", "kr16_like", ("rubber_bush",), 140, "random"),
    ("ZC21", "kr16_like", ("air_preload",), 140, "random"),
    ("ZC22", "kr16_like", ("counterweight_base",), 150, "random"),
    ("ZC23", "kr16_like", (), 100, "random"),
    ("ZC24", "kr16_like", ("coupled_wrist", "bayonet_play"), 200, "random"),
]

#: set ZD: 12 new kinds (every family, two for each), 3 geometry-only cases, 3 mixtures of two new kinds, a quarter
#: split by time (:mod:`effects_zd`); written as an independent test set after set ZC, from the literature, without
#: reading how the diagnosis models effects. Oracle labels when written (oracle.py only; the diagnosis was not run):
#: every case its truth (gains 28-92 %; each mixture component's removal costs 8 % or more: ZD24's levelling valves 8 %
#: and drive tendons 9 %, ZD08's range shift 214 %, ZD16's gun warm-up 271 %), the geometry-only cases none; no soft
#: labels (the closest rivals: ZD10's backlash model 1.39x, ZD14's link model 1.41x, ZD21's link model 1.42x, ZD01's
#: backlash model 1.42x, ZD02's transmission model 1.43x; the smallest gains 28 % on ZD10, 29 % on ZD01). Changed after
#: trial draws (the modules' docstrings give the final ranges and the first ones): the crosstalk first moved the target
#: 0.15-0.45 mm (ZD02: 18 %, the transmission model at 1.10x), now 0.3-0.6 mm (a compliant joint impedance); the
#: spline drag's play was first 0.1-0.3 mrad whatever the wrist's lever (ZD09: 0.05 mm, 17 %, 1.14x), now sized by its
#: move, 0.15-0.4 mm; the scissor table's heave was first 60-80 % of a 0.3-0.6 mm move (ZD21: the link model at 1.18x,
#: then 1.24x at 75-90 %), now 75-90 % of 0.4-0.8 mm (the table at full height); the booth's flash-off first 10-20 K
#: with 3-10 min pauses (ZD22 on kr16_like: 14 %, 1.14x), now 15-30 K with 5-15 min; the read-heads' eccentricity first
#: moved the target 0.15-0.4 mm (9-15 % on ZD04 and ZD20 in draws on other seeds), now 0.3-0.6 mm; the floating sun was
#: first on ur10 (ZD03: 13 %, the link model at 1.13x; 1.18x at a larger float) and then on tool_changer (ZD14:
#: ambiguous, 10 %; absorbed on the seed + 1 and + 2): ur10's joints are strain-wave gears, and tool_changer's boom axes
#: never unload, so the float stays taken up -- it is on kr16_like alone (ZD19), ZD03 and ZD14 carry the soft float.
#: No pose count or seed was changed. Trial draws on the seed + 1 and + 2 (the case seeds + 1000003 k) with the final
#: physics: every case labelled its truth in both, none absorbed or ambiguous; below the 20 % / 1.25x bar the bake booth
#: on kr16_like (ZD22, + 1: 7 %, the link model at 1.08x -- its thick walls lag a short schedule), the scissor table on
#: kr16_like (ZD21, + 2: the link model at 1.09x) and the soft float on tool_changer (ZD14, + 2: 1.11x) -- the booth the
#: weakest kind.
SET_ZD = [
    ("ZD01", "ur10", ("soft_float",), 130, "random"),
    ("ZD02", "ur10", ("torque_crosstalk",), 120, "random"),
    ("ZD03", "ur10", ("soft_float",), 50, "random"),
    ("ZD04", "ur10", ("readhead_dropout",), 140, "random"),
    ("ZD05", "ur10", ("levelling_valves",), 130, "time"),
    ("ZD06", "ur10", ("bake_booth",), 150, "time"),
    ("ZD07", "ur10", (), 70, "random"),
    ("ZD08", "ur10", ("curing_bond", "range_shift"), 180, "random"),
    ("ZD09", "tool_changer", ("spline_drag",), 120, "random"),
    ("ZD10", "tool_changer", ("range_shift",), 140, "random"),
    ("ZD11", "tool_changer", ("scissor_lift",), 130, "random"),
    ("ZD12", "tool_changer", ("curing_bond",), 150, "time"),
    ("ZD13", "tool_changer", ("gun_warmup",), 150, "time"),
    ("ZD14", "tool_changer", ("soft_float",), 120, "random"),
    ("ZD15", "tool_changer", (), 40, "random"),
    ("ZD16", "tool_changer", ("spline_drag", "gun_warmup"), 190, "random"),
    ("ZD17", "kr16_like", ("drive_tendons",), 130, "random"),
    ("ZD18", "kr16_like", ("torque_crosstalk",), 130, "random"),
    ("ZD19", "kr16_like", ("floating_sun",), 120, "random"),
    ("ZD20", "kr16_like", ("readhead_dropout",), 140, "random"),
    ("ZD21", "kr16_like", ("scissor_lift",), 140, "random"),
    ("ZD22", "kr16_like", ("bake_booth",), 150, "time"),
    ("ZD23", "kr16_like", (), 100, "random"),
    ("ZD24", "kr16_like", ("drive_tendons", "levelling_valves"), 200, "time"),
]

#: Set ZE (seed 40_7031): twelve new kinds, two per family (sim2real_indep.effects_ze; physics and sources in
#: effects_ze_joint, effects_ze_body, effects_ze_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, 6 split by time. Trial draws on the final physics: every effect case labelled its truth (the smallest gains
#: 26 % on ZE06, 36 % on ZE05; the closest rivals ZE06's joint model 1.35x, ZE05's link model 1.56x; a mixture
#: component's removal costs 49 % at least, ZE08's reversal counts), the geometry-only cases none. Changed after trial
#: draws (the modules' docstrings give the first ranges): the ball reducers first on axes 2 and 3 (ZE02: the mount model
#: at 1.06x; ZE18: 1.10x), then 3 and 5 (the link model at 1.12x and 1.19x: axis 3 twists as the forearm bends), now on
#: the wrist axes, whose torques such reducers are rated for; the PCM bracket first 300 mm with a 25-40 K rise (ZE05:
#: 19 %, the joint model at 1.23x), now a 20-40 W head, 450 mm, 30-45 K; the holding heat first 6-20 K through 8-25 min
#: (ZE12: 0.06 mm, 19 %; ZE21 absorbed), now 15-35 K through 5-15 min, and on tool_changer alone (kr16_like's thick
#: steel castings: 11 %, the link model at 1.10x -- ZE21 carries the PCM tool); the slender pedestal first W / W_cr
#: 0.3-0.6 and 0.25-0.6 mm (ZE09 on tool_changer and ZE22 on kr16_like: 8 % and 13 %, ambiguous), then 0.4-0.7 and
#: 0.6-1.0 mm (the link model at 1.11x and 0.99x: under a heavy arm the part hardly changes the column's load, the tilt is
#: a linear one), now under ur10 alone (ZE04, its part up to a quarter of the load; ZE09 carries the disc shift, ZE22
#: the shuttle boom); the tether's anchor first 1.2-1.8 reaches out and 0-1.2 m up (ZE14 on tool_changer: 19 %, the link
#: model at 1.22x), then 1.0-1.4 reaches and 0.5-2 m up, over the fence (ZE14: 11 %, 1.11x: the pull bends
#: tool_changer's long boom as much as it twists its gears), now on ur10 alone (ZE01; ZE14 carries the ringing boom,
#: first on ur10 in ZE04); the slewing ring first also under tool_changer (ZE16 with the PCM tool: its moment hardly
#: turns within axis 1's +-60 deg, the rock stayed taken up and its removal cost nothing), now on kr16_like alone (ZE17;
#: ZE16 mixes the no-back brake and the PCM tool). No pose count or seed was changed. A trial draw on the seed + 1 (the
#: case seeds + 1000003) with the final physics: every case labelled its truth, none absorbed or ambiguous; below the
#: 20 % / 1.25x bar the disc shift on tool_changer (ZE09: 18 %, the mount model at 1.19x) and the holding heat (ZE12:
#: 17 %, the joint model at 1.20x) -- the weakest kinds.
SET_ZE = [
    ("ZE01", "ur10", ("tether_reel",), 130, "random"),
    ("ZE02", "ur10", ("ball_reducer",), 120, "random"),
    ("ZE03", "ur10", ("disc_shift",), 140, "random"),
    ("ZE04", "ur10", ("slender_pedestal",), 120, "random"),
    ("ZE05", "ur10", ("pcm_tool",), 150, "time"),
    ("ZE06", "ur10", ("rotary_clamp",), 50, "random"),
    ("ZE07", "ur10", (), 70, "random"),
    ("ZE08", "ur10", ("shuttle_boom", "reversal_counts"), 180, "random"),
    ("ZE09", "tool_changer", ("disc_shift",), 130, "random"),
    ("ZE10", "tool_changer", ("noback_brake",), 120, "random"),
    ("ZE11", "tool_changer", ("shuttle_boom",), 140, "random"),
    ("ZE12", "tool_changer", ("holding_heat",), 160, "time"),
    ("ZE13", "tool_changer", ("reversal_counts",), 150, "time"),
    ("ZE14", "tool_changer", ("ringing_boom",), 120, "random"),
    ("ZE15", "tool_changer", (), 40, "random"),
    ("ZE16", "tool_changer", ("noback_brake", "pcm_tool"), 190, "time"),
    ("ZE17", "kr16_like", ("slewing_rock",), 130, "random"),
    ("ZE18", "kr16_like", ("ball_reducer",), 130, "random"),
    ("ZE19", "kr16_like", ("noback_brake",), 120, "random"),
    ("ZE20", "kr16_like", ("disc_shift",), 140, "random"),
    ("ZE21", "kr16_like", ("pcm_tool",), 160, "time"),
    ("ZE22", "kr16_like", ("shuttle_boom",), 140, "random"),
    ("ZE23", "kr16_like", (), 100, "random"),
    ("ZE24", "kr16_like", ("rotary_clamp", "ringing_boom"), 200, "time"),
]

#: Set ZF (seed 40_7032): twelve new kinds, two per family (sim2real_indep.effects_zf; physics and sources in
#: effects_zf_joint, effects_zf_body, effects_zf_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Every effect case is labelled its truth by the oracle (gains 21 % on ZF05 to 93 %
#: on ZF12; the closest rivals ZF05's mount model at 1.27x, ZF01's link model at 1.31x; a mixture component's removal
#: costs 28 % at least, ZF16's shelf bracket), the geometry-only cases none. Changed after trial draws (the modules'
#: docstrings give the first ranges): the centring spring first held the output across 20-40 % of the largest torque
#: (ZF02 and ZF17: the joint model at 1.07x and 1.08x -- a spring that stiff is a compliance), now 5-12 % (a soft
#: spring); the repaired sector first 6-15 deg wide (ZF03: a gain of 9.5 %, few poses in it), now 12-25 deg (4-8 teeth);
#: the Peltier loop first swung with a 12-30 min period and zeta 0.1-0.3 (ZF05 absorbed, 2.9 %: settled before the
#: held-out last quarter), now 20-40 min and 0.05-0.15 (a loosely tuned loop); the bungee cord first also on kr16_like
#: (ZF19: the link model at 1.08x, its near-vertical pull bending the long arm as gravity does), now on ur10 and
#: tool_changer (ZF11; ZF19 carries the viscous crossing); the sagging disc first also on tool_changer (ZF11: the joint
#: model at 1.17x, its axis-5 housing's attitude following the wrist's torque), now on kr16_like alone (ZF18). No seed was
#: changed and no pose count to fix a label; ZF22 was first drawn with 120 poses (labelled its truth, 90 %) and set to 50
#: for the layout's short effect case (46.7 %, the thermal model at 1.86x).
SET_ZF = [
    ("ZF01", "ur10", ("bungee_cord",), 130, "random"),
    ("ZF02", "ur10", ("centring_spring",), 120, "random"),
    ("ZF03", "ur10", ("repaired_sector",), 140, "random"),
    ("ZF04", "ur10", ("shelf_bracket",), 120, "random"),
    ("ZF05", "ur10", ("peltier_loop",), 150, "time"),
    ("ZF06", "ur10", ("flange_gapping",), 110, "random"),
    ("ZF07", "ur10", (), 60, "random"),
    ("ZF08", "ur10", ("viscous_crossing", "marking_pulses"), 180, "time"),
    ("ZF09", "tool_changer", ("warm_preload",), 160, "time"),
    ("ZF10", "tool_changer", ("viscous_crossing",), 120, "random"),
    ("ZF11", "tool_changer", ("bungee_cord",), 130, "random"),
    ("ZF12", "tool_changer", ("shim_friction",), 140, "random"),
    ("ZF13", "tool_changer", ("polymer_boom",), 150, "random"),
    ("ZF14", "tool_changer", ("marking_pulses",), 150, "time"),
    ("ZF15", "tool_changer", (), 40, "random"),
    ("ZF16", "tool_changer", ("shelf_bracket", "repaired_sector"), 190, "random"),
    ("ZF17", "kr16_like", ("centring_spring",), 120, "random"),
    ("ZF18", "kr16_like", ("sagging_disc",), 130, "random"),
    ("ZF19", "kr16_like", ("viscous_crossing",), 130, "random"),
    ("ZF20", "kr16_like", ("shim_friction",), 140, "random"),
    ("ZF21", "kr16_like", ("peltier_loop",), 160, "time"),
    ("ZF22", "kr16_like", ("flange_gapping",), 50, "random"),
    ("ZF23", "kr16_like", (), 90, "random"),
    ("ZF24", "kr16_like", ("warm_preload", "polymer_boom"), 200, "time"),
]

#: Set ZG (seed 40_7033): twelve new kinds, two per family (sim2real_indep.effects_zg; physics and sources in
#: effects_zg_joint, effects_zg_body, effects_zg_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 22 % on ZG18 to 90 % on ZG08; the closest rivals ZG17's transmission model and ZG18's thermal
#: model, both at 1.27x; a mixture component's removal costs 32 % at least, ZG16's drying film), the geometry-only
#: cases none. Changed after trial draws (the modules' docstrings give the first ranges): the bolts' relaxation first
#: grew the compliance by beta 0.2-0.5 of a near-isotropic C (ZG22 absorbed, 4.6 %: an isotropic tilt following the
#: moment turns the arm in its own plane as a joint-2 offset does), now 0.8-1.5 (a plate embedding into a soft pad) and
#: an anisotropic C (one bolt row relaxing); on tool_changer it stayed at 20-32 % with the thermal model at 1.14-1.21x
#: (its moment varies little, so the growth is a near-uniform drift in time), so it moved to ur10 (ZG08, with the coast
#: flank) and tool_changer took the settlement (ZG09); the taut harness first pulled linearly past the 70-85 % quantile
#: of axis 1 (ZG17: the transmission model at 1.15x -- a long ramp over +-90 deg is nearly a sine), now progressively
#: ((q - q_t)^2, a straightening catenary) past the 80-90 % quantile; the chipped pinion first spanned 1.3-1.8
#: pitches of a 12-17-tooth pinion (ZG18: 17 %, the thermal model at 1.19x), now 1.5-2 pitches of a 9-12-tooth
#: one. Two kinds were replaced before any label counted, for novelty: a PA6 bracket's moisture swelling (the name and
#: mechanism of set V's moisture_swell, which the generator's registry would have overwritten: V06 and V21 changed) by
#: the rotary union, and a segmented ring gear (set V's rack segments on a rotary axis) by the chipped pinion. No seed
#: or pose count was changed. A trial on the seed + 1 (case seeds + 1000003): below the 20 % / 1.25x bar the taut
#: harness on ur10 (ZG02, 11 %), the bolts' relaxation on kr16_like (ZG22, 16 %, the joint model at 1.14x) and the
#: payload mismatch on tool_changer (ZG14, the link model at 1.17x) -- the weakest kinds.
SET_ZG = [
    ("ZG01", "ur10", ("gravcomp_payload",), 130, "random"),
    ("ZG02", "ur10", ("taut_harness",), 120, "random"),
    ("ZG03", "ur10", ("chipped_pinion",), 140, "random"),
    ("ZG04", "ur10", ("leaf_boom",), 120, "random"),
    ("ZG05", "ur10", ("drying_film",), 150, "time"),
    ("ZG06", "ur10", ("tilt_flank",), 50, "random"),
    ("ZG07", "ur10", (), 60, "random"),
    ("ZG08", "ur10", ("coast_flank", "bolt_relaxation"), 180, "time"),
    ("ZG09", "tool_changer", ("settlement_tilt",), 160, "time"),
    ("ZG10", "tool_changer", ("coast_flank",), 120, "random"),
    ("ZG11", "tool_changer", ("beam_column",), 140, "random"),
    ("ZG12", "tool_changer", ("missing_pin",), 140, "random"),
    ("ZG13", "tool_changer", ("rotary_union",), 150, "time"),
    ("ZG14", "tool_changer", ("gravcomp_payload",), 150, "random"),
    ("ZG15", "tool_changer", (), 40, "random"),
    ("ZG16", "tool_changer", ("tilt_flank", "drying_film"), 190, "random"),
    ("ZG17", "kr16_like", ("taut_harness",), 130, "random"),
    ("ZG18", "kr16_like", ("chipped_pinion",), 130, "random"),
    ("ZG19", "kr16_like", ("missing_pin",), 130, "random"),
    ("ZG20", "kr16_like", ("settlement_tilt",), 160, "time"),
    ("ZG21", "kr16_like", ("beam_column",), 140, "random"),
    ("ZG22", "kr16_like", ("bolt_relaxation",), 120, "random"),
    ("ZG23", "kr16_like", (), 100, "random"),
    ("ZG24", "kr16_like", ("gravcomp_payload", "rotary_union"), 200, "time"),
]

#: Set ZH (seed 40_7034): twelve new kinds, two per family (sim2real_indep.effects_zh; physics and sources in
#: effects_zh_joint, effects_zh_body, effects_zh_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 24 % on ZH13 and 25 % on ZH01 to 90 % on ZH18; the closest rivals ZH01's backlash model at
#: 1.27x and ZH13's at 1.30x; a mixture component's removal costs 5.5 % at least, ZH08's regen resistor, then ZH16's
#: wrist conduction at 7.8 %), the geometry-only cases none. Changed after trial draws (the modules' docstrings give the
#: first ranges): the Brazier pedestal first bent by the arm's moment alone ((M_max / M_b)^2 0.3-0.8, H 1-2 m; ZH03 on
#: ur10 the link model at 1.09x, on kr16_like absorbed, 2.1 % -- a tube bent only by the arm tilts nearly linearly
#: along the moment, as an arm's sag or a joint-2 offset turns it), now a riser also carrying a side console's bias
#: moment (1-2x the arm's), whose pre-ovalised tube is softer along the bias than across it, and on ur10 alone (ZH18
#: takes the loose pivot); the dished plate first turned about the base itself and sank under the arm's whole weight
#: (ZH09 and ZH20 absorbed, 2.0 % and 4.8 %: the constant sink, part of the calibrated geometry, took the sizing), now
#: sinking under the weight's change and turning about its mid-plane under a 300-800 mm riser; on kr16_like it was then
#: ambiguous (the link model at 1.03x: its moment-driven turn reads as the long arm's bending), so it stays on
#: tool_changer (ZH09) and ZH20 takes the grease gel; the cracked tooth first also on kr16_like (ZH17: 11 %, the
#: thermal model at 1.13x -- its axis-3 loads are small where the tooth meshes), now on tool_changer alone (ZH14; ZH17
#: takes the inflated boom); the wrist conduction's flange first 15-40 K above the air (ZH16: its removal cost 3.3 %),
#: now 30-60 K (a hot-knife or hot-melt head). No seed or pose count was changed. Two kinds were dropped before any
#: draw, for novelty: a sensor-zeroing error of a force-controlled arm (its tool-frame part is a target
#: offset, the rest set K's compliant wrist, the RCC) and a fan jet's push (set N's wind on a panel).
SET_ZH = [
    ("ZH01", "ur10", ("worn_mesh",), 130, "random"),
    ("ZH02", "ur10", ("pinion_handover",), 120, "random"),
    ("ZH03", "ur10", ("brazier_pedestal",), 140, "random"),
    ("ZH04", "ur10", ("inflated_boom",), 120, "random"),
    ("ZH05", "ur10", ("wrist_conduction",), 150, "time"),
    ("ZH06", "ur10", ("loose_pivot",), 50, "random"),
    ("ZH07", "ur10", (), 60, "random"),
    ("ZH08", "ur10", ("grease_gel", "regen_resistor"), 180, "time"),
    ("ZH09", "tool_changer", ("dished_plate",), 160, "time"),
    ("ZH10", "tool_changer", ("grease_gel",), 120, "random"),
    ("ZH11", "tool_changer", ("collet_root",), 140, "random"),
    ("ZH12", "tool_changer", ("running_in_te",), 140, "random"),
    ("ZH13", "tool_changer", ("regen_resistor",), 150, "time"),
    ("ZH14", "tool_changer", ("tooth_crack",), 150, "random"),
    ("ZH15", "tool_changer", (), 40, "random"),
    ("ZH16", "tool_changer", ("loose_pivot", "wrist_conduction"), 190, "random"),
    ("ZH17", "kr16_like", ("inflated_boom",), 130, "random"),
    ("ZH18", "kr16_like", ("loose_pivot",), 130, "random"),
    ("ZH19", "kr16_like", ("pinion_handover",), 130, "random"),
    ("ZH20", "kr16_like", ("grease_gel",), 160, "time"),
    ("ZH21", "kr16_like", ("collet_root",), 140, "random"),
    ("ZH22", "kr16_like", ("worn_mesh",), 120, "random"),
    ("ZH23", "kr16_like", (), 100, "random"),
    ("ZH24", "kr16_like", ("running_in_te", "inflated_boom"), 200, "time"),
]

#: Set ZI (seed 40_7035): twelve new kinds, two per family (sim2real_indep.effects_zi; physics and sources in
#: effects_zi_joint, effects_zi_body, effects_zi_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 25 % on ZI20 and 29 % on ZI05 to 92 % on ZI18; the closest rivals ZI20's link model at 1.32x,
#: ZI04's transmission model at 1.64x and ZI05's backlash model at 1.42x; a mixture component's removal costs 16 % at
#: least, ZI16's PI load step, then ZI24's cage runout at 24 %), the geometry-only cases none. Changed after trial
#: draws (the modules' docstrings give the first ranges): the helix tilt first also on tool_changer (ZI09 absorbed,
#: 3.8 %: on the planar arm a tilt with tau2 about an axis fixed in the housing reads as a constant tilt of axis 2),
#: now on kr16_like alone (ZI17, ZI24; ZI24 first held the jamming grip with the cage runout); the cage runout then
#: tried on tool_changer (ZI09 absorbed, 2.4 %: over axis 1's +-60 deg a sine at the cage's rate is nearly a line), so
#: ZI09 took the jamming grip, ZI06 (first the Bernoulli grip, which moved to tool_changer's ZI12) the jamming grip;
#: the crowned sole first rocked about the moment's own axis under a heavier pedestal (ZI11 on tool_changer the link
#: model at 1.07x, ZI22 on kr16_like ambiguous, 5.3 %: a tilt along the moment turns the arm in its plane as the
#: joints' and links' compliance do; a 1-1.8 m riser did not help), now a sole bowed along its length rocking about
#: one axis, on ur10 (ZI04, first the free swivel, now ZI11) and kr16_like; the thermosyphon first on tool_changer's
#: steel forearm (ZI13 absorbed, 2.4 %; ZI13 now the dog play with a time split) and on kr16_like with r 2-5 and 15-35 K
#: (ZI20 16.8 % as a time split), now on the aluminium arms with r 3-8, 25-45 K and pauses of 20-60 min; ZI20 keeps
#: the random split of the slot it took over (the dog play's; as a time split it scores 20.9 %, the backlash model at
#: 1.24x); the motion cooling first warmed the upper arm alone, 10-25 K from a start 30-80 % warm (ZI05 14.5 %, the link
#: model at 1.18x; with production alone between the blocks 0.3-23 % on ur10), now the upper arm and forearm, 15-35 K
#: from a start 0-50 % warm, production or pauses between the blocks. No seed or pose count was changed. A trial on
#: the seed + 1 (case seeds + 1000003): 21 of 24 at the 20 % / 1.25x bar; below it the crowned sole on ur10 (ZI04,
#: 19.5 %, the transmission model at 1.21x) and the motion cooling (ZI05 absorbed, 1.0 %; ZI21 absorbed, 4.1 %) --
#: the weakest kinds.
SET_ZI = [
    ("ZI01", "ur10", ("pi_load_step",), 130, "random"),
    ("ZI02", "ur10", ("dog_play",), 120, "random"),
    ("ZI03", "ur10", ("cage_runout",), 140, "random"),
    ("ZI04", "ur10", ("crowned_sole",), 120, "random"),
    ("ZI05", "ur10", ("motion_cooling",), 150, "time"),
    ("ZI06", "ur10", ("jamming_grip",), 50, "random"),
    ("ZI07", "ur10", (), 60, "random"),
    ("ZI08", "ur10", ("gravel_ratchet", "thermosyphon"), 180, "time"),
    ("ZI09", "tool_changer", ("jamming_grip",), 140, "random"),
    ("ZI10", "tool_changer", ("flank_profile",), 120, "random"),
    ("ZI11", "tool_changer", ("free_swivel",), 140, "random"),
    ("ZI12", "tool_changer", ("bernoulli_grip",), 140, "random"),
    ("ZI13", "tool_changer", ("dog_play",), 150, "time"),
    ("ZI14", "tool_changer", ("gravel_ratchet",), 150, "time"),
    ("ZI15", "tool_changer", (), 40, "random"),
    ("ZI16", "tool_changer", ("pi_load_step", "free_swivel"), 190, "random"),
    ("ZI17", "kr16_like", ("helix_tilt",), 130, "random"),
    ("ZI18", "kr16_like", ("flank_profile",), 130, "random"),
    ("ZI19", "kr16_like", ("bernoulli_grip",), 130, "random"),
    ("ZI20", "kr16_like", ("thermosyphon",), 160, "random"),
    ("ZI21", "kr16_like", ("motion_cooling",), 140, "time"),
    ("ZI22", "kr16_like", ("crowned_sole",), 120, "random"),
    ("ZI23", "kr16_like", (), 100, "random"),
    ("ZI24", "kr16_like", ("helix_tilt", "cage_runout"), 200, "time"),
]

#: Set ZJ (seed 40_7036): twelve new kinds, two per family (sim2real_indep.effects_zj; physics and sources in
#: effects_zj_joint, effects_zj_body, effects_zj_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every
#: effect case its truth (gains 29 % on ZJ01 and 37 % on ZJ13 to 88 % on ZJ08; the closest rivals ZJ01's thermal
#: model at 1.42x, ZJ20's transmission model at 1.53x, ZJ02's backlash model at 1.55x and ZJ13's mount model at
#: 1.59x; a mixture component's removal costs 71 % at least, ZJ16's hydrostatic rail), the geometry-only cases none.
#: Changed after trial draws (the modules' docstrings give the first forms): the clay pier first a single pier
#: turning about the moment's own axis (ZJ20 on kr16_like ambiguous with the link model at 1.04x, 10.5 %; ZJ10 on
#: tool_changer the link model at 1.17x: a turn along the moment bends the arm's plane as the links' compliance
#: does), now a pair of piers turning about the line through them; the plume bracket first on tool_changer (ZJ14
#: absorbed, 0.3 %: its tool's z points up or sideways over its range, so the plume never reaches the bracket), so
#: ZJ14 took the gecko pad and the bracket moved to kr16_like's ZJ21, where a 3-5 mm bracket of tau_b 3-8 min
#: averaged the attitudes away (0.04 mm, absorbed), then at 1.5-4 min gained 11 % (the link model at 1.10x), then as
#: a folded 1-1.5 mm sheet of 20-60 s 23 % with the link model at 1.24x; so the bracket went to ur10 (ZJ06, time
#: split) and kr16_like's ZJ21 took ur10's warm sag (random split); the traction drives' twist at gross slip first
#: drawn per axis (axis 6's, carrying next to no load, then reached 7-15e-3 rad), now one twist for the wrist's
#: drives (labels unchanged). No seed or pose count was changed. Two kinds were dropped before any draw, for novelty:
#: a pendulum inclinometer held by its pivot's friction (set ZI's free swivel's friction pendulum) and a revolute
#: joint's axial end play carrying the arm along the axis (set G's axial float, the same play and chooser). A trial
#: on the seed + 1 (case seeds + 1000003): 21 of 24 at the 20 % / 1.25x bar; below it the stray welding current on
#: tool_changer (ZJ13, 5.4 %, 0.04 mm: a steel arm's short housings), the plume bracket on ur10 (ZJ06, 14.8 %, the
#: joint model at 1.14x) and the clay piers on kr16_like (ZJ20, 20.5 %, the transmission model at 1.25x) -- the
#: weakest kinds.
SET_ZJ = [
    ("ZJ01", "ur10", ("gauge_zero_drift",), 150, "time"),
    ("ZJ02", "ur10", ("traction_microslip",), 130, "random"),
    ("ZJ03", "ur10", ("gyro_filter",), 50, "random"),
    ("ZJ04", "ur10", ("hydrostatic_rail",), 120, "random"),
    ("ZJ05", "ur10", ("gecko_pad",), 140, "random"),
    ("ZJ06", "ur10", ("plume_bracket",), 130, "time"),
    ("ZJ07", "ur10", (), 60, "random"),
    ("ZJ08", "ur10", ("plume_bracket", "stepper_stall"), 180, "time"),
    ("ZJ09", "tool_changer", ("ghost_order",), 120, "random"),
    ("ZJ10", "tool_changer", ("clay_pier",), 140, "random"),
    ("ZJ11", "tool_changer", ("warm_sag",), 140, "random"),
    ("ZJ12", "tool_changer", ("wind_flank",), 120, "random"),
    ("ZJ13", "tool_changer", ("stray_weld_current",), 150, "time"),
    ("ZJ14", "tool_changer", ("gecko_pad",), 160, "random"),
    ("ZJ15", "tool_changer", (), 40, "random"),
    ("ZJ16", "tool_changer", ("hydrostatic_rail", "gyro_filter"), 190, "random"),
    ("ZJ17", "kr16_like", ("gauge_zero_drift",), 160, "time"),
    ("ZJ18", "kr16_like", ("stepper_stall",), 130, "random"),
    ("ZJ19", "kr16_like", ("ghost_order",), 130, "random"),
    ("ZJ20", "kr16_like", ("clay_pier",), 120, "random"),
    ("ZJ21", "kr16_like", ("warm_sag",), 140, "random"),
    ("ZJ22", "kr16_like", ("wind_flank",), 130, "random"),
    ("ZJ23", "kr16_like", (), 100, "random"),
    ("ZJ24", "kr16_like", ("stray_weld_current", "traction_microslip"), 200, "time"),
]

#: Set ZK (seed 40_7037): twelve new kinds, two per family (sim2real_indep.effects_zk; physics and sources in
#: effects_zk_joint, effects_zk_body, effects_zk_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every
#: effect case its truth (gains 24 % on ZK13 and 41 % on ZK17 to 93 % on ZK05; the closest rivals ZK13's backlash model
#: at 1.32x, ZK01's link model at 1.42x, ZK11's link model at 1.45x and ZK04's transmission model at 1.65x; a mixture
#: component's removal costs 52 % at least, ZK08's drive boards), the geometry-only cases none. Changed after trial
#: draws (the modules' docstrings give the first forms): the capstan spans first on ur10's axes 2 and 3 with a centred
#: sector (ZK02 ambiguous with the link model at 1.04x), then with the sector's centre shifted and its spans nearly
#: wound off at one end (1.06x: on ur10 the upper arm's and forearm's joint compliance bends the arm as its tubes'
#: bending does), now on the wrist axes 4 and 5, whose short links the link model does not bend; the beam torsion
#: first under the sessions' own payload schedule on tool_changer (ZK11, 7.8 %, the link model at 1.08x) and kr16_like
#: (ZK21, 19.8 %, the transmission model at 1.22x; with parts per block 19.3 % at 1.11x: over axis 1's +-60 / +-90 deg
#: the moment about the beam's fixed line changes little beyond the mean the base's tilt absorbs), now with a part per
#: block on tool_changer and on ur10 (ZK04, first the asphalt creep; its axis 1 turns the moment through +-170 deg),
#: the asphalt creep moved to tool_changer's ZK14 (first the magnets' warming; its time split kept) and kr16_like's ZK21
#: took the magnets' warming (its random split kept); the ride height first in kr16_like's mixture ZK24 with the housing
#: spread (its removal cost 3.2 %: a 0-16 kg part opens the gap little next to the arm's weight, in a noisy case), so
#: ZK24 took the ring gear's ovality and ZK19 (first the ovality) the ride height. No seed or pose count was changed.
#: Six kinds were dropped before any draw: a polymer gear's lash shrinking as it takes up the hall's moisture (the
#: teeth's diffusion time is days: nothing changes within a session), a fresh concrete plinth bowed by its hydration
#: heat (some 0.04 mm of tilt drift over a session), a switchable magnet base (set P's vacuum feet: a hold-down preload
#: and a contact law), a blocked pneumatic cylinder holding the part (at realistic loads a linear air spring: set ZD's
#: soft float), a bevel wheel's axial runout (once per turn: set A's gear) and nested wrist shafts' drag choosing axis
#: 4's flank (synchronised point-to-point moves end together, leaving no drag). A trial on the seed + 1 (case seeds +
#: 1000003): every effect case its truth, 23 of 24 at the 20 % / 1.25x bar; below it the capstan spans (ZK02, 29.9 %,
#: the backlash model at 1.21x) -- the weakest kind; the ram wipers (ZK13, 24 %, 1.30x) next.
SET_ZK = [
    ("ZK01", "ur10", ("kt_magnet_drift",), 150, "time"),
    ("ZK02", "ur10", ("capstan_spans",), 130, "random"),
    ("ZK03", "ur10", ("sensor_hysteresis",), 140, "random"),
    ("ZK04", "ur10", ("beam_torsion",), 150, "time"),
    ("ZK05", "ur10", ("dashpot_slide",), 40, "random"),
    ("ZK06", "ur10", ("drive_board_heat",), 150, "time"),
    ("ZK07", "ur10", (), 60, "random"),
    ("ZK08", "ur10", ("capstan_spans", "drive_board_heat"), 180, "random"),
    ("ZK09", "tool_changer", ("quench_ovality",), 120, "random"),
    ("ZK10", "tool_changer", ("housing_spread",), 140, "random"),
    ("ZK11", "tool_changer", ("beam_torsion",), 140, "random"),
    ("ZK12", "tool_changer", ("flange_buckling",), 140, "random"),
    ("ZK13", "tool_changer", ("ram_wiper_heat",), 150, "time"),
    ("ZK14", "tool_changer", ("asphalt_creep",), 160, "time"),
    ("ZK15", "tool_changer", (), 40, "random"),
    ("ZK16", "tool_changer", ("ram_wiper_heat", "dashpot_slide"), 190, "random"),
    ("ZK17", "kr16_like", ("ride_height",), 130, "random"),
    ("ZK18", "kr16_like", ("sensor_hysteresis",), 130, "random"),
    ("ZK19", "kr16_like", ("ride_height",), 130, "random"),
    ("ZK20", "kr16_like", ("asphalt_creep",), 140, "random"),
    ("ZK21", "kr16_like", ("kt_magnet_drift",), 140, "random"),
    ("ZK22", "kr16_like", ("flange_buckling",), 130, "random"),
    ("ZK23", "kr16_like", (), 100, "random"),
    ("ZK24", "kr16_like", ("housing_spread", "quench_ovality"), 200, "time"),
]

#: Set ZL (seed 40_7038): twelve new kinds, two per family (sim2real_indep.effects_zl; physics and sources in
#: effects_zl_joint, effects_zl_body, effects_zl_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every
#: effect case its truth (gains 46.9 % on ZL06 and 48.4 % on ZL18 to 91.1 % on ZL09; the closest rivals ZL06's link
#: model at 1.38x, ZL02's backlash model at 1.70x, ZL18's at 1.78x, ZL11's transmission model at 1.84x and ZL03's
#: joint model at 1.85x); a mixture component's removal
#: costs 67 % at least (ZL24's load cells), the geometry-only cases none. Changed after trial draws (the modules'
#: docstrings give the first forms): the arc radiation first with production or pauses between its blocks at random
#: (ur10's first ZL06: a single production gap, in the last, time-split block -- absorbed), now a welding cell's
#: production between all blocks; its ur10 case dropped in the re-layout below, kr16_like's ZL22 kept. The helical
#: pinions' preload release (axes 2 and 3) absorbed on tool_changer (first ZL09, 1.2 %: over its boom's short ranges
#: the gravity twist is the zero offsets') and ambiguous with the link model on kr16_like (first ZL18, 1.07-1.08x with a
#: release at 30-70 % and at 15-35 % of the largest torque, and on axis 3 alone in trials: a nearly linear twist of the
#: main axes is the long links' bending): replaced by the wrist motors' torque-constant saturation (kt_saturation, ZL18
#: and the mixture ZL16). Inclined chevron mounts (their elastic centre above the base) ambiguous with the joint model
#: at 1.01-1.02x on tool_changer (first ZL13), ur10 and kr16_like, and at 1.24x on ur10 with steep mounts (a tilt about
#: a point near the shoulder is axis 2's compliance): replaced by a weighing platform's load cells (load_cells), first
#: on a square (ur10's ZL06 with the link model at 1.09x), then a pallet rectangle with a new part per block (1.19x: the
#: platform's sink under the part is the tubes' bending under it), now with the session's one part. The raised floor
#: first on tool_changer (first ZL12, 8.3 %, ambiguous: its axis 1 turns the moment over +-60 deg only) and kr16_like
#: (first ZL21, the joint model at 1.21x), now on ur10 (ZL04); the current remanence on tool_changer (first ZL12,
#: 11.1 %: its slow boom's acceleration currents rarely pass the core's coercive level), now only on ur10 (ZL03, ZL08);
#: tool_changer took the stator leakage (ZL09), the step truncation (ZL12) and the idle current (ZL13), kr16_like the
#: stator leakage (ZL21). No seed or pose count was changed. A trial on the seed + 1 (case seeds + 1000003): every
#: effect case its truth or its truth with a near rival, 19 of 21 at the 20 % / 1.25x bar; below it the raised floor
#: (ZL04, 14.5 %, the joint model at 1.07x) and the idle current on tool_changer (ZL13, ambiguous with the link model
#: at 1.02x: its one stepper bend, axis 5, under a 10-60 kg part) -- the weakest kinds; the step truncation on
#: tool_changer (ZL12, 24 %, 1.30x) and the load cells (ZL06, 1.30x) next.
SET_ZL = [
    ("ZL01", "ur10", ("thermal_ratchet",), 150, "time"),
    ("ZL02", "ur10", ("idle_current",), 130, "random"),
    ("ZL03", "ur10", ("current_remanence",), 140, "time"),
    ("ZL04", "ur10", ("raised_floor",), 120, "random"),
    ("ZL05", "ur10", ("pad_pivot",), 40, "random"),
    ("ZL06", "ur10", ("load_cells",), 150, "random"),
    ("ZL07", "ur10", (), 60, "random"),
    ("ZL08", "ur10", ("thermal_ratchet", "current_remanence"), 180, "time"),
    ("ZL09", "tool_changer", ("stator_leakage",), 120, "random"),
    ("ZL10", "tool_changer", ("hose_bourdon",), 140, "random"),
    ("ZL11", "tool_changer", ("ft_sensor",), 140, "random"),
    ("ZL12", "tool_changer", ("step_truncation",), 140, "random"),
    ("ZL13", "tool_changer", ("idle_current",), 150, "random"),
    ("ZL14", "tool_changer", ("pad_pivot",), 160, "random"),
    ("ZL15", "tool_changer", (), 40, "random"),
    ("ZL16", "tool_changer", ("ft_sensor", "kt_saturation"), 190, "random"),
    ("ZL17", "kr16_like", ("step_truncation",), 160, "time"),
    ("ZL18", "kr16_like", ("kt_saturation",), 130, "random"),
    ("ZL19", "kr16_like", ("idle_current",), 130, "random"),
    ("ZL20", "kr16_like", ("hose_bourdon",), 120, "random"),
    ("ZL21", "kr16_like", ("stator_leakage",), 140, "random"),
    ("ZL22", "kr16_like", ("arc_radiation",), 130, "time"),
    ("ZL23", "kr16_like", (), 100, "random"),
    ("ZL24", "kr16_like", ("load_cells", "step_truncation"), 200, "time"),
]

#: Set ZM (seed 40_7039): twelve new kinds, two per family (sim2real_indep.effects_zm; physics and sources in
#: effects_zm_joint, effects_zm_body, effects_zm_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 30.1 % on ZM06, 31.2 % on ZM12, 33.6 % on ZM19 and 33.9 % on ZM08 to 95.7 % on ZM18; the
#: closest rivals ZM12's transmission model at 1.29x, ZM09's link model at 1.36x, ZM06's joint model at 1.42x and ZM19's
#: thermal model at 1.48x); a mixture component's removal costs 25 % at least (ZM08's microstep error), the
#: geometry-only cases none. Changed after trial draws (the modules' docstrings give the first forms): the mesh ripple
#: first on tool_changer (ZM11 ambiguous with the link model at 1.11x: its axis 5 under a 120 kg end-effector twists
#: almost in proportion to the load, as the boom bends), now on ur10 in trials and kr16_like (ZM20); the cone mounts first
#: on a near-square frame with softer cones (ur10's ZM04, the joint model at 1.12x: a tilt along the moment just below
#: the shoulder is axis 2's compliance), now a narrow stand; the step accuracy first with the better motors' 1-3 % / 1-2
#: % behind N_g 2-4 (ZM19, 8.7 %: 0.07 mm against 0.04 mm of noise), now the catalogue's +-5 % class behind a belt stage
#: of 1.5-3; the radiant envelope first on tool_changer (ZM14, 10.3 %, the mount model at 1.12x: a steel boom grows 0.07
#: mm) and on ur10 (absorbed in a trial), now on kr16_like only (ZM22); the enclosure door first with 3-8 min loadings
#: and 3-8 K (ur10's ZM06, 21.7 %, the joint model at 1.27x; tool_changer's ZM14, 16.7 %, the mount model at 1.18x), now
#: fixture or pallet loadings of 5-15 min and 4-10 K, on ur10 (ZM06 and the mixture ZM08) -- tool_changer's ZM14 took
#: the upstream toss; a riser's bolted splice (pedestal_splice) first, on tool_changer (ZM12, 12.6 %, ambiguous) and
#: kr16_like (ZM20, the link model at 1.21x, 1.17-1.18x after a softer open gap and a turn about the compressed edge),
#: replaced by a track carriage's rail blocks, softer pulled than pressed, themselves first on a near-square carriage
#: (kr16_like ambiguous at 12 %, ur10 and tool_changer with the joint model at 1.04-1.08x), now a narrow carriage on ur10
#: (ZM01, which carried the mesh ripple; tool_changer's ZM12 took the cone mounts, kr16_like's ZM20 the mesh ripple).
#: No seed or pose count was changed to fix a label. A trial on the seed + 1 (case seeds + 1000003): every effect case
#: its truth, 20 of 21 at the 20 % / 1.25x bar; below it the cone mounts on tool_changer (ZM12, absorbed at 3.8 %: its
#: time-split test block carries a part the training blocks did not) -- the weakest kind there; the moment softening on
#: tool_changer (ZM09, the link model at 1.38x) next.
SET_ZM = [
    ("ZM01", "ur10", ("rail_blocks",), 130, "random"),
    ("ZM02", "ur10", ("limiter_play",), 140, "random"),
    ("ZM03", "ur10", ("microstep_error",), 120, "random"),
    ("ZM04", "ur10", ("conical_mounts",), 140, "random"),
    ("ZM05", "ur10", ("mandrel_rock",), 45, "random"),
    ("ZM06", "ur10", ("enclosure_door",), 150, "time"),
    ("ZM07", "ur10", (), 60, "random"),
    ("ZM08", "ur10", ("microstep_error", "enclosure_door"), 180, "time"),
    ("ZM09", "tool_changer", ("moment_softening",), 130, "random"),
    ("ZM10", "tool_changer", ("limiter_play",), 140, "random"),
    ("ZM11", "tool_changer", ("mandrel_rock",), 130, "random"),
    ("ZM12", "tool_changer", ("conical_mounts",), 140, "time"),
    ("ZM13", "tool_changer", ("jaw_guide_tilt",), 140, "random"),
    ("ZM14", "tool_changer", ("upstream_toss",), 160, "time"),
    ("ZM15", "tool_changer", (), 40, "random"),
    ("ZM16", "tool_changer", ("limiter_play", "conical_mounts"), 190, "random"),
    ("ZM17", "kr16_like", ("moment_softening",), 130, "random"),
    ("ZM18", "kr16_like", ("upstream_toss",), 140, "random"),
    ("ZM19", "kr16_like", ("step_accuracy",), 130, "time"),
    ("ZM20", "kr16_like", ("mesh_ripple",), 130, "random"),
    ("ZM21", "kr16_like", ("jaw_guide_tilt",), 120, "random"),
    ("ZM22", "kr16_like", ("mean_radiant",), 150, "time"),
    ("ZM23", "kr16_like", (), 100, "random"),
    ("ZM24", "kr16_like", ("upstream_toss", "mandrel_rock"), 200, "random"),
]

#: Set ZN (seed 40_7040): twelve new kinds, two per family (sim2real_indep.effects_zn; physics and sources in
#: effects_zn_joint, effects_zn_body, effects_zn_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 35.5 % on ZN03, 35.6 % on ZN10 and 37.4 % on ZN14 to 74.7 % on ZN13); the closest rivals
#: ZN10's link model at 1.37x, ZN14's transmission model at 1.48x, ZN03's mount model at 1.52x and ZN24's joint model at
#: 1.68x; a mixture component's removal costs 19.7 % at least (ZN08's payload estimator), the geometry-only cases none.
#: Changed after trial draws: the payload estimator's time constant, first 5-20 s of excitation (ur10's mixture ZN08
#: named transmission only: the estimate caught up within a few moves and its removal cost 4.2 %), now 20-60 s (a
#: forgetting factor slow enough to reject the torque readings' noise); ZN17 set to 45 poses for the layout's short
#: effect case (it was 130 in the first draw; its label is the truth either way). No seed was changed, and no pose count
#: to fix a label. A trial on the seed + 1 (case seeds + 1000003): every effect case its truth, 20 of 21 at the 20 % /
#: 1.25x bar; below it the payload estimator on ur10 (ZN02, 16.5 %, the mount model at 1.20x) -- the weakest kind
#: there; the focalised mounts on tool_changer (ZN14, 30.0 %, the transmission model at 1.34x) next.
SET_ZN = [
    ("ZN01", "ur10", ("hygro_gear",), 140, "time"),
    ("ZN02", "ur10", ("payload_estimator",), 150, "random"),
    ("ZN03", "ur10", ("rope_lay",), 120, "random"),
    ("ZN04", "ur10", ("wire_rope_isolators",), 140, "random"),
    ("ZN05", "ur10", ("bellows_coupling",), 130, "random"),
    ("ZN06", "ur10", ("radiant_tube_heater",), 150, "time"),
    ("ZN07", "ur10", (), 60, "random"),
    ("ZN08", "ur10", ("rope_lay", "payload_estimator"), 180, "random"),
    ("ZN09", "tool_changer", ("load_holding_valve",), 130, "random"),
    ("ZN10", "tool_changer", ("magnetostrictive_rod",), 120, "random"),
    ("ZN11", "tool_changer", ("dovetail_gib",), 140, "random"),
    ("ZN12", "tool_changer", ("dragging_brake",), 150, "time"),
    ("ZN13", "tool_changer", ("roll_endplay",), 130, "random"),
    ("ZN14", "tool_changer", ("focalised_mounts",), 140, "random"),
    ("ZN15", "tool_changer", (), 40, "random"),
    ("ZN16", "tool_changer", ("load_holding_valve", "magnetostrictive_rod"), 190, "time"),
    ("ZN17", "kr16_like", ("roll_endplay",), 45, "random"),
    ("ZN18", "kr16_like", ("hygro_gear",), 140, "time"),
    ("ZN19", "kr16_like", ("focalised_mounts",), 130, "random"),
    ("ZN20", "kr16_like", ("rope_lay",), 120, "random"),
    ("ZN21", "kr16_like", ("dovetail_gib",), 120, "random"),
    ("ZN22", "kr16_like", ("dragging_brake",), 150, "time"),
    ("ZN23", "kr16_like", (), 100, "random"),
    ("ZN24", "kr16_like", ("wire_rope_isolators", "bellows_coupling"), 200, "random"),
]

#: Set ZO (seed 40_7041): twelve new kinds, two per family (sim2real_indep.effects_zo; physics and sources in
#: effects_zo_joint, effects_zo_body, effects_zo_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth (gains 32.1 % on ZO09 and 32.2 % on ZO04 to 89.4 % on ZO10); the closest rivals ZO19's joint model at
#: 1.30x, ZO12's link model at 1.37x, ZO04's thermal model at 1.38x and ZO09's transmission model at 1.46x; a mixture
#: component's removal costs 53.6 % at least (ZO24's QZS isolator), the geometry-only cases none. Changed after trial
#: draws: the tabulated gravity first on ur10 too (ZO01, 6.5 %: its light upper arm and forearm, drawn at 0.26 mm
#: against 0.05 mm of noise, left a residual of the noise's size), now on kr16_like only (ZO17), ur10's ZO01 taking the
#: closed-cell pads; the entrained air first in axes 2 and 3's cylinders with both chambers live (ZO09 absorbed at 1.3
#: %: one-signed, smooth gravity torques that the geometry takes up; the mixture ZO16 lost 3.5 % without it), then with
#: their loaded chambers alone holding the load (still 7.7 %, ambiguous; then 15.2 % with the ram's cylinder added), now
#: the telescopic ram's cylinder alone, whose axial load changes side as the ram tips (the long cylinder where air
#: gathers); the dry-ice nozzle first on a 400 mm bracket chilled 15-35 K (ur10's ZO06 at 20.0 % with the joint model at
#: 1.23x, kr16_like's ZO22 13.6 %), now on a 600 mm lance chilled 25-45 K; the deck cupping first with the washdown
#: 10-40 min before the session and pauses of 15-45 min (ZO04, 23.3 %, the thermal model at 1.25x: a short session on
#: the flat part of the square-root law), now 3-10 min (the session at the shift's end) and pauses of 20-60 min;
#: supports nearer the deck's centre were tried and dropped (ZO04 20.7 %, the backlash model at 1.26x). No seed or pose
#: count was changed to fix a label. A trial on the seed + 1 (case seeds + 1000003): every effect case its truth, 18 of
#: 21 at the 20 % / 1.25x bar; below it the QZS isolator on ur10 (ZO05, 45 poses, 14.2 %, the thermal model at 1.16x) --
#: the weakest kind there --, the foam pads on tool_changer (ZO12, 22.2 %, the link model at 1.14x) and the gravity
#: table (ZO17, the link model at 1.20x); the dry-ice nozzle on kr16_like just above it (ZO22, 20.5 %, the joint model
#: at 1.252x).
SET_ZO = [
    ("ZO01", "ur10", ("closed_cell_pads",), 140, "random"),
    ("ZO02", "ur10", ("tensioner_stop",), 140, "random"),
    ("ZO03", "ur10", ("race_waviness",), 130, "random"),
    ("ZO04", "ur10", ("deck_cupping",), 150, "time"),
    ("ZO05", "ur10", ("qzs_mount",), 45, "random"),
    ("ZO06", "ur10", ("dry_ice_nozzle",), 150, "time"),
    ("ZO07", "ur10", (), 60, "random"),
    ("ZO08", "ur10", ("cross_spring_pivot", "deck_cupping"), 180, "time"),
    ("ZO09", "tool_changer", ("entrained_air",), 130, "random"),
    ("ZO10", "tool_changer", ("differential_lash",), 140, "random"),
    ("ZO11", "tool_changer", ("lever_cam_fit",), 120, "random"),
    ("ZO12", "tool_changer", ("closed_cell_pads",), 140, "random"),
    ("ZO13", "tool_changer", ("cross_spring_pivot",), 130, "random"),
    ("ZO14", "tool_changer", ("ultrasonic_ram",), 160, "time"),
    ("ZO15", "tool_changer", (), 40, "random"),
    ("ZO16", "tool_changer", ("entrained_air", "ultrasonic_ram"), 190, "time"),
    ("ZO17", "kr16_like", ("gravity_table",), 130, "random"),
    ("ZO18", "kr16_like", ("differential_lash",), 140, "random"),
    ("ZO19", "kr16_like", ("closed_cell_pads",), 130, "random"),
    ("ZO20", "kr16_like", ("cross_spring_pivot",), 120, "random"),
    ("ZO21", "kr16_like", ("tensioner_stop",), 130, "random"),
    ("ZO22", "kr16_like", ("dry_ice_nozzle",), 150, "time"),
    ("ZO23", "kr16_like", (), 100, "random"),
    ("ZO24", "kr16_like", ("race_waviness", "qzs_mount"), 200, "random"),
]

#: Set ZP (seed 40_7042): twelve new kinds, two per family (sim2real_indep.effects_zp; physics and sources in
#: effects_zp_joint, effects_zp_body, effects_zp_thermal), 8 cases per arm, 3 geometry-only, 3 mixtures of two new
#: kinds, a quarter split by time. Oracle labels when written (oracle.py only; the diagnosis was not run): every effect
#: case its truth, gains 22.4 % (ZP13) and 28.7 % (ZP10) to 81.9 % (ZP18); TWO CASES MISS THE 1.25x BAR, left as found:
#: ZP13's link model at 1.11x and ZP03's at 1.15x (both mount kinds: a base's tilt under the arm's moment resembles the
#: links' bending); next ZP10's backlash model at 1.34x; a mixture component's removal costs 14.3 % at least (ZP08's
#: heated bed), the geometry-only cases none.
#: Changed after trial draws: the clevis clearance first taken up by the cylinders' gravity load alone (ZP09 absorbed at
#: 1.2 %: the load never changes side, so the play is a smooth function of the pose), now by the load less a
#: counterbalance set near the median load (heavy booms are counterbalanced); the tachogenerators' gain error first as
#: large as the offset's drift (ZP10 absorbed at 0.5 %: a scale on a short range the geometry takes up), now the drift
#: dominant over a working day's pauses of 30-90 min, ZP10 split at random (split by time the thermal model's linear
#: drift came within 1.22x) and ZP14 split by time instead; the heated bed first sized by its flux at the bed and
#: lagged 5-15 min (ur10's ZP05 absorbed, 0.09 mm: the node settles to the mean exposure), then by the lowest pose's
#: flux and a thin wall's 2-5 min (still 5.8 %: a forearm's length change), now with the bed off before the session
#: and in the mixture ZP08 only (its removal costs 14.3 %), ZP05 holding the boom; the air-motor lance first 250-500 mm
#: at 3-15 K and a 2-6 min lag (0.03 mm, ZP06 ambiguous), now 700 mm at 10-20 K through 1-3 min (the air flowing
#: through it); the soaked jacket first on ur10 too (ZP01, the thermal model at 1.08x: its light links carry little
#: water), now on kr16_like only, ZP01 the vessel list; the ballasted stand first on ur10 and kr16_like (ambiguous with
#: the link model at 1.04x; absorbed at 1.9 %), now on tool_changer only, and first allowed onto two feet (ZP13 67.9 %,
#: but such a stand would tip), now ballasted to stay on three at least (24.4 % at 0.3-1.2 weights, 22.4 % at
#: 0.05-0.4: the link model at 1.09x and 1.11x); the magnet base tried on kr16_like and tool_changer (16.7 % and 9.4 %,
#: the link model within 1.12x and 1.02x) and on ur10 with holding forces of 2-5 and 1.2-2.5 weights and quarters
#: 0.1-0.2 and 0.06-0.12 m apart (the link model at 1.17x, 1.16x, 1.15x). No seed or pose count was changed to fix a
#: label.
SET_ZP = [
    ("ZP01", "ur10", ("vessel_list",), 140, "time"),
    ("ZP02", "ur10", ("clock_spring_flank",), 140, "random"),
    ("ZP03", "ur10", ("magnet_base",), 130, "random"),
    ("ZP04", "ur10", ("needle_gripper",), 45, "random"),
    ("ZP05", "ur10", ("ltb_boom",), 150, "random"),
    ("ZP06", "ur10", ("air_motor_heat",), 130, "time"),
    ("ZP07", "ur10", (), 60, "random"),
    ("ZP08", "ur10", ("heated_bed", "clock_spring_flank"), 180, "random"),
    ("ZP09", "tool_changer", ("clevis_clearance",), 130, "random"),
    ("ZP10", "tool_changer", ("tacho_integration",), 140, "random"),
    ("ZP11", "tool_changer", ("vessel_list",), 150, "time"),
    ("ZP12", "tool_changer", ("ltb_boom",), 130, "random"),
    ("ZP13", "tool_changer", ("ballast_stand",), 140, "random"),
    ("ZP14", "tool_changer", ("mylar_strip",), 120, "time"),
    ("ZP15", "tool_changer", (), 40, "random"),
    ("ZP16", "tool_changer", ("clevis_clearance", "ltb_boom"), 190, "random"),
    ("ZP17", "kr16_like", ("vessel_list",), 130, "random"),
    ("ZP18", "kr16_like", ("mylar_strip",), 140, "time"),
    ("ZP19", "kr16_like", ("clock_spring_flank",), 130, "random"),
    ("ZP20", "kr16_like", ("ltb_boom",), 120, "random"),
    ("ZP21", "kr16_like", ("air_motor_heat",), 130, "random"),
    ("ZP22", "kr16_like", ("soaked_jacket",), 150, "time"),
    ("ZP23", "kr16_like", (), 100, "random"),
    ("ZP24", "kr16_like", ("needle_gripper", "mylar_strip"), 200, "random"),
]

#: ``all`` in run.py means every set (A-Z, ZA, ZB, ZC, ZD, ZE, ZF, ZG, ZH, ZI, ZJ, ZK, ZL, ZM, ZN, ZO, ZP)
SETS = {"A": (SET_A, SEED_A), "B": (set_b(), SEED_B), "C": (SET_C, SEED_C), "D": (SET_D, SEED_D),
        "E": (SET_E, SEED_E), "F": (SET_F, SEED_F), "G": (SET_G, SEED_G), "H": (SET_H, SEED_H),
        "I": (SET_I, SEED_I), "J": (SET_J, SEED_J), "K": (SET_K, SEED_K), "L": (SET_L, SEED_L),
        "M": (SET_M, SEED_M), "N": (SET_N, SEED_N), "O": (SET_O, SEED_O), "P": (SET_P, SEED_P),
        "Q": (SET_Q, SEED_Q), "R": (SET_R, SEED_R), "S": (SET_S, SEED_S), "T": (SET_T, SEED_T),
        "U": (SET_U, SEED_U), "V": (SET_V, SEED_V), "W": (SET_W, SEED_W), "X": (SET_X, SEED_X),
        "Y": (SET_Y, SEED_Y), "Z": (SET_Z, SEED_Z), "ZA": (SET_ZA, SEED_ZA),
        "ZB": (SET_ZB, SEED_ZB), "ZC": (SET_ZC, SEED_ZC), "ZD": (SET_ZD, SEED_ZD),
        "ZE": (SET_ZE, SEED_ZE), "ZF": (SET_ZF, SEED_ZF), "ZG": (SET_ZG, SEED_ZG),
        "ZH": (SET_ZH, SEED_ZH), "ZI": (SET_ZI, SEED_ZI), "ZJ": (SET_ZJ, SEED_ZJ),
        "ZK": (SET_ZK, SEED_ZK), "ZL": (SET_ZL, SEED_ZL), "ZM": (SET_ZM, SEED_ZM),
        "ZN": (SET_ZN, SEED_ZN), "ZO": (SET_ZO, SEED_ZO),
        "ZP": (SET_ZP, SEED_ZP)}


def case_seed(set_name: str, index: int) -> int:
    return SETS[set_name][1] * 1000 + index

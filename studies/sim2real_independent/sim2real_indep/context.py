"""The model of a robot at a session's poses, shared by the effects and the oracle. Imports nothing of tolalloc."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.session import Session

FAMILY = {"gear": "transmission", "encoder": "transmission", "heat": "thermal", "ambient": "thermal",
          "hardening": "joint_compliance", "compliance": "joint_compliance", "mount": "mount_compliance",
          "sag": "link_deflection", "backlash": "backlash", "none": "none",
          # set C (sim2real_indep.effects_c); tracker_scale is a measurement error that follows the air
          # temperature: scored as thermal, the family whose generic model (air-driven scaling) describes it
          "twonode": "thermal", "workcell": "thermal", "column_bow": "thermal", "tracker_scale": "thermal",
          "rv_error": "transmission", "dual_encoder": "transmission", "runout": "transmission",
          "hyst_stiffness": "joint_compliance", "bearing_tilt": "joint_compliance", "dahl": "backlash",
          "track": "mount_compliance", "box_torsion": "link_deflection", "bolted_tube": "link_deflection",
          # set D (sim2real_indep.effects_d; refraction, a measurement error following the air, scored as thermal)
          "gas_spring": "joint_compliance", "dresspack": "joint_compliance", "varlash": "backlash",
          "belt": "transmission", "ball_screw": "transmission", "loose_anchor": "mount_compliance",
          "pad_creep": "mount_compliance", "tapered": "link_deflection", "bracket": "link_deflection",
          "thermal_bend": "thermal", "tool_heat": "thermal", "refraction": "thermal",
          # set E (sim2real_indep.effects_e)
          "parallelogram": "joint_compliance", "varstiff": "joint_compliance", "friction_windup": "backlash",
          "scissor_gear": "backlash", "magnetic_ring": "transmission", "ring_gear": "transmission",
          "table_frame": "mount_compliance", "soft_foot": "mount_compliance", "channel": "link_deflection",
          "ram": "link_deflection", "sunlight": "thermal", "fan_thermostat": "thermal",
          # set F (sim2real_indep.effects_f)
          "cable_balancer": "joint_compliance", "lever_stiffness": "joint_compliance",
          "plate_yield": "mount_compliance", "uplift": "mount_compliance", "eccentric_axis": "link_deflection",
          "weld_crack": "link_deflection", "wear_zones": "backlash", "brake_hub": "backlash",
          "tape_scale": "transmission", "lever_drive": "transmission", "day_night": "thermal",
          "screw_growth": "thermal",
          # set G (sim2real_indep.effects_g; target_rod, the target's support bending, scored as link deflection;
          # tripod_growth, a drift of the measurement frame following the air, scored as thermal)
          "twin_pinion": "joint_compliance", "hose_catenary": "joint_compliance", "jack_leak": "mount_compliance",
          "air_isolator": "mount_compliance", "cfrp_twist": "link_deflection", "target_rod": "link_deflection",
          "axial_float": "backlash", "bearing_clearance": "backlash", "ratio_rounding": "transmission",
          "ring_shift": "transmission", "tripod_growth": "thermal", "bar_expansion": "thermal",
          # set H (sim2real_indep.effects_h; skid, the arm's base and the tracker's stand on one bedded skid, scored
          # as mount compliance; tracker_warmup, the instrument's warm-up drift, as thermal; cold_grease, friction
          # lost motion fading as the joints warm, as backlash)
          "load_data": "joint_compliance", "gear_creep": "joint_compliance", "agv_wheels": "mount_compliance",
          "skid": "mount_compliance", "curved_link": "link_deflection", "bond_creep": "link_deflection",
          "wrist_lash": "backlash", "cold_grease": "backlash", "stale_table": "transmission",
          "wrist_coupling": "transmission", "tracker_warmup": "thermal", "helix_shift": "thermal",
          # set I (sim2real_indep.effects_i; tilted_base, the gear torsion under gravity acting obliquely in the base
          # frame of an inclined installation, scored as joint compliance; rail_boom, a tool-side boom bowing like a
          # bimetal strip with the air temperature, as thermal; nut_play, a prismatic stage's nut play, as backlash)
          "tilted_base": "joint_compliance", "balancer_relax": "joint_compliance", "floor_beams": "mount_compliance",
          "portal": "mount_compliance", "lap_splice": "link_deflection", "fork_arm": "link_deflection",
          "overrun_lash": "backlash", "nut_play": "backlash", "idler_runout": "transmission",
          "para_gear": "transmission", "rail_boom": "thermal", "housing_growth": "thermal",
          # set J (sim2real_indep.effects_j; flange_slip, a link turned across its bolt-hole clearance by its load's
          # history, and bar_pins, the play of a parallelogram bar's pins, scored as backlash; tool_plate, the
          # end-of-arm plate carrying the target, as link deflection)
          "planet_stage": "transmission", "diff_wrist": "transmission", "flange_slip": "backlash",
          "bar_pins": "backlash", "hose_retract": "joint_compliance", "wrist_shafts": "joint_compliance",
          "grout_creep": "mount_compliance", "wall_console": "mount_compliance", "skew_casting": "link_deflection",
          "tool_plate": "link_deflection", "brake_tilt": "thermal", "laminate_twist": "thermal",
          # set K (sim2real_indep.effects_k; vacuum_hose, the hose's pressure thrust twisting the gears, and tele_rope,
          # the ropes holding the telescopic stage, scored as joint compliance; rcc, the compliant device carrying the
          # gripper and the target, as link deflection; bulkhead, the arm's support bowed by the chamber's pressure, as
          # mount compliance; thermal_lash, a backlash whose width follows a housing's temperature, and ram_roll, the
          # telescopic ram turning in its key's clearance, as backlash; spline_twist, a wrist angle off in proportion
          # to the extension, as transmission; comp_mismatch, the residual of the controller's thermal correction, as
          # thermal)
          "vacuum_hose": "joint_compliance", "tele_rope": "joint_compliance", "rcc": "link_deflection",
          "outrigger_soil": "mount_compliance", "bulkhead": "mount_compliance", "side_cylinder": "link_deflection",
          "thermal_lash": "backlash", "ram_roll": "backlash", "cardan": "transmission",
          "spline_twist": "transmission", "read_head": "thermal", "comp_mismatch": "thermal",
          # set L (sim2real_indep.effects_l; polymer_heat, the twist of polymer gears growing as their drives warm them,
          # scored as joint compliance, the family whose model holds its shape (as set K's thermal backlash is
          # backlash); dispense_drain, the gears twisted by an unlogged, emptying cartridge, as joint compliance;
          # gauge_pinion, the lost motion of the pinion driving axis 1's secondary encoder (the joint leads its
          # reading), and valve_lap, a hydraulic axis stopping anywhere in its valve's dead band and drifting across it
          # by the leakage, as backlash; guide_errors, the telescopic stage's straightness and angular error motions
          # along its stroke, as transmission (a joint's motion errors as a function of its own position, as set C's
          # bearing runout); grip_spread, the target's finger spread by the grip force and the part, and float_holder, a
          # tool on a preloaded compliant holder, as link deflection (the end-of-arm structure carrying the target);
          # hot_part, the gripper heated by the hot parts it holds, as thermal)
          "polymer_heat": "joint_compliance", "dispense_drain": "joint_compliance", "gauge_pinion": "backlash",
          "valve_lap": "backlash", "pin_ring": "transmission", "guide_errors": "transmission",
          "pallet_load": "mount_compliance", "anchor_loose": "mount_compliance", "grip_spread": "link_deflection",
          "float_holder": "link_deflection", "hot_part": "thermal", "wet_arm": "thermal",
          # set M (sim2real_indep.effects_m; slurry_lift, the gears twisted by the slurry's lift on what dips into it,
          # and oil_column, the hydraulic axes' oil springs, scored as joint compliance; spindle_dither, the main axes'
          # lost motion whose flank a running spindle's vibration chooses, and jaw_play, the target's jaw rocking in its
          # guide's clearance, as backlash; friction_wheel, axis 1 read through a measuring wheel, as transmission;
          # cart_dock, the cart docked anew between the blocks, and carriage_play, the track carriage rocking across its
          # rollers' clearance, as mount compliance (the robot's support); rope_mount, the tool on wire-rope
          # isolators, and tie_rod_bar, a gripper bar bending at two rates, as link deflection (the end-of-arm structure
          # carrying the target); hot_plume, a measurement error following a hot air column's temperature, as thermal)
          "slurry_lift": "joint_compliance", "oil_column": "joint_compliance", "spindle_dither": "backlash",
          "jaw_play": "backlash", "chain_stage": "transmission", "friction_wheel": "transmission",
          "cart_dock": "mount_compliance", "carriage_play": "mount_compliance", "rope_mount": "link_deflection",
          "tie_rod_bar": "link_deflection", "hot_plume": "thermal", "oil_growth": "thermal",
          # set N (sim2real_indep.effects_n; wind_panel, the gears twisted by the wind on a carried panel, and
          # jet_reaction, by a water jet's reaction, scored as joint compliance; harness_lash, axis 1's lost motion
          # whose flank the base harness's torsion chooses, and balanced_lash, axis 2's under gravity, a counterbalance
          # and its seal friction, as backlash; rope_creep, a telescopic stage's rope creeping on its traction sheave,
          # and mag_drift, magnetic encoders' once- and twice-per-turn errors growing as they warm (the family whose
          # model holds the shape), as transmission; crawler_sink, a tracked carrier sinking into soft ground, and
          # leaf_springs, a vehicle's hysteretic leaf-spring suspension, as mount compliance (the robot's support);
          # truss_slack, a lattice gripper boom's pin slack, and ring_frame, a ring gripper frame that the held part
          # stiffens, as link deflection (the end-of-arm structure carrying the target); tripod_tilt, the tracker's head
          # tilted by its unequally heated tripod legs (a measurement effect), and pad_heat, the base lifted and tilted
          # by unequally heated elastomer pads, as thermal)
          "wind_panel": "joint_compliance", "jet_reaction": "joint_compliance", "harness_lash": "backlash",
          "balanced_lash": "backlash", "rope_creep": "transmission", "mag_drift": "transmission",
          "crawler_sink": "mount_compliance", "leaf_springs": "mount_compliance", "truss_slack": "link_deflection",
          "ring_frame": "link_deflection", "tripod_tilt": "thermal", "pad_heat": "thermal",
          # set O (sim2real_indep.effects_o; cut_flank, the lost motion of axes 1, 4 and 6 whose flank a milling cut's
          # load chooses, and enc_hysteresis, the hysteresis band of the output encoders closing the position loop,
          # scored as backlash; lsb_stop, those encoders' counts and stopping dead band, and mesh_te, a ring gear's
          # tooth-mesh transmission error, as transmission; pontoon, a floating support, and guyed_mast, a guyed mast,
          # as mount compliance (the robot's support); weld_gun, a C-frame tool opened by its squeeze force, and
          # spindle_bracket, a spindle's bracket bent by the cut, as link deflection (the end-of-arm structure
          # carrying the target); purge_air, the hollow arm cooled by its purge air, and ir_dryer, the links warmed
          # by an infrared panel, as thermal; milling_force and bolt_torque, the gears twisted by a cut and by a
          # nutrunner's reaction, as joint compliance)
          "milling_force": "joint_compliance", "bolt_torque": "joint_compliance", "cut_flank": "backlash",
          "enc_hysteresis": "backlash", "lsb_stop": "transmission", "mesh_te": "transmission",
          "pontoon": "mount_compliance", "guyed_mast": "mount_compliance", "weld_gun": "link_deflection",
          "spindle_bracket": "link_deflection", "purge_air": "thermal", "ir_dryer": "thermal",
          # set P (sim2real_indep.effects_p; mag_coupling, the main axes' gear inputs lagging their motors across
          # magnetic couplings, and belt_slack, a wrist axis' belt stage softening as its slack span goes slack, scored
          # as joint compliance; seal_relax, the output seals' relaxing wind-up against the last motion, and
          # quick_change, the tool re-seated in its locating pins' clearance at each change, as backlash (lost motion in
          # a clearance or a friction-held wind-up); pole_pitch, a magnetised encoder ring's accumulated pitch errors,
          # and stray_field, a magnetic encoder turned by the next axis' brake magnet, as transmission; vacuum_feet, a
          # portable arm's vacuum-held pads, and platen_clamp, a moulding machine's platen bent by the clamp, as mount
          # compliance (the robot's support); vacuum_plate, a vacuum gripper's face plate bowed in while it holds a
          # part,
          # and hose_lance, a dispensing lance bent by its supply hose, as link deflection (the end-of-arm structure
          # carrying the target); jacket_cycle, the links following a jacket cooler's on-off cycle, and
          # charging_heat, an AMR's deck bowed by its charging battery, as thermal)
          "mag_coupling": "joint_compliance", "belt_slack": "joint_compliance", "seal_relax": "backlash",
          "quick_change": "backlash", "pole_pitch": "transmission", "stray_field": "transmission",
          "vacuum_feet": "mount_compliance", "platen_clamp": "mount_compliance", "vacuum_plate": "link_deflection",
          "hose_lance": "link_deflection", "jacket_cycle": "thermal", "charging_heat": "thermal",
          # set Q (sim2real_indep.effects_q; sensor_stops, the main axes' torque-sensor flexures locking on their
          # overload stops, and fluid_tank, the gears twisted by a tool tank's liquid settling to its low side, scored
          # as joint compliance; lash_comp, the controller's backlash compensation against the worn gears' lost motion,
          # and servo_tail, a PI-controlled axis' overshoot decaying through the dwell, as backlash (errors that follow
          # the last motion); ball_pass, strain-wave gears' error at their wave-generator bearing's ball-pass rate, and
          # draw_wire, the telescopic stage's draw-wire sensor, as transmission; disc_springs, the arm's feet on disc
          # springs, and kinematic_mount, its base on a clamped three-ball coupling, as mount compliance (the robot's
          # support); ball_holder, the reflector's articulated holder, and gooseneck, the nozzle's supply tube
          # straightening under its pressure, as link deflection (the end-of-arm structure carrying the target);
          # ejector_chill, a gripper boom chilled by its ejector's exhaust, and door_draught, the arm chilled by a hall
          # door's draught, as thermal)
          "sensor_stops": "joint_compliance", "fluid_tank": "joint_compliance", "lash_comp": "backlash",
          "servo_tail": "backlash", "ball_pass": "transmission", "draw_wire": "transmission",
          "disc_springs": "mount_compliance", "kinematic_mount": "mount_compliance", "ball_holder": "link_deflection",
          "gooseneck": "link_deflection", "ejector_chill": "thermal", "door_draught": "thermal",
          # set R (sim2real_indep.effects_r; line_pressure, axis 2's gear twisted by a line-fed pneumatic balancer's
          # force swinging with the compressor's load / unload cycle, and slide_shift, the gears twisted by a tool
          # slide's carriage standing out or in, scored as joint compliance; stick_band, axes held by a proportional
          # loop short of their target by their friction on the approach's side, and floor_cable, the joints twisted by
          # a floor-dragged cable's friction only when it was last pulled out, as backlash (errors that follow the last
          # motion); rehoming, incremental encoders' zero set anew at each power-up's homing, and belt_splice, a belt
          # splice's pitch error as a function of axis 5's angle, as transmission (the joints' reading and drive);
          # forklift_slab, the base on a slab dished by a parked truck, and sprayer_tank, the base on a sprung chassis
          # under its draining tank, as mount compliance (the robot's support); web_buckling, the target's sheet-metal
          # bracket buckling in shear, and swing_mount, the target's tool swung off its stop by its weight, as link
          # deflection (the end-of-arm structure carrying the target); heated_hose and welding_cable, links bowed by a
          # heated hose and a welding cable, as thermal)
          "line_pressure": "joint_compliance", "slide_shift": "joint_compliance", "stick_band": "backlash",
          "floor_cable": "backlash", "rehoming": "transmission", "belt_splice": "transmission",
          "forklift_slab": "mount_compliance", "sprayer_tank": "mount_compliance", "web_buckling": "link_deflection",
          "swing_mount": "link_deflection", "heated_hose": "thermal", "welding_cable": "thermal",
          # set S (sim2real_indep.effects_s; float_pinion, axis 2's gear let go by a sprung pinion that its teeth wedge
          # out of mesh, and wall_boot, the joints twisted by the spring rates of a wall bellows the forearm passes
          # through, scored as joint compliance; overshoot_lash, the lost motion of axes 1, 4 and 6 crossed back by the
          # position loop's overshoot, and dowel_yaw, the base turned across its dowels' clearance by axis 1's reaction
          # torque, as backlash (errors that follow the last motion); cogging, the drives' cogging torque against a
          # proportional loop at standstill, and pot_loading, the boom cylinders' potentiometric transducers read
          # through an input of finite impedance, as transmission (a joint's error as a function of its own position);
          # twin_robot, the table shared with a twin robot tilted by its production cycle, and mullins_mounts, the base
          # on new isolators softening below their largest load so far, as mount compliance (the robot's support);
          # profile_frame, the target's profile-frame joint turning by its semi-rigid curve, and diaphragm, the tool on
          # a double-diaphragm flexure stiffening by membrane action, as link deflection (the end-of-arm structure
          # carrying the target); oil_shrink, the boom sinking as the oil trapped in its cylinders cools in the dwell,
          # and wheel_growth, axis 1's measuring wheel and ring growing apart with the hall's air, as thermal)
          "float_pinion": "joint_compliance", "wall_boot": "joint_compliance", "overshoot_lash": "backlash",
          "dowel_yaw": "backlash", "cogging": "transmission", "pot_loading": "transmission",
          "twin_robot": "mount_compliance", "mullins_mounts": "mount_compliance", "profile_frame": "link_deflection",
          "diaphragm": "link_deflection", "oil_shrink": "thermal", "wheel_growth": "thermal",
          # set T (sim2real_indep.effects_t; charge_cable, the joints twisted by a floor-lying charging cable's
          # hanging weight, which grows with the clamp's height, and balancer_leak, axis 2's gear loaded by its
          # balancer's gas leaking away through a worn seal, scored as joint compliance; hose_capstan, the joints
          # twisted by a retracted hose's pull that the guide ring's capstan friction raises after a pull-out and lowers
          # after a retraction, and via_approach, the lost motion's flank set by a hidden approach move along a
          # tool-fixed direction, as backlash (errors that follow the last motion); inclinometer, tool_changer's boom
          # joints read as differences of the links' absolute pitches from MEMS inclinometers, and rangefinder, its
          # telescopic stage read by a phase-comparison laser rangefinder with cyclic errors, as transmission (the
          # joints' reading); crane_runway, the base on a hall column bent by an overhead crane's wheel loads on its
          # corbel, and shield_squeeze, the console on a shield that squeezing rock ovalises during the standstill, as
          # mount compliance (the robot's support); lockable_float, a tool floating under its weight on a compliance
          # unit that is locked while a part is held, and plunger_stiction, a tool on an axial compliance plunger held
          # by its guide friction (a play operator of the axial weight), as link deflection (the end-of-arm structure
          # carrying the target); dew_warming, an arm brought in cold and warmed by the air and by the dew condensing
          # on it, and main_drive, the console bowed back as a tunnelling machine's main drive cools, as thermal)
          "charge_cable": "joint_compliance", "balancer_leak": "joint_compliance", "hose_capstan": "backlash",
          "via_approach": "backlash", "inclinometer": "transmission", "rangefinder": "transmission",
          "crane_runway": "mount_compliance", "shield_squeeze": "mount_compliance",
          "lockable_float": "link_deflection", "plunger_stiction": "link_deflection", "dew_warming": "thermal",
          "main_drive": "thermal",
          # set U (sim2real_indep.effects_u; integral_clamp, the main axes sagging by the load their anti-windup-clamped
          # integrator leaves to the proportional term, and parked_tool, the gears twisted by a spare tool parked on the
          # forearm in some blocks, scored as joint compliance; chain_slack, axis 3's lost motion across a roller
          # chain's sagging slack strand, and bowden_lash, axis 5's across a Bowden cable's sheath friction over the
          # elbow, as backlash (errors that follow the last motion); dropped_counts, the main axes' incremental encoders
          # dropping counts in fast moves, and soiled_disc, axis 2's optical encoder misreading a soiled sector, as
          # transmission (the joints' reading); trunnion, the arm on a tilting positioner's worm drive, and slab_joint,
          # its base plate straddling a floor slab's sawn joint, as mount compliance (the robot's support);
          # sandwich_boom, a sandwich gripper boom carrying the part and the target, and sleeve_rock, the target's
          # telescopic extension rocking in its sleeve's clearance, as link deflection (the end-of-arm structure
          # carrying the target); platform_growth, the arm's steel mezzanine following the hall's air, and magnet_coil,
          # a magnetic gripper warmed by its coil while it holds a part, as thermal)
          "integral_clamp": "joint_compliance", "parked_tool": "joint_compliance", "chain_slack": "backlash",
          "bowden_lash": "backlash", "dropped_counts": "transmission", "soiled_disc": "transmission",
          "trunnion": "mount_compliance", "slab_joint": "mount_compliance", "sandwich_boom": "link_deflection",
          "sleeve_rock": "link_deflection", "platform_growth": "thermal", "magnet_coil": "thermal",
          # set V (sim2real_indep.effects_v; coiled_cord, the joints twisted by a coiled cord's spring pull towards
          # its junction box, and overhead_festoon, by a hose hanging as a catenary from an overhead boom, scored as
          # joint compliance; coupled_flank, a wrist axis' lost motion whose flank its motor's net motion (its own move
          # plus the coupling compensation for the axis it passes through) chooses, and journal_climb, tool_changer's
          # boom pins climbing the walls of their worn bushes against the last rotation, as backlash (errors that follow
          # the last motion); interpolation_error, the output encoders' sub-divisional error within their signal
          # periods, and rack_segments, the telescopic stage's rack of butted segments and its pinion's runout, as
          # transmission (the joints' reading and drive); stabilizer_jacks, a mobile carrier standing on its suspension
          # or on its jacks by block, and self_leveling, a carrier levelled on its locked jacks at the start of each
          # block, as mount compliance (the robot's support); bolt_loosening, a gripper boom's root bolts loosening move
          # by move, and moisture_swell, a printed polyamide boom swelling with the humidity it takes up, as link
          # deflection (the end-of-arm structure carrying the target); restrained_bar, a crossbar restrained by its
          # frame bowing as the air warms it, and slab_curl, the floor slab between the arm and the tracker curling with
          # the air, as thermal)
          "coiled_cord": "joint_compliance", "overhead_festoon": "joint_compliance", "coupled_flank": "backlash",
          "journal_climb": "backlash", "interpolation_error": "transmission", "rack_segments": "transmission",
          "stabilizer_jacks": "mount_compliance", "self_leveling": "mount_compliance",
          "bolt_loosening": "link_deflection", "moisture_swell": "link_deflection", "restrained_bar": "thermal",
          "slab_curl": "thermal",
          # set W (sim2real_indep.effects_w; swarf_shroud, the gears twisted by the chips a spindle's suction shroud
          # collects in the production between the blocks, and rail_trolley, by a balancer hanging from a trolley
          # that runs freely on an overhead rail, scored as joint compliance; stable_probe, the tracker's stable-probe
          # trigger firing while the servo still creeps (the point taken behind the pose along the last approach), and
          # part_slide, a part sliding in its gripper nest to the stop the last move's deceleration or its weight
          # chose, as backlash (errors that follow the last motion); hub_slip, the output hubs of axes 2 and 3
          # slipping on their shafts when an emergency stop's brakes catch the arm, and emi_counts, welding noise
          # miscounting the main axes' incremental output encoders, as transmission (the joints' reading and drive);
          # cracked_plinth, the arm's concrete plinth cracked at its root, and young_grout, its pedestal's grout bed
          # still stiffening as it hydrates, as mount compliance (the robot's support); air_bellows, the tool on a
          # bellows compliance unit that follows the shop air's pressure cycle, and bent_bracket, the target's bracket
          # bent for good in a collision, as link deflection (the end-of-arm structure carrying the target);
          # cooling_part, a hot part carrying the target shrinking as it cools in the gripper, and air_stratification,
          # the links at the temperatures of the stratified air at their heights, as thermal)
          "swarf_shroud": "joint_compliance", "rail_trolley": "joint_compliance", "stable_probe": "backlash",
          "part_slide": "backlash", "hub_slip": "transmission", "emi_counts": "transmission",
          "cracked_plinth": "mount_compliance", "young_grout": "mount_compliance", "air_bellows": "link_deflection",
          "bent_bracket": "link_deflection", "cooling_part": "thermal", "air_stratification": "thermal",
          # set X (sim2real_indep.effects_x; magnet_fanner, the gears twisted by a sheet fanner's magnetic pull on the
          # steel blank in the gripper, and support_arm, by a spring-balanced tool-support arm's lift that changes with
          # the flange's height, scored as joint compliance; track_lash, the arm's linear track (an unlogged seventh
          # axis) left on the flank of its carriage's last approach to the station, and run_in_wear, a replaced gear
          # set's lost motion opening as its flanks run in through the production, as backlash (errors that follow the
          # last motion); ring_lobing, axis 1's ring scale pulled into three lobes by its clamping screws, and
          # cosine_error, the telescopic stage's length sensor mounted at an angle to its travel, as transmission (the
          # joints' reading); collision_shift, the base plate slipped on its friction-grip bolted joint in a collision,
          # and levelling_foot, the stand's levelling foot unscrewing in the production's vibration, as mount
          # compliance (the robot's support);
          # printed_fingers, 3D-printed gripper fingers creeping under the held part, and suction_cup, a part tilting
          # on its suction cup, as link deflection (the end-of-arm structure carrying the target); washdown, the arm
          # cooling after a hot sanitation rinse, and induction_stray, the forearm heated by an induction heater's
          # stray field, as thermal)
          "magnet_fanner": "joint_compliance", "support_arm": "joint_compliance", "track_lash": "backlash",
          "run_in_wear": "backlash", "ring_lobing": "transmission", "cosine_error": "transmission",
          "collision_shift": "mount_compliance", "levelling_foot": "mount_compliance",
          "printed_fingers": "link_deflection", "suction_cup": "link_deflection", "washdown": "thermal",
          "induction_stray": "thermal",
          # set Y (sim2real_indep.effects_y; frost_load, the gears twisted by the frost a cold-store arm gathers on its
          # links, and output_brake, the outputs of axes 2 and 3 held in some blocks by safety brakes whose armatures
          # give under the load, scored as joint compliance; coupling_play, the output encoders of axes 1-3 dragged
          # across their couplings' play (the joint driven past its target along the last motion), and squeeze_film,
          # the lost motion of axes 2 and 3 crossed slowly under their load through stiff grease (the point taken while
          # the output is on its way), as backlash (errors that follow the last motion); pinion_runout, axis 1's gauge
          # pinion running eccentrically, and torque_arm, the output encoders of axes 3-5 turned by their own weight on
          # their torque arms, as transmission (the joints' reading); press_walk, the base plate walking on its bolted
          # joint under a press's shocks through the production, and tyre_leak, the arm's cart sinking at a leaking
          # tyre, as mount compliance (the robot's support); foam_gripper, a part compressing and shearing a foam
          # vacuum pad, and sheet_part, a thin panel held at one edge bending under its own weight, as link deflection
          # (the end-of-arm structure carrying the target); vision_lamp, the upper arm bowed by the vision lamps clamped
          # to one side of it, and cabinet_exhaust, the pedestal bowed by the drive cabinet's exhaust, as thermal)
          "frost_load": "joint_compliance", "output_brake": "joint_compliance", "coupling_play": "backlash",
          "squeeze_film": "backlash", "pinion_runout": "transmission", "torque_arm": "transmission",
          "press_walk": "mount_compliance", "tyre_leak": "mount_compliance", "foam_gripper": "link_deflection",
          "sheet_part": "link_deflection", "vision_lamp": "thermal", "cabinet_exhaust": "thermal",
          # set Z (sim2real_indep.effects_z; water_slug, the gears twisted by water trapped in a hollow gripper boom and
          # running to its lower end, and balancer_gas, axis 2's gear loaded by its gas balancer's force following the
          # hall's air by the gas law, scored as joint compliance; balancer_seal, axis 2 held back against its last
          # motion by the balancer's rod-seal friction, and tripod_windup, the tracker's frame turned by its tripod's
          # friction-held windup after each slew, as backlash (errors that follow the last motion); band_spiral, the
          # telescopic stage driven by a band winding on its drum in a spiral, and head_tilt, axis 1's output encoder
          # misread as its bearing tilts under the arm's moment, as transmission (the joints' reading and drive);
          # warm_isolators, the base's elastomer isolators softening as the hall warms them, and oil_canning, the base
          # table's thin top plate snapping between its two dished shapes, as mount compliance (the robot's support);
          # bowstring, the upper arm bent by a harness strapped taut along it, and stress_relief, a welded gripper frame
          # distorting as the production's vibration relaxes its welding stresses, as link deflection (the arm's and
          # the end-of-arm structure carrying the target); floor_heating, the base plate curled by an underfloor
          # heating loop cooling after its switch-off, and duct_lag, the upper arm bowed as the air drifts because a
          # duct slows one side, as thermal)
          "water_slug": "joint_compliance", "balancer_gas": "joint_compliance", "balancer_seal": "backlash",
          "tripod_windup": "backlash", "band_spiral": "transmission", "head_tilt": "transmission",
          "warm_isolators": "mount_compliance", "oil_canning": "mount_compliance", "bowstring": "link_deflection",
          "stress_relief": "link_deflection", "floor_heating": "thermal", "duct_lag": "thermal",
          # set ZA (sim2real_indep.effects_za; flank_stiffness, gears stiffer on one tooth flank than on the other, and
          # luff_rope, tool_changer's boom luffed by a rope tackle whose compliance follows the luff angle, scored as
          # joint compliance; guide_drag, the telescopic stage held back against its last stroke by its guides'
          # friction, and tool_recoil, a tool on viscoelastic mounts still creeping back from the last stop's
          # deceleration, as backlash (errors that follow the last motion); scratch_count, a ring scale losing counts at
          # a scratch, and tooth_skip, a wrist belt that jumped a tooth between two blocks, as transmission;
          # slide_overhang, the arm on a slide table pulled out to another length for each block, and ground_thaw,
          # outrigger pads on thawing ground, as mount compliance; offcentre_pick, a gripper bar twisted by parts picked
          # off its centre line, and soft_fingers, an inflatable gripper's fingers bent by the part, as link deflection
          # (the end-of-arm structure carrying the target); ac_jet, the upper arm bowed by an air conditioner's cycling
          # cold jet, and oven_door, the forearm heated by an oven door's pulses, as thermal)
          "flank_stiffness": "joint_compliance", "luff_rope": "joint_compliance", "guide_drag": "backlash",
          "tool_recoil": "backlash", "scratch_count": "transmission", "tooth_skip": "transmission",
          "slide_overhang": "mount_compliance", "ground_thaw": "mount_compliance",
          "offcentre_pick": "link_deflection", "soft_fingers": "link_deflection", "ac_jet": "thermal",
          "oven_door": "thermal",
          # set ZB (sim2real_indep.effects_zb; impedance_preset, a torque-controlled arm's joint-impedance stiffness set
          # per block, and hose_wrap, the joints yielding to a hose wrapped round the wrist by axis 6, scored as joint
          # compliance; pawl_notch, gravity-loaded axes settling onto the next notch of a positive-locking brake, and
          # reversal_pulse, a friction-compensation pulse left over after a reversal, as backlash (lost motion in a
          # clearance, errors that follow the last motion); nonius_slip, a two-track absolute encoder decoding the
          # wrong fine period in a window of angles, and fieldbus_rounding, joint targets sent as integers of 0.01 deg,
          # as transmission (the joints' reading and command); mecanum_base, an AMR's mecanum wheels whose stiffness
          # changes at each docking, and grout_void, a base plate over a grout void under one edge, as mount
          # compliance; insulating_flange, a torch turning on its insulating flange, and stay_cable, a tool boom on a
          # sagging stay cable, as link deflection (the end-of-arm structure carrying the target); air_knife, the
          # forearm heated when axis 1 turns it into a hot air curtain, and sonotrode, an ultrasonic welding stack
          # warming in the production, as thermal)
          "impedance_preset": "joint_compliance", "hose_wrap": "joint_compliance", "pawl_notch": "backlash",
          "reversal_pulse": "backlash", "nonius_slip": "transmission", "fieldbus_rounding": "transmission",
          "mecanum_base": "mount_compliance", "grout_void": "mount_compliance",
          "insulating_flange": "link_deflection", "stay_cable": "link_deflection", "air_knife": "thermal",
          "sonotrode": "thermal",
          # set ZC (sim2real_indep.effects_zc; spool_tension, the joints yielding to a dancer-tensioned wire pulled
          # towards its guide eye, and coupled_wrist, a wrist whose drive trains' compliances act in motor coordinates,
          # scored as joint compliance; bayonet_play, a tool turned across its bayonet's play by its hose's drag against
          # axis 6's last rotation, and air_preload, axis 1's gear play preloaded by a cylinder only in the blocks with
          # the air on, as backlash (lost motion in a clearance, errors that follow the last motion); swapped_bits, the
          # output encoders' words logged with two data lines crossed, and multistart_worm, a worm stage's
          # start-to-start index error, as transmission (the joints' reading and drive); hexapod_mount, the arm on a
          # six-strut pedestal whose struts are softer in tension, and counterweight_base, a carrier whose active
          # counterweight cancels the arm's moment only within its stroke, as mount compliance (the robot's support);
          # rubber_bush, a tool boom hinged on a progressive rubber bush, and floor_hose, a tool boom bent by the hose
          # it lifts off the floor, as link deflection (the end-of-arm structure carrying the target); cure_exotherm, a
          # bonded part warmed by its adhesive's cure, and link_convection, the forearm bowed by the warm air its
          # motors stratify inside it, as thermal)
          "spool_tension": "joint_compliance", "coupled_wrist": "joint_compliance", "bayonet_play": "backlash",
          "air_preload": "backlash", "swapped_bits": "transmission", "multistart_worm": "transmission",
          "hexapod_mount": "mount_compliance", "counterweight_base": "mount_compliance",
          "rubber_bush": "link_deflection", "floor_hose": "link_deflection", "cure_exotherm": "thermal",
          "link_convection": "thermal",
          # set ZD (sim2real_indep.effects_zd; soft_float, a Cartesian soft-float compliance yielding to the tool's and
          # part's weight in the tool frame, and torque_crosstalk, joint torque sensors' bending-moment crosstalk in a
          # torque-controlled arm, scored as joint compliance; floating_sun, a planetary stage's floating-sun play that
          # the load takes up, and spline_drag, tool_changer's wrist play whose flank the telescope's last stroke
          # chooses, as backlash (lost motion in a clearance, errors that follow the last motion); readhead_dropout, a
          # diametric read-head pair whose averaging lapses in some blocks, and range_shift, a range-change gearbox's
          # rounded low-range ratio, as transmission (the joints' reading and drive); levelling_valves, air mounts
          # re-levelled by valves with a dead band, and scissor_lift, a scissor lift table heaved by its cylinder's oil
          # column, as mount compliance (the robot's support); curing_bond, a tool boom whose root bond stiffens as it
          # cures, and drive_tendons, the forearm bent by the wrist's drive tendons, as link deflection; bake_booth,
          # the arm in a paint booth whose unlogged air follows its flash-off schedule, and gun_warmup, a tool bracket
          # warmed by a hot-melt gun's warm-up, as thermal)
          "soft_float": "joint_compliance", "torque_crosstalk": "joint_compliance", "floating_sun": "backlash",
          "spline_drag": "backlash", "readhead_dropout": "transmission", "range_shift": "transmission",
          "levelling_valves": "mount_compliance", "scissor_lift": "mount_compliance",
          "curing_bond": "link_deflection", "drive_tendons": "link_deflection", "bake_booth": "thermal",
          "gun_warmup": "thermal",
          # set ZE (sim2real_indep.effects_ze; tether_reel, the gears twisted by a constant-force tether's pull towards
          # a fixed anchor, and ball_reducer, the Hertzian twist of ball reducers, scored as joint compliance;
          # rotary_clamp, axis 1's flank chosen by a clamp, and noback_brake, a no-back brake's release travel, as
          # backlash; disc_shift, axis 1's encoder disc shifted by the bearing's tilt, and reversal_counts, a decoder's
          # count gained per reversal, as transmission; slender_pedestal, a riser's P-delta tilt, and slewing_rock, a
          # slewing ring's tilting clearance, as mount compliance; shuttle_boom, a boom bent by a parked carriage, and
          # ringing_boom, a boom's residual vibration, as link deflection; holding_heat, the links warmed by the
          # motors' holding copper loss, and pcm_tool, a bracket on a phase-change heat sink, as thermal)
          "tether_reel": "joint_compliance", "ball_reducer": "joint_compliance", "rotary_clamp": "backlash",
          "noback_brake": "backlash", "disc_shift": "transmission", "reversal_counts": "transmission",
          "slender_pedestal": "mount_compliance", "slewing_rock": "mount_compliance",
          "shuttle_boom": "link_deflection", "ringing_boom": "link_deflection", "holding_heat": "thermal",
          "pcm_tool": "thermal",
          # set ZF (sim2real_indep.effects_zf; bungee_cord, the gears twisted by an elastic cord's stretch towards an
          # overhead eye, and warm_preload, joints stiffening as their preload grows with warming, scored as joint
          # compliance; viscous_crossing, the output crossing its lash in the dwell against an oil film, and
          # centring_spring, the output held inside its clearance by a centring spring, as backlash; repaired_sector, a
          # re-cut sector of axis 1's gear, and sagging_disc, a wrist encoder disc sinking on its hub, as transmission;
          # shelf_bracket, the base on a cantilevered shelf, and shim_friction, the base slipping on its shims, as mount
          # compliance; polymer_boom, a printed boom softening as the air warms, and flange_gapping, a tool flange
          # opening past its preload, as link deflection; peltier_loop, a bracket on a PID-run Peltier cooler, and
          # marking_pulses, a bracket warmed by a marking laser's pulses, as thermal)
          "bungee_cord": "joint_compliance", "warm_preload": "joint_compliance", "viscous_crossing": "backlash",
          "centring_spring": "backlash", "repaired_sector": "transmission", "sagging_disc": "transmission",
          "shelf_bracket": "mount_compliance", "shim_friction": "mount_compliance",
          "polymer_boom": "link_deflection", "flange_gapping": "link_deflection", "peltier_loop": "thermal",
          "marking_pulses": "thermal",
          # set ZG (sim2real_indep.effects_zg; gravcomp_payload, an impedance-controlled arm yielding to the part's
          # weight beyond the load its gravity compensation declares, and taut_harness, axis 1 twisted by its supply
          # bundle past the bundle's slack, scored as joint compliance; tilt_flank, axis 1's lost motion flanked by an
          # inclined installation's gravity torque, and coast_flank, the loaded axes' lost motion crossed by the link's
          # inertia at a fast move's end, as backlash; chipped_pinion, axis 1's pinion with a chipped tooth, and missing_pin,
          # axis 2's RV reducer with a broken ring pin, as transmission; settlement_tilt, the foundation settling
          # unevenly in time, and bolt_relaxation, the base's anchor bolts relaxing, as mount compliance; beam_column,
          # a slender boom whose bending the axial load amplifies, and leaf_boom, a flat-bar boom bending towards its
          # weak axis, as link deflection; drying_film, the links held below the air by an evaporating film, and
          # rotary_union, a bracket warmed by the seals of a rotary union that axis 6 turns, as thermal)
          "gravcomp_payload": "joint_compliance", "taut_harness": "joint_compliance", "tilt_flank": "backlash",
          "coast_flank": "backlash", "chipped_pinion": "transmission", "missing_pin": "transmission",
          "settlement_tilt": "mount_compliance", "bolt_relaxation": "mount_compliance",
          "beam_column": "link_deflection", "leaf_boom": "link_deflection", "drying_film": "thermal",
          "rotary_union": "thermal",
          # set ZH (sim2real_indep.effects_zh; worn_mesh, axis 2's mesh softened in its worn production zone, and
          # tooth_crack, axis 3's ring softened while a cracked tooth meshes, scored as joint compliance; grease_gel,
          # the loaded axes' lost motion held centred by grease gelled in each pause, and loose_pivot, a target bracket
          # between the stops of a loose pin, as backlash; pinion_handover, axis 1's runout switching between two
          # torque-biased pinions, and running_in_te, axis 2's tooth-mesh error fading as the gears run in, as
          # transmission; brazier_pedestal, a thin tube pedestal softened by ovalisation, and dished_plate, the base on
          # a rim-clamped plate, as mount compliance; inflated_boom, an air-inflated boom wrinkling past a moment, and
          # collet_root, a boom giving in its clamp bush, as link deflection; wrist_conduction, a hot tool's heat
          # diffusing into the forearm, and regen_resistor, a braking resistor on the pedestal heated by the lowering
          # moves, as thermal)
          "worn_mesh": "joint_compliance", "tooth_crack": "joint_compliance", "grease_gel": "backlash",
          "loose_pivot": "backlash", "pinion_handover": "transmission", "running_in_te": "transmission",
          "brazier_pedestal": "mount_compliance", "dished_plate": "mount_compliance",
          "inflated_boom": "link_deflection", "collet_root": "link_deflection", "wrist_conduction": "thermal",
          "regen_resistor": "thermal",
          # set ZI (sim2real_indep.effects_zi; pi_load_step, the loaded axes' PI loops still recovering from the pose's
          # load step, and helix_tilt, the outputs tilted by their helical stages' axial thrust, scored as joint
          # compliance; dog_play, axis 1 twisted by its dress pack inside the wide play of its guide's dog, and
          # free_swivel, the target on a friction-held swivel hanging downhill, as backlash (errors that follow the path
          # through a play or a friction band); flank_profile, axis 2's mesh error switching with the loaded flank, and
          # cage_runout, axis 1's encoder misread by its bearing's cage-borne runout, as transmission; gravel_ratchet,
          # the base on a granular bed densifying under each move's moment, and crowned_sole, an unanchored base rocking
          # on its bowed sole against its weight, as mount compliance; bernoulli_grip, a part floating on a Bernoulli
          # gripper's air film, and jamming_grip, a part in a jamming gripper locked at each block's start, as link
          # deflection (the end-of-arm structure carrying the target); thermosyphon, the forearm cooled by a heat pipe
          # that works with the wrist end down, and motion_cooling, the upper arm and forearm cooled by the air they
          # move through, as thermal)
          "pi_load_step": "joint_compliance", "helix_tilt": "joint_compliance", "dog_play": "backlash",
          "free_swivel": "backlash", "flank_profile": "transmission", "cage_runout": "transmission",
          "gravel_ratchet": "mount_compliance", "crowned_sole": "mount_compliance",
          "bernoulli_grip": "link_deflection", "jamming_grip": "link_deflection", "thermosyphon": "thermal",
          "motion_cooling": "thermal",
          # set ZJ (sim2real_indep.effects_zj; gauge_zero_drift, joint torque sensors' thermal zero drift that a joint-
          # impedance controller turns into joint offsets, and traction_microslip, traction-roller wrist reducers
          # yielding by Mindlin micro-slip with Masing's memory, scored as joint compliance; gyro_filter, link angles
          # from gyro-aided inclination sensors whose complementary filter still carries the last moves' gyro scale
          # error, and wind_flank, axis 1's lost motion whose flank a steady wind's torque chooses, as backlash (errors
          # that follow the last motion); stepper_stall, open-loop stepper wrists losing steps in loaded, fast moves,
          # and ghost_order, axis 1's wheel carrying its hobbing machine's index order, as transmission (the joints'
          # drive); hydrostatic_rail, the base on a carriage held by opposed constant-flow hydrostatic pads, and
          # clay_pier, the base on a pair of short piers in soft clay, as mount compliance; gecko_pad, a part on a
          # directional dry adhesive stiffened by its shear, and warm_sag, a warm moulding creeping under its weight's
          # history, as link deflection (the end-of-arm structure carrying the target); stray_weld_current, the main
          # bearings heated by a welding current returning through the arm, and plume_bracket, a bracket heated by a hot
          # part's plume while the tool points down, as thermal)
          "gauge_zero_drift": "joint_compliance", "traction_microslip": "joint_compliance", "gyro_filter": "backlash",
          "wind_flank": "backlash", "stepper_stall": "transmission", "ghost_order": "transmission",
          "hydrostatic_rail": "mount_compliance", "clay_pier": "mount_compliance", "gecko_pad": "link_deflection",
          "warm_sag": "link_deflection", "stray_weld_current": "thermal", "plume_bracket": "thermal",
          # set ZK (sim2real_indep.effects_zk; kt_magnet_drift, the gravity feed-forward of current-based compliant
          # control falling short as the motors' magnets warm, and capstan_spans, a cable-capstan stage whose free spans
          # change length with the joint's angle, scored as joint compliance; sensor_hysteresis, joint torque sensors'
          # hysteresis read by a joint-impedance controller (an error following the load's last change), and
          # housing_spread, axis 1's lost motion widened as its housing spreads under the tilting moment, as backlash;
          # quench_ovality, axis 1's ring gear left out of round by its hardening, and ride_height, axis 1's magnetic
          # ring encoder read across an air gap that the axial load sets, as transmission; beam_torsion, the base on a
          # single I-beam twisting about its axis, and asphalt_creep, the base's pads creeping into a sun-warmed asphalt
          # yard, as mount compliance; flange_buckling, a sheet-metal bracket whose free flange buckles when bent one
          # way, and dashpot_slide, a tool on a spring-and-dashpot compliance slide, as link deflection (the end-of-arm
          # structure carrying the target); drive_board_heat, the link tubes warmed by the drives built into the joints,
          # and ram_wiper_heat, the telescopic ram warmed by its wipers' friction, as thermal)
          "kt_magnet_drift": "joint_compliance", "capstan_spans": "joint_compliance",
          "sensor_hysteresis": "backlash", "housing_spread": "backlash", "quench_ovality": "transmission",
          "ride_height": "transmission", "beam_torsion": "mount_compliance", "asphalt_creep": "mount_compliance",
          "flange_buckling": "link_deflection", "dashpot_slide": "link_deflection", "drive_board_heat": "thermal",
          "ram_wiper_heat": "thermal",
          # set ZL (sim2real_indep.effects_zl; idle_current, stepper wrists sagging as their drivers cut the holding
          # current at standstill, and kt_saturation, current-based wrist control whose motors' torque constant
          # saturates at high currents, scored as joint compliance; current_remanence, Hall current sensors magnetised by the last
          # large current under current-based joint control (an error following the last moves, reset at each servo
          # enable), and hose_bourdon, a wrist roll's lash flank chosen by a pressurised gripper hose while a part is
          # held, as backlash; stator_leakage, output magnetic encoders misread by the motor's current-borne leakage
          # field, and step_truncation, stepper wrists short by the running sum of truncated step counts, as
          # transmission (the joints' reading and drive); raised_floor, the base on an access floor's panels and
          # pedestals, and load_cells, the base on a weighing platform's load cells, as mount compliance; ft_sensor, a force/torque sensor's flexure between flange and tool, and pad_pivot, a part
          # pivoting between soft finger pads, as link deflection (the end-of-arm structure carrying the target);
          # thermal_ratchet, link tubes growing through their fits' friction, and arc_radiation, the forearm heated by
          # the welding arc's radiation, as thermal)
          "idle_current": "joint_compliance", "kt_saturation": "joint_compliance",
          "current_remanence": "backlash", "hose_bourdon": "backlash", "stator_leakage": "transmission",
          "step_truncation": "transmission", "raised_floor": "mount_compliance", "load_cells": "mount_compliance",
          "ft_sensor": "link_deflection", "pad_pivot": "link_deflection", "thermal_ratchet": "thermal",
          "arc_radiation": "thermal",
          # set ZM (sim2real_indep.effects_zm; moment_softening, wrist gears whose torsional stiffness falls with the
          # tilting moment on their output bearing, and mesh_ripple, wrist strain-wave gears whose mesh stiffness
          # ripples with the wave generator's angle, scored as joint compliance; upstream_toss, a wrist bend's lost
          # motion tossed onto a flank by the main axes' deceleration, and limiter_play, a ball-detent torque limiter's
          # seat play flanked by the off-axis tool's weight, as backlash; microstep_error, stepper wrists short of their
          # microsteps, and step_accuracy, their full steps off by the motors' tooth-pitch errors, as transmission (the
          # joints' drive); conical_mounts, the base on hardening cone mounts, and rail_blocks, the base on a parked
          # track carriage's profile-rail blocks, softer pulled than pressed, as mount compliance; mandrel_rock, a part rocking on an
          # expanding mandrel's sleeve, and jaw_guide_tilt, a gripper's jaws tilting in their rail guides, as link
          # deflection (the end-of-arm structure carrying the target); mean_radiant, links at the operative
          # temperature of the drifting air and the lagging envelope, and enclosure_door, a conditioned cell opened at
          # each loading, as thermal)
          "moment_softening": "joint_compliance", "mesh_ripple": "joint_compliance", "upstream_toss": "backlash",
          "limiter_play": "backlash", "microstep_error": "transmission", "step_accuracy": "transmission",
          "conical_mounts": "mount_compliance", "rail_blocks": "mount_compliance",
          "mandrel_rock": "link_deflection", "jaw_guide_tilt": "link_deflection", "mean_radiant": "thermal",
          "enclosure_door": "thermal",
          # set ZN (sim2real_indep.effects_zn; hygro_gear, polymer wrist gears softened by the water they take up
          # after a washdown, and payload_estimator, a cobot's on-line payload identification lagging each part
          # change, scored as joint compliance; load_holding_valve, a hydraulic boom dropping as its holding valves
          # close after a lowering move, and roll_endplay, a roll bearing's end play crossed by the axial weight, as
          # backlash; rope_lay, a capstan stage's rope-lay waviness, and magnetostrictive_rod, the telescopic stage's
          # magnetostrictive sensor, as transmission; wire_rope_isolators and focalised_mounts, the base on wire-rope
          # isolators and on inclined focalised mounts, as mount compliance; dovetail_gib, a tool-side dovetail slide,
          # and bellows_coupling, a tool on a bellows coupling, as link deflection; radiant_tube_heater, tubes bowed by
          # the roof's radiant heaters, and dragging_brake, axis 2 warmed by its dragging brake, as thermal)
          "hygro_gear": "joint_compliance", "payload_estimator": "joint_compliance",
          "load_holding_valve": "backlash", "roll_endplay": "backlash", "rope_lay": "transmission",
          "magnetostrictive_rod": "transmission", "wire_rope_isolators": "mount_compliance",
          "focalised_mounts": "mount_compliance", "dovetail_gib": "link_deflection",
          "bellows_coupling": "link_deflection", "radiant_tube_heater": "thermal", "dragging_brake": "thermal",
          # set ZO (sim2real_indep.effects_zo; gravity_table, a soft servo's gravity feed-forward read from a coarse
          # table, and entrained_air, the telescopic ram's cylinder softened by the air in its loaded chamber, scored
          # as joint compliance; differential_lash, a differential wrist's two side-gear trains' lost motions, and
          # tensioner_stop, a wrist belt's tensioner arm pushed to its stop when its span is the tight one, as
          # backlash; race_waviness, axis 1's encoder read on a wavy bearing raceway, and lever_cam_fit, hydraulic
          # axes driven through a fitted cam polynomial, as transmission; deck_cupping, a cart deck cupping as its
          # underside takes up moisture, and closed_cell_pads, the stand on gas-stiffened foam pads, as mount
          # compliance; cross_spring_pivot, a tool on a load-stiffened flexure pivot, and qzs_mount, a sensor on a
          # quasi-zero-stiffness isolator, as link deflection; ultrasonic_ram, the telescopic stage read by an
          # ultrasonic sensor whose compensation lags the air (a reading following the air, as set C's tracker scale),
          # and dry_ice_nozzle, a tool bracket chilled by dry-ice blasting, as thermal)
          "gravity_table": "joint_compliance", "entrained_air": "joint_compliance",
          "differential_lash": "backlash", "tensioner_stop": "backlash", "race_waviness": "transmission",
          "lever_cam_fit": "transmission", "deck_cupping": "mount_compliance",
          "closed_cell_pads": "mount_compliance", "cross_spring_pivot": "link_deflection",
          "qzs_mount": "link_deflection", "ultrasonic_ram": "thermal", "dry_ice_nozzle": "thermal",
          # set ZP (sim2real_indep.effects_zp; soaked_jacket, a drying jacket's water on the links, and vessel_list,
          # gravity turning in the base frame as a vessel lists, scored as joint compliance (the gears twisted);
          # clevis_clearance, the boom cylinders' eye-pin clearances seen through their lever arms, and
          # clock_spring_flank, the wrist rolls' lost motion whose flank a spiral spring's wind-up chooses, as backlash;
          # mylar_strip, axis 1's polyester code strip swelling with the humidity, and tacho_integration, boom axes
          # read by integrating tachogenerators, as transmission (the joints' reading); magnet_base, a magnetically
          # clamped base on its rough interface, and ballast_stand, an unanchored stand lifting a foot, as mount
          # compliance; needle_gripper, a part on a needle gripper, and ltb_boom, a gripper boom near lateral-torsional
          # buckling, as link deflection; heated_bed, the forearm warmed by a heated bed by where the arm has worked,
          # and air_motor_heat, a spindle's extension following the compressor-cycled supply air, as thermal)
          "soaked_jacket": "joint_compliance", "vessel_list": "joint_compliance",
          "clevis_clearance": "backlash", "clock_spring_flank": "backlash", "mylar_strip": "transmission",
          "tacho_integration": "transmission", "magnet_base": "mount_compliance",
          "ballast_stand": "mount_compliance", "needle_gripper": "link_deflection", "ltb_boom": "link_deflection",
          "heated_bed": "thermal", "air_motor_heat": "thermal"}
#: the families the diagnosis names (issue 40), in the report's column order
FAMILIES = ["joint_compliance", "mount_compliance", "link_deflection", "backlash", "thermal", "transmission"]


@dataclass
class Ctx:
    """A robot model at the session's poses: chain, mass model, payload placement and probe."""

    chain: kin.Chain
    session: Session
    masses: np.ndarray
    com: np.ndarray
    mass_link: tuple
    payload_com_mm: np.ndarray  # payload centre of mass in the tool frame
    probe_mm: np.ndarray

    @property
    def q(self):
        return self.session.q

    @cached_property
    def mass_index(self):
        """Chain link index of each mass (payload: past the last link)."""
        idx = [self.chain.link_names.index(n) for n in self.mass_link]
        return np.array(idx + [len(self.chain.link_names)])

    @cached_property
    def mass_state(self):
        """Masses (P, B+1) [kg] with the payload last, their positions (P, B+1, 3) [mm] and bodies (B+1,)."""
        ch, P = self.chain, len(self.q)
        body = np.r_[np.array([ch.link_body[i] for i in self.mass_index[:-1]], int), ch.n]
        pos = kin.mass_positions(ch, self.q, com=self.com, body=body[:-1])
        p, Rt = kin.flange(ch, self.q)
        pay = p + Rt @ self.payload_com_mm
        m = np.hstack([np.broadcast_to(self.masses, (P, len(self.masses))), self.session.payload_kg[:, None]])
        return m, np.concatenate([pos, pay[:, None]], axis=1), body

    @cached_property
    def loads(self):
        """Static gravity load on each joint (P, n) [N m / N]."""
        m, pos, body = self.mass_state
        return kin.gravity_loads(self.chain, self.q, m, pos, body)

    @cached_property
    def target(self):
        return kin.target(self.chain, self.q, self.probe_mm)

    @cached_property
    def jac(self):
        return kin.position_jacobian(self.chain, self.q, self.target)

    def joint_feature(self, j, signal):
        """Displacement (P, 3) of the target for a joint offset ``signal`` (P,) on joint j."""
        return self.jac[:, :, j] * signal[:, None]

    def link_scale_feature(self, link_mask):
        """Displacement (P, 3) [mm] of the target when the links in ``link_mask`` (L,) stretch by a unit strain."""
        R, _ = kin.body_transforms(self.chain, self.q)
        ch = self.chain
        out = np.zeros((len(self.q), 3))
        for li in np.flatnonzero(link_mask):
            out += R[:, ch.link_body[li]] @ ch.links[li]
        return out


@dataclass
class Contribution:
    dq: np.ndarray | None = None          # joint offsets (P, n)
    strain: np.ndarray | None = None      # link strains (P, L)
    displace: np.ndarray | None = None    # target displacements (P, 3) [mm], base frame

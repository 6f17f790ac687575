"""Physical effect models in physical units, fed by the robot's component data: one implementation each, used by
the diagnosis (fitted to measurements) and by the design (sampled from catalogue figures).

* :mod:`.loads` -- the mass model, gravity loads on the joints and on the base mount, a payload at the target;
* :mod:`.compliance` -- joint wind-up (linear, the catalogue's K1/K2/K3 bands, a smooth hardening law), a joint
  bearing's tilt under the moment across its axis, and the tilt (and rocking) of a compliant mount;
* :mod:`.mount_creep` -- a mount that creeps under the moment it holds (a delayed compliance, a viscous flow);
* :mod:`.beams` -- arm segments bending and shearing as cantilevers; a telescopic stage tilting in its guide;
* :mod:`.transmission` -- kinematic error of gears and encoders at the orders 1, N and 2N of the gear ratio;
* :mod:`.error_motions` -- a linear axis' six error motions along its stroke (ISO 230-1);
* :mod:`.lost_motion` -- backlash and hysteresis loss: the flank a joint rests on;
* :mod:`.clearance` -- the joints' bearing play (axial, radial, tilt), taken up on the side the load presses;
* :mod:`.blocks` -- runs of a session between tool changes or power cycles, with an offset per run;
* :mod:`.seating` -- a tool re-seated within its coupling's clearance at every tool change (payload blocks);
* :mod:`.rehoming` -- incremental encoders' zeros homed anew at each power-up (blocks between pauses);
* :mod:`.thermal` -- link growth driven by the logged temperature, a warm-up, the motion history, the motors'
  losses or a held part, with first-order heating and cooling; links bowing, joint axes tilting, the measuring frame
  drifting;
* :mod:`.thermal_scale` -- a declared position scale growing with the air temperature (``c_j q_j dT``);
* :mod:`.thermal_design` -- the design's forward model: the links' temperatures over an ambient range and a duty cycle.
"""

from tolalloc.physics.beams import beam_columns, beam_sag, deflection_segments, guide_columns, guide_joints
from tolalloc.physics.compliance import (COMPLIANCE_LAWS, bearing_tilt, compliance_columns, joint_loads, joint_windup,
                                         mount_columns, mount_tilt)
from tolalloc.physics.loads import (G, base_moment, gravity_torques, joint_wrenches, point_jacobian, robot_masses,
                                    target_points, tip_load)
from tolalloc.physics.clearance import clearance_columns
from tolalloc.physics.error_motions import stroke_columns
from tolalloc.physics.lost_motion import SIDES, flank, lost_motion_basis, lost_motion_columns
from tolalloc.physics.thermal import link_growth
from tolalloc.physics.thermal_history import lag_filter, motor_heat, time_problem
from tolalloc.physics.transmission import gear_orders, transmission_columns, transmission_error

__all__ = ["beam_columns", "beam_sag", "deflection_segments", "guide_columns", "guide_joints", "COMPLIANCE_LAWS",
           "compliance_columns", "joint_loads", "joint_windup", "mount_columns", "mount_tilt", "bearing_tilt", "G",
           "base_moment",
           "gravity_torques", "point_jacobian", "robot_masses", "target_points", "tip_load", "SIDES", "flank",
           "lost_motion_basis", "lost_motion_columns", "lag_filter", "link_growth", "motor_heat", "time_problem",
           "gear_orders", "transmission_columns", "transmission_error", "stroke_columns",
           "clearance_columns", "joint_wrenches"]

"""report.md of the independent benchmark, written from the cases table (run.py)."""

from __future__ import annotations

import os

import numpy as np
import pandas as pd

from sim2real_indep.context import FAMILIES

SHORT = {"joint_compliance": "joint", "mount_compliance": "mount", "link_deflection": "link",
         "backlash": "backl", "thermal": "therm", "transmission": "trans"}

HEAD = """# Independent sim-to-real benchmark (issue 40, part 7)

**This is an independent benchmark.** Its physics was written from the literature by a helper who never read
tolalloc's effect code, fitted bases, own blind benchmark or diagnosis docs; the generator
(`studies/sim2real_independent/generator.py` and its modules) imports nothing of tolalloc -- its own robot-file
parser, forward kinematics, mass model and physics (tests/test_sim2real_independent.py checks the imports and
the kinematics against tolalloc's to 1e-9 mm). The diagnosis is called through the public API only:
`tolalloc.diagnose_measurements(robot, train_df, test_df)` with default settings (`folds=3` for cases of 60
poses or fewer).

**What it measures:** whether the diagnosis names the physical effect that a truth-aware oracle says the data can
name -- on effects whose shapes the diagnosis was not written against (gear ratios it is not told, heat from drive
activity, hardening gear stiffness, a compliant mount, tube sag under a changing payload, lost motion with
gravity preload) -- and whether it stays quiet where the data cannot name anything. It does not measure how close
the diagnosis's own fitted model comes to the truth beyond the RMS ratio reported below.

Regenerate: `python studies/sim2real_independent/run.py --set A --jobs 2` (set B, the held-out set:
`--set B`; both: `--set both`; set C: `--set C`; set D: `--set D`; set E: `--set E`; set F: `--set F`; set G:
`--set G`; set H: `--set H`; set I: `--set I`; set J: `--set J`; set K: `--set K`; set L: `--set L`; set M: `--set M`; set N: `--set N`; set O: `--set O`; set P: `--set P`; set Q: `--set Q`; set R: `--set R`; set S: `--set S`; set T: `--set T`; set U: `--set U`; set V: `--set V`; set W: `--set W`; set X: `--set X`; set Y: `--set Y`; set Z: `--set Z`; set ZA: `--set ZA`; set ZB: `--set ZB`; set ZC: `--set ZC`; set ZD: `--set ZD`; set ZE: `--set ZE`; set ZF: `--set ZF`; set ZG: `--set ZG`; set ZH: `--set ZH`; set ZI: `--set ZI`; set ZJ: `--set ZJ`; set ZK: `--set ZK`; set ZL: `--set ZL`; set ZM: `--set ZM`; set ZN: `--set ZN`; set ZO: `--set ZO`; set ZP: `--set ZP`; all forty-two: `--set all`; labels alone, without diagnosing:
`--oracle-only`). The measurement tables are regenerated from the seeds and never stored.

**Set C** (24 cases, seed 40_7003) was written after the diagnosis had been tuned while looking at sets A and B:
its physics kinds are variants neither set contains (`sim2real_indep/effects_c*.py`, table below), so it is the
set that measures how the diagnosis does on physics it was not built against.

**Set D** (24 cases, seed 40_7004) is a further independent test set of twelve new physics kinds
(`sim2real_indep/effects_d*.py`, table below), written by a helper who did not read the diagnosis or its effect
models, and meant to be run once to judge a change of the diagnosis.

**Set E** (24 cases, seed 40_7005) is another independent test set of twelve new kinds
(`sim2real_indep/effects_e*.py`, table below), written by a helper who read neither the diagnosis, its effect
models, nor the results of sets A-D. It was run once, on the code of this report, as an unseen judge: nothing in
the diagnosis was changed after its results were seen.

**Set F** (24 cases, seed 40_7006) is a sixth independent test set of twelve new kinds
(`sim2real_indep/effects_f*.py`, table below), written from the literature by a helper who read neither the
diagnosis, its effect models, nor any result of sets A-E, and who did not run the diagnosis. It was first run on
the code of this report, after the last change of the diagnosis (the thermal `bow` variant) was committed; nothing
in the diagnosis was changed after its results were seen.

**Set G** (24 cases, seed 40_7007) is a seventh independent test set of twelve new kinds
(`sim2real_indep/effects_g*.py`, table below), written from the literature by a helper who read neither the
diagnosis, its effect models, nor any result of sets A-F, and who did not run the diagnosis (its brief listed a
few example effects to show the breadth wanted; it chose its own). It was first run on the code of this report,
after the session's last change of the diagnosis (the lost-motion flank convention and the `preload+hysteresis`
variant) was made; nothing in the diagnosis was changed after its results were seen. The same cases diagnosed by
the code before those changes score the same.

**Set H** (24 cases, seed 40_7008) is an eighth independent test set of twelve new kinds
(`sim2real_indep/effects_h*.py`, table below), written the same way by another helper, whose brief named no
example effects. It was first run on the code of this report, after set G had been judged and with nothing in the
diagnosis changed since; the code before this release's lost-motion changes scores one case fewer on it (H08,
whose grease friction holds the output trailing its last motion, was `ambiguous`).

**Set I** (24 cases, seed 40_7009) is a ninth independent test set of twelve new kinds
(`sim2real_indep/effects_i*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-H, and who did not run the diagnosis (its brief named no
example effects). It was first run once the diagnosis of this report was final (its tie rule by the model evidence
settled on sets A-H), and once on the code before this release's tie rule, which scores one case fewer on it
(I14, a base installed tilted, was `ambiguous` between joint and mount compliance).

**Set J** (24 cases, seed 40_7010) is a tenth independent test set of twelve new kinds
(`sim2real_indep/effects_j*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-I, and who did not run the diagnosis (its brief listed a few
example mechanisms; it chose its own). It was first run once on the code as it stood when set I had been judged:
17/24 strict, 18 lenient, no false claim, median final / oracle RMS 1.40 (J05 and J14, a brake-heated housing
tilting an axis, and J06, a laminate twisting with the air, were `none`). The thermal axis tilt (`tilt_<tau>min`) and
the first step's test of the family the evidence singles out were written after those misses were seen, so the set
J figures below measure the code that was fitted to them, not its accuracy; set K judges it.

**Set K** (24 cases, seed 40_7011) is an eleventh independent test set of twelve new kinds
(`sim2real_indep/effects_k*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-J, and who did not run the diagnosis (its brief named no
example mechanisms). It was first run once on the code that set J's misses had shaped (the thermal axis tilt, the
test of the family the evidence singles out, the drift between the measuring frame and the base), none of it written
while looking at set K: 12/24 strict, 17 lenient, no false claim, median final / oracle RMS 1.54 (the remote-centre
compliance of K02 and K18 called joint compliance, K07 inconclusive; the spline twist K15 called link deflection;
the ram roll K13 `none`). Two variants were written after those misses were seen -- link deflection's `flange` (a
compliant element between the flange and the tool) and transmission's `coupling` (a joint turning with another
joint's position) -- so the set K figures below measure code fitted to them; set L judges it.

**Set L** (24 cases, seed 40_7012) is a twelfth independent test set of twelve new kinds
(`sim2real_indep/effects_l*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-K, and who did not run the diagnosis (its brief named no
example mechanisms). It was first run once on the code that set K's misses had shaped (the `flange` and `coupling`
variants), none of it written while looking at set L: 13/24 strict, 14 lenient, no false claim, median final / oracle
RMS 1.63 (a growing pallet on the base frame, L03 and L18, hot parts, L20, grip-spread fingers, L04 and L14, the
telescopic guideway's error motions, L12, and a hydraulic dead band, L10, were `none`; loosening anchors, L13, were
called thermal). One variant was written after those misses were seen -- transmission's `stroke` (a linear axis'
error motions along its stroke) -- so the set L figures below measure code fitted to it; set M judges it.

**Set M** (24 cases, seed 40_7013) is a thirteenth independent test set of twelve new kinds
(`sim2real_indep/effects_m*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-L, and who did not run the diagnosis. Its independence is
weaker than the earlier sets': the helper's brief reached it empty, and before finding the written brief it read the
subject lines of the latest commits, which name the diagnosis's newest variants (among them the `flange` variant of a
compliant element between the flange and the tool). Two of its link kinds sit there (the wire-rope tool mount and the
tie-rod gripper bar: M03, M06, M08, M19, M22). It was run once, on the code of the release that added it (after set L's misses had
shaped the `stroke` variant, nothing written while looking at set M); the code before the `stroke` variant scores one
case fewer (M11, a telescopic stage pulled by a roller chain, was `ambiguous`).

**Set N** (24 cases, seed 40_7014) is a fourteenth independent test set of twelve new kinds
(`sim2real_indep/effects_n*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-M, and who did not run the diagnosis (by its own report it
read nothing of them; a search for its own placeholder names ran over the three files it must not read and found
nothing, and it counted their lines). It was run once, on the code that set M's misses had shaped (the `clearance`
variant of backlash and the `play` variant of mount compliance; the code before them scores the same, 11/24), none of
it written while looking at set N: 11/24 strict, 11 lenient, no false claim, median final / oracle RMS 2.83; right on
5 of 7 effect cases where the true family's generic model helps, 3 of 14 where it does not. Unlogged forces at the
tool (a jet's reaction, N09, N16, N17, wind on a carried panel, N01) were `none` or thermal; the tracker's tripod
tilting with heat (N14, N21) was thermal but did not transfer to the later test file (`inconclusive`); magnetic
encoders drifting with heat (N06, N22), a rope creeping on its sheave (N12) and a truss boom's pin clearances on the
tool changer (N13) were `none`; a counterbalanced axis 2's lost motion (N11, N20) was named joint compliance and
transmission. A variant written after those misses were seen (an unknown constant force at the target winding the
joints up, in the tool frame or across gravity) changed no set N verdict -- the jet runs only in some blocks and the
wind gusts -- and cost other sets a right name (J17); it was not kept, so the set N figures below are those of its
one judging run.

**Set O** (24 cases, seed 40_7015) is a fifteenth independent test set of twelve new kinds
(`sim2real_indep/effects_o*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-N, and who did not run the diagnosis (a first helper, whose
brief reached it empty, read the subject lines of the latest commits and stopped before writing anything: it named
that exposure and handed the set back; a fresh helper with the written brief wrote it). It was run once, on the code
as it stood after set N had been judged -- nothing in the diagnosis changed since, only refusal texts and one shared
helper of the clearance and play columns, bit-identical -- none of it written while looking at set O: 15/24 strict,
15 lenient, no false claim, median final / oracle RMS 1.47; right on 7 of 7 effect cases where the true family's
generic model helps, 5 of 14 where it does not. Seven of its nine misses are forces at the tool that no column of the
data carries: the gears twisted by a milling cut whose feed direction changes from pose to pose (O01, O17) and by a
nutrunner's reaction (O09, O24), a spindle bracket bent by the cut (O04), a weld gun's C-frame opened by its squeeze
(O11), axis flanks chosen by the cutting torque (O02), all `none`; on them no family's generic model gains over
geometry alone either (the oracle's truth-structure fit knows the force at every pose). The other two are a
quantised output encoder's in-position dead band (O06, O14), which stops the axis short of its target on the side
it came from and was named backlash.

**Set P** (24 cases, seed 40_7016) is a sixteenth independent test set of twelve new kinds
(`sim2real_indep/effects_p*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-O, and who did not run the diagnosis. It was run once, on the
code as it stood after set O had been judged -- the diagnosis had gained the logged process wrench (columns no set P
case carries, so nothing of it acts there), a per-axis probe-offset prior and refusal texts, none of it written while
looking at set P: 14/24 strict, 14 lenient, no false claim, median final / oracle RMS 1.39; right on 9 of 11 effect
cases where the true family's generic model helps, 2 of 10 where it does not. Most misses are again drivers no column
carries, all `none`: the fixed platen of a moulding machine tilting while the mould is clamped (P03, P21), a foundry
jacket's thermostat cycle that the logged hall air does not see (P05, and with a vacuum plate in P24), and tools whose
locating pins land anywhere in their clearance at each tool change (P06, P10, P19: a new target offset per block,
which the logged tool weight marks but no family models). A slender dispensing lance bent by its hose was named
transmission (P04) or a transmission / joint compliance tie (P22), and the mixture of a slack belt and pole-pitch
encoder errors a three-way tie (P16). The tool re-seat per tool change written after these misses (backlash
`reseat`) names P06 and P19 in the tables below (16/24 on the code as it stands); a re-run after a set's misses were
seen is not a judgement of the set -- set R judges it.

**Set Q** (24 cases, seed 40_7017) is a seventeenth independent test set of twelve new kinds
(`sim2real_indep/effects_q*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-P, and who did not run the diagnosis. It was run once, on the
code as it stood after set P had been judged -- the logged process wrench now also in link deflection and the
identified model, and a guard on a stated instrument noise (neither acts on set Q, whose data carry no force and whose
runs state no noise), none of it written while looking at set Q: 16/24 strict, 17 lenient, no false claim, median
final / oracle RMS 1.37; right on 12 of 14 effect cases where the true family's generic model helps, 1 of 7 where it
does not. Its misses: a pressurised gooseneck tube straightening while its valve is open (Q04, Q21) and a vacuum
ejector's cold exhaust chilling the gripper boom while a part is held (Q05, Q18), all `none` -- the valve's state is
not logged, and the holding schedule, which the logged payload marks, drives heat no thermal variant follows; a
strain-wave gear's error at the wave-generator bearing's ball-pass rate, a non-integer order of the turn (Q06,
`none`); a servo's overshoot in the direction of motion, scaled by the move's speed (Q02, named transmission); torque
sensors' flexures locked by their overload stops (Q11, a tie won by link deflection); and a base on disc-spring stacks
softening towards flat (Q19, named transmission).

**Set R** (24 cases, seed 40_7018) is an eighteenth independent test set of twelve new kinds
(`sim2real_indep/effects_r*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-Q, and who did not run the diagnosis. It was run once, on the
code as it stood after set Q had been judged -- the diagnosis had gained two effects read from the logged payload's
history, heat exchanged with a held part (thermal `held_<tau>min`) and a tool re-seated at each tool change (backlash
`reseat`), written from the misses of sets P and Q; neither acts on a set-R case -- none of it written while looking
at set R: 10/24 strict, 12 lenient, no false claim, median final / oracle RMS 1.62; right on 5 of 9 effect cases
where the true family's generic model helps, 2 of 12 where it does not. Six of the twelve kinds are driven by
quantities no column carries and four only partly (the helper's own account): the shop air line's pressure under a
pneumatic counterbalance (R09, `none`), a pneumatic tool slide's state (R01 `none`, R12 named link deflection), a
forklift dishing the floor slab while it stands (R03, R14, `none`), a sprayer's tank draining and refilled on a sprung
carrier (R06, R18, hedged over three or four families without the truth in R06), incremental encoders re-homed after
each power-down (R10 named thermal, R19 `none`), a floor cable's friction pulling the flange (R17, and with a heated
hose in R08, `none`), and a swing-away mount beyond its spring's preload (R21 `none`, R11 a link deflection /
backlash tie).

**Set S** (24 cases, seed 40_7019) is a nineteenth independent test set of twelve new kinds
(`sim2real_indep/effects_s*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-R, and who did not run the diagnosis. It was run once, on the
code as it stood after set R had been judged -- the diagnosis had gained transmission `rehome` (offered only for joints
whose encoder the robot file declares incremental, which no study robot file does), none of it written while looking at
set S; the session's other changes were on the design side: 14/24 strict, 15 lenient, no false claim, median final /
oracle RMS 2.13; right on 8 of 10 effect cases where the true family's generic model helps, 3 of 11 where it does not.
Its misses, all `none` but one: a twin robot on the same table tilting it through its own production cycle, nothing of
which is logged (S03, S13, and with motor cogging in S24); motor cogging at Z N periods per output turn, an order the
poses cannot resolve (S06); a measuring wheel on axis 1 whose tread grows with the logged hall air, a scale error of q1
that follows the temperature (S14, S18) -- driven by a logged column, but no thermal variant scales a joint's angle;
a pinion pushed out of mesh above a load threshold on tool_changer (S09; named on kr16_like, S17); a base turning on
its dowels under axis 1's reaction at the start and stop of moves, which `time_s` and the joints only imply (S12; in
S08, beside a flexure on the tool, the flexure is named and the yaw is not); a servo's overshoot carried across the lost motion on
kr16_like (S19; named on ur10, S02); and a booth wall's bellows pulling the forearm on ur10, hedged over three families
with the truth among them (S01; named on kr16_like, S20).

**Set T** (24 cases, seed 40_7020) is a twentieth independent test set of twelve new kinds
(`sim2real_indep/effects_t*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-S, and who did not run the diagnosis. It was run once, on the
code as it stood after set S had been judged -- the diagnosis unchanged since then (the session's changes were on the
design side: ISO 9283's multi-directional accuracy and static compliance, and the ball probability with a mean far
from the centre, which the diagnosis does not use): 14/24 strict, 15 lenient, no false claim, median final / oracle
RMS 1.46; right on 10 of 12 effect cases where the true family's generic model helps, 1 of 9 where it does not. Its
misses: an overhead crane's wheel loads bending the hall column the robot hangs on, nothing of which is logged (T03,
T20, `none`); a hose sliding round a guide ring whose friction follows the hose's last sliding direction, which no
joint's direction column gives (T06, T19, `none`); a tunnel shield squeezed by the rock during the standstill, moving
the console with time alone -- named thermal, the family whose time-driven variants copy a drift (T10, T17: confident
and wrong, where the oracle's generic mount model gains nothing); a leaking gas balancer loading gear 2 more as the
session goes on, likewise named thermal with link deflection (T13; with a plunger's stiction on the tool, T24, hedged
between thermal and joint compliance); and MEMS inclinometers reading axes 2, 3 and 5 with pitch-dependent offset and
gain errors, hedged over four families with the truth among them (T09, and with a laser rangefinder's cyclic error,
T16; the rangefinder alone is named, T11).

**Set U** (24 cases, seed 40_7021) is a twenty-first independent test set of twelve new kinds
(`sim2real_indep/effects_u*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-T, and who did not run the diagnosis. It was run once, on the
code as it stood after set T had been judged -- the diagnosis's choices unchanged (its only change, a reason text
for thermal variants driven by the time alone, moves no verdict): 17/24 strict, 17 lenient, no false claim, median
final / oracle RMS 1.75; right on 13 of 18 effect cases where the true family's generic model helps, 1 of 3 where
it does not. Its misses: a chain drive on axis 3 whose slack strand's sag, and so its lost motion, depends on the
upper arm's inclination, named joint compliance with link deflection (U06, U19: confident and wrong); a spare tool
parked in a holder by the wrist in every other block, which no column logs (U12, U17, `none`); incremental encoders
missing counts in fast moves, an error that accumulates over the session, named thermal (U11; with a magnetic
gripper's coil heating, U08, `none`); and a telescopic extension rocking across its sleeve's clearance towards
gravity's sideways component, named backlash -- a gravity-held flank of the same size, whose final model matches the
oracle's true structure (U21: 0.056 mm both).

**Set V** (24 cases, seed 40_7022) is a twenty-second independent test set of twelve new kinds
(`sim2real_indep/effects_v*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-U, and who did not run the diagnosis. It was run once, on the
code as it stood after set U had been judged -- the diagnosis unchanged since then (the session's only other change
was to a test): 11/24 strict, 13 lenient, no false claim, median final / oracle RMS 1.80; right on 4 of 8 effect
cases where the true family's generic model helps, 4 of 13 where it does not. Its misses: forces and supports no
column logs -- a coiled cord's spring pull from a column (V01, `none`; on tool_changer, V09, named transmission and
mount compliance with confidence, both mimicking it better than geometry, as the oracle's generic transmission model
does), a mobile carrier on its jacks in some blocks and on its wheels in the others (V19, and with ring encoders'
interpolation error, V08, `none`), a carrier levelled on its jacks at each block's start (V12, `none`; hedged with
link deflection, V03); a restrained crossbar's bow, r / (1 - r) of the logged air's lagged rise, along the tool
(V05, V22, `none`: no thermal variant bows a member at the tool, and the oracle's generic thermal model gains
nothing); a printed boom swelling with the hall's humidity as the square root of the time since it left its cabinet
(V06, V21, `none`); a wrist axis whose lost motion's flank follows its motor's net motion through the coupling, which
no direction column logs (V17, `none`; beside a curling slab, V24, only the slab named); and worn pin bushes with a
butted rack on tool_changer, each named alone (V10, V11) but neither together (V16, `none`).

**Set W** (24 cases, seed 40_7023) is a twenty-third independent test set of twelve new kinds
(`sim2real_indep/effects_w*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-V, and who did not run the diagnosis. It was run once, on the
code as it stood after set V had been judged -- the diagnosis unchanged since then except that a box section now
twists by Bredt's torsion constant (the tool changer's beams): 10/24 strict, 12 lenient, no false claim, median
final / oracle RMS 2.02; right on 5 of 10 effect cases where the true family's generic model helps, 2 of 11 where it
does not. Its misses: events no column logs, read as a slow course in time -- output hubs slipping on their shafts at
one emergency stop (W11, W18) and welding noise adding encoder counts in each production gap (W19), all three named
thermal through a variant driven by the time alone, whose reason says a slow process of any kind would fit as well;
a target bracket bent in a collision between blocks (W13, W21) and a hot part cooling in the gripper, a new one at
each block (W05; with the encoder counts, W16), `none`; chips filling a shroud bin during machining, hedged over four
families with the truth among them (W14) and over three (W17, lenient; named with thermal, W01); a balancer's trolley
rolling on an overhead rail (W09, `none`; W22 hedged between backlash and transmission); a part sliding in its nest
towards gravity or its last deceleration, named link deflection at the flange with confidence (W10: a tool-frame
offset that follows gravity, which the flange load also gives), and beside a young grout bed hedged over four
families, the slide read as link deflection (W08).

**Set X** (24 cases, seed 40_7024) is a twenty-fourth independent test set of twelve new kinds
(`sim2real_indep/effects_x*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-W, and who did not run the diagnosis. It was run once, on the
code as it stood after set W had been judged -- the diagnosis unchanged since then (a variant for joint zeros that
step at a pause was tried on sets A-W in between and not kept: it named steps, but it cost as many thermal and
quiet cases of the earlier sets as it gained): 16/24 strict, 16 lenient, no false claim, median final / oracle RMS
1.26; right on 8 of 10 effect cases where the true family's generic model helps, 5 of 11 where it does not. Its
misses: events and drivers no column logs, read as a course in time -- a base plate slipping on its bolted joint in a
collision between blocks (X12, X20), a levelling foot unscrewing with the production's vibration (X06) and a
replaced gear's lash opening as it runs in (X11), all named thermal through a variant driven by the time alone,
whose reason says a slow process of any kind would fit as well; a sheet fanner's magnet pulling on the blank (X01),
the rack lash of a seventh-axis track the file does not know (X02, X22) and a hot wash-down before each block
(X14), `none`.

**Set Y** (24 cases, seed 40_7025) is a twenty-fifth independent test set of twelve new kinds
(`sim2real_indep/effects_y*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-X, and who did not run the diagnosis. It was run once, on the
code as it stood after set X had been judged -- the diagnosis unchanged since then: 14/24 strict, 16 lenient, no false
claim, median final / oracle RMS 1.35; right on 7 of 13 effect cases where the true family's generic model helps, 4
of 8 where it does not. Its misses: a base that moves with the time alone -- a cart's leaking tyre sinking as
exp(t / tau) (Y04, Y20) and a base plate walking under a press's shocks through the production (Y12) -- named
thermal through the drift variant, a translation common to every pose that grows with the time, whose reason reads it
as the measuring frame and the robot's base drifting apart (a settling pedestal among its causes) but which the
diagnosis files under heat; frost gathering on a cold-store arm's links (Y01) and safety brakes closed in some
blocks (Y06), `none`, the brakes on kr16_like hedged between joint compliance and link deflection (Y17, lenient);
encoders turned by their own weight on their torque arms, hedged between link deflection and transmission (Y03,
lenient); grease-damped lost motion still crossing at the dwell, named joint compliance (Y18); vision lamps bowing the
upper arm in every second block, alone (Y09) and beside a gauge pinion's runout (Y24), `none`.

**Set Z** (24 cases, seed 40_7026) is a twenty-sixth independent test set of twelve new kinds
(`sim2real_indep/effects_z*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-Y, and who did not run the diagnosis. It was run once, on the
code as it stood after set Y had been judged -- the diagnosis changed since then only by a check for a single step at a
pause, which adds a finding line beside a thermal verdict driven by the time alone and changes no verdict (it fired on
none of set Z's cases): 16/24 strict, 18 lenient, no false claim, median final / oracle RMS 1.37; right on 9 of 12
effect cases where the true family's generic model helps, 4 of 9 where it does not. Its misses: the laser tracker's
tripod wound up by its head's slews, its frame turned by the sign of the last slew, which no column logs -- `none` on
ur10 (Z02), a mount's compliance on kr16_like (Z22); a base table's dished top plate snapping between its two shapes
as the tipping moment's history swings, `none` on kr16_like (Z20) and hedged between link deflection, the mount and
joint compliance on ur10 (Z04, lenient); a taut harness bowing the upper arm as the elbow bends (Z05), `none`; a
welded gripper frame relaxing its welding stresses with the production time (Z06), inconclusive, leaning thermal; an
outdoor balancer's gas following the air by the gas law (Z11), named thermal -- the logged temperature drives it, but
through the balancer's torque on a joint, not through a link's length; the balancer's rod-seal friction locked
against axis 2's last motion, hedged between backlash and transmission on tool_changer (Z10, lenient).

**Set ZA** (24 cases, seed 40_7027) is a twenty-seventh independent test set of twelve new kinds
(`sim2real_indep/effects_za*.py`, table below; the sets after Z are named ZA, ZB, ...), written the same way by
another helper, who read neither the diagnosis, its effect models, nor any result of sets A-Z, and who did not run the
diagnosis. It was run once, on the code as it stood after set Z had been judged -- the diagnosis unchanged since then:
15/24 strict, 17 lenient, no false claim, median final / oracle RMS 1.57; right on 6 of 10 effect cases where the true
family's generic model helps, 6 of 11 where it does not. Its misses: a gripper bar twisted by parts picked off its
centre line, the offset not logged, `none` (ZA06, ZA20); a wrist belt jumping a tooth at an overload between blocks,
`none` on tool_changer (ZA11) and named thermal on kr16_like (ZA21) -- a step in time read as a course; a slide table
pulled out to another length each block, the extension not logged, `none` (ZA12); hot air from an oven door heating
the forearm in pulses, `none` on one of its two cases (ZA17); a thawing ground under outrigger pads beside inflated
soft fingers, named joint compliance (ZA08); a boom luffed by a rope tackle, hedged between joint compliance and link
deflection (ZA09, lenient); a slide table's overhang beside a scratched scale, hedged between transmission and
backlash (ZA24, lenient).

**Set ZB** (24 cases, seed 40_7028) is a twenty-eighth independent test set of twelve new kinds
(`sim2real_indep/effects_zb*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZA, and who did not run the diagnosis. It was run once, on the
code as it stood after set ZA had been judged -- the diagnosis changed since then only in speed (an effect's ridge
weights on a cross-validation fold computed once per fold instead of once per model; set ZA's cases diagnose
identically): 16/24 strict, 17 lenient, no false claim, median final / oracle RMS 1.61; right on 9 of 11 effect cases
where the true family's generic model helps, 4 of 10 where it does not. Its misses: a torque-controlled arm whose
wrist impedance preset changes per block, the preset not logged, `none` on ur10 (ZB01) and hedged between backlash
and joint compliance on kr16_like (ZB22, lenient); a process hose wrapping round the flange as axis 6 turns and
pulling it once taut, `none` alone (ZB09, ZB19) and beside an air knife's hot curtain (ZB24); a notched holding brake
letting gravity-loaded axes settle onto the next notch, `none` on tool_changer (ZB10); an ultrasonic welding stack
warming in the production between blocks, not logged, `none` (ZB11); joint targets sent over a fieldbus as integers
of 0.01 deg, `none` on tool_changer (ZB13) -- named transmission on kr16_like (ZB17).

**Set ZC** (24 cases, seed 40_7029) is a twenty-ninth independent test set of twelve new kinds
(`sim2real_indep/effects_zc*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZB, and who did not run the diagnosis. It was run once, on the
code with one change of the verdict made after set ZB had been judged and decided on sets A-ZB alone: a tie on a later
effect leaves the verdict `effect` when the first selected effect is clear (it names the clear effects and reports the
tied one as a further effect whose family the data cannot tell, kept in the final model), where before any tie of an
effect with a gain of at least the margin made the whole verdict `ambiguous`. On sets A-ZB it turns 22 `ambiguous`
verdicts into `effect`: 13 now name the truth, 9 name a first effect that is not the truth (which the `ambiguous`
headline also led with); A-ZB score 458 strict (445 before), 491 lenient (489), still no false claim, no other case
changed. The benchmark scores what an `effect` verdict names (its candidates), not the final model's effects, so a
further effect whose family is not claimed never counts. Set ZC: 16/24 strict, 17 lenient, no false claim, median
final / oracle RMS 1.59; the code before the change scores 15 (ZC19, heat stratifying in the forearm, was `ambiguous`
for its further effect); right on 9 of 11 effect cases where the true family's generic model helps, 4 of 10 where it
does not. Its misses: a wire laid from a spool at a constant tension, its tension set per roll and not logged, named
transmission (ZC01 on ur10, ZC09 on tool_changer, with thermal); encoder words logged with two data lines crossed
(ZC02) and a multi-start worm's index error (ZC11), `none`; a bonded part warmed by its adhesive's cure (ZC14),
`none`; heat stratifying in the hollow forearm on ur10, hedged between link deflection, joint compliance and thermal
(ZC03, lenient); a six-strut pedestal on kr16_like, named transmission (ZC18); a counterweight base's dead zone on
kr16_like (ZC22), `none`. On the code after set ZG had been judged (the gear-ratio search's second band, see set ZH)
the worm's index error is named transmission (ZC11): set ZC 17/24 strict, 18 lenient.

**Set ZD** (24 cases, seed 40_7030) is a thirtieth independent test set of twelve new kinds
(`sim2real_indep/effects_zd*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZC, and who did not run the diagnosis. It was run once, on the
code as it stood after set ZC had been judged (the diagnosis unchanged since): 9/24 strict, 10 lenient, median final /
oracle RMS 1.55, and **one false claim**, the first in the benchmark: a geometry-only case on tool_changer with 30
training poses for 25 parameters (ZD15), named link deflection for an out-of-fold gain of 6.8 % (p = 3.6e-4), less
than the spread of a test RMS over 30 poses (about 7.5 %). The later-tie rule scores one case more on it than the rule
before (ZD19, a floating sun's play, was `ambiguous` for its further effect). Right on 3 of 10 effect cases where the
true family's generic model helps, 4 of 11 where it does not. Its misses: a controller's Cartesian stiffness yielding
to the tool's and the part's weight, named link deflection (ZD01, ZD03, ZD14); joint torque sensors reading part of
the bending moment, named transmission on ur10 (ZD02) and `none` on kr16_like (ZD18); an encoder's read-head
dropping out in some blocks (ZD04, ZD20) and a two-speed gearbox's rounded low-range ratio (ZD10), `none`; air
mounts with levelling valves, named transmission (ZD05) and hedged beside the tendons (ZD24, lenient); a paint
booth's flash-off air on ur10 (ZD06), `none`; a scissor lift table's oil column, named link deflection (ZD11, ZD21);
a wrist's spline drag beside a hot-melt gun's warm-up, named link deflection (ZD16). After set ZD had been judged, a
selection step on a small training file (fewer than 10 poses per fitted parameter) asks for a gain beyond the spread
of its out-of-fold RMS (below): on that code ZD15 is `none`, and set ZD scores 10/24 strict, 11 lenient, no false
claim (the table and totals below are from the current code).

**Set ZE** (24 cases, seed 40_7031) is a thirty-first independent test set of twelve new kinds
(`sim2real_indep/effects_ze*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZD, and who did not run the diagnosis. It was run once, on the
code with one change of the selection made after set ZD had been judged and decided on sets A-ZD alone: on a small
training file (fewer than 10 poses per fitted parameter; every case of this benchmark is one) each forward and backward
step asks for a clipped out-of-fold gain of at least 1/sqrt(6P) for P training poses (the relative spread of an RMS
over 3P coordinates; 7.45 % for 30 poses) instead of 2 %. On sets A-ZD it turns ZD15's false claim into `none`, costs
Z04 a lenient three-way `ambiguous` (its first step gained 3.5 %, below 4.12 %) and drops a weak later effect from
five final models (the verdicts unchanged): 484 strict (483 before), 518 lenient (518), no false claim. Set ZE: 17/24
strict, 18 lenient, no false claim, median final / oracle RMS 1.37; the code before the change scores the same (only
ZE17's final model differs, by a weak joint compliance); right on 10 of 13 effect cases where the true family's
generic model helps, 4 of 8 where it does not. Its misses: a constant-force tether pulling the tool towards an
anchor beside the cell, hedged between link deflection, joint compliance and backlash on ur10 (ZE01, lenient); axis
1's encoder disc carried under its read head by the main bearing's tilt, `none` on ur10 (ZE03); a rotary clamp
choosing axis 1's flank in the blocks it is used, `none` on ur10 with 50 poses (ZE06) and beside a ringing tool boom
on kr16_like (ZE24); a quadrature decoder gaining a count at each reversal of axis 1, named thermal (ZE13); a lightly
damped tool boom still ringing from the last stop, `none` on tool_changer (ZE14); a slewing ring's tilting clearance
rocking the base towards the moment on kr16_like, named transmission, with a further effect the data cannot attribute
to mount compliance, joint compliance or link deflection (ZE17).

**Set ZF** (24 cases, seed 40_7032) is a thirty-second independent test set of twelve new kinds
(`sim2real_indep/effects_zf*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZE, and who did not run the diagnosis. It was run once, on the
code after set ZE had been judged, with one change since: the evidence-led first step asks for the small file's raised
minimum gain too, where it asked for the 5 % margin alone (it changes none of the 134 cases of A-ZD with at most 90
poses, nor set ZE). Set ZF: 17/24 strict, 18 lenient, no false claim, median final / oracle RMS 1.40; the code before
the small-file rule diagnoses every ZF case the same; right on 9 of 14 effect cases where the true family's generic
model helps, 5 of 7 where it does not. Its misses: a soft spring centring the output in its lash (ZF02 on ur10, named
joint compliance; right on kr16_like); a welded and re-cut sector of axis 1's ring gear (ZF03), a wrist encoder disc
sinking on its compliant hub (ZF18) and a Peltier bracket's PID loop settling as a damped oscillation on kr16_like
(ZF21), `none`; bearing preload rising as the joint warms (ZF09, named thermal, with a further effect the data cannot
attribute to joint compliance or link deflection); a bungee cord pulling towards an overhead eye on tool_changer,
hedged between link deflection, joint compliance and transmission (ZF11, lenient); micro-slip in a shimmed base on
kr16_like, named backlash (ZF20; on tool_changer named beside backlash, ZF12).

**Set ZG** (24 cases, seed 40_7033) is a thirty-third independent test set of twelve new kinds
(`sim2real_indep/effects_zg*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZF, and who did not run the diagnosis. It was run once, on the
code after set ZF had been judged, with no change to the diagnosis since. Set ZG: 13/24 strict, 14 lenient, no false
claim, median final / oracle RMS 1.70; right on 7 of 10 effect cases where the true family's generic model helps, 3 of
11 where it does not (the true family's generic model helps on 10 of its 21 effect cases; on ZE 13, on ZF 14). Its
misses: an axis-1 supply bundle twisting the gear once its slack is taken up (ZG02 on ur10, ZG17 on kr16_like), a
chipped pinion tooth on axis 1 (ZG03, ZG18), axis 1's lash on the flank an inclined installation's gravity chooses, on 50 poses (ZG06,
where the generic backlash model gains 30 % on the test poses), the main axes' lash crossed by the arm's inertia at a
fast move's end (ZG10) and an RV reducer with a broken ring pin on kr16_like (ZG19): `none`; a foundation settling
unevenly, its tilt growing with time alone, named thermal (ZG09, ZG20: no mount model follows time); anchor bolts
relaxing so that the base tilts more under the same moment, named transmission on kr16_like (ZG22: the generic mount
model gains 42 % on the test poses, 4.3 % out of fold on the training file); a tilted arm's flank with a drying film,
hedged between thermal and backlash (ZG16, lenient).

**Set ZH** (24 cases, seed 40_7034) is a thirty-fourth independent test set of twelve new kinds
(`sim2real_indep/effects_zh*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZG, and who did not run the diagnosis. It was run once, on the
code after set ZG had been judged, with one change since, made on sets A-ZG: where no reducer ratio (30-200) stands
out, the gear-ratio search tries a stage's orders before the output (7-29 per output turn; on A-ZG it names ZC11
and changes no other verdict). Set ZH: 16/24 strict, 16 lenient, no false claim, median final / oracle RMS 1.21;
the code before that change scores 15/24 (ZH12, a tooth-mesh error fading as a new final stage runs in, is `none`
there); right on 7 of 8 effect cases where the true family's generic model helps, 6 of 13 where it does not. Its
misses: axis 2's gear softer in the zone its teeth wore (ZH01 on ur10, `none`; ZH22 on kr16_like, named
transmission); a slewing axis driven by two torque-biased pinions whose runouts take turns with the direction (ZH02
on ur10, `none`; right on kr16_like); a target bracket on a loose pin resting on the stop its weight chooses, named
link deflection on all three arms (ZH06, ZH18, and ZH16 beside a heated tool's conduction); a base on a rim-clamped
dished plate, named link deflection with a further effect not attributed (ZH09); a cracked tooth softening axis 3's
mesh once per turn (ZH14, `none`).

**Set ZI** (24 cases, seed 40_7035) is a thirty-fifth independent test set of twelve new kinds
(`sim2real_indep/effects_zi*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZH, and who did not run the diagnosis. It was run once, on the
code after set ZH had been judged, with no change of the diagnosis since (the gear-ratio search's notes say whether a
frequency stood out by a flag instead of by their wording; the same reasons are printed). Set ZI: 13/24 strict, 13
lenient, no false claim, median final / oracle RMS 1.57; right on 6 of 11 effect cases where the true family's generic
model helps, 4 of 10 where it does not. Its misses: a PI servo without gravity feed-forward still recovering from the
load step between poses (ZI01, `none`; with a free swivel, ZI16, named transmission); a dress pack twisting axis 1
inside the wide play of its guide's dog (ZI02 on ur10, named transmission; right on tool_changer); an unanchored base
rocking on a sole bowed along its length, named transmission on both arms (ZI04, ZI22: the generic mount model of this
study -- a full 2 x 2 compliance about a pivot below the base -- gains 43 % and 79 % on the test poses, the
diagnosis's mount variants, an isotropic or a base-x / base-y compliance, 11 % and 3 % out of fold on the training
file: the sole's rocking axis lies at any heading); a jamming gripper whose seat locked at each block's first pose
(ZI06 on ur10, named backlash; right on tool_changer); a tooth-mesh error switching between its flanks' profiles with
the load's sign (ZI10 on tool_changer, `none`; right on kr16_like); a target on a free swivel turned downhill by its
unbalance until seal friction holds it (ZI11, named link deflection); a gravel bed densifying under each move's moment
(ZI14, named thermal; beside a thermosyphon in ZI08 only the thermosyphon is named, which counts); helical final
stages' thrust tilting the outputs of axes 2 and 3 (ZI17, named transmission; beside a cage runout in ZI24 only the runout is
named, which counts); an arm cooled by the air it moves through (ZI21 on kr16_like: the thermal selection does not
transfer to the test file, `inconclusive`; right on ur10). The helper flags four kinds as close to earlier ones in
signal though not in mechanism (pi_load_step / set Q's servo_tail, dog_play / set N's harness_lash, flank_profile /
the mesh errors, bernoulli_grip / set Y's foam gripper); on a second seed three of its cases fall below the oracle's
bars (ZI04, ZI05, ZI21).

**Set ZJ** (24 cases, seed 40_7036) is a thirty-sixth independent test set of twelve new kinds
(`sim2real_indep/effects_zj*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZI, ran no git command and did not run the diagnosis. It was
run once, on the code after one change made after set ZI's misses were seen: a `tensor` variant of the mount's
compliance (a symmetric 2 x 2 horizontal compliance about a pivot of fitted depth: a support whose stiff and soft axes
lie at any heading; set ZI's base rocking on a bowed sole was named transmission on both arms). On A-ZI it names 14
more cases (C08, E19, I20, Q19, R06, R18, Z04, Z20, ZA12, ZA24, ZC18, ZG22, ZI04, ZI22), loses none and claims
nothing on a quiet case: 561 -> 575 strict, 598 -> 610 lenient, median final / oracle RMS 1.41 -> 1.37; the UR10's
verdicts and final models are unchanged. Set ZJ: 14/24 strict, 14 lenient, no false claim, median final / oracle RMS
1.65; the code before the change scores 13/24 (ZJ10, a base on a pair of piers in soft clay turning about the line
through them, is `none` there); right on 7 of 10 effect cases where the true family's generic model helps, 4 of 11
where it does not. Its misses: joint torque sensors whose zero drifts as the joint electronics warm, turned into
offsets by an impedance controller (ZJ01, ZJ17, `none`); link inclination sensors whose gyro-aided filter still
carries the last moves' scale error (ZJ03, `none`); a bracket heated by a hot part's plume only while the tool points
down (ZJ06, `none`); a warm moulding that set in the shape its attitude history gave it (ZJ11, ZJ21, named backlash);
a steady wind choosing the flank of axis 1's lost motion (ZJ12, named transmission; ZJ22, `none`); welding current
returning through the arm's bearings (ZJ13, `none`); open-loop stepper wrists losing steps in loaded fast moves (ZJ18,
`none`). The helper flags two kinds as open to the objection of a new parameterisation (traction_microslip, built from
play operators; ghost_order, another periodic mesh error) and dropped two candidates that repeated earlier mechanisms;
on a second seed three of its cases fall below the oracle's bars (ZJ06, ZJ13, ZJ20).

**Set ZK** (24 cases, seed 40_7037) is a thirty-seventh independent test set of twelve new kinds
(`sim2real_indep/effects_zk*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZJ, ran no git command and did not run the diagnosis. It was
run once, on the code set ZJ was judged on (the diagnosis's choice had not changed since). Set ZK: 20/24 strict, 21
lenient, no false claim, median final / oracle RMS 1.46; right on 14 of 16 effect cases where the true family's
generic model helps, 3 of 5 where it does not. Its misses: a joint torque sensor's hysteresis fed into an impedance
controller on ur10 (ZK03, `ambiguous` between backlash and joint compliance, lenient; right on kr16_like); a
telescopic ram warmed by its wiper seals' friction in proportion to its stroke travel (ZK13, the thermal selection
does not transfer to the test file, `inconclusive`); a base on steel pads creeping into an asphalt yard the sun warms
(ZK14, ZK20, named thermal: the creep grows with time as a warm-up does). The helper names capstan_spans its weakest
kind (on a second seed ZK02 gains 30 % with the backlash model at 1.21x, below the oracle's bars) and dropped six
candidates, four as repeats of earlier mechanisms.
A change made on sets A-ZJ while set ZK was being written, before any of its results were seen -- a `masses+force`
variant of joint compliance: beside the gravity load and an unknown tool mass, an unknown constant force at the tool
along the two horizontal directions (a hose, cable or balancer pulling one way), none about an axis that stays
vertical -- names 8 more cases of A-ZJ (V02, V09, W09, W22, ZC01, ZC09, ZE01, ZF11) and loses one (I01, now named
link deflection: the force variant, chosen on the training residual, predicts the held-out poses worse than the
masses alone), claims nothing on a quiet case (A-ZJ 589 -> 596 strict, 624 -> 628 lenient, median final / oracle RMS
1.38 -> 1.37) and changes no verdict of set ZK. The figures of this report are of the code with it; set ZL judges it.

**Set ZL** (24 cases, seed 40_7038) is a thirty-eighth independent test set of twelve new kinds
(`sim2real_indep/effects_zl*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZK, ran no git command and did not run the diagnosis. It was
run once, on the code with the `masses+force` variant (the change above, which it judges). Set ZL: 17/24 strict, 18
lenient, no false claim, median final / oracle RMS 1.67; the code before the change scores the same (it changes no
verdict of set ZL: neutral on both sets it was judged by); right on 9 of 11 effect cases where the true family's
generic model helps, 5 of 10 where it does not. Its misses: stepper wrists whose drivers cut the holding current at
standstill on ur10 (ZL02, `ambiguous` between joint compliance and backlash, lenient; right on tool_changer and
kr16_like); Hall current sensors keeping a remanent offset from the last large current until the drives re-zero
(ZL03, named joint compliance); a motor's current-borne leakage field misread by the output's magnetic encoder at
pole pairs x ratio - 1 per turn (ZL09, ZL21, `none`); stepper wrists commanded by relative moves whose step counts
are truncated, the shortfalls adding up along the session (ZL12, `none`; ZL17, named thermal); a pressurised gripper
hose coiled round a wrist roll axis choosing its lash flank (ZL20 on kr16_like, named link deflection; right on
tool_changer). The helper flags idle_current and kt_saturation as related in their observables (both gravity sags
of the wrist joints), raised_floor and load_cells as close to a generic mount tilt in structure (new in mechanism),
and on a second seed two cases fall below the oracle's bars (ZL04, ZL13).

**Set ZM** (24 cases, seed 40_7039) is a thirty-ninth independent test set of twelve new kinds
(`sim2real_indep/effects_zm*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZL, ran no git command and did not run the diagnosis. It was
run once, on the code of set ZL's figures (before the creep variants below) and on the code with them: both score
22/24 strict, 22 lenient, no false claim, median final / oracle RMS 1.23, with the same verdict on every case; right
on 16 of 17 effect cases where the true family's generic model helps, 3 of 4 where it does not. Its misses: a
ball-detent torque limiter's seat play at the flange of tool_changer, its flank set by the tool's weight or axis 6's
last turn (ZM10, named link deflection; right on ur10), and the same limiter with the base on hardening cone mounts
(ZM16, named link deflection and transmission). The helper names rail_blocks (the law of set ZC's hexapod struts on a
new machine element), jaw_guide_tilt, enclosure_door and mesh_ripple as the kinds nearest to earlier ones, and on a
second seed one case falls below the oracle's bars (ZM12).
A change made on sets A-ZL while set ZM was being written, before any of its results were seen -- mount creep: a
support that keeps giving under the moment it holds (`tolalloc.physics.mount_creep`), an instant and a delayed
compliance reached with a time constant (`creep_<tau>min`: elastomer pads, grout) or a viscous flow whose tilt grows
with the moment's time integral (`flow`: asphalt, soft soil), both driven by the poses' history through `time_s` --
names 7 more cases of A-ZL (D24, G16, T10, Y20, ZI14, ZK14, ZK20: pads, jacks, tyres, gravel and asphalt giving way
over the session, named thermal or `ambiguous` before) and loses 6 (J05, J14, T14: heat tilting the joints or
warming the drive, a slow drift the flow variant now fits as well, `none` or named mount compliance; K03, N18: a
static or sinking support where the creep variant, chosen on the training residual, predicts the held-out poses
worse; ZI08 `ambiguous`, lenient). A-ZL: 633 -> 634 strict, 667 -> 672 lenient, no false claim, median final /
oracle RMS 1.374 -> 1.372; it changes no verdict of set ZM. A creep of the support and a slow drift of any other
cause share a time course: on a session with no other clue they tie, and the verdict says so. The figures of this
report are of the code with the change; set ZN judges it.

**Set ZN** (24 cases, seed 40_7040) is a fortieth independent test set of twelve new kinds
(`sim2real_indep/effects_zn*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZM, ran no git command and did not run the diagnosis. It was
run once, on the code with the creep variants (the change above, which it judges): 18/24 strict, 18 lenient, no
false claim, median final / oracle RMS 1.16; the code before the change scores the same, with the same verdict on
every case (neutral on both sets it was judged by: neither holds a support that creeps); right on 12 of 12 effect
cases where the true family's generic model helps, 3 of 9 where it does not. Its misses: an online payload estimate
lagging each part change (ZN02, `none`), a capstan rope's strand crowns repeating with rope travel (ZN03, ZN20,
`none`), both together (ZN08, `none`), roof heaters switched by the hall's thermostat bowing the tubes from above
(ZN06 on ur10, named link deflection), and a roll axis' end play taken up to the side the axial weight pushes on 45
poses of kr16_like (ZN17, `none`; right on tool_changer). The helper names hygro_gear, payload_estimator and
radiant_tube_heater as the kinds nearest to earlier ones (a new cause, a familiar response law), and on a second seed
one case falls below the oracle's bars (ZN02).

**Set ZO** (24 cases, seed 40_7041) is a forty-first independent test set of twelve new kinds
(`sim2real_indep/effects_zo*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZN, ran no git command and did not run the diagnosis. It was
run once, on the code as it stood after set ZN had been judged (no verdict of the diagnosis changed since; the
session's changes were to its reason texts and to reading exported models): 19/24 strict, 20 lenient, no false claim,
median final / oracle RMS 1.38; right on 10 of 14 effect cases where the true family's generic model helps, 6 of 7
where it does not. Its misses: a wrist belt's tensioner arm swinging to its stop when its span is the tight one (ZO02
on ur10, named joint compliance; ZO21 on kr16_like, `none`), a cart's fibreboard deck cupping as its underside takes up
the washdown's water (ZO04, named thermal: the humidity is not logged, and a support drifting with the time alone
ties with a warm-up), the tool changer's telescopic stage read by an ultrasonic sensor whose temperature
compensation lags the air (ZO14, `none`), and the stand on closed-cell foam pads on tool_changer (ZO12, `ambiguous`
between mount compliance, link deflection and transmission; lenient; right on ur10 and kr16_like). On a second seed
three cases fall below the oracle's bars (ZO05, ZO12, ZO17) and one sits at them (ZO22).

**Set ZP** (24 cases, seed 40_7042) is a forty-second independent test set of twelve new kinds
(`sim2real_indep/effects_zp*.py`, table below), written the same way by another helper, who read neither the
diagnosis, its effect models, nor any result of sets A-ZO, ran no git command but `git status` and did not run the
diagnosis. Two of its cases miss the brief's rival bar: the oracle labels them their truth, but the link-deflection
model comes within 1.15x (ZP03, a magnet base) and 1.11x (ZP13, a ballasted stand rocking onto three feet) of the
true structure's test RMS; the helper tried several physical changes for each and kept them (`cases.py`'s SET_ZP
comment). It was run once, on the code of this report (the same code that judged set ZO, with refusals of bad
payload columns added, which no case here meets): 11/24 strict, 12 lenient, no false claim, median final / oracle
RMS 1.96; right on 5 of 7 effect cases where the true family's generic model helps, 3 of 14 where it does not -- the
set holds mostly physics outside the family models. Its misses: a deck listing as ballast is pumped, turning gravity
in the base frame (ZP01, ZP17 `none`; ZP11 named thermal: the list grows with the time alone), wrist rolls held on
one flank by a spiral spring (ZP02, ZP19, and in ZP08's mixture: named transmission), a supply air cycled by a
load / unload compressor warming an air-motor lance (ZP06, ZP21, `none`), a boom cylinder's clevis clearance taken up
on the side of its net force (ZP09, `ambiguous` without backlash; ZP16, named joint compliance), tachogenerator
positions integrating an offset drift (ZP10, named thermal: a drift with time), a code strip swelling with an unlogged
humidity (ZP14 on tool_changer, `ambiguous` with thermal; lenient; right on kr16_like), and a soaked jacket drying on
the arm (ZP22, named thermal beside joint compliance).

"The true family's generic model helps" below: the generic model (c) of the true family (of one of them, for a
mixture) gains at least 5 % over geometry alone (a) on the test poses. Where it does not, the effect lies outside
this study's own generic model of its family too, and a diagnosis built on family models can at best stay quiet
or name a family that mimics it: such a miss is a gap in the physics, not in the decision.
"""

PHYSICS = """## How the physics was written (sources)

Each case: a true robot that differs from its file by geometric errors on every kinematic parameter (link-vector
components N(0, s_L), s_L ~ U(0.1, 0.5) mm; joint-axis tilts and zero offsets N(0, s_A), s_A ~ U(0.01, 0.05) deg),
a mass model off the file's (x U(0.85, 1.15), centres of mass + N(0, 20 mm)), a laser tracker in its own frame
(levelled within 3 deg, any yaw, 1.5-5 m away), a target 5-100 mm from the tool point, Gaussian noise
U(0.01, 0.05) mm per coordinate (Leica AT960 MPE +-(15 um + 6 um/m)), and the case's effects:

| kind | family | physics and ranges | sources |
| --- | --- | --- | --- |
| gear | transmission | strain-wave kinematic error at 2N, N and 1 cycles per output turn, N in {80, 100, 120, 160} (not given to the diagnosis), total amplitude = half the catalogue accuracy 0.5-1.5 arcmin peak to peak, 2-4 joints | Tuttle & Seering, IEEE T-RA 12(3) 1996; Ghorbel, Gandhi & Alpeter, J. Mech. Des. 123 2001; Harmonic Drive catalogue (transmission accuracy) |
| encoder | transmission | disc eccentricity 3-20 um on a 40-120 mm disc: (2e/D) sin(theta), once per turn of the measuring side (output side, or motor side with 70/30 odds: then N per output turn, divided by N) | HEIDENHAIN angle-encoder brochure (+-412 e/D arcsec) |
| heat | thermal | drive losses P = P_cu,rated (T/T_rated)^2 + (5-15 %) T_rated |omega| along the pose sequence (moves, holding torque during dwells, exercise periods of 10-30 min, pauses of 10-40 min with servo off), each link body heated by its two drives through a first-order lag of 10-60 min, rising 10-30 K at rated copper loss; links expand with CTE (aluminium 23e-6, steel 11.7e-6 /K); the logged air stays within +-0.05 K | lumped capacitance (Incropera & DeWitt ch. 5); motor losses (Mohan, *Electric Drives*); thermal drift tests ISO 9283 7.2.6 |
| ambient | thermal | a working day: the air drifts 2-6 K (+ an HVAC cycle of 0-1 K, 60-180 min) and is logged; the structure follows through a 20-120 min first-order lag; uniform expansion of all links | Incropera & DeWitt; handbook CTEs |
| hardening | joint_compliance | strain-wave gears: catalogue K1/K2/K3 over T1/T2 (size-32 example scaled by (size/32)^3); cycloid (RV) gears: half the 1-arcmin lost motion at 3 % rated torque, then the catalogue rigidity; gear sized for 1.3x the session's largest load; assembled joint 1-2x softer; gravity + payload loads | Harmonic Drive engineering data (worked example: 60 N m -> 7.15e-4 rad); Nabtesco RV-E catalogue; Dumas et al., RCIM 27 2011 |
| compliance | joint_compliance | the same gears' high-torque stiffness alone (linear); ball-screw axial stiffness 200-800 N/um for the prismatic stage | as above; THK / Hiwin ball-screw catalogues |
| mount | mount_compliance | steel pedestal column (height by arm, section 180-450 mm) under the gravity moment of arm + payload, on a base plate of 0.5-20 MN m/rad (anisotropic up to 2x): the whole robot tilts | Timoshenko & Gere (end moment); EN 1993-1-8 semi-rigid column bases (assumed range) |
| sag | link_deflection | round-tube equivalents of the long links (aluminium or steel, diameters and walls per arm) as cantilevers: bending F L^3/3EI, end moment, own weight w L^4/8EI, shear F L/kGA (Cowper's k), torsion; payload changed between blocks (logged) | Timoshenko & Gere; Roark; Cowper 1966 |
| backlash | backlash | lost motion 1-4 arcmin per revolute joint: the output rests on the flank of the last motion unless the gravity load exceeds a 2-8 % of rated friction preload (then on the gravity flank), plus 0.2-1 arcmin hysteresis trailing the motion | Nordin & Gutman, Automatica 38 2002; Harmonic Drive / Nabtesco lost-motion and hysteresis-loss data |

Set C's kinds (same case machinery: geometric errors, mass model, tracker, target offset, noise):

| kind | family | physics and ranges | sources |
| --- | --- | --- | --- |
| twonode | thermal | two-node drive thermal network (winding 3-15 min -> housing 20-120 min, each joint its own), heat from RMS torque (gravity + J alpha acceleration torque) along a duty cycle with exercise and pauses of 5-60 min; housings 8-20 K above ambient under continuous exercise; link bodies expand with their drives' housing temperatures | Boglietti et al., IEEE TIE 56(3) 2009; Heisel, Richter & Wurst, CIRP Annals 46(1) 1997 |
| workcell | thermal | the logged air drifts 2-5 K (+ HVAC cycle), the structure follows through a 20-90 min lag, while the drives warm up (twonode) | as above; Incropera & DeWitt |
| column_bow | thermal | steel riser column 400-1200 mm, depth 250-450 mm, heated on one side by the drives of axes 1-2 (lag 20-60 min): 1-3 K across -> thermal bow (curvature alpha dT / D) tilting the arm, plus axial growth | Timoshenko & Goodier; Roark (thermal-gradient beams) |
| tracker_scale | thermal (a measurement error following the air temperature) | the tracker's weather compensation frozen at the session start: distances read short by ~0.93 ppm/K of air warming (scaling about the tracker), air drifting 2-5 K | Edlen, Metrologia 2 1966; Birch & Downs, Metrologia 30 1993 |
| rv_error | transmission | RV reducer error at the crank order Z_p (30/36/40 pins), 2 Z_p, once per output turn and the input order R = 1 + i Z_p in 100-200 (not in the robot file), 0.6-1.5 arcmin peak to peak | Blanche & Yang, ASME JMTAD 111(3) 1989; Nabtesco RV catalogues |
| dual_encoder | transmission | motor-side encoder eccentricity (N and 2N per output turn, divided by N) plus output-side gear eccentricity and ovality (1 and 2 per turn), 2-4 joints | HEIDENHAIN angle encoders; Ghorbel, Gandhi & Alpeter, J. Mech. Des. 123 2001 |
| runout | transmission | radial runout 4-12 um of every output bearing: the distal arm translates on a circle turning with the joint | THK / IKO crossed-roller bearing precision classes |
| hyst_stiffness | joint_compliance | linear joint torsion plus a friction hysteresis loop (three Prandtl-Ishlinskii play operators, radius 3-10 % rated torque, half loop 0.25-0.75 arcmin) along the pose sequence; pick and place with 2-4 loads | Ruderman, Hoffmann & Bertram, IEEE TIE 56(10) 2009; Iwan, J. Appl. Mech. 33 1966; Harmonic Drive hysteresis loss |
| bearing_tilt | joint_compliance | linear joint torsion plus the tilt of axes 1-3's main bearings under the moment normal to the axis (RV: 1.5-4 x rated torque per arcmin; strain-wave units 2-5 x K3); pick and place | Nabtesco RV catalogue (moment rigidity), assumed ranges |
| dahl | backlash | dead band 1-4 arcmin and a Dahl / LuGre friction state reached exponentially over the travel (0.01-0.1 deg) of the main move and of a final approach of random side, travel 0.005-0.5 deg and speed 0.2-20 deg/s (Stribeck curve); gravity above a 2-8 % preload holds the flank | Dahl 1968; Canudas de Wit et al., IEEE TAC 40(3) 1995; Nordin & Gutman 2002 |
| track | mount_compliance | the robot on a linear-track carriage: four preloaded ball guide blocks (Hertz, F ~ d^1.5), a box track beam twisting (Bredt) and bending between feet 1-3 m apart; soft in roll, stiff in pitch; pick and place | Harris & Kotzalas; Timoshenko & Gere; Roark; linear-guide catalogues (assumed ranges) |
| box_torsion | link_deflection | rectangular box links bending about two principal axes and twisting (Bredt) under an offset gripper payload (120-250 mm off the tool axis); pick and place | Timoshenko & Gere; Roark |
| bolted_tube | link_deflection | 1-2 tube links as cantilevers plus a bolted root flange: 2-5 x EI/L until decompression (40-80 % of the session's largest moment), then 2-3x softer; pick and place | VDI 2230 Part 1; EN 1993-1-8 6.3.1 |

Set D's kinds (same case machinery):

| kind | family | physics and ranges | sources |
| --- | --- | --- | --- |
| gas_spring | joint_compliance | a gas-spring counterbalance on joint 2 (polytropic n = 1-1.3, progression 1.2-1.6, pivot / rod-eye radii by arm, sized for 40-90 % of the largest gravity torque, opposing it): the gear deflects under the net torque; linear torsion of every joint; pick and place | Stabilus / Suspa gas-spring catalogues (progression); two-force-member statics (Craig ch. 5) |
| dresspack | joint_compliance | a hose package twisted by the three wrist joints: torsion spring (2-30 N m at 180 deg by arm) plus 10-25 % guide friction against the motion, loading the compliant wrist gears; gravity torsion of every joint; pick and place | dress-pack twist limits of robot makers (assumed torques); Harmonic Drive K3 |
| loose_anchor | mount_compliance | the mount of set A (plate about two axes, pedestal) plus one loose anchor: past a threshold moment (10-60 % of the largest) lifting its side the plate joint opens and rocks 1-4x more compliantly; pick and place | EN 1993-1-8 6.2.8 / 6.3.4; Wald et al., HERON 53 2008 (component method for column bases) |
| pad_creep | mount_compliance | elastomer levelling pads: tilt C0 M + creep of a standard linear solid (C1 / C0 = 0.3-1, tau 5-40 min) under the gravity moment's history (moment held during pauses, averaged during exercise); pick and place | Findley, Lai & Onaran 1976; Gent, *Engineering with Rubber* ch. 6 |
| tapered | link_deflection | cast links whose I falls linearly from the root to 0.3-0.6x at the tip: Mohr's integrals of M(x) / EI(x) for the tip deflection and slope, own weight, torsion with the mean GJ; pick and place | Timoshenko & Gere (non-prismatic beams); Roark |
| bracket | link_deflection | an end-effector extension boom (square hollow bar, 200-800 mm, aluminium or steel by arm) mostly across the tool axis, carrying payload and target: bending, shear, Bredt torsion under payload and own weight; pick and place | Timoshenko & Gere; Roark |
| varlash | backlash | lost motion 1-3 arcmin modulated once per output turn by the wheel's eccentricity, b0 (1 + 0.3-0.7 cos(theta + phi)); gravity above a 2-8 % preload holds the flank; hysteresis 0.1-0.5 arcmin | ISO 1328-1 / ISO 21771 (backlash from centre distance); AGMA 2002; Nordin & Gutman 2002 |
| thermal_bend | thermal | 1-2 tube links warmed on one side by the drive at their root or tip (lag 15-60 min): 1-4 K across -> bow with curvature alpha dT / D (tip shift and rotation), mean rise 1-3x -> growth; duty cycle with exercise and pauses | Timoshenko & Goodier; Roark; Heisel, Richter & Wurst, CIRP Annals 46(1) 1997 |
| tool_heat | thermal | a process tool (spindle / torch head) working during the exercise periods between blocks, idle 0-10 % while measured: tool housing (tau 5-20 min, 10-40 K) -> wrist (tau 20-60 min, 3-10 K) in series; the 150-300 mm steel tool grows along its axis, the wrist links expand | Incropera & DeWitt ch. 5 (lumped nodes), assumed ranges |
| refraction | thermal (a measurement error, expected absorbed) | the beam bends in a vertically stratified air (0.2-1.5 K/m, growing 0.1-0.3 K/m per K of warming): the target appears raised by (dn/dT) G L^2 / 2, a few um at 1.5-5 m | Edlen 1966; Birch & Downs 1993; Estler et al., CIRP Annals 51(2) 2002 |
| belt | transmission | 1-2 wrist joints through a timing belt of non-integer ratio Z2 / Z1: driven and driver pulley eccentricities 5-25 um (1 and Z2 / Z1 cycles per output turn) and a tooth-mesh ripple at Z2, divided by the driven pitch radius | ISO 5294 / ISO 13050 pulley tolerances (as recalled), assumed ripple |
| ball_screw | transmission | lead deviation of the prismatic stage's ball screw: mean travel deviation log-U(0.03, 0.25) mm over the travel (classes C5-C10), bow 5-30 um, wobble 2-8 um at the lead (5, 10 or 20 mm) | ISO 3408-3 / JIS B 1192 lead accuracy (THK / NSK catalogues, as recalled) |

Set E's kinds (same case machinery):

| kind | family | physics and ranges | sources |
| --- | --- | --- | --- |
| parallelogram | joint_compliance | axis 3 driven from the base through a link bar: gear 2 carries tau2 - tau3, gear 3 (+10-40 % bar compliance) tau3, joint compliance G^-1 diag(c) G^-T with off-diagonal terms; linear torsion of the other joints; pick and place | Craig ch. 5 / 8; Alici & Shirinzadeh, IEEE T-RO 21(4) 2005 |
| varstiff | joint_compliance | joint compliance modulated along the output turn, C0 (1 + 0.1-0.3 cos(theta) + 0.05-0.2 cos(k theta)), k = 2N (strain-wave) or the crank order (RV); pick and place | ISO 6336-1 mesh stiffness; Kahraman & Singh, JSV 146 1991; Blanche & Yang 1989 |
| friction_windup | backlash | output-side friction (2-6 % of rated torque + crossed-roller bearing friction mu (2.2 M_k + d_M/2 (F_a + 2.2 F_r)), mu 0.003-0.006) winds the compliant gear and stays locked after the stop: the output trails the last motion by C T_f; pick and place | INA / Schaeffler crossed-roller friction formula (as recalled) |
| scissor_gear | backlash | anti-backlash split gear on the wrist joints whose spring (preload 20-60 % of the largest load against it) yields: 1-4 arcmin taken up at the spring rate, one load direction only; pick and place | Michalec, *Precision Gearing* 1966 |
| magnetic_ring | transmission | off-axis magnetic ring encoder (pole pitch 1-5 mm, ring 60-150 mm): sub-divisional error at P and 2P cycles per turn (P = pi D / pitch), 1-6 um on the ring, 2-4 joints | HEIDENHAIN interpolation error; RLS / Renishaw ring data sheets |
| ring_gear | transmission | pinion on a large ring gear at axis 1: cumulative pitch deviation F_p (ISO 1328-1 formula, classes 7-9) as harmonics 1-10 (~k^-1.5), pinion runout 10-25 um at Z / z, single pitch 3-8 um at Z | ISO 1328-1 (as recalled); Smith, *Gear Noise and Vibration* 2003 |
| table_frame | mount_compliance | welded stand 400-900 mm high, 2-4x softer in its unbraced direction, the robot 100-350 mm off its centre (its weight tilts the frame), legs sinking 50-200 N/um; pick and place | Koenigsberger & Tlusty 1970; Roark (assumed ranges) |
| soft_foot | mount_compliance | base plate on four feet, one short by 0.03-0.12 mm: rocks onto the other tripod (tilt g / (sqrt(2) a) about the diagonal) when the gravity moment about that diagonal changes sign; elastic feet; pick and place | Piotrowski, *Shaft Alignment Handbook* 2006 (soft foot); four-legged table statics |
| channel | link_deflection | an upper arm / forearm of ribbed open channel section (flanges 0.6-0.9 h, J x 5-15 for ribs): bending about both principal axes, Saint-Venant torsion by loads missing the shear centre (e = 3 b^2 / (6 b + h) behind the web); pick and place | Timoshenko & Gere; Vlasov 1961; Roark (shear centres) |
| ram | link_deflection | the prismatic stage as a ram through a carriage with two guide pads 0.25-0.45 m apart (100-400 N/um): pad yield tilts the ram; the ram bends over its overhang L0 + q (tool_changer only); pick and place | Timoshenko & Gere; Roark; linear-guide catalogues (as recalled) |
| sunlight | thermal | sun through the hall's windows over a half-day session (start 8-12 h, sun path from the hour angle): tubes 0.5-2.5 K warmer on the side facing the sun (quasi-static), bowing away from it, and 2-6 K warmer on the mean through a 15-60 min lag; the logged air is still | Duffie & Beckman 2013 ch. 1; Incropera & DeWitt; Timoshenko & Goodier |
| fan_thermostat | thermal | main-axis motor housings heated by the drive losses from a cold start, fan switched on by a thermostat at 35-60 % of the fan-less rise (15-35 K) and off 2-5 K lower, cutting the thermal resistance to 0.35-0.6x: a rise, overshoot and limit cycle; link bodies 1-3 expand with their drives | Incropera & DeWitt ch. 7-9; servo-motor forced-ventilation ratings (as recalled) |

Set F's kinds (same case machinery; every number the module docstrings do not source is marked assumed there):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| cable_balancer | joint_compliance | a spring balancer on a ceiling hook pulls the forearm (its pull plus a spring rate along the cable); the joints deflect through their gear stiffness under gravity and the pull | balancer catalogues (as recalled); Craig ch. 5 (statics) |
| lever_stiffness | joint_compliance | axes 2-3 driven by electric cylinders through levers: joint stiffness = cylinder stiffness x moment arm squared, which changes with the angle (tool_changer, kr16_like) | law of cosines (Hartenberg & Denavit); Koivo et al. 1996 |
| plate_yield | mount_compliance | a base plate that yields a little: elastic tilt plus a plastic set that remembers the history of the gravity moment | Prager hardening; Krasnosel'skii & Pokrovskii; Brokate & Sprekels |
| uplift | mount_compliance | a free-standing plate on a rubber mat lifting off its far edge once the load leaves the middle third: the tilt grows non-linearly; the plate sinks with the weight | Winkler foundation; Bowles, *Foundation Analysis and Design* |
| eccentric_axis | link_deflection | a link tube offset sideways from its bearing line: axial loads bend it, transverse loads twist it, besides its normal bending | Timoshenko & Gere; Roark |
| weld_crack | link_deflection | a fatigue crack at the root weld of the most stressed tube adds flexibility only while the bending opens it | Dimarogonas 1996; Chondros et al. 1998 |
| wear_zones | backlash | backlash grown in two worn sectors of each main-axis gear; the gravity load picks the flank | ISO 10825 / AGMA 1010 wear terms; Nordin & Gutman 2002 |
| brake_hub | backlash | the holding brake closes after a standstill; gravity turns the motor through the play of the brake hub, so only poses after long dwells shift | standstill-brake practice (as recalled) |
| tape_scale | transmission | an output-side tape-scale encoder with a gap at its butt joint: a sawtooth error in the joint angle (ur10, kr16_like) | HEIDENHAIN ERA 7000/8000 (as recalled) |
| lever_drive | transmission | cylinder pin positions and mounting length off their drawing values: the stroke-to-angle conversion is wrong (tool_changer, kr16_like) | law of cosines |
| day_night | thermal | the hall's air cycles over 24 h; the arm follows with a 20-90 min lag and the floor slab's top with 1-4 h, so the slab curls and tilts the base | Westergaard 1926; Bradbury 1938; Neville; Incropera & DeWitt |
| screw_growth | thermal | the cylinders' ball screws (and the tool_changer's ram screw) grow with their own friction heat, which the motor encoder does not see | Bryan 1990; Ramesh et al. 2000; Mayr et al. 2012 |

Set G's kinds (same case machinery; every number the module docstrings do not source is marked assumed there):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| twin_pinion | joint_compliance | two pinions preloaded against each other on a sector gear (axes 2-3): twist tau / 2k while the load is below twice the bias torque, slope 1/k beyond (a softening joint) | Gawronski et al., IEEE Antennas Propag. Mag. 42(6) 2000 |
| hose_catenary | joint_compliance | a heavy hose hanging as a catenary from a boom to the flange: its end force loads the joints (tau = J^T F), which twist through their gear stiffness | Irvine, *Cable Structures* 1981; Craig ch. 5 |
| jack_leak | mount_compliance | a mobile platform parked on four hydraulic jacks: oil-column spring plus leakage with pressure, so tilt and sink follow the time integral of the support loads | Merritt, *Hydraulic Control Systems* 1967 |
| air_isolator | mount_compliance | self-levelling air isolators whose height valves leave each support inside a dead band (a stop operator along the load path) | levelling-valve notes (as recalled); Krasnosel'skii & Pokrovskii 1989 |
| cfrp_twist | link_deflection | carbon-fibre tube links with an unbalanced layup: bending-twist coupling on top of bending, shear and torsion | Chandra, Stemple & Chopra, J. Aircraft 27(7) 1990; Hodges 2006 |
| target_rod | link_deflection | the reflector on a 250-600 mm carbon extension rod sagging under its own weight and the reflector's | Timoshenko & Gere |
| axial_float | backlash | a helical output stage whose shaft floats in its bearings' axial play: it turns by the float times tan(helix) / r, the flank set by the axial gravity force, with friction memory (tool_changer, kr16_like) | ISO 21771; bearing catalogues |
| bearing_clearance | backlash | a wrist shaft in an unpreloaded bearing pair tilting by its clearance over the span towards the moment across its axis, with friction memory | ISO 5753-1 clearance groups |
| ratio_rounding | transmission | a fractional RV ratio entered rounded to 0.1 in the drive: a joint scale error (tool_changer, kr16_like) | Nabtesco RV-N catalogue (as recalled) |
| ring_shift | transmission | an output ring encoder read by one head while the bearing tilts under the moment across the axis: the reading errs by the ring's shift over its radius | HEIDENHAIN angle encoders (2e/D) |
| tripod_growth | thermal (a measurement error) | the tracker's tripod grows with the air temperature through a 5-20 min lag: every measured point sinks | Bryan, CIRP Annals 39(2) 1990; Incropera & DeWitt |
| bar_expansion | thermal | a parallelogram axis 3 whose bar and upper arm are of different metals with different lags: the length difference turns the forearm, and the arm expands (tool_changer, kr16_like) | Hartenberg & Denavit 1964; Incropera & DeWitt |

Set H's kinds (same case machinery; every number the module docstrings do not source is marked assumed there):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| load_data | joint_compliance | the controller compensates the deflection for the file's masses and a fixed programmed load, not the payload carried, with a +-15 % stiffness-model error: the joints deflect by the rest | robot makers' load-data and absolute-accuracy options (as recalled); Nubiola & Bonev 2013 |
| gear_creep | joint_compliance | polymer strain-wave gears creeping (standard linear solid) under the load history (ur10) | Findley, Lai & Onaran 1976; Crawford, *Plastics Engineering* (ranges assumed) |
| agv_wheels | mount_compliance | a mobile platform on elastomer tyres (deflection ~ F^(2/3)) with a rocker axle: three supports, wheel loads from statics | Johnson, *Contact Mechanics* (ranges assumed) |
| skid | mount_compliance | arm and tracker stand on one skid bedded on the floor: the measurement sees the skid's motion under the arm minus that under the tracker | Hetenyi 1946; Roark |
| curved_link | link_deflection | a curved (gooseneck) forearm: out-of-plane loads twist the arc | Timoshenko & Gere; Roark (curved beams) |
| bond_creep | link_deflection | adhesive-bonded tube roots: an elastic and a creeping root rotation in the tube's own frame | Adams, Comyn & Wake 1997; Findley et al. 1976 |
| wrist_lash | backlash | backlash in a coupled wrist's bevel train: the flank follows the train's last motion (a sum of the coupled joints' moves), not the joint's own | Craig ch. 8; Nordin & Gutman 2002 |
| cold_grease | backlash | output-side grease friction winds the gear against the last motion and fades as the drive warms | SKF / Palmgren friction; ASTM D341 |
| stale_table | transmission | the joint-error compensation table of a replaced reducer left active: minus the old error, sampled on a grid and interpolated | ISO 230-2; Ghorbel et al. 2001; Blanche & Yang 1989 |
| wrist_coupling | transmission | wrist coupling factors configured to three decimals: a joint off by (c_cfg - c) q_k | Craig ch. 8 |
| tracker_warmup | thermal (a measurement error) | the tracker measuring while it warms up: azimuth, elevation and distance drift as 1 - exp(-t / tau) | Muralikrishnan et al. 2016; ASME B89.4.19 (amplitudes assumed) |
| helix_shift | thermal | a wrist motor's shaft grows with the drive's heat and pushes its helical pinion: a joint offset alpha L dT tan(beta) / r | ISO 21771; Incropera & DeWitt |

Set I's kinds (same case machinery; every number the module docstrings do not source is marked assumed there):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| tilted_base | joint_compliance | the arm installed on a base inclined by 4-20 deg: gravity acts obliquely in its base frame, so every joint, axis 1 included, carries a gravity torque and twists through its gear stiffness (an installation, not a compliant mount) | makers' permitted mounting angles (as recalled); Craig ch. 5 |
| balancer_relax | joint_compliance | a hydropneumatic balancer on axis 2 whose gas heats on compression during each move and relaxes to the wall temperature through a thermal time constant of 8-40 s: its force depends on the last move and the dwell; the gears twist under gravity plus balancer (tool_changer, kr16_like) | Pourmovahed & Otis, J. Dyn. Syst. Meas. Control 112 1990; law of cosines |
| floor_beams | mount_compliance | the base bolted across two steel mezzanine beams off their mid-span: the weight tilts the plate, the moment about the beams' axis bends them apart, the moment across them sinks it | Roark (simply supported beam, force and couple at a point); statics of a rigid plate |
| portal | mount_compliance | the arm at the mid-span of a portal bridge with fixed feet: the in-plane couple sways the frame, the couple about the beam twists the beam's halves into the column tops, which bend out of plane | direct stiffness method (Przemieniecki 1968); Bredt torsion; Timoshenko & Gere |
| lap_splice | link_deflection | a bolted splice in the upper arm's tube that micro-slips under its bending moment: a series Iwan model of vector play operators along the load path (Masing hysteresis) (ur10, whose wrist offsets load the upper arm out of its plane) | Goodman & Klumpp, J. Appl. Mech. 23 1956; Iwan 1966; Segalman 2005; Krasnosel'skii & Pokrovskii 1989 |
| fork_arm | link_deflection | a fork-type upper arm of two side plates twisting by non-uniform torsion with warping restrained at its root, under the torque a rolled forearm puts on it (kr16_like) | Vlasov 1961; Timoshenko & Gere, *Theory of Elastic Stability* ch. 5 |
| overrun_lash | backlash | lost motion whose flank after a stop is chosen by the load: the output overruns onto the leading flank when its inertia torque at the deceleration (plus gravity along the motion) beats the output friction, trails otherwise; a gravity torque above the friction holds its own flank | Nordin & Gutman, Automatica 38 2002 (impact phases of backlash) |
| nut_play | backlash | the axial play of a non-preloaded ball-screw nut on the prismatic stage: the ram rests on the flank its axial gravity force pushes it to when that beats a guide friction growing with the ram's transverse loads, else trails its last motion (tool_changer) | THK / NSK ball-screw and LM-guide catalogues (as recalled) |
| idler_runout | transmission | the runout of an idler bevel gear in a coupled wrist train, which turns with the train's angle q_j + sum c_jk q_k: a transmission error periodic in a combination of wrist angles (kr16_like) | ISO 17485 / AGMA 2009 (as recalled); Craig ch. 8 |
| para_gear | transmission | the cycloid reducer of a parallelogram-driven axis 3 sits on the base side and turns with the forearm's absolute angle: its error spectrum (crank order, twice it, once per turn, input order) repeats in q2 + q3 (tool_changer, kr16_like) | Blanche & Yang, ASME JMTAD 111(3) 1989 |
| rail_boom | thermal | an aluminium end-of-arm boom (400-900 mm) with a steel rail on one face bows like a bimetal strip as the drifting hall air warms it, and grows; the target at its end | Timoshenko, J. Opt. Soc. Am. 11 1925 (bi-metal thermostats); Incropera & DeWitt |
| housing_growth | thermal | the joint housings grow along their own axes with their drives' heat, shifting every body beyond each joint along that joint's axis (an axis shift the links' uniform expansion lacks) | Heisel, Richter & Wurst, CIRP Annals 46(1) 1997; Incropera & DeWitt |

Set J's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_J
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| planet_stage | transmission | a planetary output stage: the planets average the ring gear's error, so only ring harmonics that are multiples of the planet count reach the output, plus each planet's runout at the order Zr/Zp | Kahraman, Mech. Mach. Theory 29(8) 1994; Bodas & Kahraman 2004; Inalpolat & Kahraman, JSV 323 2009 |
| diff_wrist | transmission | a bevel-gear differential wrist: the errors of the two side-gear trains mix into pitch ((e_A + e_B)/2) and roll ((e_A - e_B)/2i), at the angles q5 +- i q6 (kr16_like) | Rosheim, *Robot Wrist Actuators* 1989; Craig ch. 8; ISO 17485 |
| flange_slip | backlash | a bolted output flange that lost preload slips across its bolt-hole clearance once the torque passes +-T_s and stays there: a relay remembering the load history | VDI 2230; EN 1993-1-8 3.9; Junker, SAE 690055; Krasnosel'skii & Pokrovskii 1989 |
| bar_pins | backlash | pin clearance in the parallelogram bar: axis 3 off by +-c / (2 r sin gamma), the side set by the load, or by the crank's last motion (q2 + q3) when the load is small (kr16_like) | Flores et al. 2008; Hartenberg & Denavit 1964 |
| hose_retract | joint_compliance | a dress-pack retract spring pulls the tool towards the forearm: an internal force that twists only the wrist gears (with gravity on those joints) | dress-pack catalogues (as recalled); Craig ch. 5 |
| wrist_shafts | joint_compliance | long drive shafts of a coupled wrist twist under load, coupling the wrist joints through the gear ratios (G^-1 diag(L/GJ) G^-T tau) | Craig ch. 8; Rivin 1999 |
| grout_creep | mount_compliance | the base on a young grout bed and anchors: creep by Bazant's double power law summed over the moment history (tool_changer) | Bazant & Osman 1976; ACI 209.2R-08; ACI 351.1R-12 |
| wall_console | mount_compliance | the arm on a welded steel console cantilevered from a wall: bending, shear, torsion and a semi-rigid end plate tilt it under weight and moment (ur10) | Roark; Timoshenko & Gere; EN 1993-1-8 5.2.2 |
| skew_casting | link_deflection | a cast link whose principal axes are unequal and turned 15-40 deg from the arm's plane: in-plane loads bend it out of plane | Timoshenko & Gere; Roark ch. 8 |
| tool_plate | link_deflection | a flat tool plate offset from the flange with the gripper below it twists (thin rectangle in torsion) and bends | Roark Table 10.1; Timoshenko & Goodier ch. 10 |
| brake_tilt | thermal | a brake coil (on whenever the servo is on) and the motor warm one side of a joint housing: the axis tilts by alpha h dT / s | Bryan, CIRP Annals 39(2) 1990; ISO 230-3; Mayr et al., CIRP Annals 61(2) 2012; Incropera & DeWitt |
| laminate_twist | thermal | carbon-fibre tubes with an unbalanced layup twist about their axes as the hall air warms them | Jones 1999; Daniel & Ishai 2006 |

Set K's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_K
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| vacuum_hose | joint_compliance | a vacuum hose's pull (pressure x area) drags the gripper towards its fixed stand while a part is held; the pull's joint loads twist the gears (ur10, kr16_like) | EJMA (bellows pressure thrust); Craig (statics) |
| tele_rope | joint_compliance | the telescopic stage held by two unequal wire ropes whose stretch depends on the stroke and the load's sign, stiffening with load (tool_changer) | Feyrer, *Wire Ropes* 2015 |
| outrigger_soil | mount_compliance | outrigger pads settling into soft ground (rigid-punch settlement) plus Terzaghi consolidation over the load history (ur10, kr16_like) | Boussinesq; Poulos & Davis; Terzaghi; Das |
| bulkhead | mount_compliance | the excavation chamber's support pressure (drifting and cycling) bows the tunnel machine's pressure bulkhead that carries the robot (tool_changer) | Timoshenko & Woinowsky-Krieger (clamped plates); Maidl et al. |
| side_cylinder | link_deflection | axis 2 driven by one cylinder beside the arm: its offset force twists the upper arm's root and bends it sideways (tool_changer) | law of cosines; Timoshenko & Gere |
| rcc | link_deflection | a remote-centre compliance device between flange and gripper translates and tilts under the gripper's and payload's weight | Whitney 1982; Whitney & Nevins 1979 |
| thermal_lash | backlash | an axis-1 pinion / ring-gear backlash that opens as the housing warms; the axis trails its last motion (kr16_like, tool_changer) | AGMA 2002; ISO TR 10064-2 |
| ram_roll | backlash | the telescopic ram rolls inside its worn anti-rotation key slot, flipping sides with the roll torque (a relay) of a cutter held off the wrist axis (tool_changer) | Krasnosel'skii & Pokrovskii; Flores et al. |
| cardan | transmission | Hooke's-joint error of the wrist drive shafts, the shaft angle shrinking as the arm extends: not a whole number of cycles per joint turn (tool_changer) | Seherr-Thoss et al.; Mabie & Reinholtz |
| spline_twist | transmission | twisted ball-spline grooves turn the wrist in proportion to the extension (tool_changer) | THK / NB ball-spline accuracy tables |
| read_head | thermal | output-encoder read heads drift on warming brackets, so the joint angles drift with each drive's heat (ur10: all joints; kr16_like: axes 1-3) | HEIDENHAIN mounting notes; Bryan 1990 |
| comp_mismatch | thermal | the controller corrects thermal growth from winding temperatures, which lead the links: it over-corrects while warming and under-corrects while cooling | Bryan 1990; Mayr et al. 2012; ISO 230-3 |

Set L's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_L
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| polymer_heat | joint_compliance | polymer strain-wave gears soften as their drives warm them: the twist under load grows by exp(beta dT) - 1 (ur10) | Crawford, *Plastics Engineering*; Menges et al.; iglidur data |
| dispense_drain | joint_compliance | a sealant cartridge at the tool, not in the logged payload, empties during production and is swapped when empty; its weight twists the gears (ur10, kr16_like) | Craig (statics); dispensing-equipment catalogues |
| gauge_pinion | backlash | lost motion in the pinion of a secondary encoder: its drag keeps it on the trailing flank, so the joint leads its command by j / (2R) (axis 1; kr16_like, tool_changer) | Nordin & Gutman 2002; ISO 21771; AGMA 2002 |
| valve_lap | backlash | a hydraulic axis 2 whose valve overlap leaves a dead band: the cylinder stops short on the approach side, then leaks towards the load in the dwell (tool_changer) | Merritt 1967; Jelali & Kroll 2003 |
| pin_ring | transmission | each pin of a pin ring off its pitch position: a random staircase in the axis angle (axis 1, tool_changer) | Litvin & Fuentes; ISO 2768; ISO 286 |
| guide_errors | transmission | straightness and roll / pitch / yaw error motions of the telescopic stage's guideway along the stroke (tool_changer) | ISO 230-1:2012; Slocum 1992 |
| pallet_load | mount_compliance | the robot and a growing pallet share one base frame on four elastic feet, which tilts and sinks (ur10, kr16_like) | statics of a rigid plate on springs |
| anchor_loose | mount_compliance | anchor preload falling with production cycles: the base plate opens at ever smaller moments and rocks about its compressed edge (tool_changer) | Junker 1969; Jiang et al. 2004; VDI 2230; EN 1993-1-8 |
| grip_spread | link_deflection | the finger carrying the target spread by the grip force while a part is held and bent by the part's weight | Roark Table 8.1 |
| float_holder | link_deflection | a tool on a preloaded, radially compliant holder: no motion below the preload, then the spring rate up to a stroke end (ur10, kr16_like) | Shigley; ATI / SCHUNK compensation units |
| hot_part | thermal | hot die-cast parts heat the gripper's fingers (fast) and body (slow) while held; both grow along the tool axis (kr16_like) | Incropera & DeWitt; Madhusudana |
| wet_arm | thermal | coolant on one side of the forearm evaporating towards the wet-bulb temperature: the tube bows towards the wet side and shortens (ur10, kr16_like) | ASHRAE Fundamentals; Incropera & DeWitt; Timoshenko & Goodier |

Set M's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_M
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| slurry_lift | joint_compliance | a slurry shield's half-drained excavation chamber buoys the held cutter and the wrist bodies below its level; the lift twists the gears (tool_changer) | Maidl et al. 2012; Archimedes; Craig (statics) |
| oil_column | joint_compliance | the trapped oil (with entrained air) of the axis-2 / axis-3 cylinders is a spring whose chamber volumes follow the stroke (tool_changer) | Merritt 1967; Yu, Chen & Lu 1994; Jelali & Kroll 2003 |
| spindle_dither | backlash | where a spindle runs, its vibration lets the main axes' lost motion settle on the gravity flank; otherwise friction holds the last motion's flank (kr16_like, tool_changer) | Armstrong-Helouvry et al. 1994; Nordin & Gutman 2002 |
| jaw_play | backlash | a gripper jaw carrying the target rocks in its guide's clearance: opened by the grip, turned by gravity, friction-held near zero load (ur10, tool_changer) | Shigley; gripper catalogues |
| chain_stage | transmission | the telescopic stage pulled by a roller chain: chordal action at the sprocket's pitch and wear elongation (tool_changer) | ISO 606; Binder 1956 (chordal action) |
| friction_wheel | transmission | axis 1 read through a measuring wheel rolling on the slewing ring: a scale error and an eccentricity at the non-integer order R / r (kr16_like, tool_changer) | HEIDENHAIN / measuring-wheel notes; Slocum 1992 |
| cart_dock | mount_compliance | a mobile cart re-docked between production runs lands elsewhere inside its docking pins' clearance (ur10, kr16_like) | Rong & Zhu 1999; ISO 286 |
| carriage_play | mount_compliance | a track carriage rocks across its cam followers' clearance as the arm's moment about the rail changes sign, friction-held inside a band (ur10, kr16_like) | Slocum 1992; roller-guide catalogues |
| rope_mount | link_deflection | a tool on wire-rope isolators: elastic deflection plus dry-friction slip of the strands (a play operator) (ur10, kr16_like) | wire-rope isolator catalogues; Krasnosel'skii & Pokrovskii |
| tie_rod_bar | link_deflection | a long gripper bar stiffened by a tension-only tie rod: it bends at two rates (ur10, kr16_like) | Roark; Timoshenko & Gere |
| hot_plume | thermal | a column of hot air between the tracker and the robot bends the beams through its flanks and lengthens their optical path (all three arms) | Edlen 1966; Ciddor 1996; Born & Wolf; Estler et al. 2002 |
| oil_growth | thermal | the hydraulic oil warms through production; cylinders servoed on their own stroke grow between their pins (tool_changer) | Merritt 1967; Incropera & DeWitt |

Set N's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_N
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| wind_panel | joint_compliance | gusty wind's normal force on a carried panel (cross-flow drag), J^T F twisting the gears (ur10, kr16_like) | Hoerner, *Fluid-Dynamic Drag* 1965; EN 1991-1-4; ESDU 85020 |
| jet_reaction | joint_compliance | a water jet's reaction rho Q v along the nozzle in the blocks where the pump runs (kr16_like, tool_changer) | Bernoulli and the momentum balance; Momber & Kovacevic 1998 |
| harness_lash | backlash | axis 1's lost motion, its flank chosen by the base cable harness's spring-plus-friction torque (all three arms) | Nordin & Gutman 2002; dress-pack guidelines |
| balanced_lash | backlash | axis 2's lost motion under gravity plus a counterbalance and its seal friction (kr16_like, tool_changer) | Nordin & Gutman 2002; set D's gas spring; seal makers' friction data |
| rope_creep | transmission | the telescopic stage's rope creeping on its traction sheave, F abs(du) / EA, reset per block (tool_changer) | Feyrer, *Wire Ropes* 2015 |
| mag_drift | transmission | magnetic encoders' once- and twice-per-turn errors growing with the drive's temperature (ur10, kr16_like) | HEIDENHAIN angle-encoder brochure; ams AS5047 / iC-Haus iC-MU data sheets |
| crawler_sink | mount_compliance | a tracked carrier on soft ground: Bekker sinkage, stiff unloading and reloading that remembers the largest past load (ur10, kr16_like) | Bekker 1956; Wong, *Theory of Ground Vehicles* 2008 |
| leaf_springs | mount_compliance | a van's bed on rear leaf springs with inter-leaf friction hysteresis (ur10, kr16_like) | Fancher, Ervin, MacAdam & Winkler 1980 |
| truss_slack | link_deflection | a lattice gripper boom whose pinned members take up their clearance by the sign of their force (all three arms) | Williot-Mohr; Timoshenko & Young |
| ring_frame | link_deflection | a ring gripper frame on spokes (a 3-D frame model), stiffened by the part it holds (ur10, kr16_like) | Roark's *Formulas for Stress and Strain* |
| tripod_tilt | thermal | the tracker's tripod legs heated unequally, tilting the head (the error arises after the tracker) (all three arms) | Lee & Shah 1988; Bryan 1990; Estler et al. 2002; Incropera & DeWitt |
| pad_heat | thermal | elastomer levelling pads heated unequally by a heater, lifting and tilting the base (ur10, kr16_like) | Gent, *Engineering with Rubber* 2012 |

Set O's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_O
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| milling_force | joint_compliance | the gears twisted by a milling cut's mean forces and spindle torque (mechanistic cutting model), the feed direction changing from pose to pose (ur10, kr16_like) | Altintas, *Manufacturing Automation* |
| bolt_torque | joint_compliance | the gears twisted by a nutrunner's reaction moment about the tool axis, blocks alternating tightening and loosening (kr16_like, tool_changer) | ISO 5393; Bickford, *Bolted Joints* 2008 |
| cut_flank | backlash | lost motion on axes 1, 4 and 6 whose flank the cutting load's torque chooses against a drag (ur10, kr16_like) | Nordin & Gutman 2002; strain-wave and cycloid catalogues |
| enc_hysteresis | backlash | output encoders closing the position loop report with a hysteresis band: the joint overshoots by half of it in the direction of its last motion (all three arms) | ams AS5047P / iC-Haus iC-MU data sheets; Krasnosel'skii & Pokrovskii 1989 |
| lsb_stop | transmission | a quantised output encoder with an in-position dead band: the axis stops at the near edge of the target count (all three arms) | Ellis, *Control System Design Guide* 2012 |
| mesh_te | transmission | a ring gear's transmission error at the tooth-mesh frequency and its harmonic, from tooth profile errors (kr16_like, tool_changer) | Welbourn 1979; Smith, *Gear Noise and Vibration* 2003; ISO 1328-1 |
| pontoon | mount_compliance | a floating support: heave, heel and trim set by the waterplane's area and second moment (ur10, kr16_like) | Rawson & Tupper, *Basic Ship Theory* 2001; Biran 2003 |
| guyed_mast | mount_compliance | a pinned mast held by three guy ropes (elastic-catenary chord law), its equilibrium solved per pose (ur10, kr16_like) | Irvine, *Cable Structures* 1981; Feyrer, *Wire Ropes* 2015; TIA-222-H |
| weld_gun | link_deflection | a clinching / riveting C-frame opened by a squeeze force that varies per pose with the weld schedule; the target on the die (kr16_like, tool_changer) | Zhang & Senkara, *Resistance Welding* 2011; Roark's *Formulas for Stress and Strain* |
| spindle_bracket | link_deflection | a spindle's flat-bar bracket bent and twisted by the cut (ur10, kr16_like) | Roark's *Formulas for Stress and Strain*; Timoshenko & Gere |
| purge_air | thermal | an Ex-p purge with vortex-cooled air: joint housings, links and the base wall cool before each block, then relax under the leakage flow (kr16_like, tool_changer) | IEC 60079-2; Incropera & DeWitt; Timoshenko & Goodier |
| ir_dryer | thermal | links warmed by an infrared panel in proportion to their own (r0 / r)^2 distance at each pose, with a lag (all three arms) | Modest, *Radiative Heat Transfer* 2013; Incropera & DeWitt |

Set P's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_P
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| mag_coupling | joint_compliance | sealed wrist axes driven through permanent-magnet couplings across their housings' walls: a sine torque-angle law, the output lagging by arcsin(tau / (N T_max)) / (p N) (ur10, kr16_like) | Furlani, *Permanent Magnet and Electromechanical Devices* 2001 |
| belt_slack | joint_compliance | a toothed-belt last stage whose slack span goes slack above 2 T0 r, halving the stage's stiffness (tool_changer) | Gates synchronous belt design manual; Childs, *Mechanical Design Engineering Handbook* 2014 |
| seal_relax | backlash | the output lip seals' drag winding the gear against the motion, relaxing through the dwell like a standard linear solid (ur10, tool_changer) | Ferry, *Viscoelastic Properties of Polymers* 1980; Mueller & Nau, *Fluid Sealing Technology* 1998 |
| quick_change | backlash | a tool changer's locating pins landing anywhere in their clearance at each tool change; each tool's weight logged as the payload (all three arms) | ISO 9409-1; ISO 286; Slocum, *Precision Machine Design* 1992 |
| pole_pitch | transmission | the accumulated pole-pitch error of magnetised output encoder rings (a closed random walk, 1/k spectrum) on axes 1-3 (tool_changer) | RLS / Renishaw, AMO and SIKO ring-encoder data sheets |
| stray_field | transmission | the next axis' brake magnet (a dipole) turning a magnetic encoder's reading with the next axis' angle (tool_changer, kr16_like) | magnetic-encoder data sheets; dipole field |
| vacuum_feet | mount_compliance | a portable arm held down by three vacuum cups on hardening elastomer pads, the base sinking and tilting with the pads' compressions (ur10, in a mixture) | Gent, *Engineering with Rubber* 2012; Schmalz / Piab cup data |
| platen_clamp | mount_compliance | an arm on a moulding machine's fixed platen, which turns while the mould is clamped (the machine's signal not logged) (ur10, kr16_like) | EUROMAP 18; Johannaber, *Injection Molding Machines* 2008 |
| vacuum_plate | link_deflection | a vacuum gripper's face plate bowing under the atmosphere while a part is held, w0 = p a^4 / (64 D) (tool_changer, kr16_like) | Timoshenko & Woinowsky-Krieger 1959; Roark's *Formulas for Stress and Strain* |
| hose_lance | link_deflection | a slender dispensing lance bent by the supply hose clipped to its nozzle, the pull set by the wrist angles (ur10, kr16_like) | Roark's *Formulas for Stress and Strain*; Timoshenko & Gere |
| jacket_cycle | thermal | a foundry jacket's vortex cooler switched by a thermostat: the jacket air's sawtooth limit cycle, the links following through a lag; the logged hall air stays still (ur10, kr16_like) | Astrom & Murray, *Feedback Systems* 2008; Incropera & DeWitt |
| charging_heat | thermal | an AMR's deck bowed by its battery's heat while it charges in the pauses, tilting the arm's base (ur10, kr16_like) | Timoshenko & Goodier, *Theory of Elasticity* |

Set Q's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_Q
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| sensor_stops | joint_compliance | joint-torque-sensor flexures on axes 2-3 in series with the gears, locked by their overload stops: twist clip(tau, +-T_stop) / k (ur10, tool_changer) | DLR lightweight-robot papers; Kashiri et al. 2017 |
| fluid_tank | joint_compliance | liquid in a part-full tank on the tool settling to the low side as the tool tilts, its weight twisting the gears (ur10, kr16_like) | Rawson & Tupper, *Basic Ship Theory* (free-surface effect) |
| lash_comp | backlash | worn gear lash with the controller's backlash compensation added on each reversal (ur10, tool_changer) | SINUMERIK MD32450; FANUC parameter 1851 |
| servo_tail | backlash | a PI-controlled axis overshooting in the direction of motion by a share of the move's speed, decaying over the dwell (all three arms) | Ellis, *Control System Design Guide*; Gross et al. |
| ball_pass | transmission | a strain-wave gear's error at the wave-generator bearing's ball-pass rate, 2 (1 - f_c) N periods per output turn (ur10) | Harris, *Rolling Bearing Analysis*; Tuttle & Seering; Ghorbel et al. |
| draw_wire | transmission | the telescopic stage's draw-wire sensor: the wire stretching under its return spring, an eccentric drum (tool_changer) | draw-wire sensor data sheets |
| disc_springs | mount_compliance | a base on three feet preloaded through Belleville stacks whose stiffness falls towards flat (kr16_like) | Almen & Laszlo 1936 |
| kinematic_mount | mount_compliance | a base on a clamped three-ball kinematic coupling with Hertzian contacts, delta ~ F^(2/3) (tool_changer) | Slocum, *Precision Machine Design*; Johnson, *Contact Mechanics* |
| ball_holder | link_deflection | a reflector on a two-ball-joint articulated holder whose clamped joints give under its weight (tool_changer) | clamping ball-joint holders |
| gooseneck | link_deflection | a curved supply tube carrying the nozzle, straightening under pressure like a Bourdon tube while the valve is open (ur10, kr16_like) | Wolf 1946; Clark & Reissner 1950 |
| ejector_chill | thermal | a vacuum ejector's cold exhaust making the gripper boom shrink and bow while a part is held, through a lag (ur10, kr16_like) | Incropera & DeWitt; ejector data |
| door_draught | thermal | cold air through a loading door's random openings chilling the whole arm through two lags, unseen by the hall's sensor (ur10, kr16_like) | Incropera & DeWitt |

Set R's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_R
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| line_pressure | joint_compliance | a pneumatic counterbalance on axis 2 fed from the shop air line, whose pressure saws with the compressor's load / unload cycle (not logged) (tool_changer) | Atlas Copco, *Compressed Air Manual* 2015; Craig, *Introduction to Robotics* ch. 5 |
| slide_shift | joint_compliance | a pneumatic slide on the tool whose carriage mass sits extended or retracted (the valve not logged) (ur10, tool_changer) | Craig, *Introduction to Robotics* ch. 5; pneumatic slide catalogues |
| stick_band | backlash | axes under a proportional position loop stopping short on the approach side by friction over servo stiffness (all three arms) | Armstrong-Helouvry, Dupont & Canudas de Wit, *Automatica* 30, 1994; Ellis 2012 |
| floor_cable | backlash | a cable on the floor pulling the flange only when it was last pulled out (Coulomb friction) (ur10, kr16_like) | Coulomb friction; Craig, *Introduction to Robotics* ch. 5 |
| rehoming | transmission | incremental encoders re-homed on a reference switch after each power-down pause (tool_changer, kr16_like) | precision-switch data sheets; SINUMERIK "Reference point approach"; IEC 60947-5-2 |
| belt_splice | transmission | a welded belt's splice pitch error while the splice is on the tight span, a function of q5 (kr16_like) | Perneder & Osborne, *Handbook Timing Belts* 2012 |
| forklift_slab | mount_compliance | a parked forklift dishing the floor slab (Westergaard / Hetenyi basin), the base sinking and tilting while it stands (all three arms) | Westergaard 1926; Hetenyi 1946 |
| sprayer_tank | mount_compliance | the arm on a sprung carrier loaded by its own weights and a tank that drains during work and is refilled in pauses (ur10, kr16_like) | sprung rigid-body statics |
| web_buckling | link_deflection | a thin-web bracket carrying the target buckling in shear, then a tension field (Wagner / Kuhn): bilinear in the gravity component along the tool (ur10, tool_changer) | Kuhn 1956; Wagner 1929 |
| swing_mount | link_deflection | a swing-away tool mount on a preloaded spring, swung off its stop above the preload (tool_changer, kr16_like) | breakaway-mount statics |
| heated_hose | thermal | a heated hot-melt hose strapped along one side of the forearm, which bows and grows after switch-on (ur10, kr16_like) | Boley & Weiner, *Theory of Thermal Stresses* 1960; Incropera & DeWitt |
| welding_cable | thermal | a welding cable's Joule heat warming the upper arm in production periods between blocks (ur10) | Incropera & DeWitt ch. 5 |

Set S's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_S
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| float_pinion | joint_compliance | axis 2's pinion held in mesh by a radial spring, pushed out above a load threshold: a give sign(tau) (\|tau\| - T_0)+ tan^2(alpha) / (k_s R^2) (kr16_like, tool_changer) | Niemann & Winter, *Maschinenelemente* II; ISO 21771 |
| wall_boot | joint_compliance | the forearm passing a booth wall through a rubber bellows whose axial and lateral rates pull on a collar, the joints twisting under tau = J^T F (ur10, kr16_like) | EJMA Standards, 10th ed.; Craig, *Introduction to Robotics* ch. 5 |
| overshoot_lash | backlash | a position loop's overshoot, a share of the following error, carried back across the lost motion only as far as it reaches (all three arms) | Ellis, *Control System Design Guide*; Nordin & Gutman, Automatica 38, 2002 |
| dowel_yaw | backlash | a base on two dowel pins with clearance and slack bolts, turned across the clearance by axis 1's reaction at the start and stop of moves (a relay) (all three arms) | VDI 2230 Part 1; Junker, SAE 690055; Krasnosel'skii & Pokrovskii |
| cogging | transmission | motor cogging torque against a proportional loop at standstill, A sin(Z N q + phi) (all three arms, axes 1, 4, 6) | servo-motor cogging literature (module docstring) |
| pot_loading | transmission | the boom cylinders' potentiometric stroke sensors read through a finite input impedance, u / (1 + rho u (1 - u)) (tool_changer) | potentiometer loading (module docstring) |
| twin_robot | mount_compliance | a twin robot on the same table running its production cycle, its weights tilting the table top on its feet (not logged) (all three arms) | Timoshenko & Young, *Engineering Mechanics* |
| mullins_mounts | mount_compliance | new filled-rubber isolators softening on reloading below their largest compression so far (Mullins; Ogden & Roxburgh), the plate solved pose by pose with its history (all three arms) | Mullins 1969; Ogden & Roxburgh 1999 |
| profile_frame | link_deflection | the target on an aluminium profile frame whose T-slot bracket follows a semi-rigid moment-rotation curve (all three arms) | Kishi & Chen (semi-rigid connections) |
| diaphragm | link_deflection | the tool on a double-diaphragm axial flexure stiffened by membrane action (large-deflection plate law) (ur10, kr16_like) | large-deflection plate theory (module docstring) |
| oil_shrink | thermal | warm oil trapped in the loaded cylinder chambers cooling during the dwell, shrinking and letting the boom sink (oil temperature not logged) (tool_changer) | Merritt, *Hydraulic Control Systems*; Incropera & DeWitt |
| wheel_growth | thermal | axis 1 read by a polyurethane-tyred measuring wheel on a steel ring, wheel and ring growing by different amounts with different lags: q1 (alpha_eff dT_w - alpha_St dT_R), driven by the logged hall air (kr16_like, tool_changer) | Incropera & DeWitt ch. 5; material data |

Set T's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_T
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| charge_cable | joint_compliance | a heavy charging cable lying on the floor and hanging up to a clamp on the tool: its weight on the clamp grows with the clamp's height, the joints twisting under tau = J^T F (ur10, kr16_like) | Irvine, *Cable Structures* 1981; Craig ch. 5 |
| balancer_leak | joint_compliance | axis 2's gas balancer losing gas through a worn seal, gear 2 carrying more of the load as the session goes on (kr16_like, tool_changer) | Merritt, *Hydraulic Control Systems* 1967 (laminar leakage) |
| hose_capstan | backlash | a retracted hose sliding round a guide ring on the turret, its pull raised after a pull-out and lowered after a retraction by the ring's friction (capstan law) (all three arms) | Euler-Eytelwein belt friction: Johnson, *Contact Mechanics* 1985 |
| via_approach | backlash | each pose reached by a short hidden approach move along a tool-fixed direction, which sets the flank the lightly loaded joints rest on (all three arms) | Whitney, IEEE Trans. Man-Mach. Syst. 10(2) 1969; Nordin & Gutman, Automatica 38, 2002 |
| inclinometer | transmission | axes 2, 3 and 5 read as differences of MEMS tilt sensors on the links, with offset, gain and orthogonality errors varying with each link's pitch (tool_changer) | Fisher, Analog Devices AN-1057, 2010; Luczak et al., IEEE Sensors J. 6(6), 2006 |
| rangefinder | transmission | the telescopic axis read by a phase-comparison laser distance sensor with cyclic errors in the stroke (tool_changer) | Ruger, *Electronic Distance Measurement* |
| crane_runway | mount_compliance | the robot on a bracket of a hall column whose corbel an overhead crane's wheel loads bend as the crane travels and lifts (ur10, kr16_like) | EN 1993-6; Timoshenko & Gere, *Mechanics of Materials* |
| shield_squeeze | mount_compliance | a tunnel-boring machine's shield ovalised by squeezing rock during the cutter-change standstill, moving the robot's console (tool_changer, kr16_like) | Sulem, Panet & Guenot, Int. J. Rock Mech. Min. Sci. 24(3), 1987; Timoshenko, *Strength of Materials* II |
| lockable_float | link_deflection | the tool on a lateral compliance unit sagging under its own weight, locked and centred while a part is held (ur10, kr16_like) | compliance units with locking (as recalled from SCHUNK AGE-XY / ATI data) |
| plunger_stiction | link_deflection | the tool on an axial spring plunger whose guide friction keeps it where it last stuck (ur10, kr16_like) | Krasnosel'skii & Pokrovskii, *Systems with Hysteresis* 1989 |
| dew_warming | thermal | the arm brought in cold, warming with the air and faster while dew condenses on it (ur10, kr16_like) | Incropera & DeWitt ch. 5-6 (Chilton-Colburn); Threlkeld 1970; Alduchov & Eskridge 1996 |
| main_drive | thermal | the robot's console on the tunnel machine's bulkhead bowing back as the main drive cools, re-warmed each time the cutterhead is inched (tool_changer) | Incropera & DeWitt ch. 5; Timoshenko & Goodier, *Theory of Elasticity* |

Set U's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_U
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| integral_clamp | joint_compliance | axes 2-3's position loops with the integral term clamped by anti-windup: above the clamp the proportional term alone holds the load, a dead-zone sag sign(tau) max(\|tau\| - T_I, 0) / K_s (ur10, tool_changer) | Astrom & Hagglund; Ellis, *Control System Design Guide* |
| parked_tool | joint_compliance | a spare tool parked in a holder by the wrist in every other block, its weight twisting axes 1-3 (not logged: the payload column is the flange's) (tool_changer, kr16_like) | Craig, *Introduction to Robotics* ch. 5 |
| chain_slack | backlash | axis 3 driven by a roller chain whose slack strand's sag sets the lost motion, b = w^2 L^3 cos^2(beta) / (24 H^2 r), varying with the upper arm's inclination (ur10, kr16_like) | Irvine, *Cable Structures*; ISO 606 |
| bowden_lash | backlash | axis 5 driven through a Bowden cable whose sheath friction over the elbow bend gives lost motion b0 (e^(mu theta) - 1) (ur10, kr16_like) | Kaneko et al.; Palli & Melchiorri |
| dropped_counts | transmission | incremental encoders on axes 1-3 missing counts in moves faster than the counter's input limit: the joint overshoots by a share of each fast move's travel, accumulating (ur10, tool_changer) | HEIDENHAIN encoder documentation |
| soiled_disc | transmission | contamination on axis 2's optical encoder disc: a Gaussian error bump over one sector of q2 (tool_changer) | HEIDENHAIN angle-encoder guidance |
| trunnion | mount_compliance | the arm on a tilting positioner whose worm drive is compliant about its one trunnion axis (ur10, tool_changer) | Niemann & Winter, *Maschinenelemente* |
| slab_joint | mount_compliance | the base plate straddling a sawn slab joint, tilting about the joint line with a different compliance on each side (tool_changer, kr16_like) | Westergaard; Huang, *Pavement Analysis and Design* |
| sandwich_boom | link_deflection | a foam-core sandwich gripper boom carrying the target, bending in its faces and shearing in its core under the part's weight (ur10, kr16_like) | Allen; Zenkert, *An Introduction to Sandwich Construction* |
| sleeve_rock | link_deflection | the target's telescopic extension rocking across its sleeve's clearance towards gravity's sideways component, a fixed amount c L / l, reduced by friction near vertical (tool_changer, kr16_like) | clearance statics (module docstring) |
| platform_growth | thermal | the arm on a mezzanine platform growing from its fixed bearing and its columns lengthening with the logged hall air through a lag (ur10, kr16_like) | Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer* |
| magnet_coil | thermal | a magnetic gripper's coil, on while a part is held, heating the gripper body, which grows along the tool axis (ur10, kr16_like) | Incropera & DeWitt ch. 5 |

Set V's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_V
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| coiled_cord | joint_compliance | the tool's supply as a coiled cord from a junction box on a column, a tension spring F = F_i + k (d - L0) along its chord twisting the joints by tau = J^T F (not logged) (all three arms) | Wahl, *Mechanical Springs*; Craig ch. 5 |
| overhead_festoon | joint_compliance | a hose of fixed length hanging as a catenary from an overhead swivel, its end tension twisting the joints (not logged) (all three arms) | Irvine, *Cable Structures* 1981 |
| coupled_flank | backlash | a wrist axis driven through the previous one: its lost motion's flank follows its motor's net motion dq5 + c dq4, which no direction column logs (kr16_like) | Rosheim, *Robot Wrist Actuators* 1989 |
| journal_climb | backlash | the boom joints' pins climbing the walls of worn bronze bushes against the last rotation, shifting the distal arm by c_r sin(atan mu) (tool_changer) | Shigley, *Mechanical Engineering Design* ch. 12; Hamrock |
| interpolation_error | transmission | magnetic ring encoders on axes 2 and 3 with sub-divisional error once and twice per signal period (N = 128-256 periods per turn) (all three arms) | Heydemann, Applied Optics 20(19) 1981; HEIDENHAIN |
| rack_segments | transmission | the telescopic axis driven by a pinion on a rack of butted segments: a step at each butt joint and the pinion's once-per-revolution runout (tool_changer) | DIN 3962 / ISO 1328; rack makers' mounting instructions |
| stabilizer_jacks | mount_compliance | a mobile carrier standing on its wheels' suspension in some blocks and on jacks 5-15 times stiffer in the others (which, not logged), tilting under the arm's gravity moment (all three arms) | mobile-manipulator practice; rigid deck on springs |
| self_leveling | mount_compliance | a carrier levelled on locked jacks at each block's start, then tilting by the change of the gravity moment since (all three arms) | EN 280 / EN 13000 levelling |
| bolt_loosening | link_deflection | a gripper boom's root bolts, short of their preload after a tool change, loosening with each move: compliance c0 (1 + gamma ln(1 + n / n0)) (all three arms) | Junker, SAE 690055 1969; VDI 2230 Part 1 |
| moisture_swell | link_deflection | a 3D-printed PA12 boom taking up the hall's humidity after leaving its dry cabinet, growing as sqrt(t) (Fickian, early time) (all three arms) | Crank, *The Mathematics of Diffusion* 1975 |
| restrained_bar | thermal | an aluminium crossbar restrained by a steel frame, its initial crookedness amplified by the thermal force, delta0 r / (1 - r), r from the logged air lagged (all three arms) | Timoshenko & Gere, *Theory of Elastic Stability* 1961 |
| slab_curl | thermal | the floor slab between the arm and the tracker curling as its top follows the logged air with a lag, turning and sinking the base (all three arms) | Westergaard 1926; Bradbury |

Set W's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_W
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| swarf_shroud | joint_compliance | chips collecting in a spindle's suction-shroud bin during the machining between blocks, their weight twisting the joints, tau = J^T m g (not logged: `payload_kg` leaves them out) (all three arms) | Pan et al., J. Mater. Process. Technol. 173 (2006); Craig ch. 5 |
| rail_trolley | joint_compliance | a constant-force balancer hanging from a trolley that rolls freely on an overhead rail: its pull points at the rail's nearest point, with nothing along the rail (not logged) (tool_changer, kr16_like) | balancer catalogues; statics of a frictionless trolley |
| stable_probe | backlash | the tracker's stable-probe trigger firing while the servo still creeps: the point is taken behind the pose along the approach, eps / (1 - exp(-dt / tau)) (ur10, tool_changer, kr16_like) | Leica / FARO tracker manuals (stable probe); first-order closed loop |
| part_slide | backlash | the part carrying the target sliding in its nest's clearance to the stop its weight chooses where it beats friction, else to the one its last deceleration chose (ur10, tool_changer) | Coulomb friction on an inclined plane |
| hub_slip | transmission | the clamped output hubs of axes 2 and 3 slipping on their shafts under the brakes' inertia torque at one emergency stop: a zero step (not logged) (tool_changer, kr16_like) | Ringfeder / Tollok locking-assembly data; IEC 60204-1 stop category 0 |
| emi_counts | transmission | welding noise adding or dropping counts on the output encoders of axes 1-3 (2^16 counts a turn) in each production gap: a running sum per block (not logged) (tool_changer, kr16_like) | HEIDENHAIN, *Interfaces of HEIDENHAIN encoders*; Renishaw installation guides |
| cracked_plinth | mount_compliance | a concrete plinth with a flexural crack at its root, softer when the moment opens the crack (I_cr against I_g) (ur10) | ACI 318-19, 24.2.3.5 |
| young_grout | mount_compliance | the pedestal's grout bed still hydrating: strength f = t / (a + b t), E ~ sqrt(f), the tilt compliance falling through the day (ur10) | ACI 209R-92, eq. 2-1; ACI 318 |
| air_bellows | link_deflection | a pneumatic bellows compliance unit moving the tool with the shop air's compressor saw-tooth and with its own weight (pressure not logged) (ur10, kr16_like) | Atlas Copco, *Compressed Air Manual* (2015) ch. 3 |
| bent_bracket | link_deflection | the target's bracket bent past yield in a collision between blocks: a step in the target's offset in the tool frame (not logged) (tool_changer, kr16_like) | Timoshenko & Gere, *Mechanics of Materials* (plastic bending) |
| cooling_part | thermal | a hot part (40-100 K above the air, tau 3-8 min) carrying the target, shrinking as it cools in the gripper; a new part at each block (not logged) (ur10, tool_changer) | Incropera & DeWitt ch. 5 (lumped capacitance) |
| air_stratification | thermal | each link in air stratified beside a furnace (3-8 K/m, building up over 1-3 h), growing by alpha G (z_mid - z_sensor) (one sensor height logged) (kr16_like) | ASHRAE Handbook -- Fundamentals ch. 20; Awbi, *Ventilation of Buildings* (2003) ch. 8 |

Set X's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_X
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| magnet_fanner | joint_compliance | a sheet fanner's magnet pulling the steel blank in the gripper, the pull falling as 1 / r^3 from its pole and twisting the joints (not logged) (ur10) | Furlani, *Permanent Magnet and Electromechanical Devices*; Gilbert pole model |
| support_arm | joint_compliance | a spring-balanced tool-support arm lifting the flange by F0 + k (z - z0) (not logged) (tool_changer, kr16_like) | zero-gravity tool-arm and balancer data (as recalled; the drift with height assumed) |
| track_lash | backlash | the rack-and-pinion lash of a seventh-axis track the robot file does not know: each block on the flank the carriage last approached (not logged) (ur10, kr16_like) | ISO 1328 (rack quality) |
| run_in_wear | backlash | a replaced gear set's lash opening along a running-in curve, the flank chosen by load or last motion (production time not logged) (tool_changer) | Blau, *Friction and Wear Transitions of Materials*; Archard |
| ring_lobing | transmission | axis 1's ring scale pulled into three lobes by its clamping screws: the reading errs by (a / 3R) sin 3 (q - phi) (ur10, kr16_like) | Timoshenko, *Strength of Materials* (thin rings); Renishaw / HEIDENHAIN ring-scale guides |
| cosine_error | transmission | the telescopic stage's position sensor mounted at an angle beta: the stage stands off by q (1 / cos beta - 1) (tool_changer) | Slocum, *Precision Machine Design* |
| collision_shift | mount_compliance | the base plate slipping on its friction-grip bolted joint in a collision between blocks: a slide and a turn, as a step (not logged) (tool_changer, kr16_like) | VDI 2230 Part 1; EN 1993-1-8 |
| levelling_foot | mount_compliance | one of three levelling feet unscrewing in the production's vibration, the stand tilting about the line through the other two (not logged) (ur10, kr16_like) | Junker (self-loosening under transverse vibration) |
| printed_fingers | link_deflection | 3D-printed fingers bending under the part's weight and creeping from the grip, a power law in time (ur10, kr16_like) | Findley, Lai & Onaran, *Creep and Relaxation of Nonlinear Viscoelastic Materials* |
| suction_cup | link_deflection | the part tilting on its suction cup's lip under its weight's moment, theta = M_perp / k_t (tool_changer, kr16_like) | Schmalz / Piab cup data; Roark, *Formulas for Stress and Strain* |
| washdown | thermal | a hot sanitation rinse before each block heating the arm, which then cools as a lumped body (not logged) (ur10, tool_changer) | Incropera & DeWitt ch. 5 |
| induction_stray | thermal | an induction heater's stray field heating the forearm during production, first-order heating and cooling (not logged) (ur10, kr16_like) | Rudnev, Loveless & Cook, *Handbook of Induction Heating* |

Set Y's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_Y
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| frost_load | joint_compliance | frost gathering on a cold-store arm's links at a steady rate, by link length, the joints twisting under its weight, tau = J^T m g (the time logged, the frost's mass not) (ur10, tool_changer) | Incropera & DeWitt ch. 6; Hayashi, Aoki & Yuhara, Heat Transfer Jpn. Res. 6 (1977); Craig ch. 5 |
| output_brake | joint_compliance | safety brakes on the outputs of axes 2 and 3 closed in some blocks, their armatures giving by c_b tau under the load (brake mode not logged) (ur10, kr16_like) | EN ISO 10218-1, 5.13; Shigley ch. 16; spring-applied brake makers' data (as recalled) |
| coupling_play | backlash | output encoders of axes 1-3 coupled through play and dragged across it by their seals: the joint overshoots by d / 2 along its last motion (ur10, tool_changer) | coupling makers' catalogues (R+W, KTR; as recalled) |
| squeeze_film | backlash | the lost motion of axes 2 and 3 crossed slowly through stiff grease under the load, caught part-way at the dwell (dwell not logged) (tool_changer, kr16_like) | Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication* (2004) |
| pinion_runout | transmission | axis 1 read through an eccentric gauge pinion: (e / R) sin(i q1 + phi), i = Z_r / Z_p (tool_changer, kr16_like) | Smith, *Gear Noise and Vibration* (2003) ch. 2; Litvin & Fuentes (2004) |
| torque_arm | transmission | the output encoders of axes 3-5 turned on their leaf-spring torque arms by their own weight: an error that follows the joints before the axis, not its own angle (ur10, kr16_like) | HEIDENHAIN, *Rotary encoders* (stator couplings; as recalled); Craig ch. 5 |
| press_walk | mount_compliance | the base plate ratcheting on its friction-grip joint under a neighbouring press's shocks, sliding and turning at a steady rate through the production (not logged) (ur10, tool_changer) | VDI 2230 Part 1; Junker, SAE 690055 (1969); Pai & Hess, Eng. Fail. Anal. 9 (2002) |
| tyre_leak | mount_compliance | a three-wheeled cart one of whose tyres leaks, its corner sinking by delta0 (exp(t / tau) - 1) (the time logged, the pressure not) (ur10, kr16_like) | Rhyne, Tire Sci. Technol. 33(3) (2005) |
| foam_gripper | link_deflection | a part on a foam vacuum pad that compresses along its axis and shears across it (E / G = 2 (1 + nu)) under the part's weight (ur10, kr16_like) | Gibson & Ashby, *Cellular Solids* (1997) ch. 5 |
| sheet_part | link_deflection | a thin panel held at one edge bending under its own weight across its thickness, q L^4 / (8 E I) (ur10, tool_changer) | Roark, *Formulas for Stress and Strain* |
| vision_lamp | thermal | vision lamps clamped to one side of the upper arm, lit in every second gap and block, bowing and lengthening it (not logged) (tool_changer, kr16_like) | Incropera & DeWitt ch. 5; Timoshenko & Goodier; Boley & Weiner (1960) |
| cabinet_exhaust | thermal | the drive cabinet's exhaust heating one side of the steel pedestal in the production gaps: the base rises and tilts (not logged) (tool_changer, kr16_like) | Incropera & DeWitt ch. 5; Boley & Weiner (1960) |

Set Z's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_Z
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| water_slug | joint_compliance | wash water trapped in a hollow gripper boom running to its lower end, the joints twisting under its weight, tau = J^T m g (the pose logged, the water not) (ur10, kr16_like) | IEC 60529; Flitney, *Seals and Sealing Handbook* (2014); Craig ch. 5 |
| balancer_gas | joint_compliance | axis 2's gas balancer whose force follows its charge's temperature by the gas law, lagging the outdoor air by 20-50 min (the temperature logged) (tool_changer) | Craig ch. 5; gas-spring catalogues (Stabilus, as recalled); Incropera & DeWitt ch. 5 |
| balancer_seal | backlash | the balancer's rod-seal friction locked against axis 2's last motion, zero at the balancer's dead centre (tool_changer, kr16_like) | Belforte, Manuello Bertetto & Mazza (2014); Nikas, Proc. IMechE J 224 (2010) |
| tripod_windup | backlash | the tracker's tripod twisted by its head's slews and held by its clamps' friction: the frame turned about the vertical by the sign of the last slew (not logged) (ur10, kr16_like) | Al-Bender & Swevers, IEEE Control Syst. Mag. 28(6) (2008) |
| band_spiral | transmission | the telescopic stage driven by a steel band winding on its drum in a spiral: k (s^2 - S s) over the stroke (tool_changer) | Bronshtein & Semendyayev (Archimedean spiral) |
| head_tilt | transmission | axis 1's output encoder misread as the main bearing tilts under the arm's moment, -(h / R) c (M . u_h) (tool_changer, kr16_like) | THK RB moment rigidity (as recalled); HEIDENHAIN, *Angle encoders* (as recalled) |
| warm_isolators | mount_compliance | elastomer isolators under the base softening by 3-6 %/K as the hall's air warms them through a lag (kr16_like) | Gent, *Engineering with Rubber* (2012) ch. 4; Nashif, Jones & Henderson (1985) |
| oil_canning | mount_compliance | the base table's dished top plate snapping between its two shapes as the arm's tipping moment swings (a play operator of the moment) (ur10, kr16_like) | Timoshenko & Gere, *Theory of Elastic Stability* (1961) ch. 11 |
| bowstring | link_deflection | a harness strapped taut along the upper arm, its tension growing with the square of the elbow's bend, bending the tube by T e / EI (ur10) | Roark, *Formulas for Stress and Strain* |
| stress_relief | link_deflection | a welded gripper frame relaxing its welding stresses with the production's vibration, its end moving by d (1 - exp(-E / tau)) (not logged) (ur10, tool_changer) | Claxton, Metallurgia (1974); Walker, Waddell & Johnston, Proc. IMechE E 209 (1995) |
| floor_heating | thermal | the base plate curling over an underfloor heating pipe that cools after its switch-off, exp(-t / tau) (the time logged, the screed not) (ur10, tool_changer) | Incropera & DeWitt ch. 5; Timoshenko & Goodier; EN 1264 (as recalled) |
| duct_lag | thermal | a cable duct along one side of the upper arm making that side follow the air more slowly: a bow by the two lags' difference (the temperature logged) (ur10, tool_changer, kr16_like) | Incropera & DeWitt ch. 5; Timoshenko & Goodier |

Set ZA's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZA
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| flank_stiffness | joint_compliance | axis 3's asymmetric gear teeth, softer on one flank: the twist c tau one way and c (1 + r) tau the other (ur10) | Kapelevich, *Asymmetric Gearing* (2018); Litvin et al., CMAME 196 (2007) |
| luff_rope | joint_compliance | tool_changer's boom luffed by a wire-rope tackle whose free length and lever change with the luff angle (tool_changer) | Feyrer, *Wire Ropes* (2015) ch. 3; Craig ch. 5 |
| guide_drag | backlash | the telescopic stage's guide-shoe friction holding its drive's wind-up against the last stroke, in proportion to the stage's tilt (tool_changer) | Al-Bender & Swevers, IEEE Control Syst. Mag. 28(6) (2008) |
| tool_recoil | backlash | a tool on elastomer mounts still creeping back from the last stop's deceleration (the dwell not logged) (ur10, tool_changer, kr16_like) | Findley, Lai & Onaran (1976) |
| scratch_count | transmission | a scratched incremental ring scale losing counts: a step in the reading at one angle (ur10, kr16_like) | HEIDENHAIN, *Angle encoders* (as recalled) |
| tooth_skip | transmission | a wrist belt jumping one tooth at an overload between blocks (not logged) (tool_changer, kr16_like) | ISO 13050 |
| slide_overhang | mount_compliance | the arm on a cantilevered slide table pulled out to another length each block (the extension not logged) (tool_changer, kr16_like) | Roark, *Formulas for Stress and Strain* |
| ground_thaw | mount_compliance | outrigger pads on frozen ground whose thawed layer deepens with the square root of the time (ur10, kr16_like) | Lunardini (1991) ch. 3; Andersland & Ladanyi (2004); Poulos & Davis (1974) |
| offcentre_pick | link_deflection | a gripper channel twisted by parts picked off its centre line, T L / G J_t (the offset not logged) (ur10, tool_changer, kr16_like) | Young & Budynas, *Roark's Formulas* ch. 10 |
| soft_fingers | link_deflection | inflatable fingers whose stiffness follows the pressure set for each part (the pressure not logged) (ur10) | Comer & Levy, AIAA J. 1 (1963); Polygerinos et al., Adv. Eng. Mater. 19 (2017) |
| ac_jet | thermal | a split air conditioner's cold jet on one side of the upper arm, cycling with its compressor (not logged) (ur10, tool_changer) | Rajaratnam, *Turbulent Jets* (1976); ASHRAE Handbook; Incropera & DeWitt ch. 5 |
| oven_door | thermal | hot air from an oven door heating the forearm in pulses at each load change (not logged) (kr16_like) | ASHRAE Handbook -- Refrigeration; Incropera & DeWitt ch. 5; Timoshenko & Goodier |

Set ZB's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZB
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| impedance_preset | joint_compliance | a torque-controlled arm in joint-impedance control, its wrist stiffness preset changed per block and its load data without the part: dq = (tau_part + e tau_arm) / K (the preset not logged) (ur10, kr16_like) | Albu-Schaeffer, Ott & Hirzinger, IJRR 26 (2007) |
| hose_wrap | joint_compliance | a process hose wrapping round the flange as axis 6 turns, pulling it towards the elbow once its slack is used up, k_h (r abs(q6 - q6_0) - s)+ (tool_changer, kr16_like) | makers' dress-pack manuals (as recalled); Craig, *Introduction to Robotics* ch. 5 |
| pawl_notch | backlash | a notched holding brake engaging at each dwell: a gravity-loaded axis settles onto the next notch wall, a sawtooth of the joint's angle (ur10, tool_changer) | Shigley, *Mechanical Engineering Design* (as recalled) |
| reversal_pulse | backlash | a mistuned friction-compensation pulse leaving an axis past its target after a reversal only (ur10, kr16_like) | Tung, Anwar & Tomizuka, ASME J. Dyn. Syst. 115 (1993) |
| nonius_slip | transmission | a two-track absolute encoder decoding the neighbouring fine period inside a window of angles (ur10, tool_changer) | HEIDENHAIN, *Angle encoders with integral bearing* (as recalled) |
| fieldbus_rounding | transmission | joint targets sent by a cell PLC as integers of 0.01 deg, rounded or truncated; the log keeps full precision (tool_changer, kr16_like) | IEC 61131-3 (type conversions) |
| mecanum_base | mount_compliance | a mobile manipulator on four mecanum wheels whose rollers' contact stiffness changes at each docking (the roller phases not logged) (tool_changer, kr16_like) | Gfrerrer, Comput. Aided Geom. Des. 25 (2008); Roark |
| grout_void | mount_compliance | a grout void under one edge of the base plate: a one-sided tilt about the far edge (ur10) | ACI 351.1R |
| insulating_flange | link_deflection | a welding torch bending and twisting on its insulating flange under its own weight (the torch is the payload) (ur10, kr16_like) | VDI 2230 (as recalled); NEMA LI 1 |
| stay_cable | link_deflection | a tool boom on a stay cable whose sag straightens as its tension rises (Ernst's equivalent modulus) (ur10, tool_changer) | Ernst, Der Bauingenieur 40 (1965); Gimsing & Georgakis, *Cable Supported Bridges* (2012) |
| air_knife | thermal | the forearm heated whenever axis 1 puts it in a drying air knife's hot curtain, first-order heating and cooling (ur10, kr16_like) | Martin, Adv. Heat Transfer 13 (1977); Timoshenko & Goodier |
| sonotrode | thermal | an ultrasonic welding stack warming in the production between blocks and cooling while measured (the production not logged) (tool_changer) | Graff, in *Power Ultrasonics* (2015) ch. 2 (as recalled); Incropera & DeWitt ch. 5 |

Set ZC's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZC
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| spool_tension | joint_compliance | a wire laid from a spool at a constant tension pulls the flange towards a fixed guide eye, the joints yield by their compliance, dq = C J^T T u; the tension set anew for each roll (not logged) (ur10, tool_changer) | Ebler, Arnason, Michaelis & D'Sa, IEEE T-IA 29 (1993); Craig, *Introduction to Robotics* ch. 5 |
| coupled_wrist | joint_compliance | a wrist whose motors sit in the forearm: the drive trains' compliances act in motor coordinates, dq = T^-1 diag(c) T^-T tau, so a torque on one wrist axis turns the others too (kr16_like) | Tsai, *Robot Analysis* (1999) ch. 10 |
| bayonet_play | backlash | a tool on a bayonet coupling lagging across its lugs' play about the tool axis, held on the flank by its hose's drag after axis 6's last rotation (ur10, kr16_like) | Nordin & Gutman, Automatica 38 (2002); quick-change coupling makers (as recalled) |
| air_preload | backlash | a pneumatic cylinder takes up axis 1's gear play while the air is on; in blocks with the air off the axis stands on its last approach's flank (the air not logged) (tool_changer, kr16_like) | preloaded gear trains of positioners, makers' notes (as recalled) |
| swapped_bits | transmission | output-encoder words logged through an interface with two data lines crossed: bits k and k+1 exchanged in the logged angle (ur10, tool_changer) | parallel absolute-encoder outputs, makers' data sheets (as recalled) |
| multistart_worm | transmission | a 2-4-start worm's start-to-start index error: a transmission error repeating Z/s times per output turn (tool_changer) | DIN 3974 / ISO 1328; Dudley, *Handbook of Practical Gear Design* (1984) (as recalled) |
| hexapod_mount | mount_compliance | the arm on a tall six-strut pedestal whose struts are stiffer in compression than in tension: the top plate sinks, tilts, slides and turns together, K = sum k_i s_i s_i^T (tool_changer, kr16_like) | Merlet, *Parallel Robots* (2006) ch. 8; Gosselin, IEEE T-RA 6 (1990) |
| counterweight_base | mount_compliance | a mobile carrier's active counterweight cancels the arm's moment only within its stroke; the suspension tilts under the rest, a dead zone (tool_changer, kr16_like) | Huang, Sugano & Tanie, Adv. Robotics 13 (1999) |
| rubber_bush | link_deflection | a tool boom hinged on a rubber torsion bush whose stiffness rises with the turn angle, M = k0 phi (1 + gamma phi^2) (ur10, kr16_like) | Goebel, *Gummifedern* (1969); Gent, *Engineering with Rubber* (2012) ch. 10 |
| floor_hose | link_deflection | a tool boom bent by a hose it lifts off the floor, the hanging weight growing with the tip's height (ur10, tool_changer) | Irvine, *Cable Structures* (1981) ch. 1; Roark, table 8.1 |
| cure_exotherm | thermal | a freshly bonded part carrying the target warmed by its adhesive's cure, then cooling, a new part each block (the bonding times not logged) (ur10, tool_changer) | Kamal & Sourour, Polym. Eng. Sci. 13 (1973); Incropera & DeWitt ch. 5 |
| link_convection | thermal | motor heat stratifying inside the hollow forearm: the side that is up runs warmer, so the bow follows gravity, not the link (ur10, kr16_like) | Ostrach, J. Heat Transfer 110 (1988); Incropera & DeWitt ch. 9; Timoshenko & Goodier |

Set ZD's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZD
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| soft_float | joint_compliance | a controller's Cartesian stiffness ("soft float") yielding to the tool's (unlogged) and the part's weight, softest along the tool's axis, K^-1 W (ur10, tool_changer) | Salisbury, IEEE CDC (1980); Hogan, ASME J. Dyn. Syst. 107 (1985) |
| torque_crosstalk | joint_compliance | a torque-controlled arm whose joint torque sensors also read 1-3 % of the bending moment across them: each joint settles off by -(kappa / K) M.e (ur10, kr16_like) | Kashiri, Malzahn & Tsagarakis, IEEE RA-L 2 (2017); Albu-Schaeffer, Ott & Hirzinger, IJRR 26 (2007) |
| floating_sun | backlash | a planetary stage's floating sun adding lost motion at light load, taken up as the mesh forces centre it; the flank from the load, else the last motion (kr16_like) | Mueller, *Epicyclic Drive Trains* (1982); Kahraman, Mech. Mach. Theory 29 (1994); Nordin & Gutman, Automatica 38 (2002) |
| spline_drag | backlash | a wrist axis resting on the flank the telescope's last stroke chose, dragged round by its ball spline's friction and helix (tool_changer) | THK ball-spline catalogue (as recalled) |
| readhead_dropout | transmission | a ring encoder's eccentricity error, cancelled by its opposite read-head, returning in blocks where one head drops out (not logged) (ur10, kr16_like) | HEIDENHAIN modular angle encoders (as recalled) |
| range_shift | transmission | axis 1 behind a two-speed gearbox whose low range's ratio the controller holds rounded: an error proportional to the angle in the low-range blocks (not logged) (ur10, tool_changer) | range-change gearboxes of positioners (as recalled) |
| levelling_valves | mount_compliance | air mounts whose levelling valves act only outside a dead band: each mount's height a play operator of its load history (ur10, kr16_like) | Rivin, *Passive Vibration Isolation* (2003) ch. 4 |
| scissor_lift | mount_compliance | a scissor lift table heaved by its cylinder's oil column under a load whose lever changes with where it stands, plus a small tilt (tool_changer, kr16_like) | Merritt, *Hydraulic Control Systems* (1967); EN 1570-1 (as recalled) |
| curing_bond | link_deflection | a tool boom bonded into its root fitting with an epoxy still curing: the root's compliance falls with the adhesive's conversion (ur10, tool_changer) | Kamal & Sourour, Polym. Eng. Sci. 13 (1973) |
| drive_tendons | link_deflection | a wrist's drive tendons run off the forearm's axis: their tension, following axis 5's torque, bends the forearm, T e L^2 / 2EI (kr16_like) | Townsend & Salisbury (1993); Tsai, *Robot Analysis* ch. 10; Roark, table 8.1 |
| bake_booth | thermal | a paint booth's flash-off air switched by block, the links following through their walls' lag; the logged air is the hall's (ur10, kr16_like) | Goldschmidt & Streitberger, *BASF Handbook on Basics of Coating Technology* (2007) ch. 7; Incropera & DeWitt ch. 5 |
| gun_warmup | thermal | a hot-melt gun warming its bracket through two lags in series, an S-shaped growth from the switch-on (not logged) (tool_changer) | Incropera & DeWitt ch. 5 |

Set ZE's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZE
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| tether_reel | joint_compliance | a constant-force tether reel anchored beside the cell pulling the tool towards the anchor with a constant tension; the pull twists the gears through J^T F (ur10) | Wahl, *Mechanical Springs* (1963); Craig, *Introduction to Robotics* ch. 5 |
| ball_reducer | joint_compliance | ball reducers on the wrist axes whose Hertzian point contacts twist as the torque to the 2/3 power, soft at small loads (ur10, kr16_like) | Terada, J. Mech. Sci. Tech. 24 (2010) (as recalled); Johnson, *Contact Mechanics* (1985) ch. 4; Harris & Kotzalas (2007) |
| rotary_clamp | backlash | a hydraulic clamp on axis 1 pulling the output to its side of the lash in the blocks it is used (not logged), elsewhere the flank of the last motion (ur10, kr16_like) | ISO 230-1 on clamping (as recalled); Nordin & Gutman, Automatica 38 (2002) |
| noback_brake | backlash | a no-back brake on axis 2 whose release travel makes the output lag only when the last motion went the load's way (tool_changer, kr16_like) | Duff-Norton no-back catalogue (as recalled) |
| disc_shift | transmission | axis 1's encoder disc carried sideways under its read head by the main bearing's tilt under the overturning moment (all three arms) | IKO / THK crossed-roller bearing catalogues (as recalled) |
| reversal_counts | transmission | a quadrature decoder with a marginal channel phase gaining one count at every reversal of axis 1 (ur10, tool_changer) | encoder signal processing (as recalled) |
| slender_pedestal | mount_compliance | a slender riser column whose tilt under the overturning moment is amplified by the weight on it, 1 / (1 - W / W_cr) (P-delta), a new part each block (ur10) | Timoshenko & Gere, *Theory of Elastic Stability* (1961) ch. 1 |
| slewing_rock | mount_compliance | the base on a slewing ring rocking across its tilting clearance towards the moment, the play taken up progressively (kr16_like) | Rothe Erde slewing-bearing catalogue (as recalled) |
| shuttle_boom | link_deflection | a tool boom bent by a carriage parked at a new station along it each block (not logged), W a^2 (3L - a) / 6EI (all three arms) | Roark, *Formulas for Stress and Strain* (7th ed.) table 8.1 |
| ringing_boom | link_deflection | a lightly damped tool boom still vibrating from the last stop's deceleration when the tracker measures (tool_changer, kr16_like) | Singer & Seering, ASME J. Dyn. Syst. 112 (1990) |
| holding_heat | thermal | the motors of axes 2 and 3 heating their links by the copper loss of the gravity torque they hold, through a lag, cooling in the pauses (tool_changer) | Hughes & Drury, *Electric Motors and Drives* (2013) ch. 9; Incropera & DeWitt ch. 5 |
| pcm_tool | thermal | a tool head on a paraffin phase-change heat sink: its bracket warms, halts on a plateau while the wax melts, then warms on (all three arms) | Mehling & Cabeza, *Heat and Cold Storage with PCM* (2008); Voller, Numer. Heat Transfer B 17 (1990) |

Set ZF's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZF
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| bungee_cord | joint_compliance | a rubber cord to an overhead eye pulling the tool with a tension k (|d| - L0), twisting the gears through J^T F (ur10, tool_changer) | Treloar, *The Physics of Rubber Elasticity* (1975); Craig ch. 5 |
| warm_preload | joint_compliance | bearing and gear preload rising as the joint warms, so the joint's compliance falls over the session (tool_changer, kr16_like) | Stein & Tu, ASME J. Dyn. Syst. 116 (1994) |
| viscous_crossing | backlash | an oil-bath gearbox whose output gravity pushes across the lash during the dwell, against the oil's drag (all three arms) | Hamrock, *Fundamentals of Fluid Film Lubrication* (1994) |
| centring_spring | backlash | a soft spring centring the output in its clearance: the flank clip(tau / T_c, -1, 1), the motion's direction playing no part (ur10, kr16_like) | Slocum, *Precision Machine Design* (1992) |
| repaired_sector | transmission | a welded and re-cut sector of axis 1's ring gear: one local bump of transmission error in the angle (ur10, tool_changer) | ISO 1328-1:2013 |
| sagging_disc | transmission | a wrist encoder's thin disc sinking on its compliant hub, the head reading gravity's share across the axis (kr16_like) | encoder mounting practice (no specific citation) |
| shelf_bracket | mount_compliance | the base on a steel shelf bracket cantilevered from a wall, turning and dropping under the arm's weight and moment, a new part each block (ur10, tool_changer) | Roark, *Formulas for Stress and Strain* table 8.1 |
| shim_friction | mount_compliance | micro-slip in a shimmed base joint: the base tilts by the sign of the moment's change since the last pose (tool_changer, kr16_like) | Iwan, ASME J. Appl. Mech. 33 (1966); Segalman, ASME J. Appl. Mech. 72 (2005) |
| polymer_boom | link_deflection | a printed PA12 tool boom sagging more as its modulus falls with the logged air temperature (tool_changer, kr16_like) | Ashby, *Materials Selection in Mechanical Design* (2011) (as recalled) |
| flange_gapping | link_deflection | a bolted tool flange opening once the tool's moment exceeds its preload's limit: a threshold rotation (ur10, kr16_like) | VDI 2230 Part 1 (2015) |
| peltier_loop | thermal | a Peltier-cooled bracket under a loosely tuned PID loop settling as a damped oscillation from its switch-on (not logged) (ur10, kr16_like) | Rowe, *CRC Handbook of Thermoelectrics* (1995); Astrom & Murray, *Feedback Systems* (2008) |
| marking_pulses | thermal | a laser marker heating its bracket by one pulse per dwell, each decaying through the bracket's lag (ur10, tool_changer) | Incropera & DeWitt ch. 5 |

Set ZG's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZG
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| gravcomp_payload | joint_compliance | a torque-controlled arm compensating gravity for a declared tool load: only the held part's mass beyond (or short of) it deflects the joints (all three arms) | Albu-Schaeffer, Ott & Hirzinger, IJRR 26 (2007) |
| taut_harness | joint_compliance | axis 1's supply bundle pulling progressively, k (q1 - q_t)^2, once its slack is taken up, twisting the gear (ur10, kr16_like) | Irvine, *Cable Structures* (1981) ch. 2; Craig ch. 5 |
| tilt_flank | backlash | an arm on an inclined wedge: axis 1's lash on the flank the gravity torque chooses beyond the friction, else the last motion's (ur10, tool_changer) | Nordin & Gutman, Automatica 38 (2002) |
| coast_flank | backlash | the loaded axes' lash crossed by the link's inertia at a fast move's end, kept where gravity is below the friction (ur10, tool_changer) | Nordin & Gutman (2002); Tao & Kokotovic (1996) ch. 2 |
| chipped_pinion | transmission | a chipped tooth on axis 1's drive pinion: a transmission-error dip once per pinion turn (ur10, kr16_like) | Smith, *Gear Noise and Vibration* (2003) ch. 9; Randall (2011) ch. 5; ISO 10825-1:2022 |
| missing_pin | transmission | an RV reducer on axis 2 with a broken ring pin: a yield proportional to the torque, once per crank turn (tool_changer, kr16_like) | Blanche & Yang, ASME JMTAD 111 (1989); Gorla et al., ASME JMD 130 (2008) |
| settlement_tilt | mount_compliance | a foundation consolidating unevenly: the base tilt grows at a near-constant rate in time, whatever the arm does (tool_changer, kr16_like) | Arya, O'Neill & Pincus (1979) ch. 1 |
| bolt_relaxation | mount_compliance | anchor bolts losing preload logarithmically in time, so the base tilts more under the same moment, one bolt row more than the other (ur10, kr16_like) | Bickford, *Bolted Joints* (2008) ch. 10 |
| beam_column | link_deflection | a slender tool boom whose bending the load along it amplifies (boom up) or relieves (boom down), 1 / (1 - P / P_cr) (tool_changer, kr16_like) | Timoshenko & Gere (1961) ch. 1 |
| leaf_boom | link_deflection | a flat-bar boom bending towards its weak axis, not along the weight's component (ur10) | Roark, *Formulas for Stress and Strain* (7th ed.) table 8.1 |
| drying_film | thermal | an arm wet from a wash held below the air by evaporation until its film dries, the links following with a lag; the logged air unchanged (ur10, tool_changer) | ASHRAE *Handbook -- Fundamentals* (2017) ch. 1; Mujumdar (2014) ch. 1 |
| rotary_union | thermal | a tool bracket warmed by the seals of a rotary union in proportion to axis 6's travel, cooling between moves (tool_changer, kr16_like) | Flitney, *Seals and Sealing Handbook* (2014) ch. 3 |

Set ZH's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZH
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| worn_mesh | joint_compliance | axis 2's gear flanks thinned by mild wear in the production zone, so the mesh is softer there: a torque-driven twist in an angle window (ur10, kr16_like) | Flodin & Andersson, Wear 207 (1997); ISO 6336-1:2019 |
| tooth_crack | joint_compliance | a root crack at one tooth of axis 3's ring softening the mesh while it carries load, once per output turn (tool_changer) | Chaari, Fakhfakh & Haddar, Eur. J. Mech. A/Solids 28 (2009) |
| grease_gel | backlash | thixotropic grease setting in the lash during a pause and holding the output centred, sheared open by the moves after it (all three arms) | Barnes, J. Non-Newtonian Fluid Mech. 70 (1997); Lugt (2013) ch. 5 |
| loose_pivot | backlash | a target bracket on a loose pin resting on the stop its weight's moment chooses beyond the friction, else where it was (all three arms) | Flores et al. (2008) |
| pinion_handover | transmission | a slewing axis on two torque-biased pinions: the ring follows the runout of the pinion that drove last (ur10, kr16_like) | Gawronski et al., IEEE Antennas Propag. Mag. 42 (2000); Smith (2003) ch. 9 |
| running_in_te | transmission | a new final stage's tooth-mesh error fading with axis 2's travel as the flanks run in (tool_changer, kr16_like) | Sosa et al., Tribol. Int. 82 (2015) |
| brazier_pedestal | mount_compliance | a thin-walled tube riser softening as its section ovalises under the moment, pre-bent by a side console (ur10) | Brazier, Proc. R. Soc. A 116 (1927); Calladine (1983) ch. 15 |
| dished_plate | mount_compliance | the base on the boss of a rim-clamped plate: it sinks with the weight change and turns under the moment (tool_changer) | Roark & Young (7th ed.) table 11.2; Timoshenko & Woinowsky-Krieger (1959) |
| inflated_boom | link_deflection | an air-inflated fabric boom bending linearly until it wrinkles, then progressively (all three arms) | Comer & Levy, AIAA J. 1 (1963); Wielgosz & Thomas (2002) |
| collet_root | link_deflection | a boom held in a long clamp bush giving on it as on an elastic foundation, its root shifting and turning (tool_changer, kr16_like) | Hetenyi, *Beams on Elastic Foundation* (1946) ch. 2 |
| wrist_conduction | thermal | a heated tool's heat diffusing into the forearm's wall from the wrist, the warmed length growing as sqrt(t) (ur10, tool_changer) | Carslaw & Jaeger (1959) sec. 2.4 |
| regen_resistor | thermal | a braking resistor on the pedestal heated by the energy of each lowering move, cooling in between (ur10, tool_changer) | Mohan, Undeland & Robbins (2003) ch. 14 |

Set ZI's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZI
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| pi_load_step | joint_compliance | axes 2 and 3 held by PI loops without gravity feed-forward, still recovering at the dwell's end from the load step since the previous pose (ur10, tool_changer) | Astrom & Hagglund, *Advanced PID Control* (2006) sec. 4.2; Ellis (2012) ch. 6 |
| helix_tilt | joint_compliance | the axial thrust of a helical final stage tilting the output across its axis in proportion to the joint torque (kr16_like) | ISO 21771:2007; Niemann & Winter, *Maschinenelemente* II (1989) ch. 21 |
| dog_play | backlash | axis 1's dress pack wound up inside the wide play of the dog that drags its rotary guide (ur10, tool_changer) | Krasnosel'skii & Pokrovskii (1989); Visintin (1994) |
| free_swivel | backlash | a target on a free swivel turned downhill by its unbalance until the seals' friction holds it (tool_changer) | Den Hartog, *Mechanical Vibrations* (4th ed.) ch. 8 |
| flank_profile | transmission | a tooth-mesh error switching between the left and right flanks' profile errors with the load's sign (tool_changer, kr16_like) | ISO 1328-1:2013; Smith, *Gear Noise and Vibration* (2003) ch. 3, 9 |
| cage_runout | transmission | bearing runout turning with the cage (0.43-0.5 of the shaft angle), read by axis 1's encoder as an angle (ur10, kr16_like) | Harris & Kotzalas (2007) ch. 1, 8; Heidenhain, *Angle Encoders* (2015) |
| gravel_ratchet | mount_compliance | a gravel bed densifying under each move's moment, the base tilt ratcheting up with the cycles (ur10, tool_changer) | Sawicki & Swidzinski (1989); Wichtmann et al., Soil Dyn. Earthq. Eng. 25 (2005) |
| crowned_sole | mount_compliance | an unanchored base rocking on a sole bowed along its length about one axis, its weight the stiffness (ur10, kr16_like) | Timoshenko & Young (1956); Housner, BSSA 53 (1963) |
| bernoulli_grip | link_deflection | a part floating on a Bernoulli gripper's air film at the gap its weight's normal share sets (tool_changer, kr16_like) | Brun & Melkote, J. Manuf. Sci. Eng. 131 (2009); Li et al., Precis. Eng. (2015) |
| jamming_grip | link_deflection | a part held in a granular jamming gripper, tilting with the change of its moment since the block's first pose (ur10, tool_changer) | Brown et al., PNAS 107 (2010); Amend et al., IEEE Trans. Robot. 28 (2012) |
| thermosyphon | thermal | a forearm cooled by a heat pipe that works only while the wrist end hangs below the elbow (ur10, kr16_like) | Faghri (1995) ch. 5, 7; Reay, Kew & McGlen, *Heat Pipes* (2014) ch. 2 |
| motion_cooling | thermal | upper arm and forearm heated by joint electronics and cooled faster while they move through the air (ur10, kr16_like) | Incropera & DeWitt, ch. 7 |

Set ZJ's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZJ
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| gauge_zero_drift | joint_compliance | joint torque sensors' zero drifting as the joint electronics warm, the impedance controller turning the phantom torque into offsets of axes 1-3 (ur10, kr16_like) | Albu-Schaeffer, Ott & Hirzinger, IJRR 26 (2007); Hoffmann, HBM (2012) |
| traction_microslip | joint_compliance | traction-roller wrist reducers yielding by Mindlin micro-slip with Masing's memory of turning points (ur10, kr16_like) | Mindlin & Deresiewicz, J. Appl. Mech. 20 (1953); Johnson, *Contact Mechanics* (1985) |
| gyro_filter | backlash | gyro-aided inclination sensors on links 2-3 whose complementary filter still carries the last moves' gyro scale error (ur10, tool_changer) | Mahony, Hamel & Pflimlin, IEEE TAC 53 (2008); Colton, MIT (2007) |
| wind_flank | backlash | a steady wind's torque about axis 1 choosing the flank of its lost motion (tool_changer, kr16_like) | Hoerner, *Fluid-Dynamic Drag* (1965) |
| stepper_stall | transmission | open-loop stepper wrists losing a step group in each loaded fast move (ur10, kr16_like) | Kenjo & Sugawara, *Stepping Motors* (2nd ed., 1994) |
| ghost_order | transmission | axis 1's gear carrying the order of the hobbing machine's index gear (tool_changer, kr16_like) | Smith, *Gear Noise and Vibration* (2003) |
| hydrostatic_rail | mount_compliance | the base on a rail carriage held by opposed constant-flow pads (cube law), rolling about the rail and sinking (ur10, tool_changer) | Rowe, *Hydrostatic, Aerostatic and Hybrid Bearing Design* (2012) |
| clay_pier | mount_compliance | the base on a pair of short piers in soft clay turning about the line through them with the cube of the moment (tool_changer, kr16_like) | Matlock, OTC 1204 (1970); API RP 2A |
| gecko_pad | link_deflection | a part on a directional dry-adhesive pad whose tilt stiffness grows with the shear along its preferred direction (ur10, tool_changer) | Autumn et al., J. Exp. Biol. 209 (2006); Hawkes et al., IEEE/ASME TMech 20 (2015) |
| warm_sag | link_deflection | a warm moulding creeping under its own weight while it cools, set in the shape its attitude history gave it (tool_changer, kr16_like) | Ferry, *Viscoelastic Properties of Polymers* (3rd ed., 1980) |
| stray_weld_current | thermal | welding current returning through the arm heating the bearings of axes 1-3, the housings growing along their axes (tool_changer, kr16_like) | Harris & Kotzalas (2007); SKF, *Bearing damage and failure analysis* (2017) |
| plume_bracket | thermal | a hot part's convective plume heating its bracket only while the tool points down (ur10) | Morton, Taylor & Turner, Proc. R. Soc. A 234 (1956); Gebhart et al. (1988) |

Set ZK's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZK
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| kt_magnet_drift | joint_compliance | the gravity feed-forward of current-based compliant control falling short as the motor magnets warm and their torque constant drops (ur10, kr16_like) | Wensing et al., IEEE T-RO 33 (2017); Hendershot & Miller (2010) ch. 3 |
| capstan_spans | joint_compliance | a cable-capstan wrist stage whose two free spans lengthen and shorten with the angle (ur10) | Townsend, MIT PhD thesis (1988); Baser & Konukseven, Mech. Mach. Theory 45 (2010) |
| sensor_hysteresis | backlash | a joint torque sensor's hysteresis (a play operator of the load) fed into a joint-impedance controller (ur10, kr16_like) | Hoffmann, HBM (2012); Albu-Schaeffer, Ott & Hirzinger, IJRR 26 (2007) |
| housing_spread | backlash | axis 1's lost motion widening as its gear housing spreads under the tilting moment (tool_changer, kr16_like) | ISO 21771:2007 sec. 8; Niemann & Winter, *Maschinenelemente* II (1989) ch. 21 |
| quench_ovality | transmission | axis 1's ring gear left out of round by hardening: errors at 2 and 4 per turn (tool_changer, kr16_like) | Totten & Howes (1997); Smith, *Gear Noise and Vibration* (2003) ch. 3 |
| ride_height | transmission | axis 1's magnetic ring encoder whose 1- and 2-per-turn errors grow with the air gap the bearing's axial deflection sets (kr16_like) | Furlani (2001) ch. 4; Harris & Kotzalas (2007) |
| beam_torsion | mount_compliance | the base at mid-span of a single I-beam twisting about its axis under the moment along it (ur10, tool_changer) | Trahair (1993) ch. 10; SCI P385 (2011) |
| asphalt_creep | mount_compliance | base pads creeping into an asphalt yard whose binder the sun warms (tool_changer, kr16_like) | EN 12697-20/-21; Read & Whiteoak (2003) ch. 8; Ferry (1980) ch. 11 |
| flange_buckling | link_deflection | a sheet-metal bracket whose free flange buckles when bending compresses it: softer one way only (tool_changer, kr16_like) | Koiter (1945); Bulson (1970); EN 1993-1-5 |
| dashpot_slide | link_deflection | a tool on a spring-and-dashpot slide lagging its weight's history (ur10, tool_changer) | Whitney, *Mechanical Assemblies* (2004) ch. 10; Findley, Lai & Onaran (1976) ch. 5 |
| drive_board_heat | thermal | the drive electronics inside the joints heating the tube ends: servo on, production, pause (ur10) | Mohan, Undeland & Robbins (2003) ch. 7; Incropera & DeWitt ch. 5 |
| ram_wiper_heat | thermal | the telescopic ram heated by its wiper seals' friction in proportion to its stroke travel (tool_changer) | Bhushan (2013) ch. 6; Mueller & Nau (1998) |

Set ZL's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZL
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| idle_current | joint_compliance | stepper drivers cutting the holding current at standstill, the wrist joints sagging within a step (ur10, tool_changer, kr16_like) | Acarnley, *Stepping Motors* (4th ed., 2002) |
| kt_saturation | joint_compliance | current-based wrist control whose motor torque constant falls as the stator iron saturates: a sag cubic in the load (tool_changer, kr16_like) | Wensing et al., IEEE T-RO 33 (2017); Hendershot & Miller (2010); Krishnan (2010) |
| current_remanence | backlash | Hall current sensors keeping a magnetic offset from the last large current, reset when the drives re-zero at servo enable (ur10) | Ripka, *Magnetic Sensors and Magnetometers* (2001); Wensing et al. (2017) |
| hose_bourdon | backlash | a pressurised gripper hose coiled round a wrist roll axis straightening and choosing the lash flank while a part is held (tool_changer, kr16_like) | Timoshenko, *Strength of Materials* II (1956); Nordin & Gutman, Automatica 38 (2002) |
| stator_leakage | transmission | the motor's current-borne leakage field misread by the output's magnetic encoder, at pole pairs x ratio - 1 per turn (tool_changer, kr16_like) | Lenz & Edelstein, IEEE Sensors J. 6 (2006) |
| step_truncation | transmission | stepper wrists commanded by relative moves whose step counts are truncated towards zero, the shortfalls adding up (tool_changer, kr16_like) | ISO/IEC 9899 sec. 6.3.1.4 |
| raised_floor | mount_compliance | the base on access-floor panels and pedestals, softer across the stringers, and sinking under the weight (ur10) | CISCA, *Recommended Test Procedures for Access Floors* (2007) |
| load_cells | mount_compliance | the base on a pallet-sized weighing platform of four shear-beam load cells (ur10, kr16_like) | OIML R 60 (2017) |
| ft_sensor | link_deflection | a six-axis force-torque sensor's measuring flexure between the flange and the tool (tool_changer) | ATI F/T catalogue (as recalled) |
| pad_pivot | link_deflection | the part pivoting between elastomer finger pads about the closing axis (ur10, tool_changer) | Xydas & Kao, IJRR 18 (1999) |
| thermal_ratchet | thermal | tube growth held back by the friction of the clamped end fits: a play operator of the drives' warming (ur10) | Peng & Peng, *Pipe Stress Engineering* (2009); Pokrovskii, *Systems with Hysteresis* (1989) |
| arc_radiation | thermal | the welding arc's radiation heating the forearm's torch side in production: the forearm bows and grows (kr16_like) | Messler, *Principles of Welding* (1999) |

Set ZM's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZM
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| moment_softening | joint_compliance | a wrist gear whose torsional stiffness falls as the tilting moment on its output bearing rises (tool_changer, kr16_like) | Harmonic Drive / Nabtesco catalogues; Dhaouadi & Ghorbel (2008); the coupling law assumed |
| mesh_ripple | joint_compliance | a sound strain-wave gear's mesh stiffness rippling with the wave generator's angle (kr16_like) | Kahraman & Singh (1990); Tuttle & Seering (1996) |
| upstream_toss | backlash | axis 5's lost motion thrown onto a flank by the main axes braking at the end of each move (tool_changer, kr16_like) | Nordin & Gutman, Automatica 38 (2002) |
| limiter_play | backlash | a ball-detent torque limiter's seat play at the flange, its flank set by an off-axis tool's weight or axis 6's last turn (ur10, tool_changer) | R+W / Mayr catalogues |
| microstep_error | transmission | an open-loop stepper stopping short within each full step (detent torque, non-sinusoidal torque curve) (ur10) | Kenjo & Sugawara; Acarnley, *Stepping Motors* |
| step_accuracy | transmission | a stepper's tooth-pitch errors and rotor eccentricity repeating once per motor turn behind a belt stage (kr16_like) | NEMA ICS 16 |
| conical_mounts | mount_compliance | the base on hardening cone mounts on a narrow stand (ur10, tool_changer) | Gent, *Engineering with Rubber*; makers' curves |
| rail_blocks | mount_compliance | the base on a parked track carriage whose rail blocks are softer pulled than pressed (ur10) | THK / Hiwin / Rexroth rigidity data |
| mandrel_rock | link_deflection | a part gripped by its bore on an expanding elastomer sleeve, shifting and rocking (ur10, tool_changer, kr16_like) | Hetenyi, *Beams on Elastic Foundation* (1946) |
| jaw_guide_tilt | link_deflection | gripper jaws tilting elastically in preloaded miniature rail guides (tool_changer, kr16_like) | THK / Hiwin catalogues |
| mean_radiant | thermal | links settling at the operative temperature of the drifting air and of walls lagging it by hours (kr16_like) | ISO 7726; Incropera & DeWitt |
| enclosure_door | thermal | a conditioned cell off the hall's temperature whose door is opened at each loading (ur10) | ASHRAE Fundamentals ch. 16 |

Set ZN's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZN
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| hygro_gear | joint_compliance | polymer gear stages softened by the water their teeth take up after the cell's washdown (ur10, kr16_like) | Kohan, *Nylon Plastics Handbook* (1995); Crank, *The Mathematics of Diffusion* (1975) ch. 4 |
| payload_estimator | joint_compliance | a cobot's on-line payload identification lagging each part change, the gravity compensation carrying the old estimate (ur10) | Kubus, Kroeger & Wahl, ICRA 2008; Swevers et al., IEEE T-RA 13 (1997) |
| load_holding_valve | backlash | a hydraulic boom dropping as its load-holding valves close late after a lowering move, not after lifting (tool_changer) | Watton, *Fundamentals of Fluid Power Control* (2009) ch. 4 |
| roll_endplay | backlash | everything beyond a roll axis sliding along it by the bearings' end play, to the side the axial weight pushes (tool_changer, kr16_like) | Harris & Kotzalas, *Rolling Bearing Analysis* (2007) ch. 1, 5 |
| rope_lay | transmission | a capstan drive's rope rolling on its strand crowns: an error periodic in rope travel (ur10, kr16_like) | Townsend, MIT PhD thesis (1988); Feyrer, *Wire Ropes* (2015) ch. 1 |
| magnetostrictive_rod | transmission | the telescopic stage read by a magnetostrictive waveguide sensor: a scale error and a smooth bow along the stroke (tool_changer) | Lenz & Edelstein, IEEE Sensors J. 6 (2006); makers' data as recalled |
| wire_rope_isolators | mount_compliance | the base on wire-rope isolators, softening pressed and stiffening pulled (ur10, kr16_like) | Demetriades, Constantinou & Reinhorn, Eng. Struct. 15 (1993) |
| focalised_mounts | mount_compliance | inclined elastomer mounts turning the base about a focal point above their plane (tool_changer, kr16_like) | Harris & Piersol, *Shock and Vibration Handbook* (2002) ch. 30; Rivin (1999) |
| dovetail_gib | link_deflection | a tool-side dovetail slide turning elastically, softer to its gib's side (tool_changer, kr16_like) | Slocum, *Precision Machine Design* (1992) ch. 8; Rivin (1999) ch. 4 |
| bellows_coupling | link_deflection | the tool on a metal bellows coupling stretching along the tool axis and tilting in the bellows' ratio (ur10, kr16_like) | EJMA Standards, 10th ed. (2015) |
| radiant_tube_heater | thermal | roof radiant tube heaters switched by the hall's thermostat bowing the tubes from above (ur10) | EN 416-1; ASHRAE HVAC Systems and Equipment ch. 16; Boley & Weiner (1960) |
| dragging_brake | thermal | axis 2's holding brake dragging, its friction heat following the axis' speed (tool_changer, kr16_like) | Incropera & DeWitt ch. 5; brake makers' manuals as recalled |

Set ZO's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZO
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| gravity_table | joint_compliance | a soft servo's gravity feed-forward read from a coarse (q2, q3) table and interpolated bilinearly (kr16_like) | Raibert & Horn, The Industrial Robot 5 (1978); de Boor, *A Practical Guide to Splines* (1978) ch. 2 |
| entrained_air | joint_compliance | the telescopic ram's loaded cylinder chamber softened by entrained air following the gas law (tool_changer) | Merritt, *Hydraulic Control Systems* (1967) ch. 2; Yu, Chen & Lu, J. Dyn. Syst. Meas. Control 116 (1994) |
| differential_lash | backlash | a roll-pitch bevel differential wrist whose two side-gear trains each have their own lost motion (tool_changer, kr16_like) | Rosheim, *Robot Wrist Actuators* (1989); Nordin & Gutman, Automatica 38 (2002) |
| tensioner_stop | backlash | a wrist belt's tensioner arm swinging to its stop when its span is the tight one (ur10, kr16_like) | Gates synchronous belt design manual (as recalled); Beikmann, Perkins & Ulsoy, J. Vib. Acoust. 118 (1996) |
| race_waviness | transmission | axis 1's encoder read on a bearing inner ring with raceway waviness, at the orders near Z (1 - f_c) (ur10, kr16_like) | Yhland, Proc. IMechE 206 (1992); Wardle, Proc. IMechE 202 (1988); Harris & Kotzalas (2007) ch. 8 |
| lever_cam_fit | transmission | hydraulic axes driven to a cylinder stroke mapped from the joint angle by a fitted cubic (tool_changer) | VDI 2143; PLCopen Motion Control part 1 (as recalled) |
| deck_cupping | mount_compliance | a cart's fibreboard deck cupping as its bare underside takes up the washdown's water (ur10) | Crank, *The Mathematics of Diffusion* (1975) eq. 4.17; Timoshenko & Goodier ch. 13; *Wood Handbook* (2010) ch. 13 |
| closed_cell_pads | mount_compliance | the stand on closed-cell foam pads whose trapped cell gas stiffens them as they are squeezed (ur10, tool_changer, kr16_like) | Gibson & Ashby, *Cellular Solids* (1997) ch. 5 |
| cross_spring_pivot | link_deflection | the tool on a cross-spring flexure pivot whose stiffness the load along its leaves changes (ur10, tool_changer, kr16_like) | Haringx, Appl. Sci. Res. A1 (1949); Wittrick, Aeronaut. Q. 1 (1948); Jensen & Howell, Mech. Mach. Theory 39 (2004) |
| qzs_mount | link_deflection | a sensor on a quasi-zero-stiffness isolator moving by the cube root of its load's change (ur10, kr16_like) | Carrella, Brennan & Waters, J. Sound Vib. 301 (2007); Ibrahim, J. Sound Vib. 314 (2008) |
| ultrasonic_ram | thermal | the telescopic stage read by an ultrasonic sensor whose speed-of-sound compensation lags the air (tool_changer) | Kinsler, Frey, Coppens & Sanders, *Fundamentals of Acoustics* (2000) ch. 5; makers' notes as recalled; Incropera & DeWitt ch. 5 |
| dry_ice_nozzle | thermal | a dry-ice blasting lance's bracket chilled in the production between the blocks, warming while measured (ur10, kr16_like) | Spur, Uhlmann & Elbing, Wear 233-235 (1999); Incropera & DeWitt ch. 5 |

Set ZP's kinds (same case machinery; ranges and the changes made while checking the labels are in `cases.py`'s SET_ZP
comment):

| kind | family | physics | sources |
| --- | --- | --- | --- |
| soaked_jacket | joint_compliance | a protective jacket soaked in the washdown drying on the upper arm and forearm, its water's weight twisting axes 2 and 3 (kr16_like) | Keey, *Drying of Loose and Particulate Materials* (1992) ch. 1, 6; Mujumdar (ed.), *Handbook of Industrial Drying* |
| vessel_list | joint_compliance | the arm and the tracker on a deck listing as ballast is pumped: gravity turns in the base frame and loads axes 1-3 (ur10, tool_changer, kr16_like) | Biran & Lopez-Pulido, *Ship Hydrostatics and Stability* (2014) ch. 2, 6 |
| clevis_clearance | backlash | the boom cylinders' eye-pin clearances taken up on the side of the cylinder's net force, gravity less a counterbalance (tool_changer) | Shigley's *Mechanical Engineering Design* (10th ed.) ch. 7; Slocum, *Precision Machine Design* (1992) ch. 7 |
| clock_spring_flank | backlash | wrist rolls held on one flank of their lost motion by a spiral spring, the flank flipping where spring and gravity torques cancel (ur10, kr16_like) | Wahl, *Mechanical Springs* (1963) ch. 15; Slocum (1992) ch. 7 |
| mylar_strip | transmission | axis 1 read on a polyester code strip swelling with an unlogged humidity (tool_changer, kr16_like) | DuPont Teijin Films *Mylar* bulletin (as recalled); Crank, *The Mathematics of Diffusion* (1975) |
| tacho_integration | transmission | boom axes positioned by integrating analogue tachogenerators: a gain error and an integrated offset drift (tool_changer) | D'Azzo & Houpis, *Linear Control System Analysis and Design* (1995) |
| magnet_base | mount_compliance | the base clamped to steel by a permanent-magnet base whose rough interface closes by a log law of the contact pressure (ur10) | Greenwood & Williamson, Proc. R. Soc. A 295 (1966); Johnson, *Contact Mechanics* (1985) ch. 13 |
| ballast_stand | mount_compliance | an unanchored ballasted stand whose pads take no tension: a foot lifts and the stand rocks onto three (tool_changer) | Johnson (1985) ch. 5; Housner, BSSA 53 (1963) |
| needle_gripper | link_deflection | a part held on two rows of slanted needles, stiffer along than across them (ur10, kr16_like) | Timoshenko & Gere, *Mechanics of Materials* |
| ltb_boom | link_deflection | a deep, narrow gripper boom near lateral-torsional buckling moving sideways under its load (ur10, tool_changer, kr16_like) | Timoshenko & Gere, *Theory of Elastic Stability* (1961) ch. 6; Trahair, *Flexural-Torsional Buckling of Structures* (1993) |
| heated_bed | thermal | the forearm warmed by a heated bed by how low and how long the arm worked over it (ur10, in a mixture) | Howell, *A Catalog of Radiation Heat Transfer Configuration Factors*; Incropera & DeWitt ch. 5 |
| air_motor_heat | thermal | an idling air-motor spindle's lance following supply air that a load / unload compressor cycles (ur10, kr16_like) | Atlas Copco *Compressed Air Manual* (2015) ch. 3, as recalled |

Parameter ranges marked as assumptions in the module docstrings (`hardware.py`, `session.py`, `effects_body.py`)
are this study's own choices, not catalogue values; the gear table is an approximation (scaled from one catalogue
example) and the RV values are as recalled from the catalogue, not re-checked against it.
"""

LABELS = """## How the labels are made (oracle.py)

On the training poses (75 %, random or the last 25 % in time), with this study's own least squares:
(a) geometry alone (tracker frame, target offset and a complete product-of-exponentials error model: per joint two
axis tilts, two axis-point shifts, a zero offset; `scipy.optimize.least_squares`); (b) geometry + the TRUE
effect structure (its shape parameters known -- gear ratio, time constants, torque knots, true masses and
payload placement -- amplitudes free); (c) geometry + each family's generic model (`families.py`: the robot file's
masses, payload at the tool point, shape grids chosen by 3-fold cross-validation on the training poses). All are
scored on the test poses (RMS of the 3-D error). Label: `absorbed` where (b) gains < 5 % over (a) (then `none` is
a defensible answer); `ambiguous:{truth,f..}` where another family's (c) comes within 5 % of (b); else the truth
(for a mixture, its components whose removal from (b) costs >= 5 %).
"""


NOTES = """## Reading these numbers

* The oracle's (b) knows the true shapes (the gear ratio, the heat time constants, the torque knots, the true
  masses): it is a bound on what the data can give, not a model a diagnosis could fit. (c) are this study's own
  generic models; a stronger rival model would turn more labels `ambiguous`, a weaker one fewer.
* The 5 % thresholds are applied to one held-out split. {noise_note} Labels near the thresholds (gains of 5-15 %,
  rivals within 5-15 %) are therefore soft; the per-case table shows the RMS values behind each label.
* An `effect` verdict names its candidates. Its final model may hold a further effect whose family the diagnosis
  does not claim (tied with another family in its place, or a minor one); that effect is not counted as named.
* `right` is about naming, not fit: a verdict can name the truth while its final test RMS is no better than the
  geometric model (e.g. a time split, where a thermal model extrapolates), and a wrong name can still fit well
  (gravity-driven families mimic each other).
* Mount tilt, joint compliance and link sag are all driven by the gravity load: the same pose set often cannot
  separate them, which the ambiguous labels record.
* What the physics leaves out: axis shifts of the links from temperature gradients (per-link uniform expansion;
  set C bends a pedestal column, set D bends links warmed on one side, set I shifts the bodies along the axes of
  growing joint housings), dynamic loads, tracker outliers and anisotropic tracker noise, a second tracker station,
  the overlap compliance of the telescopic stage (set E's ram models the stage's guide pads and overhang, not the
  overlap).
"""


def _pct(a, b):
    return f"{a}/{b}" if b else "-"


def _summary(part: pd.DataFrame) -> list[str]:
    clear = part[~part.label.str.startswith("ambiguous") & ~part.label.isin(["none", "absorbed"])]
    amb = part[part.label.str.startswith("ambiguous")]
    quiet = part[part.label.isin(["none", "absorbed"])]
    mix = part[part.named.fillna("").str.contains(r"\+")]
    ratio = part.diag_final_mm / part.oracle_true_mm
    eff = part[~part.label.isin(["none", "absorbed"])]
    helps = np.array([any(r[f"rms_{f}_mm"] <= 0.95 * r.oracle_geom_mm for f in r.truth.split("+"))
                      for _, r in eff.iterrows()], bool)
    lines = [
        "| measure | count |", "| --- | --- |",
        f"| cases | {len(part)} |",
        f"| **right** (strict rules) | **{int(part.right.sum())}/{len(part)}** |",
        f"| right, counting ambiguous verdicts of up to three candidates | "
        f"{int(part.right3.sum())}/{len(part)} |",
        "| right, lenient (confident claim naming the truth where the data cannot decide; "
        f"hedged verdict of <= 3 on a clear label) | "
        f"{int(part.right_lenient.sum())}/{len(part)} |",
        f"| clear labels named | {_pct(int(clear.right.sum()), len(clear))} |",
        f"| ambiguous labels answered `ambiguous` with the truth in <= 2 candidates | "
        f"{_pct(int(amb.right.sum()), len(amb))} |",
        f"| confident `effect` where the oracle says the data cannot decide | "
        f"{_pct(int(amb.confident_undecidable.sum()), len(amb))} |",
        f"| none / absorbed labels answered none or inconclusive | "
        f"{_pct(int(quiet.right.sum()), len(quiet))} |",
        f"| false claims (an effect or ambiguity claimed on a none / absorbed label) | "
        f"{_pct(int(quiet.false_claim.sum()), len(quiet))} |",
        f"| mixtures (two named components): one named / both named | "
        f"{_pct(int(mix.right.sum()), len(mix))} / {int(mix.both.sum())} |",
        f"| diagnosis errors | {int((part.verdict == 'error').sum())} |",
        f"| median final test RMS / oracle true-structure test RMS | "
        f"{np.nanmedian(ratio):.2f} |",
        f"| effect labels where the true family's generic model helps: named right | "
        f"{_pct(int(eff[helps].right.sum()), int(helps.sum()))} |",
        f"| effect labels where it does not (a physics gap): named right | "
        f"{_pct(int(eff[~helps].right.sum()), int((~helps).sum()))} |",
    ]
    return lines


def _by_class(part: pd.DataFrame) -> list[str]:
    lines = ["| physics | cases | right | labels |", "| --- | --- | --- | --- |"]
    for phys, g in part.groupby("physics"):
        labels = ", ".join(f"{k} x{v}" for k, v in g.label.value_counts().items())
        lines.append(f"| {phys} | {len(g)} | {int(g.right.sum())} | {labels} |")
    return lines


def _cases(part: pd.DataFrame) -> list[str]:
    fams = " | ".join(SHORT[f] for f in FAMILIES)
    lines = [f"| case | robot | physics | poses / split | effect RMS | label | geom | true | {fams} | verdict | "
             "named / candidates | final RMS | right |",
             "| " + " | ".join(["---"] * (13 + len(FAMILIES) - 1)) + " |"]
    for _, r in part.iterrows():
        fam = " | ".join(f"{r[f'rms_{f}_mm']:.3f}" for f in FAMILIES)
        said = r.candidates if isinstance(r.candidates, str) else ""
        unnamed = [e for e in str(r.effects).split("+") if r.verdict == "effect" and isinstance(r.effects, str)
                   and e not in said.split("+")]
        said += f" (+ {'+'.join(unnamed)}: family not claimed)" if unnamed else ""
        mark = "right" if r.right else ("lenient" if r.right_lenient else "wrong")
        final = "-" if pd.isna(r.get("diag_final_mm")) else f"{r.diag_final_mm:.3f}"
        lines.append(f"| {r.case} | {r.robot} | {r.physics} | {r.poses} / {r.split} | {r.effect_rms_mm:.3f} | "
                     f"{r.label} | {r.oracle_geom_mm:.3f} | {r.oracle_true_mm:.3f} | {fam} | {r.verdict} | "
                     f"{said or ''} | {final} | {mark} |")
    return lines


def write_report(frame: pd.DataFrame, path, *, wall: float, jobs: int, quick: bool) -> None:
    out = [HEAD]
    if quick:
        out.append("**Quick run (--quick): four cases per set at 40 poses; not the benchmark's numbers.**\n")
    out.append(f"Run: {len(frame)} cases in {wall:.0f} s wall on {jobs} worker(s); oracle "
               f"{frame.oracle_s.sum():.0f} s and diagnosis {frame.diag_s.sum():.0f} s of CPU in total.\n")
    for name, part in frame.groupby("set"):
        out += [f"## Set {name}: results\n", *_summary(part), "", f"### Set {name} by physics\n", *_by_class(part),
                "", f"### Set {name} case by case\n",
                "RMS in mm on the test poses: effect RMS = the effects' displacement before any fit; geom = oracle "
                "(a); true = oracle (b); then each family's generic model (c); final = the diagnosis's final "
                "model. Verdict `effect`: the effects it named (a further effect in its final model whose family it does "
                "not claim in brackets); otherwise its candidates.\n", *_cases(part), ""]
        errs = part[part.verdict == "error"]
        if len(errs):
            out += ["Diagnosis errors:\n"] + [f"- {r.case}: {r.error}" for _, r in errs.iterrows()] + [""]
    n_test = float(np.median(np.ceil(0.25 * frame.poses)))
    spread = 100 / np.sqrt(2 * 3 * n_test)
    noise_note = (f"With the median {n_test:.0f} test poses a test RMS of pure noise scatters by about {spread:.0f} % "
                  f"from split to split (1 / sqrt(2 x 3 x n_test)), {'more' if spread > 5 else 'less'} than the 5 % "
                  "threshold; two models scored on the same poses differ by less, as their errors are correlated.")
    out += [NOTES.format(noise_note=noise_note), PHYSICS, LABELS]
    tmp = str(path) + ".tmp"
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write("\n".join(out) + "\n")
    os.replace(tmp, path)

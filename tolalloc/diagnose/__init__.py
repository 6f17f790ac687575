"""Sim-to-real diagnosis: where the measured robot misses its model, which unmodelled effect explains it,
and how far the held-out error shrinks once the effect is added.

Modules: :mod:`.measurements` (CSV reading and checks), :mod:`.geometry` (the complete, minimal geometric
calibration model; the paper's error-screw model stays the tolerance model), :mod:`.calibrate` (registration,
target offset, identifiable geometric errors, MAP), :mod:`.guards` (implausible parameters, extrapolation,
CV fallback), :mod:`.uncertainty` (parameter covariance, predicted test uncertainty), :mod:`.effects` and
:mod:`.thermal` (candidate effects), :mod:`.gravity_loads` (mass model, gravity torques), :mod:`.choice` and
:mod:`.evidence` (variant choice, fitted priors), :mod:`.select` (held-out scoring on the training file),
:mod:`.stepwise` (forward selection, backward elimination), :mod:`.verdict` (effect / none / ambiguous /
inconclusive), :mod:`.where` (residual breakdown), :mod:`.pipeline` (:func:`diagnose`; the test file is sealed
until the model is chosen), :mod:`.synth` (synthetic measurement sets with a withheld effect),
:mod:`.ipa_ur10` (reader of the public IPA UR10 laser-tracker files); progress bars of the fits and stages come
from :mod:`tolalloc.progress`. The Markdown report of a diagnosis is written by :mod:`tolalloc.report.diagnosis`.
"""

from tolalloc.diagnose.calibrate import Calibration, Fit, Identifiability, calibrate
from tolalloc.diagnose.effects import EFFECTS
from tolalloc.diagnose.ipa_ur10 import read_ipa_ur10
from tolalloc.diagnose.measurements import Measurements, measurements_from_frame, read_measurements
from tolalloc.diagnose.diagnosis import Diagnosis
from tolalloc.diagnose.pipeline import diagnose
from tolalloc.diagnose.verdict import VERDICTS, Verdict
from tolalloc.diagnose.synth import LABELS, SynthCase, generate

__all__ = ["EFFECTS", "LABELS", "Measurements", "read_measurements", "measurements_from_frame", "read_ipa_ur10",
           "calibrate", "Calibration", "Fit", "Identifiability", "diagnose", "Diagnosis", "generate", "SynthCase",
           "Verdict", "VERDICTS"]

"""The settings of :func:`~tolalloc.workflows.diagnose_measurements`: a test file measured in another tracker frame
(:class:`Refit`) and how the fits weigh and place the data (:class:`FitOptions`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.workflows import defaults as D
from tolalloc.workflows.checks import check_choice, number, shown
from tolalloc.workflows.settings import Settings

__all__ = ["Refit", "FitOptions"]


def _numbers(value):
    """``value`` for a JSON record: None, one number, or a list of numbers."""
    if value is None:
        return None
    flat = [float(v) for v in np.ravel(value)]
    return flat[0] if np.ndim(value) == 0 else flat


@dataclass(frozen=True, eq=False)
class Refit(Settings):
    """The test file is another session in another tracker frame: its registration (and target offset) is re-fitted
    on some of its poses, which are then not scored (``test_frame=Refit(...)``; ``test_frame="refit"`` is
    ``Refit()``).

    Parameters
    ----------
    register_n : int or float, optional
        How many test poses register the frame: a count (>= 5, default 30) or, below 1, a fraction of the test
        poses; chosen spread in joint space (seeded by the job's ``seed``).
    register_rows : sequence of int, optional
        Instead of ``register_n``: the test file's rows that register the frame (data rows from 1, e.g.
        ``range(1, 61)`` for a registration set measured first; a DataFrame's by position); every other row is scored.
    update : {"frame", "calibration"}
        What the registration poses re-fit: ``frame`` (default) the tracker frame and probe offset, the trained model
        frozen; ``calibration`` also a correction of the trained geometric and effect parameters, the training fit as
        the prior (:mod:`tolalloc.diagnose.recalibrate`).
    """

    register_n: float | None = None
    register_rows: object = None
    update: str = "frame"

    def check(self) -> None:
        from tolalloc.diagnose.register import MIN_REGISTER, check_register_rows

        if self.register_n is not None:
            x = number(self.register_n, "register_n")
            if not (np.isfinite(x) and 0 < x and (x < 1 or (x == int(x) and x >= MIN_REGISTER))):
                raise ArgumentError("register_n", f"expected a count of registration poses (a whole number >= "
                                    f"{MIN_REGISTER}, e.g. 30) or a fraction of the test poses (0 < f < 1, e.g. 0.2), "
                                    f"got {shown(self.register_n)}.")
        rows = check_register_rows(self.register_rows, self.register_n, test_given=True, test_frame="refit")
        check_choice(self.update, "update", ("frame", "calibration"))
        self._set(register_rows=None if rows is None else tuple(rows))

    def to_dict(self) -> dict:
        return {"register_n": self.register_n,
                "register_rows": None if self.register_rows is None else list(self.register_rows),
                "update": self.update}


@dataclass(frozen=True, eq=False)
class FitOptions(Settings):
    """How the diagnosis's fits weigh the measurements and where they place the probe.

    Parameters
    ----------
    robust_loss : {"auto", "tukey", "huber", "soft_l1"}
        M-estimator of the fits (IRLS on each pose's 3-D residual); ``auto`` (default): ``tukey``, or ``huber`` on a
        small training file (fewer than 10 poses per fitted parameter); ``tukey`` gives gross outliers no weight
        and lists them.
    target_offset_mm : array (3,), optional
        Prior mean of the probe / target offset in the flange frame, relative to the robot's tool point [mm]
        (needs ``target_offset_sd_mm``).
    target_offset_sd_mm : float or array (3,), optional
        Its prior standard deviation [mm], one value for x, y and z or one each, used by every fit; without it each
        fold borrows the full training fit's offset as its prior.
    instrument_noise_mm : float, optional
        The measuring instrument's stated noise, one standard deviation per axis [mm]: a final model whose
        out-of-fold error is far above it gets a guard (an unlogged load or disturbance, or physics outside the
        families). Choices and verdicts do not use it.
    """

    robust_loss: str = D.ROBUST_LOSS
    target_offset_mm: object = None
    target_offset_sd_mm: object = None
    instrument_noise_mm: float | None = None

    def check(self) -> None:
        from tolalloc.diagnose.calibrate import offset_prior
        from tolalloc.diagnose.guards import instrument_noise

        check_choice(self.robust_loss, "robust_loss", ("auto", "tukey", "huber", "soft_l1"))
        offset_prior(self.target_offset_mm, self.target_offset_sd_mm)
        instrument_noise(self.instrument_noise_mm)

    def to_dict(self) -> dict:
        off = self.target_offset_mm
        return {"robust_loss": self.robust_loss,
                "target_offset_mm": _numbers(off),
                "target_offset_sd_mm": _numbers(self.target_offset_sd_mm),
                "instrument_noise_mm": _numbers(self.instrument_noise_mm)}

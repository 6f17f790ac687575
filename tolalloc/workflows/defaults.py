"""The defaults of every job, in one place: the Python calls, their settings objects and the command line read them
from here, so a call and the command with the same inputs give the same numbers.

=============================  ==================  =====================================================
constant                       value               what
=============================  ==================  =====================================================
``RADIUS_MM``, ``PROB``        0.25 mm, 0.95       the requirement ``P(|dP| < r) >= p``
``N_MC``                       1 000 000           Monte Carlo samples per pose of an allocation's verification
``SEED``                       0                   every job's random seed
``ESTIMATOR``                  ``"auto"``          the verification's probability estimator
``CORRECTION_ROUNDS``          2                   rounds of the correction loop at most
``COVERAGE_N``                 100 000             fresh poses of a box region's coverage check
``SOLVER``                     ``"exact"``         the design reported (``"certified"``: cvxpy + Clarabel)
``SIMULATION_N_MC``            100 000             robots sampled by :func:`~tolalloc.workflows.simulate_errors`
``SIMULATION_RADII_MM``        (0.15, 0.25)        its radii of ``P(|dP| < r)``
``CHUNK_SIZE``                 1 048 576           samples per Dask task
``LINK_MODE``                  ``"consistent"``    link errors move axes and tool
``DEFLECTION_MODE``            ``"screw"``         axis deflections as error screws
=============================  ==================  =====================================================
"""

from tolalloc.workflows.requirements import DEFAULT_PROB as PROB
from tolalloc.workflows.requirements import DEFAULT_RADIUS_MM as RADIUS_MM

__all__ = ["RADIUS_MM", "PROB", "N_MC", "SEED", "ESTIMATOR", "CORRECTION_ROUNDS", "COVERAGE_N", "SOLVER",
           "SIMULATION_N_MC", "SIMULATION_RADII_MM", "CHUNK_SIZE", "LINK_MODE", "DEFLECTION_MODE", "CI",
           "TOP", "FOLDS", "ALPHA", "ROBUST_LOSS", "N_POSES", "N_CANDIDATES", "NOISE_MM", "NOISE_DEG",
           "RANDOM_PLANS"]

N_MC = 10**6
SEED = 0
ESTIMATOR = "auto"
CORRECTION_ROUNDS = 2
COVERAGE_N = 100_000
SOLVER = "exact"
SIMULATION_N_MC = 100_000
SIMULATION_RADII_MM = (0.15, 0.25)
CHUNK_SIZE = 2**20
CI = "wilson"
LINK_MODE = "consistent"
DEFLECTION_MODE = "screw"
#: budget rows of :func:`~tolalloc.workflows.analyze_errors`
TOP = 10
#: :func:`~tolalloc.workflows.diagnose_measurements`: cross-validation folds, significance level, M-estimator
FOLDS = 5
ALPHA = 0.01
ROBUST_LOSS = "auto"
#: :func:`~tolalloc.workflows.plan_calibration`: plan size, candidates, tracker noise, random plans compared
N_POSES = 30
N_CANDIDATES = 2000
NOISE_MM = 0.02
NOISE_DEG = 0.001
RANDOM_PLANS = 100

"""ISO 9283 acceptance: requirements as robot makers state them, the acceptance test simulated, and the verdict
with the measurement uncertainty (ISO 14253-1)."""

from tolalloc.acceptance.statistics import (pose_accuracy, pose_repeatability, orientation_accuracy,
                                            orientation_repeatability, multidirectional_accuracy,
                                            multidirectional_orientation, distance_accuracy,
                                            distance_repeatability, path_accuracy, path_repeatability)
from tolalloc.acceptance.requirements import (Requirement, Conditions, PositionRequirement, OrientationRequirement,
                                              IsoRequirement, PoseAccuracy, PoseRepeatability, OrientationAccuracy,
                                              OrientationRepeatability, MultiDirectionalAccuracy,
                                              MultiDirectionalOrientation, DistanceAccuracy,
                                              PathAccuracy, check_requirements, split_requirements)
from tolalloc.acceptance.cube import TestCube, CubePlacement, place_cube
from tolalloc.acceptance.instrument import Tracker
from tolalloc.acceptance.layout import AcceptanceTest, acceptance_test
from tolalloc.acceptance.model import ErrorEffects, EffectCovariance, StatisticModel, statistic_models
from tolalloc.acceptance.decision import Decision, decide
from tolalloc.acceptance.predict import AcceptancePrediction, StatisticPrediction, predict_acceptance
from tolalloc.acceptance.parts import parts_effects
from tolalloc.acceptance.static_load import StaticCompliance, static_compliance

__all__ = ["pose_accuracy", "pose_repeatability", "orientation_accuracy", "orientation_repeatability",
           "multidirectional_accuracy", "MultiDirectionalAccuracy", "multidirectional_orientation",
           "MultiDirectionalOrientation",
           "distance_accuracy", "distance_repeatability", "path_accuracy", "path_repeatability", "Requirement",
           "Conditions", "PositionRequirement", "OrientationRequirement", "IsoRequirement", "PoseAccuracy",
           "PoseRepeatability", "OrientationAccuracy", "OrientationRepeatability", "DistanceAccuracy", "PathAccuracy",
           "check_requirements", "split_requirements", "TestCube", "CubePlacement", "place_cube", "Tracker",
           "AcceptanceTest", "acceptance_test", "ErrorEffects", "EffectCovariance", "StatisticModel",
           "statistic_models", "Decision", "decide", "AcceptancePrediction", "StatisticPrediction",
           "predict_acceptance", "parts_effects", "StaticCompliance", "static_compliance"]

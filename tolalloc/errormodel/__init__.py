"""The error model: error screws inserted in the POE chain, their sigma sets and sampling, and the exact perturbed-chain program."""

from tolalloc.errormodel.model import ErrorParameter, ErrorModel, KINDS
from tolalloc.errormodel.build import build_error_model
from tolalloc.errormodel.sampling import sample_values

__all__ = ["ErrorParameter", "ErrorModel", "build_error_model", "KINDS", "sample_values"]

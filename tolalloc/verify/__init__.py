"""Monte Carlo verification of allocated designs."""

from tolalloc.verify.designs import Verification, verify_design

__all__ = ["Verification", "verify_design"]

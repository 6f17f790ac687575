"""Monte Carlo verification of allocated designs."""

from tolalloc.verify.designs import Verification, check_resolvable, verify_design

__all__ = ["Verification", "verify_design", "check_resolvable"]

"""The Examples sections of the public API run (doctest) and every public name is documented in numpydoc form."""

import doctest
import importlib

import pytest

import tolalloc

#: modules whose docstring examples are part of the documentation
DOCTEST_MODULES = ["tolalloc.workflows.allocation", "tolalloc.workflows.allocation_result",
                   "tolalloc.workflows.analysis", "tolalloc.workflows.simulation", "tolalloc.workflows.calplan",
                   "tolalloc.workflows.diagnosis", "tolalloc.robot.model", "tolalloc.robot.io.load"]


@pytest.mark.parametrize("name", DOCTEST_MODULES)
def test_examples_run(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed"


def test_every_workflow_function_has_a_running_example():
    for name in ("allocate_tolerances", "analyze_errors", "simulate_errors", "plan_calibration",
                 "diagnose_measurements"):
        doc = getattr(tolalloc, name).__doc__
        assert "Examples\n    --------\n" in doc and ">>>" in doc.split("Examples", 1)[1], name

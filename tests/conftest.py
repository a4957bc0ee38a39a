"""Shared pytest configuration.

``--update-generated``: SymForce's compare_or_update pattern.  Without it, the staleness test
regenerates ``generated/`` (and the derivation reports) into a temporary folder and fails with a
unified diff when anything differs; with it, the committed files are overwritten instead.

Hypothesis profiles (``HYPOTHESIS_PROFILE``): "ci", the default, derandomised with a fixed
example budget (``make test``); "fuzz", a larger randomised budget (``make fuzz``).
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

_FUZZ_CHECKS = [HealthCheck.too_slow, HealthCheck.data_too_large]
settings.register_profile(
    "ci", max_examples=40, derandomize=True, deadline=None, suppress_health_check=_FUZZ_CHECKS
)
settings.register_profile(
    "fuzz", max_examples=2000, deadline=None, suppress_health_check=_FUZZ_CHECKS
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--update-generated",
        action="store_true",
        default=False,
        help="overwrite generated/ and the derivation reports instead of failing when stale",
    )


@pytest.fixture(scope="session")
def update_generated(request: pytest.FixtureRequest) -> bool:
    """True when pytest runs with --update-generated."""
    return bool(request.config.getoption("--update-generated"))

"""Shared pytest configuration.

``--update-generated``: SymForce's compare_or_update pattern.  Without it, the staleness test
regenerates ``generated/`` (and the derivation reports) into a temporary folder and fails with a
unified diff when anything differs; with it, the committed files are overwritten instead.
"""

from __future__ import annotations

import pytest


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

"""The one exception type of the library.

Every bad input raises :class:`CurveReconError` with a one-line message; the command line prints
``curverecon: error: <message>`` on stderr and exits with status 2.
"""

from __future__ import annotations


class CurveReconError(ValueError):
    """Bad or insufficient input (one-line message, no traceback on the command line)."""

    def __init__(self, message: str) -> None:
        super().__init__(" ".join(str(message).split()))

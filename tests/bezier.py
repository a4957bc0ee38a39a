"""Independent test geometry shared by the test files: a cubic Bezier curve (no project code)."""

from __future__ import annotations

import numpy as np


def bezier(ctrl: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Points (len(u), D) of the cubic Bezier curve with control points ctrl (4, D), u in [0, 1]."""
    u = u[:, None]
    return (
        (1 - u) ** 3 * ctrl[0]
        + 3 * u * (1 - u) ** 2 * ctrl[1]
        + 3 * u**2 * (1 - u) * ctrl[2]
        + u**3 * ctrl[3]
    )

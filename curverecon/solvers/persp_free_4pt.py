"""Perspective, free motion, A, B, C and D, three frames: no practical minimal solver (why).

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): the six distances
of the four points are the same in every frame, |lambda_Qf m_Qf - lambda_Pf m_Pf| =
|lambda_Q0 m_Q0 - lambda_P0 m_P0| (m the rays, lambda the depths, lambda_A0 = 1): 6 (F - 1)
equations in 4 F - 1 depths.  Two frames leave a curve of solutions (msolve: dimension 1), three
frames are overdetermined by one (12 equations in 11 unknowns; msolve: no solution on random
data, four on noise-free data: the truth and the point reflection -X of a later frame's points,
which keeps every distance but puts them behind the camera).  So three frames, as the seed's
table says, determine the motion, but there is no square minimal problem to solve: leaving one
equation out gives 1,280 complex solutions (msolve), a homotopy over that many paths costs
about a second a sample, far above a RANSAC sample's budget.  Nister and Schaffalitzky (IJCV
2006) solve this case by a one-dimensional search along the two-view curve; that is not built
here.  The rigid stage seeds this row otherwise (e.g. weak perspective: the orthographic
three-point solver on A, B, C, then maximum likelihood under the pinhole).
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B", "C", "D")
ROW = "persp_free_4pt"
PRACTICAL = False
"""No practical minimal solver (see the module docstring)."""


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Always raises CurveReconError: the four-point row has no practical minimal solver."""
    raise CurveReconError(
        f"{ROW}: no practical minimal solver (three frames are overdetermined by one; the "
        "relaxed square system has 1,280 solutions); the rigid stage seeds this model otherwise"
    )

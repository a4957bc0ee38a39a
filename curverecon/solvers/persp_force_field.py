"""Perspective, homogeneous force field, A and B: no practical minimal solver (why).

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): the mass centre G,
an unseen body point, moves as G(t) = g0 + g1 t + g2 t^2 / 2 in camera coordinates (9
unknowns); the body invariants aa = |A - G|^2, bb = |B - G|^2, ab = (A - G).(B - G) (3) hold in
every frame with A_f = lambda_Af m_Af, B_f = lambda_Bf m_Bf (m the rays, lambda_A0 = 1): 3
equations per frame in its 2 depths, one net constraint a frame on 12 unknowns less the one
depth fixed in frame 0.  So 11 frames are the least: the Jacobian of the equations at the truth
of a construction has full rank 33 at 11 frames and rank 30 of 31 at 10 (a curve of solutions).
The seed's "n" is an 11.  33 quadrics (Bezout 2^33) are far beyond msolve within ``make derive``
and beyond a homotopy per RANSAC sample, so there is no practical minimal solver; the rigid
stage seeds this row otherwise (e.g. from the free-motion or orthographic fit).
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 11
POINTS: tuple[str, ...] = ("A", "B")
ROW = "persp_force_field"
PRACTICAL = False
"""No practical minimal solver (see the module docstring)."""


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Always raises CurveReconError: the force field has no practical minimal solver."""
    raise CurveReconError(
        f"{ROW}: no practical minimal solver (11 frames, 33 quadrics in 33 unknowns); the "
        "rigid stage seeds this model otherwise"
    )

"""Every real solution of a rigid body's minimal problem under orthographic projection.

The minimal solvers of the seed's Section 2 rows (``curverecon/solvers/ortho_<row>.py``) return a
:class:`RigidSolutions`.  Conventions (CONTRACT.md, "Configurations beyond the paper's own"):

- ``points3[s, f, p]`` is point ``p`` (A first, then B, C in the solver's ``POINTS`` order) in
  frame ``f``'s camera coordinates, input units: x, y equal the input's image position and z is
  the orthographic depth relative to A (A's z = 0 in every frame);
- ``rotations[s, f]`` is R_f with X_f - A_f = R_f (X_0 - A_0) for every body point X, R_0 = I;
- ``motion[s]`` holds the contract's ``motion_parameters`` keys the row's model has: ``"axis"``
  (unit vector in frame 0's camera coordinates), ``"rate_deg"`` (degrees per unit of t),
  ``"angle_deg"`` (per frame, frame 0's = 0), ``"acceleration"``;
- every real solution is listed, mirror images (z -> -z) included; paths that failed are counted
  in ``n_failed_paths``, never dropped silently.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class RigidSolutions:
    """Every real solution of one minimal problem (S solutions, FRAMES frames, P points)."""

    points3: np.ndarray
    """(S, FRAMES, P, 3): every point in every frame's camera coordinates (A's z = 0)."""
    rotations: np.ndarray
    """(S, FRAMES, 3, 3): X_f - A_f = R_f (X_0 - A_0); R_0 = I."""
    motion: list[dict] = field(default_factory=list)
    """Per solution: the motion model's parameters (contract's ``motion_parameters`` keys)."""
    n_paths: int = 0
    """Solutions of the polynomial system over the complex numbers that were computed."""
    n_complex: int = 0
    """Computed solutions that are not real."""
    n_failed_paths: int = 0
    """Homotopy paths that failed after every retry (0 for closed-form solvers)."""

    @property
    def n_solutions(self) -> int:
        """The number S of real solutions listed."""
        return int(self.points3.shape[0])

    @staticmethod
    def empty(frames: int, points: int) -> RigidSolutions:
        """No real solution (arrays of the right shapes with S = 0)."""
        return RigidSolutions(
            points3=np.zeros((0, frames, points, 3)),
            rotations=np.zeros((0, frames, 3, 3)),
        )

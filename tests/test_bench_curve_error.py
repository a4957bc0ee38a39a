"""The bench's curve errors (bench/curve_end_to_end.py) on curves moved by a known rotation."""

from __future__ import annotations

import numpy as np

from bench.curve_end_to_end import curve_error, curve_error_up_to_rotation
from curverecon.curve_families import FAMILIES
from curverecon.simulate import make_scene


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = axis / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


def test_a_tilt_about_a_counts_in_frame_0_and_not_up_to_rotation() -> None:
    """A true curve tilted 2 degrees about its first point: its error in frame 0's coordinates
    is well above 0.5 % of the length; up to a rotation about A it is below 1e-4."""
    truth = make_scene(np.random.default_rng(3), 4, with_curve=True, curve_family=FAMILIES[0])
    q = truth.curve_3d
    rot = _rotation(np.array([1.0, 0.3, 0.0]), np.radians(2.0))
    tilted = q[0] + (q - q[0]) @ rot.T
    assert curve_error(tilted, q) > 5e-3
    assert curve_error_up_to_rotation(tilted, q) < 1e-4
    # a different shape stays different after any rotation
    bent = q + np.outer(np.sin(np.linspace(0, np.pi, len(q))), [0.0, 0.0, 0.05]) * np.ptp(q)
    assert curve_error_up_to_rotation(bent, q) > 1e-3

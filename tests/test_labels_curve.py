"""Which end is A judged by a polyline (``curve.labels``, ``curve.labels_kernel``)."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from curverecon.curve.labels_kernel import placement_mean_squares


def test_placement_sweep_is_the_brute_force_mean_of_nearest_distances():
    """The kernel's mean squares equal the nearest distances taken from the full distance
    tables of the projected curve and the polyline, placement by placement."""
    rng = np.random.default_rng(5)
    s = np.linspace(0.0, 1.0, 40)
    body = np.column_stack([150.0 * s, 30.0 * np.sin(4.0 * s), 12.0 * s * s])
    rots = Rotation.random(7, random_state=rng).as_matrix()
    origin = np.array([40.0, -15.0])
    poly = rng.uniform(-50.0, 200.0, (11, 2))
    dense = rng.uniform(-50.0, 200.0, (60, 2))
    got = placement_mean_squares(rots, body, origin, poly, dense, 3)
    for k, rot in enumerate(rots):
        proj = body @ rot[:2].T + origin
        there = np.linalg.norm(poly[:, None] - proj[None], axis=2).min(axis=1)
        back = np.linalg.norm(proj[::3, None] - dense[None], axis=2).min(axis=1)
        want = np.mean(np.concatenate([there, back]) ** 2)
        assert abs(got[k] - want) <= 1e-9 * want

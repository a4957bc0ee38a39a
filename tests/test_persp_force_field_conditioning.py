"""The perspective force field with A and B: its count is right, its conditioning is the turn.

The construction and the hand-written Jacobian are ``bench.persp_force_field_bound``'s (a body
with A, B and an unseen mass centre on a 3-D parabola, a smooth turn, a pinhole; independent of
``curverecon``): its rank and c's Cramer-Rao bound (1 px) say what the derivation's count (full
rank from 11 frames, ``derivations.section2_perspective.force_field_jacobian_ranks``) means in
practice.
"""

from __future__ import annotations

import numpy as np

from bench.persp_force_field_bound import jacobian, median_bound, scene


def test_the_jacobian_has_full_rank_from_eleven_frames_at_a_practical_scene():
    """At the bench's kind of scene (a 240 degree turn, body a fifth of its distance) the
    Jacobian has more unknowns than measurements up to 10 frames and full column rank from 11:
    the smallest column-scaled singular value is far below the largest but far above
    rounding, so the count holds and the trouble is conditioning."""
    rng = np.random.default_rng(39)
    for frames in (10, 11, 12, 16):
        a, b, g, rots, t, focal = scene(rng, frames, 240.0)
        jac = jacobian(a, b, g, rots, t, focal)
        sv = np.linalg.svd(jac / np.linalg.norm(jac, axis=0), compute_uv=False)
        if frames == 10:
            assert jac.shape[0] < jac.shape[1]
        else:
            assert jac.shape[0] >= jac.shape[1]
            assert 1e-11 < sv[-1] / sv[0] < 1e-3


def test_the_chord_is_determined_only_when_the_body_turns_far():
    """c's bound at 1 px, 30 frames: above c itself for a 240 degree turn (the bench's scenes
    turn 180-300 degrees), a few per cent for two turns; the orthographic twin of the same
    motion is within 2 % already at 240 degrees (the pinhole's unknown depth path costs it)."""
    assert median_bound(240.0, 30, scenes=7, seed=7) > 1.0
    assert median_bound(720.0, 30, scenes=7, seed=7) < 0.1
    assert median_bound(240.0, 30, perspective=False, scenes=7, seed=7) < 0.02

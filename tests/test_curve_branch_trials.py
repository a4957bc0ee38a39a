"""Branch choice by the curve (``curve/branches.py``) on trials that cannot carry the curve, and
the answer's chi2 after a switch.

Helix seed 1105 (0.5 px, 0.5 degree, 12 frames; simulator: a 3-D curve moved and projected),
without the curve bundle: some refits put every frame's line of sight along frame 0's, and
section 4 refuses them ("no frame views the curve from a different direction than frame 0").
Such a trial used to end the whole reconstruction; it is scored inf (never chosen) and the
reconstruction goes on.  (Start poses that section 4 refuses still end it with a one-line
message: tests/test_curve_pipeline.py, helix 2104.)
"""

from __future__ import annotations

import numpy as np

from curverecon.curve.bundle import end_point_chi2
from curverecon.options import CurveOptions, ReconstructOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene

NO_BUNDLE = ReconstructOptions(curve=CurveOptions(bundle=False))


def _scene(seed: int, noise: float):
    return make_scene(
        np.random.default_rng(seed), 12, noise, noise, with_curve=True, curve_family="helix"
    )


def test_a_trial_section_4_refuses_does_not_end_the_reconstruction():
    scene = _scene(1105, 0.5)
    rec = reconstruct(scene.observations, options=NO_BUNDLE)
    assert rec.curve3d is not None and np.all(np.isfinite(rec.curve3d))
    # the pose branches the curve chose are reported, and the shape is near the simulator's
    assert any("pose branch chosen by the curve" in w for w in rec.warnings)
    assert abs(rec.c - scene.truth.c) < 0.05 * scene.truth.c
    assert np.degrees(np.abs(rec.shape[1:] - scene.truth.shape[1:])).max() < 5.0


def test_the_answers_chi2_follows_the_switched_branches():
    """Helix 1105: the curve switches frames [1, 3, 4, 8] to their other branch.  The answer's
    chi2 is the end points' chi2 of its own shape and poses, recomputed here from the input
    (per-frame sigmas 1 px and 1 degree, the defaults), not the start's (0.83 for 1.27)."""
    scene = _scene(1105, 0.5)
    obs = scene.observations
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    for options in (
        NO_BUNDLE,
        # the refused bundle: the end-point answer (with the switches) stays
        ReconstructOptions(curve=CurveOptions(never_worse_f_test=False)),
    ):
        rec = reconstruct(obs, options=options)
        assert any("pose branch chosen by the curve" in w for w in rec.warnings)
        inl = np.asarray(rec.inliers, bool)
        own = float(np.sum(end_point_chi2(rec.shape, rec.poses, obs, inl, w8)[inl]))
        np.testing.assert_allclose(rec.chi2, own, rtol=1e-6)

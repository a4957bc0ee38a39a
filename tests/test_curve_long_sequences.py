"""The curve stage on long sequences: linear in the frames.

From ``CurveOptions.bundle_max_frames`` frames on (end points and tangents given) the branch
choice by the curve and the start curve use ``curve_search_max_frames`` frames spread over the
sequence, the end-point answer stays and the curve alone is fitted with every pose fixed.  The
threshold is lowered here so that a 40-frame scene takes that path in seconds.  The curve is
checked against the scene's own 3-D curve (``simulate.make_scene``, built without project code).
"""

from __future__ import annotations

import numpy as np
import pytest

from bench.curve_end_to_end import curve_error
from curverecon.curve import section4
from curverecon.curve.stage import subset_frames
from curverecon.options import CurveOptions, ReconstructOptions
from curverecon.pipeline import reconstruct, reconstruct_end_points
from curverecon.simulate import make_scene


@pytest.mark.parametrize(("n", "count"), [(5, 20), (20, 20), (21, 20), (1000, 20), (57, 7)])
def test_subset_frames_spread_over_the_sequence_from_frame_0(n, count):
    sub = subset_frames(n, count)
    assert sub[0] == 0
    assert len(sub) == min(n, count)
    assert np.all(np.diff(sub) > 0) and sub[-1] == n - 1
    if n > count:  # no gap much wider than the even spacing
        assert np.diff(sub).max() <= int(np.ceil((n - 1) / (count - 1))) + 1


@pytest.mark.parametrize("family", ["helix", "clothoid"])
def test_long_sequence_keeps_the_end_point_answer_and_fits_the_curve(family):
    scene = make_scene(np.random.default_rng(7), 40, 1.0, 1.0, with_curve=True, curve_family=family)
    opts = ReconstructOptions(curve=CurveOptions(bundle_max_frames=30))
    rec = reconstruct(scene.observations, options=opts)
    ends_only = reconstruct_end_points(scene.observations, opts)
    # the branch choice on the subset switches poses only, never the shape
    assert np.array_equal(rec.shape, ends_only.shape)
    info = rec.curve_bundle
    assert info["accepted"] is False and info["iterations"] == 0
    assert len(info["frame_rms_px"]) == 40  # measured on every frame, fitted on 20
    # every frame's polyline lies near the curve under its (end-point) pose: a few pixels
    assert np.median(info["frame_rms_px"]) < 5.0
    # the end-point answer's shape and poses bound the curve (at 1 px / 1 degree and 40 frames
    # the joint bundle gets 0.15 %, this path 1.1 % on the helix): within 2 % of the length
    assert curve_error(rec.curve3d, scene.curve_3d) < 0.02
    assert rec.curve3d_std is not None and np.all(np.isfinite(rec.curve3d_std))
    assert len(rec.curve3d_std) == len(rec.curve3d)


def test_section_4_gives_the_same_curve_after_other_trials():
    """Section 4 keeps per-frame blocks of its unary cost between calls (the branch search
    switches one frame at a time): a call after trials with other poses gives the same curve as
    the first call."""
    scene = make_scene(np.random.default_rng(3), 12, 1.0, 1.0, with_curve=True)
    rec = reconstruct_end_points(scene.observations, ReconstructOptions())
    curves, rot, tr = scene.observations.curves, rec.rotations(), rec.translations()
    # polylines no other test uses: nothing of them is kept from before
    curves = [c + 1e-7 for c in curves]
    first = section4.reconstruct_curve(curves, rot, tr, n_samples=60, smooth=False)
    for i in (3, 7):
        other = rot.copy()
        other[i] = other[i] @ np.diag([1.0, -1.0, -1.0])  # another pose of frame i
        section4.reconstruct_curve(curves, other, tr, n_samples=60, smooth=False)
    again = section4.reconstruct_curve(curves, rot, tr, n_samples=60, smooth=False)
    np.testing.assert_array_equal(again.points, first.points)
    np.testing.assert_array_equal(again.frame_residual, first.frame_residual)

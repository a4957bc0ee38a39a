"""The curve bundle is never worse than the answer without polylines, and a polyline of
another curve is flagged, not averaged in.

Scenes: ``simulate.make_scene`` with curve families built in 3-D (``curve_families``), 1 px on
every image point and 1 degree on the tangents, end points and tangents given.  Shape error:
E = max over (c, alpha, beta, phi) of |error| / std, the std of the answer without polylines;
"no worse beyond noise" means E with polylines <= E without + 1 (one standard deviation of
the answer without polylines, the noise of the comparison itself).
"""

from __future__ import annotations

import numpy as np
import pytest
from bezier import bezier

from bench.curve_end_to_end import curve_error
from curverecon.model.observations import Observations
from curverecon.options import CurveOptions, ReconstructOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene

NO_BUNDLE = ReconstructOptions(curve=CurveOptions(bundle=False))


def _shape_error(rec, truth, std) -> float:
    return float(np.max(np.abs(rec.shape - truth.shape) / std))


@pytest.mark.parametrize(("family", "seed"), [("helix", 1), ("sharp-ends", 0), ("fourier", 2)])
def test_polylines_do_not_make_the_shape_worse(family, seed):
    scene = make_scene(
        np.random.default_rng(seed), 10, 1.0, 1.0, with_curve=True, curve_family=family
    )
    with_curves = reconstruct(scene.observations)
    without = reconstruct(scene.observations, options=NO_BUNDLE)
    e_with = _shape_error(with_curves, scene.truth, without.std)
    e_without = _shape_error(without, scene.truth, without.std)
    assert e_with <= e_without + 1.0, (e_with, e_without)


def test_a_polyline_of_another_curve_is_flagged_and_left_out():
    """Frame 3's polyline is the image of a different curve with the same ends (a tracking
    error): the bundle flags frame 3, leaves its polyline out and the shape stays as good as
    the answer without polylines; the curve follows the other frames."""
    rng = np.random.default_rng(7)
    scene = make_scene(np.random.default_rng(4), 12, 0.5, 0.5, with_curve=True)
    obs, t = scene.observations, scene.truth
    # another cubic curve from A to B (frame 0's camera coordinates), seen in frame 3
    a, b = scene.curve_3d[0], scene.curve_3d[-1]
    ctrl = np.array([a, a + rng.normal(scale=60.0, size=3), b + rng.normal(scale=60.0, size=3), b])
    other = bezier(ctrl, np.linspace(0.0, 1.0, 150)) - a
    r30 = t.rotations[3] @ t.rotations[0].T  # frame 0 camera -> frame 3 camera
    poly3 = (other @ r30.T)[:, :2] + t.A3[3, :2] + rng.normal(scale=0.5, size=(150, 2))
    curves = list(obs.curves)
    curves[3] = poly3
    bad = Observations(obs.a, obs.b, obs.tangent_a, obs.tangent_b, curves)
    rec = reconstruct(bad)
    assert 3 in rec.curve_bundle["flagged_frames"]
    assert any("contradicts" in w for w in rec.warnings)
    without = reconstruct(bad, options=NO_BUNDLE)
    assert _shape_error(rec, t, without.std) <= _shape_error(without, t, without.std) + 1.0
    assert curve_error(rec.curve3d, scene.curve_3d) < 0.01


def test_reported_std_covers_the_errors():
    """1 px, 12 frames: the shape's errors are within 3 of its std, and the curve3d points'
    distances from the true curve (densely sampled, same random stream) within 3 of their
    ``curve3d_std`` (honest uncertainty)."""
    seed, family = 2, "clothoid"
    scene = make_scene(
        np.random.default_rng(seed), 12, 1.0, 1.0, with_curve=True, curve_family=family
    )
    dense = make_scene(
        np.random.default_rng(seed),
        12,
        1.0,
        1.0,
        with_curve=True,
        curve_family=family,
        n_curve_points=4000,
    ).curve_3d
    rec = reconstruct(scene.observations)
    assert np.all(np.abs(rec.shape - scene.truth.shape) < 3.0 * rec.std)
    assert rec.curve3d_std is not None and len(rec.curve3d_std) == len(rec.curve3d)
    best = np.inf
    for q in (dense, dense * [1.0, 1.0, -1.0]):
        seg0, seg = q[:-1], np.diff(q, axis=0)
        d = []
        for p in rec.curve3d:
            t = np.clip(((p - seg0) * seg).sum(1) / (seg * seg).sum(1), 0.0, 1.0)
            d.append(np.linalg.norm(seg0 + t[:, None] * seg - p, axis=1).min())
        d = np.array(d)
        if d.mean() < best:
            best, z = d.mean(), d / rec.curve3d_std
    assert np.mean(z < 3.0) >= 0.95
    assert "curve3d_std" in rec.to_json_dict()


def test_gate_reference_is_the_best_of_the_answer_and_its_alternatives():
    """``gate.gate_reference_chi2``: the least chi2 among the answer and its equally good
    alternatives (non-finite ones ignored); the answer's own with the option off."""
    from curverecon.curve.bundle import gate_reference_chi2
    from curverecon.model.reconstruction import Alternative

    alts = [
        Alternative(np.ones(4), np.zeros((5, 5)), 3.5),
        Alternative(np.ones(4), np.zeros((5, 5)), 2.0),
        Alternative(np.ones(4), np.zeros((5, 5)), float("nan")),
    ]
    assert gate_reference_chi2(2.7, alts) == 2.0
    assert gate_reference_chi2(2.7, alts[:1]) == 2.7
    assert gate_reference_chi2(2.7, []) == 2.7
    off = CurveOptions(never_worse_alternatives=False)
    assert gate_reference_chi2(2.7, alts, off) == 2.7


def test_the_gate_holds_where_the_end_points_have_alternatives():
    """Bench scene random 1205 (1 px, 12 frames): the end-point answer has equally good
    alternatives, nearby minima of a loosely fixed end-point fit (within 5 of its std).  The
    bundle's shape lies outside the end points' 99 % region about every one of them; skipping
    the gate there (the option off, the old rule) took it, beta 3.5 std of the end-point
    answer off where that answer was 1.24 off: worse beyond noise.  The gate from the best of
    the answer and its alternatives refuses it."""
    scene = make_scene(
        np.random.default_rng(1205), 12, 1.0, 1.0, with_curve=True, curve_family="random"
    )
    without = reconstruct(scene.observations, options=NO_BUNDLE)
    assert without.alternatives
    e_without = _shape_error(without, scene.truth, without.std)
    rec = reconstruct(scene.observations)
    assert not rec.curve_bundle["accepted"]
    assert rec.curve_bundle["end_point_dchi2"] > CurveOptions().never_worse_dchi2
    assert _shape_error(rec, scene.truth, without.std) <= e_without + 1.0
    # the answer kept: its std widened by the disagreement covers the errors
    assert np.all(np.abs(rec.shape - scene.truth.shape) < 3.0 * rec.std)
    old = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=CurveOptions(never_worse_alternatives=False)),
    )
    assert old.curve_bundle["accepted"]
    assert _shape_error(old, scene.truth, without.std) > e_without + 1.0


def test_never_worse_limit_is_the_99_percent_point_with_an_estimated_variance():
    """``gate.never_worse_limit``: with the variance factor estimated from ``dof`` degrees of
    freedom, (chi2 with 4 dof) / (s2 from a chi2 with ``dof``) stays below the limit with the
    probability of ``never_worse_dchi2`` under chi2_4 (99 %; checked by drawing both, seeded),
    and the limit falls to ``never_worse_dchi2`` itself as dof grows."""
    from curverecon.curve.bundle import never_worse_limit

    rng = np.random.default_rng(11)
    for dof in (8, 16):
        x = rng.chisquare(4, 400_000)
        s2 = rng.chisquare(dof, 400_000) / dof
        frac = float(np.mean(x / s2 <= never_worse_limit(dof)))
        assert abs(frac - 0.99) < 0.001, (dof, frac)
        assert np.mean(x / s2 <= CurveOptions().never_worse_dchi2) < 0.975
    assert never_worse_limit(8) > never_worse_limit(16) > CurveOptions().never_worse_dchi2
    assert never_worse_limit(10**6) == pytest.approx(CurveOptions().never_worse_dchi2, rel=1e-3)


def test_a_bundle_at_the_truths_minimum_refused_by_a_low_variance_factor_is_kept():
    """Bench scene helix 1105 (0.5 px, 0.5 degree, 12 frames): the bundle reaches the minimum
    the fit started at the true curve and poses reaches, but the end-point fit's variance
    factor from its 8 degrees of freedom is low, and against the known-variance limit alone
    (``never_worse_f_test`` off) the shape was refused and the curve fitted on the end-point
    poses came out 2.5 % of its length off.  Within the F limit and with the polylines
    rejecting those poses, the bundle's answer is kept: the curve within 0.1 % of the
    simulator's true curve, the angles within 1 degree."""
    scene = make_scene(
        np.random.default_rng(1105), 12, 0.5, 0.5, with_curve=True, curve_family="helix"
    )
    rec = reconstruct(scene.observations)
    info = rec.curve_bundle
    assert info["accepted"]
    assert CurveOptions().never_worse_dchi2 < info["end_point_dchi2"]
    assert any("polylines reject" in w for w in rec.warnings)
    assert curve_error(rec.curve3d, scene.curve_3d) < 0.001
    truth = scene.truth.shape
    assert np.degrees(np.abs(rec.shape[1:3] - truth[1:3])).max() < 1.0
    old = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=CurveOptions(never_worse_f_test=False)),
    )
    assert not old.curve_bundle["accepted"]
    assert curve_error(old.curve3d, scene.curve_3d) > 0.02

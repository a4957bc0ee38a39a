"""The curve bundle's std of the shape is honest.

One scene (``simulate.make_scene``: a random 3-D curve of the ``random`` family moved and
projected by the simulator, 12 frames, end points and tangents given) seen again under
independent noise draws: 1 px on every image point (A', B' and each polyline point), 1 degree
on the tangents.  Honest: the errors of (c, alpha, beta, phi) over the draws are centred on the
truth within a std (no bias the std does not show) and spread no more than the std says.
With the former heavy difference penalty (``CurveOptions.bundle_smooth_weight`` 2.0) this
scene's beta was biased by about 2 std and phi by 1.6 std (spread equal to the std).
And where the never-worse test refuses the bundle, the end-point answer's std is widened by
the disagreement (``CurveOptions.never_worse_dchi2``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from bench.noise_free_curves import distance_to
from curverecon.model.observations import Observations
from curverecon.options import CurveOptions, ReconstructOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene

DRAWS = 8


def _noisy(obs: Observations, rng: np.random.Generator) -> Observations:
    """The noise-free observations with 1 px on every point and 1 degree on the tangents."""

    def turned(t: np.ndarray) -> np.ndarray:
        ang = np.arctan2(t[:, 1], t[:, 0]) + rng.normal(scale=np.radians(1.0), size=len(t))
        return np.column_stack([np.cos(ang), np.sin(ang)])

    return Observations(
        obs.a + rng.normal(size=obs.a.shape),
        obs.b + rng.normal(size=obs.b.shape),
        turned(obs.tangent_a),
        turned(obs.tangent_b),
        [c + rng.normal(size=c.shape) for c in obs.curves],
    )


def test_bundle_shape_std_matches_the_spread_over_noise_draws():
    # the same geometry as the 1 px scene of this seed (the noise draws consume the same
    # random stream), without its noise: the draws below add their own
    scene = make_scene(
        np.random.default_rng(5502), 12, 0.0, 0.0, with_curve=True, curve_family="random"
    )
    truth = scene.truth.shape
    rng = np.random.default_rng(777)
    err, std = [], []
    for _ in range(DRAWS):
        rec = reconstruct(_noisy(scene.observations, rng))
        if not rec.curve_bundle.get("accepted", False):
            continue  # the end-point answer stayed: not the bundle's std
        err.append(rec.shape - truth)
        std.append(rec.std)
    assert len(err) >= DRAWS - 2
    err, std = np.array(err), np.median(std, axis=0)
    # bias in units of the reported std: the mean of n draws has a std of 1 / sqrt(n) ~ 0.38
    bias = np.abs(err.mean(axis=0)) / std
    assert np.all(bias < 1.0), bias
    # the spread over the draws against the reported std (its sample estimate varies ~25 %)
    spread = err.std(axis=0, ddof=1) / std
    assert np.all(spread < 1.6), spread
    assert np.all(np.abs(err) / std < 3.5), np.abs(err) / std


def test_refused_bundle_widens_the_end_point_std():
    """A scene (clothoid family, 1 px, 1 degree, 12 frames) whose bundle shape falls outside
    the end points' 99 % region: the end-point answer stays, its std scaled by
    sqrt(dchi2 / never_worse_dchi2); unscaled, its own errors were 3.7 and 3.3 std."""
    scene = make_scene(
        np.random.default_rng(5212), 12, 1.0, 1.0, with_curve=True, curve_family="clothoid"
    )
    birge = ReconstructOptions(curve=CurveOptions(refused_std_disagreement=False))
    rec = reconstruct(scene.observations, options=birge)
    off = reconstruct(
        scene.observations, options=ReconstructOptions(curve=CurveOptions(bundle=False))
    )
    info = rec.curve_bundle
    assert info["accepted"] is False
    dchi2 = info["end_point_dchi2"]
    assert dchi2 > CurveOptions().never_worse_dchi2
    np.testing.assert_allclose(rec.shape, off.shape)
    np.testing.assert_allclose(rec.std, off.std * np.sqrt(dchi2 / CurveOptions().never_worse_dchi2))
    z_off = np.abs(off.shape - scene.truth.shape) / off.std
    z = np.abs(rec.shape - scene.truth.shape) / rec.std
    assert z_off.max() > 3.0 and z.max() < 3.0, (z_off, z)
    # the default also adds the two answers' difference: the same shape, a std no smaller
    default = reconstruct(scene.observations)
    np.testing.assert_allclose(default.shape, off.shape)
    assert np.all(default.std >= rec.std * (1 - 1e-12))


# sharp-ends 6001 with the joint refits before the bundle (its end-point answer then 10-18
# degrees off) was the second scene here; since the pose search leaves the current pose's basin
# alone (pose_search.RESECT_SAME_DEG) its bundle is accepted on that path too
# (test_curve_search_speed).  Refused scenes found instead (sharp-ends, fourier, random, bezier,
# seeds 6000-6029): fourier 6027 has its Birge-scaled std cover already (2.7 std), so it serves
# the curve3d test below only
@pytest.mark.parametrize(("family", "seed"), [("helix", 6007)])
def test_refused_bundle_std_includes_the_answers_disagreement(family, seed):
    """A scene (1 px, 1 degree, 12 frames) whose end-point answer is itself off (by 2-3
    degrees) and whose bundle shape, nearer the truth, is refused just past the limit: the
    Birge scaling alone leaves errors of more than 3 std; with the two answers' difference in
    quadrature every parameter is within 3 std of the truth."""
    scene = make_scene(
        np.random.default_rng(seed), 12, 1.0, 1.0, with_curve=True, curve_family=family
    )
    truth = scene.truth.shape
    # the known-variance gate alone (never_worse_f_test off): helix 6007's dchi2 lies within
    # the F limit of its 8 degrees of freedom and the polylines reject the end-point poses, so
    # by default its bundle's (nearer) shape is kept (checked below); the refused path's std
    # is what this test measures
    base = CurveOptions(never_worse_f_test=False)
    birge = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=replace(base, refused_std_disagreement=False)),
    )
    rec = reconstruct(scene.observations, options=ReconstructOptions(curve=base))
    assert rec.curve_bundle["accepted"] is False
    accepted = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=replace(base, never_worse_dchi2=1e12)),
    )
    # the bundle's answer is the nearer one (independent: the simulator's truth)
    assert (
        np.abs(np.degrees(accepted.shape[1:] - truth[1:])).max()
        < np.abs(np.degrees(rec.shape[1:] - truth[1:])).max()
    )
    default = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=CurveOptions()),
    )
    if family == "helix":
        assert default.curve_bundle["accepted"]
        np.testing.assert_allclose(default.shape, accepted.shape)
    assert (np.abs(birge.shape - truth) / birge.std).max() > 3.0
    assert (np.abs(rec.shape - truth) / rec.std).max() < 3.0


def _distances(rec, seed: int, family: str, noise: float) -> np.ndarray:
    """Each ``curve3d`` point's distance from the true curve (sampled at 5,000 points by the
    simulator; the better of it and its mirror image, the depth sign)."""
    dense = make_scene(
        np.random.default_rng(seed),
        12,
        noise,
        noise,
        with_curve=True,
        curve_family=family,
        n_curve_points=5000,
    ).curve_3d
    return min(
        (distance_to(rec.curve3d, q) for q in (dense, dense * [1.0, 1.0, -1.0])),
        key=lambda d: float(d.mean()),
    )


def test_curve3d_normal_std_matches_the_distances_over_noise_draws():
    """``curve3d_normal_std`` (across the curve) against the distances of the ``curve3d``
    points from the true curve over noise draws of one geometry (Bezier, 12 frames, 1 px,
    1 degree): calibrated to within a factor two.  ``curve3d_std`` (the whole 3x3 covariance)
    is dominated by each point's slide along the curve, which moves no point of the curve:
    against it the same distances are a small fraction of a std."""
    scene = make_scene(
        np.random.default_rng(1201), 12, 0.0, 0.0, with_curve=True, curve_family="bezier"
    )
    rng = np.random.default_rng(99)
    zn, zt = [], []
    for _ in range(4):
        rec = reconstruct(_noisy(scene.observations, rng))
        assert np.all(rec.curve3d_normal_std <= rec.curve3d_std * (1 + 1e-12))
        d = _distances(rec, 1201, "bezier", 0.0)
        zn.append(d / rec.curve3d_normal_std)
        zt.append(d / rec.curve3d_std)
    zn, zt = np.concatenate(zn), np.concatenate(zt)
    assert 0.5 < np.sqrt(np.mean(zn**2)) < 2.0, np.sqrt(np.mean(zn**2))
    assert np.mean(zn < 3.0) > 0.95
    assert np.sqrt(np.mean(zt**2)) < 0.5, np.sqrt(np.mean(zt**2))


@pytest.mark.parametrize(
    ("family", "seed"), [("clothoid", 5212), ("helix", 6007), ("fourier", 6027)]
)
def test_refused_bundle_curve3d_std_includes_the_curves_disagreement(family, seed):
    """Where the bundle is refused, ``curve3d`` is fitted with the end-point answer's poses
    fixed and its std alone is the curve's given those poses; the refusal says they are off,
    so each point's std adds its distance from the bundle's curve: then the true curve is
    within 3 std across the curve of 97-100 % of the points, without that term of 10-84 %.
    (fourier 6027: its end-point answer 12 degrees off.)"""
    scene = make_scene(
        np.random.default_rng(seed), 12, 1.0, 1.0, with_curve=True, curve_family=family
    )
    # the known-variance gate alone: helix 6007 falls in the band of
    # CurveOptions.never_worse_f_test, where the polylines keep its bundle (fourier 6027 is
    # refused either way: dchi2 30.5)
    base = CurveOptions(never_worse_f_test=False)
    rec = reconstruct(scene.observations, options=ReconstructOptions(curve=base))
    assert rec.curve_bundle["accepted"] is False
    plain = reconstruct(
        scene.observations,
        options=ReconstructOptions(curve=replace(base, refused_std_disagreement=False)),
    )
    d = _distances(rec, seed, family, 1.0)
    np.testing.assert_allclose(rec.curve3d, plain.curve3d)
    assert np.mean(d < 3.0 * rec.curve3d_normal_std) >= 0.95
    assert np.mean(d < 3.0 * plain.curve3d_normal_std) < 0.9

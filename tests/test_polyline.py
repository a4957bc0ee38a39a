"""Tests of curverecon.curve.polyline: end tangents on noisy polylines, validation, helpers.

The angle-error study (error vs fit length, several noise levels and point densities) that chose
the default fit length is ``python tests/test_polyline.py`` (prints a table; not run by pytest).
"""

from __future__ import annotations

import numpy as np
import pytest
from bezier import bezier as _bezier

from curverecon.curve import polyline as pl
from curverecon.errors import CurveReconError


def _random_polylines(seed: int, n: int, sigma: float, density: float = 1.0):
    """Yield (noisy polyline, true unit tangent at A, at B, curve length) for random 2-D Beziers.

    Curves a few hundred pixels across, ``density`` points per pixel of arc length, uniform in the
    Bezier parameter; Gaussian noise ``sigma`` px on each coordinate. Curves whose end derivative
    is tiny (a near-cusp end, tangent ill-defined) are skipped.
    """
    rng = np.random.default_rng(seed)
    made = 0
    while made < n:
        ctrl = rng.uniform(-150, 150, (4, 2))
        ta, tb = 3 * (ctrl[1] - ctrl[0]), 3 * (ctrl[2] - ctrl[3])
        if np.hypot(*ta) < 60 or np.hypot(*tb) < 60:
            continue
        fine = _bezier(ctrl, np.linspace(0, 1, 4000))
        length = float(np.hypot(*np.diff(fine, axis=0).T).sum())
        m = max(int(length * density), 8)
        pts = _bezier(ctrl, np.linspace(0, 1, m))
        pts = pts + rng.normal(0, sigma, pts.shape)
        made += 1
        yield pts, ta / np.hypot(*ta), tb / np.hypot(*tb), length


def _angle_deg(u: np.ndarray, v: np.ndarray) -> float:
    return float(np.degrees(np.arccos(np.clip(u @ v / np.hypot(*u) / np.hypot(*v), -1, 1))))


def _errors(seed: int, n: int, sigma: float, fit_fraction: float | None = None) -> np.ndarray:
    errs = []
    for pts, ta, tb, length in _random_polylines(seed, n, sigma):
        fit = None if fit_fraction is None else fit_fraction * length
        ea, eb = pl.end_tangents(pts, fit_length=fit)
        errs += [_angle_deg(ea, ta), _angle_deg(eb, tb)]
    return np.asarray(errs)


def test_end_tangents_noise_free_exact_on_a_line_and_parabola():
    x = np.linspace(0, 100, 50)
    ta, tb = pl.end_tangents(np.column_stack([x, 0.5 * x + 3]))
    np.testing.assert_allclose(ta, np.array([2, 1]) / np.sqrt(5), atol=1e-9)
    np.testing.assert_allclose(tb, -np.array([2, 1]) / np.sqrt(5), atol=1e-9)
    # A parabola y = x^2 / 200 is reproduced exactly by the quadratic fit in the chord parameter
    # only approximately (x(s) is not polynomial); the slope at x = 0 is 0, at x = 100 it is 1.
    ta, tb = pl.end_tangents(np.column_stack([x, x**2 / 200]))
    assert _angle_deg(ta, np.array([1.0, 0.0])) < 0.1
    assert _angle_deg(tb, -np.array([1.0, 1.0])) < 0.1


def test_end_tangents_direction_points_into_curve():
    pts = np.column_stack([np.linspace(0, 10, 20), np.zeros(20)])
    ta, tb = pl.end_tangents(pts)
    assert ta[0] > 0.99 and tb[0] < -0.99


def test_end_tangents_accuracy_noise_free():
    errs = _errors(seed=1, n=60, sigma=0.0)
    # Measured (seed 1, 60 curves): median 0.1 deg.
    assert np.median(errs) < 0.3


def test_end_tangents_accuracy_half_pixel_noise():
    errs = _errors(seed=2, n=80, sigma=0.5)
    # Measured (seed 2, 80 curves, ~1 point per pixel): median ~1.2 deg, 90th percentile ~4 deg.
    assert np.median(errs) < 2.0
    assert np.percentile(errs, 90) < 7.0


def test_end_tangents_default_beats_a_too_short_fit_under_noise():
    # With 0.5 px noise, a 3 % stretch is noise-dominated (median ~10 deg measured).
    short = _errors(seed=3, n=40, sigma=0.5, fit_fraction=0.03)
    default = _errors(seed=3, n=40, sigma=0.5)
    assert np.median(default) < 0.5 * np.median(short)


def test_explicit_fit_length_is_used():
    # On a circle, a longer fit is biased towards the chord direction: angles must differ.
    t = np.linspace(0, np.pi, 400)
    pts = 100 * np.column_stack([np.cos(t), np.sin(t)])
    ta_short, _ = pl.end_tangents(pts, fit_length=5.0, degree=1)
    ta_long, _ = pl.end_tangents(pts, fit_length=150.0, degree=1)
    assert _angle_deg(ta_short, np.array([0.0, 1.0])) < 2.0
    assert _angle_deg(ta_long, np.array([0.0, 1.0])) > 10.0


@pytest.mark.parametrize(
    "points, message",
    [
        (np.zeros((4, 2)) + np.arange(4)[:, None], "at least 5"),
        (np.column_stack([np.arange(10.0), np.full(10, np.nan)]), "NaN"),
        (np.ones((10, 2)), "at least 5"),
        (np.arange(10.0), "shape"),
        (np.zeros((10, 3)), "shape"),
        ([[0, 0], [1, 1], [1, 1], [1, 1], [1, 1], [1, 1], [2, 2]], "at least 5"),
        ("abc", "points"),
    ],
)
def test_end_tangents_bad_input(points, message):
    with pytest.raises(CurveReconError, match=message):
        pl.end_tangents(points)


def test_end_tangents_bad_fit_length():
    pts = np.column_stack([np.arange(10.0), np.arange(10.0) ** 2])
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(CurveReconError, match="fit_length"):
            pl.end_tangents(pts, fit_length=bad)


def test_noise_level_estimate():
    rng = np.random.default_rng(5)
    for pts, *_ in _random_polylines(5, 5, 0.0):
        for sigma in (0.25, 1.0):
            est = pl.noise_level(pts + rng.normal(0, sigma, pts.shape))
            assert abs(est - sigma) < 0.25 * sigma
        assert pl.noise_level(pts) < 0.05


def test_crossing_helpers_agree():
    t = np.linspace(0, 2 * np.pi, 500)
    circle = 50 * np.column_stack([np.cos(t), np.sin(t)])
    u, arc, sn = pl.segment_line_crossings(circle, np.array([0.0, 0.0]), np.array([1.0, 1.0]))
    assert len(u) == 2
    np.testing.assert_allclose(np.sort(np.abs(u)) * np.sqrt(2), [50, 50], atol=0.05)
    np.testing.assert_allclose(sn, 1.0, atol=0.01)
    np.testing.assert_allclose(np.sort(arc), [50 * np.pi / 4, 50 * 5 * np.pi / 4], rtol=1e-3)
    origins = np.array([[0.0, 0.0], [0.0, 30.0], [0.0, 80.0]])
    kk, u2, _ = pl.parallel_line_crossings(circle, origins, np.array([1.0, 0.0]))
    assert list(np.bincount(kk, minlength=3)) == [2, 2, 0]
    d, a = pl.distance_to_polyline(np.array([[0.0, 0.0], [100.0, 0.0]]), circle)
    np.testing.assert_allclose(d, [50, 50], atol=0.01)
    np.testing.assert_allclose(a[1], 0.0, atol=0.01)


def _study() -> None:  # pragma: no cover - documentation of the fit-length choice
    fracs = [0.03, 0.05, 0.08, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4]
    print("median / 90th percentile angle error (deg) vs fit length (fraction of curve length)")
    for sigma in (0.0, 0.25, 0.5, 1.0):
        row = []
        for f in [*fracs, None]:
            e = _errors(seed=11, n=150, sigma=sigma, fit_fraction=f)
            row.append(
                f"{'auto' if f is None else f}: {np.median(e):.2f}/{np.percentile(e, 90):.1f}"
            )
        print(f"sigma {sigma} px | " + "  ".join(row))


if __name__ == "__main__":  # pragma: no cover
    _study()


def test_end_tangent_at_a_sharply_curved_end():
    """A tight end (20 px radius quarter circle, then 300 px straight): the adaptive fit length
    must stay on the arc where a fixed 12 % stretch reaches into the straight part (measured:
    0.1 deg against 11 deg)."""
    t = np.linspace(0.0, np.pi / 2, 40)
    arc = 20.0 * np.column_stack([np.sin(t), 1.0 - np.cos(t)])  # leaves A along +x
    line = arc[-1] + np.column_stack([np.zeros(300), np.linspace(1.0, 300.0, 300)])
    pts = np.vstack([arc, line])
    length = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    fixed, _ = pl.end_tangents(pts, fit_length=0.12 * length)
    adaptive, _ = pl.end_tangents(pts)
    assert _angle_deg(fixed, np.array([1.0, 0.0])) > 5.0
    assert _angle_deg(adaptive, np.array([1.0, 0.0])) < 0.5

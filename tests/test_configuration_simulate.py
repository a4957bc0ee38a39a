"""Scenes of the Section 2 table's rows (``simulate_configuration``): the document is the truth
projected, the body is rigid, and the motion is the model's, each checked by its own geometry."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from curverecon.errors import CurveReconError
from curverecon.simulate import CONFIG_MOTIONS, simulate_configuration

ROWS = [(m, p) for m in CONFIG_MOTIONS for p in ("AB", "ABC") if (m, p) != ("free", "AB")]


def _truth_points(truth: dict) -> np.ndarray:
    names = truth["configuration"]["points"]
    return np.array([[f["points3"][k] for k in names] for f in truth["frames"]])


@pytest.mark.parametrize("motion, points", ROWS)
def test_document_is_the_rigid_body_projected(motion, points):
    doc, truth = simulate_configuration(motion, points, frames=12, seed=5, with_curve=True)
    p3 = _truth_points(truth)
    names = truth["configuration"]["points"]
    assert doc["motion"] == motion and names == list(points)
    for f, frame in enumerate(doc["frames"]):
        assert frame["t"] == truth["times"][f] == float(f)
        img = [frame["A"], frame["B"], *(frame["points"][k] for k in names[2:])]
        np.testing.assert_allclose(img, p3[f, :, :2], atol=1e-12)
        np.testing.assert_allclose(frame["curve"][0], frame["A"], atol=1e-5)
        np.testing.assert_allclose(frame["curve"][-1], frame["B"], atol=1e-5)
        assert "tangent_A" not in frame
    assert np.all(p3[:, 0, 2] == 0.0)  # A at depth 0
    body = np.array([truth["body"]["points"][k] for k in names])
    for f, frame in enumerate(truth["frames"]):  # X_f - A_f = R_f (X_0 - A_0), R_f a rotation
        r = np.array(frame["rotation"])
        np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
        np.testing.assert_allclose(p3[f] - p3[f, 0], body @ r.T, atol=1e-9)
    assert abs(np.linalg.norm(body[1]) - truth["c"]) < 1e-9 * truth["c"]
    if len(names) == 3:  # C is a marked point of the curve, away from the line AB
        curve = np.array(truth["curve3d"]) - p3[0, 0]
        assert np.min(np.linalg.norm(curve - body[2], axis=1)) < 0.02 * truth["c"]
        e = body[1] / np.linalg.norm(body[1])
        assert np.linalg.norm(body[2] - (body[2] @ e) * e) > 0.1 * truth["c"]


@pytest.mark.parametrize("motion", ["fixed-axis", "uniform-rotation"])
def test_axis_motions_turn_about_one_tilted_axis(motion):
    _, truth = simulate_configuration(motion, "AB", frames=9, seed=2, times=np.arange(9) * 0.5)
    mp = truth["motion_parameters"]
    n = np.array(mp["axis"])
    assert abs(np.linalg.norm(n) - 1) < 1e-12 and abs(n[2]) < np.cos(np.radians(30))
    for frame, angle in zip(truth["frames"], mp["angle_deg"], strict=True):
        want = Rotation.from_rotvec(n * np.radians(angle)).as_matrix()
        np.testing.assert_allclose(frame["rotation"], want, atol=1e-12)
    angles = np.array(mp["angle_deg"])
    assert angles[0] == 0 and np.all(np.diff(angles) > 0) and angles[-1] >= 179.0
    if motion == "uniform-rotation":
        np.testing.assert_allclose(angles, mp["rate_deg"] * np.array(truth["times"]), atol=1e-9)


def test_force_field_mass_centre_on_a_parabola():
    times = np.sort(np.random.default_rng(0).uniform(0, 3, 15)) + 1.0
    _, truth = simulate_configuration("force-field", "AB", frames=15, seed=4, times=times)
    mp = truth["motion_parameters"]
    p3 = _truth_points(truth)
    g = p3[:, 0] + np.array([np.array(f["rotation"]) @ mp["mass_centre"] for f in truth["frames"]])
    g0, g1, g2 = (np.array(mp[k]) for k in ("position", "velocity", "acceleration"))
    want = g0 + np.outer(times, g1) + np.outer(times**2, g2) / 2
    np.testing.assert_allclose(g[:, :2], want, atol=1e-9)
    assert np.linalg.norm(g2) * (times[-1] - times[0]) ** 2 / 2 > 100  # visibly parabolic
    # the mass centre is the wire's centroid: the mean of the curve's points (evenly spaced in
    # arc length after resampling) in frame 0
    curve = np.array(truth["curve3d"]) - p3[0, 0]
    seg = np.linalg.norm(np.diff(curve, axis=0), axis=1)
    mid = (curve[1:] + curve[:-1]) / 2
    np.testing.assert_allclose(seg @ mid / seg.sum(), mp["mass_centre"], atol=0.01 * truth["c"])


def test_noise_tangents_outliers_and_seed():
    doc, truth = simulate_configuration(
        "fixed-axis", "ABC", frames=20, seed=9, noise_px=1.0, tangent_noise_deg=2.0,
        outlier_fraction=0.2,
    )  # fmt: skip
    again, _ = simulate_configuration(
        "fixed-axis", "ABC", frames=20, seed=9, noise_px=1.0, tangent_noise_deg=2.0,
        outlier_fraction=0.2,
    )  # fmt: skip
    assert doc == again
    out = truth["outlier_frames"]
    assert len(out) == 4
    p3 = _truth_points(truth)
    img = np.array([[f["A"], f["B"], f["points"]["C"]] for f in doc["frames"]])
    err = np.linalg.norm(img - p3[..., :2], axis=2)
    inl = np.setdiff1d(np.arange(20), out)
    assert 0.5 < np.sqrt(np.mean(err[inl] ** 2) / 2) < 1.5
    assert np.all(err[out].max(axis=1) > 5.0)
    ta3 = np.array([f["tangent_A3"] for f in truth["frames"]])[inl]
    ta = np.array([doc["frames"][i]["tangent_A"] for i in inl])
    diff = np.degrees(np.arctan2(ta[:, 1], ta[:, 0]) - np.arctan2(ta3[:, 1], ta3[:, 0]))
    assert np.max(np.abs((diff + 90) % 180 - 90)) < 10.0


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"motion": "spin"}, 'unknown motion "spin"'),
        ({"motion": "free", "points": "AB"}, "free motion with only A and B"),
        ({"motion": "fixed-axis", "points": "BA"}, 'must be "AB" followed'),
        ({"motion": "fixed-axis", "frames": 1}, "at least 2 frames"),
        ({"motion": "fixed-axis", "times": [0.0, 2.0, 1.0]}, "increasing"),
    ],
)
def test_bad_arguments(kwargs, message):
    with pytest.raises(CurveReconError, match=message):
        simulate_configuration(**kwargs)


@pytest.mark.parametrize("family", ["helix", "clothoid", "fourier", "sharp-ends", "random"])
def test_every_curve_family_gives_a_rigid_scene_with_c_on_the_curve(family):
    doc, truth = simulate_configuration("fixed-axis", "ABC", frames=5, seed=7, family=family)
    p3 = _truth_points(truth)
    body = np.array([truth["body"]["points"][k] for k in "ABC"])
    for f, frame in enumerate(truth["frames"]):
        np.testing.assert_allclose(
            p3[f] - p3[f, 0], body @ np.array(frame["rotation"]).T, atol=1e-9
        )
    curve = np.array(truth["curve3d"]) - p3[0, 0]
    assert np.min(np.linalg.norm(curve - body[2], axis=1)) < 0.02 * truth["c"]
    assert truth["family"] == family and 100 <= truth["c"] <= 300

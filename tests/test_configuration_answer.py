"""Every configuration's answer is assembled in one place (``rigid.answer.configuration_answer``):
the orthographic rows, the perspective and stereo rows and the ordinary camera's curve bundle
write the same keys and carry the fit's warnings.

Scenes from the simulators' 3-D constructions (``simulate_configuration``,
``simulate_camera_configuration``), 1 px point noise.  The ordinary camera's answer is its
bundle's (``curve.pinhole``) started at the simulated curve and poses: its search is
``tests/test_persp_curve.py``'s and costs a minute a scene."""

from __future__ import annotations

import math

import numpy as np
import pytest

from curverecon.curve import pinhole
from curverecon.io import observations_from_dict, read_json, write_json
from curverecon.options import ReconstructOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import simulate_camera_configuration, simulate_configuration

NOISE_PX = 1.0
CONTRACT_KEYS = {"c", "alpha_deg", "beta_deg", "phi_deg", "frames", "configuration"}
CONTRACT_KEYS |= {"motion_parameters", "format"}
CONTRACT_FRAME_KEYS = {"delta_deg", "tau_deg", "A3", "B3", "tangent_A3", "tangent_B3", "points3"}
CURVE_KEYS = {"curve3d", "curve3d_std", "curve3d_normal_std", "curve_bundle"}
DEPTH_FRAME_KEYS = {"R", "T"}
"""Written where the camera places the answer in depth (perspective, stereo)."""

SCENES = {
    "orthographic uniform rotation": lambda: simulate_configuration(
        "uniform-rotation", "AB", 10, 0, NOISE_PX
    ),
    # A, B and C: with A and B alone a frame has one degree of freedom, and the outlier test
    # leaves out enough of the frames of understated noise that the rest's chi2 is not improbable
    "perspective uniform rotation": lambda: simulate_camera_configuration(
        "perspective", "uniform-rotation", "ABC", 12, 0, NOISE_PX
    ),
    "stereo": lambda: simulate_camera_configuration("stereo", "free", "AB", 6, 0, NOISE_PX),
}


def _ordinary_camera(sigma: float):
    """The ordinary camera (perspective, free motion, A, B and polylines, five frames): its
    pinhole bundle from the simulated curve and poses, assembled as the route assembles it."""
    doc, truth = simulate_camera_configuration(
        "perspective", "free", "AB", 5, 1, NOISE_PX, with_curve=True
    )
    obs = observations_from_dict(doc)
    data = pinhole._prepare(
        obs.configuration.camera, obs.curves, obs.point("A"), obs.point("B"), sigma, 1.0
    )
    poses = np.array(
        [np.column_stack([f["frame_pose"]["R"], f["frame_pose"]["T"]]) for f in truth["frames"]]
    )
    ctrl = pinhole.fit_spline(np.asarray(truth["curve3d"], float), pinhole.CONTROL_POINTS)
    fit = pinhole.bundle(
        data, ctrl, poses[:, :, :3].copy(), poses[:, :, 3].copy(), pinhole._free(len(poses))
    )
    return pinhole._answer(obs, fit, math.inf, data), truth


def _answers(sigma: float) -> dict:
    out = {}
    for name, scene in SCENES.items():
        doc, truth = scene()
        rec = reconstruct(
            observations_from_dict(doc), options=ReconstructOptions(point_sigma=sigma)
        )
        out[name] = (rec, truth)
    out["ordinary camera"] = _ordinary_camera(sigma)
    return out


@pytest.fixture(scope="module")
def right_noise() -> dict:
    return _answers(NOISE_PX)


@pytest.fixture(scope="module")
def noise_understated() -> dict:
    return _answers(NOISE_PX / 3.0)


def test_every_route_writes_the_same_keys(right_noise, tmp_path):
    written = {}
    for name, (rec, _) in right_noise.items():
        write_json(tmp_path / "answer.json", rec.to_json_dict())
        written[name] = read_json(tmp_path / "answer.json")
    common = set.intersection(*(set(doc) for doc in written.values()))
    assert CONTRACT_KEYS <= common
    for name, doc in written.items():
        assert set(doc) - common == (CURVE_KEYS if name == "ordinary camera" else set()), name
        assert set(doc["frames"][0]["points3"]) == set(doc["configuration"]["points"]), name
        assert ("rate_deg" in doc["motion_parameters"]) == ("uniform rotation" in name), name
        frame_keys = {frozenset(frame) for frame in doc["frames"]}
        assert len(frame_keys) == 1, name
        depth = DEPTH_FRAME_KEYS if doc["configuration"]["projection"] != "orthographic" else set()
        (keys,) = frame_keys
        assert CONTRACT_FRAME_KEYS | depth <= keys, name
        assert set(keys) & DEPTH_FRAME_KEYS == depth, name
    frames = [set(doc["frames"][0]) - DEPTH_FRAME_KEYS for doc in written.values()]
    assert all(keys == frames[0] for keys in frames)


def test_every_route_finds_the_simulated_body(right_noise):
    """The answers against the 3-D construction: c within four of its std; every frame's
    points3 a rigid body of that c (the answer's units in both)."""
    for name, (rec, truth) in right_noise.items():
        c_true = float(truth["c"])
        assert abs(rec.c - c_true) < 4.0 * rec.std[0], (name, rec.c, c_true, rec.std[0])
        chords = [np.linalg.norm(np.subtract(p["B"], p["A"])) for p in rec.points3]
        assert np.allclose(chords, rec.c, rtol=1e-9), name


def _fit_warnings(rec) -> list[str]:
    """The warnings that say the images disagree with the stated noise (``rigid.answer``)."""
    return [
        w
        for w in rec.warnings
        if (w.startswith("chi2 ") and "degrees of freedom" in w) or "were left out" in w
    ]


def test_stated_noise_three_times_too_small_warns_on_every_route(right_noise, noise_understated):
    for name, (rec, _) in right_noise.items():
        assert _fit_warnings(rec) == [], name
    for name, (rec, _) in noise_understated.items():
        (line,) = _fit_warnings(rec)
        assert "noise" in line and "\n" not in line, name
        if line.startswith("chi2 "):  # the chi2's ratio: the noise about 3 times the stated
            ratio = float(line.split(" by ")[1].split(" times")[0])
            assert 1.5 < ratio < 4.5, (name, line)


def test_a_pose_branch_chosen_by_the_curve_keeps_the_rest_of_the_answer():
    """The paper's row: a frame switched to its other pose branch by the curve
    (``curve.branches``) changes that frame's pose and chi2 and nothing else of the answer (its
    estimator, labels and configuration stay).  The curve's residuals here are a stand-in that
    prefers frame 2's other branch."""
    from types import SimpleNamespace

    from curverecon.curve.branches import resolve_branches_with_curves
    from curverecon.model.pose import rotations
    from curverecon.model.reconstruction import Reconstruction
    from curverecon.options import CurveOptions

    rng = np.random.default_rng(7)
    poses = rng.uniform(-1.0, 1.0, (5, 5))
    other = poses.copy()
    other[2, :2] = [0.3, -poses[2, 1]]
    rec = Reconstruction(
        shape=np.array([100.0, 0.4, 0.5, 0.6]),
        poses=poses,
        std=np.full(4, 0.01),
        inliers=np.ones(5, bool),
        chi2=5.0,
        frame_chi2=np.ones(5),
        branch_alternatives=other,
        branch_alternative_chi2=np.full(5, 2.0),
        estimator="marginal",
        ends_exchanged=np.zeros(5, bool),
    )

    def curve_residuals(curves, rot, tra):
        wrong = not np.allclose(rot[2], rotations(other)[2])
        return SimpleNamespace(frame_residual=np.array([1.0, 1.0, 9.0 if wrong else 1.0, 1, 1]))

    new, _ = resolve_branches_with_curves(rec, [None] * 5, curve_residuals, CurveOptions())
    kept = [0, 1, 3, 4]
    assert np.array_equal(new.poses[2], other[2]) and np.array_equal(new.poses[kept], poses[kept])
    assert new.frame_chi2[2] == 2.0 and new.chi2 == 6.0
    assert new.estimator == "marginal" and new.ends_exchanged is rec.ends_exchanged
    assert new.shape is rec.shape and new.std is rec.std

"""A stereo frame's placement of a known curve (curverecon.curve.stereo_place), and the stereo
answer's poses, against independent 3-D constructions.

The placement: a curve moved by a known rigid motion is projected here by the pinhole formula
(u = f x / z + cx) into both cameras of a verged pair; the placement from a disturbed start
recovers the motion.  The answer: the simulator's own 3-D scene (a short curve that frame 0
sees nearly along its epipolar lines) is recovered within 1 % of its length, and the poses the
answer writes are the ones its curve was fused with.
"""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.curve.stereo import match_stereo_curve
from curverecon.curve.stereo_place import place_shape
from curverecon.curve_families import draw_curve
from curverecon.solvers.camera import Camera, StereoRig

FOCAL, PP = 800.0, np.array([320.0, 240.0])


def _rig() -> StereoRig:
    """Camera 1 0.25 to the right of camera 0, turned 6 degrees towards it (X1 = R X0 + t)."""
    a = np.radians(-6.0)
    rot = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    return StereoRig(Camera(FOCAL, tuple(PP)), Camera(FOCAL, tuple(PP)), rot, -rot @ [0.25, 0, 0])


def _project(x: np.ndarray) -> np.ndarray:
    return FOCAL * x[:, :2] / x[:, 2:] + PP


def _turn(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' formula written out."""
    axis = axis / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def _shape_and_views(rng, sigma: float):
    """(shape (150, 3) about the origin, true pose (3, 4), camera 0's and 1's polylines)."""
    curve = draw_curve(rng, "random", (0.3, 0.5))
    shape = curve.points(np.linspace(0.0, 1.0, 150))
    shape = shape - shape.mean(axis=0)
    rot = _turn(rng.normal(size=3), rng.uniform(0.0, np.pi))
    shift = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 2.0])
    x0 = shape @ rot.T + shift
    rig = _rig()
    x1 = x0 @ np.asarray(rig.R).T + rig.t
    views = tuple(_project(x) + rng.normal(scale=sigma, size=(len(x), 2)) for x in (x0, x1))
    return shape, np.column_stack([rot, shift]), views


def _disturbed(pose: np.ndarray, rng) -> np.ndarray:
    """The pose turned by 4 degrees about a random axis and shifted by 0.02."""
    turn = _turn(rng.normal(size=3), np.radians(4.0))
    return np.column_stack([turn @ pose[:, :3], pose[:, 3] + rng.normal(scale=0.02, size=3)])


def test_placement_recovers_the_motion_without_noise():
    rng = np.random.default_rng(31)
    for _ in range(3):
        shape, truth, views = _shape_and_views(rng, 0.0)
        pose, std = place_shape(_rig(), shape, _disturbed(truth, rng), views, 0.5)
        placed = shape @ pose[:, :3].T + pose[:, 3]
        assert np.abs(placed - (shape @ truth[:, :3].T + truth[:, 3])).max() <= 1e-6
        assert std.shape == (len(shape),) and np.all(std > 0)


def test_placement_std_covers_its_error():
    rng = np.random.default_rng(32)
    z = []
    for _ in range(30):
        shape, truth, views = _shape_and_views(rng, 0.5)
        pose, std = place_shape(_rig(), shape, _disturbed(truth, rng), views, 0.5)
        err = shape @ pose[:, :3].T + pose[:, 3] - (shape @ truth[:, :3].T + truth[:, 3])
        z.append(np.linalg.norm(err, axis=1) / std)
    z = np.concatenate(z)
    assert np.mean(z <= 3.0) >= 0.95
    assert 0.2 <= np.median(z) <= 2.0  # no blanket either


def _scene(seed: int, frames: int):
    from curverecon.io import observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.rigid import reconstruct_rigid
    from curverecon.simulate import simulate_camera_configuration

    doc, truth = simulate_camera_configuration(
        "stereo", "free", "AB", frames, seed, noise_px=0.5, with_curve=True
    )
    obs = observations_from_dict(doc)
    return obs, truth, reconstruct_rigid(obs, ReconstructOptions(point_sigma=0.5))


def _distance(x: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point from the polyline ``curve`` (point to segment)."""
    seg0, seg = curve[:-1], np.diff(curve, axis=0)
    len2 = (seg * seg).sum(1)
    u = np.clip(((x[:, None, :] - seg0) * seg).sum(2) / len2, 0.0, 1.0)
    return np.linalg.norm(x[:, None, :] - seg0 - u[..., None] * seg, axis=2).min(1)


@pytest.fixture(scope="module")
def badly_seen():
    """Bench seed 8 (20 frames, 0.5 px): a curve of length 159 that frame 0 sees nearly along
    its epipolar lines (before its placement by reprojection: 2.8 % off)."""
    return _scene(8, 20)


def test_short_curve_frame_0_sees_badly_within_1pct(badly_seen):
    obs, truth, rec = badly_seen
    rig, true_curve = obs.configuration.rig, np.asarray(truth["curve3d"])
    length = float(np.linalg.norm(np.diff(true_curve, axis=0), axis=1).sum())
    assert length < 200.0
    # the kind of scene: frame 0 triangulates its curve far worse than the others
    med = [
        np.median(match_stereo_curve(rig, a, b, 0.5)[1])
        for a, b in zip(obs.curves, obs.view1.curves, strict=True)
    ]
    assert med[0] > 20.0 * np.median(med[1:])
    d = _distance(rec.curve3d, true_curve)
    back = _distance(true_curve, rec.curve3d)
    assert 0.5 * (d.mean() + back.mean()) <= 0.01 * length
    assert np.mean(d <= 3.0 * rec.curve3d_normal_std) >= 0.95


def _paper_rotations(poses: np.ndarray) -> np.ndarray:
    """R_z(theta) R_y(tau) R_x(delta) of the paper's (delta, tau, theta), written out."""
    out = []
    for d, t, h in poses[:, :3]:
        rx = np.array([[1, 0, 0], [0, np.cos(d), -np.sin(d)], [0, np.sin(d), np.cos(d)]])
        ry = np.array([[np.cos(t), 0, np.sin(t)], [0, 1, 0], [-np.sin(t), 0, np.cos(t)]])
        rz = np.array([[np.cos(h), -np.sin(h), 0], [np.sin(h), np.cos(h), 0], [0, 0, 1]])
        out.append(rz @ ry @ rx)
    return np.array(out)


def test_answer_poses_are_the_curves(badly_seen):
    """The paper's poses written are the frame poses the curve was fused with: the curve frame
    (A at the origin, B on +x, the viewing axis of frame 0 in the xz plane) turned by them, A
    at their positions; A under those poses agrees with each frame's triangulated A."""
    obs, truth, rec = badly_seen
    a0, b0 = (np.asarray(rec.points3[0][k]) for k in ("A", "B"))
    e1 = (b0 - a0) / np.linalg.norm(b0 - a0)
    e2 = np.array([0.0, 0.0, 1.0]) - e1[2] * e1
    e2 /= np.linalg.norm(e2)
    frame = np.column_stack([e1, e2, np.cross(e1, e2)])
    poses = np.asarray(rec.poses)
    written = _paper_rotations(poses)
    rig, true_rot = obs.configuration.rig, []
    for f, pose in enumerate(rec.frame_poses):
        np.testing.assert_allclose(written[f], pose[:, :3] @ frame, atol=1e-9)
        a_f = pose[:, :3] @ a0 + pose[:, 3]
        np.testing.assert_allclose(poses[f, 3:5], a_f[:2], atol=1e-9)
        x, std = match_stereo_curve(rig, obs.curves[f], obs.view1.curves[f], 0.5)
        assert np.linalg.norm(a_f - x[0]) <= 3.0 * np.hypot(std[0], std[0])
        true_rot.append(np.asarray(truth["frames"][f]["frame_pose"]["R"]))
    # and the turns about AB are the true ones (the fit's own leave them free)
    cos = [
        (np.trace(p[:, :3] @ r.T) - 1) / 2 for p, r in zip(rec.frame_poses, true_rot, strict=True)
    ]
    assert np.degrees(np.arccos(np.clip(cos, -1, 1))).max() <= 3.0


def test_placement_bad_input():
    from curverecon.errors import CurveReconError

    rng = np.random.default_rng(33)
    shape, truth, views = _shape_and_views(rng, 0.5)
    with pytest.raises(CurveReconError, match="M >= 3"):
        place_shape(_rig(), shape[:2], truth, views, 0.5)
    with pytest.raises(CurveReconError, match=r"\(3, 4\)"):
        place_shape(_rig(), shape, truth[:, :3], views, 0.5)
    with pytest.raises(CurveReconError, match="two polylines"):
        place_shape(_rig(), shape, truth, views[:1], 0.5)
    with pytest.raises(CurveReconError, match="point_sigma"):
        place_shape(_rig(), shape, truth, views, 0.0)
    bad = views[0].copy()
    bad[4, 1] = np.nan
    with pytest.raises(CurveReconError, match="non-finite"):
        place_shape(_rig(), shape, truth, (bad, views[1]), 0.5)

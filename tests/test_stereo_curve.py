"""Stereo curve matching and triangulation (curverecon.curve.stereo) against a 3-D construction.

A curve from curverecon.curve_families is placed in front of a verged stereo pair and projected
here by the pinhole formula (u = f x / z + cx), independently of the library's camera code; the
matched, triangulated points are compared with the true curve (their distance from it, which is
what the std covers, and, noise-free, the very point each pixel of camera 0 shows).

``python tests/test_stereo_curve.py`` prints the figures of docs/accuracy.md ("Stereo curves").
"""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.curve.stereo import match_stereo_curve, stereo_curve3d
from curverecon.curve_families import bezier_curve, draw_curve
from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera, StereoRig

FOCAL, PP = 800.0, np.array([320.0, 240.0])
FAMILIES = ("helix", "clothoid", "fourier", "sharp-ends", "random")


def _rot_y(deg: float) -> np.ndarray:
    a = np.radians(deg)
    return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])


def _rig(verge_deg: float = -6.0, baseline: float = 0.25) -> StereoRig:
    """Camera 1 a baseline to the right of camera 0, turned towards it (X1 = R X0 + t)."""
    rot = _rot_y(verge_deg)
    centre1 = np.array([baseline, 0.0, 0.0])
    return StereoRig(Camera(FOCAL, tuple(PP)), Camera(FOCAL, tuple(PP)), rot, -rot @ centre1)


def _project(x: np.ndarray) -> np.ndarray:
    return FOCAL * x[:, :2] / x[:, 2:] + PP


def _rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _place(points_fn, rot, offset, n=150, dense=40001):
    """(polyline samples (n, 3), dense truth (dense, 3)) of a curve turned and moved."""
    s, sd = np.linspace(0.0, 1.0, n), np.linspace(0.0, 1.0, dense)
    pts, tru = points_fn(s) @ rot.T, points_fn(sd) @ rot.T
    mid = tru.mean(axis=0)
    return pts - mid + offset, tru - mid + offset


def _scene(rng: np.random.Generator, family: str):
    curve = draw_curve(rng, family, (0.3, 0.5))
    offset = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 2.0])
    return _place(curve.points, _rotation(rng), offset)


def _views(rig: StereoRig, pts: np.ndarray, rng, sigma: float):
    p0 = _project(pts) + rng.normal(scale=sigma, size=(len(pts), 2))
    p1 = _project(pts @ np.asarray(rig.R).T + rig.t) + rng.normal(scale=sigma, size=(len(pts), 2))
    return p0, p1


def _distance(x: np.ndarray, dense: np.ndarray) -> np.ndarray:
    """Distance of each point from the dense true polyline (segments)."""
    seg = np.diff(dense, axis=0)
    len2 = (seg * seg).sum(1)
    out = np.empty(len(x))
    for k, p in enumerate(x):
        u = np.clip(((p - dense[:-1]) * seg).sum(1) / len2, 0.0, 1.0)
        out[k] = np.sqrt(((dense[:-1] + u[:, None] * seg - p) ** 2).sum(1).min())
    return out


def _length(dense: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(dense, axis=0), axis=1).sum())


@pytest.mark.parametrize("family", FAMILIES)
def test_noise_free_points_are_the_curve_points(family):
    rng = np.random.default_rng(11)
    rig = _rig()
    for _ in range(2):
        pts, dense = _scene(rng, family)
        p0, p1 = _views(rig, pts, rng, 0.0)
        x, std = match_stereo_curve(rig, p0, p1, 0.5)
        length = _length(dense)
        assert x.shape == (len(pts), 3) and std.shape == (len(pts),)
        assert _distance(x, dense).max() <= 1e-6 * length
        # each pixel of camera 0 gives the very 3-D point it shows
        assert np.linalg.norm(x - pts, axis=1).max() <= 1e-6 * length
        assert np.all(std > 0)


def _coverage(sigma: float, draws: int, seed: int):
    """z = distance from the true curve / std over all points of ``draws`` scenes, and the
    RMS distance relative to each curve's length."""
    rng = np.random.default_rng(seed)
    rig = _rig()
    z, rel = [], []
    for k in range(draws):
        pts, dense = _scene(rng, FAMILIES[k % len(FAMILIES)])
        p0, p1 = _views(rig, pts, rng, sigma)
        x, std = match_stereo_curve(rig, p0, p1, sigma)
        d = _distance(x, dense)
        z.append(d / std)
        rel.append(np.sqrt(np.mean(d**2)) / _length(dense))
    return np.concatenate(z), np.array(rel)


def test_std_covers_the_distance_from_the_curve_at_half_a_pixel():
    z, _ = _coverage(0.5, draws=20, seed=3)
    assert np.mean(z <= 3.0) >= 0.98
    # and it is no blanket: a typical point's error is a fair part of its std
    assert 0.15 <= np.median(z) <= 1.5


def _arch(rig: StereoRig, sigma: float, rng):
    """An arch in front of a rig with a horizontal baseline: its top runs along the epipolar
    plane (tangent there horizontal, flat for a stretch), so the epipolar lines near the top
    touch the curve or cut it twice in both views."""
    ctrl = np.array([[0.0, 0.0, 0.0], [0.12, -0.2, 0.05], [0.28, -0.2, 0.05], [0.4, 0.0, 0.0]])
    pts, dense = _place(bezier_curve(ctrl).points, np.eye(3), np.array([0.0, 0.0, 1.5]), n=200)
    p0, p1 = _views(rig, pts, rng, sigma)
    return pts, dense, p0, p1


def _arc_on(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Arc position of each 2-D point's foot on a polyline."""
    seg = np.diff(polyline, axis=0)
    len2 = (seg * seg).sum(1)
    cum = np.concatenate([[0.0], np.cumsum(np.sqrt(len2))])
    out = np.empty(len(points))
    for k, p in enumerate(points):
        u = np.clip(((p - polyline[:-1]) * seg).sum(1) / len2, 0.0, 1.0)
        j = int(np.argmin(((polyline[:-1] + u[:, None] * seg - p) ** 2).sum(1)))
        out[k] = cum[j] + u[j] * np.sqrt(len2[j])
    return out


def test_epipolar_tangent_stretch():
    rig = _rig(verge_deg=0.0, baseline=0.2)
    rng = np.random.default_rng(5)
    pts, dense, p0, p1 = _arch(rig, 0.0, rng)
    x, std = match_stereo_curve(rig, p0, p1, 0.5)
    length = _length(dense)
    assert np.linalg.norm(x - pts, axis=1).max() <= 1e-6 * length
    # the matches keep the order along camera 1's curve
    back = _project(x @ np.asarray(rig.R).T + rig.t)
    assert np.all(np.diff(_arc_on(back, p1)) >= -1e-6)
    top = int(np.argmin(pts[:, 1]))
    assert std[top] > 5.0 * np.median(std)
    z = []
    for _ in range(10):
        pts, dense, p0, p1 = _arch(rig, 0.5, rng)
        x, std = match_stereo_curve(rig, p0, p1, 0.5)
        z.append(_distance(x, dense) / std)
    assert np.mean(np.concatenate(z) <= 3.0) >= 0.98


def _moving_frames(rng, rig, sigma, frames=6):
    """A curve turned and moved between frames; frame poses X_f = R_f X_0 + T_f."""
    pts, dense = _scene(rng, FAMILIES[int(rng.integers(len(FAMILIES)))])
    centre = dense.mean(axis=0)
    poses, views0, views1 = [], [], []
    for f in range(frames):
        rot = np.eye(3)
        if f:
            axis = rng.normal(size=3)
            axis /= np.linalg.norm(axis)
            k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
            a = np.radians(rng.uniform(5.0, 25.0))
            rot = np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k
        tr = centre - rot @ centre + (rng.normal(scale=0.05, size=3) if f else 0.0)
        poses.append(np.column_stack([rot, tr]))
        p0, p1 = _views(rig, pts @ rot.T + tr, rng, sigma)
        views0.append(p0)
        views1.append(p1)
    return pts, dense, np.array(poses), views0, views1


def test_frames_fused_on_their_poses():
    rig = _rig()
    rng = np.random.default_rng(8)
    pts, dense, poses, v0, v1 = _moving_frames(rng, rig, 0.0)
    curve, std = stereo_curve3d(rig, v0, v1, poses, 0.5, smooth=False)
    length = _length(dense)
    assert curve.shape == (len(pts), 3) and std.shape == (len(pts),)
    # linear resampling between points 1/150 of the curve apart: chord error only
    assert _distance(curve, dense).max() <= 1e-4 * length
    np.testing.assert_allclose(curve[[0, -1]], pts[[0, -1]], atol=1e-9 * length)
    # smoothed without noise: the least smoothing tried bends the curve only a little
    smoothed, _ = stereo_curve3d(rig, v0, v1, poses, 0.5)
    assert _distance(smoothed, dense).max() <= 5e-4 * length
    single, rms_fused, rms_single, z = [], [], [], []
    for _ in range(6):
        pts, dense, poses, v0, v1 = _moving_frames(rng, rig, 0.5)
        curve, std = stereo_curve3d(rig, v0, v1, poses, 0.5)
        x0, std0 = match_stereo_curve(rig, v0[0], v1[0], 0.5)
        d, d0 = _distance(curve, dense), _distance(x0, dense)
        rms_fused.append(np.sqrt(np.mean(d**2)))
        rms_single.append(np.sqrt(np.mean(d0**2)))
        single.append(np.median(std) / np.median(std0))
        z.append(d / std)
    assert np.mean(rms_fused) < 0.75 * np.mean(rms_single)
    assert np.median(single) < 0.6  # six frames: about 1 / sqrt(6) of one frame's std
    assert np.mean(np.concatenate(z) <= 3.0) >= 0.95


def test_one_frame_is_its_own_match():
    rig = _rig()
    rng = np.random.default_rng(2)
    pts, _ = _scene(rng, "helix")
    p0, p1 = _views(rig, pts, rng, 0.3)
    pose = np.hstack([np.eye(3), np.zeros((3, 1))])[None]
    curve, std = stereo_curve3d(rig, [p0], [p1], pose, 0.3, smooth=False)
    x, s = match_stereo_curve(rig, p0, p1, 0.3)
    np.testing.assert_allclose(curve, x)
    np.testing.assert_allclose(std, s)


def test_bad_input():
    rig = _rig()
    rng = np.random.default_rng(4)
    pts, _ = _scene(rng, "fourier")
    p0, p1 = _views(rig, pts, rng, 0.0)
    with pytest.raises(CurveReconError, match="at least 2"):
        match_stereo_curve(rig, p0[:1], p1, 0.5)
    with pytest.raises(CurveReconError, match="at least 2"):
        match_stereo_curve(rig, p0, p1[:1], 0.5)
    closed = np.vstack([p1, p1[:1]])
    with pytest.raises(CurveReconError, match="A' and B' coincide"):
        match_stereo_curve(rig, p0, closed, 0.5)
    with pytest.raises(CurveReconError, match="A' and B' coincide"):
        match_stereo_curve(rig, np.vstack([p0, p0[:1]]), p1, 0.5)
    bad = p0.copy()
    bad[3, 0] = np.nan
    with pytest.raises(CurveReconError, match="NaN"):
        match_stereo_curve(rig, bad, p1, 0.5)
    with pytest.raises(CurveReconError, match="point_sigma"):
        match_stereo_curve(rig, p0, p1, 0.0)
    pose = np.hstack([np.eye(3), np.zeros((3, 1))])[None]
    with pytest.raises(CurveReconError, match="frame poses"):
        stereo_curve3d(rig, [p0, p0], [p1, p1], pose, 0.5)
    with pytest.raises(CurveReconError, match="frame poses"):
        stereo_curve3d(rig, [p0], [p1], np.eye(3)[None], 0.5)
    # the two views swapped end for end do not show one curve in front of both cameras
    with pytest.raises(CurveReconError):
        match_stereo_curve(rig, p0, p1[::-1], 0.5)


def _print_figures() -> None:  # pragma: no cover - figures for docs/accuracy.md
    print("one frame: sigma_px  coverage(z<=3)  median_z  rms_error/length (median of 20 draws)")
    for sigma in (0.25, 0.5, 1.0, 2.0):
        z, rel = _coverage(sigma, draws=20, seed=3)
        print(f"{sigma:8.2f}  {np.mean(z <= 3):14.4f}  {np.median(z):8.3f}  {np.median(rel):.2e}")
    rng, rig = np.random.default_rng(9), _rig()
    z, ratio = [], []
    for _ in range(20):
        _, dense, poses, v0, v1 = _moving_frames(rng, rig, 0.5)
        curve, std = stereo_curve3d(rig, v0, v1, poses, 0.5)
        x0, _ = match_stereo_curve(rig, v0[0], v1[0], 0.5)
        d = _distance(curve, dense)
        z.append(d / std)
        ratio.append(np.sqrt(np.mean(d**2)) / np.sqrt(np.mean(_distance(x0, dense) ** 2)))
    z = np.concatenate(z)
    print(
        f"six frames fused, 0.5 px: coverage {np.mean(z <= 3):.4f}, median z {np.median(z):.3f},"
        f" rms error / frame 0's alone {np.median(ratio):.2f} (median of 20 draws)"
    )


if __name__ == "__main__":  # pragma: no cover
    _print_figures()


def test_turn_about_the_chord_recovered():
    """A curve turned about its chord AB by a known angle: the turn is found, and the pose it
    gives moves frame f's points back onto frame 0's curve with A and B kept."""
    from curverecon.curve.stereo_turn import best_turn, rotation_about, turned_pose

    rng = np.random.default_rng(21)
    pts, _ = _scene(rng, "helix")
    a0, axis = pts[0], (pts[-1] - pts[0]) / np.linalg.norm(pts[-1] - pts[0])
    std = np.full(len(pts), 0.01)
    for angle in (-2.5, -0.4, 0.3, 1.7, 3.0):
        # an independent turn: Rodrigues' formula written out
        k = np.cross(axis, pts - a0)
        turned = a0 + (pts - a0) * np.cos(angle) + k * np.sin(angle)
        turned += np.outer((pts - a0) @ axis, axis) * (1 - np.cos(angle))
        found = best_turn(turned, std, pts, a0, axis)
        assert abs(np.angle(np.exp(1j * (found + angle)))) < 1e-7
        pose = np.column_stack([rotation_about(axis, 0.0), np.zeros(3)])
        new = turned_pose(pose, a0, axis, found)
        back = (turned - new[:, 3]) @ new[:, :3]
        np.testing.assert_allclose(back, pts, atol=1e-9)


def _stereo_scene(seed: int, frames: int):
    from curverecon.io import observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.rigid import reconstruct_rigid
    from curverecon.simulate import simulate_camera_configuration

    doc, truth = simulate_camera_configuration(
        "stereo", "free", "AB", frames, seed, noise_px=0.5, with_curve=True
    )
    obs = observations_from_dict(doc)
    return obs, truth, reconstruct_rigid(obs, ReconstructOptions(point_sigma=0.5))


@pytest.mark.parametrize("seed", [1, 2])
def test_stereo_frames_with_a_and_b_alone_give_the_curve(seed):
    """Five stereo frames, A, B and polylines, 0.5 px (the simulator's own 3-D scene): each
    frame's turn about AB, left free by the points, comes from the curves, so the fused curve
    lies on the true one and reprojects onto every frame's polyline."""
    obs, truth, rec = _stereo_scene(seed, 5)
    dense = np.asarray(truth["curve3d"])
    length = _length(dense)
    d = _distance(rec.curve3d, dense)
    assert np.mean(d) <= 0.01 * length
    assert np.max(d) <= 0.04 * length
    assert np.mean(d <= 3.0 * rec.curve3d_normal_std) >= 0.95
    cam, gaps = obs.configuration.rig.camera0, []
    for f, frame in enumerate(truth["frames"]):
        rot, true_rot = rec.frame_poses[f, :, :3], np.asarray(frame["frame_pose"]["R"])
        cos = (np.trace(rot @ true_rot.T) - 1.0) / 2.0
        assert np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))) <= 5.0
        pix = cam.project(rec.curve3d @ rot.T + rec.frame_poses[f, :, 3])
        poly = np.asarray(obs.curves[f])
        gaps.append(np.median(_distance(pix, poly)))
    # pixels: 0.34 for a curve exactly on the truth (median distance of 0.5 px noise)
    assert np.median(gaps) <= 0.6 and np.max(gaps) <= 2.0
    assert not any("turn about the chord" in w for w in rec.warnings)

"""The perspective and stereo figure (curverecon.plot.plot_camera_file) from a 3-D construction.

A rigid curve with points A, B is moved between frames (X_f = R_f X_0 + T_f) in front of a
pinhole camera or a stereo pair; the frames' pixels are computed here with the pinhole formula.
A Reconstruction holding the construction's own frame poses, curve and points must then be drawn
with reprojections equal to the observed pixels and cameras where the construction put them.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from curverecon.cli import main
from curverecon.errors import CurveReconError
from curverecon.io import observations_to_dict
from curverecon.model.configuration import Configuration, RigidObservations, StereoView
from curverecon.model.reconstruction import Reconstruction
from curverecon.plot import camera_frustums, camera_reprojection, plot_camera_file
from curverecon.solvers.camera import Camera, StereoRig

FOCAL, PP = 700.0, np.array([320.0, 240.0])
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
RIG_R = np.array([[np.cos(0.1), 0, -np.sin(0.1)], [0, 1, 0], [np.sin(0.1), 0, np.cos(0.1)]])
RIG_C1 = np.array([0.3, 0.0, 0.0])  # camera 1's centre in camera 0's coordinates
RIG_T = -RIG_R @ RIG_C1


def _pixels(x: np.ndarray) -> np.ndarray:
    return FOCAL * x[..., :2] / x[..., 2:] + PP


def _rotation(axis, angle) -> np.ndarray:
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def _construction(frames: int, seed: int = 0):
    """(curve in frame 0 (K, 3), frame poses (N, 3, 4), the curve in every frame (N, K, 3))."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, 80)[:, None]
    curve = np.column_stack([0.4 * u[:, 0], 0.1 * np.sin(3 * u[:, 0]), 0.15 * u[:, 0] ** 2])
    curve = curve + np.array([-0.2, 0.0, 2.0])
    centre = curve.mean(axis=0)
    poses, moved = [], []
    for f in range(frames):
        rot = np.eye(3) if f == 0 else _rotation(rng.normal(size=3), rng.uniform(0.1, 0.4))
        tr = centre - rot @ centre + (0.0 if f == 0 else rng.normal(scale=0.1, size=3))
        poses.append(np.column_stack([rot, tr]))
        moved.append(curve @ rot.T + tr)
    return curve, np.array(poses), np.array(moved)


def _scene(projection: str, frames: int):
    curve, poses, moved = _construction(frames)
    cam = Camera(FOCAL, tuple(PP))
    if projection == "stereo":
        cfg = Configuration(
            "stereo", "free", ("A", "B"), False, rig=StereoRig(cam, cam, RIG_R, RIG_T)
        )
    else:
        cfg = Configuration("perspective", "free", ("A", "B"), False, camera=cam)
    ends = moved[:, [0, -1]]
    view1 = None
    if projection == "stereo":
        in1 = moved @ RIG_R.T + RIG_T
        view1 = StereoView(_pixels(in1[:, [0, -1]]), None, list(_pixels(in1)))
    obs = RigidObservations(
        cfg, np.arange(frames, dtype=float), _pixels(ends), None, list(_pixels(moved)), view1=view1
    )
    rec = Reconstruction(
        shape=np.full(4, np.nan),
        poses=np.full((frames, 5), np.nan),
        std=None,
        inliers=np.ones(frames, dtype=bool),
        curve3d=curve,
        points3=[{"A": m[0].tolist(), "B": m[-1].tolist()} for m in moved],
        frame_poses=poses,
        configuration=cfg.to_json_dict(),
    )
    return rec, obs, moved, poses


@pytest.mark.parametrize("projection, frames", [("perspective", 5), ("stereo", 3)])
def test_reprojection_is_the_construction(projection, frames):
    rec, obs, moved, _ = _scene(projection, frames)
    drawn = camera_reprojection(rec, obs)
    assert len(drawn) == frames
    for f in range(frames):
        np.testing.assert_allclose(drawn[f]["curve"][0], _pixels(moved[f]), atol=1e-9)
        np.testing.assert_allclose(drawn[f]["points"][0], obs.points[f], atol=1e-9)
        if projection == "stereo":
            in1 = moved[f] @ RIG_R.T + RIG_T
            np.testing.assert_allclose(drawn[f]["curve"][1], _pixels(in1), atol=1e-9)
            np.testing.assert_allclose(drawn[f]["points"][1], obs.view1.points[f], atol=1e-9)
        else:
            assert len(drawn[f]["curve"]) == 1


def test_frustums_sit_where_the_cameras_are():
    rec, obs, _, poses = _scene("stereo", 4)
    frusta = camera_frustums(rec, obs, depth=0.5)
    assert len(frusta) == 8
    for fr in frusta:
        rot, tr = poses[fr["frame"], :, :3], poses[fr["frame"], :, 3]
        # the body moved by (R_f, T_f) is the camera moved by the inverse: in frame 0's
        # coordinates camera 0 of frame f is at R_f^T (0 - T_f), camera 1 at R_f^T (C1 - T_f)
        own = np.zeros(3) if fr["label"] == "camera 0" else RIG_C1
        np.testing.assert_allclose(fr["centre"], rot.T @ (own - tr), atol=1e-12)
        # its optical axis: the corners' mean lies along it at the given depth
        axis = fr["axes"][2]
        mean = fr["corners"].mean(axis=0) - fr["centre"]
        np.testing.assert_allclose(mean, 0.5 * axis, atol=1e-12)
        # a frame-f point straight ahead of camera 0 maps onto camera 0's axis
    frame0 = [fr for fr in frusta if fr["frame"] == 0 and fr["label"] == "camera 0"][0]
    np.testing.assert_allclose(frame0["axes"], np.eye(3), atol=1e-12)


@pytest.mark.parametrize(
    "projection, frames", [("perspective", 1), ("perspective", 15), ("stereo", 8)]
)
def test_png_written(tmp_path, projection, frames):
    rec, obs, _, _ = _scene(projection, frames)
    path = tmp_path / "camera.png"
    plot_camera_file(str(path), rec, obs)
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC and len(data) > 10_000


def test_without_curve_or_poses(tmp_path):
    rec, obs, _, _ = _scene("perspective", 3)
    rec.curve3d = None
    rec.frame_poses = None
    drawn = camera_reprojection(rec, obs)
    assert all(d["curve"] == [None] for d in drawn)
    assert len(camera_frustums(rec, obs, 1.0)) == 1
    plot_camera_file(str(tmp_path / "p.png"), rec, obs)
    assert (tmp_path / "p.png").read_bytes()[:8] == PNG_MAGIC


def test_unwritable_path(tmp_path):
    rec, obs, _, _ = _scene("perspective", 2)
    with pytest.raises(CurveReconError, match="cannot write plot"):
        plot_camera_file(str(tmp_path / "missing" / "p.png"), rec, obs)


def test_command_draws_the_camera_figure(tmp_path, monkeypatch):
    """``reconstruct --plot`` chooses the camera figure for a stereo document."""
    import curverecon.pipeline
    import curverecon.plot

    rec, obs, _, _ = _scene("stereo", 3)
    src = tmp_path / "in.json"
    src.write_text(json.dumps(observations_to_dict(obs)))
    monkeypatch.setattr(curverecon.pipeline, "reconstruct", lambda obs, options=None: rec)
    seen = []
    real = curverecon.plot.plot_camera_file
    monkeypatch.setattr(
        curverecon.plot,
        "plot_camera_file",
        lambda path, r, o: seen.append(o.configuration.projection) or real(path, r, o),
    )
    png = tmp_path / "out.png"
    assert (
        main(["reconstruct", str(src), "-o", str(tmp_path / "out.json"), "--plot", str(png)]) == 0
    )
    assert seen == ["stereo"]
    assert png.read_bytes()[:8] == PNG_MAGIC


@pytest.mark.parametrize("projection", ["perspective", "stereo"])
def test_3d_panel_names_the_points_and_frame_0s_cameras(projection):
    """The 3-D panel labels A and B at the construction's frame-0 positions and each of frame
    0's cameras at its centre (camera 1's at C1 = -R^T t, the construction's RIG_C1)."""
    from matplotlib.figure import Figure

    from curverecon.plot import _camera_3d_panel

    rec, obs, moved, _ = _scene(projection, 3)
    ax = Figure().add_subplot(projection="3d")
    _camera_3d_panel(ax, rec, obs)
    texts = {t.get_text().strip(): np.array(t.get_position_3d(), float) for t in ax.texts}
    np.testing.assert_allclose(texts["A"], moved[0, 0], atol=1e-12)
    np.testing.assert_allclose(texts["B"], moved[0, -1], atol=1e-12)
    if projection == "stereo":
        np.testing.assert_allclose(texts["camera 0, frame 0"], np.zeros(3), atol=1e-12)
        np.testing.assert_allclose(texts["camera 1, frame 0"], RIG_C1, atol=1e-12)
    else:
        np.testing.assert_allclose(texts["camera, frame 0"], np.zeros(3), atol=1e-12)

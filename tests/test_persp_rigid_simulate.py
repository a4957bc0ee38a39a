"""``simulate --projection perspective|stereo``: the documents are the truth seen through the
cameras (a pinhole projection written here, not the camera class), the body is rigid, the
frame poses map frame 0 to every frame, and the units follow the contract."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from curverecon.io import load_observations
from curverecon.simulate import simulate_camera_configuration


def _pinhole(x: np.ndarray, cam: dict) -> np.ndarray:
    f, (cx, cy) = cam["focal_px"], cam["principal_point"]
    return np.column_stack([f * x[:, 0] / x[:, 2] + cx, f * x[:, 1] / x[:, 2] + cy])


@pytest.mark.parametrize(
    "projection,motion,points",
    [
        ("perspective", "rotation-free", "AB"),
        ("perspective", "uniform-rotation", "AB"),
        ("perspective", "fixed-axis", "ABC"),
        ("perspective", "free", "ABCD"),
        ("perspective", "force-field", "AB"),
        ("stereo", "free", "AB"),
    ],
)
def test_document_is_the_truth_through_the_cameras(projection, motion, points):
    doc, truth = simulate_camera_configuration(projection, motion, points, frames=7, seed=3)
    names = list(points)
    p3 = np.array([[fr["points3"][k] for k in names] for fr in truth["frames"]])
    if projection == "perspective":
        assert p3[0, 0, 2] == pytest.approx(1.0)  # A's depth in frame 0 is the unit
    for f, fr in enumerate(truth["frames"]):
        pose_r, pose_t = np.array(fr["frame_pose"]["R"]), np.array(fr["frame_pose"]["T"])
        np.testing.assert_allclose(p3[0] @ pose_r.T + pose_t, p3[f], atol=1e-9)
        views = [doc["frames"][f]] if projection == "perspective" else doc["frames"][f]["views"]
        cams = [doc["camera"]] if projection == "perspective" else doc["cameras"]
        for view, cam in zip(views, cams, strict=True):
            x = p3[f]
            if "R" in cam:
                x = x @ np.array(cam["R"]).T + np.array(cam["t"])
            img = np.array([view[k] if k in "AB" else view["points"][k] for k in names])
            np.testing.assert_allclose(img, _pinhole(x, cam), atol=1e-9)
    dist = np.linalg.norm(p3[:, 1] - p3[:, 0], axis=1)
    np.testing.assert_allclose(dist, truth["c"], rtol=1e-12)
    if motion == "rotation-free":
        rel = p3 - p3[:, :1]
        np.testing.assert_allclose(rel, np.broadcast_to(rel[0], rel.shape), atol=1e-12)


def test_force_field_mass_centre_on_a_3d_parabola():
    _, truth = simulate_camera_configuration("perspective", "force-field", frames=9, seed=5)
    mp = truth["motion_parameters"]
    g = np.array([mp["position"], mp["velocity"], mp["acceleration"]])
    t = np.array(truth["times"])
    a3 = np.array([fr["A3"] for fr in truth["frames"]])
    rot = np.array([fr["rotation"] for fr in truth["frames"]])
    centre = a3 + rot @ np.array(mp["mass_centre"])
    expect = g[0] + np.outer(t, g[1]) + np.outer(t * t / 2, g[2])
    np.testing.assert_allclose(centre, expect, atol=1e-9)


def test_command_writes_documents_the_reader_takes(tmp_path):
    out, tru = tmp_path / "s.json", tmp_path / "t.json"
    cmd = [sys.executable, "-m", "curverecon", "simulate", "--motion", "free", "--projection"]
    run = subprocess.run(
        [*cmd, "stereo", "--with-curve", "--frames", "3", "-o", str(out), "--truth", str(tru)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    obs = load_observations(str(out))
    assert obs.configuration.projection == "stereo" and obs.view1 is not None
    assert obs.curves is not None and len(obs.view1.curves) == 3
    assert json.loads(tru.read_text())["configuration"]["projection"] == "stereo"
    bad = subprocess.run(
        [*cmd[:-2], "rotation-free", "-o", str(out)], capture_output=True, text=True
    )
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1

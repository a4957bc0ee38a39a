"""Perspective and stereo documents (CONTRACT.md, "Configurations"): read, validated, written back.

The documents are built from a 3-D construction here (a rigid body seen by a pinhole camera, or
by a stereo pair), independently of the simulator, so that the reader's conventions (camera 1's
X1 = R X0 + t, each frame's "views" in camera order) are checked against the geometry.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from curverecon.cli import main
from curverecon.errors import CurveReconError
from curverecon.io import observations_from_dict, observations_to_dict
from curverecon.model.configuration import RigidObservations
from curverecon.solvers.camera import Camera

FOCAL, PP = 800.0, [320.0, 240.0]


def _rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _body_frames(seed: int, frames: int = 5) -> list[np.ndarray]:
    """(3, 3) A, B, C in each frame's camera coordinates (a rigid body 5 units in front)."""
    rng = np.random.default_rng(seed)
    body = rng.normal(size=(3, 3))
    out = []
    for _ in range(frames):
        out.append(body @ _rotation(rng).T + np.array([*rng.normal(size=2) * 0.3, 5.0]))
    return out


def _pixels(x: np.ndarray) -> list[list[float]]:
    cam = Camera(FOCAL, tuple(PP))
    return cam.project(x).tolist()


def _view(x: np.ndarray) -> dict:
    px = _pixels(x)
    return {"A": px[0], "B": px[1], "points": {"C": px[2]}}


def perspective_doc(seed: int = 0) -> dict:
    frames = [{"t": float(i), **_view(x)} for i, x in enumerate(_body_frames(seed))]
    return {
        "format": "curverecon.observations/1",
        "projection": "perspective",
        "camera": {"focal_px": FOCAL, "principal_point": PP},
        "motion": "free",
        "frames": frames,
    }


RIG_R = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
RIG_T = np.array([5.0, 0.0, 5.0])  # camera 1 looks at the body from the side


def stereo_doc(seed: int = 0) -> dict:
    frames = []
    for i, x in enumerate(_body_frames(seed, 3)):
        frames.append({"t": float(i), "views": [_view(x), _view(x @ RIG_R.T + RIG_T)]})
    cam = {"focal_px": FOCAL, "principal_point": PP}
    return {
        "format": "curverecon.observations/1",
        "projection": "stereo",
        "cameras": [cam, {**cam, "R": RIG_R.tolist(), "t": RIG_T.tolist()}],
        "frames": frames,
    }


def test_perspective_document_reads_with_its_camera():
    doc = perspective_doc()
    obs = observations_from_dict(doc)
    assert isinstance(obs, RigidObservations)
    cfg = obs.configuration
    assert (cfg.projection, cfg.motion, cfg.points) == ("perspective", "free", ("A", "B", "C"))
    assert cfg.camera.focal_px == FOCAL
    # the camera's rays give back each frame's 3-D points up to their depths
    x0 = _body_frames(0)[0]
    rays = cfg.camera.rays(obs.points[0])
    np.testing.assert_allclose(rays * x0[:, 2:], x0, atol=1e-9)
    assert obs.view1 is None
    again = observations_from_dict(json.loads(json.dumps(observations_to_dict(obs))))
    np.testing.assert_array_equal(again.points, obs.points)
    assert again.configuration == cfg


def test_stereo_document_reads_both_views():
    doc = stereo_doc()
    obs = observations_from_dict(doc)
    rig = obs.configuration.rig
    assert obs.view1 is not None and obs.view1.points.shape == obs.points.shape
    # camera 1's pixel of A is the projection of camera 0's A moved by X1 = R X0 + t
    x0 = _body_frames(0, 3)[1]
    np.testing.assert_allclose(
        rig.camera1.project(x0 @ rig.R.T + rig.t), obs.view1.points[1], atol=1e-9
    )
    back = observations_to_dict(obs)
    assert back["cameras"][1]["t"] == RIG_T.tolist()
    again = observations_from_dict(json.loads(json.dumps(back)))
    np.testing.assert_array_equal(again.view1.points, obs.view1.points)
    sub = obs.subset(np.array([0, 2]))
    np.testing.assert_array_equal(sub.view1.points, obs.view1.points[[0, 2]])


def _broken(doc: dict, path: tuple, value) -> dict:
    target = doc
    for key in path[:-1]:
        target = target[key]
    if value is KeyError:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return doc


BAD = {
    "no camera": (perspective_doc, ("camera",), KeyError, 'needs "camera"'),
    "focal not positive": (
        perspective_doc, ("camera", "focal_px"), -5.0, "focal_px must be a positive number"),
    "principal point": (
        perspective_doc, ("camera", "principal_point"), [1.0], "principal_point must be"),
    "camera in stereo": (stereo_doc, ("camera",), {"focal_px": 1.0}, '"camera" given'),
    "no R": (stereo_doc, ("cameras", 1, "R"), KeyError, 'cameras[1]: missing key "R"'),
    "R not a rotation": (
        stereo_doc, ("cameras", 1, "R"), [[2, 0, 0], [0, 1, 0], [0, 0, 1]], "not a rotation"),
    "no baseline": (stereo_doc, ("cameras", 1, "t"), [0, 0, 0], "no baseline"),
    "one view": (stereo_doc, ("frames", 1, "views"), [{}], "frame 1: \"views\" must be"),
    "length_AB orthographic": (
        lambda: {**perspective_doc(), "projection": "orthographic", "length_AB": 2.0},
        ("camera",), KeyError, '"length_AB" applies to projection "perspective" only'),
    "length_AB negative": (
        perspective_doc, ("length_AB",), -1.0, "length_AB must be a positive number"),
}  # fmt: skip


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_camera_input_is_one_line(case, tmp_path, capsys):
    make, path, value, message = BAD[case]
    doc = _broken(make(), path, value)
    with pytest.raises(CurveReconError, match=re.escape(message)):
        observations_from_dict(doc)
    inp = tmp_path / "in.json"
    inp.write_text(json.dumps(doc))
    code = main(["reconstruct", str(inp), "-o", str(tmp_path / "o.json"), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and message in err[0]

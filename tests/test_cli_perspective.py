"""What a user with a real camera meets first: perspective and stereo documents written by hand.

The documents are built here from a 3-D construction (a rigid body in front of a pinhole camera
or a stereo pair, projected by the pinhole formula u = f x / z + cx), independently of the
simulator, so the checks (points behind the cameras, camera keys, NaN places) are tested against
the geometry.  Every bad input is one line and exit status 2 from the command and a
CurveReconError from the library.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from curverecon.cli import main
from curverecon.errors import CurveReconError
from curverecon.io import observations_from_dict, read_json

FOCAL, PP = 700.0, (300.0, 200.0)


def _project(x: np.ndarray) -> list[list[float]]:
    """Pixels of (P, 3) camera coordinates (z > 0 in front)."""
    return (x[:, :2] / x[:, 2:] * FOCAL + np.array(PP)).tolist()


def _rot_y(deg: float) -> np.ndarray:
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


RIG_R = _rot_y(-10.0)  # camera 1 turned towards the body ...
RIG_T = np.array([-1.0, 0.0, 0.2])  # ... from one unit to the right: X1 = R X0 + t


def _body(seed: int, frames: int) -> list[np.ndarray]:
    """(3, 3) A, B, C in each frame's camera-0 coordinates: a rigid body about 6 units ahead."""
    rng = np.random.default_rng(seed)
    body = rng.normal(size=(3, 3)) * 0.5
    out = []
    for _ in range(frames):
        q, r = np.linalg.qr(rng.normal(size=(3, 3)))
        q = q * np.sign(np.diag(r))
        q = q if np.linalg.det(q) > 0 else -q
        out.append(body @ q.T + np.array([*rng.normal(size=2) * 0.3, 6.0]))
    return out


def _view(x: np.ndarray) -> dict:
    px = _project(x)
    return {"A": px[0], "B": px[1], "points": {"C": px[2]}}


def _camera() -> dict:
    return {"focal_px": FOCAL, "principal_point": list(PP)}


def perspective_doc(frames: int = 4, motion: str = "free") -> dict:
    return {
        "format": "curverecon.observations/1",
        "projection": "perspective",
        "camera": _camera(),
        "motion": motion,
        "frames": [{"t": float(i), **_view(x)} for i, x in enumerate(_body(3, frames))],
    }


def stereo_doc(frames: int = 2, t: np.ndarray = RIG_T) -> dict:
    pairs = [[_view(x), _view(x @ RIG_R.T + RIG_T)] for x in _body(4, frames)]
    return {
        "format": "curverecon.observations/1",
        "projection": "stereo",
        "cameras": [_camera(), {**_camera(), "R": RIG_R.tolist(), "t": list(t)}],
        "frames": [{"t": float(i), "views": v} for i, v in enumerate(pairs)],
    }


def _command(doc: dict | str, tmp_path, capsys) -> tuple[int, list[str]]:
    """Exit status and stderr lines of ``curverecon reconstruct`` on the document."""
    inp = tmp_path / "in.json"
    inp.write_text(doc if isinstance(doc, str) else json.dumps(doc))
    capsys.readouterr()
    code = main(["reconstruct", str(inp), "-o", str(tmp_path / "o.json"), "--quiet"])
    return code, capsys.readouterr().err.strip().splitlines()


def _refused(doc: dict | str, message: str, tmp_path, capsys) -> None:
    """The library raises CurveReconError with ``message``; the command prints it in one line
    and exits with status 2."""
    with pytest.raises(CurveReconError, match=re.escape(message)):
        if isinstance(doc, str):
            (tmp_path / "lib.json").write_text(doc)
            observations_from_dict(read_json(tmp_path / "lib.json"))
        else:
            observations_from_dict(doc)
    code, err = _command(doc, tmp_path, capsys)
    assert code == 2 and len(err) == 1 and message in err[0], err


def test_stereo_construction_is_in_front_and_reads():
    """The construction's rig is right: read without complaint, camera 1 sees X1 = R X0 + t."""
    obs = observations_from_dict(stereo_doc())
    x = _body(4, 2)[1]
    np.testing.assert_allclose(obs.view1.points[1], _project(x @ RIG_R.T + RIG_T), atol=1e-9)


@pytest.mark.parametrize("with_curve", [False, True])
def test_stereo_t_of_the_other_direction_is_refused(with_curve, tmp_path, capsys):
    """t negated (camera 1's position given instead of X1 = R X0 + t): the points triangulate
    behind the cameras; refused before any fitting, with the fix named."""
    doc = stereo_doc()
    doc["cameras"][1]["t"] = (-RIG_T).tolist()
    if with_curve:
        for frame in doc["frames"]:
            for view in frame["views"]:
                view["curve"] = [view["A"], view["points"]["C"], view["B"]]
    _refused(doc, "triangulate behind the cameras", tmp_path, capsys)
    with pytest.raises(CurveReconError, match=r"X1 = R X0 \+ t"):
        observations_from_dict(doc)


def test_stereo_views_in_the_wrong_order_are_refused(tmp_path, capsys):
    """A parallel rig (R = I, camera 1 one unit to the right: t = (-1, 0, 0)) with each frame's
    views given as [camera 1, camera 0]: the disparity has the wrong sign, every point behind."""
    doc = stereo_doc()
    doc["cameras"][1].update(R=np.eye(3).tolist(), t=[-1.0, 0.0, 0.0])
    for frame, x in zip(doc["frames"], _body(4, 2), strict=True):
        frame["views"] = [_view(x - [1.0, 0.0, 0.0]), _view(x)]
    _refused(doc, "triangulate behind the cameras", tmp_path, capsys)
    for frame in doc["frames"]:
        frame["views"].reverse()
    observations_from_dict(doc)  # the right order reads


def test_stereo_depths_in_the_message_are_the_construction(tmp_path):
    """The depths the message quotes for frame 0's A are the construction's, mirrored: with t
    negated, -X satisfies X1 = R X0 + t (as -X1, which a pinhole sees as X1), so the rays meet
    at the point reflected through camera 0's centre."""
    doc = stereo_doc(frames=1)
    doc["cameras"][1]["t"] = (-RIG_T).tolist()
    a0 = _body(4, 1)[0][0]
    depth, depth1 = a0[2], (RIG_R @ a0 + RIG_T)[2]
    with pytest.raises(CurveReconError) as info:
        observations_from_dict(doc)
    quoted = re.search(
        r"frame 0's A at depth (\S+) in camera 0, (\S+) in camera 1", str(info.value)
    )
    assert float(quoted[1]) == pytest.approx(-depth, rel=1e-3)
    assert float(quoted[2]) == pytest.approx(-depth1, rel=1e-3)


@pytest.mark.parametrize(
    "place",
    [("frames", 1, "A", 0), ("camera", "principal_point", 1), ("camera", "focal_px")],
)
def test_nan_is_named_by_its_place(place, tmp_path, capsys):
    doc = perspective_doc()
    target = doc
    for key in place[:-1]:
        target = target[key]
    target[place[-1]] = float("nan")
    text = json.dumps(doc)  # writes the NaN literal, as some tools do
    where = "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in place).lstrip(".")
    _refused(text, f"non-finite number NaN in JSON at {where}", tmp_path, capsys)


def test_nan_in_camera_1s_view_is_named(tmp_path, capsys):
    doc = stereo_doc()
    doc["frames"][1]["views"][1]["B"][1] = float("-inf")
    _refused(json.dumps(doc), "-Infinity in JSON at frames[1].views[1].B[1]", tmp_path, capsys)


@pytest.mark.parametrize(
    "camera",
    [
        {"fx": FOCAL, "fy": FOCAL, "cx": PP[0], "cy": PP[1]},
        {"K": [[FOCAL, 0, PP[0]], [0, FOCAL, PP[1]], [0, 0, 1]]},
    ],
)
def test_other_camera_conventions_name_the_keys(camera, tmp_path, capsys):
    doc = perspective_doc()
    doc["camera"] = camera
    _refused(doc, '"focal_px": f, "principal_point": [cx, cy]', tmp_path, capsys)


def test_negative_focal_length_is_refused(tmp_path, capsys):
    doc = perspective_doc()
    doc["camera"]["focal_px"] = -FOCAL
    _refused(doc, "focal_px must be a positive number", tmp_path, capsys)


def test_distortion_keys_are_warned_not_silently_dropped():
    doc = perspective_doc()
    doc["camera"]["distortion"] = [0.1, -0.02, 0.0, 0.0, 0.0]
    warnings = observations_from_dict(doc).warnings
    assert any("distortion ignored" in w and "undistort" in w for w in warnings), warnings
    plain = observations_from_dict(perspective_doc()).warnings
    assert not any("ignored" in w for w in plain)


def test_stereo_rig_keys_are_not_warned():
    assert not any("ignored" in w for w in observations_from_dict(stereo_doc()).warnings)


def test_rounded_rotation_is_taken_as_the_nearest_rotation():
    """R printed to 4 decimals (R R^T off by about 1e-4) reads as a rotation within 1e-4 of it;
    a matrix that is no rotation is still refused."""
    doc = stereo_doc()
    rounded = np.round(RIG_R, 4)
    doc["cameras"][1]["R"] = rounded.tolist()
    r = observations_from_dict(doc).configuration.rig.R
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.max(np.abs(r - RIG_R)) < 1e-4
    doc["cameras"][1]["R"] = (RIG_R * 1.01).tolist()
    with pytest.raises(CurveReconError, match="not a rotation"):
        observations_from_dict(doc)


def test_stereo_without_the_second_view_or_camera(tmp_path, capsys):
    doc = stereo_doc()
    doc["frames"][0]["views"] = doc["frames"][0]["views"][:1]
    _refused(doc, 'frame 0: "views" must be a list of two objects', tmp_path, capsys)
    doc = stereo_doc()
    doc["cameras"] = doc["cameras"][:1]
    _refused(doc, '"cameras" must be a list of two camera objects', tmp_path, capsys)


def test_stereo_view_error_names_the_camera(tmp_path, capsys):
    doc = stereo_doc()
    doc["frames"][1]["views"][1]["A"] = [1.0]
    _refused(doc, "camera 1: frame 1: A must be [x, y]", tmp_path, capsys)


def test_too_few_frames_for_the_motion(tmp_path, capsys):
    """Uniform rotation under a pinhole needs 5 frames (docs/derivation.md): 4 refused."""
    doc = perspective_doc(frames=4, motion="uniform-rotation")
    for frame in doc["frames"]:
        del frame["points"]
    code, err = _command(doc, tmp_path, capsys)
    assert code == 2 and len(err) == 1 and "needs at least 5" in err[0], err


def test_free_motion_with_two_points_names_both_remedies(tmp_path, capsys):
    doc = perspective_doc(frames=4)
    for frame in doc["frames"]:
        del frame["points"]
    code, err = _command(doc, tmp_path, capsys)
    assert code == 2 and len(err) == 1, err
    assert "four points (A, B, C, D)" in err[0] and 'polyline ("curve")' in err[0]


def test_one_frame_stereo_from_the_command(tmp_path, capsys):
    """The Section 2 table's stereo row needs one frame: simulate draws it, reconstruct solves
    it (c within 4 std of the truth), and no warning about turns between frames appears."""
    scene, truth, out = (tmp_path / n for n in ("s.json", "t.json", "r.json"))
    assert (
        main(
            [
                "simulate",
                "--motion",
                "free",
                "--projection",
                "stereo",
                "--frames",
                "1",
                "--noise-px",
                "0.5",
                "--seed",
                "2",
                "-o",
                str(scene),
                "--truth",
                str(truth),
            ]
        )  # fmt: skip
        == 0
    )
    capsys.readouterr()
    assert main(["reconstruct", str(scene), "-o", str(out), "--quiet"]) == 0
    assert "turn about the chord" not in capsys.readouterr().err
    rec, tru = json.loads(out.read_text()), json.loads(truth.read_text())
    assert len(rec["frames"]) == 1
    assert abs(rec["c"] - tru["c"]) < 4 * rec["std"]["c"]
    np.testing.assert_allclose(
        rec["frames"][0]["points3"]["A"], tru["frames"][0]["points3"]["A"], rtol=0.02
    )


def test_motion_rotation_free_from_the_command(tmp_path, capsys):
    """``--motion rotation-free`` (a translating body, the document saying "free"): the answer is
    the construction in units of A's depth in frame 0, noise-free to 1e-6."""
    rng = np.random.default_rng(5)
    body = rng.normal(size=(2, 3)) * 0.5 + [0.0, 0.0, 6.0]
    shifts = [np.zeros(3), np.array([0.8, -0.3, 1.5])]
    doc = perspective_doc(frames=2)
    for frame, shift in zip(doc["frames"], shifts, strict=True):
        px = _project(body + shift)
        frame.update(A=px[0], B=px[1])
        del frame["points"]
    inp, out = tmp_path / "in.json", tmp_path / "out.json"
    inp.write_text(json.dumps(doc))
    assert main(["reconstruct", str(inp), "-o", str(out), "--motion", "rotation-free"]) == 0
    rec = json.loads(out.read_text())
    assert rec["configuration"]["motion"] == "rotation-free"
    unit = body[0, 2]
    for frame, shift in zip(rec["frames"], shifts, strict=True):
        got = np.array([frame["points3"]["A"], frame["points3"]["B"]])
        np.testing.assert_allclose(got, (body + shift) / unit, atol=1e-6)
    assert rec["c"] == pytest.approx(np.linalg.norm(body[1] - body[0]) / unit, abs=1e-6)


def test_camera_without_projection_names_the_missing_key(tmp_path, capsys):
    """A document with a camera but no "projection" would read as orthographic, the camera
    unused (without "motion", as the paper's own setting asking for tangents): refused."""
    doc = perspective_doc()
    del doc["projection"], doc["motion"]
    _refused(doc, '"camera" given with projection "orthographic"; add "projection": '
             '"perspective"', tmp_path, capsys)  # fmt: skip
    doc = stereo_doc()
    del doc["projection"]
    _refused(doc, 'add "projection": "stereo"', tmp_path, capsys)


def test_views_under_one_camera_are_refused(tmp_path, capsys):
    doc = stereo_doc()
    doc["projection"] = "perspective"
    doc["camera"] = doc.pop("cameras")[0]
    _refused(doc, 'frame 0: "views" (two cameras) belong to projection "stereo"', tmp_path, capsys)


@pytest.mark.parametrize(
    "args, message",
    [
        (["--motion", "free"], "--points ABCD or --with-curve"),
        (["--motion", "free", "--points", "ABC"], "four points (A, B, C, D)"),
        (["--motion", "fixed-axis"], "a third point (C) (simulate: --points ABC)"),
    ],
)
def test_simulate_refuses_a_camera_scene_reconstruct_would_refuse(args, message, tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["simulate", *args, "--projection", "perspective", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0] and not out.exists(), err


def test_simulate_warns_of_too_few_frames(tmp_path, capsys):
    out = tmp_path / "s.json"
    args = ["--motion", "uniform-rotation", "--projection", "perspective", "--frames", "4"]
    assert main(["simulate", *args, "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "reconstruct needs at least 5" in err and out.exists()
    assert main(["reconstruct", str(out), "-o", str(tmp_path / "r.json"), "--quiet"]) == 2
    assert "needs at least 5" in capsys.readouterr().err


def test_stereo_frame_written_as_one_view_says_so(tmp_path, capsys):
    doc = stereo_doc()
    for frame in doc["frames"]:
        frame.update(frame.pop("views")[0])
    _refused(doc, 'frame 0: "views" must be a list of two objects (camera 0, camera 1) (a '
             'stereo frame has no "A" of its own)', tmp_path, capsys)  # fmt: skip

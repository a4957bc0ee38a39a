"""The configuration data model: Configuration, RigidObservations and their input checks, and the
Reconstruction's new output keys (points3, configuration, motion_parameters, motion_scores)."""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.errors import CurveReconError
from curverecon.model.configuration import (
    PAPER_CONFIGURATION,
    Configuration,
    RigidObservations,
    in_plane_motion,
    min_frames,
)
from curverecon.model.reconstruction import Reconstruction


def _frames(n: int, p: int, seed: int = 0) -> np.ndarray:
    """(n, p, 2) image points of a rigid body turning about a tilted axis (3-D construction)."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(seed)
    body = rng.normal(scale=100.0, size=(p, 3))
    axis = np.array([1.0, 0.3, 0.2]) / np.linalg.norm([1.0, 0.3, 0.2])
    out = []
    for k in range(n):
        r = Rotation.from_rotvec(axis * 0.4 * k).as_matrix()
        out.append((body @ r.T)[:, :2] + [10.0 * k, -5.0 * k])
    return np.array(out)


def test_configuration_checks_and_dict():
    cfg = Configuration("orthographic", "fixed-axis", ("A", "B"), False)
    assert cfg.to_json_dict() == {
        "projection": "orthographic",
        "motion": "fixed-axis",
        "points": ["A", "B"],
        "tangents": False,
    }
    assert PAPER_CONFIGURATION.is_paper_row and not cfg.is_paper_row
    with pytest.raises(CurveReconError, match='unknown motion "spin"'):
        Configuration("orthographic", "spin")
    with pytest.raises(CurveReconError, match='needs "camera"'):
        Configuration("perspective")
    with pytest.raises(CurveReconError, match="unknown projection"):
        Configuration("fisheye")
    with pytest.raises(CurveReconError, match="start with"):
        Configuration(points=("B", "A"))
    with pytest.raises(CurveReconError, match="distinct"):
        Configuration(points=("A", "B", "C", "C"))
    with pytest.raises(AttributeError):
        cfg.motion = "free"  # frozen


def test_rigid_observations_structure_checks():
    cfg = Configuration(motion="free", points=("A", "B", "C"), tangents=False)
    pts = _frames(4, 3)
    obs = RigidObservations(cfg, np.arange(4.0), pts)
    assert obs.n_frames == 4 and obs.n_points == 3
    np.testing.assert_array_equal(obs.point("C"), pts[:, 2])
    assert obs.subset([0, 2]).frame_ids.tolist() == [0, 2]
    assert obs.with_motion("auto").configuration.motion == "auto"
    with pytest.raises(CurveReconError, match="frame 2: times are not increasing"):
        RigidObservations(cfg, [0.0, 1.0, 1.0, 2.0], pts)
    with pytest.raises(CurveReconError, match="frame 1: times is not finite"):
        RigidObservations(cfg, [0.0, np.nan, 1.0, 2.0], pts)
    with pytest.raises(CurveReconError, match="points must have shape"):
        RigidObservations(cfg, np.arange(4.0), pts[:, :2])
    bad = pts.copy()
    bad[3, 1] = bad[3, 0]
    with pytest.raises(CurveReconError, match="frame 3: A' and B' coincide"):
        RigidObservations(cfg, np.arange(4.0), bad)
    with pytest.raises(CurveReconError, match="tangents must be given"):
        RigidObservations(cfg, np.arange(4.0), pts, tangents=np.ones((4, 2, 2)))
    with pytest.raises(CurveReconError, match="3 curves for 4 frames"):
        RigidObservations(cfg, np.arange(4.0), pts, curves=[pts[0]] * 3)


def test_required_frames_points_and_motion():
    assert min_frames("free", 3) == 3
    assert min_frames("fixed-axis", 2) == 4
    assert min_frames("auto", 3) == 3
    ab = Configuration(motion="fixed-axis", points=("A", "B"), tangents=False)
    RigidObservations(ab, np.arange(4.0), _frames(4, 2)).require_reconstructable()
    with pytest.raises(CurveReconError, match="3 frame\\(s\\) given; motion fixed-axis"):
        RigidObservations(ab, np.arange(3.0), _frames(3, 2)).require_reconstructable()
    free2 = Configuration(motion="free", points=("A", "B"), tangents=False)
    with pytest.raises(CurveReconError, match="free motion with only A and B"):
        RigidObservations(free2, np.arange(6.0), _frames(6, 2)).require_reconstructable()
    still = Configuration(motion="rotation-free", points=("A", "B", "C"), tangents=False)
    with pytest.raises(CurveReconError, match="rotation-free"):
        RigidObservations(still, np.arange(6.0), _frames(6, 3)).require_reconstructable()


def test_in_plane_motion_is_refused_and_out_of_plane_passes():
    rng = np.random.default_rng(3)
    body = rng.normal(scale=100.0, size=(3, 2))
    frames = []
    for k in range(20):  # rotation about the viewing direction and a shift: no depth shown
        a = 0.3 * k
        r = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        frames.append(body @ r.T + rng.uniform(-50, 50, 2) + rng.normal(scale=1.0, size=(3, 2)))
    msg = in_plane_motion(np.array(frames), None, 1.0, 1.0)
    assert msg is not None and "no rotation out of the image plane" in msg
    alike = body[None] + rng.normal(scale=1.0, size=(20, 3, 2))
    assert "all frames alike" in in_plane_motion(alike, None, 1.0, 1.0)
    moving = _frames(20, 3) + rng.normal(scale=1.0, size=(20, 3, 2))
    assert in_plane_motion(moving, None, 1.0, 1.0) is None


def _rigid_reconstruction(n: int) -> Reconstruction:
    nan = np.full((n, 5), np.nan)
    pts3 = [{"A": [0.0, 0.0, 0.0], "B": [3.0, 4.0, 12.0], "C": [1.0, 1.0, -1.0]}] * n
    return Reconstruction(
        np.array([13.0, np.nan, np.nan, np.nan]),
        nan,
        None,
        np.ones(n, bool),
        points3=pts3,
        configuration=Configuration("orthographic", "free", ("A", "B", "C"), False).to_json_dict(),
        motion_parameters={},
        motion_scores={"free": 1.0},
    )


def test_reconstruction_writes_the_new_keys(tmp_path):
    import json

    from curverecon.io import write_json

    rec = _rigid_reconstruction(3)
    write_json(tmp_path / "r.json", rec.to_json_dict())
    doc = json.loads((tmp_path / "r.json").read_text())
    assert doc["c"] == 13.0 and doc["alpha_deg"] is None and doc["phi_deg"] is None
    assert doc["configuration"]["points"] == ["A", "B", "C"]
    assert doc["frames"][1]["points3"]["C"] == [1.0, 1.0, -1.0]
    assert doc["frames"][1]["B3"] == [3.0, 4.0, 12.0]
    assert doc["frames"][0]["delta_deg"] is None
    assert doc["motion_parameters"] == {} and doc["motion_scores"] == {"free": 1.0}


def test_paper_row_writes_its_configuration_and_points3():
    from curverecon.model.pose import translations

    poses = np.array([[0.3, 0.5, 0.1, 10.0, 20.0], [0.7, -0.4, 1.0, -5.0, 2.0]])
    rec = Reconstruction(np.array([100.0, 0.5, 0.6, 1.0]), poses, None, np.ones(2, bool))
    doc = rec.to_json_dict()
    assert doc["configuration"] == PAPER_CONFIGURATION.to_json_dict()
    assert doc["motion_parameters"] == {} and "motion_scores" not in doc
    for i, frame in enumerate(doc["frames"]):
        assert frame["points3"]["A"] == frame["A3"]
        assert frame["points3"]["B"] == frame["B3"]
        np.testing.assert_allclose(frame["A3"], translations(poses)[i])
        assert abs(np.linalg.norm(np.subtract(frame["B3"], frame["A3"])) - 100.0) < 1e-9

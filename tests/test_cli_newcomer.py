"""Slips a newcomer makes by accident: each is one line on stderr with exit status 2 from the
command, naming what to do, and a ``CurveReconError`` from the library."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from curverecon.cli import main
from curverecon.errors import CurveReconError
from curverecon.io import (
    MAX_FIELD_FOCAL_LENGTHS,
    MAX_IMAGE_COORDINATE,
    load_observations,
    observations_from_dict,
    observations_to_dict,
    read_json,
)
from curverecon.model.configuration import RigidObservations
from curverecon.simulate import make_scene, simulate_camera_configuration

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _command(capsys, *argv: str) -> str:
    """Run the command; assert exit 2 and one line on stderr; return that line."""
    status = main(list(argv))
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2, err
    assert len(err) == 1, err
    assert err[0].startswith("curverecon: error: ")
    return err[0]


def _paper_doc(seed: int = 0) -> dict:
    """A scene of the paper's own setting (A, B, tangents, polylines), by the 3-D construction."""
    scene = make_scene(np.random.default_rng(seed), 6, 0.5, 0.5, with_curve=True)
    return observations_to_dict(scene.observations)


def _scaled(doc: dict, factor: float) -> dict:
    """``doc`` with every image point and polyline point multiplied by ``factor``."""
    out = copy.deepcopy(doc)
    for frame in out["frames"]:
        for key in ("A", "B"):
            frame[key] = [factor * v for v in frame[key]]
        frame["curve"] = [[factor * x, factor * y] for x, y in frame["curve"]]
    return out


@pytest.mark.parametrize(
    "text",
    [
        '{"format": "curverecon.observations/1", "frames": [{"A": [1, 2], "B": [3, 4],}]}',
        '{"format": "curverecon.observations/1", "frames": [{"A": [1, 2], "B": [3, 4]},]}',
    ],
    ids=["object", "list"],
)
def test_a_trailing_comma_is_named(tmp_path, capsys, text):
    path = tmp_path / "obs.json"
    path.write_text(text)
    line = _command(capsys, "reconstruct", str(path), "-o", str(tmp_path / "out.json"))
    assert "malformed JSON" in line and "no comma before ] or }" in line
    with pytest.raises(CurveReconError, match="no comma before"):
        read_json(path)
    assert not (tmp_path / "out.json").exists()


def test_a_malformed_file_without_a_trailing_comma_gets_no_comma_hint(tmp_path):
    path = tmp_path / "obs.json"
    path.write_text('{"format": "curverecon.observations/1", "frames": [')
    with pytest.raises(CurveReconError, match="malformed JSON") as err:
        read_json(path)
    assert "comma" not in str(err.value)


KINDS = {
    "curverecon.reconstruction/1": "the answer `curverecon reconstruct` writes",
    "curverecon.truth/1": "simulate --truth",
    "curverecon.flat-views/1": "`curverecon match-flat`",
    "curverecon.matches/1": "the answer `curverecon match-flat` writes",
}


@pytest.mark.parametrize("fmt", sorted(KINDS))
def test_reconstruct_names_the_document_it_was_given(tmp_path, capsys, fmt):
    path = tmp_path / "doc.json"
    path.write_text(json.dumps({**_paper_doc(), "format": fmt}))
    line = _command(capsys, "reconstruct", str(path), "-o", str(tmp_path / "out.json"))
    assert "wrong format tag" in line and KINDS[fmt] in line
    with pytest.raises(CurveReconError, match="wrong format tag"):
        load_observations(path)


def test_match_flat_given_observations_points_to_reconstruct(tmp_path, capsys):
    path = tmp_path / "obs.json"
    path.write_text(json.dumps(_paper_doc()))
    line = _command(capsys, "match-flat", str(path), "-o", str(tmp_path / "m.json"))
    assert "curverecon.flat-views/1" in line and "`curverecon reconstruct`" in line


def test_the_real_outputs_are_refused_by_name(tmp_path, capsys):
    """A reconstruction the command wrote, fed back to it (the usual slip after a first run)."""
    scene = tmp_path / "scene.json"
    obs = make_scene(np.random.default_rng(1), 8, 0.5, 0.5).observations
    scene.write_text(json.dumps(observations_to_dict(obs)))
    rec, truth = tmp_path / "rec.json", tmp_path / "truth.json"
    assert main(["reconstruct", str(scene), "-o", str(rec), "--quiet"]) == 0
    assert main(["simulate", "-o", str(tmp_path / "s.json"), "--truth", str(truth)]) == 0
    capsys.readouterr()
    line = _command(capsys, "reconstruct", str(rec), "-o", str(tmp_path / "again.json"))
    assert "not its input" in line
    line = _command(capsys, "reconstruct", str(truth), "-o", str(tmp_path / "again.json"))
    assert "scene of `-o`" in line


def test_a_missing_relative_path_says_where_it_looked(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    line = _command(capsys, "reconstruct", "data/obs.json", "-o", "out.json")
    assert "cannot read data/obs.json" in line and f"looked in {tmp_path}" in line
    line = _command(capsys, "reconstruct", str(tmp_path / "obs.json"), "-o", "out.json")
    assert "cannot read" in line and "looked in" not in line  # an absolute path says it all


@pytest.mark.parametrize(
    "doc",
    [
        {"format": "curverecon.observations/1", "frames": []},
        {"format": "curverecon.observations/1", "motion": "fixed-axis", "frames": []},
        {
            "format": "curverecon.observations/1",
            "projection": "perspective",
            "camera": {"focal_px": 800, "principal_point": [320, 240]},
            "frames": [],
        },
    ],
    ids=["paper", "fixed-axis", "perspective"],
)
def test_an_empty_frames_list(tmp_path, capsys, doc):
    path = tmp_path / "obs.json"
    path.write_text(json.dumps(doc))
    line = _command(capsys, "reconstruct", str(path), "-o", str(tmp_path / "out.json"))
    assert '"frames" is empty' in line
    with pytest.raises(CurveReconError, match='"frames" is empty'):
        observations_from_dict(doc)


def test_huge_coordinates_under_orthographic_projection(tmp_path, capsys):
    """A scene in pixels scaled a million times (points in the wrong units) is refused; scaled a
    thousand times (coordinates up to some 1e5) it still reads, every point where it was."""
    doc = _paper_doc()
    big = _scaled(doc, 1e6)
    path = tmp_path / "big.json"
    path.write_text(json.dumps(big))
    line = _command(capsys, "reconstruct", str(path), "-o", str(tmp_path / "out.json"))
    assert "frame 0: an image coordinate of" in line and "pixels" in line
    with pytest.raises(CurveReconError, match="image coordinate"):
        observations_from_dict(big)
    larger = _scaled(doc, 1e3)
    largest = max(abs(v) for f in larger["frames"] for p in f["curve"] for v in p)
    assert 1e4 < largest < MAX_IMAGE_COORDINATE
    obs = observations_from_dict(larger)
    np.testing.assert_allclose(obs.a, 1e3 * np.array([f["A"] for f in doc["frames"]]))


def _normalised(doc: dict, camera: dict) -> dict:
    """``doc``'s points and camera in normalised image coordinates (focal length 1, principal
    point at the origin): the same rays."""
    f, (cx, cy) = camera["focal_px"], camera["principal_point"]
    out = copy.deepcopy(doc)
    out["camera"] = {"focal_px": 1.0, "principal_point": [0.0, 0.0]}
    for frame in out["frames"]:
        for key in ("A", "B"):
            frame[key] = [(frame[key][0] - cx) / f, (frame[key][1] - cy) / f]
        for name, p in frame.get("points", {}).items():
            frame["points"][name] = [(p[0] - cx) / f, (p[1] - cy) / f]
    return out


def test_pixel_points_with_a_normalised_camera(tmp_path, capsys):
    """A camera in normalised units (focal_px 1) with the points left in pixels: rays 89.8
    degrees off the axis.  Refused; the same rays with the points normalised too read."""
    doc, _ = simulate_camera_configuration("perspective", "free", "ABCD", 4, 5)
    camera = doc["camera"]
    normalised = _normalised(doc, camera)
    obs = observations_from_dict(normalised)
    assert isinstance(obs, RigidObservations)
    rays = np.concatenate([obs.points, np.ones(obs.points.shape[:-1] + (1,))], axis=-1)
    pixels = observations_from_dict(doc).points
    cx, cy = camera["principal_point"]
    np.testing.assert_allclose(rays[..., 0] * camera["focal_px"] + cx, pixels[..., 0])
    np.testing.assert_allclose(rays[..., 1] * camera["focal_px"] + cy, pixels[..., 1])
    mixed = {**doc, "camera": normalised["camera"]}
    path = tmp_path / "mixed.json"
    path.write_text(json.dumps(mixed))
    line = _command(capsys, "reconstruct", str(path), "-o", str(tmp_path / "out.json"))
    assert "focal lengths from the principal point" in line and "units" in line
    with pytest.raises(CurveReconError, match="focal lengths"):
        observations_from_dict(mixed)


def test_a_stereo_camera_in_other_units_is_named(tmp_path):
    doc, _ = simulate_camera_configuration("stereo", "free", "AB", 1, 3)
    observations_from_dict(doc)
    wrong = copy.deepcopy(doc)
    wrong["cameras"][1]["focal_px"] = 800.0 / (2 * MAX_FIELD_FOCAL_LENGTHS * 100)
    with pytest.raises(CurveReconError, match="camera 1: frame 0: an image point"):
        observations_from_dict(wrong)


def test_the_bundled_examples_still_read():
    for name in ("wire.json",):
        obs = load_observations(EXAMPLES / name)
        assert len(obs.a) == 20


def _camera_scene(size: float, frames: int = 3):
    """A curve ``size`` across, 2 units before an 800 px camera, turned a little per frame:
    the observations (pixels by the pinhole formula) and a Reconstruction holding the truth."""
    from curverecon.model.configuration import Configuration
    from curverecon.model.reconstruction import Reconstruction
    from curverecon.solvers.camera import Camera

    u = np.linspace(0.0, 1.0, 40)
    curve = size * np.column_stack([u - 0.5, 0.3 * np.sin(3 * u), 0.2 * u**2]) + [0, 0, 2.0]
    poses, moved = [], []
    for f in range(frames):
        a = 0.3 * f
        rot = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
        tr = curve.mean(axis=0) - rot @ curve.mean(axis=0)
        poses.append(np.column_stack([rot, tr]))
        moved.append(curve @ rot.T + tr)
    moved = np.array(moved)
    pixels = 800.0 * moved[..., :2] / moved[..., 2:] + [320.0, 240.0]
    cfg = Configuration("perspective", "free", ("A", "B"), False, camera=Camera(800.0, (320, 240)))
    obs = RigidObservations(cfg, np.arange(float(frames)), pixels[:, [0, -1]], None, list(pixels))
    rec = Reconstruction(
        shape=np.full(4, np.nan),
        poses=np.full((frames, 5), np.nan),
        std=None,
        inliers=np.ones(frames, dtype=bool),
        curve3d=curve,
        points3=[{"A": m[0].tolist(), "B": m[-1].tolist()} for m in moved],
        frame_poses=np.array(poses),
        configuration=cfg.to_json_dict(),
    )
    return rec, obs


def test_a_small_curve_among_the_cameras_is_also_drawn_enlarged(tmp_path):
    """A body a fortieth of its distance across is a dot beside the frustums: the figure adds
    the curve enlarged; a body as large as its distance needs no enlargement."""
    from curverecon.plot import _needs_zoom, plot_camera_file

    small, obs = _camera_scene(0.05)
    assert _needs_zoom(small, obs)
    large, obs_large = _camera_scene(2.0)
    assert not _needs_zoom(large, obs_large)
    path = tmp_path / "small.png"
    plot_camera_file(str(path), small, obs)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_stereo_scene_with_polylines_answers_the_angles():
    """The contract leaves alpha, beta, phi null only where neither tangents nor curves were
    given: with polylines in both views they come from the curve's end tangents (noise-free
    stereo scene, against the simulated body's angles)."""
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct

    doc, truth = simulate_camera_configuration("stereo", "free", "AB", 6, 2, with_curve=True)
    rec = reconstruct(observations_from_dict(doc), options=ReconstructOptions(progress=False))
    out = rec.to_json_dict()
    assert out["c"] == pytest.approx(truth["c"], rel=1e-6)
    for key in ("alpha_deg", "beta_deg", "phi_deg"):
        assert out[key] is not None
        assert abs(out[key] - truth[key]) < 3.0, (key, out[key], truth[key])
    assert any("end tangents" in w and "no std" in w for w in out["warnings"])


def test_a_curve_that_does_not_fit_a_rows_poses_leaves_the_points_answer(monkeypatch):
    """``--motion auto`` on a freely moving body seen by one camera with A, B and polylines
    chooses among the rows the points allow; when the polylines fit none of the chosen row's
    poses the answer is the row's points with a warning naming --motion free, not an error."""
    import curverecon.curve.pinhole as pinhole
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct

    def refuse(*args, **kwargs):
        raise CurveReconError("pinhole curve bundle: the start is not valid (behind the camera)")

    monkeypatch.setattr(pinhole, "curve_on_pinhole_poses", refuse)
    doc, truth = simulate_camera_configuration(
        "perspective", "uniform-rotation", "AB", 6, 4, with_curve=True
    )
    rec = reconstruct(observations_from_dict(doc), options=ReconstructOptions(progress=False))
    assert rec.curve3d is None
    assert rec.c == pytest.approx(truth["c"], rel=1e-6)
    assert any("--motion free" in w and "behind the camera" in w for w in rec.warnings)


def test_a_video_given_to_reconstruct_points_to_trace(tmp_path, capsys):
    video = EXAMPLES / "trace" / "sequence.mp4"
    line = _command(capsys, "reconstruct", str(video), "-o", str(tmp_path / "out.json"))
    assert "not UTF-8 text" in line and "`curverecon trace`" in line
    with pytest.raises(CurveReconError, match="curverecon trace"):
        read_json(video)


def test_observations_given_to_trace_point_to_reconstruct(tmp_path, capsys):
    line = _command(capsys, "trace", str(EXAMPLES / "wire.json"), "-o", str(tmp_path / "o.json"))
    assert "wire.json" in line and "`curverecon reconstruct`" in line
    assert not (tmp_path / "o.json").exists()


def test_the_camera_figure_names_the_motion_auto_chose(tmp_path, monkeypatch):
    from dataclasses import replace

    from matplotlib.figure import Figure

    from curverecon.plot import plot_camera_file

    rec, obs = _camera_scene(0.05)
    obs = replace(obs, configuration=replace(obs.configuration, motion="auto"))
    rec.configuration = {**rec.configuration, "motion": "fixed-axis"}
    titles = []
    real = Figure.savefig
    monkeypatch.setattr(
        Figure,
        "savefig",
        lambda fig, *a, **k: titles.append(fig._suptitle.get_text()) or real(fig, *a, **k),
    )
    plot_camera_file(str(tmp_path / "auto.png"), rec, obs)
    assert titles and "motion fixed-axis" in titles[0] and "auto" not in titles[0]


def test_a_byte_order_mark_is_read_as_without_it(tmp_path):
    """A JSON file saved by an editor that writes a UTF-8 byte-order mark reads as the same
    document without it."""
    path = tmp_path / "bom.json"
    path.write_bytes(b"\xef\xbb\xbf" + (EXAMPLES / "wire.json").read_bytes())
    assert read_json(path) == read_json(EXAMPLES / "wire.json")


@pytest.mark.parametrize("command", ["reconstruct", "match-flat"])
def test_an_output_that_would_overwrite_the_input_is_refused(
    tmp_path, capsys, monkeypatch, command
):
    path = tmp_path / "obs.json"
    text = json.dumps(_paper_doc())
    path.write_text(text)
    monkeypatch.chdir(tmp_path)
    line = _command(capsys, command, "obs.json", "-o", str(path))
    assert "would overwrite the input" in line
    assert path.read_text() == text


@pytest.mark.parametrize(
    "projection, points, curve",
    [("perspective", "AB", True), ("perspective", "ABCD", True), ("stereo", "AB", True)],
)
def test_the_slow_camera_curve_note_matches_the_route(monkeypatch, projection, points, curve):
    """The terminal note before the pinhole curve bundle is said exactly for the documents the
    pipeline sends there."""
    import curverecon.curve.pinhole as pinhole
    from curverecon.cli import _slow_camera_curve
    from curverecon.pipeline import reconstruct

    class Routed(Exception):
        pass

    def routed(*args, **kwargs):
        raise Routed

    monkeypatch.setattr(pinhole, "reconstruct_perspective_curve", routed)
    doc, _ = simulate_camera_configuration(projection, "free", points, 5, 1, with_curve=curve)
    obs = observations_from_dict(doc)
    sent = False
    try:
        reconstruct(obs)
    except Routed:
        sent = True
    assert _slow_camera_curve(obs) == sent
    assert sent == (projection == "perspective" and points == "AB")

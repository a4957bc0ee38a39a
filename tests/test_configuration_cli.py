"""The other rows of the Section 2 table through the command: reading the new keys, every input
check (exit 2, one line), ``--motion`` overriding the document, ``simulate --motion``, the plot."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from curverecon.cli import MOTIONS, SIMULATED_MOTIONS, main
from curverecon.errors import CurveReconError
from curverecon.io import load_observations, observations_from_dict, observations_to_dict
from curverecon.model.configuration import (
    FITTED_MOTIONS,
    Configuration,
    RigidObservations,
    in_plane_motion,
)
from curverecon.model.observations import Observations
from curverecon.simulate import CAMERA_MOTIONS, CONFIG_MOTIONS, make_scene, simulate_configuration


def _scene(motion="fixed-axis", points="AB", frames=8, **kw) -> dict:
    doc, _ = simulate_configuration(motion, points, frames=frames, seed=3, noise_px=0.5, **kw)
    return doc


def _refused(tmp_path, capsys, doc, *extra: str) -> str:
    """Run ``curverecon reconstruct`` on ``doc``: exit 2 and one line on stderr, returned."""
    inp = tmp_path / "in.json"
    inp.write_text(doc if isinstance(doc, str) else json.dumps(doc))
    code = main(["reconstruct", str(inp), "-o", str(tmp_path / "out.json"), "--quiet", *extra])
    err = capsys.readouterr().err
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("curverecon: error: "), err
    assert "Traceback" not in err
    return lines[0]


def test_a_configuration_reads_as_rigid_observations():
    doc = _scene("force-field", "ABC", frames=10, tangent_noise_deg=1.0, with_curve=True)
    obs = observations_from_dict(doc)
    assert isinstance(obs, RigidObservations)
    assert obs.configuration == Configuration("orthographic", "force-field", ("A", "B", "C"), True)
    assert obs.points.shape == (10, 3, 2) and obs.tangents.shape == (10, 2, 2)
    assert len(obs.curves) == 10
    np.testing.assert_array_equal(obs.times, [f["t"] for f in doc["frames"]])
    np.testing.assert_array_equal(obs.point("C"), [f["points"]["C"] for f in doc["frames"]])
    again = observations_from_dict(observations_to_dict(obs))
    np.testing.assert_array_equal(again.points, obs.points)
    assert again.configuration == obs.configuration


def test_defaults_and_partial_keys():
    doc = _scene("fixed-axis", "AB", frames=6, tangent_noise_deg=1.0, with_curve=True)
    for f in doc["frames"]:
        f.pop("t")
    doc["frames"][2].pop("tangent_B")
    doc["frames"][4].pop("curve")
    obs = observations_from_dict(doc)
    np.testing.assert_array_equal(obs.times, np.arange(6.0))  # time defaults to the index
    assert obs.tangents is None and not obs.configuration.tangents and obs.curves is None
    assert any("tangents ignored" in w for w in obs.warnings)
    assert any("polylines ignored" in w for w in obs.warnings)


def test_traced_tangents_are_not_used_beside_their_polylines():
    doc = _scene("fixed-axis", "AB", frames=6, tangent_noise_deg=1.0, with_curve=True)
    assert observations_from_dict(doc).tangents is not None
    doc["tangents_from_curve"] = True
    obs = observations_from_dict(doc)
    assert obs.tangents is None and obs.curves is not None
    assert any("fitted to the polylines" in w for w in obs.warnings)


def test_the_paper_setting_reads_as_before():
    doc = observations_to_dict(make_scene(np.random.default_rng(0), 6, 0.5, 0.5).observations)
    plain = observations_from_dict(doc)
    doc["motion"] = "free"
    for i, f in enumerate(doc["frames"]):
        f["t"] = 0.5 * i
    explicit = observations_from_dict(doc)
    for obs in (plain, explicit):
        assert isinstance(obs, Observations)
        np.testing.assert_array_equal(obs.a, plain.a)
        np.testing.assert_array_equal(obs.tangent_b, plain.tangent_b)
    doc["motion"] = "auto"  # every model: the rigid stage decides
    assert isinstance(observations_from_dict(doc), RigidObservations)


def test_motion_option_overrides_the_document(tmp_path):
    path = tmp_path / "in.json"
    path.write_text(json.dumps(_scene("fixed-axis", "ABC")))
    assert load_observations(path).configuration.motion == "fixed-axis"
    assert load_observations(path, motion="auto").configuration.motion == "auto"
    doc = observations_to_dict(make_scene(np.random.default_rng(0), 6, 0.5, 0.5).observations)
    path.write_text(json.dumps(doc))
    obs = load_observations(path, motion="uniform-rotation")
    assert obs.configuration.motion == "uniform-rotation" and obs.configuration.tangents
    assert set(MOTIONS) == {*FITTED_MOTIONS, "auto"}
    assert set(SIMULATED_MOTIONS) == set(CAMERA_MOTIONS)  # rotation-free: camera scenes only


def _along_view(n: int = 8) -> dict:
    """Two points turning about the viewing direction (a turntable seen from above): the image
    distance |A'B'| never changes and the depth of AB is not determined."""
    doc = _scene("fixed-axis", "AB", frames=n)
    rng = np.random.default_rng(1)
    ab = np.array([120.0, 30.0])
    for k, f in enumerate(doc["frames"]):
        r = Rotation.from_rotvec([0.0, 0.0, 0.4 * k]).as_matrix()[:2, :2]
        f["A"] = (rng.uniform(-50, 50, 2)).tolist()
        f["B"] = (np.array(f["A"]) + r @ ab + rng.normal(scale=0.5, size=2)).tolist()
    return doc


def _set(doc: dict, key: str, value) -> dict:
    doc[key] = value
    return doc


def _frame(doc: dict, i: int, **changes) -> dict:
    doc["frames"][i].update(changes)
    return doc


def _alike() -> dict:
    doc = _scene("free", "ABC", frames=6)
    for f in doc["frames"][1:]:
        for k in ("A", "B"):
            f[k] = list(doc["frames"][0][k])
        f["points"] = dict(doc["frames"][0]["points"])
    return doc


def _drop_point(doc: dict) -> dict:
    doc["frames"][3]["points"].pop("C")
    return doc


def _no_tangents_anywhere() -> dict:
    doc = observations_to_dict(make_scene(np.random.default_rng(0), 6).observations)
    for f in doc["frames"]:
        f.pop("tangent_A")
        f.pop("tangent_B")
    return doc


REFUSED = {
    "too few frames (fixed axis)": (lambda: _scene("fixed-axis", frames=3), "needs at least 4"),
    "too few frames (free, three points)": (
        lambda: _scene("free", "ABC", frames=2),
        "needs at least 3",
    ),
    "too few points (free, A and B)": (
        lambda: _set(_scene("fixed-axis"), "motion", "free"),
        "free motion with only A and B and no tangents",
    ),
    "unknown motion": (lambda: _set(_scene(), "motion", "wobble"), 'unknown motion "wobble"'),
    "motion not a string": (lambda: _set(_scene(), "motion", 3), "unknown motion 3"),
    "times not increasing": (
        lambda: _frame(_scene(), 4, t=2.5),
        "frame 4: times are not increasing",
    ),
    "times not finite": (
        lambda: json.dumps(_scene()).replace('"t": 5.0', '"t": 1e999'),
        'frame 5: "t" is not finite',
    ),
    "time not a number": (lambda: _frame(_scene(), 1, t="1"), 'frame 1: "t" must be a number'),
    "time missing in a frame": (
        lambda: _scene() | {"frames": _t_missing()},
        'frame 2: missing key "t"',
    ),
    "point missing in a frame": (
        lambda: _drop_point(_scene("free", "ABC")),
        'frame 3: point "C" missing',
    ),
    "point named A": (
        lambda: _frame(_scene("free", "ABC"), 1, points={"A": [1.0, 2.0], "C": [3.0, 4.0]}),
        'frame 1: "points" names "A"',
    ),
    "point not [x, y]": (
        lambda: _frame(_scene("free", "ABC"), 2, points={"C": [1.0]}),
        'frame 2: point "C" must be [x, y]',
    ),
    "points not an object": (
        lambda: _frame(_scene("free", "ABC"), 0, points=[[1.0, 2.0]]),
        '"points" must be an object',
    ),
    "all frames alike": (_alike, "all frames alike"),
    "axis along the view (two points)": (_along_view, "no rotation out of the image plane"),
    "perspective without a camera": (
        lambda: _set(_scene(), "projection", "perspective"),
        'projection "perspective" needs "camera"',
    ),
    "unknown projection": (
        lambda: _set(_scene(), "projection", "fisheye"),
        'unknown projection "fisheye"',
    ),
    "ends not identified": (
        lambda: _set(_scene("free", "ABC"), "ends_identified", False),
        '"ends_identified": false is supported in the paper',
    ),
    "rotation-free": (
        lambda: _set(_scene("free", "ABC"), "motion", "rotation-free"),
        "rotation-free",
    ),
    "paper row without tangents": (_no_tangents_anywhere, 'give the motion ("motion"'),
}


def _t_missing() -> list:
    frames = _scene()["frames"]
    frames[2].pop("t")
    return frames


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_bad_configurations_exit_2_with_one_line(tmp_path, capsys, case):
    make, needle = REFUSED[case]
    line = _refused(tmp_path, capsys, make())
    assert needle in line


def test_linear_method_is_the_paper_row_only(tmp_path, capsys):
    line = _refused(tmp_path, capsys, _scene("free", "ABC"), "--method", "linear")
    assert "paper's linearisation" in line


def test_motion_option_reaches_the_checks(tmp_path, capsys):
    # three frames of three points: enough for free motion, too few for a fixed axis
    doc = _scene("free", "ABC", frames=3)
    line = _refused(tmp_path, capsys, doc, "--motion", "fixed-axis")
    assert "needs at least 4" in line


@pytest.mark.parametrize("motion, points", [("fixed-axis", "AB"), ("free", "ABC")])
def test_a_determined_configuration_passes_the_checks(motion, points):
    """A scene drawn by the 3-D construction passes every check (its frame count is enough)."""
    obs = observations_from_dict(_scene(motion, points, frames=6))
    obs.require_reconstructable(point_sigma=1.0)


def test_degeneracy_threshold_refuses_in_plane_motion_and_passes_scenes():
    """The measured figure behind DEGENERACY_QUANTILE on a smaller sample: in-plane motion at
    1 px refused at least 98 % of the time; every simulated scene of every row passes."""
    rng = np.random.default_rng(11)
    refused = 0
    for _ in range(200):
        body = rng.normal(scale=100.0, size=(2, 3))
        r0 = Rotation.random(random_state=rng).as_matrix()
        pts = np.array(
            [
                (body @ (Rotation.from_rotvec([0, 0, a]).as_matrix() @ r0).T)[:, :2]
                + rng.uniform(-100, 100, 2)
                for a in np.cumsum(rng.uniform(0, 0.6, 8))
            ]
        )
        pts = pts + rng.normal(scale=1.0, size=pts.shape)
        refused += in_plane_motion(pts, None, 1.0, 1.0) is not None
    assert refused >= 196
    for motion in CONFIG_MOTIONS:
        points = "ABC" if motion == "free" else "AB"
        for seed in range(50):
            doc, _ = simulate_configuration(motion, points, frames=4, seed=seed, noise_px=1.0)
            assert in_plane_motion(observations_from_dict(doc).points, None, 1.0, 1.0) is None


def test_reconstruct_dispatches_to_the_rigid_stage(monkeypatch):
    """``curverecon.reconstruct`` hands a configuration, checked, to reconstruct_rigid."""
    import sys
    import types

    from curverecon.pipeline import reconstruct

    seen = {}

    def fake(obs, options=None):
        seen["obs"], seen["options"] = obs, options
        return "answer"

    module = types.ModuleType("curverecon.rigid")
    module.reconstruct_rigid = fake
    monkeypatch.setitem(sys.modules, "curverecon.rigid", module)
    obs = observations_from_dict(_scene("free", "ABC"))
    assert reconstruct(obs, point_sigma=0.5) == "answer"
    assert seen["obs"] is obs and seen["options"].point_sigma == 0.5
    with pytest.raises(CurveReconError, match="needs at least 4"):
        reconstruct(obs.subset([0, 1, 2]).with_motion("fixed-axis"))


@pytest.mark.parametrize("motion, points", [("uniform-rotation", "AB"), ("free", "ABC")])
def test_simulate_command_writes_a_scene_and_its_truth(tmp_path, motion, points):
    out, truth = tmp_path / "scene.json", tmp_path / "truth.json"
    args = ["simulate", "--motion", motion, "--points", points, "--frames", "7", "--seed", "4"]
    args += ["--noise-px", "0.5", "--with-curve", "--tangents", "-o", str(out)]
    assert main([*args, "--truth", str(truth)]) == 0
    obs = load_observations(out)
    assert isinstance(obs, RigidObservations) and obs.n_frames == 7 and obs.curves is not None
    assert obs.configuration.points == tuple(points) and obs.configuration.tangents
    t = json.loads(truth.read_text())
    p3 = np.array([[f["points3"][k] for k in points] for f in t["frames"]])
    err = obs.points - p3[..., :2]
    assert 0.2 < np.sqrt(np.mean(err**2)) < 1.0  # the 0.5 px noise asked for
    doc, _ = simulate_configuration(
        motion, points, frames=7, seed=4, noise_px=0.5, tangent_noise_deg=0.0, with_curve=True
    )
    assert json.loads(out.read_text()) == json.loads(json.dumps(doc))


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--motion", "free", "--points", "AB"], "free motion with only A and B"),
        (["--motion", "fixed-axis", "--points", "AC"], 'must be "AB" followed'),
        (["--points", "ABC"], "--points needs --motion"),
        (["--tangents"], "--tangents needs --motion"),
        (["--motion", "fixed-axis", "--images", "x"], "--images draws the paper"),
        (["--motion", "fixed-axis", "--curve-noise", "-1"], "--curve-noise must be"),
        (["--motion", "spin"], "invalid choice"),
    ],
)
def test_simulate_bad_arguments(tmp_path, capsys, args, needle):
    code = main(["simulate", "-o", str(tmp_path / "s.json"), *args])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and needle in err


def test_plot_of_a_configuration(tmp_path):
    from curverecon.model.reconstruction import Reconstruction
    from curverecon.plot import plot_configuration_file

    doc, truth = simulate_configuration("fixed-axis", "ABC", frames=5, seed=1, with_curve=True)
    obs = observations_from_dict(doc)
    rec = Reconstruction(
        np.array([truth["c"], np.nan, np.nan, np.nan]),
        np.full((5, 5), np.nan),
        None,
        np.ones(5, bool),
        curve3d=np.array(truth["curve3d"]),
        points3=[f["points3"] for f in truth["frames"]],
    )
    path = tmp_path / "p.png"
    plot_configuration_file(str(path), rec, obs)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 10_000
    with pytest.raises(CurveReconError, match="no per-frame points"):
        plot_configuration_file(
            str(path), Reconstruction(rec.shape, rec.poses, None, rec.inliers), obs
        )


def test_the_command_writes_what_the_library_returns(tmp_path):
    """A configuration through ``curverecon reconstruct --plot`` and through
    ``curverecon.reconstruct``: the same document, with the configuration's keys."""
    from curverecon.io import write_json
    from curverecon.pipeline import reconstruct

    doc = _scene("fixed-axis", "ABC", frames=8, with_curve=True)
    inp, out, png = tmp_path / "in.json", tmp_path / "out.json", tmp_path / "rec.png"
    inp.write_text(json.dumps(doc))
    argv = ["reconstruct", str(inp), "-o", str(out), "--quiet", "--plot", str(png)]
    assert main(argv) == 0
    written = json.loads(out.read_text())
    write_json(tmp_path / "library.json", reconstruct(observations_from_dict(doc)).to_json_dict())
    assert json.loads((tmp_path / "library.json").read_text()) == written
    assert isinstance(written["alpha_deg"], float)  # from the curve (no tangents given)
    assert written["configuration"]["motion"] == "fixed-axis"
    assert written["configuration"]["points"] == ["A", "B", "C"]
    assert set(written["frames"][3]["points3"]) == {"A", "B", "C"}
    assert written["frames"][3]["points3"]["A"][2] == 0.0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

"""JSON input/output: contract keys, round trips and one-line errors."""

from __future__ import annotations

import json
import sys
import types

import numpy as np
import pytest

from curverecon.errors import CurveReconError
from curverecon.io import (
    load_observations,
    observations_from_dict,
    observations_to_dict,
    read_json,
    write_json,
)
from curverecon.simulate import make_scene


def _doc(n=5, seed=0):
    return observations_to_dict(make_scene(np.random.default_rng(seed), n).observations)


def test_round_trip(tmp_path):
    sc = make_scene(np.random.default_rng(1), 6, 1.0, 1.0, with_curve=True)
    path = tmp_path / "obs.json"
    write_json(path, observations_to_dict(sc.observations))
    obs = load_observations(path)
    assert np.allclose(obs.a, sc.observations.a) and np.allclose(
        obs.tangent_b, sc.observations.tangent_b
    )
    assert obs.curves is not None and len(obs.curves) == 6
    assert json.loads(path.read_text())["format"] == "curverecon.observations/1"


def test_tangents_from_curve_round_trips():
    doc = _doc()
    assert not observations_from_dict(doc).tangents_from_curve
    assert "tangents_from_curve" not in observations_to_dict(observations_from_dict(doc))
    doc["tangents_from_curve"] = True
    obs = observations_from_dict(doc)
    assert obs.tangents_from_curve and obs.subset([0, 1, 2, 3]).tangents_from_curve
    assert observations_to_dict(obs)["tangents_from_curve"] is True


@pytest.mark.parametrize(
    "mutate,needle",
    [
        (lambda d: d.update(format="curverecon.reconstruction/1"), "wrong format tag"),
        (lambda d: d.pop("format"), 'missing key "format"'),
        (lambda d: d.pop("frames"), 'missing key "frames"'),
        (lambda d: d["frames"][1].pop("B"), 'missing key "B"'),
        (lambda d: d["frames"][2].pop("tangent_A"), 'missing key "tangent_A"'),
        (lambda d: d["frames"][0].update(A=[1.0]), "frame 0: A must be [x, y]"),
        (lambda d: d["frames"][0].update(A=["x", 2]), "frame 0: A must be [x, y]"),
        (lambda d: d.update(projection="perspective"), 'needs "camera"'),
        (lambda d: d.update(frames={}), "must be a list"),
        (lambda d: d.update(tangents_from_curve="yes"), '"tangents_from_curve" must be'),
    ],
)
def test_bad_documents(mutate, needle):
    doc = _doc()
    mutate(doc)
    with pytest.raises(CurveReconError) as err:
        observations_from_dict(doc)
    assert needle in str(err.value) and "\n" not in str(err.value)


def test_malformed_and_non_finite_json(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "curverecon.observations/1", "frames": [')
    with pytest.raises(CurveReconError, match="malformed JSON"):
        read_json(bad)
    nan = tmp_path / "nan.json"
    nan.write_text(json.dumps(_doc()).replace('"A": [', '"A": [NaN, ', 1))
    with pytest.raises(CurveReconError, match="non-finite"):
        load_observations(nan)
    inf = tmp_path / "inf.json"
    inf.write_text(json.dumps(_doc()).replace('"B": [', '"B": [1e999, 0.0, ', 1))
    with pytest.raises(CurveReconError):
        load_observations(inf)
    with pytest.raises(CurveReconError, match="cannot read"):
        read_json(tmp_path / "missing.json")


def test_curve_without_tangents_uses_polyline_hook(monkeypatch):
    sc = make_scene(np.random.default_rng(2), 5, with_curve=True)
    doc = observations_to_dict(sc.observations)
    for f in doc["frames"]:
        del f["tangent_A"], f["tangent_B"], f["A"], f["B"]
    fake = types.ModuleType("curverecon.curve.polyline")
    calls = []

    def end_tangents(points):
        calls.append(len(points))
        p = np.asarray(points)
        return p[1] - p[0], p[-2] - p[-1]

    fake.end_tangents = end_tangents
    monkeypatch.setitem(sys.modules, "curverecon.curve.polyline", fake)
    obs = observations_from_dict(doc)
    assert len(calls) == 5
    assert np.allclose(obs.a, [c[0] for c in sc.observations.curves])
    assert np.allclose(obs.b, [c[-1] for c in sc.observations.curves])


def test_write_json_replaces_non_finite(tmp_path):
    path = tmp_path / "sub" / "x.json"
    write_json(path, {"a": float("nan"), "b": np.array([1.0, np.inf]), "c": np.bool_(True)})
    assert json.loads(path.read_text()) == {"a": None, "b": [1.0, None], "c": True}


def test_long_polyline_is_averaged_down_with_a_warning():
    """A frame whose polyline has 300,000 noisy points (a circle arc, the truth) loads as 1,000
    points that stay on the arc (closer than the raw points: each is a mean of ~300), its ends
    kept, and the loader says so."""
    from curverecon.io import MAX_POLYLINE_POINTS

    rng = np.random.default_rng(5)
    scene = make_scene(rng, 5, with_curve=True)
    doc = observations_to_dict(scene.observations)
    t = np.linspace(0.0, 2.0, 300_000)
    arc = np.column_stack([100 + 80 * np.cos(t), 50 + 80 * np.sin(t)])
    noisy = arc + rng.normal(0.0, 0.5, arc.shape)
    noisy[0], noisy[-1] = arc[0], arc[-1]
    doc["frames"][2]["curve"] = noisy.tolist()
    obs = observations_from_dict(doc)
    pts = obs.curves[2]
    assert len(pts) == MAX_POLYLINE_POINTS
    assert np.array_equal(pts[0], arc[0]) and np.array_equal(pts[-1], arc[-1])
    radial = np.abs(np.hypot(pts[:, 0] - 100, pts[:, 1] - 50) - 80)
    assert np.median(radial) < 0.05  # raw points: median 0.34 (0.674 sigma)
    assert len(obs.warnings) == 1 and "frames [2]" in obs.warnings[0]
    assert [len(c) for i, c in enumerate(obs.curves) if i != 2] == [
        len(c) for i, c in enumerate(scene.observations.curves) if i != 2
    ]

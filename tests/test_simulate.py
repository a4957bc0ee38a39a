"""The independent simulator: reproducible, geometric truth, noise, curves, outliers."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from curverecon import curve_families, simulate
from curverecon.cli import main
from curverecon.curve_families import FAMILIES
from curverecon.simulate import make_scene, shape_from_geometry


def test_simulator_is_independent_of_the_generated_model():
    for module in (simulate, curve_families):
        source = inspect.getsource(module)
        assert "generated" not in source.replace("generated modules", "")
        assert "delta" not in source.split('"""', 2)[2]  # no (delta, tau) parametrisation


def test_same_seed_same_scene():
    s1 = make_scene(np.random.default_rng(5), 7, 1.0, 1.0)
    s2 = make_scene(np.random.default_rng(5), 7, 1.0, 1.0)
    assert np.array_equal(s1.observations.a, s2.observations.a)
    assert np.array_equal(s1.observations.tangent_b, s2.observations.tangent_b)
    s3 = make_scene(np.random.default_rng(6), 7, 1.0, 1.0)
    assert not np.array_equal(s1.observations.a, s3.observations.a)


@pytest.mark.parametrize("alpha,beta,phi", [(0.3, 0.7, 2.0), (1.2, 0.4, 0.5), (0.8, 0.8, 3.0)])
def test_shape_from_geometry_inverts_the_canonical_construction(alpha, beta, phi):
    rng = np.random.default_rng(1)
    rot = simulate.Rotation.random(random_state=rng).as_matrix()
    a = np.array([3.0, -2.0, 5.0])
    b = a + rot @ np.array([7.0, 0.0, 0.0])
    tb = rot @ np.array([-np.cos(alpha), np.sin(alpha), 0.0])
    ta = rot @ np.array([np.cos(beta), np.sin(beta) * np.cos(phi), np.sin(beta) * np.sin(phi)])
    c, al, be, ph = shape_from_geometry(a, b, -2.0 * ta, 0.5 * tb)  # any length, either sign
    assert np.allclose([c, al, be, ph], [7.0, alpha, beta, phi], atol=1e-12)


def test_noise_free_scene_projects_the_truth():
    sc = make_scene(np.random.default_rng(2), 9)
    t = sc.truth
    assert np.allclose(sc.observations.a, t.A3[:, :2])
    assert np.allclose(sc.observations.b, t.B3[:, :2])
    assert np.allclose(t.A3[:, 2], 0.0)
    assert np.allclose(np.linalg.norm(t.B3 - t.A3, axis=1), t.c)
    assert 100.0 <= t.c <= 300.0
    assert np.radians(10) <= t.alpha <= np.radians(80) and 0 <= t.phi <= np.pi
    ta, tt = sc.observations.tangent_a, t.tangent_A3
    cross = ta[:, 0] * tt[:, 1] - ta[:, 1] * tt[:, 0]
    assert np.allclose(cross, 0.0, atol=1e-12)
    assert np.allclose(np.einsum("nij,nkj->nik", t.rotations, t.rotations), np.eye(3))


def test_noise_levels():
    sc = make_scene(np.random.default_rng(3), 400, point_sigma=2.0, tangent_sigma_deg=3.0)
    err = (sc.observations.a - sc.truth.A3[:, :2]).ravel()
    assert 1.8 < np.std(err) < 2.2
    ang = np.arctan2(sc.observations.tangent_a[:, 1], sc.observations.tangent_a[:, 0])
    true = np.arctan2(sc.truth.tangent_A3[:, 1], sc.truth.tangent_A3[:, 0])
    d = np.degrees(np.mod(ang - true + np.pi / 2, np.pi) - np.pi / 2)
    assert 2.7 < np.std(d) < 3.3


def test_curves_and_outliers():
    sc = make_scene(np.random.default_rng(4), 10, outlier_fraction=0.2, with_curve=True)
    assert sc.observations.curves is not None and len(sc.observations.curves) == 10
    for i, cur in enumerate(sc.observations.curves):
        assert 100 <= len(cur) <= 200
        assert np.allclose(cur[0], sc.observations.a[i]) and np.allclose(
            cur[-1], sc.observations.b[i]
        )
    assert sc.curve_3d.shape[1] == 3 and np.allclose(sc.curve_3d[0], sc.truth.A3[0])
    assert np.allclose(sc.curve_3d[-1], sc.truth.B3[0])
    assert (~sc.truth.inliers).sum() == 2


@pytest.mark.parametrize("family", FAMILIES)
def test_curve_families_are_consistent_3d_curves(family):
    """Each family's scene: the polyline runs from A' to B', leaves A' along the image tangent
    (to the curve's bend over one sample), the 3-D curve's chord is c and its end tangents give
    the truth's angles by the CONTRACT's construction."""
    scene = make_scene(
        np.random.default_rng(3), 5, with_curve=True, curve_family=family, n_curve_points=20000
    )
    obs, t = scene.observations, scene.truth
    lo, hi = np.radians([10.0, 80.0])
    assert lo <= t.alpha <= hi and lo <= t.beta <= hi
    curve = scene.curve_3d
    assert np.isclose(np.linalg.norm(curve[-1] - curve[0]), t.c, rtol=1e-9)
    assert np.allclose(curve[0], t.A3[0]) and np.allclose(curve[-1], t.B3[0], atol=1e-6)
    for i, poly in enumerate(obs.curves):
        assert np.allclose(poly[0], obs.a[i]) and np.allclose(poly[-1], obs.b[i], atol=1e-6)
        d = (poly[2] - poly[0]) / np.linalg.norm(poly[2] - poly[0])
        assert abs(d @ obs.tangent_a[i]) / np.linalg.norm(obs.tangent_a[i]) > 0.99
    c, alpha, beta, phi = shape_from_geometry(
        curve[0], curve[-1], curve[1] - curve[0], curve[-2] - curve[-1]
    )
    assert abs(c - t.c) < 1e-9 * t.c
    assert abs(alpha - t.alpha) < 0.01 and abs(beta - t.beta) < 0.01 and abs(phi - t.phi) < 0.01


def test_simulate_command_family(tmp_path):
    out = tmp_path / "s.json"
    assert main(["simulate", "-o", str(out), "--with-curve", "--family", "helix"]) == 0
    helix = out.read_text()
    assert main(["simulate", "-o", str(out), "--with-curve", "--family", "bezier"]) == 0
    assert out.read_text() != helix
    # the former name of the option draws the same scene
    assert main(["simulate", "-o", str(out), "--with-curve", "--curve-family", "helix"]) == 0
    assert out.read_text() == helix
    assert main(["simulate", "-o", str(out), "--with-curve", "--family", "spiral"]) == 2
    assert main(["simulate", "-o", str(out), "--with-curve", "--curve-family", "spiral"]) == 2


@pytest.mark.parametrize("family", ["wave", "loop"])
def test_a_rendered_only_family_is_refused_for_json_scenes(tmp_path, capsys, family):
    out = tmp_path / "s.json"
    assert main(["simulate", "-o", str(out), "--family", family]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("curverecon: error: --family " + family)
    assert "--images" in err[0] and not out.exists()


@pytest.mark.parametrize("family", ["clothoid", "fourier", "sharp-ends", "random"])
def test_a_json_only_family_is_refused_for_rendered_scenes(tmp_path, capsys, family):
    out, images = tmp_path / "s.json", tmp_path / "img"
    args = ["simulate", "-o", str(out), "--images", str(images), "--frames", "3"]
    assert main([*args, "--family", family]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("curverecon: error: --family " + family)
    assert not out.exists() and not images.exists()


def test_the_command_offers_every_family_either_scene_kind_draws():
    from curverecon.cli import FAMILIES, IMAGE_FAMILIES, OUTLIER_MODELS, SCENE_FAMILIES
    from curverecon.trace import render

    assert SCENE_FAMILIES == curve_families.FAMILIES
    assert IMAGE_FAMILIES == render.FAMILIES
    assert set(FAMILIES) == set(SCENE_FAMILIES) | set(IMAGE_FAMILIES)
    assert OUTLIER_MODELS == simulate.OUTLIER_MODELS


def _line_angle_error_deg(observed: np.ndarray, true3: np.ndarray) -> np.ndarray:
    """Angle (degrees, in [-90, 90)) between observed 2-D tangent lines and the projections of
    the true 3-D tangents (lines: either sign)."""
    ang = np.arctan2(observed[:, 1], observed[:, 0])
    true = np.arctan2(true3[:, 1], true3[:, 0])
    return np.degrees(np.mod(ang - true + np.pi / 2, np.pi) - np.pi / 2)


def test_random_outlier_model_replaces_both_tangents_of_outlier_frames_only():
    """outlier_model="random": against the projections of the true 3-D tangents, inlier frames'
    tangents are off by the noise alone, outlier frames' tangents at A and at B are off by
    independent uniformly distributed line angles; the end points keep their noise."""
    n, sigma = 400, 1.0
    sc = make_scene(
        np.random.default_rng(8),
        n,
        point_sigma=sigma,
        tangent_sigma_deg=sigma,
        outlier_fraction=0.3,
        outlier_model="random",
    )
    obs, t = sc.observations, sc.truth
    out = ~t.inliers
    assert out.sum() == 120
    da = _line_angle_error_deg(obs.tangent_a, t.tangent_A3)
    db = _line_angle_error_deg(obs.tangent_b, t.tangent_B3)
    assert np.max(np.abs(da[~out])) < 5 * sigma and np.max(np.abs(db[~out])) < 5 * sigma
    for d in (da[out], db[out]):
        # uniform on [-90, 90): mean |d| 45 (standard error 2.4), 94 % beyond 5 degrees
        assert 38.0 < np.mean(np.abs(d)) < 52.0
        assert np.mean(np.abs(d) > 5.0) > 0.85
    assert abs(np.corrcoef(da[out], db[out])[0, 1]) < 0.3  # independent at A and at B
    for p, p3 in ((obs.a, t.A3), (obs.b, t.B3)):
        assert np.max(np.abs(p - p3[:, :2])) < 5 * sigma


def test_outlier_models_reproducible_and_default_stream_unchanged():
    """Same seed, same scene under either model; the default ("gross") stream is the one the
    bench's robustness rows were measured on (values printed before "random" existed)."""
    kw = {"point_sigma": 1.0, "tangent_sigma_deg": 1.0, "outlier_fraction": 0.3}
    s1 = make_scene(np.random.default_rng(11), 20, **kw, outlier_model="random")
    s2 = make_scene(np.random.default_rng(11), 20, **kw, outlier_model="random")
    assert np.array_equal(s1.observations.tangent_a, s2.observations.tangent_a)
    assert np.array_equal(s1.observations.tangent_b, s2.observations.tangent_b)
    g = make_scene(np.random.default_rng(11), 20, **kw)
    out = np.flatnonzero(~g.truth.inliers)
    assert out.tolist() == [1, 2, 4, 5, 9, 14]
    expected = [[-0.75157734, -0.65964498], [0.14508451, -0.98941927]]
    assert np.allclose(g.observations.tangent_a[out[:2]], expected, atol=1e-8)
    with pytest.raises(ValueError, match="outlier_model"):
        make_scene(np.random.default_rng(11), 20, **kw, outlier_model="uniform")


def test_simulate_command_outlier_model(tmp_path):
    """``curverecon simulate --outlier-model random``: the truth lists the outlier frames, and
    their tangents are not the projected true ones."""
    import json

    out, truth = str(tmp_path / "s.json"), str(tmp_path / "t.json")
    args = ["simulate", "-o", out, "--truth", truth, "--outlier-fraction", "0.5", "--seed", "4"]
    assert main([*args, "--outlier-model", "random"]) == 0
    frames = json.loads(open(out).read())["frames"]
    t = json.loads(open(truth).read())
    assert len(t["outlier_frames"]) == 10
    for i, f in enumerate(frames):
        obs = np.array([f["tangent_A"], f["tangent_B"]])
        true3 = np.array([t["frames"][i]["tangent_A3"], t["frames"][i]["tangent_B3"]])
        d = np.abs(_line_angle_error_deg(obs, true3))
        assert (d.max() > 1e-6) == (i in t["outlier_frames"])
    assert main([*args, "--outlier-model", "uniform"]) == 2

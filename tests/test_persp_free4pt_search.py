"""The perspective free row's depth search (``curverecon.rigid.pinhole_search``) against the 3-D
construction: P3P against posed points, the search's best body on noise-free scenes, and the
whole row exact on scenes (seeds 8, 9, 10) whose weak-perspective starts alone land in a
wrong valley or a singular fit."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid, rigid_data
from curverecon.rigid.pinhole_search import depth_search, p3p
from curverecon.simulate import simulate_camera_configuration


def _truth_points(truth: dict, names: str) -> np.ndarray:
    return np.array([[fr["points3"][k] for k in names] for fr in truth["frames"]])


def test_p3p_lists_the_posed_points():
    rng = np.random.default_rng(11)
    body = rng.normal(size=(50, 3, 3))
    rots = Rotation.random(50, random_state=rng).as_matrix()
    shift = np.column_stack([rng.normal(size=(50, 2)), rng.uniform(8.0, 12.0, 50)])
    cam = np.einsum("kij,kpj->kpi", rots, body) + shift[:, None]
    rays = cam / cam[..., 2:]  # (x, y, 1): the depths are not given
    pts, valid = p3p(rays, body)
    err = np.max(np.abs(pts - cam[:, None]), axis=(2, 3))  # (50, 4)
    err = np.where(valid, err, np.inf)
    assert np.all(np.min(err, axis=1) < 1e-8 * np.max(np.abs(cam)))
    # every valid root keeps the body's side lengths
    sides = [(0, 1), (0, 2), (1, 2)]
    for i, j in sides:
        d_body = np.linalg.norm(body[:, i] - body[:, j], axis=-1)[:, None]
        d_pts = np.linalg.norm(pts[..., i, :] - pts[..., j, :], axis=-1)
        assert np.all(np.abs(d_pts - d_body)[valid] < 1e-5 * d_body.repeat(4, 1)[valid])


def test_p3p_of_collinear_points_has_no_valid_root():
    body = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    cam = body + np.array([0.0, 0.0, 10.0])
    rays = cam / cam[:, 2:]
    pts, valid = p3p(rays[None], body[None])
    assert not np.any(valid & ~np.all(np.isfinite(pts), axis=(-1, -2)))


@pytest.mark.parametrize("seed", [3, 10])
def test_search_finds_the_body_of_a_noise_free_scene(seed):
    doc, truth = simulate_camera_configuration("perspective", "free", "ABCD", 6, seed)
    obs = observations_from_dict(doc)
    data = rigid_data(obs, ReconstructOptions(point_sigma=1e-3))
    p3 = _truth_points(truth, "ABCD")
    best = depth_search(data)[0]
    np.testing.assert_allclose(best, p3, atol=1e-4 * float(np.max(np.abs(p3))))


@pytest.mark.parametrize("seed", [8, 9, 10])
def test_noise_free_scene_is_exact(seed):
    doc, truth = simulate_camera_configuration("perspective", "free", "ABCD", 6, seed)
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=1e-3))
    p3 = _truth_points(truth, "ABCD")
    got = np.array([[fr[k] for k in "ABCD"] for fr in rec.points3])
    np.testing.assert_allclose(got, p3, atol=1e-9 * float(np.max(np.abs(p3))))
    assert rec.c == pytest.approx(truth["c"], rel=1e-9)

"""Tests of curverecon.plot: the PNG is written, reprojection is consistent with the poses."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from curverecon.errors import CurveReconError
from curverecon.plot import (
    MAX_PANELS,
    _panel_frames,
    feature_polyline,
    plot_reconstruction,
    reproject,
)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _scene(n_frames: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    u = np.linspace(0, 1, 100)[:, None]
    ctrl = rng.uniform(-100, 100, (4, 3))
    ctrl -= ctrl[0]
    curve = (1 - u) ** 3 * ctrl[0] + 3 * u * (1 - u) ** 2 * ctrl[1]
    curve = curve + 3 * u**2 * (1 - u) * ctrl[2] + u**3 * ctrl[3]
    rots = Rotation.random(n_frames, random_state=rng).as_matrix()
    trans = np.column_stack([rng.uniform(100, 300, (n_frames, 2)), np.zeros(n_frames)])
    polys = [(curve @ r.T + t)[:, :2] for r, t in zip(rots, trans, strict=True)]
    curve0 = curve @ rots[0].T + trans[0]
    return polys, curve0, rots, trans


def test_reproject_matches_projection():
    polys, curve0, rots, trans = _scene(5)
    proj = reproject(curve0, rots, trans)
    assert proj.shape == (5, 100, 2)
    for i in range(5):
        np.testing.assert_allclose(proj[i], polys[i], atol=1e-9)


@pytest.mark.parametrize("n_frames, with_polylines", [(1, True), (6, True), (20, False)])
def test_png_written(tmp_path, n_frames, with_polylines):
    polys, curve0, rots, trans = _scene(n_frames)
    path = tmp_path / "rec.png"
    plot_reconstruction(str(path), polys if with_polylines else None, curve0, rots, trans)
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC
    assert len(data) > 10_000


def test_panel_selection():
    assert _panel_frames(5) == [0, 1, 2, 3, 4]
    sel = _panel_frames(40)
    assert len(sel) == MAX_PANELS and sel[0] == 0 and sel[-1] == 39


def test_bad_input(tmp_path):
    polys, curve0, rots, trans = _scene(3)
    path = str(tmp_path / "x.png")
    with pytest.raises(CurveReconError, match="curve3d"):
        plot_reconstruction(path, polys, curve0[:, :2], rots, trans)
    with pytest.raises(CurveReconError, match="rotations"):
        plot_reconstruction(path, polys, curve0, rots[:2], trans)
    with pytest.raises(CurveReconError, match="polylines"):
        plot_reconstruction(path, polys[:2], curve0, rots, trans)
    with pytest.raises(CurveReconError, match="cannot write"):
        plot_reconstruction(str(tmp_path / "no" / "dir" / "x.png"), polys, curve0, rots, trans)


def test_feature_polyline_geometry():
    a3, b3 = np.array([0.0, 0.0, 0.0]), np.array([30.0, 40.0, 0.0])  # |AB| = 50
    ta, tb = np.array([0.0, 0.0, 2.0]), np.array([-3.0, 0.0, 0.0])
    poly = feature_polyline(a3, b3, ta, tb)
    np.testing.assert_allclose(poly[1], a3)
    np.testing.assert_allclose(poly[2], b3)
    np.testing.assert_allclose(poly[0], [0.0, 0.0, 12.5])  # a quarter of |AB| along t_A
    np.testing.assert_allclose(poly[3], [30.0 - 12.5, 40.0, 0.0])


def test_cli_plot_without_polylines(tmp_path):
    """`reconstruct --plot` on frames without curves draws A, B and the tangents."""
    from curverecon.cli import main

    scene, out, png = tmp_path / "s.json", tmp_path / "r.json", tmp_path / "r.png"
    args = ["simulate", "-o", str(scene), "--frames", "8", "--seed", "3"]
    assert main(args) == 0
    assert main(["reconstruct", str(scene), "-o", str(out), "--plot", str(png)]) == 0
    assert png.read_bytes()[:8] == PNG_MAGIC

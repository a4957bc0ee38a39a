"""The perspective force field with A and B on scenes that determine it (the body turns 720-1080
degrees over 30 frames, ``simulate.FORCE_FIELD_TURN_DEG``): noise-free scenes come out exact.

The truth is ``simulate_camera_configuration``'s own 3-D construction (a curve's ends moved
rigidly about its wire's centroid on a 3-D parabola, seen by a pinhole); the reconstruction
knows only the pixels.  The search of ``rigid/pinhole_force_field.py`` finds the truth's basin
on most such scenes, not all (docs/accuracy.md): the seeds here are three it finds.
"""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.errors import CurveReconError
from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid
from curverecon.rigid.pinhole_force_field import search
from curverecon.simulate import simulate_camera_configuration


def _points(frames, names="AB") -> np.ndarray:
    return np.array([[f[k] for k in names] for f in frames])


@pytest.mark.parametrize("seed", [0, 2, 110459265])
def test_noise_free_determined_scene_is_exact(seed):
    """Every point of every frame within 1e-9 c of the simulated geometry (units of A's depth
    in frame 0, as the truth's).  Seed 110459265 (the bench's noise-free scene 0 of seed 1):
    c 7e-9 off with the search alone, a minimum of chi2 3.5e-7 px^2 (c 0.4 % off) with the
    frames' root pairs chosen again; exact once the settled candidates are walked along their
    weakest direction (``pinhole_branches.walk``)."""
    doc, truth = simulate_camera_configuration("perspective", "force-field", "AB", 30, seed)
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=1e-6))
    want = _points([f["points3"] for f in truth["frames"]])
    got = _points(rec.points3)
    assert np.max(np.abs(got - want)) <= 1e-9 * truth["c"]
    assert rec.c == pytest.approx(truth["c"], rel=1e-9)


def test_search_equation_vanishes_at_the_truth_only():
    """The search's per-frame equation (the depths eliminated) is zero at the simulated
    parabola and invariants and not when the mass centre moves by a tenth of c."""
    from curverecon.rigid.pinhole_force_field import _residuals

    doc, truth = simulate_camera_configuration("perspective", "force-field", "AB", 30, 0)
    cam = doc["camera"]
    pts = np.array([[f["A"], f["B"]] for f in doc["frames"]])
    u = (pts - np.asarray(cam["principal_point"])) / cam["focal_px"]
    t = np.array(truth["times"])
    mp = truth["motion_parameters"]
    g = np.array([mp["position"], mp["velocity"], mp["acceleration"]])
    centre = g[0] + g[1] * t[0] + g[2] * t[0] ** 2 / 2
    a = np.array(truth["frames"][0]["A3"]) - centre
    b = np.array(truth["frames"][0]["B3"]) - centre
    scale = 1.0 / g[0, 2]
    g, a, b = g * scale, a * scale, b * scale
    row = np.concatenate([g[0, :2], g[1], g[2], [a @ a, b @ b, a @ b]])
    assert np.max(np.abs(_residuals(u, t, row[None]))) < 1e-12
    moved = row.copy()
    moved[0] += 0.1 * truth["c"] * scale
    assert np.max(np.abs(_residuals(u, t, moved[None]))) > 1e-6
    assert len(search(u, t, count=2)) >= 1


def test_a_bad_turn_range_is_refused():
    with pytest.raises(CurveReconError, match="turn range"):
        simulate_camera_configuration("perspective", "force-field", "AB", 12, 0, turn_deg=(0, 10))
    with pytest.raises(CurveReconError, match="turn range"):
        simulate_camera_configuration("perspective", "force-field", "AB", 12, 0, turn_deg=(9, 3))


def test_the_force_field_scene_turns_as_asked():
    """The default force-field scene turns at least 720 degrees in all (the sum of its frame
    to frame rotation angles); the earlier range stays available."""

    def turned(doc_truth) -> float:
        rots = np.array([f["rotation"] for f in doc_truth[1]["frames"]])
        steps = np.einsum("fji,fjk->fik", rots[:-1], rots[1:])
        cos = np.clip((np.trace(steps, axis1=1, axis2=2) - 1) / 2, -1, 1)
        return float(np.degrees(np.sum(np.arccos(cos))))

    new = simulate_camera_configuration("perspective", "force-field", "AB", 30, 3)
    old = simulate_camera_configuration(
        "perspective", "force-field", "AB", 30, 3, turn_deg=(180.0, 300.0)
    )
    assert turned(new) >= 700.0
    assert turned(old) <= 450.0

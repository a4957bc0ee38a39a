"""Tangents under a pinhole: the model uses them (each tangent's image angle, generated in
``derivations/rigid_pinhole.py``), and where the points and tangents still leave every frame
as many unknowns as measurements the input is refused with one line."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from curverecon.errors import CurveReconError
from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid
from curverecon.simulate import simulate_camera_configuration

EXACT = ReconstructOptions(point_sigma=1e-6, tangent_sigma_deg=1e-6)


@pytest.mark.parametrize("motion,seed", [("rotation-free", 4), ("uniform-rotation", 4)])
def test_noise_free_tangents_give_the_shape(motion, seed):
    """A and B with their tangents, noise-free: c and the tangent angles alpha, beta, phi of
    the 3-D construction come back (the rotation-free row's two-frame samples carry the
    tangents too)."""
    doc, truth = simulate_camera_configuration(
        "perspective", motion, "AB", 8, seed, tangent_noise_deg=0.0
    )
    rec = reconstruct_rigid(observations_from_dict(doc), EXACT)
    assert rec.c == pytest.approx(truth["c"], rel=1e-6)
    got = np.degrees(rec.shape[1:])
    want = [truth["alpha_deg"], truth["beta_deg"], truth["phi_deg"]]
    np.testing.assert_allclose(got, want, atol=1e-4)


def test_noisy_rotation_free_tangents_are_fitted():
    """With noise the rotation-free row with tangents is fitted (it used to fail on a sample
    without tangent directions): c within 5 % of the truth at 1 px and 0.5 degrees."""
    doc, truth = simulate_camera_configuration(
        "perspective", "rotation-free", "AB", 12, 3, noise_px=1.0, tangent_noise_deg=0.5
    )
    opts = ReconstructOptions(point_sigma=1.0, tangent_sigma_deg=0.5)
    rec = reconstruct_rigid(observations_from_dict(doc), opts)
    assert rec.c == pytest.approx(truth["c"], rel=0.05)


def test_free_motion_with_two_points_and_tangents_is_refused(tmp_path):
    """Free motion, A and B with tangents, one pinhole: 6 measurements and 6 unknowns (a
    rotation, a position) a frame, never determined: the library raises, the command prints
    one line and exits 2."""
    doc, _ = simulate_camera_configuration(
        "perspective", "rotation-free", "AB", 6, 0, tangent_noise_deg=0.0
    )
    doc["motion"] = "free"
    with pytest.raises(CurveReconError, match="four points"):
        reconstruct_rigid(observations_from_dict(doc), EXACT)
    (tmp_path / "in.json").write_text(json.dumps(doc))
    run = subprocess.run(
        [sys.executable, "-m", "curverecon", "reconstruct", "in.json", "-o", "out.json"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert run.returncode == 2
    assert len(run.stderr.strip().splitlines()) == 1 and "tangents" in run.stderr


def test_a_fit_behind_the_camera_is_refused():
    """A pinhole sees X and -X alike: a fit with A behind the camera in frame 0 would give
    negative units (c < 0); the answer refuses it with one line."""
    from curverecon.rigid.pinhole_answer import answer_scale

    doc, _ = simulate_camera_configuration("perspective", "force-field", "AB", 12, 0)
    obs = observations_from_dict(doc)
    p3 = np.array([[[0.1, 0.0, 2.0], [0.3, 0.0, 2.1]]] * 12)
    assert answer_scale(obs, p3) == pytest.approx(0.5)
    with pytest.raises(CurveReconError, match="behind the camera"):
        answer_scale(obs, -p3)

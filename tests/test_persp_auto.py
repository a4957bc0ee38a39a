"""``--motion auto`` on perspective documents: the motion the scene was built with is chosen
among those the points determine under a pinhole, and every candidate is accounted for."""

from __future__ import annotations

import pytest

from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid
from curverecon.simulate import simulate_camera_configuration


@pytest.mark.parametrize(
    "motion,tangents", [("rotation-free", False), ("uniform-rotation", False), ("fixed-axis", True)]
)
def test_auto_chooses_the_simulated_motion(motion, tangents):
    """Eight frames, 0.5 px (and 0.5 degrees): the simulated motion wins the BIC; the force
    field, which needs 11 frames without tangents, is listed with its reason; free motion with
    A and B is no candidate under a pinhole (never determined), the fixed axis only with
    tangents (without, a frame's angle and position take all four of its measurements)."""
    doc, truth = simulate_camera_configuration(
        "perspective", motion, "AB", 8, 21, noise_px=0.5,
        tangent_noise_deg=0.5 if tangents else None,
    )  # fmt: skip
    doc["motion"] = "auto"
    opts = ReconstructOptions(point_sigma=0.5, tangent_sigma_deg=0.5)
    rec = reconstruct_rigid(observations_from_dict(doc), opts)
    scores = rec.motion_scores["scores"]
    assert rec.motion_scores["chosen"] == motion
    assert rec.configuration["motion"] == motion
    if not tangents:  # with tangents every frame measures two more: the force field is fitted
        assert scores["force-field"]["bic"] is None and "11" in scores["force-field"]["reason"]
    else:
        assert scores["force-field"]["bic"] > scores[motion]["bic"]
    assert "free" not in scores
    assert ("fixed-axis" in scores) == tangents
    assert rec.c == pytest.approx(truth["c"], rel=0.1)

"""``--motion auto`` on perspective documents: the motion the scene was built with is chosen
among those the points determine under a pinhole, and every candidate is accounted for."""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid
from curverecon.simulate import simulate_camera_configuration


@pytest.mark.parametrize(
    "motion,tangents", [("rotation-free", False), ("uniform-rotation", False), ("fixed-axis", True)]
)
def test_auto_chooses_the_simulated_motion(motion, tangents):
    """Eight frames, 0.5 px (and 0.5 degrees): the simulated motion is chosen; the force
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


def _auto(motion, names, frames, seed, noise=1.0):
    doc, truth = simulate_camera_configuration(
        "perspective", motion, names, frames, seed, noise_px=noise
    )
    doc["motion"] = "auto"
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=noise))
    tests = {(t["simple"], t["complex"]): t for t in rec.motion_scores["tests"]}
    return rec, truth, rec.motion_scores["scores"], tests


def test_a_fixed_axis_whose_angles_stray_from_uniform_is_read_as_one():
    """A, B, C turned about one axis by angles that stray up to 10 degrees from a uniform
    rate (20 frames, 1 px; ``bench.persp_auto``'s fixed-axis scene 10 of seed 0): BIC, which
    charges each of the 18 extra angles ln(120), preferred the uniform rotation; the nested
    likelihood-ratio test rejects it, and the fixed axis, fitted from the uniform rotation's
    optimum too, fits at least as well as the model it contains."""
    from curverecon.rigid.select import LEVEL

    rec, truth, scores, tests = _auto("fixed-axis", "ABC", 20, 688178419)
    angles = np.asarray(truth["motion_parameters"]["angle_deg"])
    frames = np.arange(len(angles))
    straying = angles - np.polyval(np.polyfit(frames, angles, 1), frames)
    assert np.abs(straying).max() > 5.0
    assert rec.motion_scores["chosen"] == "fixed-axis"
    assert scores["uniform-rotation"]["bic"] < scores["fixed-axis"]["bic"]
    assert tests[("uniform-rotation", "fixed-axis")]["p"] < LEVEL
    assert tests[("uniform-rotation", "fixed-axis")]["df"] == 18
    assert scores["fixed-axis"]["robust_chi2"] <= scores["uniform-rotation"]["robust_chi2"]
    assert rec.c == pytest.approx(truth["c"], rel=0.05)


def test_a_uniform_rotation_of_three_points_is_not_read_as_a_fixed_axis():
    """A, B, C at a uniform rate (10 frames, 1 px): the fixed axis, which contains it, fits
    no significantly better (p above the level), so the simpler model is the answer."""
    from curverecon.rigid.select import LEVEL

    rec, truth, scores, tests = _auto("uniform-rotation", "ABC", 10, 1)
    assert rec.motion_scores["chosen"] == "uniform-rotation"
    assert tests[("uniform-rotation", "fixed-axis")]["p"] > LEVEL
    assert tests[("rotation-free", "uniform-rotation")]["p"] < LEVEL
    assert rec.c == pytest.approx(truth["c"], rel=0.1)


def _candidate(chi2, k, n_local, threshold=10.0):
    from curverecon.rigid.select import Candidate

    return Candidate(np.asarray(chi2, float), threshold, k, n_local, 4 * len(chi2), lambda: None)


def test_choose_tests_nested_models_and_compares_the_rest_by_bic():
    """Ten frames.  A fixed axis (8 parameters more) that lowers chi2 by 12, below chi2(8)'s
    1 % point 20.1, leaves the uniform rotation the answer; one that lowers it by 30 is
    chosen.  The force field nests in neither: against the uniform rotation, the lower BIC
    (chi2 + k ln 40).  A frame both axis models leave out (chi2 at or above T) adds nothing to
    D and takes its angle out of df."""
    from curverecon.rigid.select import choose, likelihood_ratio

    uni = _candidate([3.0] * 10, 20, 3)
    close = _candidate([3.0] * 6 + [0.0] * 4, 28, 4)
    far = _candidate([0.0] * 10, 28, 4)
    ff = _candidate([3.0] * 10, 27, 6)
    assert choose({"uniform-rotation": uni, "fixed-axis": close})[0] == "uniform-rotation"
    assert choose({"uniform-rotation": uni, "fixed-axis": far})[0] == "fixed-axis"
    assert choose({"uniform-rotation": uni, "force-field": ff})[0] == "uniform-rotation"
    cheap = _candidate([2.0] * 10, 18, 6)
    assert choose({"uniform-rotation": uni, "force-field": cheap})[0] == "force-field"
    out = _candidate([3.0] * 9 + [50.0], 20, 3)
    out_c = _candidate([3.0] * 9 + [40.0], 28, 4)
    assert likelihood_ratio(out, out_c) == (0.0, 7)


def test_a_force_field_that_turns_two_turns_is_read_as_one():
    """A and B thrown and turning 720 degrees or more (30 frames, 1 px; ``bench.persp_auto``'s
    force-field scene 0 of seed 0): a uniform rotation no longer explains the frames.  The
    force field nests in no determined candidate (free motion needs four points), so no test
    names it: BIC decides between it and the uniform rotation, whose free translations it
    does not contain."""
    rec, truth, scores, tests = _auto("force-field", "AB", 30, 1184838978)
    assert rec.motion_scores["chosen"] == "force-field"
    assert scores["force-field"]["bic"] < scores["uniform-rotation"]["bic"]
    assert not any("force-field" in pair for pair in tests)
    assert rec.c == pytest.approx(truth["c"], rel=0.1)


def _auto_with_curves(motion, seed, frames):
    doc, truth = simulate_camera_configuration(
        "perspective", motion, "AB", frames, seed, noise_px=0.5, with_curve=True, distance=400
    )
    doc["motion"] = "auto"
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=0.5))
    tests = {(t["simple"], t["complex"]): t for t in rec.motion_scores["tests"]}
    return rec, truth, rec.motion_scores["scores"], tests


def test_a_freely_moving_body_with_polylines_is_read_by_the_curve_bundle():
    """One camera, A, B and a polyline in every frame (16 frames, 0.5 px, 400 units
    away), the body moving freely: the rigid motions fail their test against free motion,
    the curve bundle's saturated model on the points (every frame's A and B fitted exactly),
    so free motion is chosen and the ordinary camera's bundle answers with the curve.  (At 12
    frames the force field, determined from 11, has almost as many parameters as the points
    have measurements and passes its test: A and B alone cannot tell it from free motion.)"""
    from curverecon.rigid.select import LEVEL

    rec, truth, scores, tests = _auto_with_curves("free", 3, 16)
    assert rec.motion_scores["chosen"] == "free"
    assert rec.configuration["motion"] == "free"
    assert rec.estimator == "curve-bundle" and rec.curve3d is not None
    assert scores["free"]["robust_chi2"] == 0.0
    assert all(t["p"] < LEVEL for (s, c), t in tests.items() if c == "free")
    assert rec.c == pytest.approx(truth["c"], rel=0.1)


def test_a_rigid_motion_with_polylines_is_not_read_as_free():
    """The same camera and polylines (eight frames), the body turning uniformly: the uniform
    rotation passes its test against the curve bundle's free motion, so the bundle never runs."""
    from curverecon.rigid.select import LEVEL

    rec, truth, scores, tests = _auto_with_curves("uniform-rotation", 3, 8)
    assert rec.motion_scores["chosen"] == "uniform-rotation"
    assert rec.estimator == "ml"
    assert tests[("uniform-rotation", "free")]["p"] > LEVEL
    assert rec.c == pytest.approx(truth["c"], rel=0.1)


def test_a_force_field_fit_run_into_a_singular_motion_gives_way_to_a_determined_one():
    """A force field of A and B, 30 frames, 1 px (``bench.persp_auto``'s seed 1, scene 4): one
    start's fit runs into a motion whose Fisher information is singular a fraction of a chi2
    below the others'; the determined fit is kept, so the force field is not refused and is
    chosen, its c within three of its std of the simulated chord."""
    rec, truth, scores, _ = _auto("force-field", "AB", 30, 905065056)
    assert scores["force-field"]["bic"] is not None
    assert rec.motion_scores["chosen"] == "force-field"
    assert abs(rec.c - truth["c"]) < 3 * rec.std[0]

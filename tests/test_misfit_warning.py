"""A fit the stated point noise cannot explain says so (``rigid.answer.misfit_warning``,
``outlier_share_warning``): a stereo rig whose calibration is off by a small turn, or points
noisier than ``point_sigma`` (a high chi2, or many frames left out), against the same scenes
with the right rig and noise (the 3-D construction of ``simulate_camera_configuration``), which
carry no such warning."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid
from curverecon.simulate import simulate_camera_configuration


def _misfit(doc: dict, sigma: float) -> list[str]:
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=sigma))
    return [w for w in rec.warnings if w.startswith("chi2 ")]


def _turn_y(deg: float) -> np.ndarray:
    a = np.radians(deg)
    return np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])


def _turn_x(deg: float) -> np.ndarray:
    a = np.radians(deg)
    return np.array([[1.0, 0.0, 0.0], [0.0, np.cos(a), -np.sin(a)], [0.0, np.sin(a), np.cos(a)]])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_right_rig_and_noise_carry_no_misfit_warning(seed):
    doc, _ = simulate_camera_configuration("stereo", "free", "AB", 10, seed, noise_px=1.0)
    assert _misfit(doc, 1.0) == []


@pytest.mark.parametrize("seed", [0, 1])
def test_a_rig_turned_by_a_degree_is_reported(seed):
    doc, _ = simulate_camera_configuration("stereo", "free", "AB", 10, seed, noise_px=0.5)
    wrong = copy.deepcopy(doc)
    r = np.asarray(wrong["cameras"][1]["R"])
    # about the baseline's normal: the epipolar lines move by about 14 px at 800 px focal length
    wrong["cameras"][1]["R"] = (_turn_y(1.0) @ _turn_x(1.0) @ r).tolist()
    assert _misfit(doc, 0.5) == []
    (line,) = _misfit(wrong, 0.5)
    assert "degrees of freedom" in line and "\n" not in line


def test_points_noisier_than_stated_are_reported():
    doc, _ = simulate_camera_configuration("stereo", "free", "AB", 20, 0, noise_px=3.0)
    assert _misfit(doc, 3.0) == []
    assert len(_misfit(doc, 1.0)) == 1


@pytest.mark.parametrize("seed", [0, 2])
def test_many_frames_left_out_is_reported(seed):
    # three times the stated noise: the outlier test, in the stated units, drops 7 of 20 frames
    doc, _ = simulate_camera_configuration("perspective", "fixed-axis", "ABC", 20, seed, 3.0)
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=1.0))
    left_out = int(np.sum(~rec.inliers))
    assert left_out > 5
    assert [w for w in rec.warnings if "were left out" in w] == [
        f"{left_out} of 20 frames do not fit the model and were left out: if that many images "
        "are not bad, the points are noisier than --point-sigma says (raise it)"
    ]
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=3.0))
    assert int(np.sum(~rec.inliers)) <= 5
    assert not [w for w in rec.warnings if "were left out" in w]

"""The perspective force field's root pairs and valleys (``rigid/pinhole_branches.py``).

The truth is ``simulate_camera_configuration``'s own 3-D construction (A, B and the wire's
centroid G moved rigidly, G on a 3-D parabola, seen by a pinhole); the wrong root pair is built
here from that geometry: the other point where each ray meets the sphere about G.
"""

from __future__ import annotations

import numpy as np

from curverecon.io import observations_from_dict
from curverecon.options import ReconstructOptions
from curverecon.rigid import reconstruct_rigid, rigid_data
from curverecon.rigid.model import Layout
from curverecon.rigid.pinhole_branches import choose_pairs
from curverecon.rigid.pinhole_starts import state_from_points3
from curverecon.rigid.refinement import refine
from curverecon.rigid.starts import kabsch
from curverecon.simulate import simulate_camera_configuration

LAYOUT = Layout("force-field", ("A", "B"), False, "perspective")


def _truth(seed: int):
    doc, truth = simulate_camera_configuration("perspective", "force-field", "AB", 30, seed)
    data = rigid_data(observations_from_dict(doc), ReconstructOptions(point_sigma=1.0))
    p3 = np.array([[f["points3"][k] for k in "AB"] for f in truth["frames"]])
    rots = np.array([f["rotation"] for f in truth["frames"]])
    state = state_from_points3(LAYOUT, data, p3, rots)
    state.parabola[0, 2] = 1.0  # the gauge, exactly
    return data, state


def _far_root(x: np.ndarray, g: np.ndarray) -> np.ndarray:
    """The other point where the ray through x meets the sphere about g through x."""
    m = x / np.linalg.norm(x)
    return (2.0 * float(m @ g) - float(m @ x)) * m


def test_a_frame_on_the_wrong_root_pair_gets_its_own_back():
    """Frame 7 turned so that A and B sit at the rays' other crossings of their spheres about
    G (an exact pair of roots, not an exact frame): the pair choice returns its true rotation
    and a noise-free chi2; the other frames keep theirs."""
    data, state = _truth(0)
    fit = refine(LAYOUT, state, data, max_iter=5, covariance=False, fix_globals=True)
    assert fit.chi2 < 1e-12
    times = data.times
    f = 7
    g = state.parabola[0] + state.parabola[1] * times[f] + 0.5 * state.parabola[2] * times[f] ** 2
    a, b = state.rotations[f] @ state.body[0] + g, state.rotations[f] @ state.body[1] + g
    a2, b2 = _far_root(a, g), _far_root(b, g)
    body = np.stack([state.body[0], state.body[1], np.cross(state.body[0], state.body[1])])
    tri = np.stack([a2 - g, b2 - g, np.cross(a2 - g, b2 - g)])
    wrong = state.copy()
    wrong.rotations[f] = kabsch(body, tri[None])[0]
    bad = refine(LAYOUT, wrong, data, max_iter=30, covariance=False, fix_globals=True)
    assert bad.frame_chi2[f] > 1.0  # a local minimum of its own, pixels off
    moved, changed = choose_pairs(LAYOUT, data, bad.state, bad.frame_chi2)
    assert changed >= 1
    assert np.max(np.abs(moved.rotations[f] - state.rotations[f])) < 1e-6
    again = refine(LAYOUT, moved, data, max_iter=30, covariance=False, fix_globals=True)
    assert again.frame_chi2[f] < 1e-9


def test_valleys_of_near_equal_chi2_are_listed_and_the_std_reaches_the_truth():
    """At 1 px (the bench's accuracy scene 1 of seed 1) the likelihood has several valleys
    within a few units of chi2: the answer lists the others, each within 4 of its chi2, and
    its std, widened to reach them, covers the simulated chord within three of it."""
    doc, truth = simulate_camera_configuration(
        "perspective", "force-field", "AB", 30, 975003556, noise_px=1.0
    )
    rec = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions(point_sigma=1.0))
    assert len(rec.alternatives) >= 1
    for alt in rec.alternatives:
        assert 0.0 <= alt.chi2 - rec.chi2 <= 4.0
        assert abs(alt.shape[0] - rec.c) > 1e-3 * truth["c"]  # another valley, not the same
    assert abs(rec.c - truth["c"]) <= 3.0 * rec.std[0]
    assert any("alternative" in w.lower() for w in rec.warnings)

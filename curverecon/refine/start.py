"""Stage 2's start: one hypothesis (a shape, optionally poses) refined on all frames.

The hypotheses stage hands over a shape found on a subset of the frames; here every frame gets
its pose on its best branch of (10) for that shape (``solvers.pose`` / ``robust.search``'s
branch switching, shape fixed), and the shape and all poses are refined by maximum likelihood
(``refine.ml``).  Then, while that moves any frame, every frame is put on its best branch
for the refined shape (the frames still far off, chi2 above ``SearchOptions.rescue_chi2``,
re-solved from a grid of pose starts as well) and the fit is redone.  Every step is linear in
the number of frames.
"""

from __future__ import annotations

import numpy as np

from curverecon.model.observations import Observations, wrap_angle
from curverecon.model.pose import normalise
from curverecon.options import SearchOptions
from curverecon.refine.ml import RefineResult, refine_batch, standardised_residuals
from curverecon.robust.search import poses_from_branches, switch_branches

START_MAX_ITER = 60
"""Iteration limit of the refinement on all frames (as the search's own refinement)."""

OTHER_BRANCH_DELTA = np.radians(5.0)
"""Poses whose delta differs by more than this are on different branches (as
``robust.search.branch_alternatives`` counts them)."""

START_MIN_GAIN = 1.0
"""Another round only if the frames that changed branch lower chi2 by this much at the current
shape (with 100,000 frames some frame always changes between two branches that fit alike, and
every round cost a refit on all frames; a gain below 1 moves the shape by a fraction of its
standard deviation)."""

START_REL_GAIN = 1e-4
"""... or this fraction of chi2, if less (nearly noise-free data: every gain counts)."""

START_SWITCH_CHI2 = 4.0
"""After the first round only frames whose chi2 exceeds this (or ten times the median frame's,
if less: nearly noise-free data) are tried on their other branches: a switch to a branch that
fits better by less cannot move the shape much, and trying every frame's four branches cost
about 10 s per round at 100,000 frames."""

START_ROUNDS = 4
"""Rounds of branch switching and refinement at most: a start a few percent off the shape
(noise-free, 600 frames, c and the angles 2-3 % off) left half of the frames on the wrong
branch for the refined shape (chi2 46); two more rounds reached the exact fit."""


def refine_hypothesis(
    obs: Observations,
    shape: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    poses: np.ndarray | None = None,
    options: SearchOptions | None = None,
) -> RefineResult:
    """The maximum-likelihood fit on all frames of ``obs`` from one shape (4,) (and poses
    (N, 5), if given; else every frame's best branch of (10) for the shape).  The result's
    shape and poses are normalised (``model.pose.normalise``); no covariance."""
    o = options or SearchOptions()
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)
    meas = obs.measurements()
    g = np.asarray(shape, float)
    p = poses_from_branches(obs, g) if poses is None else np.asarray(poses, float)
    r = standardised_residuals(g, p, meas, w8)
    fc = np.sum(r * r, axis=1)
    chi2, iters, conv = np.inf, 0, False
    for k in range(START_ROUNDS):
        # every frame on its best branch of (10) for the current shape (after the first
        # round: with the frames still far off re-solved from a grid of starts too)
        if k == 0:
            p_sw = switch_branches(obs, g, p, w8, options=o)
        else:  # only the frames that fit worse than most can gain from another branch
            worse = np.flatnonzero(fc > min(START_SWITCH_CHI2, 10.0 * float(np.median(fc))))
            if worse.size == 0:
                break
            p_sw = np.array(p)
            p_sw[worse] = switch_branches(
                obs.subset(worse), g, p[worse], w8, rescue=True, options=o
            )
            moved = _other_branch(p_sw, p)
            if not moved.any():
                break
            rs = standardised_residuals(g, p_sw[moved], meas[moved], w8)
            gain = np.sum(fc[moved]) - np.sum(rs * rs)
            if gain < min(START_MIN_GAIN, START_REL_GAIN * chi2):
                break
        g2, p2, r2, chi22, it2, conv2 = refine_batch(
            meas, g[None], p_sw[None], point_sigma, tangent_sigma, max_iter=START_MAX_ITER
        )
        iters += int(it2[0])
        if not chi22[0] < chi2:
            break
        g, p, r, chi2, conv = g2[0], p2[0], r2[0], float(chi22[0]), bool(conv2[0])
        fc = np.sum(r * r, axis=1)
    shape_n, poses_n = normalise(g, p)
    return RefineResult(shape_n, poses_n, chi2, fc, r, None, iters, conv)


def _other_branch(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N,) whether poses ``a`` and ``b`` (N, 5) lie on different branches of (10): the other
    sign of tau, or delta more than ``OTHER_BRANCH_DELTA`` apart (the polishing of a pose on
    its own branch moves it by far less)."""
    flipped = np.sign(a[:, 1]) != np.sign(b[:, 1])
    return flipped | (np.abs(wrap_angle(a[:, 0] - b[:, 0])) > OTHER_BRANCH_DELTA)

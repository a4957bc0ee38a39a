"""Which end is A judged by a polyline (``curve.labels``, ``curve.labels_kernel``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.spatial.transform import Rotation

from curverecon.curve.labels_kernel import placement_mean_squares
from curverecon.model.observations import Observations
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import LabelOptions, ReconstructOptions
from curverecon.pipeline import reconstruct
from curverecon.robust.labels import exchange, reconstruct_any_labels
from curverecon.simulate import make_scene


def test_placement_sweep_is_the_brute_force_mean_of_nearest_distances():
    """The kernel's mean squares equal the nearest distances taken from the full distance
    tables of the projected curve and the polyline, placement by placement."""
    rng = np.random.default_rng(5)
    s = np.linspace(0.0, 1.0, 40)
    body = np.column_stack([150.0 * s, 30.0 * np.sin(4.0 * s), 12.0 * s * s])
    rots = Rotation.random(7, random_state=rng).as_matrix()
    origin = np.array([40.0, -15.0])
    poly = rng.uniform(-50.0, 200.0, (11, 2))
    dense = rng.uniform(-50.0, 200.0, (60, 2))
    got = placement_mean_squares(rots, body, origin, poly, dense, 3)
    for k, rot in enumerate(rots):
        proj = body @ rot[:2].T + origin
        there = np.linalg.norm(poly[:, None] - proj[None], axis=2).min(axis=1)
        back = np.linalg.norm(proj[::3, None] - dense[None], axis=2).min(axis=1)
        want = np.mean(np.concatenate([there, back]) ** 2)
        assert abs(got[k] - want) <= 1e-9 * want


def _relabelled(obs: Observations, share: float, seed: int) -> tuple[Observations, np.ndarray]:
    """``obs`` with a random ``share`` of its frames (never frame 0) relabelled, flagged
    ``ends_identified`` false, and the mask of those frames."""
    rng = np.random.default_rng(seed)
    n = obs.n_frames
    mask = np.zeros(n, bool)
    mask[rng.choice(np.arange(1, n), int(round(share * n)), replace=False)] = True
    return replace(exchange(obs, mask), ends_identified=False), mask


def _full_runs(obs: Observations, opts: ReconstructOptions) -> tuple[Reconstruction, int]:
    """The stage's answer and how many pipeline runs with the curve bundle it took."""
    full = []

    def run(o: Observations, op: ReconstructOptions) -> Reconstruction:
        full.append(op.curve.bundle)
        return reconstruct(o, options=op)

    rec = reconstruct_any_labels(obs, opts, run)
    return rec, sum(full)


def test_labels_the_quick_curve_leaves_wrong_are_settled_before_the_full_run():
    """16 frames with 0.5 px polylines, 40 % relabelled, where the label search's shape leaves
    frames labelled wrong that the quick curve cannot place: judged again at the end-point
    answer, the labels are the simulation's before the one full run (without that step the
    first full run meets frames labelled wrong and the pipeline runs again), and the curve is
    the consistent twin's."""
    sc = make_scene(np.random.default_rng(0), 16, 0.5, 0.5, with_curve=True)
    unordered, mask = _relabelled(sc.observations, 0.4, 4)
    rec, runs = _full_runs(unordered, ReconstructOptions())
    assert runs == 1
    assert np.array_equal(rec.ends_exchanged, mask)
    twin = reconstruct(sc.observations)
    assert rec.curve3d is not None and twin.curve3d is not None
    assert np.allclose(rec.curve3d, twin.curve3d, rtol=1e-6, atol=1e-6)
    never = ReconstructOptions(labels=LabelOptions(unsettled_fit=np.inf))
    _, runs_without = _full_runs(unordered, never)
    assert runs_without > 1

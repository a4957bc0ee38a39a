"""The numba per-frame pose iteration (refine/pose_kernel.py) and the generated scalar kernels
(generated/measurement_kernel.py) against the NumPy model and the simulator's 3-D truth."""

from __future__ import annotations

import numpy as np
import pytest
from curverecon.generated import measurement_kernel, measurement_model
from test_conventions import canonical_parameters

from curverecon.refine.ml import optimise_poses
from curverecon.simulate import make_scene


@pytest.fixture(scope="module")
def scene():
    return make_scene(np.random.default_rng(47), 300)


def test_scalar_kernels_equal_the_numpy_model():
    """Same derivation, two templates: every prediction and pose Jacobian entry agrees."""
    rng = np.random.default_rng(5)
    for _ in range(50):
        x = np.concatenate([[rng.uniform(50, 400)], rng.uniform(-3, 3, 5), rng.normal(0, 100, 3)])
        pred, _, jl = measurement_model.predict_with_jacobians(*x)
        p1, p2, jac = np.empty(6), np.empty(6), np.full((6, 5), np.nan)
        measurement_kernel.predict_frame(*x, p1)
        measurement_kernel.predict_frame_with_pose_jacobian(*x, p2, jac)
        assert np.allclose(p1, pred.reshape(6), rtol=1e-13, atol=1e-12)
        assert np.allclose(p2, pred.reshape(6), rtol=1e-13, atol=1e-12)
        assert np.allclose(jac, jl.reshape(6, 5), rtol=1e-12, atol=1e-12)


def test_poses_return_to_the_3d_truth(scene):
    """Noise-free frames, the true shape, every pose disturbed: the iteration returns to the
    pose of the 3-D construction (with halvings), and its residuals are the model's."""
    shape, truth = canonical_parameters(scene.truth)
    rng = np.random.default_rng(9)
    start = truth + rng.normal(0.0, [0.05, 0.05, 0.05, 2.0, 2.0], truth.shape)
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    meas = scene.observations.measurements()
    poses, resid = optimise_poses(shape, start, meas, w8, 30)
    # near the fold tau = 0 (B' = c cos tau is flat in tau) Gauss-Newton creeps: there the
    # fit is close, not exact, after 30 steps (two frames of 300, tau 0.01 and 0.16: chi2 6e-5
    # and 3e-4)
    clear = np.abs(truth[:, 1]) > 0.3
    assert clear.sum() > 200
    assert np.allclose(poses[clear], truth[clear], atol=1e-7)
    assert np.max(np.abs(resid[clear])) < 1e-6
    assert np.max(np.sum(resid * resid, axis=1)) < 1e-3
    # one shape per row gives the same as one shape for all
    rows, _ = optimise_poses(np.tile(shape, (len(start), 1)), start, meas, w8, 30)
    assert np.array_equal(rows, poses)


def test_no_step_is_taken_that_raises_a_frames_chi2(scene):
    """Each frame's chi2 never rises, and a non-finite frame stays where it was."""
    shape, truth = canonical_parameters(scene.truth)
    rng = np.random.default_rng(11)
    start = truth + rng.normal(0.0, [0.6, 0.6, 0.6, 20.0, 20.0], truth.shape)
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    meas = scene.observations.measurements().copy()
    meas[3, 0] = np.nan
    _, r0 = optimise_poses(shape, start, meas, w8, 0)
    poses, r1 = optimise_poses(shape, start, meas, w8, 3, halvings=0)
    f0, f1 = np.sum(r0 * r0, axis=1), np.sum(r1 * r1, axis=1)
    ok = np.isfinite(f0)
    assert np.all(f1[ok] <= f0[ok])
    assert np.array_equal(poses[3], start[3])
    assert (f1[ok] < f0[ok]).mean() > 0.5


def _chi2_in_child(args):
    shape, start, meas, w8 = args
    _, r = optimise_poses(shape, start, meas, w8, 5)
    return float(np.sum(r * r))


def test_a_forked_child_runs_the_frame_pool(scene):
    """The chunks' thread pool is used in the parent, then a forked worker uses its own (the
    parent's threads do not exist in a fork: a pool carried over waited forever)."""
    import multiprocessing

    from curverecon.refine import ml

    shape, truth = canonical_parameters(scene.truth)
    reps = ml.FRAME_CHUNK // len(truth) + 2  # more than one chunk
    start = np.tile(truth, (reps, 1)) + 0.01
    meas = np.tile(scene.observations.measurements(), (reps, 1))
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    here = _chi2_in_child((shape, start, meas, w8))
    with multiprocessing.get_context("fork").Pool(1) as pool:
        there = pool.apply_async(_chi2_in_child, ((shape, start, meas, w8),)).get(timeout=30)
    assert there == here


def test_chunks_mapped_from_inside_a_chunk_run_in_that_thread():
    """map_chunks called from one of its own workers does not wait on the pool (a deadlock
    when every worker waits so); the nested call's results are the same, in order."""
    from curverecon.refine import ml

    n = 3 * ml.FRAME_CHUNK

    def inner(c: slice) -> int:
        return c.start

    def outer(c: slice) -> list[int]:
        return ml.map_chunks(inner, n)

    expected = [c.start for c in ml.frame_chunks(n)]
    assert ml.map_chunks(outer, n) == [expected] * len(expected)

"""The pipeline's shortcuts: each must give the answer the full search gives.

- exact stage (``exact_stage_starts``): with at least 5 frames the best grid minima are
  searched first and an exact fit ends the search;
- restarts and single-frame branch flips are skipped once the best fit is exact
  (``SearchOptions.exact_cost``): nothing can beat it by the margin they require;
- with 4 frames every start fits exactly: the exact stage is not used and the other exact
  shapes are still reported as alternatives.
"""

from __future__ import annotations

import numpy as np
import pytest

import curverecon.refine.answer as answer_module
import curverecon.robust.branches as branches_module
import curverecon.robust.search as start_module
from curverecon.options import ReconstructOptions, SearchOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene

SEARCH = SearchOptions()
NO_EXACT_STAGE = ReconstructOptions(search=SearchOptions(exact_stage_min_frames=10**6))


def _rel_err(shape, truth):
    return np.max(np.abs(shape - truth) / np.array([truth[0], 1.0, 1.0, 1.0]))


def _count_polished(monkeypatch) -> list[int]:
    """Record the number of starts of every compass search (grid minima polished)."""
    sizes: list[int] = []
    orig = start_module.pattern_search

    def counting(terms, params, *args, **kwargs):
        sizes.append(len(params))
        return orig(terms, params, *args, **kwargs)

    monkeypatch.setattr(start_module, "pattern_search", counting)
    return sizes


def _count_batches(monkeypatch) -> list[int]:
    """Record the number of starts of every batched ML refinement of the search."""
    sizes: list[int] = []
    orig = start_module.refine_batch

    def counting(obs, shapes, *args, **kwargs):
        sizes.append(len(np.atleast_2d(shapes)))
        return orig(obs, shapes, *args, **kwargs)

    monkeypatch.setattr(start_module, "refine_batch", counting)
    return sizes


@pytest.mark.parametrize("seed", [4, 5])
def test_exact_stage_ends_the_search_with_the_exact_answer(monkeypatch, seed):
    sc = make_scene(np.random.default_rng(seed), 6)
    polished = _count_polished(monkeypatch)
    batches = _count_batches(monkeypatch)
    rec = reconstruct(sc.observations)
    assert _rel_err(rec.shape, sc.truth.shape) < 1e-9
    assert rec.chi2 < 1e-16
    # only the first grid minima were polished, and no restarts ran
    assert polished == [SEARCH.exact_stage_starts]
    assert max(batches) <= SEARCH.exact_stage_starts
    # the full search (exact stage off) gives the same shape
    full = reconstruct(sc.observations, options=NO_EXACT_STAGE)
    assert len(polished) == 2 and polished[1] > SEARCH.exact_stage_starts
    assert _rel_err(full.shape, rec.shape) < 1e-9


def test_noisy_scene_falls_through_the_exact_stage(monkeypatch):
    sc = make_scene(np.random.default_rng(11), 6, 1.0, 1.0)
    polished = _count_polished(monkeypatch)
    batches = _count_batches(monkeypatch)
    rec = reconstruct(sc.observations, point_sigma=1.0, tangent_sigma_deg=1.0)
    # the first minima, then the rest; the restarts ran (around each of 3 centres)
    assert len(polished) == 2 and polished[0] == SEARCH.exact_stage_starts
    assert max(batches) >= 3 * SEARCH.restarts_few
    full = reconstruct(sc.observations, point_sigma=1.0, options=NO_EXACT_STAGE)
    assert np.allclose(full.shape, rec.shape, rtol=1e-8, atol=1e-10)
    assert abs(full.chi2 - rec.chi2) < 1e-8 * (1 + rec.chi2)


def test_four_frames_skip_restarts_but_list_the_other_exact_shapes(monkeypatch):
    sc = make_scene(np.random.default_rng(1), 4)
    polished = _count_polished(monkeypatch)
    batches = _count_batches(monkeypatch)
    flips = []
    orig_flip = answer_module.branch_alternatives

    def counting_alternatives(*args, **kwargs):
        flips.append(1)
        return orig_flip(*args, **kwargs)

    monkeypatch.setattr(answer_module, "branch_alternatives", counting_alternatives)
    monkeypatch.setattr(branches_module, "branch_alternatives", counting_alternatives)
    rec = reconstruct(sc.observations)
    # the full grid search (no exact stage with 4 frames), but no restarts and no flips
    assert len(polished) == 1 and polished[0] > SEARCH.exact_stage_starts
    assert max(batches) < SEARCH.restarts_few
    assert len(flips) == 1  # the answer's own branch alternatives only
    assert rec.chi2 < 1e-16
    # several shapes fit exactly: they are reported, each an exact fit, one of them the truth
    assert len(rec.alternatives) >= 1
    assert all(alt.chi2 < 1e-12 for alt in rec.alternatives)
    shapes = [rec.shape] + [alt.shape for alt in rec.alternatives]
    assert min(_rel_err(s, sc.truth.shape) for s in shapes) < 1e-9
    # the same answer and alternatives as with the restarts forced (they cannot change anything)
    forced = reconstruct(
        sc.observations, options=ReconstructOptions(search=SearchOptions(exact_cost=-1.0))
    )
    assert max(batches) in (3 * SEARCH.restarts_few, 3 * SEARCH.restarts_implausible)
    assert _rel_err(forced.shape, rec.shape) < 1e-9
    assert len(forced.alternatives) == len(rec.alternatives)


@pytest.mark.parametrize(
    "index",
    [
        629,  # phi 0.6 deg, four frames with tau within 15 deg of 0 (a triple branch switch)
    ],
)
def test_bench_noise_free_scenes_that_used_to_miss_the_exact_fit(index):
    from bench.common import make, shape_errors, true_poses

    sc = make(20260521, "stability", (6, index), 6, chord=(100.0, 300.0))
    shape, _ = true_poses(sc)
    rec = reconstruct(sc.observations)
    assert np.max(np.abs(shape_errors(rec.shape, shape))) < 1e-9
    assert rec.chi2 < 1e-16


def test_gamma_grid_power():
    spec = start_module.GridSpec.for_frames(6)
    assert np.allclose(np.degrees(spec.gammas()), np.linspace(0.0, 80.0, 12))  # the default
    spec.gamma_power = 2.0
    g = np.degrees(spec.gammas())
    assert g[0] == 0.0 and abs(g[-1] - spec.gamma_max_deg) < 1e-12
    assert np.all(np.diff(g) > 0) and np.all(np.diff(np.diff(g)) > 0)  # packed near 0


def test_long_sequences_refine_one_candidate_per_basin_on_all_frames():
    """Above ``medium_frames`` the candidates screened on a few hundred frames are merged by
    basin (``medium_merge_distance``) before the refinement on all frames: those that go on are
    pairwise distinct (without merging, four identical ones are), and the answer is the one
    without merging (here)."""
    from curverecon.robust.search import robust_start, shape_distance

    # seed 20: without merging, four candidates of one basin (distance 0) go on to all frames
    sc = make_scene(np.random.default_rng(20), 1200, 1.0, 1.0)
    opts = SearchOptions(medium_frames=300)
    cands = robust_start(sc.observations, 1.0, np.radians(1.0), options=opts)
    shapes = [c.result.shape for c in cands]
    assert all(
        shape_distance(a, b) >= opts.medium_merge_distance
        for i, a in enumerate(shapes)
        for b in shapes[i + 1 :]
    )
    # the maximum-likelihood answers (the bias correction's simulation would magnify their
    # last digits)
    merged = reconstruct(sc.observations, options=ReconstructOptions(search=opts, estimator="ml"))
    unmerged = reconstruct(
        sc.observations,
        options=ReconstructOptions(
            search=SearchOptions(medium_frames=300, medium_merge_distance=0.0), estimator="ml"
        ),
    )
    assert _rel_err(merged.shape, unmerged.shape) < 1e-6

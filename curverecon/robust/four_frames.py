"""Exactly four frames: every shape that fits them, from the complete minimal solver.

Four frames determine the shape only up to a finite set: each real solution of the minimal
problem (:func:`curverecon.solvers.minimal.solve`) fits all four frames exactly, noise or not,
so the data cannot choose between them.  :func:`add_minimal_solutions` lists every one of them
that the answer does not already stand for among ``Reconstruction.alternatives`` (each with its
poses, chi2 and covariance), and says so in a warning.
"""

from __future__ import annotations

from dataclasses import replace

from curverecon.model.observations import Observations
from curverecon.model.pose import normalise
from curverecon.model.reconstruction import Alternative, Reconstruction, alternatives_warning
from curverecon.options import MinimalOptions
from curverecon.refine.ml import refine
from curverecon.robust.search import shape_distance
from curverecon.solvers import minimal

SAME_SHAPE = 1e-6
"""``shape_distance`` below which a minimal solution is the answer or an alternative already:
exact fits only (four-frame solutions can lie much closer together than the 0.02 that makes
two noisy fits one alternative)."""


def add_minimal_solutions(
    rec: Reconstruction,
    obs: Observations,
    point_sigma: float,
    tangent_sigma: float,
    options: MinimalOptions | None = None,
) -> Reconstruction:
    """``rec`` with every real minimal solution of its four frames among the alternatives."""
    result = minimal.solve(obs, options)
    known = [rec.shape] + [a.shape for a in rec.alternatives]
    added: list[Alternative] = []
    for shape, poses in zip(result.shapes, result.poses, strict=True):
        shape_n, poses_n = normalise(shape, poses)
        if any(shape_distance(shape_n, k) < SAME_SHAPE for k in known):
            continue
        fit = refine(obs, shape_n, poses_n, point_sigma, tangent_sigma, max_iter=0)
        added.append(Alternative(shape_n, poses_n, float(fit.chi2), fit.std))
        known.append(shape_n)
    alternatives = sorted(list(rec.alternatives) + added, key=lambda a: a.chi2)
    # the four-frame warning below replaces the search's count of equally good fits
    earlier = (
        alternatives_warning(rec.shape, rec.std, rec.alternatives) if rec.alternatives else None
    )
    warnings = [w for w in rec.warnings if w != earlier]
    n_shapes = 1 + len(alternatives)
    if n_shapes > 1:
        warnings.append(
            f"four frames: {n_shapes} shapes fit them (the answer and {len(alternatives)} "
            "alternatives, every real solution of the minimal problem); four frames cannot "
            "choose between them: add frames"
        )
    if result.n_failed_paths:
        warnings.append(
            f"the minimal solver lost {result.n_failed_paths} of {result.n_paths} solution "
            "paths after retries: a shape that fits may be missing from the alternatives"
        )
    return replace(rec, alternatives=alternatives, warnings=warnings)

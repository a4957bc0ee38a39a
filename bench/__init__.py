"""The curverecon benchmark (``make bench`` = ``python -m bench``; ``--quick`` for a tiny run).

Modules:

- ``config``: what runs (full and quick configurations, seeds, counts).
- ``common``: per-scene seeding, the true poses of a simulated scene, error metrics, the pool.
- ``accuracy``: RMSE / CRLB per parameter for the linearisation, the default pipeline and the
  refinement started at the truth, over a grid of noise levels and frame counts.
- ``robustness``: success without the truth, with outlier frames, and whether they were flagged.
- ``stability``: log10 error on noise-free scenes at (near-)minimal frame counts.
- ``speed``: derivation time, generated functions against sympy.lambdify, analytic against
  finite-difference refinement, reconstruction time against the number of frames.
- ``plan``: priority order under the time budget, per-scene costs (reported, never silent).
- ``report``: summaries, targets, plots, ``REPORT.md`` and ``report.json``.
"""

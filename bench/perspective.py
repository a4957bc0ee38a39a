"""Section ``perspective``: the perspective and stereo rows of the Section 2 table
(``bench.configurations_persp``: noise-free exactness, RMSE over the Cramer-Rao bound, std
coverage, outlier frames) and the ordinary camera beyond the table (``bench.persp_curve``: free
motion, A, B and polylines under a pinhole; the curve rate at a fifth of the distance and
against the distance, plotted in bench/persp_curve_vs_distance.png), and the stereo row's curve
with A, B and polylines (``bench.stereo_curve``).

``python -m bench --only perspective`` (about 10 minutes on 2 cores; more scenes: `python -m
bench.persp_curve --scenes N`); each module also runs
alone with its own seed (``python -m bench.configurations_persp --seed S``,
``python -m bench.persp_curve --seed S``).  The minimal solvers' keys of these rows come from
the configurations section (``bench.config_minimal_persp``).
"""

from __future__ import annotations

from bench import configurations_persp, persp_curve, stereo_curve

CURVE_SCENES = 12
"""Scenes of the ordinary camera at a fifth of the distance (the target's cell); 26 s a scene
(median, one core), so that ``make bench`` stays within 45 minutes on 2 cores."""

SWEEP_SCENES = 2
"""Scenes at each other distance of the sweep."""

STEREO_CURVE_SCENES = 20
"""Stereo scenes with A, B and polylines (20 frames, 0.5 px): about 4 s a scene on one core."""


def run(quick: bool = False) -> dict:
    out = configurations_persp.run(scale=0.1 if quick else 1.0)
    out.update(
        persp_curve.run(
            scenes=2 if quick else CURVE_SCENES,
            sweep_scenes=1 if quick else SWEEP_SCENES,
            workers=configurations_persp.WORKERS,
        )
    )
    out.update(
        stereo_curve.run(
            scenes=2 if quick else STEREO_CURVE_SCENES, workers=configurations_persp.WORKERS
        )
    )
    return out

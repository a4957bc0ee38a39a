"""Compile every numba kernel of the package once, so that the first reconstruction does not.

``python -m curverecon.warmup`` (``make setup`` and ``make demo`` run it after installing).

The package's kernels are compiled with ``cache=True``: numba writes the machine code to its
on-disk cache (``__pycache__`` beside the sources, or ``NUMBA_CACHE_DIR``) and later processes
load it instead of compiling.  A fresh install has an empty cache, so its first reconstruction
would spend minutes compiling.  The cache cannot be shipped with the sources: numba keys every
entry on the numba version, the source file's contents and the host CPU (name and features),
and keeps it under the sources' own path, so a cache built elsewhere is either ignored or not
found.  Numba's ahead-of-time compiler (``numba.pycc``) is deprecated.  Hence this step: it runs
the pipeline on small synthetic scenes that call every kernel, with the argument types the
pipeline uses, and reports any cached kernel that is still not compiled.

``curverecon.jit_cache`` keeps the cross-module stamps: the modules that define the kernels call
``drop_stale`` at import, as they do for any other process, so the warmed cache holds the code of
the current sources.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from collections.abc import Sequence
from typing import Any

KERNEL_MODULES = (
    "curverecon.solvers.homotopy",
    "curverecon.solvers.minimal",
    "curverecon.refine.pose_kernel",
    "curverecon.curve.section4_kernel",
    "curverecon.curve.bundle_kernel",
    "curverecon.curve.labels_kernel",
    "curverecon.generated.measurement_kernel",
    "curverecon.generated.minimal_unsquared_kernel",
    "curverecon.solvers.persp_uniform_rotation",
    "curverecon.solvers.persp_fixed_axis_3pt",
    "curverecon.generated.persp_uniform_rotation_kernel",
    "curverecon.generated.persp_fixed_axis_kernel",
)
"""Every module of the package that defines numba kernels."""

PERSPECTIVE_MODULES = (
    "curverecon.solvers.persp_uniform_rotation",
    "curverecon.solvers.persp_fixed_axis_3pt",
    "curverecon.generated.persp_uniform_rotation_kernel",
    "curverecon.generated.persp_fixed_axis_kernel",
)
"""The perspective minimal solvers' kernels: compiled only with ``--perspective`` (about 50
CPU-seconds more, which would double the warm-up of ``make demo``; without it a perspective
uniform-rotation or fixed-axis reconstruction compiles them on first use)."""

PERSPECTIVE_ONLY = frozenset({"curverecon.solvers.homotopy.track_workspace"})
"""Kernels of shared modules that only the perspective solvers call (with ``--perspective``)."""

TABLE_TRACKER = frozenset(
    f"curverecon.solvers.homotopy.{name}"
    for name in (
        "_hermite_weights",
        "_newton_tables",
        "_table_coefficient_rates",
        "_table_coefficients",
        "_table_coefficients_t",
        "_table_residual_jacobian",
        "_table_residual_jacobian_t",
        "_table_workspace",
        "_track_paths",
    )
)
"""The homotopy tracker's table-driven kernels: they serve polynomial systems without generated
kernels (tests, derivations), never a reconstruction, so the warm-up leaves them alone."""

UNCALLED = frozenset(
    f"curverecon.generated.persp_fixed_axis_kernel.{name}"
    for name in ("coefficients_t", "coefficient_rates")
)
"""Generated kernels no solver calls: the fixed-axis solver tracks W(q(t)) as a polynomial in t
(``persp_fixed_axis_3pt._track_kernels``), not by way of dW/dt along dq."""


def cached_kernels() -> dict[str, Any]:
    """``module.name`` -> numba dispatcher, for every kernel with an on-disk cache."""
    from numba.core.registry import CPUDispatcher

    found = {}
    for name in KERNEL_MODULES:
        module = importlib.import_module(name)
        for attr, value in vars(module).items():
            cache = getattr(value, "_cache", None)
            if isinstance(value, CPUDispatcher) and getattr(cache, "cache_path", None):
                found[f"{name}.{attr}"] = value
    return found


def not_compiled(perspective: bool = False) -> list[str]:
    """The cached kernels with no machine code in numba's on-disk cache for their current source.

    A kernel called only from other kernels gets no signature in a process that loads its
    callers from the cache, so the check reads the cache's index instead (numba's ``_cache``
    object, as ``jit_cache`` does; numba is pinned): empty when missing or stale."""
    return sorted(
        name
        for name, d in cached_kernels().items()
        if _warmed(name, perspective) and not d._cache._cache_file._load_index()
    )


def _warmed(name: str, perspective: bool) -> bool:
    """Whether the warm-up compiles kernel ``module.name`` (with ``--perspective`` or not)."""
    if name in TABLE_TRACKER or name in UNCALLED:
        return False
    perspective_only = name in PERSPECTIVE_ONLY or name.startswith(
        tuple(m + "." for m in PERSPECTIVE_MODULES)
    )
    return perspective or not perspective_only


def run_scenes() -> None:
    """Reconstruct small scenes that reach every kernel: polylines (section 4, the curve bundle,
    the pose iteration; with the labels unknown, the polylines' placements), outlier frames
    (the minimal solver inside LO-RANSAC), and the minimal solver called directly on four
    frames."""
    from dataclasses import replace

    import numpy as np

    from curverecon.pipeline import reconstruct
    from curverecon.simulate import make_scene
    from curverecon.solvers.minimal import solve

    with np.errstate(all="ignore"):
        curve = make_scene(np.random.default_rng(1), 12, 0.5, 0.5, with_curve=True)
        reconstruct(curve.observations)
        # frames in any order: the polylines' placements (curve.labels_kernel)
        reconstruct(replace(curve.observations, ends_identified=False))
        outliers = make_scene(np.random.default_rng(2), 16, 0.5, 0.5, outlier_fraction=0.25)
        reconstruct(outliers.observations)
        solve(make_scene(np.random.default_rng(3), 4).observations)


def perspective_solves() -> None:
    """The two perspective minimal solvers tracked on their generated kernels: uniform rotation
    (five equally spaced frames of A, B) and a fixed axis (three frames of A, B, C), each on a
    body two units before an 800 px camera turning about a random axis."""
    import numpy as np

    from curverecon.rigid.model import rodrigues
    from curverecon.solvers import persp_fixed_axis_3pt, persp_uniform_rotation
    from curverecon.solvers.camera import Camera

    camera = Camera(800.0, (320.0, 240.0))
    rng = np.random.default_rng(4)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    for solver, angles in (
        (persp_uniform_rotation, 0.4 * np.arange(5)),
        (persp_fixed_axis_3pt, np.array([0.0, 0.7, -1.1])),
    ):
        body = rng.normal(size=(len(solver.POINTS), 3)) * 0.3
        x3 = np.array([body @ rodrigues(a * axis).T + [0.0, 0.0, 2.0] for a in angles])
        solver.solve(camera.project(x3), np.arange(len(angles), dtype=float), camera)


def main(argv: Sequence[str] | None = None) -> int:
    """Compile the kernels and print one line (a second, a warning, names any kernel the
    scenes did not reach: tests/test_warmup.py keeps that list empty).  Status 0 either way:
    a kernel left out is compiled on first use, as without the warm-up."""
    parser = argparse.ArgumentParser(
        prog="python -m curverecon.warmup",
        description="Compile every numba kernel of curverecon into numba's on-disk cache.",
    )
    parser.add_argument(
        "--perspective",
        action="store_true",
        help="also the perspective minimal solvers' kernels (about 50 CPU-seconds more)",
    )
    args = parser.parse_args(argv)
    start = time.perf_counter()
    run_scenes()
    if args.perspective:
        perspective_solves()
    seconds = time.perf_counter() - start
    kernels, missing = cached_kernels(), not_compiled(args.perspective)
    ready = sum(_warmed(name, args.perspective) for name in kernels) - len(missing)
    print(f"curverecon warm-up: {ready} compiled kernels in numba's cache ({seconds:.1f} s)")
    if missing:
        print(f"curverecon warm-up: warning: not reached: {', '.join(missing)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""curverecon: recover a rigid smooth 3-D curve from orthographic images of it moving freely when
only two points A, B are traceable (after M. A. Klopotek, section 3).

The pipeline's stages, in the order the data passes through them (docs/architecture.md):
``model`` (observations, conventions) -> ``solvers`` (closed-form solvers) -> ``robust``
(hypotheses, outlier frames) -> ``refine`` (maximum and marginal likelihood) -> ``curve``
(polylines, section 4, the curve bundle); :func:`reconstruct` chains them.

``curverecon.refine.refine`` is maximum likelihood, ``curverecon.refine.crlb`` the bound;
:func:`solve_minimal` (``curverecon.solvers.minimal.solve``) every shape that fits four frames.

Library units: lengths in input units, angles in radians; files use degrees.

The public names below are imported on first use (PEP 562 ``__getattr__``): ``import
curverecon`` itself loads no NumPy, SciPy or numba, so the command line answers ``--help``
without them.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

#: public name -> (module, attribute in it)
_PUBLIC = {
    "Alternative": ("curverecon.model.reconstruction", "Alternative"),
    "BranchOptions": ("curverecon.options", "BranchOptions"),
    "Configuration": ("curverecon.model.configuration", "Configuration"),
    "CurveOptions": ("curverecon.options", "CurveOptions"),
    "CurveReconError": ("curverecon.errors", "CurveReconError"),
    "MinimalOptions": ("curverecon.options", "MinimalOptions"),
    "MinimalResult": ("curverecon.solvers.minimal", "MinimalResult"),
    "Observations": ("curverecon.model.observations", "Observations"),
    "OutlierOptions": ("curverecon.options", "OutlierOptions"),
    "ReconstructOptions": ("curverecon.options", "ReconstructOptions"),
    "Reconstruction": ("curverecon.model.reconstruction", "Reconstruction"),
    "RigidObservations": ("curverecon.model.configuration", "RigidObservations"),
    "RefineResult": ("curverecon.refine", "RefineResult"),
    "Scene": ("curverecon.simulate", "Scene"),
    "SearchOptions": ("curverecon.options", "SearchOptions"),
    "crlb": ("curverecon.refine", "crlb"),
    "make_scene": ("curverecon.simulate", "make_scene"),
    "match_flat": ("curverecon.solvers.flat", "match_flat"),
    "poses_from_shape": ("curverecon.solvers.pose", "poses_from_shape"),
    "reconstruct": ("curverecon.pipeline", "reconstruct"),
    "refine_marginal": ("curverecon.refine", "refine_marginal"),
    "simulate_configuration": ("curverecon.simulate", "simulate_configuration"),
    "solve_linear": ("curverecon.solvers.linear", "solve_linear"),
    "solve_minimal": ("curverecon.solvers.minimal", "solve"),
}

__all__ = [
    "Alternative",
    "BranchOptions",
    "Configuration",
    "CurveOptions",
    "CurveReconError",
    "MinimalOptions",
    "MinimalResult",
    "Observations",
    "OutlierOptions",
    "ReconstructOptions",
    "Reconstruction",
    "RefineResult",
    "RigidObservations",
    "Scene",
    "SearchOptions",
    "__version__",
    "crlb",
    "make_scene",
    "match_flat",
    "poses_from_shape",
    "reconstruct",
    "refine_marginal",
    "simulate_configuration",
    "solve_linear",
    "solve_minimal",
]


def __getattr__(name: str) -> Any:
    """A public name (imported from its module on first use) or a submodule of the package."""
    if name in _PUBLIC:
        module, attribute = _PUBLIC[name]
        value = getattr(importlib.import_module(module), attribute)
        globals()[name] = value
        return value
    try:
        return importlib.import_module(f"{__name__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_PUBLIC})


if TYPE_CHECKING:  # pragma: no cover - for type checkers and editors only
    from curverecon.errors import CurveReconError
    from curverecon.model.configuration import Configuration, RigidObservations
    from curverecon.model.observations import Observations
    from curverecon.model.reconstruction import Alternative, Reconstruction
    from curverecon.options import (
        BranchOptions,
        CurveOptions,
        MinimalOptions,
        OutlierOptions,
        ReconstructOptions,
        SearchOptions,
    )
    from curverecon.pipeline import reconstruct
    from curverecon.refine import RefineResult, crlb, refine_marginal
    from curverecon.simulate import Scene, make_scene, simulate_configuration
    from curverecon.solvers.flat import match_flat
    from curverecon.solvers.linear import solve_linear
    from curverecon.solvers.minimal import MinimalResult
    from curverecon.solvers.minimal import solve as solve_minimal
    from curverecon.solvers.pose import poses_from_shape

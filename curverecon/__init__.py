"""curverecon: recover a rigid smooth 3-D curve from orthographic images of it moving freely when
only two points A, B are traceable (after M. A. Klopotek, section 3).

The pipeline's stages, in the order the data passes through them (docs/architecture.md):
``model`` (observations, conventions) -> ``solvers`` (closed-form solvers) -> ``robust``
(hypotheses, outlier frames) -> ``refine`` (maximum and marginal likelihood) -> ``curve``
(polylines, section 4, the curve bundle); :func:`reconstruct` chains them.

``curverecon.refine.refine`` is maximum likelihood, ``curverecon.refine.crlb`` the bound;
:func:`solve_minimal` (``curverecon.solvers.minimal.solve``) every shape that fits four frames.

Library units: lengths in input units, angles in radians; files use degrees.
"""

from curverecon.errors import CurveReconError
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
from curverecon.simulate import Scene, make_scene
from curverecon.solvers.flat import match_flat
from curverecon.solvers.linear import solve_linear
from curverecon.solvers.minimal import MinimalResult
from curverecon.solvers.minimal import solve as solve_minimal
from curverecon.solvers.pose import poses_from_shape

__version__ = "0.1.0"
__all__ = [
    "Alternative",
    "BranchOptions",
    "CurveOptions",
    "CurveReconError",
    "MinimalOptions",
    "MinimalResult",
    "Observations",
    "OutlierOptions",
    "ReconstructOptions",
    "Reconstruction",
    "RefineResult",
    "Scene",
    "SearchOptions",
    "__version__",
    "crlb",
    "make_scene",
    "match_flat",
    "poses_from_shape",
    "reconstruct",
    "refine_marginal",
    "solve_linear",
    "solve_minimal",
]

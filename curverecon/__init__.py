"""curverecon: recover a rigid smooth 3-D curve from orthographic images of it moving freely when
only two points A, B are traceable (after M. A. Klopotek, section 3).

Library entry points (NumPy arrays in, dataclasses out; lengths in input units, angles in radians):

- :class:`curverecon.model.observations.Observations`  per-frame A', B' and tangent directions
- :func:`curverecon.pipeline.reconstruct`      the full pipeline (method "auto" or "linear")
- :func:`curverecon.solvers.linear.solve_linear`          the paper's linearisation alone
- :func:`curverecon.robust.search.robust_start`           start without the truth (global search)
- :func:`curverecon.refine.ml.refine`               maximum likelihood (Schur-complement LM)
- :func:`curverecon.refine.ml.crlb`                 the Cramer-Rao bound of the shape
- :func:`curverecon.simulate.make_scene`          independent synthetic scenes with the truth
"""

from curverecon.errors import CurveReconError

__version__ = "0.1.0"
__all__ = ["CurveReconError", "__version__"]

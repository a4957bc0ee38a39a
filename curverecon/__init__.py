"""curverecon: recover a rigid smooth 3-D curve from orthographic images of it moving freely when
only two points A, B are traceable (after M. A. Klopotek, section 3).

Library entry points (NumPy arrays in, dataclasses out; lengths in input units, angles in radians):

- :class:`curverecon.observations.Observations`  per-frame A', B' and tangent directions
- :func:`curverecon.reconstruct.reconstruct`      the full pipeline (method "auto" or "linear")
- :func:`curverecon.linear.solve_linear`          the paper's linearisation alone
- :func:`curverecon.start.robust_start`           start without the truth (global search)
- :func:`curverecon.refine.refine`               maximum likelihood (Schur-complement LM)
- :func:`curverecon.refine.crlb`                 the Cramer-Rao bound of the shape
- :func:`curverecon.simulate.make_scene`          independent synthetic scenes with the truth
"""

from curverecon.errors import CurveReconError

__version__ = "0.1.0"
__all__ = ["CurveReconError", "__version__"]

"""Refinement: maximum likelihood (``ml``: Schur-complement Levenberg-Marquardt, covariance and
Cramer-Rao bound), the marginal likelihood (``marginal``: every frame's pose integrated out) and
the final estimate among equally good fits (``answer``)."""

from curverecon.refine.marginal import MarginalResult, refine_marginal
from curverecon.refine.ml import RefineResult, crlb, crlb_covariance, refine, refine_batch

__all__ = [
    "MarginalResult",
    "RefineResult",
    "crlb",
    "crlb_covariance",
    "refine",
    "refine_batch",
    "refine_marginal",
]

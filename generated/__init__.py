# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/__main__.py
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Code generated from derivations/ (NumPy only; imported as curverecon.generated).

- ``measurement_model``: maximum-likelihood measurement model and its Jacobians
  (derivations/measurement.py)
- ``measurement_kernel``: the measurement model as scalar numba kernels, one frame per call
  (derivations/measurement.py)
- ``frame_equations``: section 3 per-frame equations (10), (11), (12) (derivations/section3.py)
- ``lean_polynomial``: single-squaring elimination, grouped by observable monomial
  (derivations/lean.py)
- ``polynomial_12p``: the paper's (12'), grouped by observable monomial (derivations/squaring.py)
- ``minimal_unsquared``: the four-frame minimal problem and its start system, solved by monodromy
  (derivations/minimal.py)
- ``minimal_unsquared_kernel``: the same system as straight-line numba kernels: F, F_x, F_t by way
  of W(q) (derivations/minimal.py)
- ``section2_minimal``: the seed's Section 2 orthographic rows: closed forms and residuals of their
  minimal problems (derivations/section2.py)
- ``rigid_model``: the orthographic rigid-body measurement model of the Section 2 rows and its
  Jacobians (derivations/rigid_model.py)
- ``rigid_pinhole``: the pinhole rigid-body measurement model of the perspective and stereo rows and
  its Jacobians (derivations/rigid_pinhole.py)
- ``section2_perspective``: the seed's Section 2 perspective and stereo rows: linear systems of the
  closed-form rows (derivations/section2_perspective.py)
- ``persp_uniform_rotation_system``: perspective uniform rotation, five frames, with its start
  system solved by monodromy (derivations/section2_perspective.py)
- ``persp_fixed_axis_system``: perspective rotation about a fixed direction, three points, three
  frames, with its start system solved by monodromy (derivations/section2_perspective.py)
- ``persp_uniform_rotation_kernel``: the perspective uniform rotation system as straight-line numba
  kernels (its 15 dense unknowns solved by the tracker's loop) (derivations/section2_perspective.py)
- ``persp_fixed_axis_kernel``: the perspective fixed-axis system as straight-line numba kernels
  (derivations/section2_perspective.py)
"""

__all__ = (
    "measurement_model",
    "measurement_kernel",
    "frame_equations",
    "lean_polynomial",
    "polynomial_12p",
    "minimal_unsquared",
    "minimal_unsquared_kernel",
    "section2_minimal",
    "rigid_model",
    "rigid_pinhole",
    "section2_perspective",
    "persp_uniform_rotation_system",
    "persp_fixed_axis_system",
    "persp_uniform_rotation_kernel",
    "persp_fixed_axis_kernel",
)

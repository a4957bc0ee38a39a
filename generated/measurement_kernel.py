# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/measurement.py
# Template:   derivations/codegen/templates/kernel.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Scalar numba kernels of the measurement model, for loops over frames (generated).

The same expressions as generated/measurement_model.py (derivations/measurement.py), one frame
per call: float arguments (c, alpha, beta, phi, delta, tau, theta, tx, ty), outputs written
into arrays the caller passes.  Used by the per-frame pose iterations of long sequences
(curverecon.refine.pose_kernel), where NumPy's per-call overhead on (N, 6, 5) blocks was most
of the time.  Conventions and units as in measurement_model.py and docs/CONVENTIONS.md.
"""

from __future__ import annotations

import math

import numba
import numpy as np

# Compiled on first call and cached next to this file (no C compiler needed: numba's LLVM).
# fastmath stays off: a kernel rounds as the NumPy module of the same derivation does.
_JIT = {"cache": True, "nogil": True, "fastmath": False}


@numba.njit(**_JIT)
def predict_frame(
    c: float,
    alpha: float,
    beta: float,
    phi: float,
    delta: float,
    tau: float,
    theta: float,
    tx: float,
    ty: float,
    prediction: np.ndarray,
) -> None:
    """Predicted (ax, ay, bx, by, psi_a, psi_b) of one frame (input units, radians).

    Outputs written in place: prediction (6,).
    """
    _tmp0 = math.cos(theta)
    _tmp1 = math.cos(tau)
    _tmp2 = _tmp1 * c
    _tmp3 = math.sin(theta)
    _tmp4 = _tmp1 * math.cos(beta)
    _tmp5 = math.cos(delta)
    _tmp6 = _tmp0 * _tmp5
    _tmp7 = math.sin(tau)
    _tmp8 = math.sin(delta)
    _tmp9 = _tmp3 * _tmp8
    _tmp10 = _tmp6 + _tmp7 * _tmp9
    _tmp11 = math.sin(beta)
    _tmp12 = _tmp11 * math.cos(phi)
    _tmp13 = _tmp0 * _tmp8
    _tmp14 = _tmp3 * _tmp5
    _tmp15 = _tmp11 * math.sin(phi)
    _tmp16 = _tmp13 * _tmp7 - _tmp14
    _tmp17 = _tmp1 * math.cos(alpha)
    _tmp18 = math.sin(alpha)
    prediction[0] = tx
    prediction[1] = ty
    prediction[2] = _tmp0 * _tmp2 + tx
    prediction[3] = _tmp2 * _tmp3 + ty
    prediction[4] = math.atan2(
        _tmp10 * _tmp12 - _tmp15 * (_tmp13 - _tmp14 * _tmp7) + _tmp3 * _tmp4,
        _tmp0 * _tmp4 + _tmp12 * _tmp16 + _tmp15 * (_tmp6 * _tmp7 + _tmp9),
    )
    prediction[5] = math.atan2(_tmp10 * _tmp18 - _tmp17 * _tmp3, -_tmp0 * _tmp17 + _tmp16 * _tmp18)


@numba.njit(**_JIT)
def predict_frame_with_pose_jacobian(
    c: float,
    alpha: float,
    beta: float,
    phi: float,
    delta: float,
    tau: float,
    theta: float,
    tx: float,
    ty: float,
    prediction: np.ndarray,
    jac_local: np.ndarray,
) -> None:
    """Prediction of one frame and its Jacobian (6, 5) with respect to the pose
    (delta, tau, theta, tx, ty).

    Outputs written in place: prediction (6,), jac_local (6, 5,).
    """
    _tmp0 = math.cos(theta)
    _tmp1 = math.cos(tau)
    _tmp2 = _tmp1 * c
    _tmp3 = _tmp0 * _tmp2
    _tmp4 = math.sin(theta)
    _tmp5 = _tmp2 * _tmp4
    _tmp6 = math.cos(beta)
    _tmp7 = _tmp1 * _tmp6
    _tmp8 = math.cos(delta)
    _tmp9 = _tmp0 * _tmp8
    _tmp10 = math.sin(tau)
    _tmp11 = math.sin(delta)
    _tmp12 = _tmp11 * _tmp4
    _tmp13 = _tmp10 * _tmp12 + _tmp9
    _tmp14 = math.cos(phi)
    _tmp15 = math.sin(beta)
    _tmp16 = _tmp14 * _tmp15
    _tmp17 = _tmp0 * _tmp11
    _tmp18 = _tmp4 * _tmp8
    _tmp19 = -_tmp10 * _tmp18 + _tmp17
    _tmp20 = math.sin(phi)
    _tmp21 = _tmp15 * _tmp20
    _tmp22 = _tmp13 * _tmp16 - _tmp19 * _tmp21 + _tmp4 * _tmp7
    _tmp23 = _tmp10 * _tmp9 + _tmp12
    _tmp24 = _tmp10 * _tmp17 - _tmp18
    _tmp25 = _tmp0 * _tmp7 + _tmp16 * _tmp24 + _tmp21 * _tmp23
    _tmp26 = math.cos(alpha)
    _tmp27 = _tmp1 * _tmp26
    _tmp28 = math.sin(alpha)
    _tmp29 = _tmp13 * _tmp28 - _tmp27 * _tmp4
    _tmp30 = -_tmp0 * _tmp27 + _tmp24 * _tmp28
    _tmp31 = _tmp10 * c
    _tmp32 = 1 / (_tmp22 * _tmp22 + _tmp25 * _tmp25)
    _tmp33 = _tmp1 * _tmp11
    _tmp34 = 1 / (_tmp29 * _tmp29 + _tmp30 * _tmp30)
    prediction[0] = tx
    prediction[1] = ty
    prediction[2] = _tmp3 + tx
    prediction[3] = _tmp5 + ty
    prediction[4] = math.atan2(_tmp22, _tmp25)
    prediction[5] = math.atan2(_tmp29, _tmp30)
    jac_local[0, 0] = 0.0
    jac_local[0, 1] = 0.0
    jac_local[0, 2] = 0.0
    jac_local[0, 3] = 1
    jac_local[0, 4] = 0.0
    jac_local[1, 0] = 0.0
    jac_local[1, 1] = 0.0
    jac_local[1, 2] = 0.0
    jac_local[1, 3] = 0.0
    jac_local[1, 4] = 1
    jac_local[2, 0] = 0.0
    jac_local[2, 1] = -_tmp0 * _tmp31
    jac_local[2, 2] = -_tmp5
    jac_local[2, 3] = 1
    jac_local[2, 4] = 0.0
    jac_local[3, 0] = 0.0
    jac_local[3, 1] = -_tmp31 * _tmp4
    jac_local[3, 2] = _tmp3
    jac_local[3, 3] = 0.0
    jac_local[3, 4] = 1
    jac_local[4, 0] = (
        -_tmp15
        * _tmp32
        * (
            _tmp22 * (_tmp14 * _tmp23 - _tmp20 * _tmp24)
            + _tmp25 * (_tmp13 * _tmp20 + _tmp14 * _tmp19)
        )
    )
    jac_local[4, 1] = (
        _tmp32
        * (-_tmp0 * _tmp22 + _tmp25 * _tmp4)
        * (_tmp1 * _tmp21 * _tmp8 - _tmp10 * _tmp6 + _tmp16 * _tmp33)
    )
    jac_local[4, 2] = 1
    jac_local[4, 3] = 0.0
    jac_local[4, 4] = 0.0
    jac_local[5, 0] = -_tmp28 * _tmp34 * (_tmp19 * _tmp30 + _tmp23 * _tmp29)
    jac_local[5, 1] = (
        -_tmp34 * (_tmp0 * _tmp29 - _tmp30 * _tmp4) * (_tmp10 * _tmp26 + _tmp28 * _tmp33)
    )
    jac_local[5, 2] = 1
    jac_local[5, 3] = 0.0
    jac_local[5, 4] = 0.0

# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/minimal.py
# Template:   derivations/codegen/templates/system_kernel.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Straight-line numba kernels of generated/minimal_unsquared.py (generated).

The system F(x; q) = W(q) u(x) of derivations/minimal.py, written out after one
common-subexpression pass instead of read from tables: ``coefficients`` and ``coefficients_t``
give the nonzero entries of W (and dW/dt along dq), ``residual_jacobian`` and
``residual_jacobian_t`` give F, F_x (and F_t) from them.  Complex arithmetic; every argument a
contiguous complex128 array.  curverecon.solvers.homotopy tracks paths with these when a system
comes with them, and reads the tables of the system module otherwise.
"""

from __future__ import annotations

import numba
import numpy as np

UNKNOWNS = ("C", "A", "B", "P", "m", "s0", "s1", "s2", "s3")
PARAMETERS = ("cp0", "dp0", "ep0", "cp1", "dp1", "ep1", "cp2", "dp2", "ep2", "cp3", "dp3", "ep3")
EQUATIONS = (
    "unsquared (12*), frame 0",
    "unsquared (12*), frame 1",
    "unsquared (12*), frame 2",
    "unsquared (12*), frame 3",
    "s0**2 - C*A*B*(1 - P)*(C - cp0**2)",
    "s1**2 - C*A*B*(1 - P)*(C - cp1**2)",
    "s2**2 - C*A*B*(1 - P)*(C - cp2**2)",
    "s3**2 - C*A*B*(1 - P)*(C - cp3**2)",
    "m**2 - A*B*P",
)

#: Entries of the coefficient matrix W(q) the kernels exchange (nonzero ones only).
N_COEFFICIENTS = 82

#: (equation, exponents of UNKNOWNS of the unknown monomial) of each entry of W, in order.
# fmt: off
COEFFICIENT_ENTRIES = (
    (0, (0, 0, 0, 0, 0, 1, 0, 0, 0)), (0, (0, 0, 0, 0, 1, 0, 0, 0, 0)),
    (0, (0, 0, 0, 0, 1, 1, 0, 0, 0)), (0, (0, 0, 1, 0, 0, 0, 0, 0, 0)),
    (0, (0, 1, 0, 0, 0, 0, 0, 0, 0)), (0, (0, 1, 1, 0, 0, 0, 0, 0, 0)),
    (0, (0, 1, 1, 1, 0, 0, 0, 0, 0)), (0, (1, 0, 0, 0, 1, 0, 0, 0, 0)),
    (0, (1, 0, 0, 0, 1, 1, 0, 0, 0)), (0, (1, 0, 1, 0, 0, 0, 0, 0, 0)),
    (0, (1, 1, 0, 0, 0, 0, 0, 0, 0)), (0, (1, 1, 1, 0, 0, 0, 0, 0, 0)),
    (0, (1, 1, 1, 1, 0, 0, 0, 0, 0)), (0, (2, 1, 1, 0, 0, 0, 0, 0, 0)),
    (0, (2, 1, 1, 1, 0, 0, 0, 0, 0)), (1, (0, 0, 0, 0, 0, 0, 1, 0, 0)),
    (1, (0, 0, 0, 0, 1, 0, 0, 0, 0)), (1, (0, 0, 0, 0, 1, 0, 1, 0, 0)),
    (1, (0, 0, 1, 0, 0, 0, 0, 0, 0)), (1, (0, 1, 0, 0, 0, 0, 0, 0, 0)),
    (1, (0, 1, 1, 0, 0, 0, 0, 0, 0)), (1, (0, 1, 1, 1, 0, 0, 0, 0, 0)),
    (1, (1, 0, 0, 0, 1, 0, 0, 0, 0)), (1, (1, 0, 0, 0, 1, 0, 1, 0, 0)),
    (1, (1, 0, 1, 0, 0, 0, 0, 0, 0)), (1, (1, 1, 0, 0, 0, 0, 0, 0, 0)),
    (1, (1, 1, 1, 0, 0, 0, 0, 0, 0)), (1, (1, 1, 1, 1, 0, 0, 0, 0, 0)),
    (1, (2, 1, 1, 0, 0, 0, 0, 0, 0)), (1, (2, 1, 1, 1, 0, 0, 0, 0, 0)),
    (2, (0, 0, 0, 0, 0, 0, 0, 1, 0)), (2, (0, 0, 0, 0, 1, 0, 0, 0, 0)),
    (2, (0, 0, 0, 0, 1, 0, 0, 1, 0)), (2, (0, 0, 1, 0, 0, 0, 0, 0, 0)),
    (2, (0, 1, 0, 0, 0, 0, 0, 0, 0)), (2, (0, 1, 1, 0, 0, 0, 0, 0, 0)),
    (2, (0, 1, 1, 1, 0, 0, 0, 0, 0)), (2, (1, 0, 0, 0, 1, 0, 0, 0, 0)),
    (2, (1, 0, 0, 0, 1, 0, 0, 1, 0)), (2, (1, 0, 1, 0, 0, 0, 0, 0, 0)),
    (2, (1, 1, 0, 0, 0, 0, 0, 0, 0)), (2, (1, 1, 1, 0, 0, 0, 0, 0, 0)),
    (2, (1, 1, 1, 1, 0, 0, 0, 0, 0)), (2, (2, 1, 1, 0, 0, 0, 0, 0, 0)),
    (2, (2, 1, 1, 1, 0, 0, 0, 0, 0)), (3, (0, 0, 0, 0, 0, 0, 0, 0, 1)),
    (3, (0, 0, 0, 0, 1, 0, 0, 0, 0)), (3, (0, 0, 0, 0, 1, 0, 0, 0, 1)),
    (3, (0, 0, 1, 0, 0, 0, 0, 0, 0)), (3, (0, 1, 0, 0, 0, 0, 0, 0, 0)),
    (3, (0, 1, 1, 0, 0, 0, 0, 0, 0)), (3, (0, 1, 1, 1, 0, 0, 0, 0, 0)),
    (3, (1, 0, 0, 0, 1, 0, 0, 0, 0)), (3, (1, 0, 0, 0, 1, 0, 0, 0, 1)),
    (3, (1, 0, 1, 0, 0, 0, 0, 0, 0)), (3, (1, 1, 0, 0, 0, 0, 0, 0, 0)),
    (3, (1, 1, 1, 0, 0, 0, 0, 0, 0)), (3, (1, 1, 1, 1, 0, 0, 0, 0, 0)),
    (3, (2, 1, 1, 0, 0, 0, 0, 0, 0)), (3, (2, 1, 1, 1, 0, 0, 0, 0, 0)),
    (4, (0, 0, 0, 0, 0, 2, 0, 0, 0)), (4, (1, 1, 1, 0, 0, 0, 0, 0, 0)),
    (4, (1, 1, 1, 1, 0, 0, 0, 0, 0)), (4, (2, 1, 1, 0, 0, 0, 0, 0, 0)),
    (4, (2, 1, 1, 1, 0, 0, 0, 0, 0)), (5, (0, 0, 0, 0, 0, 0, 2, 0, 0)),
    (5, (1, 1, 1, 0, 0, 0, 0, 0, 0)), (5, (1, 1, 1, 1, 0, 0, 0, 0, 0)),
    (5, (2, 1, 1, 0, 0, 0, 0, 0, 0)), (5, (2, 1, 1, 1, 0, 0, 0, 0, 0)),
    (6, (0, 0, 0, 0, 0, 0, 0, 2, 0)), (6, (1, 1, 1, 0, 0, 0, 0, 0, 0)),
    (6, (1, 1, 1, 1, 0, 0, 0, 0, 0)), (6, (2, 1, 1, 0, 0, 0, 0, 0, 0)),
    (6, (2, 1, 1, 1, 0, 0, 0, 0, 0)), (7, (0, 0, 0, 0, 0, 0, 0, 0, 2)),
    (7, (1, 1, 1, 0, 0, 0, 0, 0, 0)), (7, (1, 1, 1, 1, 0, 0, 0, 0, 0)),
    (7, (2, 1, 1, 0, 0, 0, 0, 0, 0)), (7, (2, 1, 1, 1, 0, 0, 0, 0, 0)),
    (8, (0, 0, 0, 0, 2, 0, 0, 0, 0)), (8, (0, 1, 1, 1, 0, 0, 0, 0, 0)),
)
# fmt: on

# Compiled on first call and cached next to this file (numba's LLVM).  Complex arithmetic;
# fastmath without the finite-math flags, as the homotopy tracker that calls these.
_JIT = {"cache": True, "nogil": True, "fastmath": {"contract", "reassoc", "arcp", "nsz"}}


@numba.njit(**_JIT)
def coefficients(q: np.ndarray, w: np.ndarray) -> None:
    """The nonzero entries of the coefficient matrix W(q) (COEFFICIENT_ENTRIES order).

    Outputs written in place (every entry): w.
    """
    cp0 = q[0]
    dp0 = q[1]
    ep0 = q[2]
    cp1 = q[3]
    dp1 = q[4]
    ep1 = q[5]
    cp2 = q[6]
    dp2 = q[7]
    ep2 = q[8]
    cp3 = q[9]
    dp3 = q[10]
    ep3 = q[11]
    _tmp0 = dp0 * ep0
    _tmp1 = 2 * _tmp0 * (cp0 * cp0 * cp0) * (dp0 + ep0)
    _tmp2 = cp0 * cp0 * cp0 * cp0
    _tmp3 = dp0 * dp0
    _tmp4 = ep0 * ep0
    _tmp5 = _tmp3 * _tmp4
    _tmp6 = _tmp2 * _tmp5
    _tmp7 = -_tmp6
    _tmp8 = cp0 * cp0
    _tmp9 = _tmp0 * _tmp8
    _tmp10 = 2 * _tmp9 * (-_tmp8 + dp0 * ep0)
    _tmp11 = _tmp3 * _tmp8
    _tmp12 = _tmp4 * _tmp8
    _tmp13 = _tmp11 + _tmp12 + 4 * _tmp9
    _tmp14 = dp1 * ep1
    _tmp15 = 2 * _tmp14 * (cp1 * cp1 * cp1) * (dp1 + ep1)
    _tmp16 = cp1 * cp1 * cp1 * cp1
    _tmp17 = dp1 * dp1
    _tmp18 = ep1 * ep1
    _tmp19 = _tmp17 * _tmp18
    _tmp20 = _tmp16 * _tmp19
    _tmp21 = -_tmp20
    _tmp22 = cp1 * cp1
    _tmp23 = _tmp14 * _tmp22
    _tmp24 = 2 * _tmp23 * (-_tmp22 + dp1 * ep1)
    _tmp25 = _tmp17 * _tmp22
    _tmp26 = _tmp18 * _tmp22
    _tmp27 = 4 * _tmp23 + _tmp25 + _tmp26
    _tmp28 = dp2 * ep2
    _tmp29 = 2 * _tmp28 * (cp2 * cp2 * cp2) * (dp2 + ep2)
    _tmp30 = cp2 * cp2 * cp2 * cp2
    _tmp31 = dp2 * dp2
    _tmp32 = ep2 * ep2
    _tmp33 = _tmp31 * _tmp32
    _tmp34 = _tmp30 * _tmp33
    _tmp35 = -_tmp34
    _tmp36 = cp2 * cp2
    _tmp37 = _tmp28 * _tmp36
    _tmp38 = 2 * _tmp37 * (-_tmp36 + dp2 * ep2)
    _tmp39 = _tmp31 * _tmp36
    _tmp40 = _tmp32 * _tmp36
    _tmp41 = 4 * _tmp37 + _tmp39 + _tmp40
    _tmp42 = dp3 * ep3
    _tmp43 = 2 * _tmp42 * (cp3 * cp3 * cp3) * (dp3 + ep3)
    _tmp44 = cp3 * cp3 * cp3 * cp3
    _tmp45 = dp3 * dp3
    _tmp46 = ep3 * ep3
    _tmp47 = _tmp45 * _tmp46
    _tmp48 = _tmp44 * _tmp47
    _tmp49 = -_tmp48
    _tmp50 = cp3 * cp3
    _tmp51 = _tmp42 * _tmp50
    _tmp52 = 2 * _tmp51 * (-_tmp50 + dp3 * ep3)
    _tmp53 = _tmp45 * _tmp50
    _tmp54 = _tmp46 * _tmp50
    _tmp55 = 4 * _tmp51 + _tmp53 + _tmp54
    w[0] = _tmp1
    w[1] = -2 * _tmp6
    w[2] = -_tmp1
    w[3] = _tmp7
    w[4] = _tmp7
    w[5] = _tmp7
    w[6] = _tmp6
    w[7] = _tmp10
    w[8] = 2 * cp0 * (_tmp3 * ep0 + _tmp4 * dp0 - _tmp8 * dp0 - _tmp8 * ep0)
    w[9] = _tmp11 * (_tmp4 + _tmp8)
    w[10] = _tmp12 * (_tmp3 + _tmp8)
    w[11] = _tmp10
    w[12] = _tmp8 * (_tmp13 - 2 * _tmp5)
    w[13] = -_tmp2 - _tmp5 + 2 * _tmp8 * dp0 * ep0
    w[14] = -_tmp13 + _tmp2 + _tmp5
    w[15] = _tmp15
    w[16] = -2 * _tmp20
    w[17] = -_tmp15
    w[18] = _tmp21
    w[19] = _tmp21
    w[20] = _tmp21
    w[21] = _tmp20
    w[22] = _tmp24
    w[23] = 2 * cp1 * (_tmp17 * ep1 + _tmp18 * dp1 - _tmp22 * dp1 - _tmp22 * ep1)
    w[24] = _tmp25 * (_tmp18 + _tmp22)
    w[25] = _tmp26 * (_tmp17 + _tmp22)
    w[26] = _tmp24
    w[27] = _tmp22 * (-2 * _tmp19 + _tmp27)
    w[28] = -_tmp16 - _tmp19 + 2 * _tmp22 * dp1 * ep1
    w[29] = _tmp16 + _tmp19 - _tmp27
    w[30] = _tmp29
    w[31] = -2 * _tmp34
    w[32] = -_tmp29
    w[33] = _tmp35
    w[34] = _tmp35
    w[35] = _tmp35
    w[36] = _tmp34
    w[37] = _tmp38
    w[38] = 2 * cp2 * (_tmp31 * ep2 + _tmp32 * dp2 - _tmp36 * dp2 - _tmp36 * ep2)
    w[39] = _tmp39 * (_tmp32 + _tmp36)
    w[40] = _tmp40 * (_tmp31 + _tmp36)
    w[41] = _tmp38
    w[42] = _tmp36 * (-2 * _tmp33 + _tmp41)
    w[43] = -_tmp30 - _tmp33 + 2 * _tmp36 * dp2 * ep2
    w[44] = _tmp30 + _tmp33 - _tmp41
    w[45] = _tmp43
    w[46] = -2 * _tmp48
    w[47] = -_tmp43
    w[48] = _tmp49
    w[49] = _tmp49
    w[50] = _tmp49
    w[51] = _tmp48
    w[52] = _tmp52
    w[53] = 2 * cp3 * (_tmp45 * ep3 + _tmp46 * dp3 - _tmp50 * dp3 - _tmp50 * ep3)
    w[54] = _tmp53 * (_tmp46 + _tmp50)
    w[55] = _tmp54 * (_tmp45 + _tmp50)
    w[56] = _tmp52
    w[57] = _tmp50 * (-2 * _tmp47 + _tmp55)
    w[58] = -_tmp44 - _tmp47 + 2 * _tmp50 * dp3 * ep3
    w[59] = _tmp44 + _tmp47 - _tmp55
    w[60] = 1
    w[61] = _tmp8
    w[62] = -_tmp8
    w[63] = -1
    w[64] = 1
    w[65] = 1
    w[66] = _tmp22
    w[67] = -_tmp22
    w[68] = -1
    w[69] = 1
    w[70] = 1
    w[71] = _tmp36
    w[72] = -_tmp36
    w[73] = -1
    w[74] = 1
    w[75] = 1
    w[76] = _tmp50
    w[77] = -_tmp50
    w[78] = -1
    w[79] = 1
    w[80] = 1
    w[81] = -1


@numba.njit(**_JIT)
def coefficients_t(q: np.ndarray, dq: np.ndarray, w: np.ndarray, wt: np.ndarray) -> None:
    """W(q) as ``coefficients`` and its derivative dW/dt = W_q . dq along dq = dq/dt.

    Outputs written in place (every entry): w, wt.
    """
    cp0 = q[0]
    dp0 = q[1]
    ep0 = q[2]
    cp1 = q[3]
    dp1 = q[4]
    ep1 = q[5]
    cp2 = q[6]
    dp2 = q[7]
    ep2 = q[8]
    cp3 = q[9]
    dp3 = q[10]
    ep3 = q[11]
    d_cp0 = dq[0]
    d_dp0 = dq[1]
    d_ep0 = dq[2]
    d_cp1 = dq[3]
    d_dp1 = dq[4]
    d_ep1 = dq[5]
    d_cp2 = dq[6]
    d_dp2 = dq[7]
    d_ep2 = dq[8]
    d_cp3 = dq[9]
    d_dp3 = dq[10]
    d_ep3 = dq[11]
    _tmp0 = cp0 * cp0 * cp0
    _tmp1 = dp0 * ep0
    _tmp2 = 2 * _tmp0 * _tmp1
    _tmp3 = _tmp2 * (dp0 + ep0)
    _tmp4 = cp0 * cp0 * cp0 * cp0
    _tmp5 = dp0 * dp0
    _tmp6 = ep0 * ep0
    _tmp7 = _tmp5 * _tmp6
    _tmp8 = _tmp4 * _tmp7
    _tmp9 = -_tmp8
    _tmp10 = cp0 * cp0
    _tmp11 = 2 * _tmp10
    _tmp12 = _tmp1 * _tmp11 * (-_tmp10 + dp0 * ep0)
    _tmp13 = _tmp10 * dp0
    _tmp14 = _tmp10 * ep0
    _tmp15 = 2 * cp0
    _tmp16 = _tmp10 * _tmp5
    _tmp17 = _tmp10 * _tmp6
    _tmp18 = 2 * _tmp7
    _tmp19 = 4 * _tmp1
    _tmp20 = _tmp10 * _tmp19
    _tmp21 = _tmp16 + _tmp17 + _tmp20
    _tmp22 = cp1 * cp1 * cp1
    _tmp23 = dp1 * ep1
    _tmp24 = 2 * _tmp22 * _tmp23
    _tmp25 = _tmp24 * (dp1 + ep1)
    _tmp26 = cp1 * cp1 * cp1 * cp1
    _tmp27 = dp1 * dp1
    _tmp28 = ep1 * ep1
    _tmp29 = _tmp27 * _tmp28
    _tmp30 = _tmp26 * _tmp29
    _tmp31 = -_tmp30
    _tmp32 = cp1 * cp1
    _tmp33 = 2 * _tmp32
    _tmp34 = _tmp23 * _tmp33 * (-_tmp32 + dp1 * ep1)
    _tmp35 = _tmp32 * dp1
    _tmp36 = _tmp32 * ep1
    _tmp37 = 2 * cp1
    _tmp38 = _tmp27 * _tmp32
    _tmp39 = _tmp28 * _tmp32
    _tmp40 = 2 * _tmp29
    _tmp41 = 4 * _tmp23
    _tmp42 = _tmp32 * _tmp41
    _tmp43 = _tmp38 + _tmp39 + _tmp42
    _tmp44 = cp2 * cp2 * cp2
    _tmp45 = dp2 * ep2
    _tmp46 = 2 * _tmp44 * _tmp45
    _tmp47 = _tmp46 * (dp2 + ep2)
    _tmp48 = cp2 * cp2 * cp2 * cp2
    _tmp49 = dp2 * dp2
    _tmp50 = ep2 * ep2
    _tmp51 = _tmp49 * _tmp50
    _tmp52 = _tmp48 * _tmp51
    _tmp53 = -_tmp52
    _tmp54 = cp2 * cp2
    _tmp55 = 2 * _tmp54
    _tmp56 = _tmp45 * _tmp55 * (-_tmp54 + dp2 * ep2)
    _tmp57 = _tmp54 * dp2
    _tmp58 = _tmp54 * ep2
    _tmp59 = 2 * cp2
    _tmp60 = _tmp49 * _tmp54
    _tmp61 = _tmp50 * _tmp54
    _tmp62 = 2 * _tmp51
    _tmp63 = 4 * _tmp45
    _tmp64 = _tmp54 * _tmp63
    _tmp65 = _tmp60 + _tmp61 + _tmp64
    _tmp66 = cp3 * cp3 * cp3
    _tmp67 = dp3 * ep3
    _tmp68 = 2 * _tmp66 * _tmp67
    _tmp69 = _tmp68 * (dp3 + ep3)
    _tmp70 = cp3 * cp3 * cp3 * cp3
    _tmp71 = dp3 * dp3
    _tmp72 = ep3 * ep3
    _tmp73 = _tmp71 * _tmp72
    _tmp74 = _tmp70 * _tmp73
    _tmp75 = -_tmp74
    _tmp76 = cp3 * cp3
    _tmp77 = 2 * _tmp76
    _tmp78 = _tmp67 * _tmp77 * (-_tmp76 + dp3 * ep3)
    _tmp79 = _tmp76 * dp3
    _tmp80 = _tmp76 * ep3
    _tmp81 = 2 * cp3
    _tmp82 = _tmp71 * _tmp76
    _tmp83 = _tmp72 * _tmp76
    _tmp84 = 2 * _tmp73
    _tmp85 = 4 * _tmp67
    _tmp86 = _tmp76 * _tmp85
    _tmp87 = _tmp82 + _tmp83 + _tmp86
    _tmp88 = cp0 * d_dp0
    _tmp89 = _tmp6 * _tmp88
    _tmp90 = cp0 * d_ep0
    _tmp91 = _tmp5 * _tmp90
    _tmp92 = _tmp6 * dp0
    _tmp93 = _tmp92 * d_cp0
    _tmp94 = _tmp5 * ep0
    _tmp95 = _tmp94 * d_cp0
    _tmp96 = _tmp1 * _tmp15
    _tmp97 = _tmp96 * d_dp0 + _tmp96 * d_ep0
    _tmp98 = _tmp11 * (_tmp89 + _tmp91 + 3 * _tmp93 + 3 * _tmp95 + _tmp97)
    _tmp99 = 2 * d_cp0
    _tmp100 = _tmp1 * _tmp99 + _tmp88 * ep0 + _tmp90 * dp0
    _tmp101 = _tmp100 * _tmp2
    _tmp102 = -_tmp101
    _tmp103 = _tmp0 * d_dp0
    _tmp104 = _tmp103 * ep0
    _tmp105 = _tmp0 * d_ep0
    _tmp106 = _tmp105 * dp0
    _tmp107 = _tmp92 * d_dp0
    _tmp108 = _tmp94 * d_ep0
    _tmp109 = -_tmp107 * _tmp15 - _tmp108 * _tmp15 - _tmp18 * d_cp0
    _tmp110 = _tmp15 * (-_tmp104 - _tmp106 - _tmp109 - _tmp20 * d_cp0)
    _tmp111 = 3 * d_cp0
    _tmp112 = _tmp89 + _tmp93
    _tmp113 = _tmp91 + _tmp95
    _tmp114 = _tmp0 * _tmp99
    _tmp115 = cp0 * d_cp0
    _tmp116 = cp1 * d_dp1
    _tmp117 = _tmp116 * _tmp28
    _tmp118 = cp1 * d_ep1
    _tmp119 = _tmp118 * _tmp27
    _tmp120 = _tmp28 * dp1
    _tmp121 = _tmp120 * d_cp1
    _tmp122 = _tmp27 * ep1
    _tmp123 = _tmp122 * d_cp1
    _tmp124 = _tmp23 * _tmp37
    _tmp125 = _tmp124 * d_dp1 + _tmp124 * d_ep1
    _tmp126 = _tmp33 * (_tmp117 + _tmp119 + 3 * _tmp121 + 3 * _tmp123 + _tmp125)
    _tmp127 = 2 * d_cp1
    _tmp128 = _tmp116 * ep1 + _tmp118 * dp1 + _tmp127 * _tmp23
    _tmp129 = _tmp128 * _tmp24
    _tmp130 = -_tmp129
    _tmp131 = _tmp22 * d_dp1
    _tmp132 = _tmp131 * ep1
    _tmp133 = _tmp22 * d_ep1
    _tmp134 = _tmp133 * dp1
    _tmp135 = _tmp120 * d_dp1
    _tmp136 = _tmp122 * d_ep1
    _tmp137 = -_tmp135 * _tmp37 - _tmp136 * _tmp37 - _tmp40 * d_cp1
    _tmp138 = _tmp37 * (-_tmp132 - _tmp134 - _tmp137 - _tmp42 * d_cp1)
    _tmp139 = 3 * d_cp1
    _tmp140 = _tmp117 + _tmp121
    _tmp141 = _tmp119 + _tmp123
    _tmp142 = _tmp127 * _tmp22
    _tmp143 = cp1 * d_cp1
    _tmp144 = cp2 * d_dp2
    _tmp145 = _tmp144 * _tmp50
    _tmp146 = cp2 * d_ep2
    _tmp147 = _tmp146 * _tmp49
    _tmp148 = _tmp50 * dp2
    _tmp149 = _tmp148 * d_cp2
    _tmp150 = _tmp49 * ep2
    _tmp151 = _tmp150 * d_cp2
    _tmp152 = _tmp45 * _tmp59
    _tmp153 = _tmp152 * d_dp2 + _tmp152 * d_ep2
    _tmp154 = _tmp55 * (_tmp145 + _tmp147 + 3 * _tmp149 + 3 * _tmp151 + _tmp153)
    _tmp155 = 2 * d_cp2
    _tmp156 = _tmp144 * ep2 + _tmp146 * dp2 + _tmp155 * _tmp45
    _tmp157 = _tmp156 * _tmp46
    _tmp158 = -_tmp157
    _tmp159 = _tmp44 * d_dp2
    _tmp160 = _tmp159 * ep2
    _tmp161 = _tmp44 * d_ep2
    _tmp162 = _tmp161 * dp2
    _tmp163 = _tmp148 * d_dp2
    _tmp164 = _tmp150 * d_ep2
    _tmp165 = -_tmp163 * _tmp59 - _tmp164 * _tmp59 - _tmp62 * d_cp2
    _tmp166 = _tmp59 * (-_tmp160 - _tmp162 - _tmp165 - _tmp64 * d_cp2)
    _tmp167 = 3 * d_cp2
    _tmp168 = _tmp145 + _tmp149
    _tmp169 = _tmp147 + _tmp151
    _tmp170 = _tmp155 * _tmp44
    _tmp171 = cp2 * d_cp2
    _tmp172 = cp3 * d_dp3
    _tmp173 = _tmp172 * _tmp72
    _tmp174 = cp3 * d_ep3
    _tmp175 = _tmp174 * _tmp71
    _tmp176 = _tmp72 * dp3
    _tmp177 = _tmp176 * d_cp3
    _tmp178 = _tmp71 * ep3
    _tmp179 = _tmp178 * d_cp3
    _tmp180 = _tmp67 * _tmp81
    _tmp181 = _tmp180 * d_dp3 + _tmp180 * d_ep3
    _tmp182 = _tmp77 * (_tmp173 + _tmp175 + 3 * _tmp177 + 3 * _tmp179 + _tmp181)
    _tmp183 = 2 * d_cp3
    _tmp184 = _tmp172 * ep3 + _tmp174 * dp3 + _tmp183 * _tmp67
    _tmp185 = _tmp184 * _tmp68
    _tmp186 = -_tmp185
    _tmp187 = _tmp66 * d_dp3
    _tmp188 = _tmp187 * ep3
    _tmp189 = _tmp66 * d_ep3
    _tmp190 = _tmp189 * dp3
    _tmp191 = _tmp176 * d_dp3
    _tmp192 = _tmp178 * d_ep3
    _tmp193 = -_tmp191 * _tmp81 - _tmp192 * _tmp81 - _tmp84 * d_cp3
    _tmp194 = _tmp81 * (-_tmp188 - _tmp190 - _tmp193 - _tmp86 * d_cp3)
    _tmp195 = 3 * d_cp3
    _tmp196 = _tmp173 + _tmp177
    _tmp197 = _tmp175 + _tmp179
    _tmp198 = _tmp183 * _tmp66
    _tmp199 = cp3 * d_cp3
    _tmp200 = _tmp15 * d_cp0
    _tmp201 = _tmp37 * d_cp1
    _tmp202 = _tmp59 * d_cp2
    _tmp203 = _tmp81 * d_cp3
    w[0] = _tmp3
    w[1] = -2 * _tmp8
    w[2] = -_tmp3
    w[3] = _tmp9
    w[4] = _tmp9
    w[5] = _tmp9
    w[6] = _tmp8
    w[7] = _tmp12
    w[8] = _tmp15 * (-_tmp13 - _tmp14 + _tmp5 * ep0 + _tmp6 * dp0)
    w[9] = _tmp16 * (_tmp10 + _tmp6)
    w[10] = _tmp17 * (_tmp10 + _tmp5)
    w[11] = _tmp12
    w[12] = _tmp10 * (-_tmp18 + _tmp21)
    w[13] = 2 * _tmp10 * dp0 * ep0 - _tmp4 - _tmp7
    w[14] = -_tmp21 + _tmp4 + _tmp7
    w[15] = _tmp25
    w[16] = -2 * _tmp30
    w[17] = -_tmp25
    w[18] = _tmp31
    w[19] = _tmp31
    w[20] = _tmp31
    w[21] = _tmp30
    w[22] = _tmp34
    w[23] = _tmp37 * (_tmp27 * ep1 + _tmp28 * dp1 - _tmp35 - _tmp36)
    w[24] = _tmp38 * (_tmp28 + _tmp32)
    w[25] = _tmp39 * (_tmp27 + _tmp32)
    w[26] = _tmp34
    w[27] = _tmp32 * (-_tmp40 + _tmp43)
    w[28] = -_tmp26 - _tmp29 + 2 * _tmp32 * dp1 * ep1
    w[29] = _tmp26 + _tmp29 - _tmp43
    w[30] = _tmp47
    w[31] = -2 * _tmp52
    w[32] = -_tmp47
    w[33] = _tmp53
    w[34] = _tmp53
    w[35] = _tmp53
    w[36] = _tmp52
    w[37] = _tmp56
    w[38] = _tmp59 * (_tmp49 * ep2 + _tmp50 * dp2 - _tmp57 - _tmp58)
    w[39] = _tmp60 * (_tmp50 + _tmp54)
    w[40] = _tmp61 * (_tmp49 + _tmp54)
    w[41] = _tmp56
    w[42] = _tmp54 * (-_tmp62 + _tmp65)
    w[43] = -_tmp48 - _tmp51 + 2 * _tmp54 * dp2 * ep2
    w[44] = _tmp48 + _tmp51 - _tmp65
    w[45] = _tmp69
    w[46] = -2 * _tmp74
    w[47] = -_tmp69
    w[48] = _tmp75
    w[49] = _tmp75
    w[50] = _tmp75
    w[51] = _tmp74
    w[52] = _tmp78
    w[53] = _tmp81 * (_tmp71 * ep3 + _tmp72 * dp3 - _tmp79 - _tmp80)
    w[54] = _tmp82 * (_tmp72 + _tmp76)
    w[55] = _tmp83 * (_tmp71 + _tmp76)
    w[56] = _tmp78
    w[57] = _tmp76 * (-_tmp84 + _tmp87)
    w[58] = -_tmp70 - _tmp73 + 2 * _tmp76 * dp3 * ep3
    w[59] = _tmp70 + _tmp73 - _tmp87
    w[60] = 1
    w[61] = _tmp10
    w[62] = -_tmp10
    w[63] = -1
    w[64] = 1
    w[65] = 1
    w[66] = _tmp32
    w[67] = -_tmp32
    w[68] = -1
    w[69] = 1
    w[70] = 1
    w[71] = _tmp54
    w[72] = -_tmp54
    w[73] = -1
    w[74] = 1
    w[75] = 1
    w[76] = _tmp76
    w[77] = -_tmp76
    w[78] = -1
    w[79] = 1
    w[80] = 1
    w[81] = -1
    wt[0] = _tmp98
    wt[1] = -_tmp0 * _tmp100 * _tmp19
    wt[2] = -_tmp98
    wt[3] = _tmp102
    wt[4] = _tmp102
    wt[5] = _tmp102
    wt[6] = _tmp101
    wt[7] = _tmp110
    wt[8] = (
        -2 * _tmp103
        - 2 * _tmp105
        - 2 * _tmp111 * _tmp13
        - 2 * _tmp111 * _tmp14
        + 2 * _tmp112
        + 2 * _tmp113
        + 2 * _tmp97
    )
    wt[9] = _tmp15 * dp0 * (_tmp1 * _tmp90 + _tmp103 + _tmp112 + _tmp13 * _tmp99)
    wt[10] = _tmp15 * ep0 * (_tmp1 * _tmp88 + _tmp105 + _tmp113 + _tmp14 * _tmp99)
    wt[11] = _tmp110
    wt[12] = _tmp15 * (
        8 * _tmp1 * _tmp10 * d_cp0
        + _tmp103 * dp0
        + 2 * _tmp104
        + _tmp105 * ep0
        + 2 * _tmp106
        + _tmp109
        + _tmp16 * _tmp99
        + _tmp17 * _tmp99
    )
    wt[13] = (
        2 * _tmp10 * d_dp0 * ep0
        + 2 * _tmp10 * d_ep0 * dp0
        - 2 * _tmp107
        - 2 * _tmp108
        - 2 * _tmp114
        + 4 * cp0 * d_cp0 * dp0 * ep0
    )
    wt[14] = (
        2 * _tmp107
        + 2 * _tmp108
        + 2 * _tmp114
        - 2 * _tmp115 * _tmp19
        - 2 * _tmp115 * _tmp5
        - 2 * _tmp115 * _tmp6
        - 2 * _tmp13 * d_dp0
        - 4 * _tmp13 * d_ep0
        - 4 * _tmp14 * d_dp0
        - 2 * _tmp14 * d_ep0
    )
    wt[15] = _tmp126
    wt[16] = -_tmp128 * _tmp22 * _tmp41
    wt[17] = -_tmp126
    wt[18] = _tmp130
    wt[19] = _tmp130
    wt[20] = _tmp130
    wt[21] = _tmp129
    wt[22] = _tmp138
    wt[23] = (
        2 * _tmp125
        - 2 * _tmp131
        - 2 * _tmp133
        - 2 * _tmp139 * _tmp35
        - 2 * _tmp139 * _tmp36
        + 2 * _tmp140
        + 2 * _tmp141
    )
    wt[24] = _tmp37 * dp1 * (_tmp118 * _tmp23 + _tmp127 * _tmp35 + _tmp131 + _tmp140)
    wt[25] = _tmp37 * ep1 * (_tmp116 * _tmp23 + _tmp127 * _tmp36 + _tmp133 + _tmp141)
    wt[26] = _tmp138
    wt[27] = _tmp37 * (
        _tmp127 * _tmp38
        + _tmp127 * _tmp39
        + _tmp131 * dp1
        + 2 * _tmp132
        + _tmp133 * ep1
        + 2 * _tmp134
        + _tmp137
        + 8 * _tmp23 * _tmp32 * d_cp1
    )
    wt[28] = (
        -2 * _tmp135
        - 2 * _tmp136
        - 2 * _tmp142
        + 2 * _tmp32 * d_dp1 * ep1
        + 2 * _tmp32 * d_ep1 * dp1
        + 4 * cp1 * d_cp1 * dp1 * ep1
    )
    wt[29] = (
        2 * _tmp135
        + 2 * _tmp136
        + 2 * _tmp142
        - 2 * _tmp143 * _tmp27
        - 2 * _tmp143 * _tmp28
        - 2 * _tmp143 * _tmp41
        - 2 * _tmp35 * d_dp1
        - 4 * _tmp35 * d_ep1
        - 4 * _tmp36 * d_dp1
        - 2 * _tmp36 * d_ep1
    )
    wt[30] = _tmp154
    wt[31] = -_tmp156 * _tmp44 * _tmp63
    wt[32] = -_tmp154
    wt[33] = _tmp158
    wt[34] = _tmp158
    wt[35] = _tmp158
    wt[36] = _tmp157
    wt[37] = _tmp166
    wt[38] = (
        2 * _tmp153
        - 2 * _tmp159
        - 2 * _tmp161
        - 2 * _tmp167 * _tmp57
        - 2 * _tmp167 * _tmp58
        + 2 * _tmp168
        + 2 * _tmp169
    )
    wt[39] = _tmp59 * dp2 * (_tmp146 * _tmp45 + _tmp155 * _tmp57 + _tmp159 + _tmp168)
    wt[40] = _tmp59 * ep2 * (_tmp144 * _tmp45 + _tmp155 * _tmp58 + _tmp161 + _tmp169)
    wt[41] = _tmp166
    wt[42] = _tmp59 * (
        _tmp155 * _tmp60
        + _tmp155 * _tmp61
        + _tmp159 * dp2
        + 2 * _tmp160
        + _tmp161 * ep2
        + 2 * _tmp162
        + _tmp165
        + 8 * _tmp45 * _tmp54 * d_cp2
    )
    wt[43] = (
        -2 * _tmp163
        - 2 * _tmp164
        - 2 * _tmp170
        + 2 * _tmp54 * d_dp2 * ep2
        + 2 * _tmp54 * d_ep2 * dp2
        + 4 * cp2 * d_cp2 * dp2 * ep2
    )
    wt[44] = (
        2 * _tmp163
        + 2 * _tmp164
        + 2 * _tmp170
        - 2 * _tmp171 * _tmp49
        - 2 * _tmp171 * _tmp50
        - 2 * _tmp171 * _tmp63
        - 2 * _tmp57 * d_dp2
        - 4 * _tmp57 * d_ep2
        - 4 * _tmp58 * d_dp2
        - 2 * _tmp58 * d_ep2
    )
    wt[45] = _tmp182
    wt[46] = -_tmp184 * _tmp66 * _tmp85
    wt[47] = -_tmp182
    wt[48] = _tmp186
    wt[49] = _tmp186
    wt[50] = _tmp186
    wt[51] = _tmp185
    wt[52] = _tmp194
    wt[53] = (
        2 * _tmp181
        - 2 * _tmp187
        - 2 * _tmp189
        - 2 * _tmp195 * _tmp79
        - 2 * _tmp195 * _tmp80
        + 2 * _tmp196
        + 2 * _tmp197
    )
    wt[54] = _tmp81 * dp3 * (_tmp174 * _tmp67 + _tmp183 * _tmp79 + _tmp187 + _tmp196)
    wt[55] = _tmp81 * ep3 * (_tmp172 * _tmp67 + _tmp183 * _tmp80 + _tmp189 + _tmp197)
    wt[56] = _tmp194
    wt[57] = _tmp81 * (
        _tmp183 * _tmp82
        + _tmp183 * _tmp83
        + _tmp187 * dp3
        + 2 * _tmp188
        + _tmp189 * ep3
        + 2 * _tmp190
        + _tmp193
        + 8 * _tmp67 * _tmp76 * d_cp3
    )
    wt[58] = (
        -2 * _tmp191
        - 2 * _tmp192
        - 2 * _tmp198
        + 2 * _tmp76 * d_dp3 * ep3
        + 2 * _tmp76 * d_ep3 * dp3
        + 4 * cp3 * d_cp3 * dp3 * ep3
    )
    wt[59] = (
        2 * _tmp191
        + 2 * _tmp192
        + 2 * _tmp198
        - 2 * _tmp199 * _tmp71
        - 2 * _tmp199 * _tmp72
        - 2 * _tmp199 * _tmp85
        - 2 * _tmp79 * d_dp3
        - 4 * _tmp79 * d_ep3
        - 4 * _tmp80 * d_dp3
        - 2 * _tmp80 * d_ep3
    )
    wt[60] = 0.0
    wt[61] = _tmp200
    wt[62] = -_tmp200
    wt[63] = 0.0
    wt[64] = 0.0
    wt[65] = 0.0
    wt[66] = _tmp201
    wt[67] = -_tmp201
    wt[68] = 0.0
    wt[69] = 0.0
    wt[70] = 0.0
    wt[71] = _tmp202
    wt[72] = -_tmp202
    wt[73] = 0.0
    wt[74] = 0.0
    wt[75] = 0.0
    wt[76] = _tmp203
    wt[77] = -_tmp203
    wt[78] = 0.0
    wt[79] = 0.0
    wt[80] = 0.0
    wt[81] = 0.0


@numba.njit(**_JIT)
def coefficient_rates(q: np.ndarray, dq: np.ndarray, wt: np.ndarray) -> None:
    """dW/dt = W_q . dq alone (``coefficients_t`` without W): a tracker needs it only where it
    keeps a tangent.

    Outputs written in place (every entry): wt.
    """
    cp0 = q[0]
    dp0 = q[1]
    ep0 = q[2]
    cp1 = q[3]
    dp1 = q[4]
    ep1 = q[5]
    cp2 = q[6]
    dp2 = q[7]
    ep2 = q[8]
    cp3 = q[9]
    dp3 = q[10]
    ep3 = q[11]
    d_cp0 = dq[0]
    d_dp0 = dq[1]
    d_ep0 = dq[2]
    d_cp1 = dq[3]
    d_dp1 = dq[4]
    d_ep1 = dq[5]
    d_cp2 = dq[6]
    d_dp2 = dq[7]
    d_ep2 = dq[8]
    d_cp3 = dq[9]
    d_dp3 = dq[10]
    d_ep3 = dq[11]
    _tmp0 = ep0 * ep0
    _tmp1 = cp0 * d_dp0
    _tmp2 = _tmp0 * _tmp1
    _tmp3 = dp0 * dp0
    _tmp4 = cp0 * d_ep0
    _tmp5 = _tmp3 * _tmp4
    _tmp6 = _tmp0 * dp0
    _tmp7 = _tmp6 * d_cp0
    _tmp8 = _tmp3 * ep0
    _tmp9 = _tmp8 * d_cp0
    _tmp10 = _tmp1 * ep0
    _tmp11 = _tmp10 * dp0
    _tmp12 = _tmp4 * dp0
    _tmp13 = _tmp12 * ep0
    _tmp14 = 2 * _tmp11 + 2 * _tmp13
    _tmp15 = cp0 * cp0
    _tmp16 = 2 * _tmp15
    _tmp17 = _tmp16 * (_tmp14 + _tmp2 + _tmp5 + 3 * _tmp7 + 3 * _tmp9)
    _tmp18 = dp0 * ep0
    _tmp19 = 4 * _tmp18
    _tmp20 = cp0 * cp0 * cp0
    _tmp21 = 2 * d_cp0
    _tmp22 = _tmp20 * (_tmp10 + _tmp12 + _tmp18 * _tmp21)
    _tmp23 = 2 * _tmp18 * _tmp22
    _tmp24 = -_tmp23
    _tmp25 = _tmp20 * d_dp0
    _tmp26 = _tmp25 * ep0
    _tmp27 = _tmp20 * d_ep0
    _tmp28 = _tmp27 * dp0
    _tmp29 = _tmp15 * d_cp0
    _tmp30 = -_tmp0 * _tmp21 * _tmp3 - 2 * _tmp2 * dp0 - 2 * _tmp5 * ep0
    _tmp31 = 2 * cp0
    _tmp32 = _tmp31 * (-_tmp19 * _tmp29 - _tmp26 - _tmp28 - _tmp30)
    _tmp33 = d_cp0 * dp0
    _tmp34 = 3 * _tmp15
    _tmp35 = d_cp0 * ep0
    _tmp36 = _tmp2 + _tmp7
    _tmp37 = _tmp5 + _tmp9
    _tmp38 = _tmp16 * d_cp0
    _tmp39 = _tmp20 * _tmp21
    _tmp40 = _tmp6 * d_dp0
    _tmp41 = _tmp8 * d_ep0
    _tmp42 = cp0 * d_cp0
    _tmp43 = ep1 * ep1
    _tmp44 = cp1 * d_dp1
    _tmp45 = _tmp43 * _tmp44
    _tmp46 = dp1 * dp1
    _tmp47 = cp1 * d_ep1
    _tmp48 = _tmp46 * _tmp47
    _tmp49 = _tmp43 * dp1
    _tmp50 = _tmp49 * d_cp1
    _tmp51 = _tmp46 * ep1
    _tmp52 = _tmp51 * d_cp1
    _tmp53 = _tmp44 * ep1
    _tmp54 = _tmp53 * dp1
    _tmp55 = _tmp47 * dp1
    _tmp56 = _tmp55 * ep1
    _tmp57 = 2 * _tmp54 + 2 * _tmp56
    _tmp58 = cp1 * cp1
    _tmp59 = 2 * _tmp58
    _tmp60 = _tmp59 * (_tmp45 + _tmp48 + 3 * _tmp50 + 3 * _tmp52 + _tmp57)
    _tmp61 = dp1 * ep1
    _tmp62 = 4 * _tmp61
    _tmp63 = cp1 * cp1 * cp1
    _tmp64 = 2 * d_cp1
    _tmp65 = _tmp63 * (_tmp53 + _tmp55 + _tmp61 * _tmp64)
    _tmp66 = 2 * _tmp61 * _tmp65
    _tmp67 = -_tmp66
    _tmp68 = _tmp63 * d_dp1
    _tmp69 = _tmp68 * ep1
    _tmp70 = _tmp63 * d_ep1
    _tmp71 = _tmp70 * dp1
    _tmp72 = _tmp58 * d_cp1
    _tmp73 = -_tmp43 * _tmp46 * _tmp64 - 2 * _tmp45 * dp1 - 2 * _tmp48 * ep1
    _tmp74 = 2 * cp1
    _tmp75 = _tmp74 * (-_tmp62 * _tmp72 - _tmp69 - _tmp71 - _tmp73)
    _tmp76 = d_cp1 * dp1
    _tmp77 = 3 * _tmp58
    _tmp78 = d_cp1 * ep1
    _tmp79 = _tmp45 + _tmp50
    _tmp80 = _tmp48 + _tmp52
    _tmp81 = _tmp59 * d_cp1
    _tmp82 = _tmp63 * _tmp64
    _tmp83 = _tmp49 * d_dp1
    _tmp84 = _tmp51 * d_ep1
    _tmp85 = cp1 * d_cp1
    _tmp86 = ep2 * ep2
    _tmp87 = cp2 * d_dp2
    _tmp88 = _tmp86 * _tmp87
    _tmp89 = dp2 * dp2
    _tmp90 = cp2 * d_ep2
    _tmp91 = _tmp89 * _tmp90
    _tmp92 = _tmp86 * dp2
    _tmp93 = _tmp92 * d_cp2
    _tmp94 = _tmp89 * ep2
    _tmp95 = _tmp94 * d_cp2
    _tmp96 = _tmp87 * ep2
    _tmp97 = _tmp96 * dp2
    _tmp98 = _tmp90 * dp2
    _tmp99 = _tmp98 * ep2
    _tmp100 = 2 * _tmp97 + 2 * _tmp99
    _tmp101 = cp2 * cp2
    _tmp102 = 2 * _tmp101
    _tmp103 = _tmp102 * (_tmp100 + _tmp88 + _tmp91 + 3 * _tmp93 + 3 * _tmp95)
    _tmp104 = dp2 * ep2
    _tmp105 = 4 * _tmp104
    _tmp106 = cp2 * cp2 * cp2
    _tmp107 = 2 * d_cp2
    _tmp108 = _tmp106 * (_tmp104 * _tmp107 + _tmp96 + _tmp98)
    _tmp109 = 2 * _tmp104 * _tmp108
    _tmp110 = -_tmp109
    _tmp111 = _tmp106 * d_dp2
    _tmp112 = _tmp111 * ep2
    _tmp113 = _tmp106 * d_ep2
    _tmp114 = _tmp113 * dp2
    _tmp115 = _tmp101 * d_cp2
    _tmp116 = -_tmp107 * _tmp86 * _tmp89 - 2 * _tmp88 * dp2 - 2 * _tmp91 * ep2
    _tmp117 = 2 * cp2
    _tmp118 = _tmp117 * (-_tmp105 * _tmp115 - _tmp112 - _tmp114 - _tmp116)
    _tmp119 = d_cp2 * dp2
    _tmp120 = 3 * _tmp101
    _tmp121 = d_cp2 * ep2
    _tmp122 = _tmp88 + _tmp93
    _tmp123 = _tmp91 + _tmp95
    _tmp124 = _tmp102 * d_cp2
    _tmp125 = _tmp106 * _tmp107
    _tmp126 = _tmp92 * d_dp2
    _tmp127 = _tmp94 * d_ep2
    _tmp128 = cp2 * d_cp2
    _tmp129 = ep3 * ep3
    _tmp130 = cp3 * d_dp3
    _tmp131 = _tmp129 * _tmp130
    _tmp132 = dp3 * dp3
    _tmp133 = cp3 * d_ep3
    _tmp134 = _tmp132 * _tmp133
    _tmp135 = _tmp129 * dp3
    _tmp136 = _tmp135 * d_cp3
    _tmp137 = _tmp132 * ep3
    _tmp138 = _tmp137 * d_cp3
    _tmp139 = _tmp130 * ep3
    _tmp140 = _tmp139 * dp3
    _tmp141 = _tmp133 * dp3
    _tmp142 = _tmp141 * ep3
    _tmp143 = 2 * _tmp140 + 2 * _tmp142
    _tmp144 = cp3 * cp3
    _tmp145 = 2 * _tmp144
    _tmp146 = _tmp145 * (_tmp131 + _tmp134 + 3 * _tmp136 + 3 * _tmp138 + _tmp143)
    _tmp147 = dp3 * ep3
    _tmp148 = 4 * _tmp147
    _tmp149 = cp3 * cp3 * cp3
    _tmp150 = 2 * d_cp3
    _tmp151 = _tmp149 * (_tmp139 + _tmp141 + _tmp147 * _tmp150)
    _tmp152 = 2 * _tmp147 * _tmp151
    _tmp153 = -_tmp152
    _tmp154 = _tmp149 * d_dp3
    _tmp155 = _tmp154 * ep3
    _tmp156 = _tmp149 * d_ep3
    _tmp157 = _tmp156 * dp3
    _tmp158 = _tmp144 * d_cp3
    _tmp159 = -_tmp129 * _tmp132 * _tmp150 - 2 * _tmp131 * dp3 - 2 * _tmp134 * ep3
    _tmp160 = 2 * cp3
    _tmp161 = _tmp160 * (-_tmp148 * _tmp158 - _tmp155 - _tmp157 - _tmp159)
    _tmp162 = d_cp3 * dp3
    _tmp163 = 3 * _tmp144
    _tmp164 = d_cp3 * ep3
    _tmp165 = _tmp131 + _tmp136
    _tmp166 = _tmp134 + _tmp138
    _tmp167 = _tmp145 * d_cp3
    _tmp168 = _tmp149 * _tmp150
    _tmp169 = _tmp135 * d_dp3
    _tmp170 = _tmp137 * d_ep3
    _tmp171 = cp3 * d_cp3
    _tmp172 = _tmp31 * d_cp0
    _tmp173 = _tmp74 * d_cp1
    _tmp174 = _tmp117 * d_cp2
    _tmp175 = _tmp160 * d_cp3
    wt[0] = _tmp17
    wt[1] = -_tmp19 * _tmp22
    wt[2] = -_tmp17
    wt[3] = _tmp24
    wt[4] = _tmp24
    wt[5] = _tmp24
    wt[6] = _tmp23
    wt[7] = _tmp32
    wt[8] = (
        2 * _tmp14
        - 2 * _tmp25
        - 2 * _tmp27
        - 2 * _tmp33 * _tmp34
        - 2 * _tmp34 * _tmp35
        + 2 * _tmp36
        + 2 * _tmp37
    )
    wt[9] = _tmp31 * dp0 * (_tmp13 + _tmp16 * _tmp33 + _tmp25 + _tmp36)
    wt[10] = _tmp31 * ep0 * (_tmp11 + _tmp16 * _tmp35 + _tmp27 + _tmp37)
    wt[11] = _tmp32
    wt[12] = _tmp31 * (
        _tmp0 * _tmp38
        + 8 * _tmp18 * _tmp29
        + _tmp25 * dp0
        + 2 * _tmp26
        + _tmp27 * ep0
        + 2 * _tmp28
        + _tmp3 * _tmp38
        + _tmp30
    )
    wt[13] = (
        2 * _tmp15 * d_dp0 * ep0
        + 2 * _tmp15 * d_ep0 * dp0
        - 2 * _tmp39
        - 2 * _tmp40
        - 2 * _tmp41
        + 4 * cp0 * d_cp0 * dp0 * ep0
    )
    wt[14] = (
        -2 * _tmp0 * _tmp42
        - 2 * _tmp15 * d_dp0 * dp0
        - 2 * _tmp15 * d_ep0 * ep0
        - 2 * _tmp16 * d_dp0 * ep0
        - 2 * _tmp16 * d_ep0 * dp0
        - 2 * _tmp19 * _tmp42
        - 2 * _tmp3 * _tmp42
        + 2 * _tmp39
        + 2 * _tmp40
        + 2 * _tmp41
    )
    wt[15] = _tmp60
    wt[16] = -_tmp62 * _tmp65
    wt[17] = -_tmp60
    wt[18] = _tmp67
    wt[19] = _tmp67
    wt[20] = _tmp67
    wt[21] = _tmp66
    wt[22] = _tmp75
    wt[23] = (
        2 * _tmp57
        - 2 * _tmp68
        - 2 * _tmp70
        - 2 * _tmp76 * _tmp77
        - 2 * _tmp77 * _tmp78
        + 2 * _tmp79
        + 2 * _tmp80
    )
    wt[24] = _tmp74 * dp1 * (_tmp56 + _tmp59 * _tmp76 + _tmp68 + _tmp79)
    wt[25] = _tmp74 * ep1 * (_tmp54 + _tmp59 * _tmp78 + _tmp70 + _tmp80)
    wt[26] = _tmp75
    wt[27] = _tmp74 * (
        _tmp43 * _tmp81
        + _tmp46 * _tmp81
        + 8 * _tmp61 * _tmp72
        + _tmp68 * dp1
        + 2 * _tmp69
        + _tmp70 * ep1
        + 2 * _tmp71
        + _tmp73
    )
    wt[28] = (
        2 * _tmp58 * d_dp1 * ep1
        + 2 * _tmp58 * d_ep1 * dp1
        - 2 * _tmp82
        - 2 * _tmp83
        - 2 * _tmp84
        + 4 * cp1 * d_cp1 * dp1 * ep1
    )
    wt[29] = (
        -2 * _tmp43 * _tmp85
        - 2 * _tmp46 * _tmp85
        - 2 * _tmp58 * d_dp1 * dp1
        - 2 * _tmp58 * d_ep1 * ep1
        - 2 * _tmp59 * d_dp1 * ep1
        - 2 * _tmp59 * d_ep1 * dp1
        - 2 * _tmp62 * _tmp85
        + 2 * _tmp82
        + 2 * _tmp83
        + 2 * _tmp84
    )
    wt[30] = _tmp103
    wt[31] = -_tmp105 * _tmp108
    wt[32] = -_tmp103
    wt[33] = _tmp110
    wt[34] = _tmp110
    wt[35] = _tmp110
    wt[36] = _tmp109
    wt[37] = _tmp118
    wt[38] = (
        2 * _tmp100
        - 2 * _tmp111
        - 2 * _tmp113
        - 2 * _tmp119 * _tmp120
        - 2 * _tmp120 * _tmp121
        + 2 * _tmp122
        + 2 * _tmp123
    )
    wt[39] = _tmp117 * dp2 * (_tmp102 * _tmp119 + _tmp111 + _tmp122 + _tmp99)
    wt[40] = _tmp117 * ep2 * (_tmp102 * _tmp121 + _tmp113 + _tmp123 + _tmp97)
    wt[41] = _tmp118
    wt[42] = _tmp117 * (
        8 * _tmp104 * _tmp115
        + _tmp111 * dp2
        + 2 * _tmp112
        + _tmp113 * ep2
        + 2 * _tmp114
        + _tmp116
        + _tmp124 * _tmp86
        + _tmp124 * _tmp89
    )
    wt[43] = (
        2 * _tmp101 * d_dp2 * ep2
        + 2 * _tmp101 * d_ep2 * dp2
        - 2 * _tmp125
        - 2 * _tmp126
        - 2 * _tmp127
        + 4 * cp2 * d_cp2 * dp2 * ep2
    )
    wt[44] = (
        -2 * _tmp101 * d_dp2 * dp2
        - 2 * _tmp101 * d_ep2 * ep2
        - 2 * _tmp102 * d_dp2 * ep2
        - 2 * _tmp102 * d_ep2 * dp2
        - 2 * _tmp105 * _tmp128
        + 2 * _tmp125
        + 2 * _tmp126
        + 2 * _tmp127
        - 2 * _tmp128 * _tmp86
        - 2 * _tmp128 * _tmp89
    )
    wt[45] = _tmp146
    wt[46] = -_tmp148 * _tmp151
    wt[47] = -_tmp146
    wt[48] = _tmp153
    wt[49] = _tmp153
    wt[50] = _tmp153
    wt[51] = _tmp152
    wt[52] = _tmp161
    wt[53] = (
        2 * _tmp143
        - 2 * _tmp154
        - 2 * _tmp156
        - 2 * _tmp162 * _tmp163
        - 2 * _tmp163 * _tmp164
        + 2 * _tmp165
        + 2 * _tmp166
    )
    wt[54] = _tmp160 * dp3 * (_tmp142 + _tmp145 * _tmp162 + _tmp154 + _tmp165)
    wt[55] = _tmp160 * ep3 * (_tmp140 + _tmp145 * _tmp164 + _tmp156 + _tmp166)
    wt[56] = _tmp161
    wt[57] = _tmp160 * (
        _tmp129 * _tmp167
        + _tmp132 * _tmp167
        + 8 * _tmp147 * _tmp158
        + _tmp154 * dp3
        + 2 * _tmp155
        + _tmp156 * ep3
        + 2 * _tmp157
        + _tmp159
    )
    wt[58] = (
        2 * _tmp144 * d_dp3 * ep3
        + 2 * _tmp144 * d_ep3 * dp3
        - 2 * _tmp168
        - 2 * _tmp169
        - 2 * _tmp170
        + 4 * cp3 * d_cp3 * dp3 * ep3
    )
    wt[59] = (
        -2 * _tmp129 * _tmp171
        - 2 * _tmp132 * _tmp171
        - 2 * _tmp144 * d_dp3 * dp3
        - 2 * _tmp144 * d_ep3 * ep3
        - 2 * _tmp145 * d_dp3 * ep3
        - 2 * _tmp145 * d_ep3 * dp3
        - 2 * _tmp148 * _tmp171
        + 2 * _tmp168
        + 2 * _tmp169
        + 2 * _tmp170
    )
    wt[60] = 0.0
    wt[61] = _tmp172
    wt[62] = -_tmp172
    wt[63] = 0.0
    wt[64] = 0.0
    wt[65] = 0.0
    wt[66] = _tmp173
    wt[67] = -_tmp173
    wt[68] = 0.0
    wt[69] = 0.0
    wt[70] = 0.0
    wt[71] = _tmp174
    wt[72] = -_tmp174
    wt[73] = 0.0
    wt[74] = 0.0
    wt[75] = 0.0
    wt[76] = _tmp175
    wt[77] = -_tmp175
    wt[78] = 0.0
    wt[79] = 0.0
    wt[80] = 0.0
    wt[81] = 0.0


@numba.njit(**_JIT)
def residual_jacobian(x: np.ndarray, w: np.ndarray, f: np.ndarray, jac: np.ndarray) -> None:
    """F(x; q) = W(q) u(x) and its Jacobian F_x, from W's entries w.

    Outputs written in place (every entry): f, jac.
    """
    C = x[0]
    A = x[1]
    B = x[2]
    P = x[3]
    m = x[4]
    s0 = x[5]
    s1 = x[6]
    s2 = x[7]
    s3 = x[8]
    w0 = w[0]
    w1 = w[1]
    w2 = w[2]
    w3 = w[3]
    w4 = w[4]
    w5 = w[5]
    w6 = w[6]
    w7 = w[7]
    w8 = w[8]
    w9 = w[9]
    w10 = w[10]
    w11 = w[11]
    w12 = w[12]
    w13 = w[13]
    w14 = w[14]
    w15 = w[15]
    w16 = w[16]
    w17 = w[17]
    w18 = w[18]
    w19 = w[19]
    w20 = w[20]
    w21 = w[21]
    w22 = w[22]
    w23 = w[23]
    w24 = w[24]
    w25 = w[25]
    w26 = w[26]
    w27 = w[27]
    w28 = w[28]
    w29 = w[29]
    w30 = w[30]
    w31 = w[31]
    w32 = w[32]
    w33 = w[33]
    w34 = w[34]
    w35 = w[35]
    w36 = w[36]
    w37 = w[37]
    w38 = w[38]
    w39 = w[39]
    w40 = w[40]
    w41 = w[41]
    w42 = w[42]
    w43 = w[43]
    w44 = w[44]
    w45 = w[45]
    w46 = w[46]
    w47 = w[47]
    w48 = w[48]
    w49 = w[49]
    w50 = w[50]
    w51 = w[51]
    w52 = w[52]
    w53 = w[53]
    w54 = w[54]
    w55 = w[55]
    w56 = w[56]
    w57 = w[57]
    w58 = w[58]
    w59 = w[59]
    w61 = w[61]
    w62 = w[62]
    w66 = w[66]
    w67 = w[67]
    w71 = w[71]
    w72 = w[72]
    w76 = w[76]
    w77 = w[77]
    _tmp0 = B * w5
    _tmp1 = A * w10
    _tmp2 = B * w9
    _tmp3 = m * w7
    _tmp4 = s0 * w2
    _tmp5 = A * B
    _tmp6 = _tmp5 * w11
    _tmp7 = B * P
    _tmp8 = A * _tmp7
    _tmp9 = s0 * w8
    _tmp10 = _tmp9 * m
    _tmp11 = C * w12
    _tmp12 = C * C
    _tmp13 = _tmp12 * _tmp5
    _tmp14 = _tmp12 * w14
    _tmp15 = B * w20
    _tmp16 = A * w25
    _tmp17 = B * w24
    _tmp18 = m * w22
    _tmp19 = s1 * w17
    _tmp20 = _tmp5 * w26
    _tmp21 = C * m
    _tmp22 = s1 * w23
    _tmp23 = C * w27
    _tmp24 = _tmp12 * w29
    _tmp25 = B * w35
    _tmp26 = A * w40
    _tmp27 = B * w39
    _tmp28 = m * w37
    _tmp29 = s2 * w32
    _tmp30 = _tmp5 * w41
    _tmp31 = s2 * w38
    _tmp32 = C * w42
    _tmp33 = _tmp12 * w44
    _tmp34 = B * w50
    _tmp35 = A * w55
    _tmp36 = B * w54
    _tmp37 = m * w52
    _tmp38 = s3 * w47
    _tmp39 = _tmp5 * w56
    _tmp40 = s3 * w53
    _tmp41 = C * w57
    _tmp42 = _tmp12 * w59
    _tmp43 = C * _tmp5
    _tmp44 = P * w62
    _tmp45 = _tmp12 * _tmp8 - _tmp13
    _tmp46 = C * P
    _tmp47 = _tmp46 * _tmp5
    _tmp48 = 2 * C
    _tmp49 = _tmp48 * _tmp5
    _tmp50 = _tmp48 * _tmp8
    _tmp51 = C * w11
    _tmp52 = _tmp12 * w13
    _tmp53 = A * P
    _tmp54 = C * w26
    _tmp55 = _tmp12 * w28
    _tmp56 = C * w41
    _tmp57 = _tmp12 * w43
    _tmp58 = C * w56
    _tmp59 = _tmp12 * w58
    _tmp60 = _tmp44 + w61
    _tmp61 = P * _tmp48 - _tmp48
    _tmp62 = -C + _tmp46
    _tmp63 = C * (_tmp60 + _tmp62)
    _tmp64 = P * w67 + w66
    _tmp65 = C * (_tmp62 + _tmp64)
    _tmp66 = P * w72 + w71
    _tmp67 = C * (_tmp62 + _tmp66)
    _tmp68 = P * w77 + w76
    _tmp69 = C * (_tmp62 + _tmp68)
    f[0] = (
        A * _tmp0
        + A * w4
        + B * w3
        + C * _tmp1
        + C * _tmp10
        + C * _tmp2
        + C * _tmp3
        + C * _tmp6
        + _tmp11 * _tmp8
        + _tmp13 * w13
        + _tmp14 * _tmp8
        + _tmp4 * m
        + _tmp8 * w6
        + m * w1
        + s0 * w0
    )
    f[1] = (
        A * _tmp15
        + A * w19
        + B * w18
        + C * _tmp16
        + C * _tmp17
        + C * _tmp18
        + C * _tmp20
        + _tmp13 * w28
        + _tmp19 * m
        + _tmp21 * _tmp22
        + _tmp23 * _tmp8
        + _tmp24 * _tmp8
        + _tmp8 * w21
        + m * w16
        + s1 * w15
    )
    f[2] = (
        A * _tmp25
        + A * w34
        + B * w33
        + C * _tmp26
        + C * _tmp27
        + C * _tmp28
        + C * _tmp30
        + _tmp13 * w43
        + _tmp21 * _tmp31
        + _tmp29 * m
        + _tmp32 * _tmp8
        + _tmp33 * _tmp8
        + _tmp8 * w36
        + m * w31
        + s2 * w30
    )
    f[3] = (
        A * _tmp34
        + A * w49
        + B * w48
        + C * _tmp35
        + C * _tmp36
        + C * _tmp37
        + C * _tmp39
        + _tmp13 * w58
        + _tmp21 * _tmp40
        + _tmp38 * m
        + _tmp41 * _tmp8
        + _tmp42 * _tmp8
        + _tmp8 * w51
        + m * w46
        + s3 * w45
    )
    f[4] = _tmp43 * _tmp44 + _tmp43 * w61 + _tmp45 + s0 * s0
    f[5] = _tmp43 * w66 + _tmp45 + _tmp47 * w67 + s1 * s1
    f[6] = _tmp43 * w71 + _tmp45 + _tmp47 * w72 + s2 * s2
    f[7] = _tmp43 * w76 + _tmp45 + _tmp47 * w77 + s3 * s3
    f[8] = -_tmp8 + m * m
    jac[0, 0] = _tmp1 + _tmp10 + _tmp2 + _tmp3 + _tmp49 * w13 + _tmp50 * w14 + _tmp6 + _tmp8 * w12
    jac[0, 1] = (
        B * _tmp51
        + B * _tmp52
        + C * w10
        + _tmp0
        + _tmp11 * _tmp7
        + _tmp14 * _tmp7
        + _tmp7 * w6
        + w4
    )
    jac[0, 2] = (
        A * _tmp51
        + A * _tmp52
        + A * w5
        + C * w9
        + _tmp11 * _tmp53
        + _tmp14 * _tmp53
        + _tmp53 * w6
        + w3
    )
    jac[0, 3] = _tmp5 * (_tmp11 + _tmp14 + w6)
    jac[0, 4] = C * _tmp9 + C * w7 + _tmp4 + w1
    jac[0, 5] = _tmp21 * w8 + m * w2 + w0
    jac[0, 6] = 0.0
    jac[0, 7] = 0.0
    jac[0, 8] = 0.0
    jac[1, 0] = (
        _tmp16 + _tmp17 + _tmp18 + _tmp20 + _tmp22 * m + _tmp49 * w28 + _tmp50 * w29 + _tmp8 * w27
    )
    jac[1, 1] = (
        B * _tmp54
        + B * _tmp55
        + C * w25
        + _tmp15
        + _tmp23 * _tmp7
        + _tmp24 * _tmp7
        + _tmp7 * w21
        + w19
    )
    jac[1, 2] = (
        A * _tmp54
        + A * _tmp55
        + A * w20
        + C * w24
        + _tmp23 * _tmp53
        + _tmp24 * _tmp53
        + _tmp53 * w21
        + w18
    )
    jac[1, 3] = _tmp5 * (_tmp23 + _tmp24 + w21)
    jac[1, 4] = C * _tmp22 + C * w22 + _tmp19 + w16
    jac[1, 5] = 0.0
    jac[1, 6] = _tmp21 * w23 + m * w17 + w15
    jac[1, 7] = 0.0
    jac[1, 8] = 0.0
    jac[2, 0] = (
        _tmp26 + _tmp27 + _tmp28 + _tmp30 + _tmp31 * m + _tmp49 * w43 + _tmp50 * w44 + _tmp8 * w42
    )
    jac[2, 1] = (
        B * _tmp56
        + B * _tmp57
        + C * w40
        + _tmp25
        + _tmp32 * _tmp7
        + _tmp33 * _tmp7
        + _tmp7 * w36
        + w34
    )
    jac[2, 2] = (
        A * _tmp56
        + A * _tmp57
        + A * w35
        + C * w39
        + _tmp32 * _tmp53
        + _tmp33 * _tmp53
        + _tmp53 * w36
        + w33
    )
    jac[2, 3] = _tmp5 * (_tmp32 + _tmp33 + w36)
    jac[2, 4] = C * _tmp31 + C * w37 + _tmp29 + w31
    jac[2, 5] = 0.0
    jac[2, 6] = 0.0
    jac[2, 7] = _tmp21 * w38 + m * w32 + w30
    jac[2, 8] = 0.0
    jac[3, 0] = (
        _tmp35 + _tmp36 + _tmp37 + _tmp39 + _tmp40 * m + _tmp49 * w58 + _tmp50 * w59 + _tmp8 * w57
    )
    jac[3, 1] = (
        B * _tmp58
        + B * _tmp59
        + C * w55
        + _tmp34
        + _tmp41 * _tmp7
        + _tmp42 * _tmp7
        + _tmp7 * w51
        + w49
    )
    jac[3, 2] = (
        A * _tmp58
        + A * _tmp59
        + A * w50
        + C * w54
        + _tmp41 * _tmp53
        + _tmp42 * _tmp53
        + _tmp53 * w51
        + w48
    )
    jac[3, 3] = _tmp5 * (_tmp41 + _tmp42 + w51)
    jac[3, 4] = C * _tmp40 + C * w52 + _tmp38 + w46
    jac[3, 5] = 0.0
    jac[3, 6] = 0.0
    jac[3, 7] = 0.0
    jac[3, 8] = _tmp21 * w53 + m * w47 + w45
    jac[4, 0] = _tmp5 * (_tmp60 + _tmp61)
    jac[4, 1] = B * _tmp63
    jac[4, 2] = A * _tmp63
    jac[4, 3] = _tmp43 * (C + w62)
    jac[4, 4] = 0.0
    jac[4, 5] = 2 * s0
    jac[4, 6] = 0.0
    jac[4, 7] = 0.0
    jac[4, 8] = 0.0
    jac[5, 0] = _tmp5 * (_tmp61 + _tmp64)
    jac[5, 1] = B * _tmp65
    jac[5, 2] = A * _tmp65
    jac[5, 3] = _tmp43 * (C + w67)
    jac[5, 4] = 0.0
    jac[5, 5] = 0.0
    jac[5, 6] = 2 * s1
    jac[5, 7] = 0.0
    jac[5, 8] = 0.0
    jac[6, 0] = _tmp5 * (_tmp61 + _tmp66)
    jac[6, 1] = B * _tmp67
    jac[6, 2] = A * _tmp67
    jac[6, 3] = _tmp43 * (C + w72)
    jac[6, 4] = 0.0
    jac[6, 5] = 0.0
    jac[6, 6] = 0.0
    jac[6, 7] = 2 * s2
    jac[6, 8] = 0.0
    jac[7, 0] = _tmp5 * (_tmp61 + _tmp68)
    jac[7, 1] = B * _tmp69
    jac[7, 2] = A * _tmp69
    jac[7, 3] = _tmp43 * (C + w77)
    jac[7, 4] = 0.0
    jac[7, 5] = 0.0
    jac[7, 6] = 0.0
    jac[7, 7] = 0.0
    jac[7, 8] = 2 * s3
    jac[8, 0] = 0.0
    jac[8, 1] = -_tmp7
    jac[8, 2] = -_tmp53
    jac[8, 3] = -_tmp5
    jac[8, 4] = 2 * m
    jac[8, 5] = 0.0
    jac[8, 6] = 0.0
    jac[8, 7] = 0.0
    jac[8, 8] = 0.0


@numba.njit(**_JIT)
def residual_jacobian_t(
    x: np.ndarray, w: np.ndarray, wt: np.ndarray, f: np.ndarray, jac: np.ndarray, ft: np.ndarray
) -> None:
    """F and F_x as ``residual_jacobian``, and F_t = (dW/dt) u(x) from dW/dt's entries wt.

    Outputs written in place (every entry): f, jac, ft.
    """
    C = x[0]
    A = x[1]
    B = x[2]
    P = x[3]
    m = x[4]
    s0 = x[5]
    s1 = x[6]
    s2 = x[7]
    s3 = x[8]
    w0 = w[0]
    w1 = w[1]
    w2 = w[2]
    w3 = w[3]
    w4 = w[4]
    w5 = w[5]
    w6 = w[6]
    w7 = w[7]
    w8 = w[8]
    w9 = w[9]
    w10 = w[10]
    w11 = w[11]
    w12 = w[12]
    w13 = w[13]
    w14 = w[14]
    w15 = w[15]
    w16 = w[16]
    w17 = w[17]
    w18 = w[18]
    w19 = w[19]
    w20 = w[20]
    w21 = w[21]
    w22 = w[22]
    w23 = w[23]
    w24 = w[24]
    w25 = w[25]
    w26 = w[26]
    w27 = w[27]
    w28 = w[28]
    w29 = w[29]
    w30 = w[30]
    w31 = w[31]
    w32 = w[32]
    w33 = w[33]
    w34 = w[34]
    w35 = w[35]
    w36 = w[36]
    w37 = w[37]
    w38 = w[38]
    w39 = w[39]
    w40 = w[40]
    w41 = w[41]
    w42 = w[42]
    w43 = w[43]
    w44 = w[44]
    w45 = w[45]
    w46 = w[46]
    w47 = w[47]
    w48 = w[48]
    w49 = w[49]
    w50 = w[50]
    w51 = w[51]
    w52 = w[52]
    w53 = w[53]
    w54 = w[54]
    w55 = w[55]
    w56 = w[56]
    w57 = w[57]
    w58 = w[58]
    w59 = w[59]
    w61 = w[61]
    w62 = w[62]
    w66 = w[66]
    w67 = w[67]
    w71 = w[71]
    w72 = w[72]
    w76 = w[76]
    w77 = w[77]
    wt0 = wt[0]
    wt1 = wt[1]
    wt2 = wt[2]
    wt3 = wt[3]
    wt4 = wt[4]
    wt5 = wt[5]
    wt6 = wt[6]
    wt7 = wt[7]
    wt8 = wt[8]
    wt9 = wt[9]
    wt10 = wt[10]
    wt11 = wt[11]
    wt12 = wt[12]
    wt13 = wt[13]
    wt14 = wt[14]
    wt15 = wt[15]
    wt16 = wt[16]
    wt17 = wt[17]
    wt18 = wt[18]
    wt19 = wt[19]
    wt20 = wt[20]
    wt21 = wt[21]
    wt22 = wt[22]
    wt23 = wt[23]
    wt24 = wt[24]
    wt25 = wt[25]
    wt26 = wt[26]
    wt27 = wt[27]
    wt28 = wt[28]
    wt29 = wt[29]
    wt30 = wt[30]
    wt31 = wt[31]
    wt32 = wt[32]
    wt33 = wt[33]
    wt34 = wt[34]
    wt35 = wt[35]
    wt36 = wt[36]
    wt37 = wt[37]
    wt38 = wt[38]
    wt39 = wt[39]
    wt40 = wt[40]
    wt41 = wt[41]
    wt42 = wt[42]
    wt43 = wt[43]
    wt44 = wt[44]
    wt45 = wt[45]
    wt46 = wt[46]
    wt47 = wt[47]
    wt48 = wt[48]
    wt49 = wt[49]
    wt50 = wt[50]
    wt51 = wt[51]
    wt52 = wt[52]
    wt53 = wt[53]
    wt54 = wt[54]
    wt55 = wt[55]
    wt56 = wt[56]
    wt57 = wt[57]
    wt58 = wt[58]
    wt59 = wt[59]
    wt61 = wt[61]
    wt62 = wt[62]
    wt66 = wt[66]
    wt67 = wt[67]
    wt71 = wt[71]
    wt72 = wt[72]
    wt76 = wt[76]
    wt77 = wt[77]
    _tmp0 = B * w5
    _tmp1 = A * w10
    _tmp2 = B * w9
    _tmp3 = m * w7
    _tmp4 = s0 * w2
    _tmp5 = A * B
    _tmp6 = _tmp5 * w11
    _tmp7 = B * P
    _tmp8 = A * _tmp7
    _tmp9 = s0 * w8
    _tmp10 = _tmp9 * m
    _tmp11 = C * w12
    _tmp12 = C * C
    _tmp13 = _tmp12 * _tmp5
    _tmp14 = _tmp12 * w14
    _tmp15 = B * w20
    _tmp16 = A * w25
    _tmp17 = B * w24
    _tmp18 = m * w22
    _tmp19 = s1 * w17
    _tmp20 = _tmp5 * w26
    _tmp21 = C * m
    _tmp22 = s1 * w23
    _tmp23 = C * w27
    _tmp24 = _tmp12 * w29
    _tmp25 = B * w35
    _tmp26 = A * w40
    _tmp27 = B * w39
    _tmp28 = m * w37
    _tmp29 = s2 * w32
    _tmp30 = _tmp5 * w41
    _tmp31 = s2 * w38
    _tmp32 = C * w42
    _tmp33 = _tmp12 * w44
    _tmp34 = B * w50
    _tmp35 = A * w55
    _tmp36 = B * w54
    _tmp37 = m * w52
    _tmp38 = s3 * w47
    _tmp39 = _tmp5 * w56
    _tmp40 = s3 * w53
    _tmp41 = C * w57
    _tmp42 = _tmp12 * w59
    _tmp43 = C * _tmp5
    _tmp44 = P * w62
    _tmp45 = _tmp12 * _tmp8
    _tmp46 = -_tmp13 + _tmp45
    _tmp47 = C * P
    _tmp48 = _tmp47 * _tmp5
    _tmp49 = 2 * C
    _tmp50 = _tmp49 * _tmp5
    _tmp51 = _tmp49 * _tmp8
    _tmp52 = C * w11
    _tmp53 = _tmp12 * w13
    _tmp54 = A * P
    _tmp55 = C * w26
    _tmp56 = _tmp12 * w28
    _tmp57 = C * w41
    _tmp58 = _tmp12 * w43
    _tmp59 = C * w56
    _tmp60 = _tmp12 * w58
    _tmp61 = _tmp44 + w61
    _tmp62 = P * _tmp49 - _tmp49
    _tmp63 = -C + _tmp47
    _tmp64 = C * (_tmp61 + _tmp63)
    _tmp65 = P * w67 + w66
    _tmp66 = C * (_tmp63 + _tmp65)
    _tmp67 = P * w72 + w71
    _tmp68 = C * (_tmp63 + _tmp67)
    _tmp69 = P * w77 + w76
    _tmp70 = C * (_tmp63 + _tmp69)
    _tmp71 = A * C
    _tmp72 = B * C
    f[0] = (
        A * _tmp0
        + A * w4
        + B * w3
        + C * _tmp1
        + C * _tmp10
        + C * _tmp2
        + C * _tmp3
        + C * _tmp6
        + _tmp11 * _tmp8
        + _tmp13 * w13
        + _tmp14 * _tmp8
        + _tmp4 * m
        + _tmp8 * w6
        + m * w1
        + s0 * w0
    )
    f[1] = (
        A * _tmp15
        + A * w19
        + B * w18
        + C * _tmp16
        + C * _tmp17
        + C * _tmp18
        + C * _tmp20
        + _tmp13 * w28
        + _tmp19 * m
        + _tmp21 * _tmp22
        + _tmp23 * _tmp8
        + _tmp24 * _tmp8
        + _tmp8 * w21
        + m * w16
        + s1 * w15
    )
    f[2] = (
        A * _tmp25
        + A * w34
        + B * w33
        + C * _tmp26
        + C * _tmp27
        + C * _tmp28
        + C * _tmp30
        + _tmp13 * w43
        + _tmp21 * _tmp31
        + _tmp29 * m
        + _tmp32 * _tmp8
        + _tmp33 * _tmp8
        + _tmp8 * w36
        + m * w31
        + s2 * w30
    )
    f[3] = (
        A * _tmp34
        + A * w49
        + B * w48
        + C * _tmp35
        + C * _tmp36
        + C * _tmp37
        + C * _tmp39
        + _tmp13 * w58
        + _tmp21 * _tmp40
        + _tmp38 * m
        + _tmp41 * _tmp8
        + _tmp42 * _tmp8
        + _tmp8 * w51
        + m * w46
        + s3 * w45
    )
    f[4] = _tmp43 * _tmp44 + _tmp43 * w61 + _tmp46 + s0 * s0
    f[5] = _tmp43 * w66 + _tmp46 + _tmp48 * w67 + s1 * s1
    f[6] = _tmp43 * w71 + _tmp46 + _tmp48 * w72 + s2 * s2
    f[7] = _tmp43 * w76 + _tmp46 + _tmp48 * w77 + s3 * s3
    f[8] = -_tmp8 + m * m
    jac[0, 0] = _tmp1 + _tmp10 + _tmp2 + _tmp3 + _tmp50 * w13 + _tmp51 * w14 + _tmp6 + _tmp8 * w12
    jac[0, 1] = (
        B * _tmp52
        + B * _tmp53
        + C * w10
        + _tmp0
        + _tmp11 * _tmp7
        + _tmp14 * _tmp7
        + _tmp7 * w6
        + w4
    )
    jac[0, 2] = (
        A * _tmp52
        + A * _tmp53
        + A * w5
        + C * w9
        + _tmp11 * _tmp54
        + _tmp14 * _tmp54
        + _tmp54 * w6
        + w3
    )
    jac[0, 3] = _tmp5 * (_tmp11 + _tmp14 + w6)
    jac[0, 4] = C * _tmp9 + C * w7 + _tmp4 + w1
    jac[0, 5] = _tmp21 * w8 + m * w2 + w0
    jac[0, 6] = 0.0
    jac[0, 7] = 0.0
    jac[0, 8] = 0.0
    jac[1, 0] = (
        _tmp16 + _tmp17 + _tmp18 + _tmp20 + _tmp22 * m + _tmp50 * w28 + _tmp51 * w29 + _tmp8 * w27
    )
    jac[1, 1] = (
        B * _tmp55
        + B * _tmp56
        + C * w25
        + _tmp15
        + _tmp23 * _tmp7
        + _tmp24 * _tmp7
        + _tmp7 * w21
        + w19
    )
    jac[1, 2] = (
        A * _tmp55
        + A * _tmp56
        + A * w20
        + C * w24
        + _tmp23 * _tmp54
        + _tmp24 * _tmp54
        + _tmp54 * w21
        + w18
    )
    jac[1, 3] = _tmp5 * (_tmp23 + _tmp24 + w21)
    jac[1, 4] = C * _tmp22 + C * w22 + _tmp19 + w16
    jac[1, 5] = 0.0
    jac[1, 6] = _tmp21 * w23 + m * w17 + w15
    jac[1, 7] = 0.0
    jac[1, 8] = 0.0
    jac[2, 0] = (
        _tmp26 + _tmp27 + _tmp28 + _tmp30 + _tmp31 * m + _tmp50 * w43 + _tmp51 * w44 + _tmp8 * w42
    )
    jac[2, 1] = (
        B * _tmp57
        + B * _tmp58
        + C * w40
        + _tmp25
        + _tmp32 * _tmp7
        + _tmp33 * _tmp7
        + _tmp7 * w36
        + w34
    )
    jac[2, 2] = (
        A * _tmp57
        + A * _tmp58
        + A * w35
        + C * w39
        + _tmp32 * _tmp54
        + _tmp33 * _tmp54
        + _tmp54 * w36
        + w33
    )
    jac[2, 3] = _tmp5 * (_tmp32 + _tmp33 + w36)
    jac[2, 4] = C * _tmp31 + C * w37 + _tmp29 + w31
    jac[2, 5] = 0.0
    jac[2, 6] = 0.0
    jac[2, 7] = _tmp21 * w38 + m * w32 + w30
    jac[2, 8] = 0.0
    jac[3, 0] = (
        _tmp35 + _tmp36 + _tmp37 + _tmp39 + _tmp40 * m + _tmp50 * w58 + _tmp51 * w59 + _tmp8 * w57
    )
    jac[3, 1] = (
        B * _tmp59
        + B * _tmp60
        + C * w55
        + _tmp34
        + _tmp41 * _tmp7
        + _tmp42 * _tmp7
        + _tmp7 * w51
        + w49
    )
    jac[3, 2] = (
        A * _tmp59
        + A * _tmp60
        + A * w50
        + C * w54
        + _tmp41 * _tmp54
        + _tmp42 * _tmp54
        + _tmp54 * w51
        + w48
    )
    jac[3, 3] = _tmp5 * (_tmp41 + _tmp42 + w51)
    jac[3, 4] = C * _tmp40 + C * w52 + _tmp38 + w46
    jac[3, 5] = 0.0
    jac[3, 6] = 0.0
    jac[3, 7] = 0.0
    jac[3, 8] = _tmp21 * w53 + m * w47 + w45
    jac[4, 0] = _tmp5 * (_tmp61 + _tmp62)
    jac[4, 1] = B * _tmp64
    jac[4, 2] = A * _tmp64
    jac[4, 3] = _tmp43 * (C + w62)
    jac[4, 4] = 0.0
    jac[4, 5] = 2 * s0
    jac[4, 6] = 0.0
    jac[4, 7] = 0.0
    jac[4, 8] = 0.0
    jac[5, 0] = _tmp5 * (_tmp62 + _tmp65)
    jac[5, 1] = B * _tmp66
    jac[5, 2] = A * _tmp66
    jac[5, 3] = _tmp43 * (C + w67)
    jac[5, 4] = 0.0
    jac[5, 5] = 0.0
    jac[5, 6] = 2 * s1
    jac[5, 7] = 0.0
    jac[5, 8] = 0.0
    jac[6, 0] = _tmp5 * (_tmp62 + _tmp67)
    jac[6, 1] = B * _tmp68
    jac[6, 2] = A * _tmp68
    jac[6, 3] = _tmp43 * (C + w72)
    jac[6, 4] = 0.0
    jac[6, 5] = 0.0
    jac[6, 6] = 0.0
    jac[6, 7] = 2 * s2
    jac[6, 8] = 0.0
    jac[7, 0] = _tmp5 * (_tmp62 + _tmp69)
    jac[7, 1] = B * _tmp70
    jac[7, 2] = A * _tmp70
    jac[7, 3] = _tmp43 * (C + w77)
    jac[7, 4] = 0.0
    jac[7, 5] = 0.0
    jac[7, 6] = 0.0
    jac[7, 7] = 0.0
    jac[7, 8] = 2 * s3
    jac[8, 0] = 0.0
    jac[8, 1] = -_tmp7
    jac[8, 2] = -_tmp54
    jac[8, 3] = -_tmp5
    jac[8, 4] = 2 * m
    jac[8, 5] = 0.0
    jac[8, 6] = 0.0
    jac[8, 7] = 0.0
    jac[8, 8] = 0.0
    ft[0] = (
        A * wt4
        + B * wt3
        + _tmp13 * wt13
        + _tmp21 * s0 * wt8
        + _tmp21 * wt7
        + _tmp43 * wt11
        + _tmp45 * wt14
        + _tmp48 * wt12
        + _tmp5 * wt5
        + _tmp71 * wt10
        + _tmp72 * wt9
        + _tmp8 * wt6
        + m * s0 * wt2
        + m * wt1
        + s0 * wt0
    )
    ft[1] = (
        A * wt19
        + B * wt18
        + _tmp13 * wt28
        + _tmp21 * s1 * wt23
        + _tmp21 * wt22
        + _tmp43 * wt26
        + _tmp45 * wt29
        + _tmp48 * wt27
        + _tmp5 * wt20
        + _tmp71 * wt25
        + _tmp72 * wt24
        + _tmp8 * wt21
        + m * s1 * wt17
        + m * wt16
        + s1 * wt15
    )
    ft[2] = (
        A * wt34
        + B * wt33
        + _tmp13 * wt43
        + _tmp21 * s2 * wt38
        + _tmp21 * wt37
        + _tmp43 * wt41
        + _tmp45 * wt44
        + _tmp48 * wt42
        + _tmp5 * wt35
        + _tmp71 * wt40
        + _tmp72 * wt39
        + _tmp8 * wt36
        + m * s2 * wt32
        + m * wt31
        + s2 * wt30
    )
    ft[3] = (
        A * wt49
        + B * wt48
        + _tmp13 * wt58
        + _tmp21 * s3 * wt53
        + _tmp21 * wt52
        + _tmp43 * wt56
        + _tmp45 * wt59
        + _tmp48 * wt57
        + _tmp5 * wt50
        + _tmp71 * wt55
        + _tmp72 * wt54
        + _tmp8 * wt51
        + m * s3 * wt47
        + m * wt46
        + s3 * wt45
    )
    ft[4] = _tmp43 * (P * wt62 + wt61)
    ft[5] = _tmp43 * (P * wt67 + wt66)
    ft[6] = _tmp43 * (P * wt72 + wt71)
    ft[7] = _tmp43 * (P * wt77 + wt76)
    ft[8] = 0.0

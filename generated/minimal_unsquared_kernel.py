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
    _tmp0 = dp0 + ep0
    _tmp1 = cp0 * cp0 * cp0
    _tmp2 = dp0 * ep0
    _tmp3 = 2 * _tmp2
    _tmp4 = _tmp1 * _tmp3
    _tmp5 = _tmp0 * _tmp4
    _tmp6 = cp0 * cp0 * cp0 * cp0
    _tmp7 = dp0 * dp0
    _tmp8 = ep0 * ep0
    _tmp9 = _tmp7 * _tmp8
    _tmp10 = _tmp6 * _tmp9
    _tmp11 = -_tmp10
    _tmp12 = cp0 * cp0
    _tmp13 = -_tmp2
    _tmp14 = _tmp12 + _tmp13
    _tmp15 = 2 * _tmp12
    _tmp16 = -_tmp14 * _tmp15 * _tmp2
    _tmp17 = _tmp8 * dp0
    _tmp18 = -_tmp17
    _tmp19 = _tmp7 * ep0
    _tmp20 = -_tmp19
    _tmp21 = 2 * cp0
    _tmp22 = _tmp12 + _tmp8
    _tmp23 = _tmp12 * _tmp7
    _tmp24 = _tmp12 + _tmp7
    _tmp25 = _tmp12 * _tmp8
    _tmp26 = 4 * _tmp2
    _tmp27 = _tmp12 * _tmp26 + _tmp23 + _tmp25
    _tmp28 = -_tmp9
    _tmp29 = dp1 + ep1
    _tmp30 = cp1 * cp1 * cp1
    _tmp31 = dp1 * ep1
    _tmp32 = 2 * _tmp31
    _tmp33 = _tmp30 * _tmp32
    _tmp34 = _tmp29 * _tmp33
    _tmp35 = cp1 * cp1 * cp1 * cp1
    _tmp36 = dp1 * dp1
    _tmp37 = ep1 * ep1
    _tmp38 = _tmp36 * _tmp37
    _tmp39 = _tmp35 * _tmp38
    _tmp40 = -_tmp39
    _tmp41 = cp1 * cp1
    _tmp42 = -_tmp31
    _tmp43 = _tmp41 + _tmp42
    _tmp44 = 2 * _tmp41
    _tmp45 = -_tmp31 * _tmp43 * _tmp44
    _tmp46 = _tmp37 * dp1
    _tmp47 = -_tmp46
    _tmp48 = _tmp36 * ep1
    _tmp49 = -_tmp48
    _tmp50 = 2 * cp1
    _tmp51 = _tmp37 + _tmp41
    _tmp52 = _tmp36 * _tmp41
    _tmp53 = _tmp36 + _tmp41
    _tmp54 = _tmp37 * _tmp41
    _tmp55 = 4 * _tmp31
    _tmp56 = _tmp41 * _tmp55 + _tmp52 + _tmp54
    _tmp57 = -_tmp38
    _tmp58 = dp2 + ep2
    _tmp59 = cp2 * cp2 * cp2
    _tmp60 = dp2 * ep2
    _tmp61 = 2 * _tmp60
    _tmp62 = _tmp59 * _tmp61
    _tmp63 = _tmp58 * _tmp62
    _tmp64 = cp2 * cp2 * cp2 * cp2
    _tmp65 = dp2 * dp2
    _tmp66 = ep2 * ep2
    _tmp67 = _tmp65 * _tmp66
    _tmp68 = _tmp64 * _tmp67
    _tmp69 = -_tmp68
    _tmp70 = cp2 * cp2
    _tmp71 = -_tmp60
    _tmp72 = _tmp70 + _tmp71
    _tmp73 = 2 * _tmp70
    _tmp74 = -_tmp60 * _tmp72 * _tmp73
    _tmp75 = _tmp66 * dp2
    _tmp76 = -_tmp75
    _tmp77 = _tmp65 * ep2
    _tmp78 = -_tmp77
    _tmp79 = 2 * cp2
    _tmp80 = _tmp66 + _tmp70
    _tmp81 = _tmp65 * _tmp70
    _tmp82 = _tmp65 + _tmp70
    _tmp83 = _tmp66 * _tmp70
    _tmp84 = 4 * _tmp60
    _tmp85 = _tmp70 * _tmp84 + _tmp81 + _tmp83
    _tmp86 = -_tmp67
    _tmp87 = dp3 + ep3
    _tmp88 = cp3 * cp3 * cp3
    _tmp89 = dp3 * ep3
    _tmp90 = 2 * _tmp89
    _tmp91 = _tmp88 * _tmp90
    _tmp92 = _tmp87 * _tmp91
    _tmp93 = cp3 * cp3 * cp3 * cp3
    _tmp94 = dp3 * dp3
    _tmp95 = ep3 * ep3
    _tmp96 = _tmp94 * _tmp95
    _tmp97 = _tmp93 * _tmp96
    _tmp98 = -_tmp97
    _tmp99 = cp3 * cp3
    _tmp100 = -_tmp89
    _tmp101 = _tmp100 + _tmp99
    _tmp102 = 2 * _tmp99
    _tmp103 = -_tmp101 * _tmp102 * _tmp89
    _tmp104 = _tmp95 * dp3
    _tmp105 = -_tmp104
    _tmp106 = _tmp94 * ep3
    _tmp107 = -_tmp106
    _tmp108 = 2 * cp3
    _tmp109 = _tmp95 + _tmp99
    _tmp110 = _tmp94 * _tmp99
    _tmp111 = _tmp94 + _tmp99
    _tmp112 = _tmp95 * _tmp99
    _tmp113 = 4 * _tmp89
    _tmp114 = _tmp110 + _tmp112 + _tmp113 * _tmp99
    _tmp115 = -_tmp96
    _tmp116 = -_tmp12
    _tmp117 = -_tmp41
    _tmp118 = -_tmp70
    _tmp119 = -_tmp99
    _tmp120 = _tmp0 * d_cp0
    _tmp121 = 2 * dp0
    _tmp122 = _tmp121 + ep0
    _tmp123 = d_dp0 * ep0
    _tmp124 = _tmp123 * cp0
    _tmp125 = 2 * ep0
    _tmp126 = _tmp125 + dp0
    _tmp127 = _tmp126 * dp0
    _tmp128 = cp0 * d_ep0
    _tmp129 = _tmp15 * (3 * _tmp120 * _tmp2 + _tmp122 * _tmp124 + _tmp127 * _tmp128)
    _tmp130 = d_ep0 * dp0
    _tmp131 = _tmp130 * cp0
    _tmp132 = _tmp3 * d_cp0
    _tmp133 = _tmp124 + _tmp131 + _tmp132
    _tmp134 = _tmp133 * _tmp4
    _tmp135 = -_tmp134
    _tmp136 = _tmp12 - _tmp3
    _tmp137 = -_tmp21 * (_tmp124 * _tmp136 + _tmp131 * _tmp136 + _tmp132 * (_tmp13 + _tmp15))
    _tmp138 = cp0 * d_dp0
    _tmp139 = _tmp12 * _tmp126
    _tmp140 = _tmp12 * _tmp122
    _tmp141 = _tmp8 + dp0 * (dp0 + 4 * ep0)
    _tmp142 = _tmp21 * d_cp0
    _tmp143 = -_tmp142
    _tmp144 = _tmp29 * d_cp1
    _tmp145 = 2 * dp1
    _tmp146 = _tmp145 + ep1
    _tmp147 = d_dp1 * ep1
    _tmp148 = _tmp147 * cp1
    _tmp149 = 2 * ep1
    _tmp150 = _tmp149 + dp1
    _tmp151 = _tmp150 * dp1
    _tmp152 = cp1 * d_ep1
    _tmp153 = _tmp44 * (3 * _tmp144 * _tmp31 + _tmp146 * _tmp148 + _tmp151 * _tmp152)
    _tmp154 = d_ep1 * dp1
    _tmp155 = _tmp154 * cp1
    _tmp156 = _tmp32 * d_cp1
    _tmp157 = _tmp148 + _tmp155 + _tmp156
    _tmp158 = _tmp157 * _tmp33
    _tmp159 = -_tmp158
    _tmp160 = -_tmp32 + _tmp41
    _tmp161 = -_tmp50 * (_tmp148 * _tmp160 + _tmp155 * _tmp160 + _tmp156 * (_tmp42 + _tmp44))
    _tmp162 = cp1 * d_dp1
    _tmp163 = _tmp150 * _tmp41
    _tmp164 = _tmp146 * _tmp41
    _tmp165 = _tmp37 + dp1 * (dp1 + 4 * ep1)
    _tmp166 = _tmp50 * d_cp1
    _tmp167 = -_tmp166
    _tmp168 = _tmp58 * d_cp2
    _tmp169 = 2 * dp2
    _tmp170 = _tmp169 + ep2
    _tmp171 = d_dp2 * ep2
    _tmp172 = _tmp171 * cp2
    _tmp173 = 2 * ep2
    _tmp174 = _tmp173 + dp2
    _tmp175 = _tmp174 * dp2
    _tmp176 = cp2 * d_ep2
    _tmp177 = _tmp73 * (3 * _tmp168 * _tmp60 + _tmp170 * _tmp172 + _tmp175 * _tmp176)
    _tmp178 = d_ep2 * dp2
    _tmp179 = _tmp178 * cp2
    _tmp180 = _tmp61 * d_cp2
    _tmp181 = _tmp172 + _tmp179 + _tmp180
    _tmp182 = _tmp181 * _tmp62
    _tmp183 = -_tmp182
    _tmp184 = -_tmp61 + _tmp70
    _tmp185 = -_tmp79 * (_tmp172 * _tmp184 + _tmp179 * _tmp184 + _tmp180 * (_tmp71 + _tmp73))
    _tmp186 = cp2 * d_dp2
    _tmp187 = _tmp174 * _tmp70
    _tmp188 = _tmp170 * _tmp70
    _tmp189 = _tmp66 + dp2 * (dp2 + 4 * ep2)
    _tmp190 = _tmp79 * d_cp2
    _tmp191 = -_tmp190
    _tmp192 = _tmp87 * d_cp3
    _tmp193 = 2 * dp3
    _tmp194 = _tmp193 + ep3
    _tmp195 = d_dp3 * ep3
    _tmp196 = _tmp195 * cp3
    _tmp197 = 2 * ep3
    _tmp198 = _tmp197 + dp3
    _tmp199 = _tmp198 * dp3
    _tmp200 = cp3 * d_ep3
    _tmp201 = _tmp102 * (3 * _tmp192 * _tmp89 + _tmp194 * _tmp196 + _tmp199 * _tmp200)
    _tmp202 = d_ep3 * dp3
    _tmp203 = _tmp202 * cp3
    _tmp204 = _tmp90 * d_cp3
    _tmp205 = _tmp196 + _tmp203 + _tmp204
    _tmp206 = _tmp205 * _tmp91
    _tmp207 = -_tmp206
    _tmp208 = -_tmp90 + _tmp99
    _tmp209 = -_tmp108 * (_tmp196 * _tmp208 + _tmp203 * _tmp208 + _tmp204 * (_tmp100 + _tmp102))
    _tmp210 = cp3 * d_dp3
    _tmp211 = _tmp198 * _tmp99
    _tmp212 = _tmp194 * _tmp99
    _tmp213 = _tmp95 + dp3 * (dp3 + 4 * ep3)
    _tmp214 = _tmp108 * d_cp3
    _tmp215 = -_tmp214
    w[0] = _tmp5
    w[1] = -2 * _tmp10
    w[2] = -_tmp5
    w[3] = _tmp11
    w[4] = _tmp11
    w[5] = _tmp11
    w[6] = _tmp10
    w[7] = _tmp16
    w[8] = _tmp21 * (-_tmp12 * dp0 - _tmp12 * ep0 - _tmp18 - _tmp20)
    w[9] = _tmp22 * _tmp23
    w[10] = _tmp24 * _tmp25
    w[11] = _tmp16
    w[12] = _tmp12 * (_tmp27 - 2 * _tmp9)
    w[13] = 2 * _tmp12 * dp0 * ep0 - _tmp6 - _tmp9
    w[14] = -_tmp27 - _tmp28 + _tmp6
    w[15] = _tmp34
    w[16] = -2 * _tmp39
    w[17] = -_tmp34
    w[18] = _tmp40
    w[19] = _tmp40
    w[20] = _tmp40
    w[21] = _tmp39
    w[22] = _tmp45
    w[23] = _tmp50 * (-_tmp41 * dp1 - _tmp41 * ep1 - _tmp47 - _tmp49)
    w[24] = _tmp51 * _tmp52
    w[25] = _tmp53 * _tmp54
    w[26] = _tmp45
    w[27] = _tmp41 * (-2 * _tmp38 + _tmp56)
    w[28] = -_tmp35 - _tmp38 + 2 * _tmp41 * dp1 * ep1
    w[29] = _tmp35 - _tmp56 - _tmp57
    w[30] = _tmp63
    w[31] = -2 * _tmp68
    w[32] = -_tmp63
    w[33] = _tmp69
    w[34] = _tmp69
    w[35] = _tmp69
    w[36] = _tmp68
    w[37] = _tmp74
    w[38] = _tmp79 * (-_tmp70 * dp2 - _tmp70 * ep2 - _tmp76 - _tmp78)
    w[39] = _tmp80 * _tmp81
    w[40] = _tmp82 * _tmp83
    w[41] = _tmp74
    w[42] = _tmp70 * (-2 * _tmp67 + _tmp85)
    w[43] = -_tmp64 - _tmp67 + 2 * _tmp70 * dp2 * ep2
    w[44] = _tmp64 - _tmp85 - _tmp86
    w[45] = _tmp92
    w[46] = -2 * _tmp97
    w[47] = -_tmp92
    w[48] = _tmp98
    w[49] = _tmp98
    w[50] = _tmp98
    w[51] = _tmp97
    w[52] = _tmp103
    w[53] = _tmp108 * (-_tmp105 - _tmp107 - _tmp99 * dp3 - _tmp99 * ep3)
    w[54] = _tmp109 * _tmp110
    w[55] = _tmp111 * _tmp112
    w[56] = _tmp103
    w[57] = _tmp99 * (_tmp114 - 2 * _tmp96)
    w[58] = -_tmp93 - _tmp96 + 2 * _tmp99 * dp3 * ep3
    w[59] = -_tmp114 - _tmp115 + _tmp93
    w[60] = 1
    w[61] = _tmp12
    w[62] = _tmp116
    w[63] = -1
    w[64] = 1
    w[65] = 1
    w[66] = _tmp41
    w[67] = _tmp117
    w[68] = -1
    w[69] = 1
    w[70] = 1
    w[71] = _tmp70
    w[72] = _tmp118
    w[73] = -1
    w[74] = 1
    w[75] = 1
    w[76] = _tmp99
    w[77] = _tmp119
    w[78] = -1
    w[79] = 1
    w[80] = 1
    w[81] = -1
    wt[0] = _tmp129
    wt[1] = -_tmp1 * _tmp133 * _tmp26
    wt[2] = -_tmp129
    wt[3] = _tmp135
    wt[4] = _tmp135
    wt[5] = _tmp135
    wt[6] = _tmp134
    wt[7] = _tmp137
    wt[8] = (
        -2 * _tmp120 * (3 * _tmp12 + _tmp13)
        - 2 * _tmp128 * (_tmp12 - _tmp127)
        + 2 * cp0 * d_dp0 * (_tmp116 + _tmp3 + _tmp8)
    )
    wt[9] = _tmp121 * cp0 * (_tmp128 * _tmp2 + _tmp138 * _tmp22 + d_cp0 * dp0 * (_tmp15 + _tmp8))
    wt[10] = _tmp125 * cp0 * (_tmp128 * _tmp24 + _tmp138 * _tmp2 + d_cp0 * ep0 * (_tmp15 + _tmp7))
    wt[11] = _tmp137
    wt[12] = _tmp21 * (
        _tmp128 * (_tmp140 - 2 * _tmp19)
        + _tmp138 * (_tmp139 - 2 * _tmp17)
        + 2 * d_cp0 * (_tmp12 * _tmp141 + _tmp28)
    )
    wt[13] = 2 * _tmp14 * (_tmp123 + _tmp130 + _tmp143)
    wt[14] = (
        -2 * cp0 * d_cp0 * (_tmp141 - _tmp15)
        - 2 * d_dp0 * (_tmp139 + _tmp18)
        - 2 * d_ep0 * (_tmp140 + _tmp20)
    )
    wt[15] = _tmp153
    wt[16] = -_tmp157 * _tmp30 * _tmp55
    wt[17] = -_tmp153
    wt[18] = _tmp159
    wt[19] = _tmp159
    wt[20] = _tmp159
    wt[21] = _tmp158
    wt[22] = _tmp161
    wt[23] = (
        -2 * _tmp144 * (3 * _tmp41 + _tmp42)
        - 2 * _tmp152 * (-_tmp151 + _tmp41)
        + 2 * cp1 * d_dp1 * (_tmp117 + _tmp32 + _tmp37)
    )
    wt[24] = _tmp145 * cp1 * (_tmp152 * _tmp31 + _tmp162 * _tmp51 + d_cp1 * dp1 * (_tmp37 + _tmp44))
    wt[25] = _tmp149 * cp1 * (_tmp152 * _tmp53 + _tmp162 * _tmp31 + d_cp1 * ep1 * (_tmp36 + _tmp44))
    wt[26] = _tmp161
    wt[27] = _tmp50 * (
        _tmp152 * (_tmp164 - 2 * _tmp48)
        + _tmp162 * (_tmp163 - 2 * _tmp46)
        + 2 * d_cp1 * (_tmp165 * _tmp41 + _tmp57)
    )
    wt[28] = 2 * _tmp43 * (_tmp147 + _tmp154 + _tmp167)
    wt[29] = (
        -2 * cp1 * d_cp1 * (_tmp165 - _tmp44)
        - 2 * d_dp1 * (_tmp163 + _tmp47)
        - 2 * d_ep1 * (_tmp164 + _tmp49)
    )
    wt[30] = _tmp177
    wt[31] = -_tmp181 * _tmp59 * _tmp84
    wt[32] = -_tmp177
    wt[33] = _tmp183
    wt[34] = _tmp183
    wt[35] = _tmp183
    wt[36] = _tmp182
    wt[37] = _tmp185
    wt[38] = (
        -2 * _tmp168 * (3 * _tmp70 + _tmp71)
        - 2 * _tmp176 * (-_tmp175 + _tmp70)
        + 2 * cp2 * d_dp2 * (_tmp118 + _tmp61 + _tmp66)
    )
    wt[39] = _tmp169 * cp2 * (_tmp176 * _tmp60 + _tmp186 * _tmp80 + d_cp2 * dp2 * (_tmp66 + _tmp73))
    wt[40] = _tmp173 * cp2 * (_tmp176 * _tmp82 + _tmp186 * _tmp60 + d_cp2 * ep2 * (_tmp65 + _tmp73))
    wt[41] = _tmp185
    wt[42] = _tmp79 * (
        _tmp176 * (_tmp188 - 2 * _tmp77)
        + _tmp186 * (_tmp187 - 2 * _tmp75)
        + 2 * d_cp2 * (_tmp189 * _tmp70 + _tmp86)
    )
    wt[43] = 2 * _tmp72 * (_tmp171 + _tmp178 + _tmp191)
    wt[44] = (
        -2 * cp2 * d_cp2 * (_tmp189 - _tmp73)
        - 2 * d_dp2 * (_tmp187 + _tmp76)
        - 2 * d_ep2 * (_tmp188 + _tmp78)
    )
    wt[45] = _tmp201
    wt[46] = -_tmp113 * _tmp205 * _tmp88
    wt[47] = -_tmp201
    wt[48] = _tmp207
    wt[49] = _tmp207
    wt[50] = _tmp207
    wt[51] = _tmp206
    wt[52] = _tmp209
    wt[53] = (
        -2 * _tmp192 * (_tmp100 + 3 * _tmp99)
        - 2 * _tmp200 * (-_tmp199 + _tmp99)
        + 2 * cp3 * d_dp3 * (_tmp119 + _tmp90 + _tmp95)
    )
    wt[54] = (
        _tmp193 * cp3 * (_tmp109 * _tmp210 + _tmp200 * _tmp89 + d_cp3 * dp3 * (_tmp102 + _tmp95))
    )
    wt[55] = (
        _tmp197 * cp3 * (_tmp111 * _tmp200 + _tmp210 * _tmp89 + d_cp3 * ep3 * (_tmp102 + _tmp94))
    )
    wt[56] = _tmp209
    wt[57] = _tmp108 * (
        _tmp200 * (-2 * _tmp106 + _tmp212)
        + _tmp210 * (-2 * _tmp104 + _tmp211)
        + 2 * d_cp3 * (_tmp115 + _tmp213 * _tmp99)
    )
    wt[58] = 2 * _tmp101 * (_tmp195 + _tmp202 + _tmp215)
    wt[59] = (
        -2 * cp3 * d_cp3 * (-_tmp102 + _tmp213)
        - 2 * d_dp3 * (_tmp105 + _tmp211)
        - 2 * d_ep3 * (_tmp107 + _tmp212)
    )
    wt[60] = 0.0
    wt[61] = _tmp142
    wt[62] = _tmp143
    wt[63] = 0.0
    wt[64] = 0.0
    wt[65] = 0.0
    wt[66] = _tmp166
    wt[67] = _tmp167
    wt[68] = 0.0
    wt[69] = 0.0
    wt[70] = 0.0
    wt[71] = _tmp190
    wt[72] = _tmp191
    wt[73] = 0.0
    wt[74] = 0.0
    wt[75] = 0.0
    wt[76] = _tmp214
    wt[77] = _tmp215
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
    _tmp0 = dp0 * ep0
    _tmp1 = d_cp0 * (dp0 + ep0)
    _tmp2 = 2 * dp0
    _tmp3 = _tmp2 + ep0
    _tmp4 = d_dp0 * ep0
    _tmp5 = _tmp4 * cp0
    _tmp6 = 2 * ep0
    _tmp7 = _tmp6 + dp0
    _tmp8 = _tmp7 * dp0
    _tmp9 = cp0 * d_ep0
    _tmp10 = cp0 * cp0
    _tmp11 = 2 * _tmp10
    _tmp12 = _tmp11 * (3 * _tmp0 * _tmp1 + _tmp3 * _tmp5 + _tmp8 * _tmp9)
    _tmp13 = d_ep0 * dp0
    _tmp14 = _tmp13 * cp0
    _tmp15 = _tmp2 * ep0
    _tmp16 = _tmp15 * d_cp0
    _tmp17 = (cp0 * cp0 * cp0) * (_tmp14 + _tmp16 + _tmp5)
    _tmp18 = _tmp15 * _tmp17
    _tmp19 = -_tmp18
    _tmp20 = _tmp10 - _tmp15
    _tmp21 = -_tmp0
    _tmp22 = 2 * cp0
    _tmp23 = -_tmp22 * (_tmp14 * _tmp20 + _tmp16 * (_tmp11 + _tmp21) + _tmp20 * _tmp5)
    _tmp24 = ep0 * ep0
    _tmp25 = cp0 * d_dp0
    _tmp26 = dp0 * dp0
    _tmp27 = _tmp10 * _tmp7
    _tmp28 = _tmp10 * _tmp3
    _tmp29 = _tmp24 + dp0 * (dp0 + 4 * ep0)
    _tmp30 = _tmp22 * d_cp0
    _tmp31 = -_tmp30
    _tmp32 = dp1 * ep1
    _tmp33 = d_cp1 * (dp1 + ep1)
    _tmp34 = 2 * dp1
    _tmp35 = _tmp34 + ep1
    _tmp36 = d_dp1 * ep1
    _tmp37 = _tmp36 * cp1
    _tmp38 = 2 * ep1
    _tmp39 = _tmp38 + dp1
    _tmp40 = _tmp39 * dp1
    _tmp41 = cp1 * d_ep1
    _tmp42 = cp1 * cp1
    _tmp43 = 2 * _tmp42
    _tmp44 = _tmp43 * (3 * _tmp32 * _tmp33 + _tmp35 * _tmp37 + _tmp40 * _tmp41)
    _tmp45 = d_ep1 * dp1
    _tmp46 = _tmp45 * cp1
    _tmp47 = _tmp34 * ep1
    _tmp48 = _tmp47 * d_cp1
    _tmp49 = (cp1 * cp1 * cp1) * (_tmp37 + _tmp46 + _tmp48)
    _tmp50 = _tmp47 * _tmp49
    _tmp51 = -_tmp50
    _tmp52 = _tmp42 - _tmp47
    _tmp53 = -_tmp32
    _tmp54 = 2 * cp1
    _tmp55 = -_tmp54 * (_tmp37 * _tmp52 + _tmp46 * _tmp52 + _tmp48 * (_tmp43 + _tmp53))
    _tmp56 = ep1 * ep1
    _tmp57 = cp1 * d_dp1
    _tmp58 = dp1 * dp1
    _tmp59 = _tmp39 * _tmp42
    _tmp60 = _tmp35 * _tmp42
    _tmp61 = _tmp56 + dp1 * (dp1 + 4 * ep1)
    _tmp62 = _tmp54 * d_cp1
    _tmp63 = -_tmp62
    _tmp64 = dp2 * ep2
    _tmp65 = d_cp2 * (dp2 + ep2)
    _tmp66 = 2 * dp2
    _tmp67 = _tmp66 + ep2
    _tmp68 = d_dp2 * ep2
    _tmp69 = _tmp68 * cp2
    _tmp70 = 2 * ep2
    _tmp71 = _tmp70 + dp2
    _tmp72 = _tmp71 * dp2
    _tmp73 = cp2 * d_ep2
    _tmp74 = cp2 * cp2
    _tmp75 = 2 * _tmp74
    _tmp76 = _tmp75 * (3 * _tmp64 * _tmp65 + _tmp67 * _tmp69 + _tmp72 * _tmp73)
    _tmp77 = d_ep2 * dp2
    _tmp78 = _tmp77 * cp2
    _tmp79 = _tmp66 * ep2
    _tmp80 = _tmp79 * d_cp2
    _tmp81 = (cp2 * cp2 * cp2) * (_tmp69 + _tmp78 + _tmp80)
    _tmp82 = _tmp79 * _tmp81
    _tmp83 = -_tmp82
    _tmp84 = _tmp74 - _tmp79
    _tmp85 = -_tmp64
    _tmp86 = 2 * cp2
    _tmp87 = -_tmp86 * (_tmp69 * _tmp84 + _tmp78 * _tmp84 + _tmp80 * (_tmp75 + _tmp85))
    _tmp88 = ep2 * ep2
    _tmp89 = cp2 * d_dp2
    _tmp90 = dp2 * dp2
    _tmp91 = _tmp71 * _tmp74
    _tmp92 = _tmp67 * _tmp74
    _tmp93 = _tmp88 + dp2 * (dp2 + 4 * ep2)
    _tmp94 = _tmp86 * d_cp2
    _tmp95 = -_tmp94
    _tmp96 = dp3 * ep3
    _tmp97 = d_cp3 * (dp3 + ep3)
    _tmp98 = 2 * dp3
    _tmp99 = _tmp98 + ep3
    _tmp100 = d_dp3 * ep3
    _tmp101 = _tmp100 * cp3
    _tmp102 = 2 * ep3
    _tmp103 = _tmp102 + dp3
    _tmp104 = _tmp103 * dp3
    _tmp105 = cp3 * d_ep3
    _tmp106 = cp3 * cp3
    _tmp107 = 2 * _tmp106
    _tmp108 = _tmp107 * (_tmp101 * _tmp99 + _tmp104 * _tmp105 + 3 * _tmp96 * _tmp97)
    _tmp109 = d_ep3 * dp3
    _tmp110 = _tmp109 * cp3
    _tmp111 = _tmp98 * ep3
    _tmp112 = _tmp111 * d_cp3
    _tmp113 = (cp3 * cp3 * cp3) * (_tmp101 + _tmp110 + _tmp112)
    _tmp114 = _tmp111 * _tmp113
    _tmp115 = -_tmp114
    _tmp116 = _tmp106 - _tmp111
    _tmp117 = -_tmp96
    _tmp118 = 2 * cp3
    _tmp119 = -_tmp118 * (_tmp101 * _tmp116 + _tmp110 * _tmp116 + _tmp112 * (_tmp107 + _tmp117))
    _tmp120 = ep3 * ep3
    _tmp121 = cp3 * d_dp3
    _tmp122 = dp3 * dp3
    _tmp123 = _tmp103 * _tmp106
    _tmp124 = _tmp106 * _tmp99
    _tmp125 = _tmp120 + dp3 * (dp3 + 4 * ep3)
    _tmp126 = _tmp118 * d_cp3
    _tmp127 = -_tmp126
    wt[0] = _tmp12
    wt[1] = -4 * _tmp0 * _tmp17
    wt[2] = -_tmp12
    wt[3] = _tmp19
    wt[4] = _tmp19
    wt[5] = _tmp19
    wt[6] = _tmp18
    wt[7] = _tmp23
    wt[8] = (
        -2 * _tmp1 * (3 * _tmp10 + _tmp21)
        - 2 * _tmp9 * (_tmp10 - _tmp8)
        + 2 * cp0 * d_dp0 * (-_tmp10 + _tmp15 + _tmp24)
    )
    wt[9] = (
        _tmp2 * cp0 * (_tmp0 * _tmp9 + _tmp25 * (_tmp10 + _tmp24) + d_cp0 * dp0 * (_tmp11 + _tmp24))
    )
    wt[10] = (
        _tmp6 * cp0 * (_tmp0 * _tmp25 + _tmp9 * (_tmp10 + _tmp26) + d_cp0 * ep0 * (_tmp11 + _tmp26))
    )
    wt[11] = _tmp23
    wt[12] = _tmp22 * (
        _tmp25 * (-_tmp2 * _tmp24 + _tmp27)
        + _tmp9 * (-_tmp26 * _tmp6 + _tmp28)
        + 2 * d_cp0 * (_tmp10 * _tmp29 - _tmp24 * _tmp26)
    )
    wt[13] = 2 * (_tmp10 + _tmp21) * (_tmp13 + _tmp31 + _tmp4)
    wt[14] = (
        -2 * cp0 * d_cp0 * (-_tmp11 + _tmp29)
        - 2 * d_dp0 * (-_tmp24 * dp0 + _tmp27)
        - 2 * d_ep0 * (-_tmp26 * ep0 + _tmp28)
    )
    wt[15] = _tmp44
    wt[16] = -4 * _tmp32 * _tmp49
    wt[17] = -_tmp44
    wt[18] = _tmp51
    wt[19] = _tmp51
    wt[20] = _tmp51
    wt[21] = _tmp50
    wt[22] = _tmp55
    wt[23] = (
        -2 * _tmp33 * (3 * _tmp42 + _tmp53)
        - 2 * _tmp41 * (-_tmp40 + _tmp42)
        + 2 * cp1 * d_dp1 * (-_tmp42 + _tmp47 + _tmp56)
    )
    wt[24] = (
        _tmp34
        * cp1
        * (_tmp32 * _tmp41 + _tmp57 * (_tmp42 + _tmp56) + d_cp1 * dp1 * (_tmp43 + _tmp56))
    )
    wt[25] = (
        _tmp38
        * cp1
        * (_tmp32 * _tmp57 + _tmp41 * (_tmp42 + _tmp58) + d_cp1 * ep1 * (_tmp43 + _tmp58))
    )
    wt[26] = _tmp55
    wt[27] = _tmp54 * (
        _tmp41 * (-_tmp38 * _tmp58 + _tmp60)
        + _tmp57 * (-_tmp34 * _tmp56 + _tmp59)
        + 2 * d_cp1 * (_tmp42 * _tmp61 - _tmp56 * _tmp58)
    )
    wt[28] = 2 * (_tmp42 + _tmp53) * (_tmp36 + _tmp45 + _tmp63)
    wt[29] = (
        -2 * cp1 * d_cp1 * (-_tmp43 + _tmp61)
        - 2 * d_dp1 * (-_tmp56 * dp1 + _tmp59)
        - 2 * d_ep1 * (-_tmp58 * ep1 + _tmp60)
    )
    wt[30] = _tmp76
    wt[31] = -4 * _tmp64 * _tmp81
    wt[32] = -_tmp76
    wt[33] = _tmp83
    wt[34] = _tmp83
    wt[35] = _tmp83
    wt[36] = _tmp82
    wt[37] = _tmp87
    wt[38] = (
        -2 * _tmp65 * (3 * _tmp74 + _tmp85)
        - 2 * _tmp73 * (-_tmp72 + _tmp74)
        + 2 * cp2 * d_dp2 * (-_tmp74 + _tmp79 + _tmp88)
    )
    wt[39] = (
        _tmp66
        * cp2
        * (_tmp64 * _tmp73 + _tmp89 * (_tmp74 + _tmp88) + d_cp2 * dp2 * (_tmp75 + _tmp88))
    )
    wt[40] = (
        _tmp70
        * cp2
        * (_tmp64 * _tmp89 + _tmp73 * (_tmp74 + _tmp90) + d_cp2 * ep2 * (_tmp75 + _tmp90))
    )
    wt[41] = _tmp87
    wt[42] = _tmp86 * (
        _tmp73 * (-_tmp70 * _tmp90 + _tmp92)
        + _tmp89 * (-_tmp66 * _tmp88 + _tmp91)
        + 2 * d_cp2 * (_tmp74 * _tmp93 - _tmp88 * _tmp90)
    )
    wt[43] = 2 * (_tmp74 + _tmp85) * (_tmp68 + _tmp77 + _tmp95)
    wt[44] = (
        -2 * cp2 * d_cp2 * (-_tmp75 + _tmp93)
        - 2 * d_dp2 * (-_tmp88 * dp2 + _tmp91)
        - 2 * d_ep2 * (-_tmp90 * ep2 + _tmp92)
    )
    wt[45] = _tmp108
    wt[46] = -4 * _tmp113 * _tmp96
    wt[47] = -_tmp108
    wt[48] = _tmp115
    wt[49] = _tmp115
    wt[50] = _tmp115
    wt[51] = _tmp114
    wt[52] = _tmp119
    wt[53] = (
        -2 * _tmp105 * (-_tmp104 + _tmp106)
        - 2 * _tmp97 * (3 * _tmp106 + _tmp117)
        + 2 * cp3 * d_dp3 * (-_tmp106 + _tmp111 + _tmp120)
    )
    wt[54] = (
        _tmp98
        * cp3
        * (_tmp105 * _tmp96 + _tmp121 * (_tmp106 + _tmp120) + d_cp3 * dp3 * (_tmp107 + _tmp120))
    )
    wt[55] = (
        _tmp102
        * cp3
        * (_tmp105 * (_tmp106 + _tmp122) + _tmp121 * _tmp96 + d_cp3 * ep3 * (_tmp107 + _tmp122))
    )
    wt[56] = _tmp119
    wt[57] = _tmp118 * (
        _tmp105 * (-_tmp102 * _tmp122 + _tmp124)
        + _tmp121 * (-_tmp120 * _tmp98 + _tmp123)
        + 2 * d_cp3 * (_tmp106 * _tmp125 - _tmp120 * _tmp122)
    )
    wt[58] = 2 * (_tmp106 + _tmp117) * (_tmp100 + _tmp109 + _tmp127)
    wt[59] = (
        -2 * cp3 * d_cp3 * (-_tmp107 + _tmp125)
        - 2 * d_dp3 * (-_tmp120 * dp3 + _tmp123)
        - 2 * d_ep3 * (-_tmp122 * ep3 + _tmp124)
    )
    wt[60] = 0.0
    wt[61] = _tmp30
    wt[62] = _tmp31
    wt[63] = 0.0
    wt[64] = 0.0
    wt[65] = 0.0
    wt[66] = _tmp62
    wt[67] = _tmp63
    wt[68] = 0.0
    wt[69] = 0.0
    wt[70] = 0.0
    wt[71] = _tmp94
    wt[72] = _tmp95
    wt[73] = 0.0
    wt[74] = 0.0
    wt[75] = 0.0
    wt[76] = _tmp126
    wt[77] = _tmp127
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


#: The linear solves' elimination plan ``solve_pair`` is written for: n, the number of pairs,
#: (unknown, row, row) of each pair, the dense unknowns, the rows in no pair
#: (``curverecon.solvers.homotopy.PolynomialSystem.elimination``).
ELIMINATION = (9, 4, 5, 0, 4, 6, 1, 5, 7, 2, 6, 8, 3, 7, 4, 0, 1, 2, 3, 8)

# Without "reassoc", as the tracker's own linear solve (the same arithmetic, in the same order).
_JIT_SOLVE = {"cache": True, "nogil": True, "fastmath": {"contract", "arcp", "nsz"}}


@numba.njit(**_JIT_SOLVE)
def solve_one(a, b, out):  # type: ignore[no-untyped-def]
    """out = a^-1 b (``out`` not ``b``): ``solve_pair`` for one right-hand side."""
    m0_0 = a[8, 4]
    m0_1 = a[8, 0]
    m0_2 = a[8, 1]
    m0_3 = a[8, 2]
    m0_4 = a[8, 3]
    g0 = b[8]
    va = a[0, 5]
    vb = a[4, 5]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 4, 0
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 0, 4
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v0 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v0
    p0_0 = a[ip, 4]
    m1_0 = a[io, 4] - fac * p0_0
    p0_1 = a[ip, 0]
    m1_1 = a[io, 0] - fac * p0_1
    p0_2 = a[ip, 1]
    m1_2 = a[io, 1] - fac * p0_2
    p0_3 = a[ip, 2]
    m1_3 = a[io, 2] - fac * p0_3
    p0_4 = a[ip, 3]
    m1_4 = a[io, 3] - fac * p0_4
    pr0 = b[ip]
    g1 = b[io] - fac * pr0
    va = a[1, 6]
    vb = a[5, 6]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 5, 1
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 1, 5
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v1 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v1
    p1_0 = a[ip, 4]
    m2_0 = a[io, 4] - fac * p1_0
    p1_1 = a[ip, 0]
    m2_1 = a[io, 0] - fac * p1_1
    p1_2 = a[ip, 1]
    m2_2 = a[io, 1] - fac * p1_2
    p1_3 = a[ip, 2]
    m2_3 = a[io, 2] - fac * p1_3
    p1_4 = a[ip, 3]
    m2_4 = a[io, 3] - fac * p1_4
    pr1 = b[ip]
    g2 = b[io] - fac * pr1
    va = a[2, 7]
    vb = a[6, 7]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 6, 2
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 2, 6
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v2 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v2
    p2_0 = a[ip, 4]
    m3_0 = a[io, 4] - fac * p2_0
    p2_1 = a[ip, 0]
    m3_1 = a[io, 0] - fac * p2_1
    p2_2 = a[ip, 1]
    m3_2 = a[io, 1] - fac * p2_2
    p2_3 = a[ip, 2]
    m3_3 = a[io, 2] - fac * p2_3
    p2_4 = a[ip, 3]
    m3_4 = a[io, 3] - fac * p2_4
    pr2 = b[ip]
    g3 = b[io] - fac * pr2
    va = a[3, 8]
    vb = a[7, 8]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 7, 3
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 3, 7
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v3 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v3
    p3_0 = a[ip, 4]
    m4_0 = a[io, 4] - fac * p3_0
    p3_1 = a[ip, 0]
    m4_1 = a[io, 0] - fac * p3_1
    p3_2 = a[ip, 1]
    m4_2 = a[io, 1] - fac * p3_2
    p3_3 = a[ip, 2]
    m4_3 = a[io, 2] - fac * p3_3
    p3_4 = a[ip, 3]
    m4_4 = a[io, 3] - fac * p3_4
    pr3 = b[ip]
    g4 = b[io] - fac * pr3
    best = abs(m0_0.real) + abs(m0_0.imag)
    mag = abs(m1_0.real) + abs(m1_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, m1_0, m1_1, m1_2, m1_3, m1_4, g1 = (
            m1_0,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
        )
    mag = abs(m2_0.real) + abs(m2_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, m2_0, m2_1, m2_2, m2_3, m2_4, g2 = (
            m2_0,
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            g2,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
        )
    mag = abs(m3_0.real) + abs(m3_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, m3_0, m3_1, m3_2, m3_3, m3_4, g3 = (
            m3_0,
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            g3,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
        )
    mag = abs(m4_0.real) + abs(m4_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, m4_0, m4_1, m4_2, m4_3, m4_4, g4 = (
            m4_0,
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            g4,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m0_0.real * m0_0.real + m0_0.imag * m0_0.imag)
    u0 = complex(m0_0.real * dd, -m0_0.imag * dd)
    fac = m1_0 * u0
    m1_1 = m1_1 - fac * m0_1
    m1_2 = m1_2 - fac * m0_2
    m1_3 = m1_3 - fac * m0_3
    m1_4 = m1_4 - fac * m0_4
    g1 = g1 - fac * g0
    fac = m2_0 * u0
    m2_1 = m2_1 - fac * m0_1
    m2_2 = m2_2 - fac * m0_2
    m2_3 = m2_3 - fac * m0_3
    m2_4 = m2_4 - fac * m0_4
    g2 = g2 - fac * g0
    fac = m3_0 * u0
    m3_1 = m3_1 - fac * m0_1
    m3_2 = m3_2 - fac * m0_2
    m3_3 = m3_3 - fac * m0_3
    m3_4 = m3_4 - fac * m0_4
    g3 = g3 - fac * g0
    fac = m4_0 * u0
    m4_1 = m4_1 - fac * m0_1
    m4_2 = m4_2 - fac * m0_2
    m4_3 = m4_3 - fac * m0_3
    m4_4 = m4_4 - fac * m0_4
    g4 = g4 - fac * g0
    best = abs(m1_1.real) + abs(m1_1.imag)
    mag = abs(m2_1.real) + abs(m2_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, m2_1, m2_2, m2_3, m2_4, g2 = (
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            g2,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
        )
    mag = abs(m3_1.real) + abs(m3_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, m3_1, m3_2, m3_3, m3_4, g3 = (
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            g3,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
        )
    mag = abs(m4_1.real) + abs(m4_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, m4_1, m4_2, m4_3, m4_4, g4 = (
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            g4,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m1_1.real * m1_1.real + m1_1.imag * m1_1.imag)
    u1 = complex(m1_1.real * dd, -m1_1.imag * dd)
    fac = m2_1 * u1
    m2_2 = m2_2 - fac * m1_2
    m2_3 = m2_3 - fac * m1_3
    m2_4 = m2_4 - fac * m1_4
    g2 = g2 - fac * g1
    fac = m3_1 * u1
    m3_2 = m3_2 - fac * m1_2
    m3_3 = m3_3 - fac * m1_3
    m3_4 = m3_4 - fac * m1_4
    g3 = g3 - fac * g1
    fac = m4_1 * u1
    m4_2 = m4_2 - fac * m1_2
    m4_3 = m4_3 - fac * m1_3
    m4_4 = m4_4 - fac * m1_4
    g4 = g4 - fac * g1
    best = abs(m2_2.real) + abs(m2_2.imag)
    mag = abs(m3_2.real) + abs(m3_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, g2, m3_2, m3_3, m3_4, g3 = m3_2, m3_3, m3_4, g3, m2_2, m2_3, m2_4, g2
    mag = abs(m4_2.real) + abs(m4_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, g2, m4_2, m4_3, m4_4, g4 = m4_2, m4_3, m4_4, g4, m2_2, m2_3, m2_4, g2
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m2_2.real * m2_2.real + m2_2.imag * m2_2.imag)
    u2 = complex(m2_2.real * dd, -m2_2.imag * dd)
    fac = m3_2 * u2
    m3_3 = m3_3 - fac * m2_3
    m3_4 = m3_4 - fac * m2_4
    g3 = g3 - fac * g2
    fac = m4_2 * u2
    m4_3 = m4_3 - fac * m2_3
    m4_4 = m4_4 - fac * m2_4
    g4 = g4 - fac * g2
    best = abs(m3_3.real) + abs(m3_3.imag)
    mag = abs(m4_3.real) + abs(m4_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, g3, m4_3, m4_4, g4 = m4_3, m4_4, g4, m3_3, m3_4, g3
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m3_3.real * m3_3.real + m3_3.imag * m3_3.imag)
    u3 = complex(m3_3.real * dd, -m3_3.imag * dd)
    fac = m4_3 * u3
    m4_4 = m4_4 - fac * m3_4
    g4 = g4 - fac * g3
    best = abs(m4_4.real) + abs(m4_4.imag)
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m4_4.real * m4_4.real + m4_4.imag * m4_4.imag)
    u4 = complex(m4_4.real * dd, -m4_4.imag * dd)
    x4 = (g4) * u4
    x3 = (g3 - m3_4 * x4) * u3
    x2 = (g2 - m2_3 * x3 - m2_4 * x4) * u2
    x1 = (g1 - m1_2 * x2 - m1_3 * x3 - m1_4 * x4) * u1
    x0 = (g0 - m0_1 * x1 - m0_2 * x2 - m0_3 * x3 - m0_4 * x4) * u0
    out[5] = (pr0 - p0_0 * x0 - p0_1 * x1 - p0_2 * x2 - p0_3 * x3 - p0_4 * x4) * v0
    out[6] = (pr1 - p1_0 * x0 - p1_1 * x1 - p1_2 * x2 - p1_3 * x3 - p1_4 * x4) * v1
    out[7] = (pr2 - p2_0 * x0 - p2_1 * x1 - p2_2 * x2 - p2_3 * x3 - p2_4 * x4) * v2
    out[8] = (pr3 - p3_0 * x0 - p3_1 * x1 - p3_2 * x2 - p3_3 * x3 - p3_4 * x4) * v3
    out[4] = x0
    out[0] = x1
    out[1] = x2
    out[2] = x3
    out[3] = x4
    return True


@numba.njit(**_JIT_SOLVE)
def solve_pair(a, b, c, out, out2, m, r, r2, plan, two):  # type: ignore[no-untyped-def]
    """out = a^-1 b and, if ``two``, out2 = a^-1 c (``out``, ``out2`` not ``b``, ``c``): the
    arithmetic of ``curverecon.solvers.homotopy._solve_pair`` with ELIMINATION's loops
    unrolled and every entry a local variable.  ``m``, ``r``, ``r2`` and ``plan`` are not read
    (that function's signature).  False if a pivot is zero or not finite."""
    if not two:
        return solve_one(a, b, out)
    m0_0 = a[8, 4]
    m0_1 = a[8, 0]
    m0_2 = a[8, 1]
    m0_3 = a[8, 2]
    m0_4 = a[8, 3]
    g0 = b[8]
    e0 = c[8]
    va = a[0, 5]
    vb = a[4, 5]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 4, 0
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 0, 4
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v0 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v0
    p0_0 = a[ip, 4]
    m1_0 = a[io, 4] - fac * p0_0
    p0_1 = a[ip, 0]
    m1_1 = a[io, 0] - fac * p0_1
    p0_2 = a[ip, 1]
    m1_2 = a[io, 1] - fac * p0_2
    p0_3 = a[ip, 2]
    m1_3 = a[io, 2] - fac * p0_3
    p0_4 = a[ip, 3]
    m1_4 = a[io, 3] - fac * p0_4
    pr0 = b[ip]
    g1 = b[io] - fac * pr0
    pt0 = c[ip]
    e1 = c[io] - fac * pt0
    va = a[1, 6]
    vb = a[5, 6]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 5, 1
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 1, 5
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v1 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v1
    p1_0 = a[ip, 4]
    m2_0 = a[io, 4] - fac * p1_0
    p1_1 = a[ip, 0]
    m2_1 = a[io, 0] - fac * p1_1
    p1_2 = a[ip, 1]
    m2_2 = a[io, 1] - fac * p1_2
    p1_3 = a[ip, 2]
    m2_3 = a[io, 2] - fac * p1_3
    p1_4 = a[ip, 3]
    m2_4 = a[io, 3] - fac * p1_4
    pr1 = b[ip]
    g2 = b[io] - fac * pr1
    pt1 = c[ip]
    e2 = c[io] - fac * pt1
    va = a[2, 7]
    vb = a[6, 7]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 6, 2
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 2, 6
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v2 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v2
    p2_0 = a[ip, 4]
    m3_0 = a[io, 4] - fac * p2_0
    p2_1 = a[ip, 0]
    m3_1 = a[io, 0] - fac * p2_1
    p2_2 = a[ip, 1]
    m3_2 = a[io, 1] - fac * p2_2
    p2_3 = a[ip, 2]
    m3_3 = a[io, 2] - fac * p2_3
    p2_4 = a[ip, 3]
    m3_4 = a[io, 3] - fac * p2_4
    pr2 = b[ip]
    g3 = b[io] - fac * pr2
    pt2 = c[ip]
    e3 = c[io] - fac * pt2
    va = a[3, 8]
    vb = a[7, 8]
    mag_a = abs(va.real) + abs(va.imag)
    mag_b = abs(vb.real) + abs(vb.imag)
    if mag_b > mag_a:
        ip, io = 7, 3
        va, vb, mag_a = vb, va, mag_b
    else:
        ip, io = 3, 7
    if mag_a == 0.0 or not np.isfinite(mag_a):
        return False
    dd = 1.0 / (va.real * va.real + va.imag * va.imag)
    v3 = complex(va.real * dd, -va.imag * dd)
    fac = vb * v3
    p3_0 = a[ip, 4]
    m4_0 = a[io, 4] - fac * p3_0
    p3_1 = a[ip, 0]
    m4_1 = a[io, 0] - fac * p3_1
    p3_2 = a[ip, 1]
    m4_2 = a[io, 1] - fac * p3_2
    p3_3 = a[ip, 2]
    m4_3 = a[io, 2] - fac * p3_3
    p3_4 = a[ip, 3]
    m4_4 = a[io, 3] - fac * p3_4
    pr3 = b[ip]
    g4 = b[io] - fac * pr3
    pt3 = c[ip]
    e4 = c[io] - fac * pt3
    best = abs(m0_0.real) + abs(m0_0.imag)
    mag = abs(m1_0.real) + abs(m1_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, e0, m1_0, m1_1, m1_2, m1_3, m1_4, g1, e1 = (
            m1_0,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
            e1,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
            e0,
        )
    mag = abs(m2_0.real) + abs(m2_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, e0, m2_0, m2_1, m2_2, m2_3, m2_4, g2, e2 = (
            m2_0,
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            g2,
            e2,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
            e0,
        )
    mag = abs(m3_0.real) + abs(m3_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, e0, m3_0, m3_1, m3_2, m3_3, m3_4, g3, e3 = (
            m3_0,
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            g3,
            e3,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
            e0,
        )
    mag = abs(m4_0.real) + abs(m4_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, g0, e0, m4_0, m4_1, m4_2, m4_3, m4_4, g4, e4 = (
            m4_0,
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            g4,
            e4,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            g0,
            e0,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m0_0.real * m0_0.real + m0_0.imag * m0_0.imag)
    u0 = complex(m0_0.real * dd, -m0_0.imag * dd)
    fac = m1_0 * u0
    m1_1 = m1_1 - fac * m0_1
    m1_2 = m1_2 - fac * m0_2
    m1_3 = m1_3 - fac * m0_3
    m1_4 = m1_4 - fac * m0_4
    g1 = g1 - fac * g0
    e1 = e1 - fac * e0
    fac = m2_0 * u0
    m2_1 = m2_1 - fac * m0_1
    m2_2 = m2_2 - fac * m0_2
    m2_3 = m2_3 - fac * m0_3
    m2_4 = m2_4 - fac * m0_4
    g2 = g2 - fac * g0
    e2 = e2 - fac * e0
    fac = m3_0 * u0
    m3_1 = m3_1 - fac * m0_1
    m3_2 = m3_2 - fac * m0_2
    m3_3 = m3_3 - fac * m0_3
    m3_4 = m3_4 - fac * m0_4
    g3 = g3 - fac * g0
    e3 = e3 - fac * e0
    fac = m4_0 * u0
    m4_1 = m4_1 - fac * m0_1
    m4_2 = m4_2 - fac * m0_2
    m4_3 = m4_3 - fac * m0_3
    m4_4 = m4_4 - fac * m0_4
    g4 = g4 - fac * g0
    e4 = e4 - fac * e0
    best = abs(m1_1.real) + abs(m1_1.imag)
    mag = abs(m2_1.real) + abs(m2_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, e1, m2_1, m2_2, m2_3, m2_4, g2, e2 = (
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            g2,
            e2,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
            e1,
        )
    mag = abs(m3_1.real) + abs(m3_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, e1, m3_1, m3_2, m3_3, m3_4, g3, e3 = (
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            g3,
            e3,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
            e1,
        )
    mag = abs(m4_1.real) + abs(m4_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, g1, e1, m4_1, m4_2, m4_3, m4_4, g4, e4 = (
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            g4,
            e4,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            g1,
            e1,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m1_1.real * m1_1.real + m1_1.imag * m1_1.imag)
    u1 = complex(m1_1.real * dd, -m1_1.imag * dd)
    fac = m2_1 * u1
    m2_2 = m2_2 - fac * m1_2
    m2_3 = m2_3 - fac * m1_3
    m2_4 = m2_4 - fac * m1_4
    g2 = g2 - fac * g1
    e2 = e2 - fac * e1
    fac = m3_1 * u1
    m3_2 = m3_2 - fac * m1_2
    m3_3 = m3_3 - fac * m1_3
    m3_4 = m3_4 - fac * m1_4
    g3 = g3 - fac * g1
    e3 = e3 - fac * e1
    fac = m4_1 * u1
    m4_2 = m4_2 - fac * m1_2
    m4_3 = m4_3 - fac * m1_3
    m4_4 = m4_4 - fac * m1_4
    g4 = g4 - fac * g1
    e4 = e4 - fac * e1
    best = abs(m2_2.real) + abs(m2_2.imag)
    mag = abs(m3_2.real) + abs(m3_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, g2, e2, m3_2, m3_3, m3_4, g3, e3 = (
            m3_2,
            m3_3,
            m3_4,
            g3,
            e3,
            m2_2,
            m2_3,
            m2_4,
            g2,
            e2,
        )
    mag = abs(m4_2.real) + abs(m4_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, g2, e2, m4_2, m4_3, m4_4, g4, e4 = (
            m4_2,
            m4_3,
            m4_4,
            g4,
            e4,
            m2_2,
            m2_3,
            m2_4,
            g2,
            e2,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m2_2.real * m2_2.real + m2_2.imag * m2_2.imag)
    u2 = complex(m2_2.real * dd, -m2_2.imag * dd)
    fac = m3_2 * u2
    m3_3 = m3_3 - fac * m2_3
    m3_4 = m3_4 - fac * m2_4
    g3 = g3 - fac * g2
    e3 = e3 - fac * e2
    fac = m4_2 * u2
    m4_3 = m4_3 - fac * m2_3
    m4_4 = m4_4 - fac * m2_4
    g4 = g4 - fac * g2
    e4 = e4 - fac * e2
    best = abs(m3_3.real) + abs(m3_3.imag)
    mag = abs(m4_3.real) + abs(m4_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, g3, e3, m4_3, m4_4, g4, e4 = m4_3, m4_4, g4, e4, m3_3, m3_4, g3, e3
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m3_3.real * m3_3.real + m3_3.imag * m3_3.imag)
    u3 = complex(m3_3.real * dd, -m3_3.imag * dd)
    fac = m4_3 * u3
    m4_4 = m4_4 - fac * m3_4
    g4 = g4 - fac * g3
    e4 = e4 - fac * e3
    best = abs(m4_4.real) + abs(m4_4.imag)
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m4_4.real * m4_4.real + m4_4.imag * m4_4.imag)
    u4 = complex(m4_4.real * dd, -m4_4.imag * dd)
    x4 = (g4) * u4
    y4 = (e4) * u4
    x3 = (g3 - m3_4 * x4) * u3
    y3 = (e3 - m3_4 * y4) * u3
    x2 = (g2 - m2_3 * x3 - m2_4 * x4) * u2
    y2 = (e2 - m2_3 * y3 - m2_4 * y4) * u2
    x1 = (g1 - m1_2 * x2 - m1_3 * x3 - m1_4 * x4) * u1
    y1 = (e1 - m1_2 * y2 - m1_3 * y3 - m1_4 * y4) * u1
    x0 = (g0 - m0_1 * x1 - m0_2 * x2 - m0_3 * x3 - m0_4 * x4) * u0
    y0 = (e0 - m0_1 * y1 - m0_2 * y2 - m0_3 * y3 - m0_4 * y4) * u0
    out[5] = (pr0 - p0_0 * x0 - p0_1 * x1 - p0_2 * x2 - p0_3 * x3 - p0_4 * x4) * v0
    out[6] = (pr1 - p1_0 * x0 - p1_1 * x1 - p1_2 * x2 - p1_3 * x3 - p1_4 * x4) * v1
    out[7] = (pr2 - p2_0 * x0 - p2_1 * x1 - p2_2 * x2 - p2_3 * x3 - p2_4 * x4) * v2
    out[8] = (pr3 - p3_0 * x0 - p3_1 * x1 - p3_2 * x2 - p3_3 * x3 - p3_4 * x4) * v3
    out[4] = x0
    out[0] = x1
    out[1] = x2
    out[2] = x3
    out[3] = x4
    out2[5] = (pt0 - p0_0 * y0 - p0_1 * y1 - p0_2 * y2 - p0_3 * y3 - p0_4 * y4) * v0
    out2[6] = (pt1 - p1_0 * y0 - p1_1 * y1 - p1_2 * y2 - p1_3 * y3 - p1_4 * y4) * v1
    out2[7] = (pt2 - p2_0 * y0 - p2_1 * y1 - p2_2 * y2 - p2_3 * y3 - p2_4 * y4) * v2
    out2[8] = (pt3 - p3_0 * y0 - p3_1 * y1 - p3_2 * y2 - p3_3 * y3 - p3_4 * y4) * v3
    out2[4] = y0
    out2[0] = y1
    out2[1] = y2
    out2[2] = y3
    out2[3] = y4
    return True

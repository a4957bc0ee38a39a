# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/section2_perspective.py
# Template:   derivations/codegen/templates/system_kernel.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Straight-line numba kernels of generated/persp_fixed_axis_system.py (generated).

The system F(x; q) = W(q) u(x) of derivations/section2_perspective.py, written out after one
common-subexpression pass instead of read from tables: ``coefficients`` and ``coefficients_t``
give the nonzero entries of W (and dW/dt along dq), ``residual_jacobian`` and
``residual_jacobian_t`` give F, F_x (and F_t) from them.  Complex arithmetic; every argument a
contiguous complex128 array.  curverecon.solvers.homotopy tracks paths with these when a system
comes with them, and reads the tables of the system module otherwise.
"""

from __future__ import annotations

import numba
import numpy as np

UNKNOWNS = ("b0", "c0", "n1", "n2", "m1", "m2")
PARAMETERS = (
    "a0x",
    "a0y",
    "a0z",
    "b0x",
    "b0y",
    "b0z",
    "c0x",
    "c0y",
    "c0z",
    "nab1x",
    "nab1y",
    "nab1z",
    "nac1x",
    "nac1y",
    "nac1z",
    "nbc1x",
    "nbc1y",
    "nbc1z",
    "nab2x",
    "nab2y",
    "nab2z",
    "nac2x",
    "nac2y",
    "nac2z",
    "nbc2x",
    "nbc2y",
    "nbc2z",
    "z1",
    "z2",
)
EQUATIONS = (
    "plane equation 0",
    "plane equation 1",
    "plane equation 2",
    "plane equation 3",
    "plane equation 4",
    "plane equation 5",
)

#: Entries of the coefficient matrix W(q) the kernels exchange (nonzero ones only).
N_COEFFICIENTS = 120

#: (equation, exponents of UNKNOWNS of the unknown monomial) of each entry of W, in order.
# fmt: off
COEFFICIENT_ENTRIES = (
    (0, (0, 0, 0, 0, 0, 0)), (0, (0, 0, 0, 0, 1, 0)), (0, (0, 0, 0, 0, 2, 0)),
    (0, (0, 0, 0, 1, 1, 0)), (0, (0, 0, 0, 1, 2, 0)), (0, (0, 0, 0, 2, 2, 0)),
    (0, (0, 0, 1, 0, 1, 0)), (0, (0, 0, 1, 0, 2, 0)), (0, (0, 0, 1, 1, 2, 0)),
    (0, (0, 0, 2, 0, 2, 0)), (0, (1, 0, 0, 0, 0, 0)), (0, (1, 0, 0, 0, 1, 0)),
    (0, (1, 0, 0, 0, 2, 0)), (0, (1, 0, 0, 1, 1, 0)), (0, (1, 0, 0, 1, 2, 0)),
    (0, (1, 0, 0, 2, 2, 0)), (0, (1, 0, 1, 0, 1, 0)), (0, (1, 0, 1, 0, 2, 0)),
    (0, (1, 0, 1, 1, 2, 0)), (0, (1, 0, 2, 0, 2, 0)), (1, (0, 0, 0, 0, 0, 0)),
    (1, (0, 0, 0, 0, 1, 0)), (1, (0, 0, 0, 0, 2, 0)), (1, (0, 0, 0, 1, 1, 0)),
    (1, (0, 0, 0, 1, 2, 0)), (1, (0, 0, 0, 2, 2, 0)), (1, (0, 0, 1, 0, 1, 0)),
    (1, (0, 0, 1, 0, 2, 0)), (1, (0, 0, 1, 1, 2, 0)), (1, (0, 0, 2, 0, 2, 0)),
    (1, (0, 1, 0, 0, 0, 0)), (1, (0, 1, 0, 0, 1, 0)), (1, (0, 1, 0, 0, 2, 0)),
    (1, (0, 1, 0, 1, 1, 0)), (1, (0, 1, 0, 1, 2, 0)), (1, (0, 1, 0, 2, 2, 0)),
    (1, (0, 1, 1, 0, 1, 0)), (1, (0, 1, 1, 0, 2, 0)), (1, (0, 1, 1, 1, 2, 0)),
    (1, (0, 1, 2, 0, 2, 0)), (2, (0, 1, 0, 0, 0, 0)), (2, (0, 1, 0, 0, 1, 0)),
    (2, (0, 1, 0, 0, 2, 0)), (2, (0, 1, 0, 1, 1, 0)), (2, (0, 1, 0, 1, 2, 0)),
    (2, (0, 1, 0, 2, 2, 0)), (2, (0, 1, 1, 0, 1, 0)), (2, (0, 1, 1, 0, 2, 0)),
    (2, (0, 1, 1, 1, 2, 0)), (2, (0, 1, 2, 0, 2, 0)), (2, (1, 0, 0, 0, 0, 0)),
    (2, (1, 0, 0, 0, 1, 0)), (2, (1, 0, 0, 0, 2, 0)), (2, (1, 0, 0, 1, 1, 0)),
    (2, (1, 0, 0, 1, 2, 0)), (2, (1, 0, 0, 2, 2, 0)), (2, (1, 0, 1, 0, 1, 0)),
    (2, (1, 0, 1, 0, 2, 0)), (2, (1, 0, 1, 1, 2, 0)), (2, (1, 0, 2, 0, 2, 0)),
    (3, (0, 0, 0, 0, 0, 0)), (3, (0, 0, 0, 0, 0, 1)), (3, (0, 0, 0, 0, 0, 2)),
    (3, (0, 0, 0, 1, 0, 1)), (3, (0, 0, 0, 1, 0, 2)), (3, (0, 0, 0, 2, 0, 2)),
    (3, (0, 0, 1, 0, 0, 1)), (3, (0, 0, 1, 0, 0, 2)), (3, (0, 0, 1, 1, 0, 2)),
    (3, (0, 0, 2, 0, 0, 2)), (3, (1, 0, 0, 0, 0, 0)), (3, (1, 0, 0, 0, 0, 1)),
    (3, (1, 0, 0, 0, 0, 2)), (3, (1, 0, 0, 1, 0, 1)), (3, (1, 0, 0, 1, 0, 2)),
    (3, (1, 0, 0, 2, 0, 2)), (3, (1, 0, 1, 0, 0, 1)), (3, (1, 0, 1, 0, 0, 2)),
    (3, (1, 0, 1, 1, 0, 2)), (3, (1, 0, 2, 0, 0, 2)), (4, (0, 0, 0, 0, 0, 0)),
    (4, (0, 0, 0, 0, 0, 1)), (4, (0, 0, 0, 0, 0, 2)), (4, (0, 0, 0, 1, 0, 1)),
    (4, (0, 0, 0, 1, 0, 2)), (4, (0, 0, 0, 2, 0, 2)), (4, (0, 0, 1, 0, 0, 1)),
    (4, (0, 0, 1, 0, 0, 2)), (4, (0, 0, 1, 1, 0, 2)), (4, (0, 0, 2, 0, 0, 2)),
    (4, (0, 1, 0, 0, 0, 0)), (4, (0, 1, 0, 0, 0, 1)), (4, (0, 1, 0, 0, 0, 2)),
    (4, (0, 1, 0, 1, 0, 1)), (4, (0, 1, 0, 1, 0, 2)), (4, (0, 1, 0, 2, 0, 2)),
    (4, (0, 1, 1, 0, 0, 1)), (4, (0, 1, 1, 0, 0, 2)), (4, (0, 1, 1, 1, 0, 2)),
    (4, (0, 1, 2, 0, 0, 2)), (5, (0, 1, 0, 0, 0, 0)), (5, (0, 1, 0, 0, 0, 1)),
    (5, (0, 1, 0, 0, 0, 2)), (5, (0, 1, 0, 1, 0, 1)), (5, (0, 1, 0, 1, 0, 2)),
    (5, (0, 1, 0, 2, 0, 2)), (5, (0, 1, 1, 0, 0, 1)), (5, (0, 1, 1, 0, 0, 2)),
    (5, (0, 1, 1, 1, 0, 2)), (5, (0, 1, 2, 0, 0, 2)), (5, (1, 0, 0, 0, 0, 0)),
    (5, (1, 0, 0, 0, 0, 1)), (5, (1, 0, 0, 0, 0, 2)), (5, (1, 0, 0, 1, 0, 1)),
    (5, (1, 0, 0, 1, 0, 2)), (5, (1, 0, 0, 2, 0, 2)), (5, (1, 0, 1, 0, 0, 1)),
    (5, (1, 0, 1, 0, 0, 2)), (5, (1, 0, 1, 1, 0, 2)), (5, (1, 0, 2, 0, 0, 2)),
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
    a0x = q[0]
    a0y = q[1]
    a0z = q[2]
    b0x = q[3]
    b0y = q[4]
    b0z = q[5]
    c0x = q[6]
    c0y = q[7]
    c0z = q[8]
    nab1x = q[9]
    nab1y = q[10]
    nab1z = q[11]
    nac1x = q[12]
    nac1y = q[13]
    nac1z = q[14]
    nbc1x = q[15]
    nbc1y = q[16]
    nbc1z = q[17]
    nab2x = q[18]
    nab2y = q[19]
    nab2z = q[20]
    nac2x = q[21]
    nac2y = q[22]
    nac2z = q[23]
    nbc2x = q[24]
    nbc2y = q[25]
    nbc2z = q[26]
    z1 = q[27]
    z2 = q[28]
    _tmp0 = a0y * nab1y
    _tmp1 = a0x * nab1x
    _tmp2 = a0z * nab1z
    _tmp3 = _tmp1 + _tmp2
    _tmp4 = a0x * nab1y
    _tmp5 = -_tmp0
    _tmp6 = z1 * z1
    _tmp7 = 2 * z1
    _tmp8 = -_tmp1 + _tmp2
    _tmp9 = a0x * nab1z
    _tmp10 = a0z * nab1x
    _tmp11 = a0y * nab1z
    _tmp12 = a0z * nab1y
    _tmp13 = b0y * nab1y
    _tmp14 = b0x * nab1x
    _tmp15 = b0z * nab1z
    _tmp16 = _tmp14 + _tmp15
    _tmp17 = b0x * nab1y
    _tmp18 = b0y * nab1x
    _tmp19 = -_tmp13
    _tmp20 = -_tmp14 + _tmp15
    _tmp21 = b0x * nab1z
    _tmp22 = b0y * nab1z
    _tmp23 = b0z * nab1y
    _tmp24 = b0z * nab1x
    _tmp25 = a0y * nac1y
    _tmp26 = a0x * nac1x
    _tmp27 = a0z * nac1z
    _tmp28 = _tmp26 + _tmp27
    _tmp29 = a0x * nac1y
    _tmp30 = -_tmp25
    _tmp31 = -_tmp26 + _tmp27
    _tmp32 = a0x * nac1z
    _tmp33 = a0z * nac1x
    _tmp34 = a0y * nac1z
    _tmp35 = a0z * nac1y
    _tmp36 = c0y * nac1y
    _tmp37 = c0x * nac1x
    _tmp38 = c0z * nac1z
    _tmp39 = _tmp37 + _tmp38
    _tmp40 = c0x * nac1y
    _tmp41 = c0y * nac1x
    _tmp42 = -_tmp36
    _tmp43 = -_tmp37 + _tmp38
    _tmp44 = c0x * nac1z
    _tmp45 = c0y * nac1z
    _tmp46 = c0z * nac1y
    _tmp47 = c0z * nac1x
    _tmp48 = c0y * nbc1y
    _tmp49 = c0x * nbc1x
    _tmp50 = c0z * nbc1z
    _tmp51 = _tmp49 + _tmp50
    _tmp52 = c0x * nbc1y
    _tmp53 = c0y * nbc1x
    _tmp54 = -_tmp48
    _tmp55 = -_tmp49 + _tmp50
    _tmp56 = c0x * nbc1z
    _tmp57 = c0y * nbc1z
    _tmp58 = c0z * nbc1y
    _tmp59 = c0z * nbc1x
    _tmp60 = b0y * nbc1y
    _tmp61 = b0x * nbc1x
    _tmp62 = b0z * nbc1z
    _tmp63 = _tmp61 + _tmp62
    _tmp64 = b0x * nbc1y
    _tmp65 = -_tmp60
    _tmp66 = -_tmp61 + _tmp62
    _tmp67 = b0x * nbc1z
    _tmp68 = b0z * nbc1x
    _tmp69 = b0y * nbc1z
    _tmp70 = b0z * nbc1y
    _tmp71 = a0y * nab2y
    _tmp72 = a0x * nab2x
    _tmp73 = a0z * nab2z
    _tmp74 = _tmp72 + _tmp73
    _tmp75 = a0x * nab2y
    _tmp76 = -_tmp71
    _tmp77 = z2 * z2
    _tmp78 = 2 * z2
    _tmp79 = -_tmp72 + _tmp73
    _tmp80 = a0x * nab2z
    _tmp81 = a0z * nab2x
    _tmp82 = a0y * nab2z
    _tmp83 = a0z * nab2y
    _tmp84 = b0y * nab2y
    _tmp85 = b0x * nab2x
    _tmp86 = b0z * nab2z
    _tmp87 = _tmp85 + _tmp86
    _tmp88 = b0x * nab2y
    _tmp89 = b0y * nab2x
    _tmp90 = -_tmp84
    _tmp91 = -_tmp85 + _tmp86
    _tmp92 = b0x * nab2z
    _tmp93 = b0y * nab2z
    _tmp94 = b0z * nab2y
    _tmp95 = b0z * nab2x
    _tmp96 = a0y * nac2y
    _tmp97 = a0x * nac2x
    _tmp98 = a0z * nac2z
    _tmp99 = _tmp97 + _tmp98
    _tmp100 = a0x * nac2y
    _tmp101 = -_tmp96
    _tmp102 = -_tmp97 + _tmp98
    _tmp103 = a0x * nac2z
    _tmp104 = a0z * nac2x
    _tmp105 = a0y * nac2z
    _tmp106 = a0z * nac2y
    _tmp107 = c0y * nac2y
    _tmp108 = c0x * nac2x
    _tmp109 = c0z * nac2z
    _tmp110 = _tmp108 + _tmp109
    _tmp111 = c0x * nac2y
    _tmp112 = c0y * nac2x
    _tmp113 = -_tmp107
    _tmp114 = -_tmp108 + _tmp109
    _tmp115 = c0x * nac2z
    _tmp116 = c0y * nac2z
    _tmp117 = c0z * nac2y
    _tmp118 = c0z * nac2x
    _tmp119 = c0y * nbc2y
    _tmp120 = c0x * nbc2x
    _tmp121 = c0z * nbc2z
    _tmp122 = _tmp120 + _tmp121
    _tmp123 = c0x * nbc2y
    _tmp124 = c0y * nbc2x
    _tmp125 = -_tmp119
    _tmp126 = -_tmp120 + _tmp121
    _tmp127 = c0x * nbc2z
    _tmp128 = c0y * nbc2z
    _tmp129 = c0z * nbc2y
    _tmp130 = c0z * nbc2x
    _tmp131 = b0y * nbc2y
    _tmp132 = b0x * nbc2x
    _tmp133 = b0z * nbc2z
    _tmp134 = _tmp132 + _tmp133
    _tmp135 = b0x * nbc2y
    _tmp136 = -_tmp131
    _tmp137 = -_tmp132 + _tmp133
    _tmp138 = b0x * nbc2z
    _tmp139 = b0z * nbc2x
    _tmp140 = b0y * nbc2z
    _tmp141 = b0z * nbc2y
    w[0] = -_tmp0 - _tmp3
    w[1] = -2 * _tmp0 * z1 - 2 * _tmp1 * z1 - 2 * _tmp2 * z1 - 2 * _tmp4 + 2 * a0y * nab1x
    w[2] = (
        -_tmp0 * _tmp6
        - _tmp1 * _tmp6
        - _tmp2 * _tmp6
        - _tmp4 * _tmp7
        - _tmp5
        - _tmp8
        + 2 * a0y * nab1x * z1
    )
    w[3] = -2 * _tmp10 + 2 * _tmp9
    w[4] = -2 * _tmp10 * z1 - 2 * _tmp11 - 2 * _tmp12 + 2 * a0x * nab1z * z1
    w[5] = _tmp3 + _tmp5
    w[6] = -2 * _tmp11 + 2 * _tmp12
    w[7] = -2 * _tmp10 - 2 * _tmp11 * z1 - 2 * _tmp9 + 2 * a0z * nab1y * z1
    w[8] = -2 * _tmp4 - 2 * a0y * nab1x
    w[9] = _tmp0 + _tmp8
    w[10] = _tmp13 + _tmp16
    w[11] = 2 * _tmp13 * z1 + 2 * _tmp14 * z1 + 2 * _tmp15 * z1 + 2 * _tmp17 - 2 * _tmp18
    w[12] = (
        _tmp13 * _tmp6
        + _tmp14 * _tmp6
        + _tmp15 * _tmp6
        + _tmp17 * _tmp7
        - _tmp18 * _tmp7
        + _tmp19
        + _tmp20
    )
    w[13] = -2 * _tmp21 + 2 * b0z * nab1x
    w[14] = -2 * _tmp21 * z1 + 2 * _tmp22 + 2 * _tmp23 + 2 * _tmp24 * z1
    w[15] = -_tmp16 - _tmp19
    w[16] = 2 * _tmp22 - 2 * _tmp23
    w[17] = 2 * _tmp21 + 2 * _tmp22 * z1 - 2 * _tmp23 * z1 + 2 * _tmp24
    w[18] = 2 * _tmp17 + 2 * _tmp18
    w[19] = -_tmp13 - _tmp20
    w[20] = -_tmp25 - _tmp28
    w[21] = -2 * _tmp25 * z1 - 2 * _tmp26 * z1 - 2 * _tmp27 * z1 - 2 * _tmp29 + 2 * a0y * nac1x
    w[22] = (
        -_tmp25 * _tmp6
        - _tmp26 * _tmp6
        - _tmp27 * _tmp6
        - _tmp29 * _tmp7
        - _tmp30
        - _tmp31
        + 2 * a0y * nac1x * z1
    )
    w[23] = 2 * _tmp32 - 2 * _tmp33
    w[24] = -2 * _tmp33 * z1 - 2 * _tmp34 - 2 * _tmp35 + 2 * a0x * nac1z * z1
    w[25] = _tmp28 + _tmp30
    w[26] = -2 * _tmp34 + 2 * _tmp35
    w[27] = -2 * _tmp32 - 2 * _tmp33 - 2 * _tmp34 * z1 + 2 * a0z * nac1y * z1
    w[28] = -2 * _tmp29 - 2 * a0y * nac1x
    w[29] = _tmp25 + _tmp31
    w[30] = _tmp36 + _tmp39
    w[31] = 2 * _tmp36 * z1 + 2 * _tmp37 * z1 + 2 * _tmp38 * z1 + 2 * _tmp40 - 2 * _tmp41
    w[32] = (
        _tmp36 * _tmp6
        + _tmp37 * _tmp6
        + _tmp38 * _tmp6
        + _tmp40 * _tmp7
        - _tmp41 * _tmp7
        + _tmp42
        + _tmp43
    )
    w[33] = -2 * _tmp44 + 2 * c0z * nac1x
    w[34] = -2 * _tmp44 * z1 + 2 * _tmp45 + 2 * _tmp46 + 2 * _tmp47 * z1
    w[35] = -_tmp39 - _tmp42
    w[36] = 2 * _tmp45 - 2 * _tmp46
    w[37] = 2 * _tmp44 + 2 * _tmp45 * z1 - 2 * _tmp46 * z1 + 2 * _tmp47
    w[38] = 2 * _tmp40 + 2 * _tmp41
    w[39] = -_tmp36 - _tmp43
    w[40] = _tmp48 + _tmp51
    w[41] = 2 * _tmp48 * z1 + 2 * _tmp49 * z1 + 2 * _tmp50 * z1 + 2 * _tmp52 - 2 * _tmp53
    w[42] = (
        _tmp48 * _tmp6
        + _tmp49 * _tmp6
        + _tmp50 * _tmp6
        + _tmp52 * _tmp7
        - _tmp53 * _tmp7
        + _tmp54
        + _tmp55
    )
    w[43] = -2 * _tmp56 + 2 * c0z * nbc1x
    w[44] = -2 * _tmp56 * z1 + 2 * _tmp57 + 2 * _tmp58 + 2 * _tmp59 * z1
    w[45] = -_tmp51 - _tmp54
    w[46] = 2 * _tmp57 - 2 * _tmp58
    w[47] = 2 * _tmp56 + 2 * _tmp57 * z1 - 2 * _tmp58 * z1 + 2 * _tmp59
    w[48] = 2 * _tmp52 + 2 * _tmp53
    w[49] = -_tmp48 - _tmp55
    w[50] = -_tmp60 - _tmp63
    w[51] = -2 * _tmp60 * z1 - 2 * _tmp61 * z1 - 2 * _tmp62 * z1 - 2 * _tmp64 + 2 * b0y * nbc1x
    w[52] = (
        -_tmp6 * _tmp60
        - _tmp6 * _tmp61
        - _tmp6 * _tmp62
        - _tmp64 * _tmp7
        - _tmp65
        - _tmp66
        + 2 * b0y * nbc1x * z1
    )
    w[53] = 2 * _tmp67 - 2 * _tmp68
    w[54] = -2 * _tmp68 * z1 - 2 * _tmp69 - 2 * _tmp70 + 2 * b0x * nbc1z * z1
    w[55] = _tmp63 + _tmp65
    w[56] = -2 * _tmp69 + 2 * _tmp70
    w[57] = -2 * _tmp67 - 2 * _tmp68 - 2 * _tmp69 * z1 + 2 * b0z * nbc1y * z1
    w[58] = -2 * _tmp64 - 2 * b0y * nbc1x
    w[59] = _tmp60 + _tmp66
    w[60] = -_tmp71 - _tmp74
    w[61] = -2 * _tmp71 * z2 - 2 * _tmp72 * z2 - 2 * _tmp73 * z2 - 2 * _tmp75 + 2 * a0y * nab2x
    w[62] = (
        -_tmp71 * _tmp77
        - _tmp72 * _tmp77
        - _tmp73 * _tmp77
        - _tmp75 * _tmp78
        - _tmp76
        - _tmp79
        + 2 * a0y * nab2x * z2
    )
    w[63] = 2 * _tmp80 - 2 * _tmp81
    w[64] = -2 * _tmp81 * z2 - 2 * _tmp82 - 2 * _tmp83 + 2 * a0x * nab2z * z2
    w[65] = _tmp74 + _tmp76
    w[66] = -2 * _tmp82 + 2 * _tmp83
    w[67] = -2 * _tmp80 - 2 * _tmp81 - 2 * _tmp82 * z2 + 2 * a0z * nab2y * z2
    w[68] = -2 * _tmp75 - 2 * a0y * nab2x
    w[69] = _tmp71 + _tmp79
    w[70] = _tmp84 + _tmp87
    w[71] = 2 * _tmp84 * z2 + 2 * _tmp85 * z2 + 2 * _tmp86 * z2 + 2 * _tmp88 - 2 * _tmp89
    w[72] = (
        _tmp77 * _tmp84
        + _tmp77 * _tmp85
        + _tmp77 * _tmp86
        + _tmp78 * _tmp88
        - _tmp78 * _tmp89
        + _tmp90
        + _tmp91
    )
    w[73] = -2 * _tmp92 + 2 * b0z * nab2x
    w[74] = -2 * _tmp92 * z2 + 2 * _tmp93 + 2 * _tmp94 + 2 * _tmp95 * z2
    w[75] = -_tmp87 - _tmp90
    w[76] = 2 * _tmp93 - 2 * _tmp94
    w[77] = 2 * _tmp92 + 2 * _tmp93 * z2 - 2 * _tmp94 * z2 + 2 * _tmp95
    w[78] = 2 * _tmp88 + 2 * _tmp89
    w[79] = -_tmp84 - _tmp91
    w[80] = -_tmp96 - _tmp99
    w[81] = -2 * _tmp100 - 2 * _tmp96 * z2 - 2 * _tmp97 * z2 - 2 * _tmp98 * z2 + 2 * a0y * nac2x
    w[82] = (
        -_tmp100 * _tmp78
        - _tmp101
        - _tmp102
        - _tmp77 * _tmp96
        - _tmp77 * _tmp97
        - _tmp77 * _tmp98
        + 2 * a0y * nac2x * z2
    )
    w[83] = 2 * _tmp103 - 2 * _tmp104
    w[84] = -2 * _tmp104 * z2 - 2 * _tmp105 - 2 * _tmp106 + 2 * a0x * nac2z * z2
    w[85] = _tmp101 + _tmp99
    w[86] = -2 * _tmp105 + 2 * _tmp106
    w[87] = -2 * _tmp103 - 2 * _tmp104 - 2 * _tmp105 * z2 + 2 * a0z * nac2y * z2
    w[88] = -2 * _tmp100 - 2 * a0y * nac2x
    w[89] = _tmp102 + _tmp96
    w[90] = _tmp107 + _tmp110
    w[91] = 2 * _tmp107 * z2 + 2 * _tmp108 * z2 + 2 * _tmp109 * z2 + 2 * _tmp111 - 2 * _tmp112
    w[92] = (
        _tmp107 * _tmp77
        + _tmp108 * _tmp77
        + _tmp109 * _tmp77
        + _tmp111 * _tmp78
        - _tmp112 * _tmp78
        + _tmp113
        + _tmp114
    )
    w[93] = -2 * _tmp115 + 2 * c0z * nac2x
    w[94] = -2 * _tmp115 * z2 + 2 * _tmp116 + 2 * _tmp117 + 2 * _tmp118 * z2
    w[95] = -_tmp110 - _tmp113
    w[96] = 2 * _tmp116 - 2 * _tmp117
    w[97] = 2 * _tmp115 + 2 * _tmp116 * z2 - 2 * _tmp117 * z2 + 2 * _tmp118
    w[98] = 2 * _tmp111 + 2 * _tmp112
    w[99] = -_tmp107 - _tmp114
    w[100] = _tmp119 + _tmp122
    w[101] = 2 * _tmp119 * z2 + 2 * _tmp120 * z2 + 2 * _tmp121 * z2 + 2 * _tmp123 - 2 * _tmp124
    w[102] = (
        _tmp119 * _tmp77
        + _tmp120 * _tmp77
        + _tmp121 * _tmp77
        + _tmp123 * _tmp78
        - _tmp124 * _tmp78
        + _tmp125
        + _tmp126
    )
    w[103] = -2 * _tmp127 + 2 * c0z * nbc2x
    w[104] = -2 * _tmp127 * z2 + 2 * _tmp128 + 2 * _tmp129 + 2 * _tmp130 * z2
    w[105] = -_tmp122 - _tmp125
    w[106] = 2 * _tmp128 - 2 * _tmp129
    w[107] = 2 * _tmp127 + 2 * _tmp128 * z2 - 2 * _tmp129 * z2 + 2 * _tmp130
    w[108] = 2 * _tmp123 + 2 * _tmp124
    w[109] = -_tmp119 - _tmp126
    w[110] = -_tmp131 - _tmp134
    w[111] = -2 * _tmp131 * z2 - 2 * _tmp132 * z2 - 2 * _tmp133 * z2 - 2 * _tmp135 + 2 * b0y * nbc2x
    w[112] = (
        -_tmp131 * _tmp77
        - _tmp132 * _tmp77
        - _tmp133 * _tmp77
        - _tmp135 * _tmp78
        - _tmp136
        - _tmp137
        + 2 * b0y * nbc2x * z2
    )
    w[113] = 2 * _tmp138 - 2 * _tmp139
    w[114] = -2 * _tmp139 * z2 - 2 * _tmp140 - 2 * _tmp141 + 2 * b0x * nbc2z * z2
    w[115] = _tmp134 + _tmp136
    w[116] = -2 * _tmp140 + 2 * _tmp141
    w[117] = -2 * _tmp138 - 2 * _tmp139 - 2 * _tmp140 * z2 + 2 * b0z * nbc2y * z2
    w[118] = -2 * _tmp135 - 2 * b0y * nbc2x
    w[119] = _tmp131 + _tmp137


@numba.njit(**_JIT)
def coefficients_t(q: np.ndarray, dq: np.ndarray, w: np.ndarray, wt: np.ndarray) -> None:
    """W(q) as ``coefficients`` and its derivative dW/dt = W_q . dq along dq = dq/dt.

    Outputs written in place (every entry): w, wt.
    """
    a0x = q[0]
    a0y = q[1]
    a0z = q[2]
    b0x = q[3]
    b0y = q[4]
    b0z = q[5]
    c0x = q[6]
    c0y = q[7]
    c0z = q[8]
    nab1x = q[9]
    nab1y = q[10]
    nab1z = q[11]
    nac1x = q[12]
    nac1y = q[13]
    nac1z = q[14]
    nbc1x = q[15]
    nbc1y = q[16]
    nbc1z = q[17]
    nab2x = q[18]
    nab2y = q[19]
    nab2z = q[20]
    nac2x = q[21]
    nac2y = q[22]
    nac2z = q[23]
    nbc2x = q[24]
    nbc2y = q[25]
    nbc2z = q[26]
    z1 = q[27]
    z2 = q[28]
    d_a0x = dq[0]
    d_a0y = dq[1]
    d_a0z = dq[2]
    d_b0x = dq[3]
    d_b0y = dq[4]
    d_b0z = dq[5]
    d_c0x = dq[6]
    d_c0y = dq[7]
    d_c0z = dq[8]
    d_nab1x = dq[9]
    d_nab1y = dq[10]
    d_nab1z = dq[11]
    d_nac1x = dq[12]
    d_nac1y = dq[13]
    d_nac1z = dq[14]
    d_nbc1x = dq[15]
    d_nbc1y = dq[16]
    d_nbc1z = dq[17]
    d_nab2x = dq[18]
    d_nab2y = dq[19]
    d_nab2z = dq[20]
    d_nac2x = dq[21]
    d_nac2y = dq[22]
    d_nac2z = dq[23]
    d_nbc2x = dq[24]
    d_nbc2y = dq[25]
    d_nbc2z = dq[26]
    d_z1 = dq[27]
    d_z2 = dq[28]
    _tmp0 = a0y * nab1y
    _tmp1 = a0x * nab1x
    _tmp2 = a0z * nab1z
    _tmp3 = _tmp1 + _tmp2
    _tmp4 = _tmp0 + _tmp3
    _tmp5 = a0x * nab1y
    _tmp6 = a0y * nab1x
    _tmp7 = _tmp5 - _tmp6
    _tmp8 = -_tmp0
    _tmp9 = z1 * z1
    _tmp10 = 2 * z1
    _tmp11 = -_tmp1 + _tmp2
    _tmp12 = a0x * nab1z
    _tmp13 = a0z * nab1x
    _tmp14 = _tmp12 - _tmp13
    _tmp15 = a0y * nab1z
    _tmp16 = a0z * nab1y
    _tmp17 = _tmp15 - _tmp16
    _tmp18 = b0y * nab1y
    _tmp19 = b0x * nab1x
    _tmp20 = b0z * nab1z
    _tmp21 = _tmp19 + _tmp20
    _tmp22 = _tmp18 + _tmp21
    _tmp23 = b0x * nab1y
    _tmp24 = b0y * nab1x
    _tmp25 = _tmp23 - _tmp24
    _tmp26 = -_tmp18
    _tmp27 = -_tmp19 + _tmp20
    _tmp28 = b0x * nab1z
    _tmp29 = _tmp28 - b0z * nab1x
    _tmp30 = b0y * nab1z
    _tmp31 = b0z * nab1y
    _tmp32 = b0z * nab1x
    _tmp33 = _tmp30 - _tmp31
    _tmp34 = a0y * nac1y
    _tmp35 = a0x * nac1x
    _tmp36 = a0z * nac1z
    _tmp37 = _tmp35 + _tmp36
    _tmp38 = _tmp34 + _tmp37
    _tmp39 = a0x * nac1y
    _tmp40 = a0y * nac1x
    _tmp41 = _tmp39 - _tmp40
    _tmp42 = -_tmp34
    _tmp43 = -_tmp35 + _tmp36
    _tmp44 = a0x * nac1z
    _tmp45 = a0z * nac1x
    _tmp46 = _tmp44 - _tmp45
    _tmp47 = a0y * nac1z
    _tmp48 = a0z * nac1y
    _tmp49 = _tmp47 - _tmp48
    _tmp50 = c0y * nac1y
    _tmp51 = c0x * nac1x
    _tmp52 = c0z * nac1z
    _tmp53 = _tmp51 + _tmp52
    _tmp54 = _tmp50 + _tmp53
    _tmp55 = c0x * nac1y
    _tmp56 = c0y * nac1x
    _tmp57 = _tmp55 - _tmp56
    _tmp58 = -_tmp50
    _tmp59 = -_tmp51 + _tmp52
    _tmp60 = c0x * nac1z
    _tmp61 = _tmp60 - c0z * nac1x
    _tmp62 = c0y * nac1z
    _tmp63 = c0z * nac1y
    _tmp64 = c0z * nac1x
    _tmp65 = _tmp62 - _tmp63
    _tmp66 = c0y * nbc1y
    _tmp67 = c0x * nbc1x
    _tmp68 = c0z * nbc1z
    _tmp69 = _tmp67 + _tmp68
    _tmp70 = _tmp66 + _tmp69
    _tmp71 = c0x * nbc1y
    _tmp72 = c0y * nbc1x
    _tmp73 = _tmp71 - _tmp72
    _tmp74 = -_tmp66
    _tmp75 = -_tmp67 + _tmp68
    _tmp76 = c0x * nbc1z
    _tmp77 = _tmp76 - c0z * nbc1x
    _tmp78 = c0y * nbc1z
    _tmp79 = c0z * nbc1y
    _tmp80 = c0z * nbc1x
    _tmp81 = _tmp78 - _tmp79
    _tmp82 = b0y * nbc1y
    _tmp83 = b0x * nbc1x
    _tmp84 = b0z * nbc1z
    _tmp85 = _tmp83 + _tmp84
    _tmp86 = _tmp82 + _tmp85
    _tmp87 = b0x * nbc1y
    _tmp88 = b0y * nbc1x
    _tmp89 = _tmp87 - _tmp88
    _tmp90 = -_tmp82
    _tmp91 = -_tmp83 + _tmp84
    _tmp92 = b0x * nbc1z
    _tmp93 = b0z * nbc1x
    _tmp94 = _tmp92 - _tmp93
    _tmp95 = b0y * nbc1z
    _tmp96 = b0z * nbc1y
    _tmp97 = _tmp95 - _tmp96
    _tmp98 = a0y * nab2y
    _tmp99 = a0x * nab2x
    _tmp100 = a0z * nab2z
    _tmp101 = _tmp100 + _tmp99
    _tmp102 = _tmp101 + _tmp98
    _tmp103 = a0x * nab2y
    _tmp104 = a0y * nab2x
    _tmp105 = _tmp103 - _tmp104
    _tmp106 = -_tmp98
    _tmp107 = z2 * z2
    _tmp108 = 2 * z2
    _tmp109 = _tmp100 - _tmp99
    _tmp110 = a0x * nab2z
    _tmp111 = a0z * nab2x
    _tmp112 = _tmp110 - _tmp111
    _tmp113 = a0y * nab2z
    _tmp114 = a0z * nab2y
    _tmp115 = _tmp113 - _tmp114
    _tmp116 = b0y * nab2y
    _tmp117 = b0x * nab2x
    _tmp118 = b0z * nab2z
    _tmp119 = _tmp117 + _tmp118
    _tmp120 = _tmp116 + _tmp119
    _tmp121 = b0x * nab2y
    _tmp122 = b0y * nab2x
    _tmp123 = _tmp121 - _tmp122
    _tmp124 = -_tmp116
    _tmp125 = -_tmp117 + _tmp118
    _tmp126 = b0x * nab2z
    _tmp127 = _tmp126 - b0z * nab2x
    _tmp128 = b0y * nab2z
    _tmp129 = b0z * nab2y
    _tmp130 = b0z * nab2x
    _tmp131 = _tmp128 - _tmp129
    _tmp132 = a0y * nac2y
    _tmp133 = a0x * nac2x
    _tmp134 = a0z * nac2z
    _tmp135 = _tmp133 + _tmp134
    _tmp136 = _tmp132 + _tmp135
    _tmp137 = a0x * nac2y
    _tmp138 = a0y * nac2x
    _tmp139 = _tmp137 - _tmp138
    _tmp140 = -_tmp132
    _tmp141 = -_tmp133 + _tmp134
    _tmp142 = a0x * nac2z
    _tmp143 = a0z * nac2x
    _tmp144 = _tmp142 - _tmp143
    _tmp145 = a0y * nac2z
    _tmp146 = a0z * nac2y
    _tmp147 = _tmp145 - _tmp146
    _tmp148 = c0y * nac2y
    _tmp149 = c0x * nac2x
    _tmp150 = c0z * nac2z
    _tmp151 = _tmp149 + _tmp150
    _tmp152 = _tmp148 + _tmp151
    _tmp153 = c0x * nac2y
    _tmp154 = c0y * nac2x
    _tmp155 = _tmp153 - _tmp154
    _tmp156 = -_tmp148
    _tmp157 = -_tmp149 + _tmp150
    _tmp158 = c0x * nac2z
    _tmp159 = _tmp158 - c0z * nac2x
    _tmp160 = c0y * nac2z
    _tmp161 = c0z * nac2y
    _tmp162 = c0z * nac2x
    _tmp163 = _tmp160 - _tmp161
    _tmp164 = c0y * nbc2y
    _tmp165 = c0x * nbc2x
    _tmp166 = c0z * nbc2z
    _tmp167 = _tmp165 + _tmp166
    _tmp168 = _tmp164 + _tmp167
    _tmp169 = c0x * nbc2y
    _tmp170 = c0y * nbc2x
    _tmp171 = _tmp169 - _tmp170
    _tmp172 = -_tmp164
    _tmp173 = -_tmp165 + _tmp166
    _tmp174 = c0x * nbc2z
    _tmp175 = _tmp174 - c0z * nbc2x
    _tmp176 = c0y * nbc2z
    _tmp177 = c0z * nbc2y
    _tmp178 = c0z * nbc2x
    _tmp179 = _tmp176 - _tmp177
    _tmp180 = b0y * nbc2y
    _tmp181 = b0x * nbc2x
    _tmp182 = b0z * nbc2z
    _tmp183 = _tmp181 + _tmp182
    _tmp184 = _tmp180 + _tmp183
    _tmp185 = b0x * nbc2y
    _tmp186 = b0y * nbc2x
    _tmp187 = _tmp185 - _tmp186
    _tmp188 = -_tmp180
    _tmp189 = -_tmp181 + _tmp182
    _tmp190 = b0x * nbc2z
    _tmp191 = b0z * nbc2x
    _tmp192 = _tmp190 - _tmp191
    _tmp193 = b0y * nbc2z
    _tmp194 = b0z * nbc2y
    _tmp195 = _tmp193 - _tmp194
    _tmp196 = a0x * d_nab1x
    _tmp197 = a0z * d_nab1z
    _tmp198 = d_a0x * nab1x
    _tmp199 = d_a0z * nab1z
    _tmp200 = _tmp196 + _tmp197 + _tmp198 + _tmp199
    _tmp201 = a0y * d_nab1y
    _tmp202 = d_a0y * nab1y
    _tmp203 = _tmp201 + _tmp202
    _tmp204 = nab1x * z1
    _tmp205 = _tmp204 + nab1y
    _tmp206 = a0y * z1
    _tmp207 = _tmp206 + a0x
    _tmp208 = -nab1y * z1
    _tmp209 = _tmp208 + nab1x
    _tmp210 = -a0y
    _tmp211 = a0x * z1
    _tmp212 = _tmp210 + _tmp211
    _tmp213 = _tmp9 + 1
    _tmp214 = nab1x - z1 * (_tmp204 + 2 * nab1y)
    _tmp215 = _tmp208 + 2 * nab1x
    _tmp216 = -2 * a0y
    _tmp217 = a0x - z1 * (_tmp211 + _tmp216)
    _tmp218 = 2 * a0x
    _tmp219 = a0y - z1 * (_tmp206 + _tmp218)
    _tmp220 = 2 * d_z1
    _tmp221 = d_a0x * nab1z
    _tmp222 = a0z * d_nab1x
    _tmp223 = a0z * d_nab1y
    _tmp224 = d_a0y * nab1z
    _tmp225 = b0x * d_nab1x
    _tmp226 = b0z * d_nab1z
    _tmp227 = d_b0x * nab1x
    _tmp228 = d_b0z * nab1z
    _tmp229 = _tmp225 + _tmp226 + _tmp227 + _tmp228
    _tmp230 = b0y * d_nab1y
    _tmp231 = d_b0y * nab1y
    _tmp232 = _tmp230 + _tmp231
    _tmp233 = b0y * z1
    _tmp234 = _tmp233 + b0x
    _tmp235 = -b0y
    _tmp236 = b0x * z1
    _tmp237 = _tmp235 + _tmp236
    _tmp238 = -2 * b0y
    _tmp239 = b0x - z1 * (_tmp236 + _tmp238)
    _tmp240 = 2 * b0x
    _tmp241 = b0y - z1 * (_tmp233 + _tmp240)
    _tmp242 = d_b0x * nab1z
    _tmp243 = b0z * d_nab1y
    _tmp244 = d_b0y * nab1z
    _tmp245 = b0z * d_nab1x
    _tmp246 = a0x * d_nac1x
    _tmp247 = a0z * d_nac1z
    _tmp248 = d_a0x * nac1x
    _tmp249 = d_a0z * nac1z
    _tmp250 = _tmp246 + _tmp247 + _tmp248 + _tmp249
    _tmp251 = a0y * d_nac1y
    _tmp252 = d_a0y * nac1y
    _tmp253 = _tmp251 + _tmp252
    _tmp254 = nac1x * z1
    _tmp255 = _tmp254 + nac1y
    _tmp256 = -nac1y * z1
    _tmp257 = _tmp256 + nac1x
    _tmp258 = nac1x - z1 * (_tmp254 + 2 * nac1y)
    _tmp259 = _tmp256 + 2 * nac1x
    _tmp260 = d_a0x * nac1z
    _tmp261 = a0z * d_nac1x
    _tmp262 = a0z * d_nac1y
    _tmp263 = d_a0y * nac1z
    _tmp264 = c0x * d_nac1x
    _tmp265 = c0z * d_nac1z
    _tmp266 = d_c0x * nac1x
    _tmp267 = d_c0z * nac1z
    _tmp268 = _tmp264 + _tmp265 + _tmp266 + _tmp267
    _tmp269 = c0y * d_nac1y
    _tmp270 = d_c0y * nac1y
    _tmp271 = _tmp269 + _tmp270
    _tmp272 = c0y * z1
    _tmp273 = _tmp272 + c0x
    _tmp274 = -c0y
    _tmp275 = c0x * z1
    _tmp276 = _tmp274 + _tmp275
    _tmp277 = -2 * c0y
    _tmp278 = c0x - z1 * (_tmp275 + _tmp277)
    _tmp279 = 2 * c0x
    _tmp280 = c0y - z1 * (_tmp272 + _tmp279)
    _tmp281 = d_c0x * nac1z
    _tmp282 = c0z * d_nac1y
    _tmp283 = d_c0y * nac1z
    _tmp284 = c0z * d_nac1x
    _tmp285 = c0x * d_nbc1x
    _tmp286 = c0z * d_nbc1z
    _tmp287 = d_c0x * nbc1x
    _tmp288 = d_c0z * nbc1z
    _tmp289 = _tmp285 + _tmp286 + _tmp287 + _tmp288
    _tmp290 = c0y * d_nbc1y
    _tmp291 = d_c0y * nbc1y
    _tmp292 = _tmp290 + _tmp291
    _tmp293 = nbc1x * z1
    _tmp294 = _tmp293 + nbc1y
    _tmp295 = -nbc1y * z1
    _tmp296 = _tmp295 + nbc1x
    _tmp297 = nbc1x - z1 * (_tmp293 + 2 * nbc1y)
    _tmp298 = _tmp295 + 2 * nbc1x
    _tmp299 = d_c0x * nbc1z
    _tmp300 = c0z * d_nbc1y
    _tmp301 = d_c0y * nbc1z
    _tmp302 = c0z * d_nbc1x
    _tmp303 = b0x * d_nbc1x
    _tmp304 = b0z * d_nbc1z
    _tmp305 = d_b0x * nbc1x
    _tmp306 = d_b0z * nbc1z
    _tmp307 = _tmp303 + _tmp304 + _tmp305 + _tmp306
    _tmp308 = b0y * d_nbc1y
    _tmp309 = d_b0y * nbc1y
    _tmp310 = _tmp308 + _tmp309
    _tmp311 = d_b0x * nbc1z
    _tmp312 = b0z * d_nbc1x
    _tmp313 = b0z * d_nbc1y
    _tmp314 = d_b0y * nbc1z
    _tmp315 = a0x * d_nab2x
    _tmp316 = a0z * d_nab2z
    _tmp317 = d_a0x * nab2x
    _tmp318 = d_a0z * nab2z
    _tmp319 = _tmp315 + _tmp316 + _tmp317 + _tmp318
    _tmp320 = a0y * d_nab2y
    _tmp321 = d_a0y * nab2y
    _tmp322 = _tmp320 + _tmp321
    _tmp323 = nab2x * z2
    _tmp324 = _tmp323 + nab2y
    _tmp325 = a0y * z2
    _tmp326 = _tmp325 + a0x
    _tmp327 = -nab2y * z2
    _tmp328 = _tmp327 + nab2x
    _tmp329 = a0x * z2
    _tmp330 = _tmp210 + _tmp329
    _tmp331 = _tmp107 + 1
    _tmp332 = nab2x - z2 * (_tmp323 + 2 * nab2y)
    _tmp333 = _tmp327 + 2 * nab2x
    _tmp334 = a0x - z2 * (_tmp216 + _tmp329)
    _tmp335 = a0y - z2 * (_tmp218 + _tmp325)
    _tmp336 = 2 * d_z2
    _tmp337 = d_a0x * nab2z
    _tmp338 = a0z * d_nab2x
    _tmp339 = a0z * d_nab2y
    _tmp340 = d_a0y * nab2z
    _tmp341 = b0x * d_nab2x
    _tmp342 = b0z * d_nab2z
    _tmp343 = d_b0x * nab2x
    _tmp344 = d_b0z * nab2z
    _tmp345 = _tmp341 + _tmp342 + _tmp343 + _tmp344
    _tmp346 = b0y * d_nab2y
    _tmp347 = d_b0y * nab2y
    _tmp348 = _tmp346 + _tmp347
    _tmp349 = b0y * z2
    _tmp350 = _tmp349 + b0x
    _tmp351 = b0x * z2
    _tmp352 = _tmp235 + _tmp351
    _tmp353 = b0x - z2 * (_tmp238 + _tmp351)
    _tmp354 = b0y - z2 * (_tmp240 + _tmp349)
    _tmp355 = d_b0x * nab2z
    _tmp356 = b0z * d_nab2y
    _tmp357 = d_b0y * nab2z
    _tmp358 = b0z * d_nab2x
    _tmp359 = a0x * d_nac2x
    _tmp360 = a0z * d_nac2z
    _tmp361 = d_a0x * nac2x
    _tmp362 = d_a0z * nac2z
    _tmp363 = _tmp359 + _tmp360 + _tmp361 + _tmp362
    _tmp364 = a0y * d_nac2y
    _tmp365 = d_a0y * nac2y
    _tmp366 = _tmp364 + _tmp365
    _tmp367 = nac2x * z2
    _tmp368 = _tmp367 + nac2y
    _tmp369 = -nac2y * z2
    _tmp370 = _tmp369 + nac2x
    _tmp371 = nac2x - z2 * (_tmp367 + 2 * nac2y)
    _tmp372 = _tmp369 + 2 * nac2x
    _tmp373 = d_a0x * nac2z
    _tmp374 = a0z * d_nac2x
    _tmp375 = a0z * d_nac2y
    _tmp376 = d_a0y * nac2z
    _tmp377 = c0x * d_nac2x
    _tmp378 = c0z * d_nac2z
    _tmp379 = d_c0x * nac2x
    _tmp380 = d_c0z * nac2z
    _tmp381 = _tmp377 + _tmp378 + _tmp379 + _tmp380
    _tmp382 = c0y * d_nac2y
    _tmp383 = d_c0y * nac2y
    _tmp384 = _tmp382 + _tmp383
    _tmp385 = c0y * z2
    _tmp386 = _tmp385 + c0x
    _tmp387 = c0x * z2
    _tmp388 = _tmp274 + _tmp387
    _tmp389 = c0x - z2 * (_tmp277 + _tmp387)
    _tmp390 = c0y - z2 * (_tmp279 + _tmp385)
    _tmp391 = d_c0x * nac2z
    _tmp392 = c0z * d_nac2y
    _tmp393 = d_c0y * nac2z
    _tmp394 = c0z * d_nac2x
    _tmp395 = c0x * d_nbc2x
    _tmp396 = c0z * d_nbc2z
    _tmp397 = d_c0x * nbc2x
    _tmp398 = d_c0z * nbc2z
    _tmp399 = _tmp395 + _tmp396 + _tmp397 + _tmp398
    _tmp400 = c0y * d_nbc2y
    _tmp401 = d_c0y * nbc2y
    _tmp402 = _tmp400 + _tmp401
    _tmp403 = nbc2x * z2
    _tmp404 = _tmp403 + nbc2y
    _tmp405 = -nbc2y * z2
    _tmp406 = _tmp405 + nbc2x
    _tmp407 = nbc2x - z2 * (_tmp403 + 2 * nbc2y)
    _tmp408 = _tmp405 + 2 * nbc2x
    _tmp409 = d_c0x * nbc2z
    _tmp410 = c0z * d_nbc2y
    _tmp411 = d_c0y * nbc2z
    _tmp412 = c0z * d_nbc2x
    _tmp413 = b0x * d_nbc2x
    _tmp414 = b0z * d_nbc2z
    _tmp415 = d_b0x * nbc2x
    _tmp416 = d_b0z * nbc2z
    _tmp417 = _tmp413 + _tmp414 + _tmp415 + _tmp416
    _tmp418 = b0y * d_nbc2y
    _tmp419 = d_b0y * nbc2y
    _tmp420 = _tmp418 + _tmp419
    _tmp421 = d_b0x * nbc2z
    _tmp422 = b0z * d_nbc2x
    _tmp423 = b0z * d_nbc2y
    _tmp424 = d_b0y * nbc2z
    w[0] = -_tmp4
    w[1] = -2 * _tmp0 * z1 - 2 * _tmp1 * z1 - 2 * _tmp2 * z1 - 2 * _tmp7
    w[2] = (
        -_tmp0 * _tmp9
        - _tmp1 * _tmp9
        - _tmp10 * _tmp5
        - _tmp11
        - _tmp2 * _tmp9
        - _tmp8
        + 2 * a0y * nab1x * z1
    )
    w[3] = 2 * _tmp14
    w[4] = -2 * _tmp13 * z1 - 2 * _tmp15 - 2 * _tmp16 + 2 * a0x * nab1z * z1
    w[5] = _tmp3 + _tmp8
    w[6] = -2 * _tmp17
    w[7] = -2 * _tmp12 - 2 * _tmp13 - 2 * _tmp15 * z1 + 2 * a0z * nab1y * z1
    w[8] = -2 * _tmp5 - 2 * _tmp6
    w[9] = _tmp0 + _tmp11
    w[10] = _tmp22
    w[11] = 2 * _tmp18 * z1 + 2 * _tmp19 * z1 + 2 * _tmp20 * z1 + 2 * _tmp25
    w[12] = (
        _tmp10 * _tmp23
        - _tmp10 * _tmp24
        + _tmp18 * _tmp9
        + _tmp19 * _tmp9
        + _tmp20 * _tmp9
        + _tmp26
        + _tmp27
    )
    w[13] = -2 * _tmp29
    w[14] = -2 * _tmp28 * z1 + 2 * _tmp30 + 2 * _tmp31 + 2 * _tmp32 * z1
    w[15] = -_tmp21 - _tmp26
    w[16] = 2 * _tmp33
    w[17] = 2 * _tmp28 + 2 * _tmp30 * z1 - 2 * _tmp31 * z1 + 2 * _tmp32
    w[18] = 2 * _tmp23 + 2 * _tmp24
    w[19] = -_tmp18 - _tmp27
    w[20] = -_tmp38
    w[21] = -2 * _tmp34 * z1 - 2 * _tmp35 * z1 - 2 * _tmp36 * z1 - 2 * _tmp41
    w[22] = (
        -_tmp10 * _tmp39
        - _tmp34 * _tmp9
        - _tmp35 * _tmp9
        - _tmp36 * _tmp9
        - _tmp42
        - _tmp43
        + 2 * a0y * nac1x * z1
    )
    w[23] = 2 * _tmp46
    w[24] = -2 * _tmp45 * z1 - 2 * _tmp47 - 2 * _tmp48 + 2 * a0x * nac1z * z1
    w[25] = _tmp37 + _tmp42
    w[26] = -2 * _tmp49
    w[27] = -2 * _tmp44 - 2 * _tmp45 - 2 * _tmp47 * z1 + 2 * a0z * nac1y * z1
    w[28] = -2 * _tmp39 - 2 * _tmp40
    w[29] = _tmp34 + _tmp43
    w[30] = _tmp54
    w[31] = 2 * _tmp50 * z1 + 2 * _tmp51 * z1 + 2 * _tmp52 * z1 + 2 * _tmp57
    w[32] = (
        _tmp10 * _tmp55
        - _tmp10 * _tmp56
        + _tmp50 * _tmp9
        + _tmp51 * _tmp9
        + _tmp52 * _tmp9
        + _tmp58
        + _tmp59
    )
    w[33] = -2 * _tmp61
    w[34] = -2 * _tmp60 * z1 + 2 * _tmp62 + 2 * _tmp63 + 2 * _tmp64 * z1
    w[35] = -_tmp53 - _tmp58
    w[36] = 2 * _tmp65
    w[37] = 2 * _tmp60 + 2 * _tmp62 * z1 - 2 * _tmp63 * z1 + 2 * _tmp64
    w[38] = 2 * _tmp55 + 2 * _tmp56
    w[39] = -_tmp50 - _tmp59
    w[40] = _tmp70
    w[41] = 2 * _tmp66 * z1 + 2 * _tmp67 * z1 + 2 * _tmp68 * z1 + 2 * _tmp73
    w[42] = (
        _tmp10 * _tmp71
        - _tmp10 * _tmp72
        + _tmp66 * _tmp9
        + _tmp67 * _tmp9
        + _tmp68 * _tmp9
        + _tmp74
        + _tmp75
    )
    w[43] = -2 * _tmp77
    w[44] = -2 * _tmp76 * z1 + 2 * _tmp78 + 2 * _tmp79 + 2 * _tmp80 * z1
    w[45] = -_tmp69 - _tmp74
    w[46] = 2 * _tmp81
    w[47] = 2 * _tmp76 + 2 * _tmp78 * z1 - 2 * _tmp79 * z1 + 2 * _tmp80
    w[48] = 2 * _tmp71 + 2 * _tmp72
    w[49] = -_tmp66 - _tmp75
    w[50] = -_tmp86
    w[51] = -2 * _tmp82 * z1 - 2 * _tmp83 * z1 - 2 * _tmp84 * z1 - 2 * _tmp89
    w[52] = (
        -_tmp10 * _tmp87
        - _tmp82 * _tmp9
        - _tmp83 * _tmp9
        - _tmp84 * _tmp9
        - _tmp90
        - _tmp91
        + 2 * b0y * nbc1x * z1
    )
    w[53] = 2 * _tmp94
    w[54] = -2 * _tmp93 * z1 - 2 * _tmp95 - 2 * _tmp96 + 2 * b0x * nbc1z * z1
    w[55] = _tmp85 + _tmp90
    w[56] = -2 * _tmp97
    w[57] = -2 * _tmp92 - 2 * _tmp93 - 2 * _tmp95 * z1 + 2 * b0z * nbc1y * z1
    w[58] = -2 * _tmp87 - 2 * _tmp88
    w[59] = _tmp82 + _tmp91
    w[60] = -_tmp102
    w[61] = -2 * _tmp100 * z2 - 2 * _tmp105 - 2 * _tmp98 * z2 - 2 * _tmp99 * z2
    w[62] = (
        -_tmp100 * _tmp107
        - _tmp103 * _tmp108
        - _tmp106
        - _tmp107 * _tmp98
        - _tmp107 * _tmp99
        - _tmp109
        + 2 * a0y * nab2x * z2
    )
    w[63] = 2 * _tmp112
    w[64] = -2 * _tmp111 * z2 - 2 * _tmp113 - 2 * _tmp114 + 2 * a0x * nab2z * z2
    w[65] = _tmp101 + _tmp106
    w[66] = -2 * _tmp115
    w[67] = -2 * _tmp110 - 2 * _tmp111 - 2 * _tmp113 * z2 + 2 * a0z * nab2y * z2
    w[68] = -2 * _tmp103 - 2 * _tmp104
    w[69] = _tmp109 + _tmp98
    w[70] = _tmp120
    w[71] = 2 * _tmp116 * z2 + 2 * _tmp117 * z2 + 2 * _tmp118 * z2 + 2 * _tmp123
    w[72] = (
        _tmp107 * _tmp116
        + _tmp107 * _tmp117
        + _tmp107 * _tmp118
        + _tmp108 * _tmp121
        - _tmp108 * _tmp122
        + _tmp124
        + _tmp125
    )
    w[73] = -2 * _tmp127
    w[74] = -2 * _tmp126 * z2 + 2 * _tmp128 + 2 * _tmp129 + 2 * _tmp130 * z2
    w[75] = -_tmp119 - _tmp124
    w[76] = 2 * _tmp131
    w[77] = 2 * _tmp126 + 2 * _tmp128 * z2 - 2 * _tmp129 * z2 + 2 * _tmp130
    w[78] = 2 * _tmp121 + 2 * _tmp122
    w[79] = -_tmp116 - _tmp125
    w[80] = -_tmp136
    w[81] = -2 * _tmp132 * z2 - 2 * _tmp133 * z2 - 2 * _tmp134 * z2 - 2 * _tmp139
    w[82] = (
        -_tmp107 * _tmp132
        - _tmp107 * _tmp133
        - _tmp107 * _tmp134
        - _tmp108 * _tmp137
        - _tmp140
        - _tmp141
        + 2 * a0y * nac2x * z2
    )
    w[83] = 2 * _tmp144
    w[84] = -2 * _tmp143 * z2 - 2 * _tmp145 - 2 * _tmp146 + 2 * a0x * nac2z * z2
    w[85] = _tmp135 + _tmp140
    w[86] = -2 * _tmp147
    w[87] = -2 * _tmp142 - 2 * _tmp143 - 2 * _tmp145 * z2 + 2 * a0z * nac2y * z2
    w[88] = -2 * _tmp137 - 2 * _tmp138
    w[89] = _tmp132 + _tmp141
    w[90] = _tmp152
    w[91] = 2 * _tmp148 * z2 + 2 * _tmp149 * z2 + 2 * _tmp150 * z2 + 2 * _tmp155
    w[92] = (
        _tmp107 * _tmp148
        + _tmp107 * _tmp149
        + _tmp107 * _tmp150
        + _tmp108 * _tmp153
        - _tmp108 * _tmp154
        + _tmp156
        + _tmp157
    )
    w[93] = -2 * _tmp159
    w[94] = -2 * _tmp158 * z2 + 2 * _tmp160 + 2 * _tmp161 + 2 * _tmp162 * z2
    w[95] = -_tmp151 - _tmp156
    w[96] = 2 * _tmp163
    w[97] = 2 * _tmp158 + 2 * _tmp160 * z2 - 2 * _tmp161 * z2 + 2 * _tmp162
    w[98] = 2 * _tmp153 + 2 * _tmp154
    w[99] = -_tmp148 - _tmp157
    w[100] = _tmp168
    w[101] = 2 * _tmp164 * z2 + 2 * _tmp165 * z2 + 2 * _tmp166 * z2 + 2 * _tmp171
    w[102] = (
        _tmp107 * _tmp164
        + _tmp107 * _tmp165
        + _tmp107 * _tmp166
        + _tmp108 * _tmp169
        - _tmp108 * _tmp170
        + _tmp172
        + _tmp173
    )
    w[103] = -2 * _tmp175
    w[104] = -2 * _tmp174 * z2 + 2 * _tmp176 + 2 * _tmp177 + 2 * _tmp178 * z2
    w[105] = -_tmp167 - _tmp172
    w[106] = 2 * _tmp179
    w[107] = 2 * _tmp174 + 2 * _tmp176 * z2 - 2 * _tmp177 * z2 + 2 * _tmp178
    w[108] = 2 * _tmp169 + 2 * _tmp170
    w[109] = -_tmp164 - _tmp173
    w[110] = -_tmp184
    w[111] = -2 * _tmp180 * z2 - 2 * _tmp181 * z2 - 2 * _tmp182 * z2 - 2 * _tmp187
    w[112] = (
        -_tmp107 * _tmp180
        - _tmp107 * _tmp181
        - _tmp107 * _tmp182
        - _tmp108 * _tmp185
        - _tmp188
        - _tmp189
        + 2 * b0y * nbc2x * z2
    )
    w[113] = 2 * _tmp192
    w[114] = -2 * _tmp191 * z2 - 2 * _tmp193 - 2 * _tmp194 + 2 * b0x * nbc2z * z2
    w[115] = _tmp183 + _tmp188
    w[116] = -2 * _tmp195
    w[117] = -2 * _tmp190 - 2 * _tmp191 - 2 * _tmp193 * z2 + 2 * b0z * nbc2y * z2
    w[118] = -2 * _tmp185 - 2 * _tmp186
    w[119] = _tmp180 + _tmp189
    wt[0] = -_tmp200 - _tmp203
    wt[1] = (
        -2 * _tmp197 * z1
        - 2 * _tmp199 * z1
        - 2 * _tmp205 * d_a0x
        - 2 * _tmp207 * d_nab1y
        + 2 * _tmp209 * d_a0y
        - 2 * _tmp212 * d_nab1x
        - 2 * _tmp4 * d_z1
    )
    wt[2] = (
        -_tmp197 * _tmp213
        - _tmp199 * _tmp213
        + _tmp214 * d_a0x
        + _tmp217 * d_nab1x
        + _tmp219 * d_nab1y
        - _tmp220 * (_tmp4 * z1 + _tmp7)
        + d_a0y * (_tmp215 * z1 + nab1y)
    )
    wt[3] = 2 * _tmp221 - 2 * _tmp222 + 2 * a0x * d_nab1z - 2 * d_a0z * nab1x
    wt[4] = (
        2 * _tmp14 * d_z1
        - 2 * _tmp205 * d_a0z
        + 2 * _tmp212 * d_nab1z
        - 2 * _tmp222 * z1
        - 2 * _tmp223
        - 2 * _tmp224
        + 2 * d_a0x * nab1z * z1
    )
    wt[5] = _tmp200 - _tmp201 - _tmp202
    wt[6] = 2 * _tmp223 - 2 * _tmp224 - 2 * a0y * d_nab1z + 2 * d_a0z * nab1y
    wt[7] = (
        -2 * _tmp17 * d_z1
        - 2 * _tmp207 * d_nab1z
        - 2 * _tmp209 * d_a0z
        - 2 * _tmp221
        - 2 * _tmp222
        - 2 * _tmp224 * z1
        + 2 * a0z * d_nab1y * z1
    )
    wt[8] = -2 * (a0x * d_nab1y + a0y * d_nab1x + d_a0x * nab1y + d_a0y * nab1x)
    wt[9] = -_tmp196 + _tmp197 - _tmp198 + _tmp199 + _tmp203
    wt[10] = _tmp229 + _tmp232
    wt[11] = (
        2 * _tmp205 * d_b0x
        - 2 * _tmp209 * d_b0y
        + 2 * _tmp22 * d_z1
        + 2 * _tmp226 * z1
        + 2 * _tmp228 * z1
        + 2 * _tmp234 * d_nab1y
        + 2 * _tmp237 * d_nab1x
    )
    wt[12] = (
        _tmp213 * b0z * d_nab1z
        + _tmp213 * d_b0z * nab1z
        - _tmp214 * d_b0x
        - _tmp239 * d_nab1x
        - _tmp241 * d_nab1y
        - d_b0y * (_tmp215 * z1 + nab1y)
        + 2 * d_z1 * (_tmp22 * z1 + _tmp25)
    )
    wt[13] = -2 * _tmp242 - 2 * b0x * d_nab1z + 2 * b0z * d_nab1x + 2 * d_b0z * nab1x
    wt[14] = (
        2 * _tmp205 * d_b0z
        - 2 * _tmp237 * d_nab1z
        - 2 * _tmp242 * z1
        + 2 * _tmp243
        + 2 * _tmp244
        + 2 * _tmp245 * z1
        - 2 * _tmp29 * d_z1
    )
    wt[15] = -_tmp229 + _tmp230 + _tmp231
    wt[16] = -2 * _tmp243 + 2 * _tmp244 + 2 * b0y * d_nab1z - 2 * d_b0z * nab1y
    wt[17] = (
        2 * _tmp209 * d_b0z
        + 2 * _tmp234 * d_nab1z
        + 2 * _tmp242
        - 2 * _tmp243 * z1
        + 2 * _tmp244 * z1
        + 2 * _tmp245
        + 2 * _tmp33 * d_z1
    )
    wt[18] = 2 * (b0x * d_nab1y + b0y * d_nab1x + d_b0x * nab1y + d_b0y * nab1x)
    wt[19] = _tmp225 - _tmp226 + _tmp227 - _tmp228 - _tmp232
    wt[20] = -_tmp250 - _tmp253
    wt[21] = (
        -2 * _tmp207 * d_nac1y
        - 2 * _tmp212 * d_nac1x
        - 2 * _tmp247 * z1
        - 2 * _tmp249 * z1
        - 2 * _tmp255 * d_a0x
        + 2 * _tmp257 * d_a0y
        - 2 * _tmp38 * d_z1
    )
    wt[22] = (
        -_tmp213 * _tmp247
        - _tmp213 * _tmp249
        + _tmp217 * d_nac1x
        + _tmp219 * d_nac1y
        - _tmp220 * (_tmp38 * z1 + _tmp41)
        + _tmp258 * d_a0x
        + d_a0y * (_tmp259 * z1 + nac1y)
    )
    wt[23] = 2 * _tmp260 - 2 * _tmp261 + 2 * a0x * d_nac1z - 2 * d_a0z * nac1x
    wt[24] = (
        2 * _tmp212 * d_nac1z
        - 2 * _tmp255 * d_a0z
        - 2 * _tmp261 * z1
        - 2 * _tmp262
        - 2 * _tmp263
        + 2 * _tmp46 * d_z1
        + 2 * d_a0x * nac1z * z1
    )
    wt[25] = _tmp250 - _tmp251 - _tmp252
    wt[26] = 2 * _tmp262 - 2 * _tmp263 - 2 * a0y * d_nac1z + 2 * d_a0z * nac1y
    wt[27] = (
        -2 * _tmp207 * d_nac1z
        - 2 * _tmp257 * d_a0z
        - 2 * _tmp260
        - 2 * _tmp261
        - 2 * _tmp263 * z1
        - 2 * _tmp49 * d_z1
        + 2 * a0z * d_nac1y * z1
    )
    wt[28] = -2 * (a0x * d_nac1y + a0y * d_nac1x + d_a0x * nac1y + d_a0y * nac1x)
    wt[29] = -_tmp246 + _tmp247 - _tmp248 + _tmp249 + _tmp253
    wt[30] = _tmp268 + _tmp271
    wt[31] = (
        2 * _tmp255 * d_c0x
        - 2 * _tmp257 * d_c0y
        + 2 * _tmp265 * z1
        + 2 * _tmp267 * z1
        + 2 * _tmp273 * d_nac1y
        + 2 * _tmp276 * d_nac1x
        + 2 * _tmp54 * d_z1
    )
    wt[32] = (
        _tmp213 * c0z * d_nac1z
        + _tmp213 * d_c0z * nac1z
        - _tmp258 * d_c0x
        - _tmp278 * d_nac1x
        - _tmp280 * d_nac1y
        - d_c0y * (_tmp259 * z1 + nac1y)
        + 2 * d_z1 * (_tmp54 * z1 + _tmp57)
    )
    wt[33] = -2 * _tmp281 - 2 * c0x * d_nac1z + 2 * c0z * d_nac1x + 2 * d_c0z * nac1x
    wt[34] = (
        2 * _tmp255 * d_c0z
        - 2 * _tmp276 * d_nac1z
        - 2 * _tmp281 * z1
        + 2 * _tmp282
        + 2 * _tmp283
        + 2 * _tmp284 * z1
        - 2 * _tmp61 * d_z1
    )
    wt[35] = -_tmp268 + _tmp269 + _tmp270
    wt[36] = -2 * _tmp282 + 2 * _tmp283 + 2 * c0y * d_nac1z - 2 * d_c0z * nac1y
    wt[37] = (
        2 * _tmp257 * d_c0z
        + 2 * _tmp273 * d_nac1z
        + 2 * _tmp281
        - 2 * _tmp282 * z1
        + 2 * _tmp283 * z1
        + 2 * _tmp284
        + 2 * _tmp65 * d_z1
    )
    wt[38] = 2 * (c0x * d_nac1y + c0y * d_nac1x + d_c0x * nac1y + d_c0y * nac1x)
    wt[39] = _tmp264 - _tmp265 + _tmp266 - _tmp267 - _tmp271
    wt[40] = _tmp289 + _tmp292
    wt[41] = (
        2 * _tmp273 * d_nbc1y
        + 2 * _tmp276 * d_nbc1x
        + 2 * _tmp286 * z1
        + 2 * _tmp288 * z1
        + 2 * _tmp294 * d_c0x
        - 2 * _tmp296 * d_c0y
        + 2 * _tmp70 * d_z1
    )
    wt[42] = (
        _tmp213 * c0z * d_nbc1z
        + _tmp213 * d_c0z * nbc1z
        - _tmp278 * d_nbc1x
        - _tmp280 * d_nbc1y
        - _tmp297 * d_c0x
        - d_c0y * (_tmp298 * z1 + nbc1y)
        + 2 * d_z1 * (_tmp70 * z1 + _tmp73)
    )
    wt[43] = -2 * _tmp299 - 2 * c0x * d_nbc1z + 2 * c0z * d_nbc1x + 2 * d_c0z * nbc1x
    wt[44] = (
        -2 * _tmp276 * d_nbc1z
        + 2 * _tmp294 * d_c0z
        - 2 * _tmp299 * z1
        + 2 * _tmp300
        + 2 * _tmp301
        + 2 * _tmp302 * z1
        - 2 * _tmp77 * d_z1
    )
    wt[45] = -_tmp289 + _tmp290 + _tmp291
    wt[46] = -2 * _tmp300 + 2 * _tmp301 + 2 * c0y * d_nbc1z - 2 * d_c0z * nbc1y
    wt[47] = (
        2 * _tmp273 * d_nbc1z
        + 2 * _tmp296 * d_c0z
        + 2 * _tmp299
        - 2 * _tmp300 * z1
        + 2 * _tmp301 * z1
        + 2 * _tmp302
        + 2 * _tmp81 * d_z1
    )
    wt[48] = 2 * (c0x * d_nbc1y + c0y * d_nbc1x + d_c0x * nbc1y + d_c0y * nbc1x)
    wt[49] = _tmp285 - _tmp286 + _tmp287 - _tmp288 - _tmp292
    wt[50] = -_tmp307 - _tmp310
    wt[51] = (
        -2 * _tmp234 * d_nbc1y
        - 2 * _tmp237 * d_nbc1x
        - 2 * _tmp294 * d_b0x
        + 2 * _tmp296 * d_b0y
        - 2 * _tmp304 * z1
        - 2 * _tmp306 * z1
        - 2 * _tmp86 * d_z1
    )
    wt[52] = (
        -_tmp213 * _tmp304
        - _tmp213 * _tmp306
        - _tmp220 * (_tmp86 * z1 + _tmp89)
        + _tmp239 * d_nbc1x
        + _tmp241 * d_nbc1y
        + _tmp297 * d_b0x
        + d_b0y * (_tmp298 * z1 + nbc1y)
    )
    wt[53] = 2 * _tmp311 - 2 * _tmp312 + 2 * b0x * d_nbc1z - 2 * d_b0z * nbc1x
    wt[54] = (
        2 * _tmp237 * d_nbc1z
        - 2 * _tmp294 * d_b0z
        - 2 * _tmp312 * z1
        - 2 * _tmp313
        - 2 * _tmp314
        + 2 * _tmp94 * d_z1
        + 2 * d_b0x * nbc1z * z1
    )
    wt[55] = _tmp307 - _tmp308 - _tmp309
    wt[56] = 2 * _tmp313 - 2 * _tmp314 - 2 * b0y * d_nbc1z + 2 * d_b0z * nbc1y
    wt[57] = (
        -2 * _tmp234 * d_nbc1z
        - 2 * _tmp296 * d_b0z
        - 2 * _tmp311
        - 2 * _tmp312
        - 2 * _tmp314 * z1
        - 2 * _tmp97 * d_z1
        + 2 * b0z * d_nbc1y * z1
    )
    wt[58] = -2 * (b0x * d_nbc1y + b0y * d_nbc1x + d_b0x * nbc1y + d_b0y * nbc1x)
    wt[59] = -_tmp303 + _tmp304 - _tmp305 + _tmp306 + _tmp310
    wt[60] = -_tmp319 - _tmp322
    wt[61] = (
        -2 * _tmp102 * d_z2
        - 2 * _tmp316 * z2
        - 2 * _tmp318 * z2
        - 2 * _tmp324 * d_a0x
        - 2 * _tmp326 * d_nab2y
        + 2 * _tmp328 * d_a0y
        - 2 * _tmp330 * d_nab2x
    )
    wt[62] = (
        -_tmp316 * _tmp331
        - _tmp318 * _tmp331
        + _tmp332 * d_a0x
        + _tmp334 * d_nab2x
        + _tmp335 * d_nab2y
        - _tmp336 * (_tmp102 * z2 + _tmp105)
        + d_a0y * (_tmp333 * z2 + nab2y)
    )
    wt[63] = 2 * _tmp337 - 2 * _tmp338 + 2 * a0x * d_nab2z - 2 * d_a0z * nab2x
    wt[64] = (
        2 * _tmp112 * d_z2
        - 2 * _tmp324 * d_a0z
        + 2 * _tmp330 * d_nab2z
        - 2 * _tmp338 * z2
        - 2 * _tmp339
        - 2 * _tmp340
        + 2 * d_a0x * nab2z * z2
    )
    wt[65] = _tmp319 - _tmp320 - _tmp321
    wt[66] = 2 * _tmp339 - 2 * _tmp340 - 2 * a0y * d_nab2z + 2 * d_a0z * nab2y
    wt[67] = (
        -2 * _tmp115 * d_z2
        - 2 * _tmp326 * d_nab2z
        - 2 * _tmp328 * d_a0z
        - 2 * _tmp337
        - 2 * _tmp338
        - 2 * _tmp340 * z2
        + 2 * a0z * d_nab2y * z2
    )
    wt[68] = -2 * (a0x * d_nab2y + a0y * d_nab2x + d_a0x * nab2y + d_a0y * nab2x)
    wt[69] = -_tmp315 + _tmp316 - _tmp317 + _tmp318 + _tmp322
    wt[70] = _tmp345 + _tmp348
    wt[71] = (
        2 * _tmp120 * d_z2
        + 2 * _tmp324 * d_b0x
        - 2 * _tmp328 * d_b0y
        + 2 * _tmp342 * z2
        + 2 * _tmp344 * z2
        + 2 * _tmp350 * d_nab2y
        + 2 * _tmp352 * d_nab2x
    )
    wt[72] = (
        _tmp331 * b0z * d_nab2z
        + _tmp331 * d_b0z * nab2z
        - _tmp332 * d_b0x
        - _tmp353 * d_nab2x
        - _tmp354 * d_nab2y
        - d_b0y * (_tmp333 * z2 + nab2y)
        + 2 * d_z2 * (_tmp120 * z2 + _tmp123)
    )
    wt[73] = -2 * _tmp355 - 2 * b0x * d_nab2z + 2 * b0z * d_nab2x + 2 * d_b0z * nab2x
    wt[74] = (
        -2 * _tmp127 * d_z2
        + 2 * _tmp324 * d_b0z
        - 2 * _tmp352 * d_nab2z
        - 2 * _tmp355 * z2
        + 2 * _tmp356
        + 2 * _tmp357
        + 2 * _tmp358 * z2
    )
    wt[75] = -_tmp345 + _tmp346 + _tmp347
    wt[76] = -2 * _tmp356 + 2 * _tmp357 + 2 * b0y * d_nab2z - 2 * d_b0z * nab2y
    wt[77] = (
        2 * _tmp131 * d_z2
        + 2 * _tmp328 * d_b0z
        + 2 * _tmp350 * d_nab2z
        + 2 * _tmp355
        - 2 * _tmp356 * z2
        + 2 * _tmp357 * z2
        + 2 * _tmp358
    )
    wt[78] = 2 * (b0x * d_nab2y + b0y * d_nab2x + d_b0x * nab2y + d_b0y * nab2x)
    wt[79] = _tmp341 - _tmp342 + _tmp343 - _tmp344 - _tmp348
    wt[80] = -_tmp363 - _tmp366
    wt[81] = (
        -2 * _tmp136 * d_z2
        - 2 * _tmp326 * d_nac2y
        - 2 * _tmp330 * d_nac2x
        - 2 * _tmp360 * z2
        - 2 * _tmp362 * z2
        - 2 * _tmp368 * d_a0x
        + 2 * _tmp370 * d_a0y
    )
    wt[82] = (
        -_tmp331 * _tmp360
        - _tmp331 * _tmp362
        + _tmp334 * d_nac2x
        + _tmp335 * d_nac2y
        - _tmp336 * (_tmp136 * z2 + _tmp139)
        + _tmp371 * d_a0x
        + d_a0y * (_tmp372 * z2 + nac2y)
    )
    wt[83] = 2 * _tmp373 - 2 * _tmp374 + 2 * a0x * d_nac2z - 2 * d_a0z * nac2x
    wt[84] = (
        2 * _tmp144 * d_z2
        + 2 * _tmp330 * d_nac2z
        - 2 * _tmp368 * d_a0z
        - 2 * _tmp374 * z2
        - 2 * _tmp375
        - 2 * _tmp376
        + 2 * d_a0x * nac2z * z2
    )
    wt[85] = _tmp363 - _tmp364 - _tmp365
    wt[86] = 2 * _tmp375 - 2 * _tmp376 - 2 * a0y * d_nac2z + 2 * d_a0z * nac2y
    wt[87] = (
        -2 * _tmp147 * d_z2
        - 2 * _tmp326 * d_nac2z
        - 2 * _tmp370 * d_a0z
        - 2 * _tmp373
        - 2 * _tmp374
        - 2 * _tmp376 * z2
        + 2 * a0z * d_nac2y * z2
    )
    wt[88] = -2 * (a0x * d_nac2y + a0y * d_nac2x + d_a0x * nac2y + d_a0y * nac2x)
    wt[89] = -_tmp359 + _tmp360 - _tmp361 + _tmp362 + _tmp366
    wt[90] = _tmp381 + _tmp384
    wt[91] = (
        2 * _tmp152 * d_z2
        + 2 * _tmp368 * d_c0x
        - 2 * _tmp370 * d_c0y
        + 2 * _tmp378 * z2
        + 2 * _tmp380 * z2
        + 2 * _tmp386 * d_nac2y
        + 2 * _tmp388 * d_nac2x
    )
    wt[92] = (
        _tmp331 * c0z * d_nac2z
        + _tmp331 * d_c0z * nac2z
        - _tmp371 * d_c0x
        - _tmp389 * d_nac2x
        - _tmp390 * d_nac2y
        - d_c0y * (_tmp372 * z2 + nac2y)
        + 2 * d_z2 * (_tmp152 * z2 + _tmp155)
    )
    wt[93] = -2 * _tmp391 - 2 * c0x * d_nac2z + 2 * c0z * d_nac2x + 2 * d_c0z * nac2x
    wt[94] = (
        -2 * _tmp159 * d_z2
        + 2 * _tmp368 * d_c0z
        - 2 * _tmp388 * d_nac2z
        - 2 * _tmp391 * z2
        + 2 * _tmp392
        + 2 * _tmp393
        + 2 * _tmp394 * z2
    )
    wt[95] = -_tmp381 + _tmp382 + _tmp383
    wt[96] = -2 * _tmp392 + 2 * _tmp393 + 2 * c0y * d_nac2z - 2 * d_c0z * nac2y
    wt[97] = (
        2 * _tmp163 * d_z2
        + 2 * _tmp370 * d_c0z
        + 2 * _tmp386 * d_nac2z
        + 2 * _tmp391
        - 2 * _tmp392 * z2
        + 2 * _tmp393 * z2
        + 2 * _tmp394
    )
    wt[98] = 2 * (c0x * d_nac2y + c0y * d_nac2x + d_c0x * nac2y + d_c0y * nac2x)
    wt[99] = _tmp377 - _tmp378 + _tmp379 - _tmp380 - _tmp384
    wt[100] = _tmp399 + _tmp402
    wt[101] = (
        2 * _tmp168 * d_z2
        + 2 * _tmp386 * d_nbc2y
        + 2 * _tmp388 * d_nbc2x
        + 2 * _tmp396 * z2
        + 2 * _tmp398 * z2
        + 2 * _tmp404 * d_c0x
        - 2 * _tmp406 * d_c0y
    )
    wt[102] = (
        _tmp331 * c0z * d_nbc2z
        + _tmp331 * d_c0z * nbc2z
        - _tmp389 * d_nbc2x
        - _tmp390 * d_nbc2y
        - _tmp407 * d_c0x
        - d_c0y * (_tmp408 * z2 + nbc2y)
        + 2 * d_z2 * (_tmp168 * z2 + _tmp171)
    )
    wt[103] = -2 * _tmp409 - 2 * c0x * d_nbc2z + 2 * c0z * d_nbc2x + 2 * d_c0z * nbc2x
    wt[104] = (
        -2 * _tmp175 * d_z2
        - 2 * _tmp388 * d_nbc2z
        + 2 * _tmp404 * d_c0z
        - 2 * _tmp409 * z2
        + 2 * _tmp410
        + 2 * _tmp411
        + 2 * _tmp412 * z2
    )
    wt[105] = -_tmp399 + _tmp400 + _tmp401
    wt[106] = -2 * _tmp410 + 2 * _tmp411 + 2 * c0y * d_nbc2z - 2 * d_c0z * nbc2y
    wt[107] = (
        2 * _tmp179 * d_z2
        + 2 * _tmp386 * d_nbc2z
        + 2 * _tmp406 * d_c0z
        + 2 * _tmp409
        - 2 * _tmp410 * z2
        + 2 * _tmp411 * z2
        + 2 * _tmp412
    )
    wt[108] = 2 * (c0x * d_nbc2y + c0y * d_nbc2x + d_c0x * nbc2y + d_c0y * nbc2x)
    wt[109] = _tmp395 - _tmp396 + _tmp397 - _tmp398 - _tmp402
    wt[110] = -_tmp417 - _tmp420
    wt[111] = (
        -2 * _tmp184 * d_z2
        - 2 * _tmp350 * d_nbc2y
        - 2 * _tmp352 * d_nbc2x
        - 2 * _tmp404 * d_b0x
        + 2 * _tmp406 * d_b0y
        - 2 * _tmp414 * z2
        - 2 * _tmp416 * z2
    )
    wt[112] = (
        -_tmp331 * _tmp414
        - _tmp331 * _tmp416
        - _tmp336 * (_tmp184 * z2 + _tmp187)
        + _tmp353 * d_nbc2x
        + _tmp354 * d_nbc2y
        + _tmp407 * d_b0x
        + d_b0y * (_tmp408 * z2 + nbc2y)
    )
    wt[113] = 2 * _tmp421 - 2 * _tmp422 + 2 * b0x * d_nbc2z - 2 * d_b0z * nbc2x
    wt[114] = (
        2 * _tmp192 * d_z2
        + 2 * _tmp352 * d_nbc2z
        - 2 * _tmp404 * d_b0z
        - 2 * _tmp422 * z2
        - 2 * _tmp423
        - 2 * _tmp424
        + 2 * d_b0x * nbc2z * z2
    )
    wt[115] = _tmp417 - _tmp418 - _tmp419
    wt[116] = 2 * _tmp423 - 2 * _tmp424 - 2 * b0y * d_nbc2z + 2 * d_b0z * nbc2y
    wt[117] = (
        -2 * _tmp195 * d_z2
        - 2 * _tmp350 * d_nbc2z
        - 2 * _tmp406 * d_b0z
        - 2 * _tmp421
        - 2 * _tmp422
        - 2 * _tmp424 * z2
        + 2 * b0z * d_nbc2y * z2
    )
    wt[118] = -2 * (b0x * d_nbc2y + b0y * d_nbc2x + d_b0x * nbc2y + d_b0y * nbc2x)
    wt[119] = -_tmp413 + _tmp414 - _tmp415 + _tmp416 + _tmp420


@numba.njit(**_JIT)
def coefficient_rates(q: np.ndarray, dq: np.ndarray, wt: np.ndarray) -> None:
    """dW/dt = W_q . dq alone (``coefficients_t`` without W): a tracker needs it only where it
    keeps a tangent.

    Outputs written in place (every entry): wt.
    """
    a0x = q[0]
    a0y = q[1]
    a0z = q[2]
    b0x = q[3]
    b0y = q[4]
    b0z = q[5]
    c0x = q[6]
    c0y = q[7]
    c0z = q[8]
    nab1x = q[9]
    nab1y = q[10]
    nab1z = q[11]
    nac1x = q[12]
    nac1y = q[13]
    nac1z = q[14]
    nbc1x = q[15]
    nbc1y = q[16]
    nbc1z = q[17]
    nab2x = q[18]
    nab2y = q[19]
    nab2z = q[20]
    nac2x = q[21]
    nac2y = q[22]
    nac2z = q[23]
    nbc2x = q[24]
    nbc2y = q[25]
    nbc2z = q[26]
    z1 = q[27]
    z2 = q[28]
    d_a0x = dq[0]
    d_a0y = dq[1]
    d_a0z = dq[2]
    d_b0x = dq[3]
    d_b0y = dq[4]
    d_b0z = dq[5]
    d_c0x = dq[6]
    d_c0y = dq[7]
    d_c0z = dq[8]
    d_nab1x = dq[9]
    d_nab1y = dq[10]
    d_nab1z = dq[11]
    d_nac1x = dq[12]
    d_nac1y = dq[13]
    d_nac1z = dq[14]
    d_nbc1x = dq[15]
    d_nbc1y = dq[16]
    d_nbc1z = dq[17]
    d_nab2x = dq[18]
    d_nab2y = dq[19]
    d_nab2z = dq[20]
    d_nac2x = dq[21]
    d_nac2y = dq[22]
    d_nac2z = dq[23]
    d_nbc2x = dq[24]
    d_nbc2y = dq[25]
    d_nbc2z = dq[26]
    d_z1 = dq[27]
    d_z2 = dq[28]
    _tmp0 = a0x * d_nab1x
    _tmp1 = a0z * d_nab1z
    _tmp2 = d_a0x * nab1x
    _tmp3 = d_a0z * nab1z
    _tmp4 = _tmp0 + _tmp1 + _tmp2 + _tmp3
    _tmp5 = a0y * d_nab1y
    _tmp6 = d_a0y * nab1y
    _tmp7 = _tmp5 + _tmp6
    _tmp8 = nab1x * z1
    _tmp9 = _tmp8 + nab1y
    _tmp10 = a0y * z1
    _tmp11 = _tmp10 + a0x
    _tmp12 = -nab1y * z1
    _tmp13 = _tmp12 + nab1x
    _tmp14 = -a0y
    _tmp15 = a0x * z1
    _tmp16 = _tmp14 + _tmp15
    _tmp17 = a0x * nab1x + a0y * nab1y + a0z * nab1z
    _tmp18 = z1 * z1 + 1
    _tmp19 = nab1x - z1 * (_tmp8 + 2 * nab1y)
    _tmp20 = _tmp12 + 2 * nab1x
    _tmp21 = -2 * a0y
    _tmp22 = a0x - z1 * (_tmp15 + _tmp21)
    _tmp23 = 2 * a0x
    _tmp24 = a0y - z1 * (_tmp10 + _tmp23)
    _tmp25 = 2 * d_z1
    _tmp26 = d_a0x * nab1z
    _tmp27 = a0z * d_nab1x
    _tmp28 = a0z * d_nab1y
    _tmp29 = d_a0y * nab1z
    _tmp30 = b0x * d_nab1x
    _tmp31 = b0z * d_nab1z
    _tmp32 = d_b0x * nab1x
    _tmp33 = d_b0z * nab1z
    _tmp34 = _tmp30 + _tmp31 + _tmp32 + _tmp33
    _tmp35 = b0y * d_nab1y
    _tmp36 = d_b0y * nab1y
    _tmp37 = _tmp35 + _tmp36
    _tmp38 = b0y * z1
    _tmp39 = _tmp38 + b0x
    _tmp40 = -b0y
    _tmp41 = b0x * z1
    _tmp42 = _tmp40 + _tmp41
    _tmp43 = b0x * nab1x + b0y * nab1y + b0z * nab1z
    _tmp44 = -2 * b0y
    _tmp45 = b0x - z1 * (_tmp41 + _tmp44)
    _tmp46 = 2 * b0x
    _tmp47 = b0y - z1 * (_tmp38 + _tmp46)
    _tmp48 = d_b0x * nab1z
    _tmp49 = b0z * d_nab1y
    _tmp50 = d_b0y * nab1z
    _tmp51 = b0z * d_nab1x
    _tmp52 = a0x * d_nac1x
    _tmp53 = a0z * d_nac1z
    _tmp54 = d_a0x * nac1x
    _tmp55 = d_a0z * nac1z
    _tmp56 = _tmp52 + _tmp53 + _tmp54 + _tmp55
    _tmp57 = a0y * d_nac1y
    _tmp58 = d_a0y * nac1y
    _tmp59 = _tmp57 + _tmp58
    _tmp60 = nac1x * z1
    _tmp61 = _tmp60 + nac1y
    _tmp62 = -nac1y * z1
    _tmp63 = _tmp62 + nac1x
    _tmp64 = a0x * nac1x + a0y * nac1y + a0z * nac1z
    _tmp65 = nac1x - z1 * (_tmp60 + 2 * nac1y)
    _tmp66 = _tmp62 + 2 * nac1x
    _tmp67 = d_a0x * nac1z
    _tmp68 = a0z * d_nac1x
    _tmp69 = a0z * d_nac1y
    _tmp70 = d_a0y * nac1z
    _tmp71 = c0x * d_nac1x
    _tmp72 = c0z * d_nac1z
    _tmp73 = d_c0x * nac1x
    _tmp74 = d_c0z * nac1z
    _tmp75 = _tmp71 + _tmp72 + _tmp73 + _tmp74
    _tmp76 = c0y * d_nac1y
    _tmp77 = d_c0y * nac1y
    _tmp78 = _tmp76 + _tmp77
    _tmp79 = c0y * z1
    _tmp80 = _tmp79 + c0x
    _tmp81 = -c0y
    _tmp82 = c0x * z1
    _tmp83 = _tmp81 + _tmp82
    _tmp84 = c0x * nac1x + c0y * nac1y + c0z * nac1z
    _tmp85 = -2 * c0y
    _tmp86 = c0x - z1 * (_tmp82 + _tmp85)
    _tmp87 = 2 * c0x
    _tmp88 = c0y - z1 * (_tmp79 + _tmp87)
    _tmp89 = d_c0x * nac1z
    _tmp90 = c0z * d_nac1y
    _tmp91 = d_c0y * nac1z
    _tmp92 = c0z * d_nac1x
    _tmp93 = c0x * d_nbc1x
    _tmp94 = c0z * d_nbc1z
    _tmp95 = d_c0x * nbc1x
    _tmp96 = d_c0z * nbc1z
    _tmp97 = _tmp93 + _tmp94 + _tmp95 + _tmp96
    _tmp98 = c0y * d_nbc1y
    _tmp99 = d_c0y * nbc1y
    _tmp100 = _tmp98 + _tmp99
    _tmp101 = nbc1x * z1
    _tmp102 = _tmp101 + nbc1y
    _tmp103 = -nbc1y * z1
    _tmp104 = _tmp103 + nbc1x
    _tmp105 = c0x * nbc1x + c0y * nbc1y + c0z * nbc1z
    _tmp106 = nbc1x - z1 * (_tmp101 + 2 * nbc1y)
    _tmp107 = _tmp103 + 2 * nbc1x
    _tmp108 = d_c0x * nbc1z
    _tmp109 = c0z * d_nbc1y
    _tmp110 = d_c0y * nbc1z
    _tmp111 = c0z * d_nbc1x
    _tmp112 = b0x * d_nbc1x
    _tmp113 = b0z * d_nbc1z
    _tmp114 = d_b0x * nbc1x
    _tmp115 = d_b0z * nbc1z
    _tmp116 = _tmp112 + _tmp113 + _tmp114 + _tmp115
    _tmp117 = b0y * d_nbc1y
    _tmp118 = d_b0y * nbc1y
    _tmp119 = _tmp117 + _tmp118
    _tmp120 = b0x * nbc1x + b0y * nbc1y + b0z * nbc1z
    _tmp121 = d_b0x * nbc1z
    _tmp122 = b0z * d_nbc1x
    _tmp123 = b0z * d_nbc1y
    _tmp124 = d_b0y * nbc1z
    _tmp125 = a0x * d_nab2x
    _tmp126 = a0z * d_nab2z
    _tmp127 = d_a0x * nab2x
    _tmp128 = d_a0z * nab2z
    _tmp129 = _tmp125 + _tmp126 + _tmp127 + _tmp128
    _tmp130 = a0y * d_nab2y
    _tmp131 = d_a0y * nab2y
    _tmp132 = _tmp130 + _tmp131
    _tmp133 = nab2x * z2
    _tmp134 = _tmp133 + nab2y
    _tmp135 = a0y * z2
    _tmp136 = _tmp135 + a0x
    _tmp137 = -nab2y * z2
    _tmp138 = _tmp137 + nab2x
    _tmp139 = a0x * z2
    _tmp140 = _tmp139 + _tmp14
    _tmp141 = a0x * nab2x + a0y * nab2y + a0z * nab2z
    _tmp142 = z2 * z2 + 1
    _tmp143 = nab2x - z2 * (_tmp133 + 2 * nab2y)
    _tmp144 = _tmp137 + 2 * nab2x
    _tmp145 = a0x - z2 * (_tmp139 + _tmp21)
    _tmp146 = a0y - z2 * (_tmp135 + _tmp23)
    _tmp147 = 2 * d_z2
    _tmp148 = d_a0x * nab2z
    _tmp149 = a0z * d_nab2x
    _tmp150 = a0z * d_nab2y
    _tmp151 = d_a0y * nab2z
    _tmp152 = b0x * d_nab2x
    _tmp153 = b0z * d_nab2z
    _tmp154 = d_b0x * nab2x
    _tmp155 = d_b0z * nab2z
    _tmp156 = _tmp152 + _tmp153 + _tmp154 + _tmp155
    _tmp157 = b0y * d_nab2y
    _tmp158 = d_b0y * nab2y
    _tmp159 = _tmp157 + _tmp158
    _tmp160 = b0y * z2
    _tmp161 = _tmp160 + b0x
    _tmp162 = b0x * z2
    _tmp163 = _tmp162 + _tmp40
    _tmp164 = b0x * nab2x + b0y * nab2y + b0z * nab2z
    _tmp165 = b0x - z2 * (_tmp162 + _tmp44)
    _tmp166 = b0y - z2 * (_tmp160 + _tmp46)
    _tmp167 = d_b0x * nab2z
    _tmp168 = b0z * d_nab2y
    _tmp169 = d_b0y * nab2z
    _tmp170 = b0z * d_nab2x
    _tmp171 = a0x * d_nac2x
    _tmp172 = a0z * d_nac2z
    _tmp173 = d_a0x * nac2x
    _tmp174 = d_a0z * nac2z
    _tmp175 = _tmp171 + _tmp172 + _tmp173 + _tmp174
    _tmp176 = a0y * d_nac2y
    _tmp177 = d_a0y * nac2y
    _tmp178 = _tmp176 + _tmp177
    _tmp179 = nac2x * z2
    _tmp180 = _tmp179 + nac2y
    _tmp181 = -nac2y * z2
    _tmp182 = _tmp181 + nac2x
    _tmp183 = a0x * nac2x + a0y * nac2y + a0z * nac2z
    _tmp184 = nac2x - z2 * (_tmp179 + 2 * nac2y)
    _tmp185 = _tmp181 + 2 * nac2x
    _tmp186 = d_a0x * nac2z
    _tmp187 = a0z * d_nac2x
    _tmp188 = a0z * d_nac2y
    _tmp189 = d_a0y * nac2z
    _tmp190 = c0x * d_nac2x
    _tmp191 = c0z * d_nac2z
    _tmp192 = d_c0x * nac2x
    _tmp193 = d_c0z * nac2z
    _tmp194 = _tmp190 + _tmp191 + _tmp192 + _tmp193
    _tmp195 = c0y * d_nac2y
    _tmp196 = d_c0y * nac2y
    _tmp197 = _tmp195 + _tmp196
    _tmp198 = c0y * z2
    _tmp199 = _tmp198 + c0x
    _tmp200 = c0x * z2
    _tmp201 = _tmp200 + _tmp81
    _tmp202 = c0x * nac2x + c0y * nac2y + c0z * nac2z
    _tmp203 = c0x - z2 * (_tmp200 + _tmp85)
    _tmp204 = c0y - z2 * (_tmp198 + _tmp87)
    _tmp205 = d_c0x * nac2z
    _tmp206 = c0z * d_nac2y
    _tmp207 = d_c0y * nac2z
    _tmp208 = c0z * d_nac2x
    _tmp209 = c0x * d_nbc2x
    _tmp210 = c0z * d_nbc2z
    _tmp211 = d_c0x * nbc2x
    _tmp212 = d_c0z * nbc2z
    _tmp213 = _tmp209 + _tmp210 + _tmp211 + _tmp212
    _tmp214 = c0y * d_nbc2y
    _tmp215 = d_c0y * nbc2y
    _tmp216 = _tmp214 + _tmp215
    _tmp217 = nbc2x * z2
    _tmp218 = _tmp217 + nbc2y
    _tmp219 = -nbc2y * z2
    _tmp220 = _tmp219 + nbc2x
    _tmp221 = c0x * nbc2x + c0y * nbc2y + c0z * nbc2z
    _tmp222 = nbc2x - z2 * (_tmp217 + 2 * nbc2y)
    _tmp223 = _tmp219 + 2 * nbc2x
    _tmp224 = d_c0x * nbc2z
    _tmp225 = c0z * d_nbc2y
    _tmp226 = d_c0y * nbc2z
    _tmp227 = c0z * d_nbc2x
    _tmp228 = b0x * d_nbc2x
    _tmp229 = b0z * d_nbc2z
    _tmp230 = d_b0x * nbc2x
    _tmp231 = d_b0z * nbc2z
    _tmp232 = _tmp228 + _tmp229 + _tmp230 + _tmp231
    _tmp233 = b0y * d_nbc2y
    _tmp234 = d_b0y * nbc2y
    _tmp235 = _tmp233 + _tmp234
    _tmp236 = b0x * nbc2x + b0y * nbc2y + b0z * nbc2z
    _tmp237 = d_b0x * nbc2z
    _tmp238 = b0z * d_nbc2x
    _tmp239 = b0z * d_nbc2y
    _tmp240 = d_b0y * nbc2z
    wt[0] = -_tmp4 - _tmp7
    wt[1] = (
        -2 * _tmp1 * z1
        - 2 * _tmp11 * d_nab1y
        + 2 * _tmp13 * d_a0y
        - 2 * _tmp16 * d_nab1x
        - 2 * _tmp17 * d_z1
        - 2 * _tmp3 * z1
        - 2 * _tmp9 * d_a0x
    )
    wt[2] = (
        -_tmp1 * _tmp18
        - _tmp18 * _tmp3
        + _tmp19 * d_a0x
        + _tmp22 * d_nab1x
        + _tmp24 * d_nab1y
        - _tmp25 * (_tmp17 * z1 + a0x * nab1y - a0y * nab1x)
        + d_a0y * (_tmp20 * z1 + nab1y)
    )
    wt[3] = 2 * _tmp26 - 2 * _tmp27 + 2 * a0x * d_nab1z - 2 * d_a0z * nab1x
    wt[4] = (
        2 * _tmp16 * d_nab1z
        - 2 * _tmp27 * z1
        - 2 * _tmp28
        - 2 * _tmp29
        - 2 * _tmp9 * d_a0z
        + 2 * d_a0x * nab1z * z1
        + 2 * d_z1 * (a0x * nab1z - a0z * nab1x)
    )
    wt[5] = _tmp4 - _tmp5 - _tmp6
    wt[6] = 2 * _tmp28 - 2 * _tmp29 - 2 * a0y * d_nab1z + 2 * d_a0z * nab1y
    wt[7] = (
        -2 * _tmp11 * d_nab1z
        - 2 * _tmp13 * d_a0z
        - 2 * _tmp26
        - 2 * _tmp27
        - 2 * _tmp29 * z1
        + 2 * a0z * d_nab1y * z1
        - 2 * d_z1 * (a0y * nab1z - a0z * nab1y)
    )
    wt[8] = -2 * (a0x * d_nab1y + a0y * d_nab1x + d_a0x * nab1y + d_a0y * nab1x)
    wt[9] = -_tmp0 + _tmp1 - _tmp2 + _tmp3 + _tmp7
    wt[10] = _tmp34 + _tmp37
    wt[11] = (
        -2 * _tmp13 * d_b0y
        + 2 * _tmp31 * z1
        + 2 * _tmp33 * z1
        + 2 * _tmp39 * d_nab1y
        + 2 * _tmp42 * d_nab1x
        + 2 * _tmp43 * d_z1
        + 2 * _tmp9 * d_b0x
    )
    wt[12] = (
        _tmp18 * b0z * d_nab1z
        + _tmp18 * d_b0z * nab1z
        - _tmp19 * d_b0x
        - _tmp45 * d_nab1x
        - _tmp47 * d_nab1y
        - d_b0y * (_tmp20 * z1 + nab1y)
        + 2 * d_z1 * (_tmp43 * z1 + b0x * nab1y - b0y * nab1x)
    )
    wt[13] = -2 * _tmp48 - 2 * b0x * d_nab1z + 2 * b0z * d_nab1x + 2 * d_b0z * nab1x
    wt[14] = (
        -2 * _tmp42 * d_nab1z
        - 2 * _tmp48 * z1
        + 2 * _tmp49
        + 2 * _tmp50
        + 2 * _tmp51 * z1
        + 2 * _tmp9 * d_b0z
        - 2 * d_z1 * (b0x * nab1z - b0z * nab1x)
    )
    wt[15] = -_tmp34 + _tmp35 + _tmp36
    wt[16] = -2 * _tmp49 + 2 * _tmp50 + 2 * b0y * d_nab1z - 2 * d_b0z * nab1y
    wt[17] = (
        2 * _tmp13 * d_b0z
        + 2 * _tmp39 * d_nab1z
        + 2 * _tmp48
        - 2 * _tmp49 * z1
        + 2 * _tmp50 * z1
        + 2 * _tmp51
        + 2 * d_z1 * (b0y * nab1z - b0z * nab1y)
    )
    wt[18] = 2 * (b0x * d_nab1y + b0y * d_nab1x + d_b0x * nab1y + d_b0y * nab1x)
    wt[19] = _tmp30 - _tmp31 + _tmp32 - _tmp33 - _tmp37
    wt[20] = -_tmp56 - _tmp59
    wt[21] = (
        -2 * _tmp11 * d_nac1y
        - 2 * _tmp16 * d_nac1x
        - 2 * _tmp53 * z1
        - 2 * _tmp55 * z1
        - 2 * _tmp61 * d_a0x
        + 2 * _tmp63 * d_a0y
        - 2 * _tmp64 * d_z1
    )
    wt[22] = (
        -_tmp18 * _tmp53
        - _tmp18 * _tmp55
        + _tmp22 * d_nac1x
        + _tmp24 * d_nac1y
        - _tmp25 * (_tmp64 * z1 + a0x * nac1y - a0y * nac1x)
        + _tmp65 * d_a0x
        + d_a0y * (_tmp66 * z1 + nac1y)
    )
    wt[23] = 2 * _tmp67 - 2 * _tmp68 + 2 * a0x * d_nac1z - 2 * d_a0z * nac1x
    wt[24] = (
        2 * _tmp16 * d_nac1z
        - 2 * _tmp61 * d_a0z
        - 2 * _tmp68 * z1
        - 2 * _tmp69
        - 2 * _tmp70
        + 2 * d_a0x * nac1z * z1
        + 2 * d_z1 * (a0x * nac1z - a0z * nac1x)
    )
    wt[25] = _tmp56 - _tmp57 - _tmp58
    wt[26] = 2 * _tmp69 - 2 * _tmp70 - 2 * a0y * d_nac1z + 2 * d_a0z * nac1y
    wt[27] = (
        -2 * _tmp11 * d_nac1z
        - 2 * _tmp63 * d_a0z
        - 2 * _tmp67
        - 2 * _tmp68
        - 2 * _tmp70 * z1
        + 2 * a0z * d_nac1y * z1
        - 2 * d_z1 * (a0y * nac1z - a0z * nac1y)
    )
    wt[28] = -2 * (a0x * d_nac1y + a0y * d_nac1x + d_a0x * nac1y + d_a0y * nac1x)
    wt[29] = -_tmp52 + _tmp53 - _tmp54 + _tmp55 + _tmp59
    wt[30] = _tmp75 + _tmp78
    wt[31] = (
        2 * _tmp61 * d_c0x
        - 2 * _tmp63 * d_c0y
        + 2 * _tmp72 * z1
        + 2 * _tmp74 * z1
        + 2 * _tmp80 * d_nac1y
        + 2 * _tmp83 * d_nac1x
        + 2 * _tmp84 * d_z1
    )
    wt[32] = (
        _tmp18 * c0z * d_nac1z
        + _tmp18 * d_c0z * nac1z
        - _tmp65 * d_c0x
        - _tmp86 * d_nac1x
        - _tmp88 * d_nac1y
        - d_c0y * (_tmp66 * z1 + nac1y)
        + 2 * d_z1 * (_tmp84 * z1 + c0x * nac1y - c0y * nac1x)
    )
    wt[33] = -2 * _tmp89 - 2 * c0x * d_nac1z + 2 * c0z * d_nac1x + 2 * d_c0z * nac1x
    wt[34] = (
        2 * _tmp61 * d_c0z
        - 2 * _tmp83 * d_nac1z
        - 2 * _tmp89 * z1
        + 2 * _tmp90
        + 2 * _tmp91
        + 2 * _tmp92 * z1
        - 2 * d_z1 * (c0x * nac1z - c0z * nac1x)
    )
    wt[35] = -_tmp75 + _tmp76 + _tmp77
    wt[36] = -2 * _tmp90 + 2 * _tmp91 + 2 * c0y * d_nac1z - 2 * d_c0z * nac1y
    wt[37] = (
        2 * _tmp63 * d_c0z
        + 2 * _tmp80 * d_nac1z
        + 2 * _tmp89
        - 2 * _tmp90 * z1
        + 2 * _tmp91 * z1
        + 2 * _tmp92
        + 2 * d_z1 * (c0y * nac1z - c0z * nac1y)
    )
    wt[38] = 2 * (c0x * d_nac1y + c0y * d_nac1x + d_c0x * nac1y + d_c0y * nac1x)
    wt[39] = _tmp71 - _tmp72 + _tmp73 - _tmp74 - _tmp78
    wt[40] = _tmp100 + _tmp97
    wt[41] = (
        2 * _tmp102 * d_c0x
        - 2 * _tmp104 * d_c0y
        + 2 * _tmp105 * d_z1
        + 2 * _tmp80 * d_nbc1y
        + 2 * _tmp83 * d_nbc1x
        + 2 * _tmp94 * z1
        + 2 * _tmp96 * z1
    )
    wt[42] = (
        -_tmp106 * d_c0x
        + _tmp18 * c0z * d_nbc1z
        + _tmp18 * d_c0z * nbc1z
        - _tmp86 * d_nbc1x
        - _tmp88 * d_nbc1y
        - d_c0y * (_tmp107 * z1 + nbc1y)
        + 2 * d_z1 * (_tmp105 * z1 + c0x * nbc1y - c0y * nbc1x)
    )
    wt[43] = -2 * _tmp108 - 2 * c0x * d_nbc1z + 2 * c0z * d_nbc1x + 2 * d_c0z * nbc1x
    wt[44] = (
        2 * _tmp102 * d_c0z
        - 2 * _tmp108 * z1
        + 2 * _tmp109
        + 2 * _tmp110
        + 2 * _tmp111 * z1
        - 2 * _tmp83 * d_nbc1z
        - 2 * d_z1 * (c0x * nbc1z - c0z * nbc1x)
    )
    wt[45] = -_tmp97 + _tmp98 + _tmp99
    wt[46] = -2 * _tmp109 + 2 * _tmp110 + 2 * c0y * d_nbc1z - 2 * d_c0z * nbc1y
    wt[47] = (
        2 * _tmp104 * d_c0z
        + 2 * _tmp108
        - 2 * _tmp109 * z1
        + 2 * _tmp110 * z1
        + 2 * _tmp111
        + 2 * _tmp80 * d_nbc1z
        + 2 * d_z1 * (c0y * nbc1z - c0z * nbc1y)
    )
    wt[48] = 2 * (c0x * d_nbc1y + c0y * d_nbc1x + d_c0x * nbc1y + d_c0y * nbc1x)
    wt[49] = -_tmp100 + _tmp93 - _tmp94 + _tmp95 - _tmp96
    wt[50] = -_tmp116 - _tmp119
    wt[51] = (
        -2 * _tmp102 * d_b0x
        + 2 * _tmp104 * d_b0y
        - 2 * _tmp113 * z1
        - 2 * _tmp115 * z1
        - 2 * _tmp120 * d_z1
        - 2 * _tmp39 * d_nbc1y
        - 2 * _tmp42 * d_nbc1x
    )
    wt[52] = (
        _tmp106 * d_b0x
        - _tmp113 * _tmp18
        - _tmp115 * _tmp18
        - _tmp25 * (_tmp120 * z1 + b0x * nbc1y - b0y * nbc1x)
        + _tmp45 * d_nbc1x
        + _tmp47 * d_nbc1y
        + d_b0y * (_tmp107 * z1 + nbc1y)
    )
    wt[53] = 2 * _tmp121 - 2 * _tmp122 + 2 * b0x * d_nbc1z - 2 * d_b0z * nbc1x
    wt[54] = (
        -2 * _tmp102 * d_b0z
        - 2 * _tmp122 * z1
        - 2 * _tmp123
        - 2 * _tmp124
        + 2 * _tmp42 * d_nbc1z
        + 2 * d_b0x * nbc1z * z1
        + 2 * d_z1 * (b0x * nbc1z - b0z * nbc1x)
    )
    wt[55] = _tmp116 - _tmp117 - _tmp118
    wt[56] = 2 * _tmp123 - 2 * _tmp124 - 2 * b0y * d_nbc1z + 2 * d_b0z * nbc1y
    wt[57] = (
        -2 * _tmp104 * d_b0z
        - 2 * _tmp121
        - 2 * _tmp122
        - 2 * _tmp124 * z1
        - 2 * _tmp39 * d_nbc1z
        + 2 * b0z * d_nbc1y * z1
        - 2 * d_z1 * (b0y * nbc1z - b0z * nbc1y)
    )
    wt[58] = -2 * (b0x * d_nbc1y + b0y * d_nbc1x + d_b0x * nbc1y + d_b0y * nbc1x)
    wt[59] = -_tmp112 + _tmp113 - _tmp114 + _tmp115 + _tmp119
    wt[60] = -_tmp129 - _tmp132
    wt[61] = (
        -2 * _tmp126 * z2
        - 2 * _tmp128 * z2
        - 2 * _tmp134 * d_a0x
        - 2 * _tmp136 * d_nab2y
        + 2 * _tmp138 * d_a0y
        - 2 * _tmp140 * d_nab2x
        - 2 * _tmp141 * d_z2
    )
    wt[62] = (
        -_tmp126 * _tmp142
        - _tmp128 * _tmp142
        + _tmp143 * d_a0x
        + _tmp145 * d_nab2x
        + _tmp146 * d_nab2y
        - _tmp147 * (_tmp141 * z2 + a0x * nab2y - a0y * nab2x)
        + d_a0y * (_tmp144 * z2 + nab2y)
    )
    wt[63] = 2 * _tmp148 - 2 * _tmp149 + 2 * a0x * d_nab2z - 2 * d_a0z * nab2x
    wt[64] = (
        -2 * _tmp134 * d_a0z
        + 2 * _tmp140 * d_nab2z
        - 2 * _tmp149 * z2
        - 2 * _tmp150
        - 2 * _tmp151
        + 2 * d_a0x * nab2z * z2
        + 2 * d_z2 * (a0x * nab2z - a0z * nab2x)
    )
    wt[65] = _tmp129 - _tmp130 - _tmp131
    wt[66] = 2 * _tmp150 - 2 * _tmp151 - 2 * a0y * d_nab2z + 2 * d_a0z * nab2y
    wt[67] = (
        -2 * _tmp136 * d_nab2z
        - 2 * _tmp138 * d_a0z
        - 2 * _tmp148
        - 2 * _tmp149
        - 2 * _tmp151 * z2
        + 2 * a0z * d_nab2y * z2
        - 2 * d_z2 * (a0y * nab2z - a0z * nab2y)
    )
    wt[68] = -2 * (a0x * d_nab2y + a0y * d_nab2x + d_a0x * nab2y + d_a0y * nab2x)
    wt[69] = -_tmp125 + _tmp126 - _tmp127 + _tmp128 + _tmp132
    wt[70] = _tmp156 + _tmp159
    wt[71] = (
        2 * _tmp134 * d_b0x
        - 2 * _tmp138 * d_b0y
        + 2 * _tmp153 * z2
        + 2 * _tmp155 * z2
        + 2 * _tmp161 * d_nab2y
        + 2 * _tmp163 * d_nab2x
        + 2 * _tmp164 * d_z2
    )
    wt[72] = (
        _tmp142 * b0z * d_nab2z
        + _tmp142 * d_b0z * nab2z
        - _tmp143 * d_b0x
        - _tmp165 * d_nab2x
        - _tmp166 * d_nab2y
        - d_b0y * (_tmp144 * z2 + nab2y)
        + 2 * d_z2 * (_tmp164 * z2 + b0x * nab2y - b0y * nab2x)
    )
    wt[73] = -2 * _tmp167 - 2 * b0x * d_nab2z + 2 * b0z * d_nab2x + 2 * d_b0z * nab2x
    wt[74] = (
        2 * _tmp134 * d_b0z
        - 2 * _tmp163 * d_nab2z
        - 2 * _tmp167 * z2
        + 2 * _tmp168
        + 2 * _tmp169
        + 2 * _tmp170 * z2
        - 2 * d_z2 * (b0x * nab2z - b0z * nab2x)
    )
    wt[75] = -_tmp156 + _tmp157 + _tmp158
    wt[76] = -2 * _tmp168 + 2 * _tmp169 + 2 * b0y * d_nab2z - 2 * d_b0z * nab2y
    wt[77] = (
        2 * _tmp138 * d_b0z
        + 2 * _tmp161 * d_nab2z
        + 2 * _tmp167
        - 2 * _tmp168 * z2
        + 2 * _tmp169 * z2
        + 2 * _tmp170
        + 2 * d_z2 * (b0y * nab2z - b0z * nab2y)
    )
    wt[78] = 2 * (b0x * d_nab2y + b0y * d_nab2x + d_b0x * nab2y + d_b0y * nab2x)
    wt[79] = _tmp152 - _tmp153 + _tmp154 - _tmp155 - _tmp159
    wt[80] = -_tmp175 - _tmp178
    wt[81] = (
        -2 * _tmp136 * d_nac2y
        - 2 * _tmp140 * d_nac2x
        - 2 * _tmp172 * z2
        - 2 * _tmp174 * z2
        - 2 * _tmp180 * d_a0x
        + 2 * _tmp182 * d_a0y
        - 2 * _tmp183 * d_z2
    )
    wt[82] = (
        -_tmp142 * _tmp172
        - _tmp142 * _tmp174
        + _tmp145 * d_nac2x
        + _tmp146 * d_nac2y
        - _tmp147 * (_tmp183 * z2 + a0x * nac2y - a0y * nac2x)
        + _tmp184 * d_a0x
        + d_a0y * (_tmp185 * z2 + nac2y)
    )
    wt[83] = 2 * _tmp186 - 2 * _tmp187 + 2 * a0x * d_nac2z - 2 * d_a0z * nac2x
    wt[84] = (
        2 * _tmp140 * d_nac2z
        - 2 * _tmp180 * d_a0z
        - 2 * _tmp187 * z2
        - 2 * _tmp188
        - 2 * _tmp189
        + 2 * d_a0x * nac2z * z2
        + 2 * d_z2 * (a0x * nac2z - a0z * nac2x)
    )
    wt[85] = _tmp175 - _tmp176 - _tmp177
    wt[86] = 2 * _tmp188 - 2 * _tmp189 - 2 * a0y * d_nac2z + 2 * d_a0z * nac2y
    wt[87] = (
        -2 * _tmp136 * d_nac2z
        - 2 * _tmp182 * d_a0z
        - 2 * _tmp186
        - 2 * _tmp187
        - 2 * _tmp189 * z2
        + 2 * a0z * d_nac2y * z2
        - 2 * d_z2 * (a0y * nac2z - a0z * nac2y)
    )
    wt[88] = -2 * (a0x * d_nac2y + a0y * d_nac2x + d_a0x * nac2y + d_a0y * nac2x)
    wt[89] = -_tmp171 + _tmp172 - _tmp173 + _tmp174 + _tmp178
    wt[90] = _tmp194 + _tmp197
    wt[91] = (
        2 * _tmp180 * d_c0x
        - 2 * _tmp182 * d_c0y
        + 2 * _tmp191 * z2
        + 2 * _tmp193 * z2
        + 2 * _tmp199 * d_nac2y
        + 2 * _tmp201 * d_nac2x
        + 2 * _tmp202 * d_z2
    )
    wt[92] = (
        _tmp142 * c0z * d_nac2z
        + _tmp142 * d_c0z * nac2z
        - _tmp184 * d_c0x
        - _tmp203 * d_nac2x
        - _tmp204 * d_nac2y
        - d_c0y * (_tmp185 * z2 + nac2y)
        + 2 * d_z2 * (_tmp202 * z2 + c0x * nac2y - c0y * nac2x)
    )
    wt[93] = -2 * _tmp205 - 2 * c0x * d_nac2z + 2 * c0z * d_nac2x + 2 * d_c0z * nac2x
    wt[94] = (
        2 * _tmp180 * d_c0z
        - 2 * _tmp201 * d_nac2z
        - 2 * _tmp205 * z2
        + 2 * _tmp206
        + 2 * _tmp207
        + 2 * _tmp208 * z2
        - 2 * d_z2 * (c0x * nac2z - c0z * nac2x)
    )
    wt[95] = -_tmp194 + _tmp195 + _tmp196
    wt[96] = -2 * _tmp206 + 2 * _tmp207 + 2 * c0y * d_nac2z - 2 * d_c0z * nac2y
    wt[97] = (
        2 * _tmp182 * d_c0z
        + 2 * _tmp199 * d_nac2z
        + 2 * _tmp205
        - 2 * _tmp206 * z2
        + 2 * _tmp207 * z2
        + 2 * _tmp208
        + 2 * d_z2 * (c0y * nac2z - c0z * nac2y)
    )
    wt[98] = 2 * (c0x * d_nac2y + c0y * d_nac2x + d_c0x * nac2y + d_c0y * nac2x)
    wt[99] = _tmp190 - _tmp191 + _tmp192 - _tmp193 - _tmp197
    wt[100] = _tmp213 + _tmp216
    wt[101] = (
        2 * _tmp199 * d_nbc2y
        + 2 * _tmp201 * d_nbc2x
        + 2 * _tmp210 * z2
        + 2 * _tmp212 * z2
        + 2 * _tmp218 * d_c0x
        - 2 * _tmp220 * d_c0y
        + 2 * _tmp221 * d_z2
    )
    wt[102] = (
        _tmp142 * c0z * d_nbc2z
        + _tmp142 * d_c0z * nbc2z
        - _tmp203 * d_nbc2x
        - _tmp204 * d_nbc2y
        - _tmp222 * d_c0x
        - d_c0y * (_tmp223 * z2 + nbc2y)
        + 2 * d_z2 * (_tmp221 * z2 + c0x * nbc2y - c0y * nbc2x)
    )
    wt[103] = -2 * _tmp224 - 2 * c0x * d_nbc2z + 2 * c0z * d_nbc2x + 2 * d_c0z * nbc2x
    wt[104] = (
        -2 * _tmp201 * d_nbc2z
        + 2 * _tmp218 * d_c0z
        - 2 * _tmp224 * z2
        + 2 * _tmp225
        + 2 * _tmp226
        + 2 * _tmp227 * z2
        - 2 * d_z2 * (c0x * nbc2z - c0z * nbc2x)
    )
    wt[105] = -_tmp213 + _tmp214 + _tmp215
    wt[106] = -2 * _tmp225 + 2 * _tmp226 + 2 * c0y * d_nbc2z - 2 * d_c0z * nbc2y
    wt[107] = (
        2 * _tmp199 * d_nbc2z
        + 2 * _tmp220 * d_c0z
        + 2 * _tmp224
        - 2 * _tmp225 * z2
        + 2 * _tmp226 * z2
        + 2 * _tmp227
        + 2 * d_z2 * (c0y * nbc2z - c0z * nbc2y)
    )
    wt[108] = 2 * (c0x * d_nbc2y + c0y * d_nbc2x + d_c0x * nbc2y + d_c0y * nbc2x)
    wt[109] = _tmp209 - _tmp210 + _tmp211 - _tmp212 - _tmp216
    wt[110] = -_tmp232 - _tmp235
    wt[111] = (
        -2 * _tmp161 * d_nbc2y
        - 2 * _tmp163 * d_nbc2x
        - 2 * _tmp218 * d_b0x
        + 2 * _tmp220 * d_b0y
        - 2 * _tmp229 * z2
        - 2 * _tmp231 * z2
        - 2 * _tmp236 * d_z2
    )
    wt[112] = (
        -_tmp142 * _tmp229
        - _tmp142 * _tmp231
        - _tmp147 * (_tmp236 * z2 + b0x * nbc2y - b0y * nbc2x)
        + _tmp165 * d_nbc2x
        + _tmp166 * d_nbc2y
        + _tmp222 * d_b0x
        + d_b0y * (_tmp223 * z2 + nbc2y)
    )
    wt[113] = 2 * _tmp237 - 2 * _tmp238 + 2 * b0x * d_nbc2z - 2 * d_b0z * nbc2x
    wt[114] = (
        2 * _tmp163 * d_nbc2z
        - 2 * _tmp218 * d_b0z
        - 2 * _tmp238 * z2
        - 2 * _tmp239
        - 2 * _tmp240
        + 2 * d_b0x * nbc2z * z2
        + 2 * d_z2 * (b0x * nbc2z - b0z * nbc2x)
    )
    wt[115] = _tmp232 - _tmp233 - _tmp234
    wt[116] = 2 * _tmp239 - 2 * _tmp240 - 2 * b0y * d_nbc2z + 2 * d_b0z * nbc2y
    wt[117] = (
        -2 * _tmp161 * d_nbc2z
        - 2 * _tmp220 * d_b0z
        - 2 * _tmp237
        - 2 * _tmp238
        - 2 * _tmp240 * z2
        + 2 * b0z * d_nbc2y * z2
        - 2 * d_z2 * (b0y * nbc2z - b0z * nbc2y)
    )
    wt[118] = -2 * (b0x * d_nbc2y + b0y * d_nbc2x + d_b0x * nbc2y + d_b0y * nbc2x)
    wt[119] = -_tmp228 + _tmp229 - _tmp230 + _tmp231 + _tmp235


@numba.njit(**_JIT)
def residual_jacobian(x: np.ndarray, w: np.ndarray, f: np.ndarray, jac: np.ndarray) -> None:
    """F(x; q) = W(q) u(x) and its Jacobian F_x, from W's entries w.

    Outputs written in place (every entry): f, jac.
    """
    b0 = x[0]
    c0 = x[1]
    n1 = x[2]
    n2 = x[3]
    m1 = x[4]
    m2 = x[5]
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
    w60 = w[60]
    w61 = w[61]
    w62 = w[62]
    w63 = w[63]
    w64 = w[64]
    w65 = w[65]
    w66 = w[66]
    w67 = w[67]
    w68 = w[68]
    w69 = w[69]
    w70 = w[70]
    w71 = w[71]
    w72 = w[72]
    w73 = w[73]
    w74 = w[74]
    w75 = w[75]
    w76 = w[76]
    w77 = w[77]
    w78 = w[78]
    w79 = w[79]
    w80 = w[80]
    w81 = w[81]
    w82 = w[82]
    w83 = w[83]
    w84 = w[84]
    w85 = w[85]
    w86 = w[86]
    w87 = w[87]
    w88 = w[88]
    w89 = w[89]
    w90 = w[90]
    w91 = w[91]
    w92 = w[92]
    w93 = w[93]
    w94 = w[94]
    w95 = w[95]
    w96 = w[96]
    w97 = w[97]
    w98 = w[98]
    w99 = w[99]
    w100 = w[100]
    w101 = w[101]
    w102 = w[102]
    w103 = w[103]
    w104 = w[104]
    w105 = w[105]
    w106 = w[106]
    w107 = w[107]
    w108 = w[108]
    w109 = w[109]
    w110 = w[110]
    w111 = w[111]
    w112 = w[112]
    w113 = w[113]
    w114 = w[114]
    w115 = w[115]
    w116 = w[116]
    w117 = w[117]
    w118 = w[118]
    w119 = w[119]
    _tmp0 = n2 * w5
    _tmp1 = n1 * w9
    _tmp2 = n2 * w8 + w7
    _tmp3 = m1 * (n1 * (_tmp1 + _tmp2) + n2 * (_tmp0 + w4) + w2)
    _tmp4 = n1 * w6 + n2 * w3 + w1
    _tmp5 = n2 * w15
    _tmp6 = n1 * w19
    _tmp7 = n2 * w18 + w17
    _tmp8 = m1 * (n1 * (_tmp6 + _tmp7) + n2 * (_tmp5 + w14) + w12)
    _tmp9 = n1 * w16 + n2 * w13 + w11
    _tmp10 = m1 * (_tmp8 + _tmp9) + w10
    _tmp11 = n2 * w25
    _tmp12 = n1 * w29
    _tmp13 = n2 * w28 + w27
    _tmp14 = m1 * (n1 * (_tmp12 + _tmp13) + n2 * (_tmp11 + w24) + w22)
    _tmp15 = n1 * w26 + n2 * w23 + w21
    _tmp16 = n2 * w35
    _tmp17 = n1 * w39
    _tmp18 = n2 * w38 + w37
    _tmp19 = m1 * (n1 * (_tmp17 + _tmp18) + n2 * (_tmp16 + w34) + w32)
    _tmp20 = n1 * w36 + n2 * w33 + w31
    _tmp21 = m1 * (_tmp19 + _tmp20) + w30
    _tmp22 = n2 * w55
    _tmp23 = n1 * w59
    _tmp24 = n2 * w58 + w57
    _tmp25 = m1 * (n1 * (_tmp23 + _tmp24) + n2 * (_tmp22 + w54) + w52)
    _tmp26 = n1 * w56 + n2 * w53 + w51
    _tmp27 = m1 * (_tmp25 + _tmp26) + w50
    _tmp28 = n2 * w45
    _tmp29 = n1 * w49
    _tmp30 = n2 * w48 + w47
    _tmp31 = m1 * (n1 * (_tmp29 + _tmp30) + n2 * (_tmp28 + w44) + w42)
    _tmp32 = n1 * w46 + n2 * w43 + w41
    _tmp33 = m1 * (_tmp31 + _tmp32) + w40
    _tmp34 = n2 * w65
    _tmp35 = n1 * w69
    _tmp36 = n2 * w68 + w67
    _tmp37 = m2 * (n1 * (_tmp35 + _tmp36) + n2 * (_tmp34 + w64) + w62)
    _tmp38 = n1 * w66 + n2 * w63 + w61
    _tmp39 = n2 * w75
    _tmp40 = n1 * w79
    _tmp41 = n2 * w78 + w77
    _tmp42 = m2 * (n1 * (_tmp40 + _tmp41) + n2 * (_tmp39 + w74) + w72)
    _tmp43 = n1 * w76 + n2 * w73 + w71
    _tmp44 = m2 * (_tmp42 + _tmp43) + w70
    _tmp45 = n2 * w85
    _tmp46 = n1 * w89
    _tmp47 = n2 * w88 + w87
    _tmp48 = m2 * (n1 * (_tmp46 + _tmp47) + n2 * (_tmp45 + w84) + w82)
    _tmp49 = n1 * w86 + n2 * w83 + w81
    _tmp50 = n2 * w95
    _tmp51 = n1 * w99
    _tmp52 = n2 * w98 + w97
    _tmp53 = m2 * (n1 * (_tmp51 + _tmp52) + n2 * (_tmp50 + w94) + w92)
    _tmp54 = n1 * w96 + n2 * w93 + w91
    _tmp55 = m2 * (_tmp53 + _tmp54) + w90
    _tmp56 = n2 * w115
    _tmp57 = n1 * w119
    _tmp58 = n2 * w118 + w117
    _tmp59 = m2 * (n1 * (_tmp57 + _tmp58) + n2 * (_tmp56 + w114) + w112)
    _tmp60 = n1 * w116 + n2 * w113 + w111
    _tmp61 = m2 * (_tmp59 + _tmp60) + w110
    _tmp62 = n2 * w105
    _tmp63 = n1 * w109
    _tmp64 = n2 * w108 + w107
    _tmp65 = m2 * (n1 * (_tmp63 + _tmp64) + n2 * (_tmp62 + w104) + w102)
    _tmp66 = n1 * w106 + n2 * w103 + w101
    _tmp67 = m2 * (_tmp65 + _tmp66) + w100
    f[0] = _tmp10 * b0 + m1 * (_tmp3 + _tmp4) + w0
    f[1] = _tmp21 * c0 + m1 * (_tmp14 + _tmp15) + w20
    f[2] = _tmp27 * b0 + _tmp33 * c0
    f[3] = _tmp44 * b0 + m2 * (_tmp37 + _tmp38) + w60
    f[4] = _tmp55 * c0 + m2 * (_tmp48 + _tmp49) + w80
    f[5] = _tmp61 * b0 + _tmp67 * c0
    jac[0, 0] = _tmp10
    jac[0, 1] = 0.0
    jac[0, 2] = m1 * (b0 * (m1 * (2 * _tmp6 + _tmp7) + w16) + m1 * (2 * _tmp1 + _tmp2) + w6)
    jac[0, 3] = m1 * (
        b0 * (m1 * (2 * _tmp5 + n1 * w18 + w14) + w13) + m1 * (2 * _tmp0 + n1 * w8 + w4) + w3
    )
    jac[0, 4] = 2 * _tmp3 + _tmp4 + b0 * (2 * _tmp8 + _tmp9)
    jac[0, 5] = 0.0
    jac[1, 0] = 0.0
    jac[1, 1] = _tmp21
    jac[1, 2] = m1 * (c0 * (m1 * (2 * _tmp17 + _tmp18) + w36) + m1 * (2 * _tmp12 + _tmp13) + w26)
    jac[1, 3] = m1 * (
        c0 * (m1 * (2 * _tmp16 + n1 * w38 + w34) + w33) + m1 * (2 * _tmp11 + n1 * w28 + w24) + w23
    )
    jac[1, 4] = 2 * _tmp14 + _tmp15 + c0 * (2 * _tmp19 + _tmp20)
    jac[1, 5] = 0.0
    jac[2, 0] = _tmp27
    jac[2, 1] = _tmp33
    jac[2, 2] = m1 * (
        b0 * (m1 * (2 * _tmp23 + _tmp24) + w56) + c0 * (m1 * (2 * _tmp29 + _tmp30) + w46)
    )
    jac[2, 3] = m1 * (
        b0 * (m1 * (2 * _tmp22 + n1 * w58 + w54) + w53)
        + c0 * (m1 * (2 * _tmp28 + n1 * w48 + w44) + w43)
    )
    jac[2, 4] = b0 * (2 * _tmp25 + _tmp26) + c0 * (2 * _tmp31 + _tmp32)
    jac[2, 5] = 0.0
    jac[3, 0] = _tmp44
    jac[3, 1] = 0.0
    jac[3, 2] = m2 * (b0 * (m2 * (2 * _tmp40 + _tmp41) + w76) + m2 * (2 * _tmp35 + _tmp36) + w66)
    jac[3, 3] = m2 * (
        b0 * (m2 * (2 * _tmp39 + n1 * w78 + w74) + w73) + m2 * (2 * _tmp34 + n1 * w68 + w64) + w63
    )
    jac[3, 4] = 0.0
    jac[3, 5] = 2 * _tmp37 + _tmp38 + b0 * (2 * _tmp42 + _tmp43)
    jac[4, 0] = 0.0
    jac[4, 1] = _tmp55
    jac[4, 2] = m2 * (c0 * (m2 * (2 * _tmp51 + _tmp52) + w96) + m2 * (2 * _tmp46 + _tmp47) + w86)
    jac[4, 3] = m2 * (
        c0 * (m2 * (2 * _tmp50 + n1 * w98 + w94) + w93) + m2 * (2 * _tmp45 + n1 * w88 + w84) + w83
    )
    jac[4, 4] = 0.0
    jac[4, 5] = 2 * _tmp48 + _tmp49 + c0 * (2 * _tmp53 + _tmp54)
    jac[5, 0] = _tmp61
    jac[5, 1] = _tmp67
    jac[5, 2] = m2 * (
        b0 * (m2 * (2 * _tmp57 + _tmp58) + w116) + c0 * (m2 * (2 * _tmp63 + _tmp64) + w106)
    )
    jac[5, 3] = m2 * (
        b0 * (m2 * (2 * _tmp56 + n1 * w118 + w114) + w113)
        + c0 * (m2 * (2 * _tmp62 + n1 * w108 + w104) + w103)
    )
    jac[5, 4] = 0.0
    jac[5, 5] = b0 * (2 * _tmp59 + _tmp60) + c0 * (2 * _tmp65 + _tmp66)


@numba.njit(**_JIT)
def residual_jacobian_t(
    x: np.ndarray, w: np.ndarray, wt: np.ndarray, f: np.ndarray, jac: np.ndarray, ft: np.ndarray
) -> None:
    """F and F_x as ``residual_jacobian``, and F_t = (dW/dt) u(x) from dW/dt's entries wt.

    Outputs written in place (every entry): f, jac, ft.
    """
    b0 = x[0]
    c0 = x[1]
    n1 = x[2]
    n2 = x[3]
    m1 = x[4]
    m2 = x[5]
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
    w60 = w[60]
    w61 = w[61]
    w62 = w[62]
    w63 = w[63]
    w64 = w[64]
    w65 = w[65]
    w66 = w[66]
    w67 = w[67]
    w68 = w[68]
    w69 = w[69]
    w70 = w[70]
    w71 = w[71]
    w72 = w[72]
    w73 = w[73]
    w74 = w[74]
    w75 = w[75]
    w76 = w[76]
    w77 = w[77]
    w78 = w[78]
    w79 = w[79]
    w80 = w[80]
    w81 = w[81]
    w82 = w[82]
    w83 = w[83]
    w84 = w[84]
    w85 = w[85]
    w86 = w[86]
    w87 = w[87]
    w88 = w[88]
    w89 = w[89]
    w90 = w[90]
    w91 = w[91]
    w92 = w[92]
    w93 = w[93]
    w94 = w[94]
    w95 = w[95]
    w96 = w[96]
    w97 = w[97]
    w98 = w[98]
    w99 = w[99]
    w100 = w[100]
    w101 = w[101]
    w102 = w[102]
    w103 = w[103]
    w104 = w[104]
    w105 = w[105]
    w106 = w[106]
    w107 = w[107]
    w108 = w[108]
    w109 = w[109]
    w110 = w[110]
    w111 = w[111]
    w112 = w[112]
    w113 = w[113]
    w114 = w[114]
    w115 = w[115]
    w116 = w[116]
    w117 = w[117]
    w118 = w[118]
    w119 = w[119]
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
    wt60 = wt[60]
    wt61 = wt[61]
    wt62 = wt[62]
    wt63 = wt[63]
    wt64 = wt[64]
    wt65 = wt[65]
    wt66 = wt[66]
    wt67 = wt[67]
    wt68 = wt[68]
    wt69 = wt[69]
    wt70 = wt[70]
    wt71 = wt[71]
    wt72 = wt[72]
    wt73 = wt[73]
    wt74 = wt[74]
    wt75 = wt[75]
    wt76 = wt[76]
    wt77 = wt[77]
    wt78 = wt[78]
    wt79 = wt[79]
    wt80 = wt[80]
    wt81 = wt[81]
    wt82 = wt[82]
    wt83 = wt[83]
    wt84 = wt[84]
    wt85 = wt[85]
    wt86 = wt[86]
    wt87 = wt[87]
    wt88 = wt[88]
    wt89 = wt[89]
    wt90 = wt[90]
    wt91 = wt[91]
    wt92 = wt[92]
    wt93 = wt[93]
    wt94 = wt[94]
    wt95 = wt[95]
    wt96 = wt[96]
    wt97 = wt[97]
    wt98 = wt[98]
    wt99 = wt[99]
    wt100 = wt[100]
    wt101 = wt[101]
    wt102 = wt[102]
    wt103 = wt[103]
    wt104 = wt[104]
    wt105 = wt[105]
    wt106 = wt[106]
    wt107 = wt[107]
    wt108 = wt[108]
    wt109 = wt[109]
    wt110 = wt[110]
    wt111 = wt[111]
    wt112 = wt[112]
    wt113 = wt[113]
    wt114 = wt[114]
    wt115 = wt[115]
    wt116 = wt[116]
    wt117 = wt[117]
    wt118 = wt[118]
    wt119 = wt[119]
    _tmp0 = n2 * w5
    _tmp1 = n1 * w9
    _tmp2 = n2 * w8 + w7
    _tmp3 = m1 * (n1 * (_tmp1 + _tmp2) + n2 * (_tmp0 + w4) + w2)
    _tmp4 = n1 * w6 + n2 * w3 + w1
    _tmp5 = n2 * w15
    _tmp6 = n1 * w19
    _tmp7 = n2 * w18 + w17
    _tmp8 = m1 * (n1 * (_tmp6 + _tmp7) + n2 * (_tmp5 + w14) + w12)
    _tmp9 = n1 * w16 + n2 * w13 + w11
    _tmp10 = m1 * (_tmp8 + _tmp9) + w10
    _tmp11 = n2 * w25
    _tmp12 = n1 * w29
    _tmp13 = n2 * w28 + w27
    _tmp14 = m1 * (n1 * (_tmp12 + _tmp13) + n2 * (_tmp11 + w24) + w22)
    _tmp15 = n1 * w26 + n2 * w23 + w21
    _tmp16 = n2 * w35
    _tmp17 = n1 * w39
    _tmp18 = n2 * w38 + w37
    _tmp19 = m1 * (n1 * (_tmp17 + _tmp18) + n2 * (_tmp16 + w34) + w32)
    _tmp20 = n1 * w36 + n2 * w33 + w31
    _tmp21 = m1 * (_tmp19 + _tmp20) + w30
    _tmp22 = n2 * w55
    _tmp23 = n1 * w59
    _tmp24 = n2 * w58 + w57
    _tmp25 = m1 * (n1 * (_tmp23 + _tmp24) + n2 * (_tmp22 + w54) + w52)
    _tmp26 = n1 * w56 + n2 * w53 + w51
    _tmp27 = m1 * (_tmp25 + _tmp26) + w50
    _tmp28 = n2 * w45
    _tmp29 = n1 * w49
    _tmp30 = n2 * w48 + w47
    _tmp31 = m1 * (n1 * (_tmp29 + _tmp30) + n2 * (_tmp28 + w44) + w42)
    _tmp32 = n1 * w46 + n2 * w43 + w41
    _tmp33 = m1 * (_tmp31 + _tmp32) + w40
    _tmp34 = n2 * w65
    _tmp35 = n1 * w69
    _tmp36 = n2 * w68 + w67
    _tmp37 = m2 * (n1 * (_tmp35 + _tmp36) + n2 * (_tmp34 + w64) + w62)
    _tmp38 = n1 * w66 + n2 * w63 + w61
    _tmp39 = n2 * w75
    _tmp40 = n1 * w79
    _tmp41 = n2 * w78 + w77
    _tmp42 = m2 * (n1 * (_tmp40 + _tmp41) + n2 * (_tmp39 + w74) + w72)
    _tmp43 = n1 * w76 + n2 * w73 + w71
    _tmp44 = m2 * (_tmp42 + _tmp43) + w70
    _tmp45 = n2 * w85
    _tmp46 = n1 * w89
    _tmp47 = n2 * w88 + w87
    _tmp48 = m2 * (n1 * (_tmp46 + _tmp47) + n2 * (_tmp45 + w84) + w82)
    _tmp49 = n1 * w86 + n2 * w83 + w81
    _tmp50 = n2 * w95
    _tmp51 = n1 * w99
    _tmp52 = n2 * w98 + w97
    _tmp53 = m2 * (n1 * (_tmp51 + _tmp52) + n2 * (_tmp50 + w94) + w92)
    _tmp54 = n1 * w96 + n2 * w93 + w91
    _tmp55 = m2 * (_tmp53 + _tmp54) + w90
    _tmp56 = n2 * w115
    _tmp57 = n1 * w119
    _tmp58 = n2 * w118 + w117
    _tmp59 = m2 * (n1 * (_tmp57 + _tmp58) + n2 * (_tmp56 + w114) + w112)
    _tmp60 = n1 * w116 + n2 * w113 + w111
    _tmp61 = m2 * (_tmp59 + _tmp60) + w110
    _tmp62 = n2 * w105
    _tmp63 = n1 * w109
    _tmp64 = n2 * w108 + w107
    _tmp65 = m2 * (n1 * (_tmp63 + _tmp64) + n2 * (_tmp62 + w104) + w102)
    _tmp66 = n1 * w106 + n2 * w103 + w101
    _tmp67 = m2 * (_tmp65 + _tmp66) + w100
    f[0] = _tmp10 * b0 + m1 * (_tmp3 + _tmp4) + w0
    f[1] = _tmp21 * c0 + m1 * (_tmp14 + _tmp15) + w20
    f[2] = _tmp27 * b0 + _tmp33 * c0
    f[3] = _tmp44 * b0 + m2 * (_tmp37 + _tmp38) + w60
    f[4] = _tmp55 * c0 + m2 * (_tmp48 + _tmp49) + w80
    f[5] = _tmp61 * b0 + _tmp67 * c0
    jac[0, 0] = _tmp10
    jac[0, 1] = 0.0
    jac[0, 2] = m1 * (b0 * (m1 * (2 * _tmp6 + _tmp7) + w16) + m1 * (2 * _tmp1 + _tmp2) + w6)
    jac[0, 3] = m1 * (
        b0 * (m1 * (2 * _tmp5 + n1 * w18 + w14) + w13) + m1 * (2 * _tmp0 + n1 * w8 + w4) + w3
    )
    jac[0, 4] = 2 * _tmp3 + _tmp4 + b0 * (2 * _tmp8 + _tmp9)
    jac[0, 5] = 0.0
    jac[1, 0] = 0.0
    jac[1, 1] = _tmp21
    jac[1, 2] = m1 * (c0 * (m1 * (2 * _tmp17 + _tmp18) + w36) + m1 * (2 * _tmp12 + _tmp13) + w26)
    jac[1, 3] = m1 * (
        c0 * (m1 * (2 * _tmp16 + n1 * w38 + w34) + w33) + m1 * (2 * _tmp11 + n1 * w28 + w24) + w23
    )
    jac[1, 4] = 2 * _tmp14 + _tmp15 + c0 * (2 * _tmp19 + _tmp20)
    jac[1, 5] = 0.0
    jac[2, 0] = _tmp27
    jac[2, 1] = _tmp33
    jac[2, 2] = m1 * (
        b0 * (m1 * (2 * _tmp23 + _tmp24) + w56) + c0 * (m1 * (2 * _tmp29 + _tmp30) + w46)
    )
    jac[2, 3] = m1 * (
        b0 * (m1 * (2 * _tmp22 + n1 * w58 + w54) + w53)
        + c0 * (m1 * (2 * _tmp28 + n1 * w48 + w44) + w43)
    )
    jac[2, 4] = b0 * (2 * _tmp25 + _tmp26) + c0 * (2 * _tmp31 + _tmp32)
    jac[2, 5] = 0.0
    jac[3, 0] = _tmp44
    jac[3, 1] = 0.0
    jac[3, 2] = m2 * (b0 * (m2 * (2 * _tmp40 + _tmp41) + w76) + m2 * (2 * _tmp35 + _tmp36) + w66)
    jac[3, 3] = m2 * (
        b0 * (m2 * (2 * _tmp39 + n1 * w78 + w74) + w73) + m2 * (2 * _tmp34 + n1 * w68 + w64) + w63
    )
    jac[3, 4] = 0.0
    jac[3, 5] = 2 * _tmp37 + _tmp38 + b0 * (2 * _tmp42 + _tmp43)
    jac[4, 0] = 0.0
    jac[4, 1] = _tmp55
    jac[4, 2] = m2 * (c0 * (m2 * (2 * _tmp51 + _tmp52) + w96) + m2 * (2 * _tmp46 + _tmp47) + w86)
    jac[4, 3] = m2 * (
        c0 * (m2 * (2 * _tmp50 + n1 * w98 + w94) + w93) + m2 * (2 * _tmp45 + n1 * w88 + w84) + w83
    )
    jac[4, 4] = 0.0
    jac[4, 5] = 2 * _tmp48 + _tmp49 + c0 * (2 * _tmp53 + _tmp54)
    jac[5, 0] = _tmp61
    jac[5, 1] = _tmp67
    jac[5, 2] = m2 * (
        b0 * (m2 * (2 * _tmp57 + _tmp58) + w116) + c0 * (m2 * (2 * _tmp63 + _tmp64) + w106)
    )
    jac[5, 3] = m2 * (
        b0 * (m2 * (2 * _tmp56 + n1 * w118 + w114) + w113)
        + c0 * (m2 * (2 * _tmp62 + n1 * w108 + w104) + w103)
    )
    jac[5, 4] = 0.0
    jac[5, 5] = b0 * (2 * _tmp59 + _tmp60) + c0 * (2 * _tmp65 + _tmp66)
    ft[0] = (
        b0
        * (
            m1
            * (
                m1 * (n1 * (n1 * wt19 + n2 * wt18 + wt17) + n2 * (n2 * wt15 + wt14) + wt12)
                + n1 * wt16
                + n2 * wt13
                + wt11
            )
            + wt10
        )
        + m1
        * (
            m1 * (n1 * (n1 * wt9 + n2 * wt8 + wt7) + n2 * (n2 * wt5 + wt4) + wt2)
            + n1 * wt6
            + n2 * wt3
            + wt1
        )
        + wt0
    )
    ft[1] = (
        c0
        * (
            m1
            * (
                m1 * (n1 * (n1 * wt39 + n2 * wt38 + wt37) + n2 * (n2 * wt35 + wt34) + wt32)
                + n1 * wt36
                + n2 * wt33
                + wt31
            )
            + wt30
        )
        + m1
        * (
            m1 * (n1 * (n1 * wt29 + n2 * wt28 + wt27) + n2 * (n2 * wt25 + wt24) + wt22)
            + n1 * wt26
            + n2 * wt23
            + wt21
        )
        + wt20
    )
    ft[2] = b0 * (
        m1
        * (
            m1 * (n1 * (n1 * wt59 + n2 * wt58 + wt57) + n2 * (n2 * wt55 + wt54) + wt52)
            + n1 * wt56
            + n2 * wt53
            + wt51
        )
        + wt50
    ) + c0 * (
        m1
        * (
            m1 * (n1 * (n1 * wt49 + n2 * wt48 + wt47) + n2 * (n2 * wt45 + wt44) + wt42)
            + n1 * wt46
            + n2 * wt43
            + wt41
        )
        + wt40
    )
    ft[3] = (
        b0
        * (
            m2
            * (
                m2 * (n1 * (n1 * wt79 + n2 * wt78 + wt77) + n2 * (n2 * wt75 + wt74) + wt72)
                + n1 * wt76
                + n2 * wt73
                + wt71
            )
            + wt70
        )
        + m2
        * (
            m2 * (n1 * (n1 * wt69 + n2 * wt68 + wt67) + n2 * (n2 * wt65 + wt64) + wt62)
            + n1 * wt66
            + n2 * wt63
            + wt61
        )
        + wt60
    )
    ft[4] = (
        c0
        * (
            m2
            * (
                m2 * (n1 * (n1 * wt99 + n2 * wt98 + wt97) + n2 * (n2 * wt95 + wt94) + wt92)
                + n1 * wt96
                + n2 * wt93
                + wt91
            )
            + wt90
        )
        + m2
        * (
            m2 * (n1 * (n1 * wt89 + n2 * wt88 + wt87) + n2 * (n2 * wt85 + wt84) + wt82)
            + n1 * wt86
            + n2 * wt83
            + wt81
        )
        + wt80
    )
    ft[5] = b0 * (
        m2
        * (
            m2 * (n1 * (n1 * wt119 + n2 * wt118 + wt117) + n2 * (n2 * wt115 + wt114) + wt112)
            + n1 * wt116
            + n2 * wt113
            + wt111
        )
        + wt110
    ) + c0 * (
        m2
        * (
            m2 * (n1 * (n1 * wt109 + n2 * wt108 + wt107) + n2 * (n2 * wt105 + wt104) + wt102)
            + n1 * wt106
            + n2 * wt103
            + wt101
        )
        + wt100
    )


#: The linear solves' elimination plan ``solve_pair`` is written for: n, the number of pairs,
#: (unknown, row, row) of each pair, the dense unknowns, the rows in no pair
#: (``curverecon.solvers.homotopy.PolynomialSystem.elimination``).
ELIMINATION = (6, 0, 4, 5, 0, 1, 2, 3, 0, 1, 2, 3, 4, 5)

# Without "reassoc", as the tracker's own linear solve (the same arithmetic, in the same order).
_JIT_SOLVE = {"cache": True, "nogil": True, "fastmath": {"contract", "arcp", "nsz"}}


@numba.njit(**_JIT_SOLVE)
def solve_one(a, b, out):  # type: ignore[no-untyped-def]
    """out = a^-1 b (``out`` not ``b``): ``solve_pair`` for one right-hand side."""
    m0_0 = a[0, 4]
    m0_1 = a[0, 5]
    m0_2 = a[0, 0]
    m0_3 = a[0, 1]
    m0_4 = a[0, 2]
    m0_5 = a[0, 3]
    g0 = b[0]
    m1_0 = a[1, 4]
    m1_1 = a[1, 5]
    m1_2 = a[1, 0]
    m1_3 = a[1, 1]
    m1_4 = a[1, 2]
    m1_5 = a[1, 3]
    g1 = b[1]
    m2_0 = a[2, 4]
    m2_1 = a[2, 5]
    m2_2 = a[2, 0]
    m2_3 = a[2, 1]
    m2_4 = a[2, 2]
    m2_5 = a[2, 3]
    g2 = b[2]
    m3_0 = a[3, 4]
    m3_1 = a[3, 5]
    m3_2 = a[3, 0]
    m3_3 = a[3, 1]
    m3_4 = a[3, 2]
    m3_5 = a[3, 3]
    g3 = b[3]
    m4_0 = a[4, 4]
    m4_1 = a[4, 5]
    m4_2 = a[4, 0]
    m4_3 = a[4, 1]
    m4_4 = a[4, 2]
    m4_5 = a[4, 3]
    g4 = b[4]
    m5_0 = a[5, 4]
    m5_1 = a[5, 5]
    m5_2 = a[5, 0]
    m5_3 = a[5, 1]
    m5_4 = a[5, 2]
    m5_5 = a[5, 3]
    g5 = b[5]
    best = abs(m0_0.real) + abs(m0_0.imag)
    mag = abs(m1_0.real) + abs(m1_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, m0_5, g0, m1_0, m1_1, m1_2, m1_3, m1_4, m1_5, g1 = (
            m1_0,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            m0_5,
            g0,
        )
    mag = abs(m2_0.real) + abs(m2_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, m0_5, g0, m2_0, m2_1, m2_2, m2_3, m2_4, m2_5, g2 = (
            m2_0,
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            m0_5,
            g0,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m0_0.real * m0_0.real + m0_0.imag * m0_0.imag)
    u0 = complex(m0_0.real * dd, -m0_0.imag * dd)
    fac = m1_0 * u0
    m1_2 = m1_2 - fac * m0_2
    m1_3 = m1_3 - fac * m0_3
    m1_4 = m1_4 - fac * m0_4
    m1_5 = m1_5 - fac * m0_5
    g1 = g1 - fac * g0
    fac = m2_0 * u0
    m2_2 = m2_2 - fac * m0_2
    m2_3 = m2_3 - fac * m0_3
    m2_4 = m2_4 - fac * m0_4
    m2_5 = m2_5 - fac * m0_5
    g2 = g2 - fac * g0
    best = abs(m1_1.real) + abs(m1_1.imag)
    mag = abs(m3_1.real) + abs(m3_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, m3_1, m3_2, m3_3, m3_4, m3_5, g3 = (
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            m3_5,
            g3,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
        )
    mag = abs(m4_1.real) + abs(m4_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, m4_1, m4_2, m4_3, m4_4, m4_5, g4 = (
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            m4_5,
            g4,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
        )
    mag = abs(m5_1.real) + abs(m5_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, m5_1, m5_2, m5_3, m5_4, m5_5, g5 = (
            m5_1,
            m5_2,
            m5_3,
            m5_4,
            m5_5,
            g5,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m1_1.real * m1_1.real + m1_1.imag * m1_1.imag)
    u1 = complex(m1_1.real * dd, -m1_1.imag * dd)
    fac = m3_1 * u1
    m3_2 = m3_2 - fac * m1_2
    m3_3 = m3_3 - fac * m1_3
    m3_4 = m3_4 - fac * m1_4
    m3_5 = m3_5 - fac * m1_5
    g3 = g3 - fac * g1
    fac = m4_1 * u1
    m4_2 = m4_2 - fac * m1_2
    m4_3 = m4_3 - fac * m1_3
    m4_4 = m4_4 - fac * m1_4
    m4_5 = m4_5 - fac * m1_5
    g4 = g4 - fac * g1
    fac = m5_1 * u1
    m5_2 = m5_2 - fac * m1_2
    m5_3 = m5_3 - fac * m1_3
    m5_4 = m5_4 - fac * m1_4
    m5_5 = m5_5 - fac * m1_5
    g5 = g5 - fac * g1
    best = abs(m2_2.real) + abs(m2_2.imag)
    mag = abs(m3_2.real) + abs(m3_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, m3_2, m3_3, m3_4, m3_5, g3 = (
            m3_2,
            m3_3,
            m3_4,
            m3_5,
            g3,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
        )
    mag = abs(m4_2.real) + abs(m4_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, m4_2, m4_3, m4_4, m4_5, g4 = (
            m4_2,
            m4_3,
            m4_4,
            m4_5,
            g4,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
        )
    mag = abs(m5_2.real) + abs(m5_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, m5_2, m5_3, m5_4, m5_5, g5 = (
            m5_2,
            m5_3,
            m5_4,
            m5_5,
            g5,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m2_2.real * m2_2.real + m2_2.imag * m2_2.imag)
    u2 = complex(m2_2.real * dd, -m2_2.imag * dd)
    fac = m3_2 * u2
    m3_3 = m3_3 - fac * m2_3
    m3_4 = m3_4 - fac * m2_4
    m3_5 = m3_5 - fac * m2_5
    g3 = g3 - fac * g2
    fac = m4_2 * u2
    m4_3 = m4_3 - fac * m2_3
    m4_4 = m4_4 - fac * m2_4
    m4_5 = m4_5 - fac * m2_5
    g4 = g4 - fac * g2
    fac = m5_2 * u2
    m5_3 = m5_3 - fac * m2_3
    m5_4 = m5_4 - fac * m2_4
    m5_5 = m5_5 - fac * m2_5
    g5 = g5 - fac * g2
    best = abs(m3_3.real) + abs(m3_3.imag)
    mag = abs(m4_3.real) + abs(m4_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, m3_5, g3, m4_3, m4_4, m4_5, g4 = m4_3, m4_4, m4_5, g4, m3_3, m3_4, m3_5, g3
    mag = abs(m5_3.real) + abs(m5_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, m3_5, g3, m5_3, m5_4, m5_5, g5 = m5_3, m5_4, m5_5, g5, m3_3, m3_4, m3_5, g3
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m3_3.real * m3_3.real + m3_3.imag * m3_3.imag)
    u3 = complex(m3_3.real * dd, -m3_3.imag * dd)
    fac = m4_3 * u3
    m4_4 = m4_4 - fac * m3_4
    m4_5 = m4_5 - fac * m3_5
    g4 = g4 - fac * g3
    fac = m5_3 * u3
    m5_4 = m5_4 - fac * m3_4
    m5_5 = m5_5 - fac * m3_5
    g5 = g5 - fac * g3
    best = abs(m4_4.real) + abs(m4_4.imag)
    mag = abs(m5_4.real) + abs(m5_4.imag)
    if mag > best:
        best = mag
        m4_4, m4_5, g4, m5_4, m5_5, g5 = m5_4, m5_5, g5, m4_4, m4_5, g4
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m4_4.real * m4_4.real + m4_4.imag * m4_4.imag)
    u4 = complex(m4_4.real * dd, -m4_4.imag * dd)
    fac = m5_4 * u4
    m5_5 = m5_5 - fac * m4_5
    g5 = g5 - fac * g4
    best = abs(m5_5.real) + abs(m5_5.imag)
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m5_5.real * m5_5.real + m5_5.imag * m5_5.imag)
    u5 = complex(m5_5.real * dd, -m5_5.imag * dd)
    x5 = (g5) * u5
    x4 = (g4 - m4_5 * x5) * u4
    x3 = (g3 - m3_4 * x4 - m3_5 * x5) * u3
    x2 = (g2 - m2_3 * x3 - m2_4 * x4 - m2_5 * x5) * u2
    x1 = (g1 - m1_2 * x2 - m1_3 * x3 - m1_4 * x4 - m1_5 * x5) * u1
    x0 = (g0 - m0_2 * x2 - m0_3 * x3 - m0_4 * x4 - m0_5 * x5) * u0
    out[4] = x0
    out[5] = x1
    out[0] = x2
    out[1] = x3
    out[2] = x4
    out[3] = x5
    return True


@numba.njit(**_JIT_SOLVE)
def solve_pair(a, b, c, out, out2, m, r, r2, plan, two):  # type: ignore[no-untyped-def]
    """out = a^-1 b and, if ``two``, out2 = a^-1 c (``out``, ``out2`` not ``b``, ``c``): the
    arithmetic of ``curverecon.solvers.homotopy._solve_pair`` with ELIMINATION's loops
    unrolled and every entry a local variable.  ``m``, ``r``, ``r2`` and ``plan`` are not read
    (that function's signature).  False if a pivot is zero or not finite."""
    if not two:
        return solve_one(a, b, out)
    m0_0 = a[0, 4]
    m0_1 = a[0, 5]
    m0_2 = a[0, 0]
    m0_3 = a[0, 1]
    m0_4 = a[0, 2]
    m0_5 = a[0, 3]
    g0 = b[0]
    e0 = c[0]
    m1_0 = a[1, 4]
    m1_1 = a[1, 5]
    m1_2 = a[1, 0]
    m1_3 = a[1, 1]
    m1_4 = a[1, 2]
    m1_5 = a[1, 3]
    g1 = b[1]
    e1 = c[1]
    m2_0 = a[2, 4]
    m2_1 = a[2, 5]
    m2_2 = a[2, 0]
    m2_3 = a[2, 1]
    m2_4 = a[2, 2]
    m2_5 = a[2, 3]
    g2 = b[2]
    e2 = c[2]
    m3_0 = a[3, 4]
    m3_1 = a[3, 5]
    m3_2 = a[3, 0]
    m3_3 = a[3, 1]
    m3_4 = a[3, 2]
    m3_5 = a[3, 3]
    g3 = b[3]
    e3 = c[3]
    m4_0 = a[4, 4]
    m4_1 = a[4, 5]
    m4_2 = a[4, 0]
    m4_3 = a[4, 1]
    m4_4 = a[4, 2]
    m4_5 = a[4, 3]
    g4 = b[4]
    e4 = c[4]
    m5_0 = a[5, 4]
    m5_1 = a[5, 5]
    m5_2 = a[5, 0]
    m5_3 = a[5, 1]
    m5_4 = a[5, 2]
    m5_5 = a[5, 3]
    g5 = b[5]
    e5 = c[5]
    best = abs(m0_0.real) + abs(m0_0.imag)
    mag = abs(m1_0.real) + abs(m1_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, m0_5, g0, e0, m1_0, m1_1, m1_2, m1_3, m1_4, m1_5, g1, e1 = (
            m1_0,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
            e1,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            m0_5,
            g0,
            e0,
        )
    mag = abs(m2_0.real) + abs(m2_0.imag)
    if mag > best:
        best = mag
        m0_0, m0_1, m0_2, m0_3, m0_4, m0_5, g0, e0, m2_0, m2_1, m2_2, m2_3, m2_4, m2_5, g2, e2 = (
            m2_0,
            m2_1,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
            e2,
            m0_0,
            m0_1,
            m0_2,
            m0_3,
            m0_4,
            m0_5,
            g0,
            e0,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m0_0.real * m0_0.real + m0_0.imag * m0_0.imag)
    u0 = complex(m0_0.real * dd, -m0_0.imag * dd)
    fac = m1_0 * u0
    m1_2 = m1_2 - fac * m0_2
    m1_3 = m1_3 - fac * m0_3
    m1_4 = m1_4 - fac * m0_4
    m1_5 = m1_5 - fac * m0_5
    g1 = g1 - fac * g0
    e1 = e1 - fac * e0
    fac = m2_0 * u0
    m2_2 = m2_2 - fac * m0_2
    m2_3 = m2_3 - fac * m0_3
    m2_4 = m2_4 - fac * m0_4
    m2_5 = m2_5 - fac * m0_5
    g2 = g2 - fac * g0
    e2 = e2 - fac * e0
    best = abs(m1_1.real) + abs(m1_1.imag)
    mag = abs(m3_1.real) + abs(m3_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, e1, m3_1, m3_2, m3_3, m3_4, m3_5, g3, e3 = (
            m3_1,
            m3_2,
            m3_3,
            m3_4,
            m3_5,
            g3,
            e3,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
            e1,
        )
    mag = abs(m4_1.real) + abs(m4_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, e1, m4_1, m4_2, m4_3, m4_4, m4_5, g4, e4 = (
            m4_1,
            m4_2,
            m4_3,
            m4_4,
            m4_5,
            g4,
            e4,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
            e1,
        )
    mag = abs(m5_1.real) + abs(m5_1.imag)
    if mag > best:
        best = mag
        m1_1, m1_2, m1_3, m1_4, m1_5, g1, e1, m5_1, m5_2, m5_3, m5_4, m5_5, g5, e5 = (
            m5_1,
            m5_2,
            m5_3,
            m5_4,
            m5_5,
            g5,
            e5,
            m1_1,
            m1_2,
            m1_3,
            m1_4,
            m1_5,
            g1,
            e1,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m1_1.real * m1_1.real + m1_1.imag * m1_1.imag)
    u1 = complex(m1_1.real * dd, -m1_1.imag * dd)
    fac = m3_1 * u1
    m3_2 = m3_2 - fac * m1_2
    m3_3 = m3_3 - fac * m1_3
    m3_4 = m3_4 - fac * m1_4
    m3_5 = m3_5 - fac * m1_5
    g3 = g3 - fac * g1
    e3 = e3 - fac * e1
    fac = m4_1 * u1
    m4_2 = m4_2 - fac * m1_2
    m4_3 = m4_3 - fac * m1_3
    m4_4 = m4_4 - fac * m1_4
    m4_5 = m4_5 - fac * m1_5
    g4 = g4 - fac * g1
    e4 = e4 - fac * e1
    fac = m5_1 * u1
    m5_2 = m5_2 - fac * m1_2
    m5_3 = m5_3 - fac * m1_3
    m5_4 = m5_4 - fac * m1_4
    m5_5 = m5_5 - fac * m1_5
    g5 = g5 - fac * g1
    e5 = e5 - fac * e1
    best = abs(m2_2.real) + abs(m2_2.imag)
    mag = abs(m3_2.real) + abs(m3_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, e2, m3_2, m3_3, m3_4, m3_5, g3, e3 = (
            m3_2,
            m3_3,
            m3_4,
            m3_5,
            g3,
            e3,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
            e2,
        )
    mag = abs(m4_2.real) + abs(m4_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, e2, m4_2, m4_3, m4_4, m4_5, g4, e4 = (
            m4_2,
            m4_3,
            m4_4,
            m4_5,
            g4,
            e4,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
            g2,
            e2,
        )
    mag = abs(m5_2.real) + abs(m5_2.imag)
    if mag > best:
        best = mag
        m2_2, m2_3, m2_4, m2_5, g2, e2, m5_2, m5_3, m5_4, m5_5, g5, e5 = (
            m5_2,
            m5_3,
            m5_4,
            m5_5,
            g5,
            e5,
            m2_2,
            m2_3,
            m2_4,
            m2_5,
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
    m3_5 = m3_5 - fac * m2_5
    g3 = g3 - fac * g2
    e3 = e3 - fac * e2
    fac = m4_2 * u2
    m4_3 = m4_3 - fac * m2_3
    m4_4 = m4_4 - fac * m2_4
    m4_5 = m4_5 - fac * m2_5
    g4 = g4 - fac * g2
    e4 = e4 - fac * e2
    fac = m5_2 * u2
    m5_3 = m5_3 - fac * m2_3
    m5_4 = m5_4 - fac * m2_4
    m5_5 = m5_5 - fac * m2_5
    g5 = g5 - fac * g2
    e5 = e5 - fac * e2
    best = abs(m3_3.real) + abs(m3_3.imag)
    mag = abs(m4_3.real) + abs(m4_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, m3_5, g3, e3, m4_3, m4_4, m4_5, g4, e4 = (
            m4_3,
            m4_4,
            m4_5,
            g4,
            e4,
            m3_3,
            m3_4,
            m3_5,
            g3,
            e3,
        )
    mag = abs(m5_3.real) + abs(m5_3.imag)
    if mag > best:
        best = mag
        m3_3, m3_4, m3_5, g3, e3, m5_3, m5_4, m5_5, g5, e5 = (
            m5_3,
            m5_4,
            m5_5,
            g5,
            e5,
            m3_3,
            m3_4,
            m3_5,
            g3,
            e3,
        )
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m3_3.real * m3_3.real + m3_3.imag * m3_3.imag)
    u3 = complex(m3_3.real * dd, -m3_3.imag * dd)
    fac = m4_3 * u3
    m4_4 = m4_4 - fac * m3_4
    m4_5 = m4_5 - fac * m3_5
    g4 = g4 - fac * g3
    e4 = e4 - fac * e3
    fac = m5_3 * u3
    m5_4 = m5_4 - fac * m3_4
    m5_5 = m5_5 - fac * m3_5
    g5 = g5 - fac * g3
    e5 = e5 - fac * e3
    best = abs(m4_4.real) + abs(m4_4.imag)
    mag = abs(m5_4.real) + abs(m5_4.imag)
    if mag > best:
        best = mag
        m4_4, m4_5, g4, e4, m5_4, m5_5, g5, e5 = m5_4, m5_5, g5, e5, m4_4, m4_5, g4, e4
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m4_4.real * m4_4.real + m4_4.imag * m4_4.imag)
    u4 = complex(m4_4.real * dd, -m4_4.imag * dd)
    fac = m5_4 * u4
    m5_5 = m5_5 - fac * m4_5
    g5 = g5 - fac * g4
    e5 = e5 - fac * e4
    best = abs(m5_5.real) + abs(m5_5.imag)
    if best == 0.0 or not np.isfinite(best):
        return False
    dd = 1.0 / (m5_5.real * m5_5.real + m5_5.imag * m5_5.imag)
    u5 = complex(m5_5.real * dd, -m5_5.imag * dd)
    x5 = (g5) * u5
    y5 = (e5) * u5
    x4 = (g4 - m4_5 * x5) * u4
    y4 = (e4 - m4_5 * y5) * u4
    x3 = (g3 - m3_4 * x4 - m3_5 * x5) * u3
    y3 = (e3 - m3_4 * y4 - m3_5 * y5) * u3
    x2 = (g2 - m2_3 * x3 - m2_4 * x4 - m2_5 * x5) * u2
    y2 = (e2 - m2_3 * y3 - m2_4 * y4 - m2_5 * y5) * u2
    x1 = (g1 - m1_2 * x2 - m1_3 * x3 - m1_4 * x4 - m1_5 * x5) * u1
    y1 = (e1 - m1_2 * y2 - m1_3 * y3 - m1_4 * y4 - m1_5 * y5) * u1
    x0 = (g0 - m0_2 * x2 - m0_3 * x3 - m0_4 * x4 - m0_5 * x5) * u0
    y0 = (e0 - m0_2 * y2 - m0_3 * y3 - m0_4 * y4 - m0_5 * y5) * u0
    out[4] = x0
    out[5] = x1
    out[0] = x2
    out[1] = x3
    out[2] = x4
    out[3] = x5
    out2[4] = y0
    out2[5] = y1
    out2[0] = y2
    out2[1] = y3
    out2[2] = y4
    out2[3] = y5
    return True

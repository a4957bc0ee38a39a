# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/section2.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""The minimal problems of the seed's Section 2 orthographic rows (fixed axis, uniform rotation,
three points, force field): coefficient and residual functions of the data, derived and checked
in derivations/section2.py.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def _full(value: np.ndarray | float, shape: tuple[int, ...]) -> np.ndarray:
    """``value`` broadcast to ``shape`` as a new, writable array."""
    out = np.empty(shape, dtype=np.float64)
    out[...] = value
    return out


def _stack(values: tuple[np.ndarray | float, ...], shape: tuple[int, ...]) -> np.ndarray:
    """Broadcast each of ``values`` to ``shape`` and stack them along a new last axis."""
    out = np.empty((*shape, len(values)), dtype=np.float64)
    for k, value in enumerate(values):
        out[..., k] = value
    return out


def _scatter(
    entries: tuple[tuple[int, np.ndarray | float], ...], size: int, shape: tuple[int, ...]
) -> np.ndarray:
    """Zeros of shape (*shape, size) with ``value`` broadcast into column k for each (k, value)."""
    out = np.zeros((*shape, size), dtype=np.float64)
    for k, value in entries:
        out[..., k] = value
    return out


def fixed_axis_cubic(
    v0x: npt.ArrayLike,
    v0y: npt.ArrayLike,
    v1x: npt.ArrayLike,
    v1y: npt.ArrayLike,
    v2x: npt.ArrayLike,
    v2y: npt.ArrayLike,
    v3x: npt.ArrayLike,
    v3y: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fixed axis, four frames: the cubic in W = z0^2 (coefficients highest first) whose roots are
    the squared depths of D = B - A in frame 0; cofactors C_f and k_f = |v_0|^2 - |v_f|^2 (f =
    1, 2, 3) pick each root's depth signs by sum_f C_f (z_f - z_0) = 0, z_f^2 = W + k_f.
    Arguments: image differences v_f = B'_f - A'_f (input units).
    """
    v0x = np.asarray(v0x, dtype=np.float64)
    v0y = np.asarray(v0y, dtype=np.float64)
    v1x = np.asarray(v1x, dtype=np.float64)
    v1y = np.asarray(v1y, dtype=np.float64)
    v2x = np.asarray(v2x, dtype=np.float64)
    v2y = np.asarray(v2y, dtype=np.float64)
    v3x = np.asarray(v3x, dtype=np.float64)
    v3y = np.asarray(v3y, dtype=np.float64)
    _shape = np.broadcast_shapes(
        v0x.shape, v0y.shape, v1x.shape, v1y.shape, v2x.shape, v2y.shape, v3x.shape, v3y.shape
    )

    # Common subexpressions (116).
    _tmp0 = -v0x * v3y + v0y * v3x
    _tmp1 = v2x * v3y
    _tmp2 = v2y * v3x
    _tmp3 = _tmp1 - _tmp2
    _tmp4 = _tmp0 + _tmp3
    _tmp5 = v0x * v2y
    _tmp6 = v0y * v2x
    _tmp7 = _tmp5 - _tmp6
    _tmp8 = _tmp4 + _tmp7
    _tmp9 = v0x * v0x + v0y * v0y
    _tmp10 = _tmp9 - (v1x * v1x) - (v1y * v1y)
    _tmp11 = _tmp9 - (v3x * v3x) - (v3y * v3y)
    _tmp12 = v1x * v2y
    _tmp13 = v1y * v2x
    _tmp14 = _tmp12 - _tmp13
    _tmp15 = v0x * v1y - v0y * v1x
    _tmp16 = _tmp15 - _tmp5 + _tmp6
    _tmp17 = _tmp14 + _tmp16
    _tmp18 = _tmp9 - (v2x * v2x) - (v2y * v2y)
    _tmp19 = v1x * v3y
    _tmp20 = v1y * v3x
    _tmp21 = _tmp19 - _tmp20
    _tmp22 = _tmp0 + _tmp21
    _tmp23 = _tmp15 + _tmp22
    _tmp24 = _tmp17 * _tmp23
    _tmp25 = _tmp17 * _tmp17
    _tmp26 = _tmp10 * _tmp10
    _tmp27 = _tmp8**6
    _tmp28 = _tmp26 * _tmp27
    _tmp29 = _tmp25 * _tmp28
    _tmp30 = _tmp17 * _tmp17 * _tmp17 * _tmp17
    _tmp31 = _tmp8 * _tmp8 * _tmp8 * _tmp8
    _tmp32 = _tmp26 * _tmp31
    _tmp33 = _tmp23 * _tmp23
    _tmp34 = _tmp28 * _tmp33
    _tmp35 = _tmp23 * _tmp23 * _tmp23 * _tmp23
    _tmp36 = _tmp18 * _tmp18
    _tmp37 = _tmp23**6
    _tmp38 = _tmp36 * _tmp37
    _tmp39 = _tmp25 * _tmp38
    _tmp40 = _tmp35 * _tmp36
    _tmp41 = _tmp8 * _tmp8
    _tmp42 = _tmp38 * _tmp41
    _tmp43 = _tmp11 * _tmp11
    _tmp44 = _tmp30 * _tmp43
    _tmp45 = _tmp17**6
    _tmp46 = _tmp43 * _tmp45
    _tmp47 = _tmp33 * _tmp46
    _tmp48 = _tmp41 * _tmp46
    _tmp49 = _tmp8**5
    _tmp50 = _tmp26 * _tmp49
    _tmp51 = _tmp17 * _tmp17 * _tmp17
    _tmp52 = 2 * _tmp51
    _tmp53 = _tmp23 * _tmp23 * _tmp23
    _tmp54 = 2 * _tmp53
    _tmp55 = _tmp23**5
    _tmp56 = _tmp36 * _tmp55
    _tmp57 = _tmp8 * _tmp8 * _tmp8
    _tmp58 = 2 * _tmp57
    _tmp59 = _tmp17**5
    _tmp60 = _tmp43 * _tmp59
    _tmp61 = _tmp10 * _tmp18
    _tmp62 = _tmp49 * _tmp61
    _tmp63 = 4 * _tmp31
    _tmp64 = _tmp55 * _tmp61
    _tmp65 = _tmp10 * _tmp11
    _tmp66 = _tmp49 * _tmp65
    _tmp67 = 4 * _tmp30
    _tmp68 = _tmp59 * _tmp65
    _tmp69 = _tmp11 * _tmp18
    _tmp70 = _tmp55 * _tmp69
    _tmp71 = _tmp35 * _tmp69
    _tmp72 = _tmp59 * _tmp69
    _tmp73 = _tmp17 * _tmp8
    _tmp74 = 5 * _tmp33
    _tmp75 = _tmp17 * _tmp32
    _tmp76 = 5 * _tmp25
    _tmp77 = _tmp23 * _tmp50
    _tmp78 = _tmp23 * _tmp32
    _tmp79 = 5 * _tmp41
    _tmp80 = _tmp17 * _tmp56
    _tmp81 = _tmp56 * _tmp8
    _tmp82 = _tmp23 * _tmp44
    _tmp83 = _tmp44 * _tmp8
    _tmp84 = _tmp23 * _tmp60
    _tmp85 = 3 * _tmp25
    _tmp86 = _tmp33 * _tmp41
    _tmp87 = 2 * _tmp33
    _tmp88 = _tmp18 * _tmp53
    _tmp89 = _tmp10 * _tmp63
    _tmp90 = _tmp10 * _tmp57
    _tmp91 = 4 * _tmp18 * _tmp35
    _tmp92 = 2 * _tmp41
    _tmp93 = 2 * _tmp25
    _tmp94 = _tmp11 * _tmp51
    _tmp95 = _tmp11 * _tmp67
    _tmp96 = _tmp18 * _tmp54
    _tmp97 = _tmp18 * _tmp33
    _tmp98 = 4 * _tmp97
    _tmp99 = _tmp10 * _tmp41
    _tmp100 = 4 * _tmp99
    _tmp101 = 2 * _tmp61 * _tmp86
    _tmp102 = _tmp11 * _tmp25
    _tmp103 = 4 * _tmp102
    _tmp104 = _tmp41 * _tmp65 * _tmp93
    _tmp105 = _tmp33 * _tmp69
    _tmp106 = _tmp105 * _tmp93
    _tmp107 = _tmp10 * _tmp10 * _tmp10
    _tmp108 = _tmp8**7
    _tmp109 = _tmp11 * _tmp11 * _tmp11
    _tmp110 = _tmp17**7
    _tmp111 = _tmp18 * _tmp18 * _tmp18
    _tmp112 = _tmp23**7
    _tmp113 = _tmp107 * _tmp27
    _tmp114 = _tmp111 * _tmp37
    _tmp115 = _tmp109 * _tmp45

    # Outputs.
    coefficients = _stack(
        (
            64
            * _tmp24
            * _tmp8
            * (_tmp14 + _tmp15 + _tmp4)
            * (_tmp10 * _tmp8 + _tmp11 * _tmp17 - _tmp18 * _tmp23)
            * (-_tmp1 + _tmp16 + _tmp2 + _tmp21)
            * (-_tmp12 + _tmp13 + _tmp22 + _tmp7)
            * (_tmp14 - _tmp19 + _tmp20 + _tmp3),
            16 * _tmp100 * _tmp51 * _tmp88
            + 16 * _tmp100 * _tmp53 * _tmp94
            - 16 * _tmp101 * _tmp30
            + 16 * _tmp103 * _tmp53 * _tmp90
            + 16 * _tmp103 * _tmp57 * _tmp88
            - 16 * _tmp104 * _tmp35
            - 16 * _tmp106 * _tmp31
            - 16 * _tmp11 * _tmp33 * _tmp52 * _tmp90
            + 16 * _tmp17 * _tmp40 * _tmp58
            + 16 * _tmp17 * _tmp50 * _tmp74
            + 16 * _tmp17 * _tmp62 * _tmp87
            - 16 * _tmp17 * _tmp64 * _tmp92
            - 16 * _tmp17 * _tmp88 * _tmp89
            + 16 * _tmp17 * _tmp90 * _tmp91
            - 48 * _tmp23 * _tmp46 * _tmp8
            - 16 * _tmp23 * _tmp66 * _tmp93
            - 16 * _tmp23 * _tmp68 * _tmp92
            - 16 * _tmp23 * _tmp89 * _tmp94
            - 16 * _tmp23 * _tmp90 * _tmp95
            - 48 * _tmp24 * _tmp28
            + 16 * _tmp25 * _tmp90 * _tmp96
            + 16 * _tmp29
            + 16 * _tmp30 * _tmp32
            + 16 * _tmp30 * _tmp40
            + 16 * _tmp31 * _tmp40
            + 16 * _tmp31 * _tmp44
            + 16 * _tmp31 * _tmp65 * _tmp67
            + 16 * _tmp32 * _tmp33 * _tmp85
            + 16 * _tmp32 * _tmp35
            + 16 * _tmp34
            + 16 * _tmp35 * _tmp44
            + 16 * _tmp35 * _tmp61 * _tmp63
            + 48 * _tmp38 * _tmp73
            + 16 * _tmp39
            + 16 * _tmp40 * _tmp41 * _tmp85
            + 16 * _tmp40 * _tmp52 * _tmp8
            + 16 * _tmp41 * _tmp94 * _tmp96
            + 16 * _tmp42
            + 48 * _tmp44 * _tmp86
            + 16 * _tmp47
            + 16 * _tmp48
            + 16 * _tmp50 * _tmp52
            - 16 * _tmp50 * _tmp54
            - 16 * _tmp51 * _tmp90 * _tmp98
            - 16 * _tmp52 * _tmp56
            + 16 * _tmp52 * _tmp66
            - 16 * _tmp52 * _tmp70
            - 16 * _tmp52 * _tmp78
            - 16 * _tmp54 * _tmp60
            - 16 * _tmp54 * _tmp62
            - 16 * _tmp54 * _tmp72
            - 16 * _tmp54 * _tmp75
            - 16 * _tmp54 * _tmp83
            - 16 * _tmp56 * _tmp58
            - 16 * _tmp57 * _tmp94 * _tmp98
            + 16 * _tmp58 * _tmp60
            - 16 * _tmp58 * _tmp64
            + 16 * _tmp58 * _tmp68
            - 16 * _tmp58 * _tmp82
            + 16 * _tmp60 * _tmp74 * _tmp8
            + 16 * _tmp67 * _tmp71
            - 16 * _tmp70 * _tmp8 * _tmp93
            + 16 * _tmp72 * _tmp8 * _tmp87
            - 16 * _tmp76 * _tmp77
            - 16 * _tmp76 * _tmp81
            - 16 * _tmp79 * _tmp80
            - 16 * _tmp79 * _tmp84
            - 16 * _tmp8 * _tmp88 * _tmp95
            + 16 * _tmp8 * _tmp91 * _tmp94,
            80 * _tmp10 * _tmp11 * _tmp18 * _tmp25 * _tmp53 * _tmp57
            + 80 * _tmp10 * _tmp11 * _tmp18 * _tmp41 * _tmp51 * _tmp53
            + 8 * _tmp10 * _tmp17 * _tmp35 * _tmp36 * _tmp57
            + 8 * _tmp10 * _tmp25 * _tmp35 * _tmp36 * _tmp41
            + 16 * _tmp10 * _tmp30 * _tmp31 * _tmp43
            + 8 * _tmp10 * _tmp30 * _tmp33 * _tmp41 * _tmp43
            + 16 * _tmp10 * _tmp31 * _tmp35 * _tmp36
            - 8 * _tmp10 * _tmp42
            + 8 * _tmp10 * _tmp43 * _tmp57 * _tmp59
            - 8 * _tmp10 * _tmp48
            - 8 * _tmp10 * _tmp67 * _tmp69 * _tmp86
            - 8 * _tmp100 * _tmp25 * _tmp71
            - 8 * _tmp102 * _tmp77
            - 8 * _tmp102 * _tmp81
            - 8 * _tmp105 * _tmp25 * _tmp89
            - 8 * _tmp107 * _tmp108 * _tmp17
            + 8 * _tmp107 * _tmp108 * _tmp23
            + 8 * _tmp107 * _tmp17 * _tmp23 * _tmp27
            + 8 * _tmp109 * _tmp110 * _tmp23
            - 8 * _tmp109 * _tmp110 * _tmp8
            + 8 * _tmp109 * _tmp23 * _tmp45 * _tmp8
            + 8 * _tmp11 * _tmp25 * _tmp26 * _tmp31 * _tmp33
            + 8 * _tmp11 * _tmp25 * _tmp35 * _tmp36 * _tmp41
            + 16 * _tmp11 * _tmp26 * _tmp30 * _tmp31
            + 8 * _tmp11 * _tmp26 * _tmp49 * _tmp51
            - 8 * _tmp11 * _tmp29
            + 16 * _tmp11 * _tmp30 * _tmp35 * _tmp36
            + 8 * _tmp11 * _tmp35 * _tmp36 * _tmp51 * _tmp8
            - 8 * _tmp11 * _tmp39
            + 8 * _tmp111 * _tmp112 * _tmp17
            + 8 * _tmp111 * _tmp112 * _tmp8
            - 8 * _tmp113 * _tmp25
            - 8 * _tmp113 * _tmp33
            - 8 * _tmp114 * _tmp25
            - 8 * _tmp114 * _tmp41
            - 8 * _tmp114 * _tmp73
            - 8 * _tmp115 * _tmp33
            - 8 * _tmp115 * _tmp41
            + 8 * _tmp17 * _tmp18 * _tmp26 * _tmp33 * _tmp49
            + 8 * _tmp18 * _tmp25 * _tmp26 * _tmp31 * _tmp33
            + 16 * _tmp18 * _tmp26 * _tmp31 * _tmp35
            + 8 * _tmp18 * _tmp30 * _tmp33 * _tmp41 * _tmp43
            + 16 * _tmp18 * _tmp30 * _tmp35 * _tmp43
            + 8 * _tmp18 * _tmp33 * _tmp43 * _tmp59 * _tmp8
            - 8 * _tmp18 * _tmp34
            - 8 * _tmp18 * _tmp47
            - 8 * _tmp50 * _tmp88
            - 8 * _tmp56 * _tmp90
            - 8 * _tmp56 * _tmp94
            - 8 * _tmp60 * _tmp88
            - 8 * _tmp75 * _tmp88
            - 8 * _tmp78 * _tmp94
            - 8 * _tmp80 * _tmp99
            - 8 * _tmp82 * _tmp90
            - 8 * _tmp83 * _tmp88
            - 8 * _tmp84 * _tmp99
            - 80 * _tmp90 * _tmp94 * _tmp97,
            (-_tmp101 - _tmp104 - _tmp106 + _tmp32 + _tmp40 + _tmp44)
            * (-_tmp101 - _tmp104 - _tmp106 + _tmp32 + _tmp40 + _tmp44),
        ),
        _shape,
    )
    cofactors = _stack(
        (
            _tmp8,
            -_tmp23,
            _tmp17,
        ),
        _shape,
    )
    k = _stack(
        (
            _tmp10,
            _tmp18,
            _tmp11,
        ),
        _shape,
    )
    return coefficients, cofactors, k


def free_3pt_quadratic(
    v0x: npt.ArrayLike,
    v0y: npt.ArrayLike,
    v1x: npt.ArrayLike,
    v1y: npt.ArrayLike,
    v2x: npt.ArrayLike,
    v2y: npt.ArrayLike,
    u0x: npt.ArrayLike,
    u0y: npt.ArrayLike,
    u1x: npt.ArrayLike,
    u1y: npt.ArrayLike,
    u2x: npt.ArrayLike,
    u2y: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Three points, three frames: the quadratic in M = z0 e0 (coefficients highest first); P =
    z0^2 = (pm M + p0) / det and Q = e0^2 = (qm M + q0) / det from linear = (pm, p0, qm, q0,
    det); abc = (a_1, a_2, b_1, b_2, c_1, c_2) give the later frames' depths (z_f^2 = P + a_f,
    e_f^2 = Q + b_f, z_f e_f = M + c_f).  Arguments: v_f = B'_f - A'_f, then u_f = C'_f - A'_f
    (input units).
    """
    v0x = np.asarray(v0x, dtype=np.float64)
    v0y = np.asarray(v0y, dtype=np.float64)
    v1x = np.asarray(v1x, dtype=np.float64)
    v1y = np.asarray(v1y, dtype=np.float64)
    v2x = np.asarray(v2x, dtype=np.float64)
    v2y = np.asarray(v2y, dtype=np.float64)
    u0x = np.asarray(u0x, dtype=np.float64)
    u0y = np.asarray(u0y, dtype=np.float64)
    u1x = np.asarray(u1x, dtype=np.float64)
    u1y = np.asarray(u1y, dtype=np.float64)
    u2x = np.asarray(u2x, dtype=np.float64)
    u2y = np.asarray(u2y, dtype=np.float64)
    _shape = np.broadcast_shapes(
        v0x.shape,
        v0y.shape,
        v1x.shape,
        v1y.shape,
        v2x.shape,
        v2y.shape,
        u0x.shape,
        u0y.shape,
        u1x.shape,
        u1y.shape,
        u2x.shape,
        u2y.shape,
    )

    # Common subexpressions (16).
    _tmp0 = u0x * u0x + u0y * u0y
    _tmp1 = _tmp0 - (u1x * u1x) - (u1y * u1y)
    _tmp2 = v0x * v0x + v0y * v0y
    _tmp3 = _tmp2 - (v2x * v2x) - (v2y * v2y)
    _tmp4 = _tmp0 - (u2x * u2x) - (u2y * u2y)
    _tmp5 = _tmp2 - (v1x * v1x) - (v1y * v1y)
    _tmp6 = _tmp1 * _tmp3 - _tmp4 * _tmp5
    _tmp7 = u0x * v0x + u0y * v0y
    _tmp8 = _tmp7 - u2x * v2x - u2y * v2y
    _tmp9 = _tmp7 - u1x * v1x - u1y * v1y
    _tmp10 = _tmp1 * _tmp8 - _tmp4 * _tmp9
    _tmp11 = -_tmp3 * _tmp9 + _tmp5 * _tmp8
    _tmp12 = _tmp1 * _tmp5 - (_tmp9 * _tmp9)
    _tmp13 = _tmp3 * _tmp4 - (_tmp8 * _tmp8)
    _tmp14 = -_tmp12 * _tmp3 + _tmp13 * _tmp5
    _tmp15 = -_tmp1 * _tmp13 + _tmp12 * _tmp4

    # Outputs.
    coefficients = _stack(
        (
            4 * _tmp10 * _tmp11 + _tmp6 * _tmp6,
            -2 * _tmp10 * _tmp14 - 2 * _tmp11 * (_tmp1 * _tmp13 - _tmp12 * _tmp4),
            -_tmp14 * _tmp15,
        ),
        _shape,
    )
    linear = _stack(
        (
            -2 * _tmp11,
            _tmp14,
            2 * _tmp10,
            _tmp15,
            _tmp6,
        ),
        _shape,
    )
    abc = _stack(
        (
            _tmp5,
            _tmp3,
            _tmp1,
            _tmp4,
            _tmp9,
            _tmp8,
        ),
        _shape,
    )
    return coefficients, linear, abc


def uniform_rotation_angles(
    z0: npt.ArrayLike,
    s1: npt.ArrayLike,
    s2: npt.ArrayLike,
    v0x: npt.ArrayLike,
    v0y: npt.ArrayLike,
    v1x: npt.ArrayLike,
    v1y: npt.ArrayLike,
    v2x: npt.ArrayLike,
    v2y: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Uniform rotation, three frames, at a trial depth z0 of D = B - A in frame 0 and depth signs
    s1, s2 of frames 1, 2: atan2 arguments (y1, x1, y21, x21) of the rotation angle from frame 0
    to 1 and from 1 to 2 about axis = (D_1 - D_0) x (D_2 - D_0) (not normalised).  Arguments:
    z0, s1, s2, v_f = B'_f - A'_f.
    """
    z0 = np.asarray(z0, dtype=np.float64)
    s1 = np.asarray(s1, dtype=np.float64)
    s2 = np.asarray(s2, dtype=np.float64)
    v0x = np.asarray(v0x, dtype=np.float64)
    v0y = np.asarray(v0y, dtype=np.float64)
    v1x = np.asarray(v1x, dtype=np.float64)
    v1y = np.asarray(v1y, dtype=np.float64)
    v2x = np.asarray(v2x, dtype=np.float64)
    v2y = np.asarray(v2y, dtype=np.float64)
    _shape = np.broadcast_shapes(
        z0.shape,
        s1.shape,
        s2.shape,
        v0x.shape,
        v0y.shape,
        v1x.shape,
        v1y.shape,
        v2x.shape,
        v2y.shape,
    )

    # Common subexpressions (20).
    _tmp0 = v0x - v1x
    _tmp1 = v0y - v2y
    _tmp2 = v0x - v2x
    _tmp3 = v0y - v1y
    _tmp4 = _tmp0 * _tmp1 - _tmp2 * _tmp3
    _tmp5 = _tmp4 * _tmp4
    _tmp6 = -z0
    _tmp7 = v0x * v0x + v0y * v0y + z0 * z0
    _tmp8 = s2 * np.sqrt(_tmp7 - (v2x * v2x) - (v2y * v2y))
    _tmp9 = _tmp6 + _tmp8
    _tmp10 = s1 * np.sqrt(_tmp7 - (v1x * v1x) - (v1y * v1y))
    _tmp11 = _tmp10 + _tmp6
    _tmp12 = _tmp0 * _tmp9 - _tmp11 * _tmp2
    _tmp13 = -_tmp12
    _tmp14 = -_tmp1 * _tmp11 + _tmp3 * _tmp9
    _tmp15 = np.sqrt(_tmp13 * _tmp13 + _tmp14 * _tmp14 + _tmp5)
    _tmp16 = -_tmp0 * _tmp9 + _tmp11 * _tmp2
    _tmp17 = -_tmp14
    _tmp18 = _tmp16 * _tmp16 + _tmp17 * _tmp17 + _tmp5
    _tmp19 = _tmp10 * _tmp4 - _tmp16 * v1y + _tmp17 * v1x

    # Outputs.
    atan2_args = _stack(
        (
            _tmp15
            * (
                _tmp13 * (_tmp10 * v0x - v1x * z0)
                - _tmp14 * (_tmp10 * v0y - v1y * z0)
                + _tmp4 * (v0x * v1y - v0y * v1x)
            ),
            _tmp18 * (_tmp10 * z0 + v0x * v1x + v0y * v1y)
            - _tmp19 * (-_tmp16 * v0y + _tmp17 * v0x + _tmp4 * z0),
            -_tmp15
            * (
                _tmp16 * (_tmp10 * v2x - _tmp8 * v1x)
                + _tmp17 * (_tmp10 * v2y - _tmp8 * v1y)
                - _tmp4 * (v1x * v2y - v1y * v2x)
            ),
            _tmp18 * (_tmp10 * _tmp8 + v1x * v2x + v1y * v2y)
            - _tmp19 * (-_tmp16 * v2y + _tmp17 * v2x + _tmp4 * _tmp8),
        ),
        _shape,
    )
    axis = _stack(
        (
            _tmp17,
            _tmp12,
            _tmp4,
        ),
        _shape,
    )
    return atan2_args, axis


def force_field_residual(
    ax: npt.ArrayLike,
    ay: npt.ArrayLike,
    bx: npt.ArrayLike,
    by: npt.ArrayLike,
    t: npt.ArrayLike,
    g0x: npt.ArrayLike,
    g0y: npt.ArrayLike,
    g1x: npt.ArrayLike,
    g1y: npt.ArrayLike,
    g2x: npt.ArrayLike,
    g2y: npt.ArrayLike,
    aa: npt.ArrayLike,
    bb: npt.ArrayLike,
    ab: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Force field, one frame: (aa - |p|^2)(bb - |q|^2) - (ab - p.q)^2 with p = A' - xy(G), q = B'
    - xy(G), xy(G) = g0 + g1 t + g2 t^2 / 2, and its gradient in (g0x, g0y, g1x, g1y, g2x, g2y,
    aa, bb, ab); zero exactly when the frame's depths exist.
    """
    ax = np.asarray(ax, dtype=np.float64)
    ay = np.asarray(ay, dtype=np.float64)
    bx = np.asarray(bx, dtype=np.float64)
    by = np.asarray(by, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64)
    g0x = np.asarray(g0x, dtype=np.float64)
    g0y = np.asarray(g0y, dtype=np.float64)
    g1x = np.asarray(g1x, dtype=np.float64)
    g1y = np.asarray(g1y, dtype=np.float64)
    g2x = np.asarray(g2x, dtype=np.float64)
    g2y = np.asarray(g2y, dtype=np.float64)
    aa = np.asarray(aa, dtype=np.float64)
    bb = np.asarray(bb, dtype=np.float64)
    ab = np.asarray(ab, dtype=np.float64)
    _shape = np.broadcast_shapes(
        ax.shape,
        ay.shape,
        bx.shape,
        by.shape,
        t.shape,
        g0x.shape,
        g0y.shape,
        g1x.shape,
        g1y.shape,
        g2x.shape,
        g2y.shape,
        aa.shape,
        bb.shape,
        ab.shape,
    )

    # Common subexpressions (22).
    _tmp0 = t * t
    _tmp1 = 2 * t
    _tmp2 = _tmp0 * g2x + _tmp1 * g1x + 2 * g0x
    _tmp3 = _tmp2 - 2 * ax
    _tmp4 = _tmp2 - 2 * bx
    _tmp5 = _tmp3 * _tmp4
    _tmp6 = _tmp0 * g2y + _tmp1 * g1y + 2 * g0y
    _tmp7 = _tmp6 - 2 * ay
    _tmp8 = _tmp6 - 2 * by
    _tmp9 = _tmp7 * _tmp8
    _tmp10 = _tmp5 + _tmp9 - 4 * ab
    _tmp11 = _tmp3 * _tmp3
    _tmp12 = _tmp7 * _tmp7
    _tmp13 = _tmp11 + _tmp12 - 4 * aa
    _tmp14 = _tmp4 * _tmp4
    _tmp15 = _tmp8 * _tmp8
    _tmp16 = _tmp14 + _tmp15 - 4 * bb
    _tmp17 = 2 * _tmp10
    _tmp18 = _tmp13 * _tmp4 + _tmp16 * _tmp3 - _tmp17 * (_tmp2 - ax - bx)
    _tmp19 = _tmp13 * _tmp8 + _tmp16 * _tmp7 - _tmp17 * (_tmp6 - ay - by)
    _tmp20 = (1 / 4) * t
    _tmp21 = (1 / 8) * _tmp0

    # Outputs.
    residual = _full(-1 / 16 * (_tmp10 * _tmp10) + (1 / 16) * _tmp13 * _tmp16, _shape)
    gradient = _stack(
        (
            (1 / 4) * _tmp18,
            (1 / 4) * _tmp19,
            _tmp18 * _tmp20,
            _tmp19 * _tmp20,
            _tmp18 * _tmp21,
            _tmp19 * _tmp21,
            -1 / 4 * _tmp14 - 1 / 4 * _tmp15 + bb,
            -1 / 4 * _tmp11 - 1 / 4 * _tmp12 + aa,
            (1 / 2) * _tmp5 + (1 / 2) * _tmp9 - 2 * ab,
        ),
        _shape,
    )
    return residual, gradient

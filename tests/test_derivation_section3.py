"""Section 3 equations against a direct 3-D construction written here with NumPy.

The construction below is independent of ``derivations.construction``: it rotates the points and
the tangent *directions* with R = R_y(tau) R_x(delta) (CONVENTIONS.md) and reads d', e' from the
projected tangent directions (d' = -c' u_y/u_x, e' = c' u_y/u_x), not from line intersections.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from derivations import section3
from derivations import symbols as s

N = 300


def rot_x(a: float) -> np.ndarray:
    return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])


def rot_y(a: float) -> np.ndarray:
    return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])


def construction(seed: int = 1234, n: int = N) -> list[dict[sp.Symbol, float]]:
    """Random shapes and poses (both signs of tau) and every quantity of section 3."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        c = rng.uniform(20, 300)
        alpha, beta = np.radians(rng.uniform(3, 87, 2))
        phi, delta = np.radians(rng.uniform(-180, 180, 2))
        tau = np.radians(rng.uniform(3, 85)) * (1 if len(out) % 2 else -1)
        rd, r = rot_x(delta), rot_y(tau) @ rot_x(delta)
        b3 = r @ np.array([c, 0.0, 0.0])
        t_b = r @ np.array([-np.cos(alpha), np.sin(alpha), 0.0])
        t_a = r @ np.array([np.cos(beta), np.sin(beta) * np.cos(phi), np.sin(beta) * np.sin(phi)])
        if min(abs(t_b[0]), abs(t_a[0])) < 1e-3:
            continue  # projected tangent parallel to l1: d' or e' at infinity
        cp = b3[0]
        assert abs(b3[1]) < 1e-9 and cp > 0
        s_point = np.array([0.0, c * np.tan(alpha), 0.0])  # tangent at B meets x = 0
        s_delta = rd @ s_point
        s_rot = r @ s_point
        dp = -cp * t_b[1] / t_b[0]
        ep = cp * t_a[1] / t_a[0]
        out.append(
            {
                s.c: c,
                s.tan_alpha: np.tan(alpha),
                s.tan_beta: np.tan(beta),
                s.phi: phi,
                s.tan_phi: np.tan(phi),
                s.delta: delta,
                s.tau: tau,
                s.sin_tau: np.sin(tau),
                s.cp: cp,
                s.dp: dp,
                s.ep: ep,
                s.AS: s_point[1],
                s.AS_p: s_delta[1],
                s.SS_p: s_delta[2],
                s.AB: c,
                s.AB_p: cp,
                s.S_pS_pp: s_rot[0],
                s.AD_p: dp,
                s.D_pS_p: s_delta[1] - dp,
            }
        )
    return out


FRAMES = construction()


def relative(lhs: sp.Expr, rhs: sp.Expr, modulus: sp.Expr | None = None) -> np.ndarray:
    """|lhs - rhs| / (1 + |lhs| + |rhs|) on FRAMES (float64)."""
    lhs, rhs = section3.expand_aux(lhs), section3.expand_aux(rhs)
    free = sorted(lhs.free_symbols | rhs.free_symbols, key=str)
    f = sp.lambdify(free, [lhs, rhs], modules="numpy")
    vals = [np.array([fr[k] for fr in FRAMES]) for k in free]
    a, b = (np.asarray(v, dtype=float) * np.ones(len(FRAMES)) for v in f(*vals))
    d = a - b
    if modulus is not None:
        d = (d + np.pi) % (2 * np.pi) - np.pi
    return np.abs(d) / (1 + np.abs(a) + np.abs(b))


@pytest.mark.parametrize("eq", section3.equations(), ids=lambda e: e.number)
def test_equation_holds_on_construction(eq: section3.Equation) -> None:
    r = relative(eq.lhs, eq.rhs, eq.modulus)
    assert np.median(r) < 1e-11, eq.number
    assert np.max(r) < 1e-6, eq.number  # float64 near-degenerate frames


@pytest.mark.parametrize("eq", [e for e in section3.equations() if e.check == "symbolic"],
                         ids=lambda e: e.number)  # fmt: skip
def test_symbolic_checks(eq: section3.Equation) -> None:
    assert section3.check_symbolic(eq)


def test_numeric_checks_pass() -> None:
    for number, kind, result in section3.check_results():
        if kind == "numeric":
            assert result < 1e-20, number


def test_both_signs_of_tau_present() -> None:
    st = np.array([fr[s.sin_tau] for fr in FRAMES])
    assert (st > 0).sum() > N // 3 and (st < 0).sum() > N // 3


def test_paper_sign_of_10_fails() -> None:
    """Negative control: the printed sign of delta in (10) does not hold under CONVENTIONS."""
    p1, q1 = section3.aux_p1(), section3.aux_q1()
    r = relative(p1 * sp.sin(s.delta), q1 * sp.cos(s.delta) - s.dp * s.cp)
    assert np.median(r) > 1e-3


def test_printed_12_fails_derived_holds() -> None:
    """(12) with phi + omega2 - omega1 (any branch) fails; phi + omega1 + omega2 holds."""
    u1, u2, w1, w2 = s.u1, s.u2, s.omega1, s.omega2
    rhs = (1 - u1**2) * (1 - u2**2)
    bad = relative((sp.cos(s.phi + w2 - w1) - u1 * u2) ** 2, rhs)
    good = relative((sp.cos(s.phi + w1 + w2) - u1 * u2) ** 2, rhs)
    assert np.median(bad) > 1e-3
    assert np.max(good) < 1e-8


# ----------------------------------------------------------------------------- generated API


SIGNATURES = {
    "aux_terms": (("c", "tan_alpha", "tan_beta", "cp", "dp", "ep", "sin_tau"),
                  ("p1", "q1", "p2", "q2")),
    "residual_10": (("c", "tan_alpha", "cp", "dp", "delta", "sin_tau"), ("residual",)),
    "residual_11": (("c", "tan_beta", "phi", "cp", "ep", "delta", "sin_tau"), ("residual",)),
    "residual_12": (("c", "tan_alpha", "tan_beta", "phi", "cp", "dp", "ep", "sin_tau"),
                    ("residual",)),
    "pose_from_shape": (("c", "tan_alpha", "tan_beta", "phi", "cp", "dp", "ep", "sin_tau"),
                        ("cos_delta", "sin_delta")),
    "predicted_d_e": (("c", "tan_alpha", "tan_beta", "phi", "cp", "delta", "sin_tau"),
                      ("d", "e")),
}  # fmt: skip


def test_generated_function_signatures() -> None:
    specs = section3.generated_functions()
    assert [f.name for f in specs] == list(SIGNATURES)
    for f in specs:
        args, outs = SIGNATURES[f.name]
        assert tuple(str(a) for a in f.args) == args
        assert tuple(f.outputs) == outs
        for expr in f.outputs.values():
            assert expr.free_symbols <= set(f.args)


def _call(name: str) -> list[np.ndarray]:
    spec = next(f for f in section3.generated_functions() if f.name == name)
    fn = sp.lambdify(spec.args, list(spec.outputs.values()), modules="numpy")
    vals = [np.array([fr[a] for fr in FRAMES]) for a in spec.args]
    return [np.asarray(v, dtype=float) * np.ones(len(FRAMES)) for v in fn(*vals)]


def test_generated_functions_on_construction() -> None:
    p1, q1, p2, q2 = _call("aux_terms")
    fr = {k: np.array([f[k] for f in FRAMES]) for k in FRAMES[0]}
    assert np.allclose(p1, fr[s.dp] * fr[s.c] * fr[s.tan_alpha] * fr[s.sin_tau])
    assert np.allclose(q2, fr[s.cp] * fr[s.c] * fr[s.tan_beta])
    scale = (
        fr[s.c] ** 2
        * (1 + np.abs(fr[s.dp]) + np.abs(fr[s.ep]))
        * (1 + fr[s.tan_alpha] + fr[s.tan_beta])
    )
    (r10,) = _call("residual_10")
    (r11,) = _call("residual_11")
    (r12,) = _call("residual_12")
    assert np.max(np.abs(r10) / scale) < 1e-10
    assert np.max(np.abs(r11) / scale) < 1e-10
    assert np.max(np.abs(r12)) < 1e-8
    cd, sd = _call("pose_from_shape")
    assert np.median(np.hypot(cd - np.cos(fr[s.delta]), sd - np.sin(fr[s.delta]))) < 1e-10
    d, e = _call("predicted_d_e")
    assert np.max(np.abs(d - fr[s.dp]) / (1 + np.abs(fr[s.dp]))) < 1e-8
    assert np.max(np.abs(e - fr[s.ep]) / (1 + np.abs(fr[s.ep]))) < 1e-8


def test_residual_12_detects_wrong_shape() -> None:
    spec = next(f for f in section3.generated_functions() if f.name == "residual_12")
    fn = sp.lambdify(spec.args, spec.outputs["residual"], modules="numpy")
    fr = {k: np.array([f[k] for f in FRAMES]) for k in FRAMES[0]}
    args = [fr[a] for a in spec.args]
    args[0] = args[0] * 1.05  # c 5 % off
    assert np.median(np.abs(fn(*args))) > 1e-4

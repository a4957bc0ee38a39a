"""Section 3 of the paper, equation by equation, checked against the 3-D construction.

Each equation is a small typed function returning an :class:`Equation` (number as printed in the
paper, both sides as SymPy expressions, how it was obtained, and how it is checked).  The check is
against :mod:`derivations.construction`: *symbolic* means ``simplify(lhs - rhs) == 0`` after
substituting the construction's values; *numeric* means ``max |lhs - rhs|`` at seeded random
configurations (both signs of tau), evaluated with mpmath at 30 digits.

Sign conventions are those of ``docs/CONVENTIONS.md``: R = R_y(tau) R_x(delta), d' = -c' u_y/u_x,
e' = c' u_y/u_x, sin_tau signed.  With them the paper's (7) carries a minus sign when the lengths
are signed, so (10) reads q1 cos(delta) + p1 sin(delta) = d'c' (the paper prints the opposite sign
of delta) and the frame-free relation (12) involves phi + omega1 + omega2 (the paper prints
phi + omega2 - omega1; see derivations.errata).

Lengths in input units (pixels), angles in radians.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import mpmath
import sympy as sp

from derivations import symbols as s
from derivations.codegen.spec import FunctionSpec
from derivations.construction import random_configurations, substitutions

MODULE_DOC = (
    "Per-frame equations of section 3 of the paper (aux terms, (10), (11), (12), the pose from "
    "the shape, the predicted d', e'), derived and checked in derivations/section3.py."
)

N_RANDOM = 200  # random configurations of every numeric check
MP_DPS = 30  # mpmath working precision of the numeric checks


@dataclass(frozen=True)
class Equation:
    """One numbered equation of section 3.

    ``modulus`` is 2*pi for angle equations that hold modulo a full turn (the residual is wrapped
    to (-pi, pi] before it is compared with zero).  ``check`` is ``"symbolic"`` or ``"numeric"``.
    """

    number: str
    lhs: sp.Expr
    rhs: sp.Expr
    how_obtained: str
    check: str
    modulus: sp.Expr | None = None

    @property
    def residual(self) -> sp.Expr:
        return self.lhs - self.rhs


# --------------------------------------------------------------------------------------------
# auxiliary terms (paper: "auxiliary (frame) terms, containing only frame knowns and global
# unknowns"), with the sign convention of CONVENTIONS.md: sin_tau signed
# --------------------------------------------------------------------------------------------


def aux_p1() -> sp.Expr:
    """p1 = d' c tan(alpha) sin(tau)   (paper: sin(arccos(c'/c)), i.e. one sign of tau only)."""
    return s.dp * s.c * s.tan_alpha * s.sin_tau


def aux_q1() -> sp.Expr:
    """q1 = c' c tan(alpha)."""
    return s.cp * s.c * s.tan_alpha


def aux_p2() -> sp.Expr:
    """p2 = e' c tan(beta) sin(tau)   (the paper prints tan(alpha) here: erratum)."""
    return s.ep * s.c * s.tan_beta * s.sin_tau


def aux_q2() -> sp.Expr:
    """q2 = c' c tan(beta)."""
    return s.cp * s.c * s.tan_beta


def aux_omega1() -> sp.Expr:
    """omega1 = atan2(p1, q1): the paper's arctan(p1/q1), quadrant-correct for q1 < 0."""
    return sp.atan2(aux_p1(), aux_q1())


def aux_omega2() -> sp.Expr:
    """omega2 = atan2(p2, q2)."""
    return sp.atan2(aux_p2(), aux_q2())


def aux_u1() -> sp.Expr:
    """u1 = d'c' / sqrt(p1^2 + q1^2)   (left-hand side of (10'))."""
    return s.dp * s.cp / sp.sqrt(aux_p1() ** 2 + aux_q1() ** 2)


def aux_u2() -> sp.Expr:
    """u2 = e'c' / sqrt(p2^2 + q2^2)."""
    return s.ep * s.cp / sp.sqrt(aux_p2() ** 2 + aux_q2() ** 2)


def _aux_values() -> dict[sp.Symbol, sp.Expr]:
    return {
        s.p1: aux_p1(),
        s.q1: aux_q1(),
        s.p2: aux_p2(),
        s.q2: aux_q2(),
        s.omega1: aux_omega1(),
        s.omega2: aux_omega2(),
        s.u1: aux_u1(),
        s.u2: aux_u2(),
    }


# branch signs of (10''') and (11'''): which root of arccos the frame is on
eps1 = sp.Symbol("epsilon1", real=True)
eps2 = sp.Symbol("epsilon2", real=True)
EPS_VALUES = {
    eps1: sp.sign(sp.sin(s.delta - s.omega1)),
    eps2: sp.sign(sp.sin(s.delta + s.phi + s.omega2)),
}

# --------------------------------------------------------------------------------------------
# (1) - (7): the construction
# --------------------------------------------------------------------------------------------


def eq_1() -> Equation:
    """(1) AS / AB = tan(alpha): triangle ABS is right-angled at A, angle ABS = alpha."""
    return Equation(
        "1", s.AS / s.AB, s.tan_alpha, "angle ABS = alpha, angle BAS = 90 deg", "symbolic"
    )


def eq_2() -> Equation:
    """(2) AS' / AS = cos(delta): S' is the foot of S on l1 after the rotation by delta."""
    return Equation(
        "2", s.AS_p / s.AS, sp.cos(s.delta), "angle SAS' = delta, angle AS'S = 90 deg", "symbolic"
    )


def eq_3() -> Equation:
    """(3) SS' / AS = sin(delta)   (the paper prints SS'/AB: erratum; (3') needs AS)."""
    return Equation(
        "3", s.SS_p / s.AS, sp.sin(s.delta), "same right triangle AS'S as (2)", "symbolic"
    )


def eq_4() -> Equation:
    """(4) AB' / AB = cos(tau): the rotation by tau about l1 foreshortens AB."""
    return Equation("4", s.AB_p / s.AB, sp.cos(s.tau), "angle BAB' = tau", "symbolic")


def eq_4p() -> Equation:
    """(4') sin(tau)^2 = 1 - c'^2/c^2: (4) with AB' = c'; the sign of sin(tau) stays free."""
    return Equation(
        "4'",
        s.sin_tau**2,
        1 - s.cp**2 / s.c**2,
        "(4) with AB' = c', AB = c; sin(tau) is signed (the paper takes sin arccos(c'/c) >= 0)",
        "symbolic",
    )


def eq_5() -> Equation:
    """(5) S'S'' / SS' = cos(90 deg - tau): S' lies on the rotation axis l1."""
    return Equation(
        "5",
        s.S_pS_pp / s.SS_p,
        sp.cos(sp.pi / 2 - s.tau),
        "angle SS'S'' = 90 deg - tau, S' fixed by the rotation about l1",
        "symbolic",
    )


def eq_6() -> Equation:
    """(6) AS' = AD' + D'S': A, D', S' all lie on l1 (signed lengths along l1)."""
    return Equation("6", s.AS_p, s.AD_p + s.D_pS_p, "A, D', S' are collinear on l1", "symbolic")


def eq_7() -> Equation:
    """(7) AD' / D'S' = -AB' / S'S'': similar triangles D'AB' and D'S'S''.

    AB' and S'S'' are parallel (both perpendicular to l1 in the frame plane), so the triangles
    D'AB' and D'S'S'' are related by a homothety centred at D': B' - D' = k (S'' - D') gives
    k = AB'/S'S'' (x components) and k = -AD'/D'S' (y components, A and S' on l1, lengths signed
    in the same direction along l1).  Hence the minus sign; the paper's (7) with unsigned
    lengths is this equation's absolute value.
    """
    return Equation(
        "7",
        s.AD_p / s.D_pS_p,
        -s.AB_p / s.S_pS_pp,
        "intercept theorem on the parallels AB' and S'S'' cut by l1 and B'S''; signed lengths",
        "symbolic",
    )


# --------------------------------------------------------------------------------------------
# eliminations (2'), (3'), (5''), (6''), (7''')
# --------------------------------------------------------------------------------------------


def eq_2p() -> Equation:
    """(2') AS' = cos(delta) c tan(alpha): AS eliminated by (1) from (2)."""
    return Equation(
        "2'",
        s.AS_p,
        sp.cos(s.delta) * s.c * s.tan_alpha,
        "(2) with AS = c tan(alpha) from (1)",
        "symbolic",
    )


def eq_3p() -> Equation:
    """(3') SS' = sin(delta) c tan(alpha): AS eliminated by (1) from (3)."""
    return Equation(
        "3'",
        s.SS_p,
        sp.sin(s.delta) * s.c * s.tan_alpha,
        "(3) with AS = c tan(alpha) from (1)",
        "symbolic",
    )


def eq_5pp() -> Equation:
    """(5'') S'S'' = sin(tau) sin(delta) c tan(alpha): SS' eliminated by (3') from (5)."""
    return Equation(
        "5''",
        s.S_pS_pp,
        s.sin_tau * sp.sin(s.delta) * s.c * s.tan_alpha,
        "(5) (cos(90 deg - tau) = sin(tau)) with SS' from (3')",
        "symbolic",
    )


def eq_6pp() -> Equation:
    """(6'') cos(delta) c tan(alpha) = AD' + D'S': AS' eliminated by (2') from (6)."""
    return Equation(
        "6''",
        sp.cos(s.delta) * s.c * s.tan_alpha,
        s.AD_p + s.D_pS_p,
        "(6) with AS' from (2')",
        "symbolic",
    )


def eq_7ppp() -> Equation:
    """(7''') AD'/(cos(delta) c tan(alpha) - AD') = -AB'/(sin(tau) sin(delta) c tan(alpha)).

    D'S' eliminated by (6''), S'S'' by (5'').  The paper's denominator lacks the factor c.
    """
    return Equation(
        "7'''",
        s.AD_p / (sp.cos(s.delta) * s.c * s.tan_alpha - s.AD_p),
        -s.AB_p / (s.sin_tau * sp.sin(s.delta) * s.c * s.tan_alpha),
        "(7) with D'S' from (6'') and S'S'' from (5'')",
        "symbolic",
    )


# --------------------------------------------------------------------------------------------
# (8) - (11): one equation per frame and per tangent
# --------------------------------------------------------------------------------------------


def eq_8() -> Equation:
    """(8) d' c tan(alpha) sin(tau) sin(delta) = d'c' - c' c tan(alpha) cos(delta).

    (7''') cross-multiplied, with AD' = d', AB' = c' (4).  The paper writes sin(arccos(c'/c)) for
    sin(tau) (one sign of tau only), the opposite sign of delta, and omits the "=".
    """
    lhs = s.dp * s.c * s.tan_alpha * s.sin_tau * sp.sin(s.delta)
    rhs = s.dp * s.cp - s.cp * s.c * s.tan_alpha * sp.cos(s.delta)
    return Equation("8", lhs, rhs, "(7''') cross-multiplied; AD' = d', AB' = c'", "symbolic")


def eq_9() -> Equation:
    """(9) e' c tan(beta) sin(tau) sin(delta + phi) = c' c tan(beta) cos(delta + phi) - e'c'.

    The same construction for the tangent at A, seen from the other side: l2 through B', E' on
    it, the rotation about AB is delta + phi (the paper's text says tau + phi: erratum), the
    rotation about l2 is tau.  Seen from the other side the orientation flips, so the sign of the
    sin(tau) term is opposite to (8).
    """
    dphi = s.delta + s.phi
    lhs = s.ep * s.c * s.tan_beta * s.sin_tau * sp.sin(dphi)
    rhs = s.cp * s.c * s.tan_beta * sp.cos(dphi) - s.ep * s.cp
    return Equation("9", lhs, rhs, "(8) by analogy for the tangent at A, l2 and E'", "symbolic")


def eq_10() -> Equation:
    """(10) q1 cos(delta) + p1 sin(delta) = d'c'   ((8) with the auxiliary terms)."""
    return Equation(
        "10",
        s.q1 * sp.cos(s.delta) + s.p1 * sp.sin(s.delta),
        s.dp * s.cp,
        "(8) rearranged with p1 = d' c tan(alpha) sin(tau), q1 = c' c tan(alpha)",
        "symbolic",
    )


def eq_11() -> Equation:
    """(11) q2 cos(delta + phi) - p2 sin(delta + phi) = e'c'   ((9) with the auxiliary terms)."""
    dphi = s.delta + s.phi
    return Equation(
        "11",
        s.q2 * sp.cos(dphi) - s.p2 * sp.sin(dphi),
        s.ep * s.cp,
        "(9) rearranged with p2 = e' c tan(beta) sin(tau), q2 = c' c tan(beta)",
        "symbolic",
    )


def eq_10p() -> Equation:
    """(10') d'c'/r1 = cos(delta) q1/r1 + sin(delta) p1/r1, r1 = sqrt(p1^2 + q1^2)."""
    r1 = sp.sqrt(s.p1**2 + s.q1**2)
    return Equation(
        "10'",
        s.dp * s.cp / r1,
        sp.cos(s.delta) * s.q1 / r1 + sp.sin(s.delta) * s.p1 / r1,
        "(10) divided by sqrt(p1^2 + q1^2) (the paper's minus sign follows its sign of delta)",
        "numeric",
    )


def eq_10pp() -> Equation:
    """(10'') u1 = cos(delta - omega1), omega1 = atan2(p1, q1).

    cos(omega1) = q1/r1, sin(omega1) = p1/r1, so the right-hand side of (10') is
    cos(delta - omega1) (the paper: cos(delta + omega1), its sign of delta).
    """
    return Equation(
        "10''",
        s.u1,
        sp.cos(s.delta - s.omega1),
        "(10') with the angle-difference formula",
        "numeric",
    )


def eq_11pp() -> Equation:
    """(11'') u2 = cos(delta + phi + omega2), omega2 = atan2(p2, q2)."""
    return Equation(
        "11''",
        s.u2,
        sp.cos(s.delta + s.phi + s.omega2),
        "(11) divided by sqrt(p2^2 + q2^2), angle-sum formula",
        "numeric",
    )


def eq_10ppp() -> Equation:
    """(10''') delta - omega1 = epsilon1 arccos(u1)  (mod 2pi), epsilon1 = sign sin(delta - omega1).

    arccos returns [0, pi]; the paper's (10''') is the branch epsilon1 = +1 only.
    """
    return Equation(
        "10'''",
        s.delta - s.omega1,
        eps1 * sp.acos(s.u1),
        "arccos of (10''); epsilon1 selects the root",
        "numeric",
        modulus=2 * sp.pi,
    )


def eq_11ppp() -> Equation:
    """(11''') delta + phi + omega2 = epsilon2 arccos(u2)  (mod 2 pi)."""
    return Equation(
        "11'''",
        s.delta + s.phi + s.omega2,
        eps2 * sp.acos(s.u2),
        "arccos of (11''); epsilon2 = sign sin(delta + phi + omega2) selects the root",
        "numeric",
        modulus=2 * sp.pi,
    )


# --------------------------------------------------------------------------------------------
# (12): delta eliminated
# --------------------------------------------------------------------------------------------


def eq_12() -> Equation:
    """(12) phi + omega1 + omega2 = epsilon2 arccos(u2) - epsilon1 arccos(u1)  (mod 2 pi).

    (11''') minus (10''').  The paper prints arccos(u2) - arccos(u1) = phi + omega2 - omega1:
    with signs consistent with (10), (11) it is omega1 + omega2, and which combination of
    arccos appears depends on the frame's branch (epsilon1, epsilon2).
    """
    return Equation(
        "12",
        s.phi + s.omega1 + s.omega2,
        eps2 * sp.acos(s.u2) - eps1 * sp.acos(s.u1),
        "(11''') - (10''')",
        "numeric",
        modulus=2 * sp.pi,
    )


def eq_12_cos() -> Equation:
    """(12, branch-free) (cos(phi + omega1 + omega2) - u1 u2)^2 = (1 - u1^2)(1 - u2^2).

    cos of (12): cos(Phi) = u1 u2 + epsilon1 epsilon2 sqrt(1 - u1^2) sqrt(1 - u2^2); moving u1 u2
    to the left and squaring removes epsilon1 epsilon2.  This is ``residual_12`` (divided out:
    see :func:`residual_12_expr`); it vanishes on every branch and for both signs of tau.
    """
    big_phi = s.phi + s.omega1 + s.omega2
    return Equation(
        "12*",
        (sp.cos(big_phi) - s.u1 * s.u2) ** 2,
        (1 - s.u1**2) * (1 - s.u2**2),
        "cos of both sides of (12), squared to remove the branch signs",
        "numeric",
    )


def eq_12_tan() -> Equation:
    """(12, tangent form) y = tan^2(arccos(u2) - epsilon1 epsilon2 arccos(u1)), y = tan^2(Phi).

    tan^2 is even and pi-periodic, so tan^2 of (12) drops the overall sign epsilon2 and the
    multiple of 2 pi; the relative sign epsilon1 epsilon2 remains (removed by squaring in (12')).
    """
    return Equation(
        "12-tan",
        sp.tan(s.phi + s.omega1 + s.omega2) ** 2,
        sp.tan(sp.acos(s.u2) - eps1 * eps2 * sp.acos(s.u1)) ** 2,
        "tan^2 of (12)",
        "numeric",
    )


# --------------------------------------------------------------------------------------------
# (12'): the paper's "tangentialising and squaring twice"
# --------------------------------------------------------------------------------------------


def s1_expr() -> sp.Expr:
    """s1 = tan^2(arccos u1) = (1 - u1^2)/u1^2 as a rational function.

    p1^2 + q1^2 = d'^2 c^2 tan^2(alpha) sin^2(tau) + c'^2 c^2 tan^2(alpha) with sin^2(tau) =
    1 - c'^2/c^2 (4') gives (d'^2 + c'^2) c^2 tan^2(alpha) - d'^2 c'^2 tan^2(alpha); subtract
    d'^2 c'^2 and divide by d'^2 c'^2.  (Printed: tan(alpha) and (tan^2(alpha) - 1): erratum.)
    """
    ta2 = s.tan_alpha**2
    return ((s.dp**2 + s.cp**2) * s.c**2 * ta2 - s.dp**2 * s.cp**2 * (ta2 + 1)) / (
        s.dp**2 * s.cp**2
    )


def s2_expr() -> sp.Expr:
    """s2 = tan^2(arccos u2): s1 with d' -> e', alpha -> beta."""
    tb2 = s.tan_beta**2
    return ((s.ep**2 + s.cp**2) * s.c**2 * tb2 - s.ep**2 * s.cp**2 * (tb2 + 1)) / (
        s.ep**2 * s.cp**2
    )


def tan_sum_parts() -> tuple[sp.Expr, sp.Expr]:
    """(N, M) with tan(omega1 + omega2) = M / N.

    tan(omega_k) = p_k/q_k = d' sin(tau)/c' (resp. e' sin(tau)/c'), so
    tan(omega1 + omega2) = sin(tau)(d' + e')/c' / (1 - d'e' sin^2(tau)/c'^2), and
    sin^2(tau)/c'^2 = 1/c'^2 - 1/c^2 by (4').  N is even and M odd in sin(tau).
    """
    n = 1 - s.dp * s.ep / s.cp**2 + s.dp * s.ep / s.c**2
    m = s.sin_tau * (s.dp + s.ep) / s.cp
    return n, m


def y_expr() -> sp.Expr:
    """y = tan^2(phi + omega1 + omega2) = (N tan(phi) + M)^2 / (N - M tan(phi))^2."""
    n, m = tan_sum_parts()
    return (n * s.tan_phi + m) ** 2 / (n - m * s.tan_phi) ** 2


def y_paper_form() -> sp.Expr:
    """y in the paper's arrangement, corrected: sec^2 - 1 with a denominator even in sin(tau).

    N^2 + M^2 = (1 + d'^2/c'^2 - d'^2/c^2)(1 + e'^2/c'^2 - e'^2/c^2), and multiplying numerator
    and denominator by (N + M tan(phi))^2 leaves sqrt(1 - c'^2/c^2) in the numerator only.
    """
    n, m = tan_sum_parts()
    fd = 1 + s.dp**2 / s.cp**2 - s.dp**2 / s.c**2
    fe = 1 + s.ep**2 / s.cp**2 - s.ep**2 / s.c**2
    return (
        fd * fe * (s.tan_phi**2 + 1) * (n + m * s.tan_phi) ** 2 / (n**2 - m**2 * s.tan_phi**2) ** 2
        - 1
    )


def f12p(s1: sp.Expr, s2: sp.Expr, y: sp.Expr) -> sp.Expr:
    """Left-hand side of (12') as printed (it checks out).

    From tan(a2 -/+ a1) with tan^2 a_k = s_k: y (1 -/+ t1 t2)^2 = (t2 +/- t1)^2, i.e.
    y (1 + s1 s2) - s1 - s2 = +/- 2 t1 t2 (1 + y); squaring gives
    (y (1 + s1 s2) - s1 - s2)^2 - 4 s1 s2 (1 + y)^2 = 0, which expands to (12').
    """
    return (
        s2**2 + s1**2 + y**2 + y**2 * s2**2 * s1**2
        - 2 * s1 * s2 - 2 * y * s2 - 2 * y * s2**2 * s1 - 2 * y * s1 - 2 * y * s2 * s1**2
        - 2 * y**2 * s2 * s1 - 8 * y * s2 * s1
    )  # fmt: skip


def eq_s1() -> Equation:
    """s1 = tan^2(arccos u1) as a rational function of c, tan(alpha), c', d'."""
    return Equation(
        "s1", sp.tan(sp.acos(s.u1)) ** 2, s1_expr(), "(1 - u1^2)/u1^2 with (4')", "numeric"
    )


def eq_s2() -> Equation:
    """s2 = tan^2(arccos u2)."""
    return Equation(
        "s2", sp.tan(sp.acos(s.u2)) ** 2, s2_expr(), "(1 - u2^2)/u2^2 with (4')", "numeric"
    )


def eq_y() -> Equation:
    """y = tan^2(phi + omega1 + omega2) in observables and shape (tan(phi) = tan_phi)."""
    return Equation(
        "y",
        sp.tan(s.phi + s.omega1 + s.omega2) ** 2,
        y_expr().subs(s.tan_phi, sp.tan(s.phi)),
        "tangent addition formula twice, tan(omega_k) = p_k/q_k, (4')",
        "numeric",
    )


def eq_y_paper_form() -> Equation:
    """y in the paper's arrangement (corrected), equal to y."""
    return Equation(
        "y (paper's form)",
        y_expr(),
        y_paper_form(),
        "sec^2 - 1 and the factor (N + M tan phi)^2 above and below",
        "numeric",
    )


def eq_12p() -> Equation:
    """(12') with the s1, s2, y above; the printed positive terms on the left, the rest right."""
    s1, s2, y = s1_expr(), s2_expr(), y_expr().subs(s.tan_phi, sp.tan(s.phi))
    lhs = s2**2 + s1**2 + y**2 + y**2 * s2**2 * s1**2
    rhs = (
        2 * s1 * s2 + 2 * y * s2 + 2 * y * s2**2 * s1 + 2 * y * s1 + 2 * y * s2 * s1**2
        + 2 * y**2 * s2 * s1 + 8 * y * s2 * s1
    )  # fmt: skip
    return Equation(
        "12'",
        lhs,
        rhs,
        "tangent of (12), both branches, squared: see f12p",
        "numeric",
    )


EQUATIONS: tuple[Callable[[], Equation], ...] = (
    eq_1, eq_2, eq_3, eq_4, eq_4p, eq_5, eq_6, eq_7,
    eq_2p, eq_3p, eq_5pp, eq_6pp, eq_7ppp,
    eq_8, eq_9, eq_10, eq_11,
    eq_10p, eq_10pp, eq_11pp, eq_10ppp, eq_11ppp,
    eq_12, eq_12_cos, eq_12_tan,
    eq_s1, eq_s2, eq_y, eq_y_paper_form, eq_12p,
)  # fmt: skip


@cache
def equations() -> tuple[Equation, ...]:
    """All equations of section 3, in the paper's order."""
    return tuple(f() for f in EQUATIONS)


# --------------------------------------------------------------------------------------------
# checks against the construction
# --------------------------------------------------------------------------------------------


def expand_aux(expr: sp.Expr) -> sp.Expr:
    """``expr`` with the branch signs and auxiliary terms (p, q, omega, u) written out.

    The result is in c, tan_alpha, tan_beta, phi, tan_phi, delta, tau, sin_tau, the observables
    and the named lengths: ready to be evaluated on any construction of the observables.
    """
    return sp.sympify(expr).subs(EPS_VALUES).subs(_aux_values())


def _substituted(expr: sp.Expr) -> sp.Expr:
    """expr in (c, tan_alpha, tan_beta, phi, delta, tau): auxiliaries, then the construction."""
    expr = expr.subs(EPS_VALUES).subs(_aux_values())
    return expr.subs(substitutions())


def check_symbolic(eq: Equation) -> bool:
    """True when lhs - rhs simplifies to 0 on the construction's values."""
    r = _substituted(eq.residual)
    r = sp.cancel(sp.expand_trig(sp.together(r)))
    if r == 0:
        return True
    return sp.simplify(r) == 0


@cache
def numeric_values(n: int, dps: int = MP_DPS) -> tuple[dict[sp.Symbol, mpmath.mpf], ...]:
    """Values of every construction symbol at ``n`` seeded random configurations (mpmath).

    Keys: the primitive symbols (c, alpha, beta, phi, delta, tau), tan_alpha, tan_beta, tan_phi,
    and every key of ``construction.substitutions()`` (observables, named lengths, sin_tau).
    """
    prim = (s.c, s.alpha, s.beta, s.phi, s.delta, s.tau)
    angles = {s.tan_alpha: sp.tan(s.alpha), s.tan_beta: sp.tan(s.beta)}
    base = dict(substitutions())
    base.update(angles)
    base[s.tan_phi] = sp.tan(s.phi)
    funcs = {k: sp.lambdify(prim, v.subs(angles), modules="mpmath") for k, v in base.items()}
    out = []
    with mpmath.workdps(dps):
        for row in random_configurations(n):
            x = [mpmath.mpf(float(v)) for v in row]
            vals = {k: f(*x) for k, f in funcs.items()}
            vals.update(dict(zip(prim, x, strict=True)))
            out.append(vals)
    return tuple(out)


def relative_residuals(
    lhs: sp.Expr,
    rhs: sp.Expr,
    modulus: sp.Expr | None = None,
    n: int = N_RANDOM,
    dps: int = MP_DPS,
) -> list[mpmath.mpf]:
    """|lhs - rhs| / (1 + |lhs| + |rhs|) at each of ``n`` seeded random configurations.

    The auxiliary terms (p, q, omega, u, branch signs) are substituted symbolically, the
    construction's values numerically (mpmath, ``dps`` digits).  With ``modulus`` (2 pi) the
    difference is wrapped to (-pi, pi] first.
    """
    lhs = expand_aux(lhs)
    rhs = expand_aux(rhs)
    free = sorted(lhs.free_symbols | rhs.free_symbols, key=str)
    f = sp.lambdify(free, [lhs, rhs], modules="mpmath")
    out = []
    with mpmath.workdps(dps):
        two_pi = 2 * mpmath.pi
        for vals in numeric_values(n, dps):
            a, b = f(*[vals[k] for k in free])
            v = a - b
            if modulus is not None:
                v = v - two_pi * mpmath.nint(v / two_pi)
            out.append(abs(v) / (1 + abs(a) + abs(b)))
    return out


@cache
def check_numeric(eq: Equation, n: int = N_RANDOM) -> float:
    """max |lhs - rhs| / (1 + |lhs| + |rhs|) over ``n`` seeded random configurations (mpmath)."""
    return float(max(relative_residuals(eq.lhs, eq.rhs, eq.modulus, n)))


@cache
def check_results() -> tuple[tuple[str, str, float | bool], ...]:
    """(number, kind, result) for every equation: True, or the max numeric residual."""
    out = []
    for eq in equations():
        if eq.check == "symbolic":
            out.append((eq.number, "symbolic", check_symbolic(eq)))
        else:
            out.append((eq.number, "numeric", check_numeric(eq)))
    return tuple(out)


# --------------------------------------------------------------------------------------------
# what the runtime needs: generated/frame_equations.py
# --------------------------------------------------------------------------------------------


def residual_12_expr() -> sp.Expr:
    """Branch-free residual of (12), without atan2.

    With r_k = sqrt(p_k^2 + q_k^2), cos(omega_k) = q_k/r_k, sin(omega_k) = p_k/r_k:
    r1 r2 cos(phi + omega1 + omega2) = K = cos(phi)(q1 q2 - p1 p2) - sin(phi)(p1 q2 + q1 p2) and
    u1 u2 r1 r2 = d'e'c'^2, so (12*) times r1^2 r2^2 reads
    (K - d'e'c'^2)^2 - (r1^2 - d'^2 c'^2)(r2^2 - e'^2 c'^2) = 0.  Divided by r1^2 r2^2 it is
    dimensionless and equals (cos(Phi) - u1 u2)^2 - (1 - u1^2)(1 - u2^2) in [-1, 4].
    """
    p1, q1, p2, q2 = aux_p1(), aux_q1(), aux_p2(), aux_q2()
    r1sq = p1**2 + q1**2
    r2sq = p2**2 + q2**2
    k = sp.cos(s.phi) * (q1 * q2 - p1 * p2) - sp.sin(s.phi) * (p1 * q2 + q1 * p2)
    dc = s.dp * s.cp
    ec = s.ep * s.cp
    return ((k - dc * ec) ** 2 - (r1sq - dc**2) * (r2sq - ec**2)) / (r1sq * r2sq)


def pose_exprs() -> tuple[sp.Expr, sp.Expr]:
    """(cos(delta), sin(delta)) from (10) and (11) as a 2x2 linear system (Cramer's rule).

    (11) expanded: a cos(delta) + b sin(delta) = e'c' with a = q2 cos(phi) - p2 sin(phi),
    b = -q2 sin(phi) - p2 cos(phi); (10): q1 cos(delta) + p1 sin(delta) = d'c'.
    """
    p1, q1, p2, q2 = aux_p1(), aux_q1(), aux_p2(), aux_q2()
    a = q2 * sp.cos(s.phi) - p2 * sp.sin(s.phi)
    b = -q2 * sp.sin(s.phi) - p2 * sp.cos(s.phi)
    det = q1 * b - p1 * a
    dc = s.dp * s.cp
    ec = s.ep * s.cp
    return (dc * b - p1 * ec) / det, (q1 * ec - a * dc) / det


def predicted_exprs() -> tuple[sp.Expr, sp.Expr]:
    """(d', e') predicted from shape and pose: the construction's D' and E'.

    d' = c' c tan(alpha) cos(delta) / (c' - c tan(alpha) sin(tau) sin(delta)),
    e' = c' c tan(beta) cos(delta + phi) / (c' + c tan(beta) sin(tau) sin(delta + phi)).
    """
    ta_c = s.c * s.tan_alpha
    tb_c = s.c * s.tan_beta
    dphi = s.delta + s.phi
    d = s.cp * ta_c * sp.cos(s.delta) / (s.cp - ta_c * s.sin_tau * sp.sin(s.delta))
    e = s.cp * tb_c * sp.cos(dphi) / (s.cp + tb_c * s.sin_tau * sp.sin(dphi))
    return d, e


_CONV = (
    "Conventions (docs/CONVENTIONS.md): paper's frame (A' at the origin, B' on +x), "
    "R = R_y(tau) R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau signed "
    "(B_z = -c sin(tau)). Lengths in input units, angles in radians."
)


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/frame_equations.py, in order (see CONVENTIONS.md)."""
    c, ta, tb, phi = s.c, s.tan_alpha, s.tan_beta, s.phi
    cp, dp, ep, delta, st = s.cp, s.dp, s.ep, s.delta, s.sin_tau
    p1, q1, p2, q2 = aux_p1(), aux_q1(), aux_p2(), aux_q2()
    cd, sd = pose_exprs()
    d, e = predicted_exprs()
    dphi = delta + phi
    return [
        FunctionSpec(
            "aux_terms",
            (c, ta, tb, cp, dp, ep, st),
            {"p1": p1, "q1": q1, "p2": p2, "q2": q2},
            "Auxiliary frame terms of section 3: p1 = d' c tan(alpha) sin(tau), "
            "q1 = c' c tan(alpha), p2 = e' c tan(beta) sin(tau), q2 = c' c tan(beta). " + _CONV,
        ),
        FunctionSpec(
            "residual_10",
            (c, ta, cp, dp, delta, st),
            {"residual": q1 * sp.cos(delta) + p1 * sp.sin(delta) - dp * cp},
            "Equation (10): q1 cos(delta) + p1 sin(delta) - d'c' (zero on true data; "
            "units length^2). " + _CONV,
        ),
        FunctionSpec(
            "residual_11",
            (c, tb, phi, cp, ep, delta, st),
            {"residual": q2 * sp.cos(dphi) - p2 * sp.sin(dphi) - ep * cp},
            "Equation (11): q2 cos(delta + phi) - p2 sin(delta + phi) - e'c' (zero on true "
            "data; units length^2). " + _CONV,
        ),
        FunctionSpec(
            "residual_12",
            (c, ta, tb, phi, cp, dp, ep, st),
            {"residual": residual_12_expr()},
            "Equation (12), branch-free and dimensionless: (cos(phi + omega1 + omega2) - u1 u2)^2 "
            "- (1 - u1^2)(1 - u2^2) with u1 = d'c'/sqrt(p1^2 + q1^2), u2 = e'c'/sqrt(p2^2 + q2^2), "
            "omega_k = atan2(p_k, q_k); zero on true data for every branch of arccos and both "
            "signs of sin(tau). " + _CONV,
        ),
        FunctionSpec(
            "pose_from_shape",
            (c, ta, tb, phi, cp, dp, ep, st),
            {"cos_delta": cd, "sin_delta": sd},
            "(10) and (11) solved as a linear system in cos(delta), sin(delta) (Cramer's rule); "
            "cos^2 + sin^2 = 1 exactly on true data. " + _CONV,
        ),
        FunctionSpec(
            "predicted_d_e",
            (c, ta, tb, phi, cp, delta, st),
            {"d": d, "e": e},
            "Predicted d', e' (signed, input units) from shape and pose: the 3-D construction's "
            "D' on l1 and E' on l2. " + _CONV,
        ),
    ]

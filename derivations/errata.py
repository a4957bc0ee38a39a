"""Errata of the paper's section 3: printed formulas against the derived ones.

Each :class:`Erratum` holds the printed formula (LaTeX as printed, and a SymPy reading of it:
a pair of sides that should be equal on true data) and the derived formula (same form).  Both
are evaluated at the same seeded random true configurations (both signs of tau; the
construction of ``derivations.construction``) with mpmath at ``DPS`` digits; the relative
residual |lhs - rhs| / (1 + |lhs| + |rhs|) shows which one holds.

Where the printed text is ambiguous (missing primes, a missing "="), the reading closest to
the printed text is used and stated in ``reading``.  Sign conventions are those of
``docs/CONVENTIONS.md``; an erratum that is only a convention (the paper's sign of delta in
(10)) is tested under the paper's convention as well, so that a convention alone never counts
as an error.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cache

import sympy as sp

from derivations import section3 as s3
from derivations import symbols as s

DPS = 50  # mpmath digits
N_CONFIGS = 60  # random true configurations per check


@dataclass(frozen=True)
class Erratum:
    """A printed formula, the derived one, and how to compare them numerically.

    ``printed`` and ``derived`` are (lhs, rhs) pairs in the section-3 symbols; ``modulus`` is
    2 pi for angle equations.
    """

    label: str
    printed_latex: str
    derived_latex: str
    printed: tuple[sp.Expr, sp.Expr]
    derived: tuple[sp.Expr, sp.Expr]
    reading: str
    verdict: str
    modulus: sp.Expr | None = None


@dataclass(frozen=True)
class Evidence:
    """Relative residuals at the true configurations (``n`` of them, both signs of tau).

    ``printed_fail_fraction``: share of configurations where the printed formula misses by more
    than ``TOL``; ``printed_median``, ``derived_max``: median and max relative residuals.
    """

    printed_fail_fraction: float
    printed_median: float
    derived_max: float
    n: int


TOL = 1e-20


def _paper_p1() -> sp.Expr:
    """Printed p_{i1} = d' c tg(alpha) sin(arccos(c'/c)) (non-negative sin: one branch)."""
    return s.dp * s.c * s.tan_alpha * sp.sin(sp.acos(s.cp / s.c))


def _paper_p2() -> sp.Expr:
    """Printed p_{i2} = e' c tg(alpha) sin(arccos(c'/c)) (tg(alpha) as printed)."""
    return s.ep * s.c * s.tan_alpha * sp.sin(sp.acos(s.cp / s.c))


def _paper_omegas() -> tuple[sp.Expr, sp.Expr]:
    """Printed omega_{ik} = arctg(p_{ik}/q_{ik}), with the corrected p_{i2} (tg(beta))."""
    p1 = s.dp * s.c * s.tan_alpha * s.sin_tau
    p2 = s.ep * s.c * s.tan_beta * s.sin_tau
    return sp.atan(p1 / (s.cp * s.c * s.tan_alpha)), sp.atan(p2 / (s.cp * s.c * s.tan_beta))


def erratum_3() -> Erratum:
    """(3): SS'/AB = sin(delta) printed; the right triangle AS'S needs AS (as (3') uses)."""
    return Erratum(
        "(3)",
        r"\frac{SS'}{AB} = \sin\delta_i",
        r"\frac{SS'}{AS} = \sin\delta_i",
        (s.SS_p / s.AB, sp.sin(s.delta)),
        (s.SS_p / s.AS, sp.sin(s.delta)),
        "as printed",
        "typo: AB for AS; (3') = sin(delta) c tg(alpha) follows from the corrected (3) only",
    )


def erratum_7ppp() -> Erratum:
    """(7'''): the denominator of the right-hand side lacks the factor c."""
    printed_rhs = s.AB_p / (s.sin_tau * sp.sin(s.delta) * s.tan_alpha)
    lhs = s.AD_p / (sp.cos(s.delta) * s.c * s.tan_alpha - s.AD_p)
    # compare magnitudes: the sign of (7) is the convention (signed vs unsigned lengths)
    return Erratum(
        "(7''')",
        r"\frac{AD'}{\cos\delta_i\,c\,\mathrm{tg}\,\alpha - AD'} = "
        r"\frac{AB'}{\sin\tau_i\,\sin\delta_i\,\mathrm{tg}\,\alpha}",
        r"\frac{AD'}{\cos\delta_i\,c\,\mathrm{tg}\,\alpha - AD'} = "
        r"-\frac{AB'}{\sin\tau_i\,\sin\delta_i\,c\,\mathrm{tg}\,\alpha}",
        (sp.Abs(lhs), sp.Abs(printed_rhs)),
        (sp.Abs(lhs), sp.Abs(s.AB_p / (s.sin_tau * sp.sin(s.delta) * s.c * s.tan_alpha))),
        "compared in absolute value (the sign is the length convention of (7))",
        "typo: S'S'' = sin(tau) sin(delta) c tg(alpha) by (5''), the factor c is missing",
    )


def erratum_8() -> Erratum:
    """(8): no "=", and the sign of its sin(tau) term disagrees with (9).

    With sin(arccos(c'/c)) >= 0, the printed (8) holds exactly on the frames with sin(tau) < 0
    and the printed (9) on those with sin(tau) > 0 (:func:`erratum_9`): no single orientation of
    tau satisfies both.  Fixing tau by (9), (8) has the wrong sign of its sin(tau) term; this is
    the sign error that reaches (10) and (12).
    """
    paper_sin = sp.sin(sp.acos(s.cp / s.c))
    return Erratum(
        "(8)",
        r"d'_i\,c\,\mathrm{tg}\,\alpha\,\sin\arccos(c'/c)\,\sin\delta\;"
        r"c'_i\,c\,\mathrm{tg}\,\alpha\,\cos\delta_i - d'_i c'_i.",
        r"d'_i\,c\,\mathrm{tg}\,\alpha\,\sin\tau_i\,\sin\delta_i = "
        r"d'_i c'_i - c'_i\,c\,\mathrm{tg}\,\alpha\,\cos\delta_i",
        (
            s.dp * s.c * s.tan_alpha * paper_sin * sp.sin(s.delta),
            s.cp * s.c * s.tan_alpha * sp.cos(s.delta) - s.dp * s.cp,
        ),
        (s3.eq_8().lhs, s3.eq_8().rhs),
        "'=' inserted before c'",
        "missing '='; as printed it holds on the frames with sin(tau) < 0 only, while (9) holds "
        "on those with sin(tau) > 0: the sin(tau) terms of (8) and (9) need opposite signs "
        "relative to the rest (tangent at A seen from the other side); with tau oriented as in "
        "(9), (8) has the wrong sign.  Use signed sin(tau)",
    )


def erratum_9() -> Erratum:
    """(9) as printed: right, except that sin(arccos(c'/c)) >= 0 covers one sign of tau."""
    paper_sin = sp.sin(sp.acos(s.cp / s.c))
    dphi = s.delta + s.phi
    return Erratum(
        "(9)",
        r"e'_i\,c\,\mathrm{tg}\,\beta\,\sin\arccos(c'/c)\,\sin(\delta_i+\phi) = "
        r"c'_i\,c\,\mathrm{tg}\,\beta\,\cos(\delta_i+\phi) - e'_i c'_i",
        r"e'_i\,c\,\mathrm{tg}\,\beta\,\sin\tau_i\,\sin(\delta_i+\phi) = "
        r"c'_i\,c\,\mathrm{tg}\,\beta\,\cos(\delta_i+\phi) - e'_i c'_i",
        (
            s.ep * s.c * s.tan_beta * paper_sin * sp.sin(dphi),
            s.cp * s.c * s.tan_beta * sp.cos(dphi) - s.ep * s.cp,
        ),
        (s3.eq_9().lhs, s3.eq_9().rhs),
        "as printed",
        "correct on the frames with sin(tau) > 0; fails on the other half because "
        "sin(arccos(c'/c)) >= 0: use signed sin(tau)",
    )


def erratum_p2() -> Erratum:
    """p_{i2}: printed with tg(alpha); (9) has tg(beta)."""
    r2 = s.c * s.tan_beta * (s.cp * sp.cos(s.delta + s.phi))  # q2 cos(delta + phi)
    printed_p2 = _paper_p2().subs(sp.sin(sp.acos(s.cp / s.c)), s.sin_tau)
    derived_p2 = s.ep * s.c * s.tan_beta * s.sin_tau
    return Erratum(
        "p_{i2}",
        r"p_{i2} = e'_i\,c\,\mathrm{tg}\,\alpha\,\sin\arccos(c'_i/c)",
        r"p_{i2} = e'_i\,c\,\mathrm{tg}\,\beta\,\sin\tau_i",
        (r2 - printed_p2 * sp.sin(s.delta + s.phi), s.ep * s.cp),
        (r2 - derived_p2 * sp.sin(s.delta + s.phi), s.ep * s.cp),
        "checked through (11): q2 cos(delta + phi) - p2 sin(delta + phi) = e'c' (signed sin(tau))",
        "typo: tg(alpha) for tg(beta)",
    )


def erratum_12() -> Erratum:
    """(12): phi + omega2 - omega1 printed; consistent signs give phi + omega1 + omega2."""
    w1, w2 = _paper_omegas()
    a1, a2 = sp.acos(s.u1), sp.acos(s.u2)
    return Erratum(
        "(12)",
        r"\arccos\frac{e'_i c'_i}{\sqrt{p_{i2}^2+q_{i2}^2}} - "
        r"\arccos\frac{d'_i c'_i}{\sqrt{p_{i1}^2+q_{i1}^2}} = \phi + \omega_{i2} - \omega_{i1}",
        r"\epsilon_2\arccos\frac{e'_i c'_i}{\sqrt{p_{i2}^2+q_{i2}^2}} - "
        r"\epsilon_1\arccos\frac{d'_i c'_i}{\sqrt{p_{i1}^2+q_{i1}^2}} \equiv "
        r"\phi + \omega_{i1} + \omega_{i2} \pmod{2\pi}",
        (a2 - a1, s.phi + w2 - w1),
        (s3.eps2 * a2 - s3.eps1 * a1, s.phi + w1 + w2),
        "as printed, omega = arctg(p/q), p_{i2} with tg(beta), modulo 2 pi",
        "sign error: viewed from the other side of the frame the orientation flips, so (10) and "
        "(11) cannot both carry the same sign of the sin(tau) term; the branch of arccos also "
        "depends on the frame (epsilon_1, epsilon_2)",
        modulus=2 * sp.pi,
    )


def erratum_12_all_branches() -> Erratum:
    """(12) with every branch of arccos allowed: cos form of both sides."""
    w1, w2 = _paper_omegas()
    return Erratum(
        "(12), any branch",
        r"\pm\arccos u_2 \pm \arccos u_1 \equiv \phi + \omega_{i2} - \omega_{i1}"
        r"\iff (\cos(\phi+\omega_{i2}-\omega_{i1}) - u_1u_2)^2 = (1-u_1^2)(1-u_2^2)",
        r"(\cos(\phi+\omega_{i1}+\omega_{i2}) - u_1u_2)^2 = (1-u_1^2)(1-u_2^2)",
        ((sp.cos(s.phi + w2 - w1) - s.u1 * s.u2) ** 2, (1 - s.u1**2) * (1 - s.u2**2)),
        ((sp.cos(s.phi + w1 + w2) - s.u1 * s.u2) ** 2, (1 - s.u1**2) * (1 - s.u2**2)),
        "printed combination of omegas with the branch signs removed by cos and squaring",
        "no choice of arccos branches rescues phi + omega2 - omega1",
    )


def erratum_s1() -> Erratum:
    """s1: printed tg(alpha) and (tg^2(alpha) - 1); derived tg^2(alpha) and (tg^2(alpha) + 1)."""
    ta = s.tan_alpha
    printed = ((s.dp**2 + s.cp**2) * s.c**2 * ta - s.dp**2 * s.cp**2 * (ta**2 - 1)) / (
        s.dp**2 * s.cp**2
    )
    return Erratum(
        "s_1",
        r"s_1 = \frac{(d'^2_i + c'^2_i) c^2\,\mathrm{tg}\,\alpha - d'^2_i c'^2_i "
        r"(\mathrm{tg}^2\alpha - 1)}{d'^2_i c'^2_i}",
        r"s_1 = \frac{(d'^2_i + c'^2_i) c^2\,\mathrm{tg}^2\alpha - d'^2_i c'^2_i "
        r"(\mathrm{tg}^2\alpha + 1)}{d'^2_i c'^2_i}",
        (sp.tan(sp.acos(s.u1)) ** 2, printed),
        (sp.tan(sp.acos(s.u1)) ** 2, s3.s1_expr()),
        "s1 = tan^2(arccos u1)",
        "typos: tg(alpha) for tg^2(alpha) and (tg^2 alpha - 1) for (tg^2 alpha + 1)",
    )


def erratum_s2() -> Erratum:
    """s2: the same typos as s1."""
    tb = s.tan_beta
    printed = ((s.ep**2 + s.cp**2) * s.c**2 * tb - s.ep**2 * s.cp**2 * (tb**2 - 1)) / (
        s.ep**2 * s.cp**2
    )
    return Erratum(
        "s_2",
        r"s_2 = \frac{(e'^2_i + c'^2_i) c^2\,\mathrm{tg}\,\beta - e'^2_i c'^2_i "
        r"(\mathrm{tg}^2\beta - 1)}{e'^2_i c'^2_i}",
        r"s_2 = \frac{(e'^2_i + c'^2_i) c^2\,\mathrm{tg}^2\beta - e'^2_i c'^2_i "
        r"(\mathrm{tg}^2\beta + 1)}{e'^2_i c'^2_i}",
        (sp.tan(sp.acos(s.u2)) ** 2, printed),
        (sp.tan(sp.acos(s.u2)) ** 2, s3.s2_expr()),
        "s2 = tan^2(arccos u2)",
        "typos: tg(beta) for tg^2(beta) and (tg^2 beta - 1) for (tg^2 beta + 1)",
    )


def _printed_y(with_one: bool, omega_sum: bool) -> sp.Expr:
    """The printed y with primes restored and e/c - e/c read as e'/c' - d'/c'.

    ``with_one`` adds the missing "1 +" to the factors (d'^2/c'^2 - d'^2/c^2) and
    (e'^2/c'^2 - e'^2/c^2); ``omega_sum`` uses the consistent signs (phi + omega1 + omega2):
    1 - d'e'/c'^2 + d'e'/c^2 and d'/c' + e'/c' instead of 1 + d'e'/c'^2 - d'e'/c^2 and
    e'/c' - d'/c'.
    """
    cp, dp, ep, c, tph = s.cp, s.dp, s.ep, s.c, s.tan_phi
    root = sp.sqrt(1 - cp**2 / c**2)
    one = 1 if with_one else 0
    fd = one + dp**2 / cp**2 - dp**2 / c**2
    fe = one + ep**2 / cp**2 - ep**2 / c**2
    if omega_sum:
        n = 1 - dp * ep / cp**2 + dp * ep / c**2
        m = ep / cp + dp / cp
    else:
        n = 1 + dp * ep / cp**2 - dp * ep / c**2
        m = ep / cp - dp / cp
    return (
        fd
        * fe
        * (tph**2 + 1)
        * (n + tph * m * root) ** 2
        / (n**2 - tph**2 * m**2 * (1 - cp**2 / c**2)) ** 2
        - 1
    )


def erratum_y() -> Erratum:
    """y: primes missing, e/c - e/c, the factors lack "1 +", and omega2 - omega1 (see (12))."""
    w1, w2 = _paper_omegas()
    return Erratum(
        "y",
        r"y = \frac{(\frac{d'^2}{c'^2} - \frac{d'^2}{c^2})(\frac{e'^2}{c'^2} - \frac{e'^2}{c^2})"
        r"(\mathrm{tg}^2\phi + 1)(1 + \frac{de}{c'^2} - \frac{de}{c^2} + \mathrm{tg}\,\phi"
        r"(\frac{e}{c} - \frac{e}{c})\sqrt{1 - \frac{c'^2}{c^2}})^2}{((1 + \frac{de}{c'^2} - "
        r"\frac{de}{c^2})^2 - \mathrm{tg}^2\phi(\frac{e}{c} - \frac{d}{c})^2(1 - "
        r"\frac{c'^2}{c^2}))^2} - 1",
        r"y = \frac{(1 + \frac{d'^2}{c'^2} - \frac{d'^2}{c^2})(1 + \frac{e'^2}{c'^2} - "
        r"\frac{e'^2}{c^2})(\mathrm{tg}^2\phi + 1)(1 - \frac{d'e'}{c'^2} + \frac{d'e'}{c^2} + "
        r"\mathrm{tg}\,\phi(\frac{d'}{c'} + \frac{e'}{c'})\sin\tau)^2}{((1 - \frac{d'e'}{c'^2} + "
        r"\frac{d'e'}{c^2})^2 - \mathrm{tg}^2\phi(\frac{d'}{c'} + \frac{e'}{c'})^2(1 - "
        r"\frac{c'^2}{c^2}))^2} - 1 = \mathrm{tg}^2(\phi + \omega_1 + \omega_2)",
        # printed (primes restored) against the paper's own y = tg^2(phi + omega2 - omega1),
        # on the frames with sin(tau) > 0 where sqrt(1 - c'^2/c^2) = sin(tau)
        (sp.tan(s.phi + w2 - w1) ** 2, _printed_y(with_one=False, omega_sum=False)),
        (
            sp.tan(s.phi + s.omega1 + s.omega2) ** 2,
            _printed_y(with_one=True, omega_sum=True).subs(
                sp.sqrt(1 - s.cp**2 / s.c**2), s.sin_tau
            ),
        ),
        "primes restored (d, e, c -> d', e', c'), e/c - e/c read as e'/c' - d'/c'; compared with "
        "the paper's own y = tg^2(phi + omega2 - omega1) (sin(tau) > 0 frames only hold for "
        "sqrt(1 - c'^2/c^2) = sin(tau))",
        "typos: missing primes, e/c - e/c for e'/c' - d'/c', and the factors "
        "(d'^2/c'^2 - d'^2/c^2), (e'^2/c'^2 - e'^2/c^2) lack '1 +' (sec^2 needs N^2 + M^2 = "
        "(1 + d'^2 sin^2 tau/c'^2)(1 + e'^2 sin^2 tau/c'^2)); with consistent signs the "
        "combination is phi + omega1 + omega2 (see (12))",
    )


def erratum_y_with_one() -> Erratum:
    """y with "1 +" restored but the printed omega2 - omega1: right for the paper's (12) only."""
    w1, w2 = _paper_omegas()
    return Erratum(
        "y, '1 +' restored",
        r"y \text{ as printed with } 1 + \frac{d'^2}{c'^2} - \frac{d'^2}{c^2}, "
        r"1 + \frac{e'^2}{c'^2} - \frac{e'^2}{c^2}",
        r"\text{the derived } y",
        (
            sp.tan(s.phi + w2 - w1) ** 2,
            _printed_y(with_one=True, omega_sum=False).subs(
                sp.sqrt(1 - s.cp**2 / s.c**2), s.sin_tau
            ),
        ),
        (
            sp.tan(s.phi + s.omega1 + s.omega2) ** 2,
            _printed_y(with_one=True, omega_sum=True).subs(
                sp.sqrt(1 - s.cp**2 / s.c**2), s.sin_tau
            ),
        ),
        "the algebra of the printed y is right once '1 +' is restored: it then equals "
        "tg^2(phi + omega2 - omega1) (printed lhs column), which is the wrong angle by (12)",
        "only the '1 +' is an algebra typo; the rest follows the sign error of (12)",
    )


def erratum_12p_with_printed_y() -> Erratum:
    """(12') with y = tg^2(phi + omega2 - omega1) (printed (12)) against the consistent y."""
    w1, w2 = _paper_omegas()
    s1, s2 = s3.s1_expr(), s3.s2_expr()
    y_printed = sp.tan(s.phi + w2 - w1) ** 2
    y_derived = sp.tan(s.phi + s.omega1 + s.omega2) ** 2

    def sides(y: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
        lhs = s2**2 + s1**2 + y**2 + y**2 * s2**2 * s1**2
        return lhs, lhs - s3.f12p(s1, s2, y)

    return Erratum(
        "(12') with printed y",
        r"(12')\text{ with } y = \mathrm{tg}^2(\phi + \omega_{i2} - \omega_{i1})",
        r"(12')\text{ with } y = \mathrm{tg}^2(\phi + \omega_{i1} + \omega_{i2})",
        sides(y_printed),
        sides(y_derived),
        "s1, s2 corrected; (12') itself as printed (it checks out); sides: printed positive "
        "terms against the rest",
        "(12') is right; fed the printed (12) it does not vanish at the true shape",
    )


ERRATA = (
    erratum_3,
    erratum_7ppp,
    erratum_8,
    erratum_9,
    erratum_p2,
    erratum_12,
    erratum_12_all_branches,
    erratum_s1,
    erratum_s2,
    erratum_y,
    erratum_y_with_one,
    erratum_12p_with_printed_y,
)

TEXT_ERRATA: tuple[tuple[str, str, str], ...] = (
    (
        "before (4)",
        r"\angle S''S''A = 90^o",
        r"\angle S'S''S = 90^o \text{ (SS'' is perpendicular to the frame plane; the right "
        r"triangle SS'S'' gives (5))}",
    ),
    (
        "before (9)",
        r"\text{the rotation around } AB \text{ must be } \tau_i + \phi",
        r"\delta_i + \phi \text{ (as (9) itself uses; the rotation about } l2 \text{ is } "
        r"\tau_i)",
    ),
    (
        "(10), (10'), (10'')",
        r"p_{i1}\sin\delta_i = q_{i1}\cos\delta_i - d'_i c_i'",
        r"q_{i1}\cos\delta_i + p_{i1}\sin\delta_i = d'_i c'_i \text{ (inherits the sign "
        r"error of (8); then } u_1 = \cos(\delta_i - \omega_{i1}))",
    ),
)


@cache
def evidence(index: int) -> Evidence:
    """Numeric evidence for ``ERRATA[index]`` at N_CONFIGS true configurations, DPS digits."""
    e = ERRATA[index]()
    pr = s3.relative_residuals(*e.printed, e.modulus, N_CONFIGS, DPS)
    de = s3.relative_residuals(*e.derived, e.modulus, N_CONFIGS, DPS)
    ordered = sorted(pr)
    fails = sum(1 for v in pr if v > TOL)
    return Evidence(fails / len(pr), float(ordered[len(ordered) // 2]), float(max(de)), len(pr))


@cache
def sign_variants_10_11() -> tuple[tuple[tuple[int, int, int], float], ...]:
    """Printed (10) and (11) together under every sign convention (delta, phi, tau -> +/-).

    For each variant the median over the true configurations of max(rel. residual of the printed
    (10), of the printed (11)), with p_{i2} corrected to tg(beta) and signed sin(tau).  None
    vanishes: the printed pair is inconsistent under any of these conventions.
    """
    p1 = s.dp * s.c * s.tan_alpha * s.sin_tau
    q1 = s.cp * s.c * s.tan_alpha
    p2 = s.ep * s.c * s.tan_beta * s.sin_tau
    q2 = s.cp * s.c * s.tan_beta
    out = []
    for sd, sph, stau in itertools.product((1, -1), repeat=3):
        dl, ph = sd * s.delta, sph * s.phi
        sub = {s.sin_tau: stau * s.sin_tau}
        r10 = s3.relative_residuals(
            (p1 * sp.sin(dl)).subs(sub), (q1 * sp.cos(dl) - s.dp * s.cp), None, N_CONFIGS, DPS
        )
        r11 = s3.relative_residuals(
            (p2 * sp.sin(dl + ph)).subs(sub),
            q2 * sp.cos(dl + ph) - s.ep * s.cp,
            None,
            N_CONFIGS,
            DPS,
        )
        worst = sorted(max(a, b) for a, b in zip(r10, r11, strict=True))
        out.append(((sd, sph, stau), float(worst[len(worst) // 2])))
    return tuple(out)

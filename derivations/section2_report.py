"""The Section 2 part of docs/derivation.md and docs/errata.md (from derivations/section2.py)."""

from __future__ import annotations

from derivations import minimal_count as mc
from derivations import section2 as s2

SEED_TABLE = {
    "uniform_rotation": ("uniform rotational motion", 2, "4"),
    "fixed_axis": ("free rotation around a fixed direction", 2, "4"),
    "free_3pt": ("free motion", 3, "3"),
    "force_field": ("free motion, bounded by homogeneous force field", 2, "n"),
}
SYMMETRIES = {
    "uniform_rotation": "mirror z -> -z; axis sign (n, w) -> (-n, -w) (fixed by w >= 0)",
    "fixed_axis": "mirror z -> -z; axis sign (n, theta_f) -> (-n, -theta_f) (fixed by theta_1 "
    "in [0, 180] degrees)",
    "free_3pt": "per-frame flip (z_f, e_f) -> -(z_f, e_f) in every frame (2^F, the mirror "
    "included): the shape is the same",
    "force_field": "per-frame depth sign of A - G and B - G (2^F, the mirror included)",
}
SOLVERS = {
    "uniform_rotation": "1-D search in z_0 (transcendental for general times; bisection of the "
    "generated angle residual)",
    "fixed_axis": "closed form: cubic in z_0^2 (companion matrix), Newton polish",
    "free_3pt": "closed form: quadratic in z_0 e_0, Newton polish",
    "force_field": "none practical (778 paths; see below)",
}


def _hist(h: dict[int, int]) -> str:
    total = sum(h.values())
    return ", ".join(f"{k}: {v}/{total}" for k, v in h.items())


def _row_facts() -> dict[str, dict[str, object]]:
    facts = dict(s2.facts())
    facts["force_field"] = s2.force_field_facts()
    return facts


def table() -> list[str]:
    """The table beside the seed's."""
    facts, reals = _row_facts(), s2.real_counts()
    out = [
        "| row (seed's words) | points | frames (seed) | least frames for finitely many "
        "(derived) | complex solutions there | real solutions, noise-free instances | "
        "symmetries | unique from | minimal solver (`curverecon/solvers/ortho_<row>.py`) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for row in s2.ROWS:
        words, points, frames = SEED_TABLE[row]
        f = facts[row]
        real = _hist(reals[row]) if row in reals else "not counted"
        count = f["random"][0]  # type: ignore[index]
        if row == "uniform_rotation":
            count = f"{count} (equally spaced times)"
        out.append(
            f"| {words} | {points} | {frames} | {f['frames']} | {count} | {real} | "
            f"{SYMMETRIES[row]} | {int(f['frames']) + 1} | {SOLVERS[row]} |"  # type: ignore[call-overload]
        )
    return out


def evidence() -> list[str]:
    """How each figure was obtained."""
    facts, checks, deg = _row_facts(), s2.checks(), s2.degenerate_axes()
    ranks = s2.force_field_jacobian_ranks()
    out = ["### Evidence\n"]
    w = out.append
    w(
        f"- Construction check (`section2.checks`, {s2.N_CHECK} random bodies and motions, "
        "float64): every equation below vanishes at the 3-D construction to "
        + ", ".join(f"{k}: {v:.1e}" for k, v in checks.items())
        + " (absolute, lengths about 1; the force field relative to its terms)."
    )
    closed = s2.closed_form_checks()
    w(
        f"- Closed forms at the 3-D construction (`section2.closed_form_checks`, {s2.N_CHECK} "
        "random scenes, float64; median / max): the true z_0^2 as a root of the fixed-axis cubic "
        "{:.1e} / {:.1e} and the true z_0 e_0 as a root of the three-point quadratic {:.1e} / "
        "{:.1e} (relative distance to the nearest root; the cubic's coefficients lose digits by "
        "cancellation near z_f = 0, which is why the solver polishes on the unsquared "
        "equations), the uniform rotation's equation at the true depth with general times "
        "{:.1e} / {:.1e} rad.".format(
            *closed["fixed_axis_cubic"],
            *closed["free_3pt_quadratic"],
            *closed["uniform_rotation_angles"],
        )
    )
    for row in s2.ROWS:
        f = facts[row]
        below = (
            f"{f['below_dimension']} (Jacobian rank at the truth: "
            + ", ".join(f"{k} frames rank {r}" for k, (r, _) in ranks.items())
            + " of 9 unknowns)"
            if row == "force_field"
            else f["below_dimension"]
        )
        w(
            f"- {row}: random instances (msolve over GF({mc.PRIME}), seeds "
            f"{list(s2.COUNT_SEEDS)}): {f['random']} solutions; one frame fewer: dimension "
            f"{below}; noise-free rational construction at {f['frames']} frames: "
            f"{f['noise_free']}, at {int(f['frames']) + 1} frames: {f['noise_free_one_more']}."  # type: ignore[call-overload]
        )
    w(
        "- Real solutions: msolve's real root isolation over the rationals at "
        f"{len(s2.REAL_SEEDS)} noise-free rational constructions per row (Cayley rotations of "
        "small rational vectors; equally spaced times for the uniform rotation).  The bench "
        "(`python -m bench.config_minimal`) gives the solvers' mean over random float scenes."
    )
    w(
        "- Degenerate axes (msolve, noise-free instance): dimension of the solution set with the "
        "axis along the viewing direction / in the image plane: "
        + "; ".join(
            f"{row}: " + ", ".join(f"{k} {v}" for k, v in d.items()) for row, d in deg.items()
        )
        + ".  Along the viewing direction every depth stays z_0 and nothing fixes it; in the "
        "image plane the differences project onto one line, so for free angles (fixed axis) "
        "their coplanarity says nothing, while a uniform rate still determines the depth.\n"
    )
    return out


def derivation_markdown() -> list[str]:
    """The section of docs/derivation.md."""
    out = ["\n## Section 2: the orthographic rows of the seed's table\n"]
    w = out.append
    w(
        "Generated from `derivations/section2.py` (`section2_report.py`); do not edit.  "
        + (s2.__doc__ or "").split("\n\n", 1)[1].strip()
        + "\n"
    )
    w("### The equations\n")
    for name, fn in (
        ("equal norms", s2.equal_norms),
        ("coplanar differences", s2.coplanar_differences),
        ("equal steps", s2.equal_steps),
        ("Gram invariants", s2.gram_invariants),
        ("force field", s2.force_field_equation),
        ("fixed axis as a cubic", s2.fixed_axis_cubic_in_cofactors),
        ("three points as a quadratic", s2.free_3pt_quadratic),
        ("uniform rotation's angles", s2.uniform_rotation_angles),
    ):
        w(f"- **{name}** (`{fn.__name__}`): " + " ".join((fn.__doc__ or "").split()))
    w(
        "\nSystems counted (unknowns: the depths): fixed axis = equal norms + coplanar "
        "differences; uniform rotation (equally spaced times) = equal norms + equal steps (+ "
        "coplanar differences from four frames); three points = Gram invariants; force field = "
        "one equation per frame in (g0, g1, g2, |a|^2, |b|^2, a.b).\n"
    )
    w("### The table beside the seed's\n")
    out.extend(table())
    w(
        "\nComplex solutions count every sign and mirror image (each real shape appears with its "
        'mirror, and for three points with every per-frame flip).  "Unique from": the '
        "noise-free count one frame above the least is the symmetry orbit of the truth alone "
        "(2 = the mirror pair for the axis rows; 16 = the per-frame flips of four frames for "
        "three points; 1 for the force field, whose signs are squared away).  Uniform rotation "
        "at general times: the equation is transcendental (rate aliasing), its solutions "
        "countable; under the sampling condition (below half a turn between frames) finitely "
        "many, and the solver lists them.  The force field's 778 solutions would need a "
        "778-path homotopy (about 7 times the paper's 104-path solver, 0.02 s median) and list "
        "2^9 sign choices per real solution: no practical minimal solver, the estimation seeds "
        "it otherwise.\n"
    )
    out.extend(evidence())
    return out


def errata_markdown() -> list[str]:
    """The section of docs/errata.md: where the seed's Section 2 table is wrong or incomplete."""
    facts = _row_facts()
    ur, fa, f3, ff = (facts[r] for r in s2.ROWS)
    out = ["## The Section 2 table, orthographic rows (derived against printed)\n"]
    w = out.append
    w(
        "Generated by `derivations/section2_report.py` from `derivations/section2.py`; evidence "
        'in derivation.md, section "Section 2".\n'
    )
    w(
        f"- uniform rotational motion, 2 points: printed 4 frames.  Finitely many solutions "
        f"from {ur['frames']} frames ({ur['random'][0]} complex for equally spaced times, msolve; "  # type: ignore[index]
        f"one frame fewer: dimension {ur['below_dimension']}); 4 frames give a unique answer up "
        f"to the mirror ({ur['noise_free_one_more']} solutions at a noise-free instance).  The "
        "printed 4 is the number for uniqueness, not the least."
    )
    w(
        f"- free rotation around a fixed direction, 2 points: printed 4 frames, the least for "
        f"finitely many ({fa['random'][0]} complex solutions, up to 3 mirror pairs real), but "  # type: ignore[index]
        f"not unique: 5 frames are needed ({fa['noise_free_one_more']} solutions, the mirror "
        "pair).  Not determined at all when the axis lies along the viewing direction or in the "
        "image plane (a turntable seen from the side): the solution set is a curve."
    )
    w(
        f"- free motion, 3 points: printed 3 frames, right for finitely many ({f3['random'][0]} "  # type: ignore[index]
        "complex solutions: 2 shapes times the 8 per-frame flips); the shape is unique from 4 "
        f"frames ({f3['noise_free_one_more']} solutions, all per-frame flips of one shape).  No "
        "number of frames removes the per-frame flips (orthographic Necker reversal)."
    )
    w(
        f"- free motion bounded by a homogeneous force field, 2 points: printed n frames.  "
        f"Derived: {ff['frames']} (nine unknowns, one equation per frame; Jacobian rank 9 at "
        f"the truth), {ff['random'][0]} complex solutions there (msolve), unique from 10 frames "  # type: ignore[index]
        f"({ff['noise_free_one_more']} solution at a noise-free instance).\n"
    )
    return out

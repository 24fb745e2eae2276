"""The decision procedures on inputs where a weaker procedure would accept a false statement; ``check`` runs them.

The obligations say *holds* through :mod:`._decide` and :mod:`._inequalities`,
which rest on sympy.  Each case below is an input whose wrong answer would
prove something false (``x + 1 > 0`` for a real ``x``; ``xz + yz + z² ≥ 0``,
whose Gram matrix has all leading principal minors 0 but the minor ``{1, 3}``
negative; an ``And`` with an undecided conjunct; a case split that must keep
its boundary points; a piece of ``R`` whose membership is undecided; a 3×3
matrix whose 2×2 faces are all copositive but which is not, by Hadeler's
inequality at −0.35, for the quadratic template's copositivity decision; a stick
duration ``a − b`` whose sign is undecided, or ``0``, which ``claim1.cases`` must
refuse as the length of ``[0, T]``), with a few true statements as controls, so
a broken or patched sympy that makes a procedure say yes too often, or no
always, fails ``check``.
"""

from __future__ import annotations

__all__ = ["decision_cases"]


def decision_cases() -> tuple:
    """One :class:`~.._certify.hunting_rigour.RigourCase` per input, in the order of the module docstring."""
    import sympy as sp

    from .._certify.hunting_rigour import RigourCase
    from . import _decide, _inequalities, _region

    a, b, c = (_decide.pos(name) for name in ("a_chk", "b_chk", "c_chk"))
    n = sp.Symbol("n_chk", nonnegative=True)
    x, y, z = sp.symbols("x_chk y_chk z_chk", real=True)

    def gt(lhs, rhs):
        return sp.StrictGreaterThan(lhs, rhs, evaluate=False)

    def show(value):
        return "undecided" if value is None else str(value)

    out = [
        ("sign_of(x + 1), x real", "undecided", show(_decide.sign_of(x + 1))),
        ("sign_of(n), n ≥ 0", "undecided", show(_decide.sign_of(n))),
        ("sign_of(a + 1), a > 0", "1", show(_decide.sign_of(a + 1))),
        ("sign_of(1/(a − b))", "undecided", show(_decide.sign_of(1 / (a - b)))),
        ("decide(a > 0 ∧ a > b)", "undecided", show(_decide.decide(sp.And(gt(a, 0), gt(a, b), evaluate=False)))),
        ("decide(−a > 0 ∨ a > b)", "undecided", show(_decide.decide(sp.Or(gt(-a, 0), gt(a, b), evaluate=False)))),
        ("decide(¬(a > b))", "undecided", show(_decide.decide(sp.Not(gt(a, b), evaluate=False)))),
        ("decide(a > 0 ∧ b > 0)", "True", show(_decide.decide(sp.And(gt(a, 0), gt(b, 0), evaluate=False)))),
        ("is_nonneg(xz + yz + z²): a non-leading minor < 0", "False", show(_inequalities.is_nonneg(x * z + y * z + z**2))),
        ("is_nonneg(x² − 2xy + y²)", "True", show(_inequalities.is_nonneg(x**2 - 2 * x * y + y**2))),
        ("is_nonneg(a x³ + a): an odd power of a real x", "False", show(_inequalities.is_nonneg(a * x**3 + a))),
        ("is_nonneg(n³ a + a)", "True", show(_inequalities.is_nonneg(n**3 * a + a))),
        ("is_nonneg(1/(a − b))", "False", show(_inequalities.is_nonneg(1 / (a - b)))),
        ("is_nonneg(−(a + 1)(x² + 1))", "False", show(_inequalities.is_nonneg(sp.expand(-(a + 1) * (x**2 + 1))))),
    ]
    regions = [region for *_, region in _decide.phi_classes(c, "_chk")]
    counts = [sum(1 for r in regions if r.contains(p) == sp.true) for p in (-c - 1, -c, sp.Integer(0), c, c + 1)]
    out.append(("phi_classes: each of −c−1, −c, 0, c, c+1 in one class", "[1, 1, 1, 1, 1]", str(counts)))
    values = [case.value(x) for case in _inequalities.line_cases(x, [-c, c], name="x", beyond="t_chk")]
    out.append(("line_cases: the boundary points ±c are pieces", "True", str(-c in values and c in values)))
    v, phi, f_c = sp.symbols("v_chk phi_chk f_c_chk", real=True)
    Case = _inequalities.Case
    pieces = [Case("v > 0, φ > f_c", ((v, a), (phi, f_c + b)), (a, b)), Case("v = 0", ((v, sp.Integer(0)), (phi, b)), (b,)),
              Case("v > 0, φ = b", ((v, a), (phi, b)), (a, b))]
    failures: list[str] = []
    inside = [p.label for p in _region.pieces_of(pieces, v * (phi - f_c), inside=True, failures=failures)]
    out.append(("pieces_of: R holds its boundary, an undecided piece is a failure", "2 inside, 1 failure",
                f"{len(inside)} inside, {len(failures)} failure{'s' if len(failures) != 1 else ''}"))
    from fractions import Fraction

    from .._certify.copositive import decide_copositive

    def copositive(rows) -> str:
        return show(decide_copositive([[Fraction(x) for x in row] for row in rows]).holds)

    half = Fraction(1, 2)
    out += [
        ("copositive: faces fine, Hadeler's inequality −0.35", "False",
         copositive([[half, -half, 0], [-half, half, -half], [0, -half, half]])),
        ("copositive: not semidefinite, Hadeler's inequality holds", "True", copositive([[1, 1, -1], [1, 1, 1], [-1, 1, 1]])),
        ("copositive: a zero diagonal entry with a negative row", "False", copositive([[0, -1], [-1, 5]])),
        ("copositive: a diagonal entry < 0", "False", copositive([[-1, 2], [2, 1]])),
    ]
    from .claim1 import stick_duration_error

    def duration(T) -> str:
        return "refused" if stick_duration_error(T) else "accepted"

    out += [
        ("claim1 stick duration a − b: sign undecided", "refused", duration(a - b)),
        ("claim1 stick duration 0", "refused", duration(sp.Integer(0))),
        ("claim1 stick duration 2a/b", "accepted", duration(2 * a / b)),
    ]
    return tuple(RigourCase(name, expected, got) for name, expected, got in out)

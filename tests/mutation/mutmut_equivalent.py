"""What mutmut's report counts (:data:`SCOPE`) and the survivors argued equivalent (:data:`EQUIVALENT`).

The scope is the trusted base: the exact verifier, the decision procedures
and the case split on ``R``, the Krawczyk proof of hunting cycles, and the
part of ``check`` that turns section results into the exit code.  Printing
helpers of ``check`` (table layout, wrapping, locating the configuration)
are mutated too but reported as out of scope.
"""

from __future__ import annotations

SCOPE: tuple[str, ...] = (
    "symbolic_friction._certify.verify.*",
    "symbolic_friction._obligations._decide.x_[!l]*",  # every function but latex(), which only renders
    "symbolic_friction._obligations._region.*",
    "symbolic_friction._certify.hunting_proof.*",
    "symbolic_friction._cli.check.x_run__mutmut_*",
    "symbolic_friction._cli._sections.x_closing_line__mutmut_*",
    "symbolic_friction._cli._sections.x__crashed__mutmut_*",
    "symbolic_friction._cli._sections.x__is_verdict__mutmut_*",
)

_V = "symbolic_friction._certify.verify."
_H = "symbolic_friction._certify.hunting_proof."
_D = "symbolic_friction._obligations._decide."
_C = "symbolic_friction._cli.check."
EQUIVALENT: dict[str, str] = {
    _V + "x_decide__mutmut_22": "minors of the entries themselves instead of their Fraction copies: _exact has refused every "
    "entry that is not an int or a Fraction, and Fraction(x) == x for those, so every minor has the same value",
    _V + "x_decide__mutmut_76": "the Inequality rebuilt for margin() gets obligation None: margin() reads only op, lhs and rhs",
    _V + "x_decide__mutmut_77": "the Inequality rebuilt for margin() gets name None: margin() reads only op, lhs and rhs",
    _V + "x_premises__mutmut_130": "the identity gets a 4th column: only identity[i][j] with i, j < 3 is read",
    _V + "x_premises__mutmut_132": "the identity gets a 4th row: only identity[i][j] with i, j < 3 is read",
    _V + "x_premises__mutmut_327": "k + zero → k − zero with zero = k_i − k_i, which is 0 for Fractions and for sympy symbols",
    _V + "xǁSemidefiniteǁminors__mutmut_9": "sizes up to n + 1: combinations(range(n), n + 1) is empty, so no minor is added",
    _H + "xǁ_Arbǁball__mutmut_4": "mid − arb(0, r) is the same ball as mid + arb(0, r): arb(0, r) is symmetric about 0",
    _H + "xǁ_Arbǁball__mutmut_9": "python-flint reads arb(None, r) as arb(0, r): the same ball",
    _H + "xǁ_Arbǁstate__mutmut_5": "python-flint reads arb(None) as arb(0): the same exact zero",
    _H + "x__prove__mutmut_34": "float('NAN') is the same NaN as float('nan')",
    _H + "x__prove__mutmut_37": "float('NAN') is the same NaN as float('nan')",
    _H + "x__prove__mutmut_135": "float('NAN') is the same NaN as float('nan')",
    _H + "x__prove__mutmut_138": "float('NAN') is the same NaN as float('nan')",
    _H + "x__prove__mutmut_184": "dx = X − x̃ is a ball with midpoint exactly 0, so −row·dx is the same ball as +row·dx",
    _H + "x__prove__mutmut_185": "dx = X − x̃ is a ball with midpoint exactly 0, so −row·dx is the same ball as +row·dx",
    _H + "x__short__mutmut_2": "x = 0 then also gives Fraction(f'{0.0:.17g}') = Fraction(0): the same value",
    _V + "x__exact__mutmut_1": "a Fraction then takes the general path, which returns Fraction(value): the same number",
    _V + "x__text__mutmut_2": "a 10,000-bit integer has 3,011 digits, within str()'s 4,300-digit limit: str(q) is format_rational(q) there",
    _V + "x__text__mutmut_3": "a 10,000-bit integer has 3,011 digits, within str()'s 4,300-digit limit: str(q) is format_rational(q) there",
    _V + "x__text__mutmut_4": "a 10,000-bit integer has 3,011 digits, within str()'s 4,300-digit limit: str(q) is format_rational(q) there",
    _V + "x__text__mutmut_5": "a 10,000-bit integer has 3,011 digits, within str()'s 4,300-digit limit: str(q) is format_rational(q) there",
    _D + "x__poly_sign__mutmut_16": "Poly.coeffs() lists only non-zero coefficients (p = 0 returned above), so c ≥ 0 is c > 0 on each",
    _D + "x__poly_sign__mutmut_20": "Poly.coeffs() lists only non-zero coefficients (p = 0 returned above), so c ≤ 0 is c < 0 on each",
    _D + "x_affine_image__mutmut_34": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x_affine_image__mutmut_48": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x_affine_image__mutmut_52": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x__stationary_points__mutmut_16": "a degree-0 numerator then reaches roots(), which returns {} (multiplicities sum 0 = degree): [] again",
    _D + "x__stationary_points__mutmut_32": "sympy's solve() reads simplify only by truthiness (if flags.get('simplify', True)): None acts as False",
    _V + "x_premises__mutmut_225": "the stand-in k_v = 2 for 1: k_conditions reads k_v only in k_i·k1/k_v and k_i·k3/k_v, "
    "whose two conditions (DIVIDE_BY_K_V) are replaced by Undefined right below, so every premise is the same",
    _D + "x__coefficient_sign__mutmut_4": "a sparse PolyElement stores only non-zero coefficients (zero has none: 0 returned above), so c ≥ 0 is c > 0 on each",
    _D + "x__coefficient_sign__mutmut_8": "a sparse PolyElement stores only non-zero coefficients (zero has none: 0 returned above), so c ≤ 0 is c < 0 on each",
    _D + "x__coefficient_sign__mutmut_9": "numerator and denominator come out of PolyElement.cancel, which clears denominators: non-zero integer "
    "coefficients, and a non-zero integer is < 1 iff it is < 0",
    _D + "x__field_element__mutmut_7": "only is_zero passes a number (sign_of returns first); QQ.frac_field() of no symbols is QQ(), whose "
    "from_sympy(q) == 0 iff q == 0, as with QQ.from_sympy: the same answer",
    _C + "x_run__mutmut_25": "as_json is read only by truth value (if, not, and emit's err=, which picks the stream by it): None is False",
    _C + "x_run__mutmut_136": "json reads ensure_ascii only by truth value (if self.ensure_ascii: …): None is False",
}

"""What mutmut's report counts (:data:`SCOPE`), what of it was not run yet (:data:`PENDING`) and the survivors
argued equivalent (:data:`EQUIVALENT`).

The scope is the trusted base: the exact verifier, the decision procedures
and the case split on ``R``, the Krawczyk proof of hunting cycles, the
sup-flow verifier (its premises, its arb decisions, the model maps they
use), the two bounds of ``_inequalities`` that changed with ``_decide``,
and the part of ``check`` that turns section results into the exit code.
Printing helpers of ``check`` (table layout, wrapping, locating the
configuration) and of the sup-flow certificate (``to_dict``, the interval
and gains texts, the canonical dump, provenance) are mutated too but
reported as out of scope.
"""

from __future__ import annotations

SCOPE: tuple[str, ...] = (
    "symbolic_friction._certify.verify.*",
    "symbolic_friction._obligations._decide.x_[!l]*",  # every function but latex(), which only renders
    # the fraction of integer polynomials the decisions read (moved here from _decide._field_element)
    "symbolic_friction._obligations._fastpoly.x_rational_pair__mutmut_*",
    "symbolic_friction._obligations._fastpoly.x_is_rational_function__mutmut_*",
    "symbolic_friction._obligations._region.*",
    "symbolic_friction._certify.hunting_proof.*",
    "symbolic_friction._cli.check.x_run__mutmut_*",
    "symbolic_friction._cli._sections.x_closing_line__mutmut_*",
    "symbolic_friction._cli._sections.x__crashed__mutmut_*",
    "symbolic_friction._cli._sections.x__is_verdict__mutmut_*",
    "symbolic_friction._certify.sup_flow_enclosure.*",
    "symbolic_friction._certify.sup_flow_forms.*",
    "symbolic_friction._certify.sup_flow.x_sup_flow_premises__mutmut_*",
    "symbolic_friction._certify.sup_flow.x__paper_p__mutmut_*",
    "symbolic_friction._certify.sup_flow.x__decide__mutmut_*",
    "symbolic_friction._certify.sup_flow.x_verify_sup_flow__mutmut_*",
    "symbolic_friction._certify.sup_flow.x__exact__mutmut_*",
    "symbolic_friction._certify.sup_flow.x_load_sup_flow__mutmut_*",
    "symbolic_friction._certify.sup_flow.xǁSupFlowPieceǁ__post_init____mutmut_*",
    "symbolic_friction._certify.sup_flow.xǁSupFlowPieceǁk_matrix__mutmut_*",
    "symbolic_friction._certify.sup_flow.xǁSupFlowCertificateǁ__post_init____mutmut_*",
    "symbolic_friction._certify.sup_flow.xǁSupFlowCertificateǁfrom_dict__mutmut_*",
    "symbolic_friction._model.sup_flow.*",
    "symbolic_friction._obligations._inequalities.x_is_nonneg__mutmut_*",
    "symbolic_friction._obligations._inequalities.x__is_bound_of__mutmut_*",
)

PENDING: tuple[str, ...] = (
    # the exit forms moved out of sup_flow_enclosure into sup_flow_forms (check's speed-up): both re-enter mutmut's run
    "symbolic_friction._certify.sup_flow_enclosure.*",
    "symbolic_friction._certify.sup_flow_forms.*",
    # the obligations' speed-up: _field_element's conversion moved to _fastpoly.rational_pair (its equivalents below,
    # argued for _decide's numbering, carry over once re-numbered), and _decide's constructions go through _fastpoly
    "symbolic_friction._obligations._decide.*",
    "symbolic_friction._obligations._fastpoly.x_rational_pair__mutmut_*",
    "symbolic_friction._obligations._fastpoly.x_is_rational_function__mutmut_*",
    # the sup-flow verifier's forms in fmpq and its verdicts shared within shared_flow_decisions(): the premises'
    # mutants are re-numbered (their equivalents below, argued on the old numbering, to be re-checked)
    "symbolic_friction._certify.sup_flow.x_sup_flow_premises__mutmut_*",
    "symbolic_friction._certify.sup_flow.x__decide__mutmut_*",
)
"""In scope, but mutants of these not run since their code changed or joined the scope (``not checked`` in the
report, listed apart: neither killed nor argued; the header says what is left).  Empty: every mutant in scope was run,
so one left ``not checked`` makes the report fail; listed here, it is counted apart until the next run."""

_V = "symbolic_friction._certify.verify."
_H = "symbolic_friction._certify.hunting_proof."
_D = "symbolic_friction._obligations._decide."
_C = "symbolic_friction._cli.check."
_E = "symbolic_friction._certify.sup_flow_enclosure."
_S = "symbolic_friction._certify.sup_flow."
_M = "symbolic_friction._model.sup_flow."
_I = "symbolic_friction._obligations._inequalities."
EQUIVALENT: dict[str, str] = {
    _V + "x_decide__mutmut_76": "the Inequality rebuilt for margin() gets obligation None: margin() reads only op, lhs and rhs",
    _V + "x_decide__mutmut_77": "the Inequality rebuilt for margin() gets name None: margin() reads only op, lhs and rhs",
    _V + "x_premises__mutmut_130": "the identity gets a 4th column: only identity[i][j] with i, j < 3 is read",
    _V + "x_premises__mutmut_132": "the identity gets a 4th row: only identity[i][j] with i, j < 3 is read",
    _V + "x_premises__mutmut_328": "k + zero → k − zero with zero = k_i − k_i, which is 0 for fmpq, Fractions and sympy symbols",
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
    _D + "x__poly_sign__mutmut_16": "Poly.coeffs() lists only non-zero coefficients (p = 0 returned above), so c ≥ 0 is c > 0 on each",
    _D + "x__poly_sign__mutmut_20": "Poly.coeffs() lists only non-zero coefficients (p = 0 returned above), so c ≤ 0 is c < 0 on each",
    _D + "x_affine_image__mutmut_34": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x_affine_image__mutmut_48": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x_affine_image__mutmut_52": "sg = 0 has returned above (a point), so sg ∈ {1, −1} here and sg ≥ 0 is sg > 0",
    _D + "x__stationary_points__mutmut_16": "a degree-0 numerator then reaches roots(), which returns {} (multiplicities sum 0 = degree): [] again",
    _D + "x__stationary_points__mutmut_32": "sympy's solve() reads simplify only by truthiness (if flags.get('simplify', True)): None acts as False",
    _V + "x_premises__mutmut_225": "the stand-in k_v = −1 for 1: k_conditions reads k_v only in k_i·k1/k_v and k_i·k3/k_v, "
    "whose two conditions (DIVIDE_BY_K_V) are replaced by Undefined right below, so every premise is the same",
    _V + "x_premises__mutmut_226": "the stand-in k_v = 2 for 1: k_conditions reads k_v only in k_i·k1/k_v and k_i·k3/k_v, "
    "whose two conditions (DIVIDE_BY_K_V) are replaced by Undefined right below, so every premise is the same",
    _D + "x__coefficient_sign__mutmut_4": "python-flint's fmpz_mpoly.coeffs() lists only the non-zero coefficients (the zero "
    "polynomial has none: 0 returned above), so c ≥ 0 is c > 0 on each",
    _D + "x__coefficient_sign__mutmut_8": "python-flint's fmpz_mpoly.coeffs() lists only the non-zero coefficients (the zero "
    "polynomial has none: 0 returned above), so c ≤ 0 is c < 0 on each",
    _D + "x__coefficient_sign__mutmut_9": "numerator and denominator are fmpz_mpoly over ℤ and coeffs() lists only the non-zero "
    "ones: non-zero integers, and a non-zero integer is < 1 iff it is < 0",
    _D + "x__field_element__mutmut_10": "fmpz_mpoly_ctx.get's default ordering is lex: the same context (the same object)",
    _D + "x__field_element__mutmut_11": "the generators' names only label them in printing (x0, x1, … or XXxXX0, …): the same "
    "polynomials and arithmetic",
    _D + "x__field_element__mutmut_12": "the generators' names only label them in printing (x0, x1, … or X0, …): the same "
    "polynomials and arithmetic",
    _D + "x__field_element__mutmut_17": "one = 2 makes each symbol the pair g/2 while every pair still holds its node's value "
    "(a product starts from 2/2, a sum from 0/2): the fraction is expr at x/2, zero iff expr is, and each coefficient is the "
    "original one times a positive constant, so is_zero and sign_of answer the same",
    _D + "x__field_element__mutmut_63": "sympy never keeps a power with exponent 0 (b**0 is 1), so k ≠ 0 and k ≤ 0 is k < 0",
    _D + "x__field_element__mutmut_64": "sympy never keeps a power with exponent 0 (b**0 is 1), so k ≠ 0 and k < 1 is k < 0",
    _D + "x__field_element__mutmut_71": "sympy never keeps a power with exponent 0 (b**0 is 1), so k ≠ 0 and k > 0 is k ≥ 0",
    _D + "x__field_element__mutmut_72": "sympy never keeps a power with exponent 0 (b**0 is 1), so k ≠ 0 and k ≥ 1 is k ≥ 0",
    _D + "x__convex_quadratic_minimum__mutmut_4": "the domain only chooses how Poly stores the coefficients (the default "
    "one was the code before EX, kept for speed): all_coeffs() are the same values, so α's sign, the cancelled vertex and "
    "f.subs(var, ·) are the same; where either construction fails, the general method gives the same minimum",
    _D + "x__convex_quadratic_minimum__mutmut_7": "the domain only chooses how Poly stores the coefficients (the default "
    "one was the code before EX, kept for speed): all_coeffs() are the same values, so α's sign, the cancelled vertex and "
    "f.subs(var, ·) are the same; where either construction fails, the general method gives the same minimum",
    _E + "x__end__mutmut_25": "mantissa = 0 has returned above, so mantissa ≥ 0 is mantissa > 0",
    _E + "x__end__mutmut_30": "mantissa = 0 has returned above, so mantissa ≥ 0 is mantissa > 0",
    _E + "x__end__mutmut_40": "at exponent 0 both branches give Fraction(mantissa)",
    _E + "x__end__mutmut_41": "at exponent 0 both branches give Fraction(mantissa)",
    _E + "x__upper__mutmut_2": "_end reads down only by truth value (if down: …): None is False",
    _E + "x__exit_holds__mutmut_51": "s runs over (1, −1): s ≥ 0 is s > 0 on both",
    _E + "x__lower_ends_clearly_copositive__mutmut_31": "b = 0 then takes b·b = 0 ≤ a·c, a product of two exact ends ≥ 0 "
    "(arb rounds it outward by less than its size, never below 0): True as b ≥ 0 gives",
    _S + "x_sup_flow_premises__mutmut_112": "after a piece that ends at ∞ the premise 'starts where it ends' must be false: "
    "start − 1 differs from start as start + 1 does",
    _S + "x_sup_flow_premises__mutmut_113": "after a piece that ends at ∞ the premise 'starts where it ends' must be false: "
    "start + 2 differs from start as start + 1 does",
    _S + "x_sup_flow_premises__mutmut_196": "_sub pairs rows and entries with zip: the 4th row and column of a 4×4 p·I are never read",
    _S + "x_sup_flow_premises__mutmut_253": "_sub pairs rows and entries with zip: the 4th row and column of a 4×4 I are never read",
    _S + "x_sup_flow_premises__mutmut_345": "_sub pairs rows and entries with zip: the 4th row and column of a 4×4 γ·I are never read",
    _M + "x_exit_forms__mutmut_18": "sum starts from 0 instead of s − s: 0 + x is x for the Fractions, arb balls, floats and "
    "sympy expressions the callers pass",
    _M + "x_tail_gram__mutmut_7": "sum starts from 0 instead of p − p: 0 + x is x for the Fractions, arb balls, floats and "
    "sympy expressions the callers pass",
    _M + "x_tail_gram__mutmut_22": "sum starts from 0 instead of p − p: 0 + x is x for the Fractions, arb balls, floats and "
    "sympy expressions the callers pass",
    _E + "x__bisect__mutmut_3": "why is set by test() on the first pass of the loop (the stack starts as [(a, b)]) "
    "before it is read",
    _C + "x_run__mutmut_25": "as_json is read only by truth value (if, not, and emit's err=, which picks the stream by it): None is False",
    _C + "x_run__mutmut_146": "json reads ensure_ascii only by truth value (if self.ensure_ascii: …): None is False",
    _I + "x_is_nonneg__mutmut_23": "a polynomial's denominator 2 for 1: den is read only by the test den > 0, which 2 "
    "passes as 1 does",
    _I + "x_is_nonneg__mutmut_29": "for a number 0 < den ≤ 1 the mutant asks sign_of(den), i.e. den.is_positive, which sympy "
    "decides from den's evalf as it decides den > 0 (where it cannot, the original's comparison raises and the mutant "
    "refuses: neither proves)",
}

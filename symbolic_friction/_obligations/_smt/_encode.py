"""A :class:`~._record.Claim` as an SMT-LIB 2 query in nonlinear real arithmetic: its negation, to be refuted.

The translation is structural, term by term, so what the solver sees is the
expression the package decided, not a form the package computed from it:

* every symbol is a ``Real``; its sympy assumptions become hypotheses
  (``positive`` ``> 0``, ``nonnegative`` ``≥ 0``, …);
* ``+``, ``×`` and integer powers are themselves; a negative power is a
  division ``(/ 1 …)`` with the hypothesis that the divisor is not 0 (the
  claim is about the points where the expression is defined);
* ``Abs``, ``Max``, ``Min``, ``sign`` and ``Piecewise`` are ``ite`` terms
  (their conditions translated the same way); a hypothesis made inside a
  branch holds only on that branch;
* anything else (radicals such as ``√u``, ``exp``, ``log``, trigonometric
  functions, floating-point numbers, integer symbols) is *not expressible*,
  with that reason.

The query asserts the hypotheses and the claim's negation: ``unsat`` confirms
the claim, ``sat`` refutes it with a model.  A ``"nonzero"`` claim is
existential, so its query asserts the claim itself and expects ``sat``.

Examples
--------
>>> import sympy as sp
>>> from symbolic_friction._obligations._smt._record import Claim
>>> a = sp.Symbol("a", positive=True)
>>> print(encode(Claim("sign", a + 1/a, 1, "sign_of")).text)
(declare-fun a () Real)
(assert (> a 0))
(assert (not (= a 0)))
(assert (not (> (+ a (/ 1 a)) 0)))
>>> encode(Claim("nonneg", sp.sqrt(a) - 1, None, "is_nonneg"))
Traceback (most recent call last):
...
symbolic_friction._obligations._smt._encode.NotExpressible: a radical (sqrt(a))
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import sympy as sp

from ._record import Claim, RawPolynomial

__all__ = ["ClaimScript", "NotExpressible", "describe", "encode"]


class NotExpressible(Exception):
    """The claim is not a first-order formula of the reals that the translation knows; the message says why."""


@dataclass(frozen=True)
class ClaimScript:
    """One claim's SMT-LIB query.

    Attributes
    ----------
    label : str
        One line: which procedure decided what (ASCII, truncated).
    expect : str
        ``"unsat"`` (the negation of a universal claim) or ``"sat"`` (an existential one).
    declarations, assertions : tuple of str
        The commands, in order.
    names : tuple of (str, str)
        SMT name → the sympy symbol's name, for reading a model.
    """

    label: str
    expect: str
    declarations: tuple[str, ...]
    assertions: tuple[str, ...]
    names: tuple[tuple[str, str], ...]

    @property
    def text(self) -> str:
        """The declarations and assertions, one command a line (no ``check-sat``)."""
        return "\n".join(self.declarations + self.assertions)


_RESERVED = {"and", "or", "not", "ite", "let", "true", "false", "exists", "forall", "par", "as", "assert", "xor",
             "distinct", "select", "store", "abs", "div", "mod", "to_real", "to_int", "is_int", "root", "NUMERAL",
             "DECIMAL", "STRING", "BINARY", "HEXADECIMAL", "match", "_", "!"}

_NAMED_FUNCTIONS = {"exp": "exponential", "log": "logarithm", "LambertW": "Lambert W"}


def _sanitize(name: str) -> str:
    out = "".join(c if (c.isascii() and (c.isalnum() or c in "_.")) else f"u{ord(c):x}" for c in name) or "s"
    if out[0].isdigit() or out[0] == "." or out in _RESERVED:
        out = "v_" + out
    return out


def _number(q: sp.Rational) -> str:
    return _ratio(int(q.p), int(q.q))


def _ratio(p: int, d: int) -> str:
    """``p/d`` (``d > 0``, in lowest terms) as SMT-LIB text; on Python ints (sympy's comparisons cost more than
    the text: an export writes about 10⁵ numbers)."""
    text = str(abs(p)) if d == 1 else f"(/ {abs(p)} {d})"
    return f"(- {text})" if p < 0 else text


def _app(op: str, parts: list[str]) -> str:
    return parts[0] if len(parts) == 1 else f"({op} {' '.join(parts)})"


class _Encoder:
    """Translates terms and formulas, collecting the hypotheses they need (each under its branch's path)."""

    def __init__(self, symbols: list[sp.Symbol]) -> None:
        self.names: dict[sp.Symbol, str] = {}
        taken: set[str] = set()
        for s in sorted(symbols, key=lambda s: (s.name, sp.srepr(s))):
            base = _sanitize(s.name)
            name, n = base, 1
            while name in taken:
                n += 1
                name = f"{base}_{n}"
            taken.add(name)
            self.names[s] = name
        self.hypotheses: list[str] = []
        self.path: list[str] = []
        self.lets = 0
        self.memo: dict[tuple[Any, tuple[str, ...]], str] = {}

    # -- hypotheses and fresh names
    def hypothesis(self, formula: str) -> None:
        if self.path:
            formula = f"(=> {_app('and', self.path)} {formula})"
        if formula not in self.hypotheses:
            self.hypotheses.append(formula)

    def let(self, value: str, body: Any) -> str:
        if re.fullmatch(r"[A-Za-z_][\w.!]*|\d+", value):
            return body(value)
        self.lets += 1
        name = f"t!{self.lets}"
        return f"(let (({name} {value})) {body(name)})"

    # -- terms
    def power(self, base: sp.Expr, n: int) -> str:
        text = self.term(base)
        return text if n == 1 else self.let(text, lambda t: _app("*", [t] * n))

    def pow(self, e: sp.Pow) -> str:
        base, exp = e.base, e.exp
        if base is sp.E or not exp.is_Rational:
            raise NotExpressible("exponential (exp)" if base is sp.E else f"a symbolic exponent ({sp.sstr(e)[:60]})")
        if exp.is_Integer:
            if exp > 0:
                return self.power(base, int(exp))
            den = self.power(base, -int(exp))
            self.hypothesis(f"(not (= {self.term(base)} 0))")
            return f"(/ 1 {den})"
        raise NotExpressible(f"a radical ({sp.sstr(e)[:60]})")

    def mul(self, e: sp.Mul) -> str:
        num: list[str] = []
        den: list[str] = []
        for a in e.args:
            if isinstance(a, sp.Pow) and a.exp.is_Integer and a.exp < 0:
                den.append(self.power(a.base, -int(a.exp)))
                self.hypothesis(f"(not (= {self.term(a.base)} 0))")
            elif a.is_Rational and a.q != 1:
                if a.p != 1:
                    num.append(_ratio(int(a.p), 1))
                den.append(str(a.q))
            else:
                num.append(self.term(a))
        top = _app("*", num) if num else "1"
        return f"(/ {top} {_app('*', den)})" if den else top

    def piecewise(self, e: sp.Piecewise) -> str:
        branches: list[tuple[str, str]] = []
        before: list[str] = []
        for expr, cond in e.args:
            self.path.extend(before)  # a condition is evaluated only where the earlier ones fail
            c = self.formula(cond)
            self.path.append(c)
            value = self.term(expr)
            del self.path[len(self.path) - len(before) - 1:]
            branches.append((value, c))
            if c == "true":
                break
            before.append(f"(not {c})")
        if branches[-1][1] != "true":
            self.hypothesis(_app("or", [c for _, c in branches]))  # defined only where some branch applies
        out = branches[-1][0]
        for value, c in reversed(branches[:-1]):
            out = f"(ite {c} {value} {out})"
        return out

    def extremum(self, args: tuple, op: str) -> str:
        out = self.term(args[0])
        for a in args[1:]:
            b = self.term(a)
            out = self.let(out, lambda t, b=b: self.let(b, lambda u: f"(ite ({op} {t} {u}) {t} {u})"))
        return out

    def term(self, e: Any) -> str:
        key = (e, tuple(self.path))
        if key not in self.memo:
            self.memo[key] = self._term(e)
        return self.memo[key]

    def _term(self, e: Any) -> str:
        if isinstance(e, sp.Symbol):
            return self.names[e]
        if e.is_Rational:
            return _number(e)
        if isinstance(e, sp.Float):
            raise NotExpressible("a floating-point number")
        if isinstance(e, sp.Add):
            return _app("+", [self.term(a) for a in e.args])
        if isinstance(e, sp.Mul):
            return self.mul(e)
        if isinstance(e, sp.Pow):
            return self.pow(e)
        if isinstance(e, sp.Abs):
            return self.let(self.term(e.args[0]), lambda t: f"(ite (>= {t} 0) {t} (- {t}))")
        if isinstance(e, sp.sign):
            return self.let(self.term(e.args[0]), lambda t: f"(ite (> {t} 0) 1 (ite (< {t} 0) (- 1) 0))")
        if isinstance(e, sp.Max):
            return self.extremum(e.args, ">=")
        if isinstance(e, sp.Min):
            return self.extremum(e.args, "<=")
        if isinstance(e, sp.Piecewise):
            return self.piecewise(e)
        if isinstance(e, sp.Function):
            name = type(e).__name__
            raise NotExpressible(f"{_NAMED_FUNCTIONS.get(name, 'a transcendental function')} ({name})")
        raise NotExpressible(f"{type(e).__name__} ({sp.sstr(e)[:60]})")

    def formula(self, c: Any) -> str:
        if c is sp.true or c is True:
            return "true"
        if c is sp.false or c is False:
            return "false"
        rel = {sp.Equality: "=", sp.StrictLessThan: "<", sp.LessThan: "<=", sp.StrictGreaterThan: ">", sp.GreaterThan: ">="}
        for kind, op in rel.items():
            if isinstance(c, kind):
                return f"({op} {self.term(c.lhs)} {self.term(c.rhs)})"
        if isinstance(c, sp.Unequality):
            return f"(not (= {self.term(c.lhs)} {self.term(c.rhs)}))"
        if isinstance(c, (sp.And, sp.Or)):
            return _app("and" if isinstance(c, sp.And) else "or", [self.formula(a) for a in c.args])
        if isinstance(c, sp.Not):
            return f"(not {self.formula(c.args[0])})"
        raise NotExpressible(f"the condition {type(c).__name__}")

    def assumptions(self) -> list[str]:
        out = []
        for s, name in self.names.items():
            if s.is_integer:
                raise NotExpressible(f"the integer symbol {s}")
            for test, op in (("is_positive", ">"), ("is_negative", "<"), ("is_nonnegative", ">="), ("is_nonpositive", "<=")):
                if getattr(s, test):
                    out.append(f"(assert ({op} {name} 0))")
                    break
        return out


def _horner(terms: list[tuple[tuple[int, ...], int]], names: list[str], var: int = 0) -> str:
    """The polynomial ``Σ c·x^m`` in Horner form, variable by variable in the order of ``names``.

    The same polynomial as the sum of its monomials, written with each power of a variable once: about
    half the text, and z3 decides the large ones several times faster.
    """
    if not terms:
        return "0"
    if len(terms) == 1:  # most calls: the text the steps below give one monomial, built without them
        return _monomial(terms[0], names, var)
    while var < len(names) and all(m[var] == 0 for m, _ in terms):
        var += 1
    if var == len(names):  # monomials are distinct, so one constant term is left
        return _ratio(int(sum(c for _, c in terms)), 1)
    groups: dict[int, list[tuple[tuple[int, ...], int]]] = {}
    for m, c in terms:
        groups.setdefault(m[var], []).append((m, c))
    x = names[var]
    out, prev = "", 0
    for d in sorted(groups, reverse=True):  # ((P_n x^(n-m) + P_m) x^(m-k) + P_k) ...
        coeff = _horner(groups[d], names, var + 1)
        out = coeff if not out else f"(+ {coeff} {_app('*', [x] * (prev - d) + [out])})"
        prev = d
    return _app("*", [x] * prev + [out]) if prev else out


def _monomial(term: tuple[tuple[int, ...], int], names: list[str], var: int) -> str:
    """:func:`_horner` of the one term ``c·x^m`` from variable ``var`` on: ``(* x x (* y c))``, innermost last."""
    m, c = term
    text = _ratio(int(c), 1)
    for i in range(len(names) - 1, var - 1, -1):
        if m[i]:
            text = f"(* {' '.join([names[i]] * m[i])} {text})"
    return text


_NEGATION = {("sign", 1): ("(not (> {} 0))", "> 0"), ("sign", 0): ("(not (= {} 0))", "= 0"),
             ("sign", -1): ("(not (< {} 0))", "< 0"), ("nonneg", None): ("(not (>= {} 0))", ">= 0"),
             ("zero", None): ("(not (= {} 0))", "= 0 identically"), ("nonzero", None): ("(not (= {} 0))", "!= 0 somewhere")}


def describe(claim: Claim, width: int = 160) -> str:
    """One ASCII line: ``"<source>: <expression> <relation>"``, the expression truncated to ``width``."""
    _, rel = _NEGATION[(claim.kind, claim.sign if claim.kind == "sign" else None)]
    if isinstance(claim.expr, RawPolynomial):
        f = claim.expr
        used = [g for i, g in enumerate(f.gens) if any(m[i] for m, _ in f.terms)]
        text = f"a polynomial of {len(f.terms)} terms in {', '.join(used) or 'no variable'}"
    else:
        text = sp.sstr(claim.expr)
    text = text.encode("ascii", "backslashreplace").decode("ascii")
    if len(text) > width:
        text = text[:width] + "..."
    return f"{claim.source}: {text} {rel}"


def encode(claim: Claim) -> ClaimScript:
    """The query refuting ``claim`` (see the module docstring).

    Raises
    ------
    NotExpressible
        With the reason, for an expression outside the translation.
    """
    negation, _ = _NEGATION[(claim.kind, claim.sign if claim.kind == "sign" else None)]
    if isinstance(claim.expr, RawPolynomial):  # every generator is positive (frac_sign's convention)
        f = claim.expr
        names = [_sanitize(g) for g in f.gens]
        used = sorted({i for m, _ in f.terms for i, k in enumerate(m) if k})
        decls = tuple(f"(declare-fun {names[i]} () Real)" for i in used)
        hyps = tuple(f"(assert (> {names[i]} 0))" for i in used)
        body = _horner(sorted(f.terms), names)
        return ClaimScript(describe(claim), "unsat", decls, hyps + (f"(assert {negation.format(body)})",),
                           tuple((names[i], f.gens[i]) for i in used))
    expr = sp.sympify(claim.expr)
    if not isinstance(expr, sp.Expr):
        raise NotExpressible(f"not an expression ({type(expr).__name__})")
    enc = _Encoder(sorted(expr.free_symbols, key=lambda s: (s.name, sp.srepr(s))))
    body = enc.term(expr)
    decls = [f"(declare-fun {n} () Real)" for n in enc.names.values()]
    asserts = enc.assumptions() + [f"(assert {h})" for h in enc.hypotheses] + [f"(assert {negation.format(body)})"]
    return ClaimScript(describe(claim), "sat" if claim.kind == "nonzero" else "unsat", tuple(decls), tuple(asserts),
                       tuple((n, s.name) for s, n in enc.names.items()))

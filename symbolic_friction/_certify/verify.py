"""Exact verification of a certificate: Lemma 2, Lemma 3 and Proposition 1 instantiated with the certificate's numbers,
decided in rational arithmetic.

This is the only place where a certificate is called *proved*.  It uses exact rational arithmetic only (no floats, no
solver): the certificate's :class:`fractions.Fraction` numbers are decided as python-flint ``fmpq`` rationals, the
same values in FLINT's arithmetic, several times faster than ``Fraction``'s (a gain map verifies a certificate per
point), and it shares no code with the search (:mod:`._certify.search`, :mod:`._certify.rounding`): the matrices
come from the model's own entry functions (:func:`~symbolic_friction._model.lyapunov.lyapunov_matrix_entries`,
:func:`~symbolic_friction._model.lyapunov.vhat_matrix_entries`), the k-conditions from
:mod:`symbolic_friction._model.kconditions`, and positive semidefiniteness is decided by *all* principal minors (a
symmetric matrix is PSD iff every principal minor is ``≥ 0``).

The inequalities checked (each one a :class:`Check` in the report):

* Assumption 1 (which makes ``P ≻ 0``, obligation ``lemma2.P``): ``k_i > 0``, ``k_p > 0``, ``k_v k_p > k_i``; and ``f_c > 0``.
* Lemma 2: ``c = 2(k_v k_p - k_i)`` exactly and ``c > 0`` (item 2, ``lemma2.dVdt``); ``c₁ > 0`` and
  ``P - c₁I ⪰ 0``, i.e. ``c₁ ≤ λ_min(P)`` (item 1, ``lemma2.lower_bound``).
* Lemma 3, eq. (VandR): ``c₂I - P ⪰ 0``, i.e. ``c₂ ≥ λ_max(P)`` (``lemma3.R``).
* Lemma 3, eq. (hatVdot): the k-conditions ``k_j > 0``, ``k₃ > (k_i/k_v)k₁``, ``k₃ > k₂``, ``k₄ > (k_i/k_v)k₃``,
  ``k₄ > k_p k₂`` (``lemma3.hatV_derivative``).
* Lemma 3, eq. (hatVandHatR): ``k₁k₄ > k₃²`` (the paper's ``K ≻ 0``; not needed for the bounds below but part
  of the paper's conditions), and, for the nonnegative vector ``w = (|σ|, |dz(φ)|, |v|)``, ``0 < ĉ₁ ≤ k_j/2`` for
  ``j ∈ {1, 2, 4}`` (valid because ``k₃ ≥ 0`` and ``w ≥ 0`` make ``½wᵀKw ≥ ½min(k₁,k₂,k₄)|w|²``) and
  ``ĉ₂I - K/2 ⪰ 0`` (``lemma3.hatV_bounds``).
* Proposition 1, eq. (stabState): ``c₁ ≤ c₂``, ``ĉ₁ ≤ ĉ₂`` (so ``κ ≥ 1``) and ``overshoot_bound² ≥ c₂ĉ₂/(c₁ĉ₁)`` (``prop1.stability_bound``).

Signs are premises like the rest: a file may hold any exact rational, and a gain or constant of the wrong sign
is refused here, naming the premise (``k1 > 0: -2 > 0 is false``).  ``k_v`` has no premise of its own:
Assumption 1 implies ``k_v > 0`` (``k_v k_p > k_i > 0`` with ``k_p > 0``), so ``k_v ≤ 0`` always fails one of
its three premises.  A premise whose instance would divide by zero (``P`` has ``k_v/k_i``, the k-conditions
``k_i/k_v``, the bound ``c₁ĉ₁`` in a denominator) is not evaluated: it is reported as failing
(:class:`Undefined`), beside the sign premise that the zero breaks, and nothing raises.
"""

from __future__ import annotations

import dataclasses
import itertools
import os
import re
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any, Sequence

from flint import fmpq

from .._infra.errors import CertificateError
from .._infra.guards import ParameterTypeError, check_instance, check_items, check_path
from .._model.kconditions import CONDITION_NAMES, k_conditions
from .._model.lyapunov import lyapunov_matrix_entries, vhat_matrix_entries
from .._infra.rational import format_rational
from .certificate import CONSTANT_NAMES, PARAMETER_NAMES, Certificate, kappa_squared, load

__all__ = ["Check", "VerificationReport", "Inequality", "Semidefinite", "Undefined", "premises", "decide", "verify_certificate", "verify_file"]


@dataclass(frozen=True)
class Check:
    """One instantiated inequality and its exact verdict.

    Attributes
    ----------
    obligation : str
        Id of the proof obligation it instantiates (e.g. ``"lemma3.hatV_bounds"``).
    name : str
        The inequality in symbols, e.g. ``"k3 > k2"``.
    instance : str
        The same with the certificate's exact numbers, e.g. ``"1/2 > 3/5"``.
    holds : bool
        Exact verdict.
    evaluated : bool
        False when the instance could not be formed (a zero divisor): the
        check then fails and ``instance`` says why.
    """

    obligation: str
    name: str
    instance: str
    holds: bool
    evaluated: bool = True

    @property
    def message(self) -> str:
        """``"k3 > k2: 1/2 > 3/5 is false"`` (or without ``is false`` when it holds; ``not evaluated (…)`` when undefined)."""
        if not self.evaluated:
            return f"{self.name}: not evaluated ({self.instance})"
        return f"{self.name}: {self.instance}" + ("" if self.holds else " is false")

    def __str__(self) -> str:
        return f"{'✓' if self.holds else '✗'} {self.message}"


@dataclass(frozen=True)
class VerificationReport:
    """The per-inequality result of :func:`verify_certificate`.

    Attributes
    ----------
    certificate : Certificate
    checks : tuple of Check
        In paper order.
    source : str
        File name or ``"<certificate>"``.
    """

    certificate: Certificate
    checks: tuple[Check, ...]
    source: str = "<certificate>"

    def __post_init__(self) -> None:
        """Refuse a report no verifier returns (``VerificationReport("x", "y")``), naming the field (a :class:`ParameterTypeError`)."""
        cert = self.certificate  # a subclass's (a template beyond the paper's) is its template's: a dataclass with the gains
        if type(self) is VerificationReport or not (dataclasses.is_dataclass(cert) and all(hasattr(cert, n) for n in PARAMETER_NAMES)):
            check_instance(cert, Certificate, name="certificate", what="a Certificate (verify_certificate makes reports)")
        object.__setattr__(self, "checks", tuple(check_items(self.checks, name="checks", what="a tuple of Check", high=10**6, kind=Check)))
        check_instance(self.source, str, name="source", what="a str (a file name)")

    @property
    def proved(self) -> bool:
        """True iff every inequality holds exactly (a report that checked nothing proves nothing)."""
        return bool(self.checks) and all(check.holds for check in self.checks)

    @property
    def failures(self) -> tuple[Check, ...]:
        """The inequalities that do not hold."""
        return tuple(check for check in self.checks if not check.holds)

    def summary(self) -> str:
        """One line: ``PROVED file (κ ≤ 3.69516)`` or ``FAILED file: k3 > k2: … is false; …``."""
        if self.proved:
            return (
                f"PROVED {self.source}: all {len(self.checks)} inequalities hold; "
                f"|x(t)|_A <= {self.certificate.overshoot_bound}·|x(0)|_A"
            )
        return f"FAILED {self.source}: " + "; ".join(check.message for check in self.failures)

    def raise_if_failed(self) -> None:
        """Raise :class:`~symbolic_friction.CertificateError` naming every failed inequality."""
        if not self.proved:
            raise CertificateError(self.summary())


# -- the premises, built once with plain arithmetic -------------------------------------


@dataclass(frozen=True)
class Inequality:
    """One premise ``lhs op rhs`` the verifier decides.

    Built with plain arithmetic from the certificate's numbers, so the same
    premise is a Fraction comparison at verification time and a sympy
    relation in the obligation ``certificate.verifier``, which shows that
    the premises imply every claim of the certificate.
    """

    obligation: str
    name: str
    lhs: Any
    op: str
    rhs: Any
    rhs_text: str | None = None
    rhs_terms: tuple[Any, ...] = ()

    def margin(self) -> tuple[Any, str]:
        """``(m, kind)`` with the premise equivalent to ``m > 0``, ``m ≥ 0`` or ``m = 0`` (kind ``">"``, ``">="``, ``"=="``)."""
        if self.op == "<=":
            return self.rhs - self.lhs, ">="
        return self.lhs - self.rhs, self.op


@dataclass(frozen=True)
class Semidefinite:
    """The premise ``matrix ⪰ 0``, decided by *all* its principal minors (``≥ 0``)."""

    obligation: str
    name: str
    matrix: tuple[tuple[Any, ...], ...]

    def minors(self) -> list[tuple[tuple[int, ...], Any]]:
        """``(rows, minor)`` for every principal minor, smallest first."""
        n = len(self.matrix)
        return [
            (idx, _det([[self.matrix[i][j] for j in idx] for i in idx]))
            for size in range(1, n + 1)
            for idx in itertools.combinations(range(n), size)
        ]


DIVIDE_BY_K_V: tuple[str, ...] = tuple(name for name in CONDITION_NAMES if "k_i/k_v" in name)
"""The k-conditions (:data:`~symbolic_friction._model.kconditions.CONDITION_NAMES`) whose right side divides by ``k_v``."""


@dataclass(frozen=True)
class Undefined:
    """A premise whose instance is undefined for these numbers (it would divide by zero): it fails, unevaluated.

    Only exact numbers can be zero here; for sympy symbols the premise is built as usual.
    """

    obligation: str
    name: str
    reason: str


def _fraction(value: Any) -> Any:
    """``value`` as a Fraction when it is an ``fmpq`` (for the file format's writer), else unchanged."""
    return Fraction(int(value.p), int(value.q)) if type(value) is fmpq else value


def _f(value: Any) -> str:
    """The file format's text of an exact rational, ``fmpq`` or ``Fraction``."""
    return format_rational(_fraction(value))


def _is_zero(value: Any) -> bool:
    """True for an exact zero (a sympy symbol compares structurally, so it is never zero here)."""
    return bool(value == 0)


def _det(m: Sequence[Sequence[Any]]) -> Any:
    """Determinant by cofactor expansion (the matrices here are at most 3×3), in the entries' own arithmetic."""
    n = len(m)
    if n == 0:
        return Fraction(1)
    if n == 1:
        return m[0][0]
    if n == 2:  # written out: the verifier decides thousands of these per gain map
        return m[0][0] * m[1][1] - m[0][1] * m[1][0]
    if n == 3:  # the cofactor expansion below along the first row, written out (and for the same reason)
        (a, b, c), (d, e, f), (g, h, i) = m
        return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    total = 0
    for j in range(n):
        if m[0][j] == 0:
            continue
        minor = [row[:j] + row[j + 1 :] for row in m[1:]]
        total += (-1) ** j * m[0][j] * _det(minor)
    return total


def premises(cert: Any) -> list[Inequality | Semidefinite | Undefined]:
    """Every inequality the verifier decides, in paper order, for a certificate-like ``cert``.

    ``cert`` has the attributes of :class:`~.certificate.Certificate`
    (``k_p … f_c``, ``k1 … k4``, ``c``, ``c1``, ``c2``, ``c1_hat``, ``c2_hat``)
    and ``kappa``, the claimed overshoot bound as a number.  Only plain
    arithmetic is used, so Fractions and sympy symbols both work.  Numbers of
    any sign are accepted; where one is a zero divisor the premises that
    divide by it are :class:`Undefined` (module docstring).
    """
    k_p, k_i, k_v, f_c = cert.k_p, cert.k_i, cert.k_v, cert.f_c
    zero = k_i - k_i
    out: list[Inequality | Semidefinite | Undefined] = [
        Inequality("lemma2.P", "k_i > 0", k_i, ">", zero),
        Inequality("lemma2.P", "k_p > 0", k_p, ">", zero),
        Inequality("lemma2.P", "k_v·k_p > k_i", k_v * k_p, ">", k_i),
        Inequality("model", "f_c > 0", f_c, ">", zero),
        Inequality("lemma2.dVdt", "c = 2(k_v·k_p − k_i)", cert.c, "==", 2 * (k_v * k_p - k_i), "2·({} − {})", (k_v * k_p, k_i)),
        Inequality("lemma2.dVdt", "c > 0", cert.c, ">", zero),
        Inequality("lemma2.lower_bound", "c1 > 0", cert.c1, ">", zero),
    ]
    identity = [[int(i == j) for j in range(3)] for i in range(3)]
    if _is_zero(k_i):  # P₁₁ = k_v/k_i (eq. lyapLikeP); "k_i > 0" above fails too
        why = f"P has the entry k_v/k_i, and k_i = {_f(k_i)}"
        out += [Undefined("lemma2.lower_bound", "P − c1·I ⪰ 0", why), Undefined("lemma3.R", "c2·I − P ⪰ 0", why)]
    else:
        p = lyapunov_matrix_entries(k_p, k_i, k_v)
        out.append(Semidefinite("lemma2.lower_bound", "P − c1·I ⪰ 0", _matrix(p[i][j] - cert.c1 * identity[i][j] for i in range(3) for j in range(3))))
        out.append(Semidefinite("lemma3.R", "c2·I − P ⪰ 0", _matrix(cert.c2 * identity[i][j] - p[i][j] for i in range(3) for j in range(3))))
    # k_i/k_v: with k_v = 0 Assumption 1 fails ("k_v·k_p > k_i" or "k_i > 0"); the conditions without k_v are still
    # decided, on the model's list built with a stand-in k_v = 1 whose conditions that divide by k_v are then replaced
    no_k_v = _is_zero(k_v)
    for cond in k_conditions(k_p, k_i, zero + 1 if no_k_v else k_v, cert.k1, cert.k2, cert.k3, cert.k4):
        # k1·k4 > k3² is the paper's route to K ≻ 0 (eq. hatVandHatR); the rest come from eq. (hatVdot)
        obligation = "lemma3.hatV_bounds" if cond.kind == "definiteness" else "lemma3.hatV_derivative"
        if no_k_v and cond.name in DIVIDE_BY_K_V:
            out.append(Undefined(obligation, cond.name, f"it has k_i/k_v, and k_v = {_f(k_v)}"))
            continue
        out.append(Inequality(obligation, cond.name, cond.lhs, ">" if cond.strict else ">=", cond.rhs))
    k = vhat_matrix_entries(cert.k1, cert.k2, cert.k3, cert.k4)
    out.append(Inequality("lemma3.hatV_bounds", "c1_hat > 0", cert.c1_hat, ">", zero))
    for j, kj in ((1, cert.k1), (2, cert.k2), (4, cert.k4)):
        out.append(Inequality("lemma3.hatV_bounds", f"c1_hat ≤ k{j}/2", cert.c1_hat, "<=", kj / 2))
    out.append(Semidefinite("lemma3.hatV_bounds", "c2_hat·I − K/2 ⪰ 0", _matrix(cert.c2_hat * identity[i][j] - (k[i][j] + zero) / 2 for i in range(3) for j in range(3))))
    kappa = cert.kappa
    out += [
        Inequality("prop1.stability_bound", "c1 ≤ c2", cert.c1, "<=", cert.c2),
        Inequality("prop1.stability_bound", "c1_hat ≤ c2_hat", cert.c1_hat, "<=", cert.c2_hat),
        Inequality("prop1.stability_bound", "overshoot_bound > 0", kappa, ">", zero),
    ]
    bound = "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)"
    if _is_zero(cert.c1 * cert.c1_hat):  # "c1 > 0" or "c1_hat > 0" above fails too
        out.append(Undefined("prop1.stability_bound", bound, f"it divides by c1·c1_hat = {_f(cert.c1)}·{_f(cert.c1_hat)} = 0"))
        return out
    out.append(
        Inequality(
            "prop1.stability_bound",
            bound,
            kappa * kappa,
            ">=",
            kappa_squared(cert.c1, cert.c2, cert.c1_hat, cert.c2_hat),
            "({})/({})",
            (cert.c2 * cert.c2_hat, cert.c1 * cert.c1_hat),
        )
    )
    return out


def _matrix(entries: Any) -> tuple[tuple[Any, ...], ...]:
    flat = list(entries)
    return tuple(tuple(flat[3 * i : 3 * i + 3]) for i in range(3))


# -- the decision, in exact rationals only ------------------------------------------------

_DECIDE = {">": lambda m: m > 0, ">=": lambda m: m >= 0, "==": lambda m: m == 0}
_SYMBOL = {">": ">", ">=": "≥", "<=": "≤", "==": "="}


def _exact(value: Any, what: str) -> fmpq:
    """``value`` as an ``fmpq``; anything but an int or a rational (``Fraction``, ``fmpq``) is refused."""
    if type(value) is fmpq:  # the common case, without a copy
        return value
    if isinstance(value, bool) or not isinstance(value, (int, Fraction)):
        raise CertificateError(f"{what}: the verifier decides exact rationals only; got {type(value).__name__} {value!r}")
    return fmpq(value.numerator, value.denominator)


def _text(q: fmpq) -> str:
    """``format_rational(q)``, from FLINT's decimal digits (exact at any size, and faster than ``str(fmpq)``)."""
    num = q.p.str()
    return num if q.q == 1 else f"{num}/{q.q.str()}"


def _matrix_text(m: Sequence[Sequence[Fraction]]) -> str:
    return "[" + "; ".join(", ".join(_text(x) for x in row) for row in m) + "]"


def decide(premise: Inequality | Semidefinite | Undefined) -> Check:
    """Decide one premise in exact rational arithmetic (the only place a premise is judged); an undefined one fails."""
    if isinstance(premise, Undefined):
        return Check(premise.obligation, premise.name, premise.reason, False, evaluated=False)
    if isinstance(premise, Semidefinite):
        matrix = [[_exact(x, premise.name) for x in row] for row in premise.matrix]
        # through the premise's own minors(): the obligation certificate.decision is about that method
        minors = dataclasses.replace(premise, matrix=tuple(map(tuple, matrix))).minors()
        negative = [(idx, d) for idx, d in minors if not d >= 0]
        if negative:
            idx, d = negative[0]
            rows = ",".join(str(i + 1) for i in idx)
            # `Check.message` appends "is false": the instance states the claim, then the witness
            instance = f"{_matrix_text(matrix)} ⪰ 0 (principal minor {{{rows}}} = {_f(d)} < 0)"
            return Check(premise.obligation, premise.name, instance, False)
        smallest = min(d for _, d in minors)
        instance = f"{_matrix_text(matrix)} ⪰ 0 (all {len(minors)} principal minors ≥ 0, smallest {_text(smallest)})"
        return Check(premise.obligation, premise.name, instance, True)
    lhs, rhs = _exact(premise.lhs, premise.name), _exact(premise.rhs, premise.name)
    # the premise's own margin(): the obligation certificate.verifier reasons about that method
    margin, kind = Inequality(premise.obligation, premise.name, lhs, premise.op, rhs).margin()
    holds = bool(_DECIDE[kind](margin))
    right = _text(rhs)
    if premise.rhs_text is not None:
        terms = (_text(_exact(t, premise.name)) for t in premise.rhs_terms)
        right = f"{premise.rhs_text.format(*terms)} = {right}"
    return Check(premise.obligation, premise.name, f"{_text(lhs)} {_SYMBOL[premise.op]} {right}", holds)


def verify_certificate(certificate: Certificate, *, source: str = "<certificate>") -> VerificationReport:
    """Check every inequality of the certificate exactly.

    Parameters
    ----------
    certificate : Certificate
    source : str, keyword-only
        Name shown in the report (e.g. the file name).

    Returns
    -------
    VerificationReport
        ``report.proved`` is True iff every inequality holds; failing ones are
        named in ``report.failures`` with their exact numbers.

    Raises
    ------
    ParameterTypeError
        If ``certificate`` is not a :class:`Certificate` (also a ``TypeError``).

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> from symbolic_friction._certify import certify
    >>> verify_certificate(certify(Parameters.table_i("a"))).proved
    True
    """
    if not isinstance(certificate, Certificate):
        raise ParameterTypeError(f"verify_certificate needs a Certificate; got {type(certificate).__name__}")
    checks = tuple(decide(premise) for premise in premises(_Exact(certificate)))
    checks += provenance_checks(certificate, checks)
    return VerificationReport(certificate=certificate, checks=checks, source=source)


# The labels the package gives Table I's certificates, exactly (free text that merely
# mentions Table I, e.g. "compared with Table I, case (a)", claims nothing).
_TABLE_I_LABEL = re.compile(r"Table I, case \(([ab])\)")


def provenance_checks(certificate: Certificate, proved: Sequence[Check]) -> tuple[Check, ...]:
    """What a certificate says about itself, checked against the proof (exact, like the premises).

    * ``provenance.obligations`` lists only obligations that the premises
      above instantiate (a certificate cannot claim an obligation it does not
      prove);
    * a label that is Table I's (``Table I, case (a)`` or ``(b)``, exactly) carries Table I's gains;
    * recorded physical parameters normalise to the gains (paper §II-A):
      ``k_p = k̄_p/m``, ``k_i = k̄_i/m``, ``k_v = (k̄_d + α_v)/m``, ``f_c = f̄_c/m``.
    """
    out: list[Check] = []
    prov = certificate.provenance
    if prov is not None:
        covered = {c.obligation for c in proved}
        claimed = list(prov.obligations)
        unknown = [o for o in claimed if o not in covered]
        out.append(Check(
            "provenance", "provenance.obligations ⊆ obligations instantiated",
            f"{{{', '.join(claimed)}}} ⊆ {{{', '.join(sorted(covered))}}}"
            + (f" ({', '.join(unknown)} not instantiated)" if unknown else ""),
            not unknown and bool(claimed),
        ))
        match = _TABLE_I_LABEL.fullmatch(prov.label)
        if match is not None:
            from .._model.parameters import TABLE_I

            case = match.group(1).lower()
            table = TABLE_I[case]
            pairs = [(n, getattr(certificate, n), getattr(table, n)) for n in ("k_p", "k_i", "k_v", "f_c")]
            out.append(Check(
                "provenance", f"label {prov.label!r} ⇒ Table I, case ({case}) gains",
                ", ".join(f"{n} = {_f(got)} {'=' if got == want else '≠'} {_f(want)}" for n, got, want in pairs),
                all(got == want for _, got, want in pairs),
            ))
    phys = certificate.physical
    if phys is not None:
        m = phys["m"]
        expected = {
            "k_p": phys["k_p_bar"] / m,
            "k_i": phys["k_i_bar"] / m,
            "k_v": (phys["k_d_bar"] + phys["alpha_v"]) / m,
            "f_c": phys["f_c_bar"] / m,
        }
        for name, formula in (("k_p", "k_p_bar/m"), ("k_i", "k_i_bar/m"), ("k_v", "(k_d_bar + alpha_v)/m"), ("f_c", "f_c_bar/m")):
            got = getattr(certificate, name)
            out.append(Check("provenance", f"{name} = {formula}", f"{_f(got)} = {_f(expected[name])}", got == expected[name]))
    return tuple(out)


FORMAT_RULES: tuple[str, ...] = ("c = 2(k_v·k_p − k_i)", "provenance.obligations ⊆ obligations instantiated", "label ")
"""Checks that are rules of the file format, not premises of the proof (names, or a prefix ending in a space).

``c`` is *defined* as ``2(k_v k_p − k_i)`` (Lemma 2 needs only ``0 < c ≤`` it), a Table I label must carry Table I's
gains, and ``provenance.obligations`` must name what the premises instantiate: a file that breaks only these may
be mathematically sound, so the independent checker, which does not read them, may prove it (``verify`` says so).
"""


def is_format_rule(name: str) -> bool:
    """Whether a check of this name is a format rule (:data:`FORMAT_RULES`), not a premise."""
    return any(name == rule or (rule.endswith(" ") and name.startswith(rule)) for rule in FORMAT_RULES)


def format_rules(report: Any) -> list[str]:
    """The failing checks of a refused report when every one is a format rule (else ``[]``: a premise fails)."""
    failing = [c.name for c in report.checks if not c.holds]
    return failing if failing and all(is_format_rule(n) for n in failing) else []


class _Exact:
    """A certificate's numbers as the premises read them: ``fmpq`` (``kappa`` exact from its decimal string)."""

    def __init__(self, cert: Certificate) -> None:
        # a Certificate holds Fractions only (checked on construction), so each is taken to fmpq as it is
        for name in (*PARAMETER_NAMES, *CONSTANT_NAMES):
            q = getattr(cert, name)
            setattr(self, name, fmpq(q.numerator, q.denominator))
        kappa = cert.kappa  # exact at any length (a plain Fraction(text) stops at 4300 digits)
        self.kappa = fmpq(kappa.numerator, kappa.denominator)


def verify_file(path: str | os.PathLike[str]) -> VerificationReport:
    """Load a certificate file strictly and verify it.

    Raises
    ------
    InputFileError
        If ``path`` is not a ``str`` or ``pathlib.Path`` (``3``, ``None``, ``b"x.json"``), or does not name a
        readable regular file of bounded size (read by the package's bounded reader).
    CertificateFormatError
        If the file is not a well-formed certificate (the message names the key).
    """
    return verify_certificate(load(check_path(path, name="path", what="certificate file")), source=str(Path(path)))

"""The reset-PID contraction certificate: reset PID settles exponentially near 𝒜 (beyond the paper).

For Coulomb friction (``f_s = f_c``) and gains whose slip from a stick ends
(``E₃₁ = (e^{Aτ})₃₁`` has a first zero ``τ*``), the stick exits of reset PID
obey ``|σ_k| ≤ ρ^k|σ_0|`` with ``ρ ≥ |E₁₁(τ*)|``, ``ρ < 1``, from a stick exit
with ``|σ_0| ≤ radius``, and come at most ``cycle_time`` apart; so
``|σ(t)| ≤ tol·|σ_0|`` (and ``|s(t)| ≤ tol·|s_0|``, ``s = −σ/k_i``) for ``t ≥
settling_time``.  The paper's PID has the same ``σ_k`` but, after an
overshoot, sticks for a time unbounded as ``σ → 0`` (§IV: asymptotic, not
exponential).  The derivation and every premise are in
:mod:`.reset_contraction_proof`, which decides them (exact rationals, arb
balls); the reset is :mod:`symbolic_friction._model.reset`'s, its idea
Bisoffi et al. (*To stick or to slip*, Annu. Rev. Control 49, 2020).

The dwell: a file holds for every dwell time ``τ_d ≤ max(dwell, τ_lo)`` (a
jump at most every ``τ_d``; ``Parameters.reset_dwell``).  A dwell shorter than
the slip never delays a reset, so ``dwell = 0`` covers every ``τ_d ≤ τ_lo``:
after an overshoot the radius is ``f_c/|E₂₁(τ*)|`` and ``cycle_time`` is ``τ*``
rounded up.  A longer dwell shrinks the radius to ``f_c/(|E₂₁| + ρ(dwell −
τ_lo))`` (the stick must still have ``σφ ≤ 0`` when the timer allows the reset)
and makes ``cycle_time ≥ dwell``.  Without an overshoot the dwell does not
enter (radius ``2f_c/|E₂₁|``, cycle ``τ* + |E₂₁|/E₁₁``: a reset only shortens
the stick).

Format (``schema`` ``symbolic-friction/reset-contraction-certificate/v1``,
``template`` ``reset-contraction/v1``; keys sorted, exact rational strings)::

    {"cycle_time": …, "dwell": "0", "overshoot": true,
     "parameters": {"f_c": "1", "k_i": "4", "k_p": "3", "k_v": "32/5"},
     "provenance": {"label": …, "package": "symbolic-friction", "search": …},
     "radius": …, "rho": …, "schema": …, "template": "reset-contraction/v1",
     "settling": {"cycles": 9, "time": …, "tol": "1/1000"},
     "slip": {"monotone_from": …, "tau": [lo, hi]}}

:func:`certify_contraction` finds the numbers in floats (the first zero of
``E₃₁`` on a grid, refined), rounds them outward to short rationals (``rho``
up, ``radius`` down, 6 digits) and verifies the result; the file is stale when
it is not the canonical text of its own numbers, and drifts when the search
writes other numbers now.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from .._infra.bounds import bound_text
from .._infra.errors import CertificateError, CertificateFormatError, ParameterError
from .._infra.rational import format_rational as _f
from .._model.parameters import Parameters
from ._template import Template, register
from .quadratic import PARAMETERS, Gains, canonical_staleness, check_provenance
from .reset_contraction_proof import ContractionProof, decide_contraction
from .verify import Check, VerificationReport

__all__ = ["SCHEMA", "TEMPLATE_ID", "ContractionCertificate", "ContractionProvenance", "ContractionReport",
           "certify_contraction", "candidate_at", "verify_contraction", "dumps_contraction", "load_contraction", "regenerate_contraction",
           "RESET_CONTRACTION"]

SCHEMA = "symbolic-friction/reset-contraction-certificate/v1"
TEMPLATE_ID = "reset-contraction/v1"
_TOP = ("schema", "template", "parameters", "slip", "overshoot", "rho", "radius", "dwell", "cycle_time", "settling")
_PROVENANCE = ("package", "search", "label")
MAX_CYCLES = 10_000
"""``settling.cycles`` a file may hold (the verifier raises ``rho`` to it exactly)."""
SEARCH = "float first zero of E31, outward rounding, arb verification"


def _up(q: Fraction) -> str:
    """An upper bound (ρ, a time by which something holds) printed rounded up: never a stronger claim."""
    return bound_text(q, 6, direction="up")


def _down(q: Fraction) -> str:
    """A hypothesis' limit (the radius, the longest dwell) printed rounded down: never a weaker hypothesis."""
    return bound_text(q, 6, direction="down")


def _exact(value: Any, what: str) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, (int, Fraction)):
        raise CertificateFormatError(f"{what} must be an exact rational; got {value!r}")
    return Fraction(value)


@dataclass(frozen=True)
class ContractionProvenance:
    """How the file was found (informative; never part of the proof)."""

    label: str = ""
    search: str = SEARCH
    package: str = "symbolic-friction"

    def __post_init__(self) -> None:
        check_provenance(self, _PROVENANCE)


@dataclass(frozen=True)
class ContractionCertificate(Gains):
    """A reset-PID contraction certificate: every number exact, of any sign (the signs are premises).

    Parameters
    ----------
    k_p, k_i, k_v, f_c : Fraction
        The gains (``f_s = f_c``).
    tau_lo, tau_hi : Fraction
        An interval that holds ``τ*``, the first zero of ``E₃₁``.
    monotone_from : Fraction
        ``τ_a``: ``E₃₁`` falls on ``[τ_a, τ_lo]``.
    overshoot : bool
        Whether ``E₁₁(τ*) < 0``.
    rho, radius, dwell, cycle_time : Fraction
        ``ρ ≥ |E₁₁(τ*)|``, the radius in ``σ``, the dwell it holds for (every
        ``τ_d ≤ max(dwell, τ_lo)``), the longest time between stick exits.
    tol : Fraction
        The stated tolerance; ``cycles`` (int) exits bring ``|σ|`` below ``tol·|σ_0|``
        (``rho^cycles ≤ tol``), by ``settling_time`` (Fraction).
    provenance : ContractionProvenance

    Raises
    ------
    CertificateFormatError
        If a number is not exact, ``overshoot`` not a bool, or ``cycles`` not an integer in ``[0, MAX_CYCLES]``.

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> cert = certify_contraction(Parameters.table_i("a"))
    >>> cert.overshoot, float(cert.rho), cert.cycles
    (True, 0.458633, 9)
    >>> verify_contraction(cert).proved
    True
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_c: Fraction
    tau_lo: Fraction
    tau_hi: Fraction
    monotone_from: Fraction
    overshoot: bool
    rho: Fraction
    radius: Fraction
    dwell: Fraction
    cycle_time: Fraction
    tol: Fraction
    cycles: int
    settling_time: Fraction
    provenance: ContractionProvenance = field(default_factory=ContractionProvenance)

    def __post_init__(self) -> None:
        for name in (*PARAMETERS, "tau_lo", "tau_hi", "monotone_from", "rho", "radius", "dwell", "cycle_time", "tol",
                     "settling_time"):
            object.__setattr__(self, name, _exact(getattr(self, name), name))
        if not isinstance(self.overshoot, bool):
            raise CertificateFormatError(f"overshoot must be true or false; got {self.overshoot!r}")
        if isinstance(self.cycles, bool) or not isinstance(self.cycles, int) or not 0 <= self.cycles <= MAX_CYCLES:
            raise CertificateFormatError(f"settling.cycles must be an integer in [0, {MAX_CYCLES}]; got {self.cycles!r}")
        if not isinstance(self.provenance, ContractionProvenance):
            raise CertificateFormatError(f"provenance must be a ContractionProvenance; got {type(self.provenance).__name__}")

    @property
    def claim_column(self) -> str:
        """What ``check``'s short column shows: ``ρ`` rounded up."""
        return f"ρ≤{_up(self.rho)}" if self.rho > 0 else f"ρ={_f(self.rho)}"

    def to_dict(self) -> dict[str, Any]:
        return {
            "schema": SCHEMA, "template": TEMPLATE_ID,
            "parameters": {name: _f(value) for name, value in self.parameters.items()},
            "slip": {"tau": [_f(self.tau_lo), _f(self.tau_hi)], "monotone_from": _f(self.monotone_from)},
            "overshoot": self.overshoot, "rho": _f(self.rho), "radius": _f(self.radius), "dwell": _f(self.dwell),
            "cycle_time": _f(self.cycle_time),
            "settling": {"tol": _f(self.tol), "cycles": self.cycles, "time": _f(self.settling_time)},
            "provenance": {name: getattr(self.provenance, name) for name in _PROVENANCE},
        }

    @classmethod
    def from_dict(cls, data: object, *, source: str = "<string>") -> "ContractionCertificate":
        """Parse strictly; :class:`CertificateFormatError` names ``source`` and the member that is wrong."""
        from .certificate import _check_keys, _signed_rational_field as num

        try:
            if not isinstance(data, dict):
                raise CertificateFormatError(f"a reset-contraction certificate is a JSON object; got {type(data).__name__}")
            _check_keys(data, required=_TOP, optional=("provenance",), where="certificate")
            if data["schema"] != SCHEMA or data["template"] != TEMPLATE_ID:
                raise CertificateFormatError(f"schema {data['schema']!r} / template {data['template']!r} is not {SCHEMA} / {TEMPLATE_ID}")
            parts = {}
            for key, required in (("parameters", PARAMETERS), ("slip", ("tau", "monotone_from")),
                                  ("settling", ("tol", "cycles", "time")), ("provenance", ())):
                value = data.get(key, {})
                if not isinstance(value, dict):
                    raise CertificateFormatError(f"{key} must be a JSON object; got {type(value).__name__}")
                _check_keys(value, required=required, optional=_PROVENANCE if key == "provenance" else (), where=key)
                parts[key] = value
            tau = parts["slip"]["tau"]
            if not (isinstance(tau, list) and len(tau) == 2):
                raise CertificateFormatError(f"slip.tau must be a list [lo, hi] of two rational strings; got {tau!r:.80}")
            cycles = parts["settling"]["cycles"]
            if isinstance(cycles, bool) or not isinstance(cycles, int):
                raise CertificateFormatError(f"settling.cycles must be a JSON integer; got {cycles!r:.40}")
            return cls(
                **{n: num(parts["parameters"][n], f"parameters.{n}") for n in PARAMETERS},
                tau_lo=num(tau[0], "slip.tau[0]"), tau_hi=num(tau[1], "slip.tau[1]"),
                monotone_from=num(parts["slip"]["monotone_from"], "slip.monotone_from"),
                overshoot=data["overshoot"], rho=num(data["rho"], "rho"), radius=num(data["radius"], "radius"),
                dwell=num(data["dwell"], "dwell"), cycle_time=num(data["cycle_time"], "cycle_time"),
                tol=num(parts["settling"]["tol"], "settling.tol"), cycles=cycles,
                settling_time=num(parts["settling"]["time"], "settling.time"),
                provenance=ContractionProvenance(**parts["provenance"]),
            )
        except CertificateFormatError as exc:
            raise CertificateFormatError(f"{source}: {exc}") from None


@dataclass(frozen=True)
class ContractionReport(VerificationReport):
    """Per-premise verdicts (the stability report's rule: proved iff there is a check and every one holds)."""

    certificate: ContractionCertificate  # type: ignore[assignment]
    checks: tuple[Check, ...]
    source: str = "<certificate>"
    proof: ContractionProof | None = None

    def summary(self) -> str:
        if not self.proved:
            return super().summary()
        c = self.certificate
        kind = "overshoot: a reset ends each stick" if c.overshoot else "no overshoot"
        return (f"PROVED {self.source}: all {len(self.checks)} premises of the reset-contraction template hold; "
                f"reset PID from a stick exit with |σ| ≤ {_down(c.radius)} ({kind}): |σ_k| ≤ {_up(c.rho)}^k·|σ_0|, "
                f"exits ≤ {_up(c.cycle_time)} apart, |σ| ≤ {_f(c.tol)}·|σ_0| for t ≥ {_up(c.settling_time)}"
                f" (every dwell ≤ {_down(max(c.dwell, c.tau_lo))})")


def verify_contraction(certificate: ContractionCertificate, *, source: str = "<certificate>") -> ContractionReport:
    """Decide every premise of :mod:`.reset_contraction_proof` for the certificate."""
    if not isinstance(certificate, ContractionCertificate):
        raise TypeError(f"verify_contraction needs a ContractionCertificate; got {type(certificate).__name__}")
    proof = decide_contraction(certificate)
    return ContractionReport(certificate, proof.checks, source, proof)


def dumps_contraction(certificate: ContractionCertificate) -> str:
    """The file's bytes: sorted keys, two-space indentation, trailing newline."""
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def load_contraction(path: str | Path) -> ContractionCertificate:
    """Read a reset-contraction certificate file strictly (bounded read; not verified)."""
    from ._json import read_json

    return ContractionCertificate.from_dict(read_json(path), source=str(path))


# -- the search: floats propose, the proof decides ------------------------------------------------------


def certify_contraction(params: Parameters, *, dwell: Any = None, tol: Any = Fraction(1, 1000),
                        label: str = "") -> ContractionCertificate:
    """Find and verify a reset-contraction certificate for ``params``.

    Parameters
    ----------
    params : Parameters
        Gains with ``f_s = f_c``.
    dwell : number, keyword-only
        The dwell time the file holds for (every dwell up to it, and at least
        up to the slip's length ``τ_lo``); default ``params.reset_dwell`` for
        reset PID, else 0.
    tol : number, keyword-only
        The tolerance of the settling bound, in ``(0, 1)``.
    label : str, keyword-only
        Free text for the provenance.

    Returns
    -------
    ContractionCertificate
        Proved by :func:`verify_contraction`.

    Raises
    ------
    ParameterError
        If ``f_s > f_c``, the slip from a stick does not end (``E₃₁`` has no
        positive zero: always so with real roots of ``det(sI − A)``), the
        return map does not contract (``|E₁₁(τ*)| ≥ 1``), or an option is out of range.
    CertificateError
        If the rounded numbers are not proved (nothing unproved is returned).

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> cert = certify_contraction(Parameters.table_i("a"), dwell=0)
    >>> float(cert.tau_lo) < 4.13621668 < float(cert.tau_hi), float(cert.radius)
    (True, 13.1077)
    """
    from .._infra.rational import to_rational

    if not isinstance(params, Parameters):
        raise TypeError(f"certify_contraction needs Parameters; got {type(params).__name__}")
    if params.stiction:
        raise ParameterError(
            f"a reset-contraction certificate is for Coulomb friction f_s = f_c; got f_s = {_f(params.f_s)} > "
            f"f_c = {_f(params.f_c)}: with static friction above Coulomb the loop hunts (symbolic-friction hunting)")
    if dwell is None:
        dwell = getattr(params, "reset_dwell", None) or 0
    dwell, tol = to_rational(dwell, name="dwell"), to_rational(tol, name="tol")
    if dwell < 0 or not 0 < tol < 1 or not isinstance(label, str):
        raise ParameterError(f"dwell must be ≥ 0, tol in (0, 1) and label a string; got {_f(dwell)}, {_f(tol)}, {label!r:.40}")
    return _certificate_at(params, _first_zero(params), dwell=dwell, tol=tol, label=label)


def _first_zero(params: Parameters) -> float:
    """``τ*``, the first positive zero of ``E₃₁``, in floats; :class:`ParameterError` naming why there is none."""
    import numpy as np

    b, c, d = params.k_v, params.k_p, params.k_i  # det(sI − A) = s³ + k_v s² + k_p s + k_i
    if 18 * b * c * d - 4 * b**3 * d + b * b * c * c - 4 * c**3 - 27 * d * d >= 0:
        raise ParameterError(
            f"no reset-contraction certificate for {params}: det(sI − A) has only real roots, so E31 (the impulse "
            "response of 1/det(sI − A), a convolution of positive exponentials) stays positive: the slip from a stick "
            "never ends and there is no return map to contract")
    try:
        A = np.array([[float(x) for x in row] for row in _matrix(params)])
    except OverflowError:
        A = np.full((3, 3), np.inf)
    if not np.all(np.isfinite(A)) or np.abs(A).max() > 1e12 or np.abs(A).max() < 1e-12:
        raise ParameterError(f"the gains of {params} are beyond the range of the floats the search works in")
    roots = np.linalg.eigvals(A)
    horizon = 60.0 / float(np.min(np.abs(roots.real)))  # every mode decayed by e^-60
    step = min(2 * math.pi / max(float(np.max(np.abs(roots.imag))), 1e-300) / 64, horizon / 2000)
    if horizon / step > 1e6:
        raise ParameterError(f"the modes of {params} are too far apart for the search ({horizon / step:.3g} steps)")

    def e31(s: float) -> float:
        return float(_expm(A * s)[2, 0])

    # w = e^{At}e₁ on a grid fine enough for the fastest oscillation; E₃₁ > 0 just after 0 ((A²)₃₁ = 1)
    E_step, w, t = _expm(A * step), np.array([1.0, 0.0, 0.0]), 0.0
    while t < horizon:
        w = E_step @ w
        if w[2] <= 0:
            a, b = max(t, step / 2), t + step
            if e31(a) > 0 >= e31(b):
                return _bisect(e31, a, b)
            raise CertificateError(f"the float search lost the first zero of E31 near τ = {b:.6g} for {params}")
        t += step
    slowest = roots[int(np.argmin(np.abs(roots.real)))]
    why = "; the slowest root is real" if abs(slowest.imag) == 0 else ""
    raise ParameterError(
        f"no reset-contraction certificate for {params}: E31 has no sign change on (0, {horizon:.4g}] (every mode has "
        f"decayed by e^-60 there{why}): the slip from a stick does not end")


def _expm(M: Any) -> Any:
    """``e^M`` in floats for a 3×3 ``M``: Taylor series of ``M/2^s`` (norm ≤ 1/2), squared ``s`` times.

    The search's own (numpy only: ``check`` re-runs the search and need not import scipy); the proof encloses
    ``e^{Aτ}`` in arb balls, and the tests compare with ``scipy.linalg.expm``.
    """
    import numpy as np

    norm = float(np.abs(M).sum(axis=0).max())
    squarings = max(0, math.ceil(math.log2(norm)) + 1) if norm > 0 else 0
    X = M / 2.0**squarings
    term, total = np.eye(3), np.eye(3)
    for k in range(1, 20):  # ‖X‖ ≤ 1/2: the remainder is below 2^-19/19! of the sum
        term = term @ X / k
        total = total + term
    for _ in range(squarings):
        total = total @ total
    return total


def _bisect(f: Any, a: float, b: float) -> float:
    """A zero of ``f`` in ``[a, b]`` with ``f(a) > 0 ≥ f(b)``, to the last bit (bisection: 60-odd halvings)."""
    while True:
        mid = 0.5 * (a + b)
        if not a < mid < b:
            return b
        if f(mid) > 0:
            a = mid
        else:
            b = mid


def _matrix(params: Parameters) -> Any:
    from .._model.coordinates import system_matrix_entries

    return system_matrix_entries(params.k_p, params.k_i, params.k_v)


def _certificate_at(params: Parameters, tau: float, *, dwell: Fraction, tol: Fraction, label: str) -> ContractionCertificate:
    """The certificate around a float zero ``tau`` of ``E₃₁``, verified (:class:`CertificateError` if not proved)."""
    cert = candidate_at(params, tau, dwell=dwell, tol=tol, label=label)
    report = verify_contraction(cert)
    if not report.proved:
        raise CertificateError(f"the reset-contraction certificate found for {params} is not proved: "
                               + "; ".join(c.message for c in report.failures))
    return cert


def candidate_at(params: Parameters, tau: float, *, dwell: Fraction = Fraction(0), tol: Fraction = Fraction(1, 1000),
                 label: str = "") -> ContractionCertificate:
    """The numbers around a float zero ``tau`` of ``E₃₁``, rounded outward (``rho`` up, ``radius`` down); not verified."""
    import numpy as np
    from .rounding import round_significant as rnd

    E = _expm(np.array([[float(x) for x in row] for row in _matrix(params)]) * tau)
    e11, e21 = float(E[0, 0]), float(E[1, 0])
    if not e21 < 0:
        raise ParameterError(f"no reset-contraction certificate for {params}: E21(τ*) = {e21:.3g} (the first zero of E31 is not simple)")
    slack = 1 + 1e-7  # the floats and the interval's width, far below the 6 digits kept
    half = Fraction(tau) * Fraction(1, 10**9)
    lo, hi = rnd(Fraction(tau) - half, 10, direction="down"), rnd(Fraction(tau) + half, 10, direction="up")
    rho = rnd(Fraction(abs(e11) * slack + 1e-15), 6, direction="up")
    if rho >= 1:
        raise ParameterError(f"no reset-contraction certificate for {params}: |E11(τ*)| = {abs(e11):.6g} ≥ 1, "
                             "the return map σ ↦ E11(τ*)σ does not contract")
    e21_up = Fraction(abs(e21) * slack + 1e-15)
    if e11 < 0:
        radius = rnd(params.f_c / (e21_up + rho * max(Fraction(0), dwell - lo)), 6, direction="down")
        cycle_time = rnd(max(hi, dwell), 6, direction="up")
    else:
        radius = rnd(2 * params.f_c / e21_up, 6, direction="down")
        cycle_time = rnd(hi + Fraction(abs(e21) / e11 * slack + 1e-12), 6, direction="up")
    cycles, power = 0, Fraction(1)
    while power > tol:
        cycles, power = cycles + 1, power * rho
        if cycles > MAX_CYCLES:
            raise ParameterError(f"ρ = {float(rho):.6g} needs more than {MAX_CYCLES} cycles to reach tol = {_f(tol)}")
    return ContractionCertificate(
        k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, tau_lo=lo, tau_hi=hi,
        monotone_from=rnd(Fraction(tau) * Fraction(999, 1000), 6, direction="down"), overshoot=e11 < 0, rho=rho,
        radius=radius, dwell=dwell, cycle_time=cycle_time, tol=tol, cycles=cycles, settling_time=cycles * cycle_time,
        provenance=ContractionProvenance(label=label))


def regenerate_contraction(certificate: ContractionCertificate) -> ContractionCertificate:
    """What :func:`certify_contraction` writes now for the certificate's gains, dwell, tol and label."""
    params = Parameters(k_p=certificate.k_p, k_i=certificate.k_i, k_v=certificate.k_v, f_c=certificate.f_c)
    return certify_contraction(params, dwell=certificate.dwell, tol=certificate.tol, label=certificate.provenance.label)


def _drift(certificate: ContractionCertificate, path: Path) -> str:
    from .._infra.errors import SymbolicFrictionError

    try:
        fresh = regenerate_contraction(certificate)
    except SymbolicFrictionError as exc:
        return f"cannot be regenerated: {exc}"
    if fresh != certificate:
        return f"{Path(path).name} differs from what certify_contraction writes now for its gains"
    return ""


RESET_CONTRACTION = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: ContractionCertificate.from_dict(data, source=source),
    verify=lambda certificate, source: verify_contraction(certificate, source=source),
    dumps=dumps_contraction,
    stale=canonical_staleness(dumps_contraction),
    drift=_drift,
    regenerate=regenerate_contraction,
    claim=lambda c: (f"reset PID: ρ ≤ {_up(c.rho)}, |σ| ≤ {_f(c.tol)}·|σ_0| by t = {_up(c.settling_time)} "
                     f"from |σ_0| ≤ {_down(c.radius)}"),
    default=True,
))
"""The reset-contraction template (beyond the paper): reset PID's stick exits contract by ``ρ`` per cycle."""

"""Exact transfer functions of python-control systems, for
:mod:`symbolic_friction._model.python_control` (paper §II-A, eq. uPID).

A SISO continuous-time ``control.TransferFunction`` or ``control.StateSpace`` is
read into exact :class:`~fractions.Fraction` coefficients: each float through its
shortest round-tripping decimal, as :func:`~symbolic_friction.to_rational` reads a
float (``6.4`` is 32/5), or through its binary value (``binary=True``).  Everything
after the reading is exact: a state-space system becomes its transfer function by
Faddeev–LeVerrier, common factors of numerator and denominator are cancelled by an
exact polynomial gcd, and the denominator is made monic.  python-control is
imported inside the functions only (``pip install 'symbolic-friction[control]'``).
"""

from __future__ import annotations

import numbers
from fractions import Fraction
from typing import Any

from .._infra.errors import ParameterError
from .._infra.rational import short_rational, to_rational

__all__ = ["read_transfer_function", "control_module", "poly_str", "tf_str", "Poly", "MAX_STATES"]

MAX_STATES = 10
"""A state-space system with more states is refused before the exact conversion (the plant has 2, the PID 1 or 2)."""

Poly = list[Fraction]  # coefficients, highest power first; [] is the zero polynomial


def control_module() -> Any:
    """``import control``, or an :class:`ImportError` that says how to install it."""
    try:
        import control
    except ImportError as exc:
        raise ImportError(
            "python-control systems in and out need python-control, an optional extra: "
            f"pip install 'symbolic-friction[control]' ({exc})"
        ) from None
    return control


# ---------------------------------------------------------------- exact polynomials


def _trim(p: Poly) -> Poly:
    i = 0
    while i < len(p) and p[i] == 0:
        i += 1
    return p[i:]


def _divmod(a: Poly, b: Poly) -> tuple[Poly, Poly]:
    """Quotient and remainder of ``a / b`` (``b`` nonzero), exactly."""
    a, b = _trim(a), _trim(b)
    if len(a) < len(b):
        return [], a
    rest = list(a)
    quotient: Poly = []
    for i in range(len(a) - len(b) + 1):
        factor = rest[i] / b[0]
        quotient.append(factor)
        for j, c in enumerate(b):
            rest[i + j] -= factor * c
    return quotient, _trim(rest[len(a) - len(b) + 1:])


def _gcd(a: Poly, b: Poly) -> Poly:
    a, b = _trim(a), _trim(b)
    while b:
        a, b = b, _divmod(a, b)[1]
    return [c / a[0] for c in a]


def poly_str(p: Poly) -> str:
    """``2 s^2 - 1/2 s + 3``: a polynomial for messages."""
    n = len(p) - 1
    terms = [(("- " if c < 0 else "+ ") + ("" if abs(c) == 1 and i < n else short_rational(abs(c)) + " " * (i < n))
              + ("" if i == n else "s" if i == n - 1 else f"s^{n - i}")) for i, c in enumerate(p) if c != 0]
    text = " ".join(terms) or "+ 0"
    return text[2:] if text.startswith("+") else "-" + text[2:]


def tf_str(num: Poly, den: Poly) -> str:
    """``(s + 1)/(s^2)``, ``1/(2 s^2 + s)`` or ``6 s + 8``: a transfer function for messages."""
    if len(den) == 1:
        return poly_str([c / den[0] for c in num])
    if len(num) == 1:
        return f"1/({poly_str([c / num[0] for c in den])})"
    return f"({poly_str(num)})/({poly_str(den)})"


# ---------------------------------------------------------------- reading systems


def _read(value: Any, name: str, binary: bool) -> Fraction:
    if isinstance(value, complex) or getattr(value, "imag", 0) != 0:
        raise ParameterError(f"{name} is complex ({value!r}); the systems must have real coefficients")
    value = getattr(value, "real", value)
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        value = int(value)  # numpy integers: a Fraction of plain ints (no int64 overflow later)
    elif isinstance(value, numbers.Real) and not isinstance(value, Fraction):
        value = float(value)
    return to_rational(value, name=name, binary=binary)


def _state_space_tf(A: list[list[Fraction]], B: list[Fraction], C: list[Fraction], D: Fraction) -> tuple[Poly, Poly]:
    """``C (sI - A)⁻¹ B + D`` as (numerator, denominator), exactly (Faddeev–LeVerrier)."""
    n = len(A)
    eye = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    charpoly: Poly = [Fraction(1)]  # s^n + c_{n-1} s^{n-1} + ... + c_0
    adjugate_terms: Poly = [Fraction(0)]  # C adj(sI - A) B, adj(sI - A) = sum_k M_k s^(n-k)
    M = eye
    for k in range(1, n + 1):
        if k > 1:
            M = [[sum((A[i][l] * M[l][j] for l in range(n)), Fraction(0)) + charpoly[-1] * eye[i][j]
                  for j in range(n)] for i in range(n)]
        trace = sum((A[i][l] * M[l][i] for i in range(n) for l in range(n)), Fraction(0))
        charpoly.append(-trace / k)
        adjugate_terms.append(sum((C[i] * M[i][j] * B[j] for i in range(n) for j in range(n)), Fraction(0)))
    return [t + D * c for t, c in zip(adjugate_terms, charpoly)], charpoly


def read_transfer_function(system: Any, role: str, *, binary: bool = False) -> tuple[Poly, Poly]:
    """The SISO continuous-time ``system`` as an exact (numerator, denominator), common factors cancelled.

    ``role`` (``"plant"``, ``"controller"``) names the system in messages; ``binary``
    reads each float through its binary value instead of its shortest decimal.
    Returns the coefficients, highest power first, the denominator monic.  Raises
    :class:`ParameterError` for another type, MIMO, discrete time, a zero system or a
    coefficient that is not a finite real number.

    Examples
    --------
    >>> import control
    >>> num, den = read_transfer_function(control.tf([2, 2], [4, 4.4, 0.4]), "plant")  # (2s+2)/(4(s+1)(s+0.1))
    >>> [str(c) for c in num], [str(c) for c in den]
    (['1/2'], ['1', '1/10'])
    """
    ct = control_module()
    if isinstance(system, ct.TransferFunction):
        kind = "transfer function"
    elif isinstance(system, ct.StateSpace):
        kind = "state-space system"
    else:
        raise ParameterError(
            f"the {role} must be a python-control TransferFunction or StateSpace; got {type(system).__name__}"
        )
    if system.ninputs != 1 or system.noutputs != 1:
        raise ParameterError(
            f"the {role} is MIMO ({system.ninputs} inputs, {system.noutputs} outputs); "
            "the paper's loop is SISO: one force in, one position out"
        )
    if ct.isdtime(system, strict=True):
        raise ParameterError(
            f"the {role} is a discrete-time {kind} (dt = {system.dt}); the paper's model is continuous time "
            "(convert with control.d2c or build it with dt=0)"
        )
    if kind == "transfer function":
        num_list = getattr(system, "num_list", None) or system.num
        den_list = getattr(system, "den_list", None) or system.den
        num = [_read(c, f"the {role}'s numerator coefficient", binary) for c in num_list[0][0]]
        den = [_read(c, f"the {role}'s denominator coefficient", binary) for c in den_list[0][0]]
    else:
        n = system.nstates
        if n > MAX_STATES:
            raise ParameterError(
                f"the {role} has {n} states; at most {MAX_STATES} are read (the plant has 2, the PID 1 or 2: "
                "remove redundant states with control.minreal)"
            )
        A = [[_read(system.A[i, j], f"the {role}'s A[{i}, {j}]", binary) for j in range(n)] for i in range(n)]
        B = [_read(system.B[i, 0], f"the {role}'s B[{i}, 0]", binary) for i in range(n)]
        C = [_read(system.C[0, j], f"the {role}'s C[0, {j}]", binary) for j in range(n)]
        D = _read(system.D[0, 0], f"the {role}'s D[0, 0]", binary)
        num, den = _state_space_tf(A, B, C, D)
    num, den = _trim(num), _trim(den)
    if not den:
        raise ParameterError(f"the {role}'s denominator is zero")
    if not num:
        raise ParameterError(f"the {role} is zero (its numerator is 0)")
    common = _gcd(num, den)
    num, den = _divmod(num, common)[0], _divmod(den, common)[0]
    lead = den[0]
    return [c / lead for c in num], [c / lead for c in den]

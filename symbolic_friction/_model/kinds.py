"""The three kinds of number every model function is evaluated in.

Each paper object (``dz`` and ``|x|_𝒜`` of eq. (distFromA), ``V`` of eq.
(lyapLike), ``V̂`` of eq. (Vhat), the region ``R`` of Lemma 3) is written
*once*, with plain arithmetic plus the handful of non-arithmetic operations
below.  The same function body then serves

* **exact** scalars (:class:`fractions.Fraction`, ``int``): the certificate
  verifier, exact simulation events, the binding obligations;
* **float** scalars and numpy arrays (vectorised): the simulators and the
  cross-check;
* **sympy** expressions, for symbolic gains: the proof obligations, which
  therefore prove statements about the package's own code.

The non-arithmetic operations are where the kinds differ: ``where`` is a
Python conditional, :func:`numpy.where` or a :class:`sympy.Piecewise`;
``clip`` (the projection ``c·sat(y/c)``), ``sign`` and ``abs`` likewise.
Comparisons (``v > 0``) are plain operators in every kind: a ``bool``, a
boolean array or a sympy relational.

The binding obligations ``model.*_runtime`` evaluate each model function in
all three kinds on every branch and check that they agree, so the three
instantiations cannot drift apart.  This module imports numpy; sympy is
only touched if a sympy object is passed in (then it is already imported).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from typing import Any

import numpy as np

__all__ = ["Kind", "EXACT", "FLOAT", "kind_of", "SYMPY"]


class Kind:
    """Operations of one kind of number; see the module docstring.

    Subclasses implement :meth:`where`, :meth:`clip`, :meth:`sign`,
    :meth:`abs`, :meth:`scalar` and :meth:`finish`.
    """

    name: str = "kind"

    def where(self, cond: Any, a: Any, b: Any) -> Any:  # pragma: no cover - abstract
        """``a`` where ``cond`` holds, else ``b``."""
        raise NotImplementedError

    def clip(self, y: Any, lo: Any, hi: Any) -> Any:  # pragma: no cover - abstract
        """The projection of ``y`` on ``[lo, hi]`` (``lo ≤ hi``)."""
        raise NotImplementedError

    def sign(self, y: Any) -> Any:  # pragma: no cover - abstract
        """``sign`` of the paper's notation: ``1``, ``0`` or ``-1``."""
        raise NotImplementedError

    def abs(self, y: Any) -> Any:  # pragma: no cover - abstract
        """``|y|``."""
        raise NotImplementedError

    def scalar(self, q: Any) -> Any:  # pragma: no cover - abstract
        """A parameter (an exact rational or a symbol) as a number of this kind."""
        raise NotImplementedError

    def finish(self, expr: Any) -> Any:
        """Normalise a finished result (sympy folds nested Piecewise)."""
        return expr

    def __repr__(self) -> str:
        return f"<{self.name} kind>"


class _Exact(Kind):
    name = "exact"

    def where(self, cond: Any, a: Any, b: Any) -> Any:
        return a if cond else b

    def clip(self, y: Any, lo: Any, hi: Any) -> Any:
        return lo if y < lo else hi if y > hi else y

    def sign(self, y: Any) -> Any:
        return (y > 0) - (y < 0)

    def abs(self, y: Any) -> Any:
        return abs(y)

    def scalar(self, q: Any) -> Any:
        return q


class _Float(Kind):
    name = "float"

    def where(self, cond: Any, a: Any, b: Any) -> Any:
        return np.where(cond, a, b)

    def clip(self, y: Any, lo: Any, hi: Any) -> Any:
        return np.clip(y, lo, hi)

    def sign(self, y: Any) -> Any:
        return np.sign(y)

    def abs(self, y: Any) -> Any:
        return np.abs(y)

    def scalar(self, q: Any) -> Any:
        return float(q)


class _Sympy(Kind):
    name = "sympy"

    def where(self, cond: Any, a: Any, b: Any) -> Any:
        import sympy as sp

        return sp.Piecewise((a, cond), (b, True))

    def clip(self, y: Any, lo: Any, hi: Any) -> Any:
        import sympy as sp

        return sp.Piecewise((lo, y < lo), (hi, y > hi), (y, True))

    def sign(self, y: Any) -> Any:
        import sympy as sp

        return sp.sign(y)

    def abs(self, y: Any) -> Any:
        import sympy as sp

        return sp.Abs(y)

    def scalar(self, q: Any) -> Any:
        import sympy as sp

        return sp.sympify(q)

    def finish(self, expr: Any) -> Any:
        import sympy as sp

        return sp.piecewise_fold(expr) if isinstance(expr, sp.Basic) else expr


EXACT: Kind = _Exact()
FLOAT: Kind = _Float()
SYMPY: Kind = _Sympy()


def _is_sympy(x: Any) -> bool:
    sp = sys.modules.get("sympy")
    return sp is not None and isinstance(x, sp.Basic)


def kind_of(*values: Any) -> Kind:
    """The kind that evaluates an expression in ``values`` faithfully.

    Any sympy object makes it :data:`SYMPY` (sympy numbers included: they
    stay sympy); else any float or numpy value makes it :data:`FLOAT`; else
    (``Fraction``, ``int``, ``bool``) it is :data:`EXACT`.

    Examples
    --------
    >>> kind_of(Fraction(1, 2), 3).name, kind_of(Fraction(1), 0.5).name
    ('exact', 'float')
    """
    kind: Kind = EXACT
    for x in values:
        if _is_sympy(x):
            return SYMPY
        if isinstance(x, (float, np.ndarray, np.floating, np.integer)):
            kind = FLOAT
        elif not isinstance(x, (Fraction, int)):
            raise TypeError(f"model functions take Fractions, ints, floats, numpy arrays or sympy expressions; got {type(x).__name__}")
    return kind

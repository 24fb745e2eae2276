"""The proof obligations: one object per claim of the paper, in paper order.

:func:`symbolic_friction.run_obligations` runs them all; here are the types
their results carry.

Examples
--------
>>> import symbolic_friction as sf
>>> obligations = sf.all_obligations()  # in the order the paper proves them
>>> obligations[0].id, all(isinstance(o, sf.obligations.Obligation) for o in obligations)
('coordinates', True)
>>> sf.all_errata()[0].where  # where the paper's text needed a correction
'§IV-A, after eq. (CoC)'
>>> results = sf.run_obligations()  # every claim, decided exactly (about a minute)  # doctest: +SKIP
>>> all(r.holds for r in results)  # doctest: +SKIP
True
"""

from __future__ import annotations

from ._namespace import lazy_getattr

# name -> private module that defines it (imported on first use)
_LAZY: dict[str, str] = {
    "Obligation": "._obligations._base",
    "Outcome": "._obligations._base",
    "Result": "._obligations._base",
    "Erratum": "._obligations._base",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))

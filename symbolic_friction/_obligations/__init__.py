"""Every proof obligation of the paper, in paper order.

Each module under this package implements the obligations of one part of
the paper; :func:`all_obligations` lists them in the order the paper proves
them.  Importing this package imports sympy.
"""

from __future__ import annotations

import importlib

from ._base import Erratum, Obligation, Result

__all__ = ["all_obligations", "run_obligations", "all_errata", "OBLIGATION_MODULES"]

# Modules in paper order; each defines OBLIGATIONS: tuple[type[Obligation], ...]
OBLIGATION_MODULES: tuple[str, ...] = (
    "model",
    "runtime",
    "lemma1",
    "lemma2",
    "claim1",
    "prop1_attractivity",
    "lemma3",
    "prop1_stability",
    "cor1",
    "table1",
    "verifier",
)


def all_obligations() -> list[Obligation]:
    """Instances of every obligation, in paper order."""
    out: list[Obligation] = []
    for name in OBLIGATION_MODULES:
        try:
            module = importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"{__name__}.{name}":
                continue  # not written yet
            raise
        out.extend(cls() for cls in module.OBLIGATIONS)
    return out


def run_obligations() -> list[Result]:
    """Run every obligation and return its :class:`Result`."""
    return [ob.run() for ob in all_obligations()]


def all_errata() -> list[Erratum]:
    """Every erratum declared by an obligation, deduplicated, in paper order."""
    seen: list[Erratum] = []
    for ob in all_obligations():
        for e in ob.errata:
            if e not in seen:
                seen.append(e)
    return seen

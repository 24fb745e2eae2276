"""Lazy public namespaces (PEP 562): a name is imported from its private module on first use.

The package and its public task modules (:mod:`symbolic_friction.model`,
:mod:`~symbolic_friction.errors`, …) list what they offer in a table
``name -> private module``; importing them imports nothing heavy.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable

__all__ = ["lazy_getattr"]


def lazy_getattr(package: str, namespace: dict[str, Any], table: dict[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` resolving ``table``'s names (relative to ``package``) and caching them."""

    def __getattr__(name: str) -> Any:
        module = table.get(name)
        if module is None:
            raise AttributeError(f"module {namespace['__name__']!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module, package), name)
        namespace[name] = value
        return value

    return __getattr__

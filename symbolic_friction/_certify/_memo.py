"""A cache that lives only inside a ``with`` block: verifiers share work across many files, and never across runs.

The self-check decides dozens of known-false certificates that differ from a
true one in a single number; their expensive parts (a Krawczyk proof, the arb
enclosures of ``e^{Aτ}``) depend only on the gains and a box, so within one
self-check they are computed once.  Outside a block nothing is kept: a
verification by ``verify`` or ``check`` always recomputes.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Hashable, Iterator
from typing import Any

__all__ = ["Memo"]


class Memo:
    """Values by key, kept only while :meth:`sharing` is active (nested blocks each start empty)."""

    def __init__(self) -> None:
        self._stack: list[dict[Hashable, Any]] = []

    @contextlib.contextmanager
    def sharing(self) -> Iterator[None]:
        """Within the block, :meth:`get` computes each key once."""
        self._stack.append({})
        try:
            yield
        finally:
            self._stack.pop()

    def get(self, key: Hashable, compute: Callable[[], Any]) -> Any:
        """``compute()``, or its value for ``key`` from earlier in the innermost block."""
        if not self._stack:
            return compute()
        memo = self._stack[-1]
        if key not in memo:
            memo[key] = compute()
        return memo[key]

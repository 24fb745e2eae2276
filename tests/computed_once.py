"""One helper for the test modules that ask a pure function of the package for the same value again and again."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from typing import Any

import pytest


@contextlib.contextmanager
def computed_once(owner: Any, name: str, *, ignore: tuple[str, ...] = (),
                  fresh: Callable[[dict], bool] = lambda options: False) -> Iterator[dict]:
    """Within the block, ``owner.name`` (a pure function of hashable arguments) is computed once per arguments: a
    later call with equal arguments gets the first call's value; a call that raises is not kept.

    ``ignore`` names keyword options left out of the key (a deadline far away that changes nothing), and a call
    for which ``fresh(options)`` holds runs as it is, never shared.  Yields the values kept, by arguments.  Only
    for functions whose value depends on nothing but their arguments (no clock, no random state, no module state
    a test patches meanwhile); a test that replaces the function (``monkeypatch``) replaces this too.
    """
    real = getattr(owner, name)
    done: dict = {}

    def shared(*args: Any, **options: Any) -> Any:
        if fresh(options):
            return real(*args, **options)
        key = (args, tuple(sorted((k, v) for k, v in options.items() if k not in ignore)))
        if key not in done:
            done[key] = real(*args, **options)
        return done[key]

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(owner, name, shared)
        yield done

"""Which variant of the kernel runs: compiled by numba, or the same source as Python.

:mod:`._kernel` (with :mod:`._kernel_flow`, which it imports) is written
once, in the subset of Python that numba compiles.  :func:`kernel` returns
either that module as it is (the pure-Python fallback), or the same files
loaded a second time, under the names ``…._kernel_flow_jit`` and
``symbolic_friction._simulation._kernel_jit``, with every function compiled
(``numba.njit(cache=True)``: machine code is cached on disk beside the
sources, or in numba's user cache when that directory is read-only).

Which one runs is set by the environment variable ``SYMBOLIC_FRICTION_JIT``:

* ``0`` (or ``false``/``no``/``off``): always plain Python;
* ``1`` (or ``true``/``yes``/``on``): compiled whenever numba is installed;
* ``auto`` (the default): numba costs about 0.9 s to start in a fresh
  process (its import, its code generator, loading the cached machine code),
  which is more than a few single trajectories take in plain Python.  So the
  plain kernel runs until a single call is large (:data:`LARGE_WORK` samples
  and events) or the process has spent :data:`PLAIN_BUDGET` seconds in it, or
  numba is already imported; from then on the compiled kernel runs.  (So
  ``symbolic-friction check``, whose cross-check self-test is small, never
  waits for numba to compile on a fresh install.)

Both variants give the same results bit for bit (the tests run both and
compare), so the choice changes the speed only.  numba is imported only when
the compiled kernel is first chosen, so ``--help``, the symbolic commands and
a small simulation scene never pay for it.
"""

from __future__ import annotations

import functools
import importlib.util
import math
import os
import sys
from types import ModuleType

__all__ = ["ENV", "setting", "jit_enabled", "compiled", "plain", "kernel", "variant", "spent_in_plain"]

ENV = "SYMBOLIC_FRICTION_JIT"
_OFF = ("0", "false", "no", "off")
_ON = ("1", "true", "yes", "on")
# Seconds the plain kernel may run in a process before the compiled one is loaded: a few
# times numba's warm start (≈ 0.9 s), since its cold start (compiling, ≈ 8 s) may be due.
PLAIN_BUDGET = 3.0
# A call with this many samples and events (about 1 s in plain Python) loads the compiled kernel.
LARGE_WORK = 200_000
_spent = 0.0
# The kernel's files, each loaded a second time for the compiled variant, in this order.
_KERNEL_FILES = ("_kernel_flow", "_kernel")


def setting() -> str:
    """``"off"``, ``"on"`` or ``"auto"``, from ``SYMBOLIC_FRICTION_JIT``."""
    return _parse(os.environ.get(ENV, "auto"))


@functools.lru_cache(maxsize=16)
def _parse(value: str) -> str:
    value = value.strip().lower()
    return "off" if value in _OFF else "on" if value in _ON else "auto"


def jit_enabled() -> bool:
    """Whether the environment allows the compiled kernel at all."""
    return setting() != "off"


def spent_in_plain(seconds: float) -> None:
    """Record time spent in the plain kernel (the ``auto`` setting compiles once it adds up)."""
    global _spent
    _spent += seconds


def plain() -> ModuleType:
    """The kernel as plain Python."""
    from . import _kernel

    return _kernel


@functools.cache
def compiled() -> ModuleType | None:
    """The kernel compiled by numba, or ``None`` when numba is not installed."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return None
    folder = os.path.dirname(plain().__file__)
    module = None
    # the closed form and search first: the event loop's compiled variant imports it by this name
    for stem in _KERNEL_FILES:
        name = f"{__package__}.{stem}_jit"
        spec = importlib.util.spec_from_file_location(name, os.path.join(folder, f"{stem}.py"))
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        module._JIT = True  # read by the file's first lines: decorate with numba.njit
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            for loaded in _KERNEL_FILES:
                sys.modules.pop(f"{__package__}.{loaded}_jit", None)
            raise
    return module


def kernel(work: float = math.inf) -> ModuleType:
    """The variant to run for a call of about ``work`` samples and events (module doc)."""
    mode = setting()
    if mode == "off":
        return plain()
    if mode == "auto" and work < LARGE_WORK and _spent < PLAIN_BUDGET and "numba" not in sys.modules:
        return plain()
    module = compiled()
    return module if module is not None else plain()


def variant(work: float = math.inf) -> str:
    """``"numba"`` or ``"python"``: what :func:`kernel` returns now for ``work``."""
    return "numba" if kernel(work) is not plain() else "python"

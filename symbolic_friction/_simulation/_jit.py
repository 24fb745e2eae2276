"""Which variant of the kernel runs: compiled by numba, or the same source as Python.

:mod:`._kernel` is written once, in the subset of Python that numba compiles.
:func:`kernel` returns either that module as it is (the pure-Python
fallback), or the same file loaded a second time, under the name
``symbolic_friction._simulation._kernel_jit``, with every function compiled
(``numba.njit(cache=True)``: machine code is cached on disk beside the
sources, or in numba's user cache when that directory is read-only).

The compiled variant is used when numba is installed, unless the environment
variable ``SYMBOLIC_FRICTION_JIT`` is ``0`` (or ``false``/``no``/``off``).
Both variants give the same results bit for bit; the tests run both and
compare.  numba is imported only when a simulation first needs the kernel,
so ``--help`` and the symbolic commands never pay for it.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import sys
from types import ModuleType

__all__ = ["ENV", "jit_enabled", "compiled", "plain", "kernel", "variant"]

ENV = "SYMBOLIC_FRICTION_JIT"
_OFF = ("0", "false", "no", "off")


def jit_enabled() -> bool:
    """Whether the environment allows the compiled kernel (``SYMBOLIC_FRICTION_JIT``)."""
    return os.environ.get(ENV, "1").strip().lower() not in _OFF


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
    source = plain().__file__
    name = f"{__package__}._kernel_jit"
    spec = importlib.util.spec_from_file_location(name, source)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    module._JIT = True  # read by the kernel's first lines: decorate with numba.njit
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return module


def kernel() -> ModuleType:
    """The variant to run: compiled when numba is installed and allowed, else plain."""
    if jit_enabled():
        module = compiled()
        if module is not None:
            return module
    return plain()


def variant() -> str:
    """``"numba"`` or ``"python"``: what :func:`kernel` returns now."""
    return "numba" if kernel() is not plain() else "python"

"""Certify many gain sets: a parameter sweep over any
:class:`concurrent.futures.Executor` (default: serial, in this process).

Each worker compiles the search problem once (cvxpy DPP) and re-solves it
for every gain set of its chunk, so the per-certificate cost is one Clarabel
solve plus exact rounding and verification.  A gain set that cannot be
certified does not stop the sweep: its :class:`SweepItem` carries the error.
"""

from __future__ import annotations

import sys
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass
from typing import Iterable, TextIO

from .._infra.errors import ParameterError, SymbolicFrictionError
from .._model.parameters import Parameters
from .._infra.progress import Progress
from .certificate import Certificate
from .pipeline import certify
from .search import check_margin, check_mode

__all__ = ["SweepItem", "certify_many"]


@dataclass(frozen=True)
class SweepItem:
    """One gain set of a sweep.

    Attributes
    ----------
    index : int
        Position in the input sequence.
    params : Parameters
    certificate : Certificate or None
        The proved certificate, or None if certification failed.
    error : str
        ``"<ErrorClass>: <message>"`` when certification failed, else ``""``.
    """

    index: int
    params: Parameters
    certificate: Certificate | None
    error: str = ""

    @property
    def ok(self) -> bool:
        """True iff a proved certificate was produced."""
        return self.certificate is not None


def _certify_chunk(chunk: list[tuple[int, Parameters]], mode: str, margin: object) -> list[SweepItem]:
    """Worker: certify a chunk (module level so that process pools can pickle it)."""
    out = []
    for index, params in chunk:
        try:
            out.append(SweepItem(index, params, certify(params, mode=mode, margin=margin)))
        except SymbolicFrictionError as exc:
            out.append(SweepItem(index, params, None, f"{type(exc).__name__}: {exc}"))
    return out


def certify_many(
    gains: Iterable[Parameters],
    *,
    mode: str = "tightest",
    margin: object = None,
    executor: Executor | None = None,
    chunksize: int = 50,
    progress: bool | None = None,
    stream: TextIO | None = None,
) -> list[SweepItem]:
    """Certify every gain set of ``gains``; return one :class:`SweepItem` per input, in order.

    Parameters
    ----------
    gains : iterable of Parameters
    mode, margin : keyword-only
        As in :func:`~symbolic_friction.certify`.
    executor : concurrent.futures.Executor or None, keyword-only
        Where to run the chunks (e.g. ``ProcessPoolExecutor(2)``); ``None``
        runs serially in this process.
    chunksize : int, keyword-only
        Gain sets per task; larger chunks amortise inter-process overhead.
    progress : bool or None, keyword-only
        Draw a progress bar on ``stream``; ``None`` (default) draws it only
        when ``stream`` is a terminal.
    stream : text stream, keyword-only
        Defaults to ``sys.stderr``.

    Raises
    ------
    ParameterError
        For an unknown mode, a bad margin, a ``chunksize < 1`` or an element
        of ``gains`` that is not a :class:`~symbolic_friction.Parameters`.

    Examples
    --------
    >>> items = certify_many([Parameters.table_i("a"), Parameters.table_i("b")], progress=False)
    >>> [item.ok for item in items]
    [True, True]
    """
    mode = check_mode(mode)
    margin = check_margin(margin, mode)
    if not isinstance(chunksize, int) or isinstance(chunksize, bool) or chunksize < 1:
        raise ParameterError(f"chunksize must be a positive integer; got {chunksize!r}")
    items = list(gains)
    for i, params in enumerate(items):
        if not isinstance(params, Parameters):
            raise ParameterError(f"gains[{i}] must be a Parameters instance; got {type(params).__name__}")
    indexed = list(enumerate(items))
    chunks = [indexed[i : i + chunksize] for i in range(0, len(indexed), chunksize)]
    results: list[SweepItem] = []
    bar = Progress(len(items), desc=f"certify ({mode})", stream=sys.stderr if stream is None else stream, enabled=progress)
    with bar:
        if executor is None:
            for chunk in chunks:
                done = _certify_chunk(chunk, mode, margin)
                results.extend(done)
                bar.update(len(done))
        else:
            futures = [executor.submit(_certify_chunk, chunk, mode, margin) for chunk in chunks]
            for future in as_completed(futures):
                done = future.result()
                results.extend(done)
                bar.update(len(done))
    results.sort(key=lambda item: item.index)
    return results

"""What the command line prints, and how: one line at a time, flushed, fitted to the terminal.

* :func:`emit` prints one line and flushes it, so a CI log (a pipe) shows each
  result as it is decided, not everything at the end.
* :func:`format_table` fits a table to the terminal width
  (:func:`shutil.get_terminal_size`, which honours ``COLUMNS``), shortening the
  widest text columns first and never the short ones (ids, verdicts).
* :func:`install_ascii_fallback` makes stdout and stderr that cannot encode
  the package's symbols (``PYTHONIOENCODING=ascii``, a C locale) print
  readable ASCII (``κ`` as ``kappa``, ``≤`` as ``<=``) instead of crashing.
* :data:`VERBOSITY` is set by ``--quiet`` / ``--verbose``.

Only the standard library is imported (fast start).
"""

from __future__ import annotations

import codecs
import shutil
import sys
from collections.abc import Sequence
from typing import TextIO

__all__ = ["emit", "format_table", "terminal_width", "install_ascii_fallback", "set_verbosity", "verbosity", "fit"]

_VERBOSITY = [1]  # 0 quiet, 1 normal, 2 verbose


def set_verbosity(level: int) -> None:
    """0 for ``--quiet`` (verdicts and errors only), 1 normal, 2 for ``--verbose``."""
    _VERBOSITY[0] = level


def verbosity() -> int:
    """The current level (see :func:`set_verbosity`)."""
    return _VERBOSITY[0]


def emit(text: str = "", *, err: bool = False, level: int = 1) -> None:
    """Print ``text`` and flush, if the verbosity is at least ``level``.

    ``level=0`` lines (verdicts, the closing line) are printed even under
    ``--quiet``; ``level=2`` lines only under ``--verbose``.
    """
    if _VERBOSITY[0] < level:
        return
    stream = sys.stderr if err else sys.stdout
    print(text, file=stream, flush=True)


def terminal_width(stream: TextIO | None = None) -> int:
    """Columns available: ``COLUMNS`` if set, else the terminal's, else 100 (a pipe)."""
    return max(40, shutil.get_terminal_size(fallback=(100, 24)).columns)


def fit(text: str, width: int) -> str:
    """``text`` cut to ``width`` characters with an ellipsis."""
    return text if len(text) <= width else text[: max(0, width - 1)] + "…"


def format_table(title: str, columns: Sequence[str], rows: Sequence[Sequence[str]], *, width: int | None = None) -> str:
    """A plain-text table no wider than ``width`` (default :func:`terminal_width`).

    Columns keep their natural width while the table fits; otherwise the
    widest columns are shortened (cells end in ``…``), never below the
    column name or 8 characters, so ids and verdicts stay whole.
    """
    width = terminal_width() if width is None else width
    natural = [len(c) for c in columns]
    for row in rows:
        natural = [max(w, len(cell)) for w, cell in zip(natural, row)]
    widths = list(natural)
    gap = 2 * (len(columns) - 1)
    floor = [max(len(c), min(n, 8)) for c, n in zip(columns, natural)]
    while sum(widths) + gap > width:
        i = max(range(len(widths)), key=lambda j: widths[j] - floor[j])
        if widths[i] <= floor[i]:
            break  # nothing left to shorten: let the terminal wrap
        widths[i] -= 1
    head = "  ".join(c.ljust(w) for c, w in zip(columns, widths)).rstrip()
    line = "  ".join("-" * w for w in widths)
    body = ["  ".join(fit(cell, w).ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows]
    return "\n".join([title, head, line, *body])


# -- ASCII fallback ------------------------------------------------------------------------

_ASCII = {
    "κ": "kappa", "≤": "<=", "≥": ">=", "≠": "!=", "—": "-", "–": "-", "…": "...", "·": "*", "²": "^2", "³": "^3",
    "𝒜": "A", "⪰": ">=", "≻": ">", "≺": "<", "⇔": "<=>", "⇒": "=>", "→": "->", "←": "<-", "≡": "==", "≷": "<>",
    "λ": "lambda", "σ": "sigma", "φ": "phi", "ξ": "xi", "ρ": "rho", "α": "alpha", "δ": "delta", "θ": "theta",
    "ζ": "zeta", "μ": "mu", "ε": "epsilon", "ĉ": "c^", "V̂": "V^", "̂": "^", "∂": "d", "∈": "in", "⊂": "subset",
    "⊆": "subset", "√": "sqrt", "∞": "inf", "±": "+-", "×": "x", "−": "-", "✓": "ok", "✗": "x", "₁": "1",
    "₂": "2", "₃": "3", "₄": "4", "₀": "0", "‖": "||", "∀": "for all", "∃": "exists", "ℝ": "R", "°": "o",
    "’": "'", "‘": "'", "“": '"', "”": '"', "̄": "_bar", "ₚ": "p", "ᵢ": "i", "ᵥ": "v", "ᵀ": "^T", "⁻": "^-", "¹": "1",
}
_HANDLER = "symbolic_friction_ascii"


def _ascii_replace(exc: UnicodeError) -> tuple[str, int]:
    if not isinstance(exc, UnicodeEncodeError):
        raise exc
    bad = exc.object[exc.start : exc.end]
    return "".join(_ASCII.get(ch, ch if ch.isascii() else "?") for ch in bad), exc.end


def install_ascii_fallback() -> None:
    """Reconfigure stdout and stderr to print ASCII stand-ins where their encoding lacks a symbol.

    A UTF-8 stream is left alone; any other (``ascii``, ``latin-1``, a C
    locale) gets an error handler that writes ``kappa`` for ``κ``, ``<=``
    for ``≤`` and ``?`` for anything else, so output never crashes.
    """
    try:
        codecs.lookup_error(_HANDLER)
    except LookupError:
        codecs.register_error(_HANDLER, _ascii_replace)
    for stream in (sys.stdout, sys.stderr):
        encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
        if encoding in ("utf8", "utf8sig") or not hasattr(stream, "reconfigure"):
            continue
        try:
            stream.reconfigure(errors=_HANDLER)
        except (ValueError, OSError):  # pragma: no cover - a stream that cannot be reconfigured
            pass

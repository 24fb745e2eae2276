"""A tiny progress bar for long loops (certificate sweeps, batch simulations).

It writes to ``stderr`` only, and by default only when ``stderr`` is a
terminal, so piped or captured output (CI logs, ``--json`` on stdout) is never
polluted.  Standard library only; no third-party dependency.

Examples
--------
>>> with Progress(3, desc="certify", enabled=False) as bar:
...     for _ in range(3):
...         bar.update()
>>> bar.count
3
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

__all__ = ["Progress"]


class Progress:
    """A one-line ``[#####.....] 50/100 certify 1.2 s`` bar, redrawn in place.

    Parameters
    ----------
    total : int
        Number of steps expected (``>= 0``).
    desc : str, keyword-only
        Short label printed after the counts.
    stream : text stream, keyword-only
        Where to draw; defaults to ``sys.stderr`` at construction time.
    enabled : bool or None, keyword-only
        ``None`` (default) draws only if ``stream.isatty()``.
    width : int, keyword-only
        Number of cells of the bar.
    min_interval : float, keyword-only
        Minimum seconds between two redraws (the final state is always drawn).
    """

    def __init__(
        self,
        total: int,
        *,
        desc: str = "",
        stream: TextIO | None = None,
        enabled: bool | None = None,
        width: int = 30,
        min_interval: float = 0.1,
    ) -> None:
        if total < 0:
            raise ValueError(f"total must be >= 0; got {total}")
        self.total = int(total)
        self.desc = desc
        self.stream = sys.stderr if stream is None else stream
        if enabled is None:
            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty()) if callable(isatty) else False
        self.enabled = enabled
        self.width = width
        self.min_interval = min_interval
        self.count = 0
        self._start = time.perf_counter()
        self._last_draw = float("-inf")

    def update(self, n: int = 1) -> None:
        """Advance by ``n`` steps and redraw if enough time has passed."""
        self.count += n
        now = time.perf_counter()
        if self.enabled and (now - self._last_draw >= self.min_interval or self.count >= self.total):
            self._draw(now)

    def render(self, now: float | None = None) -> str:
        """The bar as a string (without the leading carriage return)."""
        now = time.perf_counter() if now is None else now
        frac = 1.0 if self.total == 0 else min(1.0, self.count / self.total)
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        label = f" {self.desc}" if self.desc else ""
        return f"[{bar}] {self.count}/{self.total}{label} {now - self._start:.1f} s"

    def _draw(self, now: float) -> None:
        self._last_draw = now
        self.stream.write("\r" + self.render(now))
        self.stream.flush()

    def close(self) -> None:
        """Draw the final state and end the line."""
        if self.enabled:
            self._draw(time.perf_counter())
            self.stream.write("\n")
            self.stream.flush()
            self.enabled = False

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

"""Progress bars for long loops (certificate sweeps, batch simulations, the cross-check), drawn by tqdm.

A bar is drawn on ``stderr`` only, and by default only when ``stderr`` is a
terminal and ``--quiet`` was not given, so piped or captured output (CI logs,
``--json`` on stdout) is never polluted.  tqdm is imported when a bar is
actually drawn, so a disabled bar costs nothing at start-up.

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
from typing import Any, TextIO

__all__ = ["Progress"]


class Progress:
    """A one-line ``certify: 50%|█████     | 50/100 [00:01<00:01]`` bar (tqdm), redrawn in place.

    Parameters
    ----------
    total : int
        Number of steps expected (``>= 0``).
    desc : str, keyword-only
        Short label printed before the bar.
    stream : text stream, keyword-only
        Where to draw; defaults to ``sys.stderr`` at construction time.
    enabled : bool or None, keyword-only
        ``None`` (default) draws only if ``stream.isatty()`` and the command
        line was not given ``--quiet``.
    width : int, keyword-only
        Number of cells of the bar (``render``; tqdm fits its own bar to the terminal).
    min_interval : float, keyword-only
        Minimum seconds between two redraws (the final state is always drawn).
    unit : str, keyword-only
        What a step is, shown in the rate (``"pt"``: points/s).
    initial : int, keyword-only
        Steps already done before this run (a resumed run); they do not count in the rate.
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
        unit: str = "it",
        initial: int = 0,
    ) -> None:
        if total < 0:
            raise ValueError(f"total must be >= 0; got {total}")
        self.total = int(total)
        self.desc = desc
        self.stream = sys.stderr if stream is None else stream
        if enabled is None:
            from .output import verbosity

            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty()) if callable(isatty) else False
            enabled = enabled and verbosity() > 0
        self.enabled = enabled
        self.width = width
        self.min_interval = min_interval
        self.count = int(initial)
        self.last_note = ""
        self._start = time.perf_counter()
        self._bar: Any = None
        if self.enabled:
            from tqdm import tqdm

            from .output import terminal_width

            self._bar = tqdm(
                total=self.total, desc=desc or None, file=self.stream, mininterval=min_interval, leave=True,
                ncols=min(terminal_width(), 100), ascii=_ascii_only(self.stream),
                unit=unit, initial=int(initial),
            )

    def update(self, n: int = 1) -> None:
        """Advance by ``n`` steps (tqdm redraws at most every ``min_interval`` seconds)."""
        self.count += n
        if self._bar is not None:
            self._bar.update(n)

    def note(self, text: str) -> None:
        """Show ``text`` after the bar and redraw it (the elapsed time too): work that takes long is seen running."""
        self.last_note = text
        if self._bar is not None:
            self._bar.set_postfix_str(text, refresh=True)

    def write(self, line: str, *, level: int = 1) -> None:
        """Print ``line`` on stdout, above the bar while one is drawn (see :func:`~symbolic_friction._infra.output.emit`)."""
        if self._bar is not None:
            from .output import verbosity

            if verbosity() >= level:
                self._bar.write(line, file=sys.stdout)
                sys.stdout.flush()
        else:
            from .output import emit

            emit(line, level=level)

    def render(self, now: float | None = None) -> str:
        """The state as plain text, ``[#####.....] 5/10 desc 1.2 s`` (for logs and tests)."""
        now = time.perf_counter() if now is None else now
        frac = 1.0 if self.total == 0 else min(1.0, self.count / self.total)
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        label = f" {self.desc}" if self.desc else ""
        return f"[{bar}] {self.count}/{self.total}{label} {now - self._start:.1f} s"

    def close(self) -> None:
        """Draw the final state and end the line."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        self.enabled = False

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _ascii_only(stream: Any) -> bool:
    """tqdm's block characters only where the stream can encode them."""
    encoding = (getattr(stream, "encoding", None) or "ascii").lower().replace("-", "")
    return not encoding.startswith("utf")

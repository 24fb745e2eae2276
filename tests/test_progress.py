"""Progress bars (tqdm): drawn on a terminal, silent in a pipe or under --quiet."""

from __future__ import annotations

import io

import pytest

from symbolic_friction._infra.output import set_verbosity
from symbolic_friction._infra.progress import Progress


class _Tty(io.StringIO):
    encoding = "utf-8"

    def isatty(self) -> bool:
        return True


def test_draws_on_a_terminal_and_ends_the_line():
    stream = _Tty()
    with Progress(4, desc="work", stream=stream, min_interval=0.0) as bar:
        for _ in range(4):
            bar.update()
    text = stream.getvalue()
    assert "\r" in text and "work" in text and "4/4" in text
    assert text.endswith("\n")


def test_silent_when_not_a_terminal():
    stream = io.StringIO()
    with Progress(3, stream=stream) as bar:
        bar.update(3)
    assert stream.getvalue() == "" and bar.count == 3


def test_silent_under_quiet():
    stream = _Tty()
    try:
        set_verbosity(0)
        with Progress(3, stream=stream) as bar:
            bar.update(3)
    finally:
        set_verbosity(1)
    assert stream.getvalue() == ""


def test_forced_on_or_off():
    on, off = io.StringIO(), _Tty()
    with Progress(2, stream=on, enabled=True) as bar:
        bar.update(2)
    with Progress(2, stream=off, enabled=False):
        pass
    assert "2/2" in on.getvalue() and off.getvalue() == ""


def test_render_half_way():
    bar = Progress(10, desc="x", enabled=False, width=10)
    bar.update(5)
    assert bar.render().startswith("[#####.....] 5/10 x ")
    assert Progress(0, enabled=False).render().startswith("[" + "#" * 30 + "] 0/0")


def test_negative_total_is_rejected():
    with pytest.raises(ValueError, match="total must be >= 0; got -1"):
        Progress(-1)


def test_write_goes_above_a_drawn_bar_or_plainly_to_stdout(capsys):
    stream = _Tty()
    with Progress(1, desc="w", stream=stream) as bar:
        bar.write("row one")
        bar.update()
    with Progress(1, stream=io.StringIO()) as quiet_bar:
        quiet_bar.write("row two")
    assert capsys.readouterr().out.splitlines() == ["row one", "row two"]

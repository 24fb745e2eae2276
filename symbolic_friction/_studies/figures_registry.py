"""The registry of ``symbolic-friction figures``: a figure is a registered function, or independent tasks and a
drawing (see :mod:`.figures`, which re-exports these names)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["FigureFunction", "Task", "FigureSpec", "FIGURES", "register", "register_split"]

FigureFunction = Callable[[Path], list[Path]]


@dataclass(frozen=True)
class Task:
    """One independent piece of a figure's computation: ``function(*args)``, picklable (a module-level function).

    ``cost`` is the expected time in seconds on one idle core, so that the longest work starts first.
    """

    label: str
    function: Callable[..., Any]
    args: tuple = ()
    cost: float = 1.0

    def run(self) -> Any:
        return self.function(*self.args)


@dataclass(frozen=True)
class FigureSpec:
    """A registered figure: its name, a one-line description and the function.

    A split figure (:func:`register_split`) also has ``tasks() -> list[Task]`` and
    ``draw(out_dir, results) -> list[Path]``; its ``function`` runs the tasks in order and draws.
    """

    name: str
    description: str
    function: FigureFunction
    tasks: Callable[[], list[Task]] | None = None
    draw: Callable[[Path, list], list[Path]] | None = None
    cost: float = 1.0


FIGURES: dict[str, FigureSpec] = {}
"""Registered figures, in registration order."""

def register(name: str, description: str, *, cost: float = 1.0) -> Callable[[FigureFunction], FigureFunction]:
    """Decorator registering ``function(out_dir) -> list[Path]`` as figure ``name`` (``cost``: see :class:`Task`)."""

    def deco(function: FigureFunction) -> FigureFunction:
        if name in FIGURES and FIGURES[name].function is not function:
            raise ValueError(f"a figure named {name!r} is already registered")
        FIGURES[name] = FigureSpec(name, description, function, cost=cost)
        return function

    return deco


def register_split(
    name: str, description: str, *, tasks: Callable[[], list[Task]], draw: Callable[[Path, list], list[Path]]
) -> FigureSpec:
    """Register figure ``name`` computed by independent ``tasks()`` and drawn by ``draw(out_dir, results)``."""

    def function(out: Path) -> list[Path]:
        return draw(out, [task.run() for task in tasks()])

    if name in FIGURES and FIGURES[name].draw is not draw:
        raise ValueError(f"a figure named {name!r} is already registered")
    FIGURES[name] = spec = FigureSpec(name, description, function, tasks=tasks, draw=draw)
    return spec

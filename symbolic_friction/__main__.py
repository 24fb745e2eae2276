"""``python -m symbolic_friction`` is the ``symbolic-friction`` command."""

from .cli import entry_point

entry_point()

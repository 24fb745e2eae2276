"""``python -m symbolic_friction`` is the ``symbolic-friction`` command."""

from ._cli.main import entry_point

entry_point()

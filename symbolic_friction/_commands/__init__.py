"""Subcommands of the ``symbolic-friction`` CLI (stdlib-only imports at top level)."""
